// Colour maps, percentile ranges and vertex colourings.
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "core/algorithms/coloring.h"
#include "core/algorithms/curvature.h"
#include "core/algorithms/generators.h"
#include "core/algorithms/mesh_quality.h"
#include "core/errors.h"
#include "core/geometry.h"
#include "core/mesh_builder.h"
#include "test_helpers.h"

using namespace trilab;

namespace {

/// Rec. 709 luminance.
double luminance(const Color& c) {
    return 0.2126 * c.x() + 0.7152 * c.y() + 0.0722 * c.z();
}

bool in_unit_cube(const Color& c) {
    return c.minCoeff() >= 0.0f && c.maxCoeff() <= 1.0f;
}

bool is_blue(const Color& c) {
    return c.z() > c.x() + 0.3f && c.z() > c.y() + 0.3f;
}

bool is_red(const Color& c) {
    return c.x() > c.y() + 0.3f && c.x() > c.z() + 0.3f;
}

const std::vector<VertexColoring> kAll = {
    VertexColoring::None, VertexColoring::Normal,   VertexColoring::K1,        VertexColoring::K2,
    VertexColoring::Mean, VertexColoring::Gaussian, VertexColoring::ShapeIndex};

}  // namespace

TEST_CASE("diverging map: blue, exactly white at the centre, red", "[coloring]") {
    const ValueRange symmetric{-2, 2};
    REQUIRE(is_blue(map_color(-2, symmetric, ColorMapKind::Diverging)));
    REQUIRE(is_red(map_color(2, symmetric, ColorMapKind::Diverging)));
    REQUIRE(map_color(0, symmetric, ColorMapKind::Diverging) == Color(1, 1, 1));
    // The centre of any range, not only of a symmetric one.
    REQUIRE(map_color(6, ValueRange{2, 10}, ColorMapKind::Diverging) == Color(1, 1, 1));
    REQUIRE(map_color(0.3, ValueRange{0.1, 0.5}, ColorMapKind::Diverging)
                .isApprox(Color(1, 1, 1), 1e-6f));
    // Values outside the range clamp to the ends.
    REQUIRE(map_color(-100, symmetric, ColorMapKind::Diverging) ==
            map_color(-2, symmetric, ColorMapKind::Diverging));
    REQUIRE(map_color(100, symmetric, ColorMapKind::Diverging) ==
            map_color(2, symmetric, ColorMapKind::Diverging));
    // Lightness rises to the centre and falls after it; both halves are alike.
    double previous = -1;
    for (int i = 0; i <= 500; ++i) {
        const double y =
            luminance(map_color(-2 + 2.0 * i / 500, symmetric, ColorMapKind::Diverging));
        REQUIRE(y > previous);
        previous = y;
    }
    for (int i = 1; i <= 500; ++i) {
        const double y = luminance(map_color(2.0 * i / 500, symmetric, ColorMapKind::Diverging));
        REQUIRE(y < previous);
        previous = y;
    }
    REQUIRE(luminance(map_color(-2, symmetric, ColorMapKind::Diverging)) ==
            Approx(luminance(map_color(2, symmetric, ColorMapKind::Diverging))).margin(0.02));
}

TEST_CASE("sequential map: dark blue to teal to yellow with monotone luminance", "[coloring]") {
    const ValueRange range{10, 20};
    const Color low = map_color(10, range, ColorMapKind::Sequential);
    const Color mid = map_color(15, range, ColorMapKind::Sequential);
    const Color high = map_color(20, range, ColorMapKind::Sequential);
    INFO("low " << low.transpose() << ", mid " << mid.transpose() << ", high " << high.transpose());
    // Dark blue.
    REQUIRE(low.z() > low.x());
    REQUIRE(low.z() > low.y());
    REQUIRE(luminance(low) < 0.15);
    // Teal: green and blue well above red.
    REQUIRE(mid.y() > mid.x() + 0.2f);
    REQUIRE(mid.z() > mid.x() + 0.2f);
    // Yellow: red and green high, blue low.
    REQUIRE(high.x() > 0.8f);
    REQUIRE(high.y() > 0.8f);
    REQUIRE(high.z() < 0.3f);
    double previous = -1;
    for (int i = 0; i <= 1000; ++i) {
        const Color c = map_color(10 + 10.0 * i / 1000, range, ColorMapKind::Sequential);
        REQUIRE(in_unit_cube(c));
        REQUIRE(luminance(c) > previous);
        previous = luminance(c);
    }
    REQUIRE(map_color(-1e300, range, ColorMapKind::Sequential) == low);
    REQUIRE(map_color(1e300, range, ColorMapKind::Sequential) == high);
}

