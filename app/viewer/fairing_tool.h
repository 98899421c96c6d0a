#pragma once
// FairingTool: the Fairing section's tool. Besides the operation panel's previews it keeps
// the largest stable explicit step of the current mesh and operator, and the spectral lens:
// the transfer curve over the decomposition's eigenvalues (or the analytic range), with the
// measured gain of the preview shown or of the current entry when it is a smoothing with
// the panel's settings.
#include <string>

#include "app/viewer/operation_tool.h"

namespace trilab::viewer {

class FairingTool : public OperationTool {
public:
    explicit FairingTool(ViewerContext& context);
    void update() override;
    void section(const SidebarContext& context, CommandQueue& commands) override;
    PanelEntries panels() override;
    void settings(SettingsVisitor& v) override { operation_setting(v, "panel.fairing", panel_); }
    bool show_figure(const Operation& op) override { return take_figure(panel_, op); }
    FairingPanelState& panel() { return panel_; }

private:
    void update_stable_step();
    void update_lens();
    FairingPanelState panel_;
    std::string lens_key_;  ///< what the transfer curve was computed for
};

}  // namespace trilab::viewer
