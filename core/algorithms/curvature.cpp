// Discrete curvatures per vertex.
//
// Method: M. Meyer, M. Desbrun, P. Schröder, A. H. Barr, "Discrete differential-geometry
// operators for triangulated 2-manifolds", in Visualization and Mathematics III (Hege,
// Polthier, eds.), Springer 2003, pp. 35-57.
//
// For an interior vertex x_i with one-ring neighbours x_j, alpha_ij and beta_ij the two
// angles opposite to the edge ij, and theta_T the angle of triangle T at x_i:
//
//   A_mixed = sum over the triangles T around x_i of
//               1/8 (|x_i - x_j|^2 cot(angle at x_k) + |x_i - x_k|^2 cot(angle at x_j))
//                                          when T has no obtuse angle (Voronoi region),
//               area(T) / 2                when the angle of T at x_i is obtuse,
//               area(T) / 4                when another angle of T is obtuse;
//   K(x_i)  = 1 / (2 A_mixed) sum_j (cot alpha_ij + cot beta_ij) (x_i - x_j)   (= 2 H n)
//   H       = |K(x_i)| / 2, positive when K(x_i) points along the area-weighted normal n
//             (so a sphere with outward orientation has H = 1/r > 0; flipping the
//             orientation flips the sign of H and of k1, k2);
//   K_G     = (2 pi - sum_T theta_T) / A_mixed                       (angle deficit)
//   k1,2    = H +- sqrt(max(H^2 - K_G, 0))
//   S       = (2 / pi) atan((k1 + k2) / (k1 - k2)), evaluated as (2 / pi) atan2(k1 + k2,
//             k1 - k2): k1 >= k2, so umbilics (k1 = k2) give +-1 by the sign of H and flat
//             points (k1 = k2 = 0) give 0 without a division by zero.
//
// Flat points: where the Laplacian sum or the angle deficit cancels to below 1e-12 of the
// magnitude of its terms it is rounding noise and taken as exactly 0, so a plane gives
// H = K = k1 = k2 = S = 0 exactly instead of noise amplified by the square root in k1,2 and
// by the ratio in S.
//
// Each vertex gathers the terms of the faces around it, in the order of its fan, on every
// thread (core/parallel.h: the same bits for any number of threads); per face the cotangents
// come from cot = (a . b) / |a x b| with |a x b| = twice the face area, and two angles from
// atan2(|a x b|, a . b), the third being pi minus those, so a face's three angles sum to pi,
// also when it is degenerate (a collinear face has angles 0, 0, pi; a face with coincident
// corners gets pi shared among those corners). Hence sum_v (K_G A_mixed) = 2 pi chi up to
// rounding on closed meshes whose vertices are all valid. Degenerate (zero-area) faces add no
// cotangent weight and no area; a face with a non-finite area makes its corners invalid.
//
// Boundary vertices (the Voronoi formulas need a closed one-ring), isolated vertices, vertices
// whose mixed area is zero (all incident faces degenerate) and vertices whose values would not
// be finite (non-finite positions, overflow) get valid = 0 and all values 0 (area included).
//
// Complexity: O(V + F) time (each face's terms computed once per corner), no scratch memory
// beyond the output; no allocation per face.
#include "core/algorithms/curvature.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/parallel.h"
#include "core/types.h"

