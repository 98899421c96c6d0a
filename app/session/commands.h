#pragma once
// What panels ask the viewer to do. Panels never touch the document, the window or the GPU:
// they queue commands, and the viewer executes them in one place after the UI is drawn.
#include <cstddef>
#include <iterator>
#include <memory>
#include <string>
#include <variant>
#include <vector>

#include "app/ops/operation.h"
#include "core/algorithms/coloring.h"
#include "core/algorithms/decimation.h"
#include "core/algorithms/fairing.h"
#include "core/algorithms/morph.h"
#include "core/algorithms/ray_pick.h"
#include "core/algorithms/texcoords.h"
#include "core/up_axis.h"

namespace trilab::viewer {

struct LoadFile {
    std::string path;
    bool discard_changes = false;  ///< true: do not ask about unsaved changes
};
struct SaveFile {
    std::string path;
    bool then_continue = false;  ///< then carry out the unsaved-changes question's action
};
struct RevertFile {};
/// Write the whole session (every history state, the view, the panels, the texture) to a
/// .trilab file (app/history/session_file.h), as a job.
struct SaveSession {
    std::string path;
};
/// Replace the document with a session file or a crash journal (read as a job).
struct OpenSession {
    std::string path;
    bool discard_changes = false;  ///< true: do not ask about unsaved changes
};
/// The crash-recovery question's answer about the journal at `path` (a viewer that did not
/// exit cleanly): restore it (then it is removed) or discard it (removed now).
struct RecoverJournal {
    std::string path;
    bool restore = true;
    bool discard_changes = false;  ///< true: do not ask about unsaved changes
};
struct LoadTexture {
    std::string path;
};
struct FitView {};
/// The default view for ViewSettings::up (the model's front, the up axis up), fitted; also
/// remembers the up axis (View > Up axis, View > Default view).
struct ResetView {};
struct Undo {};
struct Redo {};
struct JumpTo {
    std::size_t entry = 0;
};
/// An operation with its typed parameters (app/ops/operation.h), e.g. a panel's.
struct RunOperation {
    Operation op;
};
/// Show `op` applied to the current state without committing it (a panel's parameter
/// changed); a newer request replaces an older one that is still computing.
struct PreviewOperation {
    Operation op;
};
/// Commit `op` as one history entry: the shown preview when it was computed for `op`,
/// otherwise a run of its own.
struct ApplyOperation {
    Operation op;
};
/// Drop the preview and show the current state again (the panel's Cancel, or Esc).
struct CancelPreview {};
/// Decimation's level-of-detail slider: build the progressive mesh of the current state with
/// `op`'s cost and constraints (a job), show the level keeping `percent` of the vertices, or
/// commit the shown level as one history entry.
struct BuildLevelOfDetail {
    Operation op;
};
struct ShowLevelOfDetail {
    double percent = 100;
};
struct ApplyLevelOfDetail {};
/// The Frequency panel: decompose the current state with `op` (a "spectrum" operation's
/// options: operator, method, count, end), a job.
struct Decompose {
    Operation op;
};
/// Show the band [lo, hi] of the decomposition live (with the rest where it reaches the end
/// of the computed spectrum); no history entry.
struct PreviewBand {
    std::size_t lo = 0, hi = 0;
};
/// Push the band [lo, hi] as one geometry-only history entry.
struct CommitBand {
    std::size_t lo = 0, hi = 0;
};
/// Back to the decomposed shape, as a history entry.
struct RestoreDecomposed {};
/// Recompute the vertex colouring (its kind or options changed).
struct UpdateColoring {};
/// Compute texture coordinates by `projection` with `up` up (the mesh has none).
struct ProjectTexCoords {
    TexCoordProjection projection = TexCoordProjection::Spherical;
    UpAxis up = UpAxis::Y;
};
/// A PNG of the scene without the panels.
struct TakeScreenshot {
    std::string path;
    int width = 0, height = 0;
    bool transparent = false;
};
struct PrintInfo {};
struct StartRecording {};
struct CancelRecording {};
struct CancelJob {};
struct Quit {
    bool discard_changes = false;  ///< true: do not ask about unsaved changes
};
/// Save the document to its own file, then carry out the pending Quit or LoadFile.
struct SaveAndContinue {};
/// Ask for a file name (the file browser), save there, then carry out the pending action.
struct SaveAsAndContinue {};

// ---- selections (issue 26; app/session/session_selection.cpp): each is ONE history entry ----
/// How a new selection combines with the document's: replace it, add (the larger weight), or
/// remove (w·(1 − new)).
enum class SelectionMode { Replace, Add, Remove };
/// The selection as given, one weight in [0, 1] per vertex storage index (a brush stroke or a
/// lasso, computed by the window); `label` and `parameters` name the history entry.
struct SetSelection {
    std::vector<float> weights;
    std::string label = "Select";
    std::string parameters;
};
/// A region SPEC (app/ops/region_spec.h: sphere:..., geodesic:..., component:..., file:...).
struct SelectSpec {
    std::string spec;
    SelectionMode mode = SelectionMode::Replace;
};
/// The geodesic ball of `radius` around the first pick's vertex, or (`component`) the
/// connected component under the first pick.
struct SelectAtPick {
    bool component = false;
    double radius = 0;
    SelectionMode mode = SelectionMode::Replace;
};
/// Vertices whose value under the current colouring is above (or below) `value`.
struct SelectThreshold {
    double value = 0;
    bool above = true;
    SelectionMode mode = SelectionMode::Replace;
};
/// Grow or shrink by `rings` rings, invert, clear (no selection: the whole mesh), or feather
/// over `width` (model units).
struct EditSelection {
    enum class Kind { Grow, Shrink, Invert, Clear, Feather };
    Kind kind = Kind::Clear;
    int rings = 1;
    double width = 0;
};
/// Help > Reference figures: load the figure's model and run its settings (Session::
/// load_figure, app/session/reference_figures.h).
struct LoadFigure {
    std::string name;  ///< "1.12b"
};

/// Inspector: forget the picks (and the measurement).
struct ClearPicks {};
/// Inspector: make the first pick's point the centre of rotation.
struct CentreOnPick {};

/// The current entry's morph on the session's clock (the Morph section, Space): play (from
/// where the playback is) or stop.
struct PlayMorph {
    bool play = true;
};
/// Shows the current entry's morph at `t` in [0, 1] (0: before, 1: after); stops playback.
struct ShowMorphAt {
    double t = 1.0;
};
/// The morph animation's settings (the Morph section).
struct SetMorphAnimation {
    double duration = 2.0;  ///< seconds for one pass (> 0)
    Easing easing = Easing::SmoothStep;
    Playback playback = Playback::PingPong;
};
/// Colours the current state by `coloring` on a job (the window's colouring of a large mesh;
/// Session::coloring_result() when it ends). `reference`: the smoothing distance's positions.
struct ComputeColoring {
    VertexColoring coloring = VertexColoring::None;
    ColoringOptions options;
    std::shared_ptr<const std::vector<Point>> reference;
};
/// The error popup has shown the current notice (it opens once per error).
struct NoticeShown {};
/// The transfer curve's "Show the diverging run" (Session::show_diverging_run).
struct ShowDivergingRun {
    Operation op;
};

/// Casts `ray` (from depth t_min) at the shown surface: a hit replaces the picks, or with
/// `second` is the second pick (a measurement from the first); a miss clears them.
struct PickAt {
    Ray ray;
    double t_min = 0;
    bool second = false;
};
/// Keep the geodesic distance from the picked vertices up to date (its colouring is shown).
struct WantPickDistances {
    bool want = true;
};
/// The decimation options the Inspector explains an edge's collapse with (the Decimation
/// panel's).
struct SetInspectionOptions {
    DecimationOptions options;
};
/// The current colouring's value per vertex storage index (NaN: none; empty: the colouring
/// has none), for SelectThreshold.
struct SetColoringValues {
    std::vector<double> values;
};
/// The view has drawn the shown spectral prediction: the exact preview may start.
struct PredictionDrawn {};
/// Fairing's guidance: estimate the current state's largest stable explicit step for `op`
/// (SessionGuidance, off the render thread).
struct EstimateStableStep {
    FairingOperator op = FairingOperator::Umbrella;
};
/// Decimation's overlay: find the edges the next iteration of `op` (a decimation) collapses
/// on the current state (SessionGuidance, off the render thread).
struct FindCollapsingEdges {
    Operation op;
};
/// The window's settings (view, panels) changed: the crash journal records them.
struct JournalSettings {
    std::string text;
};

using Command = std::variant<
    LoadFile, SaveFile, RevertFile, SaveSession, OpenSession, RecoverJournal, LoadTexture, FitView,
    ResetView, Undo, Redo, JumpTo, RunOperation, PreviewOperation, ApplyOperation, CancelPreview,
    BuildLevelOfDetail, ShowLevelOfDetail, ApplyLevelOfDetail, Decompose, PreviewBand, CommitBand,
    RestoreDecomposed, UpdateColoring, ProjectTexCoords, TakeScreenshot, PrintInfo, StartRecording,
    CancelRecording, CancelJob, Quit, SaveAndContinue, SaveAsAndContinue, ClearPicks, CentreOnPick,
    SetSelection, SelectSpec, SelectAtPick, SelectThreshold, EditSelection, LoadFigure, PlayMorph,
    ShowMorphAt, SetMorphAnimation, ShowDivergingRun, NoticeShown, ComputeColoring, PickAt,
    WantPickDistances, SetInspectionOptions, SetColoringValues, PredictionDrawn, JournalSettings,
    EstimateStableStep, FindCollapsingEdges>;
using CommandQueue = std::vector<Command>;

/// The command's type name ("StartRecording"), for logs and scripted clicks.
inline const char* command_name(const Command& command) {
    static constexpr const char* kNames[] = {"LoadFile",
                                             "SaveFile",
                                             "RevertFile",
                                             "SaveSession",
                                             "OpenSession",
                                             "RecoverJournal",
                                             "LoadTexture",
                                             "FitView",
                                             "ResetView",
                                             "Undo",
                                             "Redo",
                                             "JumpTo",
                                             "RunOperation",
                                             "PreviewOperation",
                                             "ApplyOperation",
                                             "CancelPreview",
                                             "BuildLevelOfDetail",
                                             "ShowLevelOfDetail",
                                             "ApplyLevelOfDetail",
                                             "Decompose",
                                             "PreviewBand",
                                             "CommitBand",
                                             "RestoreDecomposed",
                                             "UpdateColoring",
                                             "ProjectTexCoords",
                                             "TakeScreenshot",
                                             "PrintInfo",
                                             "StartRecording",
                                             "CancelRecording",
                                             "CancelJob",
                                             "Quit",
                                             "SaveAndContinue",
                                             "SaveAsAndContinue",
                                             "ClearPicks",
                                             "CentreOnPick",
                                             "SetSelection",
                                             "SelectSpec",
                                             "SelectAtPick",
                                             "SelectThreshold",
                                             "EditSelection",
                                             "LoadFigure",
                                             "PlayMorph",
                                             "ShowMorphAt",
                                             "SetMorphAnimation",
                                             "ShowDivergingRun",
                                             "NoticeShown",
                                             "ComputeColoring",
                                             "PickAt",
                                             "WantPickDistances",
                                             "SetInspectionOptions",
                                             "SetColoringValues",
                                             "PredictionDrawn",
                                             "JournalSettings",
                                             "EstimateStableStep",
                                             "FindCollapsingEdges"};
    static_assert(std::size(kNames) == std::variant_size_v<Command>, "a name per command");
    return kNames[command.index()];
}

}  // namespace trilab::viewer
