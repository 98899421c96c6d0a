// The "noise" operation: random displacement along the normals (core/noise.h).
#include <chrono>
#include <cstdio>
#include <limits>
#include <string>
#include <utility>

#include "app/ops/operation_entries.h"
#include "app/ops/operation_entry.h"
#include "core/noise.h"

namespace trilab {
namespace {

constexpr const char* kNoiseUsage =
    "--amount PCT (percent of the mean edge length, 0 to 1000, default 1), "
    "--seed S (0 to 4294967295, default 1)";

NoiseOptions parse_noise(OptionReader& r) {
    NoiseOptions o;
    while (r.next()) {
        if (r.is("--amount"))
            o.amount_percent =
                r.number(0, kMaxNoiseAmountPercent, " (percent of the mean edge length)");
        else if (r.is("--seed"))
            o.seed = std::uint32_t(r.whole_number(0, std::numeric_limits<std::uint32_t>::max()));
        else
            r.unknown();
    }
    return o;
}

OperationResult run_noise(const NoiseOptions& o, const HalfedgeMesh& mesh, Progress& progress) {
    progress.check_cancelled();
    progress.report(0, "adding noise");
    OperationResult result;
    result.label = "Add noise";
    result.parameters = "--amount " + OptionReader::format_number(o.amount_percent) + " --seed " +
                        std::to_string(o.seed);
    OperationStep step{mesh, MorphCorrespondence{MorphCorrespondence::Kind::SameVertices, {}}};
    const auto t0 = std::chrono::steady_clock::now();
    const NoiseReport report = add_noise(step.mesh, o);
    result.ms = ms_since(t0);
    progress.report(1, "adding noise");
    result.steps.push_back(std::move(step));
    char line[160];
    std::snprintf(line, sizeof(line), "mean edge length %.6g", report.mean_edge_length);
    result.report.emplace_back(line);
    std::snprintf(line, sizeof(line), "largest displacement %.6g (bound %.6g)",
                  report.max_displacement, o.amount_percent / 100.0 * report.mean_edge_length);
    result.report.emplace_back(line);
    std::snprintf(line, sizeof(line), "moved %zu of %zu vertices", report.moved_vertices,
                  mesh.n_vertices());
    result.report.emplace_back(line);
    result.values = {{"amount", o.amount_percent},
                     {"seed", double(o.seed)},
                     {"mean_edge_length", report.mean_edge_length},
                     {"max_displacement", report.max_displacement},
                     {"moved_vertices", double(report.moved_vertices)}};
    return result;
}

}  // namespace

OperationEntry noise_operation() {
    return make_entry<NoiseOptions>("noise", kNoiseUsage, parse_noise, run_noise);
}

}  // namespace trilab
