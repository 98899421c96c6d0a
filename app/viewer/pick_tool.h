#pragma once
// PickTool: picking in the view and the Inspector. A click that does not drag picks the
// vertex, edge and face under the cursor (Ctrl: the second pick, measuring the straight and
// geodesic distance); a double click also centres the view there. The tool draws the picked
// elements and the geodesic path over the surface and prepares the Inspector's rows (the
// panel holds no mesh and computes nothing).
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "app/viewer/tool.h"
#include "render/line_renderer.h"

namespace trilab::viewer {

class PickTool : public Tool {
public:
    /// `geodesic_colored`: the picks version the geodesic colours on the screen show.
    PickTool(ViewerContext& context, std::function<std::uint64_t()> geodesic_colored)
        : Tool(context), geodesic_colored_(std::move(geodesic_colored)) {}
    void update() override;
    void describe(SidebarContext& context) const override { context.inspector = &inspector_; }
    bool mouse(const ViewMouse& mouse) override;
    void draw_overlay() override;
    /// Picks at `view_pos` (pixels relative to the view's top left); opens the Inspector.
    std::optional<Pick> pick_at(const glm::vec2& view_pos, bool second);
    void section(const SidebarContext& context, CommandQueue& commands) override;
    PanelEntries panels() override;
    /// The frequency band the Inspector explains a vertex in (the Frequency tool's sliders).
    void set_band(const FrequencyPanelState* band) { band_ = band; }
    bool& inspector_open() { return inspector_open_; }

private:
    void update_overlay();
    std::function<std::uint64_t()> geodesic_colored_;
    std::unique_ptr<LineRenderer> face_lines_, edge_lines_, vertex_lines_, path_lines_;
    std::string overlay_key_;
    std::string inspector_key_;
    InspectorView inspector_;
    bool inspector_open_ = false;
    const FrequencyPanelState* band_ = nullptr;
    int band_lo() const { return band_ ? band_->lo : 0; }
    int band_hi() const { return band_ ? band_->hi : 0; }
};

}  // namespace trilab::viewer
