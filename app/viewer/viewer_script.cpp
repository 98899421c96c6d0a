// Scripted runs: --op after the initial load, the end of a run (--frames: the last frame
// waits for everything started), its log and --print-layout.
#include "app/viewer/viewer.h"

// glad before GLFW: GLFW must not include the system GL header.
#include <glad/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>
#include <imgui_internal.h>  // --print-layout reads the window list

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <tuple>
#include <utility>
#include <vector>

#include "app/ops/operation.h"
#include "app/ops/operation_entries.h"
#include "app/record/recorder.h"
#include "app/viewer/key_bindings.h"
#include "app/viewer/viewer_tuning.h"
#include "core/algorithms/coincident.h"
#include "core/algorithms/decimation.h"
#include "core/algorithms/fairing.h"
#include "core/algorithms/generators.h"
#include "core/algorithms/mesh_stats.h"
#include "core/algorithms/orientation.h"
#include "core/algorithms/texcoords.h"
#include "core/errors.h"
#include "core/geometry.h"
#include "core/io/mesh_io.h"
#include "render/offscreen.h"

namespace trilab::viewer {
using namespace tuning;

void Viewer::advance_script() {
    // The initial load has ended (or failed): each --op runs on what it loaded, in order, each
    // once the one before has finished (one job at a time).
    if (!initial_load_ended_ && !session_.busy()) initial_load_ended_ = true;
    if (!initial_load_ended_ || initial_op_done_) return;
    const bool loaded =
        options_.mesh_path.empty() || session_.document().path == options_.mesh_path;
    // --select, one SPEC at a time, before --op (which then acts on the selection).
    if (loaded && next_scripted_select_ < options_.selections.size()) {
        if (!session_.busy() && commands_.empty()) scripted_selection();
        return;
    }
    if (loaded && next_op_ < options_.operations.size()) {
        if (session_.busy() || !commands_.empty()) return;
        commands_.push_back(RunOperation{parse_operation(options_.operations[next_op_++])});
    }
    if (!loaded || next_op_ >= options_.operations.size()) initial_op_done_ = true;
}

bool Viewer::ready_for_script() const {
    // The initial load and --op are done (queued) and no job runs.
    return !session_.jobs().busy() && initial_load_ended_ && initial_op_done_ && commands_.empty();
}

bool Viewer::script_settled() {
    if (session_.jobs().busy() || !commands_.empty() || session_.preview_pending() ||
        !ready_for_script() || sweep_.active || panels_.record.running)
        return false;
    if (!options_.decompose.empty() && scripted_decompose_ != 2) return false;
    if (clicks_pending() || scripted_picks_pending() || selection_script_pending()) return false;
    if (!options_.sweep_op.empty() && !sweep_started_) return false;
    if (!motion_settled()) return false;  // the orbit, its rest, the exact surface
    if (session_.morph().playing) {       // end it: the next frame shows where it ends
        session_.morph().t = 1.0;
        session_.morph().playing = false;
        return false;
    }
    if (options_.morph_t >= 0 && !morph_t_done_) {
        morph_t_done_ = true;
        if (session_.history().current() == 0 || !session_.morph().moves)
            session_.log().warning("--morph-t: the current state has no morph to show");
        session_.morph().t = options_.morph_t;
        session_.morph().playing = false;
        return false;
    }
    return true;
}

void Viewer::print_layout() const {
    int fb_w = 0, fb_h = 0;
    glfwGetFramebufferSize(window_.get(), &fb_w, &fb_h);
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
    line("view", view_rect_.x, view_rect_.y, view_rect_.w, view_rect_.h);
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

void Viewer::log_last_frame() {
    char buf[96];
    std::snprintf(buf, sizeof(buf), "median frame time %.1f ms over the last %zu frames",
                  frame_ms(), std::min(n_frame_times_, frame_times_ms_.size()));
    session_.log().info(buf);
    // What the last frame showed, for scripts and tests.
    const History& h = session_.history();
    std::string entries;
    for (std::size_t i = 0; i < h.size() && i < 20; ++i)
        entries += (i ? " | " : "") + std::to_string(i) + " " + h.info(i).label;
    session_.log().info("history: " + entries);
    std::snprintf(buf, sizeof(buf), ", morph t = %.3f", session_.morph().t);
    session_.log().info("last frame: " + session_.document().info[1] + buf);
    const char* setting = view_.settings.wireframe == WireframeOverlay::Auto ? "automatic"
                          : view_.settings.wireframe == WireframeOverlay::On ? "on"
                                                                             : "off";
    std::snprintf(buf, sizeof(buf), "wireframe overlay %s (%s; edges %.1f px on the screen)",
                  view_.style.wireframe ? "on" : "off", setting, edge_pixels_);
    session_.log().info(buf);
    session_.log().info("status: " + session_.notice().text);
}

}  // namespace trilab::viewer
