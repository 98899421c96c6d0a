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
    glfwSetCursorPosCallback(window, [](GLFWwindow* w, double, double) { wake(w); });
    glfwSetMouseButtonCallback(window, [](GLFWwindow* w, int, int, int) { wake(w); });
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
    if (Viewer* viewer = from(window)) viewer->active_frames_ = kFramesAfterInput;
}

Viewer::Viewer(ViewerOptions options) : options_(std::move(options)) {
    glfw_ = std::make_unique<GlfwLibrary>();
    window_.reset(create_window(options_, this));
    glfwMakeContextCurrent(window_.get());
    if (gladLoadGL(glfwGetProcAddress) == 0)
        throw Error("cannot load the OpenGL 3.3 core functions");
    glfwSwapInterval(options_.frames > 0 ? 0 : 1);
    // --click finds its widgets through the hook (viewer_clicks.cpp).
    if (!options_.clicks.empty())
        set_widget_hook([this](const WidgetNote& note) { clicks_.drawing.push_back(note); });

    // HiDPI: fonts and line widths follow the monitor's content scale; input stays in window
    // coordinates and the GL viewport in framebuffer pixels.
    float scale_x = 1.0f, scale_y = 1.0f;
    glfwGetWindowContentScale(window_.get(), &scale_x, &scale_y);
    int window_w = 0, window_h = 0, fb_w = 0, fb_h = 0;
    glfwGetWindowSize(window_.get(), &window_w, &window_h);
    glfwGetFramebufferSize(window_.get(), &fb_w, &fb_h);
    // Where the framebuffer is already larger than the window (macOS), ImGui scales itself.
    float fb_ratio = window_w > 0 ? float(fb_w) / float(window_w) : 1.0f;
    ui_scale_ = std::max(1.0f, scale_x / std::max(fb_ratio, 1.0f));
    if (options_.ui_scale > 0) ui_scale_ = options_.ui_scale;
    imgui_ = std::make_unique<ImGuiLayer>(window_.get(), ui_scale_);

    renderer_ = std::make_unique<MeshRenderer>();
    proxy_.renderer = std::make_unique<MeshRenderer>();
    // A large file shows a simplified picture while it loads (viewer_motion.cpp): made on the
    // load job's thread from the file's arrays, with the document proxy's own options.
    session_.set_loading_picture_maker(
        [](const PolygonSoup& soup) -> std::shared_ptr<const ProxyMesh> {
            if (soup.n_faces() < proxy_min_faces()) return nullptr;
            return std::make_shared<ProxyMesh>(
                make_soup_proxy_mesh(soup, proxy_options(soup.n_faces())));
        });
    collapse_lines_ = std::make_unique<LineRenderer>();
    checkerboard_ = make_checkerboard();
    update_texture();
    view_.camera.set_viewport(float(window_w), float(window_h));
    view_rect_ = Rect{0, 0, float(window_w), float(window_h)};
    // Recent files persist only for interactive sessions, not for scripted runs.
    if (options_.frames == 0) recent_.load(RecentFiles::default_file());
    if (options_.frames == 0) preferences_.load(Preferences::default_file());
    view_.settings.up = options_.up.empty() ? preferences_.up : parse_up_axis(options_.up, "--up");
    view_.camera.reset_rotation(view_.settings.up);
    if (options_.memory_budget_mb > 0)
        session_.set_history_budget(std::size_t(options_.memory_budget_mb) << 20);
    // The panels follow what the session did (viewer_frequency.cpp, follow_session()).
    session_.on_decomposed = [this](std::size_t lo, std::size_t hi) { on_decomposed(lo, hi); };
    follow_session();  // the built-in model: upload it, fit the view
    session_.log().info("OpenGL " +
                        std::string(reinterpret_cast<const char*>(glGetString(GL_VERSION))) +
                        " on " + reinterpret_cast<const char*>(glGetString(GL_RENDERER)));
    // Initial rendering options; bad names throw InvalidArgument before any window work.
    if (!options_.mode.empty()) view_.style.mode = parse_render_mode(options_.mode);
    if (options_.wireframe == "on")
        view_.settings.wireframe = WireframeOverlay::On;
    else if (options_.wireframe == "off")
        view_.settings.wireframe = WireframeOverlay::Off;
    else if (!options_.wireframe.empty() && options_.wireframe != "auto")
        throw InvalidArgument("--wireframe: expected on, off or auto, got '" + options_.wireframe +
                              "'");
    if (!options_.color.empty()) {
        view_.settings.coloring = parse_coloring(options_.color);
        update_coloring();
    }
    for (const std::string& text : options_.operations) {  // refuse bad ones now
        const Operation op = parse_operation(text);
        for (OperationPanelState* panel : operation_panels())  // the panel shows its values
            if (panel->op.def == op.def) panel->op = op;
    }
    open_panels(panels_, options_.show);
    initial_load_ended_ = options_.mesh_path.empty();
    if (!options_.no_recovery) start_recovery();  // --restore may start a job
    if (!options_.mesh_path.empty()) session_.execute(LoadFile{options_.mesh_path, true});
}

