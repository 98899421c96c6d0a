#pragma once
// Isotropic remeshing: a triangle mesh whose edges all have about one target length L and
// whose vertices mostly have valence 6, on the input's surface.
//
// Method: Botsch, Kobbelt, "A remeshing approach to multiresolution modeling", SGP 2004. Each
// iteration (1) splits every edge longer than 4/3 L' at its midpoint, (2) collapses every edge
// shorter than 4/5 L' into one of its ends (the one of lower valence goes first) unless that
// would make an edge longer than 4/3 L', fail the link condition (HalfedgeMesh::is_collapse_ok),
// fold a face or leave the removed vertex farther than 0.1 L' from the faces that replace its
// ring, (3) flips edges where that brings the valences of the four vertices involved
// closer to 6 (4 on the boundary; the sum of the absolute deviations, two sweeps), (4) moves
// every free vertex towards the mean of its neighbours within its tangent plane (tangential
// relaxation), and (5) projects the moved vertices back onto the input surface: the closest
// point found by walking over the input's triangles from the one the vertex was last projected
// onto (a moved vertex costs a triangle or two, and stays on its own sheet where the input
// folds close to itself; a bounding-box tree over the input answers a vertex without one).
// L' = 1.06 L: with Botsch and Kobbelt's thresholds for L itself the output's edges come out
// about 4 % short on average (collapses that would make an edge longer than 4/3 L are refused,
// so too many vertices stay), and fewer of them within [0.8 L, 4/3 L]. After the last
// iteration, faces with an angle under 25 degrees have their shortest edge collapsed where
// that makes the smallest angle around it larger, and edges facing an angle under 25 degrees
// are flipped where that makes the worse of their two triangles better (kept from folding).
//
// Boundaries: boundary vertices never move; a boundary edge is split at its midpoint (on the
// boundary polyline) and a boundary vertex is only removed along a boundary edge into its
// neighbour on the boundary, when it is at most 0.3 L from the new boundary edge and is not a
// corner (a point where the boundary, seen half a length either way, turns by more than 60
// degrees, and more than its neighbours do), so every boundary loop keeps its corners and its
// vertices' positions as a subset of the input's polyline, and no loop closes or opens.
// Texture seams (per-corner "h:texcoord" with different values on the two sides of a vertex)
// are kept as they are: their vertices and the faces around them are frozen (as outside a
// region); other corners and per-vertex "v:texcoord" and "v:color" take their values from the
// input triangle a vertex lies on (barycentric interpolation); "v:normal" is recomputed. Other
// attributes of new vertices take their default values.
//
// Stored features (options.features; core/features.h) are remeshed along their curves (Botsch
// and Kobbelt's feature handling): a sharp edge (sharpness > 0) is split at its midpoint like any
// other (both halves keep its sharpness) and the new vertex is put on the input's sharp edges
// (the closest point, found by a walk along them); it is never flipped; a crease vertex (exactly
// two sharp edges, not on the boundary) is removed only by collapsing one of its sharp edges into
// the neighbour along the curve, when it is at most 0.1 L' from the curve's new edge, and its
// relaxation moves it towards the midpoint of its two curve neighbours and back onto the input's
// sharp edges; corners (tagged, or three or more sharp edges), the ends of open curves (one sharp
// edge) and feature vertices on the boundary never move and are never removed. A collapse that
// merges a sharp edge with another keeps the larger sharpness on the survivor. So every feature
// vertex stays on an input curve, every corner where it was, and the curves' edges get lengths
// near L like the rest. Untagged creases are not detected (options.features Auto detects them
// first): relaxation may move a crease's vertices off it, so the chord error there can reach
// about L/2 (the bunny's flat base).
//
// Region (options.region, core/algorithms/selection.h): only faces whose three corners have a
// positive weight change, and only where every face at the edge or vertex involved is such a
// face, so every face outside is kept bit for bit and the border between is conforming (its
// edges are neither split nor collapsed nor flipped). A vertex's relaxation is scaled by its
// weight (soft selections feather the relaxation only).
//
// Size: before it runs, the number of faces it will make is estimated as the area to be
// remeshed over the area of an equilateral triangle of side L (plus the faces kept outside
// the region); a run whose estimate does not fit the memory this process may still allocate
// (core/system_memory.h) is refused.
//
// Throws InvalidArgument naming the option (length or relative not finite or not positive,
// iterations outside [1, 1000]), for a mesh with no faces or a non-finite position, and for an
// output that would not fit in memory; the mesh is unchanged then. Cancelled from `progress`
// (the mesh is then the state after the last complete step, valid). Meshes with coordinates
// far from 1 are worked on scaled by a power of two (exact) and scaled back.
// Complexity: O(F log F) to build the tree over the input, then O(F) per iteration (a
// projection walks over a triangle or two); the mesh is renumbered into a spatial order before
// the first iteration and after it (core/algorithms/spatial_order.h); relaxation and
// projection run on two threads for large meshes. Memory: linear in the output.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/features.h"
#include "core/halfedge_mesh.h"
#include "core/progress.h"

