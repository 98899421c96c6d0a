#pragma once
// SessionGuidance: what the panels show beside their values that the core computes from the
// current state: Fairing's largest stable explicit step for an operator, and the edges
// Decimation's next iteration collapses (Rendering > Vectors > Collapsing edges). Each is
// computed off the render thread, on a future of its own from a copy-on-write snapshot (they
// must not wait for a long job on the runner, nor hold it), and kept for the state and the
// settings it was computed for; a newer request replaces the result when it arrives.
#include <array>
#include <future>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "app/ops/operation.h"
#include "app/session/session_core.h"
#include "core/algorithms/fairing.h"

namespace trilab::viewer {

class SessionGuidance {
public:
    explicit SessionGuidance(SessionCore& core) : core_(core) {}

    /// The largest stable explicit step of a state for an operator (NaN: not known).
    struct StableStep {
        HalfedgeMesh::Revision state;
        FairingOperator op = FairingOperator::Umbrella;
        double step = std::numeric_limits<double>::quiet_NaN();
    };
    /// The last estimate that arrived (null: none yet); check its state and operator.
    const StableStep* stable_step() const { return stable_step_.get(); }
    /// The edges the next decimation iteration of `op` collapses, as segments (removed vertex,
    /// kept vertex) of a state's positions.
    struct CollapsingEdges {
        HalfedgeMesh::Revision state;
        Operation op;
        std::vector<std::array<Point, 2>> segments;
        std::string failure;  ///< why there are none ("" when they were computed)
    };
    const CollapsingEdges* collapsing_edges() const { return collapsing_.get(); }
    /// An estimate or a search is computing.
    bool computing() const { return stable_job_.valid() || collapsing_job_.valid(); }

    /// Estimates the stable step of the current state for `op` (Taubin: its umbrella steps),
    /// unless the last estimate or the one computing is of this state and operator.
    void estimate_stable_step(FairingOperator op);
    /// Finds the edges the next iteration of decimation `op` collapses on the current state,
    /// unless the last search or the one computing is of this state and operation.
    void find_collapsing_edges(const Operation& op);
    /// Each frame: takes what arrived.
    void update();
    /// Waits for what is computing (tests and scripted runs).
    void finish();

    /// Meshes above these sizes get no estimate or overlay (a preview of the fairing reports
    /// its step at any size).
    static constexpr std::size_t kMaxStableStepVertices = 2000000;
    static constexpr std::size_t kMaxCollapsingVertices = 300000;

private:
    void start_stable_job();
    void start_collapsing_job();

    SessionCore& core_;
    std::shared_ptr<const StableStep> stable_step_;
    std::future<std::shared_ptr<const StableStep>> stable_job_;
    StableStep stable_requested_;
    std::shared_ptr<const CollapsingEdges> collapsing_;
    std::future<std::shared_ptr<const CollapsingEdges>> collapsing_job_;
    CollapsingEdges collapsing_requested_;
};

}  // namespace trilab::viewer
