// The live previews of the operation panels; see session_preview.h.
#include "app/session/session_preview.h"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <memory>
#include <thread>
#include <utility>

#include "app/ops/operation_entries.h"
#include "core/algorithms/transfer_function.h"
#include "core/features.h"

namespace trilab::viewer {
namespace {

/// The index of the parameter that counts the steps (iterations) when `a` and `b` differ in
/// it alone (npos otherwise).
std::size_t only_iterations_differ(const Operation& a, const Operation& b) {
    if (!a.def || a.def != b.def) return std::string::npos;
    std::size_t differing = std::string::npos;
    for (std::size_t i = 0; i < a.values.size(); ++i) {
        if (a.values[i] == b.values[i]) continue;
        if (!a.def->params[i].counts_steps || differing != std::string::npos)
            return std::string::npos;
        differing = i;
    }
    return differing;
}

}  // namespace

bool SessionPreviews::previewing(const Operation& op) const {
    return state_.requested && state_.requested->def == op.def &&
           (state_.result || state_.pending || core_.preview_job());
}

bool SessionPreviews::shown(const Operation& op) const {
    if (prediction_shown() && state_.predicted_op == op) return true;
    return state_.result && core_.shown.kind == Shown::Kind::Preview && state_.shown_op == op;
}

bool SessionPreviews::prediction_shown() const {
    return state_.predicted_op && core_.shown.kind == Shown::Kind::Preview &&
           core_.shown.mesh == &state_.prediction;
}

std::optional<SessionPreviews::Predictable> SessionPreviews::predictable(
    const Operation& op) const {
    if (!is_operation<FairingOptions>(op) || region_of(op, core_.mesh())) return std::nullopt;
    const FrequencyDocument& doc = core_.document.frequency;
    if (!doc.valid || !doc.decomposition || doc.decomposition->empty()) return std::nullopt;
    const SpectralDecomposition& d = *doc.decomposition;
    try {
        const FairingOptions o = options_of<FairingOptions>(op);
        if (d.op != laplacian_of(o.op) || d.mass != MassMatrix::Normalizer ||
            d.end != SpectrumEnd::Smallest || o.preserve_volume)
            return std::nullopt;
        // Features in use (fixed, or sliding along their curves) change the operator's rows
        // at the feature vertices, which the spectrum does not know: no prediction.
        if (o.features == FeatureSource::Auto ||
            (o.features == FeatureSource::Stored && has_features(core_.mesh())))
            return std::nullopt;
        if (d.base_positions.size() != core_.mesh().vertices_size()) return std::nullopt;
        return Predictable{doc.decomposition, o};
    } catch (const std::exception&) {
        return std::nullopt;  // the exact preview says what is wrong
    }
}

void SessionPreviews::show_predicted(const Operation& op, std::vector<Point> positions) {
    state_.prediction = core_.mesh();
    state_.prediction.set_positions(std::move(positions));
    state_.predicted_op = op;
    core_.inform("preview: the spectral prediction of " + op.text() +
                 " (from the decomposition; the exact result follows)");
    core_.show(Shown::Kind::Preview, &state_.prediction);
}

namespace {

/// From this many rows x frequencies on (200,000 vertices at k = 100: about 50 ms of the frame
/// on this machine's two cores), the prediction runs on a worker thread.
constexpr std::size_t kAsyncPredictionWork = 20000000;

std::size_t async_prediction_work() {
    // For tests only: a smaller threshold sends small decompositions to the worker.
    if (const char* env = std::getenv("TRILAB_ASYNC_PREDICTION_WORK"); env && *env)
        return std::size_t(std::strtoull(env, nullptr, 10));
    return kAsyncPredictionWork;
}

/// Whether every position is finite (a diverging step is not shown: the exact run says why).
bool all_finite(const std::vector<Point>& p) {
    return std::all_of(p.begin(), p.end(), [](const Point& x) { return x.allFinite(); });
}

}  // namespace

bool SessionPreviews::show_prediction(const Operation& op) {
    std::optional<Predictable> p = predictable(op);
    if (!p) return false;
    const SpectralDecomposition& d = *p->decomposition;
    try {
        if (d.rows() * d.size() >= async_prediction_work()) {
            if (state_.prediction_job.valid())
                state_.prediction_next = op;  // after the running one
            else
                start_prediction_job(op, std::move(*p));
            return true;
        }
        std::vector<Point> predicted = predict_fairing(d, p->options, core_.mesh().positions());
        if (!all_finite(predicted)) return false;  // a diverging step: wait for the exact run
        show_predicted(op, std::move(predicted));
        return true;
    } catch (const std::exception&) {
        return false;  // the exact preview says what is wrong
    }
}

void SessionPreviews::start_prediction_job(const Operation& op, Predictable p) {
    state_.prediction_job_op = op;
    state_.prediction_job_base = core_.mesh().revision();
    state_.prediction_next.reset();
    // The worker's own copy of the positions; the decomposition is shared and immutable.
    // For tests only: the worker first waits this long (a large mesh's prediction time).
    int delay_ms = 0;
    if (const char* env = std::getenv("TRILAB_PREDICTION_WORKER_DELAY_MS"); env && *env)
        delay_ms = std::clamp(std::atoi(env), 0, 10000);
    state_.prediction_job = std::async(
        std::launch::async, [p = std::move(p), input = core_.mesh().positions(), delay_ms] {
            if (delay_ms) std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms));
            return predict_fairing(*p.decomposition, p.options, input);
        });
}

