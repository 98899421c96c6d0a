// Fairing: the four discrete Laplacians (sign convention, constants, linear precision,
// symmetric forms) and smooth() (noise reduction, stability, volume, first-order agreement of
// implicit and explicit steps, boundaries, degenerate input, option checks).
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "core/curvature.h"
#include "core/errors.h"
#include "core/fairing.h"
#include "core/generators.h"
#include "core/geometry.h"
#include "core/io/mesh_io.h"
#include "core/laplacian.h"
#include "core/mesh_builder.h"
#include "core/noise.h"
#include "test_helpers.h"

using namespace trilab;

namespace {

const LaplacianOperator kOperators[] = {
    LaplacianOperator::Umbrella, LaplacianOperator::ImprovedUmbrella,
    LaplacianOperator::CurvatureFlow, LaplacianOperator::SecondOrder};

HalfedgeMesh noisy_sphere() {
    return make_noisy_sphere(10, 0.01, 7);
}

/// A flat grid whose interior vertices are moved in the plane (an irregular triangulation).
HalfedgeMesh jittered_grid() {
    HalfedgeMesh m = make_grid(8);
    unsigned k = 0;
    for (Vertex v : m.vertices()) {
        if (m.is_boundary(v)) continue;
        ++k;
        m.position(v).x() += 0.02 * std::sin(3.1 * k);
        m.position(v).y() += 0.02 * std::cos(1.7 * k);
    }
    return m;
}

double variance_of_mean_curvature(const HalfedgeMesh& m) {
    const VertexCurvatures c = compute_curvatures(m);
    double sum = 0, sum2 = 0, n = 0;
    for (std::size_t i = 0; i < c.mean.size(); ++i) {
        if (!c.valid[i]) continue;
        sum += c.mean[i];
        sum2 += c.mean[i] * c.mean[i];
        n += 1;
    }
    REQUIRE(n > 0);
    return sum2 / n - (sum / n) * (sum / n);
}

void require_finite(const HalfedgeMesh& m) {
    for (Vertex v : m.vertices()) {
        INFO("vertex " << v.idx());
        REQUIRE(m.position(v).allFinite());
    }
}

void require_sane(const FairingResult& r, std::size_t expected_steps) {
    REQUIRE(r.steps.size() == expected_steps);
    for (const HalfedgeMesh& s : r.steps) {
        REQUIRE_VALID(s);
        require_finite(s);
    }
}

double max_abs(const Eigen::MatrixXd& x) {
    return x.size() ? x.cwiseAbs().maxCoeff() : 0.0;
}

double steps_for_explicit(LaplacianOperator op) {
    switch (op) {
        case LaplacianOperator::ImprovedUmbrella:
            return 0.002;
        case LaplacianOperator::SecondOrder:
            return 0.2;
        default:
            return 0.5;
    }
}

}  // namespace

TEST_CASE("every Laplacian annihilates constants and has symmetric K, positive S", "[fairing]") {
    const LaplacianOperator op = GENERATE(from_range(std::begin(kOperators), std::end(kOperators)));
    const bool sphere = GENERATE(true, false);
    INFO(laplacian_operator_name(op) << (sphere ? " on a noisy sphere" : " on a jittered grid"));
    const HalfedgeMesh m = sphere ? noisy_sphere() : jittered_grid();
    const Laplacian lap = build_laplacian(m, op);
    const auto n = Eigen::Index(lap.map.rows());
    REQUIRE(n == Eigen::Index(m.n_vertices()));
    const Eigen::VectorXd ones = Eigen::VectorXd::Ones(n);
    const double kscale =
        std::max(1.0, Eigen::Map<const Eigen::VectorXd>(lap.K.valuePtr(), lap.K.nonZeros())
                          .cwiseAbs()
                          .maxCoeff());
    CHECK(max_abs(lap.L * ones) < 1e-12);
    CHECK(max_abs(lap.K * ones) < 1e-12 * kscale);
    const SparseMatrix kt = lap.K.transpose();
    CHECK((lap.K - kt).norm() <= 1e-12 * kscale);
    // L = -S⁻¹ K on free rows, 0 on fixed rows; S > 0.
    for (Eigen::Index r = 0; r < n; ++r) REQUIRE(lap.S[r] > 0);
    const Eigen::MatrixXd x = gather_positions(m, lap.map);
    const Eigen::MatrixXd lx = lap.L * x, kx = lap.K * x;
    for (Eigen::Index r = 0; r < n; ++r) {
        if (lap.fixed[std::size_t(r)])
            REQUIRE(lx.row(r).norm() == 0.0);
        else
            REQUIRE((lx.row(r) + kx.row(r) / lap.S[r]).norm() <= 1e-9 * (1 + kx.row(r).norm()));
    }
    // PSD: xᵀ K x >= 0 for the coordinates (a cheap spot check of the sign convention).
    for (int c = 0; c < 3; ++c) CHECK(x.col(c).dot(lap.K * x.col(c)) >= -1e-9 * kscale);
    // Boundary rows are fixed by default.
    for (std::size_t r = 0; r < lap.map.rows(); ++r)
        if (m.is_boundary(lap.map.vertex_of[r])) REQUIRE(lap.fixed[r] == 1);
    CHECK(lap.diagnostics.degenerate_corners == 0);
}

