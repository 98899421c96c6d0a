#pragma once
// Hole filling (issue 41): closes boundary loops with a triangulation that matches the surface
// around them in shape, density and smoothness, after Liepa, "Filling holes in meshes" (SGP 2003).
//
// Each chosen loop goes through three stages:
//  1. Triangulation by dynamic programming over the loop's polygon: among all triangulations
//     that use only the loop's vertices, the one minimising, in this order, the largest
//     dihedral angle between adjacent triangles (new ones, and the old faces across the rim)
//     and the total area. O(n^3) time, O(n^2) memory for n rim vertices. A diagonal that is an
//     edge of the mesh already and a triangle without area are never used.
//     Restriction for large loops (Zou, Ju and Carr 2013; core/algorithms/hole_filling_delaunay.h):
//     a loop of more than kMaxDpLoop vertices is triangulated by the same programme over the
//     triangles whose edges are candidates only: the edges of the 2-D Delaunay triangulation
//     of the loop projected onto its Newell plane that lie inside the polygon, plus the other
//     diagonal of each convex pair of such triangles. O(n log n) for the triangulation, O(n)
//     candidate edges and triangles: a loop of 5,000 vertices takes a few milliseconds.
//     Where that is refused (the projection is not simple, a rim edge is not a Delaunay edge,
//     or no solution avoids the existing edges; a note says which), the loop is cut in two by
//     a chord, recursively, until every piece has at most kMaxDpLoop vertices, and each piece
//     is triangulated by the full programme. A chord joins two vertices of the piece between a
//     third and two thirds of the piece apart along it, the shortest (in space) such pair that
//     is not an edge already: O(n^2) for the cuts plus O(n kMaxDpLoop^2) for the pieces.
//  2. Refinement to the density around the hole (Liepa section 3.2): each rim vertex gets the
//     mean length s of its edges; a new triangle is split at its centroid c (s(c) the mean of
//     its corners') while 1.6·|c - v| exceeds both s(c) and s(v) for each corner v (Liepa's
//     factor is sqrt(2), which leaves the fill's edges 13-22 % longer than the old ones around
//     the hole and the fill bending more across its rim than the surface beside it; 1.6 brings
//     them within 1-9 %), and a
//     new edge longer than twice its ends' mean s is split at its midpoint; after each split
//     Lawson's flips make the new edges Delaunay again (the two angles opposite an edge sum to
//     at most 180 degrees), and the faces a split or flip touched are tested again (a worklist,
//     so the refinement runs along a long thin hole in one sweep). Then tangential smoothing
//     (towards the area-weighted centroid of the one-ring) with flips that raise the smallest
//     angle, before and after fairing. Then every new vertex with an angle under 25 degrees
//     around it is moved, in its tangent plane, to where the smallest angle of its triangles
//     (their angles at the rim included) is largest (a compass search, no triangle folding),
//     with flips that raise the smallest angle; a new triangle still under 20 degrees gets its
//     longest new edge split (the longest whose split leaves each rim corner across it room: k
//     new triangles spanning an angle S at a rim vertex have an angle of at most S / k there),
//     is faired, and optimized again (up to three rounds). Then one last fairing (the angle
//     repairs moved vertices off the faired surface), holding in place the new vertices of any
//     triangle it would take under 20 degrees (or under its smallest angle, when that is under
//     20 already). What remains under 20 degrees is where the rim allows no better: a rim vertex
//     whose new triangles span less than 60 degrees between a very short and a long rim edge
//     (over 7.4 times longer), where neither one, two nor three triangles can keep 20 degrees
//     without bending the fill out of the surface. There the new vertices of each such rim
//     corner's fan move together, in their tangent planes (a random search with a fixed seed,
//     keeping a move when the triangles under 20 degrees, sorted, compare larger and are no
//     more): the smallest angle is shared by two of them, and moving one alone cannot raise it.
//  3. Fairing with trilab's own implicit Laplacian (core/algorithms/laplacian.h, cotangent
//     weights with the Voronoi mass, Meyer et al. 2003): the new vertices solve
//     Δ²x = 0 (C1: tangent continuity at the rim) or Δ³x = 0 (C2: curvature continuity), with
//     the rim and every old vertex fixed; SPD form K S⁻¹ K (resp. K S⁻¹ K S⁻¹ K) restricted to
//     the new vertices, solved by a sparse Cholesky (Eigen SimplicialLDLT) over the faces
//     within two (C1) or three (C2) rings of the patch. A solve that fails or gives a
//     non-finite result falls back to the uniform (umbrella) weights, and then to the unfaired
//     patch, each said in the report.
//
// Which loops: every loop (default), those with at most `max_edges` edges, those whose rim's
// bounding-box diagonal is at most `max_diameter` times the mesh's, only the indices in `loops`,
// and only the loops with a rim vertex of positive weight in `region`; all given filters apply
// together. Loop order (the indices of `loops` and of the report): by the smallest vertex index
// on the loop, ascending (boundary_loops()).
//
// Degenerate rims are refused with a reason in HoleFillingReport::refused (the loop stays open;
// never silently skipped): a non-finite rim position, a rim edge of zero length, two rim vertices
// at the same position (a loop that touches itself, as a pinched, non-manifold rim becomes when
// loaded), a three-edge loop whose triangle exists already (the fill would cover a face twice),
// a loop with no triangulation that avoids the existing edges between rim vertices and
// triangles without area (collinear rims), a loop whose best triangulation bends by more than
// 150 degrees somewhere (it folds back onto the surface: the outer border of a flat sheet), and a
// loop whose fill, refined to the density around it, would have more than about two million faces
// (the outer border of a large open scan: estimated before anything is added, as the coarse
// triangulation's area over an equilateral triangle of the rim's mean edge length).
//
// Attributes: new vertices get a normal where the mesh has "v:normal" (and their rim
// neighbours' normals are recomputed), the mean rim colour where it has "v:color", zero
// otherwise. With `select_new` the mesh's stored selection ("v:selection",
// core/algorithms/selection.h) becomes weight 1 on the new vertices and 0 elsewhere (replacing
// one it had), so later operations can act on the fills alone; clear it to act on everything.
//
// Throws InvalidArgument naming the option (`max_edges` negative, `max_diameter` negative or not
// finite, a loop index past the end, a region of the wrong size) before changing anything.
// Otherwise the mesh is valid (validate()) after the call, with every filled loop closed.
// Complexity: O(V) to find the loops, then per loop as above, plus the refinement (linear in
// the new faces) and a sparse factorization over the patch's neighbourhood.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "core/enum_table.h"
#include "core/halfedge_mesh.h"

