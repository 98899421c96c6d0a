// Soft selections (core/algorithms/selection.h) and every operation on a region: outside the
// region nothing changes bit for bit, inside it the operation does what it does on the whole
// mesh, an all-ones region gives exactly the unselected result, the feather's jump between
// neighbours is bounded, and validate() holds after every operation.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <set>

#include "app/ops/operation.h"
#include "app/ops/smooth_op.h"
#include "core/algorithms/coloring.h"
#include "core/algorithms/decimation.h"
#include "core/algorithms/fairing.h"
#include "core/algorithms/generators.h"
#include "core/algorithms/mesh_stats.h"
#include "core/algorithms/noise.h"
#include "core/algorithms/orientation.h"
#include "core/algorithms/selection.h"
#include "core/algorithms/spectral.h"
#include "core/algorithms/weld.h"
#include "core/errors.h"
#include "core/geometry.h"
#include "core/io/mesh_io.h"
#include "core/mesh_builder.h"
#include "core/validate.h"
#include "test_helpers.h"

using namespace trilab;
using namespace trilab::test;

namespace {

bool same_point(const Point& a, const Point& b) {
    return std::memcmp(a.data(), b.data(), sizeof(Point)) == 0;
}

bool bit_identical(const std::vector<Point>& a, const std::vector<Point>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(Point)) == 0;
}

/// The faces as vertex-index triples, for comparing two meshes' connectivity.
std::vector<std::array<Vertex, 3>> face_list(const HalfedgeMesh& m) {
    std::vector<std::array<Vertex, 3>> f;
    for (Face x : m.faces()) f.push_back(m.face_vertices(x));
    return f;
}

/// A noisy sphere and a region: the cap x > 0.2 (weight 1), everything else 0.
struct Fixture {
    HalfedgeMesh mesh = make_noisy_sphere(8, 0.02, 3);
    Selection region = sphere_selection(mesh, Point(1, 0, 0), 0.9);
};

std::size_t count_weight(const Selection& s, float w) {
    return std::size_t(std::count(s.begin(), s.end(), w));
}

/// A grid whose every triangle has its own vertices (all edges are seams to weld).
HalfedgeMesh shattered_grid() {
    const PolygonSoup in = to_soup(make_grid(6));
    PolygonSoup soup;
    for (std::size_t f = 0; f < in.n_faces(); ++f) {
        std::vector<Index> face;
        for (std::size_t k = in.face_offsets[f]; k < in.face_offsets[f + 1]; ++k) {
            face.push_back(Index(soup.positions.size()));
            soup.positions.push_back(in.positions[in.corners[k]]);
        }
        soup.add_face(face);
    }
    LoadReport report;
    return build_mesh(soup, report);
}

}  // namespace

// ---- the selection itself --------------------------------------------------------------------

TEST_CASE("ways to select give 0/1 weights of the right vertices", "[selection]") {
    const HalfedgeMesh m = make_icosphere(4);
    const Selection sphere = sphere_selection(m, Point(0, 0, 1), 0.5);
    for (Vertex v : m.vertices())
        CHECK((sphere[v.idx()] == 1.0f) == ((m.position(v) - Point(0, 0, 1)).norm() <= 0.5));
    CHECK(count_selected(sphere) > 0);
    CHECK(count_selected(sphere) < m.n_vertices());

    // Geodesic ball on the unit sphere: the cap within arc length R of the pole.
    Vertex pole;
    for (Vertex v : m.vertices())
        if (!pole.is_valid() || m.position(v).z() > m.position(pole).z()) pole = v;
    const Selection ball = geodesic_selection(m, pole, 0.6);
    for (Vertex v : m.vertices()) {
        const double arc = std::acos(std::clamp(m.position(v).normalized().z(), -1.0, 1.0));
        if (arc < 0.5) CHECK(ball[v.idx()] == 1.0f);
        if (arc > 0.7) CHECK(ball[v.idx()] == 0.0f);
    }

    const HalfedgeMesh two = two_spheres();
    const Selection comp = component_selection(two, Vertex(0));
    CHECK(count_selected(comp) == two.n_vertices() / 2);
    for (Vertex v : two.vertices()) CHECK((comp[v.idx()] == 1.0f) == (two.position(v).x() < 1.5));

    std::vector<double> z(m.vertices_size());
    for (Vertex v : m.vertices()) z[v.idx()] = m.position(v).z();
    const Selection above = threshold_selection(m, z, 0.3, ThresholdSide::Above);
    const Selection below = threshold_selection(m, z, 0.3, ThresholdSide::Below);
    for (Vertex v : m.vertices()) {
        CHECK((above[v.idx()] == 1.0f) == (z[v.idx()] > 0.3));
        CHECK((below[v.idx()] == 1.0f) == (z[v.idx()] < 0.3));
    }
}

