// The Frequency panel; see frequency_panel.h.
#include "app/viewer/frequency_panel.h"

#include "app/viewer/panels.h"
#include "app/viewer/plots.h"
#include "app/viewer/widgets.h"

#include <imgui.h>

#include <algorithm>
#include <cstdio>
#include <string>

#include "core/algorithms/transfer_function.h"

namespace trilab::viewer {
namespace {

constexpr float kPlotWidthEm = 26.0f;  ///< the most width the bar and the plots take
constexpr float kPlotHeightEm = 7.0f;  ///< height of each plot, tick labels included

/// The width of the bar and the plots: kPlotWidthEm, less in a narrow sidebar.
float plot_width() {
    return std::min(kPlotWidthEm * ImGui::GetFontSize(), ImGui::GetContentRegionAvail().x);
}

/// The frequency bar: every computed frequency as a grey slot, the applied band in green, the
/// slider band outlined in orange and the visualized frequency in red. Its slots are the
/// plots' slots (the same x range: `left_margin` in, index_plot_right_pad() from the right).
void frequency_bar(const FrequencyDocument& doc, int lo, int hi, int marker, float width,
                   float left_margin) {
    const std::size_t k = doc.eigenvalues.size();
    const float h = ImGui::GetFrameHeight() * 0.7f;
    const ImVec2 p = ImGui::GetCursorScreenPos();
    const float x0 = p.x + left_margin, x1 = p.x + width - index_plot_right_pad();
    ImDrawList* dl = ImGui::GetWindowDrawList();
    dl->AddRectFilled(ImVec2(x0, p.y), ImVec2(x1, p.y + h), IM_COL32(70, 70, 70, 255));
    note_widget_rect("frequency bar", x0, p.y, x1, p.y + h);
    if (k > 0) {
        if (doc.applied && doc.applied_lo <= doc.applied_hi && doc.applied_hi < k) {
            const Span a = band_span(x0, x1, k, doc.applied_lo, doc.applied_hi);
            dl->AddRectFilled(ImVec2(a.x0, p.y), ImVec2(a.x1, p.y + h), IM_COL32(60, 170, 90, 255));
            note_widget_rect("frequency bar: applied", a.x0, p.y, a.x1, p.y + h);
        }
        if (lo >= 0 && lo <= hi && std::size_t(hi) < k) {
            const Span b = band_span(x0, x1, k, std::size_t(lo), std::size_t(hi));
            dl->AddRect(ImVec2(b.x0, p.y), ImVec2(b.x1, p.y + h), IM_COL32(255, 160, 40, 255), 0.0f,
                        0, 2.0f);
            note_widget_rect("frequency bar: band", b.x0, p.y, b.x1, p.y + h);
        }
        if (marker >= 0 && std::size_t(marker) < k) {
            const Span m = index_slot(x0, x1, k, std::size_t(marker));
            const float half = std::max(1.0f, 0.5f * m.width());
            const float c = m.centre();
            dl->AddRectFilled(ImVec2(c - half, p.y - 2.0f), ImVec2(c + half, p.y + h + 2.0f),
                              IM_COL32(230, 50, 50, 255));
            note_widget_rect("frequency bar: marker", c - half, p.y, c + half, p.y + h);
        }
    }
    ImGui::Dummy(ImVec2(width, h));
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip(
            "grey: the %zu computed frequencies; green: the band of the current "
            "state; orange: the sliders' band; red: the visualized frequency",
            k);
}

/// The eigenvalues the band-split check reads: the decomposition's own (double) when they are
/// the plotted ones, else the plotted floats.
Eigen::VectorXd band_eigenvalues(const FrequencyDocument& doc) {
    if (doc.decomposition &&
        std::size_t(doc.decomposition->eigenvalues.size()) == doc.eigenvalues.size())
        return doc.decomposition->eigenvalues;
    Eigen::VectorXd values(Eigen::Index(doc.eigenvalues.size()));
    for (std::size_t i = 0; i < doc.eigenvalues.size(); ++i)
        values[Eigen::Index(i)] = double(doc.eigenvalues[i]);
    return values;
}

/// A band whose edge splits a set of equal eigenvalues (core/algorithms/transfer_function.h
/// band_splits_multiplet, the check trilab-cli spectrum prints): the warning, and a button for
/// each nearest band that splits none (it sets the sliders and pushes that band).
void band_split_warning(FrequencyPanelState& s, const FrequencyDocument& doc, bool busy,
                        CommandQueue& commands) {
    const std::size_t lo = std::size_t(s.lo), hi = std::size_t(s.hi);
    const MultipletSplit split = band_splits_multiplet(band_eigenvalues(doc), lo, hi);
    if (!split.splits) return;
    const std::string text = multiplet_split_text(split, lo, hi);
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.65f, 0.2f, 1.0f));
    ImGui::PushTextWrapPos(0.0f);
    ImGui::TextUnformatted(text.c_str());
    ImGui::PopTextWrapPos();
    ImGui::PopStyleColor();
    note_widget("band-split", WidgetNote::Kind::Other, text.c_str());
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip(
            "equal eigenvalues (a symmetric shape's sets, e.g. a sphere's three-fold lambda_1) "
            "belong together: a band that keeps only part of a set keeps an arbitrary mix of "
            "it (the sphere's band 0:2 flattens it into a disc)");
    if (busy) ImGui::BeginDisabled();
    bool first = true;
    for (const std::optional<MultipletSplit::Band>& band : {split.narrower, split.wider}) {
        if (!band) continue;
        if (!first) ImGui::SameLine();
        first = false;
        const std::string label =
            "use " + std::to_string(band->first) + ":" + std::to_string(band->second);
        if (button(label.c_str())) {
            s.lo = int(band->first);
            s.hi = int(band->second);
            commands.push_back(PreviewBand{band->first, band->second});
            commands.push_back(CommitBand{band->first, band->second});
        }
    }
    if (busy) ImGui::EndDisabled();
}

}  // namespace

