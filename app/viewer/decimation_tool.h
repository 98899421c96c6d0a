#pragma once
// DecimationTool: the Decimation section's tool. Besides the operation panel's previews it
// keeps the level-of-detail slider's state in step with the session's progressive mesh, the
// Inspector's collapse explanation options, and draws Rendering > Vectors > Collapsing edges:
// the edges the next iteration collapses, recomputed when the mesh or the options change.
#include <memory>
#include <string>

#include "app/viewer/operation_tool.h"
#include "render/line_renderer.h"

namespace trilab::viewer {

class DecimationTool : public OperationTool {
public:
    /// The overlay's lines are made when first drawn (with the GL context current).
    explicit DecimationTool(ViewerContext& context);
    void update() override;
    void describe(SidebarContext& context) const override;
    void draw_overlay() override;
    void section(const SidebarContext& context, CommandQueue& commands) override;
    PanelEntries panels() override;
    void settings(SettingsVisitor& v) override;
    bool show_figure(const Operation& op) override { return take_figure(panel_, op); }
    DecimationPanelState& panel() { return panel_; }

private:
    void update_collapsing_edges();
    DecimationPanelState panel_;
    std::unique_ptr<LineRenderer> lines_;
    /// The session's edges that are drawn (null: none of the current state yet).
    const SessionGuidance::CollapsingEdges* drawn_ = nullptr;
};

}  // namespace trilab::viewer
