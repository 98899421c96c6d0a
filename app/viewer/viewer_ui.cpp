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

void Viewer::turn_along(const std::vector<glm::vec2>& path, const glm::vec2& origin) {
    // Every position the cursor took while the left button was down, in order (window
    // coordinates; `origin` is the view's corner): the view turns once past the click's slop.
    Camera& camera = context_.view.camera;
    for (const glm::vec2& at : path) {
        const glm::vec2 p = at - origin;
        if (turning_) {
            camera.rotate(drag_last_, p);
        } else if (glm::length(p - press_pos_) > kClickSlopPixels) {
            turning_ = true;
            camera.rotate(press_pos_, p);
        }
        drag_last_ = p;
    }
    if (turning_) context_.view.fitted = false;
}

void Viewer::handle_input() {
    const ImGuiIO& io = ImGui::GetIO();
    Camera& camera = context_.view.camera;
    const Rect& view = context_.view_rect;
    // Mouse input in the view's coordinates; drags count when they began in the view.
    const auto inside = [&](const glm::vec2& p) {
        return p.x >= view.x && p.y >= view.y && p.x < view.right() && p.y < view.bottom();
    };
    const bool in_view = ImGui::IsMousePosValid() && inside({io.MousePos.x, io.MousePos.y});
    // The mouse's events since the last frame, where they happened: a press, drag and release
    // during one slow frame turn the view instead of clicking where the cursor is by then.
    const LeftDrag drag = left_drag(pointer_trail_.take(), left_down_);
    left_down_ = drag.pressed ? !drag.released : (!drag.released && left_down_);
    if (ImGui::IsMouseClicked(ImGuiMouseButton_Left) ||
        ImGui::IsMouseClicked(ImGuiMouseButton_Middle))
        drag_in_view_ = (drag.pressed ? inside(drag.press_pos) : in_view) && !io.WantCaptureMouse;
    // A frame that handles a drag in the view draws a large mesh's stand-in.
    if (drag_in_view_ && (drag.pressed || !drag.path.empty())) scene_->note_input();
    if (!io.WantCaptureMouse && ImGui::IsMousePosValid()) {
        ViewMouse mouse;
        mouse.pos = glm::vec2(io.MousePos.x - view.x, io.MousePos.y - view.y);
        mouse.in_view = in_view;
        mouse.drag_in_view = drag_in_view_;
        mouse.ctrl = io.KeyCtrl;
        mouse.alt = io.KeyAlt;
        mouse.shift = io.KeyShift;
        const glm::vec2 delta(io.MouseDelta.x, io.MouseDelta.y);
        const bool moved = delta.x != 0.0f || delta.y != 0.0f;
        // A left click that does not drag picks (Ctrl: the second pick, measuring); the view
        // turns once the cursor has moved past the click's slop (from where it was pressed),
        // so a click never turns it. A double click makes the picked point the centre of
        // rotation (Home fits the view).
        const glm::vec2 origin(view.x, view.y);
        if (ImGui::IsMouseClicked(ImGuiMouseButton_Left) && drag_in_view_) {
            press_pos_ = drag.pressed ? drag.press_pos - origin : mouse.pos;
            drag_last_ = press_pos_;
            turning_ = false;
        }
        const bool double_clicked = ImGui::IsMouseDoubleClicked(ImGuiMouseButton_Left);
        mouse.clicked = ImGui::IsMouseReleased(ImGuiMouseButton_Left) && drag_in_view_ && in_view &&
                        !turning_ && !double_clicked;
        mouse.double_clicked = double_clicked && in_view && drag_in_view_;
        // The tools in turn (the selection's brush and lasso take Ctrl/Alt drags, a click
        // picks) until one has the mouse; then the view does not turn.
        bool taken = false;
        for (const auto& tool : tools_.all)
            if (tool->mouse(mouse)) {
                taken = true;
                break;
            }
        const glm::vec2& pos = mouse.pos;
        if (taken || mouse.double_clicked) {
            // the tool has the mouse, or a double click centred the view
        } else if (!drag.path.empty() && drag_in_view_ && !io.KeyShift) {
            turn_along(drag.path, origin);
        } else if (drag.path.empty() && moved && drag_in_view_ &&
                   ImGui::IsMouseDown(ImGuiMouseButton_Left) && !io.KeyShift) {
            // Input without window events (scripted): ImGui's frame positions.
            if (turning_) {
                camera.rotate(pos - delta, pos);
                context_.view.fitted = false;
            } else if (glm::length(pos - press_pos_) > kClickSlopPixels) {
                turning_ = true;
                camera.rotate(press_pos_, pos);
                context_.view.fitted = false;
            }
        } else if (moved && drag_in_view_ &&
                   (ImGui::IsMouseDown(ImGuiMouseButton_Middle) ||
                    (ImGui::IsMouseDown(ImGuiMouseButton_Left) && io.KeyShift))) {
            camera.pan(delta);
            context_.view.fitted = false;
        }
        if (io.MouseWheel != 0.0f && in_view) {
            camera.zoom(io.MouseWheel);
            context_.view.fitted = false;
        }
    }

    script_->brush_step();  // --brush: one step per frame

    // Files dropped on the window: images become the texture, anything else is opened.
    for (const std::string& path : dropped_paths_) {
        const std::vector<std::string> images = supported_image_extensions();
        const bool image =
            std::find(images.begin(), images.end(), file_extension(path)) != images.end();
        context_.commands.push_back(image ? Command(LoadTexture{path}) : Command(LoadFile{path}));
    }
    dropped_paths_.clear();

    // A right click that did not drag opens the Rendering menu as a popup.
    if (!io.WantCaptureMouse && in_view && ImGui::IsMouseReleased(ImGuiMouseButton_Right) &&
        ImGui::GetMouseDragDelta(ImGuiMouseButton_Right).x == 0.0f &&
        ImGui::GetMouseDragDelta(ImGuiMouseButton_Right).y == 0.0f)
        context_.panels.context_menu_requested = true;

    std::vector<KeyPress> presses;
    presses.swap(key_presses_);
    // Typing into a text field, a slider held, a popup: the keys are the widget's, except
    // the application shortcuts (quit), which are never lost.
    const KeyboardFocus focus = io.WantCaptureKeyboard || io.WantTextInput
                                    ? KeyboardFocus::Widget
                                    : KeyboardFocus::Bindings;
    KeyActionTargets targets{context_.panels,
                             context_.view.style,
                             context_.view.settings,
                             context_.session.morph(),
                             context_.commands,
                             context_.session.log(),
                             context_.session.document().path,
                             context_.session.jobs().busy(),
                             context_.session.history().current() > 0,
                             scene_->exact().has_texcoords(),
                             context_.session.previews().requested().has_value(),
                             tools_.entries()};
    for (const KeyPress& press : presses) dispatch_key(press.key, press.mods, targets, focus);
}

