// Half-edge core: handles, properties, circulators, construction from soups, validate().
#include <set>
#include <utility>

#include "core/algorithms/generators.h"
#include "core/algorithms/mesh_stats.h"
#include "core/errors.h"
#include "core/geometry.h"
#include "core/mesh_builder.h"
#include "test_helpers.h"

using namespace trilab;

namespace {
/// build_mesh on the soup, checked against the consuming build_mesh (which must give the same
/// mesh, array for array, and the same report).
HalfedgeMesh build(const PolygonSoup& soup, LoadReport* report_out = nullptr) {
    LoadReport report;
    HalfedgeMesh m = build_mesh(soup, report);
    LoadReport consumed_report;
    PolygonSoup copy = soup;
    const HalfedgeMesh consumed = build_mesh(std::move(copy), consumed_report);
    CHECK(consumed.positions() == m.positions());
    CHECK(consumed.halfedge_to_array() == m.halfedge_to_array());
    CHECK(consumed.halfedge_next_array() == m.halfedge_next_array());
    CHECK(consumed.halfedge_prev_array() == m.halfedge_prev_array());
    CHECK(consumed.halfedge_face_array() == m.halfedge_face_array());
    CHECK(consumed.face_halfedge_array() == m.face_halfedge_array());
    CHECK(consumed.vertex_halfedge_array() == m.vertex_halfedge_array());
    CHECK(consumed_report.lines() == report.lines());
    CHECK(copy.positions.empty());  // moved into the mesh
    if (report_out) *report_out = report;
    return m;
}
PolygonSoup soup_of(std::vector<Point> pts, std::vector<std::vector<Index>> faces) {
    PolygonSoup s;
    s.positions = std::move(pts);
    for (auto& f : faces) s.add_face(f);
    return s;
}
}  // namespace

TEST_CASE("handles are distinct typed indices with an invalid value", "[core]") {
    Vertex v;
    REQUIRE_FALSE(v.is_valid());
    REQUIRE(Vertex(3).idx() == 3);
    REQUIRE(Vertex(3) == Vertex(3));
    REQUIRE(Vertex(2) < Vertex(3));
    REQUIRE(HalfedgeMesh::twin(Halfedge(6)) == Halfedge(7));
    REQUIRE(HalfedgeMesh::twin(Halfedge(7)) == Halfedge(6));
    REQUIRE(HalfedgeMesh::edge(Halfedge(7)) == Edge(3));
    STATIC_REQUIRE_FALSE(std::is_convertible_v<Vertex, Face>);
}

TEST_CASE("every built-in model is valid with the expected counts", "[core][generators]") {
    for (const std::string& name : generator_names()) {
        INFO(name);
        HalfedgeMesh m = generate(name);
        REQUIRE_VALID(m);
        REQUIRE(m.n_faces() > 0);
        REQUIRE(2 * m.n_edges() == m.n_halfedges());
    }
    HalfedgeMesh sphere = make_icosphere(10);
    REQUIRE(sphere.n_vertices() == 1002);
    REQUIRE(sphere.n_faces() == 2000);
    REQUIRE(make_default_model().n_vertices() == 1002);
}

TEST_CASE("Euler characteristic, genus and boundary loops", "[core][stats]") {
    MeshStats sphere = compute_stats(make_icosphere(4));
    REQUIRE(sphere.euler == 2);
    REQUIRE(sphere.genus == 0);
    REQUIRE(sphere.boundary_loops == 0);
    REQUIRE(sphere.components == 1);
    REQUIRE(sphere.volume.has_value());
    MeshStats torus = compute_stats(make_torus(20, 10, 1.0, 0.3));
    REQUIRE(torus.euler == 0);
    REQUIRE(torus.genus == 1);
    MeshStats grid = compute_stats(make_grid(5));
    REQUIRE(grid.boundary_loops == 1);
    REQUIRE(grid.euler == 1);
    REQUIRE_FALSE(grid.volume.has_value());
    MeshStats cyl = compute_stats(make_cylinder(12, 3));
    REQUIRE(cyl.boundary_loops == 2);
    REQUIRE(cyl.genus == 0);
}

