// The rest of a frequency decomposition (core/algorithms/spectral.h, BandRest): the part of
// the geometry the computed frequencies do not carry. The whole computed band with the rest is
// the decomposed mesh (partial and full, smallest and largest end, boundaries, isolated
// vertices, the shared bunny); bands without it are the old sums bit for bit; the umbrella
// bands above the constant frequency centre the mesh; the spectrum operation's --with-rest.
#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "app/ops/operation.h"
#include "app/ops/operation_entries.h"
#include "core/algorithms/generators.h"
#include "core/algorithms/spectral.h"
#include "core/errors.h"
#include "core/geometry.h"
#include "core/io/mesh_io.h"
#include "core/mesh_builder.h"
#include "test_helpers.h"

using namespace trilab;

namespace {

struct Case {
    std::string name;
    HalfedgeMesh mesh;
    SpectralOptions options;
};

SpectralOptions options(LaplacianOperator op, std::size_t k, SpectrumEnd end,
                        SpectralMethod method = SpectralMethod::Partial) {
    SpectralOptions o;
    o.op = op;
    o.k = k;
    o.end = end;
    o.method = method;
    return o;
}

/// A grid with a bump, open: its boundary rows are fixed with fix_boundary.
HalfedgeMesh bumpy_grid() {
    HalfedgeMesh m = make_grid(12);
    for (Vertex v : m.vertices()) m.position(v).z() = 0.1 * std::sin(5.1 * v.idx());
    return m;
}

/// Two disjoint noisy spheres plus one isolated vertex (left out of the eigenproblem).
HalfedgeMesh two_spheres_and_a_point() {
    PolygonSoup soup;
    for (int copy = 0; copy < 2; ++copy) {
        const HalfedgeMesh s = make_noisy_sphere(4, 0.03, 3 + copy);
        const Index offset = Index(soup.positions.size());
        for (Vertex v : s.vertices())
            soup.positions.push_back(s.position(v) + Point(3.0 * copy, 0.5, 0));
        for (Face f : s.faces()) {
            for (Vertex v : s.face_vertices(f)) soup.corners.push_back(offset + v.idx());
            soup.face_offsets.push_back(soup.corners.size());
        }
    }
    soup.positions.push_back(Point(10, 10, 10));
    LoadReport report;
    return build_mesh(soup, report);
}

/// Partial and full decompositions of both ends, on closed, open and disconnected meshes.
std::vector<Case> cases() {
    using Op = LaplacianOperator;
    const SpectrumEnd small = SpectrumEnd::Smallest, large = SpectrumEnd::Largest;
    const SpectralMethod full = SpectralMethod::Full;
    const HalfedgeMesh sphere = make_noisy_sphere(5, 0.05, 9);  // 252 vertices
    std::vector<Case> c;
    c.push_back({"sphere, partial smallest", sphere, options(Op::CurvatureFlow, 20, small)});
    c.push_back({"sphere, partial largest", sphere, options(Op::Umbrella, 20, large)});
    c.push_back({"sphere, full, all", sphere, options(Op::Umbrella, 0, small, full)});
    c.push_back({"sphere, full, 30 smallest", sphere, options(Op::CurvatureFlow, 30, small, full)});
    c.push_back({"sphere, full, 30 largest", sphere, options(Op::SecondOrder, 30, large, full)});
    SpectralOptions fixed = options(Op::ImprovedUmbrella, 15, small);
    fixed.fix_boundary = true;
    c.push_back({"open grid, fixed boundary, partial smallest", bumpy_grid(), fixed});
    c.push_back({"open grid, free boundary, partial largest", bumpy_grid(),
                 options(Op::CurvatureFlow, 15, large)});
    c.push_back({"two spheres and a point, partial smallest", two_spheres_and_a_point(),
                 options(Op::Umbrella, 10, small)});
    return c;
}

/// max |p - q| over the vertices, relative to the bounding-box diagonal of `mesh`.
double relative_distance(const std::vector<Point>& p, const HalfedgeMesh& mesh) {
    double d = 0;
    for (Vertex v : mesh.vertices())
        d = std::max(d, (p[v.idx()] - mesh.position(v)).cwiseAbs().maxCoeff());
    return d / bounding_box(mesh).diagonal();
}

/// The band as band_positions() computed it before the rest: Σ_{lo<=k<=hi} e_k·α_kᵀ.
Eigen::MatrixXd band_sum(const SpectralDecomposition& d, std::size_t lo, std::size_t hi) {
    const Eigen::Index a = Eigen::Index(lo), count = Eigen::Index(hi - lo + 1);
    return d.eigenvectors.middleCols(a, count) * d.coefficients.middleRows(a, count);
}

/// Whether two fields are equal bit for bit, NaN (vertices outside the eigenproblem) included.
bool same_values(const std::vector<double>& a, const std::vector<double>& b) {
    return a.size() == b.size() &&
           std::equal(a.begin(), a.end(), b.begin(), [](double x, double y) {
               return x == y || (std::isnan(x) && std::isnan(y));
           });
}

/// The rows' positions X of the decomposed mesh.
Eigen::MatrixXd rows_of(const SpectralDecomposition& d) {
    Eigen::MatrixXd x(Eigen::Index(d.rows()), 3);
    for (std::size_t r = 0; r < d.rows(); ++r)
        x.row(Eigen::Index(r)) = d.base_positions[d.map.vertex_of[r].idx()].transpose();
    return x;
}

/// The S-weighted centroid of the rows of `x`.
Eigen::RowVector3d weighted_centroid(const SpectralDecomposition& d, const Eigen::MatrixXd& x) {
    return (d.S.transpose() * x) / d.S.sum();
}

}  // namespace

