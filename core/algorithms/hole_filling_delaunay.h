#pragma once
// The search space of hole filling's dynamic programme for large loops (issue 41), after Zou,
// Ju and Carr, "An algorithm for triangulating multiple 3D polygons" (SGP 2013): instead of
// every triangle over the loop's vertices (O(n^3) time, O(n^2) memory), only the triangles
// whose three edges belong to a Delaunay triangulation of the loop's vertices. Zou et al. take
// the edges of the 3-D Delaunay tetrahedralization; here (no Delaunay package may be linked)
// the loop is projected onto the plane of its Newell normal (the loop's vector area, the
// best-fit plane of a polygon) and its 2-D Delaunay triangulation is built by incremental
// insertion with Lawson's flips (Lawson 1977; Guibas and Stolfi's predicates, in floating point
// with a relative tolerance: near-cocircular points are not flipped). The candidate edges are
// the edges of the Delaunay triangles inside the polygon (found by a flood from the rim edges)
// and, for every edge between two such triangles whose quadrilateral is strictly convex, the
// other diagonal: so the programme still chooses (Liepa's weights: the largest dihedral angle,
// then the area) among many triangulations, every one of them a valid triangulation of the
// projected polygon. The result holds O(n) edges and O(n) candidate triangles.
//
// The restriction is refused (`why` says why; the caller falls back to cutting the loop by
// chords) when the loop's vector area is zero, when its projection is not a simple polygon
// (two rim edges cross or touch: a loop on a surface that turns by more than 90 degrees
// under it), when a rim edge is not an edge of the Delaunay triangulation (the 2-D
// triangulation is not constrained: a rim whose projection has a vertex closer to a rim edge
// than that edge's own diametral circle allows), or when the triangles found inside do not
// cover the polygon's area exactly once (a check against rounding in the predicates).
// Complexity: O(n log n) expected for the insertion (in a random order, fixed seed), plus the
// walks that locate each point from the last triangle made; O(n) for the rest; memory O(n).
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "core/types.h"

namespace trilab {

/// The candidate edges of a loop's restricted programme: pairs (i, j), i < j, of positions
/// along the loop (its rim edges included), sorted; empty with `why` set when refused.
struct LoopDelaunay {
    std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
    std::string why;
};

/// The candidate edges for the loop of 3-D points `loop` (see the file comment). O(n log n).
LoopDelaunay loop_delaunay_edges(const std::vector<Point>& loop);

}  // namespace trilab
