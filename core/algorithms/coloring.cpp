// Colour maps and vertex colourings.
//
// Both maps interpolate linearly (per RGB channel) between a few control points:
//  - Sequential: a ramp designed for trilab, dark blue -> blue -> teal -> green -> yellow,
//    whose Rec. 709 luminance 0.2126 R + 0.7152 G + 0.0722 B rises at every control point, so
//    it rises monotonically along the whole ramp (linear pieces between increasing points);
//  - Diverging: blue -> light blue -> white -> light red -> red, symmetric in lightness, with
//    white exactly at the centre of the range.
// Values are mapped to t = (value - min) / (max - min) in double precision and clamped to
// [0, 1]; a non-finite value or a degenerate range maps to the centre of the map. The
// categorical map is a table of ten colours indexed by the (rounded) value itself.
//
// color_vertices: None paints every vertex the front colour (0.5, 0.62, 0.8); Normal paints
// (n + 1) / 2 of the area-weighted vertex normal (grey where there is none); the curvatures
// come from compute_curvatures() (Meyer et al. 2003) and, being signed, use the diverging map:
// K1, K2, Mean and Gaussian over symmetric_range(percentile_range(...)) of the valid values,
// ShapeIndex over the fixed range [-1, 1]; SubdivisionLevel on the categorical map, with one
// category per level present. Vertices without a valid value (boundary, isolated,
// zero area) get the neutral grey (0.55, 0.55, 0.55). GeodesicDistance reads "v:distance"
// and colours it as color_field() does. Every colouring but None and Normal also returns the
// values it coloured (NaN for the grey vertices). Percentiles are checked before any
// work (InvalidArgument naming low_percentile / high_percentile). Complexity: linear, plus
// O(n) expected for the percentiles (nth_element).
#include "core/algorithms/coloring.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>

#include "core/algorithms/curvature.h"
#include "core/algorithms/mesh_quality.h"
#include "core/errors.h"
#include "core/geometry.h"
#include "core/parallel.h"

