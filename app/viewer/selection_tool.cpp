#include "app/viewer/selection_tool.h"

#include <imgui.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "app/viewer/viewer_tuning.h"

namespace trilab::viewer {
using namespace tuning;

namespace {

/// Bit for bit equal (NaN, "no value", equals itself here).
bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
    return a.size() == b.size() &&
           (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}

Eigen::Vector2f eigen(const glm::vec2& p) {
    return {p.x, p.y};
}

}  // namespace

namespace {

/// The vertices as the view shows them now (screen_selection.h).
ProjectedVertices project_shown(const Session& session, const Camera& camera, const Rect& view,
                                bool through) {
    ScreenView screen;
    const glm::mat4 m = camera.projection() * camera.view();
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) screen.view_projection(r, c) = double(m[c][r]);
    screen.width = std::max(view.w, 1.0f);
    screen.height = std::max(view.h, 1.0f);
    // The surface as it is on the screen: the shown mesh where it has the document's vertices
    // (a preview, a morph frame), else the document.
    const HalfedgeMesh& mesh = session.mesh();
    const Shown& shown = session.shown();
    if (shown.mesh && shown.kind != Shown::Kind::Level &&
        shown.mesh->vertices_size() == mesh.vertices_size()) {
        if (shown.positions.size() == mesh.vertices_size())
            return project_vertices(*shown.mesh, shown.positions, screen, through);
        return project_vertices(*shown.mesh, shown.mesh->positions(), screen, through);
    }
    return project_vertices(mesh, mesh.positions(), screen, through);
}

}  // namespace

void SelectionTool::describe(SidebarContext& context) const {
    const HalfedgeMesh& mesh = context_.session.mesh();
    context.n_vertices = mesh.n_vertices();
    context.has_selection = mesh.has_vertex_property(kSelectionProperty);
    context.selected = context.has_selection ? context_.session.selections().count() : 0;
    context.has_pick = !context_.session.picking().picks().picks.empty();
    const std::vector<double>& values = context_.session.coloring().values();
    context.has_values = !values.empty();
    context.values_min = context_.view.colors.range.min;
    context.values_max = context_.view.colors.range.max;
}

void SelectionTool::update() {
    size_for_model();
    // The threshold works on what the colouring shows: its values, per vertex of the document.
    const std::vector<double>& values = context_.view.colors.values;
    const bool fits = values.size() == context_.session.mesh().vertices_size() &&
                      context_.view.colors.kind != ColorMapKind::Categorical;
    if (!fits && !context_.session.coloring().values().empty())
        context_.session.execute(SetColoringValues{{}});
    else if (fits && !same_bits(context_.session.coloring().values(), values))
        context_.session.execute(SetColoringValues{values});
}

void SelectionTool::size_for_model() {
    // Lengths in model units follow the model (issue 38, item 14): the geodesic ball's radius
    // 10 % and the feather width 4 % of the fitted sphere's radius (5 % and 2 % of about the
    // bounding box's diagonal), each while it is still the value set for the last model.
    const float r = context_.view.fit_radius;
    if (r == sized_for_ || !(r > 0)) return;
    sized_for_ = r;
    if (panel_.geodesic_radius == auto_radius_) panel_.geodesic_radius = auto_radius_ = 0.1f * r;
    if (panel_.feather == auto_feather_) panel_.feather = auto_feather_ = 0.04f * r;
}

void SelectionTool::begin_stroke(bool add, bool lasso, const glm::vec2& pos) {
    stroke_ = SelectionStroke{};
    stroke_.active = true;
    stroke_.add = add;
    stroke_.lasso = lasso;
    // Fixed for the stroke: the projection below decides which vertices the lasso may take.
    stroke_.through = lasso && panel_.lasso_through;
    const bool through = stroke_.through;
    context_.view.camera.set_viewport(std::max(context_.view_rect.w, 1.0f),
                                      std::max(context_.view_rect.h, 1.0f));
    stroke_.projected =
        project_shown(context_.session, context_.view.camera, context_.view_rect, through);
    const HalfedgeMesh& mesh = context_.session.mesh();
    // No selection yet: the brush starts from nothing when it adds, from everything (what an
    // operation acts on without one) when it removes.
    stroke_.before = context_.session.selections().get().value_or(add ? empty_selection(mesh)
                                                                      : full_selection(mesh));
    stroke_.weights = stroke_.before;
    stroke_.last = pos;
    stroke_.version = ++stroke_counter_;
    if (lasso)
        stroke_.lasso_points.push_back(eigen(pos));
    else
        continue_stroke(pos);
    context_.keep_drawing(kFramesAfterInput);
}

void SelectionTool::continue_stroke(const glm::vec2& pos) {
    if (stroke_.lasso) {
        if (stroke_.lasso_points.empty() ||
            (eigen(pos) - stroke_.lasso_points.back()).norm() >= 2.0f)
            stroke_.lasso_points.push_back(eigen(pos));
    } else {
        const std::size_t changed = paint_brush(stroke_.projected, eigen(stroke_.last), eigen(pos),
                                                panel_.brush_radius, stroke_.add, stroke_.weights);
        ++stroke_.dabs;
        stroke_.changed += changed;
        if (changed > 0) stroke_.version = ++stroke_counter_;
    }
    stroke_.last = pos;
    context_.keep_drawing(kFramesAfterInput);
}

