// The only translation unit that includes Spectra (it compiles slowly); see core/spectral.h.
#include "core/spectral.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Eigenvalues>
#include <Eigen/SparseCholesky>
#include <Spectra/SymEigsShiftSolver.h>
#include <Spectra/SymEigsSolver.h>

#include "core/errors.h"

namespace trilab {

namespace {

using Triplet = Eigen::Triplet<double>;
using Ldlt = Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower, Eigen::AMDOrdering<int>>;

/// The eigenproblem in its standard form A = D K D, D = S^-½, over the free rows.
struct Problem {
    VertexIndexMap map;
    SparseMatrix K;         ///< free rows and columns
    Eigen::VectorXd S;      ///< mass diagonal
    Eigen::VectorXd d;      ///< S^-½
    Eigen::VectorXd sqrt_s; ///< S^½
    double a_max = 0;       ///< max_i K_ii / S_i (scale of the spectrum)
    double k_norm = 0;      ///< |K|_inf
    LaplacianDiagnostics diagnostics;
    Eigen::Index n() const { return K.rows(); }
};

Problem make_problem(const HalfedgeMesh& mesh, const SpectralOptions& o) {
    LaplacianOptions lo;
    lo.fix_boundary = o.fix_boundary;
    lo.mass = o.mass;
    const Laplacian lap = build_laplacian(mesh, o.op, lo);
    Problem p;
    p.diagnostics = lap.diagnostics;
    const std::size_t rows = lap.map.rows();
    std::vector<Index> reduced(rows, kInvalidIndex);
    p.map.row_of.assign(mesh.vertices_size(), kInvalidIndex);
    for (std::size_t r = 0; r < rows; ++r) {
        if (lap.fixed[r]) continue;
        const Vertex v = lap.map.vertex_of[r];
        reduced[r] = Index(p.map.vertex_of.size());
        p.map.row_of[v.idx()] = reduced[r];
        p.map.vertex_of.push_back(v);
    }
    const Eigen::Index n = Eigen::Index(p.map.rows());
    std::vector<Triplet> trip;
    trip.reserve(std::size_t(lap.K.nonZeros()) + std::size_t(n));
    for (Eigen::Index c = 0; c < lap.K.outerSize(); ++c)
        for (SparseMatrix::InnerIterator it(lap.K, c); it; ++it) {
            const Index i = reduced[std::size_t(it.row())], j = reduced[std::size_t(it.col())];
            if (i != kInvalidIndex && j != kInvalidIndex) trip.emplace_back(i, j, it.value());
        }
    for (Eigen::Index i = 0; i < n; ++i) trip.emplace_back(i, i, 0.0);  // a full diagonal
    p.K.resize(n, n);
    p.K.setFromTriplets(trip.begin(), trip.end());
    p.K.makeCompressed();
    p.S.resize(n);
    for (std::size_t r = 0; r < rows; ++r)
        if (reduced[r] != kInvalidIndex) p.S[Eigen::Index(reduced[r])] = lap.S[Eigen::Index(r)];
    p.sqrt_s = p.S.array().sqrt();
    p.d = p.sqrt_s.array().inverse();
    Eigen::VectorXd row_sum = Eigen::VectorXd::Zero(n);
    for (Eigen::Index c = 0; c < p.K.outerSize(); ++c)
        for (SparseMatrix::InnerIterator it(p.K, c); it; ++it) {
            row_sum[it.row()] += std::abs(it.value());
            if (it.row() == it.col()) p.a_max = std::max(p.a_max, it.value() / p.S[it.row()]);
        }
    p.k_norm = n > 0 ? row_sum.maxCoeff() : 0.0;
    return p;
}

/// A deterministic start vector with every component non-zero (a 64-bit LCG).
Eigen::VectorXd start_vector(Eigen::Index n, std::uint64_t seed) {
    Eigen::VectorXd v(n);
    std::uint64_t x = 0x9E3779B97F4A7C15ull ^ seed;
    for (Eigen::Index i = 0; i < n; ++i) {
        x = x * 6364136223846793005ull + 1442695040888963407ull;
        v[i] = 0.5 + double(x >> 11) * 0x1.0p-53;  // in [0.5, 1.5)
    }
    return v;
}

/// (A - σI)⁻¹ = S^½ (K - σS)⁻¹ S^½ for Spectra's SymEigsShiftSolver.
class ShiftInvertOp {
public:
    using Scalar = double;
    ShiftInvertOp(const Problem& p, Ldlt& ldlt, Progress& progress, double base, double span,
                  double expected_ops)
        : p_(p),
          ldlt_(ldlt),
          progress_(progress),
          base_(base),
          span_(span),
          expected_(expected_ops),
          a_(p.n()),
          b_(p.n()) {}
    Eigen::Index rows() const { return p_.n(); }
    Eigen::Index cols() const { return p_.n(); }
    /// Factorizes K - σS (the pattern was analysed once by the caller).
    void set_shift(double sigma) {
        SparseMatrix m = p_.K;
        for (Eigen::Index c = 0; c < m.outerSize(); ++c)
            for (SparseMatrix::InnerIterator it(m, c); it; ++it)
                if (it.row() == it.col()) it.valueRef() -= sigma * p_.S[c];
        ldlt_.factorize(m);
        ++factorizations;
        if (ldlt_.info() != Eigen::Success)
            throw Error("spectrum: the sparse LDLT factorization of K - sigma*S failed at sigma = " +
                        std::to_string(sigma));
        const Eigen::VectorXd& dd = ldlt_.vectorD();
        if (!dd.allFinite() || (dd.array() == 0.0).any())
            throw Error("spectrum: K - sigma*S is singular at sigma = " + std::to_string(sigma));
    }
    void perform_op(const double* x_in, double* y_out) const {
        progress_.check_cancelled();
        Eigen::Map<const Eigen::VectorXd> x(x_in, p_.n());
        Eigen::Map<Eigen::VectorXd> y(y_out, p_.n());
        a_ = p_.sqrt_s.cwiseProduct(x);
        b_ = ldlt_.solve(a_);
        y = p_.sqrt_s.cwiseProduct(b_);
        ++operations;
        if ((operations & 7) == 0)
            progress_.report(base_ + span_ * std::min(0.95, double(operations) / expected_),
                             "Lanczos (shift-invert)");
    }
    mutable std::size_t operations = 0;
    std::size_t factorizations = 0;

private:
    const Problem& p_;
    Ldlt& ldlt_;
    Progress& progress_;
    double base_, span_, expected_;
    mutable Eigen::VectorXd a_, b_;
};

/// A = S^-½ K S^-½ for Spectra's SymEigsSolver (largest eigenvalues).
class ProductOp {
public:
    using Scalar = double;
    ProductOp(const Problem& p, Progress& progress, double expected_ops)
        : p_(p), progress_(progress), expected_(expected_ops), a_(p.n()) {}
    Eigen::Index rows() const { return p_.n(); }
    Eigen::Index cols() const { return p_.n(); }
    void perform_op(const double* x_in, double* y_out) const {
        progress_.check_cancelled();
        Eigen::Map<const Eigen::VectorXd> x(x_in, p_.n());
        Eigen::Map<Eigen::VectorXd> y(y_out, p_.n());
        a_ = p_.d.cwiseProduct(x);
        y = p_.d.cwiseProduct(p_.K * a_);
        ++operations;
        if ((operations & 15) == 0)
            progress_.report(std::min(0.95, double(operations) / expected_), "Lanczos");
    }
    mutable std::size_t operations = 0;

private:
    const Problem& p_;
    Progress& progress_;
    double expected_;
    mutable Eigen::VectorXd a_;
};

std::string not_converged(std::size_t got, std::size_t wanted, const char* where) {
    return "spectrum: the Lanczos iteration " + std::string(where) + " converged for only " +
           std::to_string(got) + " of " + std::to_string(wanted) +
           " eigenpairs; ask for fewer frequencies (k), a smaller band_size, a larger "
           "max_iterations, or use the full method (meshes up to max_full_rows vertices)";
}

/// Eigenpairs (ascending) of the m eigenvalues of A nearest σ, in y-space.
struct Band {
    Eigen::VectorXd values;
    Eigen::MatrixXd vectors;
};

Band shift_invert_band(const Problem& p, Ldlt& ldlt, double sigma, Eigen::Index m,
                       const SpectralOptions& o, Progress& progress, double base, double span,
                       SpectralReport& report) {
    const Eigen::Index n = p.n();
    Eigen::Index ncv = std::min(n, std::max(2 * m + 1, m + 20));
    int max_it = o.max_iterations;
    for (int attempt = 0; attempt < 2; ++attempt) {
        ShiftInvertOp op(p, ldlt, progress, base, span, 2.0 * double(ncv));
        Spectra::SymEigsShiftSolver<ShiftInvertOp> eigs(op, m, ncv, sigma);
        const Eigen::VectorXd v0 = start_vector(n, std::uint64_t(report.bands));
        eigs.init(v0.data());
        eigs.compute(Spectra::SortRule::LargestMagn, max_it, o.tolerance,
                     Spectra::SortRule::SmallestAlge);
        report.factorizations += op.factorizations;
        report.operations += op.operations;
        report.restarts += std::size_t(eigs.num_iterations());
        if (eigs.info() == Spectra::CompInfo::Successful) {
            ++report.bands;
            return Band{eigs.eigenvalues(), eigs.eigenvectors()};
        }
        if (attempt == 1)
            throw Error(not_converged(std::size_t(eigs.eigenvalues().size()), std::size_t(m),
                                      ("around sigma = " + std::to_string(sigma)).c_str()));
        ncv = std::min(n, 2 * ncv);
        max_it *= 2;
    }
    return {};
}

/// The k smallest eigenpairs, band by band. Returns values (ascending) and y-space vectors.
Band smallest(const Problem& p, std::size_t k, const SpectralOptions& o, Progress& progress,
              SpectralReport& report) {
    const Eigen::Index n = p.n();
    std::size_t band = o.band_size ? o.band_size : (k <= 200 ? k : 150);
    band = std::min<std::size_t>({band, k, std::size_t(n - 1)});
    const Eigen::Index m = Eigen::Index(band);
    Ldlt ldlt;
    ldlt.analyzePattern(p.K);
    report.solver = "Spectra shift-invert Lanczos + SimplicialLDLT (AMD)";

    Band out;
    out.values.resize(Eigen::Index(k));
    out.vectors.resize(n, Eigen::Index(k));
    std::size_t have = 0;
    const double tiny = 1e-12 * std::max(p.a_max, 1e-300);
    double sigma = -1e-8 * std::max(p.a_max, 1e-300);
    double last = 0, width = 0;
    while (have < k) {
        const double base = double(have) / double(k), span = double(band) / double(k);
        Band b = shift_invert_band(p, ldlt, sigma, m, o, progress, base, span, report);
        if (have == 0) {
            const std::size_t take = std::min<std::size_t>(k, std::size_t(b.values.size()));
            out.values.head(Eigen::Index(take)) = b.values.head(Eigen::Index(take));
            out.vectors.leftCols(Eigen::Index(take)) = b.vectors.leftCols(Eigen::Index(take));
            have = take;
        } else {
            // The band must reach down to the last accepted eigenvalue, else there may be a gap.
            const double tol = 1e-6 * std::abs(last) + tiny;
            if (b.values[0] > last + tol) {
                if (sigma - last < 1e-6 * width)
                    throw Error(not_converged(have, k, "(bands do not overlap)"));
                sigma = last + 0.5 * (sigma - last);
                continue;
            }
            // Accepted vectors in the cluster at `last` (for de-duplication).
            std::vector<Eigen::Index> cluster;
            for (Eigen::Index j = Eigen::Index(have) - 1; j >= 0 && out.values[j] >= last - tol; --j)
                cluster.push_back(j);
            for (Eigen::Index i = 0; i < b.values.size() && have < k; ++i) {
                const double lambda = b.values[i];
                if (lambda < last - tol) {
                    ++report.duplicates_removed;
                    continue;
                }
                Eigen::VectorXd y = b.vectors.col(i);
                if (lambda <= last + tol) {
                    for (int pass = 0; pass < 2; ++pass)
                        for (Eigen::Index j : cluster)
                            y -= out.vectors.col(j).dot(y) * out.vectors.col(j);
                    const double norm = y.norm();
                    if (norm < 0.5) {
                        ++report.duplicates_removed;
                        continue;
                    }
                    y /= norm;
                    cluster.push_back(Eigen::Index(have));
                }
                out.values[Eigen::Index(have)] = lambda;
                out.vectors.col(Eigen::Index(have)) = y;
                ++have;
            }
        }
        progress.report(double(have) / double(k), "Lanczos (shift-invert)");
        if (have >= k) break;
        width = std::max(b.values[b.values.size() - 1] - b.values[0], tiny);
        last = out.values[Eigen::Index(have) - 1];
        sigma = last + 0.4 * width;
    }
    return out;
}

Band largest(const Problem& p, std::size_t k, const SpectralOptions& o, Progress& progress,
             SpectralReport& report) {
    const Eigen::Index n = p.n(), m = Eigen::Index(k);
    Eigen::Index ncv = std::min(n, std::max(2 * m + 1, m + 20));
    int max_it = o.max_iterations;
    report.solver = "Spectra Lanczos (sparse products)";
    for (int attempt = 0; attempt < 2; ++attempt) {
        ProductOp op(p, progress, 4.0 * double(ncv));
        Spectra::SymEigsSolver<ProductOp> eigs(op, m, ncv);
        const Eigen::VectorXd v0 = start_vector(n, 0);
        eigs.init(v0.data());
        eigs.compute(Spectra::SortRule::LargestAlge, max_it, o.tolerance,
                     Spectra::SortRule::SmallestAlge);
        report.operations += op.operations;
        report.restarts += std::size_t(eigs.num_iterations());
        if (eigs.info() == Spectra::CompInfo::Successful) {
            report.bands = 1;
            return Band{eigs.eigenvalues(), eigs.eigenvectors()};
        }
        if (attempt == 1)
            throw Error(not_converged(std::size_t(eigs.eigenvalues().size()), k, "(largest)"));
        ncv = std::min(n, 2 * ncv);
        max_it *= 2;
    }
    return {};
}

Band full(const Problem& p, std::size_t k, SpectrumEnd end, Progress& progress,
          SpectralReport& report) {
    const Eigen::Index n = p.n();
    progress.report(-1, "dense symmetric eigen solver");
    Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, n);
    for (Eigen::Index c = 0; c < p.K.outerSize(); ++c)
        for (SparseMatrix::InnerIterator it(p.K, c); it; ++it)
            a(it.row(), it.col()) = it.value() * p.d[it.row()] * p.d[it.col()];
    progress.check_cancelled();
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(a);
    if (es.info() != Eigen::Success)
        throw Error("spectrum: the dense eigen solver did not converge; use the partial method");
    report.solver = "Eigen SelfAdjointEigenSolver (dense)";
    report.bands = 1;
    const Eigen::Index keep = Eigen::Index(k);
    const Eigen::Index first = end == SpectrumEnd::Smallest ? 0 : n - keep;
    return Band{es.eigenvalues().segment(first, keep), es.eigenvectors().middleCols(first, keep)};
}

void check_band(const SpectralDecomposition& d, std::size_t lo, std::size_t hi) {
    if (d.empty())
        throw InvalidArgument("band: the decomposition is empty (decompose the mesh first)");
    if (!(lo <= hi && hi < d.size()))
        throw InvalidArgument("band: expected LO:HI with 0 <= LO <= HI < " +
                              std::to_string(d.size()) + ", got " + std::to_string(lo) + ":" +
                              std::to_string(hi));
}

}  // namespace

