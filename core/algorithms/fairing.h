#pragma once
// Fairing (smoothing) by diffusion, dX/dt = L(X) (section 1.2.3 of the reference report), with
// the operators of core/algorithms/laplacian.h:
//  - explicit Euler (1.4/1.6): X <- X + step·L·X;
//  - implicit Euler (1.13-1.14, Desbrun-Meyer-Schröder-Barr 1999): (I - step·L)·X' = X,
//    solved in the symmetric form (S + step·K)·X' = S·X - step·K_fb·X_b (fixed vertices on
//    the right) with Eigen::SimplicialLDLT (reused across iterations when the weights do not
//    depend on the geometry) or Jacobi-preconditioned conjugate gradients warm-started from
//    the current positions, chosen by the system's condition bound and size;
//  - Taubin λ|μ (Taubin 1995): explicit umbrella steps X <- X + λ·L·X then X <- X + μ·L·X
//    per iteration (0 < λ <= 1, -1 <= μ < -λ, pass band k_PB = 1/λ + 1/μ below 1), or μ
//    from k_PB. Taubin uses λ and μ, never `step`;
//  - volume preservation (1.15): after every step the mesh is scaled about the centroid of
//    its vertices by (V0/Vn)^(1/3). Closed meshes only.
//
// What `step` means (every operator is scale-free, so it means the same on any mesh size):
//  - Umbrella, CurvatureFlow: the fraction of the way to the neighbours' (weighted) average
//    each vertex moves; every explicit step <= 1 is stable, the limit is about 1.3 (umbrella)
//    and 1.0-1.3 (curvature flow) on typical meshes.
//  - ImprovedUmbrella: twice that on a mesh of equal edges (lengths in units of the mean edge
//    length); the explicit limit is about 0.4-0.5, and it falls during a run when short edges
//    shorten further (the reference's "numerical instability"): prefer implicit.
//  - SecondOrder: step 1 is the relaxation (1.12), damped per vertex (about 2/3) so that the
//    simultaneous update is stable; every explicit step <= 1 is stable (the limit is about
//    1.2-1.3).
//  - implicit: any step > 0 is stable; step t smooths about like t explicit steps of 1.
// max_stable_explicit_step() estimates the limit for the actual mesh (explicit Euler is stable
// while step < 2/ρ(S⁻¹K)).
//
// Health checks (never a silent failure): an implicit solve whose relative residual is above
// max_relative_residual (1e-8) is retried with the sparse Cholesky factorization; if that
// fails too the run stops. An explicit iteration stops the run when a coordinate is not
// finite, the bounding box grows by more than 10 % in one iteration, the fairing energy xᵀKx
// of the step's own operator grows (explicit Euler below the stable limit never lets it grow;
// Taubin: more than its pass-band gain allows), the surface area falls below 10 % of the
// previous iteration's, or the volume of a closed mesh changes sign (implicit runs check the
// residual, finiteness and the volume's sign). The energy check runs where the step is not
// provably stable (step·G > 2, G Gershgorin's bound on S⁻¹K: 2 for umbrella, curvature flow
// and second order, about 4 for the improved umbrella); the area check with it and for the
// geometry-dependent operators; the volume's sign on every iteration of a closed mesh (even a
// stable step turns a tetrahedron inside out). So a provably stable umbrella or Taubin iteration
// costs one pass over the edges and one over the vertices (and one over the faces on a closed
// mesh). A stopped run keeps the iterations before the failing one: result.mesh is the last good
// state, stopped_early is set and stop_reason names the iteration and the reason (for an explicit
// instability with the stable limit at the last good state).
//
// Boundary vertices stay fixed (or slide along the boundary curve); isolated vertices never
// move. Connectivity and attributes other than positions are copied unchanged.
// Coincident vertices (core/algorithms/coincident.h: a seam between patches, the copies
// build_mesh() makes of a non-manifold vertex) move as one: the run is on the mesh welded where
// that keeps it manifold (core/algorithms/weld.h), so a seam is smoothed as interior surface (its
// curve is a boundary only where no partner lies on it) and a mesh closed up to its seams counts as
// closed (volume preservation applies); copies that cannot be joined (surfaces touching at a
// point) stay where they are. Every copy gets its joined vertex's positions, bit for bit.
// Throws InvalidArgument naming the option (`step`, `iterations`, `taubin_lambda`,
// `taubin_mu`, `taubin_pass_band`, `integration`, `preserve_volume`, `cg_tolerance`,
// `max_relative_residual`, `cg_max_iterations`) before doing anything; Cancelled from the
// progress. The input mesh is never modified.
// Complexity: explicit O(iterations · (V + F)) with one position-sized buffer beyond the
// result (two for Taubin; umbrella and Taubin build no matrix); implicit one factorization per
// iteration (one in all for umbrella) plus a solve per iteration.
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "core/algorithms/laplacian.h"
#include "core/enum_table.h"
#include "core/halfedge_mesh.h"
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
    double step = 0.5;             ///< λ·dt, finite and >= 0; not used by Taubin
    int iterations = 1;            ///< in [1, 10000]
    bool preserve_volume = false;  ///< closed meshes only
    double taubin_lambda = 0.5;    ///< Taubin only: in (0, 1]
    /// Taubin only: in [-1, -taubin_lambda), with the pass band 1/λ + 1/μ below 1.
    double taubin_mu = -0.53;
    /// Taubin only: 0 = use taubin_mu; in (0, 1) = the pass-band frequency k_PB, and μ =
    /// 1/(k_PB - 1/λ) (Taubin 1995 suggests 0.01 to 0.1), which must be >= -1.
    double taubin_pass_band = 0;
    /// Auto: by condition bound and size; Direct: SimplicialLDLT first; Iterative: conjugate
    /// gradients first. A solve that misses max_relative_residual is retried with the other.
    ImplicitSolver solver = ImplicitSolver::Auto;
    double cg_tolerance = 1e-10;  ///< relative residual target of the iterative solver
    /// Iterative solver's iteration cap; 0 = automatic (max(1000, 4 x rows)).
    int cg_max_iterations = 0;
    /// A solve is accepted when |A·x - b| <= max_relative_residual·|b|; in (0, 1e-2].
    double max_relative_residual = 1e-8;
    BoundaryMode boundary = BoundaryMode::Fixed;
    /// true: result.step_positions holds the positions after every iteration.
    bool keep_steps = true;
    /// true: result.max_stable_step is estimated (about 20 sparse products with the operator
    /// at the input positions: a few ms on the 36k-vertex bunny). An explicit run that stops
    /// for instability estimates it at the last good state regardless.
    bool estimate_max_stable_step = true;
};