TEST_CASE("circulators visit each neighbourhood once and agree with each other", "[core]") {
    for (HalfedgeMesh m : {make_icosphere(3), make_grid(4), make_cylinder(8, 2)}) {
        std::size_t valence_sum = 0, face_corner_sum = 0;
        for (Vertex v : m.vertices()) {
            std::set<Index> ring;
            for (Vertex w : m.vertices_around(v)) {
                REQUIRE(m.find_halfedge(v, w).is_valid());
                REQUIRE(m.to_vertex(m.find_halfedge(v, w)) == w);
                ring.insert(w.idx());
            }
            REQUIRE(ring.size() == m.valence(v));
            valence_sum += m.valence(v);
            std::size_t faces = 0;
            for (Face f : m.faces_around(v)) {
                const auto c = m.face_vertices(f);
                REQUIRE((c[0] == v || c[1] == v || c[2] == v));
                ++faces;
            }
            face_corner_sum += faces;
            REQUIRE(faces == m.valence(v) - (m.is_boundary(v) ? 1u : 0u));
        }
        REQUIRE(valence_sum == 2 * m.n_edges());
        REQUIRE(face_corner_sum == 3 * m.n_faces());
        for (Face f : m.faces()) {
            int n = 0;
            for (Halfedge h : m.halfedges_of(f)) {
                REQUIRE(m.face(h) == f);
                ++n;
            }
            REQUIRE(n == 3);
        }
    }
}

TEST_CASE("boundary detection on an open grid", "[core]") {
    HalfedgeMesh m = make_grid(3);
    std::size_t boundary_vertices = 0, boundary_edges = 0;
    for (Vertex v : m.vertices()) boundary_vertices += m.is_boundary(v);
    for (Edge e : m.edges()) boundary_edges += m.is_boundary(e);
    REQUIRE(boundary_vertices == 12);
    REQUIRE(boundary_edges == 12);
    for (Vertex v : m.vertices())
        if (m.is_boundary(v)) REQUIRE(m.is_boundary(m.halfedge(v)));
}

TEST_CASE("named typed properties", "[core][properties]") {
    HalfedgeMesh m = make_tetrahedron();
    auto weight = m.add_vertex_property<double>("v:weight", 1.5);
    REQUIRE(weight);
    REQUIRE(weight[Vertex(2)] == 1.5);
    weight[Vertex(2)] = 7.0;
    REQUIRE(m.get_vertex_property<double>("v:weight")[Vertex(2)] == 7.0);
    // Wrong type or name gives an empty view; a taken name throws.
    REQUIRE_FALSE(m.get_vertex_property<float>("v:weight"));
    REQUIRE_FALSE(m.get_vertex_property<double>("v:nothing"));
    REQUIRE_THROWS_AS(m.add_vertex_property<double>("v:weight"), InvalidArgument);
    // Built-in connectivity cannot be removed.
    REQUIRE_THROWS_AS(m.remove_vertex_property("v:position"), InvalidArgument);
    // New elements get the default; copies are deep.
    HalfedgeMesh copy = m;
    copy.get_vertex_property<double>("v:weight")[Vertex(2)] = -1.0;
    REQUIRE(m.get_vertex_property<double>("v:weight")[Vertex(2)] == 7.0);
    Vertex v = m.add_vertex(Point(0, 0, 0));
    REQUIRE(weight[v] == 1.5);
    m.remove_vertex_property("v:weight");
    REQUIRE_FALSE(m.has_vertex_property("v:weight"));
    // Eigen-typed properties default to zero, not garbage.
    auto n = m.vertex_property<Vector3>("v:normal");
    REQUIRE(n[Vertex(0)] == Vector3::Zero());
    auto fl = m.face_property<int>("f:label", 4);
    auto el = m.edge_property<float>("e:len");
    auto hl = m.halfedge_property<int>("h:mark", -1);
    REQUIRE(fl[Face(1)] == 4);
    REQUIRE(el.vector().size() == m.edges_size());
    REQUIRE(hl.vector().size() == m.halfedges_size());
}

TEST_CASE("a mesh copy is independent and moves leave an empty mesh", "[core]") {
    HalfedgeMesh a = make_icosphere(2);
    HalfedgeMesh b = a;
    b.position(Vertex(0)) = Point(9, 9, 9);
    REQUIRE(a.position(Vertex(0)) != Point(9, 9, 9));
    REQUIRE_VALID(b);
    HalfedgeMesh c = std::move(b);
    REQUIRE_VALID(c);
    REQUIRE(b.n_vertices() == 0);  // NOLINT(bugprone-use-after-move): moved-from is empty
    REQUIRE_VALID(b);
    c.clear();
    REQUIRE(c.n_vertices() == 0);
}