TEST_CASE("grow and shrink by rings, invert, clear", "[selection]") {
    const HalfedgeMesh m = make_icosphere(3);
    Selection s = empty_selection(m);
    s[0] = 1.0f;
    Selection grown = s;
    grow_selection(m, grown, 1);
    CHECK(count_selected(grown) == 1 + m.valence(Vertex(0)));
    grow_selection(m, grown, 2);
    Selection back = grown;
    shrink_selection(m, back, 2);
    CHECK(count_selected(back) == 1 + m.valence(Vertex(0)));
    shrink_selection(m, back, 1);
    CHECK(back == s);
    Selection inv = s;
    invert_selection(m, inv);
    CHECK(count_selected(inv) == m.n_vertices() - 1);
    CHECK(inv[0] == 0.0f);
    CHECK(count_selected(empty_selection(m)) == 0);
    CHECK(selects_everything(m, full_selection(m)));
    CHECK_FALSE(selects_everything(m, inv));
}

TEST_CASE("a bad selection is refused with a message naming the problem", "[selection]") {
    const HalfedgeMesh m = make_icosahedron();
    Selection s(m.vertices_size(), 0.5f);
    CHECK_NOTHROW(check_selection(m, s));
    Selection short_one(3, 1.0f);
    CHECK_THROWS_WITH(check_selection(m, short_one, "--region"),
                      "--region: expected one weight per vertex (12), got 3");
    s[4] = 1.5f;
    CHECK_THROWS_WITH(check_selection(m, s),
                      "selection: vertex 4: expected a weight from 0 to 1, "
                      "got 1.5");
    s[4] = std::nanf("");
    CHECK_THROWS_AS(check_selection(m, s), InvalidArgument);
    CHECK_THROWS_AS(sphere_selection(m, Point::Zero(), -1), InvalidArgument);
    CHECK_THROWS_AS(geodesic_selection(m, Vertex(99), 1), InvalidArgument);
    CHECK_THROWS_AS(component_selection(m, Vertex(12)), InvalidArgument);
    Selection ok = full_selection(m);
    CHECK_THROWS_AS(grow_selection(m, ok, -1), InvalidArgument);
    CHECK_THROWS_AS(feather_selection(m, ok, -0.1), InvalidArgument);
}

TEST_CASE("the feather falls smoothly with a bounded jump between neighbours", "[selection]") {
    const HalfedgeMesh m = make_icosphere(20);
    const double width = 0.5;
    const Selection hard = sphere_selection(m, Point(0, 0, 1), 0.5);
    Selection soft = hard;
    feather_selection(m, soft, width);
    CHECK_NOTHROW(check_selection(m, soft));
    std::size_t fractional = 0;
    for (Vertex v : m.vertices()) {
        if (hard[v.idx()] == 1.0f) CHECK(soft[v.idx()] == 1.0f);  // the selection is kept
        if (soft[v.idx()] > 0.0f && soft[v.idx()] < 1.0f) ++fractional;
    }
    CHECK(fractional > 20);
    // The bound: |w_i - w_j| <= 1.5 l_ij / width (smoothstep's slope is at most 1.5 and the
    // edge-graph distance changes by at most l_ij across an edge), plus float rounding.
    double worst = 0;
    for (Edge e : m.edges()) {
        const Halfedge h = HalfedgeMesh::halfedge(e, 0);
        const Vertex a = m.from_vertex(h), b = m.to_vertex(h);
        const double l = (m.position(a) - m.position(b)).norm();
        const double jump = std::abs(double(soft[a.idx()]) - double(soft[b.idx()]));
        CHECK(jump <= 1.5 * l / width + 1e-6);
        worst = std::max(worst, jump);
    }
    // Without the feather the jump across the selection's edge is 1.
    CHECK(worst < 0.5);
    // Far away nothing is selected.
    for (Vertex v : m.vertices())
        if (m.position(v).z() < 0) CHECK(soft[v.idx()] == 0.0f);
}

