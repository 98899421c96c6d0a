// The spectral lens (core/algorithms/transfer_function.h): the transfer curve against measured
// gains of real fairing runs, the spectral prediction against the run's result, the exact
// instability limit, the nonlinearity of curvature flow, Taubin's μ following λ, multiplets,
// and the change split by frequency.
#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "core/algorithms/coloring.h"
#include "core/algorithms/fairing.h"
#include "core/algorithms/generators.h"
#include "core/algorithms/proxy_mesh.h"
#include "core/algorithms/spectral.h"
#include "core/algorithms/transfer_function.h"
#include "core/errors.h"
#include "core/geometry.h"
#include "test_helpers.h"

using namespace trilab;

namespace {

SpectralDecomposition full_decomposition(const HalfedgeMesh& mesh, FairingOperator op) {
    SpectralOptions s;
    s.op = laplacian_of(op);
    s.method = SpectralMethod::Full;
    s.k = 0;
    return decompose(mesh, s);
}

/// Largest |measured - predicted| over the frequencies with a measured gain; counts them.
double max_gain_difference(const MeasuredGain& m, const std::vector<double>& predicted,
                           std::size_t& compared) {
    double diff = 0;
    compared = 0;
    for (std::size_t k = 0; k < predicted.size(); ++k) {
        if (std::isnan(m.gain[k])) continue;
        diff = std::max(diff, std::abs(m.gain[k] - predicted[k]));
        ++compared;
    }
    return diff;
}

/// Largest |a - b| over the vertices, relative to the largest |b| coordinate.
double relative_distance(const std::vector<Point>& a, const std::vector<Point>& b) {
    double diff = 0, scale = 1e-300;
    for (std::size_t i = 0; i < a.size(); ++i) {
        diff = std::max(diff, (a[i] - b[i]).cwiseAbs().maxCoeff());
        scale = std::max(scale, b[i].cwiseAbs().maxCoeff());
    }
    return diff / scale;
}

struct Setting {
    const char* name;
    FairingOptions options;
};

std::vector<Setting> linear_settings() {
    FairingOptions ex;
    ex.op = FairingOperator::Umbrella;
    ex.step = 0.7;
    ex.iterations = 5;
    FairingOptions im = ex;
    im.integration = Integration::Implicit;
    im.step = 20;
    im.iterations = 3;
    im.solver = ImplicitSolver::Direct;
    FairingOptions taubin;
    taubin.op = FairingOperator::Taubin;
    taubin.taubin_lambda = 0.6;
    taubin.taubin_mu = -0.65;
    taubin.iterations = 10;
    return {{"explicit umbrella", ex}, {"implicit umbrella", im}, {"taubin", taubin}};
}

}  // namespace

TEST_CASE("the transfer curve has the decomposition's sign convention", "[transfer_function]") {
    // L = -S⁻¹K and K e = λ S e: one explicit step moves an eigenvector to (1 - s·λ) times
    // itself, one implicit step to 1/(1 + s·λ) times.
    const HalfedgeMesh mesh = make_icosphere(2);
    const SpectralDecomposition d = full_decomposition(mesh, FairingOperator::Umbrella);
    const std::size_t k = d.size() - 1;  // the largest eigenvalue
    // smooth(X + ε·e_k) - smooth(X) = ε·g(λ_k)·e_k for the linear umbrella.
    HalfedgeMesh m = mesh;
    const double eps = 0.01;
    for (std::size_t r = 0; r < d.rows(); ++r)
        m.position(d.map.vertex_of[r]).x() +=
            eps * d.eigenvectors(Eigen::Index(r), Eigen::Index(k));
    FairingOptions o;
    o.step = 0.3;
    const FairingResult base = smooth(mesh, o), r = smooth(m, o);
    REQUIRE_FALSE(r.stopped_early);
    const double g = gain_per_iteration(o, d.eigenvalues[Eigen::Index(k)]);
    CHECK(g == Approx(1 - 0.3 * d.eigenvalues[Eigen::Index(k)]));
    for (std::size_t row = 0; row < d.rows(); ++row) {
        const Vertex v = d.map.vertex_of[row];
        CHECK(r.mesh.position(v).x() - base.mesh.position(v).x() ==
              Approx(g * eps * d.eigenvectors(Eigen::Index(row), Eigen::Index(k))).margin(1e-12));
    }
    o.integration = Integration::Implicit;
    CHECK(gain_per_iteration(o, 2.0) == Approx(1 / 1.6));
    CHECK(fairing_gain(o, 2.0) == Approx(1 / 1.6));
    o.iterations = 3;
    CHECK(fairing_gain(o, 2.0) == Approx(std::pow(1 / 1.6, 3)));
    FairingOptions t;
    t.op = FairingOperator::Taubin;
    t.taubin_lambda = 0.5;
    t.taubin_mu = -0.53;
    CHECK(gain_per_iteration(t, 1.0) == Approx((1 - 0.5) * (1 + 0.53)));
    CHECK(taubin_pass_band_of(t) == Approx(1 / 0.5 - 1 / 0.53));
    // g(k_PB) = 1 again: the pass band's edge.
    CHECK(gain_per_iteration(t, taubin_pass_band_of(t)) == Approx(1.0));
}

