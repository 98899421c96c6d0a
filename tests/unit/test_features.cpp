// Features (issue 39): the feature graph (sharpness and corner tags as mesh properties, checked
// by validate(), carried by copies, splits, files), the vertex classes, detection by the
// dihedral angle with its histogram and plateau, the "features" operation, and Loop
// subdivision with crease rules against OpenSubdiv 3.5 (the oracle program built from
// tests/oracle/osd_loop_oracle.cpp where libosd-dev is installed; skipped clearly otherwise).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <string>
#include <unordered_map>
#include <vector>

#include <unistd.h>

#include "app/history/session_file.h"
#include "app/ops/operation.h"
#include "app/ops/region_spec.h"
#include "core/algorithms/decimation.h"
#include "core/algorithms/feature_detection.h"
#include "core/algorithms/generators.h"
#include "core/algorithms/mesh_distance.h"
#include "core/algorithms/noise.h"
#include "core/algorithms/region_subdivision.h"
#include "core/algorithms/selection.h"
#include "core/algorithms/subdivision.h"
#include "core/errors.h"
#include "core/features.h"
#include "core/geometry.h"
#include "core/io/mesh_io.h"
#include "core/mesh_builder.h"
#include "session_test_util.h"
#include "test_helpers.h"

using namespace trilab;

namespace {

/// The edge joining a and b (invalid when none).
Edge edge_between(const HalfedgeMesh& m, Vertex a, Vertex b) {
    for (Halfedge h : m.halfedges_around(a))
        if (m.to_vertex(h) == b) return HalfedgeMesh::edge(h);
    return Edge();
}

/// Vertex pairs of the sharp edges (sorted pair -> sharpness).
std::map<std::pair<Index, Index>, float> sharp_pairs(const HalfedgeMesh& m) {
    std::map<std::pair<Index, Index>, float> out;
    const auto s = m.get_edge_property<float>(kSharpnessProperty);
    if (!s) return out;
    for (Edge e : m.edges()) {
        if (!(s[e] > 0.0f)) continue;
        Index a = m.to_vertex(m.halfedge(e, 0)).idx(), b = m.to_vertex(m.halfedge(e, 1)).idx();
        if (a > b) std::swap(a, b);
        out[{a, b}] = s[e];
    }
    return out;
}

HalfedgeMesh load_fandisk() {
    return read_mesh(test::shared_mesh("fandisk.obj")).mesh;
}

}  // namespace

TEST_CASE("sharpness and corner tags are checked, shared by copies and kept by splits",
          "[features]") {
    HalfedgeMesh m = make_icosahedron();
    REQUIRE_FALSE(has_features(m));
    const Edge e0(0), e1(5);
    set_sharpness(m, e0, kInfiniteSharpness);
    set_sharpness(m, e1, 0.5f);
    REQUIRE(has_features(m));
    REQUIRE_VALID(m);
    // Bad values change nothing.
    REQUIRE_THROWS_AS(set_sharpness(m, e1, -1.0f), InvalidArgument);
    {
        const test::FpTrapsOff traps_off;  // NaN on purpose
        REQUIRE_THROWS_AS(set_sharpness(m, e1, std::numeric_limits<float>::quiet_NaN()),
                          InvalidArgument);
    }
    REQUIRE_THROWS_AS(set_sharpness(m, Edge(Index(m.edges_size())), 1.0f), InvalidArgument);
    REQUIRE(sharpness(m, e1) == 0.5f);
    // Copy-on-write: the copy shares the values until one of them writes.
    HalfedgeMesh copy = m;
    set_sharpness(copy, e1, 3.0f);
    CHECK(sharpness(m, e1) == 0.5f);
    CHECK(sharpness(copy, e1) == 3.0f);
    // validate() names a broken value.
    HalfedgeMesh broken = m;
    sharpness_property(broken)[e1] = -2.0f;
    const ValidationResult bad = validate(broken);
    REQUIRE_FALSE(bad.ok);
    CHECK(bad.message.find("edge 5") != std::string::npos);
    corner_property(broken)[Vertex(0)] = 2;
    sharpness_property(broken)[e1] = 1.0f;
    CHECK_FALSE(validate(broken).ok);
    // A split edge's two halves keep its sharpness; the new cross edges are smooth.
    const std::size_t before = m.edges_size();
    const Vertex a = m.to_vertex(m.halfedge(e0, 1)), b = m.to_vertex(m.halfedge(e0, 0));
    const Vertex v = m.split(e0, 0.5 * (m.position(a) + m.position(b)));
    REQUIRE_VALID(m);
    CHECK(sharpness(m, edge_between(m, a, v)) == kInfiniteSharpness);
    CHECK(sharpness(m, edge_between(m, v, b)) == kInfiniteSharpness);
    for (std::size_t e = before; e < m.edges_size(); ++e)
        if (edge_between(m, a, v) != Edge(Index(e)) && edge_between(m, v, b) != Edge(Index(e)))
            CHECK(sharpness(m, Edge(Index(e))) == 0.0f);
    // Garbage collection moves them with their edges.
    HalfedgeMesh g = m;
    g.collapse(g.halfedge(Edge(Index(m.edges_size() - 1)), 0));
    const auto pairs_before = sharp_pairs(g);
    g.garbage_collection();
    REQUIRE_VALID(g);
    CHECK(sharp_pairs(g).size() == pairs_before.size());
}

