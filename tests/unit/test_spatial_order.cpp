// The spatial renumbering (core/algorithms/spatial_order.h), HalfedgeMesh::renumber(), and
// decimation's independence of the input's vertex order, which rests on them.
#include <algorithm>
#include <random>
#include <vector>

#include "core/algorithms/decimation.h"
#include "core/algorithms/generators.h"
#include "core/algorithms/spatial_order.h"
#include "core/errors.h"
#include "core/mesh_builder.h"
#include "test_helpers.h"

using namespace trilab;

namespace {

// The same surface with its vertices and its faces in a random order (from `seed`), each face
// starting at another corner, as another tool may write it.
HalfedgeMesh shuffled(const HalfedgeMesh& mesh, unsigned seed) {
    PolygonSoup soup = to_soup(mesh);
    std::mt19937 rng(seed);
    std::vector<Index> order(soup.positions.size());  // new -> old
    for (Index i = 0; i < order.size(); ++i) order[i] = i;
    std::shuffle(order.begin(), order.end(), rng);
    std::vector<Index> new_index(order.size());
    for (Index i = 0; i < order.size(); ++i) new_index[order[i]] = i;
    PolygonSoup out;
    for (Index old : order) out.positions.push_back(soup.positions[old]);
    std::vector<Index> faces(soup.n_faces());
    for (Index f = 0; f < faces.size(); ++f) faces[f] = f;
    std::shuffle(faces.begin(), faces.end(), rng);
    for (Index f : faces) {
        const std::size_t b = soup.face_offsets[f];
        const unsigned turn = rng() % 3;
        std::vector<Index> face;
        for (unsigned k = 0; k < 3; ++k)
            face.push_back(new_index[soup.corners[b + (k + turn) % 3]]);
        out.add_face(face);
    }
    LoadReport report;
    return build_mesh(out, report);
}

// Every face as its three positions in order from its halfedge, and every vertex position.
void require_same_numbering(const HalfedgeMesh& a, const HalfedgeMesh& b) {
    REQUIRE(a.vertices_size() == b.vertices_size());
    REQUIRE(a.faces_size() == b.faces_size());
    REQUIRE(a.edges_size() == b.edges_size());
    REQUIRE(a.positions() == b.positions());
    for (Face f : a.faces()) REQUIRE(a.face_vertices(f) == b.face_vertices(f));
    for (Edge e : a.edges())
        REQUIRE(a.to_vertex(HalfedgeMesh::halfedge(e, 0)) ==
                b.to_vertex(HalfedgeMesh::halfedge(e, 0)));
    for (Vertex v : a.vertices()) REQUIRE(a.to_vertex(a.halfedge(v)) == b.to_vertex(b.halfedge(v)));
}

}  // namespace

TEST_CASE("renumber_spatially gives the same numbering whatever the input's order",
          "[spatial_order]") {
    HalfedgeMesh mesh = make_noisy_sphere(12, 0.05, 3);
    auto tag = mesh.vertex_property<Index>("v:tag");
    for (Vertex v : mesh.vertices()) tag[v] = v.idx();
    HalfedgeMesh other = shuffled(mesh, 7);
    REQUIRE(other.positions() != mesh.positions());

    const HalfedgeMesh before = mesh;
    const IndexRemap remap = renumber_spatially(mesh);
    REQUIRE_VALID(mesh);
    // Attributes moved with their vertices.
    auto moved = mesh.get_vertex_property<Index>("v:tag");
    for (Vertex v : before.vertices()) {
        const Vertex now(remap.vertices[v.idx()]);
        REQUIRE(mesh.position(now) == before.position(v));
        REQUIRE(moved[now] == v.idx());
    }
    // Neighbours in memory are neighbours in space: consecutive vertices are much closer than
    // in a shuffled order.
    const auto path = [](const HalfedgeMesh& m) {
        double sum = 0;
        for (std::size_t i = 1; i < m.positions().size(); ++i)
            sum += (m.positions()[i] - m.positions()[i - 1]).norm();
        return sum;
    };
    const double shuffled_path = path(other);
    renumber_spatially(other);
    REQUIRE(path(other) < 0.25 * shuffled_path);
    REQUIRE_VALID(other);
    require_same_numbering(mesh, other);
}

TEST_CASE("HalfedgeMesh::renumber refuses a list that is not a permutation of the live elements",
          "[spatial_order]") {
    HalfedgeMesh mesh = make_icosahedron();
    std::vector<Index> v(mesh.n_vertices()), h(mesh.n_halfedges()), f(mesh.n_faces());
    for (Index i = 0; i < v.size(); ++i) v[i] = i;
    for (Index i = 0; i < h.size(); ++i) h[i] = i;
    for (Index i = 0; i < f.size(); ++i) f[i] = i;
    std::vector<Index> twice = v;
    twice[1] = 0;
    REQUIRE_THROWS_AS(mesh.renumber(twice, h, f), InvalidArgument);
    std::vector<Index> split = h;
    std::swap(split[1], split[2]);  // halves of different edges side by side
    REQUIRE_THROWS_AS(mesh.renumber(v, split, f), InvalidArgument);
    REQUIRE_THROWS_AS(mesh.renumber(v, h, std::vector<Index>(f.begin(), f.end() - 1)),
                      InvalidArgument);
    REQUIRE_VALID(mesh);
    // Turning every edge around and reversing the vertices keeps a valid mesh.
    std::reverse(v.begin(), v.end());
    for (Index i = 0; i < h.size(); ++i) h[i] = i ^ 1u;
    const IndexRemap r = mesh.renumber(v, h, f);
    REQUIRE_VALID(mesh);
    REQUIRE(r.vertices[0] == mesh.n_vertices() - 1);
}