TEST_CASE("the measured gain equals the prediction for linear fairing on closed meshes",
          "[transfer_function]") {
    const HalfedgeMesh meshes[] = {make_icosphere(3), make_noisy_sphere(4, 0.05, 7),
                                   make_torus(12, 8, 1.0, 0.4)};
    for (const Setting& s : linear_settings()) {
        for (const HalfedgeMesh& mesh : meshes) {
            INFO(s.name << ", " << mesh.n_vertices() << " vertices");
            REQUIRE(is_closed(mesh));
            const SpectralDecomposition d = full_decomposition(mesh, s.options.op);
            REQUIRE(d.size() == d.rows());
            const FairingResult r = smooth(mesh, s.options);
            REQUIRE_FALSE(r.stopped_early);
            REQUIRE_VALID(r.mesh);
            const std::vector<double> predicted = fairing_gains(s.options, d.eigenvalues);
            const MeasuredGain m = measured_gain(d, mesh.positions(), r.mesh.positions());
            std::size_t compared = 0;
            CHECK(max_gain_difference(m, predicted, compared) < 1e-6);
            CHECK(compared + m.undefined == d.size());
            CHECK(compared > 0);
            for (std::size_t k = 0; k < d.size(); ++k)
                if (!std::isnan(m.mixing[k])) CHECK(m.mixing[k] < 1e-6);
            // The spectral prediction of the positions is the run's result.
            const std::vector<Point> p = predict_fairing(d, s.options, mesh.positions());
            CHECK(relative_distance(p, r.mesh.positions()) < 1e-6);
        }
    }
}

TEST_CASE("with a partial decomposition the computed frequencies' gains are still exact",
          "[transfer_function]") {
    const HalfedgeMesh mesh = make_noisy_sphere(10, 0.03, 5);  // 1,002 vertices
    SpectralOptions so;
    so.k = 60;
    const SpectralDecomposition d = decompose(mesh, so);
    for (const Setting& s : linear_settings()) {
        INFO(s.name);
        const FairingResult r = smooth(mesh, s.options);
        REQUIRE_FALSE(r.stopped_early);
        const MeasuredGain m = measured_gain(d, mesh.positions(), r.mesh.positions());
        std::size_t compared = 0;
        CHECK(max_gain_difference(m, fairing_gains(s.options, d.eigenvalues), compared) < 1e-6);
        CHECK(compared == d.size());  // the noise puts every frequency in the input
        // The prediction damps the uncomputed rest by the gain at the band's top: closer to the
        // result than the input is.
        // Where the curve falls (umbrella), the prediction damps the uncomputed rest by the
        // gain at the band's top, no less than the run did: closer to the result than the
        // input is. (Taubin's curve is not monotone: its rest is damped far more by the run.)
        // On the decomposed shape the stored coefficients stand in for the projection (the
        // fast path of the instant preview): the same prediction as projecting again.
        SpectralDecomposition unstored = d;
        unstored.coefficients.resize(0, 3);
        CHECK(relative_distance(predict_fairing(d, s.options, mesh.positions()),
                                predict_fairing(unstored, s.options, mesh.positions())) < 1e-12);
        if (s.options.op == FairingOperator::Taubin) continue;
        const std::vector<Point> p = predict_fairing(d, s.options, mesh.positions());
        CHECK(relative_distance(p, r.mesh.positions()) <
              0.5 * relative_distance(mesh.positions(), r.mesh.positions()));
    }
}