Viewer::~Viewer() {
    if (!options_.clicks.empty()) set_widget_hook(nullptr);
}

// ---- documents and commands -----------------------------------------------------------------

void Viewer::follow_session() {
    SessionEvents e = session_.take_events();
    for (const std::string& path : e.recent) recent_.add(path);
    if (e.loaded_proxy) {
        // The loading picture is the loaded document's proxy (a clean triangle soup): no
        // second clustering.
        const HalfedgeMesh& mesh = session_.mesh();
        const MeshKey key{mesh.topology_revision(), mesh.geometry_revision()};
        if (!proxy_.cache.count(key)) {
            proxy_.cache[key] = e.loaded_proxy;
            proxy_.cache_order.push_back(key);
        }
    }
    if (e.fit) loading_.restore_camera = false;  // a new model: its view stays
    if (e.state_changed) {
        const Document& doc = session_.document();
        surface_area_ = doc.area;
        shown_version_ = 0;  // upload what is shown again, with the new colours
        view_.colors = VertexColors{};
        // A large state is uploaded once its proxy was shown (sync_renderer, viewer_motion.cpp).
        if (session_.mesh().n_faces() < proxy_min_faces()) renderer_->show(session_.mesh());
        renderer_->clear_vertex_colors();
        if (view_.settings.coloring != VertexColoring::None) update_coloring();
        glfwSetWindowTitle(window_.get(), (doc.name + " - " + kTitle).c_str());
        if (e.fit) {
            view_.camera.reset_rotation(view_.settings.up);  // a new model: the default view
            fit_view();
        }
    }
    if (e.texture) {
        texture_ = std::move(*e.texture);
        view_.settings.use_checkerboard = false;
        update_texture();
        // A texture was asked for: show it.
        view_.style.mode = RenderMode::Textured;
        if (view_.style.texture_mode == TextureMode::Off)
            view_.style.texture_mode = TextureMode::Modulate;
    }
    if (e.texture) texture_path_ = e.texture_path;
    if (e.session_extras) apply_session_extras(*e.session_extras);
    if (e.saved && continue_after_save_) {  // a prompt's "Save and go on": now go on
        continue_after_save_ = false;
        if (panels_.unsaved.quitting)
            commands_.push_back(Quit{true});
        else
            commands_.push_back(LoadFile{panels_.unsaved.path, true});
    }
}

