#pragma once
// SelectionTool: the Selection section's tool in the view (issue 26). With the section open,
// Ctrl+drag paints (brush) or draws (lasso) adding, Alt+drag removing; a stroke ends as ONE
// history entry (SetSelection). It draws the brush's circle and the lasso, keeps the
// selection overlay's weights on the GPU (a stroke's while it is drawn, else the shown mesh's
// "v:selection"), and hands the session the current colouring's values for the threshold.
// The document's side is app/session/session_selection.cpp.
#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "app/session/screen_selection.h"
#include "app/viewer/tool.h"
#include "core/algorithms/selection.h"

namespace trilab::viewer {

class SelectionTool : public Tool {
public:
    /// `surface`: the exact renderer, whose overlay the tool keeps.
    /// `surface`: the exact surface the selection overlay is uploaded to (nullptr: none, as
    /// in the panel tests).
    SelectionTool(ViewerContext& context, MeshRenderer* surface)
        : Tool(context), surface_(surface) {}
    void update() override;
    void describe(SidebarContext& context) const override;
    bool mouse(const ViewMouse& mouse) override;
    void before_surface(RenderStyle& style) override;

    /// A stroke as the mouse draws it (view pixels); scripted brushes call these too.
    void begin_stroke(bool add, bool lasso, const glm::vec2& pos);
    void continue_stroke(const glm::vec2& pos);
    /// Ends the stroke: its selection as ONE history entry (SetSelection), when it changed any.
    void end_stroke();
    bool stroking() const { return stroke_.active; }
    /// A scripted brush holds the mouse: the real one waits.
    void set_scripted(bool scripted) { scripted_ = scripted; }
    void section(const SidebarContext& context, CommandQueue& commands) override {
        selection_section(panel_, context, commands);
    }
    PanelEntries panels() override {
        PanelEntry entry;
        entry.name = "selection";
        entry.title = "Selection";
        entry.open = &panel_.open;
        return {entry};
    }
    SelectionPanelState& panel() { return panel_; }

private:
    /// The geodesic radius and feather width from the model's size (its fitted sphere).
    void size_for_model();
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
    trilab::MeshRenderer* surface_;
    SelectionPanelState panel_;
    SelectionStroke stroke_;
    std::string overlay_key_;  ///< what the overlay's weights on the GPU are of
    std::uint64_t stroke_counter_ = 0;
    bool scripted_ = false;
    /// The model size the lengths were set for, and the values set then (a value the user
    /// changed is left alone).
    float sized_for_ = 0;
    float auto_radius_ = SelectionPanelState{}.geodesic_radius;
    float auto_feather_ = SelectionPanelState{}.feather;
};

}  // namespace trilab::viewer
