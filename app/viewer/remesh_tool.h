#pragma once
// RemeshTool: the Remesh section's tool (the "remesh" operation, app/ops/remesh_op.cpp,
// issue 41). Its panel is the operation's live-preview panel and, beside it, what a user
// needs before and after a remeshing: before it runs, the target length and how many faces
// it will make (remesh_plan(): the area over the ideal triangle's, refused past the memory
// this process may allocate), updated as the parameters change; and the quality of the
// document against the preview shown (mesh_quality(): the smallest angle, the mean of the
// per-face smallest angles, the share of angles under 30 degrees, of edges within
// [0.8 L, 4/3 L], of valence-6 vertices) and the cotangent Laplacian's spread (the largest
// weight over the median, the share of negative weights: cotangent_spread()), so the gain,
// and why fairing gains from it, is read, not guessed. Both are computed on a worker thread
// from copies, once per document state and parameters (the plan and the document's quality)
// and once per preview (its quality): each is O(F), tens of milliseconds on a million faces,
// never a frame's wait.
#include <array>
#include <future>
#include <optional>
#include <string>
#include <vector>

#include "app/viewer/operation_tool.h"
#include "core/algorithms/mesh_quality.h"
#include "core/algorithms/remesh.h"

namespace trilab::viewer {

/// A mesh's quality figures and its cotangent Laplacian's spread (why a remeshing helps
/// curvature-flow fairing and the spectral decomposition: 1-degree triangles give weights
/// hundreds of times the median, and negative ones).
struct RemeshQuality {
    MeshQuality quality;
    CotangentSpread spread;
};
RemeshQuality remesh_quality(const HalfedgeMesh& mesh, std::optional<double> length);

/// The lines of the before/after quality table: {label, before, after} with the numbers
/// formatted ("-" where `after` is absent).
std::vector<std::array<std::string, 3>> quality_rows(const RemeshQuality& before,
                                                     const RemeshQuality* after);

class RemeshTool : public OperationTool {
public:
    explicit RemeshTool(ViewerContext& context);
    void update() override;
    void section(const SidebarContext& context, CommandQueue& commands) override;
    PanelEntries panels() override;
    void settings(SettingsVisitor& v) override;
    bool show_figure(const Operation& op) override { return take_figure(panel_, op); }
    OperationPanelState& panel() { return panel_; }
    /// The plan of the panel's parameters on the document (empty with plan_error() set when
    /// they cannot run).
    const std::optional<RemeshReport>& plan() const { return plan_; }
    const std::string& plan_error() const { return plan_error_; }
    /// The document's quality and the preview's (empty: no remeshing preview shown), at the
    /// plan's target length.
    const std::optional<RemeshQuality>& before() const { return before_; }
    const std::optional<RemeshQuality>& after() const { return after_; }
    /// Whether a computation is running.
    bool computing() const { return plan_job_.valid() || after_job_.valid(); }
    /// Waits for the running computations and takes their results (tests).
    void finish();

private:
    /// What the worker computes for one document state and parameters.
    struct Planned {
        std::string key;
        std::optional<RemeshReport> plan;
        std::string error;
        RemeshQuality before;
    };
    void take_results();
    OperationPanelState panel_{"remesh"};
    std::optional<RemeshReport> plan_;
    std::string plan_error_;
    std::string plan_key_;  ///< the parameters and document state the plan is (being) made of
    std::optional<RemeshQuality> before_, after_;
    const OperationResult* after_of_ = nullptr;  ///< the preview result `after_` is (being) of
    std::future<Planned> plan_job_;
    std::future<RemeshQuality> after_job_;
};

}  // namespace trilab::viewer