void Viewer::draw_ui() {
    Session& session = context_.session;
    ViewState& view = context_.view;
    PanelState& panels = context_.panels;
    CommandQueue& commands = context_.commands;
    MenuContext context;
    context.has_file = !session.document().path.empty();
    context.busy = session.jobs().busy();
    context.can_undo = session.history().can_undo();
    context.can_redo = session.history().can_redo();
    context.document_path = session.document().path;
    context.recent_files = &recent_.paths();
    RenderContext render;
    render.has_texcoords = scene_->exact().has_texcoords();
    render.has_loaded_texture = !scene_->texture_image().empty();
    const bool checker = view.settings.use_checkerboard;
    menu_bar(view.style, view.settings, panels, tools_.list(), context, render, commands);
    context_menu(view.style, view.settings, panels, tools_.entries(), render, commands);
    if (checker != view.settings.use_checkerboard) scene_->update_texture();

    // The fixed regions (layout.h). A region the user resizes this frame changes the ones
    // drawn after it, so the layout is computed again after each resizable region.
    const ImGuiIO& io = ImGui::GetIO();
    LayoutInput in;
    in.width = io.DisplaySize.x;
    in.height = io.DisplaySize.y;
    in.em = ImGui::GetFontSize();
    in.frame_height = ImGui::GetFrameHeight();
    in.sidebar = panels.sidebar_open;
    in.history = panels.history_open;
    in.log = panels.log_open;
    in.legend = view.colors.has_legend;
    LayoutState& sizes = panels.layout;
    Layout layout = compute_layout(in, sizes);

    StatusInfo status;
    // What is on the screen: a preview, a level of detail or a morph frame has its own counts.
    std::tie(status.n_vertices, status.n_faces) = scene_->shown_counts();
    status.file_name = session.document().name;
    // Frames of the kind on the screen: turning a large mesh shows the stand-in's time.
    const bool simplified = scene_->drew_proxy() || scene_->loading_picture_drawn();
    status.frame_ms = frame_ms(simplified);
    if (const std::string* loading = scene_->loading_picture_path();
        loading && scene_->loading_picture_drawn()) {
        status.loading = std::filesystem::path(*loading).filename().string();
        status.n_faces = scene_->loading_picture_faces();
    } else if (scene_->drew_proxy()) {
        status.simplified = "simplified while moving";
    }
    // A preview's progress shows only when it takes a while.
    JobInfo job;
    const bool show_job = session.jobs().busy() &&
                          !(session.previews().running() && session.jobs().elapsed_seconds() < 0.5);
    if (show_job) {
        job.name = session.jobs().name();
        job.stage = session.jobs().stage();
        job.fraction = session.jobs().fraction();
        job.seconds = session.jobs().elapsed_seconds();
        job.cancel_requested = session.jobs().cancel_requested();
    }
    status_bar(status, session.notice(), show_job ? &job : nullptr, layout.status, commands);

    for (const auto& tool : tools_.all) tool->update();
    if (panels.sidebar_open && begin_sidebar(layout.sidebar, sizes)) {
        const std::vector<std::string> info =
            panels.info_open ? scene_info() : std::vector<std::string>{};
        SidebarContext sidebar;
        sidebar.history = &session.history();
        sidebar.morph = &session.morph();
        sidebar.busy = session.jobs().busy();
        sidebar.closed = session.document().closed;
        sidebar.can_record =
            session.history().current() > 0 && session.morph().moves && !session.jobs().busy();
        sidebar.record_why_not =
            session.history().current() == 0 ? "apply an operation first"
            : !session.morph().moves         ? "this entry moves no vertex: nothing to animate"
            : session.jobs().busy()          ? "wait for \"" + session.jobs().name() + "\""
                                             : "";
        sidebar.open_seams = session.document().open_seams;
        sidebar.frequency = &session.document().frequency;
        sidebar.info = &info;
        for (const auto& tool : tools_.all) tool->describe(sidebar);
        sidebar_sections(tools_.list(), sidebar, commands);
    }
    if (panels.sidebar_open) end_region();
    layout = compute_layout(in, sizes);
    history_window(panels, session.history(), session.jobs().busy(), layout.history, commands);
    layout = compute_layout(in, sizes);
    log_window(panels, session.log(), layout.log);
    layout = compute_layout(in, sizes);
    LegendSlot slot;
    slot.right = layout.legend.right();
    slot.bottom = layout.legend.bottom();
    slot.max_width = layout.legend_max_width;
    slot.max_height = layout.legend_max_height;
    if (color_legend(view.colors, view.settings.coloring_options, view.style, slot))
        commands.push_back(UpdateColoring{});
    if (slot.width > 0) {  // its size this frame places it in the next
        sizes.legend_width = slot.width;
        sizes.legend_height = slot.height;
    }
    layout = compute_layout(in, sizes);
    Rect& view_rect = context_.view_rect;
    const bool resized = layout.view.w != view_rect.w || layout.view.h != view_rect.h;
    view_rect = layout.view;
    view.camera.set_viewport(std::max(view_rect.w, 1.0f), std::max(view_rect.h, 1.0f));
    // A model framed by Fit stays framed when the view changes size, until the user moves it.
    if (resized && view.fitted) view.camera.fit_sphere(view.fit_center, view.fit_radius);

    // Dialogs float over the view.
    screenshot_dialog(panels.screenshot, commands);
    help_window(panels);
    about_window(panels);
    file_browser(panels.file_browser, commands);
    error_popup(session.notice(), commands);
    unsaved_changes_popup(panels.unsaved, commands);
    recovery_popup(panels.recovery, commands);
}