TEST_CASE("vertices are classified as OpenSubdiv does", "[features]") {
    HalfedgeMesh m = make_icosahedron();
    // A path of sharp edges a - b - c - d, and a fourth edge at c: b is a crease, a a dart...
    const Vertex c(0);
    std::vector<Vertex> ring;
    for (Vertex w : m.vertices_around(c)) ring.push_back(w);
    REQUIRE(ring.size() == 5);
    set_sharpness(m, edge_between(m, c, ring[0]), 1.0f);
    VertexClassification k = classify_vertices(m, false);
    CHECK(k.classes[c.idx()] == VertexClass::Dart);
    CHECK(k.classes[ring[0].idx()] == VertexClass::Dart);
    CHECK(k.darts == 2);
    set_sharpness(m, edge_between(m, c, ring[2]), kInfiniteSharpness);
    k = classify_vertices(m, false);
    CHECK(k.classes[c.idx()] == VertexClass::Crease);
    CHECK(k.creases == 1);
    set_sharpness(m, edge_between(m, c, ring[3]), 0.25f);
    k = classify_vertices(m, false);
    CHECK(k.classes[c.idx()] == VertexClass::Corner);
    CHECK(k.corners == 1);
    CHECK(k.darts == 3);
    // A tag makes a corner whatever the edges.
    corner_property(m)[ring[1]] = 1;
    k = classify_vertices(m, false);
    CHECK(k.classes[ring[1].idx()] == VertexClass::Corner);
    CHECK(k.tagged_corners == 1);
    // Boundary edges count when asked: a grid's corner vertices have two boundary edges.
    const HalfedgeMesh grid = make_grid(4);
    const VertexClassification open = classify_vertices(grid, true);
    for (Vertex v : grid.vertices())
        CHECK((open.classes[v.idx()] == VertexClass::Crease) == grid.is_boundary(v));
    CHECK(classify_vertices(grid, false).smooth == grid.n_vertices());
}

TEST_CASE("PLY and OM save and load the features, and OBJ, OFF and STL say they drop them",
          "[features][io]") {
    HalfedgeMesh m = make_icosphere(2);
    Index k = 0;
    for (Edge e : m.edges()) {
        if (k % 7 == 0) set_sharpness(m, e, kInfiniteSharpness);
        if (k % 11 == 0) set_sharpness(m, e, 0.5f + float(k % 3));
        ++k;
    }
    corner_property(m)[Vertex(3)] = 1;
    const auto want = sharp_pairs(m);
    REQUIRE(want.size() > 20);
    for (const char* name : {"a.ply", "a.om"}) {
        for (bool ascii : {false, true}) {
            WriteOptions w;
            w.ascii = ascii;
            const std::string bytes = write_mesh_bytes(m, name, w);
            const LoadedMesh back = std::string(name) == "a.ply" ? read_ply_bytes(bytes, name)
                                                                 : read_om_bytes(bytes, name);
            INFO(name << (ascii ? " ascii" : ""));
            REQUIRE_VALID(back.mesh);
            // PLY writes infinity as 10 and reads 10 and above as infinity: equal values.
            CHECK(sharp_pairs(back.mesh) == want);
            CHECK(is_corner_tagged(back.mesh, Vertex(3)));
            CHECK_FALSE(is_corner_tagged(back.mesh, Vertex(4)));
            CHECK(write_notes(m, name).empty());
        }
    }
    for (const char* name : {"a.obj", "a.off", "a.stl"}) {
        const std::vector<std::string> notes = write_notes(m, name);
        REQUIRE(notes.size() == 1);
        CHECK(notes[0].find("features not saved") != std::string::npos);
        CHECK(notes[0].find(std::to_string(want.size()) + " sharp edges") != std::string::npos);
    }
    CHECK(write_notes(make_icosphere(1), "a.obj").empty());
}

