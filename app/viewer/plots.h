#pragma once
// Small plots and legends for the panels: the colour legend's contents, and line plots over
// an index (the Frequency panel's spectrum and coefficients) with axes, tick labels, a shaded
// band and a marker. The layout arithmetic is plain functions (no ImGui), so tests check the
// geometry directly; the drawing reports its rectangles to the panels' test hook
// (note_widget_rect(), panels.h).
//
// Index axes: n values share the plot's width in n equal slots; value i sits at the centre
// of slot i, and the band [lo, hi] covers slots lo to hi, so its shading is exactly
// (hi - lo + 1) / n of the plot area, and a frequency bar of the same width lines up with it.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "core/algorithms/coloring.h"

namespace trilab::viewer {

/// An interval [x0, x1] along one axis (screen pixels).
struct Span {
    float x0 = 0, x1 = 0;
    float centre() const { return 0.5f * (x0 + x1); }
    float width() const { return x1 - x0; }
};

/// Slot `i` of `n` equal slots over [x0, x1] (n = 0 counts as 1).
Span index_slot(float x0, float x1, std::size_t n, std::size_t i);
/// Slots lo to hi together: [x0 + lo w, x0 + (hi + 1) w] with w = (x1 - x0) / n.
Span band_span(float x0, float x1, std::size_t n, std::size_t lo, std::size_t hi);

/// Tick values at a "nice" step (1, 2 or 5 times a power of ten, at least `min_step`) that
/// lie in [lo, hi], at most `max_ticks` of them (and at least two when lo < hi, unless the
/// step would fall below min_step). lo > hi are swapped; a non-finite bound gives none.
std::vector<double> nice_ticks(double lo, double hi, int max_ticks, double min_step = 0);
/// The step nice_ticks() uses for the same arguments (0 when it gives no ticks).
double nice_step(double lo, double hi, int max_ticks, double min_step = 0);

/// A text label to place along one axis: its anchor (screen x), width, alignment (0: left
/// edge at the anchor, 0.5: centred, 1: right edge) and priority (higher is placed first).
struct LabelSpec {
    float anchor = 0, width = 0;
    float align = 0.5f;
    int priority = 0;
};
/// Left edges of the labels, or nullopt for labels left out: in priority order (ties: the
/// given order) each label goes to its anchor, shifted inside [lo, hi] when it would stick
/// out, and is left out when it would come closer than `gap` to a label already placed. So
/// no two placed labels overlap, and the most important ones (a legend's ends) always show
/// when they fit side by side.
std::vector<std::optional<float>> place_labels(const std::vector<LabelSpec>& labels, float lo,
                                               float hi, float gap);

/// The text of a tick value: "%g", with -0 written as 0.
std::string tick_text(double value);

/// The inside of the colour legend window: the colouring's label, then for a continuous map
/// the colour bar with tick labels that never overlap (both ends always, the centre when it
/// fits) and the percentile range control; for a categorical map one swatch per category
/// with its label and vertex count, and no range control. Returns true when the user changed
/// the options. Test hook ids: "legend: bar", "legend: label TEXT", "legend: swatch LABEL",
/// "legend: percentiles". The bar is at most `max_width` wide (at least 4 em).
/// How many of `values` fall in each of `bins` equal bins over `range` (values beyond the
/// range count in the end bins; non-finite ones nowhere): the legend's histogram.
std::vector<std::size_t> value_histogram(const std::vector<double>& values, const ValueRange& range,
                                         std::size_t bins);
bool legend_contents(const VertexColors& colors, ColoringOptions& options, float max_width = 1e30f);

/// A line plot of values over their index (see the file comment), with a y axis title above,
/// tick labels on both axes, the band [lo, hi] shaded and `marker` (-1: none) drawn as a red
/// line. Non-finite values break the line. `left_margin` is the space for the y tick labels
/// (index_plot_margin()), `width` the whole widget's; the plot area then starts at
/// left_margin and ends index_plot_right_pad() before the right edge. Test hook ids:
/// "ID: area", "ID: band", "ID: marker", "ID: x tick TEXT", "ID: y tick TEXT".
struct IndexPlot {
    std::string id;       ///< e.g. "spectrum"
    std::string y_title;  ///< e.g. "eigenvalue lambda_k"
    const std::vector<float>* values = nullptr;
    int lo = 0, hi = -1;  ///< the shaded band (hi < lo: none)
    int marker = -1;
    double min_y_step = 0;  ///< 1 for decades (log10 values)
};
void index_plot(const IndexPlot& plot, float width, float height, float left_margin);
/// The left margin that fits the y tick labels of `plot`.
float index_plot_margin(const IndexPlot& plot);
/// The space kept right of a plot area (room for the last x tick label).
float index_plot_right_pad();

}  // namespace trilab::viewer
