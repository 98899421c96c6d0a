// Isotropic remeshing (core/algorithms/remesh.h), the quality figures
// (core/algorithms/mesh_quality.h) and the "remesh" operation.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include "app/ops/operation.h"
#include "core/algorithms/feature_detection.h"
#include "core/algorithms/generators.h"
#include "core/algorithms/mesh_distance.h"
#include "core/algorithms/mesh_quality.h"
#include "core/algorithms/mesh_stats.h"
#include "core/algorithms/morph.h"
#include "core/algorithms/noise.h"
#include "core/algorithms/remesh.h"
#include "core/algorithms/selection.h"
#include "core/errors.h"
#include "core/features.h"
#include "core/geometry.h"
#include "core/io/mesh_io.h"
#include "core/mesh_builder.h"
#include "test_helpers.h"

using namespace trilab;
using namespace trilab::test;

namespace {

/// The unit square in z = 0 cut into 2 x 57 triangles of 1 degree: columns of width
/// tan(1 deg) over the full height, each split along a diagonal.
HalfedgeMesh needle_square() {
    const int n = 57;
    PolygonSoup s;
    for (int row = 0; row < 2; ++row)
        for (int i = 0; i <= n; ++i) s.positions.push_back(Point(double(i) / n, row, 0));
    for (int i = 0; i < n; ++i) {
        const Index a = Index(i), b = Index(i + 1), c = Index(n + 1 + i), d = Index(n + 2 + i);
        s.add_face({a, b, c});
        s.add_face({b, d, c});
    }
    LoadReport report;
    return build_mesh(s, report);
}

/// Positions of the triangles of `mesh` whose corners are all selected by `keep`, each as its
/// corners in a canonical order (for comparing kept faces across a renumbering).
std::set<std::array<double, 9>> triangles_where(const HalfedgeMesh& mesh,
                                                const std::vector<std::uint8_t>& keep) {
    std::set<std::array<double, 9>> out;
    for (Face f : mesh.faces()) {
        auto c = mesh.face_vertices(f);
        bool all = true;
        for (Vertex v : c) all = all && keep[v.idx()];
        if (!all) continue;
        // Rotate so that the smallest index position starts (orientation kept).
        std::array<Point, 3> p = {mesh.position(c[0]), mesh.position(c[1]), mesh.position(c[2])};
        const auto less = [](const Point& a, const Point& b) {
            return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
        };
        int first = 0;
        for (int k = 1; k < 3; ++k)
            if (less(p[k], p[first])) first = k;
        std::array<double, 9> t;
        for (int k = 0; k < 3; ++k)
            for (int j = 0; j < 3; ++j) t[3 * k + j] = p[(first + k) % 3][j];
        out.insert(t);
    }
    return out;
}

bool on_square_boundary(const Point& p) {
    const auto at = [](double x, double v) { return std::abs(x - v) < 1e-12; };
    return at(p.x(), 0) || at(p.x(), 1) || at(p.y(), 0) || at(p.y(), 1);
}

}  // namespace

// ---- quality figures --------------------------------------------------------------------------

TEST_CASE("triangle quality: an equilateral triangle has Q 1 and 60 degrees, a right one less",
          "[remesh][quality]") {
    PolygonSoup s;
    s.positions = {Point(0, 0, 0), Point(1, 0, 0), Point(0.5, std::sqrt(3.0) / 2, 0),
                   Point(3, 0, 0), Point(4, 0, 0), Point(3, 1, 0)};
    s.add_face({0, 1, 2});
    s.add_face({3, 4, 5});
    LoadReport report;
    const HalfedgeMesh m = build_mesh(s, report);
    const Face eq(0), right(1);
    CHECK(triangle_quality(m, eq) == Approx(1.0).epsilon(1e-12));
    CHECK(triangle_min_angle(m, eq) == Approx(60.0).epsilon(1e-12));
    // Legs 1, hypotenuse sqrt 2: Q = 4 sqrt3 (1/2) / ((2 + sqrt2) sqrt2).
    const double q = 2 * std::sqrt(3.0) / ((2 + std::sqrt(2.0)) * std::sqrt(2.0));
    CHECK(triangle_quality(m, right) == Approx(q).epsilon(1e-12));
    CHECK(triangle_min_angle(m, right) == Approx(45.0).epsilon(1e-12));
    const MeshQuality mq = mesh_quality(m);
    CHECK(mq.faces == 2);
    CHECK(mq.min_angle == Approx(45.0).epsilon(1e-12));
    CHECK(mq.mean_min_angle == Approx(52.5).epsilon(1e-12));
    CHECK(mq.angles_under_30 == 0.0);
    CHECK(mq.min_q == Approx(q).epsilon(1e-12));
    CHECK(mq.interior_vertices == 0);
    CHECK(mq.boundary_vertices == 6);
    // Edges 1, 1, 1, 1, 1, sqrt2.
    CHECK(mesh_quality(m, 1.0).edges_in_band == Approx(5.0 / 6.0));  // sqrt 2 > 4/3
    CHECK(mesh_quality(m, 1.1).edges_in_band == 1.0);
    CHECK_THROWS_AS(mesh_quality(m, 0.0), InvalidArgument);
    CHECK_THROWS_AS(mesh_quality(m, std::numeric_limits<double>::quiet_NaN()), InvalidArgument);
}