TEST_CASE("decimating a big mesh gives the same result whatever its vertex order",
          "[decimation][spatial_order]") {
    // Above 50,000 vertices: the batches run, on the spatially renumbered copy.
    const HalfedgeMesh mesh = make_noisy_sphere(80, 0.02, 5);
    REQUIRE(mesh.n_vertices() > 50000);
    const HalfedgeMesh other = shuffled(mesh, 11);
    DecimationOptions o;
    o.target_vertices = 600;
    o.levels = DecimationLevels::Last;
    const DecimationResult a = decimate(mesh, o);
    const DecimationResult b = decimate(other, o);
    REQUIRE(a.levels.size() == 1);
    REQUIRE(b.levels.size() == 1);
    const HalfedgeMesh& ma = a.levels[0].mesh;
    const HalfedgeMesh& mb = b.levels[0].mesh;
    REQUIRE_VALID(ma);
    REQUIRE(ma.n_vertices() == 600);
    REQUIRE(a.report.collapses == b.report.collapses);
    require_same_numbering(ma, mb);
    // The source indices lead back to each input's own numbering, and the geomorph's end
    // positions follow the input's vertices.
    const auto sa = ma.get_vertex_property<Index>(kDecimationSourceName);
    const auto sb = mb.get_vertex_property<Index>(kDecimationSourceName);
    for (Vertex v : ma.vertices()) {
        REQUIRE(sa[v] < mesh.vertices_size());
        REQUIRE(sb[v] < other.vertices_size());
        REQUIRE(mesh.position(Vertex(sa[v])) == other.position(Vertex(sb[v])));
    }
    REQUIRE(a.levels[0].correspondence.positions.size() == mesh.vertices_size());
    for (Vertex v : ma.vertices())
        REQUIRE(a.levels[0].correspondence.positions[sa[v]] == ma.position(v));
}

TEST_CASE("a region on a big mesh survives the spatial renumbering",
          "[decimation][spatial_order]") {
    const HalfedgeMesh mesh = make_noisy_sphere(80, 0.02, 5);
    // The upper half may collapse, the lower half stays bit for bit.
    std::vector<float> region(mesh.vertices_size(), 0.0f);
    std::size_t fixed = 0;
    for (Vertex v : mesh.vertices()) {
        region[v.idx()] = mesh.position(v).z() > 0 ? 1.0f : 0.0f;
        fixed += region[v.idx()] > 0 ? 0 : 1;
    }
    DecimationOptions o;
    o.percent = 90;
    o.levels = DecimationLevels::Last;
    o.region = &region;
    const DecimationResult r = decimate(mesh, o);
    REQUIRE(r.levels.size() == 1);
    const HalfedgeMesh& out = r.levels[0].mesh;
    REQUIRE_VALID(out);
    REQUIRE(out.n_vertices() < mesh.n_vertices() - (mesh.n_vertices() - fixed) / 2);
    const auto source = out.get_vertex_property<Index>(kDecimationSourceName);
    std::size_t kept_fixed = 0;
    for (Vertex v : out.vertices()) {
        if (region[source[v]] > 0) continue;
        ++kept_fixed;
        REQUIRE(out.position(v) == mesh.position(Vertex(source[v])));
    }
    REQUIRE(kept_fixed == fixed);
}

