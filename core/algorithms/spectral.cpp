// Frequency decomposition (core/algorithms/spectral.h). The only translation unit that includes
// Spectra (it compiles slowly).
//
// Method. Every operator of core/algorithms/laplacian.h is L = -S⁻¹K with K symmetric positive
// semi-definite and S positive diagonal, so the reference's nonsymmetric eigenproblem
// -L·x = λ·x is the generalized symmetric problem K·x = λ·S·x: its spectrum is real and
// non-negative and its eigenvectors are S-orthonormal (Taubin 1995 for the signal-processing
// view; Vallet & Lévy 2008, "Spectral geometry processing with manifold harmonics"). With
// y = S^½·x it is the standard problem A·y = λ·y, A = S^-½·K·S^-½ (exact: S is diagonal).
//  - Partial, smallest k: shift-invert Lanczos (thick restarts, Wu & Simon 2000: equivalent to
//    ARPACK's implicitly restarted Lanczos; ThickRestartLanczos below, with ARPACK's one-pass
//    reorthogonalization; Spectra 1.0 SymEigsShiftSolver for bases of every row) on
//    (A - σI)⁻¹ with one sparse LDLᵀ of A - σI per shift (Eigen SimplicialLDLT; the rows are
//    numbered once in the approximate minimum degree order of K, so the factors need no
//    permutation, and the solves run straight over the factor's arrays). A - σI = S^-½ (K - σS)
//    S^-½ is congruent to K - σS. σ is first strictly negative (-1e-8 x the largest diagonal of A),
//    so A - σI is SPD even with several zero eigenvalues (disconnected meshes). More than
//    `band_size` frequencies are computed band by band (Vallet & Lévy 2008): each band is the
//    band_size eigenvalues nearest a shift (both sides); the next shift lies 35% of the band's
//    width above a cut in the widest gap of the band's top fifth, so consecutive bands overlap (and
//    it moves past a band that is one cluster of repeated eigenvalues); eigenvectors found twice
//    are de-duplicated by S-orthogonal projection against accepted ones of the same eigenvalue.
//    Verification: Lanczos can miss copies of a repeated eigenvalue (symmetric meshes: a
//    sphere's l(l+1) has multiplicity 2l+1), and bands could leave a gap. The number of
//    eigenvalues below a shift τ is exact by Sylvester's law of inertia: the negative pivots
//    of LDLᵀ(A - τI). Each band is checked at its own shift (its factorization gives the count
//    for free), the last band at a cut above the k-th eigenvalue (one more factorization);
//    missing ones are found by Lanczos runs with the accepted eigenvectors deflated, and a
//    count that still differs throws. Each band's vectors are orthonormalized (Cholesky QR),
//    and all k once at the end (O(rows · k²)).
//    Spectrum slicing (Campos & Roman 2012): because the counts are exact, [0, λ_k] splits
//    into slices that are independent problems. After the first band, Weyl's law (λ_i grows
//    linearly in i on a surface) extrapolated from it places a split τ near the middle of the
//    remaining eigenvalues, one factorization counts the eigenvalues below τ (when that
//    count is more than a quarter band off the middle, a secant step between the first
//    band's top and the count moves τ and a second factorization counts again: the low end
//    of a surface's spectrum is often sparser than Weyl's law says), and the two slices are
//    swept band by band on two threads at once (`threads`; 0: two when the machine has two
//    cores). Each slice is verified at its ends; should either fail (a split among close
//    eigenvalues, a repair that needed the other slice's vectors), the whole range is swept
//    once on one thread. The results do not depend on thread timing.
//    Large meshes (SpectralOptions::solver; Auto from kBlockMinRows rows): there a sparse
//    factorization costs more than the Lanczos bases, so all k are computed at one negative
//    shift by block Lanczos (block_shift_invert(): 8 vectors a block, thick restarts, full
//    reorthogonalization as matrix products) and verified by one count at a cut above the
//    k-th; a run that does not converge or whose count differs falls back to the bands.
//  - Partial, largest k: Lanczos on A itself (sparse products only), checked the same way.
//  - Full: Eigen's dense SelfAdjointEigenSolver on A, refused above max_full_rows (default
//    5,000) rows: O(n²) memory and O(n³) time. Also refused (InvalidArgument, with the
//    numbers) when its peak, two n x n matrices of doubles (16·n² bytes), exceeds the memory
//    available now (available_memory_bytes(), core/system_memory.h).
// The start vector is deterministic, so the same input gives the same output. A run that
// does not converge is retried once with a larger Krylov space, then throws an Error that
// says what to change.
//
// Rows and boundaries. The eigenproblem's rows are the Laplacian's free rows: every live,
// non-isolated vertex with the default free (Neumann) boundary, which is the natural choice
// for a shape's spectrum (boundary vertices move with their band); fix_boundary = true gives
// the Dirichlet problem on the interior (boundary vertices keep their positions, like
// fairing). Isolated vertices (the shared bunny has 1,113) and fixed rows are not in the
// problem and keep their positions in every reconstruction.
//
// Coefficients α_k = ⟨X, e_k⟩_S = e_kᵀ·S·X (k x 3); the reconstruction from a band
// [lo, hi] of the computed frequencies is Σ_{lo<=k<=hi} e_k·α_kᵀ. With every frequency of a
// full decomposition it returns the mesh (to rounding: ~1e-12 relative).
//
// Errors: InvalidArgument naming the option (k, band, max_full_rows, ...) before any work;
// Error when the solver fails (with what to change); Cancelled from the progress. The input
// mesh is never modified. A degenerate mesh is refused up front (InvalidArgument "the mesh is
// degenerate: ..."): surface area below 1e-12 of the bounding-box diagonal squared (except for
// the purely combinatorial umbrella operator with its valence mass), a vertex mass below 1e-12
// of the largest, or a zero K. Every loop is bounded (bands, restarts, repairs): a spectrum
// the bands cannot resolve ends in an Error, never in an endless iteration.
// Complexity: building the operator O(V + F); per shift one sparse factorization (for
// surfaces about O(V^1.5)) and one pair of triangular solves per Lanczos step; the Lanczos
// basis costs O(V·ncv²) per restart with ncv ≈ 2·band + 1, so O(V·k·band) in all; the final
// orthonormalization O(V·k²). Memory O(V·k) (two slices: two factors and two Lanczos bases at
// once). Figures: README.md, Benchmarks.
#include "core/algorithms/spectral.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <Spectra/SymEigsShiftSolver.h>
#include <Spectra/SymEigsSolver.h>
#include <Eigen/Eigenvalues>
#include <Eigen/OrderingMethods>
#include <Eigen/QR>
#include <Eigen/SparseCholesky>

#include "core/algorithms/selection.h"
#include "core/errors.h"
#include "core/geometry.h"
#include "core/number_text.h"
#include "core/parallel.h"
#include "core/system_memory.h"
#include "core/two_threads.h"

