// Recipes (app/history/recipe.h).
#include "app/history/recipe.h"

#include <cmath>
#include <cstring>
#include <optional>

#include "app/history/json_reader.h"
#include "app/ops/region_spec.h"
#include "core/errors.h"
#include "core/io/file_util.h"
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

namespace {

/// Whether entry `i` loads a mesh: entry 0, or an entry without an operation whose first step
/// brings positions of its own (push_loaded's FromEarlier correspondence).
bool is_load(const History& history, std::size_t i) {
    if (i == 0) return true;
    const History::EntryInfo e = history.info(i);
    return !e.operation.def && !e.steps.empty() &&
           e.steps.front().kind == MorphCorrespondence::Kind::FromEarlier;
}

/// The labels the viewer gives its selection entries (app/session/session_selection.cpp,
/// app/viewer/selection_tool.cpp).
bool is_selection_label(const std::string& label) {
    for (const char* l : {"Select", "Brush", "Lasso", "Grow selection", "Shrink selection",
                          "Invert selection", "Feather selection", "Clear selection"})
        if (label == l) return true;
    return false;
}

std::string entry_text(const History::EntryInfo& e) {
    return e.label + (e.parameters.empty() ? "" : " " + e.parameters);
}

/// The selection step of entry `i`, or nullopt when the entry is not a selection (it moves,
/// changes the connectivity, or keeps the selection and is not labelled as one).
std::optional<RecipeStep> selection_step(const History& history, std::size_t i) {
    const History::EntryInfo e = history.info(i);
    if (e.operation.def || e.steps.size() != 1 ||
        e.steps.front().kind != MorphCorrespondence::Kind::SameVertices)
        return std::nullopt;
    const HalfedgeMesh before = history.mesh(i - 1, history.info(i - 1).steps.size() - 1);
    const HalfedgeMesh after = history.mesh(i, 0);
    if (!first_difference(before, after).empty()) return std::nullopt;
    const std::optional<Selection> was = stored_selection(before);
    const std::optional<Selection> now = stored_selection(after);
    if (was == now && !is_selection_label(e.label)) return std::nullopt;
    RecipeStep step;
    step.kind = RecipeStep::Kind::SetSelection;
    step.text = entry_text(e);
    if (!now) {
        step.from = RecipeStep::From::Clear;
        return step;
    }
    // "Select SPEC" (a replacing selection by a SPEC) replays as its SPEC where that gives
    // exactly the stored weights; a file may be gone by then, so file: SPECs never do.
    if (e.label == "Select" && e.parameters.rfind("file:", 0) != 0) {
        try {
            const RegionSpec spec = parse_region_spec(e.parameters);
            if (make_region(before, spec) == *now) {
                step.from = RecipeStep::From::Spec;
                step.region = e.parameters;
                return step;
            }
        } catch (const Error&) {
            // not a SPEC (a threshold of the viewer's colouring, a combined selection)
        }
    }
    step.from = RecipeStep::From::Weights;
    step.weights = *now;
    return step;
}

}  // namespace

std::size_t Recipe::operations() const {
    std::size_t n = 0;
    for (const RecipeStep& s : steps) n += s.kind == RecipeStep::Kind::RunOperation ? 1 : 0;
    return n;
}

std::size_t Recipe::selections() const {
    return steps.size() - operations();
}

