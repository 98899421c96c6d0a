#pragma once
// OperationTool: the base of the tools of operation panels (every registered operation's
// panel, generic or of its own): whether each previews, how long its previews take (a panel
// whose previews are slow waits for the release of a drag), and what it acts on when the
// document has a selection. Fairing, Subdivision, Decimation and Denoise extend it with their
// own panels; GenericOperationTool holds a generic panel for every registered operation
// without a tool of its own.
#include <cstdint>
#include <string>
#include <vector>

#include "app/viewer/tool.h"

namespace trilab::viewer {

class OperationTool : public Tool {
public:
    OperationTool(ViewerContext& context, std::vector<OperationPanelState*> panels)
        : Tool(context), panels_(std::move(panels)) {}
    void update() override;
    std::vector<OperationPanelState*> operation_panels() override { return panels_; }
    /// The panel's preview note for a preview of `ms` and whether it stays live.
    static void note_preview_latency(OperationPanelState& panel, double ms);
    /// The operation panels this tool keeps up to date (set by a tool that owns them).
    void set_panels(std::vector<OperationPanelState*> panels) { panels_ = std::move(panels); }

protected:
    /// The operation panel's saved setting ("panel.fairing") and figure (opens it).
    static void operation_setting(SettingsVisitor& v, const std::string& key,
                                  OperationPanelState& panel) {
        v.operation(key, panel.op);
    }
    static bool take_figure(OperationPanelState& panel, const Operation& op);

private:
    std::vector<OperationPanelState*> panels_;
    std::uint64_t region_notes_state_ = ~std::uint64_t(0);
};

/// The generic tool: one panel for every registered operation that no tool in `owned` holds
/// (Add noise, Weld coincident vertices, Flip orientation, and any operation registered
/// later), in the registry's order. One without parameters is a menu action (Tools > Flip
/// orientation); the others are sidebar sections "Tools: ..." (tools_section()).
class GenericOperationTool : public OperationTool {
public:
    GenericOperationTool(ViewerContext& context, const std::vector<const OperationDef*>& owned);
    void section(const SidebarContext& context, CommandQueue& commands) override;
    PanelEntries panels() override;
    void settings(SettingsVisitor& v) override;
    /// The panel of the operation `name` (nullptr: none).
    OperationPanelState* panel(const std::string& name);
    std::vector<OperationPanelState>& all() { return tools_; }

private:
    static std::vector<OperationPanelState*> pointers(std::vector<OperationPanelState>& tools);
    std::vector<OperationPanelState> tools_;
};

}  // namespace trilab::viewer