TEST_CASE("an input frequency of zero has no measured gain: NaN, counted", "[transfer_function]") {
    // The icosphere's coordinates are in a single symmetry class: many frequencies carry none.
    const HalfedgeMesh mesh = make_icosphere(2);
    const SpectralDecomposition d = full_decomposition(mesh, FairingOperator::Umbrella);
    const FairingResult r = smooth(mesh, FairingOptions{});
    const MeasuredGain m = measured_gain(d, mesh.positions(), r.mesh.positions());
    CHECK(m.undefined > d.size() / 2);
    CHECK(std::count_if(m.gain.begin(), m.gain.end(), [](double g) { return std::isnan(g); }) ==
          std::ptrdiff_t(m.undefined));
    CHECK_THROWS_WITH(measured_gain(d, make_icosphere(3).positions(), r.mesh.positions()),
                      Catch::Contains("measured_gain") && Catch::Contains("the input"));
}

TEST_CASE("the marked instability limit is where explicit runs start to diverge",
          "[transfer_function]") {
    const HalfedgeMesh mesh = make_noisy_sphere(6, 0.05, 2);  // 362 vertices
    const SpectralDecomposition d = full_decomposition(mesh, FairingOperator::Umbrella);
    const double lambda_max = d.eigenvalues[d.eigenvalues.size() - 1];
    FairingOptions o;
    // Long enough for the growing top frequency to show at 1.01, short of the shrinking to the
    // centroid that smoothing converges to (its volume's sign is then rounding).
    o.iterations = 200;
    o.keep_steps = false;
    const double limit = instability_limit(o, lambda_max);
    CHECK(limit == Approx(2 / lambda_max));
    o.step = limit;
    CHECK(gain_per_iteration(o, lambda_max) == Approx(-1.0));
    CHECK(unstable_eigenvalue(o) == Approx(lambda_max));
    // The fairing's own estimate (Lanczos, from below) agrees.
    CHECK(max_stable_explicit_step(mesh, FairingOperator::Umbrella, 60) ==
          Approx(limit).epsilon(1e-3));

    o.step = 0.99 * limit;
    const FairingResult stable = smooth(mesh, o);
    INFO(stable.stop_reason);
    CHECK_FALSE(stable.stopped_early);
    CHECK(stable.iterations_done == o.iterations);
    o.step = 1.01 * limit;
    const FairingResult unstable = smooth(mesh, o);
    REQUIRE(unstable.stopped_early);
    CHECK_THAT(unstable.stop_reason, Catch::Contains("stable limit"));
    REQUIRE_VALID(unstable.mesh);

    // Implicit steps have no limit; Taubin's λ limit holds the pass band.
    o.integration = Integration::Implicit;
    CHECK(std::isinf(instability_limit(o, lambda_max)));
    CHECK(std::isinf(unstable_eigenvalue(o)));
    FairingOptions t;
    t.op = FairingOperator::Taubin;
    t.taubin_pass_band = 0.1;
    const double a = instability_limit(t, 2.0);
    REQUIRE(std::isfinite(a));
    t.taubin_lambda = a;
    CHECK(taubin_pass_band_of(t) == Approx(0.1));
    CHECK(gain_per_iteration(t, 2.0) == Approx(-1.0));
    CHECK(unstable_eigenvalue(t) == Approx(2.0));
    CHECK(std::isinf(instability_limit(t, 1.0)));  // any λ keeping μ >= -1 is stable there
    CHECK_THROWS_AS(instability_limit(t, -1.0), InvalidArgument);
}