TEST_CASE("cotangent and second-order Laplacians have linear precision on a flat grid",
          "[fairing]") {
    const HalfedgeMesh m = jittered_grid();
    LaplacianOptions keep_negative;
    keep_negative.clamp_negative_cotangents = false;
    auto linear_residual = [&](LaplacianOperator op, const LaplacianOptions& opt) {
        const Laplacian lap = build_laplacian(m, op, opt);
        Eigen::VectorXd f(Eigen::Index(lap.map.rows()));
        for (std::size_t r = 0; r < lap.map.rows(); ++r) {
            const Point& p = m.position(lap.map.vertex_of[r]);
            f[Eigen::Index(r)] = 2.0 * p.x() - 3.0 * p.y() + 0.5;
        }
        REQUIRE(lap.n_free() == 49);
        return max_abs(lap.L * f);
    };
    CHECK(linear_residual(LaplacianOperator::CurvatureFlow, keep_negative) < 1e-10);
    CHECK(linear_residual(LaplacianOperator::SecondOrder, {}) < 1e-10);
    // The umbrella operators depend on the parametrization: not linear-precise here.
    CHECK(linear_residual(LaplacianOperator::Umbrella, {}) > 1e-3);
    CHECK(linear_residual(LaplacianOperator::ImprovedUmbrella, {}) > 1e-3);
    // And on the unperturbed grid the cotangent weights need no clamping at all.
    const Laplacian regular = build_laplacian(make_grid(8), LaplacianOperator::CurvatureFlow);
    CHECK(regular.diagnostics.negative_weights_clamped == 0);
}

TEST_CASE("smoothing a noisy sphere lowers the variance of mean curvature", "[fairing]") {
    const HalfedgeMesh m = noisy_sphere();
    const double before = variance_of_mean_curvature(m);
    const auto op = GENERATE(FairingOperator::Umbrella, FairingOperator::ImprovedUmbrella,
                             FairingOperator::CurvatureFlow, FairingOperator::SecondOrder,
                             FairingOperator::Taubin);
    const auto integration = GENERATE(Integration::Explicit, Integration::Implicit);
    if (op == FairingOperator::Taubin && integration == Integration::Implicit) return;
    INFO(fairing_operator_name(op) << " " << integration_name(integration));
    FairingOptions o;
    o.op = op;
    o.integration = integration;
    o.iterations = 5;
    if (op != FairingOperator::Taubin) {
        const auto lop = static_cast<LaplacianOperator>(static_cast<int>(op));
        o.step = integration == Integration::Explicit         ? steps_for_explicit(lop)
                 : lop == LaplacianOperator::ImprovedUmbrella ? 0.01
                                                              : 1.0;
    }
    const FairingResult r = smooth(m, o);
    require_sane(r, 5);
    CHECK_FALSE(r.diverged);
    const double after = variance_of_mean_curvature(r.steps.back());
    INFO("variance before " << before << " after " << after);
    CHECK(after < 0.5 * before);
    if (integration == Integration::Implicit) {
        CHECK((r.solver == "SimplicialLDLT" || r.solver == "ConjugateGradient(Jacobi)"));
        CHECK(r.max_residual < 1e-8);
    }
}