TEST_CASE("a PLY edge element with bad creases is refused naming the edge", "[features][io]") {
    const std::string head =
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
        "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
        "element edge 1\nproperty int vertex1\nproperty int vertex2\nproperty float crease\n"
        "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    REQUIRE_THROWS_WITH(read_ply_bytes(head + "0 1 -1\n", "bad.ply"),
                        Catch::Contains("edge 0") && Catch::Contains("not >= 0"));
    REQUIRE_THROWS_WITH(read_ply_bytes(head + "0 7 1\n", "bad.ply"),
                        Catch::Contains("edge 0") && Catch::Contains("vertex index 7"));
    REQUIRE_THROWS_WITH(read_ply_bytes(head + "1 1 1\n", "bad.ply"), Catch::Contains("to itself"));
    // A crease between two vertices no edge joins is dropped with a note (the mesh is another).
    const std::string four =
        "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
        "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
        "element edge 2\nproperty int vertex1\nproperty int vertex2\nproperty float crease\n"
        "end_header\n0 0 0\n1 0 0\n0 1 0\n5 5 5\n3 0 1 2\n0 1 2.5\n0 3 1\n";
    const LoadedMesh l = read_ply_bytes(four, "other.ply");
    CHECK(sharpness(l.mesh, edge_between(l.mesh, Vertex(0), Vertex(1))) == 2.5f);
    bool noted = false;
    for (const std::string& n : l.report.notes)
        noted = noted || n.find("1 sharp edge joins two vertices") != std::string::npos;
    CHECK(noted);
}

TEST_CASE("detection by the dihedral angle: a cube, chains, boundaries", "[features]") {
    HalfedgeMesh cube = make_cube();
    FeatureDetectionOptions o;
    o.angle_deg = 40;
    const FeatureDetectionReport r = detect_features(cube, o);
    REQUIRE_VALID(cube);
    CHECK(r.feature_edges == 12);  // the diagonals are flat
    CHECK(r.chains == 12);
    CHECK(r.corners == 8);
    CHECK(r.histogram.counts[90] == 12);
    CHECK(r.histogram.counts[0] == 6);
    for (Edge e : cube.edges()) {
        const Halfedge h = cube.halfedge(e, 0);
        const Vector3 d = cube.position(cube.to_vertex(h)) - cube.position(cube.from_vertex(h));
        const int axes =
            (std::abs(d.x()) > 1e-12) + (std::abs(d.y()) > 1e-12) + (std::abs(d.z()) > 1e-12);
        CHECK((sharpness(cube, e) == kInfiniteSharpness) == (axes == 1));
    }
    // Refined once (Loop without features... the edges are split) and detected again at 89:
    // each cube edge is a chain of 2, dropped by --min-chain 3.
    NullProgress progress;
    SubdivisionOptions so;
    so.iterations = 1;
    HalfedgeMesh fine = subdivide(cube, so, progress).levels.back().mesh;
    REQUIRE(sharp_pairs(fine).size() == 24);  // carried: both halves, still infinite
    o.angle_deg = 1;
    o.min_chain = 3;
    const FeatureDetectionReport dropped = detect_features(fine, o);
    CHECK(dropped.dropped_chains + dropped.chains > 0);
    o.min_chain = 0;
    CHECK_THROWS_AS(detect_features(fine, FeatureDetectionOptions{0.0, 0, false, 1.0f}),
                    InvalidArgument);
    CHECK_THROWS_AS(detect_features(fine, FeatureDetectionOptions{30.0, 0, false, 0.0f}),
                    InvalidArgument);
    // Boundary edges on request: a flat grid has no sharp edge, and its boundary loop is one
    // chain.
    HalfedgeMesh grid = make_grid(5);
    o.angle_deg = 30;
    CHECK(detect_features(grid, o).feature_edges == 0);
    o.boundary = true;
    const FeatureDetectionReport b = detect_features(grid, o);
    std::size_t boundary = 0;
    for (Edge e : grid.edges()) boundary += grid.is_boundary(e) ? 1 : 0;
    CHECK(b.feature_edges == boundary);
    CHECK(b.boundary_edges == boundary);
    CHECK(b.chains == 1);
    REQUIRE_VALID(grid);
}

