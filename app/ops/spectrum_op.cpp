// The "spectrum" operation: frequency decomposition (core/spectral.h) and the reconstruction
// of the mesh from a band of the computed frequencies, as one geometry-only step.
#include <chrono>
#include <cstdio>
#include <limits>
#include <string>
#include <utility>

#include "app/ops/operation_entries.h"
#include "app/ops/operation_entry.h"
#include "core/spectral.h"

namespace trilab {
namespace {

constexpr const char* kSpectrumUsage =
    "--operator umbrella|improved-umbrella|curvature-flow|second-order (default umbrella), "
    "--k K (frequencies, 1 to vertices - 1, default 50; with --full default all), "
    "--which smallest|largest (default smallest), --band LO:HI (0 <= LO <= HI < K, default "
    "all), --full (dense, up to --max-full vertices), --max-full N (default 5000), "
    "--mass normalizer|barycentric|voronoi (default normalizer), --fix-boundary (Dirichlet; "
    "default free), --threads 1|2 (spectrum slicing; default 2 when the machine has them)";

constexpr std::uint64_t kMaxK = 10000000;

struct SpectrumOptions {
    SpectralOptions spectral;
    bool k_given = false;
    bool band_given = false;
    std::size_t lo = 0, hi = 0;
};

SpectrumOptions parse_spectrum(OptionReader& r) {
    SpectrumOptions o;
    std::string band_text;
    while (r.next()) {
        if (r.is("--operator")) {
            o.spectral.op = parse_laplacian_operator(
                r.choice({"umbrella", "improved-umbrella", "curvature-flow", "second-order"}));
        } else if (r.is("--k")) {
            o.spectral.k = std::size_t(r.whole_number(1, kMaxK));
            o.k_given = true;
        } else if (r.is("--which")) {
            o.spectral.end = parse_spectrum_end(r.choice({"smallest", "largest"}));
        } else if (r.is("--band")) {
            band_text = r.value();
            const std::size_t colon = band_text.find(':');
            const auto digits = [](const std::string& s) {
                return !s.empty() && s.size() < 9 &&
                       s.find_first_not_of("0123456789") == std::string::npos;
            };
            const std::string a = band_text.substr(0, colon);
            const std::string b = colon == std::string::npos ? "" : band_text.substr(colon + 1);
            if (colon == std::string::npos || !digits(a) || !digits(b) ||
                std::stoul(a) > std::stoul(b))
                throw r.bad_value("LO:HI with 0 <= LO <= HI < K", band_text);
            o.lo = std::stoul(a);
            o.hi = std::stoul(b);
            o.band_given = true;
        } else if (r.is("--full")) {
            o.spectral.method = SpectralMethod::Full;
        } else if (r.is("--max-full")) {
            o.spectral.max_full_rows = std::size_t(r.whole_number(2, 100000));
        } else if (r.is("--mass")) {
            o.spectral.mass = parse_mass_matrix(r.choice({"normalizer", "barycentric", "voronoi"}));
        } else if (r.is("--fix-boundary")) {
            o.spectral.fix_boundary = true;
        } else if (r.is("--threads")) {
            o.spectral.threads = std::size_t(r.whole_number(1, 2));
        } else {
            r.unknown();
        }
    }
    if (o.spectral.method == SpectralMethod::Full && !o.k_given) o.spectral.k = 0;
    const bool k_known = o.k_given || o.spectral.method == SpectralMethod::Partial;
    if (o.band_given && k_known && o.hi >= o.spectral.k)
        throw InvalidArgument(
            "--band: expected LO:HI with 0 <= LO <= HI < K = " + std::to_string(o.spectral.k) +
            ", got '" + std::to_string(o.lo) + ":" + std::to_string(o.hi) + "'");
    return o;
}

/// Core messages name the option without dashes ("k: ..."); the CLI's options have them.
[[noreturn]] void rethrow_with_dashes(const InvalidArgument& e) {
    const std::string m = e.what();
    for (const char* name : {"k:", "full:", "band:"})
        if (m.rfind(name, 0) == 0) throw InvalidArgument("--" + m);
    throw e;
}

OperationResult run_spectrum(const SpectrumOptions& o, const HalfedgeMesh& mesh,
                             Progress& progress) {
    const auto t0 = std::chrono::steady_clock::now();
    SpectralDecomposition d;
    try {
        d = decompose(mesh, o.spectral, progress);
    } catch (const InvalidArgument& e) {
        rethrow_with_dashes(e);
    }
    const std::size_t k = d.size();
    const std::size_t lo = o.band_given ? o.lo : 0, hi = o.band_given ? o.hi : k - 1;
    if (hi >= k)
        throw InvalidArgument(
            "--band: expected LO:HI with 0 <= LO <= HI < K = " + std::to_string(k) + ", got '" +
            std::to_string(lo) + ":" + std::to_string(hi) + "'");
    HalfedgeMesh out = reconstruct(mesh, d, lo, hi);
    OperationResult result;
    result.ms = ms_since(t0);
    result.label = "Spectrum";
    std::string params = std::string("--operator ") + laplacian_operator_name(o.spectral.op);
    if (o.spectral.method == SpectralMethod::Full) params += " --full";
    if (o.spectral.method == SpectralMethod::Partial || o.k_given)
        params += " --k " + std::to_string(o.spectral.k);
    params += std::string(" --which ") + spectrum_end_name(o.spectral.end) + " --band " +
              std::to_string(lo) + ":" + std::to_string(hi);
    if (o.spectral.mass != MassMatrix::Normalizer)
        params += std::string(" --mass ") + mass_matrix_name(o.spectral.mass);
    if (o.spectral.fix_boundary) params += " --fix-boundary";
    if (o.spectral.max_full_rows != kDefaultMaxFullRows)
        params += " --max-full " + std::to_string(o.spectral.max_full_rows);
    if (o.spectral.threads) params += " --threads " + std::to_string(o.spectral.threads);
    result.parameters = params;
    const SpectralReport& rep = d.report;
    char line[256];
    std::snprintf(line, sizeof line,
                  "%zu frequencies (%s, %s) of %zu vertices, band %zu:%zu, %.0f ms: %s, %zu "
                  "band(s) in %zu slice(s), %zu factorization(s), %zu operator applications, "
                  "max residual %.1e",
                  k, spectral_method_name(d.method), spectrum_end_name(d.end), d.rows(), lo, hi,
                  rep.ms, rep.solver.c_str(), rep.bands, rep.slices, rep.factorizations,
                  rep.operations, rep.max_residual);
    result.report.push_back(line);
    if (rep.diagnostics.total() > 0)
        result.report.push_back(
            "operator: " + std::to_string(rep.diagnostics.negative_weights_clamped) +
            " negative cotangent weights clamped, " +
            std::to_string(rep.diagnostics.degenerate_corners) + " degenerate corners");
    result.steps.push_back(OperationStep{std::move(out), MorphCorrespondence{}});
    result.values = {{"k", double(k)},
                     {"lo", double(lo)},
                     {"hi", double(hi)},
                     {"rows", double(d.rows())},
                     {"bands", double(rep.bands)},
                     {"slices", double(rep.slices)},
                     {"factorizations", double(rep.factorizations)},
                     {"operations", double(rep.operations)},
                     {"max_residual", rep.max_residual},
                     {"lambda_min", d.eigenvalues[0]},
                     {"lambda_max", d.eigenvalues[Eigen::Index(k - 1)]},
                     {"decompose_ms", rep.ms}};
    result.texts = {{"operator", laplacian_operator_name(d.op)},
                    {"method", spectral_method_name(d.method)},
                    {"which", spectrum_end_name(d.end)},
                    {"solver", rep.solver}};
    result.series = {
        {"eigenvalues", std::vector<double>(d.eigenvalues.data(), d.eigenvalues.data() + k)}};
    return result;
}

}  // namespace

OperationEntry spectrum_operation() {
    return make_entry<SpectrumOptions>("spectrum", kSpectrumUsage, parse_spectrum, run_spectrum);
}

}  // namespace trilab
