#pragma once
// Distance between two surfaces: a sampled two-sided Hausdorff distance and an RMS distance.
//
// Method (in the spirit of Metro, Cignoni, Rocchini, Scopigno 1998): sample each mesh (all its
// vertices plus points spread over its faces in proportion to their area, on a deterministic
// low-discrepancy pattern, so equal inputs give equal answers), find for every sample the
// closest point on the other mesh's triangles with an axis-aligned bounding-box tree
// (median split, closest-box-first traversal; point-triangle distance by Voronoi regions,
// Ericson 2005), and report the largest and the root-mean-square distances, each way and
// together. The Hausdorff distance is a lower bound of the true one (it is sampled); RMS
// weights every sample equally. Isolated vertices are not sampled (no surface).
//
// Meshes with coordinates far from 1 (above 2^100 or, not all zero, below 2^-100 in
// magnitude), whose squared distances and areas would overflow or underflow, are measured
// scaled by a power of two (exact) and the distances scaled back.
// Complexity: O(F log F) to build each tree, O(S log F) for S samples (typical).
// Throws InvalidArgument when a mesh has no faces, a non-finite position, when the sample
// count is 0, or when a distance exceeds the largest double.
//
// For two states of one mesh (the same connectivity: a clean part and its denoised copy), the
// face-normal deviation (normal_deviation(): θ, the mean and largest angle between the two
// normals of each face, and the faces flipped by more than 90 degrees, the figures of the
// denoising literature, e.g. Zheng et al. 2011, Zhang et al. 2015); for any two meshes, the
// one-sided distance of each vertex of one to the surface of the other
// (vertex_surface_distances(), on the same tree).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/halfedge_mesh.h"

namespace trilab {

struct MeshDistanceOptions {
    /// Face samples per mesh (vertices are always added); at least 1.
    std::size_t samples = 200000;
    /// Where given, one flag per face storage index of A (of B): only the flagged faces and
    /// their vertices are sampled (a region's part of the surface, `trilab-cli compare
    /// --region`); each sample is still measured against the other mesh's whole surface, so
    /// no cut edge adds a distance. nullptr: every face. A mask of another size, or one that
    /// flags no live face, throws InvalidArgument. Not owned.
    const std::vector<std::uint8_t>* a_faces = nullptr;
    const std::vector<std::uint8_t>* b_faces = nullptr;
};

struct MeshDistance {
    double hausdorff = 0;                   ///< max of the two one-sided maxima
    double rms = 0;                         ///< over all samples of both sides
    double a_to_b_max = 0, a_to_b_rms = 0;  ///< samples of A against B's surface
    double b_to_a_max = 0, b_to_a_rms = 0;  ///< samples of B against A's surface
    double diagonal = 0;      ///< bounding-box diagonal of A (to make errors relative)
    std::size_t samples = 0;  ///< total samples (both sides)
};

MeshDistance mesh_distance(const HalfedgeMesh& a, const HalfedgeMesh& b,
                           const MeshDistanceOptions& options = {});

/// Whether `a` and `b` have the same connectivity: as many vertex slots and live faces, and
/// the k-th live face of each with the same corners in the same order (vertex storage
/// indices). O(F).
bool same_connectivity(const HalfedgeMesh& a, const HalfedgeMesh& b);

/// The angles between the normals of the same face in two states of a mesh.
struct NormalDeviation {
    double mean_degrees = 0;     ///< θ: the mean angle (0 when no face was compared)
    double max_degrees = 0;      ///< the largest angle
    std::size_t faces = 0;       ///< faces compared
    std::size_t flipped = 0;     ///< faces whose normals are more than 90 degrees apart
    std::size_t degenerate = 0;  ///< faces left out: no normal in a or in b (zero area)
    std::size_t outside = 0;     ///< faces left out: not in the region
    double flipped_share() const { return faces ? double(flipped) / double(faces) : 0.0; }
};

/// θ and the flipped faces between `a` and `b`, which must have the same connectivity.
/// `region` (one weight per vertex storage index, core/algorithms/selection.h), when given,
/// keeps the faces whose three corners have a positive weight. Throws InvalidArgument when the
/// connectivity differs, or naming the region when it does not fit. O(F).
NormalDeviation normal_deviation(const HalfedgeMesh& a, const HalfedgeMesh& b,
                                 const std::vector<float>* region = nullptr);

/// For every vertex storage index of `from`, the distance from that vertex to the closest point
/// of `to`'s surface (any two meshes); NaN for deleted and isolated vertices. Scaled like
/// mesh_distance() for coordinates far from 1. Throws InvalidArgument when `to` has no faces or
/// a position is not finite. O(F log F + V log F) (typical).
std::vector<double> vertex_surface_distances(const HalfedgeMesh& from, const HalfedgeMesh& to);

/// Closest point to `p` on the triangle (a, b, c) (degenerate triangles included).
Point closest_point_on_triangle(const Point& p, const Point& a, const Point& b, const Point& c);

}  // namespace trilab