void frequency_window(FrequencyPanelState& s, const FrequencyDocument& doc, bool busy,
                      CommandQueue& commands) {
    SidebarSection section("Frequency decomposition", s.open);
    if (!section) return;
    const float em = ImGui::GetFontSize();
    // The decomposition's parameters, drawn from the operation's declaration (the band is
    // the sliders below; threads and the size limit keep their defaults here).
    operation_widgets(s.op);
    if (busy) ImGui::BeginDisabled();
    if (button("Decompose")) commands.push_back(Decompose{s.op});
    ImGui::SameLine();
    const bool have = doc.decomposition && doc.valid && !doc.eigenvalues.empty();
    if (!have) ImGui::BeginDisabled();
    if (button("Restore")) commands.push_back(RestoreDecomposed{});
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
        // The bar and both plots share their x range, so a frequency is at the same x in all.
        const float width = plot_width();
        const IndexPlot spectrum_axis{"", "", &doc.eigenvalues, 0, -1, -1, 0.0};
        const IndexPlot coefficient_axis{"", "", &doc.log_coefficients, 0, -1, -1, 1.0};
        const float margin =
            std::max(index_plot_margin(spectrum_axis), index_plot_margin(coefficient_axis));
        frequency_bar(doc, s.lo, s.hi, s.visualize, width, margin);
        // What the mesh shows, so that the sliders never seem to describe it when they do not:
        // right after Decompose it is its own shape (every frequency, computed or not), and a
        // band shows once a slider moves.
        // A band that reaches the end of the computed spectrum takes in the rest (the
        // frequencies not computed): the full band is the mesh itself.
        const bool rest =
            doc.decomposition && std::size_t(s.hi) < doc.decomposition->size() &&
            band_reaches_rest(*doc.decomposition, std::size_t(s.lo), std::size_t(s.hi));
        char shown[200];
        if (doc.applied)
            std::snprintf(shown, sizeof shown, "the mesh shows the band %zu .. %zu%s",
                          doc.applied_lo, doc.applied_hi, rest ? " and the rest" : "");
        else
            std::snprintf(shown, sizeof shown, "the mesh shows its own shape: the band %d .. %d%s",
                          s.lo, s.hi, rest ? " and the rest (every frequency not computed)" : "");
        ImGui::PushTextWrapPos(0.0f);
        ImGui::TextDisabled("%s", shown);
        ImGui::PopTextWrapPos();
        note_widget("band-state", WidgetNote::Kind::Other, shown);
        if (busy) ImGui::BeginDisabled();
        ImGui::SetNextItemWidth(std::max(4.0f * em, width - 6.0f * em));
        const int old_lo = s.lo, old_hi = s.hi;
        ImGui::SliderInt("band from", &s.lo, 0, last);
        const bool lo_done = ImGui::IsItemDeactivatedAfterEdit();
        ImGui::SetNextItemWidth(std::max(4.0f * em, width - 6.0f * em));
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
        if (s.lo != old_lo || s.hi != old_hi)
            commands.push_back(PreviewBand{std::size_t(s.lo), std::size_t(s.hi)});
        if (lo_done || hi_done)
            commands.push_back(CommitBand{std::size_t(s.lo), std::size_t(s.hi)});
        if (busy) ImGui::EndDisabled();
        band_split_warning(s, doc, busy, commands);
        if (busy) ImGui::BeginDisabled();
        ImGui::SetNextItemWidth(std::max(4.0f * em, width - 6.0f * em));
        const int old_vis = s.visualize;
        ImGui::SliderInt("visualize", &s.visualize, 0, last);
        s.visualize = std::clamp(s.visualize, 0, last);
        if (s.visualize != old_vis) commands.push_back(UpdateColoring{});
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("the frequency that Rendering > Colour by vertex > Frequency shows");
        if (busy) ImGui::EndDisabled();
        ImGui::Text("visualized: k = %d, lambda_%d = %.4g", s.visualize, s.visualize,
                    double(doc.eigenvalues[std::size_t(s.visualize)]));
        const IndexPlot spectrum{
            "spectrum", "eigenvalue lambda_k", &doc.eigenvalues, s.lo, s.hi, s.visualize, 0.0};
        const IndexPlot coefficients{"coefficients",
                                     "log10 |alpha_k| (coefficient length)",
                                     &doc.log_coefficients,
                                     s.lo,
                                     s.hi,
                                     s.visualize,
                                     1.0};
        index_plot(spectrum, width, kPlotHeightEm * em, margin);
        index_plot(coefficients, width, kPlotHeightEm * em, margin);
    }
}

}  // namespace trilab::viewer
