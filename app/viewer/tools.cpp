#include "app/viewer/tools.h"

#include "app/viewer/compare_tool.h"
#include "app/viewer/decimation_tool.h"
#include "app/viewer/denoise_tool.h"
#include "app/viewer/fairing_tool.h"
#include "app/viewer/features_tool.h"
#include "app/viewer/fill_holes_tool.h"
#include "app/viewer/frequency_tool.h"
#include "app/viewer/morph_tool.h"
#include "app/viewer/operation_tool.h"
#include "app/viewer/pick_tool.h"
#include "app/viewer/remesh_tool.h"
#include "app/viewer/selection_tool.h"
#include "app/viewer/subdivision_tool.h"

namespace trilab::viewer {

namespace {

/// Model information: the window's lines about the model and scene (PanelState::info_open,
/// the I key), drawn in the sidebar between Record and the Inspector.
class InfoTool : public Tool {
public:
    using Tool::Tool;
    void section(const SidebarContext& context, CommandQueue& /*commands*/) override {
        info_section(context_.panels.info_open,
                     context.info ? *context.info : std::vector<std::string>{});
    }
};

template <class T>
T* add(Tools& tools, std::unique_ptr<T> tool) {
    T* raw = tool.get();
    tools.all.push_back(std::move(tool));
    return raw;
}

}  // namespace

ToolList Tools::list() const {
    ToolList out;
    for (const auto& tool : all) out.push_back(tool.get());
    return out;
}

PanelEntries Tools::entries() const {
    PanelEntries out;
    for (const auto& tool : all)
        for (PanelEntry& entry : tool->panels()) out.push_back(std::move(entry));
    return out;
}

Tools make_tools(ViewerContext& context, MeshRenderer* exact,
                 std::function<std::uint64_t()> geodesic_colored) {
    Tools tools;
    tools.selection = add(tools, std::make_unique<SelectionTool>(context, exact));
    add(tools, std::make_unique<FairingTool>(context));
    tools.frequency = add(tools, std::make_unique<FrequencyTool>(context));
    add(tools, std::make_unique<SubdivisionTool>(context));
    tools.decimation = add(tools, std::make_unique<DecimationTool>(context));
    add(tools, std::make_unique<DenoiseTool>(context));
    add(tools, std::make_unique<FeaturesTool>(context));
    add(tools, std::make_unique<FillHolesTool>(context));
    add(tools, std::make_unique<RemeshTool>(context));
    add(tools, std::make_unique<CompareTool>(context));
    add(tools, std::make_unique<MorphTool>(context));
    add(tools, std::make_unique<InfoTool>(context));
    tools.pick = add(tools, std::make_unique<PickTool>(context, std::move(geodesic_colored)));
    tools.pick->set_band(&tools.frequency->panel());
    // Every registered operation without a panel of its own: the generic tool, first in the
    // sidebar ("Tools: ...").
    std::vector<const OperationDef*> owned;
    for (const auto& tool : tools.all)
        for (OperationPanelState* panel : tool->operation_panels()) owned.push_back(panel->op.def);
    owned.push_back(tools.frequency->panel().op.def);
    tools.all.insert(tools.all.begin(), std::make_unique<GenericOperationTool>(context, owned));
    return tools;
}

}  // namespace trilab::viewer
