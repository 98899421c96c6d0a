#pragma once
// A colouring's legend as trilab-cli prints it (render, record): one JSON object under
// "legend" (null without a legend) and one text fragment, so both commands agree with each
// other and with the viewer's legend (the same VertexColors).
//   {"label": ..., "min": ..., "max": ..., "map": "sequential" | "diverging" | "categorical"}
// plus, for a categorical map, "categories": [{"value", "label", "count", "color": [r, g, b]}],
// and with bands or isolines (render --bands N / --isolines N, LegendSteps) "display"
// ("bands", "isolines", "bands-isolines"), "steps" (N), "step" ((max - min) / N) and, with
// isolines, "isolines": the N - 1 values the lines are drawn at.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "app/cli/json_writer.h"
#include "core/algorithms/coloring.h"

namespace trilab::cli {

/// Bands and isolines of a legend: the range cut into `steps` equal steps; `display` is
/// "bands", "isolines" or "bands-isolines" (nullptr: a smooth map, no steps).
struct LegendSteps {
    const char* display = nullptr;
    int steps = 0;
    bool bands() const { return display && std::string(display).find("bands") == 0; }
    bool isolines() const {
        return display && std::string(display).find("isolines") != std::string::npos;
    }
};

/// The values of the N - 1 isolines: min + k (max - min) / N, k = 1..N-1.
inline std::vector<double> isoline_values(const ValueRange& range, int steps) {
    std::vector<double> v;
    for (int k = 1; k < steps; ++k) v.push_back(range.min + (range.max - range.min) * k / steps);
    return v;
}

/// A colour channel to 4 decimals (the float's own digits are noise).
inline double rounded(float channel) {
    return std::round(double(channel) * 1e4) / 1e4;
}

/// Adds "legend" to `j`: the object above, or null when `colors` has no legend.
inline void add_legend(JsonObject& j, const VertexColors& colors, const LegendSteps& steps = {}) {
    if (!colors.has_legend) {
        j.add_null("legend");
        return;
    }
    JsonObject legend;
    legend.add("label", colors.label)
        .add("min", colors.range.min)
        .add("max", colors.range.max)
        .add("map", color_map_name(colors.kind));
    if (colors.kind == ColorMapKind::Categorical) {
        std::string list = "[";
        for (const ColorCategory& c : colors.categories) {
            JsonObject o;
            o.add("value", c.value)
                .add("label", c.label)
                .add("count", c.count)
                .add("color", std::vector<double>{rounded(c.color.x()), rounded(c.color.y()),
                                                  rounded(c.color.z())});
            list += (list.size() > 1 ? ", " : "") + o.str();
        }
        legend.raw("categories", list + "]");
    }
    if (steps.display && colors.kind != ColorMapKind::Categorical) {
        legend.add("display", steps.display)
            .add("steps", steps.steps)
            .add("step", (colors.range.max - colors.range.min) / steps.steps);
        if (steps.isolines()) legend.add("isolines", isoline_values(colors.range, steps.steps));
    }
    j.add("legend", legend);
}

/// "mean curvature H in [-1.2, 1.2]" (with steps: ", 10 bands of 0.24", ", 9 isolines
/// 0.24 apart", ", 10 bands of 0.24 with isolines"); categorical: "subdivision level of each
/// vertex: level 0 (original) 12, level 1 30".
inline std::string legend_text(const VertexColors& colors, const LegendSteps& steps = {}) {
    char buf[96];
    if (colors.kind != ColorMapKind::Categorical) {
        std::snprintf(buf, sizeof(buf), " in [%.6g, %.6g]", colors.range.min, colors.range.max);
        std::string s = colors.label + buf;
        if (!steps.display) return s;
        const double step = (colors.range.max - colors.range.min) / steps.steps;
        if (steps.bands())
            std::snprintf(buf, sizeof(buf), ", %d bands of %.6g%s", steps.steps, step,
                          steps.isolines() ? " with isolines" : "");
        else
            std::snprintf(buf, sizeof(buf), ", %d isolines %.6g apart", steps.steps - 1, step);
        return s + buf;
    }
    std::string s = colors.label + ":";
    for (std::size_t i = 0; i < colors.categories.size(); ++i)
        s += (i ? ", " : " ") + colors.categories[i].label + " " +
             std::to_string(colors.categories[i].count);
    return s;
}

}  // namespace trilab::cli
