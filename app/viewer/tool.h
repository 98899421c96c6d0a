#pragma once
// Tool: one of the viewer's tools (Fairing, Decimation, Frequency, Selection, Pick and
// Inspector, the operation panels). A tool owns the state its section shows besides the
// operation's values (the stable step, the transfer curve, the collapsing edges, the brush
// stroke, the Inspector's rows), its overlays in the view and its mouse handling, and reaches
// the document only through the session's read-only views and the command queue. The viewer
// keeps a list of tools and calls each in turn every frame (the pattern of Polyscope's
// Quantity: each owns its UI, drawing and picking); it knows none of them by name.
#include <glm/glm.hpp>
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

protected:
    ViewerContext& context_;
};

}  // namespace trilab::viewer
