// The spectral lens headless:
//   trilab-cli spectrum IN OUT --filter "smooth ..." [--k K | --full] [spectrum options]
//                      [--gains FILE] [--eigenvalues FILE] [--split N --removed FILE] [--json]
// Decomposes IN with the Laplacian the filter smooths with (its own normalizer as S), runs the
// filter (the `smooth` operation, parsed like the viewer's --op) on IN, writes its result to
// OUT, and compares the transfer curve (the predicted gain per frequency) with the measured
// one (core/algorithms/transfer_function.h). A filter that stops early (a diverging explicit
// step) writes no OUT, still writes the curve (measured gains NaN) and exits 4.
#include "app/cli/spectrum_filter_command.h"

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <iostream>
#include <limits>
#include <optional>
#include <ostream>

#include "app/cli/arg_reader.h"
#include "app/cli/json_writer.h"
#include "app/cli/operation_command.h"
#include "app/cli/write_options.h"
#include "app/ops/operation.h"
#include "app/ops/smooth_op.h"
#include "app/ops/spectrum_op.h"
#include "core/algorithms/transfer_function.h"
#include "core/errors.h"
#include "core/io/file_util.h"
#include "core/io/mesh_io.h"
#include "core/progress.h"

namespace trilab::cli {

const char* const kSpectrumFilterHelp =
    "  --filter \"smooth ...\"  the lens: decompose with the filter's own Laplacian, run the "
    "smoothing on IN\n"
    "                        (OUT: its result) and compare the predicted gain per frequency with\n"
    "                        the measured one (JSON: eigenvalues, predicted_gain, measured_gain,\n"
    "                        max_difference); see docs/cli.md#the-spectral-lens\n"
    "  --gains FILE          with --filter: one line per frequency, \"index eigenvalue predicted "
    "measured\"\n"
    "  --split N --removed FILE\n"
    "                        with --filter: per vertex \"below above\", the length of its "
    "displacement in\n"
    "                        the frequencies below N and at or above N (the rest included)\n";

namespace {

struct LensArgs {
    std::string filter, gains, eigenvalues, removed;
    bool has_filter = false;
    std::optional<std::size_t> split;
    bool json = false, help = false;
    WriteOptions write;
    std::vector<std::string> op_args, files;
};

bool is_flag(const OperationDef& def, const std::string& option) {
    const std::string name = option.substr(2);
    for (const ParamSpec& p : def.params)
        if (p.name == name) return p.kind == ParamKind::Flag;
    return false;
}

std::size_t parse_count(const std::string& text, const char* option) {
    std::size_t n = 0;
    const char* end = text.data() + text.size();
    const auto [ptr, ec] = std::from_chars(text.data(), end, n);
    if (text.empty() || ec != std::errc() || ptr != end)
        throw InvalidArgument(std::string(option) + ": expected a whole number >= 0, got '" + text +
                              "'");
    return n;
}

LensArgs parse_lens_args(const std::vector<std::string>& args) {
    const OperationDef& def = operation_def("spectrum");
    LensArgs a;
    ArgReader reader(args, "spectrum");
    const auto file_value = [&reader]() {
        const std::string option = reader.arg(), value = reader.value();
        if (value.empty()) throw InvalidArgument(option + ": missing FILE");
        return value;
    };
    while (reader.next()) {
        if (reader.is_help()) {
            a.help = true;
        } else if (reader.is("--json")) {
            a.json = reader.flag();
        } else if (take_write_option(reader, a.write)) {
            continue;
        } else if (reader.is("--filter")) {
            a.filter = reader.value();
            a.has_filter = true;
        } else if (reader.is("--gains")) {
            a.gains = file_value();
        } else if (reader.is("--eigenvalues")) {
            a.eigenvalues = file_value();
        } else if (reader.is("--removed")) {
            a.removed = file_value();
        } else if (reader.is("--split")) {
            a.split = parse_count(reader.value(), "--split");
        } else if (reader.is_option()) {
            a.op_args.push_back(reader.arg());
            if (is_flag(def, reader.arg()))
                reader.flag();
            else if (reader.has_value())
                a.op_args.push_back(reader.value());
        } else {
            a.files.push_back(reader.arg());
        }
    }
    return a;
}

/// The filter's smoothing operation; InvalidArgument naming --filter otherwise.
Operation parse_filter(const std::string& text) {
    Operation op;
    try {
        op = parse_operation(text);
    } catch (const InvalidArgument& e) {
        throw InvalidArgument(std::string("--filter: ") + e.what());
    }
    if (!is_operation<FairingOptions>(op))
        throw InvalidArgument(
            "--filter: expected a smoothing operation (\"smooth --operator umbrella --step 0.5 "
            "...\"), got '" +
            op.name() + "'");
    return op;
}

/// The spectrum options for the lens: the filter's Laplacian with its own normalizer as S. An
/// operator or mass the user gave that differs is refused, not silently replaced.
SpectralOptions lens_spectral_options(const Operation& spectrum, const FairingOptions& f) {
    const LaplacianOperator op = laplacian_of(f.op);
    SpectrumOptions lens = options_of<SpectrumOptions>(spectrum);
    lens.spectral.op = op;
    lens.spectral.mass = MassMatrix::Normalizer;
    const SpectrumOptions given = given_or(spectrum, lens);
    if (given.spectral.op != op)
        throw InvalidArgument(
            std::string("--operator: the filter smooths with the ") + fairing_operator_name(f.op) +
            " operator, so the lens needs the decomposition of " + laplacian_operator_name(op) +
            " (got --operator " + laplacian_operator_name(given.spectral.op) + "; leave it out)");
    if (given.spectral.mass != MassMatrix::Normalizer)
        throw InvalidArgument(
            "--mass: the transfer curve is over the eigenvalues of the operator's own normalizer "
            "(--mass normalizer), which the fairing steps use");
    return spectral_options(lens);
}

std::string number_text_of(double v) {
    if (std::isnan(v)) return "nan";
    if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
    return JsonObject::number(v);
}

void write_lines(const std::string& path, std::size_t n,
                 const std::function<std::string(std::size_t)>& line, const std::string& header) {
    write_file_atomically(path, [&](std::ostream& os) {
        std::string text = header;
        for (std::size_t i = 0; i < n; ++i) text += line(i) + "\n";
        os << text;
    });
}

double ms_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

/// JSON array of numbers with null for NaN.
std::vector<double> as_vector(const Eigen::VectorXd& v) {
    return std::vector<double>(v.data(), v.data() + v.size());
}

std::string band_json(const MultipletSplit::Band& b) {
    return "[" + std::to_string(b.first) + ", " + std::to_string(b.second) + "]";
}

/// Everything the lens computed, for the files, the JSON and the text.
struct Lens {
    Operation filter;
    FairingOptions fo;
    LoadedMesh loaded;
    SpectralDecomposition d;
    std::size_t lo = 0, hi = 0;
    OperationResult run;
    std::vector<double> predicted;
    MeasuredGain measured;
    double max_difference = std::numeric_limits<double>::quiet_NaN();
    bool exact_top = false;  ///< lambda_max from the decomposition (else Lanczos)
    double lambda_max = 0, limit = 0, unstable_from = 0;
    MultipletSplit split;
    std::optional<ChangeByFrequency> removed;
    std::string difference_note;
    double decompose_ms = 0, smooth_ms = 0, lens_ms = 0;