TEST_CASE("curvature flow's measured gain differs from its curve: the nonlinearity is reported",
          "[transfer_function]") {
    const HalfedgeMesh mesh = make_noisy_sphere(5, 0.08, 3);
    FairingOptions o;
    o.op = FairingOperator::CurvatureFlow;
    o.step = 0.5;
    o.iterations = 20;
    REQUIRE_FALSE(fairing_is_linear(o.op));
    const SpectralDecomposition d = full_decomposition(mesh, o.op);
    const FairingResult r = smooth(mesh, o);
    REQUIRE_FALSE(r.stopped_early);
    const MeasuredGain m = measured_gain(d, mesh.positions(), r.mesh.positions());
    std::size_t compared = 0;
    const double diff = max_gain_difference(m, fairing_gains(o, d.eigenvalues), compared);
    CHECK(std::isfinite(diff));
    CHECK(compared > 0);
    CHECK(diff > 1e-3);  // reported, not equal: the weights followed the positions
    double largest_mixing = 0;
    for (double x : m.mixing)
        if (!std::isnan(x)) largest_mixing = std::max(largest_mixing, x);
    CHECK(largest_mixing > 1e-3);
}

TEST_CASE("Taubin's mu follows lambda through the pass band when only lambda is given",
          "[transfer_function][fairing]") {
    FairingOptions o;
    o.op = FairingOperator::Taubin;
    CHECK(o.taubin_mu == 0);
    CHECK(taubin_mu_of(o) == Approx(-0.53));  // Taubin's suggestion, as before
    o.taubin_lambda = 0.3;
    CHECK(taubin_pass_band_of(o) == Approx(kDefaultTaubinPassBand));
    o.taubin_lambda = 0.9;  // μ would be -1.002: raised to -1
    CHECK(taubin_mu_of(o) == -1.0);
    const FairingResult r = smooth(make_noisy_sphere(5, 0.03, 1), o);
    CHECK_FALSE(r.stopped_early);
    CHECK_THAT(r.report.front(), Catch::Contains("following lambda through the pass band") &&
                                     Catch::Contains("raised to -1"));
    o.taubin_mu = -0.95;  // an explicit μ is used as given
    CHECK(taubin_mu_of(o) == -0.95);
    o.taubin_mu = 0;
    o.taubin_lambda = 1.0;  // no μ in [-1, -1) exists
    CHECK_THROWS_WITH(smooth(make_icosphere(2), o),
                      Catch::Contains("taubin_mu") && Catch::Contains("following lambda"));
}

TEST_CASE("band_splits_multiplet flags a band that cuts equal eigenvalues and suggests whole ones",
          "[transfer_function]") {
    Eigen::VectorXd ev(9);
    ev << 0, 1, 1, 1, 3, 3, 3, 3, 3;
    MultipletSplit s = band_splits_multiplet(ev, 0, 2);
    REQUIRE(s.splits);
    CHECK_FALSE(s.cut_at_lo);
    REQUIRE(s.cut_at_hi);
    CHECK(*s.cut_at_hi == MultipletSplit::Band{1, 3});
    CHECK(*s.narrower == MultipletSplit::Band{0, 0});
    CHECK(*s.wider == MultipletSplit::Band{0, 3});
    CHECK(multiplet_split_text(s, 0, 2) ==
          "band 0:2 splits the multiplet 1:3 (eigenvalues equal within 1 %): use 0:0 or 0:3");
    s = band_splits_multiplet(ev, 2, 5);
    CHECK(*s.cut_at_lo == MultipletSplit::Band{1, 3});
    CHECK(*s.cut_at_hi == MultipletSplit::Band{4, 8});
    CHECK_FALSE(s.narrower);  // nothing whole lies between 4 and 3
    CHECK(*s.wider == MultipletSplit::Band{1, 8});
    CHECK_FALSE(band_splits_multiplet(ev, 1, 3).splits);
    CHECK(band_splits_multiplet(ev, 4, 6).splits);
    CHECK_FALSE(band_splits_multiplet(ev, 4, 8).splits);  // the computed end cuts nothing
    CHECK(multiplet_split_text(band_splits_multiplet(ev, 1, 3), 1, 3).empty());
    CHECK_THROWS_AS(band_splits_multiplet(ev, 3, 9), InvalidArgument);
    CHECK_THROWS_AS(band_splits_multiplet(ev, 0, 2, 1.5), InvalidArgument);

    // The example: the noisy sphere's band 0:2 cuts its three-fold λ_1.
    SpectralOptions so;
    so.k = 20;
    const SpectralDecomposition d = decompose(make_default_model(), so);
    s = band_splits_multiplet(d.eigenvalues, 0, 2);
    REQUIRE(s.splits);
    CHECK(*s.cut_at_hi == MultipletSplit::Band{1, 3});
    CHECK(*s.wider == MultipletSplit::Band{0, 3});
    CHECK_FALSE(band_splits_multiplet(d.eigenvalues, 0, 3).splits);
    CHECK_FALSE(band_splits_multiplet(d.eigenvalues, 0, 8).splits);  // l <= 2: 1 + 3 + 5
}

