#pragma once
// Soft selections: a weight in [0, 1] per vertex that every operation honours (issue 26).
//
// A Selection is a std::vector<float>, one weight per vertex *storage* index (deleted vertices
// weigh 0), so it indexes like mesh.positions(). float, not double: a weight is a blend factor
// where seven digits are plenty, it halves the memory of a per-vertex overlay, and it is what
// the PLY `selection` property stores, so a file round trip is exact. Weight 0: the vertex is
// outside (operations leave it bit for bit as it is); 1: fully inside (the operation does to it
// exactly what it does on the whole mesh); in between: the operation's change is blended
// (p_old + w·(p_new − p_old)), which is what a feather gives. "Selected" means weight > 0
// (count_selected(), decimation's and weld's rule).
//
// On a mesh a selection is stored as the float vertex property "v:selection"
// (kSelectionProperty): PLY reads and writes it as `property float selection`, OM as a custom
// vertex property of that name (docs/file-formats.md).
//
// The ways to select below return a new selection (0 or 1, except feather_selection());
// grow/shrink/invert/feather change one in place. Every function throws InvalidArgument naming
// the bad argument (a vertex out of range or deleted, a negative radius, a selection of the
// wrong size or with a weight outside [0, 1]) before changing anything.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "core/halfedge_mesh.h"

namespace trilab {

/// One weight in [0, 1] per vertex storage index (see the file comment).
using Selection = std::vector<float>;

/// The vertex property a mesh stores its selection in (float).
inline constexpr const char* kSelectionProperty = "v:selection";

/// Throws InvalidArgument "`what`: ..." unless `selection` has one weight per vertex storage
/// index of `mesh`, each finite and in [0, 1] (the message names the first bad index and value).
/// O(V).
void check_selection(const HalfedgeMesh& mesh, const Selection& selection,
                     const std::string& what = "selection");

/// Vertices with a positive weight. O(V).
std::size_t count_selected(const Selection& selection);

/// Whether every live vertex has weight exactly 1 (the selection is the whole mesh). O(V).
bool selects_everything(const HalfedgeMesh& mesh, const Selection& selection);

/// Weight 1 for every live vertex within `radius` (Euclidean, inclusive) of `center`.
/// Throws for a negative or non-finite radius or a non-finite centre. O(V).
Selection sphere_selection(const HalfedgeMesh& mesh, const Point& center, double radius);

/// Weight 1 for every vertex whose geodesic distance from `center` (heat method,
/// core/algorithms/geodesic.h) is at most `radius`. Throws for a bad vertex or radius.
/// Cost: one GeodesicSolver (two sparse factorizations) and one distance query.
Selection geodesic_selection(const HalfedgeMesh& mesh, Vertex center, double radius);

/// Weight 1 for every vertex of the connected component (through edges) of `v`; just `v`
/// when it is isolated. Throws for a bad vertex. O(V + E).
Selection component_selection(const HalfedgeMesh& mesh, Vertex v);

enum class ThresholdSide { Above, Below };

/// Weight 1 where values[v] > threshold (Above) or values[v] < threshold (Below); NaN values
/// and deleted vertices get 0. `values` holds one number per vertex storage index (a colouring:
/// curvature, distance, ...). Throws when its size is wrong or the threshold is not finite.
Selection threshold_selection(const HalfedgeMesh& mesh, const std::vector<double>& values,
                              double threshold, ThresholdSide side);

/// Grows by `rings` rings: each round every vertex takes the largest weight of itself and its
/// neighbours (a dilation; a 0/1 selection gains its one-ring). rings >= 0. O(rings·(V + E)).
void grow_selection(const HalfedgeMesh& mesh, Selection& selection, int rings);

/// Shrinks by `rings` rings: each round every vertex takes the smallest weight of itself and
/// its neighbours (an erosion; boundary vertices of the mesh are not eroded by the boundary
/// itself). rings >= 0. O(rings·(V + E)).
void shrink_selection(const HalfedgeMesh& mesh, Selection& selection, int rings);

/// 1 − w for every live vertex (deleted ones stay 0). O(V).
void invert_selection(const HalfedgeMesh& mesh, Selection& selection);

/// Every weight 0, one per vertex storage index. O(V).
Selection empty_selection(const HalfedgeMesh& mesh);

/// Every live vertex weight 1. O(V).
Selection full_selection(const HalfedgeMesh& mesh);

/// Feathers the selection over `width` outside it: with d the edge-graph distance (Dijkstra
/// along the edges, core/algorithms/geodesic.h edge_graph_distances()) from the nearest vertex
/// of positive weight, every vertex gets max(w, 1 − s(d / width)), s(t) = 3t² − 2t³ for t in
/// [0, 1] and 1 beyond (C1: the weight leaves 1 and reaches 0 with zero slope). Vertices of
/// positive weight keep theirs. Bounded jump: across an edge of length l between two vertices
/// the weights differ by at most 1.5·l / width (s' <= 1.5, d is 1-Lipschitz along edges) plus
/// float rounding, where the selection before was 0/1. width 0: unchanged; width < 0 or not
/// finite: InvalidArgument. O((V + E) log V).
void feather_selection(const HalfedgeMesh& mesh, Selection& selection, double width);

/// The mesh's stored selection ("v:selection"), if it has one, as a Selection.
std::optional<Selection> stored_selection(const HalfedgeMesh& mesh);

/// Stores `selection` as "v:selection" (checked first: check_selection()).
void store_selection(HalfedgeMesh& mesh, const Selection& selection);

/// The weight of vertex index `i` under `region` (nullptr: the whole mesh, 1).
inline float region_weight(const Selection* region, std::size_t i) {
    return region ? (*region)[i] : 1.0f;
}

/// p_old + w·(p_new − p_old), with w = 1 giving p_new and w = 0 giving p_old bit for bit.
inline Point blend_by_weight(const Point& p_old, const Point& p_new, float w) {
    if (w >= 1.0f) return p_new;
    if (w <= 0.0f) return p_old;
    return p_old + double(w) * (p_new - p_old);
}

}  // namespace trilab
