#pragma once
// SessionCore: what every owner of a Session shares (app/session/session.h): the document and
// its history, the one job runner, the log, the status bar's notice, the morph playback, what
// the view shows and the events the window takes once per frame; and the few things every
// owner does with them (tell the user, push a history entry and follow it). The owners
// (previews, selection, picks, levels of detail, the frequency document, files, figures,
// colouring, the morph) each hold their own state and a reference to the core; the Session
// facade wires them and is their one door.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/history/history.h"
#include "app/history/session_file.h"
#include "app/session/job_runner.h"
#include "app/session/log.h"
#include "core/algorithms/level_of_detail.h"
#include "core/algorithms/morph.h"
#include "core/algorithms/proxy_mesh.h"
#include "core/algorithms/spectral.h"
#include "core/geometry.h"
#include "core/halfedge_mesh.h"
#include "core/io/image_io.h"
#include "core/io/mesh_io.h"

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
    bool saved = false;  ///< a save finished
    /// The save finished was asked for with then_continue (the unsaved-changes question's
    /// "Save": its action goes on now).
    bool continue_after_save = false;
    /// A LoadFile or OpenSession of this path waits: the document has unsaved changes and
    /// the window asks first (set_ask_before_discarding); it sends the command again with
    /// discard_changes to go on.
    std::optional<std::string> confirm_discard;
    /// The command that waits is the restoring of the crash journal at confirm_discard
    /// (RecoverJournal), not a LoadFile.
    bool confirm_recovery = false;
    /// A session was opened: its view, panel and texture settings for the window to apply.
    std::shared_ptr<const SessionExtras> session_extras;
    /// A load ended whose picture (LoadingPicture) is also the new document's proxy: the file
    /// was a clean manifold triangle soup, so the mesh has its vertices and triangles in order
    /// and make_proxy_mesh would make the same proxy (null otherwise).
    std::shared_ptr<const ProxyMesh> loaded_proxy;
    /// A decomposition ended: its band [0, hi] (the Frequency panel's sliders).
    std::optional<std::size_t> decomposed_hi;
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

/// The state every owner reads and changes (on the render thread only).
struct SessionCore {
    Document document;
    JobRunner jobs;
    Log log;
    Notice notice;
    MorphState morph;
    Shown shown;
    SessionEvents events;
    /// Called after the current state became another one (set by the Session: every owner
    /// follows it); `fit`: a new model, fit the view.
    std::function<void(bool fit)> state_changed;
    /// Called whenever the view shows the document again (the picks follow it).
    std::function<void()> document_shown;

    const HalfedgeMesh& mesh() const { return document.mesh(); }
    /// Seconds on the session's clock (the morph's, and the panels' playback start).
    double now() const;
    /// An error in the status bar, the log and the popup.
    void notify_error(const std::string& text);
    /// An information line in the status bar.
    void inform(const std::string& text);
    /// "busy: wait for ..." (a command that needs the job runner while a job runs).
    void busy_error();
    /// A preview job runs (a document command may cancel it).
    bool preview_job() const { return jobs.busy() && jobs.kind() == JobKind::Preview; }
    /// Pushes one history entry of `meshes` and follows it (state_changed).
    void push_entry(const std::string& label, const std::string& parameters, double ms,
                    std::vector<HalfedgeMesh> meshes,
                    std::vector<MorphCorrespondence> correspondences, const Operation& op = {});
    void log_history_messages(const std::vector<std::string>& messages);
    /// Shows `mesh` (the document, a preview, a level of detail...) with no other positions.
    void show(Shown::Kind kind, const HalfedgeMesh* mesh, LevelOfDetail* level = nullptr);
    /// Shows the document (document_shown follows).
    void show_document();
    void bump() { ++shown.version; }
};

}  // namespace trilab::viewer
