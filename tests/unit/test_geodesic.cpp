// Heat-method geodesics: great circles on a unit sphere, Euclidean distance on a plane,
// edge-path bounds, solver reuse, unreached components, the traced path, bad input.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>

#include "core/algorithms/generators.h"
#include "core/algorithms/geodesic.h"
#include "core/errors.h"
#include "core/geometry.h"
#include "core/io/mesh_io.h"
#include "core/mesh_builder.h"
#include "core/validate.h"
#include "test_helpers.h"

using namespace trilab;

namespace {

double great_circle(const Point& a, const Point& b) {
    return std::atan2(a.normalized().cross(b.normalized()).norm(),
                      a.normalized().dot(b.normalized()));
}

}  // namespace

TEST_CASE("geodesic distances on a unit sphere are within 0.03 of great circles", "[geodesic]") {
    const HalfedgeMesh sphere = make_icosphere(40);  // 16,002 vertices
    REQUIRE(sphere.n_vertices() >= 10000);
    const HalfedgeMesh before = sphere;
    const Vertex source(0);
    GeodesicOptions options;
    options.mass = GENERATE(MassMatrix::Barycentric, MassMatrix::Voronoi);
    const std::vector<double> d = geodesic_distances(sphere, {source}, options);
    double worst = 0;
    for (Vertex v : sphere.vertices()) {
        REQUIRE(std::isfinite(d[v.idx()]));
        CHECK(d[v.idx()] >= 0);
        worst = std::max(worst, std::abs(d[v.idx()] - great_circle(sphere.position(source),
                                                                   sphere.position(v))));
    }
    std::printf("geodesic: icosphere(40), %s mass: worst error against great circles %.4f\n",
                mass_matrix_name(options.mass), worst);
    CHECK(worst < 0.03);
    CHECK(d[source.idx()] == 0.0);
    CHECK(validate(sphere).ok);
    CHECK(sphere.position(Vertex(5)) == before.position(Vertex(5)));
}

TEST_CASE("geodesic distances on a plane grid match the Euclidean distance", "[geodesic]") {
    const HalfedgeMesh grid = make_grid(60);
    // The vertex nearest the centre.
    Vertex centre;
    double best = 1e9;
    for (Vertex v : grid.vertices()) {
        const double r = (grid.position(v) - Point(0.5, 0.5, 0)).norm();
        if (r < best) best = r, centre = v;
    }
    const std::vector<double> d = geodesic_distances(grid, {centre});
    const double h = 1.0 / 60;
    for (Vertex v : grid.vertices()) {
        const double exact = (grid.position(v) - grid.position(centre)).norm();
        INFO("vertex " << v.idx() << " exact " << exact << " heat " << d[v.idx()]);
        // Within a few percent away from the source (plus one edge length near it; the
        // Neumann boundary bends the level sets at the edge of the square).
        CHECK(std::abs(d[v.idx()] - exact) <= 0.05 * exact + 1.5 * h);
    }
    CHECK(d[centre.idx()] == 0.0);
}

TEST_CASE("geodesic distances lie between the straight line and the edge-path distance",
          "[geodesic]") {
    const HalfedgeMesh mesh =
        GENERATE(make_noisy_sphere(12, 0.05, 3), make_torus(48, 24, 1, 0.3), make_cylinder(32, 16));
    const std::vector<Vertex> sources = {Vertex(0), Vertex(Index(mesh.vertices_size() / 2))};
    const std::vector<double> d = geodesic_distances(mesh, sources);
    const std::vector<double> graph = edge_graph_distances(mesh, sources);
    const double h = mean_edge_length(mesh);
    for (Vertex v : mesh.vertices()) {
        double straight = 1e300;
        for (Vertex s : sources)
            straight = std::min(straight, (mesh.position(v) - mesh.position(s)).norm());
        INFO("vertex " << v.idx());
        REQUIRE(std::isfinite(d[v.idx()]));
        CHECK(d[v.idx()] >= 0);
        // The heat method's error is of the order of an edge length; the bounds hold with
        // that slack (the graph distance overestimates by up to ~8 % on these meshes).
        CHECK(d[v.idx()] <= graph[v.idx()] + 0.5 * h);
        CHECK(d[v.idx()] >= straight - 0.5 * h);
        CHECK(graph[v.idx()] >= straight - 1e-12);
    }
    for (Vertex s : sources) CHECK(d[s.idx()] == 0.0);
}

