// The snapshot stack (app/history): undo, redo and jumps restore every state bit for bit over
// random operation sequences; morphs start at the earlier state and end at the later one;
// geometry-only steps share their predecessor's connectivity and attributes; the memory
// budget drops the oldest entries; a bad correspondence leaves the history unchanged.
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "app/history/history.h"
#include "core/algorithms/generators.h"
#include "core/errors.h"
#include "core/geometry.h"
#include "test_helpers.h"

using namespace trilab;

namespace {

using Kind = MorphCorrespondence::Kind;

// ---- exact comparison of two meshes ----------------------------------------------------

template <class T>
struct TypeTag {
    using type = T;
};

template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
    return a.size() == b.size() &&
           (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

/// Compares one attribute if it has type T in `a`; returns whether it had.
template <class T, class Get>
bool compare_attribute_as(Get get, const HalfedgeMesh& a, const HalfedgeMesh& b,
                          const std::string& name) {
    const auto pa = get(a, name, TypeTag<T>{});
    if (!pa) return false;
    const auto pb = get(b, name, TypeTag<T>{});
    INFO("attribute " << name);
    REQUIRE(bool(pb));
    if constexpr (std::is_same_v<T, std::string>)
        REQUIRE(pa.vector() == pb.vector());
    else
        REQUIRE(same_bits(pa.vector(), pb.vector()));
    return true;
}

template <class Get>
void compare_attributes(Get get, const std::vector<std::string>& names, const HalfedgeMesh& a,
                        const HalfedgeMesh& b) {
    for (const std::string& name : names) {
        const bool known = compare_attribute_as<Point>(get, a, b, name) ||
                           compare_attribute_as<TexCoord>(get, a, b, name) ||
                           compare_attribute_as<Color>(get, a, b, name) ||
                           compare_attribute_as<int>(get, a, b, name) ||
                           compare_attribute_as<float>(get, a, b, name) ||
                           compare_attribute_as<double>(get, a, b, name) ||
                           compare_attribute_as<std::uint8_t>(get, a, b, name) ||
                           compare_attribute_as<std::string>(get, a, b, name) ||
                           compare_attribute_as<Vertex>(get, a, b, name) ||
                           compare_attribute_as<Halfedge>(get, a, b, name) ||
                           compare_attribute_as<Face>(get, a, b, name);
        INFO("attribute " << name << " has a type the test does not compare");
        REQUIRE(known);
    }
}

/// Same storage sizes and the same connectivity, handle by handle.
void require_same_connectivity(const HalfedgeMesh& a, const HalfedgeMesh& b) {
    REQUIRE(a.vertices_size() == b.vertices_size());
    REQUIRE(a.halfedges_size() == b.halfedges_size());
    REQUIRE(a.edges_size() == b.edges_size());
    REQUIRE(a.faces_size() == b.faces_size());
    bool same = true;
    for (Index i = 0; i < a.halfedges_size(); ++i) {
        const Halfedge h(i);
        same = same && a.to_vertex(h) == b.to_vertex(h) && a.next(h) == b.next(h) &&
               a.prev(h) == b.prev(h) && a.face(h) == b.face(h);
    }
    for (Index i = 0; i < a.vertices_size(); ++i)
        same = same && a.halfedge(Vertex(i)) == b.halfedge(Vertex(i));
    for (Index i = 0; i < a.faces_size(); ++i)
        same = same && a.halfedge(Face(i)) == b.halfedge(Face(i));
    REQUIRE(same);
}

/// Identical states: positions bit for bit, connectivity, every attribute.
void require_same_mesh(const HalfedgeMesh& a, const HalfedgeMesh& b) {
    require_same_connectivity(a, b);
    REQUIRE(a.n_vertices() == b.n_vertices());
    REQUIRE(a.n_edges() == b.n_edges());
    REQUIRE(a.n_faces() == b.n_faces());
    REQUIRE(same_bits(a.positions(), b.positions()));
    REQUIRE(a.vertex_property_names() == b.vertex_property_names());
    REQUIRE(a.halfedge_property_names() == b.halfedge_property_names());
    REQUIRE(a.edge_property_names() == b.edge_property_names());
    REQUIRE(a.face_property_names() == b.face_property_names());
    compare_attributes(
        [](const HalfedgeMesh& m, const std::string& n, auto tag) {
            return m.get_vertex_property<typename decltype(tag)::type>(n);
        },
        a.vertex_property_names(), a, b);
    compare_attributes(
        [](const HalfedgeMesh& m, const std::string& n, auto tag) {
            return m.get_halfedge_property<typename decltype(tag)::type>(n);
        },
        a.halfedge_property_names(), a, b);
    compare_attributes(
        [](const HalfedgeMesh& m, const std::string& n, auto tag) {
            return m.get_edge_property<typename decltype(tag)::type>(n);
        },
        a.edge_property_names(), a, b);
    compare_attributes(
        [](const HalfedgeMesh& m, const std::string& n, auto tag) {
            return m.get_face_property<typename decltype(tag)::type>(n);
        },
        a.face_property_names(), a, b);
}

// ---- fixtures and operations done with core alone ---------------------------------------

/// A sphere with vertex normals, texture coordinates and colours, a face label and an edge
/// weight: every kind of attribute the history must carry.
HalfedgeMesh fixture() {
    HalfedgeMesh m = test::attributed_sphere();
    auto label = m.add_face_property<int>("f:label", -1);
    for (Face f : m.faces()) label[f] = int(f.idx() % 7);
    auto weight = m.add_edge_property<float>("e:weight", 1.0f);
    for (Edge e : m.edges()) weight[e] = 0.5f + float(e.idx() % 3);
    return m;
}

struct Op {
    HalfedgeMesh mesh;
    MorphCorrespondence correspondence;
};

Vector3 random_offset(std::mt19937& rng, double scale) {
    std::uniform_real_distribution<double> u(-scale, scale);
    const double x = u(rng), y = u(rng), z = u(rng);
    return Vector3(x, y, z);
}

/// Moves about a third of the vertices (at least one): a geometry-only step. With
/// `refresh_normals` it recomputes "v:normal" as an operation like noise does.
Op move_vertices(const HalfedgeMesh& before, std::mt19937& rng, bool refresh_normals) {
    Op op{before, {}};
    std::bernoulli_distribution pick(0.3);
    bool moved = false;
    for (Vertex v : op.mesh.vertices()) {
        if (pick(rng) || !moved) {
            op.mesh.position(v) += random_offset(rng, 0.02);
            moved = true;
        }
    }
    if (refresh_normals && op.mesh.has_vertex_property("v:normal")) compute_vertex_normals(op.mesh);
    return op;
}

/// Changes some face labels and vertex colours only (same vertices, same positions).
Op repaint(const HalfedgeMesh& before, std::mt19937& rng) {
    Op op{before, {}};
    auto label = op.mesh.get_face_property<int>("f:label");
    auto color = op.mesh.get_vertex_property<Color>("v:color");
    std::uniform_int_distribution<int> value(0, 99);
    for (Face f : op.mesh.faces())
        if (label && value(rng) < 20) label[f] = value(rng);
    for (Vertex v : op.mesh.vertices())
        if (color && value(rng) < 20) color[v] = Color(0.1f, float(value(rng)) / 99.0f, 0.3f);
    return op;
}

/// Flips one edge: same vertices, new connectivity (a SameVertices step with a full mesh).
Op flip_edge(const HalfedgeMesh& before, std::mt19937& rng) {
    Op op{before, {}};
    for (int tries = 0; tries < 200; ++tries) {
        const Edge e(Index(rng() % op.mesh.edges_size()));
        if (!op.mesh.is_deleted(e) && op.mesh.is_flip_ok(e)) {
            op.mesh.flip(e);
            return op;
        }
    }
    return move_vertices(before, rng, false);
}

/// Splits a face 1-to-3 or an edge 2-to-4; the new vertex ends off the surface and starts at
/// the face centroid or edge midpoint (FromEarlier); old vertices start where they were.
Op split(const HalfedgeMesh& before, std::mt19937& rng, bool face) {
    Op op{before, {Kind::FromEarlier, before.positions()}};
    Point start;
    if (face) {
        const Face f(Index(rng() % op.mesh.faces_size()));
        start = face_centroid(op.mesh, f);
        op.mesh.split(f, start + random_offset(rng, 0.05));
    } else {
        const Edge e(Index(rng() % op.mesh.edges_size()));
        start =
            0.5 * (op.mesh.position(op.mesh.vertex(e, 0)) + op.mesh.position(op.mesh.vertex(e, 1)));
        op.mesh.split(e, start + random_offset(rng, 0.05));
    }
    op.mesh.garbage_collection();  // nothing to collect: old indices stay, the new one is last
    op.correspondence.positions.push_back(start);
    REQUIRE(op.correspondence.positions.size() == op.mesh.vertices_size());
    return op;
}

/// Collapses one edge (ToLater: the removed vertex travels to its collapse target).
Op collapse(const HalfedgeMesh& before, std::mt19937& rng) {
    Op op{before, {Kind::ToLater, before.positions()}};
    for (int tries = 0; tries < 200; ++tries) {
        const Halfedge h(Index(rng() % op.mesh.halfedges_size()));
        if (op.mesh.is_deleted(h) || !op.mesh.is_collapse_ok(h)) continue;
        op.correspondence.positions[op.mesh.from_vertex(h).idx()] =
            op.mesh.position(op.mesh.to_vertex(h));
        op.mesh.collapse(h);
        op.mesh.garbage_collection();
        return op;
    }
    return move_vertices(before, rng, false);
}

Op random_op(const HalfedgeMesh& before, std::mt19937& rng) {
    switch (rng() % 7) {
        case 0:
            return move_vertices(before, rng, false);
        case 1:
            return move_vertices(before, rng, true);
        case 2:
            return repaint(before, rng);
        case 3:
            return flip_edge(before, rng);
        case 4:
            return split(before, rng, true);
        case 5:
            return split(before, rng, false);
        default:
            return collapse(before, rng);
    }
}

struct Expected {
    HalfedgeMesh mesh;
    MorphCorrespondence correspondence;
};

double drawn_area(const MorphFrame& frame) {
    double area = 0;
    const HalfedgeMesh& m = *frame.topology;
    for (Face f : m.faces()) {
        const auto c = m.face_vertices(f);
        const Point& a = frame.positions[c[0].idx()];
        const Point& b = frame.positions[c[1].idx()];
        const Point& d = frame.positions[c[2].idx()];
        area += 0.5 * (b - a).cross(d - a).norm();
    }
    return area;
}

/// The frame shows `before`: the shape of the earlier state, drawn on the mesh the step says
/// (the later state itself, or the earlier one for ToLater).
void require_frame_is_before(const MorphFrame& frame, const HalfedgeMesh& before,
                             const HalfedgeMesh& after, const MorphCorrespondence& correspondence) {
    REQUIRE(frame.topology != nullptr);
    REQUIRE(frame.positions.size() == frame.topology->vertices_size());
    switch (correspondence.kind) {
        case Kind::SameVertices:
            require_same_mesh(*frame.topology, after);
            REQUIRE(same_bits(frame.positions, before.positions()));
            break;
        case Kind::FromEarlier: {
            require_same_mesh(*frame.topology, after);
            REQUIRE(same_bits(frame.positions, correspondence.positions));
            // Old vertices where they were; new ones on the earlier surface (same area).
            const std::vector<Point> old(frame.positions.begin(),
                                         frame.positions.begin() + before.vertices_size());
            REQUIRE(same_bits(old, before.positions()));
            REQUIRE(drawn_area(frame) == Approx(surface_area(before)).epsilon(1e-12));
            break;
        }
        case Kind::ToLater:
            require_same_mesh(*frame.topology, before);
            REQUIRE(same_bits(frame.positions, before.positions()));
            break;
    }
}

/// The frame shows `after` exactly, on `after` itself.
void require_frame_is_after(const MorphFrame& frame, const HalfedgeMesh& after) {
    REQUIRE(frame.topology != nullptr);
    require_same_mesh(*frame.topology, after);
    REQUIRE(same_bits(frame.positions, after.positions()));
}

/// Checks morph(index, t) at both ends and at every step boundary of a (multi-step) entry.
void require_morph_ends(const History& h, const std::vector<std::vector<Expected>>& expected,
                        std::size_t index) {
    const std::vector<Expected>& steps = expected[index];
    const std::size_t n = steps.size();
    INFO("entry " << index << " with " << n << " steps");
    // t = 0: the state before the entry; t = 1: the entry's last step.
    require_frame_is_before(h.morph(index, 0.0), expected[index - 1].back().mesh, steps[0].mesh,
                            steps[0].correspondence);
    require_frame_is_after(h.morph(index, 1.0), steps.back().mesh);
    // t = k / n starts step k from the state after step k - 1.
    for (std::size_t k = 1; k < n; ++k) {
        INFO("boundary before step " << k);
        require_frame_is_before(h.morph(index, double(k) / double(n)), steps[k - 1].mesh,
                                steps[k].mesh, steps[k].correspondence);
    }
}

std::size_t positions_bytes(const HalfedgeMesh& m) {
    return m.vertices_size() * sizeof(Point);
}

}  // namespace

TEST_CASE("undo, redo and jump over random operations restore identical states", "[history]") {
    const unsigned seed = GENERATE(1u, 2u, 3u, 4u, 5u, 6u);
    INFO("seed " << seed);
    std::mt19937 rng(seed);
    History h;
    std::vector<std::vector<Expected>> expected;
    h.reset(fixture(), "Load", "fixture");
    expected.push_back({{fixture(), {}}});
    REQUIRE_VALID(h.current_mesh());

    for (int round = 0; round < 100; ++round) {
        INFO("round " << round);
        const unsigned action = rng() % 10;
        if (action < 5) {
            const std::size_t n_steps = 1 + rng() % 3;
            std::vector<HalfedgeMesh> meshes;
            std::vector<MorphCorrespondence> correspondences;
            std::vector<Expected> steps;
            HalfedgeMesh previous = h.current_mesh();
            for (std::size_t k = 0; k < n_steps; ++k) {
                Op op = random_op(previous, rng);
                REQUIRE_VALID(op.mesh);
                steps.push_back({op.mesh, op.correspondence});
                meshes.push_back(op.mesh);
                correspondences.push_back(op.correspondence);
                previous = std::move(op.mesh);
            }
            const std::size_t at = h.current();
            const auto messages = h.push("op " + std::to_string(round), "--round", 1.5,
                                         std::move(meshes), std::move(correspondences));
            REQUIRE(messages.empty());
            expected.resize(at + 1);
            expected.push_back(std::move(steps));
            REQUIRE(h.current() == at + 1);
            REQUIRE_FALSE(h.can_redo());
        } else if (action < 7) {
            const bool could = h.can_undo();
            const std::size_t at = h.current();
            h.undo();
            REQUIRE(h.current() == (could ? at - 1 : at));
        } else if (action < 9) {
            const bool could = h.can_redo();
            const std::size_t at = h.current();
            h.redo();
            REQUIRE(h.current() == (could ? at + 1 : at));
        } else {
            const std::size_t target = rng() % h.size();
            h.jump(target);
            REQUIRE(h.current() == target);
        }
        REQUIRE(h.size() == expected.size());
        require_same_mesh(h.current_mesh(), expected[h.current()].back().mesh);
        REQUIRE_VALID(h.current_mesh());
    }

    // Every step of every entry, its description, and the morphs between them.
    std::size_t sum = 0;
    for (std::size_t i = 0; i < h.size(); ++i) {
        const History::EntryInfo info = h.info(i);
        REQUIRE(info.steps.size() == expected[i].size());
        sum += info.bytes;
        for (std::size_t k = 0; k < expected[i].size(); ++k) {
            const HalfedgeMesh& want = expected[i][k].mesh;
            const HalfedgeMesh got = h.mesh(i, k);
            REQUIRE_VALID(got);
            require_same_mesh(got, want);
            REQUIRE(info.steps[k].vertices == want.n_vertices());
            REQUIRE(info.steps[k].faces == want.n_faces());
            REQUIRE(info.steps[k].kind == expected[i][k].correspondence.kind);
        }
        if (i > 0) require_morph_ends(h, expected, i);
    }
    REQUIRE(sum == h.bytes());
    // Walking the whole stack back and forth again still gives the same states.
    h.jump(0);
    require_same_mesh(h.current_mesh(), expected[0].back().mesh);
    while (h.can_redo()) {
        h.redo();
        require_same_mesh(h.current_mesh(), expected[h.current()].back().mesh);
    }
    while (h.can_undo()) {
        h.undo();
        require_same_mesh(h.current_mesh(), expected[h.current()].back().mesh);
    }
}

TEST_CASE("undo and redo do nothing at the ends, jump checks its index", "[history]") {
    History h;
    REQUIRE(h.size() == 0);
    REQUIRE_FALSE(h.can_undo());
    REQUIRE_FALSE(h.can_redo());
    REQUIRE(h.current_mesh().is_empty());
    h.reset(make_icosahedron(), "Load");
    h.undo();
    h.redo();
    REQUIRE(h.current() == 0);
    REQUIRE_THROWS_AS(h.jump(1), InvalidArgument);
    REQUIRE_THROWS_AS(h.info(1), InvalidArgument);
    REQUIRE_THROWS_AS(h.mesh(0, 1), InvalidArgument);
    REQUIRE_THROWS_AS(h.morph(0, 0.5), InvalidArgument);
    std::mt19937 rng(5);
    Op a = move_vertices(h.current_mesh(), rng, false);
    h.push("Move", "", 0, {a.mesh}, {a.correspondence});
    h.jump(0);
    REQUIRE(h.current() == 0);
    require_same_mesh(h.current_mesh(), make_icosahedron());
    h.jump(1);
    require_same_mesh(h.current_mesh(), a.mesh);
    REQUIRE(h.info(1).label == "Move");
}

TEST_CASE("pushing after an undo drops the redo entries", "[history]") {
    std::mt19937 rng(11);
    History h;
    h.reset(fixture(), "Load");
    Op a = move_vertices(h.current_mesh(), rng, false);
    h.push("A", "", 0, {a.mesh}, {a.correspondence});
    Op b = split(h.current_mesh(), rng, true);
    h.push("B", "", 0, {b.mesh}, {b.correspondence});
    h.undo();
    REQUIRE(h.can_redo());
    Op c = collapse(h.current_mesh(), rng);
    h.push("C", "--x 1", 2.5, {c.mesh}, {c.correspondence});
    REQUIRE(h.size() == 3);
    REQUIRE(h.current() == 2);
    REQUIRE_FALSE(h.can_redo());
    REQUIRE(h.info(2).label == "C");
    REQUIRE(h.info(2).parameters == "--x 1");
    REQUIRE(h.info(2).ms == 2.5);
    require_same_mesh(h.current_mesh(), c.mesh);
    h.undo();
    require_same_mesh(h.current_mesh(), a.mesh);
}

TEST_CASE("morph runs from the earlier state to the later one through every step", "[history]") {
    std::mt19937 rng(21);
    History h;
    h.reset(fixture(), "Load");
    std::vector<std::vector<Expected>> expected{{{fixture(), {}}}};
    // One entry per kind, then a mixed multi-step entry (like an iterated operation).
    auto push = [&](std::vector<Op> ops) {
        std::vector<HalfedgeMesh> meshes;
        std::vector<MorphCorrespondence> correspondences;
        std::vector<Expected> steps;
        for (Op& op : ops) {
            steps.push_back({op.mesh, op.correspondence});
            meshes.push_back(op.mesh);
            correspondences.push_back(op.correspondence);
        }
        h.push("step", "", 0, std::move(meshes), std::move(correspondences));
        expected.push_back(std::move(steps));
    };
    push({move_vertices(h.current_mesh(), rng, true)});
    push({split(h.current_mesh(), rng, true)});
    push({collapse(h.current_mesh(), rng)});
    {
        std::vector<Op> ops;
        ops.push_back(move_vertices(h.current_mesh(), rng, false));
        ops.push_back(move_vertices(ops.back().mesh, rng, true));
        ops.push_back(split(ops.back().mesh, rng, false));
        ops.push_back(collapse(ops.back().mesh, rng));
        ops.push_back(move_vertices(ops.back().mesh, rng, false));
        push(std::move(ops));
    }
    for (std::size_t i = 1; i < h.size(); ++i) require_morph_ends(h, expected, i);

    // Half way through a geometry-only entry: the midpoint of every vertex.
    const MorphFrame mid = h.morph(1, 0.5);
    const auto& p0 = expected[0][0].mesh.positions();
    const auto& p1 = expected[1][0].mesh.positions();
    for (std::size_t i = 0; i < p0.size(); ++i)
        REQUIRE((mid.positions[i] - 0.5 * (p0[i] + p1[i])).norm() < 1e-15);
    // t is clamped; within the 5-step entry, t = 0.5 falls in step 2 (an edge split).
    require_frame_is_after(h.morph(4, 7.0), expected[4].back().mesh);
    require_frame_is_before(h.morph(4, -1.0), expected[3].back().mesh, expected[4][0].mesh,
                            expected[4][0].correspondence);
    REQUIRE(h.morph(4, 0.5).topology->vertices_size() == expected[4][2].mesh.vertices_size());

    // The topology of a frame stays valid, and is the same for the same step, until the
    // history changes, however many other morphs come between.
    const MorphFrame kept = h.morph(4, 0.1);
    for (int i = 0; i < 20; ++i) h.morph(1 + std::size_t(i) % 4, double(i) / 20.0);
    REQUIRE(h.morph(4, 0.15).topology == kept.topology);
    require_same_mesh(*kept.topology, expected[4][0].mesh);
    REQUIRE_VALID(*kept.topology);
    // Every step of a chain of geometry-only steps has its own state (same connectivity).
    REQUIRE(h.morph(4, 0.1).topology != h.morph(4, 0.3).topology);
}

TEST_CASE("a geometry-only step stores its positions and shares the rest", "[history]") {
    std::mt19937 rng(31);
    HalfedgeMesh start = make_torus(60, 30, 1.0, 0.3);
    start.add_vertex_property<Color>("v:color", Color(0.5f, 0.5f, 0.5f));
    History h;
    h.reset(start, "Load");
    const std::size_t full = h.info(0).bytes;
    const std::size_t positions = positions_bytes(start);
    // v:position 24 + v:halfedge 4 + v:deleted 1 + v:color 12 per vertex, 16 per halfedge
    // (to, next, prev, face), 1 per edge, 5 per face.
    REQUIRE(full == start.vertices_size() * 41 + start.halfedges_size() * 16 + start.edges_size() +
                        start.faces_size() * 5);

    Op moved = move_vertices(h.current_mesh(), rng, false);
    h.push("Move", "", 0, {moved.mesh}, {moved.correspondence});
    REQUIRE(h.info(1).bytes == positions);
    REQUIRE(h.info(1).bytes * 4 < full);

    // A chain of geometry-only steps in one entry: each costs its positions.
    std::vector<HalfedgeMesh> chain;
    std::vector<MorphCorrespondence> same(3);
    for (int k = 0; k < 3; ++k)
        chain.push_back(move_vertices(k ? chain.back() : h.current_mesh(), rng, false).mesh);
    const std::vector<HalfedgeMesh> chain_copy = chain;
    h.push("Move x3", "", 0, std::move(chain), same);
    REQUIRE(h.info(2).bytes == 3 * positions);

    // Changed colours cost their array; the unchanged positions are shared too.
    Op painted = repaint(h.current_mesh(), rng);
    h.push("Paint", "", 0, {painted.mesh}, {painted.correspondence});
    REQUIRE(h.info(3).bytes == start.vertices_size() * sizeof(Color));

    // New connectivity (a flip) with the same vertices: the changed connectivity arrays (at
    // least h:to, h:next and h:prev), sharing the positions, colours and the rest.
    Op flipped = flip_edge(h.current_mesh(), rng);
    h.push("Flip", "", 0, {flipped.mesh}, {flipped.correspondence});
    REQUIRE(h.info(4).bytes >= 3 * 4 * start.halfedges_size());
    REQUIRE(h.info(4).bytes <= full - positions - start.vertices_size() * sizeof(Color));
    // A move after it shares the flipped mesh.
    Op moved_again = move_vertices(h.current_mesh(), rng, false);
    h.push("Move", "", 0, {moved_again.mesh}, {moved_again.correspondence});
    REQUIRE(h.info(5).bytes == positions);

    // An attribute of a type that cannot be compared bit for bit (strings) costs its array;
    // a step made from a copy still shares it.
    HalfedgeMesh named = h.current_mesh();
    auto tag = named.add_vertex_property<std::string>("v:tag");
    tag[Vertex(0)] = "first";
    h.push("Tag", "", 0, {named}, {MorphCorrespondence{}});
    Op moved_tagged = move_vertices(h.current_mesh(), rng, false);
    h.push("Move", "", 0, {moved_tagged.mesh}, {moved_tagged.correspondence});
    REQUIRE(h.info(6).bytes == start.vertices_size() * sizeof(std::string));
    REQUIRE(h.info(7).bytes == positions);

    REQUIRE(h.bytes() == full + h.info(4).bytes + 5 * positions +
                             start.vertices_size() * sizeof(Color) + h.info(6).bytes +
                             h.info(7).bytes);
    // Everything still comes back exactly.
    require_same_mesh(h.mesh(1, 0), moved.mesh);
    for (std::size_t k = 0; k < 3; ++k) require_same_mesh(h.mesh(2, k), chain_copy[k]);
    require_same_mesh(h.mesh(3, 0), painted.mesh);
    require_same_mesh(h.mesh(5, 0), moved_again.mesh);
    require_same_mesh(h.mesh(7, 0), moved_tagged.mesh);
    h.jump(3);
    require_same_mesh(h.current_mesh(), painted.mesh);
}

TEST_CASE("the memory budget drops the oldest entries with a message", "[history]") {
    std::mt19937 rng(41);

    SECTION("full meshes") {
        // Splits add elements to every array, so no entry shares anything with another.
        History h;
        h.reset(make_icosphere(3), "Load", "sphere");
        const std::size_t full = h.info(0).bytes;
        h.set_budget(full * 4);  // three splits fit (each a full mesh and its start positions)
        std::vector<HalfedgeMesh> states{make_icosphere(3)};
        for (int i = 1; i <= 5; ++i) {
            Op op = split(h.current_mesh(), rng, true);
            states.push_back(op.mesh);
            const auto messages =
                h.push("Flip " + std::to_string(i), "--edge", 0, {op.mesh}, {op.correspondence});
            REQUIRE(h.bytes() <= h.budget());
            if (i < 3) {
                REQUIRE(messages.empty());
                continue;
            }
            REQUIRE(messages.size() == 1);
            const std::string dropped =
                i == 3 ? "\"Load\" (sphere)" : "\"Flip " + std::to_string(i - 3) + "\" (--edge)";
            INFO(messages[0]);
            REQUIRE(messages[0].find(dropped) != std::string::npos);
            REQUIRE(messages[0].find("freed") != std::string::npos);
            REQUIRE(h.size() == 3);
            REQUIRE(h.current() == 2);
        }
        // The three newest states remain, exactly.
        for (std::size_t i = 0; i < 3; ++i) require_same_mesh(h.mesh(i, 0), states[3 + i]);
        require_same_mesh(h.current_mesh(), states[5]);
        REQUIRE_FALSE(h.morph(1, 0.5).positions.empty());
    }

    SECTION("a dropped entry frees what no later entry shares; the rest counts with the oldest") {
        HalfedgeMesh start = make_torus(40, 20, 1.0, 0.3);
        History h;
        h.reset(start, "Load");
        const std::size_t full = h.info(0).bytes;
        const std::size_t positions = positions_bytes(start);
        std::vector<HalfedgeMesh> states{start};
        for (int i = 1; i <= 5; ++i) {
            Op op = move_vertices(h.current_mesh(), rng, false);
            states.push_back(op.mesh);
            h.push("Move " + std::to_string(i), "", 0, {op.mesh}, {op.correspondence});
        }
        REQUIRE(h.bytes() == full + 5 * positions);
        h.set_budget(full + 5 * positions / 2);
        const auto messages = h.trim_to_budget();
        // Dropping "Load" frees its positions only (its connectivity is shared by every later
        // step); then each dropped move frees its positions until the rest fits.
        REQUIRE(messages.size() == 3);
        REQUIRE(messages[0].find("\"Load\"") != std::string::npos);
        REQUIRE(messages[0].find("freed 0 bytes") == std::string::npos);
        REQUIRE(messages[1].find("\"Move 1\"") != std::string::npos);
        REQUIRE(messages[2].find("\"Move 2\"") != std::string::npos);
        REQUIRE(h.size() == 3);
        REQUIRE(h.current() == 2);
        REQUIRE(h.bytes() == full + 2 * positions);
        REQUIRE(h.info(0).bytes == full);  // carries the shared connectivity now
        REQUIRE(h.info(1).bytes == positions);
        REQUIRE(h.info(2).bytes == positions);
        require_same_mesh(h.mesh(1, 0), states[4]);
        require_same_mesh(h.mesh(2, 0), states[5]);
        require_same_mesh(h.current_mesh(), states[5]);
        require_frame_is_after(h.morph(2, 1.0), states[5]);
        h.undo();
        require_same_mesh(h.current_mesh(), states[4]);
    }

    SECTION("the current entry is never dropped, redo entries are kept") {
        History h;
        h.reset(make_icosphere(2), "Load");
        std::vector<HalfedgeMesh> states{make_icosphere(2)};
        for (int i = 1; i <= 3; ++i) {
            Op op = split(h.current_mesh(), rng, true);
            states.push_back(op.mesh);
            h.push("Split", "", 0, {op.mesh}, {op.correspondence});
        }
        h.jump(1);
        h.set_budget(1);
        REQUIRE(h.trim_to_budget().size() == 1);
        REQUIRE(h.size() == 3);
        REQUIRE(h.current() == 0);
        require_same_mesh(h.current_mesh(), states[1]);
        REQUIRE(h.trim_to_budget().empty());
        h.redo();
        require_same_mesh(h.current_mesh(), states[2]);
        // A push with a budget no single entry fits keeps just the new entry.
        Op op = collapse(h.current_mesh(), rng);
        const auto messages = h.push("Collapse", "", 0, {op.mesh}, {op.correspondence});
        REQUIRE(messages.size() == 2);
        REQUIRE(h.size() == 1);
        require_same_mesh(h.current_mesh(), op.mesh);
        REQUIRE_VALID(h.current_mesh());
    }

    SECTION("the default budget is a quarter of the memory") {
        REQUIRE(History::default_budget() > 0);
        REQUIRE(History().budget() == History::default_budget());
    }
}

TEST_CASE("a bad push throws and leaves the history unchanged", "[history]") {
    std::mt19937 rng(51);
    History h;
    REQUIRE_THROWS_AS(h.push("Early", "", 0, {make_tetrahedron()}, {MorphCorrespondence{}}),
                      InvalidArgument);
    h.reset(fixture(), "Load");
    Op a = move_vertices(h.current_mesh(), rng, true);
    h.push("A", "", 0, {a.mesh}, {a.correspondence});
    Op b = split(h.current_mesh(), rng, false);
    h.push("B", "", 0, {b.mesh}, {b.correspondence});
    h.undo();
    const std::size_t bytes = h.bytes();

    auto require_unchanged = [&] {
        REQUIRE(h.size() == 3);
        REQUIRE(h.current() == 1);
        REQUIRE(h.can_redo());
        REQUIRE(h.bytes() == bytes);
        require_same_mesh(h.current_mesh(), a.mesh);
        require_same_mesh(h.mesh(2, 0), b.mesh);
    };

    // Start positions for the wrong number of vertices.
    Op bad = split(h.current_mesh(), rng, true);
    bad.correspondence.positions.pop_back();
    REQUIRE_THROWS_AS(h.push("Bad", "", 0, {bad.mesh}, {bad.correspondence}), InvalidArgument);
    require_unchanged();
    // "Same vertices" for a mesh with another vertex count.
    Op grown = split(h.current_mesh(), rng, true);
    REQUIRE_THROWS_AS(h.push("Bad", "", 0, {grown.mesh}, {MorphCorrespondence{}}), InvalidArgument);
    require_unchanged();
    // The second step is checked against the first step, not the current state.
    Op first = collapse(h.current_mesh(), rng);
    Op second = move_vertices(first.mesh, rng, false);
    MorphCorrespondence end_positions{Kind::ToLater, h.current_mesh().positions()};
    try {
        h.push("Bad", "", 0, {first.mesh, second.mesh}, {first.correspondence, end_positions});
        FAIL("push accepted a bad second step");
    } catch (const InvalidArgument& e) {
        REQUIRE(std::string(e.what()).find("step 1") != std::string::npos);
    }
    require_unchanged();
    // Non-finite positions, counts that differ, no steps.
    Op nan = split(h.current_mesh(), rng, true);
    nan.correspondence.positions[0].x() = std::numeric_limits<double>::quiet_NaN();
    REQUIRE_THROWS_AS(h.push("Bad", "", 0, {nan.mesh}, {nan.correspondence}), InvalidArgument);
    REQUIRE_THROWS_AS(h.push("Bad", "", 0, {first.mesh}, {}), InvalidArgument);
    REQUIRE_THROWS_AS(h.push("Bad", "", 0, {}, {}), InvalidArgument);
    require_unchanged();
    // The good version of the two steps goes in.
    h.push("Good", "", 0, {first.mesh, second.mesh}, {first.correspondence, second.correspondence});
    REQUIRE(h.size() == 3);
    REQUIRE_FALSE(h.can_redo());
    require_same_mesh(h.current_mesh(), second.mesh);
}

TEST_CASE("memory of a geometry-only step against a full mesh on a large torus",
          "[.][history-memory]") {
    HalfedgeMesh start = make_torus(1000, 500, 1.0, 0.3);
    History h;
    h.reset(start, "Load");
    HalfedgeMesh moved = start;
    for (Point& p : moved.positions()) p.z() += 1e-3;
    h.push("Move", "", 0, {moved}, {MorphCorrespondence{}});
    HalfedgeMesh flipped = start;
    flipped.flip(Edge(0));
    h.push("Flip", "", 0, {flipped}, {MorphCorrespondence{}});
    WARN("make_torus(1000, 500, 1, 0.3): "
         << start.n_vertices() << " vertices, " << start.n_faces() << " faces; full mesh "
         << h.info(0).bytes << " bytes; geometry-only step " << h.info(1).bytes
         << " bytes; flip (full) " << h.info(2).bytes << " bytes");
    REQUIRE(h.info(1).bytes == positions_bytes(start));
}