TEST_CASE("explicit umbrella with step 20 blows up, implicit stays bounded", "[fairing]") {
    const HalfedgeMesh m = noisy_sphere();
    const double d0 = bounding_box(m).diagonal();
    FairingOptions o;
    o.step = 20;
    o.iterations = 3;
    const FairingResult ex = smooth(m, o);
    require_sane(ex, 3);
    CHECK(bounding_box(ex.steps.back()).diagonal() > 10 * d0);
    o.integration = Integration::Implicit;
    o.solver = ImplicitSolver::Direct;
    const FairingResult im = smooth(m, o);
    o.solver = ImplicitSolver::Auto;
    require_sane(im, 3);
    CHECK(bounding_box(im.steps.back()).diagonal() <= d0 * (1 + 1e-9));
    CHECK(variance_of_mean_curvature(im.steps.front()) < variance_of_mean_curvature(m));
    CHECK(im.factorizations == 1);  // umbrella weights are fixed: one factorization reused

    // Many explicit iterations stop before overflowing instead of producing NaN.
    o.integration = Integration::Explicit;
    o.iterations = 200;
    const FairingResult far = smooth(m, o);
    CHECK(far.diverged);
    CHECK(far.steps.size() < 200);
    for (const auto& s : far.steps) require_finite(s);
}

TEST_CASE("volume preservation keeps the volume of a closed mesh", "[fairing]") {
    const HalfedgeMesh m = noisy_sphere();
    const double v0 = volume(m);
    const auto op = GENERATE(FairingOperator::Umbrella, FairingOperator::ImprovedUmbrella,
                             FairingOperator::CurvatureFlow, FairingOperator::SecondOrder);
    INFO(fairing_operator_name(op));
    FairingOptions o;
    o.op = op;
    o.integration = Integration::Implicit;
    o.step = op == FairingOperator::ImprovedUmbrella ? 0.01 : 1.0;
    o.iterations = 4;
    const FairingResult shrunk = smooth(m, o);
    require_sane(shrunk, 4);
    CHECK(volume(shrunk.steps.back()) < (1 - 1e-4) * v0);
    o.preserve_volume = true;
    const FairingResult kept = smooth(m, o);
    require_sane(kept, 4);
    for (const auto& s : kept.steps) CHECK(std::abs(volume(s) - v0) <= 1e-6 * v0);
    CHECK(kept.initial_volume == Approx(v0));
}

TEST_CASE("preserve_volume is refused on meshes with boundary", "[fairing]") {
    FairingOptions o;
    o.preserve_volume = true;
    CHECK_THROWS_WITH(smooth(make_grid(4), o), Catch::Contains("preserve_volume"));
    CHECK_THROWS_AS(smooth(make_grid(4), o), InvalidArgument);
}

TEST_CASE("an implicit step with a tiny step size agrees with the explicit one to first order",
          "[fairing]") {
    const HalfedgeMesh m = noisy_sphere();
    const LaplacianOperator op = GENERATE(from_range(std::begin(kOperators), std::end(kOperators)));
    INFO(laplacian_operator_name(op));
    auto discrepancy = [&](double dt) {
        FairingOptions o;
        o.op = static_cast<FairingOperator>(static_cast<int>(op));
        o.step = dt;
        const FairingResult ex = smooth(m, o);
        o.integration = Integration::Implicit;
        const FairingResult im = smooth(m, o);
        double diff = 0, moved = 0;
        for (Vertex v : m.vertices()) {
            diff = std::max(diff, (ex.steps[0].position(v) - im.steps[0].position(v)).norm());
            moved = std::max(moved, (ex.steps[0].position(v) - m.position(v)).norm());
        }
        REQUIRE(moved > 0);
        return diff / moved;
    };
    // Steps well inside the explicit stability range (the improved umbrella scales as 1/h²).
    const double dt = op == LaplacianOperator::ImprovedUmbrella ? 1e-5 : 1e-3;
    const double r1 = discrepancy(dt), r2 = discrepancy(0.1 * dt);
    INFO("relative discrepancy " << r1 << " at " << dt << ", " << r2 << " at " << 0.1 * dt);
    CHECK(r1 < 1e-2);
    CHECK(r2 < 0.2 * r1);  // the discrepancy is O(dt²): it shrinks with the step
}

