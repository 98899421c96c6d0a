// The spectral lens's curve (app/viewer/transfer_plot.h).
#include "app/viewer/transfer_plot.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "app/viewer/panel_helpers.h"
#include "app/viewer/widgets.h"
#include "core/algorithms/transfer_function.h"

namespace trilab::viewer {
namespace {
using ui::wrapped_disabled;

constexpr double kGainTop = 1.5, kGainBottom = -1.5;  ///< the y range drawn
constexpr int kSamples = 240;                         ///< of the analytic curve

void note(const std::string& id, const ImVec2& a, const ImVec2& b) {
    note_widget_rect(id, a.x, a.y, b.x, b.y);
}

/// Short labels inside the plot (its size never changes, so nothing below moves while a
/// parameter is dragged) and the whole sentence in its tooltip.
void describe_curve(ImDrawList* draw, const ImVec2& a0, const ImVec2& a1, double unstable,
                    float unstable_x, double lambda_lo, double lambda_hi, bool have_spectrum) {
    const float em = ImGui::GetFontSize();
    const double x_hi = lambda_hi;
    char buf[192];
    const ImU32 text_color = IM_COL32(200, 200, 210, 255);
    // The x axis's label under the plot, clear of its ticks and shading (issue 38, item 12).
    std::snprintf(buf, sizeof buf, "lambda %.3g .. %.3g (log)", lambda_lo, x_hi);
    draw->AddText(ImVec2(a1.x - ImGui::CalcTextSize(buf).x - 3, a1.y + 1), text_color, buf);
    std::string sentence;
    if (std::isfinite(unstable) && unstable <= x_hi) {
        std::snprintf(buf, sizeof buf, "unstable above %.3g", unstable);
        const float w = ImGui::CalcTextSize(buf).x;
        // Right of the gain axis's "1" label, never over it.
        const float left = a0.x + ImGui::CalcTextSize("1").x + 0.5f * em;
        const float x = std::clamp(unstable_x - w - 4, left, std::max(left, a1.x - w - 2));
        draw->AddText(ImVec2(x, a0.y + 2), IM_COL32(255, 120, 120, 255), buf);
        std::snprintf(buf, sizeof buf,
                      "Frequencies above lambda = %.4g grow and oscillate (red): this step is "
                      "unstable on this mesh.",
                      unstable);
        sentence = buf;
    } else if (std::isfinite(unstable)) {
        std::snprintf(buf, sizeof buf,
                      "Stable on this mesh: this step goes unstable only above lambda = %.4g, "
                      "beyond its largest eigenvalue %.4g.",
                      unstable, lambda_hi);
        sentence = buf;
    } else {
        sentence = "Stable for every frequency (implicit integration).";
    }
    if (ImGui::IsMouseHoveringRect(a0, a1))
        ImGui::SetTooltip(
            "The gain of these settings at each frequency (eigenvalue lambda of "
            "the operator, log scale): 1 keeps it, 0 removes it; orange: the "
            "frequency flips sign each step, red: it grows. %s%s",
            sentence.c_str(),
            have_spectrum ? " Ticks: this mesh's computed frequencies; dots: "
                            "the measured gain of the last run or preview."
                          : "");
}

/// fairing_gain() for drawing: the same value where it stays within the plotted range, and
/// ±(a large number) where it would grow beyond it, without computing an overflowing power
/// (a step 50 times the stable one raised to many iterations).
double drawn_gain(const FairingOptions& o, double lambda) {
    const double g1 = gain_per_iteration(o, lambda);
    const double n = double(std::max(o.iterations, 1));
    if (std::abs(g1) <= 1.0 || n * std::log(std::abs(g1)) < 5.0) return fairing_gain(o, lambda);
    const bool negative = g1 < 0 && (o.iterations % 2 == 1);
    return negative ? -1e3 : 1e3;
}

/// Under the curve: the reference figure's step translation, and the diverging run (its red
/// mark while shown; otherwise its button, offered when the settings `diverge` on this mesh,
/// drawn disabled elsewhere so that nothing below moves while a step is dragged across the
/// limit).
bool figure_and_divergence(const TransferView& view, bool diverges) {
    bool pressed = false;
    if (!view.figure_note.empty()) {
        wrapped_disabled("%s", view.figure_note.c_str());
        note_widget("lens: figure", WidgetNote::Kind::Other, view.figure_note.c_str());
    }
    if (!view.diverging_note.empty()) {
        // The diverging run on the screen: marked in red, never mistaken for a result.
        ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.35f, 0.35f, 1.0f));
        ImGui::PushTextWrapPos(0.0f);
        ImGui::TextUnformatted(view.diverging_note.c_str());
        ImGui::PopTextWrapPos();
        ImGui::PopStyleColor();
        note_widget("lens: diverged", WidgetNote::Kind::Other, view.diverging_note.c_str());
    } else {
        if (!diverges) ImGui::BeginDisabled();
        pressed = button("Show the diverging run");
        if (!diverges) ImGui::EndDisabled();
        if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
            ImGui::SetTooltip(
                diverges ? "for teaching: show this explicit run without its checks, up to its "
                           "last iteration, marked as diverged; it is never a result and nothing "
                           "is applied (Esc returns)"
                         : "these settings are stable on this mesh: nothing diverges");
    }
    return pressed;
}

}  // namespace

