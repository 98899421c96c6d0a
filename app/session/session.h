#pragma once
// Session: the document, its history, the job runner and the operations, with no window, no
// GL and no ImGui. The viewer (and the headless tests) drive it with the same typed commands
// the panels queue (commands.h) and read back one value, shown(): what the view shows now
// (the document, a preview step, a morph frame, a level of detail or a frequency band).
//
// Threads: every method runs on the caller's (the render) thread. A job is handed what it
// reads (a copy-on-write snapshot of the mesh, taken here) and returns a finish function
// that poll() runs back on this thread; no job reaches into the session from its worker.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <future>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "app/history/history.h"
#include "app/history/journal.h"
#include "app/history/session_file.h"
#include "app/ops/operation.h"
#include "app/session/commands.h"
#include "app/session/job_runner.h"
#include "app/session/log.h"
#include "app/session/picking.h"
#include "core/algorithms/decimation.h"
#include "core/algorithms/fairing.h"
#include "core/algorithms/level_of_detail.h"
#include "core/algorithms/morph.h"
#include "core/algorithms/proxy_mesh.h"
#include "core/algorithms/selection.h"
#include "core/algorithms/spectral.h"
#include "core/algorithms/texcoords.h"
#include "core/geometry.h"
#include "core/halfedge_mesh.h"
#include "core/io/image_io.h"
#include "core/mesh_builder.h"
#include "core/up_axis.h"