TEST_CASE("change_by_frequency splits a displacement into the band below and the rest above",
          "[transfer_function]") {
    const HalfedgeMesh mesh = make_noisy_sphere(5, 0.05, 9);
    const SpectralDecomposition d = full_decomposition(mesh, FairingOperator::Umbrella);
    const std::size_t split = 9;  // l <= 2
    // Removing everything above the split: the change lies above it.
    const std::vector<Point> low = reconstruct_positions(d, 0, split - 1);
    ChangeByFrequency c = change_by_frequency(d, mesh.positions(), low, split);
    CHECK(c.below_norm < 1e-9 * c.above_norm);
    for (std::size_t v = 0; v < c.below.size(); ++v) {
        CHECK(c.below[v] < 1e-9);
        CHECK(c.above[v] == Approx((low[v] - mesh.positions()[v]).norm()).margin(1e-12));
    }
    // Removing the low band: the change lies below it.
    const std::vector<Point> high = reconstruct_positions(d, split, d.size() - 1);
    c = change_by_frequency(d, mesh.positions(), high, split);
    CHECK(c.above_norm < 1e-9 * c.below_norm);
    // Smoothing takes away more above than below.
    const FairingResult r = smooth(mesh, FairingOptions{});
    c = change_by_frequency(d, mesh.positions(), r.mesh.positions(), split);
    CHECK(c.above_norm > c.below_norm);
    CHECK_THROWS_WITH(change_by_frequency(d, mesh.positions(), low, d.size() + 1),
                      Catch::Contains("split"));
    // The two fields are colourings of their own.
    REQUIRE(parse_coloring("removed-below") == VertexColoring::RemovedBelow);
    REQUIRE(coloring_needs_field(VertexColoring::RemovedAbove));
    const VertexColors colors = color_field(mesh, c.above, VertexColoring::RemovedAbove);
    CHECK(colors.has_legend);
    CHECK(colors.kind == ColorMapKind::Sequential);
    CHECK_THAT(colors.label, Catch::Contains("above"));
}

TEST_CASE("the prediction is g_edge X + E diag(g - g_edge) alpha, on one thread or two",
          "[transfer_function]") {
    // 18,000 vertices and 60 frequencies: enough rows times frequencies for the second thread.
    const HalfedgeMesh mesh = make_noisy_sphere(60, 0.02, 3);
    SpectralOptions so;
    so.k = 60;
    const SpectralDecomposition d = decompose(mesh, so);
    REQUIRE(d.rows() * d.size() >= (std::size_t(1) << 20));
    FairingOptions o;
    o.integration = Integration::Implicit;
    o.step = 5;
    o.iterations = 2;
    // A shape other than the decomposed one (no stored coefficients) and the decomposed one.
    std::vector<Point> moved = mesh.positions();
    for (std::size_t v = 0; v < moved.size(); ++v) moved[v] *= 1.0 + 0.01 * double(v % 7);
    const std::vector<Point>& decomposed = mesh.positions();
    for (const std::vector<Point>* input : {&decomposed, &std::as_const(moved)}) {
        Eigen::MatrixXd x(Eigen::Index(d.rows()), 3);
        for (std::size_t r = 0; r < d.rows(); ++r)
            x.row(Eigen::Index(r)) = (*input)[d.map.vertex_of[r].idx()].transpose();
        const Eigen::MatrixXd alpha = d.eigenvectors.transpose() * (d.S.asDiagonal() * x);
        const std::vector<double> g = fairing_gains(o, d.eigenvalues);
        Eigen::VectorXd scale(Eigen::Index(g.size()));
        for (std::size_t k = 0; k < g.size(); ++k) scale[Eigen::Index(k)] = g[k] - g.back();
        const Eigen::MatrixXd expected =
            g.back() * x + d.eigenvectors * (scale.asDiagonal() * alpha);
        const std::vector<Point> p = predict_fairing(d, o, *input);
        REQUIRE(p.size() == input->size());
        double worst = 0, size = 0;
        for (std::size_t r = 0; r < d.rows(); ++r) {
            const Point e = expected.row(Eigen::Index(r)).transpose();
            worst = std::max(worst, (p[d.map.vertex_of[r].idx()] - e).norm());
            size = std::max(size, e.norm());
        }
        CHECK(worst <= 1e-12 * size);
        CHECK(relative_distance(p, *input) > 1e-4);  // it did smooth
    }
}

