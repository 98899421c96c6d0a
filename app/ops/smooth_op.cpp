// The "smooth" operation: fairing with the four Laplacians and Taubin (core/fairing.h).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <utility>

#include "app/ops/operation_entries.h"
#include "app/ops/operation_entry.h"
#include "core/coloring.h"
#include "core/fairing.h"

namespace trilab {
namespace {

constexpr const char* kSmoothUsage =
    "--operator umbrella|improved-umbrella|curvature-flow|second-order|taubin (default "
    "umbrella), --integration explicit|implicit (default explicit), --step T (default 0.5), "
    "--iterations N (1 to 10000, default 1), --preserve-volume, --boundary fixed|slide (default "
    "fixed)";

FairingOptions parse_smooth(OptionReader& r) {
    FairingOptions o;
    o.step = 0.5;
    while (r.next()) {
        if (r.is("--operator"))
            o.op = parse_fairing_operator(r.choice(
                {"umbrella", "improved-umbrella", "curvature-flow", "second-order", "taubin"}));
        else if (r.is("--integration"))
            o.integration = parse_integration(r.choice({"explicit", "implicit"}));
        else if (r.is("--step"))
            o.step = r.number(0.0, 1e6);
        else if (r.is("--iterations"))
            o.iterations = int(r.whole_number(1, 10000));
        else if (r.is("--preserve-volume"))
            o.preserve_volume = true;
        else if (r.is("--boundary"))
            o.boundary = parse_boundary_mode(r.choice({"fixed", "slide"}));
        else
            r.unknown();
    }
    return o;
}

OperationResult run_smooth(const FairingOptions& o, const HalfedgeMesh& mesh, Progress& progress) {
    const auto t0 = std::chrono::steady_clock::now();
    FairingResult fairing = smooth(mesh, o, progress);
    OperationResult result;
    result.ms = ms_since(t0);
    result.label = "Smooth";
    result.parameters = std::string("--operator ") + fairing_operator_name(o.op) +
                        " --integration " + integration_name(o.integration) + " --step " +
                        OptionReader::format_number(o.step) + " --iterations " +
                        std::to_string(o.iterations) +
                        (o.preserve_volume ? " --preserve-volume" : "") +
                        (o.boundary == BoundaryMode::Slide ? " --boundary slide" : "");
    result.report = fairing.report;
    // A run that stopped (diverged, failed solve) is an error, never a result.
    if (fairing.stopped_early) throw Error("stopped at " + fairing.stop_reason);
    // Geometry-only steps: every iteration keeps the vertices of the one before.
    for (std::size_t k = 0; k < fairing.step_positions.size(); ++k) {
        HalfedgeMesh step =
            k + 1 == fairing.step_positions.size() ? std::move(fairing.mesh) : fairing.mesh;
        step.positions() = std::move(fairing.step_positions[k]);
        result.steps.push_back(OperationStep{std::move(step), MorphCorrespondence{}});
    }
    if (result.steps.empty()) throw Error("smooth: no step could be computed");
    // The smoothing distance of the result against the input (the viewer's colouring).
    const std::vector<double> distance =
        smoothing_distance(result.steps.back().mesh, mesh.positions());
    double max_distance = 0, sum_distance = 0;
    for (double d : distance) {
        max_distance = std::max(max_distance, std::abs(d));
        sum_distance += std::abs(d);
    }
    const double mean_distance = mesh.n_vertices() ? sum_distance / double(mesh.n_vertices()) : 0;
    char line[160];
    std::snprintf(line, sizeof(line),
                  "smoothing distance along the normal: largest %.6g, mean %.6g", max_distance,
                  mean_distance);
    result.report.emplace_back(line);
    result.values = {{"iterations_done", double(result.steps.size())},
                     {"max_stable_step", fairing.max_stable_step},
                     {"max_residual", fairing.max_residual},
                     {"initial_volume", fairing.initial_volume},
                     {"final_volume", fairing.final_volume},
                     {"factorizations", double(fairing.factorizations)},
                     {"cg_iterations", double(fairing.cg_iterations)},
                     {"max_smoothing_distance", max_distance},
                     {"mean_smoothing_distance", mean_distance}};
    result.texts = {{"solver", fairing.solver}};
    return result;
}

}  // namespace

OperationEntry smooth_operation() {
    return make_entry<FairingOptions>("smooth", kSmoothUsage, parse_smooth, run_smooth);
}

}  // namespace trilab
