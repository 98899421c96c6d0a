#include "app/cli/operation_report.h"

#include <algorithm>
#include <cmath>

namespace trilab::cli {
namespace {

/// The operation's parameters as typed JSON values (keys with '_' for '-'), skipping the
/// ones that do not apply, unset optional ones, and keys the result reports itself.
void add_parameter_echo(JsonObject& json, const Operation& op, const OperationResult& result) {
    const auto reported = [&](const std::string& key) {
        for (const auto& [k, v] : result.values)
            if (k == key) return true;
        for (const auto& [k, v] : result.texts)
            if (k == key) return true;
        return key == "vertices" || key == "faces";
    };
    for (std::size_t i = 0; i < op.def->params.size(); ++i) {
        const ParamSpec& p = op.def->params[i];
        const ParamValue& v = op.values[i];
        std::string key = p.name;
        std::replace(key.begin(), key.end(), '-', '_');
        if (op.def->why_not(op.values, i) || reported(key)) continue;
        if (p.optional && !v.on) continue;
        switch (p.kind) {
            case ParamKind::Flag:
                json.add(key, v.x != 0);
                break;
            case ParamKind::Choice:
                json.add(key, format_param_value(p, v));
                break;
            case ParamKind::Switchable:
                if (v.on)
                    json.add(key, v.x);
                else
                    json.add(key, p.off_word);
                break;
            case ParamKind::Range:
                json.add(key, std::vector<double>{v.x, v.y});
                break;
            case ParamKind::Integer:
                json.add(key, static_cast<long long>(v.x));
                break;
            case ParamKind::Number:
                json.add(key, v.x);
                break;
        }
    }
}

void add_values(JsonObject& json, const OperationResult& result) {
    for (const auto& [key, value] : result.values) {
        if (key == "vertices" || key == "faces") continue;
        if (std::isnan(value))
            json.add_null(key);  // not defined for this mesh (an open mesh's volume)
        else if (value == std::floor(value) && std::abs(value) < 9e15)
            json.add(key, static_cast<long long>(value));
        else
            json.add(key, value);
    }
}

}  // namespace

void add_operation_report(JsonObject& j, const Operation& op, const OperationResult& result,
                          const CommandExtras& extras,
                          const std::map<std::string, std::string>& own,
                          const std::vector<std::string>& save_notes) {
    const HalfedgeMesh& out = result.steps.back().mesh;
    j.add("operation", op.name()).add("parameters", result.parameters);
    add_parameter_echo(j, op, result);
    j.add("vertices", out.n_vertices()).add("faces", out.n_faces());
    add_values(j, result);
    for (const auto& [key, text] : result.texts) j.add(key, text);
    if (extras.finish) extras.finish(result, own, &j);
    j.add("stopped_early", result.stopped_early);
    if (result.stopped_early) j.add("stop_reason", result.stop_reason);
    if (!save_notes.empty()) j.add("save_notes", save_notes);
    j.add("report", result.report);
}

}  // namespace trilab::cli