void SessionPreviews::collect_prediction_job() {
    if (!state_.prediction_job.valid() ||
        state_.prediction_job.wait_for(std::chrono::seconds(0)) != std::future_status::ready)
        return;
    std::vector<Point> predicted;
    bool ok = false;
    try {
        predicted = state_.prediction_job.get();
        ok = all_finite(predicted);
    } catch (const std::exception&) {  // the exact preview says what is wrong
    }
    const Operation op = state_.prediction_job_op;
    const bool current = state_.requested && *state_.requested == op &&
                         state_.prediction_job_base == core_.mesh().revision();
    if (ok && current && !(state_.result && state_.computed_op == op))
        show_predicted(op, std::move(predicted));
    if (state_.prediction_next) {
        const Operation next = *state_.prediction_next;
        state_.prediction_next.reset();
        if (state_.requested && *state_.requested == next)
            if (std::optional<Predictable> p = predictable(next))
                start_prediction_job(next, std::move(*p));
    }
}

void SessionPreviews::request(const Operation& op) {
    try {
        check_operation(op);
    } catch (const std::exception&) {
        return;  // the panel shows the error next to its widgets
    }
    if (core_.shown.kind == Shown::Kind::Level) core_.show_document();  // the preview replaces it
    state_.failure.clear();
    state_.requested_at = core_.now();
    state_.requested = op;
    // Within the computed iterations: show the computed step at once.
    if (state_.result && state_.base == core_.mesh().revision()) {
        std::size_t step = std::string::npos;
        if (state_.computed_op == op) {
            step = state_.result->steps.size() - 1;
        } else if (const std::size_t i = only_iterations_differ(state_.computed_op, op);
                   i != std::string::npos) {
            const std::size_t n = std::size_t(op.values[i].x);
            if (n >= 1 && n <= state_.result->steps.size()) step = n - 1;
        }
        if (step != std::string::npos) {
            state_.shown_step = step;
            state_.shown_op = op;
            state_.pending.reset();
            if (core_.preview_job()) core_.jobs.cancel();
            show_result();
            return;
        }
    }
    state_.pending = op;
    if (core_.preview_job()) core_.jobs.cancel();  // outdated: its result would be discarded
    // With a decomposition of the fairing's operator, the spectral prediction shows in this
    // frame; the exact result replaces it when its job ends.
    state_.hold_exact = show_prediction(op);
    if (state_.hold_exact)
        state_.hold_exact_until = core_.now() + 0.25;  // the coming frame shows it alone
    else
        state_.predicted_op.reset();
    start_pending();  // at once when the runner is free (and nothing is held)
}

void SessionPreviews::advance() {
    collect_prediction_job();
    start_pending();  // not while a new prediction waits to be drawn
}

