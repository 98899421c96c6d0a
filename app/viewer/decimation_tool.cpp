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
    const HalfedgeMesh& mesh = context_.session.mesh();
    // The mesh state (its topology and geometry revisions) and the options the edges were
    // computed for.
    const std::string key = std::to_string(mesh.topology_revision()) + " " +
                            std::to_string(mesh.geometry_revision()) + " " + d.op.text();
    if (key == key_ && lines_) return;
    key_ = key;
    if (!lines_) lines_ = std::make_unique<LineRenderer>();  // the GL context is current here
    std::vector<glm::vec3> points;
    // Computed on the render thread: a dry run of the next iteration, a fraction of a second
    // up to a few hundred thousand vertices; bigger meshes skip the overlay.
    constexpr std::size_t kMaxOverlayVertices = 300000;
    if (mesh.n_vertices() > kMaxOverlayVertices) {
        context_.session.log().warning(
            "Collapsing edges: shown for meshes of up to 300,000 vertices only");
        lines_->set_segments(points);
        return;
    }
    try {
        const DecimationOptions o = decimation_options(d.op);
        for (const auto& pair : next_collapses(mesh, o)) {
            const Point& a = mesh.position(pair[0]);
            const Point& b = mesh.position(pair[1]);
            points.emplace_back(float(a.x()), float(a.y()), float(a.z()));
            points.emplace_back(float(b.x()), float(b.y()), float(b.z()));
        }
    } catch (const Error& e) {
        context_.session.notify_error(std::string("Collapsing edges: ") + e.what());
    }
    lines_->set_segments(points);
}

}  // namespace trilab::viewer
