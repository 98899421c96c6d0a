#pragma once
// Discrete curvatures per vertex, after Meyer, Desbrun, Schröder and Barr, "Discrete
// differential-geometry operators for triangulated 2-manifolds" (2003): the mean curvature
// from the cotangent Laplacian of the positions over the mixed Voronoi area, the Gaussian
// curvature from the angle deficit over the same area, and the principal curvatures
// k1,2 = H +- sqrt(max(H^2 - K, 0)).
//
// Sign convention: with outward (counter-clockwise) orientation a sphere of radius r has
// H = k1 = k2 = 1/r > 0. Boundary and isolated vertices, and vertices whose area vanishes,
// get valid = 0 and zero values (the Voronoi formulas need a closed 1-ring).
// Complexity: linear in the mesh size. Never produces NaN.
#include <cstdint>
#include <vector>

#include "core/halfedge_mesh.h"

namespace trilab {

/// Per-vertex curvature fields, indexed by vertex storage index (mesh.vertices_size()).
struct VertexCurvatures {
    std::vector<double> mean;         ///< H = (k1 + k2) / 2
    std::vector<double> gaussian;     ///< K = k1 k2
    std::vector<double> k1;           ///< first (larger) principal curvature
    std::vector<double> k2;           ///< second (smaller) principal curvature
    std::vector<double> shape_index;  ///< Koenderink's S = (2/pi) atan((k1 + k2) / (k1 - k2))
    std::vector<std::uint8_t> valid;  ///< 1 where the values are meaningful
    std::vector<double> area;         ///< mixed Voronoi area A_mixed (0 where valid is 0);
                                      ///< sum(gaussian * area) is the total curvature
};

VertexCurvatures compute_curvatures(const HalfedgeMesh& mesh);

}  // namespace trilab