namespace trilab::viewer {

/// The last thing the session has to tell the user. Errors also open a modal popup once.
struct Notice {
    enum class Level { None, Info, Error };
    Level level = Level::None;
    std::string text;                  ///< one line, shown in the status bar
    std::vector<std::string> details;  ///< extra lines for the tooltip (e.g. a load report)
    bool popup_pending = false;        ///< an error the popup has not shown yet
};

/// The morph of the current history entry: the slider and the animation.
struct MorphState {
    double t = 1.0;  ///< 0: the state before the entry, 1: after it
    bool playing = false;
    double duration = 2.0;  ///< seconds for one pass
    Easing easing = Easing::SmoothStep;
    Playback playback = Playback::PingPong;
    double play_start = 0.0;  ///< Session::now() when playback started
    /// The entry moves vertices (false for loads, reverts, texture coordinates: nothing to
    /// animate, so the morph controls say so instead).
    bool moves = true;
};

/// The current decomposition and what was derived from it for display (Frequency panel).
struct FrequencyDocument {
    std::shared_ptr<const SpectralDecomposition> decomposition;
    std::uint64_t topology_revision = 0;  ///< of the decomposed mesh (valid while it stays)
    bool valid = false;                   ///< the current mesh has the decomposed connectivity
    bool applied = false;
    std::size_t applied_lo = 0, applied_hi = 0;  ///< the band of the current state
    std::vector<float> eigenvalues;              ///< for the spectrum plot
    std::vector<float> log_coefficients;         ///< log10 |alpha_k|, for the coefficient plot
    std::string summary;                         ///< one line: count, time, solver
};

/// The model: its history of states (the current one is shown) and where it came from.
struct Document {
    History history;
    const HalfedgeMesh& mesh() const { return history.current_mesh(); }
    std::string name;               ///< file name, or "default model"
    std::string path;               ///< file path; empty for the default model
    LoadReport report;              ///< what loading it did (empty for built-in models)
    std::vector<std::string> info;  ///< model information lines, computed once per state
    bool closed = false;            ///< the current state has no boundary (volume is defined)
    bool open_seams = false;  ///< coincident boundary edges: unwelded seams (Subdivision's note)
    double area = 0;          ///< of the current state
    /// The current state's components (label_components(), from its statistics) and the
    /// topology revision they belong to: a region's flip reuses them (RunSettings::components).
    std::shared_ptr<const std::vector<Index>> components;
    std::uint64_t components_topology = 0;
    bool texcoords_projected = false;  ///< texture coordinates were computed by projection
    /// The current state differs from the file it came from or was last saved to.
    bool unsaved = false;
    FrequencyDocument frequency;  ///< the last frequency decomposition (Frequency panel)
};

/// What the view shows: one value.
struct Shown {
    enum class Kind { Document, Preview, Morph, Level, Band };
    Kind kind = Kind::Document;
    /// Document and Preview: the mesh; Morph: the frame's connectivity; Band: the document.
    const HalfedgeMesh* mesh = nullptr;
    std::vector<Point> positions;    ///< Morph and Band: every vertex's position (storage index)
    LevelOfDetail* level = nullptr;  ///< Level (the renderer reads its changes)
    std::uint64_t version = 0;       ///< changes whenever anything above changes
};

/// What happened in the session that the window has to follow (taken once per frame).
struct SessionEvents {
    bool state_changed = false;       ///< the current state is another one: recolour, re-title
    bool fit = false;                 ///< a new model: fit the view to it
    std::vector<std::string> recent;  ///< files loaded or saved (recent files)
    std::shared_ptr<Image> texture;   ///< a texture image was loaded
    std::string texture_path;
    bool saved = false;  ///< a save finished (a pending question goes on)
    /// A session was opened: its view, panel and texture settings for the window to apply.
    std::shared_ptr<const SessionExtras> session_extras;
    /// A load ended whose picture (LoadingPicture) is also the new document's proxy: the file
    /// was a clean manifold triangle soup, so the mesh has its vertices and triangles in order
    /// and make_proxy_mesh would make the same proxy (null otherwise).
    std::shared_ptr<const ProxyMesh> loaded_proxy;
};

/// A simplified picture of a file still loading, made from its arrays (vertex clustering of
/// the soup, core/algorithms/proxy_mesh.h) once they are fully read and checked, before the
/// half-edge mesh is built. The window draws it until the load ends, whatever the outcome.
struct LoadingPicture {
    std::string path;                        ///< the file being loaded
    std::shared_ptr<const ProxyMesh> proxy;  ///< its clustered triangles
    BoundingBox bounds;                      ///< of the file's vertices
    Point center;                            ///< bounds' centre
    double radius = 0;                       ///< the smallest sphere around center holding them
    std::size_t faces = 0;                   ///< the file's faces
};

/// Makes a LoadingPicture's proxy from a file's soup, on the load job's thread (pure: no
/// session state); null for no picture (a small file).
using LoadingPictureMaker = std::function<std::shared_ptr<const ProxyMesh>(const PolygonSoup&)>;

/// Whether `path` names a session file or a crash journal (.trilab, .journal): opening it
/// restores a session instead of reading a mesh.
bool is_session_path(const std::string& path);

/// The preview of an operation panel, as the panel shows it.
struct PreviewStatus {
    bool previewing = false;  ///< a preview of this operation is computing or shown
};

class Session {
public:
    /// A session on the built-in default model.
    Session();
    ~Session();
    Session(const Session&) = delete;
    Session& operator=(const Session&) = delete;

    /// Carries out a document command (a load, an operation, a preview, undo...); commands that
    /// are the window's business (FitView, TakeScreenshot, Quit, ...) are ignored.
    void execute(const Command& command);
    /// Applies a finished job; returns true when one ended (the window redraws).
    bool poll();
    /// Runs jobs to their end (tests and scripted runs): poll() until no job runs.
    void finish_jobs();
    /// Advances the morph playback (time from now()) and updates shown().
    void update();
    SessionEvents take_events();

