#include "app/viewer/operation_tool.h"

#include <cstdio>
#include <optional>
#include <string>

#include "core/algorithms/selection.h"

namespace trilab::viewer {

void OperationTool::update() {
    const Session& session = context_.session;
    // The previews (Cancel shows), and whether they stay live.
    const std::optional<Operation>& requested = session.previews().requested();
    for (OperationPanelState* panel : panels_) {
        panel->previewing = session.previews().previewing(panel->op);
        if (!requested || requested->def != panel->op.def) continue;
        const double ms = session.previews().last_ms();
        if (ms < 0 || ms == panel->latency_ms || context_.sweeping) continue;
        panel->latency_ms = ms;
        note_preview_latency(*panel, ms);
    }
    // The note when the document has a selection.
    const HalfedgeMesh& mesh = session.mesh();
    const std::uint64_t state = mesh.attribute_revision() ^ (mesh.topology_revision() << 20);
    if (state == region_notes_state_) return;
    region_notes_state_ = state;
    std::string selected, whole;
    if (const std::optional<Selection> s = stored_selection(mesh);
        s && !selects_everything(mesh, *s)) {
        selected = "acts on the selection: " + std::to_string(count_selected(*s)) + " of " +
                   std::to_string(mesh.n_vertices()) + " vertices (weight > 0)";
        whole = "the document has a selection, but this operation acts on the whole mesh";
    }
    for (OperationPanelState* panel : panels_)
        panel->region_note = selected.empty()                               ? std::string()
                             : panel->op.def && panel->op.def->takes_region ? selected
                                                                            : whole;
}

bool OperationTool::take_figure(OperationPanelState& panel, const Operation& op) {
    if (op.def != panel.op.def) return false;
    panel.op = op;
    panel.open = true;
    return true;
}

GenericOperationTool::GenericOperationTool(ViewerContext& context,
                                           const std::vector<const OperationDef*>& owned)
    : OperationTool(context, {}), tools_(tool_panels(owned)) {
    set_panels(pointers(tools_));
}

std::vector<OperationPanelState*> GenericOperationTool::pointers(
    std::vector<OperationPanelState>& tools) {
    std::vector<OperationPanelState*> out;
    for (OperationPanelState& tool : tools) out.push_back(&tool);
    return out;
}

void GenericOperationTool::section(const SidebarContext& context, CommandQueue& commands) {
    tools_section(tools_, context.busy, commands);
}

PanelEntries GenericOperationTool::panels() {
    PanelEntries entries;
    for (OperationPanelState& tool : tools_) {
        PanelEntry entry;
        entry.name = tool.op.name();
        entry.open = &tool.open;
        entry.menu = PanelMenu::Tools;
        entry.in_tools = true;
        if (tool.op.def->params.empty()) {
            entry.title = tool.op.def->label;
            entry.action = &tool.op;
        } else {
            entry.title = tool.op.def->label + "...";
        }
        entries.push_back(std::move(entry));
    }
    return entries;
}

void GenericOperationTool::settings(SettingsVisitor& v) {
    for (OperationPanelState& tool : tools_)
        operation_setting(v, "panel.tool." + tool.op.def->name, tool);
}

OperationPanelState* GenericOperationTool::panel(const std::string& name) {
    for (OperationPanelState& tool : tools_)
        if (tool.op.name() == name) return &tool;
    return nullptr;
}

void OperationTool::note_preview_latency(OperationPanelState& panel, double ms) {
    constexpr double kLiveBudgetMs = 150.0;  ///< previews slower than this wait for the release
    char buf[160];
    panel.live = ms <= kLiveBudgetMs;
    if (panel.live)
        std::snprintf(buf, sizeof buf, "preview %.0f ms", ms);
    else
        std::snprintf(buf, sizeof buf,
                      "preview %.0f ms: over the %.0f ms budget, previews when a drag ends", ms,
                      kLiveBudgetMs);
    panel.preview_note = buf;
}

}  // namespace trilab::viewer
