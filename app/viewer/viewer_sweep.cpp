// Scripted sweeps over a panel parameter (--sweep): each value is previewed through the
// session as a user's drag would, and timed from the request to the frame that shows it.
// glad before GLFW: GLFW must not include the system GL header.
#include <glad/gl.h>

#include <GLFW/glfw3.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "app/ops/decimate_op.h"
#include "app/viewer/viewer.h"

namespace trilab::viewer {

// ---- scripted sweeps (--sweep) --------------------------------------------------------------

void Viewer::start_sweep() {
    Sweep& s = sweep_;
    s.op = parse_operation(options_.sweep_op);
    // Decimation's level-of-detail slider is "lod" (percent of the vertices kept).
    s.lod = is_operation<DecimateOptions>(s.op) && options_.sweep_param == "lod";
    if (s.lod) {
        panels_.decimation.open = true;
        panels_.decimation.op = s.op;
        session_.execute(BuildLevelOfDetail{s.op});
        s.active = true;
        return;
    }
    const std::size_t i = s.op.def->index(options_.sweep_param);
    s.param = i;
    for (OperationPanelState* panel : operation_panels()) {
        if (panel->op.def != s.op.def) continue;
        panel->open = true;
        panel->op = s.op;
    }
    s.active = true;
}

void Viewer::step_sweep(bool frame_shown) {
    Sweep& s = sweep_;
    if (!s.active) return;
    if (s.lod && !session_.has_level_of_detail()) {
        if (!session_.busy()) {  // the build failed (its error is shown)
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
    if (s.waiting &&
        !session_.preview_failure().empty()) {  // refused: the sweep ends, and says why
        std::fprintf(stderr, "trilab: --sweep: the preview of %s failed: %s\n",
                     s.current.text().c_str(), session_.preview_failure().c_str());
        s.active = false;
        quit_ = true;
        exit_status_ = 1;
        return;
    }
    if (s.waiting) {
        // Done when the frame just drawn showed the preview asked for (or, on a large mesh,
        // its clustered spectral prediction while the prediction is computed).
        const bool predicted = proxy_.drew_predicted && proxy_.predicted_for == s.current;
        if (!predicted && (!frame_shown || !session_.preview_shown(s.current))) return;
        s.ms.push_back(1000.0 * (glfwGetTime() - s.t0));
        for (OperationPanelState* panel : operation_panels())
            if (panel->op.def == s.current.def) note_preview_latency(*panel, s.ms.back());
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
        session_.execute(ShowLevelOfDetail{value});
        return;
    }
    const ParamSpec& spec = s.op.def->params[s.param];
    if (spec.kind == ParamKind::Integer) {
        value = std::round(value);
        // A slider over whole numbers moves only when the value changes: with more moves than
        // whole numbers in the range the sweep drags it back and forth between FROM and TO,
        // one step a move (2:1:20 shows the computed levels 2, 1, 2, 1, ...).
        const double lo = std::round(options_.sweep_from), hi = std::round(options_.sweep_to);
        const int span = int(std::abs(hi - lo));
        if (span > 0 && n > span + 1) {
            const int pos = s.next % (2 * span);
            value = lo + (hi > lo ? 1 : -1) * (pos <= span ? pos : 2 * span - pos);
        }
    }
    s.current = s.op;
    s.current.values[s.param].x = value;
    s.current.values[s.param].on = true;
    s.current.values[s.param].given = true;
    for (OperationPanelState* panel : operation_panels())
        if (panel->op.def == s.current.def) panel->op = s.current;
    s.t0 = glfwGetTime();
    s.waiting = true;
    session_.execute(PreviewOperation{s.current});
    if (!session_.preview_requested() || *session_.preview_requested() != s.current) {
        std::fprintf(stderr, "trilab: --sweep: %s is refused\n", s.current.text().c_str());
        s.active = false;
        quit_ = true;
        exit_status_ = 1;
    }
}

}  // namespace trilab::viewer
