// Topological operators: collapse, flip, edge split, face split, garbage collection. Each
// test checks the counts the operator promises and calls validate() after every step.
#include <random>

#include "core/algorithms/generators.h"
#include "core/algorithms/mesh_stats.h"
#include "core/errors.h"
#include "core/geometry.h"
#include "test_helpers.h"

using namespace trilab;

namespace {
Edge some_interior_edge(const HalfedgeMesh& m) {
    for (Edge e : m.edges())
        if (!m.is_boundary(e)) return e;
    return Edge();
}
Edge some_boundary_edge(const HalfedgeMesh& m) {
    for (Edge e : m.edges())
        if (m.is_boundary(e)) return e;
    return Edge();
}
}  // namespace

TEST_CASE("flip keeps counts and replaces the edge by the other diagonal", "[topology]") {
    HalfedgeMesh m = make_icosphere(3);
    const auto nv = m.n_vertices(), ne = m.n_edges(), nf = m.n_faces();
    Edge e = some_interior_edge(m);
    const Halfedge h = HalfedgeMesh::halfedge(e, 0);
    const Vertex a = m.from_vertex(h), b = m.to_vertex(h);
    const Vertex c = m.to_vertex(m.next(h)), d = m.to_vertex(m.next(HalfedgeMesh::twin(h)));
    REQUIRE(m.is_flip_ok(e));
    m.flip(e);
    REQUIRE_VALID(m);
    REQUIRE(m.n_vertices() == nv);
    REQUIRE(m.n_edges() == ne);
    REQUIRE(m.n_faces() == nf);
    REQUIRE_FALSE(m.find_halfedge(a, b).is_valid());
    REQUIRE(m.find_halfedge(c, d).is_valid());
    // Flipping back is legal and restores the connection.
    REQUIRE(m.is_flip_ok(e));
    m.flip(e);
    REQUIRE_VALID(m);
    REQUIRE(m.find_halfedge(a, b).is_valid());
}

TEST_CASE("flip is refused on boundary edges and where the new edge exists", "[topology]") {
    HalfedgeMesh grid = make_grid(2);
    Edge b = some_boundary_edge(grid);
    REQUIRE_FALSE(grid.is_flip_ok(b));
    REQUIRE_THROWS_AS(grid.flip(b), TopologyError);
    REQUIRE_VALID(grid);
    // In a tetrahedron every flip would duplicate an existing edge.
    HalfedgeMesh tet = make_tetrahedron();
    for (Edge e : tet.edges()) REQUIRE_FALSE(tet.is_flip_ok(e));
}

TEST_CASE("edge split adds one vertex, three edges and two faces inside", "[topology]") {
    HalfedgeMesh m = make_icosphere(2);
    const auto nv = m.n_vertices(), ne = m.n_edges(), nf = m.n_faces();
    const double area = surface_area(m);
    Edge e = some_interior_edge(m);
    const Point mid = 0.5 * (m.position(m.vertex(e, 0)) + m.position(m.vertex(e, 1)));
    Vertex v = m.split(e, mid);
    REQUIRE_VALID(m);
    REQUIRE(m.n_vertices() == nv + 1);
    REQUIRE(m.n_edges() == ne + 3);
    REQUIRE(m.n_faces() == nf + 2);
    REQUIRE(m.valence(v) == 4);
    REQUIRE(m.to_vertex(HalfedgeMesh::halfedge(e, 0)) == v);
    REQUIRE(surface_area(m) == Approx(area));  // a midpoint split keeps the surface
}

TEST_CASE("edge split on the boundary keeps the boundary", "[topology]") {
    HalfedgeMesh m = make_grid(3);
    const auto nv = m.n_vertices(), ne = m.n_edges(), nf = m.n_faces();
    Edge e = some_boundary_edge(m);
    Vertex v = m.split(e, 0.5 * (m.position(m.vertex(e, 0)) + m.position(m.vertex(e, 1))));
    REQUIRE_VALID(m);
    REQUIRE(m.n_vertices() == nv + 1);
    REQUIRE(m.n_edges() == ne + 2);
    REQUIRE(m.n_faces() == nf + 1);
    REQUIRE(m.is_boundary(v));
    REQUIRE(m.valence(v) == 3);
    REQUIRE(count_boundary_loops(m) == 1);
}

TEST_CASE("face split 1-to-3", "[topology]") {
    HalfedgeMesh m = make_icosahedron();
    const auto nv = m.n_vertices(), ne = m.n_edges(), nf = m.n_faces();
    Face f(0);
    Vertex v = m.split(f, face_centroid(m, f));
    REQUIRE_VALID(m);
    REQUIRE(m.n_vertices() == nv + 1);
    REQUIRE(m.n_edges() == ne + 3);
    REQUIRE(m.n_faces() == nf + 2);
    REQUIRE(m.valence(v) == 3);
    REQUIRE(compute_stats(m).euler == 2);
}

TEST_CASE("collapse of an interior edge removes a vertex, three edges and two faces",
          "[topology]") {
    HalfedgeMesh m = make_icosphere(3);
    const auto nv = m.n_vertices(), ne = m.n_edges(), nf = m.n_faces();
    Halfedge h = HalfedgeMesh::halfedge(some_interior_edge(m), 0);
    const Vertex kept = m.to_vertex(h), removed = m.from_vertex(h);
    REQUIRE(m.is_collapse_ok(h));
    m.collapse(h);
    REQUIRE_VALID(m);
    REQUIRE(m.n_vertices() == nv - 1);
    REQUIRE(m.n_edges() == ne - 3);
    REQUIRE(m.n_faces() == nf - 2);
    REQUIRE(m.is_deleted(removed));
    REQUIRE_FALSE(m.is_deleted(kept));
    REQUIRE(compute_stats(m).euler == 2);
}

