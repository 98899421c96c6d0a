#pragma once
// Subdivision of a region only (issue 26): the faces of a soft selection are refined by the
// scheme, with a conforming closure around them, and the rest of the mesh is left as it is.
//
// Which faces: a face is selected when all three of its vertices have weight > 0.
// The closure:
//  - Loop, Butterfly, Modified Butterfly: red-green refinement (Bank, Sherman, Weiser 1983).
//    Every edge of a selected face is split; then, until nothing changes, a face with two
//    split edges gets its third one split too (it becomes red), a face of an earlier level's
//    closure (a green half, a child of a refined face outside the selection, or a descendant)
//    with a split edge gets all three split (red: "closure_reds"; red-green refinement's
//    removal of the previous closure: a closure triangle is never bisected again, so repeated
//    levels do not keep halving its angles), and a face outside the selection with one split
//    edge whose bisection would make a triangle flatter than the target gets its other two
//    split too (it becomes red: "grown"). The target: half the input's smallest angle by
//    default (the local closure), the input's smallest angle with options.global_closure; a
//    face with a vertex of weight > 0 must clear the target by 3 degrees (the scheme moves
//    that vertex again at every later level while the outside stays, so its descendants'
//    angles drift: 0.6 degrees over four levels of Loop on the generated sphere's cap).
//    Faces with three split edges are split 1-to-4 (red), faces with one are bisected from the
//    edge's new vertex to the opposite corner (green), the rest are kept. No T-junctions: every
//    split edge is split in both of its faces. Faces: F + 3·red + 1·green.
//  - Sqrt3: the adaptive rule of Kobbelt's "√3-Subdivision" (SIGGRAPH 2000, section on
//    adaptive refinement): every selected face is split 1-to-3 at its centroid and an old
//    edge is flipped only when both of its faces were split (same generation); an edge
//    between a split and an unsplit face stays, leaving the split side's triangle (a, b,
//    centroid). When that triangle would be flatter than the input's smallest angle, the
//    unsplit face is split too ("grown"), until nothing changes. No vertex lands on an edge,
//    so the mesh is conforming without any closure faces. Faces: F + 2·split faces.
//    Generations (the paper's bookkeeping, within one call): a closure triangle (a, b,
//    centroid) left unflipped is completed before a later iteration refines it (its
//    neighbour split at the centroid, the old edge flipped: complete_sqrt3 in the .cpp);
//    between calls such triangles are refined as ordinary ones. Boundary edges are never
//    split (the odd-step boundary rule of subdivision.h in every step).
//  - Then Lawson's max-min-angle flips among the closure's triangles (1-to-4: the faces cut
//    from refined faces outside the selection; Sqrt3: the edge between a split and an unsplit
//    face), only between faces within 15° of coplanar (before and after): each flip raises
//    the pair's smaller angle, so the closure's minimum angle never goes down.
//  Quality: a red face outside the selection is split at its edges' midpoints (a closure
//  edge that is no selected face's edge gets the midpoint of its ends' new positions) into four
//  triangles similar to it, a green bisection is kept only when both halves reach the target,
//  and the flips only raise angles; so no closure triangle is flatter than the target (to
//  rounding), except the children of a red face with a vertex inside, which follow the scheme's
//  moved vertices (as the refined region's own triangles do: min_angle_closure reports them;
//  on the generated sphere's cap (54°), Loop's, Butterfly's and Modified Butterfly's closures
//  stay at 27.02° through six levels, for a target of 27.02°, where bisecting again gave 27.8,
//  14.3, 9.5, 7.3°; on the default model (47.56°) all three keep 23.80° through six levels). With
//  options.global_closure the price of the full target: on an almost regular input (the default
//  model, 47.6°) no bisection passes (halving an angle of 50-70° gives 25-35°, and no conforming
//  2:1 transition between equilateral meshes keeps 60°), so the closure grows over the whole
//  connected surface (its outside refined at midpoints: the same surface, four times the faces); on
//  scanned and CAD meshes (bunny, spot, fandisk) it grows by a few faces at most. Sqrt3's closure
//  triangles are half their face's angles by design, and the region's relaxed border faces lose
//  more: on that cap the minimum goes 29.2, 27.0, 21.4, 21.3, 18.7° over five levels (12.3° at five
//  before the completion), above a third of the input's smallest but not half.
// Positions (w: the vertex weights):
//  - an old vertex with w = 0 keeps its position bit for bit; with w > 0 it gets
//    p_old + w·(p_scheme − p_old), p_scheme being the uniform scheme's rule on the coarse mesh
//    (Loop's even rule, Sqrt3's relaxation; the butterflies keep every old vertex);
//  - the new vertex of a split edge a-b: the edge midpoint blended towards the scheme's
//    stencil by max(w_a, w_b), so a closure edge with one end inside is at the scheme's
//    position and one entirely outside (a red closure face's far edge) at its midpoint, on the
//    untouched surface (stencil "odd, edge midpoint (region closure ...)"); Butterfly and
//    Modified Butterfly move an edge vertex whose stencil would make a new triangle flatter
//    than half the input's smallest angle back toward its edge's midpoint, halving its offset
//    until none is (`damped_vertices`: a 1-to-4 split at midpoints keeps its face's angles,
//    and these schemes never move a vertex again);
//  - a Sqrt3 centroid: the centroid.
// With weights 0 and 1 only, every vertex inside is where the uniform scheme puts it (but for
// those damped edge vertices).
// An all-ones selection runs subdivide() itself, so the result is the unselected one bit for
// bit (plus the carried selection).
// The selection is carried: "v:selection" on every level, old vertices keeping their weight,
// new ones the minimum of their parents' weights (so the region never grows into the closure).
// Provenance as in subdivision.h: "v:subdivision_level", "v:subdivision_stencil" (a vertex of
// weight 0 is "even, kept"), "v:subdivision_parents"; "v:texcoord" is interpolated linearly;
// "h:texcoord" and every other attribute are dropped (a note says so for "h:texcoord").
// Features (core/features.h; options.features as in subdivide()): Loop and the butterflies
// compute their stencils by the crease rules (the whole mesh's step, uniform_step_1to4() with
// features), never flip a sharp edge in the closure, and carry them (both halves of a split
// edge child_sharpness(), an edge not split its own sharpness, the new inner edges and cuts
// smooth, old vertices their corner tags). Sqrt3 treats sharp edges as boundaries (Kobbelt
// 2000, section 4, its odd-step rule at every level: never flipped, completed nor split), keeps
// crease and corner vertices where they are, and carries them (an old edge at a split face one
// step less sharp).
// The report gives the minimum angle before and after, and per iteration that of the closure's
// triangles and of the coarse faces they replaced.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/algorithms/selection.h"
#include "core/algorithms/subdivision.h"

