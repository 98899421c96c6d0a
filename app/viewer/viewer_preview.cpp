// Live previews of the Algorithms panels, and scripted sweeps over a panel parameter.
//
// The rule, the same for every panel: changing a parameter shows the operation applied to
// the current state (the state before it) without touching the history; a newer change
// cancels a preview that is still computing; Apply commits the shown preview as one history
// entry (or runs the operation when nothing matching is shown); Cancel or Esc shows the
// current state again. Moving the iterations slider within the iterations already computed
// shows the computed step at once (the subdivision level slider, fairing and decimation
// iterations). A preview that took longer than the frame budget switches its panel to
// preview-on-release, and the panel says so.
// glad before GLFW: GLFW must not include the system GL header.
#include <glad/gl.h>

#include <GLFW/glfw3.h>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <utility>

#include "app/ops/operation_entries.h"
#include "app/viewer/viewer.h"
#include "core/algorithms/coloring.h"
#include "core/algorithms/decimation.h"

namespace trilab::viewer {
namespace {

constexpr double kLiveBudgetMs = 150.0;  ///< previews slower than this wait for the release
constexpr const char* kPreviewJobPrefix = "Preview: ";

/// The index of "iterations" when `a` and `b` differ in it alone (npos otherwise).
std::size_t only_iterations_differ(const Operation& a, const Operation& b) {
    if (!a.def || a.def != b.def) return std::string::npos;
    std::size_t differing = std::string::npos;
    for (std::size_t i = 0; i < a.values.size(); ++i) {
        if (a.values[i] == b.values[i]) continue;
        if (a.def->params[i].name != "iterations" || differing != std::string::npos)
            return std::string::npos;
        differing = i;
    }
    return differing;
}

}  // namespace

bool Viewer::is_preview_job() const {
    return jobs_.busy() && jobs_.name().rfind(kPreviewJobPrefix, 0) == 0;
}

OperationPanelState* Viewer::panel_of(const Operation& op) {
    const std::string& name = op.name();
    if (name == "subdivide") return &panels_.subdivision;
    if (name == "smooth") return &panels_.fairing;
    if (name == "decimate") return &panels_.decimation;
    if (name == "noise") return &panels_.tools;
    if (name == "weld") return &panels_.weld;
    return nullptr;
}

void Viewer::request_preview(const Operation& op) {
    try {
        check_operation(op);
    } catch (const std::exception& e) {
        return;  // the panel shows the error next to its widgets
    }
    clear_level_of_detail(false);
    preview_.failure.clear();
    preview_.requested_at = glfwGetTime();
    preview_.requested = op;
    // Within the computed iterations: show the computed step at once.
    if (preview_.result && preview_.base == document_.mesh().revision()) {
        if (preview_.computed_op == op) {
            preview_.shown_step = preview_.result->steps.size() - 1;
            preview_.shown_op = op;
            preview_.pending.reset();
            if (is_preview_job()) jobs_.cancel();
            active_frames_ = std::max(active_frames_, 2);
            return;
        }
        const std::size_t i = only_iterations_differ(preview_.computed_op, op);
        if (i != std::string::npos) {
            const std::size_t n = std::size_t(op.values[i].x);
            if (n >= 1 && n <= preview_.result->steps.size()) {
                preview_.shown_step = n - 1;
                preview_.shown_op = op;
                preview_.pending.reset();
                if (is_preview_job()) jobs_.cancel();
                active_frames_ = std::max(active_frames_, 2);
                return;
            }
        }
    }
    preview_.pending = op;
    if (is_preview_job()) jobs_.cancel();  // outdated: its result would be discarded
    start_pending_preview();               // at once when the runner is free
    active_frames_ = std::max(active_frames_, 2);
}

void Viewer::wait_for_preview() {
    // A preview that is about to finish shows in this frame rather than the next: wait for it
    // a bounded time (a frame's hiccup, never a freeze).
    constexpr double kWaitSeconds = 0.1;
    const double until = glfwGetTime() + kWaitSeconds;
    while (is_preview_job() && jobs_.elapsed_seconds() < kWaitSeconds && glfwGetTime() < until) {
        poll_jobs();
        if (is_preview_job()) glfwWaitEventsTimeout(0.001);
    }
}

void Viewer::start_pending_preview() {
    if (!preview_.pending || jobs_.busy()) return;
    const Operation op = *preview_.pending;
    preview_.pending.reset();
    const HalfedgeMesh::Revision base = document_.mesh().revision();
    const std::string name = kPreviewJobPrefix + op.text();
    jobs_.start(name, [this, op, base](Progress& progress) {
        auto result =
            std::make_shared<OperationResult>(run_operation(op, document_.mesh(), progress));
        return JobRunner::Finish([this, op, base, result] {
            if (base != document_.mesh().revision()) return;  // the state moved on
            preview_.result = result;
            preview_.computed_op = op;
            preview_.shown_op = op;
            preview_.shown_step = result->steps.size() - 1;
            preview_.base = base;
            // The status bar tells about this preview: an older error is no longer news.
            if (result->stopped_early)
                notice_ =
                    Notice{Notice::Level::Error,
                           "preview: " + result->label + " stopped early: " + result->stop_reason,
                           {},
                           false};
            else
                notice_ = Notice{Notice::Level::Info,
                                 "preview: " + result->label + " " + result->parameters,
                                 {},
                                 false};
        });
    });
}

void Viewer::show_preview() {
    const HalfedgeMesh& mesh = preview_.result->steps[preview_.shown_step].mesh;
    if (preview_shown_ && renderer_->shows(mesh)) return;
    const HalfedgeMesh& current = document_.mesh();
    // Geometry-only previews (fairing, noise) move the vertices already on the GPU: the
    // renderer compares revisions and uploads only what changed.
    if (renderer_->show(mesh) == MeshRenderer::Update::Full) {
        if (view_.settings.coloring != VertexColoring::None &&
            !coloring_needs_field(view_.settings.coloring)) {
            std::vector<Point> reference;
            if (current.vertices_size() == mesh.vertices_size()) reference = current.positions();
            const VertexColors colors =
                color_vertices(mesh, view_.settings.coloring, view_.settings.coloring_options,
                               reference.empty() ? nullptr : &reference);
            if (colors.colors.empty())
                renderer_->clear_vertex_colors();
            else
                renderer_->set_vertex_colors(colors.colors, color_blend(colors.kind));
        }
    }
    preview_shown_ = true;
    morph_shown_ = false;
    preview_.shown_at = glfwGetTime();
}

void Viewer::clear_preview(bool reupload) {
    const bool was_shown = preview_shown_;
    preview_.pending.reset();
    preview_.result.reset();
    preview_.requested.reset();
    preview_shown_ = false;
    if (is_preview_job()) {
        jobs_.cancel();
        // Wait for it (the operations check for cancellation often), so the document is free
        // for what comes next.
        while (jobs_.busy()) {
            jobs_.poll();
            glfwWaitEventsTimeout(0.001);
        }
    }
    if (was_shown && reupload) show_document();
}

void Viewer::apply_operation(const Operation& op) {
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
        clear_preview(false);
        commit_result(op, std::move(result));
        return;
    }
    clear_preview(true);
    run_operation_job(op);
}