TEST_CASE("fandisk has a plateau from 30 to 60 degrees, and noisy, it has none", "[features]") {
    SKIP_IF_MISSING(test::shared_mesh("fandisk.obj"));
    HalfedgeMesh m = load_fandisk();
    const AngleHistogram h = angle_histogram(m);
    REQUIRE(h.plateau);
    CHECK(h.plateau_lo <= 30);
    CHECK(h.plateau_hi >= 60);
    CHECK(h.at_or_above(30) > 600);
    CHECK(h.at_or_above(30) < 800);
    // The count over the plateau, recomputed from the edges' normals directly.
    std::size_t direct = 0;
    for (Edge e : m.edges()) {
        const Face f0 = m.face(m.halfedge(e, 0)), f1 = m.face(m.halfedge(e, 1));
        if (!f0.is_valid() || !f1.is_valid()) continue;
        const double c = face_normal(m, f0).normalized().dot(face_normal(m, f1).normalized());
        direct += std::acos(std::clamp(c, -1.0, 1.0)) >= 45.0 * 3.14159265358979323846 / 180;
    }
    CHECK(h.at_or_above(45) == direct);
    NoiseOptions noise;
    noise.amount_percent = 30;  // at 10 % the sharp edges still stand out (34 to 67 degrees)
    add_noise(m, noise);
    const AngleHistogram noisy = angle_histogram(m);
    CHECK_FALSE(noisy.plateau);
    FeatureDetectionOptions o;
    const FeatureDetectionReport r = detect_features(m, o);
    CHECK(r.verdict.find("no plateau") != std::string::npos);
}

TEST_CASE("the features operation", "[features][operation]") {
    HalfedgeMesh cube = make_cube();
    NullProgress progress;
    const OperationResult r =
        run_operation(parse_operation("features --angle 60 --min-chain 1"), cube, progress);
    const HalfedgeMesh& out = r.steps.back().mesh;
    REQUIRE_VALID(out);
    CHECK(sharp_pairs(out).size() == 12);
    CHECK_FALSE(has_features(cube));  // the input is not changed
    const FeatureDetectionReport* report = report_of<FeatureDetectionReport>(r);
    REQUIRE(report);
    CHECK(report->corners == 8);
    REQUIRE_THROWS_AS(parse_operation("features --angle 0"), InvalidArgument);
    REQUIRE_THROWS_AS(parse_operation("features --angle 181"), InvalidArgument);
}

TEST_CASE("the region feature:K: the rings around the features", "[features][selection]") {
    HalfedgeMesh m = make_icosphere(3);
    REQUIRE_THROWS_WITH(make_region(m, parse_region_spec("feature:1")),
                        Catch::Contains("no features"));
    REQUIRE_THROWS_AS(parse_region_spec("feature:-1"), InvalidArgument);
    REQUIRE_THROWS_AS(parse_region_spec("feature:1.5"), InvalidArgument);
    set_sharpness(m, Edge(0), kInfiniteSharpness);
    const Vertex a = m.to_vertex(m.halfedge(Edge(0), 0)), b = m.to_vertex(m.halfedge(Edge(0), 1));
    const Selection r0 = make_region(m, parse_region_spec("feature:0"));
    const Selection r1 = make_region(m, parse_region_spec("feature:1"));
    std::size_t n0 = 0, n1 = 0;
    for (Vertex v : m.vertices()) {
        n0 += r0[v.idx()] > 0;
        n1 += r1[v.idx()] > 0;
        // One ring: the ends and their neighbours, checked from the other side.
        bool near = v == a || v == b;
        for (Vertex u : m.vertices_around(v)) near = near || u == a || u == b;
        CHECK((r1[v.idx()] == 1.0f) == near);
    }
    CHECK(n0 == 2);
    CHECK(n1 > n0);
    // Smoothing outside the features keeps them bit for bit.
    Selection keep = r0;
    for (float& w : keep) w = 1.0f - w;
    NullProgress progress;
    RunSettings settings;
    settings.region = &keep;
    const OperationResult sm =
        run_operation(parse_operation("smooth --iterations 3"), m, progress, settings);
    const HalfedgeMesh& out = sm.steps.back().mesh;
    CHECK(out.position(a) == m.position(a));
    CHECK(out.position(b) == m.position(b));
    CHECK(sharpness(out, Edge(0)) == kInfiniteSharpness);  // carried by the copy
}

