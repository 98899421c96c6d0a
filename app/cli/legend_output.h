#pragma once
// A colouring's legend as trilab-cli prints it (render, record): one JSON object under
// "legend" (null without a legend) and one text fragment, so both commands agree with each
// other and with the viewer's legend (the same VertexColors).
//   {"label": ..., "min": ..., "max": ..., "map": "sequential" | "diverging" | "categorical"}
// plus, for a categorical map, "categories": [{"value", "label", "count", "color": [r, g, b]}].
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "app/cli/json_writer.h"
#include "core/algorithms/coloring.h"

namespace trilab::cli {

/// A colour channel to 4 decimals (the float's own digits are noise).
inline double rounded(float channel) {
    return std::round(double(channel) * 1e4) / 1e4;
}

/// Adds "legend" to `j`: the object above, or null when `colors` has no legend.
inline void add_legend(JsonObject& j, const VertexColors& colors) {
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
    j.add("legend", legend);
}

/// "mean curvature H in [-1.2, 1.2]"; categorical: "subdivision level of each vertex: level
/// 0 (original) 12, level 1 30".
inline std::string legend_text(const VertexColors& colors) {
    char buf[64];
    if (colors.kind != ColorMapKind::Categorical) {
        std::snprintf(buf, sizeof(buf), " in [%.6g, %.6g]", colors.range.min, colors.range.max);
        return colors.label + buf;
    }
    std::string s = colors.label + ":";
    for (std::size_t i = 0; i < colors.categories.size(); ++i)
        s += (i ? ", " : " ") + colors.categories[i].label + " " +
             std::to_string(colors.categories[i].count);
    return s;
}

}  // namespace trilab::cli
