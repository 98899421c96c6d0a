// Recipes (app/history/recipe.h).
#include "app/history/recipe.h"

#include <cstring>

#include "app/history/json_reader.h"
#include "core/errors.h"
#include "core/progress.h"

namespace trilab {

namespace {

std::string quote(const std::string& s) {
    std::string out = "\"";
    for (unsigned char c : s) {
        if (c == '"' || c == '\\') {
            out += '\\';
            out += char(c);
        } else if (c < 0x20) {
            char buf[8];
            std::snprintf(buf, sizeof buf, "\\u%04x", c);
            out += buf;
        } else {
            out += char(c);
        }
    }
    return out + "\"";
}

/// The typed JSON value of parameter `i` of `op`, or "" when it is left out (does not apply,
/// an unset optional value, a flag that is off).
std::string typed_value(const Operation& op, std::size_t i) {
    const ParamSpec& p = op.def->params[i];
    const ParamValue& v = op.values[i];
    if (op.def->why_not(op.values, i)) return "";
    if (p.optional && !v.on) return "";
    switch (p.kind) {
        case ParamKind::Flag:
            return v.x != 0 ? "true" : "";
        case ParamKind::Choice:
            return quote(format_param_value(p, v));
        case ParamKind::Switchable:
            return v.on ? format_number(v.x) : quote(p.off_word);
        case ParamKind::Range:
            return "[" + format_number(v.x) + ", " + format_number(v.y) + "]";
        default:
            return format_number(v.x);
    }
}

/// The command-line text of a typed JSON value (the inverse of typed_value).
std::vector<std::string> option_tokens(const ParamSpec& p, const JsonValue& v,
                                       const std::string& where) {
    const std::string option = "--" + p.name;
    const auto bad = [&](const char* expected) {
        return InvalidArgument(where + ": " + option + ": expected " + expected);
    };
    switch (p.kind) {
        case ParamKind::Flag:
            if (v.type != JsonValue::Type::Bool) throw bad("true or false");
            return v.boolean ? std::vector<std::string>{option} : std::vector<std::string>{};
        case ParamKind::Choice:
            if (v.type != JsonValue::Type::String) throw bad("a string");
            return {option, v.text};
        case ParamKind::Range:
            if (v.type != JsonValue::Type::Array || v.items.size() != 2 ||
                v.items[0].type != JsonValue::Type::Number ||
                v.items[1].type != JsonValue::Type::Number)
                throw bad("[LO, HI]");
            return {option,
                    format_number(v.items[0].number) + ":" + format_number(v.items[1].number)};
        case ParamKind::Switchable:
            if (v.type == JsonValue::Type::String) return {option, v.text};
            [[fallthrough]];
        default:
            if (v.type != JsonValue::Type::Number) throw bad("a number");
            return {option, format_number(v.number)};
    }
}

}  // namespace

Recipe recipe_of(const History& history) {
    if (history.size() == 0) throw InvalidArgument("recipe: the history is empty");
    const std::size_t current = history.current();
    std::size_t load = current;
    while (load > 0 && history.info(load).operation.def) --load;
    // `load` has no operation (or is entry 0).
    Recipe r;
    const History::EntryInfo source = history.info(load);
    r.source = source.label + (source.parameters.empty() ? "" : " " + source.parameters);
    if (source.operation.def)
        throw InvalidArgument("recipe: entry 0 \"" + source.label +
                              "\" is an operation; the history does not start with a load");
    for (std::size_t i = load + 1; i <= current; ++i)
        r.operations.push_back(history.info(i).operation);
    return r;
}

std::string typed_parameters_json(const Operation& op) {
    std::string s = "{";
    for (std::size_t i = 0; op.def && i < op.def->params.size(); ++i) {
        const std::string v = typed_value(op, i);
        if (v.empty()) continue;
        s += std::string(s.size() > 1 ? ", " : "") + quote(op.def->params[i].name) + ": " + v;
    }
    return s + "}";
}

std::string recipe_json(const Recipe& recipe) {
    std::string s = "{\n  \"format\": \"trilab-recipe\",\n  \"version\": 1,\n  \"source\": " +
                    quote(recipe.source) + ",\n  \"operations\": [";
    for (std::size_t k = 0; k < recipe.operations.size(); ++k) {
        const Operation& op = recipe.operations[k];
        s += std::string(k ? "," : "") + "\n    {\"operation\": " + quote(op.name()) +
             ", \"text\": " + quote(op.text()) +
             ",\n     \"parameters\": " + typed_parameters_json(op) + "}";
    }
    return s + (recipe.operations.empty() ? "]\n}\n" : "\n  ]\n}\n");
}

Recipe parse_recipe(const std::string& json, const std::string& name) {
    const JsonValue doc = parse_json(json, name);
    const JsonValue* format = doc.find("format");
    if (doc.type != JsonValue::Type::Object || !format || format->text != "trilab-recipe")
        throw InvalidArgument(name + ": not a trilab recipe (no \"format\": \"trilab-recipe\")");
    const JsonValue* version = doc.find("version");
    if (!version || version->type != JsonValue::Type::Number || version->number != 1)
        throw InvalidArgument(name + ": recipe version is not 1");
    Recipe r;
    if (const JsonValue* source = doc.find("source")) r.source = source->text;
    const JsonValue* ops = doc.find("operations");
    if (!ops || ops->type != JsonValue::Type::Array)
        throw InvalidArgument(name + ": no \"operations\" array");
    for (std::size_t k = 0; k < ops->items.size(); ++k) {
        const JsonValue& o = ops->items[k];
        const std::string where = name + ": operation " + std::to_string(k);
        const JsonValue* op_name = o.find("operation");
        const JsonValue* params = o.find("parameters");
        if (!op_name || op_name->type != JsonValue::Type::String || !params ||
            params->type != JsonValue::Type::Object)
            throw InvalidArgument(where + ": needs \"operation\" and \"parameters\"");
        try {
            const OperationDef& def = operation_def(op_name->text);
            std::vector<std::string> args;
            for (const auto& [key, value] : params->members) {
                if (value.type == JsonValue::Type::Null) continue;  // unset
                for (std::string& t : option_tokens(def.params[def.index(key)], value, where))
                    args.push_back(std::move(t));
            }
            r.operations.push_back(parse_operation(def.name, args));
        } catch (const InvalidArgument& e) {
            const std::string what = e.what();
            if (what.rfind(where, 0) == 0) throw;
            throw InvalidArgument(where + " (" + op_name->text + "): " + what);
        }
    }
    return r;
}

ReplayStep run_recipe_step(const Operation& op, const HalfedgeMesh& mesh) {
    NullProgress progress;
    ReplayStep out;
    out.result = run_operation(op, mesh, progress);
    // As the viewer: a run that stopped before its first good step, or moved nothing, adds
    // no entry; one that stopped later keeps its good steps.
    out.changed = false;
    if (!out.result.changed) return out;
    for (const OperationStep& step : out.result.steps) {
        const HalfedgeMesh& m = step.mesh;
        if (m.revision() == mesh.revision()) continue;
        if (m.topology_revision() != mesh.topology_revision() ||
            m.vertices_size() != mesh.vertices_size() || m.positions() != mesh.positions())
            out.changed = true;
    }
    return out;
}

HalfedgeMesh replay(const Recipe& recipe, HalfedgeMesh mesh) {
    for (const Operation& op : recipe.operations) {
        ReplayStep step = run_recipe_step(op, mesh);
        if (step.changed) mesh = std::move(step.result.steps.back().mesh);
    }
    return mesh;
}

std::string first_difference(const HalfedgeMesh& a, const HalfedgeMesh& b) {
    if (a.vertices_size() != b.vertices_size() || a.edges_size() != b.edges_size() ||
        a.faces_size() != b.faces_size())
        return "sizes differ: " + std::to_string(a.vertices_size()) + "/" +
               std::to_string(a.edges_size()) + "/" + std::to_string(a.faces_size()) +
               " vertices/edges/faces against " + std::to_string(b.vertices_size()) + "/" +
               std::to_string(b.edges_size()) + "/" + std::to_string(b.faces_size());
    const auto first = [](const auto& x, const auto& y) -> std::size_t {
        for (std::size_t i = 0; i < x.size(); ++i)
            if (std::memcmp(static_cast<const void*>(&x[i]), static_cast<const void*>(&y[i]),
                            sizeof(x[i])) != 0)
                return i;
        return std::size_t(-1);
    };
    const auto check = [&](const auto& x, const auto& y, const char* what) -> std::string {
        const std::size_t i = first(x, y);
        return i == std::size_t(-1) ? ""
                                    : std::string(what) + " differ at index " + std::to_string(i);
    };
    for (const std::string& d :
         {check(a.halfedge_to_array(), b.halfedge_to_array(), "halfedge targets"),
          check(a.halfedge_next_array(), b.halfedge_next_array(), "halfedge successors"),
          check(a.halfedge_face_array(), b.halfedge_face_array(), "halfedge faces"),
          check(a.vertex_halfedge_array(), b.vertex_halfedge_array(), "vertex halfedges"),
          check(a.face_halfedge_array(), b.face_halfedge_array(), "face halfedges"),
          check(a.positions(), b.positions(), "positions")})
        if (!d.empty()) return d;
    if (a.has_garbage() != b.has_garbage()) return "one has deleted elements";
    return "";
}

}  // namespace trilab