void SessionPreviews::prediction_drawn() {
    // The exact job starts with the next frame's wait, unless a newer request (a slider still
    // moving) has come by then.
    if (prediction_shown()) state_.hold_exact = false;
}

bool SessionPreviews::update() {
    advance();
    const Shown::Kind kind = core_.shown.kind;
    if (kind == Shown::Kind::Level || kind == Shown::Kind::Band) return true;
    if (prediction_shown()) return true;  // the newest request's, until its exact result
    if (!state_.result) return false;
    show_result();
    return true;
}

void SessionPreviews::job_ended(const JobRunner::Outcome& outcome) {
    using Kind = JobRunner::Outcome::Kind;
    if (outcome.kind == Kind::Failed) {
        state_.failure = outcome.message;
    } else if (outcome.kind == Kind::Succeeded && state_.requested &&
               state_.computed_op == *state_.requested) {
        state_.latency_ms = 1000.0 * (core_.now() - state_.requested_at);
    }
}

void SessionPreviews::start_pending() {
    if (!state_.pending || core_.jobs.busy()) return;
    if (state_.hold_exact && core_.now() < state_.hold_exact_until) return;
    const Operation op = *state_.pending;
    state_.pending.reset();
    const HalfedgeMesh snapshot = core_.mesh();  // copy-on-write: the job's own
    const HalfedgeMesh::Revision base = snapshot.revision();
    const auto region = region_of(op, snapshot);
    core_.jobs.start(
        "Preview: " + op.text(),
        [this, op, base, snapshot, region](Progress& progress) {
            RunSettings settings;
            settings.region = region.get();
            auto result =
                std::make_shared<OperationResult>(run_operation(op, snapshot, progress, settings));
            return JobRunner::Finish([this, op, base, result] {
                if (base != core_.mesh().revision()) return;  // the state moved on
                state_.result = result;
                state_.computed_op = op;
                state_.shown_op = op;
                state_.shown_step = result->steps.size() - 1;
                state_.base = base;
                state_.predicted_op.reset();  // the exact result replaces the prediction
                // The status bar tells about this preview: an older error is no longer news.
                if (result->stopped_early)
                    core_.notice = Notice{
                        Notice::Level::Error,
                        "preview: " + result->label + " stopped early: " + result->stop_reason,
                        {},
                        false};
                else
                    core_.inform("preview: " + result->label + " " + result->parameters);
                show_result();
            });
        },
        JobKind::Preview);
}

void SessionPreviews::show_result() {
    const HalfedgeMesh* mesh = &state_.result->steps[state_.shown_step].mesh;
    if (core_.shown.kind == Shown::Kind::Preview && core_.shown.mesh == mesh) return;
    core_.show(Shown::Kind::Preview, mesh);
}

void SessionPreviews::clear() {
    const bool was_shown = core_.shown.kind == Shown::Kind::Preview;
    state_.pending.reset();
    state_.result.reset();
    state_.requested.reset();
    state_.predicted_op.reset();
    if (core_.preview_job()) {
        core_.jobs.cancel();
        // Wait for it (the operations check for cancellation often), so the document is free
        // for what comes next.
        while (core_.jobs.busy()) {
            core_.jobs.poll();
            std::this_thread::sleep_for(std::chrono::milliseconds(1));
        }
    }
    // The preview's mesh goes with it: the view shows the document again.
    if (was_shown) core_.show_document();
}

void SessionPreviews::apply(const Operation& op) {
    if (state_.result && state_.base == core_.mesh().revision() && state_.shown_op == op &&
        state_.shown_step < state_.result->steps.size()) {
        // Commit what is shown: the steps up to the shown one.
        OperationResult result = std::move(*state_.result);
        const std::size_t keep = state_.shown_step + 1;
        if (keep < result.steps.size()) {
            result.report.push_back("applied " + std::to_string(keep) + " of the " +
                                    std::to_string(result.steps.size()) +
                                    " iterations the preview computed");
            result.steps.resize(keep);
        }
        result.parameters = op.parameters();
        clear();
        document_.commit(op, std::move(result));
        return;
    }
    clear();
    document_.run(op);
}

}  // namespace trilab::viewer