Recipe recipe_of(const History& history) {
    if (history.size() == 0) throw InvalidArgument("recipe: the history is empty");
    const std::size_t current = history.current();
    std::size_t load = current;
    while (!is_load(history, load)) --load;
    Recipe r;
    const History::EntryInfo source = history.info(load);
    r.source = entry_text(source);
    if (source.operation.def)
        throw InvalidArgument("recipe: entry 0 \"" + source.label +
                              "\" is an operation; the history does not start with a load");
    for (std::size_t i = load + 1; i <= current; ++i) {
        const History::EntryInfo e = history.info(i);
        if (e.operation.def) {
            RecipeStep step(e.operation);
            step.text = e.operation.text();
            r.steps.push_back(std::move(step));
        } else if (std::optional<RecipeStep> select = selection_step(history, i)) {
            r.steps.push_back(std::move(*select));
        } else {
            throw InvalidArgument("recipe: entry " + std::to_string(i) + " \"" + entry_text(e) +
                                  "\" is a state the viewer made (neither an operation nor a "
                                  "selection); a recipe cannot replay it");
        }
    }
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

namespace {

std::string step_json(const RecipeStep& step) {
    if (step.kind == RecipeStep::Kind::RunOperation) {
        const Operation& op = step.operation;
        std::string s = "{\"operation\": " + quote(op.name()) + ", \"text\": " + quote(op.text()) +
                        ",\n     \"parameters\": " + typed_parameters_json(op);
        if (!step.region.empty()) s += ", \"region\": " + quote(step.region);
        return s + "}";
    }
    switch (step.from) {
        case RecipeStep::From::Spec:
            return "{\"selection\": \"spec\", \"spec\": " + quote(step.region) +
                   ", \"text\": " + quote(step.text) + "}";
        case RecipeStep::From::Clear:
            return "{\"selection\": \"clear\", \"text\": " + quote(step.text) + "}";
        case RecipeStep::From::Weights:
            break;
    }
    std::string indices, weights;
    for (std::size_t i = 0; i < step.weights.size(); ++i) {
        if (!(step.weights[i] > 0)) continue;
        if (!indices.empty()) indices += ", ", weights += ", ";
        append_number(indices, i);
        append_number(weights, step.weights[i]);
    }
    return "{\"selection\": \"weights\", \"text\": " + quote(step.text) +
           ", \"vertices\": " + std::to_string(step.weights.size()) + ",\n     \"indices\": [" +
           indices + "],\n     \"weights\": [" + weights + "]}";
}

}  // namespace

std::string recipe_json(const Recipe& recipe) {
    std::string s = "{\n  \"format\": \"trilab-recipe\",\n  \"version\": 2,\n  \"source\": " +
                    quote(recipe.source) + ",\n  \"operations\": [";
    for (std::size_t k = 0; k < recipe.steps.size(); ++k)
        s += std::string(k ? "," : "") + "\n    " + step_json(recipe.steps[k]);
    return s + (recipe.steps.empty() ? "]\n}\n" : "\n  ]\n}\n");
}

namespace {

/// A whole number in [0, limit) at `v`, or InvalidArgument naming `where`.
std::size_t index_at(const JsonValue& v, double limit, const std::string& where) {
    if (v.type != JsonValue::Type::Number || v.number < 0 || v.number >= limit ||
        v.number != std::floor(v.number))
        throw InvalidArgument(where + ": expected a whole number below " + format_number(limit));
    return std::size_t(v.number);
}

/// The weights of a {"selection": "weights", ...} step.
Selection parse_weights(const JsonValue& o, const std::string& where) {
    const JsonValue* vertices = o.find("vertices");
    const JsonValue* indices = o.find("indices");
    const JsonValue* weights = o.find("weights");
    if (!vertices || !indices || !weights || indices->type != JsonValue::Type::Array ||
        weights->type != JsonValue::Type::Array || indices->items.size() != weights->items.size())
        throw InvalidArgument(where +
                              ": a selection by weights needs \"vertices\", and "
                              "\"indices\" and \"weights\" arrays of the same length");
    const std::size_t n = index_at(*vertices, 4294967295.0, where + ": \"vertices\"");
    Selection s(n, 0.0f);
    std::size_t next = 0;
    for (std::size_t k = 0; k < indices->items.size(); ++k) {
        const std::string at = where + ": weight " + std::to_string(k);
        const std::size_t i = index_at(indices->items[k], double(n), at + ": index");
        if (i < next) throw InvalidArgument(at + ": indices must increase");
        next = i + 1;
        const JsonValue& w = weights->items[k];
        if (w.type != JsonValue::Type::Number || !(w.number > 0) || w.number > 1)
            throw InvalidArgument(at + ": expected a weight in (0, 1]");
        s[i] = float(w.number);
    }
    return s;
}

RecipeStep parse_selection_step(const JsonValue& o, const std::string& where) {
    const JsonValue* kind = o.find("selection");
    RecipeStep step;
    step.kind = RecipeStep::Kind::SetSelection;
    if (const JsonValue* text = o.find("text")) step.text = text->text;
    if (kind->text == "spec") {
        const JsonValue* spec = o.find("spec");
        if (!spec || spec->type != JsonValue::Type::String)
            throw InvalidArgument(where + ": a selection by SPEC needs \"spec\"");
        try {
            parse_region_spec(spec->text);
        } catch (const InvalidArgument& e) {
            throw InvalidArgument(where + ": " + e.what());
        }
        step.from = RecipeStep::From::Spec;
        step.region = spec->text;
    } else if (kind->text == "weights") {
        step.from = RecipeStep::From::Weights;
        step.weights = parse_weights(o, where);
    } else if (kind->text == "clear") {
        step.from = RecipeStep::From::Clear;
    } else {
        throw InvalidArgument(where + ": unknown selection \"" + kind->text +
                              "\" (expected \"spec\", \"weights\" or \"clear\")");
    }
    return step;
}

RecipeStep parse_operation_step(const JsonValue& o, const std::string& where) {
    const JsonValue* op_name = o.find("operation");
    const JsonValue* params = o.find("parameters");
    if (!op_name || op_name->type != JsonValue::Type::String || !params ||
        params->type != JsonValue::Type::Object)
        throw InvalidArgument(where +
                              ": needs \"operation\" and \"parameters\" (or \"selection\")");
    RecipeStep step;
    try {
        const OperationDef& def = operation_def(op_name->text);
        std::vector<std::string> args;
        for (const auto& [key, value] : params->members) {
            if (value.type == JsonValue::Type::Null) continue;  // unset
            for (std::string& t : option_tokens(def.params[def.index(key)], value, where))
                args.push_back(std::move(t));
        }
        step.operation = parse_operation(def.name, args);
        step.text = step.operation.text();
        if (const JsonValue* region = o.find("region")) {
            if (region->type != JsonValue::Type::String)
                throw InvalidArgument("\"region\": expected a SPEC string");
            parse_region_spec(region->text);
            if (!def.takes_region)
                throw InvalidArgument("--region: " + def.name +
                                      " does not work on a region yet (it acts on the whole "
                                      "mesh)");
            step.region = region->text;
        }
    } catch (const InvalidArgument& e) {
        const std::string what = e.what();
        if (what.rfind(where, 0) == 0) throw;
        throw InvalidArgument(where + " (" + op_name->text + "): " + what);
    }
    return step;
}

}  // namespace

Recipe parse_recipe(const std::string& json, const std::string& name) {
    const JsonValue doc = parse_json(json, name);
    const JsonValue* format = doc.find("format");
    if (doc.type != JsonValue::Type::Object || !format || format->text != "trilab-recipe")
        throw InvalidArgument(name + ": not a trilab recipe (no \"format\": \"trilab-recipe\")");
    const JsonValue* version = doc.find("version");
    if (!version || version->type != JsonValue::Type::Number ||
        (version->number != 1 && version->number != 2))
        throw InvalidArgument(name + ": recipe version is not 1 or 2");
    Recipe r;
    if (const JsonValue* source = doc.find("source")) r.source = source->text;
    const JsonValue* ops = doc.find("operations");
    if (!ops || ops->type != JsonValue::Type::Array)
        throw InvalidArgument(name + ": no \"operations\" array");
    for (std::size_t k = 0; k < ops->items.size(); ++k) {
        const JsonValue& o = ops->items[k];
        const std::string where = name + ": operation " + std::to_string(k);
        if (o.type != JsonValue::Type::Object)
            throw InvalidArgument(where + ": expected an object");
        const JsonValue* selection = o.find("selection");
        if (selection && version->number == 1)
            throw InvalidArgument(where + ": a selection step needs recipe version 2");
        if (selection && selection->type != JsonValue::Type::String)
            throw InvalidArgument(where +
                                  ": \"selection\": expected \"spec\", \"weights\" or "
                                  "\"clear\"");
        r.steps.push_back(selection ? parse_selection_step(o, where)
                                    : parse_operation_step(o, where));
    }
    return r;
}

ReplayStep run_recipe_step(const Operation& op, const HalfedgeMesh& mesh, const Selection* region) {
    NullProgress progress;
    ReplayStep out;
    RunSettings settings;
    settings.region = region;
    out.result = run_operation(op, mesh, progress, settings);
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

std::optional<Selection> recipe_region(const RecipeStep& step, const HalfedgeMesh& mesh) {
    if (!step.region.empty()) return make_region(mesh, parse_region_spec(step.region));
    if (!step.operation.def || !step.operation.def->takes_region) return std::nullopt;
    std::optional<Selection> s = stored_selection(mesh);
    if (s && selects_everything(mesh, *s)) return std::nullopt;
    return s;
}

void apply_selection_step(const RecipeStep& step, HalfedgeMesh& mesh, const std::string& where) {
    switch (step.from) {
        case RecipeStep::From::Clear:
            if (mesh.has_vertex_property(kSelectionProperty))
                mesh.remove_vertex_property(kSelectionProperty);
            return;
        case RecipeStep::From::Spec:
            store_selection(mesh, make_region(mesh, parse_region_spec(step.region)));
            return;
        case RecipeStep::From::Weights:
            if (step.weights.size() != mesh.vertices_size())
                throw InvalidArgument(where + ": the selection has " +
                                      std::to_string(step.weights.size()) +
                                      " vertex weights, the mesh " +
                                      std::to_string(mesh.vertices_size()) + " vertices");
            store_selection(mesh, step.weights);
            return;
    }
}

HalfedgeMesh replay(const Recipe& recipe, HalfedgeMesh mesh) {
    for (std::size_t k = 0; k < recipe.steps.size(); ++k) {
        const RecipeStep& step = recipe.steps[k];
        const std::string where = "step " + std::to_string(k) + " (" + step.text + ")";
        try {
            if (step.kind == RecipeStep::Kind::SetSelection) {
                apply_selection_step(step, mesh, where);
                continue;
            }
            const std::optional<Selection> region = recipe_region(step, mesh);
            ReplayStep run = run_recipe_step(step.operation, mesh, region ? &*region : nullptr);
            if (run.changed) mesh = std::move(run.result.steps.back().mesh);
        } catch (const InvalidArgument& e) {
            const std::string what = e.what();
            if (what.rfind(where, 0) == 0) throw;
            throw InvalidArgument(where + ": " + what);
        }
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
