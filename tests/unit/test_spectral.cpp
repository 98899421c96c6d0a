// Frequency decomposition (core/algorithms/spectral.h): the sphere's spectrum, partial against
// full, band by band against one band, S-orthonormality, exact reconstruction, low-pass smoothing,
// disconnected meshes, boundaries, isolated vertices, option errors and cancellation.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "app/ops/operation.h"
#include "core/algorithms/coloring.h"
#include "core/algorithms/generators.h"
#include "core/algorithms/laplacian.h"
#include "core/algorithms/spectral.h"
#include "core/errors.h"
#include "core/geometry.h"
#include "core/io/mesh_io.h"
#include "core/mesh_builder.h"
#include "core/system_memory.h"
#include "test_helpers.h"

using namespace trilab;

namespace {

const LaplacianOperator kOperators[] = {
    LaplacianOperator::Umbrella, LaplacianOperator::ImprovedUmbrella,
    LaplacianOperator::CurvatureFlow, LaplacianOperator::SecondOrder};

SpectralOptions options(LaplacianOperator op, std::size_t k,
                        SpectralMethod method = SpectralMethod::Partial) {
    SpectralOptions o;
    o.op = op;
    o.k = k;
    o.method = method;
    return o;
}

/// Largest |x - y| / max(|y|_max, tiny) over all coordinates.
double relative_distance(const HalfedgeMesh& a, const HalfedgeMesh& b) {
    double diff = 0, scale = 1e-300;
    for (Vertex v : a.vertices()) {
        diff = std::max(diff, (a.position(v) - b.position(v)).cwiseAbs().maxCoeff());
        scale = std::max(scale, b.position(v).cwiseAbs().maxCoeff());
    }
    return diff / scale;
}

/// Mean squared length of the umbrella Laplacian of the positions (a roughness measure).
double roughness(const HalfedgeMesh& m) {
    const Laplacian lap = build_laplacian(m, LaplacianOperator::Umbrella);
    const Eigen::MatrixXd lx = lap.L * gather_positions(m, lap.map);
    return lx.rowwise().squaredNorm().mean();
}

/// Mean |‖p‖ - 1| over the vertices (distance to the unit sphere).
double sphere_deviation(const HalfedgeMesh& m) {
    double s = 0;
    for (Vertex v : m.vertices()) s += std::abs(m.position(v).norm() - 1.0);
    return s / double(m.n_vertices());
}

/// Two disjoint spheres plus one isolated vertex.
HalfedgeMesh two_spheres_and_a_point() {
    PolygonSoup soup;
    for (int copy = 0; copy < 2; ++copy) {
        const HalfedgeMesh s = make_icosphere(4);
        const Index offset = Index(soup.positions.size());
        for (Vertex v : s.vertices())
            soup.positions.push_back(s.position(v) + Point(3.0 * copy, 0, 0));
        for (Face f : s.faces()) {
            for (Vertex v : s.face_vertices(f)) soup.corners.push_back(offset + v.idx());
            soup.face_offsets.push_back(soup.corners.size());
        }
    }
    soup.positions.push_back(Point(10, 10, 10));
    LoadReport report;
    return build_mesh(soup, report);
}

/// Whether every column of `a` lies (S-orthogonally) in the span of the columns of `b`
/// to `tol`: 1 - |projection|² per column.
double subspace_gap(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, const Eigen::VectorXd& S) {
    const Eigen::MatrixXd c = b.transpose() * (S.asDiagonal() * a);  // b is S-orthonormal
    double gap = 0;
    for (Eigen::Index j = 0; j < c.cols(); ++j)
        gap = std::max(gap, std::abs(1.0 - c.col(j).squaredNorm()));
    return gap;
}

/// An icosphere collapsed onto a line (as repeated smoothing leaves a mesh): every vertex at
/// z·(0.05, -0.13, 1)·0.01 plus a jitter of `jitter` (absolute, deterministic), so that the
/// triangles have areas of rounding size (many exactly zero): the stress test's mesh.
HalfedgeMesh collapsed_sphere(unsigned frequency, double jitter) {
    HalfedgeMesh m = make_icosphere(frequency);
    std::uint64_t x = 12345;
    auto uniform = [&x] {
        x = x * 6364136223846793005ull + 1442695040888963407ull;
        return double(x >> 11) * 0x1.0p-52 - 1.0;  // in [-1, 1)
    };
    for (Vertex v : m.vertices()) {
        const double t = 0.01 * m.position(v).z();
        const double a = uniform(), b = uniform(), c = uniform();
        m.position(v) = Point(0.05 * t + jitter * a, -0.13 * t + jitter * b, t + jitter * c);
    }
    return m;
}

}  // namespace