void Viewer::update_preview_flags() {
    OperationPanelState* panels[] = {&panels_.subdivision, &panels_.fairing, &panels_.decimation,
                                     &panels_.tools};
    for (OperationPanelState* panel : panels) {
        const bool mine = (preview_.requested && preview_.requested->def == panel->op.def) &&
                          (preview_.result || preview_.pending || is_preview_job());
        panel->previewing = mine;
    }
}

void Viewer::note_preview_latency(double ms) {
    if (!preview_.requested) return;
    OperationPanelState* panel = panel_of(*preview_.requested);
    if (!panel) return;
    char buf[160];
    panel->live = ms <= kLiveBudgetMs;
    if (panel->live)
        std::snprintf(buf, sizeof buf, "preview %.0f ms", ms);
    else
        std::snprintf(buf, sizeof buf,
                      "preview %.0f ms: over the %.0f ms budget, previews when a drag ends", ms,
                      kLiveBudgetMs);
    panel->preview_note = buf;
}

// ---- the level-of-detail slider ------------------------------------------------------------

void Viewer::build_level_of_detail(const Operation& op) {
    clear_preview(true);
    clear_level_of_detail(true);
    DecimationOptions options;
    try {
        options = decimation_options(op);
    } catch (const std::exception& e) {
        notify_error(e.what());
        return;
    }
    const HalfedgeMesh::Revision base = document_.mesh().revision();
    panels_.decimation.lod_building = true;
    const auto t0 = glfwGetTime();
    jobs_.start("Building levels of detail", [this, options, base, t0](Progress& progress) {
        auto build = std::make_shared<ProgressiveBuild>(
            build_progressive_mesh(document_.mesh(), options, 1.0, progress));
        auto lod = std::make_shared<LevelOfDetail>(build->progressive);
        return JobRunner::Finish([this, build, lod, base, t0] {
            panels_.decimation.lod_building = false;
            if (base != document_.mesh().revision()) return;
            lod_.progressive = std::shared_ptr<const ProgressiveMesh>(build, &build->progressive);
            lod_.lod = lod;
            lod_.base = base;
            panels_.decimation.lod_ready = true;
            panels_.decimation.lod_percent = 100.0f;
            char buf[200];
            std::snprintf(buf, sizeof buf, "%zu levels, down to %.1f %% of the vertices (%.0f ms)",
                          lod->max_level(), lod->percent_at_level(lod->max_level()),
                          1000.0 * (glfwGetTime() - t0));
            panels_.decimation.lod_note = buf;
            if (build->report.stop != DecimationStop::Done)
                panels_.decimation.lod_note += ": " + build->report.stop_message;
        });
    });
}