namespace trilab {

namespace {

using Triplet = Eigen::Triplet<double>;
/// The problem's rows are already in a fill-reducing (AMD) order, so the factorizations need
/// no permutation of their own (make_problem()).
using Ldlt = Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower, Eigen::NaturalOrdering<int>>;

/// Vectors per block of the block Lanczos method (block_shift_invert()).
constexpr Eigen::Index kLanczosBlock = 8;

/// Below these (relative) sizes the eigenproblem is refused as degenerate.
constexpr double kDegenerateAreaRatio = 1e-12;  ///< surface area / bbox diagonal²
constexpr double kDegenerateMassRatio = 1e-12;  ///< smallest mass / largest mass

/// A number in short scientific notation (std::to_string prints 1e-19 as 0.000000).
std::string sci(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3g", x);
    return buf;
}

double ms_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

/// The eigenproblem in its standard form A = D K D, D = S^-½, over the free rows, which are
/// numbered in the approximate-minimum-degree order of K (Amestoy, Davis & Duff 1996) so
/// that the LDLᵀ factors of A - σI have little fill and need no permutation.
struct Problem {
    VertexIndexMap map;
    SparseMatrix K;          ///< free rows and columns
    SparseMatrix A;          ///< D K D, the same pattern (with a full diagonal)
    Eigen::VectorXd S;       ///< mass diagonal
    Eigen::VectorXd d;       ///< S^-½
    Eigen::VectorXd sqrt_s;  ///< S^½
    double a_max = 0;        ///< max_i K_ii / S_i (scale of the spectrum)
    double k_norm = 0;       ///< |K|_inf
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
    // Free rows, first in storage order, then renumbered in the AMD order of their pattern.
    std::vector<Index> reduced(rows, kInvalidIndex);
    Index n_free = 0;
    for (std::size_t r = 0; r < rows; ++r)
        if (!lap.fixed[r]) reduced[r] = n_free++;
    const Eigen::Index n = Eigen::Index(n_free);
    std::vector<Triplet> trip;
    trip.reserve(std::size_t(lap.K.nonZeros()) + std::size_t(n));
    for (Eigen::Index c = 0; c < lap.K.outerSize(); ++c)
        for (SparseMatrix::InnerIterator it(lap.K, c); it; ++it) {
            const Index i = reduced[std::size_t(it.row())], j = reduced[std::size_t(it.col())];
            if (i != kInvalidIndex && j != kInvalidIndex) trip.emplace_back(i, j, it.value());
        }
    for (Eigen::Index i = 0; i < n; ++i) trip.emplace_back(i, i, 0.0);  // a full diagonal
    SparseMatrix storage_order(n, n);
    storage_order.setFromTriplets(trip.begin(), trip.end());
    Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> elimination;  // [new] = old
    Eigen::AMDOrdering<int>()(storage_order, elimination);
    std::vector<Index> new_of_old(static_cast<std::size_t>(n));
    for (Eigen::Index k = 0; k < n; ++k)
        new_of_old[std::size_t(elimination.indices()[k])] = Index(k);
    for (Triplet& t : trip)
        t = Triplet(Eigen::Index(new_of_old[std::size_t(t.row())]),
                    Eigen::Index(new_of_old[std::size_t(t.col())]), t.value());
    p.K.resize(n, n);
    p.K.setFromTriplets(trip.begin(), trip.end());
    p.K.makeCompressed();
    p.map.row_of.assign(mesh.vertices_size(), kInvalidIndex);
    p.map.vertex_of.resize(std::size_t(n));
    p.S.resize(n);
    for (std::size_t r = 0; r < rows; ++r)
        if (reduced[r] != kInvalidIndex) {
            const Index row = new_of_old[std::size_t(reduced[r])];
            const Vertex v = lap.map.vertex_of[r];
            p.map.vertex_of[std::size_t(row)] = v;
            p.map.row_of[v.idx()] = row;
            p.S[Eigen::Index(row)] = lap.S[Eigen::Index(r)];
        }
    p.sqrt_s = p.S.array().sqrt();
    p.d = p.sqrt_s.array().inverse();
    p.A = p.K;
    for (Eigen::Index c = 0; c < p.A.outerSize(); ++c)
        for (SparseMatrix::InnerIterator it(p.A, c); it; ++it)
            it.valueRef() *= p.d[it.row()] * p.d[c];
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

SparseMatrix shifted(const Problem& p, double sigma);
void ldlt_solve_in_place(const Ldlt& ldlt, double* z);

/// (A - σI)⁻¹ for Spectra's SymEigsShiftSolver, by the LDLᵀ factors of A - σI.
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
          expected_(expected_ops) {}
    Eigen::Index rows() const { return p_.n(); }
    Eigen::Index cols() const { return p_.n(); }
    /// Factorizes A - σI (the pattern was analysed once by the caller).
    void set_shift(double sigma) {
        const SparseMatrix m = shifted(p_, sigma);
        const auto t0 = std::chrono::steady_clock::now();
        ldlt_.factorize(m);
        factor_ms += ms_since(t0);
        ++factorizations;
        if (ldlt_.info() != Eigen::Success)
            throw Error(
                "spectrum: the sparse LDLT factorization of K - sigma*S failed at sigma = " +
                number_text(sigma));
        const Eigen::VectorXd& dd = ldlt_.vectorD();
        if (!dd.allFinite() || (dd.array() == 0.0).any())
            throw Error("spectrum: K - sigma*S is singular at sigma = " + number_text(sigma));
    }
    void perform_op(const double* x_in, double* y_out) const {
        progress_.check_cancelled();
        const auto t0 = std::chrono::steady_clock::now();
        Eigen::Map<const Eigen::VectorXd> x(x_in, p_.n());
        Eigen::Map<Eigen::VectorXd> y(y_out, p_.n());
        y = x;
        ldlt_solve_in_place(ldlt_, y.data());
        solve_ms += ms_since(t0);
        ++operations;
        if ((operations & 7) == 0)
            progress_.report(
                std::min(0.99, base_ + span_ * std::min(0.95, double(operations) / expected_)),
                "Lanczos (shift-invert)");
    }
    mutable std::size_t operations = 0;
    mutable double solve_ms = 0;
    std::size_t factorizations = 0;
    double factor_ms = 0;

private:
    const Problem& p_;
    Ldlt& ldlt_;
    Progress& progress_;
    double base_, span_, expected_;
};

/// A = S^-½ K S^-½ for Spectra's SymEigsSolver (largest eigenvalues).
class ProductOp {
public:
    using Scalar = double;
    ProductOp(const Problem& p, Progress& progress, double expected_ops)
        : p_(p), progress_(progress), expected_(expected_ops) {}
    Eigen::Index rows() const { return p_.n(); }
    Eigen::Index cols() const { return p_.n(); }
    void perform_op(const double* x_in, double* y_out) const {
        progress_.check_cancelled();
        Eigen::Map<const Eigen::VectorXd> x(x_in, p_.n());
        Eigen::Map<Eigen::VectorXd> y(y_out, p_.n());
        const auto t0 = std::chrono::steady_clock::now();
        y.noalias() = p_.A * x;
        solve_ms += ms_since(t0);
        ++operations;
        if ((operations & 15) == 0)
            progress_.report(std::min(0.95, double(operations) / expected_), "Lanczos");
    }
    mutable std::size_t operations = 0;
    mutable double solve_ms = 0;

private:
    const Problem& p_;
    Progress& progress_;
    double expected_;
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

/// Thick-restart Lanczos (Wu & Simon 2000, "Thick-restart Lanczos method for large symmetric
/// eigenvalue problems"; the symmetric Krylov–Schur method of Stewart 2001) for the `nev`
/// eigenvalues θ of largest magnitude of the symmetric operator `op` ((A - σI)⁻¹: the
/// eigenvalues of A nearest σ, both sides), with a basis of `ncv` vectors. It computes what
/// Spectra's SymEigsShiftSolver computes (the same Ritz values, the same acceptance test:
/// |β·s_last| <= tolerance · max(eps^⅔, |θ|)) with less memory traffic: each step
/// orthogonalizes against the basis once, as ARPACK does (classical Gram–Schmidt, repeated
/// only when it removed more than 1 - 1/√2 of the vector: Daniel, Gragg, Kaufman & Stewart
/// 1976), where Spectra's Lanczos repeats it until |Vᵀf| <= eps·|f| (two to five passes over
/// the basis per step, the larger part of a band's time). The projection is kept as the
/// tridiagonal (plus the restart's arrow); the rest of the coefficients are rounding.
class ThickRestartLanczos {
public:
    ThickRestartLanczos(const ShiftInvertOp& op, Eigen::Index nev, Eigen::Index ncv, double tol)
        : op_(op),
          n_(op.rows()),
          nev_(nev),
          m_(ncv),
          tol_(tol),
          v_(n_, ncv + 1),
          t_(Eigen::MatrixXd::Zero(ncv, ncv)) {}
    /// Runs up to `max_restarts` cycles from v0; true when every wanted pair converged.
    bool run(const Eigen::VectorXd& v0, int max_restarts) {
        v_.col(0) = v0 / v0.norm();
        Eigen::Index kept = 0;
        for (restarts = 0; restarts < std::max(1, max_restarts); ++restarts) {
            extend(kept);
            if (ritz()) return true;
            kept = restart();
        }
        return false;
    }
    /// The converged eigenvalues λ = σ + 1/θ (ascending) and their vectors (after run()).
    Band band(double sigma) const {
        std::vector<Eigen::Index> order(wanted_.begin(), wanted_.end());
        std::sort(order.begin(), order.end(), [&](Eigen::Index a, Eigen::Index b) {
            return 1.0 / theta_[a] < 1.0 / theta_[b];
        });
        Band out;
        out.values.resize(nev_);
        Eigen::MatrixXd sel(m_, nev_);
        for (Eigen::Index i = 0; i < nev_; ++i) {
            out.values[i] = sigma + 1.0 / theta_[order[std::size_t(i)]];
            sel.col(i) = s_.col(order[std::size_t(i)]);
        }
        out.vectors.noalias() = v_.leftCols(m_) * sel;
        return out;
    }
    int restarts = 0;
    /// The wanted Ritz pairs that had converged at the last Rayleigh–Ritz.
    std::size_t converged() const { return converged_; }

private:
    /// Lanczos steps from column `from` (the first new one) to the basis size; the residual
    /// ends normalized in column m with its norm in beta_.
    void extend(Eigen::Index from) {
        Eigen::VectorXd w(n_), h;
        for (Eigen::Index j = from; j < m_; ++j) {
            op_.perform_op(v_.col(j).data(), w.data());
            // The three-term recurrence first (cheap), so that the full projection below
            // removes only what rounding left and its repetition is rarely needed.
            const double alpha = v_.col(j).dot(w);
            w -= alpha * v_.col(j);
            if (j > from) w -= t_(j, j - 1) * v_.col(j - 1);
            const double before = w.norm();
            h.noalias() = v_.leftCols(j + 1).transpose() * w;
            w.noalias() -= v_.leftCols(j + 1) * h;
            double beta = w.norm();
            if (beta < 0.7071067811865476 * before) {  // DGKS: once more
                const Eigen::VectorXd c = v_.leftCols(j + 1).transpose() * w;
                w.noalias() -= v_.leftCols(j + 1) * c;
                h += c;
                beta = w.norm();
            }
            t_(j, j) = alpha + h[j];
            if (!(beta > 1e-13 * std::max(std::abs(alpha) + before, 1e-300))) {
                // An invariant subspace: go on from a new direction orthogonal to the basis
                // (the coupling is zero).
                w = start_vector(n_, 4099 + std::uint64_t(j));
                for (int pass = 0; pass < 2; ++pass)
                    w -= v_.leftCols(j + 1) * (v_.leftCols(j + 1).transpose() * w);
                beta = 0;
                v_.col(j + 1) = w / w.norm();
            } else {
                v_.col(j + 1) = w / beta;
            }
            if (j + 1 < m_) t_(j + 1, j) = t_(j, j + 1) = beta;
            beta_ = beta;
        }
    }
    /// Rayleigh–Ritz on T; true when the nev wanted Ritz pairs have converged.
    bool ritz() {
        Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(t_);
        if (es.info() != Eigen::Success)
            throw Error("spectrum: the Lanczos projection's eigen solver failed");
        theta_ = es.eigenvalues();
        s_ = es.eigenvectors();
        std::vector<Eigen::Index> order(static_cast<std::size_t>(m_));
        for (Eigen::Index i = 0; i < m_; ++i) order[std::size_t(i)] = i;
        std::stable_sort(order.begin(), order.end(), [&](Eigen::Index a, Eigen::Index b) {
            return std::abs(theta_[a]) > std::abs(theta_[b]);
        });
        by_magnitude_ = order;
        wanted_.assign(order.begin(), order.begin() + nev_);
        const double eps23 = std::pow(std::numeric_limits<double>::epsilon(), 2.0 / 3.0);
        converged_ = 0;
        for (Eigen::Index i : wanted_)
            if (std::abs(beta_ * s_(m_ - 1, i)) <= tol_ * std::max(eps23, std::abs(theta_[i])))
                ++converged_;
        return converged_ == std::size_t(nev_);
    }
    /// Keeps the Ritz vectors of the largest |θ| (nev plus up to half the rest, as many more
    /// as have converged: ARPACK's choice), the residual after them, and their arrow
    /// projection. Returns the number kept.
    Eigen::Index restart() {
        const Eigen::Index keep = std::min(
            m_ - 1, nev_ + std::min<Eigen::Index>(Eigen::Index(converged_), (m_ - nev_) / 2));
        Eigen::MatrixXd sel(m_, keep);
        Eigen::VectorXd diag(keep), arrow(keep);
        for (Eigen::Index i = 0; i < keep; ++i) {
            const Eigen::Index c = by_magnitude_[std::size_t(i)];
            sel.col(i) = s_.col(c);
            diag[i] = theta_[c];
            arrow[i] = beta_ * s_(m_ - 1, c);
        }
        const Eigen::MatrixXd y = v_.leftCols(m_) * sel;
        v_.leftCols(keep) = y;
        v_.col(keep) = v_.col(m_);
        t_.setZero();
        t_.topLeftCorner(keep, keep).diagonal() = diag;
        t_.block(keep, 0, 1, keep) = arrow.transpose();
        t_.block(0, keep, keep, 1) = arrow;
        return keep;
    }