TEST_CASE("boundary and isolated vertices stay fixed; degenerate input gives no NaN", "[fairing]") {
    // A noisy grid, plus an isolated vertex and a zero-area (collinear) triangle.
    PolygonSoup soup = to_soup(make_grid(6));
    const Index n0 = Index(soup.positions.size());
    soup.positions.push_back(Point(5, 5, 5));  // isolated
    soup.positions.push_back(Point(2, 0, 0));
    soup.positions.push_back(Point(3, 0, 0));
    soup.positions.push_back(Point(4, 0, 0));  // collinear with the two before
    soup.positions.push_back(Point(3, 0, 0));  // coincides with n0 + 2 (zero-length edges)
    soup.add_face({n0 + 1, n0 + 2, n0 + 3});
    soup.add_face({n0 + 2, n0 + 4, n0 + 3});
    LoadReport report;
    HalfedgeMesh m = build_mesh(soup, report);
    REQUIRE_VALID(m);
    NoiseOptions noise;
    noise.amount_percent = 20;
    add_noise(m, noise);
    const HalfedgeMesh input = m;

    const auto op = GENERATE(FairingOperator::Umbrella, FairingOperator::ImprovedUmbrella,
                             FairingOperator::CurvatureFlow, FairingOperator::SecondOrder,
                             FairingOperator::Taubin);
    const auto integration = GENERATE(Integration::Explicit, Integration::Implicit);
    if (op == FairingOperator::Taubin && integration == Integration::Implicit) return;
    INFO(fairing_operator_name(op) << " " << integration_name(integration));
    FairingOptions o;
    o.op = op;
    o.integration = integration;
    o.step = op == FairingOperator::ImprovedUmbrella ? 1e-3 : 0.3;
    o.iterations = 3;
    const FairingResult r = smooth(m, o);
    require_sane(r, 3);
    for (Vertex v : m.vertices()) REQUIRE(m.position(v) == input.position(v));  // input intact
    bool moved = false;
    for (Vertex v : m.vertices()) {
        const Point& p = r.steps.back().position(v);
        if (m.is_boundary(v))
            REQUIRE(p == m.position(v));  // boundary and isolated vertices do not move
        else if (p != m.position(v))
            moved = true;
    }
    CHECK(moved);
    // The degenerate triangles were noticed and reported, not silently turned into NaN.
    if (op == FairingOperator::CurvatureFlow || op == FairingOperator::SecondOrder)
        CHECK(r.diagnostics.degenerate_corners > 0);
    if (op == FairingOperator::ImprovedUmbrella) CHECK(r.diagnostics.short_edges > 0);
    if (r.diagnostics.total() > 0)
        CHECK(std::any_of(r.report.begin(), r.report.end(),
                          [](const std::string& l) { return l.rfind("clamped:", 0) == 0; }));
}

TEST_CASE("smooth rejects bad options naming them and reports its solver", "[fairing]") {
    const HalfedgeMesh m = make_icosphere(4);
    FairingOptions o;
    o.step = -1;
    CHECK_THROWS_WITH(smooth(m, o), Catch::Contains("step"));
    o.step = std::numeric_limits<double>::quiet_NaN();
    CHECK_THROWS_AS(smooth(m, o), InvalidArgument);
    o.step = 1;
    o.iterations = 0;
    CHECK_THROWS_WITH(smooth(m, o), Catch::Contains("iterations"));
    o.iterations = kMaxFairingIterations + 1;
    CHECK_THROWS_WITH(smooth(m, o), Catch::Contains("iterations"));
    o.iterations = 1;
    o.op = FairingOperator::Taubin;
    o.taubin_mu = -0.4;
    CHECK_THROWS_WITH(smooth(m, o), Catch::Contains("taubin_mu"));
    o.taubin_mu = -0.53;
    o.integration = Integration::Implicit;
    CHECK_THROWS_WITH(smooth(m, o), Catch::Contains("integration"));
    CHECK(parse_fairing_operator("second-order") == FairingOperator::SecondOrder);
    CHECK_THROWS_AS(parse_fairing_operator("gauss"), InvalidArgument);

    FairingOptions cg;
    cg.op = FairingOperator::CurvatureFlow;
    cg.integration = Integration::Implicit;
    cg.solver = ImplicitSolver::Iterative;
    cg.iterations = 2;
    const FairingResult r = smooth(noisy_sphere(), cg);
    require_sane(r, 2);
    CHECK(r.solver == "ConjugateGradient(Jacobi)");
    CHECK(r.max_residual < 1e-8);
    CHECK(r.factorizations == 0);
    CHECK(r.report.size() >= 3);
}

