// The document's selection; see session_selection.h.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

#include "app/ops/region_spec.h"
#include "app/session/session_selection.h"
#include "core/algorithms/selection.h"
#include "core/errors.h"

namespace trilab::viewer {
namespace {

const char* mode_word(SelectionMode mode) {
    switch (mode) {
        case SelectionMode::Add:
            return "add";
        case SelectionMode::Remove:
            return "remove";
        case SelectionMode::Replace:
            break;
    }
    return "";
}

std::string with_mode(std::string parameters, SelectionMode mode) {
    const std::string word = mode_word(mode);
    if (word.empty()) return parameters;
    return parameters.empty() ? word : parameters + " (" + word + ")";
}

std::string number(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", x);
    return buf;
}

}  // namespace

std::optional<Selection> SessionSelection::get() const {
    return stored_selection(core_.mesh());
}

std::size_t SessionSelection::count() const {
    const std::optional<Selection> s = get();
    return s ? count_selected(*s) : 0;
}

Selection SessionSelection::combine(Selection fresh, SelectionMode mode) const {
    if (mode == SelectionMode::Replace) return fresh;
    const std::optional<Selection> old = get();
    if (!old || old->size() != fresh.size()) {
        // No selection: adding gives the new one; removing takes it from the whole mesh (what
        // an operation acts on without a selection).
        if (mode == SelectionMode::Add) return fresh;
        Selection out = full_selection(core_.mesh());
        for (std::size_t i = 0; i < out.size() && i < fresh.size(); ++i) out[i] *= 1.0f - fresh[i];
        return out;
    }
    for (std::size_t i = 0; i < fresh.size(); ++i)
        fresh[i] = mode == SelectionMode::Add ? std::max((*old)[i], fresh[i])
                                              : (*old)[i] * (1.0f - fresh[i]);
    return fresh;
}

void SessionSelection::push(HalfedgeMesh mesh, const std::string& label,
                            const std::string& parameters) {
    // A preview follows the selection: computed again on the new state.
    const std::optional<Operation> previewed = previews_.requested();
    previews_.clear();
    core_.push_entry(label, parameters, 0.0, {std::move(mesh)}, {MorphCorrespondence{}});
    if (previewed) previews_.request(*previewed);
}

bool SessionSelection::set(const Selection& weights, const std::string& label,
                           const std::string& parameters) {
    if (core_.jobs.busy() && !core_.preview_job()) {
        core_.busy_error();
        return false;
    }
    HalfedgeMesh mesh = core_.mesh();  // shares its arrays: only the property is new
    try {
        store_selection(mesh, weights);
    } catch (const Error& e) {
        core_.notify_error(std::string("selection: ") + e.what());
        return false;
    }
    const std::size_t n = mesh.n_vertices();
    push(std::move(mesh), label, parameters);
    core_.log.info(label + (parameters.empty() ? "" : " " + parameters) + ": " +
                   std::to_string(count_selected(weights)) + " of " + std::to_string(n) +
                   " vertices selected");
    return true;
}

bool SessionSelection::clear() {
    if (!core_.mesh().has_vertex_property(kSelectionProperty)) return false;
    if (core_.jobs.busy() && !core_.preview_job()) {
        core_.busy_error();
        return false;
    }
    HalfedgeMesh mesh = core_.mesh();
    mesh.remove_vertex_property(kSelectionProperty);
    push(std::move(mesh), "Clear selection", "");
    return true;
}

void SessionSelection::edit(const EditSelection& edit) {
    using Kind = EditSelection::Kind;
    if (edit.kind == Kind::Clear) {
        clear();
        return;
    }
    const HalfedgeMesh& mesh = core_.mesh();
    std::optional<Selection> s = get();
    if (!s) {
        if (edit.kind != Kind::Invert)
            throw InvalidArgument("there is no selection to edit (select first)");
        s = empty_selection(mesh);  // nothing selected, inverted: everything
    }
    std::string label, parameters;
    switch (edit.kind) {
        case Kind::Grow:
            grow_selection(mesh, *s, edit.rings);
            label = "Grow selection", parameters = std::to_string(edit.rings) + " rings";
            break;
        case Kind::Shrink:
            shrink_selection(mesh, *s, edit.rings);
            label = "Shrink selection", parameters = std::to_string(edit.rings) + " rings";
            break;
        case Kind::Invert:
            invert_selection(mesh, *s);
            label = "Invert selection";
            break;
        case Kind::Feather:
            feather_selection(mesh, *s, edit.width);
            label = "Feather selection", parameters = number(edit.width);
            break;
        case Kind::Clear:
            break;
    }
    set(*s, label, parameters);
}

bool SessionSelection::execute(const Command& command) {
    const HalfedgeMesh& mesh = core_.mesh();
    try {
        if (auto* given = std::get_if<SetSelection>(&command)) {
            set(given->weights, given->label, given->parameters);
        } else if (auto* spec = std::get_if<SelectSpec>(&command)) {
            const Selection s = make_region(mesh, parse_region_spec(spec->spec));
            set(combine(s, spec->mode), "Select", with_mode(spec->spec, spec->mode));
        } else if (auto* at = std::get_if<SelectAtPick>(&command)) {
            const PickSet& picks = picking_.picks();
            if (picks.picks.empty() || picks.mesh.topology_revision() != mesh.topology_revision())
                throw InvalidArgument("pick a vertex first (click the model)");
            const Vertex v = picks.picks.front().vertex;
            if (at->component)
                set(combine(component_selection(mesh, v), at->mode), "Select",
                    with_mode("component:" + std::to_string(v.idx()), at->mode));
            else
                set(combine(geodesic_selection(mesh, v, at->radius), at->mode), "Select",
                    with_mode("geodesic:" + std::to_string(v.idx()) + "," + number(at->radius),
                              at->mode));
        } else if (auto* t = std::get_if<SelectThreshold>(&command)) {
            const std::vector<double>& values = coloring_.values();
            if (values.size() != mesh.vertices_size())
                throw InvalidArgument(
                    "threshold: the current colouring has no values (choose one such as mean "
                    "curvature)");
            const Selection s = threshold_selection(
                mesh, values, t->value, t->above ? ThresholdSide::Above : ThresholdSide::Below);
            set(combine(s, t->mode), "Select",
                with_mode(std::string("threshold ") + (t->above ? "> " : "< ") + number(t->value),
                          t->mode));
        } else if (auto* e = std::get_if<EditSelection>(&command)) {
            edit(*e);
        } else {
            return false;
        }
    } catch (const Error& e) {
        core_.notify_error(std::string("selection: ") + e.what());
    }
    return true;
}

}  // namespace trilab::viewer