TEST_CASE("garbage_collection of a big mesh keeps the live elements in their order",
          "[spatial_order][garbage]") {
    // Past 2^16 halfedges the maps are built on two threads; scattered collapses leave deleted
    // vertices, edges and faces all through the storage.
    HalfedgeMesh mesh = make_noisy_sphere(60, 0.02, 3);
    REQUIRE(mesh.halfedges_size() >= (std::size_t(1) << 16));
    auto tag = mesh.add_vertex_property<Index>("v:tag");
    auto etag = mesh.add_edge_property<Index>("e:tag");
    auto ftag = mesh.add_face_property<Index>("f:tag");
    for (Vertex v : mesh.vertices()) tag[v] = v.idx();
    for (Edge e : mesh.edges()) etag[e] = e.idx();
    for (Face f : mesh.faces()) ftag[f] = f.idx();
    std::mt19937 rng(7);
    for (int i = 0; i < 3000; ++i) {
        const Halfedge h(Index(rng() % mesh.halfedges_size()));
        if (!mesh.is_deleted(h) && mesh.is_collapse_ok(h)) mesh.collapse(h);
    }
    REQUIRE(mesh.has_garbage());
    const HalfedgeMesh before = mesh;
    const IndexRemap remap = mesh.garbage_collection();
    REQUIRE_VALID(mesh);
    REQUIRE_FALSE(mesh.has_garbage());
    REQUIRE(mesh.vertices_size() == before.n_vertices());
    REQUIRE(mesh.edges_size() == before.n_edges());
    REQUIRE(mesh.faces_size() == before.n_faces());
    // Live elements numbered in their old order, deleted ones mapped to nothing.
    const auto check = [](const std::vector<Index>& map, std::size_t n_new, auto is_deleted) {
        Index next = 0;
        for (Index old = 0; old < map.size(); ++old)
            REQUIRE(map[old] == (is_deleted(old) ? kInvalidIndex : next++));
        REQUIRE(next == n_new);
    };
    check(remap.vertices, mesh.vertices_size(),
          [&](Index i) { return before.is_deleted(Vertex(i)); });
    check(remap.edges, mesh.edges_size(), [&](Index i) { return before.is_deleted(Edge(i)); });
    check(remap.faces, mesh.faces_size(), [&](Index i) { return before.is_deleted(Face(i)); });
    for (Index h = 0; h < remap.halfedges.size(); ++h)
        REQUIRE(remap.halfedges[h] == (remap.edges[h >> 1] == kInvalidIndex
                                           ? kInvalidIndex
                                           : 2 * remap.edges[h >> 1] + (h & 1u)));
    // Attributes and links moved with their elements.
    const auto tag2 = mesh.get_vertex_property<Index>("v:tag");
    const auto etag2 = mesh.get_edge_property<Index>("e:tag");
    const auto ftag2 = mesh.get_face_property<Index>("f:tag");
    for (Vertex v : before.vertices()) {
        const Vertex w(remap.vertices[v.idx()]);
        REQUIRE(tag2[w] == v.idx());
        REQUIRE(mesh.position(w) == before.position(v));
    }
    for (Edge e : before.edges()) REQUIRE(etag2[Edge(remap.edges[e.idx()])] == e.idx());
    for (Face f : before.faces()) REQUIRE(ftag2[Face(remap.faces[f.idx()])] == f.idx());
    for (Index h = 0; h < before.halfedges_size(); ++h) {
        if (before.is_deleted(Halfedge(h))) continue;
        const Halfedge n(remap.halfedges[h]);
        REQUIRE(mesh.to_vertex(n).idx() == remap.vertices[before.to_vertex(Halfedge(h)).idx()]);
        REQUIRE(mesh.next(n).idx() == remap.halfedges[before.next(Halfedge(h)).idx()]);
    }
}

TEST_CASE("HalfedgeMesh::renumber on a big mesh names the vertex list first and changes nothing",
          "[spatial_order]") {
    // Past 2^16 halfedges the lists are checked on two threads: the vertex list's fault is the
    // one reported when the halfedge list has one too, as on one thread.
    HalfedgeMesh mesh = make_noisy_sphere(60, 0.02, 3);
    REQUIRE(mesh.halfedges_size() >= (std::size_t(1) << 16));
    std::vector<Index> v(mesh.n_vertices()), h(mesh.n_halfedges()), f(mesh.n_faces());
    for (Index i = 0; i < v.size(); ++i) v[i] = i;
    for (Index i = 0; i < h.size(); ++i) h[i] = i;
    for (Index i = 0; i < f.size(); ++i) f[i] = i;
    std::vector<Index> bad_v = v, bad_h = h;
    bad_v[5] = 4;
    std::swap(bad_h[1], bad_h[2]);
    const HalfedgeMesh before = mesh;
    REQUIRE_THROWS_WITH(mesh.renumber(bad_v, bad_h, f), Catch::Contains("vertex 4"));
    REQUIRE_THROWS_WITH(mesh.renumber(v, bad_h, f),
                        Catch::Contains("not the two halves of one edge"));
    REQUIRE(mesh.revision() == before.revision());
    REQUIRE_VALID(mesh);
}

TEST_CASE("decimating a big open mesh by roundness gives the same result whatever its order",
          "[decimation][spatial_order]") {
    // The batch passes defer the re-pricing; with the roundness cost a collapse also changes
    // the price of the edges around the kept vertex's neighbours.
    const HalfedgeMesh mesh = make_grid(240);
    REQUIRE(mesh.n_vertices() > 50000);
    const HalfedgeMesh other = shuffled(mesh, 5);
    DecimationOptions o;
    o.cost = DecimationCost::Roundness;
    o.percent = 95;
    o.levels = DecimationLevels::Last;
    const DecimationResult a = decimate(mesh, o);
    const DecimationResult b = decimate(other, o);
    REQUIRE(a.levels.size() == 1);
    REQUIRE(b.levels.size() == 1);
    REQUIRE_VALID(a.levels[0].mesh);
    REQUIRE(a.report.collapses == b.report.collapses);
    require_same_numbering(a.levels[0].mesh, b.levels[0].mesh);
}