TEST_CASE("the selection round-trips through PLY and OM bit for bit", "[selection][io]") {
    TempDir dir;
    HalfedgeMesh m = make_icosphere(3);
    Selection s = sphere_selection(m, Point(0, 0, 1), 0.8);
    feather_selection(m, s, 0.3);
    s[5] = 0.1f;  // a weight float cannot write in few digits
    store_selection(m, s);
    for (const char* name : {"s.ply", "s_ascii.ply", "s.om"}) {
        WriteOptions o;
        o.ascii = std::string(name) == "s_ascii.ply";
        write_mesh(m, dir.path(name), o);
        const LoadedMesh back = read_mesh(dir.path(name));
        const std::optional<Selection> r = stored_selection(back.mesh);
        INFO(name);
        REQUIRE(r);
        REQUIRE(r->size() == s.size());
        CHECK(std::memcmp(r->data(), s.data(), s.size() * sizeof(float)) == 0);
    }
    // An out-of-range weight in a PLY file is refused, naming the vertex.
    {
        std::ofstream f(dir.path("bad.ply"));
        f << "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
             "property float z\nproperty float selection\nelement face 1\n"
             "property list uchar int vertex_indices\nend_header\n0 0 0 0\n1 0 0 2\n0 1 0 1\n"
             "3 0 1 2\n";
    }
    CHECK_THROWS_WITH(read_mesh(dir.path("bad.ply")),
                      Catch::Matchers::Contains("vertex 1: selection weight"));
}

// ---- every operation on a region ------------------------------------------------------------

TEST_CASE("smoothing a region: outside bit for bit, inside as on the whole mesh", "[selection]") {
    Fixture fx;
    const HalfedgeMesh& m = fx.mesh;
    REQUIRE(count_weight(fx.region, 1.0f) > 20);
    REQUIRE(count_weight(fx.region, 0.0f) > 20);
    const auto op = GENERATE(FairingOperator::Umbrella, FairingOperator::CurvatureFlow,
                             FairingOperator::Taubin);
    const auto integration = GENERATE(Integration::Explicit, Integration::Implicit);
    if (op == FairingOperator::Taubin && integration == Integration::Implicit) return;
    FairingOptions o;
    o.op = op;
    o.integration = integration;
    o.step = integration == Integration::Implicit ? 2.0 : 0.5;
    o.iterations = 1;
    o.preserve_volume = GENERATE(false, true);
    const FairingResult whole = smooth(m, o);
    FairingOptions r = o;
    r.region = &fx.region;
    const FairingResult part = smooth(m, r);
    REQUIRE(validate(part.mesh));
    REQUIRE_FALSE(part.stopped_early);
    std::size_t moved = 0;
    for (Vertex v : m.vertices()) {
        const Point& before = m.position(v);
        const Point& after = part.mesh.position(v);
        if (fx.region[v.idx()] == 0.0f)
            CHECK(same_point(before, after));
        else if (!same_point(before, after))
            ++moved;
        // One explicit step without the volume's rescaling moves a selected vertex exactly as on
        // the whole mesh (its neighbours' old positions are the same).
        if (fx.region[v.idx()] == 1.0f && integration == Integration::Explicit &&
            !o.preserve_volume && op != FairingOperator::Taubin)
            CHECK(same_point(after, whole.mesh.position(v)));
    }
    CHECK(moved > 20);
    // An all-ones region is the whole mesh, bit for bit.
    const Selection ones = full_selection(m);
    FairingOptions all = o;
    all.region = &ones;
    CHECK(bit_identical(smooth(m, all).mesh.positions(), whole.mesh.positions()));
}

TEST_CASE("smoothing a feathered region blends into the untouched surface", "[selection]") {
    Fixture fx;
    Selection soft = fx.region;
    feather_selection(fx.mesh, soft, 0.3);
    FairingOptions o;
    o.iterations = 5;
    o.region = &soft;
    const FairingResult r = smooth(fx.mesh, o);
    REQUIRE(validate(r.mesh));
    for (Vertex v : fx.mesh.vertices())
        if (soft[v.idx()] == 0.0f) CHECK(same_point(fx.mesh.position(v), r.mesh.position(v)));
    // Implicit: fixed rows for weight 0, fractional weights blended.
    o.integration = Integration::Implicit;
    o.step = 5;
    const FairingResult ri = smooth(fx.mesh, o);
    REQUIRE(validate(ri.mesh));
    for (Vertex v : fx.mesh.vertices())
        if (soft[v.idx()] == 0.0f) CHECK(same_point(fx.mesh.position(v), ri.mesh.position(v)));
}

