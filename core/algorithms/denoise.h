#pragma once
// Feature-preserving denoising by normal filtering: the face normals are filtered first, then
// the vertices are moved so that the faces follow the filtered normals.
//
// Methods (DenoiseOptions::method):
//  - Bilateral: the local scheme of Zheng, Fu, Au, Tai, "Bilateral normal filtering for mesh
//    denoising" (IEEE TVCG 2011). Each iteration replaces a face's normal n_i by the normalized
//        sum over j in N(i) of  A_j · W_s(|c_i − c_j|) · W_r(|n_i − n_j|) · n_j,
//    A_j the area and c_j the centroid of face j, W_s and W_r Gaussians of standard deviation
//    sigma_s (times the mean edge length) and sigma_r; N(i) is face i and every face that
//    shares a vertex with it.
//  - Guided: Zhang, Deng, Zhang, Bouaziz, Liu, "Guided mesh normal filtering" (Pacific
//    Graphics 2015). Each iteration first gives every face a guidance normal g_i: the
//    area-weighted mean normal of the most consistent patch containing it. The patches are the
//    N(j) above; a patch's consistency is H = D · R, D the largest normal difference between
//    two of its faces, R = max φ / (ε + Σ φ) over its edges (φ(e) the normal difference across
//    edge e), and the patch of smallest H wins. The normals are then filtered by the joint
//    bilateral filter, W_r taking |g_i − g_j| instead of |n_i − n_j|: a patch that lies on one
//    side of a crease guides the faces near it, so creases stay sharp under strong noise.
// sigma_r is by default picked from the noise measured on the input (the median of |n_f − n_g|
// over the interior edges, times 0.6, within [0.2, 0.35]: DenoiseOptions::fixed_sigma_r).
// Before either filter, a face whose normal points away from the area-weighted mean normal of
// the faces around it (turned over by the noise: a tangential displacement folds a small
// triangle) starts from that mean, since no range kernel can bring it back, and takes no part
// in its neighbours' filtering (DenoiseReport::inverted_faces).
// After the last normal iteration, a side check: near a corner or along a crease under strong
// noise, the filters may give a face the normal of the other side of the crease (every patch
// around it straddles the crease), and the vertex update then turns the face over (more than
// 90 degrees off the clean part at a right-angled crease). Each face's corners and the far
// corners of its edge neighbours (up to 6 points) are fitted by a plane of each normal n:
// E(n) = the sum of (n · (p − their mean))². Among the filtered normals of N(i) that lie 60 to
// 120 degrees from face i's (another side), the one of least E replaces face i's when E is at
// most half of E(n_i) (DenoiseReport::side_corrected_faces). Measured on fandisk, Gaussian noise
// along the normals and in random directions, seeds 1 to 20: at k = 0.3 the flipped faces go
// from 2 (over 40 runs) to 0 and the largest theta from 3.55 to 3.38 degrees; at k = 0.7
// (guided) from 62 faces to 17, the largest theta 10.46 to 10.76 degrees.
// Then `vertex_iterations` steps of the vertex update of Sun, Rosin, Martin, Langbein,
// "Fast and effective feature-preserving mesh denoising" (IEEE TVCG 2007):
//        x_i += 1/|F_i| · sum over faces f at x_i of  n_f (n_f · (c_f − x_i)),
// the filtered normals n_f fixed and the centroids c_f those of the current positions, plus a
// tangential relaxation (0.1 of the way to the area-weighted mean of the centroids around x_i,
// along the plane of the mean filtered normal there: it keeps the triangles from squashing at
// creases, where a face given the other side's normal would otherwise fold over); the corners of
// a face left on the far side of its filtered normal then move to the mean of their neighbours
// along that plane, which untangles the faces the noise turned over.
//
// Features (DenoiseOptions::features, core/features.h): the sharp edges (sharpness > 0) cut the
// faces around each vertex into sectors, and N(i) keeps only the faces in face i's sector at
// every corner they share with it, so no normal is averaged with one across a sharp edge (the
// guided filter's patches are these N(j) too: one-sided at a crease). The vertices on a sharp
// edge and the tagged corners move by Sun et al.'s update only (no tangential relaxation), so
// a tagged crease is never blurred. At a dart (an inner vertex with one sharp edge: where a
// crease fades out) the fan is also cut at the edge half way round from the sharp one, so the
// two sides stay apart up to the crease's tip. Measured on the clean fandisk with its features
// detected at 60 degrees (700 edges): the dihedral angles across them change by 0.64 degrees
// (median; mean 1.5, largest 20) against 0.94 (mean 4.3, largest 78) without the features;
// the edges that move most are next to a crease's faded tip or an untagged crease, whose faces
// the filter may still smooth.
//
// Region (DenoiseOptions::region): faces with no vertex of positive weight keep their normals
// (they still guide their neighbours); each vertex update is scaled by the vertex's weight, so
// weight-0 vertices stay bit for bit and an all-ones region gives the whole-mesh result.
// Degenerate faces (twice the area at most 1e-12 times the mean edge length squared: no normal)
// take no part in the filtering nor in the vertex update and are counted in the report
// (DenoiseReport::degenerate_faces). Isolated vertices do not move. Boundary vertices move like
// the others (they have fewer faces).
// Never a silent failure: a face that ends on the far side of its filtered normal (and did not
// start there) or without area is a fold. The iterations on the way may leave folds (untangling
// the faces the noise turned over passes through them); where the last one does, the corners
// of each folded face go half way back to the last state without folds, up to four times, then
// all the way back, until no face folds (DenoiseReport::held_vertices counts them: the rest of
// the mesh keeps the last iteration's result). As a guard, a run that still leaves folds goes
// back to the state after the last iteration that left none, and the report says so and how
// many faces folded (stopped_early, folded_faces, stop_reason); a non-finite position stops
// the run at once, at that same state. Only positions change (and "v:normal" is recomputed when the
// mesh carries it).
// Throws InvalidArgument before changing anything, naming the option: iterations out of range,
// sigma_s or sigma_r not finite or not positive (or too large), a mesh without faces, a
// non-finite position, a region that does not fit the mesh; Cancelled from the progress, the
// mesh then unchanged.
// Complexity (features add O(F · m) once, for the sectors): O(F · m) per normal iteration, m the
// faces per neighbourhood (about 13 on regular meshes; the guided filter adds O(F · m²) for the
// patches' largest normal difference), O(V + F) per vertex iteration (and the neighbours of the
// faces left inverted); memory O(F · m). Large meshes (65,536 faces and more) are worked on with
// their faces and vertices in a spatial (Morton) order inside the run. The per-face and
// per-vertex passes run on core/parallel.h's pool over fixed blocks (the set-up is serial): the
// result is the same bits for any thread count.
#include <cstddef>
#include <string>
#include <vector>