    // ---- what the window reads ---------------------------------------------------------------
    const Document& document() const { return document_; }
    const HalfedgeMesh& mesh() const { return document_.mesh(); }
    const History& history() const { return document_.history; }
    const Shown& shown() const { return shown_; }
    Log& log() { return log_; }
    const Log& log() const { return log_; }
    /// What the status bar shows (notify(), notify_error(); NoticeShown after the popup).
    const Notice& notice() const { return notice_; }
    const JobRunner& jobs() const { return jobs_; }
    /// The colours of the last ComputeColoring job that ended (null: none yet), with the
    /// colouring and the document state they are of; `id` grows with each result.
    struct ColoringResult {
        std::uint64_t id = 0;
        VertexColoring coloring = VertexColoring::None;
        HalfedgeMesh::Revision state;
        VertexColors colors;
    };
    const ColoringResult* coloring_result() const { return coloring_result_.get(); }
    /// The morph playback (changed by PlayMorph, ShowMorphAt and SetMorphAnimation).
    const MorphState& morph() const { return morph_; }
    FrequencyDocument& frequency() { return document_.frequency; }
    bool busy() const { return jobs_.busy(); }
    /// The picture of the file being loaded, once its arrays are read (null otherwise; cleared
    /// when the load job ends). Safe to call while the job runs.
    std::shared_ptr<const LoadingPicture> loading_picture() const;
    /// Loads make their picture with `maker` (none without one: the default).
    void set_loading_picture_maker(LoadingPictureMaker maker) {
        loading_picture_maker_ = std::move(maker);
    }
    /// A preview job runs (its progress shows only after a while).
    bool preview_running() const;
    /// Seconds on the session's clock (the morph's, and the panels' playback start).
    double now() const;

    // ---- operations and previews -------------------------------------------------------------
    /// The preview shown or computing for `op`'s operation (its panel's Cancel shows).
    bool previewing(const Operation& op) const;
    /// The operation a preview was last asked for, if any.
    const std::optional<Operation>& preview_requested() const { return preview_.requested; }
    /// The result of the shown preview, if any (the panels read reports from it).
    const OperationResult* preview_result() const { return preview_.result.get(); }
    /// The error of the last preview job ("" when it succeeded).
    const std::string& preview_failure() const { return preview_.failure; }
    /// A preview is asked for and not started yet (the runner was busy).
    bool preview_pending() const { return preview_.pending.has_value(); }
    /// Whether the preview asked for last is computed and shown (or its spectral prediction,
    /// which shows first when there is a decomposition of the fairing's operator).
    bool preview_shown(const Operation& op) const;
    /// The preview on the screen is the spectral prediction, not the exact result yet.
    bool prediction_shown() const;
    /// A fairing `op` whose spectral prediction comes from the current decomposition's stored
    /// coefficients (a whole-mesh umbrella or Taubin preview on the decomposed shape): the
    /// decomposition and the options; nothing otherwise. A view draws a large mesh's prediction
    /// from it (predict_clustered) before the prediction itself is computed.
    struct Predictable {
        std::shared_ptr<const SpectralDecomposition> decomposition;
        FairingOptions options;
    };
    std::optional<Predictable> predictable(const Operation& op) const;
    /// A large decomposition's prediction is being computed on a worker thread.
    bool prediction_computing() const { return preview_.prediction_job.valid(); }
    /// The view has drawn the shown prediction: its exact job may start (it waits until then,
    /// at most a quarter second, so that a view drawing a large mesh's prediction gets the CPU
    /// for that frame, and a slider dragged on keeps cancelling nothing).
    void prediction_drawn();
    /// Milliseconds from the request to the result of the last preview (negative: none).
    double last_preview_ms() const { return preview_.latency_ms; }
    /// Waits up to `seconds` for a running preview, so that it shows in the coming frame.
    void wait_for_preview(double seconds);
    /// A level of detail is ready for the current state.
    bool has_level_of_detail() const;
    /// The level-of-detail note (what the progressive mesh reaches) and its build state.
    const std::string& level_note() const { return lod_.note; }
    bool level_building() const { return lod_.building; }