TEST_CASE("Loop with features: unchanged without them, carried with s - 1 per level",
          "[features][subdivision]") {
    const HalfedgeMesh plain = make_icosphere(2);
    HalfedgeMesh zero = plain;
    sharpness_property(zero);  // all 0: no feature
    NullProgress progress;
    SubdivisionOptions so;
    so.iterations = 2;
    const HalfedgeMesh a = subdivide(plain, so, progress).levels.back().mesh;
    const HalfedgeMesh b = subdivide(zero, so, progress).levels.back().mesh;
    CHECK(a.positions() == b.positions());  // bit for bit
    // Sharpness 2.5 on one edge: 1.5 on its two children, 0.5 on the four grandchildren.
    HalfedgeMesh s = plain;
    const Vertex va = s.to_vertex(s.halfedge(Edge(0), 1)), vb = s.to_vertex(s.halfedge(Edge(0), 0));
    set_sharpness(s, Edge(0), 2.5f);
    const SubdivisionResult r = subdivide(s, so, progress);
    for (const SubdivisionLevel& l : r.levels) REQUIRE_VALID(l.mesh);
    const auto p1 = sharp_pairs(r.levels[0].mesh), p2 = sharp_pairs(r.levels[1].mesh);
    REQUIRE(p1.size() == 2);
    REQUIRE(p2.size() == 4);
    for (const auto& kv : p1) CHECK(kv.second == 1.5f);
    for (const auto& kv : p2) CHECK(kv.second == 0.5f);
    // Its ends are darts (one sharp edge): the smooth rule, as without features.
    const HalfedgeMesh plain1 = subdivide(plain, so, progress).levels[0].mesh;
    CHECK(r.levels[0].mesh.position(va) == plain1.position(va));
    CHECK(r.levels[0].mesh.position(vb) == plain1.position(vb));
    // A bad sharpness is refused before anything is built.
    {
        const test::FpTrapsOff traps_off;  // NaN on purpose
        HalfedgeMesh bad = plain;
        sharpness_property(bad)[Edge(1)] = std::numeric_limits<float>::quiet_NaN();
        REQUIRE_THROWS_AS(subdivide(bad, so, progress), InvalidArgument);
    }
    // None: no features used nor carried.
    so.features = SubdivisionFeatures::None;
    const HalfedgeMesh off = subdivide(s, so, progress).levels.back().mesh;
    CHECK(off.positions() == a.positions());
    CHECK_FALSE(has_features(off));
}

TEST_CASE("smoothing keeps the feature vertices fixed unless told not to", "[features][fairing]") {
    HalfedgeMesh m = make_icosphere(3);
    for (Edge e : m.edges())
        if (e.idx() % 13 == 0) set_sharpness(m, e, 0.5f);
    NullProgress progress;
    const std::vector<float> on = feature_neighbourhood(m, 0);
    for (const char* text : {"smooth --iterations 5",
                             "smooth --iterations 2 --integration "
                             "implicit --step 0.5"}) {
        INFO(text);
        const OperationResult r = run_operation(parse_operation(text), m, progress);
        const HalfedgeMesh& out = r.steps.back().mesh;
        std::size_t moved_feature = 0, moved_other = 0;
        for (Vertex v : m.vertices())
            (on[v.idx()] > 0 ? moved_feature : moved_other) += out.position(v) != m.position(v);
        CHECK(moved_feature == 0);
        CHECK(moved_other > 0);
        CHECK(sharp_pairs(out) == sharp_pairs(m));
    }
    const OperationResult none =
        run_operation(parse_operation("smooth --iterations 5 --features none"), m, progress);
    std::size_t moved = 0;
    for (Vertex v : m.vertices())
        moved += on[v.idx()] > 0 && none.steps.back().mesh.position(v) != m.position(v);
    CHECK(moved > 0);
}

TEST_CASE("a session keeps the features of every state", "[features][session]") {
    History history(std::size_t(-1));
    history.reset(make_cube(), "Load");
    test::push_operation(history, "features --angle 40");
    test::push_operation(history, "subdivide --iterations 2");
    const std::string path = test::temp_path("features.trilab");
    const SessionWriteReport w = write_session(path, history.snapshot());
    CHECK(w.skipped.empty());
    const SessionContents s = read_session(path);
    test::require_same_history(history, s.history);
    const HalfedgeMesh& back = s.history.current_mesh();
    CHECK(sharp_pairs(back) == sharp_pairs(history.current_mesh()));
    CHECK(sharp_pairs(back).size() == 48);  // 12 edges, each split in four
    std::remove(path.c_str());
}