TEST_CASE("mesh quality counts valences and small angles", "[remesh][quality]") {
    const MeshQuality ico = mesh_quality(make_icosahedron());
    CHECK(ico.interior_vertices == 12);
    CHECK(ico.valence6 == 0.0);  // every vertex has valence 5
    CHECK(ico.min_angle == Approx(60.0).epsilon(1e-9));
    const HalfedgeMesh needles = needle_square();
    const MeshQuality nq = mesh_quality(needles);
    CHECK(nq.min_angle < 1.01);
    CHECK(nq.angles_under_30 == Approx(1.0 / 3.0).margin(1e-12));  // one per triangle
    const std::vector<double> field = face_quality_field(needles, true);
    REQUIRE(field.size() == needles.faces_size());
    for (Face f : needles.faces()) CHECK(field[f.idx()] == triangle_min_angle(needles, f));
}

// ---- remeshing --------------------------------------------------------------------------------

TEST_CASE("remesh makes a sphere isotropic, close to the input, valid after every iteration",
          "[remesh]") {
    const HalfedgeMesh input = make_noisy_sphere(3, 0.02, 7);
    HalfedgeMesh m = input;
    RemeshOptions o;
    o.iterations = 1;
    RemeshReport last;
    for (int i = 0; i < 6; ++i) {
        last = remesh(m, o);
        REQUIRE_VALID(m);
        CHECK(!m.has_garbage());
        o.length = last.target_length;  // the first run's L, kept
    }
    const MeshQuality q = mesh_quality(m, last.target_length);
    INFO("band " << q.edges_in_band << ", valence6 " << q.valence6 << ", min angle " << q.min_angle
                 << ", mean min " << q.mean_min_angle);
    CHECK(q.edges_in_band > 0.85);
    CHECK(q.valence6 > 0.65);
    CHECK(q.min_angle > 20.0);
    CHECK(q.mean_min_angle > 45.0);
    CHECK(compute_stats(m).genus == 0);
    CHECK(is_closed(m));
    MeshDistanceOptions d_options;
    d_options.samples = 20000;
    const MeshDistance d = mesh_distance(input, m, d_options);
    // Every vertex lies on the input; only the chords between them leave it.
    CHECK(d.hausdorff < 0.05 * last.target_length + 0.002 * d.diagonal);
}

TEST_CASE("remesh removes 1-degree triangles and keeps the square's boundary", "[remesh]") {
    const HalfedgeMesh input = needle_square();
    REQUIRE(mesh_quality(input).min_angle < 1.01);
    HalfedgeMesh m = input;
    RemeshOptions o;
    o.length = 0.1;
    const RemeshReport r = remesh(m, o);
    REQUIRE_VALID(m);
    const MeshQuality q = mesh_quality(m, 0.1);
    INFO("min angle " << q.min_angle << ", band " << q.edges_in_band << ", faces "
                      << r.output_faces);
    CHECK(q.min_angle >= 20.0);
    CHECK(q.edges_in_band > 0.8);
    CHECK(compute_stats(m).boundary_loops == 1);
    CHECK(surface_area(m) == Approx(1.0).epsilon(1e-9));  // flat: the area is kept
    // Boundary vertices stay on the square's sides, and its four corners stay.
    int corners = 0;
    for (Vertex v : m.vertices()) {
        const Point& p = m.position(v);
        CHECK(std::abs(p.z()) < 1e-12);
        if (m.is_boundary(v)) CHECK(on_square_boundary(p));
        const bool corner = (p.x() == 0 || p.x() == 1) && (p.y() == 0 || p.y() == 1);
        corners += corner;
    }
    CHECK(corners == 4);
    // About the predicted count (area over the ideal triangle's, plus the boundary's share).
    CHECK(double(r.output_faces) > 0.7 * double(r.predicted_faces));
    CHECK(double(r.output_faces) < 1.5 * double(r.predicted_faces));
}

