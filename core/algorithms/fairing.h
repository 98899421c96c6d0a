#pragma once
// Fairing (smoothing) by diffusion, dX/dt = L(X) (section 1.2.3 of the reference report), with
// the operators of core/algorithms/laplacian.h: explicit Euler (1.4/1.6), implicit Euler
// (1.13-1.14, Desbrun, Meyer, Schröder, Barr 1999; sparse Cholesky or preconditioned CG,
// chosen automatically), Taubin's λ|μ steps (Taubin 1995) and volume preservation (1.15, closed
// meshes). `step` means the same on any mesh size (the operators are scale-free); every
// explicit step <= 1 is stable except for the improved umbrella, any implicit step is stable;
// max_stable_explicit_step() estimates the limit for the actual mesh.
// Never a silent failure: a run stops at the first iteration whose result is not finite, whose
// implicit solve misses max_relative_residual (after retrying with the other solver), or that
// is unstable (bounding box, fairing energy, surface area, sign of a closed mesh's volume);
// result.mesh is then the last good state, with stopped_early and a stop_reason naming the
// iteration and the cause.
// Boundary vertices stay fixed (or slide along their boundary curve); isolated vertices never
// move; coincident vertices (seams, copies of split vertices) move as one (the run is on the
// weld, core/algorithms/weld.h). Only positions change. A region (FairingOptions::region)
// limits the smoothing to the selected vertices, blended by their weights. An implicit run on a
// region (umbrella, curvature flow, second order; fixed boundary, no volume preservation, no
// coincident vertices) whose faces around the moving vertices are at most 3/4 of the mesh's
// builds and solves its system on those faces only (one ring, two for second order, whose
// hinges reach that far): the same rows and values as on the whole mesh, so the outside stays
// bit for bit and the inside agrees to the solver's tolerance, in time that follows the
// region (FairingResult::solved_rows: the region's vertices). A closed mesh's volume is
// checked and reported over the whole mesh.
// Throws InvalidArgument naming the option before doing anything; Cancelled from the progress.
// The input mesh is never modified.
// Complexity: explicit O(iterations · (V + F)) (explicit umbrella and Taubin on a region:
// O(V + F) once, then O(iterations · the region's vertices and faces)); implicit one factorization
// per iteration (one in all for umbrella) plus a solve per iteration. The details (what `step`
// means per operator, the health checks and their thresholds, the solver choice): fairing.cpp.
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "core/algorithms/feature_fairing.h"
#include "core/algorithms/laplacian.h"
#include "core/enum_table.h"
#include "core/features.h"
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

/// Taubin's pass band k_PB = 1/λ + 1/μ of his suggested λ 0.5, μ -0.53 (about 0.1132): the one
/// μ follows when only λ is given (FairingOptions::taubin_mu 0).
inline constexpr double kDefaultTaubinPassBand = 1.0 / 0.5 + 1.0 / -0.53;

/// The largest accepted FairingOptions::iterations.
inline constexpr int kMaxFairingIterations = 10000;

struct FairingOptions {
    FairingOperator op = FairingOperator::Umbrella;
    Integration integration = Integration::Explicit;
    double step = 0.5;             ///< λ·dt, finite and >= 0; not used by Taubin
    int iterations = 1;            ///< in [1, 10000]
    bool preserve_volume = false;  ///< closed meshes only
    double taubin_lambda = 0.5;    ///< Taubin only: in (0, 1]
    /// Taubin only: in [-1, -taubin_lambda), with the pass band 1/λ + 1/μ below 1; 0 (the
    /// default): μ follows λ through the pass band kDefaultTaubinPassBand (taubin_mu_of()).
    double taubin_mu = 0;
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
    /// The region to smooth (core/algorithms/selection.h): one weight in [0, 1] per vertex
    /// storage index, or nullptr for the whole mesh. Weight-0 vertices are fixed rows (they
    /// stay bit for bit); every other vertex's new position is blended with its old one by its
    /// weight after each iteration (weight 1: exactly the operator's result). With a region,
    /// --preserve-volume rescales before the blend, so the volume is kept approximately.
    /// Not owned; must outlive the call.
    const std::vector<float>* region = nullptr;
    /// With a region (some vertices of weight 0), explicit umbrella and Taubin runs without
    /// --preserve-volume or a sliding boundary work on the moving vertices and the edges and
    /// faces around them only (when those vertices are at most 3/4 of the mesh's): the same
    /// positions bit for bit, in time that follows the region's size. false: the whole-mesh
    /// passes (for comparisons and tests).
    bool restrict_to_region = true;
    /// Fixed features (core/features.h): the vertices on a sharp edge and the tagged corners
    /// weigh 0 in the region (they stay bit for bit) when the mesh has features (Stored, the
    /// default) or after detecting them at `feature_angle` degrees (Auto: the result carries
    /// them); None smooths them like any vertex. A line of the report counts them.
    FeatureSource features = FeatureSource::Stored;
    double feature_angle = 60.0;  ///< FeatureSource::Auto: the angle, in (0, 180]
    /// Slide: the crease vertices (two sharp edges, no corner tag, not on the boundary, in the
    /// region) smooth along their feature curve with the curve's 1-D Laplacian instead of
    /// staying (core/algorithms/feature_fairing.h); corners and curve ends stay bit for bit.
    /// Not with a restricted region run: slide runs on the whole mesh.
    FeatureMode feature_mode = FeatureMode::Fixed;
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
    /// Rows of the implicit system (the operator's free vertices) per solve; 0 when explicit.
    /// On a region whose outside is fixed, the region's vertices only: the system is built
    /// on the faces around them (see smooth()).
    std::size_t solved_rows = 0;
    /// Rows of the operator built (its live, non-isolated vertices; on a restricted region
    /// run, those of the faces around the region); 0 for the umbrella's matrix-free path.
    std::size_t operator_rows = 0;
};

/// Taubin's μ as smooth() uses it: 1/(k_PB - 1/λ) from taubin_pass_band when that is > 0;
/// else taubin_mu when non-zero; else (μ follows λ) 1/(kDefaultTaubinPassBand - 1/λ), raised
/// to -1 where it would be below (then the pass band is 1/λ - 1, a little narrower). The
/// result is not checked (smooth() checks it).
double taubin_mu_of(const FairingOptions& options);

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

namespace fairing_detail {
/// Explicit umbrella and Taubin runs on the whole of a mesh without garbage, and
/// max_stable_explicit_step() for them, renumber the operator along a Morton curve of the
/// positions (fairing.cpp, UmbrellaOperator::localize(): the same positions bit for bit, the
/// neighbour gathers close in memory) from this many vertices on (default 65,536). Sets it and
/// returns the previous value: for tests, which compare both paths. Not thread-safe.
std::size_t set_locality_threshold(std::size_t vertices);
}  // namespace fairing_detail

}  // namespace trilab