TEST_CASE("collapse of a boundary edge keeps one boundary loop", "[topology]") {
    HalfedgeMesh m = make_grid(4);
    const auto nv = m.n_vertices(), ne = m.n_edges(), nf = m.n_faces();
    Edge e = some_boundary_edge(m);
    Halfedge h = HalfedgeMesh::halfedge(e, 0);
    if (!m.is_collapse_ok(h)) h = HalfedgeMesh::twin(h);
    REQUIRE(m.is_collapse_ok(h));
    m.collapse(h);
    REQUIRE_VALID(m);
    REQUIRE(m.n_vertices() == nv - 1);
    REQUIRE(m.n_edges() == ne - 2);
    REQUIRE(m.n_faces() == nf - 1);
    REQUIRE(count_boundary_loops(m) == 1);
}

TEST_CASE("the link condition refuses collapses that break the manifold", "[topology]") {
    // Tetrahedron: every collapse would leave a doubly covered triangle.
    HalfedgeMesh tet = make_tetrahedron();
    for (Halfedge h : tet.halfedges()) REQUIRE_FALSE(tet.is_collapse_ok(h));
    REQUIRE_THROWS_AS(tet.collapse(Halfedge(0)), TopologyError);
    REQUIRE_VALID(tet);
    // A single triangle cannot lose an edge.
    HalfedgeMesh tri = make_grid(1);
    HalfedgeMesh one;
    one.add_vertex(Point(0, 0, 0));
    for (Halfedge h : tri.halfedges()) {
        if (tri.is_boundary(h) && tri.is_boundary(HalfedgeMesh::twin(h))) continue;
    }
    // Interior edge between two boundary vertices (the grid's diagonal in a 1x1 grid).
    for (Edge e : tri.edges())
        if (!tri.is_boundary(e)) {
            REQUIRE_FALSE(tri.is_collapse_ok(HalfedgeMesh::halfedge(e, 0)));
            REQUIRE_FALSE(tri.is_collapse_ok(HalfedgeMesh::halfedge(e, 1)));
        }
    // Octahedron: collapsing leaves valence-3 vertices, legal once, then some are refused.
    HalfedgeMesh octa = make_octahedron();
    REQUIRE(octa.is_collapse_ok(Halfedge(0)));
    octa.collapse(Halfedge(0));
    REQUIRE_VALID(octa);
}

TEST_CASE("garbage collection compacts storage and reports the remapping", "[topology]") {
    HalfedgeMesh m = make_icosphere(3);
    auto tag = m.add_vertex_property<int>("v:tag");
    for (Vertex v : m.vertices()) tag[v] = int(v.idx());
    int collapsed = 0;
    for (Edge e : m.edges()) {
        if (collapsed == 20) break;
        Halfedge h = HalfedgeMesh::halfedge(e, 0);
        if (m.is_deleted(e) || !m.is_collapse_ok(h)) continue;
        m.collapse(h);
        ++collapsed;
    }
    REQUIRE(collapsed == 20);
    REQUIRE(m.has_garbage());
    const std::size_t nv = m.n_vertices(), ne = m.n_edges(), nf = m.n_faces();
    std::vector<Point> live_positions;
    for (Vertex v : m.vertices()) live_positions.push_back(m.position(v));
    IndexRemap remap = m.garbage_collection();
    REQUIRE_VALID(m);
    REQUIRE_FALSE(m.has_garbage());
    REQUIRE(m.vertices_size() == nv);
    REQUIRE(m.edges_size() == ne);
    REQUIRE(m.faces_size() == nf);
    // Attributes moved with their vertices, and the remap says where.
    tag = m.get_vertex_property<int>("v:tag");
    for (Index old = 0; old < remap.vertices.size(); ++old) {
        if (remap.vertices[old] == kInvalidIndex) continue;
        REQUIRE(tag[Vertex(remap.vertices[old])] == int(old));
    }
    std::size_t i = 0;
    for (Vertex v : m.vertices()) REQUIRE(m.position(v) == live_positions[i++]);
    REQUIRE(compute_stats(m).euler == 2);
}

TEST_CASE("random sequences of operators keep the mesh valid", "[topology][stress]") {
    const std::uint32_t seed = GENERATE(1u, 2u, 3u);
    std::mt19937 rng(seed);
    HalfedgeMesh m =
        GENERATE(as<HalfedgeMesh>{}, make_icosphere(3), make_grid(6), make_cylinder(10, 4));
    const long long euler = compute_stats(m).euler;
    for (int step = 0; step < 400; ++step) {
        const int op = int(rng() % 4);
        Edge e(Index(rng() % m.edges_size()));
        if (m.is_deleted(e)) continue;
        const Point mid = 0.5 * (m.position(m.vertex(e, 0)) + m.position(m.vertex(e, 1)));
        if (op == 0 && m.is_flip_ok(e)) m.flip(e);
        if (op == 1 && m.n_faces() < 3000) m.split(e, mid);
        if (op == 2) {
            Halfedge h = HalfedgeMesh::halfedge(e, rng() % 2);
            if (m.is_collapse_ok(h)) m.collapse(h);
        }
        if (op == 3 && m.n_faces() < 3000) {
            Face f(Index(rng() % m.faces_size()));
            if (!m.is_deleted(f)) m.split(f, mid);
        }
        INFO("seed " << seed << " step " << step << " op " << op);
        REQUIRE_VALID(m);
        if (step % 50 == 49) m.garbage_collection();
    }
    REQUIRE(compute_stats(m).euler == euler);
}