TEST_CASE(
    "the cotangent Laplacian's spread: weights as geometry.h gives them, one negative "
    "weight across a long diagonal, and remeshing shrinks the spread",
    "[remesh][quality][spread]") {
    // An independent count: cotangent_weight() per edge (geometry.h).
    HalfedgeMesh sphere = make_icosphere(2);
    NoiseOptions n;
    n.amount_percent = 20;
    add_noise(sphere, n);
    const CotangentSpread s = cotangent_spread(sphere);
    std::size_t negative = 0;
    double low = 1e300, high = -1e300;
    std::vector<double> magnitudes;
    for (Edge e : sphere.edges()) {
        const double w = cotangent_weight(sphere, e);
        negative += w < 0;
        low = std::min(low, w);
        high = std::max(high, w);
        magnitudes.push_back(std::abs(w));
    }
    CHECK(s.edges == sphere.n_edges());
    CHECK(s.negative_weights == negative);
    CHECK(s.min_weight == Approx(low));
    CHECK(s.max_weight == Approx(high));
    CHECK(s.vertices == sphere.n_vertices());
    CHECK(s.degenerate_corners == 0);
    std::sort(magnitudes.begin(), magnitudes.end());
    CHECK(s.weight_ratio == Approx(magnitudes.back() / magnitudes[magnitudes.size() / 2]));
    CHECK(s.diagonal_ratio >= 1.0);

    // Two triangles over a long diagonal, their far corners at 169 degrees: its weight is
    // negative, the others positive.
    PolygonSoup kite;
    kite.positions = {Point(0, 0, 0), Point(2, 0, 0), Point(1, 0.1, 0), Point(1, -0.1, 0)};
    kite.add_face({0, 1, 2});
    kite.add_face({1, 0, 3});
    LoadReport report;
    const CotangentSpread k = cotangent_spread(build_mesh(kite, report));
    CHECK(k.negative_weights == 1);
    CHECK(k.negative_share == Approx(1.0 / 5.0));
    CHECK(k.min_weight < -4);
    CHECK(cotangent_spread(HalfedgeMesh()).edges == 0);

    // Remeshing the 1-degree square: the weights' and the diagonal's spreads drop.
    const HalfedgeMesh needles = needle_square();
    HalfedgeMesh m = needles;
    RemeshOptions o;
    o.length = 0.1;
    remesh(m, o);
    const CotangentSpread before = cotangent_spread(needles), after = cotangent_spread(m);
    INFO("weight ratio " << before.weight_ratio << " -> " << after.weight_ratio
                         << ", largest weight " << before.max_weight << " -> " << after.max_weight);
    CHECK(before.max_weight > 25);  // cot 1 degree / 2
    CHECK(after.max_weight < 2);
    CHECK(after.weight_ratio < before.weight_ratio / 10);
}

namespace {

/// The sharp edges of `mesh` as segments.
/// The largest distance from an end of a sharp edge of `out` to the sharp edges of `in`
/// (brute force).
double feature_drift(const HalfedgeMesh& in, const HalfedgeMesh& out) {
    const auto curves = test::sharp_segments(in);
    double worst = 0;
    for (const auto& s : test::sharp_segments(out))
        for (const Point& p : s) worst = std::max(worst, test::segments_distance(p, curves));
    return worst;
}

double total_length(const std::vector<std::array<Point, 2>>& segments) {
    double sum = 0;
    for (const auto& s : segments) sum += (s[1] - s[0]).norm();
    return sum;
}

/// The positions of the corners (classify_vertices) of `mesh`, sorted.
std::vector<std::array<double, 3>> corner_positions(const HalfedgeMesh& mesh) {
    const VertexClassification c = classify_vertices(mesh, false);
    std::vector<std::array<double, 3>> out;
    for (Vertex v : mesh.vertices())
        if (c.classes[v.idx()] == VertexClass::Corner) {
            const Point& p = mesh.position(v);
            out.push_back({p.x(), p.y(), p.z()});
        }
    std::sort(out.begin(), out.end());
    return out;
}

}  // namespace