// ---- construction from soups --------------------------------------------------------------

TEST_CASE("build_mesh splits a non-manifold vertex into one copy per fan", "[core][builder]") {
    LoadReport r;
    HalfedgeMesh m = build(
        soup_of({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {-1, 0, 0}, {-1, -1, 0}}, {{0, 1, 2}, {0, 3, 4}}),
        &r);
    REQUIRE_VALID(m);
    REQUIRE(m.n_faces() == 2);
    REQUIRE(m.n_vertices() == 6);
    REQUIRE(r.nonmanifold_vertices_split == 1);
    REQUIRE(r.vertex_copies_added == 1);
    REQUIRE(compute_stats(m).components == 2);
}

TEST_CASE("build_mesh detaches faces on a non-manifold edge", "[core][builder]") {
    LoadReport r;
    HalfedgeMesh m = build(soup_of({{0, 0, 0}, {1, 0, 0}, {.5, 1, 0}, {.5, -1, 0}, {.5, 0, 1}},
                                   {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}}),
                           &r);
    REQUIRE_VALID(m);
    REQUIRE(m.n_faces() == 3);
    REQUIRE(r.detached_faces == 1);
    REQUIRE(r.degenerate_faces_dropped == 0);
}

TEST_CASE("build_mesh keeps duplicated and flipped faces detached", "[core][builder]") {
    LoadReport r;
    HalfedgeMesh dup =
        build(soup_of({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 2}, {0, 1, 2}}), &r);
    REQUIRE_VALID(dup);
    REQUIRE(dup.n_faces() == 2);
    REQUIRE(r.detached_faces == 1);
    LoadReport r2;
    HalfedgeMesh flip =
        build(soup_of({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}}, {{0, 1, 2}, {1, 2, 3}}), &r2);
    REQUIRE_VALID(flip);
    REQUIRE(flip.n_faces() == 2);
    REQUIRE(r2.detached_faces == 1);
}

TEST_CASE("build_mesh drops only faces with a repeated vertex and keeps isolated vertices",
          "[core][builder]") {
    LoadReport r;
    HalfedgeMesh m = build(soup_of({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {7, 7, 7}},
                                   {{0, 1, 2}, {1, 3, 2}, {1, 1, 3}, {0, 1}}),
                           &r);
    REQUIRE_VALID(m);
    REQUIRE(m.n_faces() == 2);
    REQUIRE(m.n_vertices() == 5);
    REQUIRE(r.degenerate_faces_dropped == 2);
    REQUIRE(r.isolated_vertices == 1);
    REQUIRE(m.is_isolated(Vertex(4)));
}

TEST_CASE("build_mesh triangulates concave polygons without folding", "[core][builder]") {
    LoadReport r;
    // L-shaped hexagon starting at the reflex corner: a fan from it would overlap.
    HalfedgeMesh m =
        build(soup_of({{1, 1, 0}, {1, 2, 0}, {0, 2, 0}, {0, 0, 0}, {2, 0, 0}, {2, 1, 0}},
                      {{0, 1, 2, 3, 4, 5}}),
              &r);
    REQUIRE_VALID(m);
    REQUIRE(m.n_faces() == 4);
    REQUIRE(r.polygons_triangulated == 1);
    REQUIRE(surface_area(m) == Approx(3.0));
    for (Face f : m.faces()) REQUIRE(face_area_vector(m, f).z() > 0);
}

TEST_CASE("build_mesh refuses bad indices and non-finite positions", "[core][builder]") {
    LoadReport r;
    REQUIRE_THROWS_AS(build_mesh(soup_of({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 5}}), r),
                      InvalidArgument);
    REQUIRE_THROWS_AS(
        build_mesh(soup_of({{0, 0, 0}, {1, 0, 0}, {0, std::nan(""), 0}}, {{0, 1, 2}}), r),
        InvalidArgument);
}

