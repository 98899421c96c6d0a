// Selections in the window (issue 26): the brush and the lasso in the view, the overlay's
// weights on the GPU, the Selection section's context, and the scripted --select, --brush and
// --lasso.
// The document's side (one history entry per change) is app/session/session_selection.cpp.
#include "app/viewer/viewer.h"

// glad before GLFW: GLFW must not include the system GL header.
#include <glad/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "app/viewer/viewer_tuning.h"
#include "core/algorithms/selection.h"

namespace trilab::viewer {
using namespace tuning;

namespace {

/// The median of `ms` (not empty).
double median(std::vector<double> ms) {
    std::nth_element(ms.begin(), ms.begin() + std::ptrdiff_t(ms.size() / 2), ms.end());
    return ms[ms.size() / 2];
}

/// Bit for bit equal (NaN, "no value", equals itself here).
bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
    return a.size() == b.size() &&
           (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}

Eigen::Vector2f eigen(const glm::vec2& p) {
    return {p.x, p.y};
}

}  // namespace

void Viewer::selection_context(SidebarContext& context) const {
    const HalfedgeMesh& mesh = session_.mesh();
    context.n_vertices = mesh.n_vertices();
    context.has_selection = mesh.has_vertex_property(kSelectionProperty);
    context.selected = context.has_selection ? session_.selected_count() : 0;
    context.has_pick = !session_.picks().picks.empty();
    const std::vector<double>& values = session_.coloring_values();
    context.has_values = !values.empty();
    context.values_min = view_.colors.range.min;
    context.values_max = view_.colors.range.max;
}

void Viewer::update_selection() {
    // The threshold works on what the colouring shows: its values, per vertex of the document.
    const std::vector<double>& values = view_.colors.values;
    const bool fits = values.size() == session_.mesh().vertices_size() &&
                      view_.colors.kind != ColorMapKind::Categorical;
    if (!fits && !session_.coloring_values().empty())
        session_.set_coloring_values({});
    else if (fits && !same_bits(session_.coloring_values(), values))
        session_.set_coloring_values(values);
}

bool Viewer::scripted_selection() {
    if (next_scripted_select_ >= options_.selections.size()) return false;
    commands_.push_back(SelectSpec{options_.selections[next_scripted_select_++]});
    return true;
}

bool Viewer::selection_script_pending() const {
    return next_scripted_select_ < options_.selections.size() ||
           (!options_.brush.empty() && brush_script_.state != 2) ||
           (!options_.lasso.empty() && lasso_script_.state != 3) || stroke_.active;
}

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

void Viewer::begin_stroke(bool add, bool lasso, const glm::vec2& pos) {
    stroke_ = SelectionStroke{};
    stroke_.active = true;
    stroke_.add = add;
    stroke_.lasso = lasso;
    // Fixed for the stroke: the projection below decides which vertices the lasso may take.
    stroke_.through = lasso && panels_.selection.lasso_through;
    const bool through = stroke_.through;
    view_.camera.set_viewport(std::max(view_rect_.w, 1.0f), std::max(view_rect_.h, 1.0f));
    stroke_.projected = project_shown(session_, view_.camera, view_rect_, through);
    const HalfedgeMesh& mesh = session_.mesh();
    // No selection yet: the brush starts from nothing when it adds, from everything (what an
    // operation acts on without one) when it removes.
    stroke_.before =
        session_.selection().value_or(add ? empty_selection(mesh) : full_selection(mesh));
    stroke_.weights = stroke_.before;
    stroke_.last = pos;
    stroke_.version = ++stroke_counter_;
    if (lasso)
        stroke_.lasso_points.push_back(eigen(pos));
    else
        continue_stroke(pos);
    active_frames_ = std::max(active_frames_, kFramesAfterInput);
}

void Viewer::continue_stroke(const glm::vec2& pos) {
    if (stroke_.lasso) {
        if (stroke_.lasso_points.empty() ||
            (eigen(pos) - stroke_.lasso_points.back()).norm() >= 2.0f)
            stroke_.lasso_points.push_back(eigen(pos));
    } else {
        const std::size_t changed =
            paint_brush(stroke_.projected, eigen(stroke_.last), eigen(pos),
                        panels_.selection.brush_radius, stroke_.add, stroke_.weights);
        ++stroke_.dabs;
        stroke_.changed += changed;
        if (changed > 0) stroke_.version = ++stroke_counter_;
    }
    stroke_.last = pos;
    active_frames_ = std::max(active_frames_, kFramesAfterInput);
}

void Viewer::end_stroke() {
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
        if (result != stroke.before || !session_.selection())
            commands_.push_back(SetSelection{std::move(result), "Lasso", parameters});
    } else {
        std::snprintf(parameters, sizeof parameters, "radius %.0f px, %zu dabs (%s)",
                      double(panels_.selection.brush_radius), stroke.dabs, how);
        if (stroke.weights != stroke.before || !session_.selection())
            commands_.push_back(SetSelection{std::move(stroke.weights), "Brush", parameters});
    }
    overlay_key_.clear();
    active_frames_ = std::max(active_frames_, kFramesAfterInput);
}

