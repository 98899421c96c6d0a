#pragma once
// SessionPreviews: the live previews of the operation panels (issue 13's rule, the same for
// every panel): a changed parameter shows the operation applied to the current state without
// touching the history; a newer change cancels a preview still computing; Apply commits the
// shown preview as one entry (or runs the operation when nothing matching is shown); Cancel
// shows the document again. A fairing preview with a decomposition of its operator shows its
// spectral prediction first (core/algorithms/transfer_function.h), then the exact result.
#include <cstddef>
#include <future>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/ops/operation.h"
#include "app/session/session_core.h"
#include "app/session/session_document.h"
#include "core/algorithms/fairing.h"

namespace trilab::viewer {

class SessionPreviews {
public:
    SessionPreviews(SessionCore& core, SessionDocument& document)
        : core_(core), document_(document) {}

    // ---- what the panels read ----------------------------------------------------------------
    /// The preview shown or computing for `op`'s operation (its panel's Cancel shows).
    bool previewing(const Operation& op) const;
    /// The operation a preview was last asked for, if any.
    const std::optional<Operation>& requested() const { return state_.requested; }
    /// The result of the shown preview, if any (the panels read reports from it).
    const OperationResult* result() const { return state_.result.get(); }
    /// The error of the last preview job ("" when it succeeded).
    const std::string& failure() const { return state_.failure; }
    /// A preview is asked for and not started yet (the runner was busy).
    bool pending() const { return state_.pending.has_value(); }
    /// A preview job runs (its progress shows only after a while).
    bool running() const { return core_.preview_job(); }
    /// Whether the preview asked for last is computed and shown (or its spectral prediction,
    /// which shows first when there is a decomposition of the fairing's operator).
    bool shown(const Operation& op) const;
    /// The preview on the screen is the spectral prediction, not the exact result yet.
    bool prediction_shown() const;
    /// A fairing `op` whose spectral prediction comes from the current decomposition's stored
    /// coefficients (a whole-mesh umbrella or Taubin preview on the decomposed shape): the
    /// decomposition and the options; nothing otherwise. A view draws a large mesh's prediction
    /// from it (predict_clustered) before the prediction itself is computed.
    struct Predictable {
        std::shared_ptr<const SpectralDecomposition> decomposition;
        FairingOptions options;
    };
    std::optional<Predictable> predictable(const Operation& op) const;
    /// A large decomposition's prediction is being computed on a worker thread.
    bool prediction_computing() const { return state_.prediction_job.valid(); }
    /// Milliseconds from the request to the result of the last preview (negative: none).
    double last_ms() const { return state_.latency_ms; }

    // ---- what the Session does (its commands) ------------------------------------------------
    void request(const Operation& op);
    /// Commits the shown preview of `op`, or runs `op` when none matches.
    void apply(const Operation& op);
    /// Drops the preview (cancelling its job); the view shows the document again.
    void clear();
    /// The view has drawn the shown prediction: its exact job may start (it waits until then,
    /// at most a quarter second, so that a view drawing a large mesh's prediction gets the CPU
    /// for that frame, and a slider dragged on keeps cancelling nothing).
    void prediction_drawn();
    /// Each frame: takes a worker's prediction, starts the pending job; returns whether a
    /// preview (or its prediction) is what the view shows now.
    bool update();
    /// A preview job ended (poll()): its latency or its failure.
    void job_ended(const JobRunner::Outcome& outcome);
    /// A preview request or prediction is still to be handled (finish_jobs()).
    bool outstanding() const { return state_.pending || state_.prediction_job.valid(); }
    /// Takes a worker's prediction when it has ended and starts the pending job when the
    /// runner is free (before waiting for a preview).
    void advance();

private:
    struct State {
        std::optional<Operation> requested;  ///< the newest request
        std::optional<Operation> pending;    ///< requested, not started yet
        std::shared_ptr<OperationResult> result;
        Operation computed_op;        ///< what `result` was computed for
        Operation shown_op;           ///< what is shown (computed_op or fewer iterations)
        std::size_t shown_step = 0;   ///< the step of `result` shown
        HalfedgeMesh::Revision base;  ///< the document state `result` applies to
        double requested_at = 0;
        double latency_ms = -1;
        std::string failure;  ///< the last preview job's error (a sweep ends on it)
        /// The spectral prediction of a fairing preview (issue 28), shown until the exact
        /// result arrives: the document's connectivity with the predicted positions.
        std::optional<Operation> predicted_op;
        HalfedgeMesh prediction;
        /// The exact job waits while the frame that shows a new prediction is drawn (it would
        /// take the CPU that frame needs): until prediction_drawn(), at most hold_exact_until
        /// on the session's clock.
        bool hold_exact = false;
        double hold_exact_until = 0;
        /// A large decomposition's prediction (rows x k at least kAsyncPredictionWork) is
        /// computed on a worker thread, the frame is not held for it: the op and document state
        /// it is for; the newest request waits in `prediction_next` while one runs.
        std::future<std::vector<Point>> prediction_job;
        Operation prediction_job_op;
        HalfedgeMesh::Revision prediction_job_base;
        std::optional<Operation> prediction_next;
    };
    /// Starts the worker prediction of `op` (predictable() on the current document).
    void start_prediction_job(const Operation& op, Predictable p);
    /// Shows the worker's prediction when it has ended and is still the newest request's.
    void collect_prediction_job();
    /// Shows `positions` as the prediction of `op`.
    void show_predicted(const Operation& op, std::vector<Point> positions);
    /// Shows the spectral prediction of fairing `op` when the decomposition is of its operator
    /// (core/algorithms/transfer_function.h predict_fairing); false when there is none.
    bool show_prediction(const Operation& op);
    void start_pending();
    void show_result();

    SessionCore& core_;
    SessionDocument& document_;
    State state_;
};

}  // namespace trilab::viewer
