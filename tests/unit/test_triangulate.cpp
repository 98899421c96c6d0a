// Polygon triangulation (core/triangulate.h) and polygons through build_mesh: n - 2
// triangles, none inverted, the polygon's area, a valid mesh, for convex, non-convex,
// collinear and degenerate polygons in any plane and orientation, small (ear clipping) and
// large (monotone partition); crossing polygons become fans without a crash.
#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "core/algorithms/mesh_stats.h"
#include "core/geometry.h"
#include "core/mesh_builder.h"
#include "core/triangulate.h"
#include "test_helpers.h"

using namespace trilab;
using Catch::Matchers::Contains;

namespace {

/// Places 2D polygons in a tilted plane away from the origin.
struct Plane {
    Point origin;
    Vector3 u, v;
    Point operator()(double x, double y) const { return origin + x * u + y * v; }
    Vector3 normal() const { return u.cross(v).normalized(); }
};

Plane tilted_plane() {
    const Vector3 n = Vector3(1, 2, 3).normalized();
    const Vector3 u = n.cross(Vector3::UnitX()).normalized();
    return {Point(10, -5, 3), u, n.cross(u)};
}

struct Shape {
    std::string name;
    std::vector<std::array<double, 2>> xy;  // counter-clockwise
};

std::vector<std::array<double, 2>> circle_points(std::size_t n, double (*radius)(std::size_t)) {
    std::vector<std::array<double, 2>> p;
    for (std::size_t i = 0; i < n; ++i) {
        const double a = 2 * M_PI * double(i) / double(n);
        const double r = radius(i);
        p.push_back({r * std::cos(a), r * std::sin(a)});
    }
    return p;
}

/// Simple polygons of about n corners (at least 4).
std::vector<Shape> shapes(std::size_t n) {
    std::vector<Shape> out;
    out.push_back({"convex", circle_points(n, [](std::size_t) { return 1.0; })});
    out.push_back(
        {"star", circle_points(n + n % 2, [](std::size_t i) { return i % 2 ? 0.4 : 1.0; })});
    {
        static std::mt19937 rng(7);
        std::vector<double> radii(n);
        std::uniform_real_distribution<double> r(0.2, 1.0);
        for (double& x : radii) x = r(rng);
        Shape s{"random star-shaped", {}};
        for (std::size_t i = 0; i < n; ++i) {
            const double a = 2 * M_PI * double(i) / double(n);
            s.xy.push_back({radii[i] * std::cos(a), radii[i] * std::sin(a)});
        }
        out.push_back(s);
    }
    {
        // A comb: teeth of width 0.5 hanging down from a bar (horizontal edges, equal y).
        Shape s{"comb", {}};
        const std::size_t teeth = std::max<std::size_t>(1, n / 4);
        s.xy.push_back({0, 1});
        for (std::size_t i = 0; i < teeth; ++i) {
            s.xy.push_back({double(i), -3});
            s.xy.push_back({i + 0.5, -3});
            s.xy.push_back({i + 0.5, 0});
            s.xy.push_back({i + 1.0, 0});
        }
        s.xy.back() = {double(teeth), 1};  // the last corner closes the bar
        out.push_back(s);
    }
    if (n >= 40) {
        // A thick spiral (two turns): deep pockets that fool a fan (too coarse below 40).
        Shape s{"spiral", {}};
        const std::size_t half = std::max<std::size_t>(4, n / 2);
        std::vector<std::array<double, 2>> inner;
        for (std::size_t i = 0; i < half; ++i) {
            const double a = 4 * M_PI * double(i) / double(half - 1);
            const double r = 1 + a;
            s.xy.push_back({r * std::cos(a), r * std::sin(a)});
            inner.push_back({(r - 0.8) * std::cos(a), (r - 0.8) * std::sin(a)});
        }
        for (std::size_t i = half; i-- > 0;) s.xy.push_back(inner[i]);
        out.push_back(s);
    }
    {
        // A square with collinear runs of corners on every side.
        Shape s{"square with collinear runs", {}};
        const std::size_t k = std::max<std::size_t>(1, n / 4);
        for (std::size_t i = 0; i < k; ++i) s.xy.push_back({double(i) / k, 0});
        for (std::size_t i = 0; i < k; ++i) s.xy.push_back({1, double(i) / k});
        for (std::size_t i = 0; i < k; ++i) s.xy.push_back({1 - double(i) / k, 1});
        for (std::size_t i = 0; i < k; ++i) s.xy.push_back({0, 1 - double(i) / k});
        out.push_back(s);
    }
    {
        // A staircase on integer coordinates: many corners on each sweep line.
        Shape s{"staircase", {}};
        const std::size_t k = std::max<std::size_t>(2, n / 2);
        for (std::size_t i = 0; i < k; ++i) {
            s.xy.push_back({double(i), double(i)});
            s.xy.push_back({double(i + 1), double(i)});
        }
        s.xy.push_back({double(k), double(k)});
        s.xy.push_back({0, double(k)});
        out.push_back(s);
    }
    return out;
}

double shoelace(const std::vector<std::array<double, 2>>& p) {
    double a = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        const auto& q = p[i];
        const auto& r = p[(i + 1) % p.size()];
        a += q[0] * r[1] - r[0] * q[1];
    }
    return 0.5 * a;
}