    bool taubin() const { return fo.op == FairingOperator::Taubin; }
    bool implicit() const { return !taubin() && fo.integration == Integration::Implicit; }
    const char* limit_name() const { return implicit() ? "none" : taubin() ? "lambda" : "step"; }
    std::size_t k() const { return d.size(); }
    const HalfedgeMesh& result() const { return run.steps.back().mesh; }
};

/// Checks the arguments that need no file: --filter's presence, --split with --removed.
void check_lens_args(const LensArgs& a) {
    if (!a.has_filter)
        throw InvalidArgument(
            std::string(!a.gains.empty()     ? "--gains"
                        : !a.removed.empty() ? "--removed"
                                             : "--split") +
            ": needs --filter \"smooth ...\" (the smoothing whose gains the lens shows)");
    if (a.split.has_value() != !a.removed.empty())
        throw InvalidArgument(a.split ? "--split: needs --removed FILE (where the fields go)"
                                      : "--removed: needs --split N (the frequency that splits)");
}

/// Reads IN, decomposes it with the filter's operator and checks the band and the split.
void decompose_input(const LensArgs& a, const Operation& spectrum, Lens& l) {
    const SpectralOptions spectral = lens_spectral_options(spectrum, l.fo);
    const SpectrumOptions so = options_of<SpectrumOptions>(spectrum);
    if (a.files.size() != 2)
        throw InvalidArgument("expected IN and OUT files (see `trilab-cli spectrum --help`)");
    l.loaded = read_mesh(a.files[0]);  // not timed
    NullProgress progress;
    const auto t0 = std::chrono::steady_clock::now();
    l.d = decompose(l.loaded.mesh, spectral, progress);
    l.decompose_ms = ms_since(t0);
    const std::size_t k = l.k();
    l.lo = so.band ? so.band->first : 0;
    l.hi = so.band ? so.band->second : k - 1;
    if (l.hi >= k)
        throw InvalidArgument(
            "--band: expected LO:HI with 0 <= LO <= HI < K = " + std::to_string(k) + ", got '" +
            std::to_string(l.lo) + ":" + std::to_string(l.hi) + "'");
    if (a.split && *a.split > k)
        throw InvalidArgument("--split: expected 0 to K = " + std::to_string(k) + ", got " +
                              std::to_string(*a.split));
    if (a.split && l.d.end != SpectrumEnd::Smallest)
        throw InvalidArgument("--split: needs the smallest frequencies (not --which largest)");
}

/// Runs the filter on IN and compares: gains, instability, the band check, the removed fields.
void run_and_measure(const LensArgs& a, Lens& l) {
    const HalfedgeMesh& mesh = l.loaded.mesh;
    NullProgress progress;
    RunSettings settings;
    settings.keep_steps = false;
    settings.morph = false;
    const auto t1 = std::chrono::steady_clock::now();
    l.run = run_operation(l.filter, mesh, progress, settings);
    l.smooth_ms = ms_since(t1);
    const auto t2 = std::chrono::steady_clock::now();
    const std::size_t k = l.k();
    l.predicted = fairing_gains(l.fo, l.d.eigenvalues);
    l.measured.gain.assign(k, std::numeric_limits<double>::quiet_NaN());
    l.measured.undefined = k;
    if (!l.run.stopped_early)
        l.measured = measured_gain(l.d, mesh.positions(), l.result().positions());
    for (std::size_t i = 0; i < k; ++i) {
        const double diff = std::abs(l.measured.gain[i] - l.predicted[i]);
        if (!std::isnan(diff))
            l.max_difference =
                std::isnan(l.max_difference) ? diff : std::max(l.max_difference, diff);
    }
    // The largest eigenvalue: the decomposition's when it holds it, else the fairing's
    // Lanczos estimate 2/max_stable_step (the umbrella's for Taubin).
    l.exact_top = l.d.end == SpectrumEnd::Largest || k == l.d.rows();
    l.lambda_max = k ? std::max(0.0, l.d.eigenvalues.maxCoeff()) : 0.0;
    const SmoothReport* smooth_report = report_of<SmoothReport>(l.run);
    if (!l.exact_top && smooth_report && std::isfinite(smooth_report->max_stable_step) &&
        smooth_report->max_stable_step > 0)
        l.lambda_max = std::max(l.lambda_max, 2.0 / smooth_report->max_stable_step);
    l.limit = instability_limit(l.fo, l.lambda_max);
    l.unstable_from = unstable_eigenvalue(l.fo);
    l.split = band_splits_multiplet(l.d.eigenvalues, l.lo, l.hi);
    if (a.split && !l.run.stopped_early)
        l.removed = change_by_frequency(l.d, mesh.positions(), l.result().positions(), *a.split);
    l.lens_ms = ms_since(t2);
    if (l.run.stopped_early)
        l.difference_note = "the run stopped early: nothing measured";
    else if (fairing_is_linear(l.fo.op))
        l.difference_note =
            "fixed weights: the measured gain is the curve (up to rounding) on a closed mesh; a "
            "boundary (fixed in the run, not in the decomposition) or seams make it differ";
    else
        l.difference_note = std::string(fairing_operator_name(l.fo.op)) +
                            "'s weights follow the positions: the difference is the nonlinearity "
                            "(the curve is the operator at the input)";
}

/// OUT (unless the run stopped early) and the text files asked for.
void write_outputs(const LensArgs& a, const Lens& l) {
    if (!l.run.stopped_early) write_mesh(l.result(), a.files[1], a.write);  // not timed
    const Eigen::VectorXd& ev = l.d.eigenvalues;
    if (!a.gains.empty())
        write_lines(
            a.gains, l.k(),
            [&](std::size_t i) {
                return std::to_string(i) + " " + number_text_of(ev[Eigen::Index(i)]) + " " +
                       number_text_of(l.predicted[i]) + " " + number_text_of(l.measured.gain[i]);
            },
            "# " + l.filter.text() + "\n# index eigenvalue predicted_gain measured_gain\n");
    if (!a.eigenvalues.empty())
        write_lines(
            a.eigenvalues, l.k(),
            [&](std::size_t i) { return number_text_of(std::max(0.0, ev[Eigen::Index(i)])); }, "");
    if (l.removed)
        write_lines(
            a.removed, l.removed->below.size(),
            [&](std::size_t v) {
                return number_text_of(l.removed->below[v]) + " " +
                       number_text_of(l.removed->above[v]);
            },
            "# per vertex (storage index): |displacement| in frequencies below " +
                std::to_string(*a.split) + ", at or above it (nan: not in the decomposition)\n");
}

void print_json(const LensArgs& a, const Lens& l) {
    JsonObject j;
    j.add("input", a.files[0]).add("operation", "spectrum").add("filter", l.filter.text());
    if (!l.run.stopped_early) j.add("output", a.files[1]);
    j.add("operator", laplacian_operator_name(l.d.op))
        .add("method", spectral_method_name(l.d.method))
        .add("which", spectrum_end_name(l.d.end))
        .add("k", l.k())
        .add("rows", l.d.rows())
        .add("linear", fairing_is_linear(l.fo.op))
        .add("eigenvalues", as_vector(l.d.eigenvalues))
        .add("predicted_gain", l.predicted)
        .add("measured_gain", l.measured.gain)
        .add("undefined_gains", l.measured.undefined)
        .add("max_difference", l.max_difference)
        .add("difference_note", l.difference_note)
        .add("lambda_max", l.lambda_max)
        .add("lambda_max_source", l.exact_top ? "decomposition" : "lanczos estimate")
        .add("instability_parameter", l.limit_name())
        .add("instability_limit", l.limit)
        .add("unstable_eigenvalue", l.unstable_from);
    if (l.taubin()) j.add("pass_band", taubin_pass_band_of(l.fo));
    j.add("band", std::vector<double>{double(l.lo), double(l.hi)})
        .add("band_splits_multiplet", l.split.splits);
    if (l.split.splits) {
        j.add("band_warning", multiplet_split_text(l.split, l.lo, l.hi));
        std::string bands = "[";
        if (l.split.narrower) bands += band_json(*l.split.narrower) + ", ";
        j.raw("suggested_bands", bands + band_json(*l.split.wider) + "]");
    }
    if (!a.gains.empty()) j.add("gains_file", a.gains);
    if (!a.eigenvalues.empty()) j.add("eigenvalues_file", a.eigenvalues);
    if (l.removed)
        j.add("split", *a.split)
            .add("removed_file", a.removed)
            .add("removed_below_norm", l.removed->below_norm)
            .add("removed_above_norm", l.removed->above_norm);
    j.add("stopped_early", l.run.stopped_early);
    if (l.run.stopped_early) j.add("stop_reason", l.run.stop_reason);
    j.add("report", l.run.report)
        .add("decompose_ms", l.decompose_ms)
        .add("smooth_ms", l.smooth_ms)
        .add("lens_ms", l.lens_ms)
        .add("ms", l.decompose_ms + l.smooth_ms + l.lens_ms);
    std::cout << j.str() << "\n";
}

void print_text(const LensArgs& a, const Lens& l) {
    const std::size_t k = l.k();
    if (!l.run.stopped_early)
        std::printf("wrote %s: %s (%.1f ms)\n", a.files[1].c_str(), l.filter.text().c_str(),
                    l.decompose_ms + l.smooth_ms + l.lens_ms);
    std::printf("  lens: %zu frequencies of the %s operator (%s, %s), eigenvalues %.6g to %.6g\n",
                k, laplacian_operator_name(l.d.op), spectral_method_name(l.d.method),
                spectrum_end_name(l.d.end), k ? l.d.eigenvalues.minCoeff() : 0.0,
                k ? l.d.eigenvalues.maxCoeff() : 0.0);
    std::printf(
        "  gain: largest |measured - predicted| %s over %zu frequencies (%zu without "
        "an input coefficient): %s\n",
        number_text_of(l.max_difference).c_str(), k - l.measured.undefined, l.measured.undefined,
        l.difference_note.c_str());
    const char* source = l.exact_top ? "decomposition" : "Lanczos estimate";
    if (l.implicit())
        std::printf("  instability: none (implicit steps damp every frequency)\n");
    else if (std::isfinite(l.limit))
        std::printf(
            "  instability: %s above %.6g makes |gain| exceed 1 at lambda_max %.6g (%s); "
            "these settings grow eigenvalues above %.6g\n",
            l.limit_name(), l.limit, l.lambda_max, source, l.unstable_from);
    else
        std::printf(
            "  instability: no %s in its valid range makes |gain| exceed 1 at "
            "lambda_max %.6g (%s); these settings grow eigenvalues above %.6g\n",
            l.limit_name(), l.lambda_max, source, l.unstable_from);
    if (l.taubin()) std::printf("  pass band k_PB %.6g\n", taubin_pass_band_of(l.fo));
    if (l.split.splits)
        std::printf("  warning: %s\n", multiplet_split_text(l.split, l.lo, l.hi).c_str());
    if (l.removed)
        std::printf("  removed: |below %zu| %.6g, |above| %.6g (S norm); wrote %s\n", *a.split,
                    l.removed->below_norm, l.removed->above_norm, a.removed.c_str());
    for (const std::string& line : l.run.report) std::printf("  %s\n", line.c_str());
    if (!a.gains.empty()) std::printf("wrote %s: %zu gains\n", a.gains.c_str(), k);
    if (!a.eigenvalues.empty())
        std::printf("wrote %s: %zu eigenvalues\n", a.eigenvalues.c_str(), k);
}

}  // namespace

bool wants_spectrum_filter(const std::vector<std::string>& args) {
    for (const std::string& a : args)
        for (const char* name : {"--filter", "--gains", "--removed", "--split"})
            if (a == name || a.rfind(std::string(name) + "=", 0) == 0) return true;
    return false;
}

int run_spectrum_filter_command(const std::vector<std::string>& args) {
    const LensArgs a = parse_lens_args(args);
    if (a.help) {
        std::fputs(operation_command_help("spectrum").c_str(), stdout);
        return 0;
    }
    check_lens_args(a);
    Lens l;
    l.filter = parse_filter(a.filter);
    l.fo = options_of<FairingOptions>(l.filter);
    decompose_input(a, parse_operation("spectrum", a.op_args), l);
    run_and_measure(a, l);
    write_outputs(a, l);
    if (a.json)
        print_json(a, l);
    else
        print_text(a, l);
    if (l.run.stopped_early) {
        std::fflush(stdout);
        std::fprintf(stderr,
                     "trilab-cli spectrum: the filter stopped early: %s (nothing written "
                     "to OUT; the curve was)\n",
                     l.run.stop_reason.c_str());
        return 4;
    }
    return 0;
}

}  // namespace trilab::cli