bool Viewer::selection_input(const glm::vec2& pos, bool in_view) {
    const ImGuiIO& io = ImGui::GetIO();
    const SelectionPanelState& s = panels_.selection;
    const bool lasso = s.tool == SelectionPanelState::Tool::Lasso;
    const bool modifier = (io.KeyCtrl || io.KeyAlt) && !io.KeyShift;
    // The brush's circle (or the lasso) where the tool would draw.
    ImDrawList* draw = ImGui::GetForegroundDrawList();
    const ImVec2 at(pos.x + view_rect_.x, pos.y + view_rect_.y);
    const bool add = stroke_.active ? stroke_.add : !io.KeyAlt;
    const ImU32 color = add ? IM_COL32(255, 200, 80, 220) : IM_COL32(120, 190, 255, 220);
    if (s.open && (modifier || stroke_.active) && in_view && !lasso)
        draw->AddCircle(at, s.brush_radius, color, 48, 1.5f);
    if (stroke_.active && stroke_.lasso && stroke_.lasso_points.size() > 1) {
        std::vector<ImVec2> points;
        for (const Eigen::Vector2f& p : stroke_.lasso_points)
            points.emplace_back(p.x() + view_rect_.x, p.y() + view_rect_.y);
        draw->AddPolyline(points.data(), int(points.size()), color, ImDrawFlags_Closed, 1.5f);
    }
    if (brush_script_.state == 1) return true;  // --brush draws; the mouse waits
    if (stroke_.active) {
        if (ImGui::IsMouseDown(ImGuiMouseButton_Left)) {
            if (pos != stroke_.last) continue_stroke(pos);
        } else {
            end_stroke();
        }
        return true;
    }
    // A preview computing does not stop the brush (the selection's entry computes it again).
    if (!s.open || !modifier || (session_.busy() && !session_.preview_running())) return false;
    if (ImGui::IsMouseClicked(ImGuiMouseButton_Left) && drag_in_view_ && in_view) {
        begin_stroke(!io.KeyAlt, lasso, pos);
        return true;
    }
    return false;
}

void Viewer::upload_selection_overlay(RenderStyle& style) {
    style.selection_outline_width *= ui_scale_;
    const Shown& shown = session_.shown();
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
        if (renderer_->has_vertex_selection()) renderer_->clear_vertex_selection();
        overlay_key_.clear();
        return;
    }
    if (key == overlay_key_ && renderer_->has_vertex_selection()) return;
    try {
        if (stroke_.active) {
            if (stroke_.weights.size() != renderer_->n_vertices()) return;
            renderer_->set_vertex_selection(stroke_.weights);
        } else {
            const std::optional<Selection> weights = stored_selection(*shown.mesh);
            if (!weights || weights->size() != renderer_->n_vertices()) return;
            renderer_->set_vertex_selection(*weights);
        }
        overlay_key_ = key;
    } catch (const std::exception& e) {
        overlay_key_ = key;  // do not try again every frame
        session_.notify_error(std::string("selection overlay: ") + e.what());
    }
}

void Viewer::scripted_brush() {
    ScriptedBrush& b = brush_script_;
    if (options_.brush.empty() || b.state == 2) return;
    const double now = glfwGetTime();
    // The frame after a move: the move's overlay has been drawn and swapped.
    if (b.moved_at >= 0) {
        b.ms.push_back(1000.0 * (now - b.moved_at));
        b.moved_at = -1;
    }
    if (b.state == 0) {
        // The view's place comes from the first frames' layout: wait for it.
        if (++b.frames_waited < 3 || !ready_for_script() || session_.busy() ||
            next_scripted_select_ < options_.selections.size())
            return;
        float x0 = 0, y0 = 0, x1 = 0, y1 = 0, r = panels_.selection.brush_radius;
        char extra = 0;
        const int n =
            std::sscanf(options_.brush.c_str(), "%f,%f:%f,%f:%f%c", &x0, &y0, &x1, &y1, &r, &extra);
        if ((n != 4 && n != 5) || !std::isfinite(x0) || !std::isfinite(y0) || !std::isfinite(x1) ||
            !std::isfinite(y1) || !(r > 0 && r < 10000)) {
            session_.notify_error(
                "--brush: expected \"X0,Y0:X1,Y1[:R]\" in window pixels (R > 0), got \"" +
                options_.brush + "\"");
            exit_status_ = 1;
            b.state = 2;
            return;
        }
        b.from = glm::vec2(x0 - view_rect_.x, y0 - view_rect_.y);
        b.to = glm::vec2(x1 - view_rect_.x, y1 - view_rect_.y);
        b.radius = r;
        panels_.selection.brush_radius = r;
        b.state = 1;
        b.step = 0;
        begin_stroke(true, false, b.from);
        b.moved_at = now;
        return;
    }
    if (b.step < b.steps) {
        ++b.step;
        const float t = float(b.step) / float(b.steps);
        const double t0 = glfwGetTime();
        continue_stroke(b.from + t * (b.to - b.from));
        b.moved_at = t0;
        active_frames_ = std::max(active_frames_, 2);
        return;
    }
    end_stroke();
    b.state = 2;
    if (b.ms.empty()) return;
    std::printf("brush: samples=%zu median_ms=%.2f max_ms=%.2f\n", b.ms.size(), median(b.ms),
                *std::max_element(b.ms.begin(), b.ms.end()));
    std::fflush(stdout);
}

