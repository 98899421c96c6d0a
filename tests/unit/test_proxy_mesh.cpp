// make_proxy_mesh: vertex clustering for drawing while moving (core/algorithms/proxy_mesh.h).
#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <map>
#include <set>

#include "core/algorithms/generators.h"
#include "core/algorithms/proxy_mesh.h"
#include "core/algorithms/subdivision.h"
#include "core/errors.h"
#include "core/geometry.h"
#include "core/io/mesh_io.h"
#include "core/parallel.h"
#include "core/progress.h"
#include "tests/unit/test_helpers.h"

using namespace trilab;

namespace {

/// `mesh` Loop-subdivided once.
HalfedgeMesh loop_once(const HalfedgeMesh& mesh) {
    SubdivisionOptions options;
    options.iterations = 1;
    options.keep_levels = false;
    options.morph = false;
    NullProgress progress;
    return subdivide(mesh, options, progress).levels.back().mesh;
}

/// Checks what every proxy promises against its mesh.
void check_proxy(const HalfedgeMesh& mesh, const ProxyMesh& p, std::size_t target) {
    REQUIRE(p.positions.size() == p.representative.size());
    CHECK(p.triangles.size() <= target);
    CHECK(p.error_bound == Approx(p.cell_size * std::sqrt(3.0)));
    // Every mesh vertex lies within the bound of its cluster's proxy vertex: its cell is the
    // representative's cell, whose proxy vertex is the cell's mean.
    const double cell = p.cell_size;
    BoundingBox box;
    for (Vertex v : mesh.vertices()) box.extend(mesh.position(v));
    auto cell_of = [&](const Point& x) {
        const Vector3 q = (x - box.min) / cell;
        return std::array<long long, 3>{(long long)q.x(), (long long)q.y(), (long long)q.z()};
    };
    std::map<std::array<long long, 3>, std::size_t> proxy_of_cell;
    for (std::size_t i = 0; i < p.positions.size(); ++i) {
        const Vertex r(p.representative[i]);
        REQUIRE(mesh.is_valid(r));
        CHECK((mesh.position(r) - p.positions[i]).norm() <= p.error_bound);
        proxy_of_cell[cell_of(mesh.position(r))] = i;
    }
    double worst = 0;
    for (Vertex v : mesh.vertices()) {
        const auto it = proxy_of_cell.find(cell_of(mesh.position(v)));
        REQUIRE(it != proxy_of_cell.end());
        worst = std::max(worst, (mesh.position(v) - p.positions[it->second]).norm());
    }
    CHECK(worst <= p.error_bound);
    // No degenerate triangle, none twice, every index in range.
    std::set<std::array<Index, 3>> seen;
    for (const auto& t : p.triangles) {
        CHECK(t[0] != t[1]);
        CHECK(t[1] != t[2]);
        CHECK(t[0] != t[2]);
        for (Index i : t) REQUIRE(i < p.positions.size());
        std::array<Index, 3> k = t;
        std::rotate(k.begin(), std::min_element(k.begin(), k.end()), k.end());
        CHECK(seen.insert(k).second);
    }
}

}  // namespace

TEST_CASE("make_proxy_mesh keeps every vertex within its bound and under the target",
          "[proxy_mesh]") {
    const unsigned frequency = GENERATE(8u, 40u);
    const std::size_t target = GENERATE(std::size_t(100), std::size_t(2000));
    const HalfedgeMesh sphere = make_icosphere(frequency);
    ProxyMeshOptions options;
    options.target_triangles = target;
    const ProxyMesh p = make_proxy_mesh(sphere, options);
    INFO("frequency " << frequency << ", target " << target << ", faces " << sphere.n_faces()
                      << ", proxy " << p.triangles.size() << " triangles, " << p.passes
                      << " passes");
    check_proxy(sphere, p, target);
    // A sphere's proxy is a closed-looking surface of a useful size, not a handful of faces.
    CHECK(p.triangles.size() >= std::min<std::size_t>(target / 4, sphere.n_faces() / 4));
}

TEST_CASE("make_proxy_mesh is deterministic, whatever the thread count", "[proxy_mesh]") {
    const HalfedgeMesh mesh = make_noisy_sphere(60, 0.02, 7);  // 36,000 faces: several chunks
    ProxyMeshOptions options;
    options.target_triangles = 3000;
    const int threads = thread_count();
    set_thread_count(1);
    const ProxyMesh a = make_proxy_mesh(mesh, options);
    set_thread_count(5);
    const ProxyMesh b = make_proxy_mesh(mesh, options), c = make_proxy_mesh(mesh, options);
    set_thread_count(threads);
    CHECK(a.triangles == b.triangles);
    CHECK(b.triangles == c.triangles);
    CHECK(a.positions == b.positions);
    CHECK(a.representative == b.representative);
    CHECK(a.error_bound == b.error_bound);
    check_proxy(mesh, a, 3000);
}

