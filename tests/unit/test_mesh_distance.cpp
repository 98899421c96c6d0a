// Mesh distance: closest points on triangles, zero for equal meshes, exact offsets for
// translated planes, scaled spheres, symmetry, determinism, bad input.
#include <cmath>

#include "core/algorithms/generators.h"
#include "core/algorithms/mesh_distance.h"
#include "core/errors.h"
#include "test_helpers.h"

using namespace trilab;

TEST_CASE("closest_point_on_triangle covers its Voronoi regions", "[distance]") {
    const Point a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
    CHECK((closest_point_on_triangle(Point(0.2, 0.2, 3), a, b, c) - Point(0.2, 0.2, 0)).norm() <
          1e-15);
    CHECK(closest_point_on_triangle(Point(-1, -1, 0), a, b, c) == a);
    CHECK(closest_point_on_triangle(Point(2, -1, 1), a, b, c) == b);
    CHECK(closest_point_on_triangle(Point(-1, 2, 0), a, b, c) == c);
    CHECK((closest_point_on_triangle(Point(0.5, -1, 0), a, b, c) - Point(0.5, 0, 0)).norm() <
          1e-15);
    CHECK((closest_point_on_triangle(Point(1, 1, 0), a, b, c) - Point(0.5, 0.5, 0)).norm() < 1e-15);
    // Degenerate: all on a line.
    CHECK((closest_point_on_triangle(Point(0.5, 1, 0), a, b, Point(2, 0, 0)) - Point(0.5, 0, 0))
              .norm() < 1e-15);
}

TEST_CASE("mesh_distance is zero between equal meshes", "[distance]") {
    const HalfedgeMesh m = make_noisy_sphere(6, 0.1, 1);
    const MeshDistance d = mesh_distance(m, m, {5000});
    CHECK(d.hausdorff < 1e-12);
    CHECK(d.rms < 1e-12);
    CHECK(d.samples >= 2 * 5000);
    CHECK(d.diagonal > 0);
}

TEST_CASE("mesh_distance measures a translated grid exactly", "[distance]") {
    const HalfedgeMesh a = make_grid(8);
    HalfedgeMesh b = a;
    for (Vertex v : b.vertices()) b.position(v).z() += 0.25;
    const MeshDistance d = mesh_distance(a, b, {4000});
    CHECK(d.hausdorff == Approx(0.25));
    CHECK(d.rms == Approx(0.25));
    CHECK(d.a_to_b_max == Approx(0.25));
    CHECK(d.b_to_a_rms == Approx(0.25));
    // Shifting sideways: the overhanging strip is sqrt(0.25^2 + 0.1^2) away at most.
    for (Vertex v : b.vertices()) b.position(v).x() += 0.1;
    const MeshDistance s = mesh_distance(a, b, {4000});
    CHECK(s.hausdorff == Approx(std::sqrt(0.25 * 0.25 + 0.1 * 0.1)));
    CHECK(s.rms > 0.25);
    CHECK(s.rms < s.hausdorff);
}

TEST_CASE("mesh_distance of nested spheres is their radius difference, both ways", "[distance]") {
    const HalfedgeMesh a = make_icosphere(16);
    HalfedgeMesh b = a;
    for (Vertex v : b.vertices()) b.position(v) *= 1.2;
    const MeshDistance d = mesh_distance(a, b, {20000});
    // Vertices are on the spheres; faces sag inwards by at most ~0.4 % of the radius.
    CHECK(d.hausdorff == Approx(0.2).epsilon(0.02));
    CHECK(d.rms == Approx(0.2).epsilon(0.02));
    const MeshDistance e = mesh_distance(b, a, {20000});
    CHECK(e.hausdorff == Approx(d.hausdorff).epsilon(0.02));
    // Deterministic.
    const MeshDistance again = mesh_distance(a, b, {20000});
    CHECK(again.hausdorff == d.hausdorff);
    CHECK(again.rms == d.rms);
}

TEST_CASE("mesh_distance rejects meshes without faces", "[distance]") {
    HalfedgeMesh empty;
    empty.add_vertex(Point(0, 0, 0));
    CHECK_THROWS_AS(mesh_distance(empty, make_tetrahedron()), InvalidArgument);
    CHECK_THROWS_AS(mesh_distance(make_tetrahedron(), make_tetrahedron(), {0}), InvalidArgument);
}