TEST_CASE("decimation keeps the features: corners stay, curve vertices stay on the input curves",
          "[features][decimation]") {
    SKIP_IF_MISSING(test::shared_mesh("fandisk.obj"));
    HalfedgeMesh m = load_fandisk();
    FeatureDetectionOptions fo;
    fo.angle_deg = 60;
    detect_features(m, fo);
    const double diagonal = bounding_box(m).diagonal();
    const VertexClassification in = classify_vertices(m, false);
    // The input feature curves as segments, and the corners by position.
    const std::vector<std::array<Point, 2>> segments = test::sharp_segments(m);
    std::map<std::array<double, 3>, int> corner_at;
    for (Vertex v : m.vertices())
        if (in.classes[v.idx()] == VertexClass::Corner)
            corner_at[{m.position(v).x(), m.position(v).y(), m.position(v).z()}] = 1;
    const auto to_curves = [&](const Point& p) { return test::segments_distance(p, segments); };
    DecimationOptions o;
    o.target_vertices = m.n_vertices() / 10;
    o.levels = DecimationLevels::Last;
    o.record_geomorph = false;
    const DecimationResult r = decimate(m, o);
    const HalfedgeMesh& out = r.levels.back().mesh;
    REQUIRE_VALID(out);
    CHECK(out.n_vertices() <= m.n_vertices() / 10);
    const VertexClassification k = classify_vertices(out, false);
    std::size_t corners = 0;
    double worst = 0;
    for (Vertex v : out.vertices()) {
        if (k.classes[v.idx()] == VertexClass::Smooth) continue;
        // Every output vertex on a feature lies on an input feature curve (crease vertices
        // slide along it to the quadric's minimum), every corner exactly where it was.
        worst = std::max(worst, to_curves(out.position(v)));
        if (k.classes[v.idx()] == VertexClass::Corner)
            corners +=
                corner_at.count({out.position(v).x(), out.position(v).y(), out.position(v).z()});
    }
    CHECK(worst <= 1e-9 * diagonal);
    CHECK(corners == in.corners);
    CHECK(k.corners == in.corners);
    // Without features the decimation moves them off the curves; with them the distance to the
    // input stays close to the featureless run's: 0.0026 against 0.0023 of a diagonal of 7.6
    // here (0.0030 before curve collapses were costed by their chord error), and at 5 % 0.0074
    // against 0.0063 (0.0124 before). Issue 39 asks for at most the featureless run's: not
    // reached (docs/cli.md, "features").
    o.features = FeatureSource::None;
    const HalfedgeMesh plain = decimate(m, o).levels.back().mesh;
    double plain_worst = 0;
    for (Vertex v : plain.vertices())
        if (to_curves(plain.position(v)) < 1e-3 * diagonal)
            plain_worst = std::max(plain_worst, to_curves(plain.position(v)));
    CHECK(plain_worst > 1e-9 * diagonal);
    MeshDistanceOptions md;
    md.samples = 20000;
    const double with = mesh_distance(m, out, md).hausdorff;
    const double without = mesh_distance(m, plain, md).hausdorff;
    CHECK(with <= 1.2 * without);
    // At 5 %, where the curves' chord error dominated (twice the featureless run's).
    o.target_vertices = m.n_vertices() / 20;
    const HalfedgeMesh plain5 = decimate(m, o).levels.back().mesh;
    o.features = FeatureSource::Stored;
    const HalfedgeMesh out5 = decimate(m, o).levels.back().mesh;
    REQUIRE_VALID(out5);
    const VertexClassification k5 = classify_vertices(out5, false);
    double worst5 = 0;
    for (Vertex v : out5.vertices())
        if (k5.classes[v.idx()] != VertexClass::Smooth)
            worst5 = std::max(worst5, to_curves(out5.position(v)));
    CHECK(worst5 <= 1e-9 * diagonal);
    CHECK(mesh_distance(m, out5, md).hausdorff <= 1.3 * mesh_distance(m, plain5, md).hausdorff);
}

