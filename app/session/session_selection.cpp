// The document's selection (issue 26): every way to select from the viewer ends here as ONE
// history entry whose mesh is the current one with "v:selection" set (or removed), so undo,
// redo, the morph, session files and saving the mesh all keep it as they keep any vertex
// property. See session.h.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

#include "app/ops/region_spec.h"
#include "app/session/session.h"
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

std::optional<Selection> Session::selection() const {
    return stored_selection(document_.mesh());
}

std::size_t Session::selected_count() const {
    const std::optional<Selection> s = selection();
    return s ? count_selected(*s) : 0;
}

Selection Session::combine_selection(Selection fresh, SelectionMode mode) const {
    if (mode == SelectionMode::Replace) return fresh;
    const std::optional<Selection> old = selection();
    if (!old || old->size() != fresh.size()) {
        // No selection: adding gives the new one; removing takes it from the whole mesh (what
        // an operation acts on without a selection).
        if (mode == SelectionMode::Add) return fresh;
        Selection out = full_selection(document_.mesh());
        for (std::size_t i = 0; i < out.size() && i < fresh.size(); ++i) out[i] *= 1.0f - fresh[i];
        return out;
    }
    for (std::size_t i = 0; i < fresh.size(); ++i)
        fresh[i] = mode == SelectionMode::Add ? std::max((*old)[i], fresh[i])
                                              : (*old)[i] * (1.0f - fresh[i]);
    return fresh;
}

bool Session::set_selection(const Selection& weights, const std::string& label,
                            const std::string& parameters) {
    if (jobs_.busy() && !is_preview_job()) {
        busy_error();
        return false;
    }
    HalfedgeMesh mesh = document_.mesh();  // shares its arrays: only the property is new
    try {
        store_selection(mesh, weights);
    } catch (const Error& e) {
        notify_error(std::string("selection: ") + e.what());
        return false;
    }
    // A preview follows the selection: computed again on the new state.
    const std::optional<Operation> previewed = preview_.requested;
    clear_preview();
    log_history_messages(
        document_.history.push(label, parameters, 0.0, {std::move(mesh)}, {MorphCorrespondence{}}));
    on_state_changed(false);
    log_.info(label + (parameters.empty() ? "" : " " + parameters) + ": " +
              std::to_string(count_selected(weights)) + " of " +
              std::to_string(document_.mesh().n_vertices()) + " vertices selected");
    if (previewed) request_preview(*previewed);
    return true;
}

bool Session::clear_selection() {
    if (!document_.mesh().has_vertex_property(kSelectionProperty)) return false;
    if (jobs_.busy() && !is_preview_job()) {
        busy_error();
        return false;
    }
    HalfedgeMesh mesh = document_.mesh();
    mesh.remove_vertex_property(kSelectionProperty);
    const std::optional<Operation> previewed = preview_.requested;
    clear_preview();
    log_history_messages(document_.history.push("Clear selection", "", 0.0, {std::move(mesh)},
                                                {MorphCorrespondence{}}));
    on_state_changed(false);
    if (previewed) request_preview(*previewed);
    return true;
}

bool Session::execute_selection(const Command& command) {
    const HalfedgeMesh& mesh = document_.mesh();
    try {
        if (auto* set = std::get_if<SetSelection>(&command)) {
            set_selection(set->weights, set->label, set->parameters);
        } else if (auto* spec = std::get_if<SelectSpec>(&command)) {
            const Selection s = make_region(mesh, parse_region_spec(spec->spec));
            set_selection(combine_selection(s, spec->mode), "Select",
                          with_mode(spec->spec, spec->mode));
        } else if (auto* at = std::get_if<SelectAtPick>(&command)) {
            if (picks_.picks.empty() || picks_.mesh.topology_revision() != mesh.topology_revision())
                throw InvalidArgument("pick a vertex first (click the model)");
            const Vertex v = picks_.picks.front().vertex;
            if (at->component) {
                set_selection(combine_selection(component_selection(mesh, v), at->mode), "Select",
                              with_mode("component:" + std::to_string(v.idx()), at->mode));
            } else {
                set_selection(
                    combine_selection(geodesic_selection(mesh, v, at->radius), at->mode), "Select",
                    with_mode("geodesic:" + std::to_string(v.idx()) + "," + number(at->radius),
                              at->mode));
            }
        } else if (auto* t = std::get_if<SelectThreshold>(&command)) {
            if (coloring_values_.size() != mesh.vertices_size())
                throw InvalidArgument(
                    "threshold: the current colouring has no values (choose one such as mean "
                    "curvature)");
            const Selection s =
                threshold_selection(mesh, coloring_values_, t->value,
                                    t->above ? ThresholdSide::Above : ThresholdSide::Below);
            set_selection(
                combine_selection(s, t->mode), "Select",
                with_mode(std::string("threshold ") + (t->above ? "> " : "< ") + number(t->value),
                          t->mode));
        } else if (auto* edit = std::get_if<EditSelection>(&command)) {
            using Kind = EditSelection::Kind;
            if (edit->kind == Kind::Clear) {
                clear_selection();
                return true;
            }
            std::optional<Selection> s = selection();
            if (!s) {
                if (edit->kind != Kind::Invert)
                    throw InvalidArgument("there is no selection to edit (select first)");
                s = empty_selection(mesh);  // nothing selected, inverted: everything
            }
            std::string label, parameters;
            switch (edit->kind) {
                case Kind::Grow:
                    grow_selection(mesh, *s, edit->rings);
                    label = "Grow selection", parameters = std::to_string(edit->rings) + " rings";
                    break;
                case Kind::Shrink:
                    shrink_selection(mesh, *s, edit->rings);
                    label = "Shrink selection", parameters = std::to_string(edit->rings) + " rings";
                    break;
                case Kind::Invert:
                    invert_selection(mesh, *s);
                    label = "Invert selection";
                    break;
                case Kind::Feather:
                    feather_selection(mesh, *s, edit->width);
                    label = "Feather selection", parameters = number(edit->width);
                    break;
                case Kind::Clear:
                    break;
            }
            set_selection(*s, label, parameters);
        } else {
            return false;
        }
    } catch (const Error& e) {
        notify_error(std::string("selection: ") + e.what());
    }
    return true;
}

}  // namespace trilab::viewer