namespace {

/// Smooths `m` on `region` twice: on the moving vertices only (the default) and through the
/// whole-mesh passes (FairingOptions::restrict_to_region false).
std::pair<FairingResult, FairingResult> restricted_and_whole(const HalfedgeMesh& m,
                                                             const Selection& region,
                                                             FairingOptions o) {
    o.region = &region;
    o.restrict_to_region = true;
    FairingResult restricted = smooth(m, o);
    o.restrict_to_region = false;
    return {std::move(restricted), smooth(m, o)};
}

/// Every figure of two runs that must agree bit for bit.
void check_same_run(const FairingResult& a, const FairingResult& b) {
    CHECK(bit_identical(a.mesh.positions(), b.mesh.positions()));
    REQUIRE(a.step_positions.size() == b.step_positions.size());
    for (std::size_t k = 0; k < a.step_positions.size(); ++k)
        CHECK(bit_identical(a.step_positions[k], b.step_positions[k]));
    CHECK(std::memcmp(&a.max_stable_step, &b.max_stable_step, sizeof(double)) == 0);
    CHECK(a.iterations_done == b.iterations_done);
    CHECK(a.stopped_early == b.stopped_early);
    CHECK(a.stop_reason == b.stop_reason);
    CHECK(a.report == b.report);
    CHECK(std::memcmp(&a.final_volume, &b.final_volume, sizeof(double)) == 0);
}

/// A unit tetrahedron (weight 1) beside a tiny one (weight 0), one closed mesh.
HalfedgeMesh big_and_tiny_tetrahedra() {
    const PolygonSoup one = to_soup(make_tetrahedron());
    PolygonSoup soup = one;
    const Index base = Index(one.positions.size());
    for (const Point& p : one.positions) soup.positions.push_back(Point(10, 0, 0) + 0.01 * p);
    for (std::size_t f = 0; f < one.n_faces(); ++f) {
        std::vector<Index> face;
        for (std::size_t k = one.face_offsets[f]; k < one.face_offsets[f + 1]; ++k)
            face.push_back(base + one.corners[k]);
        soup.add_face(face);
    }
    LoadReport report;
    return build_mesh(soup, report);
}

}  // namespace

TEST_CASE(
    "explicit smoothing restricted to a region's vertices gives the whole-mesh result bit "
    "for bit",
    "[selection][fairing]") {
    // A feathered region (fractional weights) on the bunny (open: boundary and isolated
    // vertices) and on a closed noisy sphere (the volume's sign is checked every iteration).
    const bool bunny = GENERATE(true, false);
    HalfedgeMesh m;
    Selection region;
    if (bunny) {
        const std::string path = shared_mesh("stanford-bunny.obj");
        SKIP_IF_MISSING(path);
        m = read_mesh(path).mesh;
        region = sphere_selection(m, Point(-0.02, 0.11, 0), 0.05);
        feather_selection(m, region, 0.03);
    } else {
        m = make_noisy_sphere(12, 0.02, 5);
        region = sphere_selection(m, Point(1, 0, 0), 0.8);
        feather_selection(m, region, 0.4);
    }
    REQUIRE(count_weight(region, 0.0f) > m.n_vertices() / 3);
    REQUIRE(std::count_if(region.begin(), region.end(),
                          [](float w) { return w > 0.0f && w < 1.0f; }) > 20);
    // Umbrella within the provable limit, beyond it (energy and area checks), and Taubin with
    // and without its energy check.
    const int variant = GENERATE(0, 1, 2, 3);
    INFO((bunny ? "bunny" : "noisy sphere") << ", variant " << variant);
    FairingOptions o;
    o.iterations = 6;
    o.step = variant == 1 ? 1.2 : 0.5;
    if (variant >= 2) o.op = FairingOperator::Taubin;
    if (variant == 3) {
        o.taubin_lambda = 0.9;
        o.taubin_mu = -1.0;
    }
    const auto [restricted, whole] = restricted_and_whole(m, region, o);
    REQUIRE(validate(restricted.mesh));
    REQUIRE_FALSE(restricted.stopped_early);
    check_same_run(restricted, whole);
    std::size_t moved = 0;
    for (Vertex v : m.vertices()) {
        if (region[v.idx()] == 0.0f)
            CHECK(same_point(m.position(v), restricted.mesh.position(v)));
        else if (!same_point(m.position(v), restricted.mesh.position(v)))
            ++moved;
    }
    CHECK(moved > 20);
}

