// The "smooth" operation: fairing with the four Laplacians and Taubin (core/algorithms/fairing.h).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <utility>

#include "app/ops/operation_decl.h"
#include "app/ops/operation_entries.h"
#include "app/ops/smooth_op.h"
#include "core/algorithms/coloring.h"
#include "core/algorithms/fairing.h"
#include "core/algorithms/transfer_function.h"
#include "core/geometry.h"

namespace trilab {
namespace {

/// The report's named values and texts for --json, in their fixed order.
void add_json_values(const SmoothReport& rep, OperationResult& result) {
    result.values = {{"iterations_done", double(rep.iterations_done)},
                     {"max_stable_step", rep.max_stable_step},
                     {"max_residual", rep.max_residual},
                     {"initial_volume", rep.initial_volume},
                     {"final_volume", rep.final_volume},
                     {"factorizations", double(rep.factorizations)},
                     {"cg_iterations", double(rep.cg_iterations)},
                     {"max_smoothing_distance", rep.max_smoothing_distance},
                     {"mean_smoothing_distance", rep.mean_smoothing_distance},
                     {"mean_smoothing_distance_moved", rep.mean_smoothing_distance_moved},
                     {"moved_vertices", double(rep.moved_vertices)},
                     {"solved_rows", double(rep.solved_rows)}};
    result.texts = {{"solver", rep.solver}};
    if (!rep.max_stable_step_estimated && !std::isfinite(rep.max_stable_step))
        result.texts.push_back(
            {"max_stable_step_note",
             "not estimated: explicit umbrella steps up to 1 are stable on any mesh (Gershgorin: "
             "the umbrella's eigenvalues lie in [0, 2]); the estimate is made below 65,536 "
             "vertices, and up to 2,000,000 for a larger step or another operator"});
}

OperationResult run_smooth(const FairingOptions& options, const HalfedgeMesh& mesh,
                           Progress& progress, const RunSettings& settings) {
    FairingOptions o = options;
    o.keep_steps = settings.keep_steps;
    o.region = settings.region;
    // The stable-step estimate is ~20 passes over the mesh: above this size it would cost
    // more than the smoothing, so it is left out (a run that diverges still estimates it).
    // From 65,536 vertices it is also left out where it cannot change the verdict: an explicit
    // umbrella step up to 1 is stable on any mesh (the umbrella's eigenvalues lie in [0, 2],
    // Gershgorin), and the estimate cost more than the ten iterations themselves on the
    // 557k-vertex bunny (issue 43).
    constexpr std::size_t kEstimateVertices = 2000000, kAlwaysEstimateVertices = 65536;
    const bool surely_stable = o.op == FairingOperator::Umbrella &&
                               o.integration == Integration::Explicit && o.step <= 1.0;
    const bool estimate = mesh.n_vertices() <= kEstimateVertices &&
                          (mesh.n_vertices() < kAlwaysEstimateVertices || !surely_stable);
    o.estimate_max_stable_step = estimate;
    // The input's positions, for the smoothing distance, before the input may be consumed.
    const std::size_t n_vertices = mesh.n_vertices();
    // The volume is defined for closed meshes only: NaN otherwise (--json writes null).
    const bool closed = is_closed(mesh);
    const auto volume_value = [closed](double v) {
        return closed ? v : std::numeric_limits<double>::quiet_NaN();
    };
    const bool consume = settings.consumable == &mesh;
    std::vector<Point> input_positions;
    if (consume) input_positions = mesh.positions();
    const auto t0 = std::chrono::steady_clock::now();
    FairingResult fairing =
        consume ? smooth(std::move(*settings.consumable), o, progress) : smooth(mesh, o, progress);
    OperationResult result;
    result.ms = ms_since(t0);
    result.label = "Smooth";
    result.report = fairing.report;
    // A run that stopped (diverged, failed solve) keeps its good iterations and says why;
    // callers report it as a failure (the CLI exits 4, the viewer says so).
    if (fairing.stopped_early) {
        result.stopped_early = true;
        result.stop_reason = fairing.stop_reason;
        result.report.push_back("stopped early: " + result.stop_reason);
        result.changed = fairing.iterations_done > 0;
    }
    // Geometry-only steps: every iteration keeps the vertices of the one before.
    for (std::size_t k = 0; k < fairing.step_positions.size(); ++k) {
        HalfedgeMesh step =
            k + 1 == fairing.step_positions.size() ? std::move(fairing.mesh) : fairing.mesh;
        step.set_positions(std::move(fairing.step_positions[k]));
        result.steps.push_back(OperationStep{std::move(step), MorphCorrespondence{}});
    }
    if (result.steps.empty())  // no steps kept (the CLI), or none good: the last good state
        result.steps.push_back(OperationStep{std::move(fairing.mesh), MorphCorrespondence{}});
    // The smoothing distance of the result against the input (the viewer's colouring).
    const std::vector<Point>& before = consume ? input_positions : mesh.positions();
    const HalfedgeMesh& after = result.steps.back().mesh;
    const std::vector<double> distance = smoothing_distance(after, before);
    double max_distance = 0, sum_distance = 0;
    std::size_t moved = 0;
    for (Vertex v : after.vertices()) {
        const double d = std::abs(distance[v.idx()]);
        max_distance = std::max(max_distance, d);
        sum_distance += d;
        moved += after.position(v) != before[v.idx()] ? 1 : 0;
    }
    const double mean_distance = n_vertices ? sum_distance / double(n_vertices) : 0;
    const double mean_moved = moved ? sum_distance / double(moved) : 0;
    char line[240];
    std::snprintf(line, sizeof(line),
                  "smoothing distance along the normal: largest %.6g, mean %.6g over all %zu "
                  "vertices, mean %.6g over the %zu that moved",
                  max_distance, mean_distance, n_vertices, mean_moved, moved);
    result.report.emplace_back(line);
    SmoothReport rep;
    rep.iterations_done = fairing.iterations_done;
    rep.max_stable_step = fairing.max_stable_step;
    rep.max_stable_step_estimated = estimate;
    rep.max_residual = fairing.max_residual;
    rep.initial_volume = volume_value(fairing.initial_volume);
    rep.final_volume = volume_value(fairing.final_volume);
    rep.factorizations = fairing.factorizations;
    rep.cg_iterations = fairing.cg_iterations;
    rep.max_smoothing_distance = max_distance;
    rep.mean_smoothing_distance = mean_distance;
    rep.mean_smoothing_distance_moved = mean_moved;
    rep.moved_vertices = moved;
    rep.solved_rows = fairing.solved_rows;
    rep.solver = fairing.solver;
    add_json_values(rep, result);
    if (o.op == FairingOperator::Taubin) {
        // The μ and pass band the run used (μ may follow λ): --json reports them in place of
        // the parameters' echo.
        result.values.push_back({"mu", taubin_mu_of(o)});
        result.values.push_back({"pass_band", taubin_pass_band_of(o)});
    }
    result.typed_report = std::move(rep);
    return result;
}

}  // namespace

std::unique_ptr<OperationDef> smooth_operation() {
    OperationDecl<FairingOptions> d(
        "smooth", "Smooth",
        "Fairs the mesh by diffusion (sections 1.2.1-1.2.10 of the reference; Desbrun, Meyer, "
        "Schroeder, Barr 1999; Guskov, Sweldens, Schroeder 1999; Taubin 1995), one step per "
        "iteration. Boundary vertices stay fixed unless --boundary slide; isolated vertices do "
        "not move.");
    const auto taubin_only = [](const FairingOptions& o) -> const char* {
        return o.op == FairingOperator::Taubin ? nullptr : "applies to --operator taubin only";
    };
    const auto not_taubin = [](const FairingOptions& o) -> const char* {
        return o.op == FairingOperator::Taubin
                   ? "does not apply to --operator taubin (it uses --lambda and --mu)"
                   : nullptr;
    };
    d.choice("operator", &FairingOptions::op, EnumTableView(kFairingOperators),
             "the Laplacian of the diffusion");
    d.choice("integration", &FairingOptions::integration, EnumTableView(kIntegrations),
             "explicit Euler, or implicit (backward Euler: stable for any step)")
        .only_if(not_taubin);
    d.number("step", &FairingOptions::step, 0, 1e6,
             "lambda * dt per iteration, scale-free: umbrella and curvature flow move each vertex "
             "this fraction of the way to its neighbours' average (explicit: stable up to about "
             "1.3); improved umbrella twice that on equal edges (its lengths in units of the mean "
             "edge h: a step s in the reference's 1/length² units is s / h² here); second order "
             "1 = the relaxation; implicit t smooths about like t explicit steps of 1",
             " (scale-free)")
        .slider(1e-4, 100, true)
        .only_if(not_taubin);
    d.integer("iterations", &FairingOptions::iterations, 1, kMaxFairingIterations,
              "steps, each kept in the history")
        .slider(1, 200)
        .counts_steps();
    d.number("lambda", &FairingOptions::taubin_lambda, 0, 1,
             "Taubin's shrinking step: the fraction of the way to the neighbours' average "
             "(umbrella units)")
        .above_min()
        .slider(0.01, 1)
        .only_if(taubin_only);
    d.number("mu", &FairingOptions::taubin_mu, -1, 0,
             "Taubin's inflating step in umbrella units, in [-1, -lambda) (or give --pass-band); "
             "0: follows lambda through the pass band 0.1132 of lambda 0.5, mu -0.53, at least "
             "-1")
        .slider(-1, -0.01)
        .hide_default()
        .only_if([](const FairingOptions& o) -> const char* {
            if (o.op != FairingOperator::Taubin) return "applies to --operator taubin only";
            return o.taubin_pass_band > 0 ? "does not apply with --pass-band (it sets mu)"
                                          : nullptr;
        });
    d.number("pass-band", &FairingOptions::taubin_pass_band, 0, 1,
             "Taubin's pass-band frequency k_PB = 1/lambda + 1/mu, an eigenvalue of the umbrella "
             "(frequencies below it keep their size; 0: use --mu)")
        .slider(0, 0.2)
        .hide_default()
        .only_if(taubin_only);
    d.flag("preserve-volume", &FairingOptions::preserve_volume,
           "scale back to the initial volume after every step (closed meshes)");
    d.choice("boundary", &FairingOptions::boundary, EnumTableView(kBoundaryModes),
             "boundary vertices stay fixed, or slide along the input's boundary curve")
        .hide_default();
    d.check([](const FairingOptions& o, const auto&) {
        if (o.op != FairingOperator::Taubin || o.taubin_pass_band != 0) return;
        const double mu = taubin_mu_of(o);  // --mu, or following --lambda through the pass band
        if (!(mu < -o.taubin_lambda))
            throw InvalidArgument(
                "--mu: expected a value below -lambda = " + format_number(-o.taubin_lambda) +
                ", got " + format_number(mu) +
                (o.taubin_mu == 0 ? " (following --lambda through the pass band " +
                                        format_number(kDefaultTaubinPassBand) +
                                        ", at least -1: give a --lambda below 1, or --mu)"
                                  : std::string()));
    });
    d.choice("features", &FairingOptions::features, EnumTableView(kFeatureSources),
             "the features kept (see --feature-mode): those stored in the mesh, none, or auto "
             "(detected at "
             "--feature-angle first; on the command line also auto:A)")
        .hide_default();
    d.number("feature-angle", &FairingOptions::feature_angle, 0, 180,
             "with --features auto: the dihedral angle of a sharp edge", " (degrees)")
        .above_min()
        .slider(1, 90)
        .only_if([](const FairingOptions& o) -> const char* {
            return o.features == FeatureSource::Auto ? nullptr
                                                     : "applies only with --features auto";
        });
    d.choice("feature-mode", &FairingOptions::feature_mode, EnumTableView(kFeatureModes),
             "the feature vertices stay fixed, or the crease vertices (two sharp edges) slide "
             "along their feature curve with the curve's 1-D Laplacian, corners and curve ends "
             "fixed")
        .hide_default()
        .only_if([](const FairingOptions& o) -> const char* {
            return o.features == FeatureSource::None ? "does not apply with --features none"
                                                     : nullptr;
        });
    d.run(run_smooth)
        .may_stop_early()
        .acts_on_region(
            "vertices of weight 0 stay fixed; the others move by their weight times the step");
    return d.build();
}

}  // namespace trilab