std::vector<std::string> Viewer::scene_info() const {
    const ViewState& view = context_.view;
    std::vector<std::string> lines = context_.session.document().info;
    const glm::vec3 eye = glm::vec3(glm::inverse(view.camera.view())[3]);
    char buf[200];
    std::snprintf(buf, sizeof(buf), "camera at (%.3g, %.3g, %.3g), frame %.1f ms", eye.x, eye.y,
                  eye.z, frame_ms());
    lines.push_back(buf);
    lines.push_back(std::string("mode ") + render_mode_name(view.style.mode) +
                    (view.style.wireframe ? ", wireframe overlay" : "") +
                    (view.style.fog ? ", fog" : "") + (view.style.specular ? ", specular" : ""));
    if (view.colors.has_legend) {
        std::snprintf(buf, sizeof(buf), "colour: %s in [%.4g, %.4g]", view.colors.label.c_str(),
                      view.colors.range.min, view.colors.range.max);
        lines.push_back(buf);
    }
    if (const Image& texture = scene_->texture_image(); !texture.empty())
        lines.push_back("texture " + std::to_string(texture.width) + " x " +
                        std::to_string(texture.height));
    return lines;
}

bool Viewer::confirm_quit() {
    if (!context_.session.document().unsaved || (options_.frames > 0 && options_.close_after == 0))
        return true;
    context_.session.log().info("unsaved changes: asking before quitting");
    ask_before_discarding(true, "");
    return false;
}