void Viewer::execute(const Command& command) {
    // Pictures of the scene show the exact surface, also while a large state waits for its
    // upload (viewer_motion.cpp).
    if (proxy_.exact_pending && (std::holds_alternative<TakeScreenshot>(command) ||
                                 std::holds_alternative<StartRecording>(command)))
        upload_shown();
    if (auto* c = std::get_if<LoadFile>(&command)) {
        if (c->discard_changes || confirm_discard(false, c->path)) session_.execute(command);
    } else if (auto* save_file = std::get_if<SaveFile>(&command)) {
        continue_after_save_ = save_file->then_continue;
        if (is_session_path(save_file->path))  // a session's own file: the whole session
            session_.save_session(save_file->path, session_extras());
        else
            session_.execute(command);
    } else if (auto* save_session = std::get_if<SaveSession>(&command)) {
        session_.save_session(save_session->path, session_extras());
    } else if (auto* open_session = std::get_if<OpenSession>(&command)) {
        if (open_session->discard_changes || confirm_discard(false, open_session->path))
            session_.execute(command);
    } else if (auto* recover = std::get_if<RecoverJournal>(&command)) {
        if (recover->restore) {
            session_.open_session(recover->path, true);
        } else {
            std::error_code ec;
            std::filesystem::remove(recover->path, ec);
            session_.log().info("discarded the crash journal " + recover->path);
        }
    } else if (std::holds_alternative<SaveAsAndContinue>(command)) {
        panels_.file_browser.request(FileBrowserState::Purpose::SaveMesh, session_.document().path);
        panels_.file_browser.then_continue = true;
    } else if (std::holds_alternative<FitView>(command)) {
        fit_view();
    } else if (std::holds_alternative<ClearPicks>(command)) {
        session_.clear_picks();
    } else if (std::holds_alternative<CentreOnPick>(command)) {
        if (!session_.picks().picks.empty()) {
            const Point& p = session_.picks().picks.front().position;
            view_.camera.set_target(glm::vec3(float(p.x()), float(p.y()), float(p.z())));
            camera_fitted_ = false;
        }
    } else if (std::holds_alternative<ResetView>(command)) {
        reset_view();
    } else if (std::holds_alternative<StartRecording>(command)) {
        start_recording();
    } else if (std::holds_alternative<CancelRecording>(command)) {
        finish_recording(true);
    } else if (std::holds_alternative<UpdateColoring>(command)) {
        update_coloring();
        shown_version_ = 0;  // previews and morphs take the new colours too
    } else if (std::holds_alternative<ProjectTexCoords>(command)) {
        session_.project_texcoords(view_.settings.projection, view_.settings.up);
    } else if (auto* shot = std::get_if<TakeScreenshot>(&command)) {
        take_screenshot(*shot);
    } else if (std::holds_alternative<PrintInfo>(command)) {
        for (const std::string& line : scene_info()) session_.log().info(line);
        panels_.info_open = true;
    } else if (auto* quit = std::get_if<Quit>(&command)) {
        if (quit->discard_changes || confirm_discard(true, "")) quit_ = true;
    } else if (std::holds_alternative<SaveAndContinue>(command)) {
        if (!session_.document().path.empty()) execute(SaveFile{session_.document().path, true});
    } else {  // the document's commands
        session_.execute(command);
    }
}

// ---- one frame ------------------------------------------------------------------------------

double Viewer::frame_ms() const {
    std::size_t n = std::min(n_frame_times_, frame_times_ms_.size());
    if (n == 0) return 0.0;
    auto sorted = frame_times_ms_;
    std::nth_element(sorted.begin(), sorted.begin() + n / 2, sorted.begin() + n);
    return sorted[n / 2];
}

bool Viewer::prepare_frame() {
    bool waited = false;
    // Scripted runs (--frames) show the result of the initial load, not the progress; a
    // loading picture not on the screen yet is drawn (the first picture of a large file).
    while (options_.frames > 0 && session_.jobs().busy() && !session_.preview_running()) {
        if (const auto picture = session_.loading_picture(); picture && picture != loading_.picture)
            break;
        session_.poll();
        if (session_.jobs().busy()) glfwWaitEventsTimeout(0.002);
        waited = true;
    }
    if (session_.poll()) {
        active_frames_ = kFramesAfterInput;
        if (coloring_pending_) {  // asked for while a job ran
            coloring_pending_ = false;
            commands_.push_back(UpdateColoring{});
        }
    }
    follow_session();
    journal_settings();
    advance_script();
    scripted_decomposition();
    scripted_picks();
    update_panels();
    update_inspector();
    if (sweep_.active || (!options_.sweep_op.empty() && !sweep_started_ && ready_for_script())) {
        if (!sweep_started_) {
            sweep_started_ = true;
            start_sweep();
        }
        active_frames_ = std::max(active_frames_, 1);
    }
    if (session_.jobs().busy())
        active_frames_ = std::max(active_frames_, 1);  // animate the progress

    return waited;
}

bool Viewer::draw_frame() {
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    drive_clicks();
    drive_lasso();  // --lasso: the mouse as a user draws it
    ImGui::NewFrame();
    handle_input();
    draw_ui();
    note_click_commands();
    update_motion_ui();  // the orbit's camera, the "simplified while moving" note
    ImGui::Render();

    const bool had_commands = !commands_.empty();
    for (const Command& command : commands_) execute(command);
    session_.wait_for_preview(0.1);
    follow_session();
    // Commands and popups change the UI over the next frames: keep drawing.
    if (!commands_.empty() || session_.notice().popup_pending ||
        panels_.file_browser.open_requested || panels_.context_menu_requested)
        active_frames_ = kFramesAfterInput;
    commands_.clear();

    // Textured mode on a model without texture coordinates: project them once, on the
    // shape as it is now, so that later vertex drift shows in the texture.
    if (view_.style.mode == RenderMode::Textured && !proxy_.exact_pending &&
        !renderer_->has_texcoords() && !session_.document().texcoords_projected &&
        !session_.jobs().busy())
        session_.project_texcoords(view_.settings.projection, view_.settings.up);

    if (panels_.record.running) {
        record_next_frame();
    } else {
        session_.update();
        sync_renderer();
    }
    update_wireframe();
    render_scene();
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    return had_commands;
}

