#pragma once
// Discrete Laplacians of a triangle mesh as Eigen sparse matrices (sections 1.2.4-1.2.7 of the
// reference report), shared by explicit and implicit fairing.
//
// Sign convention (one for every operator): L·x approximates the Laplacian of x, so that
// x + dt·L·x smooths (explicit Euler, 1.4/1.6) and L·(constant) = 0. Every operator is
// written as L = -S⁻¹·K with
//  - K symmetric positive semi-definite ("stiffness"), K·1 = 0;
//  - S diagonal and positive on free rows (the row normalizer).
// Implicit Euler (1.13-1.14), (I - dt·L)·X' = X, is solved in the symmetric form
// (S + dt·K)·X' = S·X, which is SPD whenever K is PSD and S > 0.
//
// Operators (w_ij: symmetric edge weight; K = D - W with D_ii = sum_j w_ij). Every operator is
// scale-free: L·x scales like x, so a mesh and the same mesh scaled by any factor smooth alike.
//  - Umbrella (1.5): w_ij = 1, S_i = valence. L_i = 1/m sum (x_j - x_i).
//  - ImprovedUmbrella (1.7) with every length measured in units of the mean edge length h
//    (of the positions it is built on): w_ij = h/|e_ij|, S_i = E_i/(2h) with E_i = sum_j
//    |e_ij|, so L_i = 2h²/E sum (x_j - x_i)/|e_ij|, i.e. h² x (1.7). On a mesh of equal edges
//    it is twice the umbrella. Lengths are frozen for one build (one step).
//  - CurvatureFlow (1.9, Desbrun-Meyer-Schröder-Barr 1999): w_ij = cot a_ij + cot b_ij,
//    S_i = sum_j w_ij (normalized cotangent weights). Negative weights (obtuse pairs) are
//    clamped to 0 by default and counted; then K stays PSD. Linear precision holds where
//    nothing was clamped (e.g. a flat grid).
//  - SecondOrder (1.10-1.12, Guskov-Sweldens-Schröder 1999): K = Cᵀ·C, where C has one row
//    per interior edge e holding the hinge coefficients c_{e,·}. (K·x)_i / K_ii is the
//    relaxation update (1.12): x_i <- -(sum_e c_{e,i} a_e) / sum_e c_{e,i}² with a_e =
//    sum_{j != i} c_{e,j} x_j. Applied to every vertex at once (Jacobi) that update is not
//    stable: K is a discrete bi-Laplacian, whose highest frequency has K's Rayleigh quotient
//    above 2 K_ii (16/6 K_ii for the 1-D stencil 1 -4 6 -4 1; about 2.3 K_ii on a noisy
//    sphere), so x <- x - D⁻¹K·x amplifies it (a regular pattern of spikes). So S_i = ½ sum_j
//    |K_ij| (half K's absolute row sum): by Gershgorin every eigenvalue of S⁻¹K lies in
//    [0, 2], as for the umbrella, every explicit step <= 1 is stable, and step 1 is the
//    relaxation (1.12) damped per vertex by 2 K_ii / sum_j |K_ij| <= 1 (about 2/3; exactly
//    1 where the row's off-diagonal entries are all <= 0).
// Fixed-weight operators (Umbrella) do not depend on the positions; the others are rebuilt
// from the current positions for every step.
//
// Derivation of the hinge coefficients. Edge e = (v1, v2), length l, unit direction t,
// triangles T1 = (v1, v2, v3) and T2 = (v2, v1, v4) unfolded into the plane, n the in-plane
// unit normal of e pointing into T1. D(e) is the jump, across e, of the derivative along n
// of the piecewise-linear function f with values f_i at the corners (the tangential
// derivative is continuous). Place v1 at (0,0), v2 at (l,0), v3 at (a,h3), v4 at (b,-h4).
// The hat functions' y-derivatives are, in T1: φ3: 1/h3, φ1: -(l-a)/(l·h3), φ2: -a/(l·h3);
// in T2: φ4: -1/h4, φ1: (l-b)/(l·h4), φ2: b/(l·h4). Hence D = sum c_i f_i with
//   c3 = 1/h3, c4 = 1/h4, c1 = -(l-a)/(l·h3) - (l-b)/(l·h4), c2 = -a/(l·h3) - b/(l·h4).
// With h3 = 2·A1/l, l - a = (v2 - v3)·t, a = (v3 - v1)·t (signed areas and the edge length,
// invariant under the unfolding) and cot θ = dot/|cross| at each corner, multiplying by l
// (to make D dimensionless, like a dihedral angle) gives
//   c3 = cot θ1(T1) + cot θ2(T1),  c4 = cot θ1(T2) + cot θ2(T2),
//   c1 = -(cot θ2(T1) + cot θ2(T2)),  c2 = -(cot θ1(T1) + cot θ1(T2)),
// θk(T) the angle of T at vk. They sum to 0 (constants) and annihilate f = x and f = y in the
// unfolded plane (linear functions): c2·l + c3·a - c4·b = -a/h3 - b/h4 + a/h3 + b/h4 = 0 (times
// l) and c3·h3 - c4·h4 = 0.
//
// Vertex index map: rows/columns are the live, non-isolated vertices in storage order.
// Isolated and deleted vertices have no row and never move. Boundary vertices are fixed by
// default (a fixed row of L is zero). A free vertex whose normalizer S_i vanishes (all its
// weights clamped, degenerate fan) is fixed too and counted as stalled.
//
// Mass matrix option (used by the spectral decomposition, core/algorithms/spectral.h): by default S
// is the row normalizer above. MassMatrix::Barycentric and MassMatrix::Voronoi replace it by a
// lumped mass S_i = 2·A_i with A_i the barycentric (a third of the incident triangle areas)
// or the mixed Voronoi area (Meyer, Desbrun, Schröder, Barr 2003: Voronoi region of non-obtuse
// triangles, half / a quarter of an obtuse triangle's area). The factor 2 matches K's full
// cotangent weights (cot a + cot b = 2 x the FEM stiffness), so for CurvatureFlow K·x = λ·S·x
// approximates the Laplace-Beltrami eigenproblem (on a sphere of radius r: l(l+1)/r²).
//
// Degenerate geometry never produces NaN: corners of zero-area triangles get cotangent 0,
// cotangents are clamped to ±kMaxCotangent, edge lengths below 1e-6 x the mean edge length are
// raised to it; every such event is counted in LaplacianDiagnostics.
// Complexity: O(vertices + faces) to build (the pattern once, then values in place).
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "core/enum_table.h"
#include "core/halfedge_mesh.h"

