// Plots and legends; see plots.h.
#include "app/viewer/plots.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numeric>
#include <utility>

#include "app/viewer/panels.h"

namespace trilab::viewer {

// ---- layout ---------------------------------------------------------------------------------

Span index_slot(float x0, float x1, std::size_t n, std::size_t i) {
    return band_span(x0, x1, n, i, i);
}

Span band_span(float x0, float x1, std::size_t n, std::size_t lo, std::size_t hi) {
    const double w = double(x1 - x0) / double(std::max<std::size_t>(n, 1));
    return {float(double(x0) + double(lo) * w), float(double(x0) + double(hi + 1) * w)};
}

namespace {

/// Multiples of `step` in [lo, hi] (with a little slack for rounding).
std::pair<double, double> multiples(double lo, double hi, double step) {
    return {std::ceil(lo / step - 1e-9), std::floor(hi / step + 1e-9)};
}

}  // namespace

double nice_step(double lo, double hi, int max_ticks, double min_step) {
    if (!std::isfinite(lo) || !std::isfinite(hi) || max_ticks < 1) return 0;
    if (lo > hi) std::swap(lo, hi);
    const double range = hi - lo;
    if (!(range > 0)) return 0;
    // The smallest nice step (1, 2, 5 x 10^e, at least min_step) that gives at most
    // max_ticks ticks: the most ticks that fit.
    const int e0 = int(std::floor(std::log10(range))) - 3;
    for (int e = e0; e <= e0 + 8; ++e) {
        for (const double m : {1.0, 2.0, 5.0}) {
            const double step = m * std::pow(10.0, e);
            if (step < min_step) continue;
            const auto [first, last] = multiples(lo, hi, step);
            if (last - first + 1 <= max_ticks) return step;
        }
    }
    return std::max(range, min_step);
}

std::vector<double> nice_ticks(double lo, double hi, int max_ticks, double min_step) {
    if (!std::isfinite(lo) || !std::isfinite(hi) || max_ticks < 1) return {};
    if (lo > hi) std::swap(lo, hi);
    if (!(hi > lo)) return {lo};
    const double step = nice_step(lo, hi, max_ticks, min_step);
    std::vector<double> ticks;
    const auto [first, last] = multiples(lo, hi, step);
    for (double k = first; k <= last && int(ticks.size()) < max_ticks; ++k) {
        double v = k * step;
        if (std::abs(v) < 1e-12 * step) v = 0;  // no -0 or 1e-17 for zero
        ticks.push_back(v);
    }
    return ticks;
}

std::vector<std::optional<float>> place_labels(const std::vector<LabelSpec>& labels, float lo,
                                               float hi, float gap) {
    std::vector<std::optional<float>> out(labels.size());
    std::vector<std::size_t> order(labels.size());
    std::iota(order.begin(), order.end(), std::size_t(0));
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return labels[a].priority > labels[b].priority;
    });
    std::vector<Span> placed;
    for (const std::size_t i : order) {
        const LabelSpec& l = labels[i];
        float x = l.anchor - l.align * l.width;
        x = std::min(x, hi - l.width);  // inside [lo, hi] where it fits at all
        x = std::max(x, lo);
        const Span s{x, x + l.width};
        const bool clear = std::all_of(placed.begin(), placed.end(), [&](const Span& p) {
            return s.x1 + gap <= p.x0 || p.x1 + gap <= s.x0;
        });
        if (!clear) continue;
        placed.push_back(s);
        out[i] = x;
    }
    return out;
}

std::string tick_text(double value) {
    if (value == 0) value = 0;  // -0 -> 0
    char buf[32];
    std::snprintf(buf, sizeof(buf), "%g", value);
    return buf;
}

// ---- drawing helpers ------------------------------------------------------------------------

