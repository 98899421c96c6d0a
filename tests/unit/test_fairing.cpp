// Fairing: the four discrete Laplacians (sign convention, constants, linear precision,
// symmetric forms) and smooth() (noise reduction, stability, volume, first-order agreement of
// implicit and explicit steps, boundaries, degenerate input, option checks), the reference's
// figures 1.4, 1.10 and 1.12, scale invariance, health checks (divergence, failed solves, no
// false alarms), the stable-step estimate, Taubin's parameters and positions-only steps.
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <Eigen/Eigenvalues>

#include "core/algorithms/curvature.h"
#include "core/algorithms/fairing.h"
#include "core/algorithms/generators.h"
#include "core/algorithms/laplacian.h"
#include "core/algorithms/noise.h"
#include "core/errors.h"
#include "core/geometry.h"
#include "core/io/mesh_io.h"
#include "core/mesh_builder.h"
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

/// The mesh of step k (0-based) of a run with keep_steps.
HalfedgeMesh step_mesh(const FairingResult& r, std::size_t k) {
    HalfedgeMesh m = r.mesh;
    m.positions() = r.step_positions.at(k);
    return m;
}

/// A run that did not stop, with `expected_steps` good iterations, valid and finite meshes.
void require_sane(const FairingResult& r, std::size_t expected_steps) {
    INFO("stop reason: " << r.stop_reason);
    REQUIRE_FALSE(r.stopped_early);
    REQUIRE(r.stop_reason.empty());
    REQUIRE(r.stopped_at_iteration == 0);
    REQUIRE(std::size_t(r.iterations_done) == expected_steps);
    REQUIRE(r.step_positions.size() == expected_steps);
    REQUIRE(r.step_positions.back() == r.mesh.positions());
    REQUIRE_VALID(r.mesh);
    require_finite(r.mesh);
    for (std::size_t k = 0; k + 1 < r.step_positions.size(); ++k) {
        const HalfedgeMesh s = step_mesh(r, k);
        REQUIRE_VALID(s);
        require_finite(s);
    }
}

double max_abs(const Eigen::MatrixXd& x) {
    return x.size() ? x.cwiseAbs().maxCoeff() : 0.0;
}

double steps_for_explicit(LaplacianOperator op) {
    return op == LaplacianOperator::ImprovedUmbrella ? 0.3 : 0.5;
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
        o.step = integration == Integration::Explicit ? steps_for_explicit(lop) : 1.0;
    }
    const FairingResult r = smooth(m, o);
    require_sane(r, 5);
    const double after = variance_of_mean_curvature(r.mesh);
    INFO("variance before " << before << " after " << after);
    CHECK(after < 0.5 * before);
    if (integration == Integration::Implicit) {
        CHECK((r.solver == "SimplicialLDLT" || r.solver == "ConjugateGradient(Jacobi)"));
        CHECK(r.max_residual < 1e-8);
    }
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
    o.step = 1.0;
    o.iterations = 4;
    const FairingResult shrunk = smooth(m, o);
    require_sane(shrunk, 4);
    CHECK(volume(shrunk.mesh) < (1 - 1e-4) * v0);
    CHECK(shrunk.final_volume == Approx(volume(shrunk.mesh)));
    o.preserve_volume = true;
    const FairingResult kept = smooth(m, o);
    require_sane(kept, 4);
    for (std::size_t k = 0; k < kept.step_positions.size(); ++k)
        CHECK(std::abs(volume(step_mesh(kept, k)) - v0) <= 1e-6 * v0);
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
            diff = std::max(diff, (ex.mesh.position(v) - im.mesh.position(v)).norm());
            moved = std::max(moved, (ex.mesh.position(v) - m.position(v)).norm());
        }
        REQUIRE(moved > 0);
        return diff / moved;
    };
    // Steps well inside the explicit stability range.
    const double dt = 1e-3;
    const double r1 = discrepancy(dt), r2 = discrepancy(0.1 * dt);
    INFO("relative discrepancy " << r1 << " at " << dt << ", " << r2 << " at " << 0.1 * dt);
    CHECK(r1 < 1e-2);
    CHECK(r2 < 0.2 * r1);  // the discrepancy is O(dt²): it shrinks with the step
}