namespace trilab {

enum class LaplacianOperator { Umbrella, ImprovedUmbrella, CurvatureFlow, SecondOrder };
/// The one table of LaplacianOperator (core/enum_table.h): identifier and label of each value.
inline constexpr EnumEntry<LaplacianOperator> kLaplacianOperators[] = {
    {LaplacianOperator::Umbrella, "umbrella", "Umbrella"},
    {LaplacianOperator::ImprovedUmbrella, "improved-umbrella", "Improved umbrella"},
    {LaplacianOperator::CurvatureFlow, "curvature-flow", "Curvature flow (cotangent)"},
    {LaplacianOperator::SecondOrder, "second-order", "Second-order difference"},
};

/// "umbrella", "improved-umbrella", "curvature-flow", "second-order".
const char* laplacian_operator_name(LaplacianOperator op);
/// The operator of that name; throws InvalidArgument listing the names otherwise.
LaplacianOperator parse_laplacian_operator(const std::string& name);

/// The largest magnitude a corner cotangent may take (about a 0.06° angle).
inline constexpr double kMaxCotangent = 1e3;

/// Rows of the operators <-> mesh vertices.
struct VertexIndexMap {
    std::vector<Index> row_of;      ///< per vertex storage index; kInvalidIndex: no row
    std::vector<Vertex> vertex_of;  ///< per row
    std::size_t rows() const { return vertex_of.size(); }
};
/// Live, non-isolated vertices in storage order.
VertexIndexMap make_vertex_index_map(const HalfedgeMesh& mesh);

/// What S (the diagonal of L = -S⁻¹K) holds; see the file comment.
enum class MassMatrix {
    Normalizer,   ///< the operator's own row normalizer (valence, E_i/2, sum of weights, K_ii)
    Barycentric,  ///< 2 x (a third of the incident triangle areas)
    Voronoi,      ///< 2 x the mixed Voronoi area (Meyer et al. 2003)
};
/// The one table of MassMatrix (core/enum_table.h): identifier and label of each value.
inline constexpr EnumEntry<MassMatrix> kMassMatrices[] = {
    {MassMatrix::Normalizer, "normalizer", "Operator's normalizer"},
    {MassMatrix::Barycentric, "barycentric", "Barycentric area"},
    {MassMatrix::Voronoi, "voronoi", "Voronoi area"},
};
/// "normalizer", "barycentric", "voronoi".
const char* mass_matrix_name(MassMatrix mass);
/// Throws InvalidArgument listing the names.
MassMatrix parse_mass_matrix(const std::string& name);

struct LaplacianOptions {
    bool fix_boundary = true;                  ///< boundary vertices get zero rows in L
    bool clamp_negative_cotangents = true;     ///< CurvatureFlow: w_ij < 0 -> 0 (keeps K PSD)
    MassMatrix mass = MassMatrix::Normalizer;  ///< what S holds
    /// Vertices fixed besides the boundary, per vertex storage index (1 = fixed); empty:
    /// none. Fairing fixes the coincident copies that cannot be joined (core/algorithms/fairing.h).
    std::vector<std::uint8_t> fixed_vertices;
};

/// What was clamped while building (all zero on a well-shaped mesh).
struct LaplacianDiagnostics {
    std::size_t negative_weights_clamped = 0;  ///< CurvatureFlow edges with w_ij < 0
    std::size_t degenerate_corners = 0;        ///< corners of zero-area triangles (cot := 0)
    std::size_t cotangents_clamped = 0;        ///< |cot| above kMaxCotangent
    std::size_t short_edges = 0;               ///< ImprovedUmbrella lengths raised
    std::size_t stalled_vertices = 0;          ///< free vertices fixed because S_i = 0
    std::size_t total() const {
        return negative_weights_clamped + degenerate_corners + cotangents_clamped + short_edges +
               stalled_vertices;
    }
};

using SparseMatrix = Eigen::SparseMatrix<double>;

struct Laplacian {
    LaplacianOperator op = LaplacianOperator::Umbrella;
    VertexIndexMap map;
    SparseMatrix K;                    ///< symmetric PSD, rows() x rows()
    Eigen::VectorXd S;                 ///< diagonal normalizer; 1 on fixed rows (unused there)
    std::vector<std::uint8_t> fixed;   ///< per row: 1 = does not move
    SparseMatrix L;                    ///< -S⁻¹K on free rows, zero rows on fixed ones
    LaplacianDiagnostics diagnostics;  ///< of the last build or refresh
    LaplacianOptions options;
    /// Value positions in K (and L) that refresh_laplacian() writes: per row its diagonal,
    /// per edge its two off-diagonal entries (SecondOrder: per interior edge its hinge's
    /// 4 x 4 block). Internal to build/refresh.
    std::vector<Index> diag_slots, edge_slots;
    std::vector<double> halfedge_cotangents;  ///< CurvatureFlow: refresh's per-halfedge buffer
    std::size_t n_free() const;
};

/// Builds the operator over the current positions. Never throws on geometry; throws nothing
/// but std::bad_alloc.
Laplacian build_laplacian(const HalfedgeMesh& mesh, LaplacianOperator op,
                          const LaplacianOptions& options = {});

/// Recomputes the values of `lap` (K, S, L, fixed, diagnostics) over the current positions of
/// `mesh`, which must have the connectivity `lap` was built on. No allocation: explicit
/// fairing calls it every iteration.
void refresh_laplacian(const HalfedgeMesh& mesh, Laplacian& lap);

/// Positions of the mapped vertices, one row per map row (rows() x 3).
Eigen::MatrixXd gather_positions(const HalfedgeMesh& mesh, const VertexIndexMap& map);
/// Writes rows back to the mapped vertices (other vertices unchanged).
void scatter_positions(HalfedgeMesh& mesh, const VertexIndexMap& map, const Eigen::MatrixXd& x);

}  // namespace trilab