TEST_CASE("on the bunny, explicit umbrella with step 20 blows up and implicit stays smooth",
          "[fairing][shared]") {
    const std::string path = test::shared_mesh("stanford-bunny.obj");
    SKIP_IF_MISSING(path);
    const HalfedgeMesh bunny = read_mesh(path).mesh;
    const double d0 = bounding_box(bunny).diagonal();
    FairingOptions o;
    o.step = 20;
    o.iterations = 5;
    o.keep_steps = false;
    const FairingResult ex = smooth(bunny, o);
    REQUIRE(ex.steps.size() == 1);
    require_finite(ex.steps.back());
    INFO("explicit diagonal " << bounding_box(ex.steps.back()).diagonal() << " vs " << d0);
    CHECK((ex.diverged || bounding_box(ex.steps.back()).diagonal() > 100 * d0));
    o.integration = Integration::Implicit;
    const FairingResult im = smooth(bunny, o);
    REQUIRE_VALID(im.steps.back());
    require_finite(im.steps.back());
    CHECK_FALSE(im.diverged);
    CHECK(bounding_box(im.steps.back()).diagonal() <= d0 * (1 + 1e-9));
    // Roughness: the mean umbrella vector relative to the mean edge length (scale-free).
    auto roughness = [](const HalfedgeMesh& mesh) {
        const Laplacian lap = build_laplacian(mesh, LaplacianOperator::Umbrella);
        const Eigen::MatrixXd lx = lap.L * gather_positions(mesh, lap.map);
        return lx.rowwise().norm().mean() / mean_edge_length(mesh);
    };
    INFO("roughness before " << roughness(bunny) << " after " << roughness(im.steps.back()));
    CHECK(roughness(im.steps.back()) < 0.5 * roughness(bunny));
}

TEST_CASE("the direct, iterative and automatic implicit solvers agree", "[fairing]") {
    const HalfedgeMesh m = noisy_sphere();
    const auto op = GENERATE(FairingOperator::Umbrella, FairingOperator::ImprovedUmbrella,
                             FairingOperator::CurvatureFlow, FairingOperator::SecondOrder);
    INFO(fairing_operator_name(op));
    FairingOptions o;
    o.op = op;
    o.integration = Integration::Implicit;
    o.step = op == FairingOperator::ImprovedUmbrella ? 0.01 : 1.0;
    o.iterations = 2;
    std::vector<FairingResult> r;
    for (ImplicitSolver solver :
         {ImplicitSolver::Direct, ImplicitSolver::Iterative, ImplicitSolver::Auto}) {
        o.solver = solver;
        r.push_back(smooth(m, o));
        require_sane(r.back(), 2);
        CHECK(r.back().max_residual < 1e-8);
    }
    CHECK(r[0].solver == "SimplicialLDLT");
    CHECK(r[1].solver == "ConjugateGradient(Jacobi)");
    CHECK(r[1].cg_iterations > 0);
    const double scale = bounding_box(m).diagonal();
    for (int k : {1, 2}) {
        double worst = 0;
        for (Vertex v : m.vertices())
            worst = std::max(
                worst, (r[std::size_t(k)].steps.back().position(v) - r[0].steps.back().position(v))
                           .norm());
        CHECK(worst < 1e-7 * scale);
    }
}

/// An irregular triangulation of the plane: a jittered equilateral lattice (all angles
/// acute, so no cotangent weight is clamped), n x n vertices, edge length 1.
HalfedgeMesh jittered_lattice(int n) {
    PolygonSoup soup;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const bool inner = i > 0 && j > 0 && i < n - 1 && j < n - 1;
            const double jx = inner ? 0.08 * std::sin(12.9898 * i + 78.233 * j) : 0.0;
            const double jy = inner ? 0.08 * std::cos(39.3468 * i + 11.135 * j) : 0.0;
            soup.positions.emplace_back(i + 0.5 * (j % 2) + jx, j * std::sqrt(0.75) + jy, 0.0);
        }
    auto add = [&](int a, int b, int c) {
        soup.corners.insert(soup.corners.end(), {Index(a), Index(b), Index(c)});
        soup.face_offsets.push_back(soup.corners.size());
    };
    for (int j = 0; j + 1 < n; ++j)
        for (int i = 0; i + 1 < n; ++i) {
            const int v = j * n + i;
            if (j % 2 == 0) {
                add(v, v + 1, v + n);
                add(v + 1, v + n + 1, v + n);
            } else {
                add(v, v + n + 1, v + n);
                add(v, v + 1, v + n + 1);
            }
        }
    LoadReport report;
    return build_mesh(soup, report);
}