TEST_CASE("a region's smoothing that diverges stops with its reason, restricted or not",
          "[selection][fairing]") {
    SECTION("an absurd step: the bounding box or the fairing energy grows") {
        Fixture fx;
        FairingOptions o;
        o.step = 50;
        o.iterations = 3;
        const auto [restricted, whole] = restricted_and_whole(fx.mesh, fx.region, o);
        CHECK(restricted.stopped_early);
        CHECK(restricted.stopped_at_iteration == 1);
        CHECK_THAT(restricted.stop_reason, Catch::Contains("iteration 1: the") &&
                                               Catch::Contains("step 50 is above the stable"));
        CHECK(bit_identical(restricted.mesh.positions(), fx.mesh.positions()));
        check_same_run(restricted, whole);
    }
    SECTION("a stable step that turns the closed mesh inside out") {
        // Umbrella step 1 reflects the big tetrahedron through its centroid (scaled by 1/3);
        // the tiny one, unselected, cannot keep the total volume's sign.
        const HalfedgeMesh m = big_and_tiny_tetrahedra();
        REQUIRE(validate(m));
        Selection region(m.vertices_size(), 0.0f);
        for (Index v = 0; v < 4; ++v) region[v] = 1.0f;
        FairingOptions o;
        o.step = 1.0;
        const auto [restricted, whole] = restricted_and_whole(m, region, o);
        CHECK(restricted.stopped_early);
        CHECK_THAT(restricted.stop_reason, Catch::Contains("the volume changed sign"));
        check_same_run(restricted, whole);
    }
}

TEST_CASE("explicit smoothing of a small region costs time that follows the region",
          "[selection][fairing]") {
    // 36,002 vertices, about 150 of them selected: 100 umbrella iterations over the whole mesh
    // cost tens of ms, on the region's vertices a few passes' set-up.
    const HalfedgeMesh m = make_icosphere(60);
    const Selection region = sphere_selection(m, Point(0, 0, 1), 0.12);
    REQUIRE(count_weight(region, 1.0f) > 50);
    REQUIRE(count_weight(region, 1.0f) < 500);
    FairingOptions o;
    o.iterations = 100;
    o.keep_steps = false;
    o.region = &region;
    auto fastest_ms = [&](bool restrict_to_region) {
        o.restrict_to_region = restrict_to_region;
        double best = 1e300;
        for (int k = 0; k < 3; ++k) {
            const auto t0 = std::chrono::steady_clock::now();
            const FairingResult r = smooth(m, o);
            const auto t1 = std::chrono::steady_clock::now();
            REQUIRE(r.iterations_done == 100);
            best = std::min(best, std::chrono::duration<double, std::milli>(t1 - t0).count());
        }
        return best;
    };
    const double whole = fastest_ms(false), restricted = fastest_ms(true);
    INFO("whole-mesh passes " << whole << " ms, restricted " << restricted << " ms");
    CHECK(restricted < 0.5 * whole);
}

TEST_CASE("noise on a region scales each offset by the weight", "[selection]") {
    Fixture fx;
    Selection soft = fx.region;
    feather_selection(fx.mesh, soft, 0.3);
    NoiseOptions o;
    o.amount_percent = 20;
    HalfedgeMesh whole = fx.mesh, part = fx.mesh, all = fx.mesh;
    add_noise(whole, o);
    NoiseOptions r = o;
    r.region = &soft;
    add_noise(part, r);
    REQUIRE(validate(part));
    for (Vertex v : fx.mesh.vertices()) {
        const float w = soft[v.idx()];
        const Point& p0 = fx.mesh.position(v);
        if (w == 0.0f) CHECK(same_point(p0, part.position(v)));
        if (w == 1.0f) CHECK(same_point(whole.position(v), part.position(v)));
        if (w > 0.0f && w < 1.0f) {
            const double full = (whole.position(v) - p0).norm();
            CHECK(std::abs((part.position(v) - p0).norm() - w * full) <= 1e-12 + 1e-6 * full);
        }
    }
    const Selection ones = full_selection(fx.mesh);
    NoiseOptions a = o;
    a.region = &ones;
    add_noise(all, a);
    CHECK(bit_identical(all.positions(), whole.positions()));
    Selection wrong(3, 1.0f);
    a.region = &wrong;
    CHECK_THROWS_AS(add_noise(all, a), InvalidArgument);
}