namespace trilab {

namespace {

struct ControlPoint {
    double t;
    double r, g, b;
};

// Rec. 709 luminance of the control points: 0.088, 0.198, 0.379, 0.613, 0.854.
constexpr std::array<ControlPoint, 5> kSequential = {{
    {0.00, 0.085, 0.065, 0.320},
    {0.25, 0.120, 0.180, 0.600},
    {0.50, 0.080, 0.450, 0.560},
    {0.75, 0.380, 0.710, 0.340},
    {1.00, 0.990, 0.880, 0.200},
}};

// Luminance 0.297, 0.675, 1, 0.674, 0.298: both halves fade to white at the same rate.
constexpr std::array<ControlPoint, 5> kDiverging = {{
    {0.00, 0.200, 0.280, 0.750},
    {0.25, 0.560, 0.680, 0.960},
    {0.50, 1.000, 1.000, 1.000},
    {0.75, 0.950, 0.610, 0.500},
    {1.00, 0.820, 0.155, 0.170},
}};

/// Runs fn(v) for every live vertex on core/parallel.h's pool: each call writes only vertex
/// v's entries, so the colours are the same for any number of threads.
template <typename Fn>
void each_vertex(const HalfedgeMesh& mesh, const Fn& fn) {
    const bool garbage = mesh.has_garbage();
    parallel_for_blocks(0, mesh.vertices_size(), [&](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) {
            const Vertex v(static_cast<Index>(i));
            if (!(garbage && mesh.is_deleted(v))) fn(v);
        }
    });
}

const Color kFrontColor(0.5f, 0.62f, 0.8f);
const Color kInvalidColor(0.55f, 0.55f, 0.55f);

template <std::size_t N>
Color interpolate(const std::array<ControlPoint, N>& map, double t) {
    std::size_t k = 1;
    while (k + 1 < N && t > map[k].t) ++k;
    const ControlPoint& a = map[k - 1];
    const ControlPoint& b = map[k];
    // (1 - s) a + s b reproduces b exactly at s = 1 (white at the diverging centre).
    const double s = std::clamp((t - a.t) / (b.t - a.t), 0.0, 1.0);
    return Color(float((1 - s) * a.r + s * b.r), float((1 - s) * a.g + s * b.g),
                 float((1 - s) * a.b + s * b.b));
}

struct ColoringEntry {
    VertexColoring coloring;
    const char* name;
    const char* label;
};

constexpr std::array<ColoringEntry, 17> kColorings = {{
    {VertexColoring::None, "none", ""},
    {VertexColoring::Normal, "normal", "vertex normal"},
    {VertexColoring::K1, "k1", "first principal curvature k1"},
    {VertexColoring::K2, "k2", "second principal curvature k2"},
    {VertexColoring::Mean, "mean", "mean curvature H"},
    {VertexColoring::Gaussian, "gaussian", "Gaussian curvature K"},
    {VertexColoring::ShapeIndex, "shape-index", "shape index"},
    {VertexColoring::SubdivisionLevel, "subdivision", "subdivision level of each vertex"},
    {VertexColoring::SmoothingDistance, "smoothing-distance",
     "smoothing distance (along the normal)"},
    {VertexColoring::Frequency, "frequency", "frequency (eigenvector values)"},
    {VertexColoring::FrequencyMass, "frequency-mass", "geometry carried by the band"},
    {VertexColoring::GeodesicDistance, "geodesic-distance", "geodesic distance"},
    {VertexColoring::RemovedBelow, "removed-below", "change in the frequencies below the split"},
    {VertexColoring::RemovedAbove, "removed-above", "change in the frequencies above the split"},
    {VertexColoring::MinAngle, "min-angle", "smallest triangle angle at the vertex (degrees)"},
    {VertexColoring::TriangleQuality, "quality",
     "smallest triangle quality Q at the vertex (1: equilateral)"},
    {VertexColoring::SurfaceDistance, "surface-distance", "distance to the compared surface"},
}};

const ColoringEntry& entry(VertexColoring coloring) {
    for (const auto& e : kColorings)
        if (e.coloring == coloring) return e;
    throw InvalidArgument("coloring: unknown VertexColoring value " +
                          std::to_string(static_cast<int>(coloring)));
}

void check_percentiles(const char* where, const char* low_name, double low, const char* high_name,
                       double high) {
    if (low >= 0 && low < high && high <= 100) return;
    std::ostringstream s;
    s << where << ": " << low_name << " = " << low << " and " << high_name << " = " << high
      << " must satisfy 0 <= " << low_name << " < " << high_name << " <= 100";
    throw InvalidArgument(s.str());
}

/// The value of rank `position` (fractional, linear interpolation) in `v`; reorders `v`.
double order_statistic(std::vector<double>& v, double position) {
    const std::size_t below = std::min(std::size_t(position), v.size() - 1);
    const double frac = position - double(below);
    std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(below), v.end());
    const double a = v[below];
    if (frac <= 0 || below + 1 >= v.size()) return a;
    // The next order statistic is the smallest value above `below`.
    const double b = *std::min_element(v.begin() + std::ptrdiff_t(below) + 1, v.end());
    return a + frac * (b - a);
}

// Ten hues chosen apart in hue and lightness; 0 is the dark slate of the original vertices.
constexpr std::array<std::array<float, 3>, 10> kCategorical = {{
    {0.30f, 0.33f, 0.42f},  // slate
    {0.93f, 0.60f, 0.12f},  // orange
    {0.22f, 0.58f, 0.92f},  // sky blue
    {0.84f, 0.22f, 0.28f},  // red
    {0.36f, 0.74f, 0.34f},  // green
    {0.62f, 0.42f, 0.82f},  // violet
    {0.96f, 0.86f, 0.30f},  // yellow
    {0.58f, 0.38f, 0.22f},  // brown
    {0.96f, 0.56f, 0.76f},  // pink
    {0.40f, 0.84f, 0.80f},  // teal
}};

/// The GeodesicDistance colouring of the mesh's "v:distance" (color_field()); negative
/// distances mark vertices no source reached (trilab-cli geodesic writes -1): no value.
VertexColors stored_distance_colors(const HalfedgeMesh& mesh, const ColoringOptions& options) {
    const auto distance = mesh.get_vertex_property<double>("v:distance");
    if (!distance)
        throw InvalidArgument(
            "color_vertices: the 'geodesic-distance' colouring needs distances: a per-vertex "
            "'distance' property (written by trilab-cli geodesic) or picked sources");
    std::vector<double> values(mesh.vertices_size(), std::numeric_limits<double>::quiet_NaN());
    for (Vertex v : mesh.vertices())
        if (std::isfinite(distance[v]) && distance[v] >= 0) values[v.idx()] = distance[v];
    return color_field(mesh, values, VertexColoring::GeodesicDistance, options);
}

}  // namespace