namespace trilab {

namespace {

constexpr double kPi = 3.14159265358979323846;
/// A sum whose magnitude is below this fraction of the magnitudes of its terms is rounding
/// noise (double precision gives ~1e-16 per operation) and is taken as exactly zero.
constexpr double kCancellation = 1e-12;

/// Per-vertex sums gathered from the faces around it.
struct Sums {
    double area = 0;           ///< mixed Voronoi area
    double angle = 0;          ///< sum of the corner angles
    Vector3 laplace{0, 0, 0};  ///< sum_j (cot alpha_ij + cot beta_ij) (x_i - x_j)
    double magnitude = 0;      ///< sum of the L1 norms of the terms of `laplace`
    Vector3 normal{0, 0, 0};   ///< sum of the incident faces' area vectors
};

/// Adds to `sums` what face f gives its corner at vertex `at`.
void add_corner(const HalfedgeMesh& mesh, Face f, Vertex at, Sums& sums) {
    const auto v = mesh.face_vertices(f);
    const Point* p[3] = {&mesh.position(v[0]), &mesh.position(v[1]), &mesh.position(v[2])};
    // e[k] is the edge opposite to corner k, from corner k+1 to corner k+2.
    const Vector3 e[3] = {*p[2] - *p[1], *p[0] - *p[2], *p[1] - *p[0]};
    const Vector3 area_vector = e[2].cross(-e[1]);
    const double twice_area = area_vector.norm();
    const bool proper = twice_area > 0 && std::isfinite(twice_area);

    // At corner k the two edge vectors are e[k+2] (to k+1) and -e[k+1] (to k+2).
    double dot[3], cot[3], angle[3];
    for (int k = 0; k < 3; ++k) {
        dot[k] = -e[(k + 2) % 3].dot(e[(k + 1) % 3]);
        cot[k] = proper ? dot[k] / twice_area : 0.0;
    }
    if (proper) {
        // |a x b| is twice the area at every corner; the third angle completes pi (one
        // atan2 fewer, and the angle sum is pi by construction).
        angle[0] = std::atan2(twice_area, dot[0]);
        angle[1] = std::atan2(twice_area, dot[1]);
        angle[2] = kPi - angle[0] - angle[1];
    } else if (std::isfinite(twice_area)) {
        // A degenerate face. A collinear one has angles (0, 0, pi): pi at the corner between
        // the other two (a . b < 0). One with coincident corners has every a . b >= 0; in the
        // limit the corners at a zero-length edge (a . b = 0) share pi.
        int middle = -1, shared = 0;
        for (int k = 0; k < 3; ++k) {
            if (dot[k] < 0) middle = k;
            shared += dot[k] == 0 ? 1 : 0;
        }
        for (int k = 0; k < 3; ++k) {
            if (middle >= 0)
                angle[k] = k == middle ? kPi : 0.0;
            else
                angle[k] = shared == 0 ? kPi / 3 : (dot[k] == 0 ? kPi / shared : 0.0);
        }
    } else {
        // Non-finite corners (or an overflowing area): the corners' values are undefined.
        angle[0] = angle[1] = angle[2] = std::numeric_limits<double>::quiet_NaN();
    }
    const int k = v[0] == at ? 0 : (v[1] == at ? 1 : 2);
    const int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
    sums.angle += angle[k];
    sums.normal += area_vector;
    // The edge opposite to corner j, from corner j+1 to corner j+2 (e[j]), has weight cot[j]
    // and term cot[j] e[j], which its first end subtracts and its second adds: corner k is the
    // second end of the edge opposite k1 and the first end of the edge opposite k2.
    const Vector3 to_second = cot[k1] * e[k1], to_first = cot[k2] * e[k2];
    sums.laplace += to_second - to_first;
    sums.magnitude += to_second.lpNorm<1>() + to_first.lpNorm<1>();
    if (!proper) return;
    const bool obtuse = dot[0] < 0 || dot[1] < 0 || dot[2] < 0;
    if (!obtuse)
        sums.area += 0.125 * (e[k1].squaredNorm() * cot[k1] + e[k2].squaredNorm() * cot[k2]);
    else
        sums.area += (dot[k] < 0 ? 0.25 : 0.125) * twice_area;
}

}  // namespace

VertexCurvatures compute_curvatures(const HalfedgeMesh& mesh) {
    const std::size_t n = mesh.vertices_size();
    VertexCurvatures c;
    c.mean.assign(n, 0.0);
    c.gaussian.assign(n, 0.0);
    c.k1.assign(n, 0.0);
    c.k2.assign(n, 0.0);
    c.shape_index.assign(n, 0.0);
    c.valid.assign(n, 0);
    c.area.assign(n, 0.0);
    const bool garbage = mesh.has_garbage();
    // Each vertex gathers its faces' terms in the order of its fan and writes only its own
    // values: the same bits for any number of threads (core/parallel.h).
    parallel_for_blocks(0, n, [&](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) {
            const Vertex v(static_cast<Index>(i));
            if ((garbage && mesh.is_deleted(v)) || mesh.is_isolated(v) || mesh.is_boundary(v))
                continue;
            Sums sums;
            for (Face f : mesh.faces_around(v)) add_corner(mesh, f, v, sums);
            const double area = sums.area;
            if (!(area > 0) || !std::isfinite(area)) continue;
            // Sums that cancel down to rounding noise are flat: exactly zero.
            const Vector3& laplace = sums.laplace;
            const double h_abs = laplace.lpNorm<1>() <= kCancellation * sums.magnitude
                                     ? 0.0
                                     : laplace.norm() / (4.0 * area);
            const double mean = laplace.dot(sums.normal) < 0 ? -h_abs : h_abs;
            const double deficit = 2.0 * kPi - sums.angle;
            const double gaussian =
                std::abs(deficit) <= kCancellation * 2.0 * kPi ? 0.0 : deficit / area;
            const double root = std::sqrt(std::max(mean * mean - gaussian, 0.0));
            const double k1 = mean + root, k2 = mean - root;
            const double shape = (2.0 / kPi) * std::atan2(k1 + k2, k1 - k2);
            if (!std::isfinite(mean) || !std::isfinite(gaussian) || !std::isfinite(k1) ||
                !std::isfinite(k2) || !std::isfinite(shape))
                continue;
            c.mean[i] = mean;
            c.gaussian[i] = gaussian;
            c.k1[i] = k1;
            c.k2[i] = k2;
            c.shape_index[i] = shape;
            c.valid[i] = 1;
            c.area[i] = area;
        }
    });
    return c;
}

}  // namespace trilab
