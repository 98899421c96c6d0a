#pragma once
// Feature detection by the dihedral angle: an interior edge is a feature (sharp) when the angle
// between the normals of its two faces is at least a threshold (0 for a flat pair, 180 for a
// pair folded onto itself). The histogram of those angles shows the natural threshold: on a
// part with sharp edges (fandisk) the number of edges above the threshold barely changes over
// a wide range of angles (a plateau, about 700 edges from 30 to 60 degrees), while on a noisy
// scan it keeps falling (no plateau: denoise first). Short chains of feature edges, usually
// noise, can be dropped; boundary edges can be made features too. The detected edges get a
// sharpness (infinity by default) in "e:sharpness" (core/features.h), replacing the mesh's
// features; corner tags are cleared. The idea is the classic one (e.g. Hubeli and Gross 2001,
// "Multiresolution feature extraction for unstructured meshes", start from dihedral angles);
// the plateau rule is trilab's own.
//
// Degenerate faces (zero area) have no normal: their edges are never features and are counted.
// Complexity: O(V + E + F); two threads for a large mesh (the normals and the angles).
#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "core/features.h"
#include "core/halfedge_mesh.h"

namespace trilab {

/// The bins of the angle histogram: one degree each, 0 to 180.
inline constexpr std::size_t kAngleBins = 180;

struct FeatureDetectionOptions {
    double angle_deg = 40.0;    ///< feature when the dihedral angle is >= this, in (0, 180]
    std::size_t min_chain = 0;  ///< drop chains of fewer edges (0 and 1 keep every chain)
    bool boundary = false;      ///< boundary edges are features too
    float sharpness = kInfiniteSharpness;  ///< given to the feature edges: > 0, or inf
};

/// The dihedral angles of the interior edges, and the plateau of the count above a threshold.
struct AngleHistogram {
    /// counts[k]: interior edges whose angle lies in [k, k + 1) degrees (180 in the last bin).
    std::array<std::size_t, kAngleBins> counts{};
    std::size_t interior_edges = 0;    ///< edges with two faces, both with a normal
    std::size_t degenerate_edges = 0;  ///< interior edges next to a face without a normal
    /// The widest range of thresholds [lo, hi] (whole degrees, lo >= 5) over which the number of
    /// edges at or above the threshold falls by at most 5 % (and 1 edge), with edges left; a
    /// plateau when at least 15 degrees wide.
    bool plateau = false;
    int plateau_lo = 0, plateau_hi = 0;
    std::size_t plateau_edges = 0;  ///< edges at or above plateau_hi
    /// Edges at or above `angle` degrees (whole degrees, by the bins).
    std::size_t at_or_above(int angle) const;
};

/// The histogram of `mesh`'s dihedral angles and its plateau. O(V + E + F).
AngleHistogram angle_histogram(const HalfedgeMesh& mesh);
/// The plateau of a histogram's counts (fills the plateau fields of `h`).
void find_plateau(AngleHistogram& h);

struct FeatureDetectionReport {
    std::size_t feature_edges = 0;   ///< edges given the sharpness (after dropping chains)
    std::size_t boundary_edges = 0;  ///< of which boundary edges (options.boundary)
    std::size_t chains = 0;          ///< chains of feature edges (between junctions, or loops)
    std::size_t dropped_chains = 0;  ///< chains shorter than min_chain
    std::size_t dropped_edges = 0;   ///< their edges
    std::size_t corners = 0, creases = 0, darts = 0;  ///< vertex classes (core/features.h)
    /// Corners where three or more feature edges meet: junctions where the feature curves are
    /// not a 1-manifold (the corner rule: they stay under subdivision and decimation).
    std::size_t junctions = 0;
    AngleHistogram histogram;
    /// What the histogram says: the plateau and a suggested angle, or that there is none
    /// (a noisy mesh: denoise first), or that no edge is sharp.
    std::string verdict;
    double ms = 0;
};

/// The vertices within `rings` edge rings of a feature vertex (an end of an edge of sharpness
/// > 0, or a tagged corner): weight 1, the others 0 (a region, core/algorithms/selection.h;
/// `--region feature:K`). Throws InvalidArgument when the mesh has no features. O(V + E).
std::vector<float> feature_neighbourhood(const HalfedgeMesh& mesh, unsigned rings);

/// Detects the feature edges of `mesh` by the dihedral angle and stores them (see the file
/// comment). Throws InvalidArgument naming `angle_deg` (outside (0, 180] or not finite) or
/// `sharpness` (not > 0) before changing anything. O(V + E + F).
FeatureDetectionReport detect_features(HalfedgeMesh& mesh, const FeatureDetectionOptions& options);

}  // namespace trilab
