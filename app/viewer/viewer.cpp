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
#include "app/platform/termination.h"
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

namespace {

void glfw_error(int code, const char* description) {
    std::fprintf(stderr, "trilab: GLFW error %d: %s\n", code, description);
}

}  // namespace

// ---- RAII pieces: destroyed in reverse order (renderer, ImGui, window, GLFW) --------------

struct Viewer::GlfwLibrary {
    GlfwLibrary() {
        glfwSetErrorCallback(glfw_error);
        if (!glfwInit()) throw Error("cannot initialise GLFW (is DISPLAY set?)");
    }
    ~GlfwLibrary() { glfwTerminate(); }
    GlfwLibrary(const GlfwLibrary&) = delete;
    GlfwLibrary& operator=(const GlfwLibrary&) = delete;
};

void Viewer::WindowDeleter::operator()(GLFWwindow* window) const {
    glfwSetWindowUserPointer(window, nullptr);  // no callback may reach a half-destroyed Viewer
    glfwDestroyWindow(window);
}

struct Viewer::ImGuiLayer {
    ImGuiLayer(GLFWwindow* window, float scale) {
        IMGUI_CHECKVERSION();
        ImGui::CreateContext();
        ImGuiIO& io = ImGui::GetIO();
        io.IniFilename = nullptr;
        ImGuiStyle& style = ImGui::GetStyle();
        apply_panel_style(style);
        if (scale > 1.0f) {
            // Re-rasterize the font at the scaled size instead of stretching it.
            ImFontConfig font;
            font.SizePixels = 13.0f * scale;
            io.Fonts->AddFontDefault(&font);
            style.ScaleAllSizes(scale);
        }
        // The backend chains to the callbacks installed before it (Viewer::wake).
        if (!ImGui_ImplGlfw_InitForOpenGL(window, true)) {
            ImGui::DestroyContext();
            throw Error("ImGui GLFW backend initialisation failed");
        }
        if (!ImGui_ImplOpenGL3_Init("#version 330 core")) {
            ImGui_ImplGlfw_Shutdown();
            ImGui::DestroyContext();
            throw Error("ImGui OpenGL 3 backend initialisation failed");
        }
    }
    ~ImGuiLayer() {
        ImGui_ImplOpenGL3_Shutdown();
        ImGui_ImplGlfw_Shutdown();
        ImGui::DestroyContext();
    }
    ImGuiLayer(const ImGuiLayer&) = delete;
    ImGuiLayer& operator=(const ImGuiLayer&) = delete;
};

// ---- construction ---------------------------------------------------------------------------

GLFWwindow* Viewer::create_window(const ViewerOptions& options, Viewer* viewer) {
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_SCALE_TO_MONITOR, GLFW_TRUE);
    // No multisampling: on llvmpipe 4x MSAA made frames 3-4 times slower, and the wireframe
    // overlay is anti-aliased in the shader anyway.
    glfwWindowHint(GLFW_SAMPLES, 0);
    GLFWwindow* window = glfwCreateWindow(options.width, options.height, kTitle, nullptr, nullptr);
    if (!window) throw Error("cannot create a window with an OpenGL 3.3 core context");
    glfwSetWindowUserPointer(window, viewer);
    // Every input or window event keeps the loop drawing for a few frames; otherwise it
    // sleeps in glfwWaitEvents. Installed before ImGui's, which call these in turn.
    // The mouse's events also go to the pointer trail, in order and where each happened (a
    // drag during a slow frame turns the view, pointer_trail.h).
    glfwSetCursorPosCallback(window, [](GLFWwindow* w, double x, double y) {
        wake(w);
        if (Viewer* v = from(w)) v->pointer_trail_.move(x, y);
    });
    glfwSetMouseButtonCallback(window, [](GLFWwindow* w, int button, int action, int) {
        wake(w);
        if (Viewer* v = from(w)) v->pointer_trail_.button(button, action == GLFW_PRESS);
    });
    glfwSetScrollCallback(window, [](GLFWwindow* w, double, double) { wake(w); });
    glfwSetKeyCallback(window, [](GLFWwindow* w, int key, int, int action, int mods) {
        wake(w);
        if (Viewer* v = from(w); v && action == GLFW_PRESS) v->key_presses_.push_back({key, mods});
    });
    glfwSetCharCallback(window, [](GLFWwindow* w, unsigned) { wake(w); });
    glfwSetCursorEnterCallback(window, [](GLFWwindow* w, int) { wake(w); });
    glfwSetWindowFocusCallback(window, [](GLFWwindow* w, int) { wake(w); });
    glfwSetFramebufferSizeCallback(window, [](GLFWwindow* w, int, int) { wake(w); });
    glfwSetWindowRefreshCallback(window, [](GLFWwindow* w) { wake(w); });
    glfwSetDropCallback(window, [](GLFWwindow* w, int count, const char** paths) {
        wake(w);
        if (Viewer* v = from(w))
            for (int i = 0; i < count; ++i) v->dropped_paths_.emplace_back(paths[i]);
    });
    return window;
}

