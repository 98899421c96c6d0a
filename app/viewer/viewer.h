#pragma once
// Viewer: the trilab window. Owns the GLFW window and GL context, the ImGui layer, the
// document (the mesh being shown), the view (camera and render style) and the panel state,
// and runs the frame loop. Panels edit their own state and queue commands; the viewer
// executes the commands, so loading, fitting and quitting happen in one place.
#include <array>
#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/history/history.h"
#include "app/viewer/frequency_panel.h"
#include "app/viewer/job_runner.h"
#include "app/viewer/log.h"
#include "app/viewer/panels.h"
#include "core/algorithms/level_of_detail.h"
#include "core/halfedge_mesh.h"
#include "core/io/image_io.h"
#include "core/mesh_builder.h"
#include "render/camera.h"
#include "render/line_renderer.h"
#include "render/mesh_renderer.h"

struct GLFWwindow;

namespace trilab::viewer {

/// Command-line options (see kUsage in main.cpp).
struct ViewerOptions {
    std::string mesh_path;   ///< empty: the built-in default model
    int frames = 0;          ///< > 0: render that many frames, then return 0
    int close_after = 0;     ///< > 0: press the window's close button after that many frames
    std::string screenshot;  ///< non-empty: write the last frame (before the swap) as PNG
    /// Print "framebuffer W H", "view X Y W H" and one `window "TITLE" X Y W H` line per
    /// visible window after the last frame (framebuffer pixels).
    bool print_layout = false;
    float ui_scale = 0;     ///< > 0: the UI (font) scale instead of the monitor's
    std::string wireframe;  ///< "on", "off" or "auto" (default)
    double morph_t = -1;    ///< in [0, 1]: show the current entry's morph at this time
    int width = 1280;       ///< window size in screen coordinates
    int height = 800;
    std::string mode;          ///< initial render mode name (render_mode_name()), empty: default
    std::string color;         ///< initial vertex colouring name (coloring_name()), empty: none
    std::string operation;     ///< an operation to apply after loading, empty: none
    std::string show;          ///< panels to open at start, comma-separated
    int memory_budget_mb = 0;  ///< the history's budget; 0: a quarter of the RAM
    std::string decompose;     ///< "K" or "K:LO:HI": Frequency panel Decompose (and a band)
    std::string up;            ///< "y" or "z": the up axis for this run; empty: the remembered one
    /// --sweep OP --param NAME --range FROM:TO:COUNT: preview OP with NAME at COUNT evenly
    /// spaced values, print "sweep: previews=N median_ms=X max_ms=Y" and exit.
    std::string sweep_op, sweep_param;
    /// --click "SECTION/LABEL" (repeatable): widgets to press, in order, after --op.
    std::vector<std::string> clicks;
    double sweep_from = 0, sweep_to = 0;
    int sweep_count = 0;
};

/// The model: its history of states (the current one is shown) and where it came from.
struct Document {
    History history;
    const HalfedgeMesh& mesh() const { return history.current_mesh(); }
    std::string name;               ///< file name, or "default model"
    std::string path;               ///< file path; empty for the default model
    LoadReport report;              ///< what loading it did (empty for built-in models)
    std::vector<std::string> info;  ///< model information lines, computed once per document
    bool closed = false;            ///< the current state has no boundary (volume is defined)
    bool open_seams = false;  ///< coincident boundary edges: unwelded seams (Subdivision's note)
    bool texcoords_projected = false;  ///< texture coordinates were computed by projection
    /// The current state differs from the file it came from or was last saved to (any
    /// operation, undo, redo or jump since; conservative: undoing back still counts).
    bool unsaved = false;
    FrequencyDocument frequency;  ///< the last frequency decomposition (Frequency panel)
};

/// How the document is looked at.
struct ViewState {
    Camera camera;
    RenderStyle style;
    ViewSettings settings;
    VertexColors colors;  ///< the current vertex colouring (empty colors: none uploaded)
};

class Viewer {
public:
    /// Opens the window, creates the GL context and ImGui, uploads the default model and,
    /// when options.mesh_path is set, loads that file (a load error becomes a notice, not an
    /// exception). Throws trilab::Error when no window or GL 3.3 core context can be had or
    /// the shaders fail.
    explicit Viewer(ViewerOptions options);
    ~Viewer();
    Viewer(const Viewer&) = delete;
    Viewer& operator=(const Viewer&) = delete;