namespace {

ImU32 to_u32(const Color& c) {
    return ImGui::ColorConvertFloat4ToU32(ImVec4(c.x(), c.y(), c.z(), 1.0f));
}

void note(const std::string& id, const ImVec2& a, const ImVec2& b) {
    note_widget_rect(id, a.x, a.y, b.x, b.y);
}

/// Draws `text` with its top-left corner at `pos` and reports it as "PREFIX TEXT".
void label_at(ImDrawList* draw, const ImVec2& pos, const std::string& text,
              const std::string& prefix, ImU32 color = ImGui::GetColorU32(ImGuiCol_Text)) {
    draw->AddText(pos, color, text.c_str());
    const ImVec2 size = ImGui::CalcTextSize(text.c_str());
    note(prefix + text, pos, ImVec2(pos.x + size.x, pos.y + size.y));
}

constexpr ImU32 kBandFill = IM_COL32(255, 160, 40, 60);
constexpr ImU32 kMarker = IM_COL32(230, 50, 50, 255);
constexpr ImU32 kLine = IM_COL32(120, 190, 255, 255);

}  // namespace

// ---- legend ---------------------------------------------------------------------------------

std::vector<std::size_t> value_histogram(const std::vector<double>& values, const ValueRange& range,
                                         std::size_t bins) {
    std::vector<std::size_t> counts(bins, 0);
    if (bins == 0 || !(range.max > range.min)) return counts;
    const double scale = double(bins) / (range.max - range.min);
    for (double v : values) {
        if (!std::isfinite(v)) continue;
        const double t = std::floor((v - range.min) * scale);
        const std::size_t k =
            t <= 0 ? 0 : (t >= double(bins - 1) ? bins - 1 : std::size_t(t));  // ends clamped
        ++counts[k];
    }
    return counts;
}

namespace {

/// The values' histogram over the bar's width (`p0`, `size`), cached per set of values.
void legend_histogram(const VertexColors& colors, const ImVec2& p0, const ImVec2& size) {
    // The key: where the values are, their count, the range, the label and a few values (a
    // new set of colours may reuse the old one's memory).
    const auto key_of = [](const VertexColors& c) {
        std::vector<double> key = {double(reinterpret_cast<std::uintptr_t>(c.values.data())),
                                   double(c.values.size()), c.range.min, c.range.max};
        const std::size_t n = c.values.size();
        for (std::size_t i : {std::size_t(0), n / 3, n / 2, 2 * n / 3, n - 1})
            if (i < n) key.push_back(std::isnan(c.values[i]) ? 1e308 : c.values[i]);
        return std::make_pair(key, c.label);
    };
    static std::pair<std::vector<double>, std::string> cached_key;
    static std::vector<std::size_t> counts;
    auto key = key_of(colors);
    if (key != cached_key) {
        cached_key = std::move(key);
        counts = value_histogram(colors.values, colors.range, 48);
    }
    std::size_t most = 1;
    for (std::size_t c : counts) most = std::max(most, c);
    ImDrawList* draw = ImGui::GetWindowDrawList();
    const float w = size.x / float(counts.size());
    for (std::size_t k = 0; k < counts.size(); ++k) {
        if (counts[k] == 0) continue;
        const float h = size.y * float(double(counts[k]) / double(most));
        draw->AddRectFilled(ImVec2(p0.x + float(k) * w, p0.y + size.y - h),
                            ImVec2(p0.x + float(k + 1) * w - 1.0f, p0.y + size.y),
                            IM_COL32(180, 185, 200, 220));
    }
    ImGui::Dummy(size);
    note("legend: histogram", p0, ImVec2(p0.x + size.x, p0.y + size.y));
}

}  // namespace