TEST_CASE("the sphere's lowest eigenvalues cluster as l(l+1) with multiplicities 2l+1",
          "[spectral]") {
    const HalfedgeMesh sphere = make_icosphere(12);  // 1,442 vertices, radius 1
    for (MassMatrix mass : {MassMatrix::Voronoi, MassMatrix::Barycentric}) {
        SpectralOptions o = options(LaplacianOperator::CurvatureFlow, 16);
        o.mass = mass;
        const SpectralDecomposition d = decompose(sphere, o);
        REQUIRE(d.size() == 16);
        INFO("mass " << mass_matrix_name(mass) << ", eigenvalues " << d.eigenvalues.transpose());
        CHECK(std::abs(d.eigenvalues[0]) < 1e-8);
        std::size_t i = 1;
        for (int l = 1; l <= 3; ++l)
            for (int m = 0; m < 2 * l + 1; ++m, ++i)
                CHECK(std::abs(d.eigenvalues[Eigen::Index(i)] / (l * (l + 1)) - 1.0) < 0.03);
        // The clusters are separated: the first of each cluster is far from the previous one.
        CHECK(d.eigenvalues[4] > 1.5 * d.eigenvalues[3]);
        CHECK(d.eigenvalues[9] > 1.5 * d.eigenvalues[8]);
    }
}

TEST_CASE("partial and full decompositions agree on every operator", "[spectral]") {
    const HalfedgeMesh mesh = make_noisy_sphere(5, 0.05, 3);  // 252 vertices
    for (LaplacianOperator op : kOperators) {
        INFO("operator " << laplacian_operator_name(op));
        const SpectralDecomposition full = decompose(mesh, options(op, 0, SpectralMethod::Full));
        REQUIRE(full.size() == mesh.n_vertices());
        CHECK(s_orthonormality_error(full) < 1e-8);
        CHECK(full.eigenvalues.minCoeff() > -1e-9 * full.eigenvalues.maxCoeff());
        const double scale = full.eigenvalues.maxCoeff();
        for (SpectrumEnd end : {SpectrumEnd::Smallest, SpectrumEnd::Largest}) {
            INFO("end " << spectrum_end_name(end));
            SpectralOptions o = options(op, 20);
            o.end = end;
            const SpectralDecomposition part = decompose(mesh, o);
            REQUIRE(part.size() == 20);
            CHECK(s_orthonormality_error(part) < 1e-8);
            CHECK(part.report.max_residual < 1e-8);
            const Eigen::Index first =
                end == SpectrumEnd::Smallest ? 0 : full.eigenvalues.size() - 20;
            const Eigen::VectorXd ref = full.eigenvalues.segment(first, 20);
            for (Eigen::Index j = 0; j < 20; ++j)
                CHECK(std::abs(part.eigenvalues[j] - ref[j]) <=
                      1e-8 * std::max(std::abs(ref[j]), 1e-3 * scale));
            // Eigenvector subspaces: every partial vector lies in the span of the full ones
            // (widened by one on each side for a possible cluster at the end).
            const Eigen::Index lo = std::max<Eigen::Index>(first - 1, 0);
            const Eigen::Index hi = std::min<Eigen::Index>(first + 21, full.eigenvalues.size());
            CHECK(subspace_gap(part.eigenvectors, full.eigenvectors.middleCols(lo, hi - lo),
                               full.S) < 1e-8);
        }
    }
}

TEST_CASE("band-by-band shift-invert gives the same frequencies as one band", "[spectral]") {
    const HalfedgeMesh mesh = make_icosphere(8);  // 642 vertices, many exact multiplicities
    SpectralOptions o = options(LaplacianOperator::CurvatureFlow, 90);
    o.mass = MassMatrix::Voronoi;
    const SpectralDecomposition one = decompose(mesh, o);
    o.band_size = 20;
    const SpectralDecomposition banded = decompose(mesh, o);
    REQUIRE(banded.size() == 90);
    CHECK(banded.report.bands >= 5);
    INFO("one band: " << one.eigenvalues.transpose()
                      << "\nbands: " << banded.eigenvalues.transpose());
    for (Eigen::Index j = 0; j < 90; ++j)
        CHECK(std::abs(banded.eigenvalues[j] - one.eigenvalues[j]) <=
              1e-8 * std::max(1.0, one.eigenvalues[j]));
    CHECK(s_orthonormality_error(banded) < 1e-8);
    // The spans agree up to the last (possibly cut) cluster: compare the first 81 = (8+1)²
    // frequencies, l <= 8, against all 90 of one band.
    CHECK(subspace_gap(banded.eigenvectors.leftCols(81), one.eigenvectors, one.S) < 1e-8);
}