const char* spectral_method_name(SpectralMethod method) {
    return method == SpectralMethod::Full ? "full" : "partial";
}

const char* spectrum_end_name(SpectrumEnd end) {
    return end == SpectrumEnd::Largest ? "largest" : "smallest";
}

SpectrumEnd parse_spectrum_end(const std::string& name) {
    if (name == "smallest") return SpectrumEnd::Smallest;
    if (name == "largest") return SpectrumEnd::Largest;
    throw InvalidArgument("parse_spectrum_end: unknown end '" + name +
                          "' (expected smallest, largest)");
}

SpectralDecomposition decompose(const HalfedgeMesh& mesh, const SpectralOptions& o) {
    NullProgress none;
    return decompose(mesh, o, none);
}

SpectralDecomposition decompose(const HalfedgeMesh& mesh, const SpectralOptions& o,
                                Progress& progress) {
    const auto t0 = std::chrono::steady_clock::now();
    if (!(o.tolerance > 0 && o.tolerance < 1))
        throw InvalidArgument("tolerance: expected a number in (0, 1)");
    if (o.max_iterations < 1) throw InvalidArgument("max_iterations: expected at least 1");
    for (const Point& q : mesh.positions())
        if (!q.allFinite())
            throw InvalidArgument("spectrum: the mesh has non-finite vertex positions");

    progress.report(0, "building the operator");
    Problem p = make_problem(mesh, o);
    const std::size_t n = p.map.rows();
    if (n < 2)
        throw InvalidArgument("spectrum: the mesh has " + std::to_string(n) +
                              " vertices in the eigenproblem (at least 2 needed)");
    if (!p.S.allFinite() || (p.S.array() <= 0).any() || !std::isfinite(p.k_norm))
        throw InvalidArgument("spectrum: the operator has a non-positive or non-finite mass "
                              "(degenerate geometry)");

    SpectralDecomposition d;
    d.op = o.op;
    d.mass = o.mass;
    d.method = o.method;
    d.end = o.end;
    d.report.diagnostics = p.diagnostics;
    Band b;
    if (o.method == SpectralMethod::Full) {
        if (n > o.max_full_rows)
            throw InvalidArgument("full: the dense decomposition is limited to " +
                                  std::to_string(o.max_full_rows) +
                                  " vertices (max_full_rows) and this mesh has " +
                                  std::to_string(n) +
                                  "; use the partial method with k frequencies");
        if (o.k > n)
            throw InvalidArgument("k: expected a whole number from 0 (all) to " +
                                  std::to_string(n) + " for this mesh, got " +
                                  std::to_string(o.k));
        b = full(p, o.k == 0 ? n : o.k, o.end, progress, d.report);
    } else {
        if (o.k < 1 || o.k > n - 1)
            throw InvalidArgument("k: expected a whole number from 1 to " + std::to_string(n - 1) +
                                  " for this mesh (" + std::to_string(n) +
                                  " vertices in the eigenproblem; the full method gives all), "
                                  "got " +
                                  std::to_string(o.k));
        b = o.end == SpectrumEnd::Smallest ? smallest(p, o.k, o, progress, d.report)
                                           : largest(p, o.k, o, progress, d.report);
    }
    progress.report(0.97, "coefficients");

    // x = S^-½ y: S-orthonormal eigenvectors of K x = λ S x.
    d.eigenvalues = std::move(b.values);
    d.eigenvectors = std::move(b.vectors);
    d.eigenvectors.array().colwise() *= p.d.array();
    if (!d.eigenvalues.allFinite() || !d.eigenvectors.allFinite())
        throw Error("spectrum: the eigen solver returned non-finite values");
    const Eigen::MatrixXd x = gather_positions(mesh, p.map);
    d.coefficients = d.eigenvectors.transpose() * (p.S.asDiagonal() * x);

    // Residuals |K e - λ S e| / (|K|_inf |e|).
    const Eigen::MatrixXd ke = p.K * d.eigenvectors;
    for (Eigen::Index j = 0; j < ke.cols(); ++j) {
        const double r =
            (ke.col(j) - d.eigenvalues[j] * p.S.cwiseProduct(d.eigenvectors.col(j))).norm();
        d.report.max_residual = std::max(
            d.report.max_residual, r / (std::max(p.k_norm, 1e-300) * d.eigenvectors.col(j).norm()));
    }
    d.map = std::move(p.map);
    d.S = std::move(p.S);
    d.base_positions = mesh.positions();
    d.report.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
                      .count();
    progress.report(1, "done");
    return d;
}