const char* color_map_name(ColorMapKind kind) {
    switch (kind) {
        case ColorMapKind::Diverging:
            return "diverging";
        case ColorMapKind::Categorical:
            return "categorical";
        default:
            return "sequential";
    }
}

Color categorical_color(std::size_t index) {
    const auto& c = kCategorical[index % kCategorical.size()];
    const std::size_t round = index / kCategorical.size();
    Color out(c[0], c[1], c[2]);
    if (round == 0) return out;
    // Odd rounds darker, even rounds lighter, a little further each time round.
    const float amount = std::min(0.8f, 0.35f * float((round + 1) / 2));
    return round % 2 == 1 ? Color(out * (1.0f - amount))
                          : Color(out + (Color::Ones() - out) * amount);
}

Color map_color(double value, const ValueRange& range, ColorMapKind kind) {
    if (kind == ColorMapKind::Categorical)  // the value is the category, whatever the range
        return std::isfinite(value) && value >= 0 && value < 1e9
                   ? categorical_color(std::size_t(std::llround(value)))
                   : kInvalidColor;
    const double width = range.max - range.min;
    double t = 0.5;
    if (std::isfinite(value) && width > 0 && std::isfinite(width))
        t = std::clamp((value - range.min) / width, 0.0, 1.0);
    return kind == ColorMapKind::Sequential ? interpolate(kSequential, t)
                                            : interpolate(kDiverging, t);
}

ValueRange percentile_range(const std::vector<double>& values,
                            const std::vector<std::uint8_t>& valid, double low, double high) {
    check_percentiles("percentile_range", "low", low, "high", high);
    if (!valid.empty() && valid.size() != values.size())
        throw InvalidArgument("percentile_range: valid has " + std::to_string(valid.size()) +
                              " entries but values has " + std::to_string(values.size()) +
                              " (it must be empty or the same size)");
    std::vector<double> v;
    v.reserve(values.size());
    for (std::size_t i = 0; i < values.size(); ++i)
        if ((valid.empty() || valid[i]) && std::isfinite(values[i])) v.push_back(values[i]);
    if (v.empty()) return {};
    const double last = double(v.size() - 1);
    ValueRange r;
    r.min = order_statistic(v, low / 100 * last);
    r.max = order_statistic(v, high / 100 * last);
    if (!(r.max > r.min)) {
        const double centre = 0.5 * (r.min + r.max);
        const double half = std::max(std::abs(centre), 1e-12);
        r.min = centre - half;
        r.max = centre + half;
    }
    return r;
}

ValueRange symmetric_range(const ValueRange& range) {
    double m = std::max(std::abs(range.min), std::abs(range.max));
    if (!(m > 0)) m = 1e-12;
    return {-m, m};
}

std::vector<double> smoothing_distance(const HalfedgeMesh& mesh,
                                       const std::vector<Point>& reference) {
    if (reference.size() != mesh.vertices_size())
        throw InvalidArgument("smoothing_distance: " + std::to_string(reference.size()) +
                              " reference positions for " + std::to_string(mesh.vertices_size()) +
                              " vertices");
    std::vector<double> d(mesh.vertices_size(), 0.0);
    parallel_for(0, mesh.vertices_size(), [&](std::size_t i) {  // each from its own ring
        const Vertex v(static_cast<Index>(i));
        if (mesh.is_deleted(v)) return;
        const Vector3 normal = vertex_normal(mesh, v);
        const double value = (mesh.position(v) - reference[i]).dot(normal);
        if (std::isfinite(value)) d[i] = value;
    });
    return d;
}