void SelectionTool::end_stroke() {
    if (!stroke_.active) return;
    SelectionStroke stroke = std::move(stroke_);
    stroke_ = SelectionStroke{};
    const char* how = stroke.add ? "add" : "remove";
    char parameters[96];
    if (stroke.lasso && stroke.lasso_points.size() < 3) {
        // A click, or a drag too short to enclose anything: no lasso, and no history entry.
    } else if (stroke.lasso) {
        Selection inside = lasso_selection(stroke.projected, stroke.lasso_points);
        Selection result = stroke.before;
        for (std::size_t i = 0; i < result.size() && i < inside.size(); ++i)
            result[i] = stroke.add ? std::max(result[i], inside[i]) : result[i] * (1 - inside[i]);
        std::snprintf(parameters, sizeof parameters, "%zu points%s (%s)",
                      stroke.lasso_points.size(), stroke.through ? ", through" : "", how);
        if (result != stroke.before || !context_.session.selections().get())
            context_.commands.push_back(SetSelection{std::move(result), "Lasso", parameters});
    } else {
        std::snprintf(parameters, sizeof parameters, "radius %.0f px, %zu dabs (%s)",
                      double(panel_.brush_radius), stroke.dabs, how);
        if (stroke.weights != stroke.before || !context_.session.selections().get())
            context_.commands.push_back(
                SetSelection{std::move(stroke.weights), "Brush", parameters});
    }
    overlay_key_.clear();
    context_.keep_drawing(kFramesAfterInput);
}

bool SelectionTool::mouse(const ViewMouse& mouse) {
    const glm::vec2& pos = mouse.pos;
    const bool in_view = mouse.in_view;
    const ImGuiIO& io = ImGui::GetIO();
    const SelectionPanelState& s = panel_;
    const bool lasso = s.tool == SelectionPanelState::Tool::Lasso;
    const bool modifier = (io.KeyCtrl || io.KeyAlt) && !io.KeyShift;
    // The brush's circle (or the lasso) where the tool would draw.
    ImDrawList* draw = ImGui::GetForegroundDrawList();
    const ImVec2 at(pos.x + context_.view_rect.x, pos.y + context_.view_rect.y);
    const bool add = stroke_.active ? stroke_.add : !io.KeyAlt;
    const ImU32 color = add ? IM_COL32(255, 200, 80, 220) : IM_COL32(120, 190, 255, 220);
    if (s.open && (modifier || stroke_.active) && in_view && !lasso)
        draw->AddCircle(at, s.brush_radius, color, 48, 1.5f);
    if (stroke_.active && stroke_.lasso && stroke_.lasso_points.size() > 1) {
        std::vector<ImVec2> points;
        for (const Eigen::Vector2f& p : stroke_.lasso_points)
            points.emplace_back(p.x() + context_.view_rect.x, p.y() + context_.view_rect.y);
        draw->AddPolyline(points.data(), int(points.size()), color, ImDrawFlags_Closed, 1.5f);
    }
    if (scripted_) return true;  // --brush draws; the mouse waits
    if (stroke_.active) {
        if (ImGui::IsMouseDown(ImGuiMouseButton_Left)) {
            if (pos != stroke_.last) continue_stroke(pos);
        } else {
            end_stroke();
        }
        return true;
    }
    // A preview computing does not stop the brush (the selection's entry computes it again).
    if (!s.open || !modifier || (context_.session.busy() && !context_.session.previews().running()))
        return false;
    if (ImGui::IsMouseClicked(ImGuiMouseButton_Left) && mouse.drag_in_view && in_view) {
        begin_stroke(!io.KeyAlt, lasso, pos);
        return true;
    }
    return false;
}

void SelectionTool::before_surface(RenderStyle& style) {
    style.selection_outline_width *= context_.ui_scale;
    if (!surface_) return;
    const Shown& shown = context_.session.shown();
    std::string key;
    if (stroke_.active && !stroke_.lasso) {
        key = "stroke " + std::to_string(stroke_.version);
    } else if (shown.mesh && shown.kind != Shown::Kind::Level &&
               shown.mesh->has_vertex_property(kSelectionProperty)) {
        key = std::to_string(shown.mesh->topology_revision()) + " " +
              std::to_string(shown.mesh->attribute_revision()) + " " +
              std::to_string(std::uintptr_t(shown.mesh));
    }
    if (key.empty()) {
        if (surface_->has_vertex_selection()) surface_->clear_vertex_selection();
        overlay_key_.clear();
        return;
    }
    if (key == overlay_key_ && surface_->has_vertex_selection()) return;
    try {
        if (stroke_.active) {
            if (stroke_.weights.size() != surface_->n_vertices()) return;
            surface_->set_vertex_selection(stroke_.weights);
        } else {
            const std::optional<Selection> weights = stored_selection(*shown.mesh);
            if (!weights || weights->size() != surface_->n_vertices()) return;
            surface_->set_vertex_selection(*weights);
        }
        overlay_key_ = key;
    } catch (const std::exception& e) {
        overlay_key_ = key;  // do not try again every frame
        context_.session.notify_error(std::string("selection overlay: ") + e.what());
    }
}

}  // namespace trilab::viewer