TEST_CASE("curvature flow and second order drift less tangentially than umbrella", "[fairing]") {
    // An irregular flat triangulation with noise only along the normal (z): the ideal
    // smoother moves vertices back along z only. Umbrella also pulls each vertex towards
    // its neighbours' centroid, which on an irregular lattice is a tangential (x, y) move.
    HalfedgeMesh m = jittered_lattice(16);
    REQUIRE_VALID(m);
    unsigned k = 0;
    for (Vertex v : m.vertices())
        if (!m.is_boundary(v)) m.position(v).z() += 0.01 * std::sin(7.3 * ++k);
    auto drift = [&](FairingOperator op) {
        FairingOptions o;
        o.op = op;
        o.step = 0.2;
        const FairingResult r = smooth(m, o);
        require_sane(r, 1);
        double tangential = 0, normal = 0;
        for (Vertex v : m.vertices()) {
            const Vector3 d = r.steps.back().position(v) - m.position(v);
            tangential += std::hypot(d.x(), d.y());
            normal += std::abs(d.z());
        }
        REQUIRE(normal > 0);
        return tangential / normal;
    };
    const double umbrella = drift(FairingOperator::Umbrella);
    const double cotangent = drift(FairingOperator::CurvatureFlow);
    const double second = drift(FairingOperator::SecondOrder);
    INFO("tangential / normal displacement: umbrella " << umbrella << ", curvature flow "
                                                       << cotangent << ", second order " << second);
    CHECK(cotangent < 0.1);
    CHECK(second < 0.1);
    CHECK(umbrella > 3 * std::max(cotangent, second));
}

TEST_CASE("boundary vertices can slide along the boundary curve", "[fairing]") {
    // A flat square grid whose boundary vertices are spaced unevenly along the sides.
    HalfedgeMesh m = make_grid(8);
    const BoundingBox box = bounding_box(m);
    const double lo = box.min.x(), hi = box.max.x();
    auto on_square = [&](const Point& p) {
        const double dx = std::min(std::abs(p.x() - lo), std::abs(p.x() - hi));
        const double dy = std::min(std::abs(p.y() - lo), std::abs(p.y() - hi));
        const bool inside = p.x() >= lo - 1e-12 && p.x() <= hi + 1e-12 && p.y() >= lo - 1e-12 &&
                            p.y() <= hi + 1e-12;
        return inside && std::min(dx, dy) < 1e-12 && std::abs(p.z()) < 1e-12;
    };
    const double h = (hi - lo) / 8;
    for (Vertex v : m.vertices()) {
        Point& p = m.position(v);
        if (!m.is_boundary(v)) continue;
        const bool corner = (std::abs(p.x() - lo) < 1e-12 || std::abs(p.x() - hi) < 1e-12) &&
                            (std::abs(p.y() - lo) < 1e-12 || std::abs(p.y() - hi) < 1e-12);
        if (corner) continue;
        const double shift = 0.3 * h * std::sin(5.0 * (p.x() + 2 * p.y()));
        if (std::abs(p.y() - lo) < 1e-12 || std::abs(p.y() - hi) < 1e-12)
            p.x() += shift;
        else
            p.y() += shift;
    }
    REQUIRE_VALID(m);
    auto spacing_spread = [&](const HalfedgeMesh& mesh) {
        double mn = 1e300, mx = 0;
        for (Halfedge hh : mesh.halfedges()) {
            if (!mesh.is_boundary(hh)) continue;
            const double len =
                (mesh.position(mesh.to_vertex(hh)) - mesh.position(mesh.from_vertex(hh))).norm();
            mn = std::min(mn, len);
            mx = std::max(mx, len);
        }
        return mx / mn;
    };
    const auto integration = GENERATE(Integration::Explicit, Integration::Implicit);
    INFO(integration_name(integration));
    FairingOptions o;
    o.integration = integration;
    o.iterations = 20;
    const FairingResult fixed = smooth(m, o);
    require_sane(fixed, 20);
    for (Vertex v : m.vertices())
        if (m.is_boundary(v)) CHECK(fixed.steps.back().position(v) == m.position(v));

    o.boundary = BoundaryMode::Slide;
    const FairingResult slid = smooth(m, o);
    require_sane(slid, 20);
    double moved = 0;
    for (Vertex v : m.vertices()) {
        if (!m.is_boundary(v)) continue;
        INFO("vertex " << v.idx());
        CHECK(on_square(slid.steps.back().position(v)));
        moved = std::max(moved, (slid.steps.back().position(v) - m.position(v)).norm());
    }
    CHECK(moved > 0.05 * h);
    INFO("boundary spacing max/min before " << spacing_spread(m) << " after "
                                            << spacing_spread(slid.steps.back()));
    CHECK(spacing_spread(slid.steps.back()) < spacing_spread(m));
    CHECK(parse_boundary_mode("slide") == BoundaryMode::Slide);
    CHECK_THROWS_AS(parse_boundary_mode("free"), InvalidArgument);
}
