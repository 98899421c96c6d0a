// The operation registry (app/ops/operation.h): one table entry per operation, each a parser
// from "--option value" tokens to the operation's options struct and a runner that applies
// the core algorithm to a copy of the mesh. Method: the text is split on whitespace; the
// OptionReader below walks the tokens so every operation reports errors the same way, naming
// the option. Guarantees: parse_operation() runs nothing; run_operation() never modifies its
// input mesh, checks everything before working, and returns at least one step whose
// correspondence fits its predecessor; numbers print in shortest round-trip form, so the
// canonical parameters parse back to the same operation.
#include "app/ops/operation.h"

#include <cctype>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <limits>
#include <set>
#include <utility>

#include "core/errors.h"
#include "core/fairing.h"
#include "core/noise.h"
#include "core/subdivision.h"

namespace trilab {
namespace {

// ---- option reading -----------------------------------------------------------------------

/// Walks the "--option value" tokens of one operation. Usage, in a parser:
///   while (r.next()) { if (r.is("--amount")) o.amount = r.number(0, 100); else r.unknown(); }
class OptionReader {
public:
    OptionReader(std::string op, std::string usage, const std::vector<std::string>& args)
        : op_(std::move(op)), usage_(std::move(usage)), args_(args) {}

    /// Moves to the next option; false after the last. Throws for a token that is not an
    /// option, an option given twice, or an "--flag=value" whose value was not read.
    bool next() {
        if (has_inline_value_) throw bad_option("takes no value");
        if (i_ >= args_.size()) return false;
        const std::string& token = args_[i_++];
        if (token.rfind("--", 0) != 0 || token.size() == 2)
            throw InvalidArgument(op_ + ": unexpected argument '" + token +
                                  "' (options: " + usage_ + ")");
        const std::size_t eq = token.find('=');
        option_ = token.substr(0, eq);
        has_inline_value_ = eq != std::string::npos;
        inline_value_ = has_inline_value_ ? token.substr(eq + 1) : std::string();
        if (!seen_.insert(option_).second) throw bad_option("given more than once");
        return true;
    }
    bool is(const char* name) const { return option_ == name; }
    const std::string& option() const { return option_; }

    /// The current option's value text.
    const std::string& value() {
        if (has_inline_value_) {
            has_inline_value_ = false;
            return inline_value_;
        }
        if (i_ >= args_.size()) throw bad_option("missing value");
        return args_[i_++];
    }
    /// The value as a finite number in [min, max]; `unit` is appended to the range text.
    double number(double min, double max, const std::string& unit = "") {
        const std::string& text = value();
        double v = 0;
        const char* end = text.data() + text.size();
        const auto [ptr, ec] = std::from_chars(text.data(), end, v);
        if (text.empty() || ec != std::errc() || ptr != end || !std::isfinite(v) || v < min ||
            v > max)
            throw bad_value(
                "a number from " + format_number(min) + " to " + format_number(max) + unit, text);
        return v;
    }
    /// The value as a whole number in [min, max] (decimal digits only).
    std::uint64_t whole_number(std::uint64_t min, std::uint64_t max) {
        const std::string& text = value();
        std::uint64_t v = 0;
        const char* end = text.data() + text.size();
        const auto [ptr, ec] = std::from_chars(text.data(), end, v);
        if (text.empty() || ec != std::errc() || ptr != end || v < min || v > max)
            throw bad_value(
                "a whole number from " + std::to_string(min) + " to " + std::to_string(max), text);
        return v;
    }
    /// The value, which must be one of `choices`.
    std::string choice(const std::vector<std::string>& choices) {
        const std::string& text = value();
        std::string list;
        for (const std::string& c : choices) {
            if (c == text) return c;
            list += (list.empty() ? "" : ", ") + c;
        }
        throw bad_value("one of " + list, text);
    }
    /// Throws: the current option is not one of this operation's.
    [[noreturn]] void unknown() const {
        throw InvalidArgument("unknown option '" + option_ + "' for " + op_ +
                              " (options: " + usage_ + ")");
    }
    /// An error about the current option's value: "--amount: expected ..., got 'text'".
    InvalidArgument bad_value(const std::string& expected, const std::string& text) const {
        return InvalidArgument(option_ + ": expected " + expected + ", got '" + text + "'");
    }
    InvalidArgument bad_option(const std::string& reason) const {
        return InvalidArgument(option_ + ": " + reason);
    }
    /// Throws when tokens are left (a parser that stopped early).
    void finish() {
        if (next()) unknown();
    }