TEST_CASE("a frequency band on a region scales the displacement per vertex", "[selection]") {
    Fixture fx;
    Selection soft = fx.region;
    feather_selection(fx.mesh, soft, 0.3);
    SpectralOptions so;
    so.k = 20;
    const SpectralDecomposition d = decompose(fx.mesh, so);
    const HalfedgeMesh whole = reconstruct(fx.mesh, d, 0, 9);
    const HalfedgeMesh part = reconstruct(fx.mesh, d, 0, 9, BandRest::Exclude, &soft);
    REQUIRE(validate(part));
    for (Vertex v : fx.mesh.vertices()) {
        const float w = soft[v.idx()];
        if (w == 0.0f) CHECK(same_point(fx.mesh.position(v), part.position(v)));
        if (w == 1.0f) CHECK(same_point(whole.position(v), part.position(v)));
    }
    const Selection ones = full_selection(fx.mesh);
    CHECK(bit_identical(reconstruct(fx.mesh, d, 0, 9, BandRest::Exclude, &ones).positions(),
                        whole.positions()));
}

TEST_CASE("decimating a region collapses only selected edges", "[selection]") {
    Fixture fx;
    HalfedgeMesh m = fx.mesh;
    auto orig = m.add_vertex_property<int>("test:orig", -1);
    for (Vertex v : m.vertices()) orig[v] = int(v.idx());
    DecimationOptions o;
    o.percent = 50;
    o.levels = DecimationLevels::Last;
    o.region = &fx.region;
    const DecimationResult r = decimate(m, o);
    REQUIRE(r.levels.size() == 1);
    const HalfedgeMesh& out = r.levels.back().mesh;
    REQUIRE(validate(out));
    const auto out_orig = out.get_vertex_property<int>("test:orig");
    std::set<int> kept;
    for (Vertex v : out.vertices()) {
        const int i = out_orig[v];
        kept.insert(i);
        if (fx.region[std::size_t(i)] == 0.0f)
            CHECK(same_point(out.position(v), m.position(Vertex(Index(i)))));
    }
    // Every unselected vertex survives, and half of the region's vertices went.
    const std::size_t outside = count_weight(fx.region, 0.0f);
    for (Vertex v : m.vertices())
        if (fx.region[v.idx()] == 0.0f) CHECK(kept.count(int(v.idx())) == 1);
    const std::size_t inside = m.n_vertices() - outside;
    CHECK(out.n_vertices() == m.n_vertices() - inside / 2);
    // All ones: the unselected run, bit for bit.
    const Selection ones = full_selection(m);
    DecimationOptions a = o, w = o;
    a.region = &ones;
    w.region = nullptr;
    const HalfedgeMesh all = decimate(m, a).levels.back().mesh;
    const HalfedgeMesh whole = decimate(m, w).levels.back().mesh;
    CHECK(bit_identical(all.positions(), whole.positions()));
    CHECK(face_list(all) == face_list(whole));
}

TEST_CASE("welding a region joins only its vertices", "[selection]") {
    const HalfedgeMesh m = shattered_grid();
    const Selection left = threshold_selection(
        m,
        [&] {
            std::vector<double> x(m.vertices_size());
            for (Vertex v : m.vertices()) x[v.idx()] = m.position(v).x();
            return x;
        }(),
        0.5, ThresholdSide::Below);
    WeldOptions o;
    const WeldResult whole = weld_coincident_vertices(m, o);
    o.region = &left;
    const WeldResult part = weld_coincident_vertices(m, o);
    REQUIRE(validate(part.mesh));
    CHECK(part.mesh.n_vertices() > whole.mesh.n_vertices());
    CHECK(part.mesh.n_vertices() < m.n_vertices());
    for (Vertex v : m.vertices()) {
        const Index w = part.vertex_map[v.idx()];
        CHECK(same_point(part.mesh.position(Vertex(w)), m.position(v)));
        if (left[v.idx()] == 0.0f) {  // joined with nothing
            for (Vertex u : m.vertices())
                if (u != v) CHECK(part.vertex_map[u.idx()] != w);
        }
    }
    const Selection ones = full_selection(m);
    o.region = &ones;
    const WeldResult all = weld_coincident_vertices(m, o);
    CHECK(bit_identical(all.mesh.positions(), whole.mesh.positions()));
    CHECK(face_list(all.mesh) == face_list(whole.mesh));
}

