#pragma once
// Viewer: the trilab window. Owns the GLFW window and GL context, the ImGui layer, the
// document (the mesh being shown), the view (camera and render style) and the panel state,
// and runs the frame loop. Panels edit their own state and queue commands; the viewer
// executes the commands, so loading, fitting and quitting happen in one place.
#include <array>
#include <cstddef>
#include <future>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/session/screen_selection.h"
#include "app/session/session.h"
#include "app/viewer/frequency_panel.h"
#include "app/viewer/panels.h"
#include "core/algorithms/level_of_detail.h"
#include "core/algorithms/proxy_mesh.h"
#include "core/algorithms/transfer_function.h"
#include "core/halfedge_mesh.h"
#include "core/io/image_io.h"
#include "core/mesh_builder.h"
#include "render/camera.h"
#include "render/line_renderer.h"
#include "render/mesh_renderer.h"
#include "render/proxy_view.h"

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
    std::string mode;   ///< initial render mode name (render_mode_name()), empty: default
    std::string color;  ///< initial vertex colouring name (coloring_name()), empty: none
    /// --op (repeatable): operations applied after loading, in order, each once the one
    /// before has finished.
    std::vector<std::string> operations;
    std::string save_session;  ///< --save-session: write the session there after the last frame
    bool restore = false;      ///< --restore: restore the newest crash journal without asking
    bool no_recovery = false;  ///< --no-recovery: no crash journal, no recovery question
    std::string show;          ///< panels to open at start, comma-separated
    int memory_budget_mb = 0;  ///< the history's budget; 0: a quarter of the RAM
    std::string decompose;     ///< "K" or "K:LO:HI": Frequency panel Decompose (and a band)
    std::string up;            ///< "y" or "z": the up axis for this run; empty: the remembered one
    /// --sweep OP --param NAME --range FROM:TO:COUNT: preview OP with NAME at COUNT evenly
    /// spaced values, print "sweep: previews=N median_ms=X max_ms=Y" and exit.
    std::string sweep_op, sweep_param;
    /// --click "SECTION/LABEL" (repeatable): widgets to press, in order, after --op.
    std::vector<std::string> clicks;
    /// --pick X,Y (repeatable): window pixels to pick once the model is shown; the second
    /// measures from the first.
    std::vector<std::string> picks;
    double sweep_from = 0, sweep_to = 0;
    int sweep_count = 0;
    /// --select SPEC (repeatable): selections set once the model is shown (issue 26).
    std::vector<std::string> selections;
    std::string brush;          ///< --brush "X0,Y0:X1,Y1[:R]": a scripted brush drag
    std::string lasso;          ///< --lasso "X0,Y0:X1,Y1:X2,Y2[:...][:through]": one lasso
    std::string figure;         ///< --figure NAME: a reference figure's mesh and settings
    int orbit_frames = 0;       ///< --orbit N: one scripted turn around the model in N frames
    bool print_timing = false;  ///< --print-timing: first and first exact frame times
};

