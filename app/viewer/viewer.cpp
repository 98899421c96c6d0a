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
namespace {

constexpr const char* kTitle = "trilab";
/// ImGui settles hover and popups within a few frames.
constexpr int kFramesAfterInput = 4;
constexpr std::size_t kColoringJobFaces = 200000;  ///< larger meshes colour in a job
/// The automatic wireframe overlay is on while a typical edge is at least this many line
/// widths long on the screen, and goes off below the second figure (no flicker at the edge).
constexpr double kWireOnLineWidths = 10.0, kWireOffLineWidths = 8.0;
/// Scripted runs wait at most this many extra frames for jobs and morphs to end.
constexpr int kMaxSettleFrames = 1000;

void glfw_error(int code, const char* description) {
    std::fprintf(stderr, "trilab: GLFW error %d: %s\n", code, description);
}

glm::vec3 to_glm(const Point& p) {
    return glm::vec3(float(p.x()), float(p.y()), float(p.z()));
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
    if (!options_.operation.empty()) {  // refuse bad ones now; the panel shows its values
        const Operation op = parse_operation(options_.operation);
        for (OperationPanelState* panel : operation_panels())
            if (panel->op.def == op.def) panel->op = op;
    }
    for (std::size_t pos = 0; pos < options_.show.size();) {
        std::size_t comma = options_.show.find(',', pos);
        if (comma == std::string::npos) comma = options_.show.size();
        const std::string panel = options_.show.substr(pos, comma - pos);
        pos = comma + 1;
        if (panel == "all") {  // every panel (not the dialogs)
            panels_.history_open = panels_.morph_open = panels_.log_open = true;
            panels_.info_open = panels_.tools.open = panels_.weld.open = panels_.fairing.open =
                true;
            panels_.subdivision.open = panels_.frequency.open = true;
            panels_.decimation.open = panels_.record.open = true;
        } else if (panel == "help")
            panels_.help_open = true;
        else if (panel == "about")
            panels_.about_open = true;
        else if (panel == "screenshot")
            panels_.screenshot.open = true;
        else if (panel == "history")
            panels_.history_open = true;
        else if (panel == "morph")
            panels_.morph_open = true;
        else if (panel == "tools")
            panels_.tools.open = true;
        else if (panel == "weld")
            panels_.weld.open = true;
        else if (panel == "fairing")
            panels_.fairing.open = true;
        else if (panel == "subdivision")
            panels_.subdivision.open = true;
        else if (panel == "frequency")
            panels_.frequency.open = true;
        else if (panel == "decimation")
            panels_.decimation.open = true;
        else if (panel == "collapsing-edges")
            panels_.decimation.show_collapsing_edges = true;
        else if (panel == "record")
            panels_.record.open = true;
        else if (panel == "log")
            panels_.log_open = true;
        else if (panel == "info")
            panels_.info_open = true;
        else
            throw InvalidArgument(
                "--show: unknown panel '" + panel +
                "' (all, history, morph, tools, weld, subdivision, fairing, frequency, "
                "decimation, collapsing-edges, record, log, info, help, about, screenshot)");
    }
    initial_load_ended_ = options_.mesh_path.empty();
    if (!options_.mesh_path.empty()) session_.execute(LoadFile{options_.mesh_path, true});
}

Viewer::~Viewer() {
    if (!options_.clicks.empty()) set_widget_hook(nullptr);
}

// ---- documents and commands -----------------------------------------------------------------

std::vector<OperationPanelState*> Viewer::operation_panels() {
    return {&panels_.subdivision, &panels_.fairing, &panels_.decimation, &panels_.tools,
            &panels_.weld};
}

void Viewer::follow_session() {
    SessionEvents e = session_.take_events();
    for (const std::string& path : e.recent) recent_.add(path);
    if (e.state_changed) {
        const Document& doc = session_.document();
        surface_area_ = doc.area;
        shown_version_ = 0;  // upload what is shown again, with the new colours
        view_.colors = VertexColors{};
        renderer_->show(session_.mesh());
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
    if (e.saved && continue_after_save_) {  // a prompt's "Save and go on": now go on
        continue_after_save_ = false;
        if (panels_.unsaved.quitting)
            commands_.push_back(Quit{true});
        else
            commands_.push_back(LoadFile{panels_.unsaved.path, true});
    }
}

void Viewer::advance_script() {
    // The initial load has ended (or failed): --op runs on what it loaded.
    if (!initial_load_ended_ && !session_.busy()) initial_load_ended_ = true;
    if (initial_load_ended_ && !initial_op_done_) {
        initial_op_done_ = true;
        const bool loaded =
            options_.mesh_path.empty() || session_.document().path == options_.mesh_path;
        if (!options_.operation.empty() && loaded)
            commands_.push_back(RunOperation{parse_operation(options_.operation)});
    }
}

void Viewer::sync_renderer() {
    const Shown& shown = session_.shown();
    if (shown.version == shown_version_) return;
    const Shown::Kind before = shown_kind_;
    shown_version_ = shown.version;
    shown_kind_ = shown.kind;
    active_frames_ = std::max(active_frames_, 2);
    try {
        switch (shown.kind) {
            case Shown::Kind::Document:
                renderer_->show(*shown.mesh);
                apply_colors(std::move(view_.colors));
                break;
            case Shown::Kind::Preview:
                // Geometry-only previews (fairing, noise) move the vertices already on the GPU:
                // the renderer compares revisions and uploads only what changed.
                if (renderer_->show(*shown.mesh) == MeshRenderer::Update::Full) {
                    const std::vector<Point> reference =
                        session_.mesh().vertices_size() == shown.mesh->vertices_size()
                            ? session_.mesh().positions()
                            : std::vector<Point>{};
                    show_colors_of(*shown.mesh, reference);
                }
                break;
            case Shown::Kind::Morph:
                // The morph's first frame, or a new connectivity: upload it once (unless the GPU
                // holds it already); colours are computed on it at its own (final) shape, so
                // each vertex keeps its colour while it moves.
                if (before != Shown::Kind::Morph || !renderer_->shows_topology_of(*shown.mesh)) {
                    if (!renderer_->shows_topology_of(*shown.mesh)) renderer_->upload(*shown.mesh);
                    show_colors_of(*shown.mesh, session_.reference_positions());
                }
                renderer_->update_positions(*shown.mesh, shown.positions);
                break;
            case Shown::Kind::Level:
                if (before == Shown::Kind::Level)
                    renderer_->update_level(*shown.level);
                else
                    renderer_->upload_level(*shown.level);
                break;
            case Shown::Kind::Band:
                renderer_->show(*shown.mesh);
                renderer_->update_positions(*shown.mesh, shown.positions);
                break;
        }
    } catch (const std::exception& e) {
        session_.notify_error(std::string("view: ") + e.what());
    }
}

void Viewer::show_colors_of(const HalfedgeMesh& mesh, const std::vector<Point>& reference) {
    if (view_.settings.coloring == VertexColoring::None) return;
    const VertexColors colors =
        coloring_needs_field(view_.settings.coloring)
            ? frequency_colors(mesh)
            : color_vertices(mesh, view_.settings.coloring, view_.settings.coloring_options,
                             reference.empty() ? nullptr : &reference);
    if (colors.colors.empty())
        renderer_->clear_vertex_colors();
    else
        renderer_->set_vertex_colors(colors.colors, color_blend(colors.kind));
}

bool Viewer::ready_for_script() const {
    // The initial load and --op are done (queued) and no job runs.
    return !session_.jobs().busy() && initial_load_ended_ && initial_op_done_ && commands_.empty();
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
    const int op = int(f.op.value("operator").x);
    const HalfedgeMesh::Revision state = session_.mesh().revision();
    // A preview of this state reports it (any size); small meshes get it at once.
    const OperationResult* preview = session_.preview_result();
    const std::optional<Operation>& requested = session_.preview_requested();
    if (preview && requested && requested->def == f.op.def &&
        int(requested->value("operator").x) == op) {
        for (const auto& [key, value] : preview->values)
            if (key == "max_stable_step" && std::isfinite(value)) f.max_stable_step = value;
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

void Viewer::start_recording() {
    RecordState& r = panels_.record;
    const History& h = session_.history();
    if (h.current() == 0 || r.running) return;
    std::error_code ec;
    std::filesystem::create_directories(r.folder, ec);
    if (ec || !std::filesystem::is_directory(r.folder)) {
        session_.notify_error("record: cannot create the folder " + r.folder);
        return;
    }
    // Framed as the view, fixed for all frames.
    record_camera_ = view_.camera;
    record_camera_.reframe_for_viewport(float(r.width), float(r.height));
    int x = 0, y = 0, view_w = 0, view_h = 0;
    view_viewport(x, y, view_w, view_h);
    record_line_scale_ =
        ui_scale_ * std::min(float(r.width) / float(view_w), float(r.height) / float(view_h));
    session_.morph().playing = false;
    r.running = true;
    r.next = 0;
    session_.log().info("recording " + std::to_string(r.frames) + " frames to " + r.folder);
}

void Viewer::record_next_frame() {
    RecordState& r = panels_.record;
    if (!r.running) return;
    active_frames_ = std::max(active_frames_, 1);
    try {
        // Show frame `next` of the morph (this also updates the window).
        session_.morph().t = r.frames > 1 ? double(r.next) / double(r.frames - 1) : 1.0;
        session_.update();
        sync_renderer();
        Framebuffer framebuffer;
        framebuffer.create(r.width, r.height, 4);
        framebuffer.bind();
        RenderStyle style = view_.style;
        style.wire_width *= record_line_scale_;
        style.point_size *= record_line_scale_;
        clear_background(style);
        renderer_->draw(record_camera_.view(), record_camera_.projection(), style);
        Image image = framebuffer.read_rgba();
        Framebuffer::bind_default();
        write_png(
            image,
            (std::filesystem::path(r.folder) / record::frame_file_name(r.name, r.next)).string());
    } catch (const std::exception& e) {
        Framebuffer::bind_default();
        session_.notify_error(std::string("record: ") + e.what());
        finish_recording(true);
        return;
    }
    if (++r.next >= r.frames) finish_recording(false);
}

void Viewer::finish_recording(bool cancelled) {
    RecordState& r = panels_.record;
    r.running = false;
    if (cancelled) {
        session_.log().warning("recording stopped after " + std::to_string(r.next) + " frames");
        return;
    }
    session_.log().info("recorded " + std::to_string(r.frames) + " frames in " + r.folder);
    if (!r.mp4) return;
    if (std::system("command -v ffmpeg > /dev/null 2>&1") != 0) {
        session_.log().warning("no ffmpeg on the PATH: the PNG frames are written, no MP4");
        return;
    }
    const std::string pattern = (std::filesystem::path(r.folder) / (r.name + "_%04d.png")).string();
    const std::string mp4 = (std::filesystem::path(r.folder) / (r.name + ".mp4")).string();
    const std::string command = "ffmpeg -y -loglevel error -framerate " + std::to_string(r.fps) +
                                " -i '" + pattern +
                                "' -vf 'pad=ceil(iw/2)*2:ceil(ih/2)*2' -c:v libx264 -pix_fmt "
                                "yuv420p '" +
                                mp4 + "'";
    if (std::system(command.c_str()) == 0)
        session_.log().info("wrote " + mp4);
    else
        session_.log().warning("ffmpeg failed; the PNG frames are in " + r.folder);
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

void Viewer::reset_view() {
    const UpAxis up = view_.settings.up;
    view_.camera.reset_rotation(up);
    fit_view();
    if (preferences_.up != up) {
        preferences_.up = up;
        preferences_.save();
        session_.log().info(std::string("up axis: +") + up_axis_name(up) +
                            " (the default view and the spherical texture projection)");
        // Coordinates the viewer projected around the other axis follow (a history entry).
        if (session_.document().texcoords_projected &&
            view_.settings.projection == TexCoordProjection::Spherical)
            session_.project_texcoords(view_.settings.projection, view_.settings.up);
    }
}

void Viewer::fit_view() {
    const HalfedgeMesh& mesh = session_.mesh();
    BoundingBox box = bounding_box(mesh);
    fit_center_ = glm::vec3(0.0f);
    fit_radius_ = 1.0f;
    if (!box.empty) {
        // The smallest sphere around the box centre that holds every vertex: tighter than the
        // box's own bounding sphere, so round models fill the view.
        Point center = box.center();
        double radius2 = 0.0;
        for (Vertex v : mesh.vertices())
            radius2 = std::max(radius2, (mesh.position(v) - center).squaredNorm());
        fit_center_ = to_glm(center);
        fit_radius_ = float(std::sqrt(radius2));
    }
    view_.camera.set_viewport(std::max(view_rect_.w, 1.0f), std::max(view_rect_.h, 1.0f));
    view_.camera.fit_sphere(fit_center_, fit_radius_);
    camera_fitted_ = true;
}

void Viewer::apply_colors(VertexColors colors) {
    view_.colors = std::move(colors);
    if (view_.settings.coloring == VertexColoring::None || view_.colors.colors.empty())
        renderer_->clear_vertex_colors();
    else
        renderer_->set_vertex_colors(view_.colors.colors, color_blend(view_.colors.kind));
}

void Viewer::update_coloring() {
    const VertexColoring coloring = view_.settings.coloring;
    const ColoringOptions options = view_.settings.coloring_options;
    if (coloring == VertexColoring::None) {
        apply_colors(VertexColors{});
        return;
    }
    if (coloring_needs_field(coloring)) {  // from the decomposition: cheap, on this thread
        VertexColors colors = frequency_colors(session_.mesh());
        if (colors.colors.empty())
            session_.notice() =
                Notice{Notice::Level::Info,
                       "the frequency colourings need a decomposition (Algorithms > "
                       "Frequency decomposition)",
                       {},
                       false};
        apply_colors(std::move(colors));
        return;
    }
    auto reference = std::make_shared<const std::vector<Point>>(
        coloring == VertexColoring::SmoothingDistance ? session_.reference_positions()
                                                      : std::vector<Point>{});
    if (session_.mesh().n_faces() < kColoringJobFaces) {
        apply_colors(color_vertices(session_.mesh(), coloring, options, reference.get()));
        return;
    }
    // Large meshes: compute on the worker; the document cannot change while a job runs.
    if (session_.jobs().busy()) {  // e.g. dragging the legend's range: colour again when it is done
        coloring_pending_ = true;
        return;
    }
    const HalfedgeMesh snapshot = session_.mesh();  // copy-on-write: the job's own
    const bool started =
        session_.jobs().start(std::string("Colouring by ") + coloring_name(coloring),
                              [this, coloring, options, reference, snapshot](Progress&) {
                                  auto colors = std::make_shared<VertexColors>(
                                      color_vertices(snapshot, coloring, options, reference.get()));
                                  return JobRunner::Finish([this, colors, coloring] {
                                      // Ignore a result the user has already replaced.
                                      if (view_.settings.coloring == coloring)
                                          apply_colors(std::move(*colors));
                                  });
                              });
    if (!started)
        session_.notify_error("busy: wait for \"" + session_.jobs().name() + "\" or cancel it");
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

void Viewer::update_texture() {
    const Image& image =
        view_.settings.use_checkerboard || texture_.empty() ? checkerboard_ : texture_;
    try {
        renderer_->set_texture(image);
    } catch (const std::exception& e) {
        session_.notify_error(std::string("texture: ") + e.what());
    }
}

void Viewer::take_screenshot(const TakeScreenshot& request) {
    try {
        Framebuffer framebuffer;
        framebuffer.create(request.width, request.height, 4);
        framebuffer.bind();
        RenderStyle style = view_.style;
        // Framed as the view; line widths and point sizes keep their look relative to it.
        int x = 0, y = 0, view_w = 0, view_h = 0;
        view_viewport(x, y, view_w, view_h);
        const float scale =
            std::min(float(request.width) / float(view_w), float(request.height) / float(view_h));
        style.wire_width *= ui_scale_ * scale;
        style.point_size *= ui_scale_ * scale;
        clear_background(style, request.transparent ? 0.0f : 1.0f);
        Camera camera = view_.camera;
        camera.reframe_for_viewport(float(request.width), float(request.height));
        renderer_->draw(camera.view(), camera.projection(), style);
        Image image = framebuffer.read_rgba();
        Framebuffer::bind_default();
        if (request.transparent) unpremultiply_alpha(image);
        write_png(image, request.path);
        session_.log().info("screenshot " + request.path + " (" + std::to_string(request.width) +
                            " x " + std::to_string(request.height) + ")");
        session_.notice() = Notice{Notice::Level::Info, "Saved " + request.path, {}, false};
    } catch (const std::exception& e) {
        Framebuffer::bind_default();
        session_.notify_error(std::string("screenshot: ") + e.what());
    }
}

void Viewer::execute(const Command& command) {
    if (auto* c = std::get_if<LoadFile>(&command)) {
        if (c->discard_changes || confirm_discard(false, c->path)) session_.execute(command);
    } else if (auto* save_file = std::get_if<SaveFile>(&command)) {
        continue_after_save_ = save_file->then_continue;
        session_.execute(command);
    } else if (std::holds_alternative<SaveAsAndContinue>(command)) {
        panels_.file_browser.request(FileBrowserState::Purpose::SaveMesh, session_.document().path);
        panels_.file_browser.then_continue = true;
    } else if (std::holds_alternative<FitView>(command)) {
        fit_view();
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
        if (!session_.document().path.empty()) {
            continue_after_save_ = true;
            session_.execute(SaveFile{session_.document().path});
        }
    } else {  // the document's commands
        session_.execute(command);
    }
}

// ---- one frame ------------------------------------------------------------------------------

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
        if (ImGui::IsMouseDoubleClicked(ImGuiMouseButton_Left) && in_view) {
            commands_.push_back(FitView{});
        } else if (moved && drag_in_view_ && ImGui::IsMouseDown(ImGuiMouseButton_Left) &&
                   !io.KeyShift) {
            camera.rotate(pos - delta, pos);
            camera_fitted_ = false;
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
    FrequencyActions frequency;
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
        frequency = sidebar_sections(panels_, session_.morph(), sidebar, commands_);
    }
    if (panels_.sidebar_open) end_region();
    frequency_actions(frequency);
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
    if (color_legend(view_.colors, view_.settings.coloring_options, slot))
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
}

void Viewer::view_viewport(int& x, int& y, int& w, int& h) const {
    // The backend reads the window and framebuffer sizes once a frame; no X round trip here.
    const ImGuiIO& io = ImGui::GetIO();
    const float sx = io.DisplayFramebufferScale.x, sy = io.DisplayFramebufferScale.y;
    const int fb_h = int(std::lround(io.DisplaySize.y * sy));
    x = int(std::lround(view_rect_.x * sx));
    w = std::max(1, int(std::lround(view_rect_.w * sx)));
    h = std::max(1, int(std::lround(view_rect_.h * sy)));
    y = fb_h - int(std::lround(view_rect_.y * sy)) - h;  // GL counts rows from the bottom
}

void Viewer::update_wireframe() {
    RenderStyle& style = view_.style;
    // A typical edge of the shown mesh: the side of an equilateral triangle of the mean
    // triangle area (the current state's area over the shown triangles, so previews,
    // morphs and levels of detail count their own density). Two multiplications a frame.
    const std::size_t triangles = renderer_->n_triangles();
    edge_pixels_ = 0;
    if (triangles > 0 && surface_area_ > 0) {
        const double edge = std::sqrt(4.0 * surface_area_ / (std::sqrt(3.0) * double(triangles)));
        edge_pixels_ = edge * double(view_.camera.pixels_per_unit()) *
                       double(ImGui::GetIO().DisplayFramebufferScale.y);
    }
    const double line = std::max(1.0, double(style.wire_width * ui_scale_));
    wire_auto_on_ = edge_pixels_ >= (wire_auto_on_ ? kWireOffLineWidths : kWireOnLineWidths) * line;
    switch (view_.settings.wireframe) {
        case WireframeOverlay::On:
            style.wireframe = true;
            break;
        case WireframeOverlay::Off:
            style.wireframe = false;
            break;
        case WireframeOverlay::Auto:
            style.wireframe = wire_auto_on_;
            break;
    }
}

void Viewer::render_scene() {
    int fb_w = 0, fb_h = 0;
    glfwGetFramebufferSize(window_.get(), &fb_w, &fb_h);
    glViewport(0, 0, fb_w, fb_h);
    clear_background(view_.style);
    if (fb_w <= 0 || fb_h <= 0 || view_rect_.empty()) return;  // minimized
    int x = 0, y = 0, w = 0, h = 0;
    view_viewport(x, y, w, h);
    glViewport(x, y, w, h);

    RenderStyle style = view_.style;
    style.wire_width *= ui_scale_;
    style.point_size *= ui_scale_;
    renderer_->draw(view_.camera.view(), view_.camera.projection(), style);
    if (panels_.decimation.show_collapsing_edges)
        collapse_lines_->draw(view_.camera.view(), view_.camera.projection(), LineStyle{},
                              ui_scale_);
    glViewport(0, 0, fb_w, fb_h);  // ImGui draws over the whole window
}

void Viewer::update_collapsing_edges() {
    const DecimationPanelState& d = panels_.decimation;
    if (!d.show_collapsing_edges) return;
    const HalfedgeMesh& mesh = session_.mesh();
    // The mesh state (its topology and geometry revisions) and the options the edges were
    // computed for.
    const std::string key = std::to_string(mesh.topology_revision()) + " " +
                            std::to_string(mesh.geometry_revision()) + " " + d.op.text();
    if (key == collapse_key_) return;
    collapse_key_ = key;
    std::vector<glm::vec3> points;
    // Computed on the render thread: a dry run of the next iteration, a fraction of a second
    // up to a few hundred thousand vertices; bigger meshes skip the overlay.
    constexpr std::size_t kMaxOverlayVertices = 300000;
    if (mesh.n_vertices() > kMaxOverlayVertices) {
        session_.log().warning("Collapsing edges: shown for meshes of up to 300,000 vertices only");
        collapse_lines_->set_segments(points);
        return;
    }
    try {
        const DecimationOptions o = decimation_options(d.op);
        for (const auto& pair : next_collapses(mesh, o)) {
            const Point& a = mesh.position(pair[0]);
            const Point& b = mesh.position(pair[1]);
            points.emplace_back(float(a.x()), float(a.y()), float(a.z()));
            points.emplace_back(float(b.x()), float(b.y()), float(b.z()));
        }
    } catch (const Error& e) {
        session_.notify_error(std::string("Collapsing edges: ") + e.what());
    }
    collapse_lines_->set_segments(points);
}

std::string Viewer::write_screenshot(const std::string& path) const {
    int w = 0, h = 0;
    glfwGetFramebufferSize(window_.get(), &w, &h);
    if (w <= 0 || h <= 0) return "the window has no pixels";
    Image image;
    image.width = w;
    image.height = h;
    image.rgba.resize(std::size_t(w) * std::size_t(h) * 4);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, image.rgba.data());
    // GL rows go bottom-up; images top-down.
    const std::size_t row = std::size_t(w) * 4;
    for (int y = 0; y < h / 2; ++y)
        std::swap_ranges(image.rgba.begin() + std::ptrdiff_t(y * row),
                         image.rgba.begin() + std::ptrdiff_t((y + 1) * row),
                         image.rgba.begin() + std::ptrdiff_t((h - 1 - y) * row));
    for (std::size_t i = 3; i < image.rgba.size(); i += 4) image.rgba[i] = 255;
    try {
        write_png(image, path);
    } catch (const std::exception& e) {
        return e.what();
    }
    return "";
}

double Viewer::frame_ms() const {
    std::size_t n = std::min(n_frame_times_, frame_times_ms_.size());
    if (n == 0) return 0.0;
    auto sorted = frame_times_ms_;
    std::nth_element(sorted.begin(), sorted.begin() + n / 2, sorted.begin() + n);
    return sorted[n / 2];
}

std::pair<std::size_t, std::size_t> Viewer::shown_counts() const {
    const Shown& shown = session_.shown();
    if (shown.kind == Shown::Kind::Level)
        return {shown.level->vertices(), renderer_->n_triangles()};
    return {shown.mesh->n_vertices(), shown.mesh->n_faces()};
}

bool Viewer::script_settled() {
    if (session_.jobs().busy() || !commands_.empty() || session_.preview_pending() ||
        !ready_for_script() || sweep_.active || panels_.record.running)
        return false;
    if (!options_.decompose.empty() && scripted_decompose_ != 2) return false;
    if (clicks_pending()) return false;
    if (!options_.sweep_op.empty() && !sweep_started_) return false;
    if (session_.morph().playing) {  // end it: the next frame shows where it ends
        session_.morph().t = 1.0;
        session_.morph().playing = false;
        return false;
    }
    if (options_.morph_t >= 0 && !morph_t_done_) {
        morph_t_done_ = true;
        if (session_.history().current() == 0 || !session_.morph().moves)
            session_.log().warning("--morph-t: the current state has no morph to show");
        session_.morph().t = options_.morph_t;
        session_.morph().playing = false;
        return false;
    }
    return true;
}

void Viewer::print_layout() const {
    int fb_w = 0, fb_h = 0;
    glfwGetFramebufferSize(window_.get(), &fb_w, &fb_h);
    const ImGuiIO& io = ImGui::GetIO();
    const float sx = io.DisplayFramebufferScale.x, sy = io.DisplayFramebufferScale.y;
    // Whole pixels that contain the rectangle (the test checks the rule on these).
    auto line = [&](const char* what, float x, float y, float w, float h) {
        const long x0 = std::lround(std::floor(x * sx)), y0 = std::lround(std::floor(y * sy));
        const long x1 = std::lround(std::ceil((x + w) * sx));
        const long y1 = std::lround(std::ceil((y + h) * sy));
        std::printf("%s %ld %ld %ld %ld\n", what, x0, y0, x1 - x0, y1 - y0);
    };
    std::printf("framebuffer %d %d\n", fb_w, fb_h);
    line("view", view_rect_.x, view_rect_.y, view_rect_.w, view_rect_.h);
    // Every window ImGui drew in the last frame, except child windows (inside their parent)
    // and tooltips (they follow the mouse).
    for (const ImGuiWindow* w : ImGui::GetCurrentContext()->Windows) {
        if (!w->Active || w->Hidden) continue;
        if (w->Flags & (ImGuiWindowFlags_ChildWindow | ImGuiWindowFlags_Tooltip)) continue;
        std::string title = w->Name;
        for (char& c : title)
            if (c == '"') c = '\'';
        const std::string what = "window \"" + title + "\"";
        line(what.c_str(), w->Pos.x, w->Pos.y, w->Size.x, w->Size.y);
    }
    std::fflush(stdout);
}

void Viewer::log_last_frame() {
    char buf[96];
    std::snprintf(buf, sizeof(buf), "median frame time %.1f ms over the last %zu frames",
                  frame_ms(), std::min(n_frame_times_, frame_times_ms_.size()));
    session_.log().info(buf);
    // What the last frame showed, for scripts and tests.
    const History& h = session_.history();
    std::string entries;
    for (std::size_t i = 0; i < h.size() && i < 20; ++i)
        entries += (i ? " | " : "") + std::to_string(i) + " " + h.info(i).label;
    session_.log().info("history: " + entries);
    std::snprintf(buf, sizeof(buf), ", morph t = %.3f", session_.morph().t);
    session_.log().info("last frame: " + session_.document().info[1] + buf);
    const char* setting = view_.settings.wireframe == WireframeOverlay::Auto ? "automatic"
                          : view_.settings.wireframe == WireframeOverlay::On ? "on"
                                                                             : "off";
    std::snprintf(buf, sizeof(buf), "wireframe overlay %s (%s; edges %.1f px on the screen)",
                  view_.style.wireframe ? "on" : "off", setting, edge_pixels_);
    session_.log().info(buf);
    session_.log().info("status: " + session_.notice().text);
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

        // Scripted runs (--frames) show the result of the initial load, not the progress.
        while (options_.frames > 0 && session_.jobs().busy() && !session_.preview_running()) {
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
        advance_script();
        update_panels();
        if (sweep_.active ||
            (!options_.sweep_op.empty() && !sweep_started_ && ready_for_script())) {
            if (!sweep_started_) {
                sweep_started_ = true;
                start_sweep();
            }
            active_frames_ = std::max(active_frames_, 1);
        }
        if (session_.jobs().busy())
            active_frames_ = std::max(active_frames_, 1);  // animate the progress

        // Scripted runs: the last frame comes once everything started has ended (jobs,
        // previews, the morph animation, the scripted actions), so screenshots show results.
        const bool scripted_end = options_.frames > 0 && frame + 1 >= options_.frames;
        const bool settled = scripted_end && script_settled();

        const double start = glfwGetTime();
        ImGui_ImplOpenGL3_NewFrame();
        ImGui_ImplGlfw_NewFrame();
        drive_clicks();
        ImGui::NewFrame();
        handle_input();
        draw_ui();
        note_click_commands();
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
        if (view_.style.mode == RenderMode::Textured && !renderer_->has_texcoords() &&
            !session_.document().texcoords_projected && !session_.jobs().busy())
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
                return 1;
            }
        }
        if (sweep_.active) glFinish();  // the frame is on the screen when we time it
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
        if (sweep_.active)
            step_sweep(session_.shown().kind == Shown::Kind::Preview ||
                       session_.shown().kind == Shown::Kind::Level);
        if (last) break;
    }
    if (options_.frames > 0) log_last_frame();
    session_.log().info(quit_ ? "quit after " + std::to_string(frame) + " frames" : "frames done");
    return exit_status_;
}

}  // namespace trilab::viewer