TEST_CASE("map_color: non-finite values and degenerate ranges give the centre colour",
          "[coloring]") {
    // NaN and infinity on purpose (ordered comparisons with NaN raise FE_INVALID).
    const test::FpTrapsOff traps_off;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    for (ColorMapKind kind : {ColorMapKind::Sequential, ColorMapKind::Diverging}) {
        const Color centre = map_color(0.5, ValueRange{0, 1}, kind);
        REQUIRE(map_color(nan, ValueRange{0, 1}, kind) == centre);
        REQUIRE(map_color(inf, ValueRange{0, 1}, kind) == centre);
        REQUIRE(map_color(3, ValueRange{3, 3}, kind) == centre);
        REQUIRE(map_color(3, ValueRange{4, 2}, kind) == centre);
        REQUIRE(in_unit_cube(map_color(1, ValueRange{nan, nan}, kind)));
    }
}

TEST_CASE("percentile_range clamps outliers and ignores invalid values", "[coloring]") {
    std::vector<double> values;
    for (int i = 0; i < 1000; ++i) values.push_back(i / 999.0);
    values.push_back(1e9);
    ValueRange r = percentile_range(values, {}, 2, 98);
    REQUIRE(r.max <= 1.0);
    REQUIRE(r.max > 0.95);
    REQUIRE(r.min >= 0.0);
    REQUIRE(r.min < 0.05);
    // The full range includes the outlier; the median of 0..100 is 50.
    REQUIRE(percentile_range(values, {}, 0, 100).max == 1e9);
    std::vector<double> ramp;
    for (int i = 0; i <= 100; ++i) ramp.push_back(i);
    r = percentile_range(ramp, {}, 25, 50);
    REQUIRE(r.min == Approx(25));
    REQUIRE(r.max == Approx(50));
    // Interpolates between order statistics.
    r = percentile_range({0, 10}, {}, 25, 75);
    REQUIRE(r.min == Approx(2.5));
    REQUIRE(r.max == Approx(7.5));

    // Non-finite and invalid values are left out.
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    r = percentile_range({nan, -inf, 1, 2, 3, inf, -500}, {1, 1, 1, 1, 1, 1, 0}, 0, 100);
    REQUIRE(r.min == 1);
    REQUIRE(r.max == 3);
}

TEST_CASE("percentile_range of a constant or empty field is not degenerate", "[coloring]") {
    ValueRange r = percentile_range(std::vector<double>(50, 3.0), {}, 2, 98);
    REQUIRE(r.min < 3.0);
    REQUIRE(r.max > 3.0);
    REQUIRE(r.min + r.max == Approx(6.0));
    r = percentile_range(std::vector<double>(50, 0.0), {}, 2, 98);
    REQUIRE(r.min < 0.0);
    REQUIRE(r.max > 0.0);
    r = percentile_range({}, {}, 2, 98);
    REQUIRE(r.max > r.min);
    r = percentile_range({1, 2}, {0, 0}, 2, 98);
    REQUIRE(r.max > r.min);
}