/// Reads --lasso's "X0,Y0:X1,Y1:X2,Y2[:...][:through]" into the polygon's window pixels (at
/// least three finite points) and whether it selects through the model. Returns "" on
/// success, else what is wrong (the caller names the option).
std::string parse_lasso_script(const std::string& text, std::vector<glm::vec2>& points,
                               bool& through);

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

    /// Before a frame: finished jobs, what the session did, the scripted actions; returns
    /// whether it waited for a job (a scripted run's initial load).
    bool prepare_frame();
    /// One frame's UI, its commands and the scene (not swapped yet); returns whether
    /// commands ran.
    bool draw_frame();
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
    /// The view region (layout.h) in framebuffer pixels, GL's origin (bottom left).
    void view_viewport(int& x, int& y, int& w, int& h) const;
    /// Carries out a command: the window's own here, the document's in the session.
    void execute(const Command& command);
    /// Follows what the session did: recolour, fit, title, recent files, texture, the
    /// unsaved-changes question's next step.
    void follow_session();
    /// Scripted runs: each --op in turn once the initial load (and the --op before) ended.
    void advance_script();

    // Sessions and the crash journal (viewer_session.cpp).
    /// The view, panels and texture a session file stores beside the history.
    SessionExtras session_extras() const;
    /// Applies an opened session's extras (settings that cannot be applied become log notes).
    void apply_session_extras(const SessionExtras& extras);
    /// Starts the journal and looks for the journals of viewers that did not exit cleanly:
    /// --restore restores the newest, an interactive run asks, a scripted run logs it.
    void start_recovery();
    /// Each frame: the settings into the journal when they changed (at most once a second),
    /// and the journal's warning, once.
    void journal_settings();
    /// --save-session: writes the session now; returns an error message or "".
    std::string save_session_now();
    std::string texture_path_;           ///< the loaded texture's file ("" : none)
    std::string journaled_settings_;     ///< the settings text last given to the journal
    double settings_journaled_at_ = -1;  ///< Session::now() of that
    /// Makes the renderer show session_.shown(), uploading only what changed.
    void sync_renderer();
    /// Colours `mesh` by the current colouring (`reference`: the smoothing distance's).
    void show_colors_of(const HalfedgeMesh& mesh, const std::vector<Point>& reference);
    /// The operation panels (each holds its operation).
    std::vector<OperationPanelState*> operation_panels();
    /// The panels' view of the session: previews, preview times, the stable step, the level
    /// of detail.
    void update_panels();
    void note_preview_latency(OperationPanelState& panel, double ms);
    /// Keeps the Fairing panel's largest stable explicit step for the current state.
    void update_stable_step();

    // Scripted sweeps (viewer_sweep.cpp).
    struct Sweep {
        bool active = false, waiting = false;
        bool lod = false;  ///< the level-of-detail slider ("decimate" with --param lod)
        Operation op, current;
        std::size_t param = 0;
        int next = 0;
        double t0 = 0;
        std::vector<double> ms;
    };
    void start_sweep();
    /// After each frame: `frame_shown` says whether the frame showed the preview.
    void step_sweep(bool frame_shown);
    Sweep sweep_;
    bool sweep_started_ = false;
    /// The initial load and --op are done and no job runs: scripted actions may start.
    bool ready_for_script() const;
    /// Recording: starts, writes the next frame (once per UI frame), finishes.
    void start_recording();
    void record_next_frame();
    void finish_recording(bool cancelled);
    /// The Frequency panel's sliders after a decomposition (viewer_frequency.cpp).
    void on_decomposed(std::size_t lo, std::size_t hi);
    /// options_.decompose: queues Decompose once the model is there, then the band.
    void scripted_decomposition();
    // The reference's figures (issue 28; viewer_frequency.cpp, viewer_lens.cpp).
    /// options_.figure: sets the figure's panels and queues LoadFigure once the initial load
    /// and --op are done; true once it has run (or there is none), so the other scripted
    /// actions wait for it.
    bool scripted_figure();
    int scripted_figure_ = 0;  ///< options_.figure: 0 to do, 1 queued, 2 done
    /// The Frequency / Frequency mass colours of `mesh` (empty without a fitting decomposition).
    VertexColors frequency_colors(const HalfedgeMesh& mesh) const;
    /// Model and scene information, for the Info panel and the `I` key.
    std::vector<std::string> scene_info() const;
    /// Whether `action` (a Quit or a LoadFile) may go ahead now; when changes are unsaved it
    /// opens the prompt instead and returns false.
    bool confirm_discard(bool quitting, const std::string& path);
    /// Computes the vertex colouring of view_.settings (as a job for large meshes) and
    /// uploads it.
    void update_coloring();
    void apply_colors(VertexColors colors);
    /// Uploads the texture chosen in view_.settings (checkerboard or the loaded image).
    void update_texture();
    /// Renders the scene without the panels into an offscreen framebuffer and writes a PNG.
    void take_screenshot(const TakeScreenshot& request);
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

    // Picking and the Inspector (viewer_picking.cpp).
    /// Picks at `view_pos` (pixels relative to the view's top left); opens the Inspector.
    std::optional<Pick> pick_at(const glm::vec2& view_pos, bool second);
    /// Rebuilds the highlight of the picks and the geodesic path when they or the shown
    /// surface changed.
    void update_pick_overlay();
    void draw_pick_overlay() const;
    /// The Inspector's rows for the current picks (when they or the state changed).
    void update_inspector();
    /// --pick: the next scripted pick, once the model is shown and no job runs.
    void scripted_picks();
    bool scripted_picks_pending() const;
    std::unique_ptr<LineRenderer> pick_face_lines_, pick_edge_lines_, pick_vertex_lines_,
        pick_path_lines_;
    std::string pick_overlay_key_;
    std::string inspector_key_;
    InspectorView inspector_;
    std::size_t next_scripted_pick_ = 0;
    std::uint64_t geodesic_colored_version_ = 0;  ///< the picks the geodesic colours show
    /// The Fairing section's transfer curve data (viewer_lens.cpp).
    void update_lens();
    /// The operation panels' note when the document has a selection (viewer_lens.cpp).
    void update_region_notes();
    std::uint64_t region_notes_state_ = 0;
    std::string lens_key_;
    glm::vec2 press_pos_{0.0f};  ///< where the left button went down (a click picks)
    bool turning_ = false;       ///< the left drag has moved past the click's slop

    ViewerOptions options_;
    std::unique_ptr<GlfwLibrary> glfw_;
    std::unique_ptr<GLFWwindow, WindowDeleter> window_;
    std::unique_ptr<ImGuiLayer> imgui_;
    std::unique_ptr<MeshRenderer> renderer_;

    Session session_;  ///< the document, its history, jobs and operations (no GL)
    ViewState view_;
    Image texture_;       ///< the loaded texture image (empty: none)
    Image checkerboard_;  ///< the built-in texture
    PanelState panels_;
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
    std::uint64_t shown_version_ = 0;   ///< of session_.shown() on the GPU
    Shown::Kind shown_kind_ = Shown::Kind::Document;
    bool initial_op_done_ = false;    ///< every options_.operations entry has been queued
    std::size_t next_op_ = 0;         ///< the next options_.operations entry
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

    // ---- selections (viewer_selection.cpp, issue 26) -----------------------------------------
    /// Each frame: the colouring's values for the threshold, --brush (once the model is shown
    /// and --op and --select are done).
    void update_selection();
    /// The Selection section's part of the sidebar's context.
    void selection_context(SidebarContext& context) const;
    /// The mouse in the view (`pos`: view pixels): with the Selection section open, Ctrl+drag
    /// paints (brush) or draws (lasso) adding, Alt+drag removing; returns true while it has
    /// the mouse (the view does not turn, no pick on release). Draws the brush's circle and
    /// the lasso.
    bool selection_input(const glm::vec2& pos, bool in_view);
    /// Before the scene is drawn: the overlay's weights on the GPU (a stroke's while it is
    /// drawn, else the shown mesh's "v:selection"); scales its outline by the UI scale.
    void upload_selection_overlay(RenderStyle& style);
    /// --select: queues the next SPEC once the model is loaded (before --op); false when
    /// none is left.
    bool scripted_selection();
    /// --select or --brush still to run (a scripted run's last frame waits for them).
    bool selection_script_pending() const;
    void begin_stroke(bool add, bool lasso, const glm::vec2& pos);
    void continue_stroke(const glm::vec2& pos);
    /// Ends the stroke: its selection as ONE history entry (SetSelection), when it changed any.
    void end_stroke();
    /// One step of --brush per frame, timed from the move to the next frame.
    void scripted_brush();
    /// --lasso, before ImGui's frame: the mouse (Ctrl held) as a user draws the lasso with the
    /// Selection section's Lasso tool: over the first point, pressed, moved along the polygon
    /// over several frames, released; then prints "lasso: vertices=N".
    void drive_lasso();
    struct SelectionStroke {
        /// through: the lasso takes hidden vertices too (fixed when it begins, as projected)
        bool active = false, add = true, lasso = false, through = false;
        ProjectedVertices projected;                ///< the view when the stroke began
        Selection before;                           ///< the document's weights then
        Selection weights;                          ///< the brush's weights as painted
        std::vector<Eigen::Vector2f> lasso_points;  ///< view pixels
        glm::vec2 last{0.0f};
        std::size_t dabs = 0, changed = 0;
        std::uint64_t version = 0;  ///< changes with every dab (the overlay's upload)
    };
    struct ScriptedBrush {
        int state = 0;  ///< 0 not started (or none), 1 dragging, 2 done
        glm::vec2 from{0.0f}, to{0.0f};
        float radius = 0;
        int step = 0, steps = 24;
        int frames_waited = 0;  ///< frames drawn before it starts (the layout settles)
        double moved_at = -1;   ///< glfw time of the last move (-1: none waiting)
        std::vector<double> ms;
    };
    struct ScriptedLasso {
        int state = 0;                ///< 0 not started (or none), 1 drawing, 2 released, 3 done
        std::vector<glm::vec2> path;  ///< the mouse's window pixels, one per frame
        std::size_t step = 0;
        int frames_waited = 0;
    };
    SelectionStroke stroke_;
    ScriptedBrush brush_script_;
    ScriptedLasso lasso_script_;
    std::size_t next_scripted_select_ = 0;
    std::string overlay_key_;  ///< what the overlay's weights on the GPU are of
    std::uint64_t stroke_counter_ = 0;

    /// Rendering > Vectors > Collapsing edges: the next decimation iteration's edges,
    /// recomputed when the mesh or the Decimation panel's options change.
    void update_collapsing_edges();
    std::unique_ptr<LineRenderer> collapse_lines_;
    std::string collapse_key_;  ///< what the drawn edges were computed for

    // ---- Large meshes: simplified while moving, exact at rest (viewer_motion.cpp) ----------
    /// A shown mesh state: its topology and geometry revisions.
    using MeshKey = std::pair<std::uint64_t, std::uint64_t>;
    struct ProxyView {
        std::unique_ptr<MeshRenderer> renderer;  ///< the proxy's GPU mirror
        MotionClock motion;
        /// Proxies made, by the state they stand for (a few: the levels a slider visits).
        std::map<MeshKey, std::shared_ptr<const ProxyMesh>> cache;
        std::vector<MeshKey> cache_order;  ///< oldest first
        std::vector<MeshKey> failed;       ///< states whose proxy could not be made
        /// The proxy being made (on a worker thread, from a copy of the mesh).
        MeshKey job_key{0, 0};
        std::future<std::shared_ptr<const ProxyMesh>> job;
        /// Jobs for states no longer shown: kept until they end (a future's destructor waits).
        std::vector<std::future<std::shared_ptr<const ProxyMesh>>> abandoned;
        bool current = false;  ///< the shown state is large enough for a proxy
        MeshKey current_key{0, 0};
        bool exact_pending = false;         ///< the shown state is not uploaded yet (sync_renderer)
        bool proxy_drawn = false;           ///< the current state's proxy was on the screen
        MeshKey uploaded_key{0, 0};         ///< on `renderer`
        std::uint64_t uploaded_colors = 0;  ///< colors_stamp of the proxy's colours
        /// The attribute revision of the state whose selection and texture coordinates the
        /// proxy's renderer has (0: none given since the last upload).
        std::uint64_t attributes_revision = 0;
        /// The colours on (or waiting for) the exact renderer, and the state they are for.
        VertexColors colors;
        MeshKey colors_key{0, 0};
        std::uint64_t colors_stamp = 1;
        bool drew_proxy = false;     ///< this frame drew the proxy
        bool shows_current = false;  ///< this frame showed the shown state (proxy or exact)
        bool note = false;           ///< the note is drawn this frame
        double error_pixels = 0;     ///< of the proxy on the screen
        std::size_t proxy_frames = 0, exact_frames = 0;  ///< frames of the current run
        /// A large mesh's spectral prediction drawn before it is computed: the decomposition
        /// averaged over the document's stand-in (cluster_basis, made on a worker thread), for
        /// that decomposition and document state; null where the document is not the
        /// decomposed shape.
        std::shared_ptr<const ClusteredBasis> basis;
        std::shared_ptr<const SpectralDecomposition> basis_of;
        MeshKey basis_key{0, 0};
        std::future<std::shared_ptr<const ClusteredBasis>> basis_job;
        std::optional<Operation> predicted_for;  ///< the request whose prediction is uploaded
        bool drew_predicted = false;             ///< this frame drew it
    };
    ProxyView proxy_;
    /// In choose_renderer: the proxy's renderer with the clustered prediction of the preview
    /// asked for, while the session computes its prediction (null otherwise).
    MeshRenderer* choose_clustered_prediction();
    /// The picture of a file still loading (Session::loading_picture), drawn by the proxy's
    /// renderer until the load ends.
    struct LoadingView {
        std::shared_ptr<const LoadingPicture> picture;  ///< on the proxy's renderer
        bool drawn = false;                             ///< this frame drew it
        Camera camera_before;                           ///< the view before the picture was fitted
        bool restore_camera = false;                    ///< the load has not brought a model yet
        double error_pixels = 0;
    };
    LoadingView loading_;
    /// In choose_renderer: the loading picture's renderer while a load shows one (null when
    /// none); restores the view when a picture goes without a new model (a failed load).
    MeshRenderer* choose_loading_picture();
    /// The proxy options for a state of `n_faces` faces (the document's and the loading
    /// picture's: the same options make the same proxy).
    static ProxyMeshOptions proxy_options(std::size_t n_faces);
    struct Orbit {
        int frame = -1;  ///< -1: not started; 1..N: the orbit's frames; N + 1: resting
        Camera start;
        std::vector<double> ms;
        double motion_end = 0;  ///< glfw time at the end of the last orbit frame
        std::size_t proxy_frames = 0;
        bool done = false;
    };
    Orbit orbit_;
    double first_frame_ms_ = -1, exact_frame_ms_ = -1;  ///< --print-timing
    /// The smallest face count drawn through a proxy while moving (TRILAB_PROXY_MIN_FACES
    /// overrides it, for tests).
    static std::size_t proxy_min_faces();
    /// Whether `shown` is a state that gets a proxy (a large Document or Preview).
    bool proxy_applies(const Shown& shown) const;
    /// Starts making the proxy of `mesh` unless it is made, being made or failed.
    void request_proxy(const HalfedgeMesh& mesh);
    /// Collects a finished proxy job.
    void poll_proxy_job();
    /// Uploads what session_.shown() shows to the exact renderer (sync_renderer's work).
    void upload_shown();
    /// Gives the proxy's renderer the current colouring, sampled through `representative`, when
    /// it is the colouring of the state `stands_for`; no colours otherwise.
    void colour_proxy(MeshRenderer& r, const MeshKey& stands_for,
                      const std::vector<Index>& representative);
    /// Gives the proxy's renderer the attributes of `mesh` (the state it stands for) sampled
    /// through `representative`: the selection overlay (none without a selection) and the
    /// texture coordinates (for Textured mode; none without).
    void dress_proxy(MeshRenderer& r, const HalfedgeMesh& mesh,
                     const std::vector<Index>& representative);
    /// Remembers the colours given to the exact renderer (for the proxy's colours).
    void note_exact_colors(const VertexColors& colors, const HalfedgeMesh& mesh);
    /// Before the UI is rendered: the orbit's camera, the note.
    void update_motion_ui();
    /// In render_scene: decides proxy or exact, uploads the exact state at rest; returns the
    /// renderer to draw (nullptr: nothing new to draw; the old content stays).
    MeshRenderer* choose_renderer();
    /// After each frame's swap: the orbit's and --print-timing's clocks.
    void note_frame_end(double frame_ms);
    /// Scripted runs: the orbit and its rest have ended and the exact surface is shown.
    bool motion_settled() const;
    /// --print-timing, after the last frame.
    void print_timing() const;
};

}  // namespace trilab::viewer