TEST_CASE("flipping a region flips the components it touches", "[selection]") {
    const HalfedgeMesh m = two_spheres();
    const Selection one = sphere_selection(m, Point(0, 0, 1), 0.3);  // on the first sphere
    HalfedgeMesh part = m, whole = m, all = m;
    FlipOptions o;
    o.region = &one;
    const FlipReport r = flip_orientation(part, o);
    REQUIRE(validate(part));
    CHECK(r.components == 1);
    CHECK(r.faces == m.n_faces() / 2);
    CHECK(bit_identical(part.positions(), m.positions()));
    const auto before = face_list(m), after = face_list(part);
    for (std::size_t f = 0; f < before.size(); ++f) {
        const bool second = m.position(before[f][0]).x() > 1.5;
        if (second)
            CHECK(after[f] == before[f]);  // untouched
        else
            CHECK(after[f] != before[f]);  // reversed (same vertices, other order)
    }
    flip_orientation(whole);
    const Selection ones = full_selection(m);
    o.region = &ones;
    flip_orientation(all, o);
    CHECK(face_list(all) == face_list(whole));
    // Exactly the whole flip, to the array (the region's components are found by a flood).
    CHECK(all.halfedge_next_array() == whole.halfedge_next_array());
    CHECK(all.halfedge_prev_array() == whole.halfedge_prev_array());
    CHECK(all.halfedge_face_array() == whole.halfedge_face_array());
    CHECK(all.vertex_halfedge_array() == whole.vertex_halfedge_array());
    CHECK(all.face_halfedge_array() == whole.face_halfedge_array());

    // The components given (as the viewer keeps them): the same flip, the same report.
    std::vector<Index> labels;
    label_components(m, labels);
    HalfedgeMesh given = m;
    o.region = &one;
    o.components = &labels;
    const FlipReport r_given = flip_orientation(given, o);
    CHECK(r_given.components == 1);
    CHECK(r_given.faces == r.faces);
    CHECK(given.halfedge_next_array() == part.halfedge_next_array());
    CHECK(given.halfedge_prev_array() == part.halfedge_prev_array());
    CHECK(given.halfedge_face_array() == part.halfedge_face_array());
    CHECK(given.vertex_halfedge_array() == part.vertex_halfedge_array());
    CHECK(given.face_halfedge_array() == part.face_halfedge_array());
    // Through the operation layer (RunSettings::components): labels that call both spheres
    // one component flip both, which shows they are the ones used.
    const std::vector<Index> one_component(m.vertices_size(), 0);
    RunSettings settings;
    settings.region = &one;
    settings.components = &one_component;
    NullProgress progress;
    const OperationResult op = run_operation(parse_operation("flip"), m, progress, settings);
    CHECK(face_list(op.steps.back().mesh) == face_list(whole));
    settings.components = &labels;
    CHECK(face_list(
              run_operation(parse_operation("flip"), m, progress, settings).steps.back().mesh) ==
          face_list(part));
    // Labels of another size are refused, and the mesh is left as it was.
    const std::vector<Index> short_labels(3, 0);
    o.components = &short_labels;
    HalfedgeMesh refused = m;
    CHECK_THROWS_WITH(flip_orientation(refused, o), Catch::Matchers::Contains("component labels"));
    CHECK(face_list(refused) == face_list(m));
}

TEST_CASE("operations take the region as input and report it", "[selection][operation]") {
    Fixture fx;
    NullProgress progress;
    RunSettings settings;
    settings.region = &fx.region;
    const OperationResult r =
        run_operation(parse_operation("smooth --iterations 3"), fx.mesh, progress, settings);
    bool found = false;
    for (const auto& [k, v] : r.values)
        if (k == "region_vertices") {
            found = true;
            CHECK(v == double(count_selected(fx.region)));
        }
    CHECK(found);
    CHECK(r.parameters == "--operator umbrella --integration explicit --step 0.5 --iterations 3");
    for (Vertex v : fx.mesh.vertices())
        if (fx.region[v.idx()] == 0.0f)
            CHECK(same_point(fx.mesh.position(v), r.steps.back().mesh.position(v)));
    // An operation that does not take a region yet refuses it, naming itself.
    CHECK_THROWS_WITH(run_operation(parse_operation("remove-components --min-faces 3"), fx.mesh,
                                    progress, settings),
                      Catch::Matchers::Contains("remove-components does not work on a region"));
    Selection wrong(4, 1.0f);
    settings.region = &wrong;
    CHECK_THROWS_WITH(run_operation(parse_operation("noise"), fx.mesh, progress, settings),
                      Catch::Matchers::Contains("--region: expected one weight"));
}

