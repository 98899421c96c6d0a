#pragma once
// FeaturesTool: the Features section's tool (the "features" operation,
// app/ops/features_op.cpp, issue 39). Its panel is the operation's live-preview panel: the
// angle slider previews the detection at once (on the session's job runner), with the
// number of feature edges, chains and corners, and the histogram of the dihedral angles with
// its plateau marked (where the count barely changes: the natural threshold) and the chosen
// angle; on a mesh with no plateau it says so and points to denoising. The feature lines of
// the shown surface (its edges of positive sharpness) are drawn over every render mode.
// Tagging by hand (the "sharpen" operation, one history entry each): with "tag edges by
// clicking" on, a click on the model toggles the edge nearest to it (sharp at the panel's
// sharpness, or smooth again); "Sharpen the selection's edges" and "Clear them" tag every
// edge with both ends selected.
// Made by following docs/recipes.md "A new operation with a panel of its own".
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "app/viewer/operation_tool.h"
#include "core/algorithms/feature_detection.h"
#include "render/line_renderer.h"

namespace trilab::viewer {

/// The segments of the edges of positive sharpness ("e:sharpness", core/features.h) of
/// `mesh`, at `positions` (one per vertex storage index) or the mesh's own when empty.
std::vector<std::array<Point, 2>> feature_segments(const HalfedgeMesh& mesh,
                                                   const std::vector<Point>& positions);

class FeaturesTool : public OperationTool {
public:
    explicit FeaturesTool(ViewerContext& context);
    void update() override;
    void section(const SidebarContext& context, CommandQueue& commands) override;
    void draw_overlay() override;
    bool mouse(const ViewMouse& mouse) override;
    PanelEntries panels() override;
    void settings(SettingsVisitor& v) override;
    bool show_figure(const Operation& op) override { return take_figure(panel_, op); }
    OperationPanelState& panel() { return panel_; }
    /// The feature lines of the shown surface (what draw_overlay() draws).
    const std::vector<std::array<Point, 2>>& lines() const { return lines_; }
    /// Whether the feature lines are drawn (the panel's check box).
    bool show_lines() const { return show_lines_; }
    /// The detection report of the preview shown (null: none).
    const FeatureDetectionReport* report() const;
    /// Tagging: clicks toggle edges; the sharpness they and the selection's buttons give
    /// (`infinite`, or `sharpness`).
    bool& tag_by_click() { return tag_by_click_; }
    bool& infinite() { return infinite_; }
    float& sharpness() { return sharpness_; }
    /// The "sharpen" operation that toggles edge `e` of the document: smooth again when it is
    /// sharp, else sharp as the panel says.
    Operation toggle_edge(Edge e) const;
    /// The "sharpen" operation for the selection's edges (`clear`: smooth again).
    Operation sharpen_selection(bool clear) const;

private:
    OperationPanelState panel_{"features"};
    void tagging(const SidebarContext& context, CommandQueue& commands);
    bool show_lines_ = true;  ///< Features > show feature lines
    bool tag_by_click_ = false;
    bool infinite_ = true;
    float sharpness_ = 2.0f;
    /// The shown mesh's sharp edges, for its connectivity and properties (edges_key_).
    std::vector<std::array<Vertex, 2>> edges_;
    std::array<std::uint64_t, 2> edges_key_{0, 0};
    std::vector<std::array<Point, 2>> lines_;
    std::uint64_t lines_version_ = ~std::uint64_t(0);  ///< the shown state they are of
    bool upload_ = false;                              ///< lines_ changed since the upload
    std::unique_ptr<LineRenderer> renderer_;
};

}  // namespace trilab::viewer