int Viewer::run() {
    int frame = 0;
    int settle_frames = 0;
    double last_frame_end = -1.0;  // glfw time at the end of the last frame drawn
    bool waited = false;           // the loop slept since then (no frame to time)
    active_frames_ = kFramesAfterInput;
    while (!quit_) {
        // The window's close button asks like File -> Quit does.
        if (glfwWindowShouldClose(window_.get())) {
            glfwSetWindowShouldClose(window_.get(), GLFW_FALSE);
            commands_.push_back(Quit{});
            active_frames_ = std::max(active_frames_, 1);
        }
        // Idle viewers sleep; a timeout keeps the text cursor blinking in the open dialog.
        if (options_.frames > 0 || active_frames_ > 0) {
            glfwPollEvents();
        } else {
            glfwWaitEventsTimeout(ImGui::GetIO().WantTextInput ? 0.5 : 10.0);
            waited = true;
            if (active_frames_ == 0 && !ImGui::GetIO().WantTextInput) continue;
        }
        if (active_frames_ > 0) --active_frames_;

        if (prepare_frame()) waited = true;

        // Scripted runs: the last frame comes once everything started has ended (jobs,
        // previews, the morph animation, the scripted actions), so screenshots show results.
        const bool scripted_end = options_.frames > 0 && frame + 1 >= options_.frames;
        const bool settled = scripted_end && script_settled();

        const double start = glfwGetTime();
        const bool had_commands = draw_frame();

        ++frame;
        if (frame == options_.close_after) glfwSetWindowShouldClose(window_.get(), GLFW_TRUE);
        bool last =
            settled && !had_commands && !session_.jobs().busy() && !session_.morph().playing;
        if (scripted_end && !last && ++settle_frames > kMaxSettleFrames) {
            session_.log().warning("still busy after " + std::to_string(kMaxSettleFrames) +
                                   " extra frames: the last frame may show an unfinished state");
            last = true;
        }
        if (last && options_.print_layout) print_layout();
        if (last && !options_.screenshot.empty()) {
            std::string error = write_screenshot(options_.screenshot);
            if (!error.empty()) {
                std::fprintf(stderr, "trilab: %s\n", error.c_str());
                session_.close_journal();
                return 1;
            }
        }
        // The frame is on the screen when we time it (sweeps, the orbit, --print-timing).
        if (sweep_.active || (options_.orbit_frames > 0 && !orbit_.done) ||
            (options_.print_timing && exact_frame_ms_ < 0))
            glFinish();
        glfwSwapBuffers(window_.get());
        // The frame time is the time from one frame's end to the next's: the GL driver may
        // finish a frame's work in the next frame's first calls (a software renderer does), so
        // the time inside one loop pass can be a fraction of it. After a sleep (no events)
        // the pass alone counts.
        const double end = glfwGetTime();
        const double since = waited || last_frame_end < 0 ? end - start : end - last_frame_end;
        frame_times_ms_[n_frame_times_++ % frame_times_ms_.size()] = 1000.0 * since;
        last_frame_end = end;
        waited = false;
        note_frame_end(1000.0 * since);
        // A spectral prediction on the screen lets its exact job start (with the next frame).
        if (proxy_.shows_current) session_.prediction_drawn();
        if (sweep_.active)
            step_sweep(proxy_.shows_current && (session_.shown().kind == Shown::Kind::Preview ||
                                                session_.shown().kind == Shown::Kind::Level));
        if (last) break;
    }
    if (options_.frames > 0) log_last_frame();
    if (options_.print_timing) print_timing();
    if (!options_.save_session.empty()) {
        const std::string error = save_session_now();
        if (!error.empty()) {
            std::fprintf(stderr, "trilab: --save-session: %s\n", error.c_str());
            exit_status_ = 1;
        }
    }
    session_.log().info(quit_ ? "quit after " + std::to_string(frame) + " frames" : "frames done");
    session_.close_journal();  // a clean exit: nothing to recover
    return exit_status_;
}

}  // namespace trilab::viewer
