#pragma once
// Triangle and mesh quality figures: what remeshing improves and what a user reads before and
// after (`trilab-cli info --quality`).
//
// Per triangle: its smallest angle, and Frey and Borouchaki's shape measure
// Q = 4 sqrt(3) A / (P h_max) ("Surface mesh quality evaluation", IJNME 1999; A the area, P the
// perimeter, h_max the longest edge), 1 for an equilateral triangle and 0 for a degenerate one.
// Per mesh: the minimum and mean of those; the share of all angles under 30 degrees; the share
// of edges whose length lies within [0.8 L, 4/3 L] for a target length L (Botsch and Kobbelt's
// band: the lengths isotropic remeshing leaves alone; L defaults to the mean edge length); the
// share of interior vertices with valence 6 (and of boundary vertices with valence 4).
// No preconditions (a mesh without faces gives zeros and counts of 0); degenerate triangles
// count with angle 0 and Q 0, never NaN. Throws InvalidArgument for a length that is given and
// not positive and finite. Complexity: O(V + E + F), one pass each.
#include <cstddef>
#include <optional>
#include <vector>

#include "core/halfedge_mesh.h"

namespace trilab {

/// The smallest interior angle of face f in degrees (0 for a degenerate face).
double triangle_min_angle(const HalfedgeMesh& mesh, Face f);
/// Frey-Borouchaki Q of face f: 4 sqrt(3) area / (perimeter * longest edge), in [0, 1].
double triangle_quality(const HalfedgeMesh& mesh, Face f);

/// One value per face storage index (NaN for deleted faces): triangle_quality(), or
/// triangle_min_angle() when `min_angle`, for a colouring.
std::vector<double> face_quality_field(const HalfedgeMesh& mesh, bool min_angle);

struct MeshQuality {
    std::size_t faces = 0;
    double min_angle = 0;          ///< degrees, smallest over all faces
    double mean_min_angle = 0;     ///< degrees, mean of the per-face smallest angles
    double angles_under_30 = 0;    ///< share of all angles (3 per face) under 30 degrees
    double min_q = 0, mean_q = 0;  ///< Frey-Borouchaki Q
    double length = 0;             ///< the L the band is for
    std::size_t edges = 0;
    double edges_in_band = 0;  ///< share of edges with length in [0.8 L, 4/3 L]
    double min_edge = 0, max_edge = 0, mean_edge = 0;
    std::size_t interior_vertices = 0, boundary_vertices = 0;
    double valence6 = 0;           ///< share of interior vertices with valence 6
    double valence4_boundary = 0;  ///< share of boundary vertices (with faces) with valence 4
};

/// The figures above; `length` is L for the band (absent: the mean edge length).
MeshQuality mesh_quality(const HalfedgeMesh& mesh, std::optional<double> length = std::nullopt);

/// The spread of the cotangent Laplacian L = -M⁻¹K (Pinkall and Polthier 1993; Meyer et al.
/// 2003): what makes curvature-flow fairing and the spectral decomposition suffer on a mesh
/// with bad triangles, and what remeshing improves (the spectral lens shows it before and
/// after an operation). With w_ij = (cot a_ij + cot b_ij) / 2 the weight of edge ij (the
/// corners opposite it; one corner on the boundary), K's diagonal entry at vertex i is
/// k_i = sum_j w_ij and M's is m_i = a third of the area of the faces at i.
/// No preconditions: a mesh without faces gives zeros. A corner of a face without area has no
/// cotangent (counted in degenerate_corners, its weight left out). O(V + E + F).
struct CotangentSpread {
    std::size_t edges = 0;
    std::size_t negative_weights = 0;  ///< edges with w_ij < 0 (not Delaunay)
    double negative_share = 0;         ///< of the edges
    double min_weight = 0, max_weight = 0;
    /// The largest |w_ij| over the median |w_ij| (1 inside a grid of equilateral triangles;
    /// a corner of 1 degree alone gives about 57; 0 when the median is 0).
    double weight_ratio = 0;
    std::size_t degenerate_corners = 0;  ///< corners of faces without area
    std::size_t vertices = 0;            ///< live vertices with faces
    /// Vertices whose diagonal k_i is not positive (their row of K is indefinite).
    std::size_t nonpositive_diagonal = 0;
    /// The largest k_i over the smallest positive one, and the same for k_i / m_i (the
    /// diagonal of L itself, where the mesh's size drops out: the spread of the time scales an
    /// explicit step must respect). 0 where no vertex has a positive one.
    double diagonal_ratio = 0, normalized_diagonal_ratio = 0;
};
CotangentSpread cotangent_spread(const HalfedgeMesh& mesh);

}  // namespace trilab
