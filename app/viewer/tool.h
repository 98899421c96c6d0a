#pragma once
// Tool: one of the viewer's tools (the generic operation panels, Selection, Fairing,
// Frequency, Subdivision, Decimation, Denoise, Morph and Record, Pick and Inspector). A tool
// owns its panel: the panel's state (the operation's values, open or not, the stable step,
// the transfer curve, the collapsing edges, the brush, the Inspector's rows), its sidebar
// section(s), the panel entries the menus, --panels and the key bindings find it by, and its
// saved settings; and its overlays in the view and its mouse handling. It reaches the
// document only through the session's read-only views and the command queue. The viewer
// keeps a list of tools and calls each in turn every frame, the sidebar in the list's order
// (the pattern of Polyscope's Quantity: each owns its UI, drawing and picking); it knows none
// of them by name.
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "app/viewer/viewer_context.h"

namespace trilab::viewer {

/// The mouse over the view this frame, in view pixels (the view's top left is 0, 0).
struct ViewMouse {
    glm::vec2 pos{0.0f};
    bool in_view = false;       ///< the cursor is over the view (and no window takes it)
    bool drag_in_view = false;  ///< the drag under way began in the view
    bool clicked = false;       ///< the left button was released without turning the view
    bool double_clicked = false;
    bool ctrl = false, alt = false, shift = false;
};

/// The saved settings of a tool (viewer_settings.cpp writes and reads them through one, by
/// key: "panel.fairing", "record.frames"; docs/file-formats.md#session-files).
class SettingsVisitor {
public:
    virtual ~SettingsVisitor() = default;
    virtual void number(const std::string& key, int& v) = 0;
    virtual void number(const std::string& key, float& v) = 0;
    virtual void flag(const std::string& key, bool& v) = 0;
    virtual void text(const std::string& key, std::string& v) = 0;
    /// The operation's text (Operation::text()); one that does not parse is left as it is.
    virtual void operation(const std::string& key, Operation& op) = 0;
};

class Tool {
public:
    explicit Tool(ViewerContext& context) : context_(context) {}
    virtual ~Tool() = default;
    Tool(const Tool&) = delete;
    Tool& operator=(const Tool&) = delete;

    /// Before the UI each frame: the displays derived from the document that the tool's
    /// section shows.
    virtual void update() {}
    /// What the sidebar's sections show of this tool besides the panels' own state.
    virtual void describe(SidebarContext& /*context*/) const {}
    /// The mouse in the view; returns true while the tool has it (the view does not turn).
    /// Called for every tool, in order, until one takes it.
    virtual bool mouse(const ViewMouse& /*mouse*/) { return false; }
    /// Before the surface is drawn: the tool's part of the surface's style and uploads (the
    /// selection overlay).
    virtual void before_surface(RenderStyle& /*style*/) {}
    /// After the surface: the tool's overlays (lines over the model).
    virtual void draw_overlay() {}
    /// The colours of a colouring computed from a field the tool owns (the frequency bands,
    /// the geodesic distance from the picks); empty when it owns none of `mesh`'s.
    virtual VertexColors field_colors(const HalfedgeMesh& /*mesh*/) const { return {}; }
    /// The operation panels this tool holds (their previews, notes and sweeps).
    virtual std::vector<OperationPanelState*> operation_panels() { return {}; }

    // ---- the tool's panel -------------------------------------------------------------------
    /// The tool's sidebar section(s): header and, when open, body; widgets queue commands.
    virtual void section(const SidebarContext& /*context*/, CommandQueue& /*commands*/) {}
    /// Its panels as the menus, --panels, the key bindings and --click find them, by name.
    virtual PanelEntries panels() { return {}; }
    /// Writes or reads its saved settings through `v`.
    virtual void settings(SettingsVisitor& /*v*/) {}
    /// A reference figure's operation: the tool takes it into its panel and opens the panel
    /// when the operation is its own (returns true).
    virtual bool show_figure(const Operation& /*op*/) { return false; }

protected:
    ViewerContext& context_;
};

}  // namespace trilab::viewer