    // ---- frequency decomposition -------------------------------------------------------------
    void decompose(const SpectralOptions& options);
    /// Shows the band [lo, hi] live (positions only, no history entry).
    void preview_band(std::size_t lo, std::size_t hi);
    /// Pushes the band (or, with `restore`, the decomposed shape) as a history entry.
    void push_band(std::size_t lo, std::size_t hi, bool restore);
    /// Called after a decomposition finishes with its band (the panel's sliders).
    std::function<void(std::size_t lo, std::size_t hi)> on_decomposed;

    // ---- picking and measuring (session_picking.cpp) -----------------------------------------
    /// Casts `ray` (from depth t_min) at the shown surface. A hit replaces the picks, or with
    /// `second` sets the second pick (a measurement from the first; without a first pick it
    /// is the first). A miss clears the picks. Geometry-only history steps keep the picks
    /// (they follow the surface); steps that renumber drop them with a note. Two picks start
    /// the geodesic measurement as a job (the factorization is kept for the state).
    std::optional<Pick> pick(const Ray& ray, double t_min, bool second);
    void clear_picks();
    const PickSet& picks() const { return picks_; }
    /// Keep the geodesic distance from the picked vertices up to date (the colouring).
    void want_pick_distances(bool want);
    /// The decimation options the Inspector explains an edge's collapse with (the Decimation
    /// panel's); a change inspects the picks again.
    void set_inspection_options(const DecimationOptions& options);
    /// Waits for the inspection of the picks (tests and scripted runs).
    void finish_inspection();
    /// The picks' inspection or measurement is still being computed.
    bool picks_pending() const {
        return inspection_future_.valid() || picks_.measurement.computing;
    }

    // ---- selections (session_selection.cpp, issue 26) ----------------------------------------
    /// The document's selection ("v:selection"), or nullopt when it has none (operations then
    /// act on the whole mesh).
    std::optional<Selection> selection() const;
    /// Vertices of positive weight in the document's selection (0 without one).
    std::size_t selected_count() const;
    /// Makes `weights` (checked: one weight in [0, 1] per vertex storage index) the document's
    /// selection as ONE history entry named `label` (with `parameters`); the shape does not
    /// move. A preview shown or computing follows: it is computed again on the new selection.
    /// Refused (an error notice, nothing changes) while a job other than a preview runs, or
    /// for bad weights. Returns whether the entry was pushed.
    bool set_selection(const Selection& weights, const std::string& label,
                       const std::string& parameters = "");
    /// Removes the selection (one history entry); nothing when there is none.
    bool clear_selection();
    /// The current colouring's value per vertex storage index (NaN: none), for SelectThreshold;
    /// the window hands it over whenever the colouring changes (empty: the colouring has none).
    void set_coloring_values(std::vector<double> values) { coloring_values_ = std::move(values); }
    const std::vector<double>& coloring_values() const { return coloring_values_; }
    // ---- the reference's figures (session_figures.cpp, app/session/reference_figures.h) -------
    /// Loads the reference figure `name` ("1.12b") as one job: its built-in model as a load
    /// entry, its setup operations and then its operation as history entries, exactly as the
    /// panels would run them (a diverging run is stopped and refused as any other). Logs what
    /// the figure used and the step's translation; an unknown name is an error listing them.
    void load_figure(const std::string& name);
    /// The figure the document is ("" when none: nothing loaded, or another model since).
    std::string figure() const;
    /// For teaching: shows the explicit fairing `op` run from the current state without its
    /// health checks, up to its last iteration whose positions are finite, as a marked shown
    /// state that is never a result (no history entry; Apply runs `op` itself, which is
    /// refused again; Cancel or Esc returns). Refused with a notice for implicit runs.
    void show_diverging_run(const Operation& op);
    /// The diverging run is on the screen.
    bool diverging_run_shown() const;
    /// What the diverging run shows (one line, starting "DIVERGED").
    const std::string& diverging_run_note() const { return diverging_note_; }