struct FairingResult {
    /// The input's connectivity and attributes with the last good positions (the input
    /// itself when the first iteration failed).
    HalfedgeMesh mesh;
    /// keep_steps: the positions (mesh.positions() layout, one per vertex storage index)
    /// after each good iteration; the last one equals mesh.positions().
    std::vector<std::vector<Point>> step_positions;
    int iterations_done = 0;  ///< good iterations (the mesh holds the last one)
    bool stopped_early = false;
    int stopped_at_iteration = 0;  ///< 1-based iteration that failed; 0 when none did
    /// One line naming the iteration and the reason, e.g. "iteration 1: the bounding box grew
    /// by 4.1e+02% in one iteration (step 20 is above the stable limit 1.31 of this mesh; use
    /// a smaller step or implicit integration)"; empty when the run did not stop.
    std::string stop_reason;
    /// Estimated largest stable explicit step of the operator at the input positions
    /// (Taubin: the limit for λ); NaN when not estimated, +inf when nothing can move.
    double max_stable_step = std::numeric_limits<double>::quiet_NaN();
    /// Human-readable lines: operator, solver and residual per implicit step, clamps, stop.
    std::vector<std::string> report;
    std::string solver;       ///< "none", "SimplicialLDLT", "ConjugateGradient(Jacobi)" or both
    double max_residual = 0;  ///< largest relative residual of the accepted implicit solves
    std::size_t factorizations = 0;
    std::size_t cg_iterations = 0;     ///< summed over the iterative solves
    double factorization_ms = 0;       ///< time in sparse Cholesky factorizations
    double solve_ms = 0;               ///< time in implicit solves (either solver)
    LaplacianDiagnostics diagnostics;  ///< summed over all builds (stalled: largest per build)
    double initial_volume = 0, final_volume = 0;  ///< closed meshes (0 otherwise)
};

/// Smooths `mesh`; see the file comment.
FairingResult smooth(const HalfedgeMesh& mesh, const FairingOptions& options, Progress& progress);
FairingResult smooth(const HalfedgeMesh& mesh, const FairingOptions& options);
/// The same, smoothing `mesh` in place of a copy (it becomes result.mesh): saves the copy of
/// a large mesh when the caller does not need the input afterwards.
FairingResult smooth(HalfedgeMesh&& mesh, const FairingOptions& options, Progress& progress);

/// The largest stable explicit step of `op` on `mesh` (boundary vertices fixed): 2/ρ with ρ
/// the largest eigenvalue of S⁻¹K over the free vertices, estimated by `lanczos_steps` Lanczos
/// iterations (a lower bound on ρ converging from below; 20 steps are within about 1 % on
/// meshes like the bunny). Taubin: the umbrella's limit, which bounds λ. +inf when no vertex
/// can move. Cost: one operator build plus lanczos_steps sparse products.
double max_stable_explicit_step(const HalfedgeMesh& mesh, FairingOperator op,
                                int lanczos_steps = 20);

}  // namespace trilab