TEST_CASE("build_mesh survives a fan of many faces around one edge and vertex", "[core][builder]") {
    // Ten triangles sharing the edge 0-1, alternating orientation, plus a repeated copy.
    PolygonSoup s;
    s.positions = {{0, 0, 0}, {1, 0, 0}};
    for (int i = 0; i < 10; ++i) {
        s.positions.emplace_back(0.5, std::cos(i * 0.6), std::sin(i * 0.6));
        if (i % 2)
            s.add_face({0, 1, Index(2 + i)});
        else
            s.add_face({1, 0, Index(2 + i)});
    }
    s.add_face({0, 1, 3});
    LoadReport r;
    HalfedgeMesh m = build_mesh(s, r);
    REQUIRE_VALID(m);
    REQUIRE(m.n_faces() == 11);
    REQUIRE(r.detached_faces == 9);
}

TEST_CASE("to_soup and build_mesh round-trip a mesh with corner texture coordinates",
          "[core][builder]") {
    PolygonSoup s = soup_of({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}}, {});
    s.add_face({0, 1, 2}, {{0, 0}, {1, 0}, {0, 1}});
    s.add_face({1, 3, 2}, {{0.5, 0}, {1, 1}, {0, 0.5}});
    LoadReport r;
    HalfedgeMesh m = build_mesh(s, r);
    REQUIRE_VALID(m);
    auto uv = m.get_halfedge_property<TexCoord>("h:texcoord");
    REQUIRE(uv);
    PolygonSoup back = to_soup(m);
    REQUIRE(back.corners == s.corners);
    REQUIRE(back.corner_texcoords == s.corner_texcoords);
}

TEST_CASE("validate reports broken connectivity", "[core][validate]") {
    HalfedgeMesh m = make_icosphere(2);
    REQUIRE_VALID(m);
    HalfedgeMesh a = m;
    a.set_next(Halfedge(0), Halfedge(4));
    REQUIRE_FALSE(validate(a).ok);
    HalfedgeMesh b = m;
    b.set_to_vertex(Halfedge(0), Vertex(Index(b.vertices_size() + 5)));
    REQUIRE_FALSE(validate(b).ok);
    HalfedgeMesh c = m;
    c.set_halfedge(Vertex(0), HalfedgeMesh::twin(c.halfedge(Vertex(0))));
    auto r = validate(c);
    REQUIRE_FALSE(r.ok);
    REQUIRE_FALSE(r.message.empty());
    HalfedgeMesh d = m;
    d.set_face(Halfedge(0), Face());
    REQUIRE_FALSE(validate(d).ok);
}

TEST_CASE("validate names the vertex-level violations", "[core][validate]") {
    auto message = [](const HalfedgeMesh& mesh) {
        const ValidationResult r = validate(mesh);
        REQUIRE_FALSE(r.ok);
        return r.message;
    };
    SECTION("two fans on one vertex") {
        // A bowtie: the loader gives the shared vertex a copy; joining them again leaves one
        // vertex with two fans.
        PolygonSoup s;
        s.positions = {Point(0, 0, 0), Point(1, 0, 0), Point(1, 1, 0), Point(-1, 0, 0),
                       Point(-1, -1, 0)};
        s.add_face({0, 1, 2});
        s.add_face({0, 3, 4});
        LoadReport report;
        HalfedgeMesh m = build_mesh(s, report);
        REQUIRE_VALID(m);
        REQUIRE(m.n_vertices() == 6);
        const Vertex copy(5);
        for (Halfedge h : m.halfedges())
            if (m.to_vertex(h) == copy) m.set_to_vertex(h, Vertex(0));
        m.set_halfedge(copy, Halfedge());
        CHECK_THAT(message(m), Catch::Contains("vertex 0 is non-manifold"));
    }
    SECTION("two spokes to the same neighbour") {
        // A pyramid without its base (a closed fan around the apex 0); pointing the spoke to
        // corner 3 at corner 1 instead gives the apex two edges to corner 1.
        PolygonSoup s;
        s.positions = {Point(0, 0, 1), Point(1, 0, 0), Point(0, 1, 0), Point(-1, 0, 0),
                       Point(0, -1, 0)};
        s.add_face({0, 1, 2});
        s.add_face({0, 2, 3});
        s.add_face({0, 3, 4});
        s.add_face({0, 4, 1});
        LoadReport report;
        HalfedgeMesh m = build_mesh(s, report);
        REQUIRE_VALID(m);
        for (Halfedge h : m.halfedges())
            if (m.to_vertex(h) == Vertex(3)) m.set_to_vertex(h, Vertex(1));
        m.set_halfedge(Vertex(3), Halfedge());
        // Corners 2 and 4 now have two edges to corner 1 too, and corner 1 has two fans: any
        // of these violations may be the one reported.
        const std::string msg = message(m);
        INFO(msg);
        CHECK((msg.find("has two edges to the same neighbour") != std::string::npos ||
               msg.find("vertex 1 is non-manifold") != std::string::npos));
    }
    SECTION("a boundary vertex whose halfedge is not the boundary one") {
        HalfedgeMesh m = make_grid(2);
        REQUIRE_VALID(m);
        const Vertex v(0);
        REQUIRE(m.is_boundary(m.halfedge(v)));
        m.set_halfedge(v, m.ccw_rotated(m.halfedge(v)));
        CHECK_THAT(message(m),
                   Catch::Contains("vertex 0 is on the boundary but its halfedge is not"));
    }
    SECTION("edges but no outgoing halfedge") {
        HalfedgeMesh m = make_icosphere(1);
        m.set_halfedge(Vertex(3), Halfedge());
        CHECK_THAT(message(m), Catch::Contains("vertex 3 has edges but no outgoing halfedge"));
    }
    SECTION("a live halfedge pointing to a deleted vertex (a mesh with garbage)") {
        HalfedgeMesh m = make_icosphere(1);
        const Halfedge h = m.halfedge(Edge(10), 0);
        REQUIRE(m.is_collapse_ok(h));
        const Vertex gone = m.from_vertex(h);  // collapse removes it
        m.collapse(h);
        REQUIRE(m.has_garbage());
        REQUIRE_VALID(m);
        REQUIRE(m.is_deleted(gone));
        for (Halfedge x : m.halfedges())
            if (!m.is_deleted(x)) {
                m.set_to_vertex(x, gone);
                break;
            }
        CHECK_THAT(message(m), Catch::Contains("points to a missing or deleted vertex"));
    }
}