Viewer* Viewer::from(GLFWwindow* window) {
    return static_cast<Viewer*>(glfwGetWindowUserPointer(window));
}

void Viewer::wake(GLFWwindow* window) {
    if (Viewer* viewer = from(window)) viewer->context_.active_frames = kFramesAfterInput;
}

Viewer::Viewer(ViewerOptions options) : options_(std::move(options)) {
    glfw_ = std::make_unique<GlfwLibrary>();
    window_.reset(create_window(options_, this));
    glfwMakeContextCurrent(window_.get());
    if (gladLoadGL(glfwGetProcAddress) == 0)
        throw Error("cannot load the OpenGL 3.3 core functions");
    glfwSwapInterval(options_.frames > 0 ? 0 : 1);

    // HiDPI: fonts and line widths follow the monitor's content scale; input stays in window
    // coordinates and the GL viewport in framebuffer pixels.
    float scale_x = 1.0f, scale_y = 1.0f;
    glfwGetWindowContentScale(window_.get(), &scale_x, &scale_y);
    int window_w = 0, window_h = 0, fb_w = 0, fb_h = 0;
    glfwGetWindowSize(window_.get(), &window_w, &window_h);
    glfwGetFramebufferSize(window_.get(), &fb_w, &fb_h);
    // Where the framebuffer is already larger than the window (macOS), ImGui scales itself.
    float fb_ratio = window_w > 0 ? float(fb_w) / float(window_w) : 1.0f;
    context_.ui_scale = std::max(1.0f, scale_x / std::max(fb_ratio, 1.0f));
    if (options_.ui_scale > 0) context_.ui_scale = options_.ui_scale;
    imgui_ = std::make_unique<ImGuiLayer>(window_.get(), context_.ui_scale);

    Session& session = context_.session;
    ViewState& view = context_.view;
    scene_ = std::make_unique<SceneView>(context_);
    SceneView& scene = *scene_;
    tools_ =
        make_tools(context_, &scene.exact(), [&scene] { return scene.geodesic_colored_version(); });
    scene_->set_field_colors([this](const HalfedgeMesh& mesh) {
        for (const auto& tool : tools_.all)
            if (VertexColors colors = tool->field_colors(mesh); !colors.colors.empty())
                return colors;
        return VertexColors{};
    });
    output_ = std::make_unique<FrameOutput>(context_, *scene_);
    script_ = std::make_unique<ScriptDriver>(options_, context_, *scene_, tools_, *output_);
    // What a session file stores beside the history; the unsaved-changes question (scripted
    // runs never ask, unless they test the close button).
    session.set_extras_provider([this] { return session_extras(); });
    session.set_ask_before_discarding(options_.frames == 0 || options_.close_after != 0);
    // A large file shows a simplified picture while it loads (scene_view.cpp): made on the
    // load job's thread from the file's arrays, with the document stand-in's own options.
    session.set_loading_picture_maker(
        [](const PolygonSoup& soup) -> std::shared_ptr<const ProxyMesh> {
            if (soup.n_faces() < SceneView::proxy_min_faces()) return nullptr;
            return std::make_shared<ProxyMesh>(
                make_soup_proxy_mesh(soup, SceneView::proxy_options(soup.n_faces())));
        });
    view.camera.set_viewport(float(window_w), float(window_h));
    context_.view_rect = Rect{0, 0, float(window_w), float(window_h)};
    // Recent files persist only for interactive sessions, not for scripted runs.
    if (options_.frames == 0) recent_.load(RecentFiles::default_file());
    if (options_.frames == 0) preferences_.load(Preferences::default_file());
    view.settings.up = options_.up.empty() ? preferences_.up : parse_up_axis(options_.up, "--up");
    view.camera.reset_rotation(view.settings.up);
    if (options_.memory_budget_mb > 0)
        session.set_history_budget(std::size_t(options_.memory_budget_mb) << 20);
    follow_session();  // the built-in model: upload it, fit the view
    session.log().info("OpenGL " +
                       std::string(reinterpret_cast<const char*>(glGetString(GL_VERSION))) +
                       " on " + reinterpret_cast<const char*>(glGetString(GL_RENDERER)));
    // Initial rendering options; bad names throw InvalidArgument before any window work.
    if (!options_.mode.empty()) view.style.mode = parse_render_mode(options_.mode);
    if (options_.wireframe == "on")
        view.settings.wireframe = WireframeOverlay::On;
    else if (options_.wireframe == "off")
        view.settings.wireframe = WireframeOverlay::Off;
    else if (!options_.wireframe.empty() && options_.wireframe != "auto")
        throw InvalidArgument("--wireframe: expected on, off or auto, got '" + options_.wireframe +
                              "'");
    if (!options_.color.empty()) {
        view.settings.coloring = parse_coloring(options_.color);
        scene_->update_coloring();
    }
    for (const std::string& text : options_.operations) {  // refuse bad ones now
        const Operation op = parse_operation(text);
        for (const auto& tool : tools_.all)  // the panel shows its values
            for (OperationPanelState* panel : tool->operation_panels())
                if (panel->op.def == op.def) panel->op = op;
    }
    open_panels(context_.panels, tools_.entries(), options_.show);
    if (!options_.no_recovery) start_recovery();  // --restore may start a job
    if (!options_.mesh_path.empty()) session.execute(LoadFile{options_.mesh_path, true});
}