    // ---- documents ---------------------------------------------------------------------------
    /// Computes texture coordinates by `projection` on the current shape (a history entry).
    void project_texcoords(TexCoordProjection projection, UpAxis up);
    /// The state before the current entry, on the current connectivity (the morph's start;
    /// the smoothing distance's reference); empty when there is none.
    std::vector<Point> reference_positions() const;
    /// Whether the current history entry moves any vertex (for the morph controls).
    bool entry_moves() const;
    /// An error in the status bar, the log and the popup.
    void notify_error(const std::string& text);
    /// Replaces the status bar's notice (Notice{}: none).
    void notify(Notice notice);
    /// The history's memory budget in bytes (History::set_budget).
    void set_history_budget(std::size_t bytes) { document_.history.set_budget(bytes); }

    // ---- session files and the crash journal (session_files.cpp) -----------------------------
    /// Writes the whole history with `extras` to `path` (a .trilab file) as a job; the
    /// texture's bytes are read there when only its path is given.
    void save_session(const std::string& path, SessionExtras extras);
    /// Replaces the document with the session file or journal at `path`, read as a job; the
    /// extras come back through take_events(). With `remove_after` the file is removed once
    /// restored (a recovered crash journal).
    void open_session(const std::string& path, bool remove_after = false);
    /// Replaces the document with `contents` now (the job's end; tests).
    void restore_session(SessionContents contents, const std::string& path);
    /// Journals every history change from now on (app/history/journal.h), starting with the
    /// history as it is.
    void start_journal(JournalOptions options);
    /// The journal, or nullptr when none runs (--no-recovery).
    Journal* journal() { return journal_.get(); }
    /// A clean end: writes what is queued and removes the journal's file.
    void close_journal();

private:
    void load(const std::string& path);
    void save(const std::string& path);
    void load_texture(const std::string& path);
    void push_loaded(HalfedgeMesh mesh, std::string label, std::string name, std::string path,
                     LoadReport report);
    void on_state_changed(bool fit);
    void log_history_messages(const std::vector<std::string>& messages);
    void run_operation_job(const Operation& op);
    void commit_result(const Operation& op, OperationResult result);
    void busy_error();
    void show_document();
    void bump() { ++shown_.version; }

    // Previews (session_preview.cpp).
    struct PreviewState {
        std::optional<Operation> requested;  ///< the newest request
        std::optional<Operation> pending;    ///< requested, not started yet
        std::shared_ptr<OperationResult> result;
        Operation computed_op;        ///< what `result` was computed for
        Operation shown_op;           ///< what is shown (computed_op or fewer iterations)
        std::size_t shown_step = 0;   ///< the step of `result` shown
        HalfedgeMesh::Revision base;  ///< the document state `result` applies to
        double requested_at = 0;
        double latency_ms = -1;
        std::string failure;  ///< the last preview job's error (a sweep ends on it)
        /// The spectral prediction of a fairing preview (issue 28), shown until the exact
        /// result arrives: the document's connectivity with the predicted positions.
        std::optional<Operation> predicted_op;
        HalfedgeMesh prediction;
        /// The exact job waits while the frame that shows a new prediction is drawn (it would
        /// take the CPU that frame needs): until prediction_drawn(), at most hold_exact_until
        /// on the session's clock.
        bool hold_exact = false;
        double hold_exact_until = 0;
        /// A large decomposition's prediction (rows x k at least kAsyncPredictionWork) is
        /// computed on a worker thread, the frame is not held for it: the op and document state
        /// it is for; the newest request waits in `prediction_next` while one runs.
        std::future<std::vector<Point>> prediction_job;
        Operation prediction_job_op;
        HalfedgeMesh::Revision prediction_job_base;
        std::optional<Operation> prediction_next;
    };
    /// Starts the worker prediction of `op` (predictable() on the current document).
    void start_prediction_job(const Operation& op, Predictable p);
    /// Shows the worker's prediction when it has ended and is still the newest request's.
    void collect_prediction_job();
    /// Shows `positions` as the prediction of `op`.
    void show_predicted(const Operation& op, std::vector<Point> positions);
    /// Shows the spectral prediction of fairing `op` when the decomposition is of its operator
    /// (core/algorithms/transfer_function.h predict_fairing); false when there is none.
    bool show_prediction(const Operation& op);
    bool is_preview_job() const;
    void request_preview(const Operation& op);
    void start_pending_preview();
    void show_preview();
    /// Drops the preview (cancelling its job); the view shows the document again.
    void clear_preview();
    void apply_operation(const Operation& op);

