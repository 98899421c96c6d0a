// The values a colouring keeps (VertexColors::values, for isolines and bands) and the
// geodesic-distance colouring from a mesh's "v:distance" property.
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "core/algorithms/coloring.h"
#include "core/algorithms/curvature.h"
#include "core/algorithms/generators.h"
#include "core/algorithms/geodesic.h"
#include "core/errors.h"
#include "core/geometry.h"
#include "test_helpers.h"

using namespace trilab;

TEST_CASE("every scalar colouring keeps the values it coloured, NaN where it painted grey",
          "[coloring]") {
    const HalfedgeMesh m = make_cylinder(24, 6);  // open: boundary vertices have no curvature
    const VertexCurvatures k = compute_curvatures(m);
    const std::vector<std::pair<VertexColoring, const std::vector<double>*>> cases = {
        {VertexColoring::K1, &k.k1},
        {VertexColoring::K2, &k.k2},
        {VertexColoring::Mean, &k.mean},
        {VertexColoring::Gaussian, &k.gaussian},
        {VertexColoring::ShapeIndex, &k.shape_index}};
    for (const auto& [coloring, field] : cases) {
        INFO(coloring_name(coloring));
        const VertexColors c = color_vertices(m, coloring);
        REQUIRE(c.values.size() == m.vertices_size());
        for (Vertex v : m.vertices()) {
            if (k.valid[v.idx()]) {
                REQUIRE(c.values[v.idx()] == (*field)[v.idx()]);
                REQUIRE(c.colors[v.idx()] == map_color(c.values[v.idx()], c.range, c.kind));
            } else {
                REQUIRE(std::isnan(c.values[v.idx()]));
            }
        }
    }
    CHECK(color_vertices(m, VertexColoring::None).values.empty());
    CHECK(color_vertices(m, VertexColoring::Normal).values.empty());

    // Smoothing distance and a given field keep theirs too.
    std::vector<Point> reference = m.positions();
    for (Point& p : reference) p *= 0.9;
    const VertexColors s = color_vertices(m, VertexColoring::SmoothingDistance, {}, &reference);
    const std::vector<double> d = smoothing_distance(m, reference);
    REQUIRE(s.values == d);
    std::vector<double> field(m.vertices_size());
    for (Vertex v : m.vertices()) field[v.idx()] = m.position(v).z();
    field[3] = std::numeric_limits<double>::quiet_NaN();
    const VertexColors f = color_field(m, field, VertexColoring::Frequency);
    REQUIRE(f.values.size() == field.size());
    CHECK(std::isnan(f.values[3]));
    CHECK(f.values[4] == field[4]);
}

TEST_CASE("geodesic-distance colours the mesh's v:distance over [0, high percentile]",
          "[coloring][geodesic]") {
    HalfedgeMesh m = make_grid(12);
    CHECK(coloring_name(VertexColoring::GeodesicDistance) == std::string("geodesic-distance"));
    CHECK(parse_coloring("geodesic-distance") == VertexColoring::GeodesicDistance);
    CHECK(coloring_needs_field(VertexColoring::GeodesicDistance));

    // Without distances: refused, saying what is missing.
    const std::string message = test::error_text<InvalidArgument>(
        [&] { color_vertices(m, VertexColoring::GeodesicDistance); });
    CHECK(message.find("geodesic-distance") != std::string::npos);
    CHECK(message.find("distance") != std::string::npos);

    // Distances as trilab-cli geodesic writes them: -1 for a vertex no source reaches.
    auto distance = m.vertex_property<double>("v:distance");
    for (Vertex v : m.vertices()) distance[v] = m.position(v).x() + 2 * m.position(v).y();
    distance[Vertex(5)] = -1.0;
    ColoringOptions all;
    all.low_percentile = 50;  // unused: distances start at 0
    all.high_percentile = 100;
    const VertexColors c = color_vertices(m, VertexColoring::GeodesicDistance, all);
    CHECK(c.kind == ColorMapKind::Sequential);
    CHECK(c.has_legend);
    CHECK(c.label == "geodesic distance");
    CHECK(c.range.min == 0.0);
    CHECK(c.range.max == Approx(3.0));  // the corner (1, 1)
    REQUIRE(c.values.size() == m.vertices_size());
    CHECK(std::isnan(c.values[5]));
    CHECK(c.colors[5] == c.colors[5].x() * Color::Ones());  // grey
    for (Vertex v : m.vertices()) {
        if (v.idx() == 5) continue;
        REQUIRE(c.values[v.idx()] == distance[v]);
        REQUIRE(c.colors[v.idx()] == map_color(distance[v], c.range, ColorMapKind::Sequential));
    }
    // The default options clip the top 2 %.
    const VertexColors clipped = color_vertices(m, VertexColoring::GeodesicDistance);
    CHECK(clipped.range.min == 0.0);
    CHECK(clipped.range.max < 3.0);
    CHECK(clipped.range.max > 2.5);

    // The same as colouring the heat-method distances directly (what the viewer does).
    const std::vector<double> heat = geodesic_distances(m, {Vertex(0)});
    for (Vertex v : m.vertices()) distance[v] = heat[v.idx()];
    const VertexColors from_property = color_vertices(m, VertexColoring::GeodesicDistance);
    const VertexColors from_field = color_field(m, heat, VertexColoring::GeodesicDistance);
    CHECK(from_property.colors == from_field.colors);
    CHECK(from_property.range.max == from_field.range.max);
}