bool legend_contents(const VertexColors& colors, ColoringOptions& options, float max_width) {
    const float em = ImGui::GetFontSize();
    ImDrawList* draw = ImGui::GetWindowDrawList();
    ImGui::TextUnformatted(colors.label.c_str());

    if (colors.kind == ColorMapKind::Categorical) {
        // One swatch per value: a discrete quantity has no range to choose.
        std::size_t total = 0;
        for (const ColorCategory& c : colors.categories) total += c.count;
        for (const ColorCategory& c : colors.categories) {
            const ImVec2 p = ImGui::GetCursorScreenPos();
            const float side = ImGui::GetTextLineHeight();
            draw->AddRectFilled(p, ImVec2(p.x + side, p.y + side), to_u32(c.color));
            draw->AddRect(p, ImVec2(p.x + side, p.y + side), IM_COL32(0, 0, 0, 160));
            ImGui::Dummy(ImVec2(side, side));
            note("legend: swatch " + c.label, p, ImVec2(p.x + side, p.y + side));
            ImGui::SameLine();
            ImGui::Text("%-20s %9zu vertices (%.0f %%)", c.label.c_str(), c.count,
                        total ? 100.0 * double(c.count) / double(total) : 0.0);
        }
        return false;
    }

    // The bar: the map sampled in 48 steps, from range.min (left) to range.max (right), under
    // the histogram of the values (how many vertices each colour has; the ends hold the
    // values beyond the range).
    const ValueRange& r = colors.range;
    const ImVec2 size(std::max(4.0f * em, std::min(14.0f * em, max_width)), 1.2f * em);
    if (!colors.values.empty())
        legend_histogram(colors, ImGui::GetCursorScreenPos(), ImVec2(size.x, 2.0f * em));
    const ImVec2 p0 = ImGui::GetCursorScreenPos();
    const int steps = 48;
    for (int i = 0; i < steps; ++i) {
        const double t0 = double(i) / steps, t1 = double(i + 1) / steps;
        const Color c0 = map_color(r.min + t0 * (r.max - r.min), r, colors.kind);
        const Color c1 = map_color(r.min + t1 * (r.max - r.min), r, colors.kind);
        draw->AddRectFilledMultiColor(ImVec2(p0.x + float(t0) * size.x, p0.y),
                                      ImVec2(p0.x + float(t1) * size.x, p0.y + size.y), to_u32(c0),
                                      to_u32(c1), to_u32(c1), to_u32(c0));
    }
    ImGui::Dummy(size);
    note("legend: bar", p0, ImVec2(p0.x + size.x, p0.y + size.y));

    // Tick labels under the bar: both ends always, the centre (0 on a diverging map) only
    // where it does not touch them.
    const double values[3] = {r.min, 0.5 * (r.min + r.max), r.max};
    std::string shown[3];
    for (int i = 0; i < 3; ++i) {
        char buf[32];
        std::snprintf(buf, sizeof(buf), "%.4g", values[i] == 0 ? 0.0 : values[i]);
        shown[i] = buf;
    }
    const float xs[3] = {p0.x, p0.x + 0.5f * size.x, p0.x + size.x};
    const float aligns[3] = {0.0f, 0.5f, 1.0f};
    const int priorities[3] = {2, 1, 2};
    std::vector<LabelSpec> specs;
    for (int i = 0; i < 3; ++i)
        specs.push_back({xs[i], ImGui::CalcTextSize(shown[i].c_str()).x, aligns[i], priorities[i]});
    const std::vector<std::optional<float>> at =
        place_labels(specs, p0.x, p0.x + size.x, 0.6f * em);
    const ImVec2 row = ImGui::GetCursorScreenPos();
    const float tick = 0.25f * em;
    for (int i = 0; i < 3; ++i) {
        if (!at[i]) continue;
        draw->AddLine(ImVec2(xs[i], p0.y + size.y), ImVec2(xs[i], p0.y + size.y + tick),
                      ImGui::GetColorU32(ImGuiCol_Text));
        label_at(draw, ImVec2(*at[i], row.y + tick), shown[i], "legend: label ");
    }
    ImGui::Dummy(ImVec2(size.x, ImGui::GetTextLineHeight() + tick));

    // Outliers beyond these percentiles are clamped to the ends of the bar.
    bool changed = false;
    float low = float(options.low_percentile), high = float(options.high_percentile);
    ImGui::SetNextItemWidth(size.x);
    if (ImGui::DragFloatRange2("##percentiles", &low, &high, 0.2f, 0.0f, 100.0f, "from %.1f %%",
                               "to %.1f %%", ImGuiSliderFlags_AlwaysClamp)) {
        if (high - low >= 0.5f) {
            options.low_percentile = low;
            options.high_percentile = high;
            changed = true;
        }
    }
    note("legend: percentiles", ImGui::GetItemRectMin(), ImGui::GetItemRectMax());
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip(
            "the range of the bar: values outside these percentiles take the "
            "colour of its ends");
    return changed;
}

