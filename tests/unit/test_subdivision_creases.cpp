// Crease rules of Sqrt3 (Kobbelt 2000's boundary rule along sharp edges) and of the two
// butterflies (the four-point rule along sharp edges): core/algorithms/subdivision_creases.h.
// Loop's rules are tested against OpenSubdiv in test_features.cpp.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/algorithms/feature_detection.h"
#include "core/algorithms/generators.h"
#include "core/algorithms/subdivision.h"
#include "core/features.h"
#include "core/geometry.h"
#include "core/io/mesh_io.h"
#include "test_helpers.h"

using namespace trilab;

namespace {

constexpr double kDeg = 180.0 / 3.14159265358979323846;

/// The angle between the normals of the two faces of interior edge e, in degrees.
double dihedral_deg(const HalfedgeMesh& m, Edge e) {
    const Halfedge h = m.halfedge(e, 0), t = m.halfedge(e, 1);
    auto normal = [&](Halfedge g) {
        const Point& a = m.position(m.from_vertex(g));
        const Point& b = m.position(m.to_vertex(g));
        const Point& c = m.position(m.to_vertex(m.next(g)));
        return Vector3((b - a).cross(c - a).normalized());
    };
    const double c = std::clamp(normal(h).dot(normal(t)), -1.0, 1.0);
    return std::acos(c) * kDeg;
}

/// The sharp interior edges of m (sharpness > 0).
std::vector<Edge> sharp_edges(const HalfedgeMesh& m) {
    std::vector<Edge> out;
    for (Edge e : m.edges())
        if (!m.is_boundary(e) && sharpness(m, e) > 0.0f) out.push_back(e);
    return out;
}

constexpr SubdivisionScheme kCreaseSchemes[] = {
    SubdivisionScheme::Sqrt3, SubdivisionScheme::Butterfly, SubdivisionScheme::ModifiedButterfly};

}  // namespace

TEST_CASE("Sqrt3 and the butterflies keep a block's creases and corners",
          "[features][subdivision][creases]") {
    HalfedgeMesh block = make_block(2, 2, 2);
    FeatureDetectionOptions fo;
    fo.angle_deg = 60;
    const FeatureDetectionReport fr = detect_features(block, fo);
    REQUIRE(fr.feature_edges == 24);  // 12 cube edges of two segments
    const VertexClassification in = classify_vertices(block, false);
    REQUIRE(in.corners == 8);
    NullProgress progress;
    for (SubdivisionScheme scheme : kCreaseSchemes) {
        INFO(scheme_name(scheme));
        SubdivisionOptions so;
        so.scheme = scheme;
        so.iterations = 3;
        const SubdivisionResult r = subdivide(block, so, progress);
        REQUIRE(r.levels.size() == 3);
        for (const SubdivisionLevel& l : r.levels) REQUIRE_VALID(l.mesh);
        const HalfedgeMesh& out = r.levels.back().mesh;
        // The corners stay where they were (old vertices keep their index in every scheme).
        for (Vertex v : block.vertices())
            if (in.classes[v.idx()] == VertexClass::Corner)
                CHECK((out.position(v) - block.position(v)).norm() == 0.0);
        // The feature curves are carried and keep their 90 degrees (sides stay planar).
        const std::vector<Edge> sharp = sharp_edges(out);
        CHECK(sharp.size() >= 24 * (scheme == SubdivisionScheme::Sqrt3 ? 3u : 8u));
        double worst = 0;
        for (Edge e : sharp) worst = std::max(worst, std::abs(dihedral_deg(out, e) - 90.0));
        CHECK(worst < 1.0);
        CHECK(classify_vertices(out, false).corners == 8);
        // Without the features the creases round off.
        so.features = SubdivisionFeatures::None;
        const HalfedgeMesh plain = subdivide(block, so, progress).levels.back().mesh;
        double plain_worst = 0;
        for (Edge e : plain.edges()) plain_worst = std::max(plain_worst, dihedral_deg(plain, e));
        CHECK(plain_worst < 80.0);
    }
}