TEST_CASE("reconstruct with the rest from every computed frequency gives the decomposed mesh",
          "[spectral][rest]") {
    for (const Case& c : cases()) {
        INFO(c.name);
        const SpectralDecomposition d = decompose(c.mesh, c.options);
        const std::size_t last = d.size() - 1;
        REQUIRE(band_reaches_rest(d, 0, last));
        const HalfedgeMesh whole = reconstruct(c.mesh, d, 0, last, BandRest::Include);
        REQUIRE_VALID(whole);
        CHECK(relative_distance(whole.positions(), c.mesh) <= 1e-9);
        // Without the rest, a partial decomposition is not the mesh (the issue: the sliders
        // read 0..K-1 but the mesh was not that band); a full one of all rows is.
        const double without = relative_distance(reconstruct_positions(d, 0, last), c.mesh);
        const double rest =
            rest_positions(d).cwiseAbs().maxCoeff() / bounding_box(c.mesh).diagonal();
        if (d.size() == d.rows()) {
            CHECK(without <= 1e-9);
            CHECK(rest <= 1e-9);
        } else {
            CHECK(without > 1e-4);
            CHECK(rest > 1e-4);
        }
        // A band reaching the open end with the rest is the band plus rest_positions().
        const bool smallest = d.end == SpectrumEnd::Smallest;
        const std::size_t lo = smallest ? 3 : 0, hi = smallest ? last : last - 3;
        REQUIRE(band_reaches_rest(d, lo, hi));
        const Eigen::MatrixXd sum = band_sum(d, lo, hi) + rest_positions(d);
        CHECK((band_positions(d, lo, hi, BandRest::Include) - sum).cwiseAbs().maxCoeff() <=
              1e-9 * bounding_box(c.mesh).diagonal());
        // Vertices outside the eigenproblem keep their positions.
        const std::vector<Point> partial = reconstruct_positions(d, lo, hi, BandRest::Include);
        std::vector<bool> row(c.mesh.vertices_size(), false);
        for (std::size_t r = 0; r < d.rows(); ++r) row[d.map.vertex_of[r].idx()] = true;
        for (Vertex v : c.mesh.vertices())
            if (!row[v.idx()]) CHECK(partial[v.idx()] == c.mesh.position(v));
    }
}

TEST_CASE("bands without the rest, or short of the open end, are the old sums bit for bit",
          "[spectral][rest]") {
    for (const Case& c : cases()) {
        INFO(c.name);
        const SpectralDecomposition d = decompose(c.mesh, c.options);
        const std::size_t last = d.size() - 1;
        const bool smallest = d.end == SpectrumEnd::Smallest;
        const std::pair<std::size_t, std::size_t> bands[] = {
            {0, last}, {0, 0}, {2, 6}, {1, last}, {last, last}};
        for (const auto& [lo, hi] : bands) {
            INFO("band " << lo << ":" << hi);
            const bool reaches = smallest ? hi == last : lo == 0;
            CHECK(band_reaches_rest(d, lo, hi) == reaches);
            const Eigen::MatrixXd old = band_sum(d, lo, hi);
            CHECK(band_positions(d, lo, hi) == old);
            CHECK(band_positions(d, lo, hi, BandRest::Exclude) == old);
            CHECK(reconstruct_positions(d, lo, hi) ==
                  reconstruct_positions(d, lo, hi, BandRest::Exclude));
            if (!reaches) {
                CHECK(band_positions(d, lo, hi, BandRest::Include) == old);
                CHECK(same_values(band_magnitude_field(d, lo, hi, BandRest::Include),
                                  band_magnitude_field(d, lo, hi)));
            }
        }
        CHECK_THROWS_WITH(band_positions(d, 0, last + 1, BandRest::Include),
                          Catch::Contains("band: expected LO:HI"));
        CHECK_THROWS_AS(band_reaches_rest(d, 2, 1), InvalidArgument);
    }
}

