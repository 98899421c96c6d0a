// Picking by ray casting: the first triangle hit, both orientations, nearest corner and edge,
// misses, t_min, ties, triangle lists with dead triangles, the threaded scan against a
// plain per-face intersection written independently here, bad input.
#include <cmath>
#include <limits>
#include <random>

#include "core/algorithms/generators.h"
#include "core/algorithms/ray_pick.h"
#include "core/errors.h"
#include "core/mesh_builder.h"
#include "test_helpers.h"

using namespace trilab;

namespace {

HalfedgeMesh build(const std::vector<Point>& points, const std::vector<std::vector<Index>>& faces) {
    PolygonSoup soup;
    soup.positions = points;
    for (const auto& f : faces) soup.add_face(f);
    LoadReport report;
    return build_mesh(soup, report);
}

/// The ray parameter where the ray meets the triangle, by the plane and three edge-side
/// tests (a different method from the one under test); infinity for a miss.
double plane_hit(const Ray& ray, const Point& a, const Point& b, const Point& c) {
    const Vector3 n = (b - a).cross(c - a);
    const double denom = n.dot(ray.direction);
    if (denom == 0.0) return std::numeric_limits<double>::infinity();
    const double t = n.dot(a - ray.origin) / denom;
    if (t <= 0) return std::numeric_limits<double>::infinity();
    const Point p = ray.origin + t * ray.direction;
    const double s0 = (b - a).cross(p - a).dot(n), s1 = (c - b).cross(p - b).dot(n),
                 s2 = (a - c).cross(p - c).dot(n);
    const bool inside = (s0 >= 0 && s1 >= 0 && s2 >= 0);
    return inside ? t : std::numeric_limits<double>::infinity();
}

}  // namespace

TEST_CASE("pick hits a triangle where the ray meets it, with its barycentric coordinates",
          "[pick]") {
    const HalfedgeMesh mesh = build({Point(0, 0, 0), Point(1, 0, 0), Point(0, 1, 0)}, {{0, 1, 2}});
    Ray ray;
    ray.origin = Point(0.2, 0.3, 5);
    ray.direction = Vector3(0, 0, -1);
    const auto hit = pick_face(mesh, mesh.positions(), ray);
    REQUIRE(hit.has_value());
    CHECK(hit->triangle == 0);
    CHECK(hit->t == Approx(5.0));
    CHECK(hit->position.isApprox(Point(0.2, 0.3, 0)));
    CHECK(hit->barycentric[0] == Approx(0.5));
    CHECK(hit->barycentric[1] == Approx(0.2));
    CHECK(hit->barycentric[2] == Approx(0.3));
    CHECK_FALSE(hit->back_face);  // the normal is +z, the ray comes from +z
    // Nearest corner: (0,0,0) at 0.36 against (1,0,0) at 0.85 and (0,1,0) at 0.73.
    CHECK(hit->corners[hit->nearest_corner] == 0);
    // Nearest edge: y = 0 (distance 0.3)? x = 0 is at 0.2: the edge from corner 2 to 0.
    CHECK(hit->nearest_edge == 2);
    // The halfedge of that side runs between those corners.
    const Halfedge side = face_side(mesh, Face(0), hit->nearest_edge);
    CHECK(mesh.from_vertex(side).idx() == hit->corners[2]);
    CHECK(mesh.to_vertex(side).idx() == hit->corners[0]);

    SECTION("from behind: the back face is hit and said so") {
        Ray back = ray;
        back.origin = Point(0.2, 0.3, -5);
        back.direction = Vector3(0, 0, 1);
        const auto b = pick_face(mesh, mesh.positions(), back);
        REQUIRE(b.has_value());
        CHECK(b->back_face);
    }
    SECTION("outside the triangle, pointing away, or closer than t_min: no hit") {
        Ray miss = ray;
        miss.origin = Point(0.8, 0.8, 5);
        CHECK_FALSE(pick_face(mesh, mesh.positions(), miss).has_value());
        Ray away = ray;
        away.direction = Vector3(0, 0, 1);
        CHECK_FALSE(pick_face(mesh, mesh.positions(), away).has_value());
        CHECK_FALSE(pick_face(mesh, mesh.positions(), ray, 6.0).has_value());
    }
}