// ---- index plots ----------------------------------------------------------------------------

namespace {

struct YAxis {
    double lo = 0, hi = 1;
    std::vector<double> ticks;
    bool any = false;  ///< some value is finite
};

YAxis y_axis(const IndexPlot& plot) {
    YAxis a;
    double lo = INFINITY, hi = -INFINITY;
    if (plot.values)
        for (const float v : *plot.values)
            if (std::isfinite(v)) {
                lo = std::min(lo, double(v));
                hi = std::max(hi, double(v));
            }
    if (!(lo <= hi)) return a;
    a.any = true;
    if (!(hi - lo > 1e-9 * std::max(std::abs(hi), 1e-30))) {  // constant: a unit around it
        const double half = std::max(std::abs(hi) * 0.5, plot.min_y_step > 0 ? 1.0 : 0.5);
        lo -= half;
        hi += half;
    }
    const double step = nice_step(lo, hi, 4, plot.min_y_step);
    if (step > 0) {  // out to the nearest multiples, so the ends carry ticks
        lo = std::floor(lo / step + 1e-9) * step;
        hi = std::ceil(hi / step - 1e-9) * step;
    }
    a.lo = lo;
    a.hi = hi;
    a.ticks = nice_ticks(lo, hi, 5, step);
    return a;
}

}  // namespace

float index_plot_right_pad() {
    return 1.5f * ImGui::GetFontSize();
}

float index_plot_margin(const IndexPlot& plot) {
    float widest = ImGui::CalcTextSize("0").x;
    for (const double t : y_axis(plot).ticks)
        widest = std::max(widest, ImGui::CalcTextSize(tick_text(t).c_str()).x);
    return widest + 0.6f * ImGui::GetFontSize();
}