TEST_CASE("GeodesicSolver reuse gives the fresh result bit for bit", "[geodesic]") {
    const HalfedgeMesh sphere = make_icosphere(40);
    const auto t0 = std::chrono::steady_clock::now();
    const GeodesicSolver solver(sphere);
    const std::vector<double> first = solver.distances({Vertex(0)});
    const auto t1 = std::chrono::steady_clock::now();
    const std::vector<double> reused = solver.distances({Vertex(777)});
    const auto t2 = std::chrono::steady_clock::now();
    const std::vector<double> fresh = geodesic_distances(sphere, {Vertex(777)});
    const double ms_fresh = std::chrono::duration<double, std::milli>(t1 - t0).count();
    const double ms_reuse = std::chrono::duration<double, std::milli>(t2 - t1).count();
    std::printf("geodesic: icosphere(40) build+solve %.2f ms, reused solve %.2f ms (%.1fx)\n",
                ms_fresh, ms_reuse, ms_fresh / ms_reuse);
    REQUIRE(reused.size() == fresh.size());
    for (std::size_t i = 0; i < fresh.size(); ++i) REQUIRE(reused[i] == fresh[i]);
    CHECK(first[0] == 0.0);
    // The heat method is nearly symmetric: 0 -> 777 and 777 -> 0 agree closely.
    CHECK(std::abs(first[777] - reused[0]) < 0.005);
}

TEST_CASE("geodesic: components without a source are unreached (+infinity)", "[geodesic]") {
    // Two spheres side by side, one with the source.
    const HalfedgeMesh a = make_icosphere(8);
    const HalfedgeMesh b = make_icosphere(8);
    PolygonSoup soup;
    for (const HalfedgeMesh* m : {&a, &b}) {
        const Index base = Index(soup.positions.size());
        const double dx = m == &a ? 0.0 : 3.0;
        for (Vertex v : m->vertices()) soup.positions.push_back(m->position(v) + Point(dx, 0, 0));
        for (Face f : m->faces()) {
            const auto fv = m->face_vertices(f);
            soup.add_face({base + fv[0].idx(), base + fv[1].idx(), base + fv[2].idx()});
        }
    }
    LoadReport report;
    const HalfedgeMesh two = build_mesh(soup, report);
    const std::vector<double> d = geodesic_distances(two, {Vertex(0)});
    for (Vertex v : two.vertices()) {
        if (v.idx() < a.vertices_size())
            CHECK(std::isfinite(d[v.idx()]));
        else
            CHECK(std::isinf(d[v.idx()]));
    }
    CHECK(validate(two).ok);
}

TEST_CASE("geodesic_path descends from the target to the source on the surface", "[geodesic]") {
    const HalfedgeMesh sphere = make_icosphere(24);
    const Vertex source(0);
    // The vertex farthest from the pole but not antipodal (where the path is not unique).
    Vertex target;
    double best = 1e9;
    for (Vertex v : sphere.vertices()) {
        const double g = great_circle(sphere.position(source), sphere.position(v));
        if (std::abs(g - 2.0) < best) best = std::abs(g - 2.0), target = v;
    }
    const std::vector<double> d = geodesic_distances(sphere, {source});
    const std::vector<SurfacePoint> path = geodesic_path(sphere, d, target);
    REQUIRE(path.size() >= 2);
    CHECK(path.front().on_vertex());
    CHECK(path.front().a == target);
    CHECK(path.back().on_vertex());
    CHECK(path.back().a == source);
    double previous = 1e300;
    for (const SurfacePoint& p : path) {
        const double value =
            p.on_vertex() ? d[p.a.idx()] : (1 - p.t) * d[p.a.idx()] + p.t * d[p.b.idx()];
        CHECK(value < previous);
        previous = value;
        CHECK(std::abs(p.position.norm() - 1.0) < 0.01);  // on the surface of the unit sphere
        if (!p.on_vertex()) {
            CHECK(p.t > 0);
            CHECK(p.t < 1);
        }
    }
    const double exact = great_circle(sphere.position(source), sphere.position(target));
    const double length = path_length(path);
    const double graph = edge_graph_distances(sphere, {source})[target.idx()];
    INFO("path " << length << " great circle " << exact << " edge path " << graph);
    CHECK(length >= exact - 0.03);
    CHECK(length <= exact + 0.03);  // the edge path is far longer (zig-zag)
    CHECK(graph > length);
}