Eigen::MatrixXd band_positions(const SpectralDecomposition& d, std::size_t lo, std::size_t hi) {
    check_band(d, lo, hi);
    const Eigen::Index a = Eigen::Index(lo), count = Eigen::Index(hi - lo + 1);
    return d.eigenvectors.middleCols(a, count) * d.coefficients.middleRows(a, count);
}

std::vector<Point> reconstruct_positions(const SpectralDecomposition& d, std::size_t lo,
                                         std::size_t hi) {
    const Eigen::MatrixXd x = band_positions(d, lo, hi);
    std::vector<Point> out = d.base_positions;
    for (std::size_t r = 0; r < d.map.rows(); ++r)
        out[d.map.vertex_of[r].idx()] = x.row(Eigen::Index(r)).transpose();
    return out;
}

HalfedgeMesh reconstruct(const HalfedgeMesh& mesh, const SpectralDecomposition& d,
                         std::size_t lo, std::size_t hi) {
    if (mesh.vertices_size() != d.base_positions.size())
        throw InvalidArgument("reconstruct: the mesh has " + std::to_string(mesh.vertices_size()) +
                              " vertices but the decomposition was made for " +
                              std::to_string(d.base_positions.size()));
    std::vector<Point> positions = reconstruct_positions(d, lo, hi);
    HalfedgeMesh out = mesh;
    out.positions() = std::move(positions);
    return out;
}