namespace trilab {

/// The largest number of iterations.
inline constexpr int kMaxRemeshIterations = 1000;

struct RemeshOptions {
    /// The target edge length L in the mesh's units; when absent, `relative` times the mean
    /// edge length (of the edges remeshed: those of the region where there is one).
    std::optional<double> length;
    double relative = 1.0;  ///< (0, 1e6], used without `length`
    int iterations = 10;    ///< [1, kMaxRemeshIterations]
    /// Adaptive sizing (Dunyach, Vanderhaeghe, Barthe, Botsch, "Adaptive remeshing for
    /// real-time mesh deformation", Eurographics 2013): 0 for a uniform length; otherwise the
    /// chord error allowed, as a fraction of L, in (0, 0.5]: each input vertex gets the length
    /// sqrt(6 e / k - 3 e^2) for e = adaptive L and k its larger absolute principal curvature
    /// (core/algorithms/curvature.h), clamped to [L / 10, L]; an edge's thresholds are those of
    /// the mean of its ends' lengths, and a new vertex takes the mean of its edge's.
    double adaptive = 0;
    /// Project the moved vertices back onto the input surface (step 5).
    bool project = true;
    /// Stored features (core/features.h) are kept: the ends of every sharp edge and the tagged
    /// corners are frozen with the faces around them, so every sharp edge and corner stays as
    /// it is. None remeshes across them; Auto first detects them at `feature_angle`
    /// (core/algorithms/feature_detection.h; the result carries them).
    FeatureSource features = FeatureSource::Stored;
    double feature_angle = 60.0;  ///< FeatureSource::Auto: the angle, in (0, 180]
    /// The region (one weight in [0, 1] per vertex storage index), or nullptr for the whole
    /// mesh. Not owned.
    const std::vector<float>* region = nullptr;
};

/// What remesh_plan() predicts and what a run did.
struct RemeshReport {
    double target_length = 0;     ///< L
    double input_mean_edge = 0;   ///< mean edge length of the edges remeshed
    double remeshed_area = 0;     ///< area of the faces that may change
    std::size_t input_faces = 0;  ///< faces of the input
    std::size_t predicted_faces = 0;
    std::size_t predicted_bytes = 0;  ///< memory the run needs (estimate)
    std::size_t available_bytes = 0;  ///< what the process may still allocate
    std::size_t output_faces = 0, output_vertices = 0;
    std::size_t splits = 0, collapses = 0, flips = 0, angle_flips = 0;
    std::size_t locked_vertices = 0;   ///< vertices kept as they are (seams, region border)
    std::size_t feature_vertices = 0;  ///< of which on sharp edges or tagged corners
    int iterations_done = 0;
    double ms = 0;
};

/// The target length, the predicted face count and the memory check, without changing
/// anything (what the run would say before it starts). Throws as remesh() does.
RemeshReport remesh_plan(const HalfedgeMesh& mesh, const RemeshOptions& options);

/// Remeshes `mesh` in place (see the file comment). Leaves a compact mesh (no garbage).
RemeshReport remesh(HalfedgeMesh& mesh, const RemeshOptions& options, Progress& progress);
RemeshReport remesh(HalfedgeMesh& mesh, const RemeshOptions& options);

}  // namespace trilab