    /// Shortest text that reads back as exactly `v`.
    static std::string format_number(double v) {
        char buf[64];
        const auto [ptr, ec] = std::to_chars(buf, buf + sizeof(buf), v);
        return ec == std::errc() ? std::string(buf, ptr) : std::to_string(v);
    }

private:
    std::string op_, usage_;
    const std::vector<std::string>& args_;
    std::size_t i_ = 0;
    std::string option_, inline_value_;
    bool has_inline_value_ = false;
    std::set<std::string> seen_;
};

double ms_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

// ---- noise --------------------------------------------------------------------------------

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

// ---- subdivide ----------------------------------------------------------------------------

constexpr const char* kSubdivideUsage =
    "--scheme loop|sqrt3|butterfly|modified-butterfly (default loop), "
    "--iterations N (1 to 10, default 1)";

SubdivisionOptions parse_subdivide(OptionReader& r) {
    SubdivisionOptions o;
    while (r.next()) {
        if (r.is("--scheme"))
            o.scheme = parse_scheme(r.choice({"loop", "sqrt3", "butterfly", "modified-butterfly"}));
        else if (r.is("--iterations"))
            o.iterations = int(r.whole_number(1, 10));
        else
            r.unknown();
    }
    return o;
}

OperationResult run_subdivide(const SubdivisionOptions& o, const HalfedgeMesh& mesh,
                              Progress& progress) {
    progress.check_cancelled();
    OperationResult result;
    result.label = "Subdivide";
    result.parameters = std::string("--scheme ") + scheme_name(o.scheme) + " --iterations " +
                        std::to_string(o.iterations);
    SubdivisionResult sub;
    if (mesh.has_garbage()) {  // subdivide() wants a compact mesh: compact a copy
        HalfedgeMesh compact = mesh;
        compact.garbage_collection();
        sub = subdivide(compact, o, progress);
    } else {
        sub = subdivide(mesh, o, progress);
    }
    result.ms = sub.ms;
    char line[160];
    for (std::size_t i = 0; i < sub.levels.size(); ++i) {
        const HalfedgeMesh& m = sub.levels[i].mesh;
        std::snprintf(line, sizeof(line), "level %zu: %zu vertices, %zu faces", i + 1,
                      m.n_vertices(), m.n_faces());
        result.report.emplace_back(line);
    }
    std::snprintf(line, sizeof(line), "%s, %d iteration%s: %zu -> %zu faces in %.1f ms",
                  scheme_name(o.scheme), o.iterations, o.iterations == 1 ? "" : "s", mesh.n_faces(),
                  sub.levels.empty() ? 0 : sub.levels.back().mesh.n_faces(), sub.ms);
    result.report.emplace_back(line);
    for (SubdivisionLevel& level : sub.levels)
        result.steps.push_back(
            OperationStep{std::move(level.mesh), std::move(level.correspondence)});
    const HalfedgeMesh& last = result.steps.back().mesh;
    // "scheme" as a number: its SubdivisionScheme index (0 loop, 1 sqrt3, 2 butterfly,
    // 3 modified-butterfly); the parameters text carries the name.
    result.values = {{"scheme", double(int(o.scheme))},
                     {"iterations", double(o.iterations)},
                     {"vertices", double(last.n_vertices())},
                     {"faces", double(last.n_faces())}};
    return result;
}

// ---- smooth -------------------------------------------------------------------------------

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

// ---- the registry -------------------------------------------------------------------------

struct Entry {
    const char* name;
    const char* usage;
    std::function<void(OptionReader&)> check;
    std::function<OperationResult(OptionReader&, const HalfedgeMesh&, Progress&)> run;
};

/// An entry from an operation's typed parser and runner.
template <class Options>
Entry make_entry(const char* name, const char* usage, Options (*parse)(OptionReader&),
                 OperationResult (*run)(const Options&, const HalfedgeMesh&, Progress&)) {
    return Entry{name, usage,
                 [parse](OptionReader& r) {
                     parse(r);
                     r.finish();
                 },
                 [parse, run](OptionReader& r, const HalfedgeMesh& mesh, Progress& progress) {
                     const Options options = parse(r);
                     r.finish();
                     return run(options, mesh, progress);
                 }};
}

/// Every operation, in menu order. Later issues add one line each (see operation.h).
const std::vector<Entry>& registry() {
    static const std::vector<Entry> entries = {
        make_entry<NoiseOptions>("noise", kNoiseUsage, parse_noise, run_noise),
        make_entry<SubdivisionOptions>("subdivide", kSubdivideUsage, parse_subdivide,
                                       run_subdivide),
        make_entry<FairingOptions>("smooth", kSmoothUsage, parse_smooth, run_smooth),
    };
    return entries;
}

std::string known_names() {
    std::string s;
    for (const Entry& e : registry()) s += (s.empty() ? "" : ", ") + std::string(e.name);
    return s;
}

const Entry& find_entry(const std::string& name) {
    for (const Entry& e : registry())
        if (name == e.name) return e;
    if (name.empty()) throw InvalidArgument("empty operation (known: " + known_names() + ")");
    throw InvalidArgument("unknown operation '" + name + "' (known: " + known_names() + ")");
}

std::vector<std::string> tokenize(const std::string& text) {
    std::vector<std::string> tokens;
    std::size_t i = 0;
    const auto space = [&](std::size_t k) { return std::isspace((unsigned char)text[k]) != 0; };
    while (i < text.size()) {
        while (i < text.size() && space(i)) ++i;
        const std::size_t start = i;
        while (i < text.size() && !space(i)) ++i;
        if (i > start) tokens.push_back(text.substr(start, i - start));
    }
    return tokens;
}

}  // namespace

Operation parse_operation(const std::string& text) {
    std::vector<std::string> tokens = tokenize(text);
    Operation op;
    if (!tokens.empty()) op.name = tokens.front();
    const Entry& entry = find_entry(op.name);
    op.args.assign(tokens.begin() + (tokens.empty() ? 0 : 1), tokens.end());
    OptionReader reader(entry.name, entry.usage, op.args);
    entry.check(reader);
    return op;
}

OperationResult run_operation(const Operation& op, const HalfedgeMesh& mesh, Progress& progress) {
    const Entry& entry = find_entry(op.name);
    OptionReader reader(entry.name, entry.usage, op.args);
    return entry.run(reader, mesh, progress);
}

std::vector<std::string> operation_names() {
    std::vector<std::string> names;
    for (const Entry& e : registry()) names.emplace_back(e.name);
    return names;
}

std::string operation_usage(const std::string& name) {
    return find_entry(name).usage;
}

}  // namespace trilab
