// The "noise" operation: random displacement along the normals or in random directions,
// uniform or Gaussian (core/algorithms/noise.h).
#include <chrono>
#include <cstdio>
#include <limits>
#include <string>
#include <utility>

#include "app/ops/operation_decl.h"
#include "app/ops/operation_entries.h"
#include "core/algorithms/noise.h"
#include "core/number_text.h"

namespace trilab {
namespace {

OperationResult run_noise(const NoiseOptions& options, const HalfedgeMesh& mesh, Progress& progress,
                          const RunSettings& settings) {
    NoiseOptions o = options;
    o.region = settings.region;
    progress.check_cancelled();
    progress.report(0, "adding noise");
    OperationResult result;
    result.label = "Add noise";
    OperationStep step{mesh, MorphCorrespondence{MorphCorrespondence::Kind::SameVertices, {}}};
    const auto t0 = std::chrono::steady_clock::now();
    const NoiseReport report = add_noise(step.mesh, o);
    result.ms = ms_since(t0);
    progress.report(1, "adding noise");
    result.steps.push_back(std::move(step));
    char line[160];
    std::snprintf(line, sizeof(line), "mean edge length %.6g", report.mean_edge_length);
    result.report.emplace_back(line);
    const bool gaussian = o.distribution == NoiseDistribution::Gaussian;
    if (gaussian)
        std::snprintf(line, sizeof(line), "largest displacement %.6g (Gaussian, sigma %.6g)",
                      report.max_displacement, report.scale);
    else
        std::snprintf(line, sizeof(line), "largest displacement %.6g (bound %.6g)",
                      report.max_displacement, o.amount_percent / 100.0 * report.mean_edge_length);
    result.report.emplace_back(line);
    result.report.push_back("moved " + std::to_string(report.moved_vertices) + " of " +
                            count_text(mesh.n_vertices(), "vertex", "vertices"));
    result.values = {{gaussian ? "sigma" : "amount", gaussian ? o.sigma : o.amount_percent},
                     {"seed", double(o.seed)},
                     {"mean_edge_length", report.mean_edge_length},
                     {"scale", report.scale},
                     {"max_displacement", report.max_displacement},
                     {"moved_vertices", double(report.moved_vertices)}};
    result.typed_report = report;
    return result;
}

}  // namespace

std::unique_ptr<OperationDef> noise_operation() {
    OperationDecl<NoiseOptions> d(
        "noise", "Add noise",
        "Moves every vertex along its normal (or in a random direction) by a random amount: "
        "uniform up to a percentage of the mean edge length, or Gaussian with a standard "
        "deviation of sigma times the mean edge length; reproducible from the seed.");
    const auto uniform_only = [](const NoiseOptions& o) -> const char* {
        return o.distribution == NoiseDistribution::Uniform
                   ? nullptr
                   : "applies to --distribution uniform only (Gaussian noise takes --sigma)";
    };
    const auto gaussian_only = [](const NoiseOptions& o) -> const char* {
        return o.distribution == NoiseDistribution::Gaussian
                   ? nullptr
                   : "applies to --distribution gaussian only";
    };
    d.choice("distribution", &NoiseOptions::distribution, EnumTableView(kNoiseDistributions),
             "uniform in [-amount, amount], or Gaussian of standard deviation sigma")
        .hide_default();
    d.number("amount", &NoiseOptions::amount_percent, 0, kMaxNoiseAmountPercent,
             "how far a vertex may move", " (percent of the mean edge length)")
        .label("amount (% of mean edge)")
        .slider(0.01, 100, true)
        .only_if(uniform_only);
    d.number("sigma", &NoiseOptions::sigma, 0, kMaxNoiseSigma,
             "the Gaussian's standard deviation, k in sigma = k x the mean edge length",
             " (multiples of the mean edge length)")
        .label("sigma (x mean edge)")
        .slider(0.01, 2, true)
        .only_if(gaussian_only);
    d.integer("seed", &NoiseOptions::seed, 0, std::numeric_limits<std::uint32_t>::max(),
              "random seed");
    d.choice("direction", &NoiseOptions::direction, EnumTableView(kNoiseDirections),
             "along the vertex normal, or a random direction (uniform on the sphere)")
        .hide_default();
    d.run(run_noise).acts_on_region("each vertex's offset is scaled by its weight");
    return d.build();
}

}  // namespace trilab