void Viewer::ask_before_discarding(bool quitting, const std::string& path, bool recover) {
    UnsavedPrompt& prompt = context_.panels.unsaved;
    prompt.open_requested = true;
    prompt.quitting = quitting;
    prompt.recover = recover;
    prompt.path = path;
    prompt.document_path = context_.session.document().path;
    context_.keep_drawing(kFramesAfterInput);
}

void Viewer::reset_view() {
    ViewState& view = context_.view;
    const UpAxis up = view.settings.up;
    view.camera.reset_rotation(up);
    fit_view();
    if (preferences_.up != up) {
        preferences_.up = up;
        preferences_.save();
        context_.session.log().info(std::string("up axis: +") + up_axis_name(up) +
                                    " (the default view and the spherical texture projection)");
        // Coordinates the viewer projected around the other axis follow (a history entry).
        if (context_.session.document().texcoords_projected &&
            view.settings.projection == TexCoordProjection::Spherical)
            context_.session.execute(ProjectTexCoords{view.settings.projection, view.settings.up});
    }
}

void Viewer::fit_view() {
    const HalfedgeMesh& mesh = context_.session.mesh();
    BoundingBox box = bounding_box(mesh);
    glm::vec3 center(0.0f);
    float radius = 1.0f;
    if (!box.empty) {
        // The smallest sphere around the box centre that holds every vertex: tighter than the
        // box's own bounding sphere, so round models fill the view.
        const Point c = box.center();
        double radius2 = 0.0;
        for (Vertex v : mesh.vertices())
            radius2 = std::max(radius2, (mesh.position(v) - c).squaredNorm());
        center = glm::vec3(float(c.x()), float(c.y()), float(c.z()));
        radius = float(std::sqrt(radius2));
    }
    context_.fit_camera(center, radius);
    context_.view.fitted = true;
}

}  // namespace trilab::viewer