Viewer::~Viewer() = default;

// ---- documents and commands -----------------------------------------------------------------

void Viewer::follow_session() {
    Session& session = context_.session;
    SessionEvents e = session.take_events();
    for (const std::string& path : e.recent) recent_.add(path);
    if (e.loaded_proxy) scene_->adopt_loaded_proxy(e.loaded_proxy);
    if (e.fit) scene_->model_fitted();  // a new model: its view stays
    if (e.state_changed) {
        const Document& doc = session.document();
        scene_->state_changed(doc.area);
        glfwSetWindowTitle(window_.get(), (doc.name + " - " + kTitle).c_str());
        if (e.fit) {
            context_.view.camera.reset_rotation(context_.view.settings.up);  // the default view
            fit_view();
        }
    }
    if (e.texture) {
        scene_->set_texture_image(std::move(*e.texture), e.texture_path);
        // A texture was asked for: show it.
        RenderStyle& style = context_.view.style;
        style.mode = RenderMode::Textured;
        if (style.texture_mode == TextureMode::Off) style.texture_mode = TextureMode::Modulate;
    }
    if (e.session_extras) apply_session_extras(*e.session_extras);
    if (e.confirm_discard) ask_before_discarding(false, *e.confirm_discard, e.confirm_recovery);
    if (e.saved && e.continue_after_save) {  // a prompt's "Save and go on": now go on
        const UnsavedPrompt& prompt = context_.panels.unsaved;
        if (prompt.quitting)
            context_.commands.push_back(Quit{true});
        else if (prompt.recover)
            context_.commands.push_back(RecoverJournal{prompt.path, true, true});
        else
            context_.commands.push_back(LoadFile{prompt.path, true});
    }
}

void Viewer::execute(const Command& command) {
    Session& session = context_.session;
    // Pictures of the scene show the exact surface, also while a large state waits for its
    // upload (scene_view.cpp).
    if (std::holds_alternative<TakeScreenshot>(command) ||
        std::holds_alternative<StartRecording>(command))
        scene_->ensure_exact();
    // The window's own commands; every other one is the session's (Session::execute).
    if (std::holds_alternative<SaveAsAndContinue>(command)) {
        context_.panels.file_browser.request(FileBrowserState::Purpose::SaveMesh,
                                             session.document().path);
        context_.panels.file_browser.then_continue = true;
    } else if (std::holds_alternative<FitView>(command)) {
        fit_view();
    } else if (std::holds_alternative<CentreOnPick>(command)) {
        if (!session.picking().picks().picks.empty()) {
            const Point& p = session.picking().picks().picks.front().position;
            context_.view.camera.set_target(glm::vec3(float(p.x()), float(p.y()), float(p.z())));
            context_.view.fitted = false;
        }
    } else if (std::holds_alternative<ResetView>(command)) {
        reset_view();
    } else if (std::holds_alternative<StartRecording>(command)) {
        output_->start_recording();
    } else if (std::holds_alternative<CancelRecording>(command)) {
        output_->finish_recording(true);
    } else if (std::holds_alternative<UpdateColoring>(command)) {
        scene_->update_coloring();
        scene_->invalidate();  // previews and morphs take the new colours too
    } else if (auto* shot = std::get_if<TakeScreenshot>(&command)) {
        output_->take_screenshot(*shot);
    } else if (std::holds_alternative<PrintInfo>(command)) {
        for (const std::string& line : scene_info()) session.log().info(line);
        context_.panels.info_open = true;
    } else if (auto* quit = std::get_if<Quit>(&command)) {
        if (quit->discard_changes || confirm_quit()) quit_ = true;
    } else if (std::holds_alternative<SaveAndContinue>(command)) {
        if (!session.document().path.empty()) execute(SaveFile{session.document().path, true});
    } else {  // the document's commands
        session.execute(command);
    }
}

