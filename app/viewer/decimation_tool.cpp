#include "app/viewer/decimation_tool.h"

#include <string>
#include <vector>

#include "app/ops/operation.h"
#include "app/ops/operation_entries.h"
#include "core/algorithms/decimation.h"
#include "core/errors.h"

namespace trilab::viewer {

DecimationTool::DecimationTool(ViewerContext& context) : OperationTool(context, {}) {
    set_panels({&panel_});
}

void DecimationTool::section(const SidebarContext& context, CommandQueue& commands) {
    decimation_section(panel_, context, commands);
}

PanelEntries DecimationTool::panels() {
    PanelEntry decimation;
    decimation.name = "decimation";
    decimation.title = "Decimation";
    decimation.open = &panel_.open;
    decimation.menu = PanelMenu::Algorithms;
    PanelEntry edges;  // Rendering > Vectors > Collapsing edges
    edges.name = "collapsing-edges";
    edges.title = "Collapsing edges";
    edges.open = &panel_.show_collapsing_edges;
    edges.in_all = false;
    return {decimation, edges};
}

void DecimationTool::settings(SettingsVisitor& v) {
    operation_setting(v, "panel.decimation", panel_);
    v.number("decimation.lod_percent", panel_.lod_percent);
    v.flag("decimation.show_collapsing_edges", panel_.show_collapsing_edges);
}

void DecimationTool::update() {
    OperationTool::update();
    Session& session = context_.session;
    // The level of detail.
    DecimationPanelState& d = panel_;
    d.lod_ready = session.levels().ready();
    d.lod_building = session.levels().building();
    d.lod_note = session.levels().note();
    if (!d.lod_ready) d.lod_percent = 100.0f;
    // The Inspector explains a collapse with the panel's options.
    try {
        session.execute(SetInspectionOptions{decimation_options(d.op)});
    } catch (const std::exception&) {
        // The panel shows its own error; the inspector keeps the last valid options.
    }
    update_collapsing_edges();
}

void DecimationTool::describe(SidebarContext& context) const {
    context.collapsing_edges = panel_.show_collapsing_edges && lines_ ? lines_->n_segments() : 0;
}

void DecimationTool::draw_overlay() {
    if (!panel_.show_collapsing_edges || !lines_) return;
    const Camera& camera = context_.view.camera;
    lines_->draw(camera.view(), camera.projection(), LineStyle{}, context_.ui_scale);
}

void DecimationTool::update_collapsing_edges() {
    const DecimationPanelState& d = panel_;
    if (!d.show_collapsing_edges) return;
    Session& session = context_.session;
    // The session finds them off the render thread (SessionGuidance): a dry run of the next
    // iteration; meshes over its size limit get none. Until the edges of this state and these
    // options arrive, none are drawn (the last ones would be of another shape).
    session.execute(FindCollapsingEdges{d.op});
    const SessionGuidance::CollapsingEdges* found = session.guidance().collapsing_edges();
    const bool current = found && found->state == session.mesh().revision() && found->op == d.op;
    if (!current) found = nullptr;
    if (found == drawn_ && lines_) return;
    drawn_ = found;
    if (!lines_) lines_ = std::make_unique<LineRenderer>();  // the GL context is current here
    std::vector<glm::vec3> points;
    if (found)
        for (const std::array<Point, 2>& segment : found->segments)
            for (const Point& p : segment)
                points.emplace_back(float(p.x()), float(p.y()), float(p.z()));
    lines_->set_segments(points);
}

}  // namespace trilab::viewer