    const ShiftInvertOp& op_;
    Eigen::Index n_, nev_, m_;
    double tol_, beta_ = 0;
    Eigen::MatrixXd v_, t_, s_;
    Eigen::VectorXd theta_;
    std::vector<Eigen::Index> by_magnitude_, wanted_;
    std::size_t converged_ = 0;
};

Band shift_invert_band(const Problem& p, Ldlt& ldlt, double sigma, Eigen::Index m,
                       const SpectralOptions& o, Progress& progress, double base, double span,
                       SpectralReport& report) {
    const Eigen::Index n = p.n();
    const Eigen::Index wanted = Eigen::Index(std::ceil(o.krylov_factor * double(m))) + 1;
    Eigen::Index ncv = std::min(n, std::max(wanted, m + 20));
    int max_it = o.max_iterations;
    for (int attempt = 0; attempt < 2; ++attempt) {
        progress.check_cancelled();
        ShiftInvertOp op(p, ldlt, progress, base, span, 2.0 * double(ncv));
        const Eigen::VectorXd v0 = start_vector(n, std::uint64_t(report.bands));
        bool ok = false;
        std::size_t got = 0;
        Band band;
        if (ncv + 1 < n) {        // the thick-restart Lanczos above
            op.set_shift(sigma);  // (Spectra's solver sets it itself)
            ThickRestartLanczos lanczos(op, m, ncv, o.tolerance);
            ok = lanczos.run(v0, max_it);
            report.restarts += std::size_t(lanczos.restarts);
            got = lanczos.converged();
            if (ok) band = lanczos.band(sigma);
        } else {  // a basis of every row: Spectra (small problems)
            Spectra::SymEigsShiftSolver<ShiftInvertOp> eigs(op, m, ncv, sigma);
            eigs.init(v0.data());
            eigs.compute(Spectra::SortRule::LargestMagn, max_it, o.tolerance,
                         Spectra::SortRule::SmallestAlge);
            report.restarts += std::size_t(eigs.num_iterations());
            ok = eigs.info() == Spectra::CompInfo::Successful;
            got = std::size_t(eigs.eigenvalues().size());
            if (ok) band = Band{eigs.eigenvalues(), eigs.eigenvectors()};
        }
        report.factorizations += op.factorizations;
        report.operations += op.operations;
        report.factor_ms += op.factor_ms;
        report.solve_ms += op.solve_ms;
        if (ok) {
            ++report.bands;
            return band;
        }
        if (attempt == 1)
            throw Error(not_converged(got, std::size_t(m),
                                      ("around sigma = " + number_text(sigma)).c_str()));
        ncv = std::min(n, 2 * ncv);
        max_it *= 2;
    }
    return {};
}

/// A - σI = D (K - σS) D (same pattern as A, whose diagonal is stored): congruent to K - σS,
/// so it has the same inertia.
SparseMatrix shifted(const Problem& p, double sigma) {
    SparseMatrix m = p.A;
    for (Eigen::Index c = 0; c < m.outerSize(); ++c)
        for (SparseMatrix::InnerIterator it(m, c); it; ++it)
            if (it.row() == it.col()) it.valueRef() -= sigma;
    return m;
}

/// z <- (LDLᵀ)⁻¹ z in place, straight over the factor's arrays (L unit lower triangular,
/// column-major, without its diagonal; no permutation: see Ldlt).
void ldlt_solve_in_place(const Ldlt& ldlt, double* z) {
    const SparseMatrix& l = ldlt.matrixL().nestedExpression();
    const Eigen::Index n = l.cols();
    const int* outer = l.outerIndexPtr();
    const int* nnz = l.innerNonZeroPtr();
    const int* inner = l.innerIndexPtr();
    const double* value = l.valuePtr();
    const auto end = [&](Eigen::Index j) { return nnz ? outer[j] + nnz[j] : outer[j + 1]; };
    for (Eigen::Index j = 0; j < n; ++j) {  // L·w = z, by columns
        const double zj = z[j];
        if (zj != 0.0)
            for (int k = outer[j]; k < end(j); ++k) z[inner[k]] -= value[k] * zj;
    }
    const Eigen::VectorXd& d = ldlt.vectorD();
    for (Eigen::Index j = 0; j < n; ++j) z[j] /= d[j];
    for (Eigen::Index j = n - 1; j >= 0; --j) {  // Lᵀ·x = w, by rows of Lᵀ
        double acc = z[j];
        for (int k = outer[j]; k < end(j); ++k) acc -= value[k] * z[inner[k]];
        z[j] = acc;
    }
}

/// The number of eigenvalues of K x = λ S x below τ: the negative pivots of the LDLᵀ
/// factorization of A - τI, congruent to K - τS (Sylvester's law of inertia).
std::size_t count_below(const Problem& p, Ldlt& ldlt, double tau, SpectralReport& report) {
    const auto t0 = std::chrono::steady_clock::now();
    ldlt.factorize(shifted(p, tau));
    report.factor_ms += ms_since(t0);
    ++report.factorizations;
    if (ldlt.info() != Eigen::Success || !ldlt.vectorD().allFinite())
        throw Error("spectrum: the LDLT factorization for the eigenvalue count failed at " +
                    std::to_string(tau));
    return std::size_t((ldlt.vectorD().array() < 0.0).count());
}

/// x -> P·f(P·x) with P = I - Q·Qᵀ: an operator with the columns of Q deflated (sent to 0).
class DeflatedOp {
public:
    using Scalar = double;
    using Apply = std::function<void(const Eigen::VectorXd&, Eigen::VectorXd&)>;
    DeflatedOp(Eigen::Index n, Apply f, const Eigen::MatrixXd& q, Progress& progress)
        : n_(n), f_(std::move(f)), q_(q), progress_(progress), a_(n), b_(n) {}
    Eigen::Index rows() const { return n_; }
    Eigen::Index cols() const { return n_; }
    void perform_op(const double* x_in, double* y_out) const {
        progress_.check_cancelled();
        Eigen::Map<const Eigen::VectorXd> x(x_in, n_);
        Eigen::Map<Eigen::VectorXd> y(y_out, n_);
        a_ = x - q_ * (q_.transpose() * x);
        f_(a_, b_);
        y = b_ - q_ * (q_.transpose() * b_);
        ++operations;
    }
    mutable std::size_t operations = 0;

private:
    Eigen::Index n_;
    Apply f_;
    const Eigen::MatrixXd& q_;
    Progress& progress_;
    mutable Eigen::VectorXd a_, b_;
};

/// One repair run: the `nev` eigenpairs of the symmetric operator `apply` with the columns of
/// q deflated, the largest by `rule` (a Krylov space of max(2·nev + 1, nev + 20)). Returns
/// false when there is no room for it or it did not converge.
bool deflated_eigenpairs(Eigen::Index n, DeflatedOp::Apply apply, const Eigen::MatrixXd& q,
                         Eigen::Index nev, Spectra::SortRule rule, int attempt,
                         const SpectralOptions& o, Progress& progress, SpectralReport& report,
                         Eigen::VectorXd& values, Eigen::MatrixXd& vectors) {
    nev = std::min<Eigen::Index>(nev, n - q.cols() - 1);
    const Eigen::Index ncv = std::min<Eigen::Index>(n - q.cols(), std::max(2 * nev + 1, nev + 20));
    if (nev < 1 || ncv <= nev) return false;
    DeflatedOp op(n, std::move(apply), q, progress);
    Spectra::SymEigsSolver<DeflatedOp> eigs(op, nev, ncv);
    const Eigen::VectorXd v0 = start_vector(n, 1000 + std::uint64_t(attempt));
    eigs.init(v0.data());
    eigs.compute(rule, o.max_iterations, o.tolerance, rule);
    report.operations += op.operations;
    report.restarts += std::size_t(eigs.num_iterations());
    ++report.repairs;
    if (eigs.info() != Spectra::CompInfo::Successful) return false;
    values = eigs.eigenvalues();
    vectors = eigs.eigenvectors();
    return true;
}

/// Orthonormalizes the columns of y in place (Cholesky QR): removes the rounding that
/// shift-invert leaves in the Ritz vectors (mostly along near-null directions). One pass is
/// enough for columns that are orthonormal to ~1e-8 already (the error is cond(y)² · eps).
void orthonormalize(Eigen::MatrixXd& y) {
    Eigen::MatrixXd g(y.cols(), y.cols());
    g.setZero();
    g.selfadjointView<Eigen::Lower>().rankUpdate(y.transpose());
    Eigen::LLT<Eigen::MatrixXd> llt(g);
    if (llt.info() != Eigen::Success) return;  // dependent columns: left to the caller
    y = llt.matrixU().solve<Eigen::OnTheRight>(y);
}

/// orthonormalize() over two fixed halves of the rows, on two threads when `two`: the Gram
/// matrix is the sum of the halves' (in that order, on one thread or two alike, so the bits
/// do not depend on `two`), and the triangular solve runs on each half. For the final
/// O(rows · k²) pass over all k vectors, which would otherwise run alone after the slices.
void orthonormalize_halves(Eigen::MatrixXd& y, bool two) {
    const Eigen::Index n = y.rows(), c = y.cols(), half = n / 2;
    Eigen::MatrixXd g[2];
    on_two_threads(two, [&](int i) {
        const Eigen::Index r0 = i ? half : 0, rows = i ? n - half : half;
        g[i].setZero(c, c);
        g[i].selfadjointView<Eigen::Lower>().rankUpdate(y.middleRows(r0, rows).transpose());
    });
    g[0] += g[1];
    Eigen::LLT<Eigen::MatrixXd> llt(g[0]);
    if (llt.info() != Eigen::Success) return;  // dependent columns: left to the caller
    on_two_threads(two, [&](int i) {
        const Eigen::Index r0 = i ? half : 0, rows = i ? n - half : half;
        y.middleRows(r0, rows) = llt.matrixU().solve<Eigen::OnTheRight>(y.middleRows(r0, rows));
    });
}

/// The accepted eigenpairs (unsorted), with the de-duplication of new candidates.
struct Accepted {
    std::vector<double> values;
    Eigen::MatrixXd vectors;  ///< n x capacity; the first values.size() columns are used
    std::size_t duplicates = 0;