TEST_CASE("percentile_range rejects bad percentiles, naming the parameter", "[coloring]") {
    const test::FpTrapsOff traps_off;  // NaN percentiles on purpose
    const std::vector<double> v = {1, 2, 3};
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (auto [low, high] : std::vector<std::pair<double, double>>{
             {-1, 50}, {50, 50}, {60, 40}, {0, 101}, {nan, 50}, {0, nan}}) {
        INFO("low " << low << ", high " << high);
        REQUIRE_THROWS_AS(percentile_range(v, {}, low, high), InvalidArgument);
        REQUIRE_THROWS_WITH(percentile_range(v, {}, low, high),
                            Catch::Contains("percentile_range") && Catch::Contains("low") &&
                                Catch::Contains("high"));
    }
    REQUIRE_THROWS_WITH(percentile_range(v, {1, 0}, 0, 100), Catch::Contains("valid"));
    ColoringOptions bad;
    bad.low_percentile = 99;
    bad.high_percentile = 1;
    REQUIRE_THROWS_WITH(color_vertices(make_icosphere(2), VertexColoring::Mean, bad),
                        Catch::Contains("low_percentile"));
}

TEST_CASE("symmetric_range", "[coloring]") {
    ValueRange r = symmetric_range({-1, 3});
    REQUIRE(r.min == -3);
    REQUIRE(r.max == 3);
    r = symmetric_range({-5, 2});
    REQUIRE(r.min == -5);
    REQUIRE(r.max == 5);
    r = symmetric_range({2, 4});
    REQUIRE(r.min == -4);
    REQUIRE(r.max == 4);
    r = symmetric_range({0, 0});
    REQUIRE(r.min < 0);
    REQUIRE(r.max == -r.min);
}

TEST_CASE("color_vertices gives one colour in [0,1] per vertex for every colouring", "[coloring]") {
    const HalfedgeMesh m = make_cylinder(24, 6);
    for (VertexColoring coloring : kAll) {
        INFO(coloring_name(coloring));
        const VertexColors c = color_vertices(m, coloring);
        REQUIRE(c.colors.size() == m.vertices_size());
        for (const Color& color : c.colors) REQUIRE(in_unit_cube(color));
        const bool curvature =
            coloring != VertexColoring::None && coloring != VertexColoring::Normal;
        REQUIRE(c.has_legend == curvature);
        if (!curvature) continue;
        REQUIRE(c.kind == ColorMapKind::Diverging);
        REQUIRE(c.range.max > 0);
        REQUIRE(c.range.min == -c.range.max);
        REQUIRE_FALSE(c.label.empty());
        // Boundary vertices have no curvature: they all get one neutral grey.
        REQUIRE(m.is_boundary(Vertex(0)));
        const Color grey = c.colors[0];
        REQUIRE(grey.x() == grey.y());
        REQUIRE(grey.y() == grey.z());
        for (Vertex v : m.vertices())
            if (m.is_boundary(v)) REQUIRE(c.colors[v.idx()] == grey);
    }
}

TEST_CASE("color_vertices None and Normal", "[coloring]") {
    const HalfedgeMesh m = make_icosphere(30);
    const VertexColors none = color_vertices(m, VertexColoring::None);
    REQUIRE_FALSE(none.has_legend);
    for (const Color& c : none.colors) REQUIRE(c.isApprox(Color(0.5f, 0.62f, 0.8f)));

    const VertexColors normal = color_vertices(m, VertexColoring::Normal);
    REQUIRE_FALSE(normal.has_legend);
    Vertex at_x;
    for (Vertex v : m.vertices())
        if (!at_x.is_valid() || m.position(v).x() > m.position(at_x).x()) at_x = v;
    REQUIRE(m.position(at_x).x() > 0.999);
    INFO("colour " << normal.colors[at_x.idx()].transpose());
    REQUIRE(normal.colors[at_x.idx()].isApprox(Color(1, 0.5f, 0.5f), 0.02f));
    // The octahedron has a vertex exactly at +x with a symmetric fan.
    const VertexColors octahedron = color_vertices(make_octahedron(), VertexColoring::Normal);
    REQUIRE(octahedron.colors[0].isApprox(Color(1, 0.5f, 0.5f), 1e-6f));
    REQUIRE(octahedron.colors[1].isApprox(Color(0, 0.5f, 0.5f), 1e-6f));
}

