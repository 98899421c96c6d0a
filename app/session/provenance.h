#pragma once
// Provenance of a vertex along the history: how far each entry moved it, following it back
// through subdivision (its parents, "v:subdivision_parents") and decimation (the vertex it
// was before, "v:decimation_source").
#include <cstddef>
#include <vector>

#include "app/history/history.h"
#include "core/halfedge_mesh.h"

namespace trilab::viewer {

/// For vertex `v` of the current state: one value per history entry, the distance the entry
/// moved the vertex (or, for an entry that made it, from where the rule started: the mean of
/// its parents), NaN for entries it cannot be followed through (a load, an entry after the
/// current one, a step that renumbers without saying how) and for the first entry. Steps of
/// an entry are followed one by one. O(entries x steps) lookups.
std::vector<double> vertex_moves(const History& history, Vertex v);

}  // namespace trilab::viewer