TEST_CASE("the clustered prediction is the clusters' mean of the prediction, within its bound",
          "[transfer_function][proxy_mesh]") {
    HalfedgeMesh mesh = make_noisy_sphere(20, 0.03, 11);
    mesh.add_vertex(Point(0.01, 0.02, 0.03));  // isolated: outside the eigenproblem
    SpectralOptions so;
    so.k = 40;
    const SpectralDecomposition d = decompose(mesh, so);
    REQUIRE(d.rows() + 1 == mesh.vertices_size());
    ProxyMeshOptions po;
    po.target_triangles = 300;
    po.keep_clusters = true;
    const ProxyMesh proxy = make_proxy_mesh(mesh, po);
    const std::size_t nc = proxy.positions.size();
    const ClusteredBasis b = cluster_basis(d, proxy.cluster_of, nc);
    REQUIRE(b.clusters() == nc);
    FairingOptions o;
    for (const double step : {0.5, 5.0, 50.0}) {
        o.integration = Integration::Implicit;
        o.step = step;
        INFO("implicit step " << step);
        const std::vector<Point> full = predict_fairing(d, o, d.base_positions);
        const std::vector<Point> means = test::cluster_means(mesh, full, proxy.cluster_of, nc);
        const ClusteredPrediction p = predict_clustered(b, d, o);
        REQUIRE(p.positions.size() == nc);
        double worst_mean = 0, farthest = 0;
        for (std::size_t c = 0; c < nc; ++c)
            worst_mean = std::max(worst_mean, (p.positions[c] - means[c]).norm());
        for (Vertex v : mesh.vertices())
            farthest =
                std::max(farthest, (full[v.idx()] - p.positions[proxy.cluster_of[v.idx()]]).norm());
        CHECK(worst_mean < 1e-12);
        CHECK(farthest <= p.bound);
        CHECK(p.bound < 4 * farthest + 1e-9);  // a bound that tells something
        // The moved stand-in of the full prediction: the same means, a measured bound.
        HalfedgeMesh predicted = mesh;
        predicted.set_positions(full);
        const ProxyMesh moved = moved_proxy_mesh(proxy, predicted);
        for (std::size_t c = 0; c < nc; ++c)
            CHECK((moved.positions[c] - p.positions[c]).norm() < 1e-12);
        CHECK(moved.error_bound == Approx(farthest).epsilon(1e-9));
    }
    CHECK_THROWS_WITH(cluster_basis(d, std::vector<Index>(3, 0), nc), Catch::Contains("3"));
    std::vector<Index> out_of_range = proxy.cluster_of;
    out_of_range[0] = Index(nc);
    CHECK_THROWS_WITH(cluster_basis(d, out_of_range, nc), Catch::Contains("vertex 0"));
    SpectralDecomposition unstored = d;
    unstored.coefficients.resize(0, 3);
    CHECK_THROWS_WITH(predict_clustered(b, unstored, o), Catch::Contains("coefficients"));
}