TransferPlotRequest transfer_plot(const FairingOptions& o, const TransferView& view) {
    const bool have_spectrum = !view.eigenvalues.empty();
    // The whole spectrum of the operator: up to the stability estimate's largest eigenvalue
    // (a partial decomposition holds only the lowest frequencies; they are ticked).
    double lambda_hi = view.lambda_max;
    if (have_spectrum && !(lambda_hi >= view.eigenvalues.back()))
        lambda_hi = view.eigenvalues.back();
    if (!std::isfinite(lambda_hi) || lambda_hi <= 0) {
        ImGui::TextDisabled("transfer curve: waiting for the stability estimate");
        return TransferPlotRequest::None;
    }
    double lambda_lo = lambda_hi * 1e-4;
    if (have_spectrum)
        for (double l : view.eigenvalues)
            if (l > 0) {
                lambda_lo = std::min(lambda_lo, l);
                break;
            }
    const double unstable = unstable_eigenvalue(o);
    const double x_hi = lambda_hi;
    const double lx1 = std::log10(x_hi);
    const double lx0 = std::min(std::log10(lambda_lo), lx1 - 1.0);  // at least a decade

    const float em = ImGui::GetFontSize();
    const ImVec2 origin = ImGui::GetCursorScreenPos();
    const float width = std::max(12.0f * em, ImGui::GetContentRegionAvail().x), height = 7.0f * em;
    ImGui::Dummy(ImVec2(width, height + em + 2.0f));  // the plot, and its x label under it
    ImDrawList* draw = ImGui::GetWindowDrawList();
    const ImVec2 a0 = origin, a1(origin.x + width, origin.y + height);
    draw->AddRectFilled(a0, a1, IM_COL32(20, 22, 26, 255));
    note("lens: area", a0, a1);
    const auto x_of = [&](double lambda) {
        const double t = (std::log10(std::max(lambda, lambda_lo)) - lx0) / (lx1 - lx0);
        return float(a0.x + t * (a1.x - a0.x));
    };
    const auto y_of = [&](double g) {
        const double t =
            (kGainTop - std::clamp(g, kGainBottom, kGainTop)) / (kGainTop - kGainBottom);
        return float(a0.y + t * (a1.y - a0.y));
    };
    // Shading of growth and oscillation, column by column of the analytic curve.
    std::vector<ImVec2> curve;
    bool grows = false, oscillates = false;
    for (int i = 0; i <= kSamples; ++i) {
        const double lambda = std::pow(10.0, lx0 + (lx1 - lx0) * i / kSamples);
        const double g = drawn_gain(o, lambda);
        const float x = x_of(lambda), x_next = x + (a1.x - a0.x) / kSamples;
        const double g1 = gain_per_iteration(o, lambda);
        if (std::abs(g1) > 1.0 + 1e-12) {  // grows (alternating where g < 0: the explosion)
            draw->AddRectFilled(ImVec2(x, a0.y), ImVec2(x_next, a1.y), IM_COL32(220, 40, 40, 70));
            grows = true;
        } else if (g1 < 0) {
            draw->AddRectFilled(ImVec2(x, a0.y), ImVec2(x_next, a1.y), IM_COL32(240, 150, 30, 50));
            oscillates = true;
        }
        curve.emplace_back(x, y_of(std::isfinite(g) ? g : kGainTop));
    }
    if (grows) note("lens: grows", a0, a1);
    if (oscillates) note("lens: oscillates", a0, a1);
    // Axes: gain 1, 0 and -1.
    for (double g : {1.0, 0.0, -1.0})
        draw->AddLine(ImVec2(a0.x, y_of(g)), ImVec2(a1.x, y_of(g)),
                      g == 0 ? IM_COL32(140, 140, 150, 160) : IM_COL32(90, 90, 100, 120));
    draw->AddText(ImVec2(a0.x + 2, y_of(1.0) - em), IM_COL32(160, 160, 170, 255), "1");
    draw->AddText(ImVec2(a0.x + 2, y_of(-1.0)), IM_COL32(160, 160, 170, 255), "-1");
    draw->AddPolyline(curve.data(), int(curve.size()), IM_COL32(90, 200, 255, 255), 0, 2.0f);
    // The decomposition's frequencies and the measured gain.
    if (have_spectrum)
        for (double l : view.eigenvalues)
            if (l > 0)
                draw->AddLine(ImVec2(x_of(l), a1.y - 4), ImVec2(x_of(l), a1.y),
                              IM_COL32(200, 200, 210, 140));
    bool measured_drawn = false;
    for (std::size_t k = 0; k < view.measured.size() && k < view.eigenvalues.size(); ++k) {
        const double g = view.measured[k];
        if (!std::isfinite(g) || view.eigenvalues[k] <= 0) continue;
        const ImVec2 c(x_of(view.eigenvalues[k]), y_of(g));
        draw->AddCircle(c, 2.5f, IM_COL32(255, 255, 255, 220));
        measured_drawn = true;
    }
    if (measured_drawn) note("lens: measured", a0, a1);
    // Marks: where the step goes unstable, Taubin's pass band.
    if (std::isfinite(unstable) && unstable <= x_hi) {
        const float x = x_of(unstable);
        draw->AddLine(ImVec2(x, a0.y), ImVec2(x, a1.y), IM_COL32(255, 60, 60, 255), 2.0f);
        note("lens: unstable", ImVec2(x - 2, a0.y), ImVec2(x + 2, a1.y));
    }
    if (o.op == FairingOperator::Taubin) {
        const double k_pb = taubin_pass_band_of(o);
        if (std::isfinite(k_pb) && k_pb > lambda_lo && k_pb < x_hi) {
            const float x = x_of(k_pb);
            draw->AddLine(ImVec2(x, a0.y), ImVec2(x, a1.y), IM_COL32(80, 220, 120, 255), 2.0f);
            note("lens: pass band", ImVec2(x - 2, a0.y), ImVec2(x + 2, a1.y));
        }
    }
    describe_curve(draw, a0, a1, unstable, std::isfinite(unstable) ? x_of(unstable) : 0.0f,
                   lambda_lo, lambda_hi, have_spectrum);
    if (!view.measured_note.empty()) wrapped_disabled("%s", view.measured_note.c_str());
    const bool diverging =
        figure_and_divergence(view, std::isfinite(unstable) && unstable < lambda_hi);
    bool decompose = false;
    if (!have_spectrum) {
        wrapped_disabled(view.decomposition_of_other_operator
                             ? "the decomposition is of another operator: the curve is drawn over "
                               "the analytic range"
                             : "no decomposition: the curve is drawn over the analytic range "
                               "[0, lambda_max] of the stability estimate");
        decompose = button("Decompose for this operator");
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip(
                "compute this operator's 100 lowest frequencies (a job), to draw "
                "the curve at them and measure runs against it");
    }
    if (diverging) return TransferPlotRequest::ShowDivergingRun;
    return decompose ? TransferPlotRequest::Decompose : TransferPlotRequest::None;
}

}  // namespace trilab::viewer