TEST_CASE("boundary and isolated vertices stay fixed, degenerate input gives no NaN", "[fairing]") {
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
    o.step = 0.3;
    o.iterations = 3;
    const FairingResult r = smooth(m, o);
    require_sane(r, 3);
    for (Vertex v : m.vertices()) REQUIRE(m.position(v) == input.position(v));  // input intact
    bool moved = false;
    for (Vertex v : m.vertices()) {
        const Point& p = r.mesh.position(v);
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
    o.taubin_lambda = 0;
    CHECK_THROWS_WITH(smooth(m, o), Catch::Contains("taubin_lambda"));
    o.taubin_lambda = 0.5;
    o.taubin_pass_band = -0.1;
    CHECK_THROWS_WITH(smooth(m, o), Catch::Contains("taubin_pass_band"));
    o.taubin_pass_band = 3;  // above 1/lambda: mu would be positive
    CHECK_THROWS_WITH(smooth(m, o), Catch::Contains("taubin_pass_band"));
    o.taubin_pass_band = 1.5;  // mu = 1/(1.5 - 2) = -2, below -1
    CHECK_THROWS_WITH(smooth(m, o), Catch::Contains("taubin_pass_band"));
    o.taubin_pass_band = 0;
    o.integration = Integration::Implicit;
    CHECK_THROWS_WITH(smooth(m, o), Catch::Contains("integration"));
    o = FairingOptions{};
    o.max_relative_residual = 0;
    CHECK_THROWS_WITH(smooth(m, o), Catch::Contains("max_relative_residual"));
    o.max_relative_residual = 1e-8;
    o.cg_max_iterations = -1;
    CHECK_THROWS_WITH(smooth(m, o), Catch::Contains("cg_max_iterations"));
    CHECK_THROWS_AS(max_stable_explicit_step(m, FairingOperator::Umbrella, 0), InvalidArgument);
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

TEST_CASE("the direct, iterative and automatic implicit solvers agree", "[fairing]") {
    const HalfedgeMesh m = noisy_sphere();
    const auto op = GENERATE(FairingOperator::Umbrella, FairingOperator::ImprovedUmbrella,
                             FairingOperator::CurvatureFlow, FairingOperator::SecondOrder);
    INFO(fairing_operator_name(op));
    FairingOptions o;
    o.op = op;
    o.integration = Integration::Implicit;
    o.step = 1.0;
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
            worst = std::max(worst,
                             (r[std::size_t(k)].mesh.position(v) - r[0].mesh.position(v)).norm());
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
            const Vector3 d = r.mesh.position(v) - m.position(v);
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
        if (m.is_boundary(v)) CHECK(fixed.mesh.position(v) == m.position(v));

    o.boundary = BoundaryMode::Slide;
    const FairingResult slid = smooth(m, o);
    require_sane(slid, 20);
    double moved = 0;
    for (Vertex v : m.vertices()) {
        if (!m.is_boundary(v)) continue;
        INFO("vertex " << v.idx());
        CHECK(on_square(slid.mesh.position(v)));
        moved = std::max(moved, (slid.mesh.position(v) - m.position(v)).norm());
    }
    CHECK(moved > 0.05 * h);
    INFO("boundary spacing max/min before " << spacing_spread(m) << " after "
                                            << spacing_spread(slid.mesh));
    CHECK(spacing_spread(slid.mesh) < spacing_spread(m));
    CHECK(parse_boundary_mode("slide") == BoundaryMode::Slide);
    CHECK_THROWS_AS(parse_boundary_mode("free"), InvalidArgument);
}

// ---- the reference's figures, health checks, stable steps ----------------------------------

namespace {

/// The reference's test object: a unit sphere (2,562 vertices) with noise along the normal
/// (a uniform offset of up to 20 % of the mean edge length, as `trilab-cli noise --amount
/// 20`).
HalfedgeMesh noisy_unit_sphere() {
    HalfedgeMesh m = make_icosphere(16);
    NoiseOptions noise;
    noise.amount_percent = 20;
    noise.seed = 3;
    add_noise(m, noise);
    return m;
}

/// The spread of the vertices' distances to their centroid relative to their mean.
double radial_spread(const HalfedgeMesh& m) {
    Point c = Point::Zero();
    double n = 0;
    for (Vertex v : m.vertices()) {
        c += m.position(v);
        n += 1;
    }
    c /= n;
    double sum = 0, sum2 = 0;
    for (Vertex v : m.vertices()) {
        const double r = (m.position(v) - c).norm();
        sum += r;
        sum2 += r * r;
    }
    const double mean = sum / n;
    return std::sqrt(std::max(0.0, sum2 / n - mean * mean)) / mean;
}

FairingOptions options(FairingOperator op, Integration integration, double step, int iterations) {
    FairingOptions o;
    o.op = op;
    o.integration = integration;
    o.step = step;
    o.iterations = iterations;
    return o;
}

/// A figure's settings smooth the noisy sphere: the radial spread falls by at least 40 % and
/// at least half the volume stays.
void require_smooths_the_sphere(const FairingOptions& o) {
    const HalfedgeMesh m = noisy_unit_sphere();
    REQUIRE(m.n_vertices() == 2562);
    const FairingResult r = smooth(m, o);
    require_sane(r, std::size_t(o.iterations));
    const double before = radial_spread(m), after = radial_spread(r.mesh);
    INFO("spread " << before << " -> " << after << ", volume " << volume(m) << " -> "
                   << volume(r.mesh));
    CHECK(after <= 0.6 * before);
    CHECK(volume(r.mesh) >= 0.5 * volume(m));
}

/// Every operator at its (1-based) options, for GENERATE-free loops.
const FairingOperator kAllOperators[] = {
    FairingOperator::Umbrella, FairingOperator::ImprovedUmbrella, FairingOperator::CurvatureFlow,
    FairingOperator::SecondOrder, FairingOperator::Taubin};

/// A noisy grid with a boundary (20 % noise along the normal).
HalfedgeMesh noisy_grid() {
    HalfedgeMesh m = make_grid(16);
    NoiseOptions noise;
    noise.amount_percent = 20;
    add_noise(m, noise);
    return m;
}

double max_position_difference(const HalfedgeMesh& a, const HalfedgeMesh& b, double scale_b) {
    double worst = 0;
    for (Vertex v : a.vertices())
        worst = std::max(worst, (a.position(v) - b.position(v) / scale_b).norm());
    return worst;
}

}  // namespace

TEST_CASE("figure 1.4: improved umbrella, implicit, step 1, one iteration smooths the sphere",
          "[fairing]") {
    require_smooths_the_sphere(
        options(FairingOperator::ImprovedUmbrella, Integration::Implicit, 1.0, 1));
}

TEST_CASE("figure 1.10: second order, explicit, step 1, 8 iterations smooths the sphere",
          "[fairing]") {
    const FairingOptions o = options(FairingOperator::SecondOrder, Integration::Explicit, 1.0, 8);
    require_smooths_the_sphere(o);
    // Many more iterations keep smoothing (no pattern of growing spikes).
    const HalfedgeMesh m = noisy_unit_sphere();
    FairingOptions many = o;
    many.iterations = 50;
    const FairingResult r = smooth(m, many);
    require_sane(r, 50);
    CHECK(radial_spread(r.mesh) < radial_spread(step_mesh(r, 7)));
    // The undamped relaxation (1.12) is beyond the stable limit: with S = diag(K) the
    // spectrum of S⁻¹K reaches about 2.3 here (a limit near 0.87); S = ½ |K| row sums keeps
    // it within Gershgorin's 2, so step 1 is stable.
    CHECK(max_stable_explicit_step(m, FairingOperator::SecondOrder) >= 1.0);
    const Laplacian lap = build_laplacian(m, LaplacianOperator::SecondOrder);
    for (Eigen::Index row = 0; row < Eigen::Index(lap.map.rows()); ++row)
        REQUIRE(lap.S[row] >= lap.K.coeff(row, row) * (1 - 1e-12));  // damped, never amplified
}

TEST_CASE("figure 1.12: explicit umbrella with step 20 stops at once, implicit stays bounded",
          "[fairing]") {
    auto check = [](const HalfedgeMesh& m, int iterations) {
        const double d0 = bounding_box(m).diagonal();
        FairingOptions o =
            options(FairingOperator::Umbrella, Integration::Explicit, 20, iterations);
        const FairingResult ex = smooth(m, o);
        INFO("stop reason: " << ex.stop_reason);
        CHECK(ex.stopped_early);
        CHECK(ex.stopped_at_iteration == 1);
        CHECK(ex.iterations_done == 0);
        CHECK(ex.step_positions.empty());
        CHECK(ex.stop_reason.rfind("iteration 1: ", 0) == 0);
        CHECK_THAT(ex.stop_reason, Catch::Contains("above the stable limit"));
        CHECK_THAT(ex.stop_reason, Catch::Contains("implicit"));
        CHECK(ex.mesh.positions() == m.positions());  // the last good state: the input
        REQUIRE_VALID(ex.mesh);
        CHECK(std::any_of(ex.report.begin(), ex.report.end(), [&](const std::string& l) {
            return l.find(ex.stop_reason) != std::string::npos;
        }));
        o.integration = Integration::Implicit;
        const FairingResult im = smooth(m, o);
        require_sane(im, std::size_t(iterations));
        CHECK(bounding_box(im.mesh).diagonal() <= d0 * (1 + 1e-9));
        // Roughness: the mean umbrella vector relative to the mean edge length (scale-free).
        auto roughness = [](const HalfedgeMesh& mesh) {
            const Laplacian lap = build_laplacian(mesh, LaplacianOperator::Umbrella);
            const Eigen::MatrixXd lx = lap.L * gather_positions(mesh, lap.map);
            return lx.rowwise().norm().mean() / mean_edge_length(mesh);
        };
        INFO("roughness before " << roughness(m) << " after " << roughness(im.mesh));
        CHECK(roughness(im.mesh) < 0.5 * roughness(m));
    };
    SECTION("noisy sphere, 200 iterations asked") {
        check(noisy_unit_sphere(), 200);
    }
    SECTION("the bunny, one iteration") {
        const std::string path = test::shared_mesh("stanford-bunny.obj");
        SKIP_IF_MISSING(path);
        check(read_mesh(path).mesh, 1);
    }
}

TEST_CASE("every operator and integration is scale-free", "[fairing]") {
    const bool closed = GENERATE(true, false);
    const HalfedgeMesh m = closed ? noisy_unit_sphere() : noisy_grid();
    HalfedgeMesh big = m;
    for (Point& p : big.positions()) p *= 1000.0;
    const double diag = bounding_box(m).diagonal();
    for (FairingOperator op : kAllOperators) {
        for (Integration integration : {Integration::Explicit, Integration::Implicit}) {
            if (op == FairingOperator::Taubin && integration == Integration::Implicit) continue;
            INFO(fairing_operator_name(op)
                 << " " << integration_name(integration) << (closed ? " sphere" : " grid"));
            FairingOptions o = options(op, integration,
                                       integration == Integration::Implicit      ? 2.0
                                       : op == FairingOperator::ImprovedUmbrella ? 0.3
                                                                                 : 0.8,
                                       3);
            const FairingResult small = smooth(m, o), large = smooth(big, o);
            require_sane(small, 3);
            require_sane(large, 3);
            const double moved = max_position_difference(small.mesh, m, 1.0);
            REQUIRE(moved > 1e-3 * diag);  // it did smooth
            CHECK(max_position_difference(small.mesh, large.mesh, 1000.0) <= 1e-9 * diag);
            CHECK(large.max_stable_step == Approx(small.max_stable_step).epsilon(1e-9));
        }
    }
}

TEST_CASE("a failed implicit solve is retried with the direct solver, then reported", "[fairing]") {
    const HalfedgeMesh m = noisy_unit_sphere();
    FairingOptions o = options(FairingOperator::CurvatureFlow, Integration::Implicit, 1.0, 2);
    o.solver = ImplicitSolver::Direct;
    const FairingResult direct = smooth(m, o);
    require_sane(direct, 2);
    CHECK(direct.solver == "SimplicialLDLT");

    // Conjugate gradients capped at one iteration cannot reach 1e-8: the sparse Cholesky
    // takes over, and says so.
    o.solver = ImplicitSolver::Iterative;
    o.cg_max_iterations = 1;
    const FairingResult retried = smooth(m, o);
    require_sane(retried, 2);
    CHECK(retried.solver == "SimplicialLDLT");
    CHECK(retried.max_residual < 1e-8);
    CHECK(std::count_if(retried.report.begin(), retried.report.end(), [](const std::string& l) {
              return l.find("retrying with SimplicialLDLT") != std::string::npos;
          }) == 2);
    CHECK(max_position_difference(retried.mesh, direct.mesh, 1.0) < 1e-12);

    // An accuracy neither solver can reach stops the run at iteration 1 with the input kept.
    o.max_relative_residual = 1e-30;
    for (ImplicitSolver solver : {ImplicitSolver::Iterative, ImplicitSolver::Direct}) {
        o.solver = solver;
        const FairingResult failed = smooth(m, o);
        INFO("stop reason: " << failed.stop_reason);
        CHECK(failed.stopped_early);
        CHECK(failed.stopped_at_iteration == 1);
        CHECK(failed.iterations_done == 0);
        CHECK(failed.step_positions.empty());
        CHECK(failed.stop_reason.rfind("iteration 1: the implicit solve failed", 0) == 0);
        CHECK_THAT(failed.stop_reason, Catch::Contains("SimplicialLDLT"));
        CHECK_THAT(failed.stop_reason, Catch::Contains("ConjugateGradient"));
        CHECK(failed.mesh.positions() == m.positions());
        REQUIRE_VALID(failed.mesh);
    }
}

TEST_CASE("the stable-step estimate matches the operator's spectrum", "[fairing]") {
    const bool closed = GENERATE(true, false);
    HalfedgeMesh m = closed ? make_icosphere(6) : make_grid(12);
    NoiseOptions noise;
    noise.amount_percent = 30;
    add_noise(m, noise);
    for (FairingOperator op : kAllOperators) {
        INFO(fairing_operator_name(op) << (closed ? " sphere" : " grid"));
        const LaplacianOperator lop = op == FairingOperator::Taubin
                                          ? LaplacianOperator::Umbrella
                                          : static_cast<LaplacianOperator>(static_cast<int>(op));
        const Laplacian lap = build_laplacian(m, lop);
        // The exact spectral radius of S⁻¹K over the free rows (dense, small mesh).
        std::vector<Eigen::Index> free_rows;
        for (std::size_t r = 0; r < lap.map.rows(); ++r)
            if (!lap.fixed[r]) free_rows.push_back(Eigen::Index(r));
        const auto nf = Eigen::Index(free_rows.size());
        const Eigen::MatrixXd k = Eigen::MatrixXd(lap.K);
        Eigen::MatrixXd a(nf, nf);
        for (Eigen::Index i = 0; i < nf; ++i)
            for (Eigen::Index j = 0; j < nf; ++j)
                a(i, j) =
                    k(free_rows[std::size_t(i)], free_rows[std::size_t(j)]) /
                    std::sqrt(lap.S[free_rows[std::size_t(i)]] * lap.S[free_rows[std::size_t(j)]]);
        const double rho =
            Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(a).eigenvalues().maxCoeff();
        const double estimate = max_stable_explicit_step(m, op);
        INFO("exact " << 2 / rho << ", estimate " << estimate);
        CHECK(estimate >= 2 / rho);           // Lanczos approaches rho from below
        CHECK(estimate <= 1.01 * (2 / rho));  // within 1 %
        const FairingResult r = smooth(m, options(op, Integration::Explicit, 0.1, 1));
        CHECK(r.max_stable_step == Approx(estimate).epsilon(1e-12));
    }
    FairingOptions quiet;
    quiet.estimate_max_stable_step = false;
    CHECK(std::isnan(smooth(m, quiet).max_stable_step));
}

TEST_CASE(
    "an explicit step above the stable limit stops at the last good iteration, below it "
    "does not",
    "[fairing]") {
    const HalfedgeMesh m = make_noisy_sphere(10, 0.02, 5);  // 1,002 vertices
    for (FairingOperator op : {FairingOperator::Umbrella, FairingOperator::ImprovedUmbrella,
                               FairingOperator::CurvatureFlow, FairingOperator::SecondOrder}) {
        INFO(fairing_operator_name(op));
        const double limit = max_stable_explicit_step(m, op);
        REQUIRE(std::isfinite(limit));
        const FairingResult below = smooth(m, options(op, Integration::Explicit, 0.9 * limit, 40));
        require_sane(below, 40);
        // The estimate is the linear limit at the input. The umbrella is linear; the other
        // operators change with the geometry, and an overshoot can lengthen the very edges that
        // set the limit (self-stabilizing), so the clear case for them is twice the limit.
        const bool linear_like =
            op == FairingOperator::Umbrella || op == FairingOperator::SecondOrder;
        const FairingResult above =
            smooth(m, options(op, Integration::Explicit, (linear_like ? 1.2 : 2.0) * limit, 40));
        INFO("stop reason: " << above.stop_reason);
        REQUIRE(above.stopped_early);
        const int k = above.stopped_at_iteration;
        CHECK(k >= 1);
        CHECK(above.iterations_done == k - 1);
        CHECK(above.step_positions.size() == std::size_t(k - 1));
        CHECK(above.stop_reason.rfind("iteration " + std::to_string(k) + ": ", 0) == 0);
        CHECK_THAT(above.stop_reason, Catch::Contains("stable limit"));
        REQUIRE_VALID(above.mesh);
        require_finite(above.mesh);
        if (k > 1) CHECK(above.mesh.positions() == above.step_positions.back());
        // The kept state is no larger than the input (nothing blew up yet).
        CHECK(bounding_box(above.mesh).diagonal() <= 1.1 * bounding_box(m).diagonal());
    }
}

TEST_CASE("normal smoothing never trips a health check", "[fairing]") {
    HalfedgeMesh torus = make_torus(24, 12, 1.0, 0.3);
    NoiseOptions noise;
    noise.amount_percent = 30;
    add_noise(torus, noise);
    const HalfedgeMesh meshes[] = {make_noisy_sphere(8, 0.03, 2), noisy_grid(), torus};
    for (const HalfedgeMesh& m : meshes) {
        const bool closed = is_closed(m);
        for (FairingOperator op : kAllOperators) {
            INFO(fairing_operator_name(op) << " on " << m.n_vertices() << " vertices");
            if (op == FairingOperator::Taubin) {
                FairingOptions o;
                o.op = op;
                o.iterations = 100;
                o.keep_steps = false;
                const FairingResult r = smooth(m, o);
                INFO(r.stop_reason);
                CHECK_FALSE(r.stopped_early);
                CHECK(r.iterations_done == 100);
                continue;
            }
            const double limit = max_stable_explicit_step(m, op);
            // Far below the limit for long, close to it for a few iterations (the limit of the
            // geometry-dependent operators moves as the mesh changes; the improved umbrella's
            // falls as it shortens short edges further, the reference's "numerical
            // instability"), and the documented everyday step.
            const bool iu = op == FairingOperator::ImprovedUmbrella;
            const std::pair<double, int> runs[] = {
                {0.3 * limit, iu ? 10 : 30}, {0.95 * limit, 5}, {iu ? 0.3 : 1.0, iu ? 5 : 30}};
            for (const auto& [step, iterations] : runs) {
                for (bool keep_volume : {false, true}) {
                    if (keep_volume && !closed) continue;
                    FairingOptions o = options(op, Integration::Explicit, step, iterations);
                    o.preserve_volume = keep_volume;
                    o.keep_steps = false;
                    const FairingResult r = smooth(m, o);
                    INFO("explicit step " << step << " (limit " << limit << "), " << iterations
                                          << " iterations, volume " << keep_volume << ": "
                                          << r.stop_reason);
                    CHECK_FALSE(r.stopped_early);
                    CHECK(r.iterations_done == iterations);
                }
            }
            for (double step : {1.0, 10.0, 100.0}) {
                FairingOptions o = options(op, Integration::Implicit, step, 3);
                o.keep_steps = false;
                o.preserve_volume = closed;
                const FairingResult r = smooth(m, o);
                INFO("implicit step " << step << ": " << r.stop_reason);
                CHECK_FALSE(r.stopped_early);
                CHECK(r.max_residual <= 1e-8);
            }
            if (!closed) {
                FairingOptions o = options(op, Integration::Explicit, 0.5 * limit, 20);
                o.boundary = BoundaryMode::Slide;
                const FairingResult r = smooth(m, o);
                INFO("sliding boundary: " << r.stop_reason);
                CHECK_FALSE(r.stopped_early);
            }
        }
    }
}

TEST_CASE("Taubin uses lambda and mu (or the pass band), never the step", "[fairing]") {
    const HalfedgeMesh m = noisy_unit_sphere();
    FairingOptions o;
    o.op = FairingOperator::Taubin;
    o.iterations = 10;
    o.step = 0.1;
    const FairingResult a = smooth(m, o);
    require_sane(a, 10);
    o.step = 5;
    const FairingResult b = smooth(m, o);
    CHECK(a.mesh.positions() == b.mesh.positions());
    // Taubin's smoothing without shrinking: the spread falls, the volume stays.
    CHECK(radial_spread(a.mesh) < 0.6 * radial_spread(m));
    CHECK(std::abs(volume(a.mesh) / volume(m) - 1) < 0.01);
    CHECK(std::abs(
              volume(smooth(m, options(FairingOperator::Umbrella, Integration::Explicit, 0.5, 10))
                         .mesh) /
                  volume(m) -
              1) > 0.02);
    // Other lambda and mu give another result.
    o.taubin_lambda = 0.6;
    o.taubin_mu = -0.65;
    const FairingResult c = smooth(m, o);
    require_sane(c, 10);
    CHECK(max_position_difference(a.mesh, c.mesh, 1.0) > 1e-4);
    // The pass band k_PB = 1/lambda + 1/mu gives mu.
    o.taubin_lambda = 0.5;
    o.taubin_mu = -0.6;  // ignored: the pass band wins
    o.taubin_pass_band = 0.1;
    const FairingResult d = smooth(m, o);
    o.taubin_pass_band = 0;
    o.taubin_mu = 1.0 / (0.1 - 2.0);
    const FairingResult e = smooth(m, o);
    require_sane(d, 10);
    CHECK(max_position_difference(d.mesh, e.mesh, 1.0) < 1e-12);
    // A pass band beyond 1 (mesh growth rather than smoothing) is refused, naming mu.
    o.taubin_lambda = 0.1;
    o.taubin_mu = -1.0;
    CHECK_THROWS_WITH(smooth(m, o), Catch::Contains("taubin_mu") && Catch::Contains("pass band"));
    // Steps beyond the umbrella's stable limit stop the run: on this sphere the umbrella's
    // spectrum ends near 1.5, where f(k) = (1 - λk)(1 - μk) = -1.05.
    o.taubin_lambda = 0.95;
    o.iterations = 200;
    const FairingResult unstable = smooth(m, o);
    INFO(unstable.stop_reason);
    CHECK(unstable.stopped_early);
    CHECK_THAT(unstable.stop_reason, Catch::Contains("lambda 0.95 and mu -1 are unstable"));
    REQUIRE_VALID(unstable.mesh);
}

TEST_CASE("steps are positions only, a moved-in mesh gives the same result", "[fairing]") {
    const HalfedgeMesh m = noisy_unit_sphere();
    FairingOptions o = options(FairingOperator::CurvatureFlow, Integration::Explicit, 0.5, 4);
    const FairingResult kept = smooth(m, o);
    require_sane(kept, 4);
    for (const auto& p : kept.step_positions) CHECK(p.size() == m.vertices_size());
    CHECK(kept.step_positions[0] != kept.step_positions[1]);
    o.keep_steps = false;
    const FairingResult lean = smooth(m, o);
    CHECK(lean.step_positions.empty());
    CHECK(lean.iterations_done == 4);
    CHECK(lean.mesh.positions() == kept.mesh.positions());
    HalfedgeMesh copy = m;
    NullProgress progress;
    const FairingResult moved = smooth(std::move(copy), o, progress);
    CHECK(moved.mesh.positions() == kept.mesh.positions());
    REQUIRE_VALID(moved.mesh);
}

TEST_CASE("a step that turns a coarse closed mesh inside out or flat is stopped", "[fairing]") {
    // Umbrella step 1 (within every stable limit) moves each corner of a tetrahedron to the
    // centroid of the other three: the reflection through the centroid scaled by 1/3. On an
    // octahedron it puts every vertex at the centre.
    const HalfedgeMesh shapes[] = {make_tetrahedron(), make_octahedron()};
    for (const HalfedgeMesh& m : shapes) {
        INFO(m.n_vertices() << " vertices");
        const FairingResult r =
            smooth(m, options(FairingOperator::Umbrella, Integration::Explicit, 1.0, 3));
        INFO(r.stop_reason);
        CHECK(r.stopped_early);
        CHECK(r.stopped_at_iteration == 1);
        CHECK_THAT(r.stop_reason, Catch::Contains("the volume changed sign"));
        CHECK(r.mesh.positions() == m.positions());
        // A gentle step is fine.
        require_sane(smooth(m, options(FairingOperator::Umbrella, Integration::Explicit, 0.2, 3)),
                     3);
    }
}