TEST_CASE("build_mesh handles high-valence vertices (a 500-triangle fan)", "[core][builder]") {
    // A disk: one centre joined to a ring of 500 vertices, plus a duplicate of one face.
    PolygonSoup s;
    const Index n = 500;
    s.positions.emplace_back(0, 0, 0);
    for (Index i = 0; i < n; ++i)
        s.positions.emplace_back(std::cos(2 * M_PI * i / n), std::sin(2 * M_PI * i / n), 0);
    for (Index i = 0; i < n; ++i) s.add_face({0, 1 + i, 1 + (i + 1) % n});
    s.add_face({0, 1, 2});
    LoadReport r;
    HalfedgeMesh m = build_mesh(s, r);
    REQUIRE_VALID(m);
    REQUIRE(m.n_faces() == n + 1);
    REQUIRE(r.detached_faces == 1);
    REQUIRE(m.valence(Vertex(0)) == n);
    REQUIRE(m.n_edges() == 2 * n + 3);  // spokes + rim + the detached triangle's three
    REQUIRE(compute_stats(m).boundary_loops == 2);
}

namespace {

/// The identity of the values of `name` in `mesh` (see HalfedgeMesh::memory_blocks()).
std::vector<const void*> block_ids(const trilab::HalfedgeMesh& mesh) {
    std::vector<const void*> ids;
    for (const auto& b : mesh.memory_blocks()) ids.push_back(b.id);
    return ids;
}

}  // namespace

