// Scripted runs (script_driver.h).
//
// --sweep: each value is previewed through the session as a user's drag would, and timed from
// the request to the frame that shows it.
//
// --orbit N turns the camera once around the up axis through the target in N frames (each
// frame's rotation computed from the start, the last one the start itself, so the rested view
// is the unturned view pixel for pixel), then rests, and prints the frame times and the time
// from the last motion to the first exact frame. --print-timing prints when the model and its
// exact surface first reached the screen, from process start.
#include "app/viewer/script_driver.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_internal.h>  // --print-layout reads the window list

#include <algorithm>
#include <cfloat>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "app/ops/decimate_op.h"
#include "app/ops/operation_entries.h"
#include "app/ops/spectrum_op.h"
#include "app/session/reference_figures.h"
#include "app/viewer/decimation_tool.h"
#include "app/viewer/figure_panels.h"
#include "app/viewer/frame_output.h"
#include "app/viewer/frequency_tool.h"
#include "app/viewer/operation_tool.h"
#include "app/viewer/pick_tool.h"
#include "app/viewer/scene_view.h"
#include "app/viewer/selection_tool.h"
#include "core/errors.h"
#include "core/up_axis.h"

namespace trilab::viewer {
namespace {

/// When the process started (static initialisation, before main).
const auto kProcessStart = std::chrono::steady_clock::now();

double ms_since_start() {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() -
                                                     kProcessStart)
        .count();
}

/// The median of `ms` (not empty).
double median(std::vector<double> ms) {
    std::nth_element(ms.begin(), ms.begin() + std::ptrdiff_t(ms.size() / 2), ms.end());
    return ms[ms.size() / 2];
}

}  // namespace

std::string parse_lasso_script(const std::string& text, std::vector<glm::vec2>& points,
                               bool& through) {
    points.clear();
    through = false;
    std::size_t start = 0;
    while (start <= text.size()) {
        const std::size_t colon = std::min(text.find(':', start), text.size());
        const std::string part = text.substr(start, colon - start);
        start = colon + 1;
        if (part == "through" && start > text.size()) {
            through = true;
            break;
        }
        float x = 0, y = 0;
        char extra = 0;
        if (std::sscanf(part.c_str(), "%f,%f%c", &x, &y, &extra) != 2 || !std::isfinite(x) ||
            !std::isfinite(y))
            return "point " + std::to_string(points.size() + 1) + " (\"" + part +
                   "\") is not X,Y in window pixels";
        points.emplace_back(x, y);
    }
    if (points.size() < 3)
        return "a lasso needs at least three points, got " + std::to_string(points.size());
    return "";
}

ScriptDriver::ScriptDriver(const ViewerOptions& options, ViewerContext& context, SceneView& scene,
                           Tools& tools, FrameOutput& output)
    : options_(options),
      context_(context),
      session_(context.session),
      scene_(scene),
      tools_(tools),
      output_(output) {
    initial_load_ended_ = options_.mesh_path.empty();
    // --click finds its widgets through the hook.
    if (!options_.clicks.empty())
        set_widget_hook([this](const WidgetNote& note) { clicks_.drawing.push_back(note); });
}

ScriptDriver::~ScriptDriver() {
    if (!options_.clicks.empty()) set_widget_hook(nullptr);
}

void ScriptDriver::advance() {
    advance_operations();
    decompose();
    next_pick();
    if (sweep_.active || (!options_.sweep_op.empty() && !sweep_.started && ready())) {
        if (!sweep_.started) {
            sweep_.started = true;
            start_sweep();
        }
        context_.keep_drawing();
    }
    context_.sweeping = sweep_.active;
}

void ScriptDriver::drive_mouse() {
    drive_clicks();
    drive_lasso();  // --lasso: the mouse as a user draws it
}

bool ScriptDriver::timing_frames() const {
    return sweep_.active || (options_.orbit_frames > 0 && !orbit_.done) ||
           (options_.print_timing && exact_frame_ms_ < 0);
}

void ScriptDriver::frame_end(double frame_ms) {
    note_timing(frame_ms);
    if (sweep_.active)
        step_sweep(scene_.shows_current() && (session_.shown().kind == Shown::Kind::Preview ||
                                              session_.shown().kind == Shown::Kind::Level));
    context_.sweeping = sweep_.active;
}

