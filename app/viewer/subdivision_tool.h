#pragma once
// SubdivisionTool: the Subdivision section's tool. An operation panel of its own for the
// note the generic panel has not: with unwelded seams (coincident boundary edges) Sqrt3
// leaves creases, and the section offers the weld.
#include "app/viewer/operation_tool.h"

namespace trilab::viewer {

class SubdivisionTool : public OperationTool {
public:
    explicit SubdivisionTool(ViewerContext& context) : OperationTool(context, {}) {
        set_panels({&panel_});
    }
    void section(const SidebarContext& context, CommandQueue& commands) override {
        subdivision_section(panel_, context, commands);
    }
    PanelEntries panels() override {
        PanelEntry entry;
        entry.name = "subdivision";
        entry.title = "Subdivision";
        entry.open = &panel_.open;
        entry.menu = PanelMenu::Algorithms;
        return {entry};
    }
    void settings(SettingsVisitor& v) override {
        operation_setting(v, "panel.subdivision", panel_);
    }
    bool show_figure(const Operation& op) override { return take_figure(panel_, op); }
    OperationPanelState& panel() { return panel_; }

private:
    OperationPanelState panel_{"subdivide"};
};

}  // namespace trilab::viewer