namespace trilab {

/// What one iteration of region subdivision refined.
struct RegionClosureCounts {
    std::size_t selected_faces = 0;  ///< faces whose three vertices weigh > 0
    std::size_t red_faces = 0;       ///< split 1-to-4 (1-to-4 schemes) or 1-to-3 (Sqrt3)
    std::size_t green_faces = 0;     ///< split 1-to-2 (1-to-4 schemes only)
    std::size_t flipped_edges = 0;   ///< Sqrt3: old edges flipped (both faces split)
    std::size_t closure_flips = 0;   ///< max-min-angle flips in the closure
    std::size_t grown_faces = 0;     ///< faces split so that the closure keeps the input's angles
    /// Faces of an earlier level's closure split 1-to-4 rather than bisected again (1-to-4
    /// schemes, from the second level on).
    std::size_t closure_reds = 0;
    /// Sqrt3: the previous level's unflipped closure triangles completed before this level
    /// refined them (their neighbour split at its centroid, the old edge flipped).
    std::size_t completed_edges = 0;
    /// Butterfly and Modified Butterfly: edge vertices moved from their stencil toward their
    /// edge's midpoint so that no new triangle is flatter than half the input's smallest angle.
    std::size_t damped_vertices = 0;
    /// Degrees: the smallest angle of the coarse faces the closure replaced (1-to-4: refined
    /// faces outside the selection; Sqrt3: the faces on both sides of the region's edge), and
    /// of the closure's own triangles (180 when there is no closure).
    double min_angle_touched = 180;
    double min_angle_closure = 180;
};

struct RegionSubdivisionReport {
    std::size_t region_vertices = 0;           ///< input vertices of weight > 0
    std::vector<RegionClosureCounts> closure;  ///< one per iteration
    double min_angle_in = 0;                   ///< degrees, over the input's faces
    double min_angle_out = 0;                  ///< degrees, over the finest level's faces
};

/// One flag per face storage index: 1 when the face is live and its three vertices weigh > 0.
/// `selection` must fit the mesh (check_selection()). O(F).
std::vector<std::uint8_t> region_faces(const HalfedgeMesh& mesh, const Selection& selection);

/// Subdivides the selected part of a copy of `mesh` (see the file comment) `options.iterations`
/// times; the levels, counts and notes are those of subdivide(). `report` receives the
/// closure counts and the minimum angles. Throws InvalidArgument for bad options or a
/// selection that does not fit the mesh (before anything is done), TopologyError when a
/// closed two-triangle pillow would be refined, Cancelled from the progress. Complexity: one
/// copy of the mesh and a few O(V + F) scans of flags per iteration, the scheme's stencils
/// only at the region's vertices and edges (uniform_step_1to4_listed(), packed), plus
/// O(size of the refined part and its closure).
SubdivisionResult subdivide_region(const HalfedgeMesh& mesh, const SubdivisionOptions& options,
                                   const Selection& selection, Progress& progress,
                                   RegionSubdivisionReport& report);

}  // namespace trilab