namespace {

/// MinAngle and TriangleQuality: per vertex the worst value of its triangles
/// (face_quality_field), over a fixed range so that two meshes compare by colour.
VertexColors triangle_quality_colors(const HalfedgeMesh& mesh, bool min_angle, const char* label) {
    const std::vector<double> faces = face_quality_field(mesh, min_angle);
    VertexColors out;
    out.label = label;
    out.kind = ColorMapKind::Sequential;
    out.has_legend = true;
    out.range = min_angle ? ValueRange{0, 60} : ValueRange{0, 1};
    const std::size_t n = mesh.vertices_size();
    out.colors.assign(n, kInvalidColor);
    out.values.assign(n, std::numeric_limits<double>::quiet_NaN());
    each_vertex(mesh, [&](Vertex v) {
        double worst = std::numeric_limits<double>::infinity();
        for (Face f : mesh.faces_around(v))
            if (std::isfinite(faces[f.idx()])) worst = std::min(worst, faces[f.idx()]);
        if (!std::isfinite(worst)) return;  // isolated, or only degenerate triangles
        out.values[v.idx()] = worst;
        out.colors[v.idx()] = map_color(worst, out.range, out.kind);
    });
    return out;
}

}  // namespace

VertexColors color_vertices(const HalfedgeMesh& mesh, VertexColoring coloring,
                            const ColoringOptions& options, const std::vector<Point>* reference) {
    check_percentiles("color_vertices", "low_percentile", options.low_percentile, "high_percentile",
                      options.high_percentile);
    const ColoringEntry& e = entry(coloring);
    VertexColors out;
    out.label = e.label;
    const std::size_t n = mesh.vertices_size();

    if (coloring == VertexColoring::None) {
        out.colors.assign(n, kFrontColor);
        return out;
    }
    if (coloring == VertexColoring::Normal) {
        out.colors.assign(n, kInvalidColor);
        each_vertex(mesh, [&](Vertex v) {
            const Vector3 normal = vertex_normal(mesh, v);
            // Isolated vertices and fully degenerate fans have no normal: neutral grey.
            if (normal != Vector3::Zero())
                out.colors[v.idx()] = ((normal + Vector3::Ones()) * 0.5).cast<float>();
        });
        out.range = {-1, 1};
        return out;
    }

    if (coloring == VertexColoring::SubdivisionLevel) {
        // One colour per level (categorical): level 0 (the original vertices) slate, each
        // later level its own hue, the same hue for the same level on every mesh.
        auto level = mesh.get_vertex_property<int>("v:subdivision_level");
        std::map<int, std::size_t> counts;
        for (Vertex v : mesh.vertices()) ++counts[level ? level[v] : 0];
        out.kind = ColorMapKind::Categorical;
        out.has_legend = true;
        out.colors.assign(n, kInvalidColor);
        for (const auto& [value, count] : counts) {
            ColorCategory c;
            c.value = value;
            c.count = count;
            // A negative level is no step of a subdivision: grey, labelled as it is.
            c.color = value >= 0 ? categorical_color(std::size_t(value)) : kInvalidColor;
            c.label = "level " + std::to_string(value) + (value == 0 ? " (original)" : "");
            out.categories.push_back(std::move(c));
        }
        if (!out.categories.empty())
            out.range = {out.categories.front().value, out.categories.back().value};
        out.values.assign(n, std::numeric_limits<double>::quiet_NaN());
        for (Vertex v : mesh.vertices()) {
            const int value = level ? level[v] : 0;
            out.values[v.idx()] = value;
            out.colors[v.idx()] =
                value >= 0 ? categorical_color(std::size_t(value)) : kInvalidColor;
        }
        return out;
    }

    if (coloring == VertexColoring::SmoothingDistance) {
        const bool have = reference && reference->size() == mesh.vertices_size();
        const std::vector<double> d =
            have ? smoothing_distance(mesh, *reference) : std::vector<double>(n, 0.0);
        if (!have) out.label += " - no earlier state";
        std::vector<std::uint8_t> valid(n, 0);
        for (Vertex v : mesh.vertices()) valid[v.idx()] = !mesh.is_isolated(v);
        out.kind = ColorMapKind::Diverging;
        out.has_legend = true;
        out.range = symmetric_range(
            percentile_range(d, valid, options.low_percentile, options.high_percentile));
        if (!(out.range.max > 0)) out.range = {-1e-12, 1e-12};
        out.colors.assign(n, kInvalidColor);
        out.values.assign(n, std::numeric_limits<double>::quiet_NaN());
        for (Vertex v : mesh.vertices())
            if (valid[v.idx()]) {
                out.colors[v.idx()] = map_color(d[v.idx()], out.range, out.kind);
                out.values[v.idx()] = d[v.idx()];
            }
        return out;
    }

    if (coloring == VertexColoring::GeodesicDistance) return stored_distance_colors(mesh, options);

    if (coloring == VertexColoring::MinAngle || coloring == VertexColoring::TriangleQuality)
        return triangle_quality_colors(mesh, coloring == VertexColoring::MinAngle, e.label);

    if (coloring_needs_field(coloring))
        throw InvalidArgument(std::string("color_vertices: the '") + e.name +
                              "' colouring needs a spectral decomposition (the viewer's "
                              "Frequency panel)");
    const VertexCurvatures c = compute_curvatures(mesh);
    const std::vector<double>* field = nullptr;
    switch (coloring) {
        case VertexColoring::K1:
            field = &c.k1;
            break;
        case VertexColoring::K2:
            field = &c.k2;
            break;
        case VertexColoring::Mean:
            field = &c.mean;
            break;
        case VertexColoring::Gaussian:
            field = &c.gaussian;
            break;
        default:
            field = &c.shape_index;
            break;
    }
    out.kind = ColorMapKind::Diverging;
    out.has_legend = true;
    out.range = coloring == VertexColoring::ShapeIndex
                    ? ValueRange{-1, 1}
                    : symmetric_range(percentile_range(*field, c.valid, options.low_percentile,
                                                       options.high_percentile));
    out.colors.assign(n, kInvalidColor);
    out.values.assign(n, std::numeric_limits<double>::quiet_NaN());
    each_vertex(mesh, [&](Vertex v) {
        if (!c.valid[v.idx()]) return;
        out.colors[v.idx()] = map_color((*field)[v.idx()], out.range, out.kind);
        out.values[v.idx()] = (*field)[v.idx()];
    });
    return out;
}

