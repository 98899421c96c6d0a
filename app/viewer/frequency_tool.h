#pragma once
// FrequencyTool: the Frequency decomposition section's tool. The panel queues its commands
// for the session (app/session/session_frequency.cpp: the decomposition job, the live band,
// the history entries); the tool sets the band's sliders when a new decomposition arrives
// and computes the colourings made from fields: Frequency and Frequency mass (the
// decomposition's eigenvectors over the band), Removed below / above (what the current entry
// changed, split at the band's top), and the geodesic distance from the picks.
#include "app/viewer/tool.h"
#include "core/algorithms/spectral.h"

namespace trilab::viewer {

class FrequencyTool : public Tool {
public:
    explicit FrequencyTool(ViewerContext& context) : Tool(context) {}
    void update() override;
    VertexColors field_colors(const HalfedgeMesh& mesh) const override;
    void section(const SidebarContext& context, CommandQueue& commands) override;
    PanelEntries panels() override;
    void settings(SettingsVisitor& v) override;
    /// A "spectrum" figure: its count, and its band on the sliders.
    bool show_figure(const Operation& op) override;
    FrequencyPanelState& panel() { return panel_; }

private:
    void on_decomposed(std::size_t hi);
    FrequencyPanelState panel_;
    /// The decomposition the sliders were set for.
    const SpectralDecomposition* decomposition_ = nullptr;
};

}  // namespace trilab::viewer