std::string parse_lasso_script(const std::string& text, std::vector<glm::vec2>& points,
                               bool& through) {
    points.clear();
    through = false;
    std::size_t start = 0;
    while (start <= text.size()) {
        const std::size_t colon = std::min(text.find(':', start), text.size());
        const std::string part = text.substr(start, colon - start);
        start = colon + 1;
        if (part == "through" && start > text.size()) {
            through = true;
            break;
        }
        float x = 0, y = 0;
        char extra = 0;
        if (std::sscanf(part.c_str(), "%f,%f%c", &x, &y, &extra) != 2 || !std::isfinite(x) ||
            !std::isfinite(y))
            return "point " + std::to_string(points.size() + 1) + " (\"" + part +
                   "\") is not X,Y in window pixels";
        points.emplace_back(x, y);
    }
    if (points.size() < 3)
        return "a lasso needs at least three points, got " + std::to_string(points.size());
    return "";
}

void Viewer::drive_lasso() {
    ScriptedLasso& l = lasso_script_;
    if (options_.lasso.empty() || l.state == 3) return;
    ImGuiIO& io = ImGui::GetIO();
    if (l.state == 0) {
        // After the layout settles, --op, --select and --brush (one stroke at a time).
        if (++l.frames_waited < 3 || !ready_for_script() || session_.busy() ||
            next_scripted_select_ < options_.selections.size() || clicks_pending() ||
            (!options_.brush.empty() && brush_script_.state != 2) || stroke_.active)
            return;
        std::vector<glm::vec2> points;
        bool through = false;
        const std::string error = parse_lasso_script(options_.lasso, points, through);
        if (!error.empty()) {  // main() checked it: not reached from the command line
            session_.notify_error("--lasso: " + error);
            exit_status_ = 1;
            l.state = 3;
            return;
        }
        // What the user chooses first: the Selection section open, its Lasso tool.
        panels_.selection.open = true;
        panels_.selection.tool = SelectionPanelState::Tool::Lasso;
        panels_.selection.lasso_through = through;
        // The mouse's place in each frame: pressed at the first point, moved along each side in
        // a few steps (the lasso closes itself back to the first point on release).
        constexpr int kStepsPerSide = 4;
        l.path = {points[0]};
        for (std::size_t i = 1; i < points.size(); ++i)
            for (int k = 1; k <= kStepsPerSide; ++k)
                l.path.push_back(points[i - 1] +
                                 (float(k) / kStepsPerSide) * (points[i] - points[i - 1]));
        l.state = 1;
        l.step = 0;
    }
    if (l.state == 1) {
        // Frame 0 hovers the first point, frames 1..n hold the button along the path (frame 1
        // presses), the frame after releases. Ctrl is the lasso's adding modifier.
        const std::size_t at = l.step == 0 ? 0 : std::min(l.step - 1, l.path.size() - 1);
        io.MousePos = ImVec2(l.path[at].x, l.path[at].y);
        io.MouseDown[0] = l.step >= 1 && l.step <= l.path.size();
        io.KeyCtrl = true;
        io.KeyAlt = io.KeyShift = false;
        if (++l.step > l.path.size() + 1) l.state = 2;
        active_frames_ = std::max(active_frames_, 2);
        return;
    }
    // Released: the mouse goes away and Ctrl up; report once the entry is in the document.
    io.MousePos = ImVec2(-FLT_MAX, -FLT_MAX);
    io.MouseDown[0] = false;
    io.KeyCtrl = false;
    active_frames_ = std::max(active_frames_, 2);
    if (stroke_.active || session_.busy() || !commands_.empty()) return;
    l.state = 3;
    std::printf("lasso: vertices=%zu\n", session_.selected_count());
    std::fflush(stdout);
}

}  // namespace trilab::viewer