TEST_CASE("remesh splits and collapses sharp edges only along their curves, and corners stay",
          "[remesh][features]") {
    HalfedgeMesh block = make_block(12, 9, 6);  // its 12 edges are its only sharp ones
    FeatureDetectionOptions d;
    d.angle_deg = 60;
    const FeatureDetectionReport found = detect_features(block, d);
    REQUIRE(found.feature_edges > 0);
    REQUIRE(found.corners == 8);
    const double diagonal = bounding_box(block).diagonal();
    RemeshOptions o;
    o.relative = 0.4;  // about half the block's grid spacing: its sharp edges must be split
    HalfedgeMesh kept = block;
    const RemeshReport r = remesh(kept, o);
    REQUIRE_VALID(kept);
    CHECK(r.feature_vertices > 0);
    // Every feature vertex on an input curve, the curves whole, the corners where they were.
    CHECK(feature_drift(block, kept) <= 1e-9 * diagonal);
    CHECK(total_length(test::sharp_segments(kept)) ==
          Approx(total_length(test::sharp_segments(block))).epsilon(1e-9));
    CHECK(corner_positions(kept) == corner_positions(block));
    CHECK(classify_vertices(kept, false).corners == 8);
    // The curves were remeshed with the rest: finer, their edges near L.
    CHECK(test::sharp_segments(kept).size() > test::sharp_segments(block).size());
    std::size_t in_band = 0;
    for (const auto& s : test::sharp_segments(kept)) {
        const double l = (s[1] - s[0]).norm();
        in_band += l >= 0.8 * r.target_length && l <= 4.0 / 3.0 * r.target_length;
    }
    CHECK(in_band >= 0.9 * double(test::sharp_segments(kept).size()));
    CHECK(kept.n_faces() > block.n_faces());
    // Without them the block's edges are cut across (vertices leave them).
    HalfedgeMesh ignored = block;
    o.features = FeatureSource::None;
    const RemeshReport none = remesh(ignored, o);
    REQUIRE_VALID(ignored);
    CHECK(none.feature_vertices == 0);
    // Auto detects them first; a bad angle is refused before anything changes.
    HalfedgeMesh plain = make_block(12, 9, 6);
    o.features = FeatureSource::Auto;
    o.feature_angle = 60;
    CHECK(remesh(plain, o).feature_vertices > 0);
    CHECK(has_features(plain));
    HalfedgeMesh untouched = make_block(12, 9, 6);
    o.feature_angle = 0;
    CHECK_THROWS_WITH(remesh(untouched, o), Catch::Contains("feature_angle"));
    CHECK_FALSE(has_features(untouched));
}

TEST_CASE("remesh on a region leaves every face outside it bit for bit", "[remesh]") {
    const HalfedgeMesh input = make_icosphere(3);
    Selection region = sphere_selection(input, Point(1, 0, 0), 1.0);
    std::vector<std::uint8_t> outside(input.vertices_size(), 0);
    for (Vertex v : input.vertices()) outside[v.idx()] = region[v.idx()] == 0.0f;
    // Faces with a corner outside stay: those with every corner outside, and the border ring.
    std::vector<std::uint8_t> touches(input.vertices_size(), 0);
    for (Vertex v : input.vertices()) {
        if (!outside[v.idx()]) continue;
        touches[v.idx()] = 1;
        for (Vertex n : input.vertices_around(v)) touches[n.idx()] = 1;
    }
    HalfedgeMesh m = input;
    RemeshOptions o;
    o.relative = 0.5;
    o.region = &region;
    remesh(m, o);
    REQUIRE_VALID(m);
    CHECK(m.n_faces() > input.n_faces());  // the region was refined
    // Every input face with a corner of weight 0 is in the output, bit for bit.
    std::set<std::array<double, 9>> kept;
    {
        std::vector<std::uint8_t> all(m.vertices_size(), 1);
        kept = triangles_where(m, all);
    }
    std::size_t checked = 0;
    for (Face f : input.faces()) {
        bool has_outside = false;
        for (Vertex v : input.vertices_of(f)) has_outside = has_outside || outside[v.idx()];
        if (!has_outside) continue;
        std::vector<std::uint8_t> only(input.vertices_size(), 0);
        for (Vertex v : input.vertices_of(f)) only[v.idx()] = 1;
        const auto t = triangles_where(input, only);
        for (const auto& tri : t) CHECK(kept.count(tri) == 1);
        ++checked;
    }
    CHECK(checked > 100);
}

