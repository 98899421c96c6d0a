#pragma once
// Discrete Laplacians of a triangle mesh as Eigen sparse matrices (sections 1.2.4-1.2.7 of the
// reference report), shared by explicit and implicit fairing and the spectral decomposition.
// Every operator is L = -S⁻¹·K with K symmetric positive semi-definite, K·1 = 0, and S
// diagonal, positive on free rows; L·x approximates the Laplacian of x (x + dt·L·x smooths)
// and scales like x. Implicit Euler is solved as (S + dt·K)·X' = S·X, which is SPD.
//  - Umbrella (1.5): w_ij = 1, S_i = valence.
//  - ImprovedUmbrella (1.7): w_ij = h/|e_ij|, S_i = E_i/(2h), h the mean edge length.
//  - CurvatureFlow (1.9, Desbrun, Meyer, Schröder, Barr 1999): cotangent weights, negative
//    ones clamped to 0 by default (K stays PSD).
//  - SecondOrder (1.10-1.12, Guskov, Sweldens, Schröder 1999): K = Cᵀ·C over the interior
//    edges' hinge coefficients, S_i = ½ Σ_j |K_ij|, so every explicit step <= 1 is stable.
// Umbrella does not depend on the positions; the others are rebuilt for every step.
// Rows are the live, non-isolated vertices in storage order. Fixed rows of L are zero:
// boundary vertices by default, LaplacianOptions::fixed_vertices, and a free vertex whose S_i
// vanishes (counted as stalled). MassMatrix Barycentric / Voronoi (Meyer et al.
// 2003) replace S by a lumped area mass for the spectral decomposition.
// Never NaN: degenerate geometry is clamped and counted in LaplacianDiagnostics.
// Complexity: O(vertices + faces) to build. The weights' derivations (the hinge
// coefficients, SecondOrder's normalizer) are in laplacian.cpp.
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