/// Checks a triangulation of the 3D polygon p (counter-clockwise around `normal`) with the
/// given 2D area: n - 2 triangles of distinct corners in range, none inverted, areas adding
/// up to the polygon's (so none overlap).
void check_triangulation(const std::vector<Point>& p, const std::vector<PolygonTriangle>& tris,
                         const Vector3& normal, double area) {
    REQUIRE(tris.size() == p.size() - 2);
    double sum = 0, sum_abs = 0, scale = 0;
    for (const Point& q : p) scale = std::max(scale, (q - p[0]).norm());
    for (const PolygonTriangle& t : tris) {
        for (Index c : t) REQUIRE(c < p.size());
        REQUIRE(t[0] != t[1]);
        REQUIRE(t[1] != t[2]);
        REQUIRE(t[0] != t[2]);
        const double a = 0.5 * (p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]]).dot(normal);
        REQUIRE(a >= -1e-12 * scale * scale);
        sum += a;
        sum_abs += std::abs(a);
    }
    CHECK(sum == Approx(area).epsilon(1e-9));
    CHECK(sum_abs == Approx(area).epsilon(1e-9));
}

}  // namespace

TEST_CASE("simple polygons are triangulated without overlaps in any plane and orientation",
          "[triangulate]") {
    const Plane plane = tilted_plane();
    // 6 and 12: ear clipping; 40 and 3000: the monotone partition.
    for (std::size_t n : {6, 12, 40, 3000}) {
        for (const Shape& shape : shapes(n)) {
            for (bool clockwise : {false, true}) {
                INFO(shape.name << ", " << shape.xy.size() << " corners"
                                << (clockwise ? ", clockwise" : ""));
                std::vector<std::array<double, 2>> xy = shape.xy;
                if (clockwise) std::reverse(xy.begin(), xy.end());
                std::vector<Point> p;
                for (const auto& q : xy) p.push_back(plane(q[0], q[1]));
                TriangulationMethod method;
                const auto tris = triangulate_polygon(p, &method);
                CHECK(method == (p.size() <= kEarClippingCorners ? TriangulationMethod::kEarClipping
                                                                 : TriangulationMethod::kMonotone));
                const double area = std::abs(shoelace(xy));
                check_triangulation(p, tris, clockwise ? -plane.normal() : plane.normal(), area);
            }
        }
    }
}

TEST_CASE("a large non-convex polygon is triangulated by the monotone partition", "[triangulate]") {
    // 20,000 corners took 2.5 s by quadratic ear clipping; here it is a fraction of that.
    const Plane plane = tilted_plane();
    const auto xy = circle_points(20000, [](std::size_t i) { return i % 2 ? 0.5 : 1.0; });
    std::vector<Point> p;
    for (const auto& q : xy) p.push_back(plane(q[0], q[1]));
    TriangulationMethod method;
    const auto tris = triangulate_polygon(p, &method);
    CHECK(method == TriangulationMethod::kMonotone);
    check_triangulation(p, tris, plane.normal(), shoelace(xy));
}