#include "core/enum_table.h"
#include "core/features.h"
#include "core/halfedge_mesh.h"
#include "core/progress.h"

namespace trilab {

enum class DenoiseMethod { Bilateral, Guided };
/// The one table of DenoiseMethod (core/enum_table.h).
inline constexpr EnumEntry<DenoiseMethod> kDenoiseMethods[] = {
    {DenoiseMethod::Bilateral, "bilateral", "Bilateral normal filter"},
    {DenoiseMethod::Guided, "guided", "Guided normal filter"},
};

/// The largest accepted iteration counts and sigmas.
inline constexpr int kMaxDenoiseIterations = 1000;
inline constexpr double kMaxDenoiseSigmaS = 100.0;
inline constexpr double kMaxDenoiseSigmaR = 100.0;
/// The automatic sigma_r (DenoiseOptions::fixed_sigma_r false): this times the measured noise
/// level, within these bounds.
inline constexpr double kDenoiseSigmaRPerNoise = 0.6;
inline constexpr double kDenoiseAutoSigmaRMin = 0.2;
inline constexpr double kDenoiseAutoSigmaRMax = 0.35;

struct DenoiseOptions {
    DenoiseMethod method = DenoiseMethod::Guided;
    /// Normal filtering iterations, in [0, 1000].
    int normal_iterations = 20;
    /// Vertex update iterations, in [0, 1000].
    int vertex_iterations = 15;
    /// The spatial Gaussian's standard deviation in multiples of the mean edge length, in
    /// (0, 100].
    double sigma_s = 1.0;
    /// Whether `sigma_r` is used as given; when false (the default) the run picks sigma_r from
    /// the noise it measures: kDenoiseSigmaRPerNoise times the median of |n_f − n_g| over the
    /// interior edges between two filtered faces (the input's normals), clamped to
    /// [kDenoiseAutoSigmaRMin, kDenoiseAutoSigmaRMax] (DenoiseReport::sigma_r, noise_level).
    /// Weaker noise leaves the normals of like faces closer together, so a narrower range
    /// kernel keeps more of the edges: on fandisk with Gaussian noise along the normals, the
    /// fixed 0.35 left seeds 5 and 6 of k = 0.3 above 3.6 degrees (0.27 keeps all of seeds 1
    /// to 20 under it), while k = 0.7 needs 0.35 (0.27 went past 11 degrees); the upper bound
    /// is that 0.35 (wider kernels fold more faces at fandisk's creases under strong noise).
    bool fixed_sigma_r = false;
    /// The range Gaussian's standard deviation on |n_i − n_j| (guided: |g_i − g_j|), in
    /// (0, 100], used when `fixed_sigma_r`; small values keep more edges, large ones smooth
    /// more (as sigma_r grows the filter becomes a plain area-and-distance-weighted average of
    /// the normals).
    double sigma_r = 0.35;
    /// Stored features (core/features.h) are honoured: no normal is filtered with those across
    /// a sharp edge from it, and the vertices on sharp edges and tagged corners get no
    /// tangential relaxation. None ignores them; Auto first detects them at `feature_angle`
    /// (core/algorithms/feature_detection.h: the result carries them).
    FeatureSource features = FeatureSource::Stored;
    double feature_angle = 60.0;  ///< FeatureSource::Auto: the angle, in (0, 180]
    /// Whether the side check runs after the normal filtering (see the file comment); off only
    /// to measure what it changes.
    bool side_check = true;
    /// The region (core/algorithms/selection.h): one weight in [0, 1] per vertex storage index,
    /// or nullptr for the whole mesh. Not owned.
    const std::vector<float>* region = nullptr;
};

struct DenoiseReport {
    double mean_edge_length = 0;
    /// The noise level measured on the input: the median of |n_f − n_g| over the interior
    /// edges between two filtered faces (0 when there are none).
    double noise_level = 0;
    double sigma_r = 0;                ///< the range sigma used (given, or picked from noise_level)
    std::size_t filtered_faces = 0;    ///< faces whose normal was filtered
    std::size_t degenerate_faces = 0;  ///< faces without a normal: no part in the run
    /// Faces turned over by the noise (normal away from the mean normal around them): their
    /// filtering starts from that mean.
    std::size_t inverted_faces = 0;
    /// Of the inverted faces (on the far side of their filtered normal when the vertex update
    /// began), those the update left there: not counted as folds (see the file comment), but
    /// said (fandisk at k = 0.7: 0 to 12 faces a run, at k = 0.3: 0 or 1).
    std::size_t inverted_left_faces = 0;
    /// Faces the side check gave a neighbour's normal (the other side of a crease's, changed
    /// for the side their vertices fit).
    std::size_t side_corrected_faces = 0;
    std::size_t feature_edges = 0;     ///< sharp edges honoured (0 without features)
    std::size_t feature_vertices = 0;  ///< their vertices and the tagged corners
    int normal_iterations_done = 0;
    int vertex_iterations_done = 0;  ///< the good ones (the state kept)
    /// Mean and largest angle (degrees) between the input's and the filtered face normals.
    double mean_normal_change_degrees = 0;
    double max_normal_change_degrees = 0;
    double max_displacement = 0;  ///< largest distance a vertex moved
    std::size_t moved_vertices = 0;
    /// The run went back to an earlier state (see the file comment); the mesh holds the state
    /// after `vertex_iterations_done` iterations.
    bool stopped_early = false;
    std::size_t folded_faces = 0;  ///< faces the last vertex iteration left folded
    /// Vertices the last iteration left folding a face, moved back towards the last state
    /// without folds (see the file comment).
    std::size_t held_vertices = 0;
    std::string stop_reason;
};

/// Denoises `mesh` in place (positions only), as the file comment says.
DenoiseReport denoise(HalfedgeMesh& mesh, const DenoiseOptions& options, Progress& progress);
/// The same without progress reports or cancellation.
DenoiseReport denoise(HalfedgeMesh& mesh, const DenoiseOptions& options = {});

}  // namespace trilab
