#pragma once
// OperationTool: the tool of operation panels (every registered operation's panel, generic
// or of its own): whether each previews, how long its previews take (a panel whose previews
// are slow waits for the release of a drag), and what it acts on when the document has a
// selection. Fairing and Decimation extend it with their own displays.
#include <cstdint>
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

private:
    std::vector<OperationPanelState*> panels_;
    std::uint64_t region_notes_state_ = ~std::uint64_t(0);
};

}  // namespace trilab::viewer