namespace {

/// A grid with a bump (a flat grid's coordinates lie in a few low frequencies).
HalfedgeMesh bumpy_grid() {
    HalfedgeMesh m = make_grid(12);
    for (Vertex v : m.vertices()) m.position(v).z() = 0.1 * std::sin(5.1 * v.idx());
    return m;
}

/// A torus with every vertex moved a little (a perfect torus lives in a few low frequencies).
HalfedgeMesh bumpy_torus() {
    HalfedgeMesh m = make_torus(16, 8, 1, 0.3);
    for (Vertex v : m.vertices()) m.position(v) *= 1.0 + 0.03 * std::sin(7.3 * v.idx());
    return m;
}

}  // namespace

TEST_CASE("a full decomposition reconstructs the mesh from all frequencies", "[spectral]") {
    const HalfedgeMesh meshes[] = {make_noisy_sphere(5, 0.05, 9), bumpy_grid(), bumpy_torus()};
    for (const HalfedgeMesh& mesh : meshes) {
        for (LaplacianOperator op : kOperators) {
            for (bool fix : {false, true}) {
                INFO("operator " << laplacian_operator_name(op) << " fix_boundary " << fix);
                SpectralOptions o = options(op, 0, SpectralMethod::Full);
                o.fix_boundary = fix;
                const SpectralDecomposition d = decompose(mesh, o);
                const HalfedgeMesh r = reconstruct(mesh, d, 0, d.size() - 1);
                REQUIRE_VALID(r);
                CHECK(relative_distance(r, mesh) < 1e-9);
                // A proper sub-band does not reconstruct it.
                const HalfedgeMesh low = reconstruct(mesh, d, 0, d.size() / 2);
                REQUIRE_VALID(low);
                CHECK(relative_distance(low, mesh) > 1e-6);
            }
        }
    }
}

TEST_CASE("a low-pass reconstruction of a noisy sphere is smooth and close to the sphere",
          "[spectral]") {
    const HalfedgeMesh noisy = make_noisy_sphere(10, 0.03, 5);  // 1,002 vertices
    for (LaplacianOperator op : kOperators) {
        INFO("operator " << laplacian_operator_name(op));
        const SpectralDecomposition d = decompose(noisy, options(op, 36));
        const HalfedgeMesh low = reconstruct(noisy, d, 0, 35);  // l <= 5 on a sphere
        REQUIRE_VALID(low);
        CHECK(roughness(low) < 0.2 * roughness(noisy));
        CHECK(sphere_deviation(low) < 0.5 * sphere_deviation(noisy));
        CHECK(sphere_deviation(low) < 0.02);
    }
}

TEST_CASE("disconnected meshes have one zero eigenvalue per piece, isolated vertices stay",
          "[spectral]") {
    const HalfedgeMesh mesh = two_spheres_and_a_point();
    REQUIRE_VALID(mesh);
    Vertex isolated;
    for (Vertex v : mesh.vertices())
        if (mesh.is_isolated(v)) isolated = v;
    REQUIRE(isolated.is_valid());
    for (LaplacianOperator op : kOperators) {
        INFO("operator " << laplacian_operator_name(op));
        const SpectralDecomposition d = decompose(mesh, options(op, 10));
        CHECK(d.rows() == mesh.n_vertices() - 1);
        INFO("eigenvalues " << d.eigenvalues.transpose());
        const double scale = d.eigenvalues[9];
        CHECK(std::abs(d.eigenvalues[0]) < 1e-8 * scale);
        CHECK(std::abs(d.eigenvalues[1]) < 1e-8 * scale);
        CHECK(d.eigenvalues[2] > 1e-3 * scale);
        CHECK(s_orthonormality_error(d) < 1e-8);
        // The two zero frequencies carry each sphere's centroid: the reconstruction from them
        // puts every vertex of a sphere at its centre.
        const HalfedgeMesh centres = reconstruct(mesh, d, 0, 1);
        REQUIRE_VALID(centres);
        for (Vertex v : centres.vertices()) {
            if (v == isolated) continue;
            const Point c = mesh.position(v).x() > 1.5 ? Point(3, 0, 0) : Point(0, 0, 0);
            CHECK((centres.position(v) - c).norm() < 1e-6);
        }
        CHECK(centres.position(isolated) == mesh.position(isolated));
        const std::vector<double> f = frequency_field(d, 3);
        CHECK(std::isnan(f[isolated.idx()]));
    }
}