TEST_CASE("make_proxy_mesh on the subdivided bunny", "[proxy_mesh]") {
    const std::string path = test::shared_mesh("stanford-bunny.obj");
    SKIP_IF_MISSING(path);
    const HalfedgeMesh mesh = loop_once(read_mesh(path).mesh);  // 278k faces
    ProxyMeshOptions proxy_options;
    proxy_options.target_triangles = 20000;
    const ProxyMesh p = make_proxy_mesh(mesh, proxy_options);
    INFO(mesh.n_faces() << " faces -> " << p.triangles.size() << " in " << p.passes << " passes");
    check_proxy(mesh, p, 20000);
    CHECK(p.triangles.size() >= 10000);
}

TEST_CASE("make_proxy_mesh skips deleted elements and handles edge cases", "[proxy_mesh]") {
    SECTION("a mesh with garbage") {
        HalfedgeMesh mesh = make_icosphere(10);
        for (Halfedge h : mesh.halfedges())
            if (mesh.is_collapse_ok(h)) {
                mesh.collapse(h);
                break;
            }
        REQUIRE(mesh.has_garbage());
        const ProxyMesh p = make_proxy_mesh(mesh, {});
        check_proxy(mesh, p, 200000);
        for (Index r : p.representative) CHECK_FALSE(mesh.is_deleted(Vertex(r)));
    }
    SECTION("an empty mesh gives an empty proxy") {
        const ProxyMesh p = make_proxy_mesh(HalfedgeMesh(), {});
        CHECK(p.positions.empty());
        CHECK(p.triangles.empty());
    }
    SECTION("a single point") {
        HalfedgeMesh mesh;
        mesh.add_vertex(Point(1, 2, 3));
        const ProxyMesh p = make_proxy_mesh(mesh, {});
        REQUIRE(p.positions.size() == 1);
        CHECK(p.positions[0] == Point(1, 2, 3));
        CHECK(p.triangles.empty());
    }
    SECTION("a target outside the range is refused") {
        ProxyMeshOptions options;
        options.target_triangles = 3;
        CHECK_THROWS_AS(make_proxy_mesh(make_cube(), options), InvalidArgument);
    }
}

namespace {

/// The two proxies are the same, field by field.
void check_same_proxy(const ProxyMesh& a, const ProxyMesh& b) {
    CHECK(a.positions == b.positions);
    CHECK(a.triangles == b.triangles);
    CHECK(a.representative == b.representative);
    CHECK(a.cell_size == b.cell_size);
    CHECK(a.passes == b.passes);
}

/// The soup of `mesh`, built back into a mesh: the soup's proxy against the built mesh's.
void check_soup_proxy_matches(const HalfedgeMesh& mesh, std::size_t target) {
    const PolygonSoup soup = to_soup(mesh);
    LoadReport report;
    const HalfedgeMesh built = build_mesh(soup, report);
    // A clean manifold soup: the soup's vertices and triangles, in order (isolated vertices
    // are kept as they are).
    REQUIRE(report.vertex_copies_added == 0);
    REQUIRE(report.detached_faces == 0);
    REQUIRE(report.degenerate_faces_dropped == 0);
    ProxyMeshOptions options;
    options.target_triangles = target;
    const ProxyMesh from_soup = make_soup_proxy_mesh(soup, options);
    check_same_proxy(from_soup, make_proxy_mesh(built, options));
    check_proxy(built, from_soup, target);
}

}  // namespace

TEST_CASE("make_soup_proxy_mesh equals make_proxy_mesh of the mesh built from the soup",
          "[proxy_mesh]") {
    SECTION("a noisy sphere") {
        check_soup_proxy_matches(make_noisy_sphere(40, 0.02, 7), 2000);
    }
    SECTION("an open grid") {
        check_soup_proxy_matches(make_grid(120), 1000);
    }
    SECTION("the subdivided bunny") {
        const std::string path = test::shared_mesh("stanford-bunny.obj");
        SKIP_IF_MISSING(path);
        check_soup_proxy_matches(loop_once(read_mesh(path).mesh), 20000);
    }
}