// ---- one frame ------------------------------------------------------------------------------

bool Viewer::prepare_frame() {
    Session& session = context_.session;
    bool waited = false;
    // Scripted runs (--frames) show the result of the initial load, not the progress; a
    // loading picture not on the screen yet is drawn (the first picture of a large file).
    while (options_.frames > 0 && session.jobs().busy() && !session.previews().running()) {
        if (scene_->new_loading_picture()) break;
        session.poll();
        if (session.jobs().busy()) glfwWaitEventsTimeout(0.002);
        waited = true;
    }
    if (session.poll()) {
        context_.keep_drawing(kFramesAfterInput);
        if (scene_->poll_coloring())  // asked for while a job ran
            context_.commands.push_back(UpdateColoring{});
    }
    follow_session();
    journal_settings();
    script_->advance();
    for (const auto& tool : tools_.all) tool->update();
    if (session.jobs().busy()) context_.keep_drawing();  // animate the progress
    return waited;
}

bool Viewer::draw_frame() {
    Session& session = context_.session;
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    script_->drive_mouse();
    ImGui::NewFrame();
    handle_input();
    draw_ui();
    script_->note_commands();
    script_->turn_camera();
    scene_->draw_note();  // "simplified while moving"
    ImGui::Render();

    CommandQueue& commands = context_.commands;
    const bool had_commands = !commands.empty();
    // A command may queue more (SaveAndContinue); they run in the next frame.
    CommandQueue running;
    running.swap(commands);
    for (const Command& command : running) execute(command);
    session.wait_for_preview(0.1);
    follow_session();
    // Commands and popups change the UI over the next frames: keep drawing.
    if (!running.empty() || !commands.empty() || session.notice().popup_pending ||
        context_.panels.file_browser.open_requested || context_.panels.context_menu_requested)
        context_.keep_drawing(kFramesAfterInput);

    // Textured mode on a model without texture coordinates: project them once, on the
    // shape as it is now, so that later vertex drift shows in the texture.
    const ViewState& view = context_.view;
    if (view.style.mode == RenderMode::Textured && !scene_->exact_pending() &&
        !scene_->exact().has_texcoords() && !session.document().texcoords_projected &&
        !session.jobs().busy())
        session.execute(ProjectTexCoords{view.settings.projection, view.settings.up});

    if (output_->recording()) {
        output_->record_next_frame();
    } else {
        session.update();
        scene_->sync();
    }
    scene_->update_wireframe();
    render_scene();
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    return had_commands;
}

void Viewer::render_scene() {
    int fb_w = 0, fb_h = 0;
    glfwGetFramebufferSize(window_.get(), &fb_w, &fb_h);
    glViewport(0, 0, fb_w, fb_h);
    const ViewState& view = context_.view;
    clear_background(view.style);
    if (fb_w <= 0 || fb_h <= 0 || context_.view_rect.empty()) return;  // minimized
    int x = 0, y = 0, w = 0, h = 0;
    framebuffer_viewport(context_.view_rect, x, y, w, h);
    glViewport(x, y, w, h);

    RenderStyle style = view.style;
    const float scale = context_.ui_scale;
    style.wire_width *= scale;
    style.isoline_width *= scale;
    style.point_size *= scale;
    style.selection_outline_width *= scale;
    for (const auto& tool : tools_.all) tool->before_surface(style);
    // Large meshes: the stand-in while the view moves, the exact surface at rest.
    scene_->draw(style);
    for (const auto& tool : tools_.all) tool->draw_overlay();
    glViewport(0, 0, fb_w, fb_h);  // ImGui draws over the whole window
}