namespace {

#ifdef TRILAB_OSD_ORACLE
/// Runs the OpenSubdiv oracle on `m` (its sharp edges and corners) for `levels` Loop levels and
/// returns its final positions in trilab's numbering (through the parents both record).
std::vector<Point> oracle_loop(const HalfedgeMesh& m, int levels,
                               const std::vector<HalfedgeMesh>& trilab_levels) {
    // In the temporary folder, named by the process: tests may run side by side.
    const std::string stem = (std::filesystem::temp_directory_path() /
                              ("trilab_osd_oracle_" + std::to_string(::getpid())))
                                 .string();
    const std::string in = stem + ".txt", out = stem + ".bin";
    struct Cleanup {
        std::string a, b;
        ~Cleanup() {
            std::remove(a.c_str());
            std::remove(b.c_str());
        }
    } cleanup{in, out};
    {
        std::ofstream f(in);
        f.precision(17);
        const auto pairs = sharp_pairs(m);
        std::vector<Index> corners;
        for (Vertex v : m.vertices())
            if (is_corner_tagged(m, v)) corners.push_back(v.idx());
        f << m.n_vertices() << " " << m.n_faces() << " " << pairs.size() << " " << corners.size()
          << "\n";
        for (Vertex v : m.vertices())
            f << m.position(v).x() << " " << m.position(v).y() << " " << m.position(v).z() << "\n";
        for (Face face : m.faces()) {
            const auto v = m.face_vertices(face);
            f << v[0].idx() << " " << v[1].idx() << " " << v[2].idx() << "\n";
        }
        for (const auto& kv : pairs)
            f << kv.first.first << " " << kv.first.second << " "
              << (std::isinf(kv.second) ? std::string("inf") : std::to_string(kv.second)) << "\n";
        for (Index c : corners) f << c << "\n";
    }
    const std::string cmd = std::string("\"") + TRILAB_OSD_ORACLE + "\" " + std::to_string(levels) +
                            " \"" + in + "\" \"" + out + "\"";
    REQUIRE(std::system(cmd.c_str()) == 0);
    std::ifstream f(out, std::ios::binary);
    auto get = [&] {
        std::int32_t v = 0;
        f.read(reinterpret_cast<char*>(&v), sizeof v);
        return v;
    };
    // map[i]: the oracle's index of trilab's vertex i at the current level.
    std::vector<std::int32_t> map(m.vertices_size());
    for (std::size_t i = 0; i < map.size(); ++i) map[i] = std::int32_t(i);
    for (int level = 0; level < levels; ++level) {
        const std::int32_t n = get();
        // The oracle's children: of a vertex by its index, of an edge by its two ends.
        std::vector<std::int32_t> vertex_child;
        std::unordered_map<std::uint64_t, std::int32_t> edge_child;
        edge_child.reserve(std::size_t(n));
        auto key = [](std::int32_t a, std::int32_t b) {
            if (a > b) std::swap(a, b);
            return (std::uint64_t(std::uint32_t(a)) << 32) | std::uint32_t(b);
        };
        for (std::int32_t i = 0; i < n; ++i) {
            const std::int32_t a = get(), b = get();
            if (b < 0) {
                if (std::size_t(a) >= vertex_child.size())
                    vertex_child.resize(std::size_t(a) + 1, -1);
                vertex_child[std::size_t(a)] = i;
            } else {
                edge_child[key(a, b)] = i;
            }
        }
        const HalfedgeMesh& t = trilab_levels[std::size_t(level)];
        const auto parents = t.get_vertex_property<SubdivisionParents>("v:subdivision_parents");
        REQUIRE(parents);
        REQUIRE(std::size_t(n) == t.n_vertices());
        std::vector<std::int32_t> next(t.vertices_size(), -1);
        std::size_t unmatched = 0;
        for (Vertex v : t.vertices()) {
            const SubdivisionParents p = parents[v];
            const std::int32_t a = map[p[0]];
            if (p[1] == kInvalidIndex) {
                if (std::size_t(a) < vertex_child.size())
                    next[v.idx()] = vertex_child[std::size_t(a)];
            } else {
                const auto it = edge_child.find(key(a, map[p[1]]));
                if (it != edge_child.end()) next[v.idx()] = it->second;
            }
            unmatched += next[v.idx()] < 0 ? 1 : 0;
        }
        INFO("level " << level + 1);
        REQUIRE(unmatched == 0);
        map.swap(next);
    }
    const std::int32_t n = get();
    std::vector<Point> osd(static_cast<std::size_t>(n));
    for (Point& p : osd) f.read(reinterpret_cast<char*>(p.data()), 3 * sizeof(double));
    REQUIRE(f.good());
    std::vector<Point> out_positions(map.size());
    for (std::size_t i = 0; i < map.size(); ++i) out_positions[i] = osd[std::size_t(map[i])];
    return out_positions;
}
#endif

}  // namespace

TEST_CASE("Loop x3 with fandisk's features equals OpenSubdiv 3.5's", "[features][subdivision]") {
#ifndef TRILAB_OSD_ORACLE
    SKIP_TEST(
        "OpenSubdiv (libosd-dev) not installed: the crease Loop oracle is not built "
        "(third_party/install-deps.sh installs it)");
#else
    SKIP_IF_MISSING(test::shared_mesh("fandisk.obj"));
    HalfedgeMesh base = load_fandisk();
    FeatureDetectionOptions o;
    o.angle_deg = 60;
    detect_features(base, o);
    const double diagonal = bounding_box(base).diagonal();
    NullProgress plain_progress;
    SubdivisionOptions plain_options;
    plain_options.iterations = 3;
    plain_options.morph = false;
    plain_options.keep_levels = false;
    plain_options.features = SubdivisionFeatures::None;
    const SubdivisionResult plain_levels = subdivide(base, plain_options, plain_progress);
    // Every feature edge infinitely sharp, of sharpness 2.0 (with two corner tags on smooth
    // vertices), and 0.5.
    for (float s : {kInfiniteSharpness, 2.0f, 0.5f}) {
        HalfedgeMesh m = base;
        auto sharp = sharpness_property(m);
        for (Edge e : m.edges())
            if (sharp[e] > 0) sharp[e] = s;
        if (s == 2.0f) {
            corner_property(m)[Vertex(10)] = 1;
            corner_property(m)[Vertex(1000)] = 1;
        }
        NullProgress progress;
        SubdivisionOptions so;
        so.iterations = 3;
        so.morph = false;
        const SubdivisionResult r = subdivide(m, so, progress);
        std::vector<HalfedgeMesh> levels;
        for (const SubdivisionLevel& l : r.levels) levels.push_back(l.mesh);
        REQUIRE_VALID(levels.back());
        const std::vector<Point> osd = oracle_loop(m, 3, levels);
        double worst = 0, moved = 0;  // moved: how far the features move the result
        const HalfedgeMesh& plain = plain_levels.levels.back().mesh;
        for (Vertex v : levels.back().vertices()) {
            worst = std::max(worst, (levels.back().position(v) - osd[v.idx()]).norm());
            moved = std::max(moved, (levels.back().position(v) - plain.position(v)).norm());
        }
        INFO("sharpness " << s << ": largest difference " << worst / diagonal
                          << " of the diagonal; the features move vertices by up to "
                          << moved / diagonal);
        CHECK(worst <= 1e-9 * diagonal);
        CHECK(moved > 1e-3 * diagonal);  // the comparison sees the creases
    }
#endif
}

