#include "app/viewer/fill_holes_tool.h"

#include <imgui.h>

#include <cstdio>
#include <string>

#include "app/viewer/panel_helpers.h"
#include "app/viewer/widgets.h"
#include "core/geometry.h"

namespace trilab::viewer {

using namespace ui;

std::vector<float> rim_weights(const std::vector<BoundaryLoop>& loops,
                               const std::vector<std::uint8_t>& checked, std::size_t n_vertices) {
    std::vector<float> weights(n_vertices, 0.0f);
    for (std::size_t i = 0; i < loops.size() && i < checked.size(); ++i) {
        if (!checked[i]) continue;
        for (Vertex v : loops[i].vertices)
            if (v.idx() < n_vertices) weights[v.idx()] = 1.0f;
    }
    return weights;
}

FillHolesTool::FillHolesTool(ViewerContext& context) : OperationTool(context, {}) {
    set_panels({&panel_});
}

void FillHolesTool::update() {
    OperationTool::update();
    // The loops of the document, while the section is open: O(V + E) once per connectivity.
    if (!panel_.open) return;
    const HalfedgeMesh& mesh = context_.session.mesh();
    if (mesh.topology_revision() == loops_key_) return;
    loops_key_ = mesh.topology_revision();
    loops_ = boundary_loops(mesh);
    checked_.assign(loops_.size(), 0);
    const BoundingBox box = bounding_box(mesh);
    diagonal_ = box.empty ? 0.0 : (box.max - box.min).norm();
    upload_ = true;
}

void FillHolesTool::draw_overlay() {
    if (!panel_.open || loops_.empty()) return;
    const Shown& shown = context_.session.shown();
    if (shown.kind != Shown::Kind::Document) return;  // a preview moves or closes the rims
    if (!all_renderer_) {                             // the GL context is current
        all_renderer_ = std::make_unique<LineRenderer>();
        checked_renderer_ = std::make_unique<LineRenderer>();
    }
    if (upload_) {
        const HalfedgeMesh& mesh = context_.session.mesh();
        std::vector<glm::vec3> all, marked;
        for (std::size_t i = 0; i < loops_.size(); ++i) {
            const std::vector<Vertex>& rim = loops_[i].vertices;
            for (std::size_t k = 0; k < rim.size(); ++k)
                for (Vertex v : {rim[k], rim[(k + 1) % rim.size()]}) {
                    const Point& p = mesh.position(v);
                    (checked_[i] ? marked : all)
                        .emplace_back(float(p.x()), float(p.y()), float(p.z()));
                }
        }
        all_renderer_->set_segments(all);
        checked_renderer_->set_segments(marked);
        upload_ = false;
    }
    const Camera& camera = context_.view.camera;
    LineStyle style;
    style.color = glm::vec3(0.95f, 0.65f, 0.15f);  // amber: the holes
    style.width = 2.0f;
    all_renderer_->draw(camera.view(), camera.projection(), style, context_.ui_scale);
    style.color = glm::vec3(0.2f, 0.95f, 0.45f);  // green: the checked ones
    style.width = 3.5f;
    checked_renderer_->draw(camera.view(), camera.projection(), style, context_.ui_scale);
}

void FillHolesTool::holes_list(const SidebarContext& context, CommandQueue& commands) {
    if (loops_.empty()) {
        wrapped_disabled("no boundary loops: the surface is closed");
        return;
    }
    ImGui::TextWrapped("%zu boundary loop%s (holes), outlined in the view", loops_.size(),
                       loops_.size() == 1 ? "" : "s");
    if (button("Check all")) {
        checked_.assign(loops_.size(), 1);
        upload_ = true;
    }
    ImGui::SameLine();
    if (button("Check none")) {
        checked_.assign(loops_.size(), 0);
        upload_ = true;
    }
    for (std::size_t i = 0; i < loops_.size() && i < kMaxRows; ++i) {
        char label[128];
        std::snprintf(label, sizeof(label), "loop %zu: %zu edges, %.2f %% of the diagonal", i,
                      loops_[i].edges(),
                      diagonal_ > 0 ? 100.0 * loops_[i].diagonal / diagonal_ : 0.0);
        const std::string id = "loop " + std::to_string(i);
        bool on = checked_[i] != 0;
        if (checkbox(label, &on, id.c_str())) {
            checked_[i] = on ? 1 : 0;
            upload_ = true;
        }
    }
    if (loops_.size() > kMaxRows)
        wrapped_disabled("... and %zu more (Check all includes them)", loops_.size() - kMaxRows);
    std::size_t n_checked = 0;
    for (std::uint8_t c : checked_) n_checked += c ? 1 : 0;
    const bool can = n_checked > 0 && !context.busy;
    if (!can) ImGui::BeginDisabled();
    if (button("Fill the checked loops")) {
        std::string which;
        for (std::size_t i = 0; i < checked_.size(); ++i)
            if (checked_[i]) which += (which.empty() ? "" : ",") + std::to_string(i);
        commands.push_back(
            SetSelection{rim_weights(loops_, checked_, context_.session.mesh().vertices_size()),
                         "Select holes", "loops " + which});
        commands.push_back(ApplyOperation{panel_.op});
    }
    if (!can) ImGui::EndDisabled();
    if (n_checked == 0) {
        ImGui::SameLine();
        ImGui::TextDisabled("(check a loop first)");
    }
}

void FillHolesTool::section(const SidebarContext& context, CommandQueue& commands) {
    SidebarSection section("Fill holes", panel_.open);
    if (!section) return;
    ImGui::TextWrapped("%s", panel_words(panel_.op.def->summary).c_str());
    operation_panel_body(panel_, "Fill", context.busy, commands);
    ImGui::Separator();
    holes_list(context, commands);
    ImGui::Separator();
    morph_hint();
}

PanelEntries FillHolesTool::panels() {
    PanelEntry entry;
    entry.name = "fill-holes";
    entry.title = "Fill holes...";
    entry.open = &panel_.open;
    entry.menu = PanelMenu::Tools;
    entry.in_tools = true;
    return {entry};
}

void FillHolesTool::settings(SettingsVisitor& v) {
    // The key the generic panel saved it under before the tool had its own panel.
    operation_setting(v, "panel.tool.fill-holes", panel_);
}

}  // namespace trilab::viewer