    std::size_t size() const { return values.size(); }
    std::size_t count_below(double tau) const {
        return std::size_t(
            std::count_if(values.begin(), values.end(), [tau](double v) { return v < tau; }));
    }
    /// Adds (λ, y) unless y lies (to 1/2) in the span of accepted vectors with λ_j within
    /// `window` of λ (the same eigenpair found twice, e.g. in the overlap of two bands).
    /// y is first made orthogonal to those and to the vectors of earlier bands (index below
    /// `first_new`) with λ_j within 1% of λ: the Ritz vectors of two bands are orthogonal
    /// only to (residual / gap), which is largest for close eigenvalues.
    bool add(double lambda, Eigen::VectorXd y, double window, std::size_t first_new = 0) {
        const double wide = std::max(window, 1e-2 * std::abs(lambda));
        std::vector<Eigen::Index> near;
        for (std::size_t j = 0; j < values.size(); ++j) {
            const double gap = std::abs(values[j] - lambda);
            if (gap <= window || (j < first_new && gap <= wide)) near.push_back(Eigen::Index(j));
        }
        for (int pass = 0; pass < 2; ++pass)
            for (Eigen::Index j : near) y -= vectors.col(j).dot(y) * vectors.col(j);
        const double norm = y.norm();
        if (!(norm >= 0.5)) {
            ++duplicates;
            return false;
        }
        if (Eigen::Index(values.size()) == vectors.cols())
            vectors.conservativeResize(Eigen::NoChange, vectors.cols() + vectors.cols() / 2 + 8);
        vectors.col(Eigen::Index(values.size())) = y / norm;
        values.push_back(lambda);
        return true;
    }
};

/// Midpoint of the widest gap between consecutive sorted values in [from, to).
double widest_gap_midpoint(std::vector<double> v, std::size_t from, std::size_t to) {
    std::sort(v.begin(), v.end());
    double best = -1, tau = v.back();
    for (std::size_t j = from; j + 1 < std::min(to, v.size()); ++j)
        if (v[j + 1] - v[j] > best) {
            best = v[j + 1] - v[j];
            tau = 0.5 * (v[j] + v[j + 1]);
        }
    return tau;
}

/// A Progress for a worker thread: it never reports (the caller's thread does), and it
/// cancels when the user cancels or when another slice failed.
class WorkerProgress final : public Progress {
public:
    WorkerProgress(const Progress& user, const std::atomic<bool>& stop)
        : user_(user), stop_(stop) {}
    void report(double, const char*) override {}
    bool cancel_requested() const override { return stop_.load() || user_.cancel_requested(); }

private:
    const Progress& user_;
    const std::atomic<bool>& stop_;
};

/// One slice [lower, upper) of the spectrum, swept band by band upward from a first shift.
/// The number of eigenvalues below either end is exact (inertia), so slices are independent
/// problems and can run at once (spectrum slicing: Campos & Roman 2012, "Strategies for
/// spectrum slicing based on restarted Lanczos methods"). Every band is verified by an
/// eigenvalue count and missed eigenvalues (repeated ones, which Lanczos may find only once)
/// are recovered by a deflated run; see the comment at the top of this file. The slice
/// without an upper end runs until k eigenvalues lie below its last cut.
class Slice {
public:
    Slice(const Problem& p, const SpectralOptions& o, std::size_t k, std::size_t band,
          Progress& progress, SpectralReport& report, double lower, std::size_t below_lower,
          double first_sigma)
        : p_(p),
          o_(o),
          k_(k),
          band_(band),
          progress_(progress),
          report_(report),
          tiny_(1e-12 * std::max(p.a_max, 1e-300)),
          sigma_(first_sigma),
          verified_(lower),
          below_lower_(below_lower),
          // Every band moves the shift up (checked below) and normally verifies about half a
          // band of new eigenvalues; far more bands than k / band mean a spectrum this method
          // cannot resolve, so the sweep is bounded instead of trusting it to end.
          max_bands_(8 * ((k + band - 1) / band) + 16) {
        ldlt_.analyzePattern(p.A);
        counter_.analyzePattern(p.A);
        acc.vectors.resize(p.n(),
                           Eigen::Index(std::min<std::size_t>(k + band, std::size_t(p.n()))));
    }
    /// Sets the number of eigenvalues per band from the next band on.
    void set_band(std::size_t band) { band_ = band; }
    /// Ends the slice at `upper`, below which `below_upper` eigenvalues lie in all.
    void set_upper(double upper, std::size_t below_upper) {
        upper_ = upper;
        below_upper_ = below_upper;
    }
    /// The eigenvalues found so far plus those below the slice.
    std::size_t total() const { return below_lower_ + acc.size(); }
    /// Progress also counts what `other` (a slice on another thread) found.
    void count_progress_of(const Slice& other) { other_ = &other.found_; }
    /// Runs one band; false once the slice is complete.
    bool step();
    void run() {
        while (step()) {
        }
    }
    /// The accepted eigenpairs: every eigenvalue in [lower, upper) (or up to the k-th), and
    /// possibly some above.
    Accepted acc;

private:
    double window(double lambda) const { return 1e-6 * std::abs(lambda) + tiny_; }
    double fraction_done(std::size_t found_here) const {
        const std::size_t other = other_ ? other_->load() : 0;
        return std::min(1.0, double(found_here + other) / double(k_));
    }
    void repair(double tau, std::size_t expected, double lo_b);