void Viewer::show_level_of_detail(double percent) {
    if (!lod_.lod || lod_.base != document_.mesh().revision()) return;
    clear_preview(false);
    LevelOfDetail& lod = *lod_.lod;
    lod.set_level(lod.level_for_percent(std::clamp(percent, 0.0, 100.0)));
    if (lod_.shown)
        renderer_->update_level(lod);
    else
        renderer_->upload_level(lod);
    lod_.shown = true;
    morph_shown_ = false;
    active_frames_ = std::max(active_frames_, 2);
}

void Viewer::clear_level_of_detail(bool forget) {
    if (lod_.shown) {
        lod_.shown = false;
        show_document();
    }
    if (forget) {
        lod_ = LodState{};
        panels_.decimation.lod_ready = false;
        panels_.decimation.lod_percent = 100.0f;
    }
}

void Viewer::apply_level_of_detail() {
    if (!lod_.lod || lod_.base != document_.mesh().revision()) return;
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
    Operation op = panels_.decimation.op;
    ParamValue& target = op.value("target-vertices");
    target.x = double(lod.vertices());
    target.on = target.given = true;
    result.parameters = op.parameters();
    clear_level_of_detail(true);
    commit_result(op, std::move(result));
}

// ---- scripted sweeps (--sweep) --------------------------------------------------------------

void Viewer::start_sweep() {
    Sweep& s = sweep_;
    s.op = parse_operation(options_.sweep_op);
    // Decimation's level-of-detail slider is "lod" (percent of the vertices kept).
    s.lod = s.op.name() == "decimate" && options_.sweep_param == "lod";
    if (s.lod) {
        panels_.decimation.open = true;
        panels_.decimation.op = s.op;
        build_level_of_detail(s.op);
        s.active = true;
        return;
    }
    const std::size_t i = s.op.def->index(options_.sweep_param);
    s.param = i;
    if (OperationPanelState* panel = panel_of(s.op)) {
        panel->open = true;
        panel->op = s.op;
    }
    s.active = true;
}

void Viewer::step_sweep(bool frame_shown) {
    Sweep& s = sweep_;
    if (!s.active) return;
    if (s.lod && !lod_.lod) {
        if (!jobs_.busy()) {  // the build failed (its error is shown)
            std::fprintf(stderr, "trilab: --sweep: no levels of detail could be built\n");
            s.active = false;
            quit_ = true;
            exit_status_ = 1;
        }
        return;
    }
    if (s.lod && s.waiting) {
        if (!frame_shown) return;
        s.ms.push_back(1000.0 * (glfwGetTime() - s.t0));
        s.waiting = false;
        ++s.next;
    }
    if (s.waiting && !preview_.failure.empty()) {  // refused: the sweep ends, and says why
        std::fprintf(stderr, "trilab: --sweep: the preview of %s failed: %s\n",
                     s.current.text().c_str(), preview_.failure.c_str());
        s.active = false;
        quit_ = true;
        exit_status_ = 1;
        return;
    }
    if (s.waiting) {
        // Done when the frame just drawn showed the preview asked for.
        if (!frame_shown || !preview_.result || preview_.shown_op != s.current) return;
        s.ms.push_back(1000.0 * (glfwGetTime() - s.t0));
        note_preview_latency(s.ms.back());
        s.waiting = false;
        ++s.next;
    }
    if (s.next >= options_.sweep_count) {
        std::vector<double> sorted = s.ms;
        std::sort(sorted.begin(), sorted.end());
        const double median = sorted.empty() ? 0 : sorted[sorted.size() / 2];
        const double max = sorted.empty() ? 0 : sorted.back();
        std::printf("sweep: previews=%zu median_ms=%.1f max_ms=%.1f\n", s.ms.size(), median, max);
        std::fflush(stdout);
        s.active = false;
        quit_ = true;
        return;
    }
    const int n = options_.sweep_count;
    const double t = n > 1 ? double(s.next) / double(n - 1) : 0.0;
    double value = options_.sweep_from + t * (options_.sweep_to - options_.sweep_from);
    if (s.lod) {
        if (!(value >= 0 && value <= 100)) {
            std::fprintf(stderr, "trilab: --sweep: lod takes percentages from 0 to 100\n");
            s.active = false;
            quit_ = true;
            exit_status_ = 1;
            return;
        }
        panels_.decimation.lod_percent = float(value);
        s.t0 = glfwGetTime();
        s.waiting = true;
        show_level_of_detail(value);
        return;
    }
    const ParamSpec& spec = s.op.def->params[s.param];
    if (spec.kind == ParamKind::Integer) value = std::round(value);
    s.current = s.op;
    s.current.values[s.param].x = value;
    s.current.values[s.param].on = true;
    s.current.values[s.param].given = true;
    if (OperationPanelState* panel = panel_of(s.current)) panel->op = s.current;
    s.t0 = glfwGetTime();
    s.waiting = true;
    request_preview(s.current);
    if (!preview_.requested || *preview_.requested != s.current) {
        std::fprintf(stderr, "trilab: --sweep: %s is refused\n", s.current.text().c_str());
        s.active = false;
        quit_ = true;
        exit_status_ = 1;
    }
}

}  // namespace trilab::viewer
