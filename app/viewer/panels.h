#pragma once
// The viewer's ImGui panels. Each panel is a function over plain state: it edits what it
// owns directly and asks the viewer for everything else by queueing a Command (commands.h),
// so panels never touch the document, the window or the GPU.
#include <cstddef>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "app/history/history.h"
#include "app/session/commands.h"
#include "app/session/log.h"
#include "app/session/session.h"
#include "app/viewer/file_browser.h"
#include "app/viewer/frequency_panel.h"
#include "app/viewer/layout.h"
#include "app/viewer/transfer_plot.h"
#include "app/viewer/widgets.h"
#include "core/algorithms/coloring.h"
#include "core/algorithms/morph.h"
#include "core/algorithms/texcoords.h"
#include "render/mesh_renderer.h"

struct ImGuiStyle;

namespace trilab::viewer {

class Tool;
/// The viewer's tools in sidebar order (tool.h, tools.h): the menus, --panels, the key
/// bindings, saved settings and scripts find a tool's panel by looping over them.
using ToolList = std::vector<Tool*>;

/// The screenshot dialog: a PNG of the scene without the panels, at any resolution.
struct ScreenshotState {
    bool open = false;
    std::string path = "trilab-screenshot.png";
    int width = 1920, height = 1080;
    bool transparent = false;
};

/// The Record panel: writes the current entry's morph as PNG frames (and an MP4 when ffmpeg
/// is on the PATH), one frame per UI frame so the window stays responsive.
struct RecordState {
    bool open = false;
    int frames = 60;
    int fps = 30;
    int width = 1280, height = 720;
    std::string folder = "trilab-frames";
    std::string name = "frame";
    bool mp4 = false;
    // While recording:
    bool running = false;
    int next = 0;  ///< the next frame to write
};

/// An operation panel's state: open or not, and the operation with the values its widgets
/// edit (the declaration's defaults at first).
struct OperationPanelState {
    explicit OperationPanelState(const std::string& name) : op(make_operation(name)) {}
    bool open = false;
    Operation op;
    // Live preview (the viewer sets these each frame; see README "Live panels").
    bool live = true;          ///< false: the preview waits until a drag is released
    bool dirty = false;        ///< changed since the last preview request
    bool previewing = false;   ///< a preview of this panel is computing or shown
    std::string preview_note;  ///< e.g. "preview 38 ms" or why it waits for the release
    std::string input_note;    ///< a typed value that was clamped, and to what
    /// "acts on the selection: N of M vertices" when the document has a selection (or that
    /// this operation acts on the whole mesh anyway); empty without one.
    std::string region_note;
    double latency_ms = -1;  ///< of the last preview the note tells about
};

/// The Fairing panel: its operation, and the stability guidance the viewer keeps up to date.
struct FairingPanelState : OperationPanelState {
    FairingPanelState() : OperationPanelState("smooth") {}
    /// The largest stable explicit step of the current mesh and operator (NaN: not known yet).
    double max_stable_step = std::numeric_limits<double>::quiet_NaN();
    HalfedgeMesh::Revision stable_step_state;             ///< the mesh state it was estimated on
    std::optional<FairingOperator> stable_step_operator;  ///< and the operator
    /// The spectral lens: what the transfer curve is drawn over (the viewer fills it).
    TransferView lens;
};

/// The Decimation panel: its operation, and the collapsing-edges overlay.
struct DecimationPanelState : OperationPanelState {
    DecimationPanelState() : OperationPanelState("decimate") {}
    /// Rendering > Vectors > Collapsing edges: the edges the next iteration collapses.
    bool show_collapsing_edges = false;
    /// The level-of-detail slider over the progressive mesh (percent of the vertices kept).
    float lod_percent = 100.0f;
    bool lod_open = false;   ///< the "Level of detail" part of the section is expanded
    bool lod_ready = false;  ///< the viewer has a progressive mesh of the current state
    bool lod_building = false;
    std::string lod_note;  ///< what the progressive mesh reaches, or the last move's time
};

/// Draws one widget per parameter of `op` that applies to its current values, from the
/// operation's declaration (combo boxes for choices, sliders for numbers, check boxes for
/// flags and switchable numbers, two fields for a range). Returns true when a value changed;
/// changed values are marked `given`. Parameters declared cli_only() are not drawn.
/// A typed value outside the declared range is clamped at once, and why goes to `notes`.
bool operation_widgets(Operation& op, std::vector<std::string>* notes = nullptr);
/// A declaration's or an error's text in the panel's words: "--min-faces N" becomes
/// "min faces N" (an option is named by its label in the panels).
std::string panel_words(const std::string& cli_text);
/// What an unset optional parameter does, in the panel's words (its declaration's default
/// note without the command line's dashes).
std::string default_note_text(const ParamSpec& p);
/// `x` inside the declared range of `p` (above min where min is exclusive: the slider's lower
/// end, or the next representable number).
double clamp_to_declared(const ParamSpec& p, double x);

/// The wireframe overlay: on, off, or automatic (on while the edges are long enough on the
/// screen to tell apart; decided again on zoom and when the shown mesh changes).
enum class WireframeOverlay { Auto, On, Off };

/// Rendering settings that live in the viewer rather than in RenderStyle.
struct ViewSettings {
    WireframeOverlay wireframe = WireframeOverlay::Auto;
    VertexColoring coloring = VertexColoring::None;
    ColoringOptions coloring_options;
    TexCoordProjection projection = TexCoordProjection::Spherical;
    /// The model's up axis (View > Up axis, remembered): the default view keeps it up on the
    /// screen, and the spherical projection puts its poles on it.
    UpAxis up = UpAxis::Y;
    bool use_checkerboard = true;  ///< the built-in texture instead of the loaded image
};

/// Which windows are open, and the dialogs' own state.
/// The "unsaved changes" question asked before quitting or opening another file.
struct UnsavedPrompt {
    bool open_requested = false;  ///< open the modal on the next frame
    bool quitting = false;        ///< the pending action: quit (true) or open `path`
    bool recover = false;         ///< opening `path` restores a crash journal (RecoverJournal)
    std::string path;
    std::string document_path;  ///< where "Save" writes (empty: only Save as)
};

/// The crash-recovery question at start-up: the journal of a viewer that did not exit cleanly.
struct RecoveryPrompt {
    bool open_requested = false;  ///< open the modal on the next frame
    std::string path;             ///< the newest orphan journal
    std::string description;      ///< what it is: file, size, time
    /// How the viewer that wrote it ended without saving ("SIGTERM"); "" for a crash.
    std::string ended;
};

/// A generic panel for each registered operation not in `owned` (the operations whose tools
/// have panels of their own), in the registry's order.
std::vector<OperationPanelState> tool_panels(const std::vector<const OperationDef*>& owned);
/// "Tools: add noise": a tool's section title, from its operation's label.
std::string tool_section_title(const OperationDef& def);

/// The Selection section (issue 26; app/viewer/selection_panel.cpp): how the brush and the
/// lasso draw in the view, and the settings of the one-shot selections and edits.
struct SelectionPanelState {
    bool open = false;
    enum class Tool { Brush, Lasso };
    Tool tool = Tool::Brush;     ///< what Ctrl+drag (add) and Alt+drag (remove) draw in the view
    float brush_radius = 30.0f;  ///< the brush's radius in screen pixels
    bool lasso_through = false;  ///< the lasso also takes vertices hidden behind the surface
    SelectionMode mode = SelectionMode::Replace;  ///< how the one-shot selections combine
    float geodesic_radius = 0.25f;                ///< model units
    float threshold = 0.0f;                       ///< on the current colouring's values
    bool threshold_above = true;
    int rings = 1;         ///< Grow / Shrink
    float feather = 0.1f;  ///< model units
};

/// Where a tool's panel is listed in the menu bar.
enum class PanelMenu { None, Edit, Tools, Algorithms };

/// A tool's panel as the window finds it, by its stable name: --panels, the menus, the key
/// bindings and --click. The tool owns the flag `open` points to.
struct PanelEntry {
    std::string name;   ///< the --panels name ("fairing", "collapsing-edges", "noise")
    std::string title;  ///< the menu item ("Fairing", "Add noise...")
    bool* open = nullptr;
    PanelMenu menu = PanelMenu::None;
    int shortcut = -1;      ///< the KeyAction (key_bindings.h) that toggles it (-1: none)
    bool in_all = true;     ///< --panels all opens it
    bool in_tools = false;  ///< --panels tools opens it (the Tools menu's sections)
    /// A menu action instead of a panel (an operation without parameters): the menu item
    /// applies it.
    const Operation* action = nullptr;
};
using PanelEntries = std::vector<PanelEntry>;
/// The entry named `name` (nullptr: none).
const PanelEntry* find_panel(const PanelEntries& entries, const std::string& name);

/// The window's own panels and dialogs; every tool's panel state is the tool's (tool.h).
struct PanelState {
    UnsavedPrompt unsaved;
    RecoveryPrompt recovery;
    ScreenshotState screenshot;
    bool history_open = false;
    FileBrowserState file_browser;
    bool help_open = false;
    bool about_open = false;
    bool log_open = false;
    bool info_open = false;
    bool context_menu_requested = false;  ///< right click in the view: open the Rendering popup
    LayoutState layout;                   ///< the regions' sizes (layout.h)
    bool sidebar_open = true;             ///< Window > Sidebar
};

/// What the menus need to know about the document and the job runner.
/// Asks what to do with unsaved changes: save them (to the document's file) and go on,
/// discard them and go on, or cancel. Queues SaveAndContinue, or Quit / LoadFile with
/// discard_changes set.
void unsaved_changes_popup(UnsavedPrompt& prompt, CommandQueue& commands);

struct MenuContext {
    bool has_file = false;  ///< the document came from a file (Revert, Save as near it)
    bool busy = false;      ///< a job runs: document commands are disabled
    bool can_undo = false, can_redo = false;
    std::string document_path;
    const std::vector<std::string>* recent_files = nullptr;
};

/// What the status bar shows.
struct StatusInfo {
    std::size_t n_vertices = 0;
    std::size_t n_faces = 0;
    std::string file_name;
    double frame_ms = 0.0;  ///< of the recent frames drawn as the last one was
    /// The file whose simplified picture is on the screen while it loads ("": none): the bar
    /// names it and its face count, not the model still open.
    std::string loading;
    /// The stand-in on the screen ("": the exact surface), e.g. "simplified: 60000 triangles".
    std::string simplified;
};

/// The running job, for the progress shown in the status bar.
struct JobInfo {
    std::string name;
    std::string stage;
    double fraction = -1.0;  ///< negative: unknown
    double seconds = 0.0;
    bool cancel_requested = false;
};

/// What the Rendering menu needs to know to explain what cannot be shown.
struct RenderContext {
    bool has_texcoords = false;
    bool has_loaded_texture = false;
};

/// The viewer's ImGui style: dark, slightly rounded, slider grabs that leave their value
/// text legible.
void apply_panel_style(ImGuiStyle& style);

/// File, Edit, View, Tools, Algorithms, Rendering, Window and Help menus; the tools' panels
/// are listed where their entries say (Tool::panels()).
void menu_bar(RenderStyle& style, ViewSettings& settings, PanelState& panels, const ToolList& tools,
              const MenuContext& context, const RenderContext& render, CommandQueue& commands);
/// The Rendering menu's items (also the right-click popup in the view); `entries` gives
/// Vectors > Collapsing edges (the panel entry "collapsing-edges").
void rendering_menu_items(RenderStyle& style, ViewSettings& settings, PanelState& panels,
                          const PanelEntries& entries, const RenderContext& render,
                          CommandQueue& commands);
/// The View menu (in the menu bar): Default view, and Up axis (+y or +z; queues ResetView).
void view_menu(ViewSettings& settings, CommandQueue& commands);
/// The right-click popup with the rendering items.
void context_menu(RenderStyle& style, ViewSettings& settings, PanelState& panels,
                  const PanelEntries& entries, const RenderContext& render, CommandQueue& commands);
// ---- fixed regions (layout.h) ---------------------------------------------------------------

/// Begins the window of a fixed region at `r`: not movable, no saved settings. The user may
/// drag its inner edge: `resizable` 'r' (the right edge: the sidebar), 'l' (the left edge: the
/// history column) or 't' (the top edge: the log); after the call the window's size is in
/// `width` or `height` (the other stays). Always pair with end_region().
bool begin_region(const char* title, const Rect& r, bool* open, char resizable, float& width,
                  float& height, int extra_flags = 0);
void end_region();

/// The left sidebar: one window holding the tool sections; pair with end_region().
bool begin_sidebar(const Rect& r, LayoutState& layout);

/// Draws a collapsing section header bound to `open` (a click toggles it; a menu or key that
/// sets it expands the section and scrolls the sidebar to it). Returns `open`.
bool section_header(const char* label, bool& open);

/// A sidebar section: its header (section_header()) and, while it is open, its body in an ID
/// scope and a widget section named after it, so that two sections never share a widget.
class SidebarSection {
public:
    SidebarSection(const char* label, bool& open);
    explicit operator bool() const { return open_; }

private:
    bool open_;
    std::optional<WidgetSection> scope_;
};

/// The History column: every entry with its steps, timing and memory; a click jumps there.
void history_window(PanelState& panels, const History& history, bool busy, const Rect& region,
                    CommandQueue& commands);
/// What the Inspector section shows: rows the viewer prepares from the picks (the panel holds
/// no mesh and computes nothing).
struct InspectorView {
    struct Row {
        std::string label, text;
    };
    struct Group {
        std::string title;  ///< "Vertex 12", "Edge 40", "Face 7", "Measure"
        std::vector<Row> rows;
    };
    std::vector<Group> groups;
    /// Provenance: how far each history entry moved the picked vertex (one value per entry,
    /// NaN where the vertex did not exist), and the current entry.
    std::vector<float> moved_by_entry;
    std::size_t current_entry = 0;
    std::string note;  ///< e.g. "computing the geodesic distance"
    bool has_picks = false;
};

/// What the sidebar's sections show besides the panels' own state.
struct SidebarContext {
    const History* history = nullptr;
    const MorphState* morph = nullptr;  ///< the session's (the Morph section; nullptr: none)
    bool busy = false;                  ///< a job runs: the Apply buttons wait
    bool closed = false;                ///< the mesh has no boundary (volume preservation applies)
    bool can_record = false;            ///< the current entry has a morph to record
    std::string record_why_not;         ///< why not, in the panel's words
    /// The mesh has coincident boundary edges (unwelded seams): Sqrt3 would leave creases
    /// along them, and the Subdivision section offers the weld.
    bool open_seams = false;
    std::size_t collapsing_edges = 0;                ///< edges the overlay shows (0: none)
    const FrequencyDocument* frequency = nullptr;    ///< the decomposition (Frequency section)
    const std::vector<std::string>* info = nullptr;  ///< model information lines
    const InspectorView* inspector = nullptr;        ///< the picks (Inspector section)
    // The Selection section.
    std::size_t selected = 0;    ///< vertices of positive weight in the document's selection
    std::size_t n_vertices = 0;  ///< of the document
    bool has_selection = false;  ///< the document stores one (operations act on it)
    bool has_pick = false;       ///< a vertex is picked (geodesic ball, component)
    /// The current colouring has values (the threshold), over this range.
    bool has_values = false;
    double values_min = 0, values_max = 0;
};

/// The Selection section: the count, the brush and lasso settings (they draw in the view with
/// Ctrl+drag to add and Alt+drag to remove), the geodesic ball and component at the pick, the
/// threshold on the colouring, grow, shrink, invert, clear and feather; queues SelectAtPick,
/// SelectThreshold and EditSelection (app/viewer/selection_panel.cpp).
void selection_section(SelectionPanelState& state, const SidebarContext& context,
                       CommandQueue& commands);

/// Every tool's sections in the tools' order (the sidebar), then the sidebar's closing note.
void sidebar_sections(const ToolList& tools, const SidebarContext& context, CommandQueue& commands);

/// The sections the tools draw (each its header and, when open, its body in an ID scope of
/// its own; every section queues commands). The tools own the state they are drawn over.
/// The parameters of an operation panel, its Apply button (labelled `apply`), the preview's
/// Cancel and notes; queues PreviewOperation (live, or when a drag ends) and ApplyOperation.
void operation_panel_body(OperationPanelState& state, const char* apply, bool busy,
                          CommandQueue& commands);
/// Where the morph of a result is: one place, the Morph section.
void morph_hint();
/// Subdivision: scheme, iterations, Subdivide; queues PreviewOperation and ApplyOperation;
/// with `context.open_seams` a note about Sqrt3 and a Weld button.
void subdivision_section(OperationPanelState& state, const SidebarContext& context,
                         CommandQueue& commands);
/// Fairing (operator, integration, step, iterations, volume preservation, Smooth).
/// `context.closed` says whether the mesh has a volume (volume preservation is disabled
/// otherwise, with a note saying why).
void fairing_section(FairingPanelState& state, const SidebarContext& context,
                     CommandQueue& commands);
/// Decimation (cost, the three constraints with their thresholds, percentage per iteration,
/// iterations, Decimate, the level-of-detail slider, the collapsing-edges overlay).
void decimation_section(DecimationPanelState& state, const SidebarContext& context,
                        CommandQueue& commands);
/// Opens the panels named in `list`, comma-separated: all, tools (every Tools section), the
/// window's history, log, info, the dialogs help, about, screenshot, and every tool's panel
/// by its entry's name (morph, fairing, subdivision, frequency, decimation,
/// collapsing-edges, record, selection, and any tool by its operation's name: noise, weld).
/// Throws InvalidArgument naming an unknown one and listing the known.
void open_panels(PanelState& panels, const PanelEntries& entries, const std::string& list);
/// The generic tools' sections (those with parameters), each "Tools: LABEL" with the
/// operation's summary, its parameters, Apply and the preview's Cancel.
void tools_section(std::vector<OperationPanelState>& tools, bool busy, CommandQueue& commands);
/// The morph slider and the animation controls for the current history entry: the one place
/// they are drawn; they queue PlayMorph, ShowMorphAt and SetMorphAnimation.
void morph_section(bool& open, const MorphState& morph, const History& history,
                   CommandQueue& commands);
/// Record; queues StartRecording / CancelRecording.
void record_section(RecordState& record, bool can_record, const std::string& why_not,
                    CommandQueue& commands);
/// The Inspector: what the picks are and why (InspectorView), the measurement, the
/// provenance plot; Clear picks (ClearPicks) and Centre view here (CentreOnPick).
void inspector_section(bool& open, const InspectorView& view, CommandQueue& commands);
/// Model and scene information (the `I` key prints the same lines to the console).
void info_section(bool& open, const std::vector<std::string>& lines);

/// The running job's text for a progress bar `width` wide: the name, the stage and the time,
/// or as much as fits by dropping whole parts from the end (the tooltip shows it all), never
/// a text cut at the edge. `text_width` measures a text (ImGui's CalcTextSize in the viewer).
std::string job_label(const JobInfo& job, float width,
                      const std::function<float(const std::string&)>& text_width);
/// `text` as it fits in `width`: whole, or its longest start that fits followed by "..." (cut
/// between UTF-8 characters, after a space where one is near the end), never cut at an edge.
/// `text_width` measures a text (ImGui's CalcTextSize in the viewer).
std::string fit_text(const std::string& text, float width,
                     const std::function<float(const std::string&)>& text_width);
/// `text` broken into lines of at most `width` at its spaces only: a number ("-0.053496") or a
/// word is never split (one longer than `width` gets a line of its own).
std::vector<std::string> wrap_at_spaces(const std::string& text, float width,
                                        const std::function<float(const std::string&)>& text_width);
/// The status bar's first part: the counts, the file and the frame time of what is on the
/// screen; while a file loads, its name and face count.
std::string status_text(const StatusInfo& info);
/// The status bar along the bottom edge: counts, file, frame time, the last notice, and the
/// running job (name, progress, Cancel) when `job` is set.
void status_bar(const StatusInfo& info, const Notice& notice, const JobInfo* job,
                const Rect& region, CommandQueue& commands);
/// The log along the bottom of the view: the messages of the session, errors highlighted.
void log_window(PanelState& panels, const Log& log, const Rect& region);

/// Where the colour legend goes: its bottom-right corner and the largest size it may take;
/// color_legend() writes the size it took (for the next frame's layout).
struct LegendSlot {
    float right = 0, bottom = 0, max_width = 0, max_height = 0;
    float width = 0, height = 0;  ///< out: the legend's size (0: not shown)
};
/// The colour bar of a vertex colouring with its value range, and the percentile sliders
/// that choose the range. Returns true when the user changed the options.
/// Under a scalar colouring's bar: the display (smooth, bands, isolines, both) and its count
/// N, in `style`.
bool color_legend(const VertexColors& colors, ColoringOptions& options, RenderStyle& style,
                  LegendSlot& slot);

// ---- dialogs: floating, kept inside the window ----------------------------------------------

/// Before a dialog's Begin: centred in the display when it appears, at most the display's size
/// less a margin (larger content scrolls).
void place_dialog(float width_em = 0, float height_em = 0);
/// After a dialog's Begin: moves it back inside the display when it was dragged or the
/// window shrank.
void keep_dialog_inside();
/// A modal popup placed as a dialog (place_dialog(), keep_dialog_inside()): true while it is
/// open, and then the caller ends it with ImGui::EndPopup().
bool begin_modal_dialog(const char* title, int flags, float width_em = 0, float height_em = 0);
/// The screenshot dialog; queues TakeScreenshot.
void screenshot_dialog(ScreenshotState& state, CommandQueue& commands);
/// The key and mouse bindings (Esc closes it).
void help_window(PanelState& panels);
void about_window(PanelState& panels);
/// Asks whether to restore a crash journal: Restore queues RecoverJournal{path, true}, Discard
/// RecoverJournal{path, false}; Later closes the question (the journal is offered again at
/// the next start).
void recovery_popup(RecoveryPrompt& prompt, CommandQueue& commands);
/// Modal popup showing an error notice once.
void error_popup(const Notice& notice, CommandQueue& commands);

}  // namespace trilab::viewer