TEST_CASE("region subdivision uses and carries the features in every scheme",
          "[features][subdivision][selection]") {
    // A block's twelve edges made sharp, a region around one of its corners.
    HalfedgeMesh base = make_block(4, 4, 4);
    FeatureDetectionOptions fo;
    fo.angle_deg = 40;
    REQUIRE(detect_features(base, fo).corners == 8);
    const auto segments = test::sharp_segments(base);
    const Selection region = sphere_selection(base, Point(1, 1, 1), 1.2);
    REQUIRE(count_selected(region) > 10);
    REQUIRE(count_selected(region) < base.n_vertices() / 2);
    NullProgress progress;
    for (SubdivisionScheme scheme :
         {SubdivisionScheme::Loop, SubdivisionScheme::Sqrt3, SubdivisionScheme::Butterfly,
          SubdivisionScheme::ModifiedButterfly}) {
        INFO(scheme_name(scheme));
        const bool sqrt3 = scheme == SubdivisionScheme::Sqrt3;
        SubdivisionOptions so;
        so.scheme = scheme;
        so.iterations = sqrt3 ? 3 : 2;
        RegionSubdivisionReport report;
        const SubdivisionResult r = subdivide_region(base, so, region, progress, report);
        for (const SubdivisionLevel& l : r.levels) REQUIRE_VALID(l.mesh);
        CHECK(r.notes.empty());
        const HalfedgeMesh& out = r.levels.back().mesh;
        // Carried: as many sharp edges or more (1-to-4: both halves of each split one; Sqrt3
        // keeps them as boundaries), every one still on the block's edges, the corner tags
        // kept, and the corner itself where it was.
        CHECK(sharp_pairs(out).size() >= sharp_pairs(base).size());
        if (!sqrt3) CHECK(sharp_pairs(out).size() > sharp_pairs(base).size());
        for (Edge e : out.edges()) {
            if (sharpness(out, e) <= 0.0f) continue;
            for (int k = 0; k < 2; ++k)
                CHECK(test::segments_distance(out.position(out.to_vertex(out.halfedge(e, k))),
                                              segments) < 1e-12);
        }
        CHECK(out.n_faces() > base.n_faces());
        if (!sqrt3) {
            // Level 1's old vertices inside are where the whole-mesh step with the creases puts
            // them.
            SubdivisionOptions one = so;
            one.iterations = 1;
            const HalfedgeMesh whole = subdivide(base, one, progress).levels.back().mesh;
            const HalfedgeMesh& first = r.levels.front().mesh;
            for (Vertex v : base.vertices())
                if (region[v.idx()] == 1.0f) CHECK(first.position(v) == whole.position(v));
        }
        // Without the features the region's crease vertices leave the block's edges (Loop and
        // Sqrt3 move old vertices; the butterflies keep them) and nothing is carried.
        so.features = SubdivisionFeatures::None;
        const HalfedgeMesh plain =
            subdivide_region(base, so, region, progress, report).levels.back().mesh;
        CHECK_FALSE(has_features(plain));
        double farthest = 0;
        for (Vertex v : base.vertices())
            if (region[v.idx()] > 0.0f &&
                test::segments_distance(base.position(v), segments) < 1e-12)
                farthest = std::max(farthest, test::segments_distance(plain.position(v), segments));
        if (scheme == SubdivisionScheme::Loop || sqrt3) CHECK(farthest > 1e-3);
    }
}