TEST_CASE("with the rest, the umbrella frequencies above the constant one centre the mesh",
          "[spectral][rest]") {
    // The umbrella operator's frequency 0 on a closed connected mesh is the constant vector
    // e_0 = 1/sqrt(Σ S): it carries e_0·α_0ᵀ = 1·cᵀ, c the S-weighted (valence-weighted)
    // centroid. So [1, K-1] with the rest is X - 1·cᵀ: the mesh moved to put c at the origin.
    HalfedgeMesh sphere = make_noisy_sphere(6, 0.04, 2);
    for (Vertex v : sphere.vertices()) sphere.position(v) += Point(3, -2, 5);
    HalfedgeMesh torus = make_torus(16, 8, 1, 0.3);
    for (Vertex v : torus.vertices())
        torus.position(v) = 1.03 * torus.position(v) + Point(-1, 4, 0.5 * std::sin(7.3 * v.idx()));
    // A partial decomposition's e_0 is constant only to the solver's accuracy (3e-9 on the
    // sphere, 1.3e-7 on the torus, whose spectral gap is small): the comparisons allow for
    // that error, which is about 1e-15 for the dense method.
    for (const HalfedgeMesh* mesh : {&sphere, &torus}) {
        for (SpectralMethod method : {SpectralMethod::Full, SpectralMethod::Partial}) {
            CAPTURE(spectral_method_name(method));
            SpectralOptions o =
                options(LaplacianOperator::Umbrella, 12, SpectrumEnd::Smallest, method);
            const SpectralDecomposition d = decompose(*mesh, o);
            const Eigen::VectorXd e0 = d.eigenvectors.col(0);
            const double e0_error = (e0.maxCoeff() - e0.minCoeff()) / e0.cwiseAbs().maxCoeff();
            CAPTURE(e0_error);
            REQUIRE(e0_error < 1e-5);
            const Eigen::MatrixXd x = rows_of(d);
            const double tol =
                1e-9 * bounding_box(*mesh).diagonal() + 2 * e0_error * x.cwiseAbs().maxCoeff();
            const Eigen::RowVector3d c = weighted_centroid(d, x);
            REQUIRE(c.norm() > 0.5);
            const Eigen::MatrixXd above = band_positions(d, 1, 11, BandRest::Include);
            CHECK((above - (x.rowwise() - c)).cwiseAbs().maxCoeff() <= tol);
            CHECK(weighted_centroid(d, above).norm() <= tol);
            // Frequency 0 alone is the centroid at every vertex.
            CHECK((band_positions(d, 0, 0).rowwise() - c).cwiseAbs().maxCoeff() <= tol);
            // The largest end: the rest holds the lower frequencies, the constant among them,
            // so it carries the centroid and the computed band none of it.
            o.end = SpectrumEnd::Largest;
            const SpectralDecomposition top = decompose(*mesh, o);
            CHECK((weighted_centroid(top, rest_positions(top)) - c).norm() <= tol);
            CHECK(weighted_centroid(top, band_positions(top, 0, 11)).norm() <= tol);
        }
    }
}

