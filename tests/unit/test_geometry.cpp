// Geometry helpers: normals, areas, bounding box, volume (1.15), edge lengths, cotangents.
#include <cmath>

#include "core/algorithms/generators.h"
#include "core/algorithms/mesh_stats.h"
#include "core/geometry.h"
#include "core/mesh_builder.h"
#include "test_helpers.h"

using namespace trilab;

TEST_CASE("unit cube: area 6, volume 1, bounding box", "[geometry]") {
    HalfedgeMesh cube = make_cube();
    REQUIRE(surface_area(cube) == Approx(6.0));
    REQUIRE(volume(cube) == Approx(1.0));
    BoundingBox box = bounding_box(cube);
    REQUIRE(box.min == Point(0, 0, 0));
    REQUIRE(box.max == Point(1, 1, 1));
    REQUIRE(box.diagonal() == Approx(std::sqrt(3.0)));
    REQUIRE(is_closed(cube));
}

TEST_CASE("volume is translation invariant and changes sign with orientation", "[geometry]") {
    HalfedgeMesh s = make_icosphere(8);
    const double v0 = volume(s);
    REQUIRE(v0 == Approx(4.0 / 3.0 * M_PI).epsilon(0.02));
    for (Vertex v : s.vertices()) s.position(v) += Point(3, -2, 5);
    REQUIRE(volume(s) == Approx(v0).epsilon(1e-12));
    for (Vertex v : s.vertices()) s.position(v) *= 2.0;
    REQUIRE(volume(s) == Approx(8 * v0).epsilon(1e-12));
    // Reversed orientation gives the negative volume.
    PolygonSoup soup = to_soup(make_tetrahedron());
    for (std::size_t f = 0; f < soup.n_faces(); ++f)
        std::swap(soup.corners[soup.face_offsets[f]], soup.corners[soup.face_offsets[f] + 1]);
    LoadReport r;
    HalfedgeMesh flipped = build_mesh(soup, r);
    REQUIRE(volume(flipped) == Approx(-volume(make_tetrahedron())));
}

TEST_CASE("vertex normals of a sphere point outwards", "[geometry]") {
    HalfedgeMesh s = make_icosphere(6);
    compute_vertex_normals(s);
    auto n = s.get_vertex_property<Vector3>("v:normal");
    REQUIRE(n);
    for (Vertex v : s.vertices()) {
        REQUIRE(n[v].norm() == Approx(1.0));
        REQUIRE(n[v].dot(s.position(v).normalized()) > 0.99);
    }
    for (Face f : s.faces()) REQUIRE(face_normal(s, f).dot(face_centroid(s, f)) > 0);
}

TEST_CASE("cotangent weights", "[geometry]") {
    // Two equilateral triangles: each opposite angle is 60 degrees.
    PolygonSoup soup;
    const double h = std::sqrt(3.0) / 2;
    soup.positions = {{0, 0, 0}, {1, 0, 0}, {0.5, h, 0}, {0.5, -h, 0}};
    soup.add_face({0, 1, 2});
    soup.add_face({1, 0, 3});
    LoadReport r;
    HalfedgeMesh m = build_mesh(soup, r);
    const Edge shared = m.find_edge(Vertex(0), Vertex(1));
    REQUIRE(cotangent_weight(m, shared) == Approx(1.0 / std::sqrt(3.0)));
    REQUIRE(edge_length(m, shared) == Approx(1.0));
    // A boundary edge only has one angle.
    const Edge outer = m.find_edge(Vertex(0), Vertex(2));
    REQUIRE(cotangent_weight(m, outer) == Approx(0.5 / std::sqrt(3.0)));
    // An obtuse angle gives a negative cotangent.
    PolygonSoup flat;
    flat.positions = {{0, 0, 0}, {1, 0, 0}, {0.5, 0.1, 0}};
    flat.add_face({0, 1, 2});
    HalfedgeMesh o = build_mesh(flat, r);
    REQUIRE(cotangent_opposite(o, o.find_halfedge(Vertex(0), Vertex(1))) < 0);
}

TEST_CASE("degenerate triangles give zero normals and cotangents, never NaN", "[geometry]") {
    PolygonSoup soup;
    soup.positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
    soup.add_face({0, 1, 2});
    LoadReport r;
    HalfedgeMesh m = build_mesh(soup, r);
    REQUIRE_VALID(m);
    REQUIRE(face_normal(m, Face(0)) == Vector3::Zero());
    REQUIRE(face_area(m, Face(0)) == 0.0);
    for (Edge e : m.edges()) REQUIRE(std::isfinite(cotangent_weight(m, e)));
    for (Vertex v : m.vertices()) REQUIRE(vertex_normal(m, v).allFinite());
}

TEST_CASE("mean edge length", "[geometry]") {
    REQUIRE(mean_edge_length(make_grid(1)) == Approx((4 + std::sqrt(2.0)) / 5));
}

TEST_CASE("area_and_volume is the face-by-face sums of face_area and centroid . area vector",
          "[geometry]") {
    HalfedgeMesh mesh = GENERATE(make_icosphere(3), make_torus(24, 12, 1.0, 0.3), make_grid(5),
                                 make_noisy_sphere(4, 0.05, 7));
    double area = 0, volume6 = 0;
    for (Face f : mesh.faces()) {
        area += face_area(mesh, f);
        volume6 += face_centroid(mesh, f).dot(face_area_vector(mesh, f));
    }
    // The same sums in the same order: equal to the bit, whichever sums are asked for.
    const AreaVolume both = area_and_volume(mesh, true, true);
    CHECK(both.area == area);
    CHECK(both.volume == volume6 / 6.0);
    CHECK(area_and_volume(mesh, true, false).area == area);
    CHECK(area_and_volume(mesh, true, false).volume == 0);
    CHECK(area_and_volume(mesh, false, true).volume == volume6 / 6.0);
    CHECK(surface_area(mesh) == area);
    CHECK(volume(mesh) == volume6 / 6.0);
    // compute_stats() reports the same figures (the volume only for a closed mesh).
    const MeshStats stats = compute_stats(mesh);
    CHECK(stats.area == area);
    if (is_closed(mesh)) CHECK(*stats.volume == volume6 / 6.0);
}