TEST_CASE("shape index colouring of a sphere is uniform red, of the flipped sphere blue",
          "[coloring]") {
    const HalfedgeMesh m = make_icosphere(30);
    const VertexColors c = color_vertices(m, VertexColoring::ShapeIndex);
    REQUIRE(c.range.min == -1);
    REQUIRE(c.range.max == 1);
    REQUIRE(c.kind == ColorMapKind::Diverging);
    for (const Color& color : c.colors) REQUIRE(color.isApprox(c.colors[0], 1e-3f));
    REQUIRE(is_red(c.colors[0]));

    PolygonSoup soup = to_soup(m);
    for (std::size_t f = 0; f < soup.n_faces(); ++f)
        std::swap(soup.corners[soup.face_offsets[f]], soup.corners[soup.face_offsets[f] + 1]);
    LoadReport report;
    const VertexColors inward =
        color_vertices(build_mesh(soup, report), VertexColoring::ShapeIndex);
    for (const Color& color : inward.colors) REQUIRE(color.isApprox(inward.colors[0], 1e-3f));
    REQUIRE(is_blue(inward.colors[0]));
}

TEST_CASE("Gaussian colouring of a torus: red outside, blue inside", "[coloring]") {
    const double R = 1.0, r = 0.3;
    const HalfedgeMesh m = make_torus(200, 100, R, r);
    const VertexColors c = color_vertices(m, VertexColoring::Gaussian);
    REQUIRE(c.has_legend);
    REQUIRE(c.kind == ColorMapKind::Diverging);
    REQUIRE(c.label.find("Gaussian") != std::string::npos);
    // The 2nd..98th percentile range of K = cos w / (r (R + r cos w)), made symmetric.
    REQUIRE(c.range.max > 2.0);
    REQUIRE(c.range.max <= 1 / (r * (R - r)) + 0.1);
    std::size_t outer = 0, inner = 0;
    for (Vertex v : m.vertices()) {
        const Point& p = m.position(v);
        const double rho = std::hypot(p.x(), p.y());
        if (std::abs(p.z()) > 1e-9) continue;
        if (rho > R) {
            ++outer;
            REQUIRE(is_red(c.colors[v.idx()]));
        } else {
            ++inner;
            REQUIRE(is_blue(c.colors[v.idx()]));
        }
    }
    REQUIRE(outer == 200);
    REQUIRE(inner == 200);
    // The top of the tube (K = 0) is white.
    for (Vertex v : m.vertices()) {
        const Point& p = m.position(v);
        if (std::abs(std::hypot(p.x(), p.y()) - R) < 1e-9)
            REQUIRE(c.colors[v.idx()].isApprox(Color(1, 1, 1), 0.02f));
    }
}

TEST_CASE("signed curvature colourings use the symmetric percentile range", "[coloring]") {
    const HalfedgeMesh m = make_noisy_sphere(10, 0.05, 2);
    const VertexCurvatures k = compute_curvatures(m);
    ColoringOptions options;
    options.low_percentile = 5;
    options.high_percentile = 90;
    const VertexColors c = color_vertices(m, VertexColoring::Mean, options);
    const ValueRange expected = symmetric_range(percentile_range(k.mean, k.valid, 5, 90));
    REQUIRE(c.range.min == expected.min);
    REQUIRE(c.range.max == expected.max);
    for (Vertex v : m.vertices())
        REQUIRE(c.colors[v.idx()] == map_color(k.mean[v.idx()], expected, ColorMapKind::Diverging));
}