void index_plot(const IndexPlot& plot, float width, float height, float left_margin) {
    if (!plot.values || plot.values->empty()) return;
    const std::vector<float>& values = *plot.values;
    const std::size_t n = values.size();
    const float em = ImGui::GetFontSize(), line = ImGui::GetTextLineHeight();
    ImGui::TextUnformatted(plot.y_title.c_str());
    const ImVec2 p = ImGui::GetCursorScreenPos();
    ImGui::InvisibleButton(plot.id.c_str(), ImVec2(width, height));
    const bool hovered = ImGui::IsItemHovered();
    ImDrawList* draw = ImGui::GetWindowDrawList();
    const ImU32 text = ImGui::GetColorU32(ImGuiCol_Text);
    const ImU32 faint = ImGui::GetColorU32(ImGuiCol_TextDisabled);

    // The area: right of the y labels, above the x labels, half a line below the top so the
    // top tick label fits.
    const float ax0 = p.x + left_margin, ax1 = p.x + width - index_plot_right_pad();
    const float ay0 = p.y + 0.5f * line, ay1 = p.y + height - line - 0.3f * em;
    draw->AddRectFilled(ImVec2(ax0, ay0), ImVec2(ax1, ay1), IM_COL32(40, 40, 45, 255));
    note(plot.id + ": area", ImVec2(ax0, ay0), ImVec2(ax1, ay1));

    if (plot.lo <= plot.hi && plot.lo >= 0 && std::size_t(plot.hi) < n) {
        const Span b = band_span(ax0, ax1, n, std::size_t(plot.lo), std::size_t(plot.hi));
        draw->AddRectFilled(ImVec2(b.x0, ay0), ImVec2(b.x1, ay1), kBandFill);
        note(plot.id + ": band", ImVec2(b.x0, ay0), ImVec2(b.x1, ay1));
    }

    const YAxis y = y_axis(plot);
    const auto y_of = [&](double v) {
        return ay1 - float((v - y.lo) / (y.hi - y.lo)) * (ay1 - ay0);
    };
    // Axes and y ticks (labels right-aligned left of the area, never overlapping).
    draw->AddLine(ImVec2(ax0, ay0), ImVec2(ax0, ay1), faint);
    draw->AddLine(ImVec2(ax0, ay1), ImVec2(ax1, ay1), faint);
    std::vector<LabelSpec> y_specs;
    for (const double t : y.ticks) y_specs.push_back({y_of(t), line, 0.5f, 0});
    const auto y_at = place_labels(y_specs, p.y, ay1 + 0.5f * line, 0.1f * line);
    for (std::size_t i = 0; i < y.ticks.size(); ++i) {
        const float yy = y_of(y.ticks[i]);
        draw->AddLine(ImVec2(ax0 - 0.25f * em, yy), ImVec2(ax0, yy), faint);
        draw->AddLine(ImVec2(ax0, yy), ImVec2(ax1, yy), IM_COL32(255, 255, 255, 18));
        if (!y_at[i]) continue;
        const std::string t = tick_text(y.ticks[i]);
        const float w = ImGui::CalcTextSize(t.c_str()).x;
        label_at(draw, ImVec2(ax0 - 0.4f * em - w, *y_at[i]), t, plot.id + ": y tick ", text);
    }

    // x ticks at slot centres; the axis name "k" at the right end of the row.
    const int max_x = std::max(2, int((ax1 - ax0) / (2.5f * em)));
    const std::vector<double> x_ticks = nice_ticks(0, double(n - 1), max_x, 1);
    std::vector<LabelSpec> x_specs;
    std::vector<std::string> x_texts;
    for (const double t : x_ticks) {
        x_texts.push_back(tick_text(t));
        const float x = index_slot(ax0, ax1, n, std::size_t(t)).centre();
        x_specs.push_back({x, ImGui::CalcTextSize(x_texts.back().c_str()).x, 0.5f,
                           t == x_ticks.front() || t == x_ticks.back() ? 1 : 0});
        draw->AddLine(ImVec2(x, ay1), ImVec2(x, ay1 + 0.25f * em), faint);
    }
    x_texts.push_back("k");
    x_specs.push_back({p.x + width, ImGui::CalcTextSize("k").x, 1.0f, 2});
    const auto x_at = place_labels(x_specs, p.x, p.x + width, 0.5f * em);
    for (std::size_t i = 0; i < x_specs.size(); ++i)
        if (x_at[i])
            label_at(draw, ImVec2(*x_at[i], ay1 + 0.3f * em), x_texts[i],
                     plot.id + (i + 1 == x_specs.size() ? ": x title " : ": x tick "),
                     i + 1 == x_specs.size() ? faint : text);

    // The values, broken where one is not finite.
    if (y.any) {
        std::vector<ImVec2> run;
        const auto flush = [&] {
            if (run.size() >= 2) draw->AddPolyline(run.data(), int(run.size()), kLine, 0, 1.5f);
            if (run.size() == 1) draw->AddCircleFilled(run[0], 1.5f, kLine);
            run.clear();
        };
        for (std::size_t i = 0; i < n; ++i) {
            if (!std::isfinite(values[i])) {
                flush();
                continue;
            }
            run.emplace_back(index_slot(ax0, ax1, n, i).centre(), y_of(values[i]));
        }
        flush();
    }

    if (plot.marker >= 0 && std::size_t(plot.marker) < n) {
        const float x = index_slot(ax0, ax1, n, std::size_t(plot.marker)).centre();
        draw->AddLine(ImVec2(x, ay0), ImVec2(x, ay1), kMarker, 2.0f);
        const float v = values[std::size_t(plot.marker)];
        if (std::isfinite(v) && y.any) draw->AddCircleFilled(ImVec2(x, y_of(v)), 3.0f, kMarker);
        note(plot.id + ": marker", ImVec2(x - 1.0f, ay0), ImVec2(x + 1.0f, ay1));
    }

    if (hovered) {
        const float mx = ImGui::GetIO().MousePos.x;
        if (mx >= ax0 && mx < ax1) {
            const std::size_t i =
                std::min(n - 1, std::size_t(double(mx - ax0) / double(ax1 - ax0) * double(n)));
            ImGui::SetTooltip(
                "k = %zu: %s = %.6g\nshaded: the band %d..%d; red: the visualized "
                "frequency",
                i, plot.y_title.c_str(), double(values[i]), plot.lo, plot.hi);
        }
    }
}

}  // namespace trilab::viewer