TEST_CASE("pick takes the nearest of stacked triangles and the lower index on a tie", "[pick]") {
    const HalfedgeMesh mesh =
        build({Point(0, 0, 0), Point(1, 0, 0), Point(0, 1, 0), Point(0, 0, 1), Point(1, 0, 1),
               Point(0, 1, 1), Point(0, 0, 2), Point(1, 0, 2), Point(0, 1, 2)},
              {{0, 1, 2}, {3, 4, 5}, {6, 7, 8}});
    Ray ray;
    ray.origin = Point(0.25, 0.25, 10);
    ray.direction = Vector3(0, 0, -2);  // not unit: t in its units
    auto hit = pick_face(mesh, mesh.positions(), ray);
    REQUIRE(hit);
    CHECK(hit->triangle == 2);
    CHECK(hit->t == Approx(4.0));
    ray.origin.z() = -10;
    ray.direction = Vector3(0, 0, 1);
    hit = pick_face(mesh, mesh.positions(), ray);
    REQUIRE(hit);
    CHECK(hit->triangle == 0);

    // A morph frame's positions: the top triangle moved below the others.
    std::vector<Point> frame = mesh.positions();
    for (int i = 6; i < 9; ++i) frame[i].z() = -1;
    hit = pick_face(mesh, frame, ray);
    REQUIRE(hit);
    CHECK(hit->triangle == 2);

    // Two coincident triangles: the lower index.
    const HalfedgeMesh twins = build({Point(0, 0, 0), Point(1, 0, 0), Point(0, 1, 0),
                                      Point(0, 0, 0), Point(1, 0, 0), Point(0, 1, 0)},
                                     {{3, 4, 5}, {0, 1, 2}});
    hit = pick_face(twins, twins.positions(), ray);
    REQUIRE(hit);
    CHECK(hit->triangle == 0);
}

TEST_CASE("pick on a large sphere agrees with a plain plane test of every face", "[pick]") {
    const HalfedgeMesh sphere = make_icosphere(110);  // 242,000 faces: the threaded scan
    REQUIRE(sphere.n_faces() > 200000);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1, 1);
    int hits = 0, misses = 0;
    for (int trial = 0; trial < 12; ++trial) {
        Ray ray;
        ray.origin = Point(u(rng), u(rng), u(rng)).normalized() * 3.0;
        const Point aim = Point(u(rng), u(rng), u(rng)) * 0.9;
        ray.direction = aim - ray.origin;
        double best = std::numeric_limits<double>::infinity();
        Index best_face = kInvalidIndex;
        for (Face f : sphere.faces()) {
            const std::array<Vertex, 3> c = sphere.face_vertices(f);
            const double t =
                plane_hit(ray, sphere.position(c[0]), sphere.position(c[1]), sphere.position(c[2]));
            if (t < best) best = t, best_face = f.idx();
        }
        const auto hit = pick_face(sphere, sphere.positions(), ray);
        if (best_face == kInvalidIndex) {
            CHECK_FALSE(hit.has_value());
            ++misses;
            continue;
        }
        REQUIRE(hit.has_value());
        ++hits;
        CHECK(hit->t == Approx(best).epsilon(1e-9));
        CHECK(std::abs(hit->position.norm() - 1.0) < 1e-3);  // on the sphere's front
        CHECK_FALSE(hit->back_face);
        // On an edge two faces meet at the same t; elsewhere the same face.
        if (hit->triangle != best_face) CHECK(hit->t == Approx(best).epsilon(1e-12));
    }
    CHECK(hits > 0);
    // A ray that passes the sphere by.
    Ray by;
    by.origin = Point(0, 2, 5);
    by.direction = Vector3(0, 0, -1);
    CHECK_FALSE(pick_face(sphere, sphere.positions(), by).has_value());
    (void)misses;
}

TEST_CASE("pick over a triangle list skips dead triangles", "[pick]") {
    const std::vector<Point> points{Point(0, 0, 0), Point(1, 0, 0), Point(0, 1, 0),
                                    Point(0, 0, 1), Point(1, 0, 1), Point(0, 1, 1)};
    const std::vector<std::array<Index, 3>> triangles{{0, 1, 2}, {3, 4, 5}};
    Ray ray;
    ray.origin = Point(0.1, 0.1, 3);
    ray.direction = Vector3(0, 0, -1);
    auto hit = pick_triangle(triangles, {}, points, ray);
    REQUIRE(hit);
    CHECK(hit->triangle == 1);
    hit = pick_triangle(triangles, {1, 0}, points, ray);
    REQUIRE(hit);
    CHECK(hit->triangle == 0);
    CHECK(hit->corners == triangles[0]);
    CHECK_FALSE(pick_triangle(triangles, {0, 0}, points, ray).has_value());
}

TEST_CASE("pick refuses a ray without direction, NaNs and mismatched arrays", "[pick]") {
    const HalfedgeMesh mesh = make_tetrahedron();
    Ray ray;
    ray.direction = Vector3::Zero();
    CHECK_THROWS_AS(pick_face(mesh, mesh.positions(), ray), InvalidArgument);
    ray.direction = Vector3(0, 0, std::numeric_limits<double>::quiet_NaN());
    CHECK_THROWS_AS(pick_face(mesh, mesh.positions(), ray), InvalidArgument);
    ray.direction = Vector3(0, 0, 1);
    CHECK_THROWS_AS(pick_face(mesh, std::vector<Point>(2, Point::Zero()), ray), InvalidArgument);
    CHECK_THROWS_AS(pick_triangle({{0, 1, 9}}, {}, mesh.positions(), ray), InvalidArgument);
    CHECK_THROWS_AS(pick_triangle({{0, 1, 2}}, {1, 1}, mesh.positions(), ray), InvalidArgument);
}
