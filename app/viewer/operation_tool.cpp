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