    /// Runs until the window closes, Quit, or options.frames frames. Returns the exit status:
    /// 0, or 1 when the screenshot cannot be written.
    int run();

private:
    struct GlfwLibrary;
    struct WindowDeleter {
        void operator()(GLFWwindow* window) const;
    };
    struct ImGuiLayer;

    /// A key press as GLFW reported it. Shortcuts are read from these rather than from
    /// ImGui's key state, which (before ImGui 1.87) misses a press and release that fall
    /// into the same frame.
    struct KeyPress {
        int key;
        int mods;
    };

    static GLFWwindow* create_window(const ViewerOptions& options, Viewer* viewer);
    static Viewer* from(GLFWwindow* window);
    static void wake(GLFWwindow* window);

    void handle_input();
    void draw_ui();
    /// Scripted runs (--frames): whether the last frame may be drawn now (no job, preview,
    /// morph animation or scripted action still running). Finishes a playing morph.
    bool script_settled();
    /// Scripted runs: what the last frame showed (history, state, wireframe, status) and the
    /// median frame time, for scripts and tests.
    void log_last_frame();
    /// --print-layout: the framebuffer, the view and every visible window.
    void print_layout() const;
    /// Decides the wireframe overlay for this frame (view_.settings.wireframe).
    void update_wireframe();
    /// Whether the current history entry moves any vertex (for the morph controls).
    bool entry_moves() const;
    /// The view region (layout.h) in framebuffer pixels, GL's origin (bottom left).
    void view_viewport(int& x, int& y, int& w, int& h) const;
    void execute(const Command& command);
    /// Starts a job that reads `path`; the document changes when it succeeds.
    void load(const std::string& path);
    /// Starts a job that writes a copy of the document to `path`.
    void save(const std::string& path);
    void load_texture(const std::string& path);
    /// Applies a finished job (or its failure) on the render thread.
    void poll_jobs();
    /// Pushes `mesh` as a new state (a load or revert): no morph, the view is fitted.
    void push_loaded(HalfedgeMesh mesh, std::string label, std::string name, std::string path,
                     LoadReport report);
    /// After the current state changed (push, undo, redo, jump): uploads it, refreshes the
    /// information and colours; fits the view when asked.
    void on_state_changed(bool fit);
    void log_history_messages(const std::vector<std::string>& messages);
    /// Runs an operation as a job; its result becomes a history entry.
    void run_operation_job(const Operation& op);
    /// Pushes an operation's result as one history entry and plays its morph.
    void commit_result(const Operation& op, OperationResult result);

