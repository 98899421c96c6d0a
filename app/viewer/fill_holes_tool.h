#pragma once
// FillHolesTool: the Fill holes section's tool (the "fill-holes" operation,
// app/ops/fill_holes_op.cpp, issue 41). Its panel is the operation's live-preview panel (the
// size limits, the rim's continuity) and, below it, the holes of the document: every
// boundary loop numbered as `trilab-cli fill-holes --loops` numbers them, with its edges and
// its size as a share of the model's diagonal, a check box each; the loops are outlined in
// the view while the section is open (the checked ones brighter). "Fill the checked loops"
// selects their rims and fills them: two history entries, the selection first, so a recipe
// replays it. The new vertices come out as the selection (Selection > Clear drops it).
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "app/viewer/operation_tool.h"
#include "core/algorithms/hole_filling.h"
#include "render/line_renderer.h"

namespace trilab::viewer {

/// The selection weights of the rims of the loops whose `checked` entry is set (1 on their
/// vertices, 0 elsewhere; one weight per vertex storage index of a mesh of `n_vertices`).
std::vector<float> rim_weights(const std::vector<BoundaryLoop>& loops,
                               const std::vector<std::uint8_t>& checked, std::size_t n_vertices);

class FillHolesTool : public OperationTool {
public:
    explicit FillHolesTool(ViewerContext& context);
    void update() override;
    void section(const SidebarContext& context, CommandQueue& commands) override;
    void draw_overlay() override;
    PanelEntries panels() override;
    void settings(SettingsVisitor& v) override;
    bool show_figure(const Operation& op) override { return take_figure(panel_, op); }
    OperationPanelState& panel() { return panel_; }
    /// The document's boundary loops (found while the section is open, once per connectivity).
    const std::vector<BoundaryLoop>& loops() const { return loops_; }
    /// One entry per loop: checked in the panel.
    std::vector<std::uint8_t>& checked() { return checked_; }

    /// Rows listed at most (a scan may have hundreds of holes; the rest are counted).
    static constexpr std::size_t kMaxRows = 60;

private:
    void holes_list(const SidebarContext& context, CommandQueue& commands);
    OperationPanelState panel_{"fill-holes"};
    std::vector<BoundaryLoop> loops_;
    std::vector<std::uint8_t> checked_;
    double diagonal_ = 0;                             ///< the document's bounding-box diagonal
    std::uint64_t loops_key_ = ~std::uint64_t(0);     ///< the document topology they are of
    bool upload_ = false;                             ///< the outlines changed since the upload
    std::unique_ptr<LineRenderer> all_renderer_;      ///< every loop's outline
    std::unique_ptr<LineRenderer> checked_renderer_;  ///< the checked loops' outlines
};

}  // namespace trilab::viewer