int Viewer::run() {
    Session& session = context_.session;
    int frame = 0;
    int settle_frames = 0;
    double last_frame_end = -1.0;  // glfw time at the end of the last frame drawn
    bool waited = false;           // the loop slept since then (no frame to time)
    context_.active_frames = kFramesAfterInput;
    while (!quit_ && !script_->quit() && !termination_signal()) {
        // The window's close button asks like File -> Quit does.
        if (glfwWindowShouldClose(window_.get())) {
            glfwSetWindowShouldClose(window_.get(), GLFW_FALSE);
            context_.commands.push_back(Quit{});
            context_.keep_drawing();
        }
        // Idle viewers sleep; a timeout keeps the text cursor blinking in the open dialog.
        if (options_.frames > 0 || context_.active_frames > 0) {
            glfwPollEvents();
        } else {
            glfwWaitEventsTimeout(ImGui::GetIO().WantTextInput ? 0.5 : 10.0);
            waited = true;
            if (context_.active_frames == 0 && !ImGui::GetIO().WantTextInput) continue;
        }
        if (context_.active_frames > 0) --context_.active_frames;

        if (prepare_frame()) waited = true;

        // Scripted runs: the last frame comes once everything started has ended (jobs,
        // previews, the morph animation, the scripted actions), so screenshots show results.
        const bool scripted_end = options_.frames > 0 && frame + 1 >= options_.frames;
        const bool settled = scripted_end && script_->settled();

        const double start = glfwGetTime();
        const bool had_commands = draw_frame();

        ++frame;
        if (frame == options_.close_after) glfwSetWindowShouldClose(window_.get(), GLFW_TRUE);
        bool last = settled && !had_commands && !session.jobs().busy() && !session.morph().playing;
        if (scripted_end && !last && ++settle_frames > kMaxSettleFrames) {
            session.log().warning("still busy after " + std::to_string(kMaxSettleFrames) +
                                  " extra frames: the last frame may show an unfinished state");
            last = true;
        }
        if (last && options_.print_layout) script_->print_layout(window_.get());
        if (last && !options_.screenshot.empty()) {
            int w = 0, h = 0;
            glfwGetFramebufferSize(window_.get(), &w, &h);
            std::string error = FrameOutput::write_window(options_.screenshot, w, h);
            if (!error.empty()) {
                std::fprintf(stderr, "trilab: %s\n", error.c_str());
                session.close_journal();
                return 1;
            }
        }
        // The frame is on the screen when we time it (sweeps, the orbit, --print-timing).
        if (script_->timing_frames()) glFinish();
        glfwSwapBuffers(window_.get());
        // The frame time is the time from one frame's end to the next's: the GL driver may
        // finish a frame's work in the next frame's first calls (a software renderer does), so
        // the time inside one loop pass can be a fraction of it. After a sleep (no events)
        // the pass alone counts.
        const double end = glfwGetTime();
        const double since = waited || last_frame_end < 0 ? end - start : end - last_frame_end;
        frame_times_ms_[n_frame_times_++ % frame_times_ms_.size()] = {
            1000.0 * since, scene_->drew_proxy() || scene_->loading_picture_drawn()};
        last_frame_end = end;
        waited = false;
        // A spectral prediction on the screen lets its exact job start (with the next frame).
        if (scene_->shows_current()) session.execute(PredictionDrawn{});
        script_->frame_end(1000.0 * since);
        if (last) break;
    }
    script_->finish(frame_ms(), std::min(n_frame_times_, frame_times_ms_.size()));
    int status = script_->exit_status();
    if (!options_.save_session.empty()) {
        const std::string error = save_session_now();
        if (!error.empty()) {
            std::fprintf(stderr, "trilab: --save-session: %s\n", error.c_str());
            status = 1;
        }
    }
    if (const char* signal = termination_signal()) {
        // Ended from outside (a logout): no question could be asked, so the work stays in the
        // journal, marked as not saved rather than crashed.
        session.log().info(std::string("ended by ") + signal + " after " + std::to_string(frame) +
                           " frames: the work is kept for recovery");
        session.end_journal_unsaved(signal);
        return status;
    }
    session.log().info(quit_ || script_->quit() ? "quit after " + std::to_string(frame) + " frames"
                                                : "frames done");
    session.close_journal();  // a clean exit: nothing to recover
    return status;
}

double Viewer::frame_ms(std::optional<bool> simplified) const {
    const std::size_t n = std::min(n_frame_times_, frame_times_ms_.size());
    std::vector<double> times;
    for (std::size_t i = 0; i < n; ++i)
        if (!simplified || frame_times_ms_[i].second == *simplified)
            times.push_back(frame_times_ms_[i].first);
    if (times.empty()) return 0.0;
    std::nth_element(times.begin(), times.begin() + times.size() / 2, times.end());
    return times[times.size() / 2];
}

}  // namespace trilab::viewer