namespace trilab {

/// Loops with more rim vertices than this are cut by chords before the dynamic programme.
inline constexpr std::size_t kMaxDpLoop = 96;

/// The continuity of the fill at its rim.
enum class HoleFairing { None, C1, C2 };
/// The one table of HoleFairing (core/enum_table.h): identifier and label of each value.
inline constexpr EnumEntry<HoleFairing> kHoleFairings[] = {
    {HoleFairing::None, "none", "None (refined, not faired)"},
    {HoleFairing::C1, "c1", "C1 (bi-Laplacian)"},
    {HoleFairing::C2, "c2", "C2 (tri-Laplacian)"},
};

/// One boundary loop: its vertices in the order of its boundary halfedges (the first is the
/// smallest vertex index on the loop), and its size.
struct BoundaryLoop {
    std::vector<Vertex> vertices;
    double length = 0;    ///< sum of the rim edges' lengths
    double diagonal = 0;  ///< the rim's bounding-box diagonal
    std::size_t edges() const { return vertices.size(); }
};

/// Every boundary loop of `mesh`, ordered by the smallest vertex index on each. O(V + E).
std::vector<BoundaryLoop> boundary_loops(const HalfedgeMesh& mesh);

struct HoleFillingOptions {
    /// Fill only loops with at most this many edges (>= 0); unset: any size.
    std::optional<long long> max_edges;
    /// Fill only loops whose rim's bounding-box diagonal is at most this fraction of the mesh's
    /// (>= 0, finite); unset: any size.
    std::optional<double> max_diameter;
    /// Fill only these loops (indices into boundary_loops()); empty: every loop.
    std::vector<long long> loops;
    /// Fill only loops with a rim vertex of positive weight here (one weight per vertex storage
    /// index); nullptr: no restriction. Not owned.
    const std::vector<float>* region = nullptr;
    HoleFairing fairing = HoleFairing::C1;
    /// Refine to the density around the hole (stage 2); false: the coarse triangulation only
    /// (then nothing is faired either: the patch has no free vertex).
    bool refine = true;
    /// Store the new vertices as the mesh's selection ("v:selection").
    bool select_new = true;
};

/// A loop that was chosen but not filled, and why.
struct RefusedLoop {
    std::size_t loop = 0;   ///< index into boundary_loops()
    std::size_t edges = 0;  ///< its size
    std::string reason;
};

struct HoleFillingReport {
    std::size_t loops_found = 0;
    std::size_t loops_chosen = 0;  ///< passing the filters
    std::size_t loops_filled = 0;
    std::vector<std::size_t> loop_edges;  ///< every loop's edge count, in loop order
    std::vector<std::size_t> filled;      ///< indices of the filled loops
    std::vector<RefusedLoop> refused;     ///< chosen but refused, with the reason
    std::size_t faces_added = 0;
    std::size_t vertices_added = 0;
    /// Loops longer than kMaxDpLoop triangulated over their Delaunay edges (Zou et al.).
    std::size_t loops_delaunay = 0;
    std::size_t loops_cut = 0;  ///< loops longer than kMaxDpLoop cut by chords (the fallback)
    /// The smallest angle of the new triangles in degrees; NaN when none was added.
    double min_new_angle_deg = 0;
    /// How many new triangles have an angle under 20 degrees.
    std::size_t new_angles_under_20 = 0;
    /// Anything else worth telling: fairing fallbacks, a patch left unfaired.
    std::vector<std::string> notes;
};

/// Fills the chosen boundary loops of `mesh`; see the file comment.
HoleFillingReport fill_holes(HalfedgeMesh& mesh, const HoleFillingOptions& options = {});

}  // namespace trilab