TEST_CASE("band_magnitude_field with the rest agrees with the band's shape", "[spectral][rest]") {
    for (const Case& c : cases()) {
        INFO(c.name);
        const SpectralDecomposition d = decompose(c.mesh, c.options);
        const std::size_t last = d.size() - 1;
        // The whole band with the rest carries X - 1·cᵀ: the magnitude is |X - c| per row.
        const Eigen::MatrixXd x = rows_of(d);
        const Eigen::RowVector3d centroid = weighted_centroid(d, x);
        const std::vector<double> m = band_magnitude_field(d, 0, last, BandRest::Include);
        const double diagonal = bounding_box(c.mesh).diagonal();
        for (std::size_t r = 0; r < d.rows(); ++r)
            CHECK(std::abs(m[d.map.vertex_of[r].idx()] -
                           (x.row(Eigen::Index(r)) - centroid).norm()) <= 1e-9 * diagonal);
        // A band reaching the open end: X' = X - 1·cᵀ less what the computed frequencies
        // outside the band carry of X' (their S-projection).
        const bool smallest = d.end == SpectrumEnd::Smallest;
        const std::size_t lo = smallest ? 2 : 0, hi = smallest ? last : last - 2;
        const Eigen::MatrixXd e = smallest ? d.eigenvectors.leftCols(Eigen::Index(lo))
                                           : d.eigenvectors.rightCols(Eigen::Index(last - hi));
        const Eigen::MatrixXd centred = x.rowwise() - centroid;
        const Eigen::MatrixXd part = centred - e * (e.transpose() * (d.S.asDiagonal() * centred));
        const std::vector<double> mb = band_magnitude_field(d, lo, hi, BandRest::Include);
        for (std::size_t r = 0; r < d.rows(); ++r)
            CHECK(std::abs(mb[d.map.vertex_of[r].idx()] - part.row(Eigen::Index(r)).norm()) <=
                  1e-9 * diagonal);
    }
}

TEST_CASE("the shared bunny: the whole band of its largest frequencies with the rest is the bunny",
          "[spectral][rest][shared]") {
    // The smallest end: "the shared bunny: isolated vertices ..." in test_spectral.cpp.
    const std::string path = test::shared_mesh("stanford-bunny.obj");
    SKIP_IF_MISSING(path);
    const HalfedgeMesh bunny = read_mesh(path).mesh;
    const SpectralDecomposition d =
        decompose(bunny, options(LaplacianOperator::CurvatureFlow, 5, SpectrumEnd::Largest));
    const HalfedgeMesh whole = reconstruct(bunny, d, 0, 4, BandRest::Include);
    REQUIRE_VALID(whole);
    CHECK(relative_distance(whole.positions(), bunny) <= 1e-9);
    CHECK(relative_distance(reconstruct_positions(d, 0, 4), bunny) > 1e-3);
    // The 1,113 isolated vertices, outside the eigenproblem, keep their positions.
    for (Vertex v : bunny.vertices())
        if (bunny.is_isolated(v)) CHECK(whole.position(v) == bunny.position(v));
}

TEST_CASE("the spectrum operation's --with-rest", "[spectral][rest][operation]") {
    const HalfedgeMesh mesh = make_noisy_sphere(6, 0.03, 8);
    NullProgress none;
    const auto run = [&](const std::string& text) {
        return run_operation(parse_operation(text), mesh, none);
    };
    // The whole band with the rest is the input; its canonical parameters say so and replay.
    const OperationResult r = run("spectrum --operator curvature-flow --k 12 --with-rest");
    REQUIRE(r.steps.size() == 1);
    REQUIRE_VALID(r.steps[0].mesh);
    CHECK(relative_distance(r.steps[0].mesh.positions(), mesh) <= 1e-9);
    CHECK(r.parameters.find("--with-rest") != std::string::npos);
    CHECK(r.report[0].find("band 0:11 and the rest (the higher frequencies)") != std::string::npos);
    const OperationResult again = run("spectrum " + r.parameters);
    CHECK(again.steps[0].mesh.positions() == r.steps[0].mesh.positions());
    const OperationResult top =
        run("spectrum --operator umbrella --k 12 --which largest --band 0:11 --with-rest");
    CHECK(relative_distance(top.steps[0].mesh.positions(), mesh) <= 1e-9);
    CHECK(top.report[0].find("and the rest (the lower frequencies)") != std::string::npos);

    // Without the flag: the old reconstruction bit for bit, no flag in the parameters.
    const Operation plain = parse_operation("spectrum --operator curvature-flow --k 12");
    const OperationResult without = run_operation(plain, mesh, none);
    CHECK(without.parameters.find("rest") == std::string::npos);
    const SpectralDecomposition d = decompose(mesh, spectral_options(plain));
    std::vector<Point> old = mesh.positions();
    const Eigen::MatrixXd x = band_sum(d, 0, 11);
    for (std::size_t row = 0; row < d.rows(); ++row)
        old[d.map.vertex_of[row].idx()] = x.row(Eigen::Index(row)).transpose();
    CHECK(without.steps[0].mesh.positions() == old);
    CHECK(relative_distance(without.steps[0].mesh.positions(), mesh) > 1e-4);
    // A band short of the open end is the same with and without the flag.
    CHECK(run("spectrum --operator curvature-flow --k 12 --band 2:5 --with-rest")
              .steps[0]
              .mesh.positions() ==
          run("spectrum --operator curvature-flow --k 12 --band 2:5").steps[0].mesh.positions());
}