TEST_CASE("remesh carries texture coordinates and colours from the input surface", "[remesh]") {
    HalfedgeMesh m = attributed_sphere();
    RemeshOptions o;
    o.relative = 0.7;
    o.iterations = 3;
    remesh(m, o);
    REQUIRE_VALID(m);
    const auto uv = m.get_vertex_property<TexCoord>("v:texcoord");
    const auto n = m.get_vertex_property<Vector3>("v:normal");
    REQUIRE(uv);
    REQUIRE(n);
    // The sphere's uv is linear in the position, so it interpolates exactly on the input
    // triangles the vertices lie on; the normals are recomputed.
    for (Vertex v : m.vertices()) {
        const Point& p = m.position(v);
        CHECK((uv[v] - TexCoord(0.5 + 0.5 * p.x(), 0.25 + 0.5 * p.y())).norm() < 1e-9);
        CHECK((n[v] - vertex_normal(m, v)).norm() < 1e-12);
    }
}

TEST_CASE("remesh keeps a texture seam: every corner keeps the uv of its side", "[remesh]") {
    // A grid whose per-corner uv is (x, y) left of x = 0.5 and (x + 10, y) right of it: the
    // corners at x = 0.5 have two values, a seam.
    HalfedgeMesh m = make_grid(12);
    const auto chart = [](const Point& p, bool right) {
        return TexCoord(p.x() + (right ? 10 : 0), p.y());
    };
    const auto right_side = [&](const HalfedgeMesh& mesh, Face f) {
        Point c = Point::Zero();
        for (Vertex v : mesh.vertices_of(f)) c += mesh.position(v) / 3.0;
        return c.x() > 0.5;
    };
    {
        auto uv = m.halfedge_property<TexCoord>("h:texcoord");
        for (Face f : m.faces())
            for (Halfedge h : m.halfedges_of(f))
                uv[h] = chart(m.position(m.to_vertex(h)), right_side(m, f));
    }
    RemeshOptions o;
    o.relative = 0.6;
    o.iterations = 4;
    const RemeshReport r = remesh(m, o);
    REQUIRE_VALID(m);
    CHECK(r.locked_vertices == 13);  // the seam's vertices
    CHECK(r.output_faces > 2 * 12 * 12);
    const auto uv = m.get_halfedge_property<TexCoord>("h:texcoord");
    REQUIRE(uv);
    for (Face f : m.faces()) {
        const bool right = right_side(m, f);
        for (Halfedge h : m.halfedges_of(f))
            CHECK((uv[h] - chart(m.position(m.to_vertex(h)), right)).norm() < 1e-9);
    }
}

TEST_CASE("adaptive remeshing makes edges shorter where the surface curves", "[remesh]") {
    // A grid with a bump in its middle: curved there, flat near the sides.
    HalfedgeMesh input = make_grid(24);
    for (Vertex v : input.vertices()) {
        Point& p = input.position(v);
        const double r2 = (p.x() - 0.5) * (p.x() - 0.5) + (p.y() - 0.5) * (p.y() - 0.5);
        p.z() = 0.15 * std::exp(-r2 / 0.01);
    }
    RemeshOptions o;
    o.length = 0.08;
    o.iterations = 5;
    HalfedgeMesh uniform = input, adaptive = input;
    const RemeshReport ru = remesh(uniform, o);
    o.adaptive = 0.02;
    const RemeshReport ra = remesh(adaptive, o);
    REQUIRE_VALID(adaptive);
    CHECK(ra.predicted_faces > ru.predicted_faces);
    CHECK(adaptive.n_faces() > uniform.n_faces());
    // Mean edge length near the bump's top against near the sides.
    const auto mean_length = [](const HalfedgeMesh& m, bool centre) {
        double sum = 0;
        int n = 0;
        for (Edge e : m.edges()) {
            const Point c = 0.5 * (m.position(m.vertex(e, 0)) + m.position(m.vertex(e, 1)));
            const double r = std::hypot(c.x() - 0.5, c.y() - 0.5);
            if (centre ? r < 0.08 : r > 0.35) {
                sum += (m.position(m.vertex(e, 0)) - m.position(m.vertex(e, 1))).norm();
                ++n;
            }
        }
        return n ? sum / n : 0.0;
    };
    INFO("adaptive: centre " << mean_length(adaptive, true) << ", sides "
                             << mean_length(adaptive, false));
    CHECK(mean_length(adaptive, true) < 0.7 * mean_length(adaptive, false));
    CHECK(mean_length(adaptive, false) > 0.8 * 0.08);
    CHECK(mesh_quality(adaptive).min_angle > 15.0);
    RemeshOptions bad;
    bad.adaptive = 0.6;
    HalfedgeMesh m = input;
    CHECK(error_text<InvalidArgument>([&] { remesh(m, bad); }).find("adaptive") !=
          std::string::npos);
}