TEST_CASE("mesh copies share their arrays until one of them writes", "[core][property]") {
    using namespace trilab;
    HalfedgeMesh a = make_icosphere(3);
    auto color = a.add_vertex_property<Color>("v:color", Color(1, 0, 0));
    const std::vector<const void*> before = block_ids(a);

    HalfedgeMesh b = a;  // shares every array
    CHECK(block_ids(b) == before);
    // Reading, through const access, copies nothing.
    const HalfedgeMesh& cb = b;
    double sum = 0;
    for (Vertex v : cb.vertices()) sum += cb.position(v).x();
    CHECK(cb.get_vertex_property<Color>("v:color")[Vertex(0)] == Color(1, 0, 0));
    CHECK(block_ids(b) == before);
    (void)sum;

    // A write copies that array only, and only in the mesh written to.
    b.position(Vertex(0)) += Point(1, 0, 0);
    const std::vector<const void*> after = block_ids(b);
    std::size_t changed = 0;
    for (std::size_t i = 0; i < after.size(); ++i) changed += after[i] != before[i] ? 1 : 0;
    CHECK(changed == 1);
    CHECK(a.position(Vertex(0)) + Point(1, 0, 0) == b.position(Vertex(0)));
    CHECK(block_ids(a) == before);

    // A view taken before the copy writes to its own mesh only.
    HalfedgeMesh c = a;
    color[Vertex(1)] = Color(0, 1, 0);
    CHECK(a.get_vertex_property<Color>("v:color")[Vertex(1)] == Color(0, 1, 0));
    CHECK(std::as_const(c).get_vertex_property<Color>("v:color")[Vertex(1)] == Color(1, 0, 0));

    // Topology edits of a copy leave the original as it was.
    HalfedgeMesh d = a;
    d.split(Face(0), Point(0, 0, 0));
    CHECK(d.n_vertices() == a.n_vertices() + 1);
    REQUIRE_VALID(a);
    REQUIRE_VALID(d);
    CHECK(block_ids(a) != block_ids(d));

    // set_positions replaces the values without copying; share_equal_arrays shares them
    // again where they are equal.
    HalfedgeMesh e = a;
    std::vector<Point> moved = a.positions();
    e.set_positions(moved);
    CHECK(block_ids(e) != block_ids(a));
    CHECK(e.share_equal_arrays(a) == before.size());
    CHECK(block_ids(e) == block_ids(a));
    CHECK_THROWS_AS(e.set_positions(std::vector<Point>(3)), InvalidArgument);
}

TEST_CASE("ranges and circulators are standard iterators, halfedges() skips deleted edges",
          "[core]") {
    using namespace trilab;
    using It = ElementRange<Vertex>::iterator;
    static_assert(std::is_same_v<std::iterator_traits<It>::value_type, Vertex>);
    static_assert(
        std::is_same_v<std::iterator_traits<It>::iterator_category, std::input_iterator_tag>);
    using Around = decltype(std::declval<HalfedgeMesh>().vertices_around(Vertex(0)).begin());
    static_assert(std::is_same_v<std::iterator_traits<Around>::value_type, Vertex>);

    HalfedgeMesh m = make_icosphere(2);
    const auto vs = m.vertices();
    CHECK(std::size_t(std::distance(vs.begin(), vs.end())) == m.n_vertices());
    const std::vector<Vertex> around(m.vertices_around(Vertex(0)).begin(),
                                     m.vertices_around(Vertex(0)).end());
    CHECK(around.size() == m.valence(Vertex(0)));
    const auto hs = m.halfedges();
    CHECK(std::size_t(std::distance(hs.begin(), hs.end())) == m.n_halfedges());

    // After a collapse (before garbage collection) the deleted edges' halfedges are skipped.
    const Halfedge h = m.halfedge(Vertex(0));
    REQUIRE(m.is_collapse_ok(h));
    m.collapse(h);
    REQUIRE(m.has_garbage());
    std::size_t live = 0;
    for (Halfedge x : m.halfedges()) {
        CHECK_FALSE(m.is_deleted(x));
        ++live;
    }
    CHECK(live == m.n_halfedges());
    CHECK(std::count_if(m.halfedges().begin(), m.halfedges().end(),
                        [&](Halfedge x) { return m.is_boundary(x); }) == 0);
}

TEST_CASE("the connectivity arrays are what navigation reads, and writing copies a shared one",
          "[core]") {
    HalfedgeMesh m = make_grid(3);
    const HalfedgeMesh& cm = m;
    REQUIRE(cm.halfedge_to_array().size() == m.halfedges_size());
    REQUIRE(cm.vertex_halfedge_array().size() == m.vertices_size());
    REQUIRE(cm.face_halfedge_array().size() == m.faces_size());
    for (Halfedge h : m.halfedges()) {
        CHECK(cm.halfedge_to_array()[h.idx()] == m.to_vertex(h));
        CHECK(cm.halfedge_next_array()[h.idx()] == m.next(h));
        CHECK(cm.halfedge_prev_array()[h.idx()] == m.prev(h));
        CHECK(cm.halfedge_face_array()[h.idx()] == m.face(h));
    }
    for (Vertex v : m.vertices()) CHECK(cm.vertex_halfedge_array()[v.idx()] == m.halfedge(v));
    for (Face f : m.faces()) CHECK(cm.face_halfedge_array()[f.idx()] == m.halfedge(f));

    // A copy shares the arrays until one side writes; a write through the mutable accessor
    // reaches only its own mesh and changes its topology revision.
    HalfedgeMesh copy = m;
    REQUIRE(&std::as_const(copy).halfedge_next_array() == &cm.halfedge_next_array());
    const auto before = copy.topology_revision();
    const Halfedge h0(0);
    const Halfedge original = m.next(h0);
    copy.halfedge_next_array()[0] = copy.prev(h0);
    CHECK(&std::as_const(copy).halfedge_next_array() != &cm.halfedge_next_array());
    CHECK(m.next(h0) == original);
    CHECK(copy.next(h0) == copy.prev(h0));
    CHECK(copy.topology_revision() != before);
    CHECK(validate(m));
}