TEST_CASE("fandisk's feature curves keep their dihedral angles in Sqrt3 and the butterflies",
          "[features][subdivision][creases]") {
    SKIP_IF_MISSING(test::shared_mesh("fandisk.obj"));
    HalfedgeMesh m = read_mesh(test::shared_mesh("fandisk.obj")).mesh;
    FeatureDetectionOptions fo;
    fo.angle_deg = 60;
    detect_features(m, fo);
    const VertexClassification in = classify_vertices(m, false);
    // The input feature edges, their dihedral angles and their curves (chains joined at
    // crease vertices, split at corners and darts).
    struct Segment {
        Point a, b;
        double angle;
        std::size_t chain;
    };
    std::vector<Segment> input;
    std::vector<std::size_t> parent;
    std::vector<std::size_t> first_at(m.vertices_size(), SIZE_MAX);
    const auto find = [&](std::size_t i) {
        while (parent[i] != i) i = parent[i] = parent[parent[i]];
        return i;
    };
    for (Edge e : sharp_edges(m)) {
        const Vertex va = m.from_vertex(m.halfedge(e, 0)), vb = m.to_vertex(m.halfedge(e, 0));
        const std::size_t i = input.size();
        input.push_back({m.position(va), m.position(vb), dihedral_deg(m, e), 0});
        parent.push_back(i);
        for (Vertex v : {va, vb}) {
            if (in.classes[v.idx()] != VertexClass::Crease) continue;
            if (first_at[v.idx()] == SIZE_MAX)
                first_at[v.idx()] = i;
            else
                parent[find(i)] = find(first_at[v.idx()]);
        }
    }
    for (std::size_t i = 0; i < input.size(); ++i) input[i].chain = find(i);
    auto distance = [](const Segment& s, const Point& p) {
        const Vector3 d = s.b - s.a;
        const double t = std::clamp((p - s.a).dot(d) / d.squaredNorm(), 0.0, 1.0);
        return (s.a + t * d - p).norm();
    };
    // Per curve, the length-weighted mean dihedral angle of the input's edges.
    std::vector<double> in_sum(input.size(), 0.0), in_len(input.size(), 0.0);
    for (const Segment& s : input) {
        in_sum[s.chain] += (s.b - s.a).norm() * s.angle;
        in_len[s.chain] += (s.b - s.a).norm();
    }
    NullProgress progress;
    for (SubdivisionScheme scheme : kCreaseSchemes) {
        INFO(scheme_name(scheme));
        SubdivisionOptions so;
        so.scheme = scheme;
        so.iterations = 3;
        so.keep_levels = false;
        so.morph = false;
        const HalfedgeMesh out = subdivide(m, so, progress).levels.back().mesh;
        REQUIRE_VALID(out);
        for (Vertex v : m.vertices())
            if (in.classes[v.idx()] == VertexClass::Corner)
                CHECK((out.position(v) - m.position(v)).norm() == 0.0);
        // Each output sharp edge belongs to the curve of the nearest input feature edge.
        std::vector<double> out_sum(input.size(), 0.0), out_len(input.size(), 0.0);
        for (Edge e : sharp_edges(out)) {
            const Point a = out.position(out.from_vertex(out.halfedge(e, 0)));
            const Point b = out.position(out.to_vertex(out.halfedge(e, 0)));
            const Point mid = 0.5 * (a + b);
            std::size_t best = 0;
            for (std::size_t i = 1; i < input.size(); ++i)
                if (distance(input[i], mid) < distance(input[best], mid)) best = i;
            out_sum[input[best].chain] += (b - a).norm() * dihedral_deg(out, e);
            out_len[input[best].chain] += (b - a).norm();
        }
        double worst = 0;
        std::size_t curves = 0;
        for (std::size_t c = 0; c < input.size(); ++c) {
            if (!(in_len[c] > 0)) continue;
            ++curves;
            REQUIRE(out_len[c] > 0);  // every curve is still there
            worst = std::max(worst, std::abs(out_sum[c] / out_len[c] - in_sum[c] / in_len[c]));
        }
        CHECK(curves > 10);
        CHECK(worst < 1.0);
    }
}

