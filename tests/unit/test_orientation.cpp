// Face orientation: flip_orientation() reverses every face and keeps a valid mesh with its
// attributes on the right corners; an inward-oriented closed mesh gets a load-report note.
#include <algorithm>
#include <array>
#include <cstdio>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "app/ops/operation.h"
#include "core/algorithms/generators.h"
#include "core/algorithms/orientation.h"
#include "core/errors.h"
#include "core/geometry.h"
#include "core/io/mesh_io.h"
#include "test_helpers.h"

using namespace trilab;
using namespace trilab::test;

namespace {

/// The corners of every live face, by face index.
std::vector<std::array<Vertex, 3>> corners(const HalfedgeMesh& m) {
    std::vector<std::array<Vertex, 3>> out(m.faces_size());
    for (Face f : m.faces()) out[f.idx()] = m.face_vertices(f);
    return out;
}

/// Whether b is a cyclic rotation of a reversed.
bool reversed(std::array<Vertex, 3> a, const std::array<Vertex, 3>& b) {
    std::reverse(a.begin(), a.end());
    for (int r = 0; r < 3; ++r) {
        if (a == b) return true;
        std::rotate(a.begin(), a.begin() + 1, a.end());
    }
    return false;
}

/// Per-corner texture coordinates that name their corner: (vertex index, face index).
void label_corners(HalfedgeMesh& m) {
    auto uv = m.halfedge_property<TexCoord>("h:texcoord");
    for (Halfedge h : m.halfedges())
        uv[h] = m.is_boundary(h) ? TexCoord(-1, -1)
                                 : TexCoord(double(m.to_vertex(h).idx()), double(m.face(h).idx()));
}

void require_corner_labels(const HalfedgeMesh& m) {
    const auto uv = m.get_halfedge_property<TexCoord>("h:texcoord");
    REQUIRE(uv);
    for (Halfedge h : m.halfedges()) {
        if (m.is_boundary(h)) continue;
        INFO("halfedge " << h.idx());
        REQUIRE(uv[h] == TexCoord(double(m.to_vertex(h).idx()), double(m.face(h).idx())));
    }
}

}  // namespace

TEST_CASE("flip_orientation reverses every face of a closed mesh and negates its volume",
          "[orientation]") {
    HalfedgeMesh m = make_icosphere(3);
    compute_vertex_normals(m);
    label_corners(m);
    const HalfedgeMesh before = m;
    const double v0 = volume(m);
    REQUIRE(v0 > 0);
    const FlipReport r = flip_orientation(m);
    REQUIRE_VALID(m);
    CHECK(r.faces == m.n_faces());
    REQUIRE(r.volume_before);
    CHECK(*r.volume_before == v0);
    CHECK(*r.volume_after == Approx(-v0).epsilon(1e-12));
    CHECK(volume(m) == Approx(-v0).epsilon(1e-12));
    CHECK(r.normals_negated);
    const auto c0 = corners(before), c1 = corners(m);
    const auto n0 = before.get_vertex_property<Vector3>("v:normal");
    const auto n1 = m.get_vertex_property<Vector3>("v:normal");
    for (Face f : m.faces()) {
        INFO("face " << f.idx());
        REQUIRE(reversed(c0[f.idx()], c1[f.idx()]));
        REQUIRE((face_normal(m, f) + face_normal(before, f)).norm() < 1e-12);
    }
    for (Vertex v : m.vertices()) {
        REQUIRE(m.position(v) == before.position(v));
        REQUIRE(n1[v] == -n0[v]);
        // The recomputed normal agrees with the negated stored one.
        REQUIRE((vertex_normal(m, v) - n1[v]).norm() < 1e-9);
    }
    require_corner_labels(m);
    // Twice is the identity, to the halfedge.
    flip_orientation(m);
    REQUIRE_VALID(m);
    for (Halfedge h : m.halfedges()) {
        REQUIRE(m.next(h) == before.next(h));
        REQUIRE(m.face(h) == before.face(h));
        REQUIRE(m.to_vertex(h) == before.to_vertex(h));
    }
    for (Vertex v : m.vertices()) REQUIRE(m.halfedge(v) == before.halfedge(v));
    for (Face f : m.faces()) REQUIRE(m.halfedge(f) == before.halfedge(f));
    require_corner_labels(m);
}