TEST_CASE("validate splits a large mesh's passes over two threads and finds what it always did",
          "[core][validate]") {
    // 72,000 faces: each pass runs as two halves (core/validate.cpp); the violations are put
    // in the second half, where the first half's thread does not look.
    const HalfedgeMesh big = make_icosphere(60);
    REQUIRE(big.n_halfedges() >= (std::size_t(1) << 16));
    REQUIRE_VALID(big);
    const Index late_v = Index(big.vertices_size() - 10);
    const Index late_h = Index(big.halfedges_size() - 10);
    auto message = [](const HalfedgeMesh& mesh) {
        const ValidationResult r = validate(mesh);
        REQUIRE_FALSE(r.ok);
        return r.message;
    };
    SECTION("edges but no outgoing halfedge") {
        HalfedgeMesh m = big;
        m.set_halfedge(Vertex(late_v), Halfedge());
        CHECK_THAT(message(m), Catch::Contains("vertex " + std::to_string(late_v) +
                                               " has edges but no outgoing halfedge"));
    }
    SECTION("a halfedge that is not outgoing") {
        HalfedgeMesh m = big;
        const Vertex v(late_v);
        m.set_halfedge(v, HalfedgeMesh::twin(m.halfedge(v)));
        CHECK_THAT(message(m), Catch::Contains("vertex " + std::to_string(late_v)));
    }
    SECTION("a broken next in the second half") {
        HalfedgeMesh m = big;
        m.set_next(Halfedge(late_h), Halfedge(late_h));
        CHECK_FALSE(message(m).empty());
    }
    SECTION("a face without its halfedge") {
        HalfedgeMesh m = big;
        m.set_face(Halfedge(late_h), Face());
        CHECK_FALSE(message(m).empty());
    }
    SECTION("two fans on one vertex, the second fan in the second half") {
        // Vertex 0's outgoing halfedges are pointed at from a late vertex's spokes: the
        // late vertex's fan becomes a second fan of vertex 0 (and the late vertex has none).
        HalfedgeMesh m = big;
        const Vertex late(late_v);
        for (Halfedge h : m.halfedges())
            if (m.to_vertex(h) == late) m.set_to_vertex(h, Vertex(0));
        m.set_halfedge(late, Halfedge());
        CHECK_THAT(message(m), Catch::Contains("vertex 0 is non-manifold"));
    }
    SECTION("a boundary vertex whose halfedge is not the boundary one, in the second half") {
        // An open grid of 80,000 faces: the boundary halfedges are listed by both halves.
        HalfedgeMesh m = make_grid(200);
        REQUIRE(m.n_halfedges() >= (std::size_t(1) << 16));
        REQUIRE_VALID(m);
        const Vertex v(Index(m.vertices_size() - 1));
        REQUIRE(m.is_boundary(m.halfedge(v)));
        m.set_halfedge(v, m.ccw_rotated(m.halfedge(v)));
        CHECK_THAT(message(m), Catch::Contains("vertex " + std::to_string(v.idx()) +
                                               " is on the boundary but its halfedge is not"));
    }
    SECTION("collapses leave deleted elements in both halves: still valid") {
        HalfedgeMesh m = big;
        std::size_t collapsed = 0;
        for (Index e : {Index(10), Index(m.edges_size() / 2 + 7), Index(m.edges_size() - 20)}) {
            const Halfedge h = m.halfedge(Edge(e), 0);
            if (m.is_deleted(Edge(e)) || !m.is_collapse_ok(h)) continue;
            m.collapse(h);
            ++collapsed;
        }
        REQUIRE(collapsed >= 2);
        REQUIRE(m.has_garbage());
        REQUIRE_VALID(m);
    }
}
