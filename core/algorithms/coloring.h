#pragma once
// Colour maps and vertex colourings: turns a per-vertex quantity into colours and a legend.
//
// Sequential quantities use a perceptually ordered map (dark blue -> yellow); signed
// quantities use a diverging map centred on zero (blue - white - red). The value range
// clamps outliers: by default it spans the 2nd to 98th percentile of the valid values, so
// curvature noise does not wash the picture out; signed ranges are made symmetric.
// Discrete quantities (the subdivision level) use a categorical map: one fixed, distinct
// colour per value and a legend of swatches, with no range to choose.
#include <cstddef>
#include <string>
#include <vector>

#include "core/halfedge_mesh.h"

namespace trilab {

enum class ColorMapKind { Sequential, Diverging, Categorical };
/// "sequential", "diverging", "categorical" (the CLI's --json legends).
const char* color_map_name(ColorMapKind kind);

/// One value of a categorical colouring and its legend swatch.
struct ColorCategory {
    double value = 0;
    Color color = Color::Zero();
    std::string label;      ///< e.g. "level 0 (original)"
    std::size_t count = 0;  ///< vertices with this value
};

struct ValueRange {
    double min = 0, max = 1;
};

/// What a vertex colouring shows. Later issues add more (smoothing distance, ...).
enum class VertexColoring {
    None,
    Normal,      ///< the unit normal as RGB ((n + 1) / 2)
    K1,          ///< first principal curvature
    K2,          ///< second principal curvature
    Mean,        ///< mean curvature
    Gaussian,    ///< Gaussian curvature
    ShapeIndex,  ///< shape index in [-1, 1]
    /// The subdivision step that created each vertex ("v:subdivision_level"): categorical.
    SubdivisionLevel,
    /// Displacement from a reference state (the state before the last operation), signed
    /// along the current vertex normal: positive where the surface moved outwards.
    SmoothingDistance,
    Frequency,  ///< an eigenvector's values (core/algorithms/spectral.h frequency_field); signed
    FrequencyMass,  ///< |part of the position carried by a band| (band_magnitude_field)
    /// Geodesic distance from source vertices (core/algorithms/geodesic.h): sequential, over
    /// [0, high percentile]. A field from outside (coloring_needs_field()); color_vertices()
    /// takes it from the mesh's "v:distance" property (written by `trilab-cli geodesic`,
    /// negative values: not reached) when there is one.
    GeodesicDistance,
    /// |what an operation moved each vertex by| in the frequencies below / above a split
    /// (core/algorithms/transfer_function.h change_by_frequency()): noise or shape removed.
    RemovedBelow,
    RemovedAbove,
    /// Triangle quality (core/algorithms/mesh_quality.h) at each vertex: the smallest angle
    /// of its triangles, in degrees, over the fixed range [0, 60] (sequential: dark is bad).
    MinAngle,
    /// The smallest Frey-Borouchaki Q of the vertex's triangles, over [0, 1] (1: equilateral).
    TriangleQuality,
    /// The distance from each vertex to another surface (a state of the history, a file:
    /// mesh_distance.h vertex_surface_distances()), over [0, high percentile]. A field from
    /// outside (coloring_needs_field()).
    SurfaceDistance,
};

struct ColoringOptions {
    double low_percentile = 2.0;    ///< lower end of the range, in percent of the values
    double high_percentile = 98.0;  ///< upper end of the range
};

/// Colours for every vertex (indexed by storage index) and what the legend shows.
struct VertexColors {
    std::vector<Color> colors;
    /// The value each vertex was coloured by (storage index; NaN where it has none and is
    /// grey), for isolines, bands and inspectors; empty for None and Normal, which colour
    /// by no scalar. Categorical: the category's value.
    std::vector<double> values;
    ValueRange range;  ///< the values that map to the ends of the colour bar
    ColorMapKind kind = ColorMapKind::Sequential;
    std::string label;        ///< e.g. "mean curvature"
    bool has_legend = false;  ///< false for None and Normal
    /// Categorical only: one entry per value present, ascending (range spans their values).
    std::vector<ColorCategory> categories;
};

/// The colour of category `index` of a categorical map: ten distinct hues, index 0 a dark
/// slate (a subdivision's original vertices); above 9 the hues repeat, darker (10-19) then
/// lighter (20-29), and so on.
Color categorical_color(std::size_t index);

/// The colour of `value` in `range` (clamped) on the given map; on the categorical map the
/// colour of category round(value) (grey for a negative or non-finite value), range unused.
Color map_color(double value, const ValueRange& range, ColorMapKind kind);
/// The range spanning [low, high] percentiles of the values whose `valid` entry is non-zero
/// (all values when `valid` is empty); non-finite values are ignored. Throws InvalidArgument
/// if 0 <= low < high <= 100 does not hold.
ValueRange percentile_range(const std::vector<double>& values,
                            const std::vector<std::uint8_t>& valid, double low, double high);
/// [-m, m] with m the larger magnitude of the range's ends.
ValueRange symmetric_range(const ValueRange& range);
/// Computes the quantity and its colours. `reference` (SmoothingDistance only): one earlier
/// position per vertex storage index of `mesh`; without it, or when its size differs, every
/// distance is zero and the label says there is no earlier state. GeodesicDistance colours
/// the mesh's "v:distance" property (negative or non-finite: no value) as color_field() does.
/// Throws InvalidArgument for the colourings that need a field (coloring_needs_field()),
/// GeodesicDistance included when the mesh has no "v:distance".
VertexColors color_vertices(const HalfedgeMesh& mesh, VertexColoring coloring,
                            const ColoringOptions& options = {},
                            const std::vector<Point>* reference = nullptr);
/// Per vertex storage index: (p - reference) · n(p), n the unit vertex normal of `mesh`
/// (0 for isolated vertices and where the normal is undefined). Throws InvalidArgument when
/// reference.size() != mesh.vertices_size().
std::vector<double> smoothing_distance(const HalfedgeMesh& mesh,
                                       const std::vector<Point>& reference);
/// Whether the colouring needs a per-vertex field from outside the mesh (Frequency,
/// FrequencyMass, RemovedBelow, RemovedAbove: a spectral decomposition; GeodesicDistance:
/// distances from sources); color_vertices() refuses those (GeodesicDistance only without
/// "v:distance").
bool coloring_needs_field(VertexColoring coloring);
/// Colours a given per-vertex field (indexed by storage index; NaN: no value, grey) as
/// `coloring` shows it: Frequency on the diverging map over a symmetric percentile range,
/// GeodesicDistance on the sequential map over [0, high percentile] (distances start at the
/// source; low_percentile is unused), FrequencyMass (and any other) on the sequential map
/// over the percentile range. Throws
/// InvalidArgument when values.size() != mesh.vertices_size() or for bad percentiles.
VertexColors color_field(const HalfedgeMesh& mesh, const std::vector<double>& values,
                         VertexColoring coloring, const ColoringOptions& options = {});
/// Names for menus and the CLI: "none", "normal", "k1", "k2", "mean", "gaussian", "shape-index",
/// "subdivision", "smoothing-distance", "frequency", "frequency-mass", "geodesic-distance",
/// "removed-below", "removed-above".
const char* coloring_name(VertexColoring coloring);
/// Parses coloring_name() strings; throws InvalidArgument listing the names otherwise.
VertexColoring parse_coloring(const std::string& name);
/// Every colouring, in the order of the table behind coloring_name() (for menus and help texts
/// that list them).
std::vector<VertexColoring> vertex_colorings();

}  // namespace trilab