bool coloring_needs_field(VertexColoring coloring) {
    return coloring == VertexColoring::Frequency || coloring == VertexColoring::FrequencyMass ||
           coloring == VertexColoring::GeodesicDistance ||
           coloring == VertexColoring::RemovedBelow || coloring == VertexColoring::RemovedAbove ||
           coloring == VertexColoring::SurfaceDistance;
}

VertexColors color_field(const HalfedgeMesh& mesh, const std::vector<double>& values,
                         VertexColoring coloring, const ColoringOptions& options) {
    check_percentiles("color_field", "low_percentile", options.low_percentile, "high_percentile",
                      options.high_percentile);
    if (values.size() != mesh.vertices_size())
        throw InvalidArgument("color_field: " + std::to_string(values.size()) +
                              " values for a mesh of " + std::to_string(mesh.vertices_size()) +
                              " vertices");
    VertexColors out;
    out.label = entry(coloring).label;
    out.has_legend = true;
    out.kind =
        coloring == VertexColoring::Frequency ? ColorMapKind::Diverging : ColorMapKind::Sequential;
    out.range = percentile_range(values, {}, options.low_percentile, options.high_percentile);
    if (out.kind == ColorMapKind::Diverging) out.range = symmetric_range(out.range);
    if (coloring == VertexColoring::GeodesicDistance ||
        coloring == VertexColoring::SurfaceDistance) {
        // Distances start at 0 (the source, the other surface): [0, high percentile].
        const double high = percentile_range(values, {}, 0.0, options.high_percentile).max;
        out.range = {0.0, high > 0 ? high : 1e-12};
    }
    out.colors.assign(values.size(), kInvalidColor);
    out.values.assign(values.size(), std::numeric_limits<double>::quiet_NaN());
    each_vertex(mesh, [&](Vertex v) {
        if (!std::isfinite(values[v.idx()])) return;
        out.colors[v.idx()] = map_color(values[v.idx()], out.range, out.kind);
        out.values[v.idx()] = values[v.idx()];
    });
    return out;
}

const char* coloring_name(VertexColoring coloring) {
    return entry(coloring).name;
}

VertexColoring parse_coloring(const std::string& name) {
    std::string known;
    for (const auto& e : kColorings) {
        if (name == e.name) return e.coloring;
        known += (known.empty() ? "" : ", ") + std::string(e.name);
    }
    throw InvalidArgument("parse_coloring: unknown colouring '" + name + "' (known: " + known +
                          ")");
}

std::vector<VertexColoring> vertex_colorings() {
    std::vector<VertexColoring> all;
    for (const auto& e : kColorings) all.push_back(e.coloring);
    return all;
}

}  // namespace trilab