TEST_CASE("flip_orientation on open meshes, isolated and deleted elements", "[orientation]") {
    SECTION("a grid: the boundary loop is reversed, boundary vertices keep a boundary halfedge") {
        HalfedgeMesh m = make_grid(5);
        label_corners(m);
        const HalfedgeMesh before = m;
        const FlipReport r = flip_orientation(m);
        REQUIRE_VALID(m);
        CHECK_FALSE(r.volume_before);
        CHECK_FALSE(r.normals_negated);
        for (Face f : m.faces()) REQUIRE(face_normal(m, f).z() == Approx(-1.0));
        for (Vertex v : m.vertices())
            if (before.is_boundary(v)) REQUIRE(m.is_boundary(m.halfedge(v)));
        require_corner_labels(m);
    }
    SECTION("after a collapse (deleted elements kept) and with an isolated vertex") {
        HalfedgeMesh m = make_icosphere(2);
        m.add_vertex(Point(5, 5, 5));
        const Halfedge h = HalfedgeMesh::halfedge(Edge(7), 0);
        REQUIRE(m.is_collapse_ok(h));
        m.collapse(h);
        REQUIRE(m.has_garbage());
        label_corners(m);
        const double v0 = volume(m);
        flip_orientation(m);
        REQUIRE_VALID(m);
        CHECK(volume(m) == Approx(-v0).epsilon(1e-12));
        require_corner_labels(m);
        m.garbage_collection();
        REQUIRE_VALID(m);
    }
    SECTION("an empty mesh") {
        HalfedgeMesh m;
        const FlipReport r = flip_orientation(m);
        CHECK(r.faces == 0);
        REQUIRE_VALID(m);
    }
}

TEST_CASE("the in-place reversal gives every masked edge its definition and leaves the rest",
          "[orientation]") {
    // The definition, from the old arrays: next'(h) = twin(prev(twin(h))), prev'(h) =
    // twin(next(twin(h))), face'(h) = face(twin(h)), halfedge'(v) = twin(prev(halfedge(v))),
    // halfedge'(f) = twin(halfedge(f)); the edges outside the mask keep theirs. Two spheres
    // (the second reversed alone by a mask, or both), with per-corner labels; an open grid
    // (boundary loops); and a mesh with deleted elements.
    const std::string name =
        GENERATE(as<std::string>(), "second sphere", "both spheres", "grid", "garbage");
    INFO(name);
    HalfedgeMesh m = name == "grid" ? make_grid(6) : two_spheres();
    if (name == "garbage") {  // a collapse leaves a vertex, three edges and two faces deleted
        const Halfedge h = HalfedgeMesh::halfedge(Edge(10), 0);
        REQUIRE(m.is_collapse_ok(h));
        m.collapse(h);
        REQUIRE(m.has_garbage());
    }
    const std::size_t n = m.vertices_size() / 2;  // the second sphere's vertices follow
    std::vector<std::uint8_t> mask(m.edges_size(), 1);
    if (name == "second sphere")
        for (Edge e : m.edges()) mask[e.idx()] = m.vertex(e, 0).idx() >= n ? 1 : 0;
    label_corners(m);
    const auto arrays = [](const HalfedgeMesh& x) {
        return std::make_tuple(x.halfedge_to_array(), x.halfedge_next_array(),
                               x.halfedge_prev_array(), x.halfedge_face_array(),
                               x.vertex_halfedge_array(), x.face_halfedge_array());
    };
    auto [to, next, prev, face, vertex_halfedge, face_halfedge] = arrays(m);
    const auto in_mask = [&](Halfedge h) { return mask[h.idx() >> 1] != 0 && !m.is_deleted(h); };
    for (Vertex v : m.vertices()) {
        const Halfedge h = m.halfedge(v);
        if (h.is_valid() && in_mask(h)) vertex_halfedge[v.idx()] = HalfedgeMesh::twin(m.prev(h));
    }
    for (Face f : m.faces())
        if (in_mask(m.halfedge(f))) face_halfedge[f.idx()] = HalfedgeMesh::twin(m.halfedge(f));
    for (std::size_t i = 0; i < m.halfedges_size(); ++i) {
        const Halfedge h(static_cast<Index>(i)), t = HalfedgeMesh::twin(h);
        if (!in_mask(h)) continue;
        next[i] = HalfedgeMesh::twin(m.prev(t));
        prev[i] = HalfedgeMesh::twin(m.next(t));
        face[i] = m.face(t);
    }
    HalfedgeMesh flipped = m;
    if (name == "second sphere")
        flipped.reverse_orientation(mask);
    else
        flipped.reverse_orientation();
    CHECK(arrays(flipped) == std::make_tuple(to, next, prev, face, vertex_halfedge, face_halfedge));
    REQUIRE_VALID(flipped);
    require_corner_labels(flipped);
    if (name != "grid" && name != "garbage")
        for (Face f : m.faces()) {
            const bool turned = name == "both spheres" || m.face_vertices(f)[0].idx() >= n;
            CHECK(reversed(m.face_vertices(f), flipped.face_vertices(f)) == turned);
        }
    // Twice is the identity.
    if (name == "second sphere")
        flipped.reverse_orientation(mask);
    else
        flipped.reverse_orientation();
    CHECK(arrays(flipped) == arrays(m));

    // A mask of the wrong size is refused, and changes nothing.
    const std::vector<std::uint8_t> short_mask(3, 1);
    CHECK_THROWS_AS(flipped.reverse_orientation(short_mask), InvalidArgument);
    CHECK(arrays(flipped) == arrays(m));
}

