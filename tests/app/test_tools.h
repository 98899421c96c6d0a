#pragma once
// The viewer's tools over a context of their own, for the panel tests (no window, no GL):
// make_tools() as the viewer calls it, and the panels the tools own under the names the
// tests reach them by (the fields PanelState had before the tools owned their panels).
#include <catch2/catch.hpp>

#include <string>
#include <vector>

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
#include "app/viewer/tools.h"

namespace trilab::viewer::testing {

/// The tool of type T in `tools` (the test fails without one).
template <class T>
T& find_tool(const Tools& tools) {
    for (const auto& tool : tools.all)
        if (T* t = dynamic_cast<T*>(tool.get())) return *t;
    FAIL("no such tool");
    throw;  // not reached
}

struct TestPanels {
    ViewerContext context;
    Tools all_tools = make_tools(context, nullptr, {});
    PanelState& window = context.panels;
    // The window's own.
    LayoutState& layout = window.layout;
    ScreenshotState& screenshot = window.screenshot;
    FileBrowserState& file_browser = window.file_browser;
    UnsavedPrompt& unsaved = window.unsaved;
    bool& history_open = window.history_open;
    bool& help_open = window.help_open;
    bool& about_open = window.about_open;
    bool& log_open = window.log_open;
    bool& info_open = window.info_open;
    bool& sidebar_open = window.sidebar_open;
    // The tools'.
    SelectionPanelState& selection = find_tool<SelectionTool>(all_tools).panel();
    OperationPanelState& subdivision = find_tool<SubdivisionTool>(all_tools).panel();
    FairingPanelState& fairing = find_tool<FairingTool>(all_tools).panel();
    FrequencyPanelState& frequency = find_tool<FrequencyTool>(all_tools).panel();
    DecimationPanelState& decimation = find_tool<DecimationTool>(all_tools).panel();
    OperationPanelState& denoise = find_tool<DenoiseTool>(all_tools).panel();
    OperationPanelState& features = find_tool<FeaturesTool>(all_tools).panel();
    OperationPanelState& fill_holes = find_tool<FillHolesTool>(all_tools).panel();
    OperationPanelState& remesh = find_tool<RemeshTool>(all_tools).panel();
    bool& compare_open = find_tool<CompareTool>(all_tools).open();
    RecordState& record = find_tool<MorphTool>(all_tools).record();
    bool& morph_open = find_tool<MorphTool>(all_tools).morph_open();
    bool& inspector_open = find_tool<PickTool>(all_tools).inspector_open();
    /// The generic tool's panels (every registered operation without a tool of its own).
    std::vector<OperationPanelState>& tools = find_tool<GenericOperationTool>(all_tools).all();
    OperationPanelState* tool(const std::string& name) {
        return find_tool<GenericOperationTool>(all_tools).panel(name);
    }
    ToolList list() const { return all_tools.list(); }
    PanelEntries entries() const { return all_tools.entries(); }
    operator PanelState&() { return window; }
};

}  // namespace trilab::viewer::testing
