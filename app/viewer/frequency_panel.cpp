// The Frequency panel; see frequency_panel.h.
#include "app/viewer/frequency_panel.h"

#include "app/viewer/panels.h"

#include <imgui.h>

#include <algorithm>
#include <cstdio>

namespace trilab::viewer {
namespace {

constexpr float kPlotWidthEm = 26.0f;  ///< the most width the bar and the plots take

/// The width of the bar and the plots: kPlotWidthEm, less in a narrow sidebar.
float plot_width() {
    return std::min(kPlotWidthEm * ImGui::GetFontSize(), ImGui::GetContentRegionAvail().x);
}

/// The frequency bar: every computed frequency as a grey strip, the applied band in green
/// and the slider band outlined in orange.
void frequency_bar(const FrequencyDocument& doc, int lo, int hi) {
    const std::size_t k = doc.eigenvalues.size();
    const float w = plot_width(), h = ImGui::GetFrameHeight() * 0.7f;
    const ImVec2 p = ImGui::GetCursorScreenPos();
    ImDrawList* dl = ImGui::GetWindowDrawList();
    dl->AddRectFilled(p, ImVec2(p.x + w, p.y + h), IM_COL32(70, 70, 70, 255));
    if (k > 0) {
        const auto x = [&](double i) { return p.x + float(i / double(k)) * w; };
        if (doc.applied)
            dl->AddRectFilled(ImVec2(x(double(doc.applied_lo)), p.y),
                              ImVec2(x(double(doc.applied_hi) + 1), p.y + h),
                              IM_COL32(60, 170, 90, 255));
        dl->AddRect(ImVec2(x(lo), p.y), ImVec2(x(hi + 1), p.y + h), IM_COL32(255, 160, 40, 255),
                    0.0f, 0, 2.0f);
    }
    ImGui::Dummy(ImVec2(w, h));
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip(
            "grey: the %zu computed frequencies; green: the band of the current "
            "state; orange: the sliders' band",
            k);
}

/// A line plot with the band [lo, hi] shaded.
void band_plot(const char* label, const std::vector<float>& values, int lo, int hi,
               const char* overlay) {
    if (values.empty()) return;
    const float w = plot_width();
    ImGui::PlotLines(label, values.data(), int(values.size()), 0, overlay, FLT_MAX, FLT_MAX,
                     ImVec2(w, 5.0f * ImGui::GetFontSize()));
    const ImVec2 a = ImGui::GetItemRectMin(), b = ImGui::GetItemRectMax();
    const float n = float(std::max<std::size_t>(values.size() - 1, 1));
    const float x0 = a.x + (b.x - a.x) * float(lo) / n, x1 = a.x + (b.x - a.x) * float(hi) / n;
    ImGui::GetWindowDrawList()->AddRectFilled(ImVec2(x0, a.y), ImVec2(std::max(x1, x0 + 1), b.y),
                                              IM_COL32(255, 160, 40, 60));
}

}  // namespace

FrequencyActions frequency_window(FrequencyPanelState& s, const FrequencyDocument& doc, bool busy) {
    FrequencyActions act;
    if (!section_header("Frequency decomposition", s.open)) return act;
    const float em = ImGui::GetFontSize();
    // The decomposition's parameters, drawn from the operation's declaration (the band is
    // the sliders below; threads and the size limit keep their defaults here).
    operation_widgets(s.op, {"band", "threads", "max-full"});
    if (busy) ImGui::BeginDisabled();
    act.decompose = ImGui::Button("Decompose");
    ImGui::SameLine();
    const bool have = doc.decomposition && doc.valid && !doc.eigenvalues.empty();
    if (!have) ImGui::BeginDisabled();
    act.restore = ImGui::Button("Restore");
    if (!have) ImGui::EndDisabled();
    if (busy) ImGui::EndDisabled();
    if (doc.decomposition && !doc.valid)
        ImGui::TextWrapped("The decomposition belongs to another mesh: decompose again.");
    if (!doc.summary.empty()) {
        ImGui::PushTextWrapPos(0.0f);
        ImGui::TextUnformatted(doc.summary.c_str());
        ImGui::PopTextWrapPos();
    }

    if (have) {
        const int last = int(doc.eigenvalues.size()) - 1;
        s.lo = std::clamp(s.lo, 0, last);
        s.hi = std::clamp(s.hi, s.lo, last);
        ImGui::Separator();
        frequency_bar(doc, s.lo, s.hi);
        if (busy) ImGui::BeginDisabled();
        ImGui::SetNextItemWidth(std::max(4.0f * em, plot_width() - 6.0f * em));
        const int old_lo = s.lo, old_hi = s.hi;
        ImGui::SliderInt("band from", &s.lo, 0, last);
        const bool lo_done = ImGui::IsItemDeactivatedAfterEdit();
        ImGui::SetNextItemWidth(std::max(4.0f * em, plot_width() - 6.0f * em));
        ImGui::SliderInt("band to", &s.hi, 0, last);
        const bool hi_done = ImGui::IsItemDeactivatedAfterEdit();
        s.lo = std::clamp(s.lo, 0, last);
        s.hi = std::clamp(s.hi, 0, last);
        if (s.lo > s.hi) {  // the dragged slider pushes the other one
            if (s.lo != old_lo)
                s.hi = s.lo;
            else
                s.lo = s.hi;
        }
        act.preview = s.lo != old_lo || s.hi != old_hi;
        act.commit = lo_done || hi_done;
        ImGui::SetNextItemWidth(std::max(4.0f * em, plot_width() - 6.0f * em));
        const int old_vis = s.visualize;
        ImGui::SliderInt("visualize", &s.visualize, 0, last);
        s.visualize = std::clamp(s.visualize, 0, last);
        act.visualize_changed = s.visualize != old_vis;
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("the frequency that Rendering > Colour by vertex > Frequency shows");
        if (busy) ImGui::EndDisabled();
        char overlay[96];
        std::snprintf(overlay, sizeof overlay, "lambda_%d = %.4g", s.visualize,
                      double(doc.eigenvalues[std::size_t(s.visualize)]));
        band_plot("spectrum", doc.eigenvalues, s.lo, s.hi, overlay);
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("eigenvalue lambda_k against k (ascending), band shaded");
        band_plot("coefficients", doc.log_coefficients, s.lo, s.hi, "log10 |alpha_k|");
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip(
                "log10 of |alpha_k|, the length of the positions' coefficient "
                "(x, y, z) on frequency k");
    }
    return act;
}

}  // namespace trilab::viewer
