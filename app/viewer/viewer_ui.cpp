// One frame's UI: mouse and keys, the menus, the fixed regions and the sidebar, and the
// panels' view of the session (previews, the stable step, the level of detail).
#include "app/ops/smooth_op.h"
#include "app/viewer/viewer.h"

// glad before GLFW: GLFW must not include the system GL header.
#include <glad/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>
#include <imgui_internal.h>  // --print-layout reads the window list

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <tuple>
#include <utility>
#include <vector>

#include "app/ops/operation.h"
#include "app/ops/operation_entries.h"
#include "app/record/recorder.h"
#include "app/viewer/key_bindings.h"
#include "app/viewer/viewer_tuning.h"
#include "core/algorithms/coincident.h"
#include "core/algorithms/decimation.h"
#include "core/algorithms/fairing.h"
#include "core/algorithms/generators.h"
#include "core/algorithms/mesh_stats.h"
#include "core/algorithms/orientation.h"
#include "core/algorithms/texcoords.h"
#include "core/errors.h"
#include "core/geometry.h"
#include "core/io/mesh_io.h"
#include "render/offscreen.h"

namespace trilab::viewer {
using namespace tuning;

void Viewer::handle_input() {
    const ImGuiIO& io = ImGui::GetIO();
    Camera& camera = view_.camera;
    const Rect& view = view_rect_;
    // Mouse input in the view's coordinates; drags count when they began in the view.
    const bool in_view = ImGui::IsMousePosValid() && io.MousePos.x >= view.x &&
                         io.MousePos.y >= view.y && io.MousePos.x < view.right() &&
                         io.MousePos.y < view.bottom();
    if (ImGui::IsMouseClicked(ImGuiMouseButton_Left) ||
        ImGui::IsMouseClicked(ImGuiMouseButton_Middle))
        drag_in_view_ = in_view && !io.WantCaptureMouse;
    if (!io.WantCaptureMouse && ImGui::IsMousePosValid()) {
        const glm::vec2 pos(io.MousePos.x - view.x, io.MousePos.y - view.y);
        const glm::vec2 delta(io.MouseDelta.x, io.MouseDelta.y);
        const bool moved = delta.x != 0.0f || delta.y != 0.0f;
        // A left click that does not drag picks (Ctrl: the second pick, measuring); the view
        // turns once the cursor has moved past the click's slop (from where it was pressed),
        // so a click never turns it. A double click makes the picked point the centre of
        // rotation (Home fits the view).
        if (ImGui::IsMouseClicked(ImGuiMouseButton_Left) && drag_in_view_) {
            press_pos_ = pos;
            turning_ = false;
        }
        // The Selection section's brush and lasso take Ctrl/Alt drags (viewer_selection.cpp).
        const bool selecting = selection_input(pos, in_view);
        if (selecting) {
            // the stroke has the mouse: no pick, no turn
        } else if (ImGui::IsMouseReleased(ImGuiMouseButton_Left) && drag_in_view_ && in_view &&
                   !io.KeyShift && !turning_ && !ImGui::IsMouseDoubleClicked(ImGuiMouseButton_Left))
            pick_at(pos, io.KeyCtrl);
        if (selecting) {
            // as above
        } else if (ImGui::IsMouseDoubleClicked(ImGuiMouseButton_Left) && in_view && drag_in_view_) {
            if (pick_at(pos, false)) commands_.push_back(CentreOnPick{});
        } else if (moved && drag_in_view_ && ImGui::IsMouseDown(ImGuiMouseButton_Left) &&
                   !io.KeyShift) {
            if (turning_) {
                camera.rotate(pos - delta, pos);
                camera_fitted_ = false;
            } else if (glm::length(pos - press_pos_) > kClickSlopPixels) {
                turning_ = true;
                camera.rotate(press_pos_, pos);
                camera_fitted_ = false;
            }
        } else if (moved && drag_in_view_ &&
                   (ImGui::IsMouseDown(ImGuiMouseButton_Middle) ||
                    (ImGui::IsMouseDown(ImGuiMouseButton_Left) && io.KeyShift))) {
            camera.pan(delta);
            camera_fitted_ = false;
        }
        if (io.MouseWheel != 0.0f && in_view) {
            camera.zoom(io.MouseWheel);
            camera_fitted_ = false;
        }
    }

    scripted_brush();  // --brush: one step per frame

    // Files dropped on the window: images become the texture, anything else is opened.
    for (const std::string& path : dropped_paths_) {
        const std::vector<std::string> images = supported_image_extensions();
        const bool image =
            std::find(images.begin(), images.end(), file_extension(path)) != images.end();
        commands_.push_back(image ? Command(LoadTexture{path}) : Command(LoadFile{path}));
    }
    dropped_paths_.clear();

    // A right click that did not drag opens the Rendering menu as a popup.
    if (!io.WantCaptureMouse && in_view && ImGui::IsMouseReleased(ImGuiMouseButton_Right) &&
        ImGui::GetMouseDragDelta(ImGuiMouseButton_Right).x == 0.0f &&
        ImGui::GetMouseDragDelta(ImGuiMouseButton_Right).y == 0.0f)
        panels_.context_menu_requested = true;

    std::vector<KeyPress> presses;
    presses.swap(key_presses_);
    // Typing into a text field, a slider held, a popup: the keys are the widget's, except
    // the application shortcuts (quit), which are never lost.
    const KeyboardFocus focus = io.WantCaptureKeyboard || io.WantTextInput
                                    ? KeyboardFocus::Widget
                                    : KeyboardFocus::Bindings;
    KeyActionTargets targets{panels_,
                             view_.style,
                             view_.settings,
                             session_.morph(),
                             commands_,
                             session_.log(),
                             session_.document().path,
                             session_.jobs().busy(),
                             session_.history().current() > 0,
                             renderer_->has_texcoords(),
                             session_.preview_requested().has_value(),
                             glfwGetTime()};
    for (const KeyPress& press : presses) dispatch_key(press.key, press.mods, targets, focus);
}

void Viewer::draw_ui() {
    MenuContext context;
    context.has_file = !session_.document().path.empty();
    context.busy = session_.jobs().busy();
    context.can_undo = session_.history().can_undo();
    context.can_redo = session_.history().can_redo();
    context.document_path = session_.document().path;
    context.recent_files = &recent_.paths();
    RenderContext render;
    render.has_texcoords = renderer_->has_texcoords();
    render.has_loaded_texture = !texture_.empty();
    const bool checker = view_.settings.use_checkerboard;
    menu_bar(view_.style, view_.settings, panels_, context, render, commands_);
    context_menu(view_.style, view_.settings, panels_, render, commands_);
    if (checker != view_.settings.use_checkerboard) update_texture();

    // The fixed regions (layout.h). A region the user resizes this frame changes the ones
    // drawn after it, so the layout is computed again after each resizable region.
    const ImGuiIO& io = ImGui::GetIO();
    LayoutInput in;
    in.width = io.DisplaySize.x;
    in.height = io.DisplaySize.y;
    in.em = ImGui::GetFontSize();
    in.frame_height = ImGui::GetFrameHeight();
    in.sidebar = panels_.sidebar_open;
    in.history = panels_.history_open;
    in.log = panels_.log_open;
    in.legend = view_.colors.has_legend;
    LayoutState& sizes = panels_.layout;
    Layout layout = compute_layout(in, sizes);

    StatusInfo status;
    // What is on the screen: a preview, a level of detail or a morph frame has its own counts.
    std::tie(status.n_vertices, status.n_faces) = shown_counts();
    status.file_name = session_.document().name;
    status.frame_ms = frame_ms();
    // A preview's progress shows only when it takes a while.
    JobInfo job;
    const bool show_job = session_.jobs().busy() &&
                          !(session_.preview_running() && session_.jobs().elapsed_seconds() < 0.5);
    if (show_job) {
        job.name = session_.jobs().name();
        job.stage = session_.jobs().stage();
        job.fraction = session_.jobs().fraction();
        job.seconds = session_.jobs().elapsed_seconds();
        job.cancel_requested = session_.jobs().cancel_requested();
    }
    status_bar(status, session_.notice(), show_job ? &job : nullptr, layout.status, commands_);

    update_panels();
    update_collapsing_edges();
    if (panels_.sidebar_open && begin_sidebar(layout.sidebar, sizes)) {
        const std::vector<std::string> info =
            panels_.info_open ? scene_info() : std::vector<std::string>{};
        SidebarContext sidebar;
        sidebar.history = &session_.history();
        sidebar.busy = session_.jobs().busy();
        sidebar.closed = session_.document().closed;
        sidebar.now = glfwGetTime();
        sidebar.can_record =
            session_.history().current() > 0 && session_.morph().moves && !session_.jobs().busy();
        sidebar.open_seams = session_.document().open_seams;
        sidebar.collapsing_edges =
            panels_.decimation.show_collapsing_edges ? collapse_lines_->n_segments() : 0;
        sidebar.frequency = &session_.document().frequency;
        sidebar.info = &info;
        sidebar.inspector = &inspector_;
        selection_context(sidebar);
        sidebar_sections(panels_, session_.morph(), sidebar, commands_);
    }
    if (panels_.sidebar_open) end_region();
    layout = compute_layout(in, sizes);
    history_window(panels_, session_.history(), session_.jobs().busy(), layout.history, commands_);
    layout = compute_layout(in, sizes);
    log_window(panels_, session_.log(), layout.log);
    layout = compute_layout(in, sizes);
    LegendSlot slot;
    slot.right = layout.legend.right();
    slot.bottom = layout.legend.bottom();
    slot.max_width = layout.legend_max_width;
    slot.max_height = layout.legend_max_height;
    if (color_legend(view_.colors, view_.settings.coloring_options, view_.style, slot))
        commands_.push_back(UpdateColoring{});
    if (slot.width > 0) {  // its size this frame places it in the next
        sizes.legend_width = slot.width;
        sizes.legend_height = slot.height;
    }
    layout = compute_layout(in, sizes);
    const bool resized = layout.view.w != view_rect_.w || layout.view.h != view_rect_.h;
    view_rect_ = layout.view;
    view_.camera.set_viewport(std::max(view_rect_.w, 1.0f), std::max(view_rect_.h, 1.0f));
    // A model framed by Fit stays framed when the view changes size, until the user moves it.
    if (resized && camera_fitted_) view_.camera.fit_sphere(fit_center_, fit_radius_);

    // Dialogs float over the view.
    screenshot_dialog(panels_.screenshot, commands_);
    help_window(panels_);
    about_window(panels_);
    file_browser(panels_.file_browser, commands_);
    error_popup(session_.notice());
    unsaved_changes_popup(panels_.unsaved, commands_);
    recovery_popup(panels_.recovery, commands_);
}

void Viewer::update_panels() {
    // The operation panels: their previews (Cancel shows), and whether they stay live.
    const std::optional<Operation>& requested = session_.preview_requested();
    for (OperationPanelState* panel : operation_panels()) {
        panel->previewing = session_.previewing(panel->op);
        if (!requested || requested->def != panel->op.def) continue;
        const double ms = session_.last_preview_ms();
        if (ms < 0 || ms == panel->latency_ms || sweep_.active) continue;
        panel->latency_ms = ms;
        note_preview_latency(*panel, ms);
    }
    update_stable_step();
    update_lens();
    update_region_notes();
    update_selection();
    // Decimation's level of detail.
    DecimationPanelState& d = panels_.decimation;
    d.lod_ready = session_.has_level_of_detail();
    d.lod_building = session_.level_building();
    d.lod_note = session_.level_note();
    if (!d.lod_ready) d.lod_percent = 100.0f;
}

void Viewer::note_preview_latency(OperationPanelState& panel, double ms) {
    constexpr double kLiveBudgetMs = 150.0;  ///< previews slower than this wait for the release
    char buf[160];
    panel.live = ms <= kLiveBudgetMs;
    if (panel.live)
        std::snprintf(buf, sizeof buf, "preview %.0f ms", ms);
    else
        std::snprintf(buf, sizeof buf,
                      "preview %.0f ms: over the %.0f ms budget, previews when a drag ends", ms,
                      kLiveBudgetMs);
    panel.preview_note = buf;
}

void Viewer::update_stable_step() {
    FairingPanelState& f = panels_.fairing;
    if (!f.open) return;
    const int op = int(options_of<FairingOptions>(f.op).op);
    const HalfedgeMesh::Revision state = session_.mesh().revision();
    // A preview of this state reports it (any size); small meshes get it at once.
    const OperationResult* preview = session_.preview_result();
    const std::optional<Operation>& requested = session_.preview_requested();
    if (preview && requested && is_operation<FairingOptions>(*requested) &&
        int(options_of<FairingOptions>(*requested).op) == op) {
        if (const SmoothReport* r = report_of<SmoothReport>(*preview);
            r && std::isfinite(r->max_stable_step))
            f.max_stable_step = r->max_stable_step;
        f.stable_step_state = state;
        f.stable_step_operator = op;
        return;
    }
    if (f.stable_step_state == state && f.stable_step_operator == op) return;
    f.stable_step_state = state;
    f.stable_step_operator = op;
    f.max_stable_step = std::numeric_limits<double>::quiet_NaN();
    constexpr std::size_t kAtOnceVertices = 100000;  // a few ms to tens of ms
    if (session_.mesh().n_vertices() <= kAtOnceVertices) {
        try {
            const FairingOperator fo = op == int(FairingOperator::Taubin)
                                           ? FairingOperator::Umbrella
                                           : FairingOperator(op);
            f.max_stable_step = max_stable_explicit_step(session_.mesh(), fo);
        } catch (const std::exception& e) {
            session_.log().warning(std::string("stable step: ") + e.what());
        }
    }
}

std::vector<std::string> Viewer::scene_info() const {
    std::vector<std::string> lines = session_.document().info;
    const glm::vec3 eye = glm::vec3(glm::inverse(view_.camera.view())[3]);
    char buf[200];
    std::snprintf(buf, sizeof(buf), "camera at (%.3g, %.3g, %.3g), frame %.1f ms", eye.x, eye.y,
                  eye.z, frame_ms());
    lines.push_back(buf);
    lines.push_back(std::string("mode ") + render_mode_name(view_.style.mode) +
                    (view_.style.wireframe ? ", wireframe overlay" : "") +
                    (view_.style.fog ? ", fog" : "") + (view_.style.specular ? ", specular" : ""));
    if (view_.colors.has_legend) {
        std::snprintf(buf, sizeof(buf), "colour: %s in [%.4g, %.4g]", view_.colors.label.c_str(),
                      view_.colors.range.min, view_.colors.range.max);
        lines.push_back(buf);
    }
    if (!texture_.empty())
        lines.push_back("texture " + std::to_string(texture_.width) + " x " +
                        std::to_string(texture_.height));
    return lines;
}

std::pair<std::size_t, std::size_t> Viewer::shown_counts() const {
    const Shown& shown = session_.shown();
    if (shown.kind == Shown::Kind::Level)
        return {shown.level->vertices(), renderer_->n_triangles()};
    return {shown.mesh->n_vertices(), shown.mesh->n_faces()};
}

std::vector<OperationPanelState*> Viewer::operation_panels() {
    std::vector<OperationPanelState*> panels = {&panels_.subdivision, &panels_.fairing,
                                                &panels_.decimation};
    for (OperationPanelState& tool : panels_.tools) panels.push_back(&tool);
    return panels;
}

bool Viewer::confirm_discard(bool quitting, const std::string& path) {
    // Unchanged documents never ask; scripted runs (--frames) only when they test the
    // close button (--close-after).
    if (!session_.document().unsaved || (options_.frames > 0 && options_.close_after == 0))
        return true;
    session_.log().info(quitting ? "unsaved changes: asking before quitting"
                                 : "unsaved changes: asking before opening " + path);
    UnsavedPrompt& prompt = panels_.unsaved;
    prompt.open_requested = true;
    prompt.quitting = quitting;
    prompt.path = path;
    prompt.document_path = session_.document().path;
    active_frames_ = std::max(active_frames_, kFramesAfterInput);
    return false;
}

}  // namespace trilab::viewer