    // The level-of-detail slider (session_preview.cpp).
    struct LodState {
        std::shared_ptr<const ProgressiveMesh> progressive;
        std::shared_ptr<LevelOfDetail> lod;
        HalfedgeMesh::Revision base;  ///< the document state it was built on
        Operation op;                 ///< the decimation it was built with
        bool building = false;
        std::string note;
    };
    void build_level_of_detail(const Operation& op);
    void show_level_of_detail(double percent);
    void apply_level_of_detail();
    void clear_level_of_detail(bool forget);

    void update_morph();
    /// Carries out a morph command (PlayMorph, ShowMorphAt, SetMorphAnimation),
    /// ShowDivergingRun, NoticeShown or ComputeColoring; false: not one.
    bool execute_morph(const Command& command);
    /// Carries out a selection command (session_selection.cpp); false: not one.
    bool execute_selection(const Command& command);
    /// `fresh` combined with the document's selection as `mode` says.
    Selection combine_selection(Selection fresh, SelectionMode mode) const;
    /// The document's selection ("v:selection", core/algorithms/selection.h) as the region of
    /// `op`: null when the mesh has none, it selects everything, or `op` takes no region.
    std::shared_ptr<const std::vector<float>> region_for(const Operation& op,
                                                         const HalfedgeMesh& mesh) const;
    /// After the document changed: the picks follow a geometry-only step or are dropped.
    void follow_picks();
    /// Starts the pending geodesic job when the runner is free.
    void start_pick_job();
    /// Inspects the first pick on a worker thread (core/algorithms/inspect.h); takes its result.
    void start_inspection();
    void take_inspection();
    /// The frequency document's validity and applied band for the current state (it changes
    /// only with the state or the decomposition: called there, not every frame).
    void update_frequency_document();

    Document document_;
    JobRunner jobs_;
    /// The load job's picture, handed from the job's thread to the window's.
    struct PictureSlot {
        mutable std::mutex mutex;
        std::shared_ptr<const LoadingPicture> picture;
    };
    std::shared_ptr<PictureSlot> picture_slot_ = std::make_shared<PictureSlot>();
    LoadingPictureMaker loading_picture_maker_;
    Log log_;
    Notice notice_;
    MorphState morph_;
    PreviewState preview_;
    LodState lod_;
    Shown shown_;
    PickSet picks_;
    bool pick_job_pending_ = false;
    bool want_pick_distances_ = false;
    std::uint64_t pick_request_ = 0;  ///< changes with every request (stale job results)
    DecimationOptions inspection_options_;
    std::future<std::shared_ptr<const PickInspection>> inspection_future_;
    std::uint64_t inspection_request_ = 0;  ///< the pick request the future inspects
    SessionEvents events_;
    HalfedgeMesh::Revision morph_topology_;  ///< the connectivity of the morph frame shown
    std::unique_ptr<Journal> journal_;       ///< records every history change (crash recovery)
    std::vector<double> coloring_values_;    ///< the colouring's values (SelectThreshold)
    std::shared_ptr<const ColoringResult> coloring_result_;
    // The reference's figures (session_figures.cpp).
    std::string figure_;           ///< the figure loaded last
    HalfedgeMesh diverging_mesh_;  ///< the diverging run shown (shown_.mesh points here)
    std::string diverging_note_;   ///< what it shows
};

}  // namespace trilab::viewer