TEST_CASE("coloring_name and parse_coloring round trip, unknown names list the known ones",
          "[coloring]") {
    const std::vector<std::string> names = {"none", "normal",   "k1",         "k2",
                                            "mean", "gaussian", "shape-index"};
    REQUIRE(kAll.size() == names.size());
    for (std::size_t i = 0; i < kAll.size(); ++i) {
        REQUIRE(coloring_name(kAll[i]) == names[i]);
        REQUIRE(parse_coloring(names[i]) == kAll[i]);
    }
    REQUIRE_THROWS_AS(parse_coloring("curvature"), InvalidArgument);
    REQUIRE_THROWS_AS(parse_coloring("Mean"), InvalidArgument);
    const std::string message =
        test::error_text<InvalidArgument>([] { parse_coloring("curvature"); });
    REQUIRE(message.find("'curvature'") != std::string::npos);
    for (const auto& name : names) REQUIRE(message.find(name) != std::string::npos);
}

TEST_CASE("subdivision-level colouring is categorical: one distinct colour per level",
          "[coloring]") {
    HalfedgeMesh m = make_icosphere(2);
    auto level = m.add_vertex_property<int>("v:subdivision_level", 0);
    // Like three Loop steps: most vertices on the newest level.
    std::size_t want[4] = {0, 0, 0, 0};
    for (Vertex v : m.vertices()) {
        const int l = v.idx() < 3 ? int(v.idx()) : 3;
        level[v] = l;
        ++want[l];
    }
    const VertexColors c = color_vertices(m, VertexColoring::SubdivisionLevel);
    REQUIRE(c.has_legend);
    REQUIRE(c.kind == ColorMapKind::Categorical);
    REQUIRE(std::string(color_map_name(c.kind)) == "categorical");
    REQUIRE(c.range.min == 0.0);
    REQUIRE(c.range.max == 3.0);
    REQUIRE(c.categories.size() == 4);
    for (std::size_t i = 0; i < 4; ++i) {
        INFO("level " << i);
        CHECK(c.categories[i].value == double(i));
        CHECK(c.categories[i].count == want[i]);
        CHECK(c.categories[i].label.find("level " + std::to_string(i)) == 0);
        // Every vertex of the level has its category's colour.
        for (Vertex v : m.vertices())
            if (level[v] == int(i)) REQUIRE(c.colors[v.idx()] == c.categories[i].color);
        // Distinct colours: every pair differs clearly in some channel.
        for (std::size_t j = 0; j < i; ++j)
            CHECK((c.categories[i].color - c.categories[j].color).cwiseAbs().maxCoeff() > 0.2f);
    }
    CHECK(c.categories[0].label == "level 0 (original)");
    // The same level has the same colour on any mesh, and map_color agrees.
    for (std::size_t i = 0; i < 4; ++i) {
        CHECK(c.categories[i].color == categorical_color(i));
        CHECK(map_color(double(i), c.range, ColorMapKind::Categorical) == categorical_color(i));
    }
    REQUIRE(parse_coloring("subdivision") == VertexColoring::SubdivisionLevel);
    // A mesh never subdivided is all level 0: one category.
    const VertexColors plain = color_vertices(make_icosahedron(), VertexColoring::SubdivisionLevel);
    REQUIRE(plain.categories.size() == 1);
    CHECK(plain.categories[0].count == 12);
    for (const Color& x : plain.colors) REQUIRE(x == plain.colors[0]);
}

TEST_CASE("categorical_color: ten distinct colours, then darker and lighter rounds", "[coloring]") {
    std::vector<Color> seen;
    for (std::size_t i = 0; i < 30; ++i) {
        const Color c = categorical_color(i);
        INFO("index " << i);
        REQUIRE(c.minCoeff() >= 0.0f);
        REQUIRE(c.maxCoeff() <= 1.0f);
        for (const Color& s : seen) REQUIRE((c - s).cwiseAbs().maxCoeff() > 0.02f);
        seen.push_back(c);
    }
    CHECK(categorical_color(10).sum() < categorical_color(0).sum());
    CHECK(categorical_color(21).sum() > categorical_color(1).sum());
}