    // Live previews (viewer_preview.cpp; the rule is in that file's comment).
    struct PreviewState {
        std::optional<Operation> requested;  ///< the newest request
        std::optional<Operation> pending;    ///< requested, not started yet
        std::shared_ptr<OperationResult> result;
        Operation computed_op;        ///< what `result` was computed for
        Operation shown_op;           ///< what is shown (computed_op or fewer iterations)
        std::size_t shown_step = 0;   ///< the step of `result` shown
        HalfedgeMesh::Revision base;  ///< the document state `result` applies to
        double requested_at = 0, shown_at = 0;
        std::string failure;  ///< the last preview job's error (a sweep ends on it)
    };
    struct Sweep {
        bool active = false, waiting = false;
        bool lod = false;  ///< the level-of-detail slider ("decimate" with --param lod)
        Operation op, current;
        std::size_t param = 0;
        int next = 0;
        double t0 = 0;
        std::vector<double> ms;
    };
    bool is_preview_job() const;
    OperationPanelState* panel_of(const Operation& op);
    void request_preview(const Operation& op);
    void start_pending_preview();
    /// Waits a bounded time for a running preview, so that it shows in the coming frame.
    void wait_for_preview();
    void show_preview();
    /// Drops the preview (cancelling its job); `reupload`: show the current state again.
    void clear_preview(bool reupload);
    void apply_operation(const Operation& op);
    void update_preview_flags();
    /// Keeps the Fairing panel's largest stable explicit step for the current state.
    void update_stable_step();
    void note_preview_latency(double ms);
    void start_sweep();
    /// After each frame: `frame_shown` says whether the frame showed the preview.
    void step_sweep(bool frame_shown);
    // Decimation's level-of-detail slider (viewer_preview.cpp).
    struct LodState {
        std::shared_ptr<const ProgressiveMesh> progressive;
        std::shared_ptr<LevelOfDetail> lod;
        HalfedgeMesh::Revision base;  ///< the document state it was built on
        bool shown = false;           ///< the renderer shows a level
    };
    void build_level_of_detail(const Operation& op);
    void show_level_of_detail(double percent);
    void apply_level_of_detail();
    /// Drops the level shown (and, with `forget`, the progressive mesh).
    void clear_level_of_detail(bool forget);
    LodState lod_;
    PreviewState preview_;
    bool preview_shown_ = false;  ///< the renderer shows a preview step, not the document
    Sweep sweep_;
    bool sweep_started_ = false;
    /// The initial load and --op are done and no job runs: scripted actions may start.
    bool ready_for_script() const;
    /// Advances playback and shows the morph of the current entry, or the current state.
    void update_morph();
    /// Recording: starts, writes the next frame (once per UI frame), finishes.
    void start_recording();
    void record_next_frame();
    void finish_recording(bool cancelled);
    /// The Frequency panel's document for this frame, and its actions (viewer_frequency.cpp).
    void update_frequency_document();
    void frequency_actions(FrequencyActions act);
    void start_decomposition();
    /// options_.decompose: Decompose once the model is there, then apply the band.
    void scripted_decomposition(FrequencyActions& act);
    /// Shows the panel's band live (positions only).
    void preview_band();
    /// Pushes the panel's band (or, with `restore`, the decomposed shape) as a history entry.
    void push_frequency_state(bool restore);
    /// The Frequency / Frequency mass colours of `mesh` (empty without a fitting decomposition).
    VertexColors frequency_colors(const HalfedgeMesh& mesh) const;
    /// Model and scene information, for the Info panel and the `I` key.
    std::vector<std::string> scene_info() const;
    /// Computes the vertex colouring of view_.settings (as a job for large meshes) and
    /// uploads it.
    /// Positions of the state before the current history entry, one per vertex of the
    /// current mesh (empty when there is none or the connectivity differs).
    std::vector<Point> reference_positions() const;
    /// Whether `action` (a Quit or a LoadFile) may go ahead now; when changes are unsaved it
    /// opens the prompt instead and returns false.
    bool confirm_discard(bool quitting, const std::string& path);
    void update_coloring();
    void apply_colors(VertexColors colors);
    /// Makes the renderer show the document's current state (after a preview, a morph, a
    /// band or a level of detail), uploading only what changed, with the document's colours.
    void show_document();
    /// Uploads the texture chosen in view_.settings (checkerboard or the loaded image).
    void update_texture();
    void project_texcoords_now();
    /// Renders the scene without the panels into an offscreen framebuffer and writes a PNG.
    void take_screenshot(const TakeScreenshot& request);
    void notify_error(const std::string& text);
    void fit_view();
    /// The default view for the up axis (View > Default view, View > Up axis), fitted; a new
    /// up axis is remembered, and spherical texture coordinates the viewer projected follow it.
    void reset_view();
    void render_scene();
    /// Reads the back buffer and writes it as PNG; returns an error message or "".
    std::string write_screenshot(const std::string& path) const;