TEST_CASE("geodesic refuses bad sources and options, naming them", "[geodesic]") {
    HalfedgeMesh m = make_icosphere(4);
    CHECK_THROWS_WITH(geodesic_distances(m, {}), Catch::Contains("no source"));
    CHECK_THROWS_AS(geodesic_distances(m, {Vertex(Index(m.vertices_size()))}), InvalidArgument);
    CHECK_THROWS_WITH(
        geodesic_distances(m, {Vertex(Index(m.vertices_size() + 5))}),
        Catch::Contains(std::to_string(m.vertices_size() + 5)) && Catch::Contains("out of range"));
    CHECK_THROWS_WITH(edge_graph_distances(m, {}), Catch::Contains("no source"));
    GeodesicOptions bad;
    bad.time_factor = -1;
    CHECK_THROWS_WITH(GeodesicSolver(m, bad), Catch::Contains("time_factor"));
    bad = {};
    bad.mass = MassMatrix::Normalizer;
    CHECK_THROWS_WITH(GeodesicSolver(m, bad), Catch::Contains("mass"));
    const std::vector<double> d = geodesic_distances(m, {Vertex(0)});
    CHECK_THROWS_WITH(geodesic_path(m, std::vector<double>(3, 0.0), Vertex(1)),
                      Catch::Contains("distances"));
    CHECK_THROWS_WITH(geodesic_path(m, d, Vertex(Index(9999))), Catch::Contains("9999"));
    // A deleted vertex (after a collapse).
    for (Halfedge h : m.halfedges())
        if (m.is_collapse_ok(h)) {
            m.collapse(h);
            break;
        }
    Vertex deleted;
    for (Index i = 0; i < m.vertices_size(); ++i)
        if (m.is_deleted(Vertex(i))) deleted = Vertex(i);
    REQUIRE(deleted.is_valid());
    CHECK_THROWS_WITH(geodesic_distances(m, {deleted}),
                      Catch::Contains(std::to_string(deleted.idx())) && Catch::Contains("deleted"));
    // The mesh with garbage still works from a live vertex.
    Vertex live = *m.vertices().begin();
    const std::vector<double> dg = geodesic_distances(m, {live});
    CHECK(std::isinf(dg[deleted.idx()]));
    CHECK(validate(m).ok);
}

TEST_CASE("a per-vertex distance survives a PLY round trip as property `distance`",
          "[geodesic][ply]") {
    HalfedgeMesh m = make_icosphere(6);
    const std::vector<double> d = geodesic_distances(m, {Vertex(3)});
    auto p = m.vertex_property<double>("v:distance");
    for (Vertex v : m.vertices()) p[v] = d[v.idx()];
    for (const bool ascii : {false, true}) {
        WriteOptions o;
        o.ascii = ascii;
        const std::string bytes = write_mesh_bytes(m, "g.ply", o);
        REQUIRE(bytes.find("property double distance") != std::string::npos);
        const LoadedMesh back = read_ply_bytes(bytes, "g.ply");
        const auto q = back.mesh.get_vertex_property<double>("v:distance");
        REQUIRE(q);
        for (Vertex v : m.vertices()) CHECK(q[v] == d[v.idx()]);
        CHECK(validate(back.mesh).ok);
    }
    // Not finite: refused when writing, naming the vertex.
    p[Vertex(7)] = std::numeric_limits<double>::infinity();
    CHECK_THROWS_WITH(write_mesh_bytes(m, "g.ply"),
                      Catch::Contains("vertex 7") && Catch::Contains("distance"));
}