    const Problem& p_;
    const SpectralOptions& o_;
    std::size_t k_, band_;
    Progress& progress_;
    SpectralReport& report_;
    Ldlt ldlt_, counter_;
    double tiny_, sigma_;
    double verified_;  ///< every eigenvalue in [lower, verified) has been accepted
    std::size_t below_lower_;
    double upper_ = std::numeric_limits<double>::infinity();
    std::size_t below_upper_ = 0;
    std::size_t max_bands_, bands_run_ = 0;
    bool done_ = false;
    std::atomic<std::size_t> found_{0};  ///< accepted eigenvalues, for the other thread
    const std::atomic<std::size_t>* other_ = nullptr;
};

bool Slice::step() {
    if (done_) return false;
    const Eigen::Index n = p_.n(), m = Eigen::Index(band_);
    progress_.check_cancelled();
    if (++bands_run_ > max_bands_)
        throw Error("spectrum: the band-by-band iteration did not reach " + std::to_string(k_) +
                    " frequencies in " + std::to_string(max_bands_) +
                    " bands (badly scaled or degenerate operator); ask for fewer "
                    "frequencies (k), a larger band_size, or use the full method (meshes up "
                    "to max_full_rows vertices)");
    const double base = fraction_done(total());
    const double span = std::min(1.0, double(band_) / double(k_));
    Band b = shift_invert_band(p_, ldlt_, sigma_, m, o_, progress_, base, span, report_);
    orthonormalize(b.vectors);
    const double lo_b = b.values[0], hi_b = b.values[b.values.size() - 1];
    const std::size_t before = acc.size();
    for (Eigen::Index i = 0; i < b.values.size(); ++i) {
        if (b.values[i] < verified_) {
            ++acc.duplicates;
            continue;
        }
        acc.add(b.values[i], b.vectors.col(i), window(b.values[i]), before);
    }
    if (acc.size() == 0)
        throw Error("spectrum: a band around sigma = " + sci(sigma_) +
                    " found no eigenvalue above " + sci(verified_) +
                    " (badly scaled or degenerate operator); use the full method (meshes up to "
                    "max_full_rows vertices)");
    // A cut in the widest gap of the top fifth of this band (or, once k are there, between
    // the k-th and the rest). A cut inside a cluster of (nearly) equal eigenvalues would
    // make a count ambiguous: without a clear gap, cut just above the largest found value.
    std::vector<double> sorted = acc.values;
    std::sort(sorted.begin(), sorted.end());
    const bool at_upper = std::isfinite(upper_) && (hi_b >= upper_ || sigma_ >= upper_);
    const bool at_k = !std::isfinite(upper_) && (total() > k_ || (total() == k_ && band_ >= k_));
    std::size_t from = at_k ? k_ - 1 - below_lower_ : before + 4 * (acc.size() - before) / 5;
    from = std::min(from, sorted.size() - 1);
    const double width_b = std::max(hi_b - lo_b, tiny_);
    double cut = sorted.back() + 1e-3 * width_b + tiny_;
    if (acc.size() > 1) {
        const double mid = widest_gap_midpoint(sorted, from, sorted.size());
        const auto above_mid = std::upper_bound(sorted.begin(), sorted.end(), mid);
        if (above_mid != sorted.begin() && above_mid != sorted.end() &&
            *above_mid - *(above_mid - 1) > 1e-3 * width_b)
            cut = mid;
    }
    // Verify up to τ: at the slice's upper end, whose count is known; for the k-th the cut (one
    // more factorization); otherwise the band's own shift, whose factorization counts the
    // eigenvalues below it for free (the first band's negative shift has none below it).
    double tau = sigma_;
    std::size_t expected = below_lower_;
    if (at_upper) {
        tau = upper_;
        expected = below_upper_;
    } else if (at_k) {
        tau = cut;
        expected = count_below(p_, counter_, tau, report_);
    } else if (sigma_ > 0) {
        expected = std::size_t((ldlt_.vectorD().array() < 0.0).count());
    }
    if (expected < below_lower_)
        throw Error("spectrum: the eigenvalue counts are inconsistent (" +
                    std::to_string(expected) + " below " + sci(tau) + ", " +
                    std::to_string(below_lower_) + " below " + sci(verified_) +
                    "): a badly scaled or degenerate operator; use the full method");
    expected -= below_lower_;
    repair(tau, expected, lo_b);
    const std::size_t found = acc.count_below(tau);
    if (found != expected)
        throw Error("spectrum: " + std::to_string(expected + below_lower_) +
                    " eigenvalues lie below " + std::to_string(tau) + " but " +
                    std::to_string(found + below_lower_) +
                    " were found (repeated eigenvalues of a symmetric mesh that the Lanczos "
                    "iteration missed); try another k, a smaller band_size, or the full method "
                    "(meshes up to max_full_rows vertices)");
    verified_ = tau;
    progress_.report(std::min(1.0, double(below_lower_ + acc.count_below(cut)) / double(k_)),
                     "Lanczos (shift-invert)");
    if (at_upper || at_k || total() >= std::size_t(n)) {
        done_ = true;
        return false;
    }
    // The next band: centred 35% of this band's width above the cut, so that it overlaps
    // this one; whatever still lies between them is found by the count at its shift. A band
    // that is one cluster (a multiplicity as large as the band) can be narrow or lie wholly
    // below σ: then (σ, σ + r) holds no eigenvalue (r: the band's radius around σ), and the
    // shift moves past it; it always moves by a quarter of a typical band (band x the mean
    // spacing), and never above the slice's end.
    const double spacing =
        (sorted.back() - sorted.front()) / double(std::max<std::size_t>(sorted.size() - 1, 1));
    const double typical = std::max(double(band_) * spacing, tiny_);
    double next = cut + 0.35 * width_b;
    if (hi_b < sigma_) next = std::max(next, sigma_ + (sigma_ - lo_b) + 0.35 * typical);
    next = std::min(std::max(next, sigma_ + 0.25 * typical), upper_);
    if (!std::isfinite(next) || !(next > sigma_))
        throw Error("spectrum: the shift of the next band does not move above sigma = " +
                    number_text(sigma_) +
                    " (badly scaled or degenerate operator); use the full method (meshes up "
                    "to max_full_rows vertices)");
    sigma_ = next;
    return true;
}

/// Looks for the eigenvalues below τ that the band missed, with the accepted vectors near
/// the band deflated, until `expected` lie in [lower, τ) (at most four runs).
void Slice::repair(double tau, std::size_t expected, double lo_b) {
    const Eigen::Index n = p_.n();
    if (acc.count_below(tau) >= expected) return;
    // The missing eigenvalues lie in [verified, τ), within R of σ. So do all eigenvalues
    // that are not deflated but lie nearer σ (above τ, or below the slice): the deflated run
    // must ask for all of them, or the missing ones stay beyond its reach. Two counts
    // (factorizations) say how many there are.
    const double radius =
        std::max(tau - sigma_, std::isfinite(verified_) ? sigma_ - verified_ : 0.0);
    const double window_lo = sigma_ - radius, window_hi = sigma_ + radius + window(sigma_ + radius);
    const std::size_t in_window = count_below(p_, counter_, window_hi, report_) -
                                  count_below(p_, counter_, window_lo, report_);
    for (int attempt = 0; acc.count_below(tau) < expected && attempt < 4; ++attempt) {
        progress_.check_cancelled();
        std::vector<Eigen::Index> cols;
        std::size_t deflated_in_window = 0;
        for (std::size_t j = 0; j < acc.size(); ++j)
            if (acc.values[j] >= std::min(lo_b, verified_) - window(lo_b)) {
                cols.push_back(Eigen::Index(j));
                if (acc.values[j] >= window_lo && acc.values[j] < window_hi) ++deflated_in_window;
            }
        Eigen::MatrixXd q(n, Eigen::Index(cols.size()));
        for (std::size_t c = 0; c < cols.size(); ++c)
            q.col(Eigen::Index(c)) = acc.vectors.col(cols[c]);
        const std::size_t missing = expected - acc.count_below(tau);
        const std::size_t wanted =
            std::max(missing, in_window - std::min(in_window, deflated_in_window)) + 3;
        // A repair recovers the few copies of repeated eigenvalues that a band missed; a
        // Krylov space for many more (the inertia count of a spectrum of rounding noise
        // said thousands) costs O(rows · ncv²) per restart, for up to max_iterations.
        if (missing > 2 * band_ + 8 || wanted > 4 * band_ + 16)
            throw Error("spectrum: " + std::to_string(expected + below_lower_) +
                        " eigenvalues lie below " + sci(tau) + " but only " +
                        std::to_string(expected - missing + below_lower_) +
                        " were found, too many to recover (a badly scaled or degenerate "
                        "operator); try a smaller band_size or the full method (meshes up "
                        "to max_full_rows vertices)");
        Eigen::VectorXd mu;
        Eigen::MatrixXd y;
        const auto solve = [&](const Eigen::VectorXd& x, Eigen::VectorXd& out) {
            out = x;
            ldlt_solve_in_place(ldlt_, out.data());
        };
        if (!deflated_eigenpairs(n, solve, q, Eigen::Index(wanted), Spectra::SortRule::LargestMagn,
                                 attempt, o_, progress_, report_, mu, y))
            break;
        for (Eigen::Index i = 0; i < mu.size(); ++i) {
            if (!(std::abs(mu[i]) > 0)) continue;
            const double lambda = sigma_ + 1.0 / mu[i];
            if (lambda < tau && lambda >= verified_)
                acc.add(lambda, y.col(i) - q * (q.transpose() * y.col(i)), window(lambda));
        }
    }
}

/// Adds the eigenpairs of `acc` with λ below `upper` to `out` (λ, column of acc.vectors).
void collect(const Accepted& acc, double upper,
             std::vector<std::pair<double, const double*>>& out) {
    for (std::size_t j = 0; j < acc.size(); ++j)
        if (acc.values[j] < upper)
            out.emplace_back(acc.values[j], acc.vectors.col(Eigen::Index(j)).data());
}

/// The number of threads for spectrum slicing: `requested`, or for 0 up to two when the
/// machine has them.
unsigned slice_threads(std::size_t requested) {
    if (requested > 0) return unsigned(std::min<std::size_t>(requested, 2));
    return unsigned(trilab::thread_count()) >= 2 ? 2u : 1u;
}

// ---- block shift-invert Lanczos (one factorization) ------------------------------------------

/// A block of vectors stored by rows, so that the b values of one row are adjacent: the
/// triangular solves of block_solve() read each entry of the factor once for all b columns.
using RowBlock = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

/// Z <- (LDLᵀ)⁻¹ Z for the columns [c0, c1) of a row-major block (see ldlt_solve_in_place()).
void ldlt_solve_columns(const Ldlt& ldlt, RowBlock& z, Eigen::Index c0, Eigen::Index c1) {
    const SparseMatrix& l = ldlt.matrixL().nestedExpression();
    const Eigen::Index n = l.cols(), b = z.cols();
    const int* outer = l.outerIndexPtr();
    const int* nnz = l.innerNonZeroPtr();
    const int* inner = l.innerIndexPtr();
    const double* value = l.valuePtr();
    const auto end = [&](Eigen::Index j) { return nnz ? outer[j] + nnz[j] : outer[j + 1]; };
    double* zp = z.data();
    const Eigen::Index w = c1 - c0;
    for (Eigen::Index j = 0; j < n; ++j) {  // L·W = Z, by columns
        const double* zj = zp + j * b + c0;
        for (int k = outer[j]; k < end(j); ++k) {
            double* zi = zp + Eigen::Index(inner[k]) * b + c0;
            const double v = value[k];
            for (Eigen::Index c = 0; c < w; ++c) zi[c] -= v * zj[c];
        }
    }
    const Eigen::VectorXd& d = ldlt.vectorD();
    for (Eigen::Index j = 0; j < n; ++j)
        for (Eigen::Index c = 0; c < w; ++c) zp[j * b + c0 + c] /= d[j];
    std::vector<double> acc(static_cast<std::size_t>(w));
    for (Eigen::Index j = n - 1; j >= 0; --j) {  // Lᵀ·X = W, by rows of Lᵀ
        double* zj = zp + j * b + c0;
        for (Eigen::Index c = 0; c < w; ++c) acc[std::size_t(c)] = zj[c];
        for (int k = outer[j]; k < end(j); ++k) {
            const double* zi = zp + Eigen::Index(inner[k]) * b + c0;
            const double v = value[k];
            for (Eigen::Index c = 0; c < w; ++c) acc[std::size_t(c)] -= v * zi[c];
        }
        for (Eigen::Index c = 0; c < w; ++c) zj[c] = acc[std::size_t(c)];
    }
}

/// The thick restart of block_shift_invert(): keeps the Ritz vectors of the largest θ (a
/// whole number of blocks short of m) in the first columns of v, the residual block after
/// them, and their projection (diagonal θ, the residual's coupling below) in h. Returns the
/// number kept.
Eigen::Index thick_restart(Eigen::MatrixXd& v, Eigen::MatrixXd& h, const Eigen::VectorXd& theta,
                           const Eigen::MatrixXd& s, const Eigen::MatrixXd& coupling,
                           Eigen::Index m, Eigen::Index nev, bool two) {
    const Eigen::Index n = v.rows(), b = kLanczosBlock, half = n / 2;
    // Thick restart: keep the p Ritz vectors of the largest θ and the residual block.
    // (m - keep a whole number of blocks, so that the next cycle ends at m again)
    const Eigen::Index keep = m - b * ((m - std::min(m - 2 * b, nev + (m - nev) / 3)) / b);
    const Eigen::MatrixXd sp = s.rightCols(keep);
    Eigen::MatrixXd y(n, keep);
    on_two_threads(two, [&](int i) {
        const Eigen::Index r0 = i ? half : 0, rows = i ? n - half : half;
        y.middleRows(r0, rows).noalias() = v.block(r0, 0, rows, m) * sp;
    });
    v.leftCols(keep) = y;
    v.middleCols(keep, b) = v.middleCols(m, b);
    const Eigen::MatrixXd bk = coupling.rightCols(keep);
    h.setZero();
    h.topLeftCorner(keep, keep).diagonal() = theta.tail(keep);
    h.block(keep, 0, b, keep) = bk;
    return keep;
}

/// What block_shift_invert() found: the eigenpairs nearest σ (y-space, ascending), or
/// converged = false.
struct BlockResult {
    Band band;
    bool converged = false;
};

/// The `nev` eigenvalues of A nearest σ (σ below the spectrum: the smallest) and their
/// vectors, by block Lanczos on (A - σI)⁻¹ with thick restarts (the symmetric block
/// Krylov–Schur method: Stewart 2001; Zhou & Saad 2008) and full reorthogonalization by block
/// classical Gram–Schmidt twice (Giraud et al. 2005). With blocks of b vectors the factor is
/// read once per block solve and the orthogonalization is matrix-matrix products, where the
/// single-vector method (shift_invert_band()) spends its time in memory-bound matrix-vector
/// products over the basis: one factorization serves every frequency, where bands need one
/// each. A Ritz pair (θ, y) is accepted as Spectra accepts one: |R·s_b| <= tolerance · |θ|,
/// with R·s_b the part of (A - σI)⁻¹·y outside the basis (exact in Krylov–Schur form).
/// Products and solves are split over two threads when `two`.
BlockResult block_shift_invert(const Problem& p, const Ldlt& ldlt, double sigma, Eigen::Index nev,
                               const SpectralOptions& o, bool two, Progress& progress,
                               SpectralReport& report,
                               const std::function<bool(const Eigen::VectorXd&)>& settled) {
    const Eigen::Index n = p.n(), b = kLanczosBlock;
    const Eigen::Index wanted = Eigen::Index(std::ceil(o.krylov_factor * double(nev)));
    const Eigen::Index m = b * ((std::max(wanted, nev + 3 * b) + b - 1) / b);  // basis size
    BlockResult out;
    if (m + b > n / 2) return out;  // a small problem: the band method
    Eigen::MatrixXd v(n, m + b), h = Eigen::MatrixXd::Zero(m + b, m + b);
    for (Eigen::Index c = 0; c < b; ++c) v.col(c) = start_vector(n, 7919 + std::uint64_t(c));
    {
        Eigen::HouseholderQR<Eigen::MatrixXd> qr(v.leftCols(b));
        v.leftCols(b) = qr.householderQ() * Eigen::MatrixXd::Identity(n, b);
    }
    RowBlock w(n, b);
    Eigen::MatrixXd wc(n, b), coeff, tmp;
    const Eigen::Index half = n / 2;
    // y <- Vᵀ x (x: n x b) over the first `cols` columns, the rows split in two halves.
    const auto project = [&](Eigen::Index cols, const Eigen::MatrixXd& x, Eigen::MatrixXd& y) {
        Eigen::MatrixXd part[2];
        on_two_threads(two, [&](int i) {
            const Eigen::Index r0 = i ? half : 0, rows = i ? n - half : half;
            part[i].noalias() = v.block(r0, 0, rows, cols).transpose() * x.middleRows(r0, rows);
        });
        y = part[0] + part[1];
    };
    // x <- x - V·c over the first `cols` columns.
    const auto subtract = [&](Eigen::Index cols, const Eigen::MatrixXd& c, Eigen::MatrixXd& x) {
        on_two_threads(two, [&](int i) {
            const Eigen::Index r0 = i ? half : 0, rows = i ? n - half : half;
            x.middleRows(r0, rows).noalias() -= v.block(r0, 0, rows, cols) * c;
        });
    };
    Eigen::Index filled = b;  // basis columns; the block at [filled - b, filled) is expanded next
    const int max_cycles = std::max(1, o.max_iterations);
    const double expected_ops = 2.0 * double(m);
    for (int cycle = 0; cycle < max_cycles; ++cycle) {
        while (filled <= m) {
            progress.check_cancelled();
            const Eigen::Index j = filled - b;
            const auto t0 = std::chrono::steady_clock::now();
            w = v.middleCols(j, b);
            on_two_threads(two, [&](int i) {
                const Eigen::Index c0 = i ? b / 2 : 0, c1 = i ? b : b / 2;
                ldlt_solve_columns(ldlt, w, c0, c1);
            });
            report.solve_ms += ms_since(t0);
            report.operations += std::size_t(b);
            wc = w;
            project(filled, wc, coeff);  // classical Gram–Schmidt, twice
            subtract(filled, coeff, wc);
            project(filled, wc, tmp);
            subtract(filled, tmp, wc);
            coeff += tmp;
            // The projection H is block tridiagonal (plus the restart's arrow) in exact
            // arithmetic: only its diagonal block and the R below are kept, which are
            // accurate where the couplings become tiny; the coefficients above are rounding
            // of the size eps·|(A - σI)⁻¹| that would pollute the residual estimates.
            h.block(j, j, b, b) = coeff.bottomRows(b);
            Eigen::HouseholderQR<Eigen::MatrixXd> qr(wc);
            const Eigen::MatrixXd r =
                qr.matrixQR().topRows(b).triangularView<Eigen::Upper>().toDenseMatrix();
            const double scale = std::max(coeff.norm(), 1e-300);
            for (Eigen::Index c = 0; c < b; ++c)
                if (!(std::abs(r(c, c)) > 1e-10 * scale)) return out;  // an invariant subspace
            v.middleCols(filled, b) = qr.householderQ() * Eigen::MatrixXd::Identity(n, b);
            h.block(filled, j, b, b) = r;
            filled += b;
            progress.report(
                std::min(0.9, double(report.operations) /
                                  std::max(expected_ops, double(report.operations) + 1)),
                "block Lanczos (shift-invert)");
        }
        ++report.restarts;
        // Rayleigh–Ritz on the symmetric projection (the lower triangle, mirrored).
        Eigen::MatrixXd hm = h.topLeftCorner(m, m).triangularView<Eigen::Lower>();
        hm.triangularView<Eigen::StrictlyUpper>() = hm.transpose();
        Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(hm);
        if (es.info() != Eigen::Success) return out;
        const Eigen::VectorXd& theta = es.eigenvalues();  // ascending: the wanted are last
        const Eigen::MatrixXd& s = es.eigenvectors();
        const Eigen::MatrixXd coupling = h.block(m, m - b, b, b) * s.bottomRows(b);  // b x m
        bool all = true;
        for (Eigen::Index i = m - nev; i < m && all; ++i)
            all = theta[i] > 0 &&
                  coupling.col(i).norm() <= o.tolerance * std::max(std::abs(theta[i]), 1e-300);
        if (!all && settled) {
            // Once every wanted Ritz value is settled (residual below 1e-4 θ: the values are
            // then accurate to about 1e-8), `settled` may start work on them on the second
            // thread; the products and solves then stay on this one.
            bool near = true;
            for (Eigen::Index i = m - nev; i < m && near; ++i)
                near = theta[i] > 0 && coupling.col(i).norm() <= 1e-4 * theta[i];
            if (near) {
                Eigen::VectorXd estimate(nev);
                for (Eigen::Index i = 0; i < nev; ++i) estimate[i] = sigma + 1.0 / theta[m - 1 - i];
                if (settled(estimate)) two = false;
            }
        }
        if (all) {
            out.band.values.resize(nev);
            for (Eigen::Index i = 0; i < nev; ++i)
                out.band.values[i] = sigma + 1.0 / theta[m - 1 - i];
            const Eigen::MatrixXd sel = s.rightCols(nev).rowwise().reverse();
            out.band.vectors.resize(n, nev);
            on_two_threads(two, [&](int i) {
                const Eigen::Index r0 = i ? half : 0, rows = i ? n - half : half;
                out.band.vectors.middleRows(r0, rows).noalias() = v.block(r0, 0, rows, m) * sel;
            });
            out.converged = true;
            ++report.bands;
            return out;
        }
        filled = thick_restart(v, h, theta, s, coupling, m, nev, two) + b;
    }
    return out;
}

/// Whether the smallest end runs as one block (SpectralOptions::solver).
bool use_block(const SpectralOptions& o, std::size_t rows) {
    if (o.solver == SpectralSolver::Auto) return rows >= kBlockMinRows;
    return o.solver == SpectralSolver::Block;
}

/// A cut above the k-th of the ascending `values`: in the widest gap among those from the k-th
/// up (as Slice::step() cuts), or just above the largest when no gap is clear.
double cut_above_kth(const Eigen::VectorXd& values, std::size_t k, double tiny) {
    std::vector<double> sorted(values.data(), values.data() + values.size());
    const double width = std::max(sorted.back() - sorted.front(), tiny);
    double cut = sorted.back() + 1e-3 * width + tiny;
    const double mid = widest_gap_midpoint(sorted, k - 1, sorted.size());
    const auto above_mid = std::upper_bound(sorted.begin(), sorted.end(), mid);
    if (above_mid != sorted.begin() && above_mid != sorted.end() &&
        *above_mid - *(above_mid - 1) > 1e-3 * width)
        cut = mid;
    return cut;
}

/// The k smallest eigenpairs by one block shift-invert run at a negative shift
/// (block_shift_invert()) and one inertia count at a cut above the k-th: two factorizations
/// in all, the count's on a second thread while the run finishes (from a cut placed among
/// the settled Ritz values; should the converged values put a different number below it, it
/// is counted again at a new cut). False when the run did not converge or the count differs
/// (a missed copy of a repeated eigenvalue): the caller then sweeps band by band, which
/// repairs such gaps.
bool block_smallest(const Problem& p, std::size_t k, const SpectralOptions& o, Progress& progress,
                    SpectralReport& report, Band& out) {
    const Eigen::Index n = p.n();
    const std::size_t extra = std::max<std::size_t>(4, k / 20);
    const Eigen::Index nev = Eigen::Index(std::min<std::size_t>(k + extra, std::size_t(n - 1)));
    const double sigma = -1e-8 * std::max(p.a_max, 1e-300);
    const double tiny = 1e-12 * std::max(p.a_max, 1e-300);
    const bool two = slice_threads(o.threads) >= 2;
    // The early count (second thread): its cut, its count, its own report figures.
    Ldlt counter;
    counter.analyzePattern(p.A);
    std::thread early;
    std::exception_ptr early_failure;
    bool early_started = false;
    double early_cut = 0;
    std::size_t early_count = 0;
    SpectralReport early_report;
    const auto start_count = [&](const Eigen::VectorXd& estimate) {
        if (!two || early.joinable()) return false;
        early_cut = cut_above_kth(estimate, k, tiny);
        early_started = true;
        early = std::thread([&] {
            try {
                early_count = count_below(p, counter, early_cut, early_report);
            } catch (...) {
                early_failure = std::current_exception();
            }
        });
        return true;
    };
    BlockResult r;
    try {
        Ldlt ldlt;
        ldlt.analyzePattern(p.A);
        const auto t0 = std::chrono::steady_clock::now();
        ldlt.factorize(shifted(p, sigma));
        report.factor_ms += ms_since(t0);
        ++report.factorizations;
        const Eigen::VectorXd& dd = ldlt.vectorD();
        if (ldlt.info() == Eigen::Success && dd.allFinite() && !(dd.array() == 0.0).any())
            r = block_shift_invert(p, ldlt, sigma, nev, o, two, progress, report, start_count);
    } catch (...) {
        if (early.joinable()) early.join();
        throw;
    }
    if (early.joinable()) {
        early.join();
        report.factor_ms += early_report.factor_ms;
        report.factorizations += early_report.factorizations;
    }
    if (!r.converged) return false;
    orthonormalize(r.band.vectors);
    const Eigen::VectorXd& values = r.band.values;
    const auto below = [&](double cut) { return std::size_t((values.array() < cut).count()); };
    // Verify with the eigenvalue count (Sylvester's law of inertia) below a cut above the k-th.
    bool verified =
        early_started && !early_failure && below(early_cut) >= k && below(early_cut) == early_count;
    if (!verified) {
        const double cut = cut_above_kth(values, k, tiny);
        const std::size_t found = below(cut);
        verified = found >= k && found == count_below(p, counter, cut, report);
    }
    if (!verified) return false;
    out.values = values.head(Eigen::Index(k));
    out.vectors = r.band.vectors.leftCols(Eigen::Index(k));
    report.solver =
        "block shift-invert Lanczos + SimplicialLDLT (AMD-ordered rows), "
        "inertia-checked";
    return true;
}

/// Where two spectrum slices meet: τ, the number of eigenvalues below it, and the second
/// slice's first shift.
struct SliceSplit {
    double tau = 0;
    std::size_t below = 0;
    double sigma = 0;
};

/// The split after the first band (its eigenvalues `found`, `total` below its top counted):
/// Weyl's law (λ_i ≈ hi · i / c_hi from the band's largest value hi) puts τ at the middle of
/// the remaining eigenvalues and one factorization counts those below it. The low end of a
/// surface's spectrum often departs from Weyl's law (the cow's first 20 put the middle of 150
/// at the 54th): when the count is more than a quarter band off the middle, one secant step
/// between the band's top and the count, and a second count, balance the slices' work. False
/// when no τ leaves real work (half a band) on both sides.
bool split_slices(const Problem& p, const std::vector<double>& found, std::size_t total,
                  std::size_t k, std::size_t band, SpectralReport& report, SliceSplit& out) {
    const double hi = *std::max_element(found.begin(), found.end());
    const double c_hi = double(total);
    const double target = 0.5 * (c_hi + double(k));
    const auto balanced = [&](std::size_t below) {
        return below >= total + band / 2 && below + band / 2 <= k;
    };
    double tau = hi * target / c_hi, spacing = hi / c_hi;
    if (!(std::isfinite(tau) && tau > hi)) return false;
    Ldlt counter;
    counter.analyzePattern(p.A);
    std::size_t below = count_below(p, counter, tau, report);
    if (double(below) > c_hi && std::abs(double(below) - target) > double(band) / 4) {
        const double measured = (tau - hi) / (double(below) - c_hi);
        const double tau2 = tau + (target - double(below)) * measured;
        if (std::isfinite(tau2) && tau2 > hi) {
            const std::size_t below2 = count_below(p, counter, tau2, report);
            if (balanced(below2) || !balanced(below)) {
                // The spacing near τ2: between the two counts when they differ.
                spacing = below2 != below
                              ? std::abs(tau2 - tau) / std::abs(double(below2) - double(below))
                              : measured;
                tau = tau2;
                below = below2;
            }
        }
    }
    if (!balanced(below)) return false;
    // The second slice's first band (the band eigenvalues nearest its shift) must reach down
    // to τ: its shift lies 45 % of a band's width (by the spacing the counts measured, a
    // little less than half for a spectrum that grows denser) above τ.
    out = SliceSplit{tau, below, tau + 0.45 * spacing * double(band)};
    return true;
}

/// The k smallest eigenpairs: a first band at a negative shift (with two slices ahead, half a
/// band: it runs alone, and the second thread starts sooner), then (with two threads and
/// enough left to do) the rest of [0, λ_k] in two slices at once, split where Weyl's law
/// (λ_i grows linearly with i on a surface) extrapolated from the first band puts the middle
/// of the remaining eigenvalues; otherwise one sweep. Returns values (ascending) and y-space
/// vectors.
Band smallest(const Problem& p, std::size_t k, const SpectralOptions& o, Progress& progress,
              SpectralReport& report) {
    const Eigen::Index n = p.n();
    const std::size_t extra = std::max<std::size_t>(4, k / 20);
    // Bands of 40, or 30 above 20,000 rows: the Lanczos basis of a band (rows x 2·band
    // doubles) is swept several times per step, so it should stay near the cache size.
    const std::size_t auto_band = n > 20000 ? 30 : 40;
    std::size_t band = o.band_size ? o.band_size : (k <= 60 ? k + extra : auto_band);
    band = std::min<std::size_t>(band, std::size_t(n - 1));
    if (use_block(o, std::size_t(n))) {  // the bands take over when it cannot vouch
        Band out;
        if (block_smallest(p, k, o, progress, report, out)) return out;
        ++report.repairs;
    }
    report.solver =
        "Spectra shift-invert Lanczos + SimplicialLDLT (AMD-ordered rows), inertia-checked";

    const double sigma0 = -1e-8 * std::max(p.a_max, 1e-300);
    Slice first(p, o, k, band, progress, report, -std::numeric_limits<double>::infinity(), 0,
                sigma0);
    const bool slicing = slice_threads(o.threads) >= 2;  // a half first band: see above
    if (slicing && k >= 3 * band && band >= 16) first.set_band(band / 2);
    std::vector<std::pair<double, const double*>> found;
    std::size_t duplicates = 0;
    std::atomic<bool> stop{false};
    WorkerProgress worker(progress, stop);
    std::unique_ptr<Slice> second;
    SpectralReport second_report;
    double split = std::numeric_limits<double>::infinity();
    const bool more = first.step();
    first.set_band(band);
    SliceSplit cut;
    if (more && slicing && k >= first.total() + 2 * band &&
        split_slices(p, first.acc.values, first.total(), k, band, report, cut)) {
        split = cut.tau;
        first.set_upper(cut.tau, cut.below);
        second = std::make_unique<Slice>(p, o, k, band, worker, second_report, cut.tau, cut.below,
                                         cut.sigma);
    }
    if (second) {
        first.count_progress_of(*second);
        std::exception_ptr worker_failure, main_failure;
        std::thread thread([&] {
            try {
                second->run();
            } catch (...) {
                worker_failure = std::current_exception();
            }
        });
        try {
            first.run();
        } catch (...) {
            main_failure = std::current_exception();
            stop = true;  // the worker throws Cancelled at its next check
        }
        thread.join();
        if (main_failure || worker_failure) {
            if (progress.cancel_requested()) throw Cancelled();
            for (const std::exception_ptr& failure : {main_failure, worker_failure}) {
                if (!failure) continue;
                try {
                    std::rethrow_exception(failure);
                } catch (const Error&) {  // solver trouble (or the stop): handled below
                }                         // anything else (std::bad_alloc) propagates
            }
            // A slice end that fell among close eigenvalues the estimate could not see, or a
            // repair that needed vectors of the other slice: one sweep instead.
            SpectralOptions one = o;
            one.threads = 1;
            one.solver = SpectralSolver::Bands;
            return smallest(p, k, one, progress, report);
        }
    } else {
        first.run();
    }
    collect(first.acc, split, found);
    duplicates += first.acc.duplicates;
    if (second) {
        collect(second->acc, std::numeric_limits<double>::infinity(), found);
        duplicates += second->acc.duplicates;
        report.bands += second_report.bands;
        report.factorizations += second_report.factorizations;
        report.operations += second_report.operations;
        report.restarts += second_report.restarts;
        report.repairs += second_report.repairs;
        report.factor_ms += second_report.factor_ms;
        report.solve_ms += second_report.solve_ms;
        report.slices = 2;
    }
    report.duplicates_removed = duplicates;

    // Sort ascending and keep the k smallest.
    std::stable_sort(found.begin(), found.end(),
                     [](const auto& a, const auto& c) { return a.first < c.first; });
    const std::size_t keep = std::min(k, found.size());
    Band out;
    out.values.resize(Eigen::Index(keep));
    out.vectors.resize(n, Eigen::Index(keep));
    for (std::size_t i = 0; i < keep; ++i) {
        out.values[Eigen::Index(i)] = found[i].first;
        out.vectors.col(Eigen::Index(i)) = Eigen::Map<const Eigen::VectorXd>(found[i].second, n);
    }
    if (keep < k) throw Error(not_converged(keep, k, "(band by band)"));
    // Ritz vectors of different bands are orthogonal only to (residual / gap): one Cholesky QR
    // over all of them (O(rows · k²)) makes them orthonormal to rounding.
    if (report.bands > 1) orthonormalize_halves(out.vectors, slicing);
    return out;
}

Band largest(const Problem& p, std::size_t k, const SpectralOptions& o, Progress& progress,
             SpectralReport& report) {
    const Eigen::Index n = p.n();
    const std::size_t extra = std::max<std::size_t>(4, k / 20);
    const Eigen::Index m = std::min<Eigen::Index>(Eigen::Index(k + extra), n - 1);
    Eigen::Index ncv = std::min(n, std::max(2 * m + 1, m + 20));
    int max_it = o.max_iterations;
    report.solver = "Spectra Lanczos (sparse products), inertia-checked";
    Band b;
    for (int attempt = 0; attempt < 2; ++attempt) {
        ProductOp op(p, progress, 4.0 * double(ncv));
        Spectra::SymEigsSolver<ProductOp> eigs(op, m, ncv);
        const Eigen::VectorXd v0 = start_vector(n, 0);
        eigs.init(v0.data());
        eigs.compute(Spectra::SortRule::LargestAlge, max_it, o.tolerance,
                     Spectra::SortRule::SmallestAlge);
        report.operations += op.operations;
        report.solve_ms += op.solve_ms;
        report.restarts += std::size_t(eigs.num_iterations());
        if (eigs.info() == Spectra::CompInfo::Successful) {
            report.bands = 1;
            b = Band{eigs.eigenvalues(), eigs.eigenvectors()};
            break;
        }
        if (attempt == 1)
            throw Error(not_converged(std::size_t(eigs.eigenvalues().size()), k, "(largest)"));
        ncv = std::min(n, 2 * ncv);
        max_it *= 2;
    }
    orthonormalize(b.vectors);
    Accepted acc;
    acc.vectors.resize(n, b.values.size() + 8);
    const double tiny = 1e-12 * std::max(p.a_max, 1e-300);
    const auto window = [&](double lambda) { return 1e-6 * std::abs(lambda) + tiny; };
    for (Eigen::Index i = 0; i < b.values.size(); ++i)
        acc.add(b.values[i], b.vectors.col(i), window(b.values[i]));
    // Verify with the count of eigenvalues above τ, in the widest gap among the lowest found.
    std::vector<double> sorted = acc.values;
    std::sort(sorted.begin(), sorted.end());
    const std::size_t top = sorted.size() > k ? sorted.size() - k : 0;
    const double width_b = std::max(sorted.back() - sorted.front(), tiny);
    double tau = sorted.front() - 1e-3 * width_b - tiny;
    {
        const double mid = widest_gap_midpoint(sorted, 0, top + 1);
        const auto above_mid = std::upper_bound(sorted.begin(), sorted.end(), mid);
        if (above_mid != sorted.begin() && above_mid != sorted.end() &&
            *above_mid - *(above_mid - 1) > 1e-3 * width_b)
            tau = mid;
    }
    Ldlt counter;
    counter.analyzePattern(p.A);
    const std::size_t expected = std::size_t(n) - count_below(p, counter, tau, report);
    const auto above = [&] { return acc.size() - acc.count_below(tau); };
    for (int attempt = 0; above() < expected && attempt < 4; ++attempt) {
        progress.check_cancelled();
        if (expected - above() > 2 * std::size_t(m) + 8)
            throw Error("spectrum: " + std::to_string(expected) + " eigenvalues lie above " +
                        sci(tau) + " but only " + std::to_string(above()) +
                        " were found, too many to recover (a badly scaled or degenerate "
                        "operator); try another k or the full method (meshes up to "
                        "max_full_rows vertices)");
        const Eigen::MatrixXd q = acc.vectors.leftCols(Eigen::Index(acc.size()));
        Eigen::VectorXd values;
        Eigen::MatrixXd vectors;
        const auto product = [&](const Eigen::VectorXd& x, Eigen::VectorXd& y) {
            y.noalias() = p.A * x;
        };
        if (!deflated_eigenpairs(n, product, q, Eigen::Index(expected - above() + 3),
                                 Spectra::SortRule::LargestAlge, attempt, o, progress, report,
                                 values, vectors))
            break;
        for (Eigen::Index i = 0; i < values.size(); ++i)
            if (values[i] > tau) acc.add(values[i], vectors.col(i), window(values[i]));
    }
    if (above() != expected)
        throw Error("spectrum: " + std::to_string(expected) + " eigenvalues lie above " +
                    std::to_string(tau) + " but " + std::to_string(above()) +
                    " were found; try another k or the full method (meshes up to max_full_rows "
                    "vertices)");
    report.duplicates_removed = acc.duplicates;
    std::vector<std::size_t> order(acc.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(),
              [&](std::size_t a, std::size_t c) { return acc.values[a] < acc.values[c]; });
    if (order.size() < k) throw Error(not_converged(order.size(), k, "(largest)"));
    Band out;
    out.values.resize(Eigen::Index(k));
    out.vectors.resize(n, Eigen::Index(k));
    for (std::size_t i = 0; i < k; ++i) {
        const std::size_t j = order[order.size() - k + i];
        out.values[Eigen::Index(i)] = acc.values[j];
        out.vectors.col(Eigen::Index(i)) = acc.vectors.col(Eigen::Index(j));
    }
    return out;
}

/// Refuses a dense decomposition whose memory exceeds what the machine has available now.
/// Its peak is two n x n matrices of doubles: the dense matrix with the solver's eigenvector
/// matrix, then that with the k <= n kept eigenvectors, then those with K times them.
void check_dense_memory(std::size_t n) {
    const double rows = double(n);
    const double need = 8.0 * 2.0 * rows * rows;
    const AvailableMemory available = available_memory();
    if (need <= double(available.bytes)) return;
    throw InvalidArgument(
        "full: the dense decomposition of " + std::to_string(n) + " rows needs about " +
        format_memory_size(need) + " (two " + std::to_string(n) + " x " + std::to_string(n) +
        " matrices of doubles), more than the " + format_memory_size(double(available.bytes)) +
        " this process may still allocate (" + available.limit +
        "); use the partial method with k frequencies");
}

Band full(const Problem& p, std::size_t k, SpectrumEnd end, Progress& progress,
          SpectralReport& report) {
    const Eigen::Index n = p.n();
    progress.report(-1, "dense symmetric eigen solver");
    Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, n);
    for (Eigen::Index c = 0; c < p.A.outerSize(); ++c)
        for (SparseMatrix::InnerIterator it(p.A, c); it; ++it) a(it.row(), it.col()) = it.value();
    progress.check_cancelled();
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(a);
    a.resize(0, 0);  // the solver keeps its own n x n matrix; the result adds n x k
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

/// The rows' base positions X (rows x 3), in the order of the eigenproblem.
Eigen::MatrixXd row_positions(const SpectralDecomposition& d) {
    Eigen::MatrixXd x(Eigen::Index(d.rows()), 3);
    for (std::size_t r = 0; r < d.rows(); ++r)
        x.row(Eigen::Index(r)) = d.base_positions[d.map.vertex_of[r].idx()].transpose();
    return x;
}

/// The computed frequencies [first, first + count) outside a band that reaches the open end:
/// below it for the smallest end, above it for the largest.
struct OutsideBand {
    Eigen::Index first = 0, count = 0;
};

OutsideBand outside_band(const SpectralDecomposition& d, std::size_t lo, std::size_t hi) {
    if (d.end == SpectrumEnd::Smallest) return {0, Eigen::Index(lo)};
    return {Eigen::Index(hi + 1), Eigen::Index(d.size() - hi - 1)};
}

/// Whether the band [lo, hi] (checked) takes in the rest.
bool with_rest(const SpectralDecomposition& d, std::size_t lo, std::size_t hi, BandRest rest) {
    return rest == BandRest::Include && band_reaches_rest(d, lo, hi);
}

}  // namespace

const char* spectral_method_name(SpectralMethod method) {
    return enum_id<SpectralMethod>(kSpectralMethods, method);
}

const char* spectrum_end_name(SpectrumEnd end) {
    return enum_id<SpectrumEnd>(kSpectrumEnds, end);
}

SpectrumEnd parse_spectrum_end(const std::string& name) {
    return parse_enum<SpectrumEnd>(kSpectrumEnds, name, "spectrum end");
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
    if (!(o.krylov_factor >= 1.2 && o.krylov_factor <= 10))
        throw InvalidArgument("krylov_factor: expected a number from 1.2 to 10");
    for (const Point& q : mesh.positions())
        if (!q.allFinite())
            throw InvalidArgument("spectrum: the mesh has non-finite vertex positions");

    const bool combinatorial =
        o.op == LaplacianOperator::Umbrella && o.mass == MassMatrix::Normalizer;
    if (!combinatorial && mesh.n_faces() > 0) {
        // A mesh collapsed to (almost) nothing has no meaningful geometric spectrum: its
        // masses and weights are rounding noise, on which the Lanczos iteration need not
        // converge. (The umbrella operator with its valence mass does not see the geometry.)
        const double area = surface_area(mesh);
        const double diag = bounding_box(mesh).diagonal();
        if (!(area > kDegenerateAreaRatio * diag * diag))
            throw InvalidArgument("spectrum: the mesh is degenerate: its surface area (" +
                                  sci(area) +
                                  ") is below 1e-12 of its bounding-box diagonal "
                                  "squared (" +
                                  sci(diag * diag) +
                                  "); repair or rescale the mesh first (the umbrella operator "
                                  "with the normalizer mass does not need its geometry)");
    }

    progress.report(0, "building the operator");
    Problem p = make_problem(mesh, o);
    const std::size_t n = p.map.rows();
    if (n < 2)
        throw InvalidArgument("spectrum: the mesh has " + std::to_string(n) +
                              " vertices in the eigenproblem (at least 2 needed)");
    if (!p.S.allFinite() || (p.S.array() <= 0).any() || !std::isfinite(p.k_norm))
        throw InvalidArgument(
            "spectrum: the mesh is degenerate: the operator has a non-positive or non-finite "
            "mass");
    const double s_max = p.S.maxCoeff();
    for (Eigen::Index i = 0; i < p.S.size(); ++i)
        if (!(p.S[i] >= kDegenerateMassRatio * s_max) || !std::isnormal(p.d[i]))
            throw InvalidArgument(
                "spectrum: the mesh is degenerate: the mass of vertex " +
                std::to_string(p.map.vertex_of[std::size_t(i)].idx()) + " (" + sci(p.S[i]) +
                ") is below 1e-12 of the largest (" + sci(s_max) +
                "); remove its zero-area faces (e.g. decimate or clean the mesh) or use another "
                "mass");
    if (!(p.k_norm > 0) || !std::isfinite(p.a_max))
        throw InvalidArgument(
            "spectrum: the mesh is degenerate: the operator K is zero or its scale is not "
            "finite");

    SpectralDecomposition d;
    d.op = o.op;
    d.mass = o.mass;
    d.method = o.method;
    d.end = o.end;
    d.report.diagnostics = p.diagnostics;
    Band b;
    if (o.method == SpectralMethod::Full) {
        if (n > o.max_full_rows)
            throw InvalidArgument(
                "full: the dense decomposition is limited to " + std::to_string(o.max_full_rows) +
                " vertices (max_full_rows) and this mesh has " + std::to_string(n) +
                "; use the partial method with k frequencies");
        if (o.k > n)
            throw InvalidArgument("k: expected a whole number from 0 (all) to " +
                                  std::to_string(n) + " for this mesh, got " + std::to_string(o.k));
        check_dense_memory(n);
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

    // Residuals |K e - λ S e| / (|K|_inf |e|), each column's on its own (two halves of the
    // columns on two threads when the machine has them: the same bits either way).
    const Eigen::Index cols = d.eigenvectors.cols(), half = cols / 2;
    Eigen::VectorXd residual(cols);
    on_two_threads(cols >= 16 && thread_count() >= 2, [&](int i) {
        const Eigen::Index c0 = i ? half : 0, count = i ? cols - half : half;
        if (count == 0) return;
        const Eigen::MatrixXd ke = p.K * d.eigenvectors.middleCols(c0, count);
        for (Eigen::Index j = 0; j < count; ++j) {
            const auto e = d.eigenvectors.col(c0 + j);
            const double r = (ke.col(j) - d.eigenvalues[c0 + j] * p.S.cwiseProduct(e)).norm();
            residual[c0 + j] = r / (std::max(p.k_norm, 1e-300) * e.norm());
        }
    });
    for (Eigen::Index j = 0; j < cols; ++j)
        d.report.max_residual = std::max(d.report.max_residual, residual[j]);
    d.map = std::move(p.map);
    d.S = std::move(p.S);
    d.base_positions = mesh.positions();
    d.report.ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    progress.report(1, "done");
    return d;
}

bool band_reaches_rest(const SpectralDecomposition& d, std::size_t lo, std::size_t hi) {
    check_band(d, lo, hi);
    return d.end == SpectrumEnd::Smallest ? hi + 1 == d.size() : lo == 0;
}

Eigen::MatrixXd rest_positions(const SpectralDecomposition& d) {
    Eigen::MatrixXd x = row_positions(d);
    x.noalias() -= d.eigenvectors * d.coefficients;
    return x;
}

Eigen::MatrixXd band_positions(const SpectralDecomposition& d, std::size_t lo, std::size_t hi,
                               BandRest rest) {
    check_band(d, lo, hi);
    if (with_rest(d, lo, hi, rest)) {
        // The band and the rest: X less the computed frequencies outside the band (exactly X
        // for the whole computed band, whatever the accuracy of the eigenvectors).
        const OutsideBand o = outside_band(d, lo, hi);
        Eigen::MatrixXd x = row_positions(d);
        if (o.count > 0)
            x.noalias() -= d.eigenvectors.middleCols(o.first, o.count) *
                           d.coefficients.middleRows(o.first, o.count);
        return x;
    }
    const Eigen::Index a = Eigen::Index(lo), count = Eigen::Index(hi - lo + 1);
    return d.eigenvectors.middleCols(a, count) * d.coefficients.middleRows(a, count);
}

std::vector<Point> reconstruct_positions(const SpectralDecomposition& d, std::size_t lo,
                                         std::size_t hi, BandRest rest,
                                         const std::vector<float>* region) {
    if (region && region->size() != d.base_positions.size())
        throw InvalidArgument("reconstruct: region: expected one weight per vertex (" +
                              std::to_string(d.base_positions.size()) + "), got " +
                              std::to_string(region->size()));
    const Eigen::MatrixXd x = band_positions(d, lo, hi, rest);
    std::vector<Point> out = d.base_positions;
    for (std::size_t r = 0; r < d.map.rows(); ++r) {
        const Index v = d.map.vertex_of[r].idx();
        const Point band = x.row(Eigen::Index(r)).transpose();
        out[v] = region ? blend_by_weight(out[v], band, (*region)[v]) : band;
    }
    return out;
}

HalfedgeMesh reconstruct(const HalfedgeMesh& mesh, const SpectralDecomposition& d, std::size_t lo,
                         std::size_t hi, BandRest rest, const std::vector<float>* region) {
    if (mesh.vertices_size() != d.base_positions.size())
        throw InvalidArgument("reconstruct: the mesh has " + std::to_string(mesh.vertices_size()) +
                              " vertices but the decomposition was made for " +
                              std::to_string(d.base_positions.size()));
    if (region) check_selection(mesh, *region, "reconstruct: region");
    std::vector<Point> positions = reconstruct_positions(d, lo, hi, rest, region);
    HalfedgeMesh out = mesh;
    out.set_positions(std::move(positions));
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
                                         std::size_t hi, BandRest rest) {
    check_band(d, lo, hi);
    std::vector<double> out(d.base_positions.size(), std::numeric_limits<double>::quiet_NaN());
    if (d.rows() == 0) return out;
    // The S-weighted centroid c of the decomposed rows. The band's part of X - 1·cᵀ has the
    // coefficients α_k - (e_kᵀ·S·1)·cᵀ: a translation t adds (e_kᵀ·S·1)·tᵀ to α_k and t to c,
    // so they cancel and the field is the same wherever the mesh sits.
    Eigen::RowVector3d c = Eigen::RowVector3d::Zero();
    double mass = 0;
    for (std::size_t r = 0; r < d.rows(); ++r) {
        const double s = d.S[Eigen::Index(r)];
        c += s * d.base_positions[d.map.vertex_of[r].idx()].transpose();
        mass += s;
    }
    c /= mass;
    const bool include = with_rest(d, lo, hi, rest);
    // With the rest: X - 1·cᵀ less the centred parts of the computed frequencies outside.
    const OutsideBand o = include ? outside_band(d, lo, hi) : OutsideBand{};
    const Eigen::Index a = include ? o.first : Eigen::Index(lo),
                       count = include ? o.count : Eigen::Index(hi - lo + 1);
    const auto e = d.eigenvectors.middleCols(a, count);
    const Eigen::VectorXd w = e.transpose() * d.S;  // e_kᵀ·S·1
    const Eigen::MatrixXd alpha = d.coefficients.middleRows(a, count) - w * c;
    Eigen::MatrixXd x = e * alpha;
    if (include) x = (row_positions(d).rowwise() - c) - x;
    for (std::size_t r = 0; r < d.rows(); ++r)
        out[d.map.vertex_of[r].idx()] = x.row(Eigen::Index(r)).norm();
    return out;
}

double s_orthonormality_error(const SpectralDecomposition& d) {
    if (d.empty()) return 0;
    const Eigen::MatrixXd g = d.eigenvectors.transpose() * (d.S.asDiagonal() * d.eigenvectors);
    return (g - Eigen::MatrixXd::Identity(g.rows(), g.cols())).cwiseAbs().maxCoeff();
}

}  // namespace trilab