void ScriptDriver::finish(double median_frame_ms, std::size_t frames_timed) {
    if (options_.frames > 0) log_last_frame(median_frame_ms, frames_timed);
    if (options_.print_timing) print_timing();
}

std::vector<OperationPanelState*> ScriptDriver::operation_panels() {
    std::vector<OperationPanelState*> panels;
    for (const auto& tool : tools_.all)
        for (OperationPanelState* panel : tool->operation_panels()) panels.push_back(panel);
    return panels;
}

void ScriptDriver::advance_operations() {
    // The initial load has ended (or failed): each --op runs on what it loaded, in order, each
    // once the one before has finished (one job at a time).
    if (!initial_load_ended_ && !session_.busy()) initial_load_ended_ = true;
    if (!initial_load_ended_ || initial_ops_done_) return;
    const bool loaded =
        options_.mesh_path.empty() || session_.document().path == options_.mesh_path;
    // --select, one SPEC at a time, before --op (which then acts on the selection).
    if (loaded && next_select_ < options_.selections.size()) {
        if (!session_.busy() && context_.commands.empty()) next_selection();
        return;
    }
    if (loaded && next_op_ < options_.operations.size()) {
        if (session_.busy() || !context_.commands.empty()) return;
        context_.commands.push_back(RunOperation{parse_operation(options_.operations[next_op_++])});
    }
    if (!loaded || next_op_ >= options_.operations.size()) initial_ops_done_ = true;
}

bool ScriptDriver::ready() const {
    // The initial load and --op are done (queued) and no job runs.
    return !session_.jobs().busy() && initial_load_ended_ && initial_ops_done_ &&
           context_.commands.empty();
}

bool ScriptDriver::settled() {
    if (session_.jobs().busy() || !context_.commands.empty() || session_.previews().pending() ||
        session_.guidance().computing() || !ready() || sweep_.active || output_.recording())
        return false;
    if (!options_.decompose.empty() && decompose_state_ != 2) return false;
    if (clicks_pending() || picks_pending() || selections_pending()) return false;
    if (!options_.sweep_op.empty() && !sweep_.started) return false;
    if (!motion_settled()) return false;  // the orbit, its rest, the exact surface
    if (session_.morph().playing) {       // end it: the next frame shows where it ends
        context_.commands.push_back(ShowMorphAt{1.0});
        return false;
    }
    if (options_.morph_t >= 0 && !morph_t_done_) {
        morph_t_done_ = true;
        if (session_.history().current() == 0 || !session_.morph().moves)
            session_.log().warning("--morph-t: the current state has no morph to show");
        context_.commands.push_back(ShowMorphAt{options_.morph_t});
        return false;
    }
    return true;
}

void ScriptDriver::print_layout(GLFWwindow* window) const {
    int fb_w = 0, fb_h = 0;
    glfwGetFramebufferSize(window, &fb_w, &fb_h);
    const ImGuiIO& io = ImGui::GetIO();
    const float sx = io.DisplayFramebufferScale.x, sy = io.DisplayFramebufferScale.y;
    // Whole pixels that contain the rectangle (the test checks the rule on these).
    auto line = [&](const char* what, float x, float y, float w, float h) {
        const long x0 = std::lround(std::floor(x * sx)), y0 = std::lround(std::floor(y * sy));
        const long x1 = std::lround(std::ceil((x + w) * sx));
        const long y1 = std::lround(std::ceil((y + h) * sy));
        std::printf("%s %ld %ld %ld %ld\n", what, x0, y0, x1 - x0, y1 - y0);
    };
    std::printf("framebuffer %d %d\n", fb_w, fb_h);
    line("view", context_.view_rect.x, context_.view_rect.y, context_.view_rect.w,
         context_.view_rect.h);
    // Every window ImGui drew in the last frame, except child windows (inside their parent)
    // and tooltips (they follow the mouse).
    for (const ImGuiWindow* w : ImGui::GetCurrentContext()->Windows) {
        if (!w->Active || w->Hidden) continue;
        if (w->Flags & (ImGuiWindowFlags_ChildWindow | ImGuiWindowFlags_Tooltip)) continue;
        std::string title = w->Name;
        for (char& c : title)
            if (c == '"') c = '\'';
        const std::string what = "window \"" + title + "\"";
        line(what.c_str(), w->Pos.x, w->Pos.y, w->Size.x, w->Size.y);
    }
    std::fflush(stdout);
}

