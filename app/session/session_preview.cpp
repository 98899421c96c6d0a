// Live previews of the operation panels, and Decimation's level-of-detail slider.
//
// The rule, the same for every panel: changing a parameter shows the operation applied to
// the current state (the state before it) without touching the history; a newer change
// cancels a preview that is still computing; Apply commits the shown preview as one history
// entry (or runs the operation when nothing matching is shown); Cancel or Esc shows the
// current state again. Moving the iterations slider within the iterations already computed
// shows the computed step at once (the subdivision level slider, fairing and decimation
// iterations).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <thread>
#include <utility>

#include "app/ops/decimate_op.h"
#include "app/ops/operation_entries.h"
#include "app/session/session.h"
#include "core/algorithms/decimation.h"
#include "core/algorithms/transfer_function.h"

namespace trilab::viewer {
namespace {

constexpr const char* kPreviewJobPrefix = "Preview: ";

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

bool Session::is_preview_job() const {
    return jobs_.busy() && jobs_.kind() == JobKind::Preview;
}

bool Session::preview_running() const {
    return is_preview_job();
}

bool Session::previewing(const Operation& op) const {
    return preview_.requested && preview_.requested->def == op.def &&
           (preview_.result || preview_.pending || is_preview_job());
}

bool Session::preview_shown(const Operation& op) const {
    if (prediction_shown() && preview_.predicted_op == op) return true;
    return preview_.result && shown_.kind == Shown::Kind::Preview && preview_.shown_op == op;
}

bool Session::prediction_shown() const {
    return preview_.predicted_op && shown_.kind == Shown::Kind::Preview &&
           shown_.mesh == &preview_.prediction;
}

std::optional<Session::Predictable> Session::predictable(const Operation& op) const {
    if (!is_operation<FairingOptions>(op) || region_for(op, document_.mesh())) return std::nullopt;
    const FrequencyDocument& doc = document_.frequency;
    if (!doc.valid || !doc.decomposition || doc.decomposition->empty()) return std::nullopt;
    const SpectralDecomposition& d = *doc.decomposition;
    try {
        const FairingOptions o = options_of<FairingOptions>(op);
        if (d.op != laplacian_of(o.op) || d.mass != MassMatrix::Normalizer ||
            d.end != SpectrumEnd::Smallest || o.preserve_volume)
            return std::nullopt;
        if (d.base_positions.size() != document_.mesh().vertices_size()) return std::nullopt;
        return Predictable{doc.decomposition, o};
    } catch (const std::exception&) {
        return std::nullopt;  // the exact preview says what is wrong
    }
}

void Session::show_predicted(const Operation& op, std::vector<Point> positions) {
    preview_.prediction = document_.mesh();
    preview_.prediction.set_positions(std::move(positions));
    preview_.predicted_op = op;
    notice_ = Notice{Notice::Level::Info,
                     "preview: the spectral prediction of " + op.text() +
                         " (from the decomposition; the exact result follows)",
                     {},
                     false};
    shown_.kind = Shown::Kind::Preview;
    shown_.mesh = &preview_.prediction;
    shown_.positions.clear();
    shown_.level = nullptr;
    bump();
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

bool Session::show_prediction(const Operation& op) {
    std::optional<Predictable> p = predictable(op);
    if (!p) return false;
    const SpectralDecomposition& d = *p->decomposition;
    try {
        if (d.rows() * d.size() >= async_prediction_work()) {
            if (preview_.prediction_job.valid())
                preview_.prediction_next = op;  // after the running one
            else
                start_prediction_job(op, std::move(*p));
            return true;
        }
        std::vector<Point> predicted = predict_fairing(d, p->options, document_.mesh().positions());
        if (!all_finite(predicted)) return false;  // a diverging step: wait for the exact run
        show_predicted(op, std::move(predicted));
        return true;
    } catch (const std::exception&) {
        return false;  // the exact preview says what is wrong
    }
}

void Session::start_prediction_job(const Operation& op, Predictable p) {
    preview_.prediction_job_op = op;
    preview_.prediction_job_base = document_.mesh().revision();
    preview_.prediction_next.reset();
    // The worker's own copy of the positions; the decomposition is shared and immutable.
    // For tests only: the worker first waits this long (a large mesh's prediction time).
    int delay_ms = 0;
    if (const char* env = std::getenv("TRILAB_PREDICTION_WORKER_DELAY_MS"); env && *env)
        delay_ms = std::clamp(std::atoi(env), 0, 10000);
    preview_.prediction_job = std::async(
        std::launch::async, [p = std::move(p), input = document_.mesh().positions(), delay_ms] {
            if (delay_ms) std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms));
            return predict_fairing(*p.decomposition, p.options, input);
        });
}

void Session::collect_prediction_job() {
    if (!preview_.prediction_job.valid() ||
        preview_.prediction_job.wait_for(std::chrono::seconds(0)) != std::future_status::ready)
        return;
    std::vector<Point> predicted;
    bool ok = false;
    try {
        predicted = preview_.prediction_job.get();
        ok = all_finite(predicted);
    } catch (const std::exception&) {  // the exact preview says what is wrong
    }
    const Operation op = preview_.prediction_job_op;
    const bool current = preview_.requested && *preview_.requested == op &&
                         preview_.prediction_job_base == document_.mesh().revision();
    if (ok && current && !(preview_.result && preview_.computed_op == op))
        show_predicted(op, std::move(predicted));
    if (preview_.prediction_next) {
        const Operation next = *preview_.prediction_next;
        preview_.prediction_next.reset();
        if (preview_.requested && *preview_.requested == next)
            if (std::optional<Predictable> p = predictable(next))
                start_prediction_job(next, std::move(*p));
    }
}

void Session::request_preview(const Operation& op) {
    try {
        check_operation(op);
    } catch (const std::exception&) {
        return;  // the panel shows the error next to its widgets
    }
    clear_level_of_detail(false);
    preview_.failure.clear();
    preview_.requested_at = now();
    preview_.requested = op;
    // Within the computed iterations: show the computed step at once.
    if (preview_.result && preview_.base == document_.mesh().revision()) {
        std::size_t step = std::string::npos;
        if (preview_.computed_op == op) {
            step = preview_.result->steps.size() - 1;
        } else if (const std::size_t i = only_iterations_differ(preview_.computed_op, op);
                   i != std::string::npos) {
            const std::size_t n = std::size_t(op.values[i].x);
            if (n >= 1 && n <= preview_.result->steps.size()) step = n - 1;
        }
        if (step != std::string::npos) {
            preview_.shown_step = step;
            preview_.shown_op = op;
            preview_.pending.reset();
            if (is_preview_job()) jobs_.cancel();
            show_preview();
            return;
        }
    }
    preview_.pending = op;
    if (is_preview_job()) jobs_.cancel();  // outdated: its result would be discarded
    // With a decomposition of the fairing's operator, the spectral prediction shows in this
    // frame; the exact result replaces it when its job ends.
    preview_.hold_exact = show_prediction(op);
    if (preview_.hold_exact)
        preview_.hold_exact_until = now() + 0.25;  // the coming frame shows the prediction alone
    else
        preview_.predicted_op.reset();
    start_pending_preview();  // at once when the runner is free (and nothing is held)
}

void Session::wait_for_preview(double seconds) {
    // A preview that is about to finish shows in this frame rather than the next: wait for it
    // a bounded time (a frame's hiccup, never a freeze). Not while the spectral prediction is
    // on the screen: it already shows the change, and the exact result replaces it when ready.
    collect_prediction_job();
    start_pending_preview();  // not while the new prediction waits to be drawn
    if (prediction_shown()) return;
    const double until = now() + seconds;
    while (is_preview_job() && jobs_.elapsed_seconds() < seconds && now() < until) {
        poll();
        if (is_preview_job()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
}

void Session::prediction_drawn() {
    // The exact job starts with the next frame's wait_for_preview(), unless a newer request
    // (a slider still moving) has come by then.
    if (prediction_shown()) preview_.hold_exact = false;
}

void Session::start_pending_preview() {
    if (!preview_.pending || jobs_.busy()) return;
    if (preview_.hold_exact && now() < preview_.hold_exact_until) return;
    const Operation op = *preview_.pending;
    preview_.pending.reset();
    const HalfedgeMesh snapshot = document_.mesh();  // copy-on-write: the job's own
    const HalfedgeMesh::Revision base = snapshot.revision();
    const auto region = region_for(op, snapshot);
    jobs_.start(
        kPreviewJobPrefix + op.text(),
        [this, op, base, snapshot, region](Progress& progress) {
            RunSettings settings;
            settings.region = region.get();
            auto result =
                std::make_shared<OperationResult>(run_operation(op, snapshot, progress, settings));
            return JobRunner::Finish([this, op, base, result] {
                if (base != document_.mesh().revision()) return;  // the state moved on
                preview_.result = result;
                preview_.computed_op = op;
                preview_.shown_op = op;
                preview_.shown_step = result->steps.size() - 1;
                preview_.base = base;
                preview_.predicted_op.reset();  // the exact result replaces the prediction
                // The status bar tells about this preview: an older error is no longer news.
                if (result->stopped_early)
                    notice_ = Notice{
                        Notice::Level::Error,
                        "preview: " + result->label + " stopped early: " + result->stop_reason,
                        {},
                        false};
                else
                    notice_ = Notice{Notice::Level::Info,
                                     "preview: " + result->label + " " + result->parameters,
                                     {},
                                     false};
                show_preview();
            });
        },
        JobKind::Preview);
}

void Session::show_preview() {
    const HalfedgeMesh* mesh = &preview_.result->steps[preview_.shown_step].mesh;
    if (shown_.kind == Shown::Kind::Preview && shown_.mesh == mesh) return;
    shown_.kind = Shown::Kind::Preview;
    shown_.mesh = mesh;
    shown_.positions.clear();
    shown_.level = nullptr;
    bump();
}

void Session::clear_preview() {
    const bool was_shown = shown_.kind == Shown::Kind::Preview;
    preview_.pending.reset();
    preview_.result.reset();
    preview_.requested.reset();
    preview_.predicted_op.reset();
    if (is_preview_job()) {
        jobs_.cancel();
        // Wait for it (the operations check for cancellation often), so the document is free
        // for what comes next.
        while (jobs_.busy()) {
            jobs_.poll();
            std::this_thread::sleep_for(std::chrono::milliseconds(1));
        }
    }
    // The preview's mesh goes with it: the view shows the document again.
    if (was_shown) show_document();
}

void Session::apply_operation(const Operation& op) {
    if (preview_.result && preview_.base == document_.mesh().revision() &&
        preview_.shown_op == op && preview_.shown_step < preview_.result->steps.size()) {
        // Commit what is shown: the steps up to the shown one.
        OperationResult result = std::move(*preview_.result);
        const std::size_t keep = preview_.shown_step + 1;
        if (keep < result.steps.size()) {
            result.report.push_back("applied " + std::to_string(keep) + " of the " +
                                    std::to_string(result.steps.size()) +
                                    " iterations the preview computed");
            result.steps.resize(keep);
        }
        result.parameters = op.parameters();
        clear_preview();
        commit_result(op, std::move(result));
        return;
    }
    clear_preview();
    run_operation_job(op);
}

// ---- the level-of-detail slider ------------------------------------------------------------

bool Session::has_level_of_detail() const {
    return lod_.lod && lod_.base == document_.mesh().revision();
}

void Session::build_level_of_detail(const Operation& op) {
    clear_preview();
    clear_level_of_detail(true);
    DecimationOptions options;
    try {
        options = decimation_options(op);
    } catch (const std::exception& e) {
        notify_error(e.what());
        return;
    }
    const HalfedgeMesh snapshot = document_.mesh();  // copy-on-write: the job's own
    const HalfedgeMesh::Revision base = snapshot.revision();
    lod_.building = true;
    lod_.op = op;
    const double t0 = now();
    const bool started = jobs_.start("Building levels of detail", [this, options, base, t0,
                                                                   snapshot](Progress& progress) {
        auto build = std::make_shared<ProgressiveBuild>(
            build_progressive_mesh(snapshot, options, 1.0, progress));
        auto lod = std::make_shared<LevelOfDetail>(build->progressive);
        return JobRunner::Finish([this, build, lod, base, t0] {
            lod_.building = false;
            if (base != document_.mesh().revision()) return;
            lod_.progressive = std::shared_ptr<const ProgressiveMesh>(build, &build->progressive);
            lod_.lod = lod;
            lod_.base = base;
            char buf[200];
            std::snprintf(buf, sizeof buf, "%zu levels, down to %.1f %% of the vertices (%.0f ms)",
                          lod->max_level(), lod->percent_at_level(lod->max_level()),
                          1000.0 * (now() - t0));
            lod_.note = buf;
            if (build->report.stop != DecimationStop::Done)
                lod_.note += ": " + build->report.stop_message;
        });
    });
    if (!started) {
        lod_.building = false;
        busy_error();
    }
}

void Session::show_level_of_detail(double percent) {
    if (!has_level_of_detail()) return;
    clear_preview();
    LevelOfDetail& lod = *lod_.lod;
    lod.set_level(lod.level_for_percent(std::clamp(percent, 0.0, 100.0)));
    shown_.kind = Shown::Kind::Level;
    shown_.mesh = &document_.mesh();
    shown_.positions.clear();
    shown_.level = &lod;
    bump();
}

void Session::clear_level_of_detail(bool forget) {
    if (shown_.kind == Shown::Kind::Level) show_document();
    if (forget) {
        const std::string note = lod_.building ? lod_.note : std::string();
        const bool building = lod_.building;
        lod_ = LodState{};
        lod_.building = building;  // a build in flight finds the state moved on, and ends
        lod_.note = note;
    }
}

void Session::apply_level_of_detail() {
    if (!has_level_of_detail()) return;
    const LevelOfDetail& lod = *lod_.lod;
    const ProgressiveMesh& pm = *lod_.progressive;
    OperationResult result;
    result.label = "Decimate";
    HalfedgeMesh mesh = lod.mesh();
    // Each kept vertex starts where it was on the finer mesh (the level's vertices are the
    // live fine vertices, in the fine order).
    std::vector<Point> start;
    for (Index i = 0; i < Index(pm.positions.size()); ++i) {
        if (!pm.vertex_alive[i]) continue;
        const Index v = lod.vertex_of(i);
        if (v != kInvalidIndex && lod.vertex_alive()[v]) start.push_back(pm.positions[i]);
    }
    if (start.size() != mesh.vertices_size()) start = mesh.positions();  // no motion then
    char buf[160];
    std::snprintf(buf, sizeof buf, "level of detail: %zu of %zu vertices (%.1f %%)", lod.vertices(),
                  lod.fine_vertices(), lod.percent_at_level(lod.level()));
    result.report.push_back(buf);
    result.steps.push_back(OperationStep{
        std::move(mesh), MorphCorrespondence{MorphCorrespondence::Kind::FromEarlier, start}});
    Operation op = lod_.op;
    DecimateOptions typed = options_of<DecimateOptions>(op);
    typed.target_vertices = lod.vertices();
    set_options(op, typed);
    result.parameters = op.parameters();
    clear_level_of_detail(true);
    commit_result(op, std::move(result));
}

}  // namespace trilab::viewer