TEST_CASE("an implicit run on a small region solves the region's rows only, with the same result",
          "[selection][fairing]") {
    // Issue 38, item 3: 3,214 region vertices solved as 34,834 rows. Restricted, the system
    // is built on the faces around the region; the outside stays bit for bit and the inside
    // agrees with the whole-mesh run to the solver's tolerance; volumes are the whole mesh's.
    const HalfedgeMesh m = make_noisy_sphere(24, 0.02, 5);
    const Selection region = sphere_selection(m, Point(0, 0, 1), 0.35);
    const std::size_t selected = count_selected(region);
    REQUIRE(selected > 30);
    REQUIRE(selected * 20 < m.n_vertices());
    for (FairingOperator op : {FairingOperator::Umbrella, FairingOperator::CurvatureFlow,
                               FairingOperator::SecondOrder}) {
        INFO(fairing_operator_name(op));
        FairingOptions o;
        o.op = op;
        o.integration = Integration::Implicit;
        o.step = 5;
        o.iterations = 2;
        o.region = &region;
        o.max_relative_residual = 1e-10;
        o.cg_tolerance = 1e-12;
        const FairingResult part = smooth(m, o);
        FairingOptions w = o;
        w.restrict_to_region = false;
        const FairingResult whole = smooth(m, w);
        REQUIRE_FALSE(part.stopped_early);
        REQUIRE_FALSE(whole.stopped_early);
        REQUIRE(validate(part.mesh));
        CHECK(part.solved_rows == selected);  // a closed sphere: every selected vertex is free
        CHECK(whole.solved_rows == selected);
        CHECK(whole.operator_rows == m.n_vertices());
        CHECK(part.operator_rows < 4 * selected);  // the region and a ring or two around it
        CHECK(part.iterations_done == 2);
        REQUIRE(part.step_positions.size() == 2);
        CHECK(bit_identical(part.step_positions.back(), part.mesh.positions()));
        double largest = 0;
        std::size_t moved = 0;
        for (Vertex v : m.vertices()) {
            const Point& p = part.mesh.position(v);
            if (region[v.idx()] == 0.0f) {
                REQUIRE(same_point(p, m.position(v)));
                REQUIRE(same_point(part.step_positions[0][v.idx()], m.position(v)));
                continue;
            }
            moved += same_point(p, m.position(v)) ? 0 : 1;
            largest = std::max(largest, (p - whole.mesh.position(v)).norm());
        }
        CHECK(moved == selected);
        CHECK(largest < 1e-8);  // the unit sphere: the solver's tolerance
        CHECK(part.initial_volume == Approx(whole.initial_volume).epsilon(1e-12));
        CHECK(part.final_volume == Approx(whole.final_volume).epsilon(1e-9));
        // The CLI's way (no steps kept) gives the same last state.
        FairingOptions last = o;
        last.keep_steps = false;
        const FairingResult cli = smooth(m, last);
        CHECK(bit_identical(cli.mesh.positions(), part.mesh.positions()));
        CHECK(cli.step_positions.empty());
    }
}

TEST_CASE("smooth on a region reports the smoothing distance over the mesh and over what moved",
          "[selection][operation]") {
    // Issue 38, item 3: a region's mean over the whole mesh is diluted by the vertices that
    // stayed; both are reported, named apart.
    const HalfedgeMesh m = make_noisy_sphere(16, 0.02, 7);
    const Selection region = sphere_selection(m, Point(0, 0, 1), 0.4);
    NullProgress progress;
    RunSettings settings;
    settings.region = &region;
    const OperationResult r = run_operation(
        parse_operation("smooth --operator curvature-flow --integration implicit --step 5"), m,
        progress, settings);
    std::map<std::string, double> v(r.values.begin(), r.values.end());
    const HalfedgeMesh& out = r.steps.back().mesh;
    const std::vector<double> d = smoothing_distance(out, m.positions());
    double sum = 0;
    std::size_t moved = 0;
    for (Vertex x : m.vertices()) {
        sum += std::abs(d[x.idx()]);
        moved += same_point(out.position(x), m.position(x)) ? 0 : 1;
    }
    REQUIRE(moved > 10);
    REQUIRE(moved <= count_selected(region));
    CHECK(v.at("moved_vertices") == double(moved));
    CHECK(v.at("mean_smoothing_distance") == Approx(sum / double(m.n_vertices())));
    CHECK(v.at("mean_smoothing_distance_moved") == Approx(sum / double(moved)));
    CHECK(v.at("mean_smoothing_distance_moved") > 5 * v.at("mean_smoothing_distance"));
    CHECK(v.at("solved_rows") == double(count_selected(region)));
    const SmoothReport* rep = report_of<SmoothReport>(r);
    REQUIRE(rep);
    CHECK(rep->mean_smoothing_distance_moved == v.at("mean_smoothing_distance_moved"));
}