TEST_CASE("boundaries: free rows give a zero eigenvalue, fixed rows do not", "[spectral]") {
    const HalfedgeMesh grid = make_grid(10);
    for (LaplacianOperator op : kOperators) {
        INFO("operator " << laplacian_operator_name(op));
        SpectralOptions o = options(op, 5);
        const SpectralDecomposition free_rows = decompose(grid, o);
        CHECK(free_rows.rows() == grid.n_vertices());
        CHECK(std::abs(free_rows.eigenvalues[0]) < 1e-8 * free_rows.eigenvalues[4]);
        // The zero eigenvector is constant (second order: linear functions of the flat grid
        // are in its null space too).
        const Eigen::VectorXd e0 = free_rows.eigenvectors.col(0);
        if (op != LaplacianOperator::SecondOrder)
            CHECK(e0.maxCoeff() - e0.minCoeff() < 1e-6 * e0.cwiseAbs().maxCoeff());
        o.fix_boundary = true;
        const SpectralDecomposition fixed = decompose(grid, o);
        CHECK(fixed.rows() < grid.n_vertices());
        CHECK(fixed.eigenvalues[0] > 1e-4 * fixed.eigenvalues[4]);
        // Boundary vertices keep their positions in any reconstruction.
        const HalfedgeMesh r = reconstruct(grid, fixed, 1, 3);
        REQUIRE_VALID(r);
        for (Vertex v : grid.vertices())
            if (grid.is_boundary(v)) CHECK(r.position(v) == grid.position(v));
    }
}

TEST_CASE("frequency fields and band magnitudes", "[spectral]") {
    const HalfedgeMesh mesh = make_noisy_sphere(6, 0.02, 4);
    const SpectralDecomposition d = decompose(mesh, options(LaplacianOperator::Umbrella, 12));
    const std::vector<double> f = frequency_field(d, 5);
    REQUIRE(f.size() == mesh.vertices_size());
    double s2 = 0;
    for (std::size_t r = 0; r < d.rows(); ++r)
        s2 += d.S[Eigen::Index(r)] * f[d.map.vertex_of[r].idx()] * f[d.map.vertex_of[r].idx()];
    CHECK(std::abs(s2 - 1.0) < 1e-8);  // S-normalized
    // The constant frequency e_0 carries the centroid, which the magnitude leaves out: band
    // [0, 0] carries nothing of the position relative to the centroid (to the accuracy of
    // the computed e_0, for a sphere of radius 1).
    const std::vector<double> m0 = band_magnitude_field(d, 0, 0);
    for (Vertex v : mesh.vertices()) CHECK(m0[v.idx()] < 1e-6);
    // The full computed band carries most of the position: |X_band| is close to |X - c| (c
    // near the origin for this sphere).
    const std::vector<double> m = band_magnitude_field(d, 0, 11);
    for (Vertex v : mesh.vertices()) CHECK(std::abs(m[v.idx()] - mesh.position(v).norm()) < 0.1);
    CHECK_THROWS_AS(band_magnitude_field(d, 3, 12), InvalidArgument);
}

TEST_CASE("frequency mass does not depend on where the mesh sits", "[spectral]") {
    // The homer at its file position and at the origin: the same mesh translated by a
    // vector much larger than itself must show the same frequency mass, for bands with and
    // without the constant frequency, free and fixed boundary, and the same colours.
    const Vector3 shift(1e3, -2.5e3, 7e2);
    struct Case {
        HalfedgeMesh mesh;
        bool fix_boundary;
    };
    // Cotangent weights and no symmetry, so no repeated eigenvalue makes a band's basis
    // arbitrary (the bands below cut through the sphere's l = 2 cluster).
    HalfedgeMesh bumps = make_grid(9);
    for (Vertex v : bumps.vertices()) {
        Point& p = bumps.position(v);
        p.z() = 0.1 * std::sin(3 * p.x() + 1) * std::cos(2 * p.y()) + 0.05 * p.x() * p.x();
    }
    std::vector<Case> cases;
    cases.push_back({make_noisy_sphere(5, 0.03, 11), false});
    cases.push_back({bumps, true});
    cases.push_back({bumps, false});
    for (Case& c : cases) {
        HalfedgeMesh moved = c.mesh;
        for (Vertex v : moved.vertices()) moved.position(v) += shift;
        SpectralOptions o = options(LaplacianOperator::CurvatureFlow, 16);
        o.fix_boundary = c.fix_boundary;
        const SpectralDecomposition a = decompose(c.mesh, o);
        const SpectralDecomposition b = decompose(moved, o);
        for (const auto& [lo, hi] : {std::pair<std::size_t, std::size_t>{0, 15}, {0, 4}, {5, 15}}) {
            INFO("band " << lo << ".." << hi << ", fixed boundary " << c.fix_boundary);
            const std::vector<double> fa = band_magnitude_field(a, lo, hi);
            const std::vector<double> fb = band_magnitude_field(b, lo, hi);
            double largest = 0;
            for (Vertex v : c.mesh.vertices())
                if (std::isfinite(fa[v.idx()])) largest = std::max(largest, fa[v.idx()]);
            REQUIRE(largest > 0);
            // Before the centring, the band with e_0 showed |p + shift|, about 2800 here.
            REQUIRE(largest < 10);
            for (Vertex v : c.mesh.vertices()) {
                if (!std::isfinite(fa[v.idx()])) {
                    REQUIRE(std::isnan(fb[v.idx()]));
                    continue;
                }
                REQUIRE(std::abs(fa[v.idx()] - fb[v.idx()]) < 1e-6 * largest);
            }
            const VertexColors ca = color_field(c.mesh, fa, VertexColoring::FrequencyMass);
            const VertexColors cb = color_field(moved, fb, VertexColoring::FrequencyMass);
            for (std::size_t i = 0; i < ca.colors.size(); ++i)
                REQUIRE((ca.colors[i] - cb.colors[i]).cwiseAbs().maxCoeff() < 1e-4f);
        }
    }
}