TEST_CASE("the reversal flooded from seed vertices is the masked reversal of their components",
          "[orientation]") {
    // reverse_orientation_from() finds the components while it reverses them; the result must
    // be, array by array, reverse_orientation() with exactly those components' edges masked,
    // per-corner labels included. Two spheres (seeds on the second, on both, repeated, with an
    // isolated and a deleted vertex among them), an open grid (a boundary loop), none, and a
    // sphere large enough to make the flood's queue grow.
    const std::string name = GENERATE(as<std::string>(), "second sphere", "both spheres", "grid",
                                      "garbage", "no seed", "large sphere");
    INFO(name);
    // The large sphere's flood front (hundreds of edges) outgrows the queue's first ring.
    HalfedgeMesh m = name == "grid"           ? make_grid(6)
                     : name == "large sphere" ? make_icosphere(40)
                                              : two_spheres();
    const std::size_t n = m.vertices_size() / 2;  // the second sphere's vertices follow
    std::vector<Vertex> seeds;
    if (name == "second sphere") seeds = {Vertex(Index(n + 3)), Vertex(Index(n + 7))};
    if (name == "both spheres" || name == "garbage")
        seeds = {Vertex(Index(n + 1)), Vertex(0), Vertex(Index(n + 1)), Vertex(5)};
    if (name == "grid") seeds = {Vertex(0)};  // a corner: on the boundary
    if (name == "large sphere") seeds = {Vertex(Index(m.vertices_size() / 3))};
    if (name == "garbage") {
        const Halfedge h = HalfedgeMesh::halfedge(Edge(10), 0);
        REQUIRE(m.is_collapse_ok(h));
        const Vertex gone = m.from_vertex(h);
        m.collapse(h);
        REQUIRE(m.is_deleted(gone));
        seeds.insert(seeds.begin(), gone);
        seeds.push_back(m.add_vertex(Point(9, 9, 9)));  // isolated
    }
    label_corners(m);
    std::vector<std::uint8_t> mask(m.edges_size(), 0);
    for (Edge e : m.edges()) {
        const bool second = m.vertex(e, 0).idx() >= n;
        mask[e.idx()] = name == "grid" || name == "both spheres" || name == "garbage" ||
                        name == "large sphere" || (name == "second sphere" && second);
    }
    const auto arrays = [](const HalfedgeMesh& x) {
        return std::make_tuple(x.halfedge_to_array(), x.halfedge_next_array(),
                               x.halfedge_prev_array(), x.halfedge_face_array(),
                               x.vertex_halfedge_array(), x.face_halfedge_array());
    };
    HalfedgeMesh masked = m, flooded = m;
    masked.reverse_orientation(mask);
    const HalfedgeMesh::ReversedPart part = flooded.reverse_orientation_from(seeds);
    CHECK(arrays(flooded) == arrays(masked));
    REQUIRE_VALID(flooded);
    require_corner_labels(flooded);
    const std::size_t components = name == "no seed"                             ? 0
                                   : name == "both spheres" || name == "garbage" ? 2
                                                                                 : 1;
    CHECK(part.components == components);
    std::size_t faces = 0;
    for (Face f : m.faces()) faces += mask[m.halfedge(f).idx() >> 1];
    CHECK(part.faces == faces);
    std::vector<Vertex> expected;
    for (Vertex v : m.vertices())
        if (!m.is_isolated(v) && mask[m.halfedge(v).idx() >> 1]) expected.push_back(v);
    CHECK(part.vertices == expected);
    // Twice is the identity; without the list of vertices, the same reversal.
    const HalfedgeMesh::ReversedPart back = flooded.reverse_orientation_from(seeds, false);
    CHECK(arrays(flooded) == arrays(m));
    CHECK(back.vertices.empty());
    CHECK(back.faces == part.faces);
    // A seed out of range is refused before anything changes.
    std::vector<Vertex> bad = seeds;
    bad.push_back(Vertex(Index(m.vertices_size())));
    CHECK_THROWS_WITH(
        flooded.reverse_orientation_from(bad),
        Catch::Matchers::Contains("seed vertex") && Catch::Matchers::Contains("out of range"));
    CHECK(arrays(flooded) == arrays(m));
}

