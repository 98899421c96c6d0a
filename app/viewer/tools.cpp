#include "app/viewer/tools.h"

#include "app/viewer/decimation_tool.h"
#include "app/viewer/fairing_tool.h"
#include "app/viewer/frequency_tool.h"
#include "app/viewer/operation_tool.h"
#include "app/viewer/pick_tool.h"
#include "app/viewer/scene_view.h"
#include "app/viewer/selection_tool.h"

namespace trilab::viewer {

Tools make_tools(ViewerContext& context, SceneView& scene) {
    Tools tools;
    // The selection takes Ctrl/Alt drags before a click picks.
    auto selection = std::make_unique<SelectionTool>(context, scene.exact());
    auto pick =
        std::make_unique<PickTool>(context, [&scene] { return scene.geodesic_colored_version(); });
    tools.selection = selection.get();
    tools.pick = pick.get();
    tools.all.push_back(std::move(selection));
    tools.all.push_back(std::move(pick));
    tools.all.push_back(std::make_unique<FairingTool>(context));
    tools.all.push_back(std::make_unique<DecimationTool>(context));
    tools.all.push_back(std::make_unique<FrequencyTool>(context));
    // Subdivision and every registered operation without a panel of its own.
    std::vector<OperationPanelState*> panels{&context.panels.subdivision};
    for (OperationPanelState& tool : context.panels.tools) panels.push_back(&tool);
    tools.all.push_back(std::make_unique<OperationTool>(context, std::move(panels)));
    return tools;
}

}  // namespace trilab::viewer
