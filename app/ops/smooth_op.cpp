// The "smooth" operation: fairing with the four Laplacians and Taubin (core/fairing.h).
#include <chrono>
#include <cstdio>
#include <limits>
#include <string>
#include <utility>

#include "app/ops/operation_entries.h"
#include "app/ops/operation_entry.h"
#include "core/fairing.h"

namespace trilab {
namespace {

constexpr const char* kSmoothUsage =
    "--operator umbrella|improved-umbrella|curvature-flow|second-order|taubin (default "
    "umbrella), --integration explicit|implicit (default explicit), --step T (default 0.5), "
    "--iterations N (1 to 10000, default 1), --preserve-volume";

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
                        (o.preserve_volume ? " --preserve-volume" : "");
    result.report = fairing.report;
    if (fairing.diverged)
        result.report.push_back(
            "stopped early: the step diverged (try a smaller step or implicit)");
    // Geometry-only steps: every iteration keeps the vertices of the one before.
    for (HalfedgeMesh& step : fairing.steps)
        result.steps.push_back(OperationStep{std::move(step), MorphCorrespondence{}});
    if (result.steps.empty()) throw Error("smooth: no step could be computed");
    result.values = {{"iterations_done", double(result.steps.size())},
                     {"max_residual", fairing.max_residual},
                     {"initial_volume", fairing.initial_volume},
                     {"final_volume", fairing.final_volume}};
    result.texts = {{"solver", fairing.solver}};
    return result;
}

}  // namespace

OperationEntry smooth_operation() {
    return make_entry<FairingOptions>("smooth", kSmoothUsage, parse_smooth, run_smooth);
}

}  // namespace trilab
