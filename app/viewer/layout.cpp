#include "app/viewer/layout.h"

#include <algorithm>
#include <cmath>

namespace trilab::viewer {
namespace {

/// `value` (or `fallback` when 0) clamped to [lo, hi], where hi wins over lo; whole pixels.
float clamp_size(float value, float fallback, float lo, float hi) {
    const float v = value > 0 ? value : fallback;
    return std::floor(std::max(0.0f, std::min(std::max(v, lo), hi)));
}

}  // namespace

Layout compute_layout(const LayoutInput& in, LayoutState& state) {
    Layout l;
    const float W = std::floor(std::max(in.width, 1.0f));
    const float H = std::floor(std::max(in.height, 1.0f));
    const float em = in.em;
    // The menu bar and the status bar: one line each, never more than a fifth of the height.
    const float menu_h = clamp_size(state.menu_height, in.frame_height, 0.0f, 0.2f * H);
    const float status_h = clamp_size(std::ceil(in.frame_height + 0.4f * em), 0, 0.0f, 0.2f * H);
    l.menu = Rect{0, 0, W, menu_h};
    l.status = Rect{0, H - status_h, W, status_h};
    const float middle_y = menu_h, middle_h = std::max(0.0f, H - menu_h - status_h);

    // Left sidebar, right history column: each at most a share of the width, so that the
    // view keeps at least a third of it.
    state.sidebar_width =
        clamp_size(state.sidebar_width, 26.0f * em, std::min(14.0f * em, 0.4f * W), 0.4f * W);
    if (in.sidebar) l.sidebar = Rect{0, middle_y, state.sidebar_width, middle_h};
    float right_x = W;
    if (in.history) {
        state.history_width =
            clamp_size(state.history_width, 20.0f * em, std::min(10.0f * em, 0.25f * W), 0.25f * W);
        right_x = W - state.history_width;
        l.history = Rect{right_x, middle_y, state.history_width, middle_h};
    }
    const float strip_x = in.sidebar ? l.sidebar.right() : 0.0f,
                strip_w = std::max(0.0f, right_x - strip_x);

    // The bottom strip under the view: the log and the colour legend side by side.
    float strip_h = 0;
    if (in.log) {
        state.log_height = clamp_size(state.log_height, 10.0f * em,
                                      std::min(4.0f * em, 0.35f * middle_h), 0.35f * middle_h);
        strip_h = state.log_height;
    }
    float legend_w = 0;
    if (in.legend) {
        const float h = state.legend_height > 0 ? state.legend_height : 5.0f * in.frame_height;
        strip_h = std::max(strip_h, clamp_size(std::ceil(h), 0, 0.0f, std::floor(0.5f * middle_h)));
        l.legend_max_width = std::floor(in.log ? 0.6f * strip_w : strip_w);
        l.legend_max_height = std::floor(0.5f * middle_h);
        const float w = state.legend_width > 0 ? state.legend_width : 18.0f * em;
        legend_w = clamp_size(std::ceil(w), 0, 0.0f, l.legend_max_width);
    }
    const float strip_y = middle_y + middle_h - strip_h;
    if (in.log) l.log = Rect{strip_x, strip_y, strip_w - legend_w, strip_h};
    if (in.legend) l.legend = Rect{strip_x + strip_w - legend_w, strip_y, legend_w, strip_h};
    l.view = Rect{strip_x, middle_y, strip_w, std::max(0.0f, middle_h - strip_h)};
    return l;
}

}  // namespace trilab::viewer
