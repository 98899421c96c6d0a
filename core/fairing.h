#pragma once
// Fairing (smoothing) by diffusion, dX/dt = L(X) (section 1.2.3 of the reference report), with
// the operators of core/laplacian.h:
//  - explicit Euler (1.4/1.6): X <- X + step·L·X;
//  - implicit Euler (1.13-1.14, Desbrun-Meyer-Schröder-Barr 1999): (I - step·L)·X' = X,
//    solved in the symmetric form (S + step·K)·X' = S·X - step·K_fb·X_b (fixed vertices on
//    the right) with Eigen::SimplicialLDLT. The factorization is reused across iterations when
//    the weights do not depend on the geometry (umbrella); a failed or non-finite
//    factorization falls back to Jacobi-preconditioned conjugate gradients warm-started
//    from the current positions. The report names the solver and the relative residual.
//  - Taubin λ|μ (Taubin 1995): explicit umbrella steps X <- X + λ·L·X then X <- X + μ·L·X
//    per iteration (λ > 0, μ < -λ); `step` is not used.
//  - volume preservation (1.15): after every step the mesh is scaled about the centroid of
//    its moving vertices by (V0/Vn)^(1/3). Closed meshes only.
//
// Boundary vertices stay fixed; isolated vertices never move. Connectivity and attributes
// other than positions are copied unchanged. Never produces NaN: a step that would leave
// non-finite or astronomically large (> 1e100) coordinates stops the run (result.diverged,
// steps so far kept).
// Throws InvalidArgument naming the option (`step`, `iterations`, `taubin_lambda`,
// `taubin_mu`, `integration`, `preserve_volume`) before doing anything; Cancelled from the
// progress. The input mesh is never modified.
// Complexity: explicit O(iterations · (V + F)); implicit one sparse factorization per
// iteration (one in all for umbrella) plus a solve per iteration.
#include <cstddef>
#include <string>
#include <vector>

#include "core/enum_table.h"
#include "core/halfedge_mesh.h"
#include "core/laplacian.h"
#include "core/progress.h"

namespace trilab {

enum class FairingOperator { Umbrella, ImprovedUmbrella, CurvatureFlow, SecondOrder, Taubin };
/// The one table of FairingOperator (core/enum_table.h): identifier and label of each value.
inline constexpr EnumEntry<FairingOperator> kFairingOperators[] = {
    {FairingOperator::Umbrella, "umbrella", "Umbrella"},
    {FairingOperator::ImprovedUmbrella, "improved-umbrella", "Improved umbrella"},
    {FairingOperator::CurvatureFlow, "curvature-flow", "Curvature flow (cotangent)"},
    {FairingOperator::SecondOrder, "second-order", "Second-order difference"},
    {FairingOperator::Taubin, "taubin", "Taubin lambda|mu"},
};
enum class Integration { Explicit, Implicit };
/// The one table of Integration (core/enum_table.h): identifier and label of each value.
inline constexpr EnumEntry<Integration> kIntegrations[] = {
    {Integration::Explicit, "explicit", "Explicit"},
    {Integration::Implicit, "implicit", "Implicit"},
};
enum class ImplicitSolver { Auto, Direct, Iterative };
/// What boundary vertices do: stay where they are, or slide along the boundary curve.
enum class BoundaryMode { Fixed, Slide };
/// The one table of BoundaryMode (core/enum_table.h): identifier and label of each value.
inline constexpr EnumEntry<BoundaryMode> kBoundaryModes[] = {
    {BoundaryMode::Fixed, "fixed", "Fixed"},
    {BoundaryMode::Slide, "slide", "Slides along its curve"},
};

const char* boundary_mode_name(BoundaryMode mode);  ///< "fixed", "slide"
BoundaryMode parse_boundary_mode(const std::string& name);

/// "umbrella", "improved-umbrella", "curvature-flow", "second-order", "taubin".
const char* fairing_operator_name(FairingOperator op);
/// Throws InvalidArgument listing the names.
FairingOperator parse_fairing_operator(const std::string& name);
const char* integration_name(Integration integration);  ///< "explicit", "implicit"
Integration parse_integration(const std::string& name);

/// The largest accepted FairingOptions::iterations.
inline constexpr int kMaxFairingIterations = 10000;

struct FairingOptions {
    FairingOperator op = FairingOperator::Umbrella;
    Integration integration = Integration::Explicit;
    double step = 0.5;             ///< λ·dt, finite and >= 0
    int iterations = 1;            ///< in [1, 10000]
    bool preserve_volume = false;  ///< closed meshes only
    double taubin_lambda = 0.5;    ///< in (0, 1]
    double taubin_mu = -0.53;      ///< < -taubin_lambda
    /// Auto/Direct: SimplicialLDLT, CG when it fails. Iterative: CG only.
    ImplicitSolver solver = ImplicitSolver::Auto;
    double cg_tolerance = 1e-10;  ///< relative residual target of the iterative solver
    BoundaryMode boundary = BoundaryMode::Fixed;
    /// false: steps holds only the result (saves a mesh copy per iteration).
    bool keep_steps = true;
};

struct FairingResult {
    /// One mesh per iteration (geometry changes only), the last one is the result.
    std::vector<HalfedgeMesh> steps;
    /// Human-readable lines: operator, solver and residual per implicit step, clamps.
    std::vector<std::string> report;
    std::string solver;       ///< "none", "SimplicialLDLT", "ConjugateGradient(Jacobi)"
    double max_residual = 0;  ///< largest relative residual of the implicit solves
    std::size_t factorizations = 0;
    std::size_t cg_iterations = 0;     ///< summed over the iterative solves
    double factorization_ms = 0;       ///< time in sparse Cholesky factorizations
    double solve_ms = 0;               ///< time in implicit solves (either solver)
    LaplacianDiagnostics diagnostics;  ///< summed over all builds (stalled: largest per build)
    double initial_volume = 0, final_volume = 0;
    bool diverged = false;
};

/// Smooths `mesh`; see the file comment.
FairingResult smooth(const HalfedgeMesh& mesh, const FairingOptions& options, Progress& progress);
FairingResult smooth(const HalfedgeMesh& mesh, const FairingOptions& options);

}  // namespace trilab