std::vector<double> frequency_field(const SpectralDecomposition& d, std::size_t index) {
    if (index >= d.size())
        throw InvalidArgument("frequency: expected an index below " + std::to_string(d.size()) +
                              ", got " + std::to_string(index));
    std::vector<double> out(d.base_positions.size(), std::numeric_limits<double>::quiet_NaN());
    for (std::size_t r = 0; r < d.map.rows(); ++r)
        out[d.map.vertex_of[r].idx()] = d.eigenvectors(Eigen::Index(r), Eigen::Index(index));
    return out;
}

std::vector<double> band_magnitude_field(const SpectralDecomposition& d, std::size_t lo,
                                         std::size_t hi) {
    const Eigen::MatrixXd x = band_positions(d, lo, hi);
    std::vector<double> out(d.base_positions.size(), std::numeric_limits<double>::quiet_NaN());
    for (std::size_t r = 0; r < d.map.rows(); ++r)
        out[d.map.vertex_of[r].idx()] = x.row(Eigen::Index(r)).norm();
    return out;
}

double s_orthonormality_error(const SpectralDecomposition& d) {
    if (d.empty()) return 0;
    const Eigen::MatrixXd g =
        d.eigenvectors.transpose() * (d.S.asDiagonal() * d.eigenvectors);
    return (g - Eigen::MatrixXd::Identity(g.rows(), g.cols())).cwiseAbs().maxCoeff();
}

}  // namespace trilab