TEST_CASE("remesh refuses bad options and oversized outputs, changing nothing", "[remesh]") {
    const HalfedgeMesh input = make_icosphere(2);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    struct Bad {
        RemeshOptions o;
        const char* word;
    };
    std::vector<Bad> bad;
    for (double x : {0.0, -1.0, nan, inf}) {
        RemeshOptions o;
        o.length = x;
        bad.push_back({o, "length"});
        RemeshOptions r;
        r.relative = x;
        bad.push_back({r, "relative"});
    }
    for (int it : {0, -3, kMaxRemeshIterations + 1}) {
        RemeshOptions o;
        o.iterations = it;
        bad.push_back({o, "iterations"});
    }
    {
        RemeshOptions o;
        o.length = 1e-7;  // about 5e14 faces on the unit sphere
        bad.push_back({o, "would make about"});
    }
    for (const Bad& b : bad) {
        HalfedgeMesh m = input;
        const std::string message = error_text<InvalidArgument>([&] { remesh(m, b.o); });
        INFO(message);
        CHECK(message.find(b.word) != std::string::npos);
        CHECK(m.n_vertices() == input.n_vertices());
        CHECK(m.positions() == input.positions());
        CHECK(m.n_faces() == input.n_faces());
    }
    HalfedgeMesh empty;
    CHECK_THROWS_AS(remesh(empty, RemeshOptions{}), InvalidArgument);
}

TEST_CASE("the remesh operation parses, runs and refuses", "[remesh]") {
    const HalfedgeMesh input = make_icosphere(2);
    NullProgress progress;
    const OperationResult r =
        run_operation(parse_operation("remesh --relative 0.8 --iterations 3"), input, progress);
    REQUIRE(r.steps.size() == 1);
    REQUIRE_VALID(r.steps[0].mesh);
    const RemeshReport* rep = report_of<RemeshReport>(r);
    REQUIRE(rep);
    CHECK(rep->iterations_done == 3);
    CHECK(rep->output_faces == r.steps[0].mesh.n_faces());
    CHECK(rep->target_length == Approx(0.8 * rep->input_mean_edge));
    CHECK_NOTHROW(check_correspondence(input, r.steps[0].mesh, r.steps[0].correspondence));
    CHECK_THROWS_AS(parse_operation("remesh --length 0"), InvalidArgument);
    CHECK_THROWS_AS(parse_operation("remesh --length 1 --relative 2"), InvalidArgument);
    CHECK_THROWS_AS(parse_operation("remesh --iterations 0"), InvalidArgument);
    const OperationResult a =
        run_operation(parse_operation("remesh --length 0.2"), input, progress);
    CHECK(report_of<RemeshReport>(a)->target_length == 0.2);
}

TEST_CASE("remeshing fandisk keeps its creases: vertices on the curves, corners in place",
          "[remesh][features]") {
    const std::string path = shared_mesh("fandisk.obj");
    SKIP_IF_MISSING(path);
    HalfedgeMesh input = read_mesh(path).mesh;
    FeatureDetectionOptions d;
    d.angle_deg = 60;
    detect_features(input, d);
    REQUIRE(has_features(input));
    HalfedgeMesh m = input;
    RemeshOptions o;  // L = the mean edge length, 10 iterations, the stored features
    const RemeshReport r = remesh(m, o);
    REQUIRE_VALID(m);
    const double diagonal = bounding_box(input).diagonal();
    CHECK(feature_drift(input, m) <= 1e-9 * diagonal);
    CHECK(corner_positions(m) == corner_positions(input));
    // The curves keep their length (chords of a curved crease are a little shorter).
    const double before = total_length(test::sharp_segments(input));
    CHECK(total_length(test::sharp_segments(m)) == Approx(before).epsilon(0.01));
    std::size_t in_band = 0;
    const auto curves = test::sharp_segments(m);
    for (const auto& s : curves) {
        const double l = (s[1] - s[0]).norm();
        in_band += l >= 0.8 * r.target_length && l <= 4.0 / 3.0 * r.target_length;
    }
    INFO("sharp edges " << curves.size() << ", in the band " << in_band);
    CHECK(in_band >= 0.85 * double(curves.size()));
}