TEST_CASE("a dense decomposition larger than the available memory is refused with the numbers",
          "[spectral]") {
    // The dense path needs 16 n^2 bytes for n rows: take n with that above twice what this
    // machine has available now, and let max_full_rows allow it.
    const double available = double(available_memory_bytes());
    const double rows = std::sqrt(available / 8.0) + 1;
    if (rows > 4e6) {
        SKIP_TEST(available << " bytes available would need a mesh of " << rows << " vertices");
    }
    const unsigned n = unsigned(std::ceil(std::sqrt(rows)));
    const HalfedgeMesh mesh = make_grid(n);  // (n + 1)^2 vertices
    REQUIRE(double(mesh.n_vertices()) >= rows);
    SpectralOptions o = options(LaplacianOperator::Umbrella, 10, SpectralMethod::Full);
    o.max_full_rows = mesh.n_vertices();
    try {
        decompose(mesh, o);
        FAIL("the dense decomposition was accepted");
    } catch (const InvalidArgument& e) {
        const std::string what = e.what();
        INFO(what);
        CHECK(what.rfind("full: the dense decomposition of " + std::to_string(mesh.n_vertices()) +
                             " rows needs about ",
                         0) == 0);
        CHECK(what.find("GiB") != std::string::npos);
        CHECK(what.find("this process may still allocate (") != std::string::npos);
    }
}