TEST_CASE("make_soup_proxy_mesh fans polygons and refuses indices out of range", "[proxy_mesh]") {
    // A grid of quads: each quad is clustered as two triangles, as its triangulated mesh.
    PolygonSoup quads;
    const int n = 60;
    for (int y = 0; y <= n; ++y)
        for (int x = 0; x <= n; ++x) quads.positions.emplace_back(x, y, 0.01 * ((x * y) % 7));
    PolygonSoup tris = quads;
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            const Index a = Index(y * (n + 1) + x), b = a + 1, c = b + Index(n + 1),
                        d = a + Index(n + 1);
            quads.add_face({a, b, c, d});
            tris.add_face({a, b, c});
            tris.add_face({a, c, d});
        }
    quads.add_face({0, 1});  // fewer than three corners: nothing
    ProxyMeshOptions options;
    options.target_triangles = 500;
    check_same_proxy(make_soup_proxy_mesh(quads, options), make_soup_proxy_mesh(tris, options));
    tris.add_face({0, 1, Index(tris.positions.size())});
    CHECK_THROWS_AS(make_soup_proxy_mesh(tris, options), InvalidArgument);
}

TEST_CASE("read_mesh shows the soup only once the file is read and checked", "[proxy_mesh][io]") {
    test::TempDir dir;
    const HalfedgeMesh sphere = make_icosphere(8);
    const std::string good = dir.path("sphere.ply");
    write_mesh(sphere, good);
    std::size_t calls = 0;
    ProxyMesh seen;
    const LoadedMesh loaded = read_mesh(good, [&](const PolygonSoup& soup) {
        ++calls;
        CHECK(soup.positions.size() == sphere.n_vertices());
        CHECK(soup.n_faces() == sphere.n_faces());
        ProxyMeshOptions options;
        options.target_triangles = 100;
        seen = make_soup_proxy_mesh(soup, options);
    });
    CHECK(calls == 1);
    ProxyMeshOptions options;
    options.target_triangles = 100;
    check_same_proxy(seen, make_proxy_mesh(loaded.mesh, options));
    // A face with a vertex index out of range: the read fails and the soup is never shown.
    const std::string bad = dir.path("bad.ply");
    {
        std::ofstream out(bad);
        out << "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
               "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
               "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n";
    }
    calls = 0;
    CHECK_THROWS_AS(read_mesh(bad, [&](const PolygonSoup&) { ++calls; }), IoError);
    CHECK(calls == 0);
    // A truncated binary file: the same.
    const std::string cut = dir.path("cut.ply");
    {
        std::ifstream in(good, std::ios::binary);
        std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() - 7);
    }
    CHECK_THROWS_AS(read_mesh(cut, [&](const PolygonSoup&) { ++calls; }), IoError);
    CHECK(calls == 0);
}

TEST_CASE("moved_proxy_mesh keeps the clusters and measures how far the moved vertices are",
          "[proxy_mesh]") {
    const HalfedgeMesh mesh = make_noisy_sphere(30, 0.03, 4);
    ProxyMeshOptions options;
    options.target_triangles = 800;
    const ProxyMesh plain = make_proxy_mesh(mesh, options);
    CHECK(plain.cluster_of.empty());
    CHECK_THROWS_WITH(moved_proxy_mesh(plain, mesh),
                      Catch::Contains("keep_clusters") && Catch::Contains("moved_proxy_mesh"));
    options.keep_clusters = true;
    const ProxyMesh p = make_proxy_mesh(mesh, options);
    REQUIRE(p.cluster_of.size() == mesh.vertices_size());
    CHECK(p.triangles == plain.triangles);
    CHECK(p.positions == plain.positions);
    // Not moved: the same proxy, and the measured bound within the grid's.
    const ProxyMesh same = moved_proxy_mesh(p, mesh);
    CHECK(same.positions == p.positions);
    CHECK(same.triangles == p.triangles);
    CHECK(same.representative == p.representative);
    CHECK(same.error_bound <= p.error_bound);
    // Moved (smoothed, then stretched): every vertex within the bound of its cluster's mean,
    // one at it; the means are the clusters' means.
    HalfedgeMesh moved = mesh;
    std::vector<Point> x = mesh.positions();
    for (Point& q : x) q = Point(2.0 * q.x(), q.y(), 0.5 * q.z());
    moved.set_positions(x);
    const ProxyMesh m = moved_proxy_mesh(p, moved);
    REQUIRE(m.positions.size() == p.positions.size());
    const std::vector<Point> means =
        test::cluster_means(moved, moved.positions(), p.cluster_of, p.positions.size());
    double worst = 0;
    for (std::size_t c = 0; c < means.size(); ++c)
        CHECK((m.positions[c] - means[c]).norm() < 1e-12);
    for (Vertex v : moved.vertices())
        worst = std::max(worst, (moved.position(v) - m.positions[p.cluster_of[v.idx()]]).norm());
    CHECK(worst == Approx(m.error_bound).epsilon(1e-12));
    CHECK(m.error_bound > p.error_bound * 0.5);  // stretched by 2: the clusters spread
    // Another vertex count: refused, saying so.
    CHECK_THROWS_WITH(moved_proxy_mesh(p, make_icosphere(2)), Catch::Contains("vertices"));
}