TEST_CASE("Sqrt3 and the butterflies with only boundary features equal the plain schemes",
          "[features][subdivision][creases]") {
    // A sharpness on a boundary edge changes no rule (boundaries are infinitely sharp) but
    // takes the crease code: it must give the plain schemes' surfaces.
    HalfedgeMesh grid = make_grid(6);
    Edge border;
    for (Edge e : grid.edges())
        if (grid.is_boundary(e)) border = e;
    set_sharpness(grid, border, 3.0f);
    REQUIRE(has_features(grid));
    NullProgress progress;
    for (SubdivisionScheme scheme : kCreaseSchemes) {
        INFO(scheme_name(scheme));
        SubdivisionOptions so;
        so.scheme = scheme;
        so.iterations = 3;
        const SubdivisionResult creased = subdivide(grid, so, progress);
        so.features = SubdivisionFeatures::None;
        const SubdivisionResult plain = subdivide(grid, so, progress);
        for (int level = 0; level < 3; ++level) {
            const HalfedgeMesh& a = creased.levels[std::size_t(level)].mesh;
            const HalfedgeMesh& b = plain.levels[std::size_t(level)].mesh;
            REQUIRE_VALID(a);
            REQUIRE(a.n_vertices() == b.n_vertices());
            REQUIRE(a.n_faces() == b.n_faces());
            // Every vertex of one has a vertex of the other at its place (the numbering of
            // the split points differs).
            double worst = 0;
            for (Vertex v : a.vertices()) {
                double nearest = 1e300;
                for (Vertex w : b.vertices())
                    nearest = std::min(nearest, (a.position(v) - b.position(w)).norm());
                worst = std::max(worst, nearest);
            }
            CHECK(worst < 1e-12);
        }
    }
}

TEST_CASE("Sqrt3 and the butterflies carry s - 1 per step and blend semi-sharp edges",
          "[features][subdivision][creases]") {
    HalfedgeMesh block = make_block(2, 2, 2);
    FeatureDetectionOptions fo;
    fo.angle_deg = 60;
    fo.sharpness = 2.0f;
    detect_features(block, fo);
    NullProgress progress;
    for (SubdivisionScheme scheme : kCreaseSchemes) {
        INFO(scheme_name(scheme));
        SubdivisionOptions so;
        so.scheme = scheme;
        so.iterations = 3;
        const SubdivisionResult r = subdivide(block, so, progress);
        for (const SubdivisionLevel& l : r.levels) REQUIRE_VALID(l.mesh);
        // Level 1: sharpness 1 on the children; level 2: none left.
        const std::vector<Edge> s1 = sharp_edges(r.levels[0].mesh);
        REQUIRE_FALSE(s1.empty());
        for (Edge e : s1) CHECK(sharpness(r.levels[0].mesh, e) == 1.0f);
        CHECK(sharp_edges(r.levels[1].mesh).empty());
        // Between the infinitely sharp and the smooth result.
        const auto radius = [](const HalfedgeMesh& m) {
            double lo = 1e300;
            for (Vertex v : m.vertices())
                lo = std::min(lo, m.position(v).lpNorm<Eigen::Infinity>());
            return lo;  // the smallest max-norm: how far the surface stays from the box
        };
        HalfedgeMesh hard = block;
        for (Edge e : sharp_edges(hard)) set_sharpness(hard, e, kInfiniteSharpness);
        const double semi = radius(r.levels.back().mesh);
        const double sharp = radius(subdivide(hard, so, progress).levels.back().mesh);
        so.features = SubdivisionFeatures::None;
        const double smooth = radius(subdivide(block, so, progress).levels.back().mesh);
        CHECK(semi <= sharp + 1e-12);
        CHECK(semi >= smooth - 1e-12);
        CHECK(sharp > smooth);
    }
}
