// The "spectrum" operation: frequency decomposition (core/algorithms/spectral.h) and the
// reconstruction of the mesh from a band of the computed frequencies, as one geometry-only step.
#include <chrono>
#include <cstdio>
#include <limits>
#include <optional>
#include <string>
#include <utility>

#include "app/ops/operation_decl.h"
#include "app/ops/operation_entries.h"
#include "app/ops/spectrum_op.h"
#include "core/algorithms/spectral.h"
#include "core/number_text.h"

namespace trilab {
namespace {

constexpr double kMaxK = 10000000;

/// Core messages name the option without dashes ("k: ..."); the CLI's options have them.
[[noreturn]] void rethrow_with_dashes(const InvalidArgument& e) {
    const std::string m = e.what();
    for (const char* name : {"k:", "full:", "band:"})
        if (m.rfind(name, 0) == 0) throw InvalidArgument("--" + m);
    throw e;
}

/// The report's named values, texts and series for --json, in their fixed order.
void add_json_values(const SpectrumReport& r, OperationResult& result) {
    const SpectralReport& rep = r.decomposition;
    result.values = {{"k", double(r.k)},
                     {"lo", double(r.lo)},
                     {"hi", double(r.hi)},
                     {"rows", double(r.rows)},
                     {"bands", double(rep.bands)},
                     {"slices", double(rep.slices)},
                     {"factorizations", double(rep.factorizations)},
                     {"operations", double(rep.operations)},
                     {"max_residual", rep.max_residual},
                     {"lambda_min", r.eigenvalues.front()},
                     {"lambda_max", r.eigenvalues.back()},
                     {"decompose_ms", rep.ms}};
    result.texts = {{"operator", laplacian_operator_name(r.op)},
                    {"method", spectral_method_name(r.method)},
                    {"which", spectrum_end_name(r.end)},
                    {"solver", rep.solver}};
    result.series = {{"eigenvalues", r.eigenvalues}};
}

OperationResult run_spectrum(const SpectrumOptions& o, const HalfedgeMesh& mesh, Progress& progress,
                             const RunSettings& settings) {
    const auto t0 = std::chrono::steady_clock::now();
    const SpectralOptions spectral = spectral_options(o);
    SpectralDecomposition d;
    try {
        d = decompose(mesh, spectral, progress);
    } catch (const InvalidArgument& e) {
        rethrow_with_dashes(e);
    }
    const std::size_t k = d.size();
    const std::size_t lo = o.band ? o.band->first : 0, hi = o.band ? o.band->second : k - 1;
    if (hi >= k)
        throw InvalidArgument(
            "--band: expected LO:HI with 0 <= LO <= HI < K = " + std::to_string(k) + ", got '" +
            std::to_string(lo) + ":" + std::to_string(hi) + "'");
    const BandRest rest = o.with_rest ? BandRest::Include : BandRest::Exclude;
    const bool rest_included = o.with_rest && band_reaches_rest(d, lo, hi);
    HalfedgeMesh out = reconstruct(mesh, d, lo, hi, rest, settings.region);
    OperationResult result;
    result.ms = ms_since(t0);
    result.label = "Spectrum";
    const SpectralReport& rep = d.report;
    char line[256];
    std::snprintf(line, sizeof line, " (%s, %s) of ", spectral_method_name(d.method),
                  spectrum_end_name(d.end));
    std::string text = count_text(k, "frequency", "frequencies") + line +
                       count_text(d.rows(), "vertex", "vertices") + ", band " + std::to_string(lo) +
                       ":" + std::to_string(hi);
    if (rest_included)
        text += d.end == SpectrumEnd::Smallest ? " and the rest (the higher frequencies)"
                                               : " and the rest (the lower frequencies)";
    std::snprintf(line, sizeof line, ", %.0f ms: ", rep.ms);
    text += line + rep.solver + ", " + count_text(rep.bands, "band", "bands") + " in " +
            count_text(rep.slices, "slice", "slices") + ", " +
            count_text(rep.factorizations, "factorization", "factorizations") + ", " +
            count_text(rep.operations, "operator application", "operator applications");
    std::snprintf(line, sizeof line, ", max residual %.1e", rep.max_residual);
    result.report.push_back(text + line);
    const MultipletSplit split = band_splits_multiplet(d.eigenvalues, lo, hi);
    if (split.splits) {
        result.report.push_back("warning: " + multiplet_split_text(split, lo, hi));
    }
    if (rep.diagnostics.total() > 0)
        result.report.push_back("operator: " +
                                count_text(rep.diagnostics.negative_weights_clamped,
                                           "negative cotangent weight",
                                           "negative cotangent weights") +
                                " clamped, " +
                                count_text(rep.diagnostics.degenerate_corners, "degenerate corner",
                                           "degenerate corners"));
    result.steps.push_back(OperationStep{std::move(out), MorphCorrespondence{}});
    SpectrumReport typed;
    typed.k = k;
    typed.rows = d.rows();
    typed.lo = lo;
    typed.hi = hi;
    typed.op = d.op;
    typed.method = d.method;
    typed.end = d.end;
    typed.eigenvalues.assign(d.eigenvalues.data(), d.eigenvalues.data() + k);
    typed.decomposition = rep;
    typed.band_split = split;
    add_json_values(typed, result);
    if (split.splits) result.texts.push_back({"band_warning", multiplet_split_text(split, lo, hi)});
    result.typed_report = std::move(typed);
    return result;
}

}  // namespace

SpectralOptions spectral_options(const SpectrumOptions& o) {
    SpectralOptions spectral = o.spectral;
    spectral.method = o.full ? SpectralMethod::Full : SpectralMethod::Partial;
    if (o.k)
        spectral.k = *o.k;
    else if (o.full)
        spectral.k = 0;
    spectral.threads = o.threads.value_or(0);
    return spectral;
}

SpectralOptions spectral_options(const Operation& op) {
    return spectral_options(options_of<SpectrumOptions>(op));
}

std::unique_ptr<OperationDef> spectrum_operation() {
    OperationDecl<SpectrumOptions> d(
        "spectrum", "Spectrum",
        "Decomposes the geometry into the eigenvectors of a fairing Laplacian, K x = lambda S x "
        "(sections 1.2.2, 1.2.11, 1.2.12 of the reference; Taubin 1995; Vallet, Levy 2008), "
        "and reconstructs the mesh from the band LO..HI of the computed frequencies (with "
        "--with-rest, and the part of the geometry they do not carry).");
    d.choice(
        "operator", [](SpectrumOptions & o) -> auto& { return o.spectral.op; },
        EnumTableView(kLaplacianOperators), "the Laplacian");
    d.integer("k", &SpectrumOptions::k, 1, kMaxK, "frequencies, 1 to vertices - 1")
        .default_note("50; with --full all");
    d.choice(
        "which", [](SpectrumOptions & o) -> auto& { return o.spectral.end; },
        EnumTableView(kSpectrumEnds), "which end of the spectrum");
    d.range("band", &SpectrumOptions::band, 0, kMaxK,
            "the frequencies of the reconstruction, 0-based, ascending")
        .default_note("all")
        .cli_only();
    d.flag("with-rest", &SpectrumOptions::with_rest,
           "a band that reaches the open end of the computed frequencies also takes in the "
           "part of the geometry they do not carry (all K then give the mesh)")
        .cli_only();
    d.flag("full", &SpectrumOptions::full, "every frequency, dense (up to --max-full vertices)");
    d.integer(
         "max-full", [](SpectrumOptions & o) -> auto& { return o.spectral.max_full_rows; }, 2,
         100000, "largest mesh for --full, in vertices")
        .hide_default()
        .cli_only();
    d.choice(
         "mass", [](SpectrumOptions & o) -> auto& { return o.spectral.mass; },
         EnumTableView(kMassMatrices), "S: the operator's normalizer or a lumped area")
        .hide_default();
    d.flag(
        "fix-boundary", [](SpectrumOptions & o) -> auto& { return o.spectral.fix_boundary; },
        "fixed (Dirichlet) boundary; default free");
    d.integer("threads", &SpectrumOptions::threads, 1, 2, "spectrum slicing threads (smallest end)")
        .default_note("2 when the machine has them")
        .cli_only();
    d.check([](const SpectrumOptions& o, const auto&) {
        const bool k_known = o.k.has_value() || !o.full;
        const std::size_t k = o.k.value_or(o.spectral.k);
        if (o.band && k_known && o.band->second >= k)
            throw InvalidArgument(
                "--band: expected LO:HI with 0 <= LO <= HI < K = " + std::to_string(k) + ", got '" +
                std::to_string(o.band->first) + ":" + std::to_string(o.band->second) + "'");
    });
    d.run(run_spectrum)
        .acts_on_region(
            "the band's displacement of each vertex is scaled by its weight (the decomposition is "
            "the "
            "whole mesh's)");
    return d.build();
}

}  // namespace trilab
