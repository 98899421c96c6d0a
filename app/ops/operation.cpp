// The operation registry (app/ops/operation.h) and the one parser, printer and checker of
// typed parameters (app/ops/parameter.h) that every operation shares. Method: the text is
// split on whitespace; each "--name" is looked up among the operation's declared
// parameters and its value parsed by the parameter's kind, so every operation reports
// errors the same way, naming the option. Guarantees: parsing runs nothing; run_operation()
// never modifies its input mesh and checks everything before working; numbers print in
// shortest round-trip form, so the canonical parameters parse back to the same values.
#include "app/ops/operation.h"

#include <cctype>
#include <charconv>
#include <chrono>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "app/ops/operation_decl.h"
#include "app/ops/operation_entries.h"
#include "core/algorithms/selection.h"
#include "core/errors.h"

namespace trilab {

double ms_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

std::string format_number(double v) {
    char buf[64];
    const auto [ptr, ec] = std::to_chars(buf, buf + sizeof(buf), v);
    return ec == std::errc() ? std::string(buf, ptr) : std::to_string(v);
}

namespace {

std::string option(const ParamSpec& s) {
    return "--" + s.name;
}

bool parse_double(const std::string& text, double& v) {
    const char* end = text.data() + text.size();
    const auto [ptr, ec] = std::from_chars(text.data(), end, v);
    return !text.empty() && ec == std::errc() && ptr == end && std::isfinite(v);
}

bool parse_whole(const std::string& text, double& v) {
    if (text.empty() || text.size() > 18 ||
        text.find_first_not_of("0123456789") != std::string::npos)
        return false;
    v = double(std::stoull(text));
    return true;
}

std::string range_text(const ParamSpec& s, const char* what) {
    std::string t = std::string(what) + " from " + format_number(s.min) + " to " +
                    format_number(s.max) + s.unit;
    if (s.min_exclusive) t += " (above " + format_number(s.min) + ")";
    return t;
}

std::string expected_text(const ParamSpec& s) {
    switch (s.kind) {
        case ParamKind::Number:
            return range_text(s, "a number");
        case ParamKind::Integer:
            return range_text(s, "a whole number");
        case ParamKind::Flag:
            return "no value";
        case ParamKind::Choice: {
            std::string list;
            for (const ChoiceItem& c : s.choices) list += (list.empty() ? "" : ", ") + c.id;
            return "one of " + list;
        }
        case ParamKind::Switchable:
            return range_text(s, "a number") + ", or " + s.off_word;
        case ParamKind::Range:
            return "LO:HI with " + format_number(s.min) + " <= LO <= HI <= " + format_number(s.max);
    }
    return "";
}

InvalidArgument bad_value(const ParamSpec& s, const std::string& text) {
    return InvalidArgument(option(s) + ": expected " + expected_text(s) + ", got '" + text + "'");
}

bool in_range(const ParamSpec& s, double v) {
    return v >= s.min && v <= s.max && !(s.min_exclusive && v == s.min);
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

std::string known_names() {
    std::string s;
    for (const OperationDef* d : operation_defs()) s += (s.empty() ? "" : ", ") + d->name;
    return s;
}

/// Refuses a parameter that was named on the command line but does not apply.
void check_applies(const OperationDef& def, const ParamValues& values) {
    for (std::size_t i = 0; i < def.params.size(); ++i) {
        if (!values[i].given) continue;
        if (const char* why = def.why_not(values, i))
            throw InvalidArgument(option(def.params[i]) + ": " + why);
    }
}

}  // namespace

std::string format_param_value(const ParamSpec& s, const ParamValue& v) {
    switch (s.kind) {
        case ParamKind::Number:
        case ParamKind::Integer:
            return format_number(v.x);
        case ParamKind::Flag:
            return "";
        case ParamKind::Choice:
            for (const ChoiceItem& c : s.choices)
                if (c.value == int(v.x)) return c.id;
            return "?";
        case ParamKind::Switchable:
            return v.on ? format_number(v.x) : s.off_word;
        case ParamKind::Range:
            return format_number(v.x) + ":" + format_number(v.y);
    }
    return "";
}

ParamValue parse_param_value(const ParamSpec& s, const std::string& text) {
    ParamValue v;
    v.given = true;
    switch (s.kind) {
        case ParamKind::Number:
            if (!parse_double(text, v.x) || !in_range(s, v.x)) throw bad_value(s, text);
            return v;
        case ParamKind::Integer:
            if (!parse_whole(text, v.x) || !in_range(s, v.x)) throw bad_value(s, text);
            return v;
        case ParamKind::Flag:
            v.x = 1;
            return v;
        case ParamKind::Choice:
            for (const ChoiceItem& c : s.choices)
                if (c.id == text) {
                    v.x = c.value;
                    return v;
                }
            throw bad_value(s, text);
        case ParamKind::Switchable:
            if (text == s.off_word) {
                v.on = false;
                return v;
            }
            if (!parse_double(text, v.x) || !in_range(s, v.x)) throw bad_value(s, text);
            return v;
        case ParamKind::Range: {
            const std::size_t colon = text.find(':');
            if (colon == std::string::npos || !parse_whole(text.substr(0, colon), v.x) ||
                !parse_whole(text.substr(colon + 1), v.y) || v.x > v.y || !in_range(s, v.x) ||
                !in_range(s, v.y))
                throw bad_value(s, text);
            return v;
        }
    }
    return v;
}

void check_param_value(const ParamSpec& s, const ParamValue& v) {
    if (s.optional && !v.on) return;  // unset: the run's default
    const bool ok = [&] {
        switch (s.kind) {
            case ParamKind::Number:
                return std::isfinite(v.x) && in_range(s, v.x);
            case ParamKind::Integer:
                return in_range(s, v.x) && v.x == std::floor(v.x);
            case ParamKind::Flag:
                return v.x == 0 || v.x == 1;
            case ParamKind::Choice:
                for (const ChoiceItem& c : s.choices)
                    if (c.value == int(v.x) && double(c.value) == v.x) return true;
                return false;
            case ParamKind::Switchable:
                return !v.on || (std::isfinite(v.x) && in_range(s, v.x));
            case ParamKind::Range:
                return !v.on || (in_range(s, v.x) && in_range(s, v.y) && v.x <= v.y &&
                                 v.x == std::floor(v.x) && v.y == std::floor(v.y));
        }
        return false;
    }();
    if (!ok)
        throw bad_value(s, s.kind == ParamKind::Number || s.kind == ParamKind::Switchable
                               ? format_number(v.x)
                               : format_param_value(s, v));
}

std::string param_usage(const ParamSpec& s, const ParamValue& d) {
    std::string line = option(s);
    switch (s.kind) {
        case ParamKind::Flag:
            break;
        case ParamKind::Choice: {
            std::string list;
            for (const ChoiceItem& c : s.choices) list += (list.empty() ? "" : "|") + c.id;
            line += " " + list;
            break;
        }
        case ParamKind::Switchable:
            line += " X|" + s.off_word;
            break;
        case ParamKind::Range:
            line += " LO:HI";
            break;
        default:
            line += " X";
    }
    std::string note = s.help;
    if (s.kind == ParamKind::Number || s.kind == ParamKind::Integer ||
        s.kind == ParamKind::Switchable)
        note += std::string(note.empty() ? "" : "; ") + format_number(s.min) + " to " +
                format_number(s.max) + s.unit;
    if (!s.default_note.empty())
        note += "; default " + s.default_note;
    else if (s.kind != ParamKind::Flag && d.on && !s.optional)
        note += "; default " + format_param_value(s, d);
    else if (s.kind == ParamKind::Switchable && !d.on)
        note += "; default " + s.off_word;
    return line + " (" + note + ")";
}

// ---- OperationDef ---------------------------------------------------------------------------

std::size_t OperationDef::index(const std::string& param) const {
    for (std::size_t i = 0; i < params.size(); ++i)
        if (params[i].name == param) return i;
    throw InvalidArgument("unknown option '--" + param + "' for " + name + " (options: " + usage() +
                          ")");
}

std::string OperationDef::usage() const {
    std::string s;
    for (std::size_t i = 0; i < params.size(); ++i)
        s += (i ? ", " : "") + param_usage(params[i], defaults[i]);
    return s.empty() ? "none" : s;
}

std::string OperationDef::help() const {
    std::string s;
    for (std::size_t i = 0; i < params.size(); ++i) {
        const ParamSpec& p = params[i];
        std::string head = "  " + param_usage(p, defaults[i]);
        s += head + "\n";
    }
    return s;
}

// ---- Operation ------------------------------------------------------------------------------

const std::string& Operation::name() const {
    static const std::string none;
    return def ? def->name : none;
}

const ParamValue& Operation::value(const std::string& param) const {
    if (!def) throw InvalidArgument("empty operation");
    return values.at(def->index(param));
}

ParamValue& Operation::value(const std::string& param) {
    if (!def) throw InvalidArgument("empty operation");
    return values.at(def->index(param));
}

std::string Operation::parameters() const {
    std::string s;
    if (!def) return s;
    for (std::size_t i = 0; i < def->params.size(); ++i) {
        const ParamSpec& p = def->params[i];
        const ParamValue& v = values[i];
        if (def->why_not(values, i)) continue;                // does not apply
        if (p.kind == ParamKind::Flag && v.x == 0) continue;  // flags only when set
        if (p.optional && !v.on) continue;                    // unset: the run's default
        if (p.kind == ParamKind::Switchable && !v.on && !def->defaults[i].on) continue;
        if (p.hide_default && v == def->defaults[i]) continue;
        s += (s.empty() ? "" : " ") + option(p);
        if (p.kind != ParamKind::Flag) s += " " + format_param_value(p, v);
    }
    return s;
}

std::string Operation::text() const {
    const std::string p = parameters();
    return p.empty() ? name() : name() + " " + p;
}

// ---- registry -------------------------------------------------------------------------------

const std::vector<const OperationDef*>& operation_defs() {
    static const std::vector<std::unique_ptr<OperationDef>> owned = [] {
        std::vector<std::unique_ptr<OperationDef>> v;
        v.push_back(noise_operation());
        v.push_back(subdivide_operation());
        v.push_back(smooth_operation());
        v.push_back(denoise_operation());
        v.push_back(spectrum_operation());
        v.push_back(decimate_operation());
        v.push_back(flip_operation());
        v.push_back(weld_operation());
        v.push_back(remove_components_operation());
        v.push_back(features_operation());
        v.push_back(sharpen_operation());
        v.push_back(fill_holes_operation());

        v.push_back(remesh_operation());
        return v;
    }();
    static const std::vector<const OperationDef*> defs = [] {
        std::vector<const OperationDef*> v;
        for (const auto& d : owned) v.push_back(d.get());
        return v;
    }();
    return defs;
}

const OperationDef& operation_def(const std::string& name) {
    for (const OperationDef* d : operation_defs())
        if (d->name == name) return *d;
    if (name.empty()) throw InvalidArgument("empty operation (known: " + known_names() + ")");
    throw InvalidArgument("unknown operation '" + name + "' (known: " + known_names() + ")");
}

const OperationDef& operation_def_of(const std::type_info& options) {
    for (const OperationDef* d : operation_defs())
        if (d->options_type && *d->options_type == options) return *d;
    throw InvalidArgument("no registered operation takes the options struct asked for (known: " +
                          known_names() + ")");
}

void require_options_type(const Operation& op, const std::type_info& options, const char* caller) {
    if (op.def && op.def->options_type && *op.def->options_type == options) return;
    std::string wanted = "an operation of the options asked for";
    for (const OperationDef* d : operation_defs())
        if (d->options_type && *d->options_type == options) wanted = "'" + d->name + "'";
    throw InvalidArgument(std::string(caller) + ": expected " + wanted + ", got " +
                          (op.def ? "'" + op.def->name + "'" : std::string("an empty operation")));
}

void store_changed_values(Operation& op, const ParamValues& values) {
    if (!op.def) throw InvalidArgument("empty operation (known: " + known_names() + ")");
    if (values.size() != op.values.size())
        throw InvalidArgument(op.def->name + ": expected " + std::to_string(op.values.size()) +
                              " parameter values, got " + std::to_string(values.size()));
    for (std::size_t i = 0; i < values.size(); ++i) {
        if (values[i] == op.values[i]) continue;  // the same meaning: left as it was
        const bool unset = op.def->params[i].optional && !values[i].on;
        op.values[i] = values[i];
        op.values[i].given = !unset;
    }
}

std::vector<std::string> operation_names() {
    std::vector<std::string> names;
    for (const OperationDef* d : operation_defs()) names.push_back(d->name);
    return names;
}

std::string operation_usage(const std::string& name) {
    return operation_def(name).usage();
}

Operation make_operation(const std::string& name) {
    const OperationDef& def = operation_def(name);
    return Operation{&def, def.defaults};
}

Operation parse_operation(const std::string& name, const std::vector<std::string>& args) {
    Operation op = make_operation(name);
    const OperationDef& def = *op.def;
    for (std::size_t k = 0; k < args.size(); ++k) {
        const std::string& token = args[k];
        if (token.rfind("--", 0) != 0 || token.size() == 2)
            throw InvalidArgument(name + ": unexpected argument '" + token +
                                  "' (options: " + def.usage() + ")");
        const std::size_t eq = token.find('=');
        const std::string param = token.substr(2, eq == std::string::npos ? eq : eq - 2);
        const std::size_t i = def.index(param);
        const ParamSpec& spec = def.params[i];
        if (op.values[i].given) throw InvalidArgument(option(spec) + ": given more than once");
        std::string text;
        if (spec.kind == ParamKind::Flag) {
            if (eq != std::string::npos) throw InvalidArgument(option(spec) + ": takes no value");
        } else if (eq != std::string::npos) {
            text = token.substr(eq + 1);
        } else {
            if (k + 1 >= args.size()) throw InvalidArgument(option(spec) + ": missing value");
            text = args[++k];
        }
        op.values[i] = parse_param_value(spec, text);
    }
    check_applies(def, op.values);
    def.check(op.values);
    return op;
}

Operation parse_operation(const std::string& text) {
    std::vector<std::string> tokens = tokenize(text);
    const std::string name = tokens.empty() ? std::string() : tokens.front();
    operation_def(name);  // names the known operations for an unknown or empty name
    return parse_operation(name, std::vector<std::string>(tokens.begin() + 1, tokens.end()));
}

void check_operation(const Operation& op) {
    if (!op.def) throw InvalidArgument("empty operation (known: " + known_names() + ")");
    const OperationDef& def = *op.def;
    if (op.values.size() != def.params.size())
        throw InvalidArgument(def.name + ": expected " + std::to_string(def.params.size()) +
                              " parameter values, got " + std::to_string(op.values.size()));
    for (std::size_t i = 0; i < def.params.size(); ++i)
        check_param_value(def.params[i], op.values[i]);
    def.check(op.values);
}

void check_parameter_applies(const Operation& op, const std::string& param) {
    if (!op.def) throw InvalidArgument("empty operation (known: " + known_names() + ")");
    const std::size_t i = op.def->index(param);
    if (const char* why = op.def->why_not(op.values, i))
        throw InvalidArgument(option(op.def->params[i]) + ": " + why);
}

std::string run_failure(const OperationResult& result) {
    if (result.stopped_early)
        return "stopped early: " +
               (result.stop_reason.empty() ? std::string("no reason given") : result.stop_reason);
    if (!result.changed) return "changed nothing";
    return "";
}

void check_region_not_empty(const HalfedgeMesh& mesh, const std::vector<float>& region,
                            const std::string& label) {
    if (count_selected(region) > 0) return;
    throw InvalidArgument(label + ": the region is empty (0 of " +
                          std::to_string(mesh.n_vertices()) +
                          " vertices selected, every weight is 0): nothing to do, nothing "
                          "changed (select some vertices, or clear the selection to act on "
                          "the whole mesh)");
}

OperationResult run_operation(const Operation& op, const HalfedgeMesh& mesh, Progress& progress,
                              const RunSettings& settings) {
    check_operation(op);
    if (settings.region) {
        if (!op.def->takes_region)
            throw InvalidArgument("--region: " + op.def->name +
                                  " does not work on a region yet (it acts on the whole mesh)");
        check_selection(mesh, *settings.region, "--region");
        check_region_not_empty(mesh, *settings.region, op.def->label);
    }
    const std::size_t n_vertices = mesh.n_vertices();  // before the run may consume `mesh`
    OperationResult result = op.def->run(op.values, mesh, progress, settings);
    if (result.label.empty()) result.label = op.def->label;
    if (settings.region) {
        const std::size_t n = count_selected(*settings.region);
        result.values.emplace_back("region_vertices", double(n));
        result.report.insert(result.report.begin(), "region: " + std::to_string(n) + " of " +
                                                        std::to_string(n_vertices) +
                                                        " vertices (weight > 0)");
    }
    result.parameters = op.parameters();
    return result;
}

}  // namespace trilab
