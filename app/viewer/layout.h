#pragma once
// The viewer's window layout: fixed regions in the spirit of Polyscope and MeshLab, so that no
// panel covers another or the model.
//
//   +----------------------------------------------------------+
//   | menu bar                                                 |
//   +-----------+----------------------------------+-----------+
//   | sidebar   | view (the model is framed here)  | history   |
//   | (tools as |                                  | (right    |
//   | collapsing|                                  | column,   |
//   | sections) +----------------------------------+ when open)|
//   |           | log                     | legend |           |
//   +-----------+-------------------------+--------+-----------+
//   | status bar (and the running job's progress)              |
//   +----------------------------------------------------------+
//
// The sidebar, the history column and the log are resizable (their inner edge); the layout
// clamps every size so that the regions tile the framebuffer at any size and content scale.
// Dialogs (key bindings, file browser, screenshot, errors) float centred over the view and are
// kept inside the window. The rule the layout keeps, checked by the viewer_layout tests
// through `trilab --print-layout`: every visible window lies inside the framebuffer and no two
// windows overlap (dialogs excepted, which only have to lie inside). No ImGui here: pure
// arithmetic, usable in tests.

namespace trilab::viewer {

/// An axis-aligned rectangle in window pixels (origin top left, y down); empty when w or h <= 0.
struct Rect {
    float x = 0, y = 0, w = 0, h = 0;
    float right() const { return x + w; }
    float bottom() const { return y + h; }
    bool empty() const { return w <= 0 || h <= 0; }
};

/// The sizes the user can change (by dragging a region's inner edge), in pixels; 0: the default.
struct LayoutState {
    float sidebar_width = 0;
    float history_width = 0;
    float log_height = 0;
    float menu_height = 0;   ///< measured when the menu bar is drawn
    float legend_width = 0;  ///< measured when the colour legend is drawn (0: none yet)
    float legend_height = 0;
};

/// What the layout depends on this frame.
struct LayoutInput {
    float width = 0, height = 0;  ///< the display (ImGui's DisplaySize)
    float em = 13;                ///< the font size
    float frame_height = 19;      ///< a widget's height (font size + frame padding)
    bool sidebar = true;          ///< the sidebar is shown
    bool history = false;         ///< the History column is open
    bool log = false;             ///< the Log is open
    bool legend = false;          ///< a colour legend is shown
};

/// The regions of one frame. Empty rectangles are not shown.
struct Layout {
    Rect menu, sidebar, status, log, legend, history;
    Rect view;  ///< what is left: the model is drawn and framed here
    /// The legend sits at the bottom right of `legend` and may take up to this size (its
    /// measured size, in LayoutState, sets `legend` in the next frame).
    float legend_max_width = 0, legend_max_height = 0;
};

/// Computes the regions and clamps `state`'s sizes to what fits (a state of 0 gets the
/// default). The regions tile [0, width] x [0, height] without overlapping; sizes are whole
/// pixels.
Layout compute_layout(const LayoutInput& input, LayoutState& state);

}  // namespace trilab::viewer