TEST_CASE("smoothing distance is the displacement along the normal", "[coloring]") {
    const HalfedgeMesh before = make_icosphere(3);
    HalfedgeMesh after = before;
    // Move every vertex outwards by 0.1 along its normal and a little tangentially.
    for (Vertex v : after.vertices()) {
        const Vector3 n = vertex_normal(before, v);
        const Vector3 t = n.unitOrthogonal();
        after.position(v) += 0.1 * n + 0.05 * t;
    }
    const std::vector<double> d = smoothing_distance(after, before.positions());
    for (Vertex v : after.vertices())
        CHECK(d[v.idx()] == Approx(0.1).epsilon(0.05));  // not |0.1 n + 0.05 t| = 0.112
    const VertexColors colors =
        color_vertices(after, VertexColoring::SmoothingDistance, {}, &before.positions());
    CHECK(colors.has_legend);
    CHECK(colors.kind == ColorMapKind::Diverging);
    CHECK(colors.range.max == Approx(-colors.range.min));
    CHECK(colors.range.max > 0.09);
    // Without a reference: zero everywhere, and the label says so.
    const VertexColors none = color_vertices(after, VertexColoring::SmoothingDistance);
    CHECK(none.label.find("no earlier state") != std::string::npos);
    CHECK(parse_coloring("smoothing-distance") == VertexColoring::SmoothingDistance);
    std::vector<Point> wrong(3, Point::Zero());
    CHECK_THROWS_AS(smoothing_distance(after, wrong), InvalidArgument);
}

TEST_CASE("triangle quality colourings: the worst triangle at each vertex, on fixed ranges",
          "[coloring][quality]") {
    // A fan of four triangles around vertex 0: three equilateral-ish ones and one sliver.
    std::vector<Point> p = {Point(0, 0, 0),
                            Point(1, 0, 0),
                            Point(0.5, 0.8660254037844386, 0),
                            Point(-0.5, 0.8660254037844386, 0),
                            Point(-1, 0, 0),
                            Point(-0.5, -0.05, 0)};
    PolygonSoup soup;
    soup.positions = p;
    for (const std::array<Index, 3> f :
         {std::array<Index, 3>{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 5}}) {
        soup.corners.insert(soup.corners.end(), f.begin(), f.end());
        soup.face_offsets.push_back(soup.corners.size());
    }
    LoadReport report;
    const HalfedgeMesh mesh = build_mesh(soup, report);
    const VertexColors angle = color_vertices(mesh, VertexColoring::MinAngle, {});
    const VertexColors q = color_vertices(mesh, VertexColoring::TriangleQuality, {});
    CHECK(angle.range.min == 0.0);
    CHECK(angle.range.max == 60.0);
    CHECK(q.range.max == 1.0);
    CHECK(angle.kind == ColorMapKind::Sequential);
    // Vertex 1 has only the first, equilateral triangle: 60 degrees and Q = 1.
    CHECK(angle.values[1] == Approx(60.0).epsilon(1e-9));
    CHECK(q.values[1] == Approx(1.0).epsilon(1e-9));
    // Vertex 0 sees the sliver too: its smallest angle, computed here from the corners.
    const auto corner = [&](int a, int b, int c) {
        const Vector3 u = p[b] - p[a], v = p[c] - p[a];
        return std::acos(u.dot(v) / (u.norm() * v.norm())) * 180.0 / 3.14159265358979323846;
    };
    const double sliver = std::min({corner(0, 4, 5), corner(4, 5, 0), corner(5, 0, 4)});
    CHECK(angle.values[0] == Approx(sliver).epsilon(1e-9));
    CHECK(angle.values[5] == Approx(sliver).epsilon(1e-9));
    CHECK(q.values[0] < 0.5);
    CHECK(q.values[0] == Approx(triangle_quality(mesh, Face(3))).epsilon(1e-12));
    // Worse triangles are darker on the sequential map.
    CHECK(angle.colors[0].norm() < angle.colors[1].norm());
    CHECK(parse_coloring("min-angle") == VertexColoring::MinAngle);
    CHECK(parse_coloring("quality") == VertexColoring::TriangleQuality);
}