    // --click (viewer_clicks.cpp): presses widgets through the widget hook (widgets.h).
    struct ScriptedClicks {
        std::size_t next = 0;  ///< the click in progress
        int phase = 0;         ///< 0 find the widget, 1 hover, 2 press, 3 release, 4 report
        std::string target;    ///< what this press is for: the click's path or an opener
        bool opening = false;  ///< the press opens a section or menu on the way
        int openings = 0;      ///< for this click (bounded)
        float x = 0, y = 0;
        std::vector<WidgetNote> shown, drawing;  ///< last frame's widgets, this frame's
        std::vector<std::string> queued;         ///< commands the press queued
    };
    /// Before NewFrame: moves and presses the mouse for the click in progress.
    void drive_clicks();
    /// After the UI is drawn: the commands this frame's press queued.
    void note_click_commands();
    void fail_click(const std::string& why);
    bool clicks_pending() const { return clicks_.next < options_.clicks.size(); }
    ScriptedClicks clicks_;

    ViewerOptions options_;
    std::unique_ptr<GlfwLibrary> glfw_;
    std::unique_ptr<GLFWwindow, WindowDeleter> window_;
    std::unique_ptr<ImGuiLayer> imgui_;
    std::unique_ptr<MeshRenderer> renderer_;

    Document document_;
    ViewState view_;
    Image texture_;       ///< the loaded texture image (empty: none)
    Image checkerboard_;  ///< the built-in texture
    PanelState panels_;
    Notice notice_;
    Log log_;
    JobRunner jobs_;
    RecentFiles recent_;
    Preferences preferences_;  ///< remembered settings (interactive sessions only)
    CommandQueue commands_;
    std::vector<KeyPress> key_presses_;       ///< since the last frame
    std::vector<std::string> dropped_paths_;  ///< files dropped on the window since the last frame

    float ui_scale_ = 1.0f;      ///< content scale of the monitor (HiDPI)
    Rect view_rect_;             ///< where the model is drawn (window pixels), from the layout
    bool camera_fitted_ = true;  ///< no rotate, pan or zoom since the last fit: refit on resize
    glm::vec3 fit_center_{0.0f};
    float fit_radius_ = 1.0f;      ///< the sphere of the last fit
    bool drag_in_view_ = false;    ///< the mouse drag began in the view
    double surface_area_ = 0;      ///< of the current state (the wireframe decision)
    bool wire_auto_on_ = false;    ///< the automatic overlay's last decision (hysteresis)
    double edge_pixels_ = 0;       ///< a typical edge on the screen (framebuffer pixels)
    bool morph_t_done_ = false;    ///< options_.morph_t has been applied
    float record_line_scale_ = 1;  ///< line widths of recorded frames relative to the view
    int active_frames_ = 0;        ///< frames still to draw after the last event or command
    bool quit_ = false;
    int exit_status_ = 0;               ///< run()'s result: 1 after a scripted action failed
    bool continue_after_save_ = false;  ///< the unsaved-changes prompt's Save: then go on
    bool coloring_pending_ = false;     ///< a colouring was asked for while a job ran
    MorphState morph_;
    bool morph_shown_ = false;        ///< the renderer shows a morph frame, not the document
    bool initial_op_done_ = false;    ///< options_.operation has been queued
    bool initial_load_ended_ = true;  ///< options_.mesh_path was read (or failed to be)
    int scripted_decompose_ = 0;      ///< options_.decompose: 0 to do, 1 started, 2 done
    Camera record_camera_;            ///< the recording's framing, fixed for the whole sequence
    /// Wall time of the most recent frames (events excluded), for a median that ignores the
    /// slow first frame (shader compilation, font upload).
    std::array<double, 15> frame_times_ms_{};
    std::size_t n_frame_times_ = 0;
    double frame_ms() const;
    /// The vertex and face counts of what is on the screen (a preview, a level of detail).
    std::pair<std::size_t, std::size_t> shown_counts() const;

    /// Rendering > Vectors > Collapsing edges: the next decimation iteration's edges,
    /// recomputed when the mesh or the Decimation panel's options change.
    void update_collapsing_edges();
    std::unique_ptr<LineRenderer> collapse_lines_;
    std::string collapse_key_;  ///< what the drawn edges were computed for
};

}  // namespace trilab::viewer
