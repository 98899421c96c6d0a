// The panels' guidance computed from the current state; see session_guidance.h.
#include "app/session/session_guidance.h"

#include <chrono>
#include <utility>

#include "app/ops/decimate_op.h"
#include "app/ops/operation_entries.h"
#include "core/algorithms/decimation.h"

namespace trilab::viewer {
namespace {

template <class T>
bool ready(const std::future<T>& job) {
    return job.valid() && job.wait_for(std::chrono::seconds(0)) == std::future_status::ready;
}

}  // namespace

void SessionGuidance::estimate_stable_step(FairingOperator op) {
    const HalfedgeMesh& mesh = core_.mesh();
    const bool same_request =
        stable_requested_.state == mesh.revision() && stable_requested_.op == op;
    if (same_request && (stable_job_.valid() || stable_step_)) return;
    stable_requested_ = StableStep{mesh.revision(), op};
    if (mesh.n_vertices() > kMaxStableStepVertices) {
        stable_step_ = std::make_shared<const StableStep>(stable_requested_);  // NaN: unknown
        return;
    }
    // A running estimate finishes first (its result is stale then and dropped): update()
    // starts this one when it has ended, so the render thread never waits for a worker.
    if (!stable_job_.valid()) start_stable_job();
}

void SessionGuidance::start_stable_job() {
    const HalfedgeMesh& mesh = core_.mesh();
    const FairingOperator op = stable_requested_.op;
    stable_job_ = std::async(std::launch::async, [snapshot = HalfedgeMesh(mesh), op] {
        auto out = std::make_shared<StableStep>();
        out->state = snapshot.revision();
        out->op = op;
        try {
            out->step = max_stable_explicit_step(snapshot, op);
        } catch (const std::exception&) {
            out->step = std::numeric_limits<double>::quiet_NaN();
        }
        return std::shared_ptr<const StableStep>(out);
    });
}

void SessionGuidance::find_collapsing_edges(const Operation& op) {
    const HalfedgeMesh& mesh = core_.mesh();
    if (collapsing_requested_.state == mesh.revision() && collapsing_requested_.op == op &&
        (collapsing_job_.valid() || collapsing_))
        return;
    collapsing_requested_.state = mesh.revision();
    collapsing_requested_.op = op;
    if (mesh.n_vertices() > kMaxCollapsingVertices) {
        auto none = std::make_shared<CollapsingEdges>(collapsing_requested_);
        none->failure = "shown for meshes of up to 300,000 vertices only";
        core_.log.warning("Collapsing edges: " + none->failure);
        collapsing_ = std::move(none);
        return;
    }
    if (!collapsing_job_.valid()) start_collapsing_job();
}

void SessionGuidance::start_collapsing_job() {
    const HalfedgeMesh& mesh = core_.mesh();
    const Operation op = collapsing_requested_.op;
    collapsing_job_ = std::async(std::launch::async, [snapshot = HalfedgeMesh(mesh), op] {
        auto out = std::make_shared<CollapsingEdges>();
        out->state = snapshot.revision();
        out->op = op;
        try {
            for (const auto& pair : next_collapses(snapshot, decimation_options(op)))
                out->segments.push_back(
                    std::array<Point, 2>{snapshot.position(pair[0]), snapshot.position(pair[1])});
        } catch (const std::exception& e) {
            out->failure = e.what();
        }
        return std::shared_ptr<const CollapsingEdges>(out);
    });
}

void SessionGuidance::update() {
    const HalfedgeMesh::Revision now = core_.mesh().revision();
    if (ready(stable_job_)) {
        std::shared_ptr<const StableStep> result = stable_job_.get();
        if (result->state == stable_requested_.state && result->op == stable_requested_.op)
            stable_step_ = std::move(result);
        else if (stable_requested_.state == now)  // a newer request waited: its turn
            start_stable_job();
    }
    if (ready(collapsing_job_)) {
        std::shared_ptr<const CollapsingEdges> result = collapsing_job_.get();
        if (result->state == collapsing_requested_.state &&
            result->op == collapsing_requested_.op) {
            if (!result->failure.empty()) core_.log.warning("Collapsing edges: " + result->failure);
            collapsing_ = std::move(result);
        } else if (collapsing_requested_.state == now) {
            start_collapsing_job();
        }
    }
}

void SessionGuidance::finish() {
    while (computing()) {
        if (stable_job_.valid()) stable_job_.wait();
        if (collapsing_job_.valid()) collapsing_job_.wait();
        update();
    }
}

}  // namespace trilab::viewer