TEST_CASE("an inward-oriented closed mesh gets a load-report note naming its volume",
          "[orientation]") {
    HalfedgeMesh sphere = make_icosphere(3);
    CHECK(inward_orientation_note(sphere).empty());
    CHECK(inward_orientation_note(make_grid(4)).empty());  // open: no volume
    HalfedgeMesh inward = sphere;
    flip_orientation(inward);
    const std::string note = inward_orientation_note(inward);
    REQUIRE_THAT(note, Catch::Contains("volume is negative") &&
                           Catch::Contains("Flip orientation") &&
                           Catch::Contains("trilab-cli flip"));
    char volume_text[32];
    std::snprintf(volume_text, sizeof(volume_text), "%.6g", volume(inward));
    CHECK_THAT(note, Catch::Contains(volume_text));

    // Through a file: read_mesh adds the note; the flip operation removes the cause.
    TempDir dir;
    const std::string path = dir.path("inward.ply");
    write_mesh(inward, path);
    const LoadedMesh loaded = read_mesh(path);
    const auto lines = loaded.report.lines();
    REQUIRE(std::count_if(lines.begin(), lines.end(), [](const std::string& l) {
                return l.find("volume is negative") != std::string::npos;
            }) == 1);
    NullProgress progress;
    const OperationResult r = run_operation(parse_operation("flip"), loaded.mesh, progress);
    REQUIRE(r.label == "Flip orientation");
    REQUIRE(r.steps.size() == 1);
    REQUIRE_VALID(r.steps[0].mesh);
    CHECK(volume(r.steps[0].mesh) > 0);
    CHECK(inward_orientation_note(r.steps[0].mesh).empty());
    write_mesh(r.steps[0].mesh, dir.path("outward.ply"));
    for (const std::string& l : read_mesh(dir.path("outward.ply")).report.lines())
        CHECK(l.find("volume is negative") == std::string::npos);
}

TEST_CASE("the shared horse is oriented inwards: noted on load, outward after a flip",
          "[orientation][shared]") {
    const std::string path = shared_mesh("horse.ply");
    SKIP_IF_MISSING(path);
    const LoadedMesh loaded = read_mesh(path);
    REQUIRE(is_closed(loaded.mesh));
    const double v = volume(loaded.mesh);
    CHECK(v == Approx(-0.000263).epsilon(0.01));
    const auto lines = loaded.report.lines();
    REQUIRE(std::any_of(lines.begin(), lines.end(), [](const std::string& l) {
        return l.find("volume is negative (-0.000263") != std::string::npos;
    }));
    HalfedgeMesh m = loaded.mesh;
    const FlipReport r = flip_orientation(m);
    REQUIRE_VALID(m);
    CHECK(*r.volume_after == Approx(-v).epsilon(1e-9));
    CHECK(inward_orientation_note(m).empty());
}