TEST_CASE("bad spectral options are refused with the option's name", "[spectral]") {
    const HalfedgeMesh mesh = make_icosphere(3);  // 92 vertices
    auto message = [&](const SpectralOptions& o) {
        try {
            decompose(mesh, o);
        } catch (const InvalidArgument& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    CHECK(message(options(LaplacianOperator::Umbrella, 0)).rfind("k: expected", 0) == 0);
    CHECK(message(options(LaplacianOperator::Umbrella, 92)).find("1 to 91") != std::string::npos);
    SpectralOptions full = options(LaplacianOperator::Umbrella, 0, SpectralMethod::Full);
    full.max_full_rows = 50;
    CHECK(message(full).find("max_full_rows") != std::string::npos);
    CHECK(message(options(LaplacianOperator::Umbrella, 0, SpectralMethod::Full)).empty());
    HalfedgeMesh nan_mesh = mesh;
    nan_mesh.position(Vertex(0)).x() = std::nan("");
    CHECK_THROWS_AS(decompose(nan_mesh, options(LaplacianOperator::Umbrella, 5)), InvalidArgument);
    const SpectralDecomposition d = decompose(mesh, options(LaplacianOperator::Umbrella, 5));
    CHECK_THROWS_WITH(band_positions(d, 3, 5), Catch::Contains("band: expected LO:HI"));
    CHECK_THROWS_AS(band_positions(d, 3, 2), InvalidArgument);
    CHECK_THROWS_AS(frequency_field(d, 5), InvalidArgument);
    CHECK_THROWS_AS(reconstruct(make_icosphere(2), d, 0, 4), InvalidArgument);
    CHECK_THROWS_AS(decompose(HalfedgeMesh(), options(LaplacianOperator::Umbrella, 1)),
                    InvalidArgument);
}

TEST_CASE("spectrum slicing on two threads gives the frequencies of one sweep", "[spectral]") {
    struct Case {
        const char* name;
        HalfedgeMesh mesh;
        std::size_t k, band;
        std::size_t compare;  // leading frequencies whose span must agree (whole clusters)
    };
    const Case cases[] = {{"icosphere (exact multiplicities)", make_icosphere(8), 90, 20, 81},
                          {"noisy sphere", make_noisy_sphere(12, 0.03, 5), 70, 15, 69}};
    for (const Case& c : cases) {
        INFO(c.name);
        SpectralOptions o = options(LaplacianOperator::CurvatureFlow, c.k);
        o.mass = MassMatrix::Voronoi;
        o.band_size = c.band;
        o.threads = 1;
        const SpectralDecomposition one = decompose(c.mesh, o);
        o.threads = 2;
        const SpectralDecomposition two = decompose(c.mesh, o);
        CHECK(one.report.slices == 1);
        CHECK(two.report.slices == 2);
        REQUIRE(two.size() == c.k);
        INFO("one sweep: " << one.eigenvalues.transpose()
                           << "\ntwo slices: " << two.eigenvalues.transpose());
        for (Eigen::Index j = 0; j < Eigen::Index(c.k); ++j)
            CHECK(std::abs(two.eigenvalues[j] - one.eigenvalues[j]) <=
                  1e-8 * std::max(1.0, one.eigenvalues[j]));
        CHECK(s_orthonormality_error(two) < 1e-8);
        CHECK(two.report.max_residual < 1e-8);
        CHECK(subspace_gap(two.eigenvectors.leftCols(Eigen::Index(c.compare)), one.eigenvectors,
                           one.S) < 1e-8);
        // The reconstruction from the sliced frequencies is a valid mesh with the same faces.
        const HalfedgeMesh low = reconstruct(c.mesh, two, 0, c.k - 1);
        REQUIRE_VALID(low);
        CHECK(low.n_faces() == c.mesh.n_faces());
    }
}

TEST_CASE("the block solver gives the frequencies of the band-by-band sweep", "[spectral]") {
    struct Case {
        const char* name;
        HalfedgeMesh mesh;
        LaplacianOperator op;
        MassMatrix mass;
        std::size_t k;
        std::size_t compare;  // leading frequencies whose span must agree (whole clusters)
        bool block_verified;  // whether the block run must be accepted (no band fallback)
    };
    // The icosphere's multiplicities (2l + 1, up to 17 here) exceed the block of 8 vectors:
    // the block run may miss copies, which the eigenvalue count then catches (the bands take
    // over); either way the frequencies must be the bands'.
    const Case cases[] = {{"noisy sphere, umbrella", make_noisy_sphere(20, 0.03, 7),
                           LaplacianOperator::Umbrella, MassMatrix::Normalizer, 60, 60, true},
                          {"noisy sphere, curvature flow", make_noisy_sphere(20, 0.03, 8),
                           LaplacianOperator::CurvatureFlow, MassMatrix::Voronoi, 45, 45, true},
                          {"icosphere (exact multiplicities)", make_icosphere(20),
                           LaplacianOperator::CurvatureFlow, MassMatrix::Voronoi, 70, 64, false}};
    for (const Case& c : cases) {
        SpectralOptions o = options(c.op, c.k);
        o.mass = c.mass;
        o.solver = SpectralSolver::Bands;
        o.threads = 1;
        const SpectralDecomposition bands = decompose(c.mesh, o);
        REQUIRE(bands.size() == c.k);
        o.solver = SpectralSolver::Block;
        for (std::size_t threads : {1, 2}) {
            INFO(c.name << ", " << threads << " thread(s)");
            o.threads = threads;
            const SpectralDecomposition block = decompose(c.mesh, o);
            REQUIRE(block.size() == c.k);
            INFO("bands: " << bands.eigenvalues.transpose() << "\nblock: "
                           << block.eigenvalues.transpose() << "\nsolver " << block.report.solver);
            if (c.block_verified) {
                CHECK(block.report.solver.rfind("block", 0) == 0);
                CHECK(block.report.factorizations == 2);
            }
            for (Eigen::Index j = 0; j < Eigen::Index(c.k); ++j)
                CHECK(std::abs(block.eigenvalues[j] - bands.eigenvalues[j]) <=
                      1e-8 * std::max(1.0, bands.eigenvalues[j]));
            CHECK(s_orthonormality_error(block) < 1e-8);
            CHECK(block.report.max_residual < 1e-8);
            CHECK(subspace_gap(block.eigenvectors.leftCols(Eigen::Index(c.compare)),
                               bands.eigenvectors, bands.S) < 1e-8);
            const HalfedgeMesh low = reconstruct(c.mesh, block, 0, c.k - 1);
            REQUIRE_VALID(low);
        }
    }
}

TEST_CASE("a sliced decomposition stops both threads when cancelled", "[spectral]") {
    const HalfedgeMesh mesh = make_icosphere(8);
    SpectralOptions o = options(LaplacianOperator::CurvatureFlow, 90);
    o.band_size = 20;
    o.threads = 2;
    for (int reports : {2, 6, 12, 20}) {
        INFO("cancelled after " << reports << " progress reports");
        // Asked from both slicing threads (CancellingProgress is thread-safe).
        auto cancel = test::CancellingProgress::after_reports(reports);
        CHECK_THROWS_AS(decompose(mesh, o, cancel), Cancelled);
    }
}

TEST_CASE("a decomposition can be cancelled and is deterministic", "[spectral]") {
    const HalfedgeMesh mesh = make_noisy_sphere(10, 0.02, 2);
    auto cancel = test::CancellingProgress::after_reports(3);
    CHECK_THROWS_AS(decompose(mesh, options(LaplacianOperator::CurvatureFlow, 30), cancel),
                    Cancelled);
    const SpectralDecomposition a = decompose(mesh, options(LaplacianOperator::CurvatureFlow, 30));
    const SpectralDecomposition b = decompose(mesh, options(LaplacianOperator::CurvatureFlow, 30));
    CHECK(a.eigenvalues == b.eigenvalues);
    CHECK(a.eigenvectors == b.eigenvectors);
}

TEST_CASE("a mesh collapsed to a line is refused or decomposed quickly, never hangs",
          "[spectral]") {
    // Found by the stress test: the shift-invert bands never finished (repairs and bands
    // without bound on a spectrum of rounding noise). Now: refused up front as degenerate, or
    // a valid decomposition, or an Error with a message, in bounded time.
    const HalfedgeMesh mesh = collapsed_sphere(20, 1e-18);  // 4002 vertices
    const HalfedgeMesh small = collapsed_sphere(8, 1e-18);  // 642, for the dense method
    const MassMatrix masses[] = {MassMatrix::Normalizer, MassMatrix::Barycentric,
                                 MassMatrix::Voronoi};
    std::size_t refused = 0;
    for (LaplacianOperator op : kOperators)
        for (MassMatrix mass : masses)
            for (SpectralMethod method : {SpectralMethod::Partial, SpectralMethod::Full})
                for (SpectrumEnd end : {SpectrumEnd::Smallest, SpectrumEnd::Largest}) {
                    if (method == SpectralMethod::Full && end == SpectrumEnd::Largest) continue;
                    SpectralOptions o =
                        options(op, method == SpectralMethod::Full ? 10 : 2, method);
                    o.mass = mass;
                    o.end = end;
                    CAPTURE(laplacian_operator_name(op), mass_matrix_name(mass),
                            spectral_method_name(method), spectrum_end_name(end));
                    const auto t0 = std::chrono::steady_clock::now();
                    std::string message;
                    try {
                        const SpectralDecomposition d =
                            decompose(method == SpectralMethod::Full ? small : mesh, o);
                        CHECK(d.eigenvalues.allFinite());
                        CHECK(d.eigenvectors.allFinite());
                        CHECK(s_orthonormality_error(d) < 1e-6);
                    } catch (const Error& e) {
                        message = e.what();
                        CHECK(!message.empty());
                        if (message.find("the mesh is degenerate") != std::string::npos) ++refused;
                    }
                    const double s =
                        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0)
                            .count();
                    CAPTURE(message);
                    CHECK(s < 5.0);
                }
    CHECK(refused > 0);
    // The umbrella operator with its valence mass does not see the geometry: decomposed.
    SpectralOptions o = options(LaplacianOperator::Umbrella, 5);
    const SpectralDecomposition d = decompose(mesh, o);
    CHECK(d.size() == 5);
    CHECK(s_orthonormality_error(d) < 1e-8);
    // The stress test's command: refused with the reason.
    o = options(LaplacianOperator::SecondOrder, 2);
    o.mass = MassMatrix::Voronoi;
    CHECK_THROWS_WITH(decompose(mesh, o), Catch::Contains("the mesh is degenerate"));
}

TEST_CASE("the shared cow: the slices' split is balanced where Weyl's law misses the middle",
          "[spectral][shared]") {
    // The cow's first 20 frequencies put Weyl's middle of 150 at the 54th: the split is moved
    // by a secant step and counted again, so two slices redo little of each other's work.
    const std::string path = test::shared_mesh("cow.obj");
    SKIP_IF_MISSING(path);
    const HalfedgeMesh cow = read_mesh(path).mesh;
    SpectralOptions o = options(LaplacianOperator::CurvatureFlow, 150);
    o.threads = 1;
    const SpectralDecomposition one = decompose(cow, o);
    o.threads = 2;
    const SpectralDecomposition two = decompose(cow, o);
    REQUIRE(two.report.slices == 2);
    REQUIRE(two.size() == one.size());
    for (Eigen::Index j = 0; j < Eigen::Index(one.size()); ++j)
        CHECK(std::abs(two.eigenvalues[j] - one.eigenvalues[j]) <=
              1e-8 * std::max(1e-3, one.eigenvalues[j]));
    CHECK(s_orthonormality_error(two) < 1e-8);
    CHECK(two.report.max_residual < 1e-8);
    // Before: 664 solves in two slices for 510 in one sweep (Weyl's split left one slice
    // 183 solves and the other 408).
    INFO("solves: one sweep " << one.report.operations << ", two slices " << two.report.operations);
    CHECK(two.report.operations * 10 <= one.report.operations * 11);
}

TEST_CASE("the shared bunny: isolated vertices are left out and keep their positions",
          "[spectral][shared]") {
    const std::string path = test::shared_mesh("stanford-bunny.obj");
    SKIP_IF_MISSING(path);
    const HalfedgeMesh bunny = read_mesh(path).mesh;
    std::size_t isolated = 0;
    for (Vertex v : bunny.vertices()) isolated += bunny.is_isolated(v);
    REQUIRE(isolated == 1113);
    const SpectralDecomposition d = decompose(bunny, options(LaplacianOperator::CurvatureFlow, 20));
    CHECK(d.rows() == bunny.n_vertices() - isolated);
    CHECK(s_orthonormality_error(d) < 1e-8);
    const HalfedgeMesh low = reconstruct(bunny, d, 0, 19);
    REQUIRE_VALID(low);
    for (Vertex v : bunny.vertices())
        if (bunny.is_isolated(v)) CHECK(low.position(v) == bunny.position(v));
    CHECK(roughness(low) < roughness(bunny));
    // With the rest (the frequencies above 19), the whole band is the bunny (the largest end:
    // test_spectral_rest.cpp).
    const HalfedgeMesh whole = reconstruct(bunny, d, 0, 19, BandRest::Include);
    REQUIRE_VALID(whole);
    double difference = 0;
    for (Vertex v : bunny.vertices())
        difference =
            std::max(difference, (whole.position(v) - bunny.position(v)).cwiseAbs().maxCoeff());
    CHECK(difference <= 1e-9 * bounding_box(bunny).diagonal());
    CHECK(relative_distance(low, bunny) > 1e-3);
}

TEST_CASE("the spectrum operation of the registry", "[spectral][operation]") {
    const HalfedgeMesh mesh = make_noisy_sphere(6, 0.03, 8);
    NullProgress none;
    const OperationResult r = run_operation(
        parse_operation("spectrum --operator curvature-flow --k 12 --band 0:8"), mesh, none);
    REQUIRE(r.steps.size() == 1);
    REQUIRE_VALID(r.steps[0].mesh);
    CHECK(r.steps[0].mesh.n_vertices() == mesh.n_vertices());
    CHECK(r.steps[0].correspondence.kind == MorphCorrespondence{}.kind);
    REQUIRE(r.series.size() == 1);
    CHECK(r.series[0].second.size() == 12);
    CHECK(std::is_sorted(r.series[0].second.begin(), r.series[0].second.end()));
    // The canonical parameters run again to the same result.
    const OperationResult again =
        run_operation(parse_operation("spectrum " + r.parameters), mesh, none);
    CHECK(again.steps[0].mesh.positions() == r.steps[0].mesh.positions());
    auto message = [&](const std::string& text) {
        try {
            run_operation(parse_operation(text), mesh, none);
        } catch (const InvalidArgument& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    CHECK(message("spectrum --k 10 --band 2:10").rfind("--band: expected LO:HI", 0) == 0);
    CHECK(message("spectrum --band 3:1").rfind("--band: expected LO:HI", 0) == 0);
    CHECK(message("spectrum --k 0").rfind("--k: expected a whole number from 1", 0) == 0);
    CHECK(message("spectrum --k 100000").find("--k: expected a whole number from 1 to") == 0);
    CHECK(message("spectrum --full --max-full 100").rfind("--full: the dense", 0) == 0);
    CHECK(message("spectrum --which middle").rfind("--which: expected one of", 0) == 0);
}