TEST_CASE("corners on the same spot and zero-area polygons never crash", "[triangulate]") {
    const Plane plane = tilted_plane();
    SECTION("a polygon that visits one point twice (distinct corners, same position)") {
        // Two squares touching at a corner, walked as one polygon: weakly simple.
        const std::vector<std::array<double, 2>> xy = {{0, 0}, {1, 0}, {1, 1}, {2, 1},
                                                       {2, 2}, {1, 2}, {1, 1}, {0, 1}};
        for (std::size_t copies : {1, 5}) {  // 8 corners, and 40 by subdividing the edges
            std::vector<Point> p;
            std::vector<std::array<double, 2>> dense;
            for (std::size_t i = 0; i < xy.size(); ++i)
                for (std::size_t k = 0; k < copies; ++k) {
                    const auto& a = xy[i];
                    const auto& b = xy[(i + 1) % xy.size()];
                    const double t = double(k) / double(copies);
                    dense.push_back({a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])});
                }
            for (const auto& q : dense) p.push_back(plane(q[0], q[1]));
            INFO(p.size() << " corners");
            const auto tris = triangulate_polygon(p);
            REQUIRE(tris.size() == p.size() - 2);
            double sum = 0;
            for (const PolygonTriangle& t : tris)
                sum += 0.5 * (p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]]).dot(plane.normal());
            CHECK(sum == Approx(2.0).epsilon(1e-9));
        }
    }
    SECTION("all corners on one line, and all on one point") {
        for (std::size_t n : {5, 50}) {
            std::vector<Point> line, point;
            for (std::size_t i = 0; i < n; ++i) {
                line.push_back(plane(double(i % 3), 0));
                point.push_back(plane(0.5, 0.5));
            }
            TriangulationMethod method;
            CHECK(triangulate_polygon(line, &method).size() == n - 2);
            CHECK(method == TriangulationMethod::kFan);
            CHECK(triangulate_polygon(point, &method).size() == n - 2);
            CHECK(method == TriangulationMethod::kFan);
        }
    }
    SECTION("coordinates near the largest double") {
        std::vector<Point> p;
        for (std::size_t i = 0; i < 40; ++i) {
            const double a = 2 * M_PI * double(i) / 40;
            p.push_back(Point(1e307 * std::cos(a), 1e307 * std::sin(a), 1e307));
        }
        TriangulationMethod method;
        const auto tris = triangulate_polygon(p, &method);
        CHECK(tris.size() == 38);
        CHECK(method == TriangulationMethod::kMonotone);
    }
}

TEST_CASE("crossing polygons are never a crash, large ones become reported fans", "[triangulate]") {
    // The star polygon {n/3} (n prime): every edge crosses others. Up to 256 corners ear
    // clipping is tried (it clips corners of a crossing polygon as it always did), above
    // that the polygon becomes a fan, and the load report says so.
    for (std::size_t n : {7, 101, 2003}) {
        std::vector<Point> p;
        for (std::size_t i = 0; i < n; ++i) {
            const double a = 2 * M_PI * double((i * (n / 3)) % n) / double(n);
            p.push_back(Point(std::cos(a), std::sin(a), 0));
        }
        INFO(n << " corners");
        TriangulationMethod method;
        const auto tris = triangulate_polygon(p, &method);
        CHECK(tris.size() == n - 2);
        CHECK(method != TriangulationMethod::kMonotone);
        if (n > kFallbackEarClippingCorners) CHECK(method == TriangulationMethod::kFan);

        PolygonSoup soup;
        soup.positions = p;
        std::vector<Index> face(n);
        for (Index i = 0; i < n; ++i) face[i] = i;
        soup.add_face(face);
        LoadReport report;
        const HalfedgeMesh mesh = build_mesh(soup, report);
        REQUIRE_VALID(mesh);
        CHECK(mesh.n_faces() == n - 2);
        CHECK(report.polygons_triangulated == 1);
        CHECK(report.triangles_from_polygons == n - 2);
        if (method == TriangulationMethod::kFan) {
            REQUIRE(report.notes.size() == 1);
            CHECK_THAT(report.notes[0], Contains("1 polygon is not simple") && Contains("fan"));
        }
    }
}

TEST_CASE("build_mesh turns a large polygon into n - 2 faces of a valid disc", "[triangulate]") {
    const Plane plane = tilted_plane();
    for (const Shape& shape : shapes(2000)) {
        INFO(shape.name);
        PolygonSoup soup;
        std::vector<Index> face;
        for (const auto& q : shape.xy) {
            face.push_back(Index(soup.positions.size()));
            soup.positions.push_back(plane(q[0], q[1]));
        }
        soup.add_face(face);
        LoadReport report;
        const HalfedgeMesh mesh = build_mesh(soup, report);
        REQUIRE_VALID(mesh);
        CHECK(mesh.n_faces() == face.size() - 2);
        CHECK(report.triangles_from_polygons == face.size() - 2);
        CHECK(report.notes.empty());
        const MeshStats s = compute_stats(mesh);
        CHECK(s.boundary_loops == 1);
        CHECK(s.components == 1);
        CHECK(s.genus == 0);
        CHECK(surface_area(mesh) == Approx(std::abs(shoelace(shape.xy))).epsilon(1e-9));
    }
}

TEST_CASE("a large face with a repeated corner is dropped as degenerate", "[triangulate]") {
    PolygonSoup soup;
    std::vector<Index> face;
    for (Index i = 0; i < 100; ++i) {
        const double a = 2 * M_PI * i / 100;
        soup.positions.push_back(Point(std::cos(a), std::sin(a), 0));
        face.push_back(i);
    }
    face[70] = 3;  // far from its first use: found by sorting, not by neighbours
    soup.add_face(face);
    soup.add_face({0, 1, 2});
    LoadReport report;
    const HalfedgeMesh mesh = build_mesh(soup, report);
    REQUIRE_VALID(mesh);
    CHECK(report.degenerate_faces_dropped == 1);
    CHECK(mesh.n_faces() == 1);
}