void ScriptDriver::log_last_frame(double median_frame_ms, std::size_t frames_timed) {
    char buf[96];
    std::snprintf(buf, sizeof(buf), "median frame time %.1f ms over the last %zu frames",
                  median_frame_ms, frames_timed);
    session_.log().info(buf);
    // What the last frame showed, for scripts and tests.
    const History& h = session_.history();
    std::string entries;
    for (std::size_t i = 0; i < h.size() && i < 20; ++i)
        entries += (i ? " | " : "") + std::to_string(i) + " " + h.info(i).label;
    session_.log().info("history: " + entries);
    std::snprintf(buf, sizeof(buf), ", morph t = %.3f", session_.morph().t);
    session_.log().info("last frame: " + session_.document().info[1] + buf);
    const char* setting = context_.view.settings.wireframe == WireframeOverlay::Auto ? "automatic"
                          : context_.view.settings.wireframe == WireframeOverlay::On ? "on"
                                                                                     : "off";
    std::snprintf(buf, sizeof(buf), "wireframe overlay %s (%s; edges %.1f px on the screen)",
                  context_.view.style.wireframe ? "on" : "off", setting, scene_.edge_pixels());
    session_.log().info(buf);
    session_.log().info("status: " + session_.notice().text);
}

void ScriptDriver::start_sweep() {
    Sweep& s = sweep_;
    s.op = parse_operation(options_.sweep_op);
    // Decimation's level-of-detail slider is "lod" (percent of the vertices kept).
    s.lod = is_operation<DecimateOptions>(s.op) && options_.sweep_param == "lod";
    if (s.lod) {
        tools_.decimation->panel().open = true;
        tools_.decimation->panel().op = s.op;
        session_.execute(BuildLevelOfDetail{s.op});
        s.active = true;
        return;
    }
    // What the command line refuses, a sweep refuses (Taubin takes no step).
    try {
        check_parameter_applies(s.op, options_.sweep_param);
    } catch (const Error& e) {
        std::fprintf(stderr, "trilab: --sweep: %s\n", e.what());
        s.started = true;
        quit_ = true;
        exit_status_ = 1;
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

void ScriptDriver::step_sweep(bool frame_shown) {
    Sweep& s = sweep_;
    if (!s.active) return;
    if (s.lod && !session_.levels().ready()) {
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
        !session_.previews().failure().empty()) {  // refused: the sweep ends, and says why
        std::fprintf(stderr, "trilab: --sweep: the preview of %s failed: %s\n",
                     s.current.text().c_str(), session_.previews().failure().c_str());
        s.active = false;
        quit_ = true;
        exit_status_ = 1;
        return;
    }
    if (s.waiting) {
        // Done when the frame just drawn showed the preview asked for (or, on a large mesh,
        // its clustered spectral prediction while the prediction is computed).
        const bool predicted = scene_.drew_prediction_of(s.current);
        if (!predicted && (!frame_shown || !session_.previews().shown(s.current))) return;
        // A preview that stopped early (a diverging step) is a failure, as --op's run is.
        const OperationResult* result = session_.previews().result();
        if (!predicted && result && result->stopped_early) {
            std::fprintf(stderr, "trilab: --sweep: the preview of %s %s\n",
                         s.current.text().c_str(), run_failure(*result).c_str());
            s.active = false;
            quit_ = true;
            exit_status_ = 1;
            return;
        }
        s.ms.push_back(1000.0 * (glfwGetTime() - s.t0));
        for (OperationPanelState* panel : operation_panels())
            if (panel->op.def == s.current.def)
                OperationTool::note_preview_latency(*panel, s.ms.back());
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
        tools_.decimation->panel().lod_percent = float(value);
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
    if (!session_.previews().requested() || *session_.previews().requested() != s.current) {
        std::fprintf(stderr, "trilab: --sweep: %s is refused\n", s.current.text().c_str());
        s.active = false;
        quit_ = true;
        exit_status_ = 1;
    }
}

void ScriptDriver::next_pick() {
    if (next_pick_ >= options_.picks.size() || !ready() || session_.busy()) return;
    const std::string& spec = options_.picks[next_pick_];
    const bool second = next_pick_ > 0;
    ++next_pick_;
    float x = 0, y = 0;
    char extra = 0;
    if (std::sscanf(spec.c_str(), "%f,%f%c", &x, &y, &extra) != 2 || !std::isfinite(x) ||
        !std::isfinite(y)) {
        session_.notify_error("--pick: expected X,Y in window pixels, got \"" + spec + "\"");
        exit_status_ = 1;
        return;
    }
    const glm::vec2 view_pos(x - context_.view_rect.x, y - context_.view_rect.y);
    const std::optional<Pick> hit = tools_.pick->pick_at(view_pos, second);
    if (hit)
        std::printf("pick: %s\n", pick_line(*hit).c_str());
    else
        std::printf("pick: nothing at %g,%g (the background)\n", double(x), double(y));
    std::fflush(stdout);
}

bool ScriptDriver::picks_pending() const {
    // The last frame of a scripted run shows the Inspector filled in.
    return next_pick_ < options_.picks.size() ||
           (!options_.picks.empty() && session_.picking().pending());
}

bool ScriptDriver::next_selection() {
    if (next_select_ >= options_.selections.size()) return false;
    context_.commands.push_back(SelectSpec{options_.selections[next_select_++]});
    return true;
}

bool ScriptDriver::selections_pending() const {
    return next_select_ < options_.selections.size() ||
           (!options_.brush.empty() && brush_.state != 2) ||
           (!options_.lasso.empty() && lasso_.state != 3) || tools_.selection->stroking();
}

void ScriptDriver::brush_step() {
    ScriptedBrush& b = brush_;
    if (options_.brush.empty() || b.state == 2) return;
    const double now = glfwGetTime();
    // The frame after a move: the move's overlay has been drawn and swapped.
    if (b.moved_at >= 0) {
        b.ms.push_back(1000.0 * (now - b.moved_at));
        b.moved_at = -1;
    }
    if (b.state == 0) {
        // The view's place comes from the first frames' layout: wait for it.
        if (++b.frames_waited < 3 || !ready() || session_.busy() ||
            next_select_ < options_.selections.size())
            return;
        float x0 = 0, y0 = 0, x1 = 0, y1 = 0, r = tools_.selection->panel().brush_radius;
        char extra = 0;
        const int n =
            std::sscanf(options_.brush.c_str(), "%f,%f:%f,%f:%f%c", &x0, &y0, &x1, &y1, &r, &extra);
        if ((n != 4 && n != 5) || !std::isfinite(x0) || !std::isfinite(y0) || !std::isfinite(x1) ||
            !std::isfinite(y1) || !(r > 0 && r < 10000)) {
            session_.notify_error(
                "--brush: expected \"X0,Y0:X1,Y1[:R]\" in window pixels (R > 0), got \"" +
                options_.brush + "\"");
            exit_status_ = 1;
            b.state = 2;
            return;
        }
        b.from = glm::vec2(x0 - context_.view_rect.x, y0 - context_.view_rect.y);
        b.to = glm::vec2(x1 - context_.view_rect.x, y1 - context_.view_rect.y);
        tools_.selection->panel().brush_radius = r;
        b.state = 1;
        tools_.selection->set_scripted(true);  // the real mouse waits
        b.step = 0;
        tools_.selection->begin_stroke(true, false, b.from);
        b.moved_at = now;
        return;
    }
    if (b.step < b.steps) {
        ++b.step;
        const float t = float(b.step) / float(b.steps);
        const double t0 = glfwGetTime();
        tools_.selection->continue_stroke(b.from + t * (b.to - b.from));
        b.moved_at = t0;
        context_.keep_drawing(2);
        return;
    }
    tools_.selection->end_stroke();
    tools_.selection->set_scripted(false);
    b.state = 2;
    if (b.ms.empty()) return;
    std::printf("brush: samples=%zu median_ms=%.2f max_ms=%.2f\n", b.ms.size(), median(b.ms),
                *std::max_element(b.ms.begin(), b.ms.end()));
    std::fflush(stdout);
}

void ScriptDriver::drive_lasso() {
    ScriptedLasso& l = lasso_;
    if (options_.lasso.empty() || l.state == 3) return;
    ImGuiIO& io = ImGui::GetIO();
    if (l.state == 0) {
        // After the layout settles, --op, --select and --brush (one stroke at a time).
        if (++l.frames_waited < 3 || !ready() || session_.busy() ||
            next_select_ < options_.selections.size() || clicks_pending() ||
            (!options_.brush.empty() && brush_.state != 2) || tools_.selection->stroking())
            return;
        std::vector<glm::vec2> points;
        bool through = false;
        const std::string error = parse_lasso_script(options_.lasso, points, through);
        if (!error.empty()) {  // main() checked it: not reached from the command line
            session_.notify_error("--lasso: " + error);
            exit_status_ = 1;
            l.state = 3;
            return;
        }
        // What the user chooses first: the Selection section open, its Lasso tool.
        tools_.selection->panel().open = true;
        tools_.selection->panel().tool = SelectionPanelState::Tool::Lasso;
        tools_.selection->panel().lasso_through = through;
        // The mouse's place in each frame: pressed at the first point, moved along each side in
        // a few steps (the lasso closes itself back to the first point on release).
        constexpr int kStepsPerSide = 4;
        l.path = {points[0]};
        for (std::size_t i = 1; i < points.size(); ++i)
            for (int k = 1; k <= kStepsPerSide; ++k)
                l.path.push_back(points[i - 1] +
                                 (float(k) / kStepsPerSide) * (points[i] - points[i - 1]));
        l.state = 1;
        l.step = 0;
    }
    if (l.state == 1) {
        // Frame 0 hovers the first point, frames 1..n hold the button along the path (frame 1
        // presses), the frame after releases. Ctrl is the lasso's adding modifier.
        const std::size_t at = l.step == 0 ? 0 : std::min(l.step - 1, l.path.size() - 1);
        io.MousePos = ImVec2(l.path[at].x, l.path[at].y);
        io.MouseDown[0] = l.step >= 1 && l.step <= l.path.size();
        io.KeyCtrl = true;
        io.KeyAlt = io.KeyShift = false;
        if (++l.step > l.path.size() + 1) l.state = 2;
        context_.keep_drawing(2);
        return;
    }
    // Released: the mouse goes away and Ctrl up; report once the entry is in the document.
    io.MousePos = ImVec2(-FLT_MAX, -FLT_MAX);
    io.MouseDown[0] = false;
    io.KeyCtrl = false;
    context_.keep_drawing(2);
    if (tools_.selection->stroking() || session_.busy() || !context_.commands.empty()) return;
    l.state = 3;
    std::printf("lasso: vertices=%zu\n", session_.selections().count());
    std::fflush(stdout);
}

void ScriptDriver::decompose() {
    // --figure first: its model is what a --decompose decomposes.
    if (!figure()) return;
    if (options_.decompose.empty() || decompose_state_ == 2) return;
    // Wait for the initial load (a job) and operation before decomposing.
    if (!ready()) return;
    unsigned k = 0, lo = 0, hi = 0;
    const int n = std::sscanf(options_.decompose.c_str(), "%u:%u:%u", &k, &lo, &hi);
    FrequencyPanelState& s = tools_.frequency->panel();
    if (decompose_state_ == 0) {
        decompose_state_ = 1;
        if (n < 1 || k < 1) {
            decompose_state_ = 2;
            session_.notify_error("--decompose: expected K or K:LO:HI, got '" + options_.decompose +
                                  "'");
            return;
        }
        SpectrumOptions o = options_of<SpectrumOptions>(s.op);
        o.k = k;
        set_options(s.op, o);
        context_.commands.push_back(Decompose{s.op});
    } else if (session_.document().frequency.valid) {
        decompose_state_ = 2;
        if (n == 3) {
            s.lo = int(lo);
            s.hi = int(hi);
            context_.commands.push_back(PreviewBand{lo, hi});
            context_.commands.push_back(CommitBand{lo, hi});
        }
    } else {
        decompose_state_ = 2;  // the decomposition failed (its error is shown)
    }
}

bool ScriptDriver::figure() {
    if (options_.figure.empty() || figure_state_ == 2) return true;
    if (!ready()) return false;
    if (figure_state_ == 1) {  // queued, and its job has ended
        figure_state_ = 2;
        return true;
    }
    figure_state_ = 1;
    const ReferenceFigure* figure = find_reference_figure(options_.figure);
    if (!figure) {
        figure_state_ = 2;
        exit_status_ = 1;
        session_.notify_error("--figure: no reference figure '" + options_.figure +
                              "'; the figures are " + reference_figure_names());
        return true;
    }
    show_figure_in_panels(*figure, tools_.list());
    context_.commands.push_back(LoadFigure{figure->name});
    return false;
}

void ScriptDriver::turn_camera() {
    const int n = options_.orbit_frames;
    if (n > 0 && !orbit_.done) {
        if (orbit_.frame < 0) {
            if (ready() && !session_.previews().pending() && !session_.morph().playing &&
                scene_.at_rest(glfwGetTime())) {
                orbit_.frame = 0;
                orbit_.start = context_.view.camera;
                orbit_.ms.clear();
            }
        }
        if (orbit_.frame >= 0 && orbit_.frame < n) {
            ++orbit_.frame;
            if (orbit_.frame == n) {
                context_.view.camera = orbit_.start;  // exactly where it started
            } else {
                const Vector3 up = up_vector(context_.view.settings.up);
                const float angle = float(2.0 * M_PI * double(orbit_.frame) / double(n));
                const glm::quat turn =
                    glm::angleAxis(angle, glm::vec3(float(up.x()), float(up.y()), float(up.z())));
                const Camera& s = orbit_.start;
                context_.view.camera.set_state(s.rotation() * turn, s.target(), s.distance(),
                                               s.radius(), s.fov_y());
            }
        }
        context_.keep_drawing();
    }
}

void ScriptDriver::note_timing(double frame_ms) {
    const bool model_shown =
        initial_load_ended_ &&
        (options_.mesh_path.empty() || session_.document().path == options_.mesh_path);
    // The loading picture of the file asked for shows the model (simplified).
    const bool picture_shown = scene_.loading_picture_drawn() && !options_.mesh_path.empty() &&
                               scene_.loading_picture_path() &&
                               *scene_.loading_picture_path() == options_.mesh_path;
    if (picture_shown && first_frame_ms_ < 0) first_frame_ms_ = ms_since_start();
    if (model_shown && scene_.shows_current()) {
        if (first_frame_ms_ < 0) first_frame_ms_ = ms_since_start();
        if (exact_frame_ms_ < 0 && !scene_.drew_proxy() && !scene_.exact_pending())
            exact_frame_ms_ = ms_since_start();
    }
    const int n = options_.orbit_frames;
    if (n <= 0 || orbit_.done || orbit_.frame <= 0) return;
    if (orbit_.frame <= n && int(orbit_.ms.size()) < orbit_.frame) {  // a turning frame
        orbit_.ms.push_back(frame_ms);
        if (scene_.drew_proxy()) ++orbit_.proxy_frames;
        if (orbit_.frame == n) orbit_.motion_end = glfwGetTime();
        return;
    }
    if (orbit_.frame < n || scene_.drew_proxy() || !scene_.shows_current() ||
        scene_.exact_pending())
        return;
    // The first exact frame after the turn is on the screen.
    const double rest_ms = 1000.0 * (glfwGetTime() - orbit_.motion_end);
    std::vector<double> sorted = orbit_.ms;
    std::sort(sorted.begin(), sorted.end());
    std::printf("orbit: frames=%d median_ms=%.1f max_ms=%.1f rest_ms=%.1f\n", n,
                sorted[sorted.size() / 2], sorted.back(), rest_ms);
    std::printf("orbit: proxy_frames=%zu exact_frames=%zu error_px=%.2f\n", orbit_.proxy_frames,
                orbit_.ms.size() - orbit_.proxy_frames,
                orbit_.proxy_frames ? scene_.error_pixels() : 0.0);
    std::fflush(stdout);
    orbit_.done = true;
}

bool ScriptDriver::motion_settled() const {
    if (options_.orbit_frames > 0 && !orbit_.done) return false;
    return scene_.settled(glfwGetTime());
}

void ScriptDriver::print_timing() const {
    std::printf("timing: first_frame_ms=%.0f exact_frame_ms=%.0f\n", first_frame_ms_,
                exact_frame_ms_);
    std::fflush(stdout);
}

}  // namespace trilab::viewer
