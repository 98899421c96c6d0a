#include "core/fairing.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <sstream>

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCholesky>

#include "core/errors.h"
#include "core/geometry.h"

namespace trilab {

namespace {

using Triplet = Eigen::Triplet<double>;

// smooth() maps the first four FairingOperator values onto LaplacianOperator by value.
static_assert(int(FairingOperator::Umbrella) == int(LaplacianOperator::Umbrella));
static_assert(int(FairingOperator::ImprovedUmbrella) == int(LaplacianOperator::ImprovedUmbrella));
static_assert(int(FairingOperator::CurvatureFlow) == int(LaplacianOperator::CurvatureFlow));
static_assert(int(FairingOperator::SecondOrder) == int(LaplacianOperator::SecondOrder));

constexpr double kDivergenceBound = 1e100;

bool finite_and_bounded(const Eigen::MatrixXd& x) {
    for (Eigen::Index i = 0; i < x.size(); ++i) {
        const double v = x.data()[i];
        if (!std::isfinite(v) || std::abs(v) > kDivergenceBound) return false;
    }
    return true;
}

void check_options(const HalfedgeMesh& mesh, const FairingOptions& o) {
    auto fail = [](const std::string& what) { throw InvalidArgument("smooth: " + what); };
    if (!std::isfinite(o.step) || o.step < 0)
        fail("step must be finite and >= 0 (got " + std::to_string(o.step) + ")");
    if (o.iterations < 1 || o.iterations > kMaxFairingIterations)
        fail("iterations must be in [1, " + std::to_string(kMaxFairingIterations) + "] (got " +
             std::to_string(o.iterations) + ")");
    if (o.op == FairingOperator::Taubin) {
        if (!std::isfinite(o.taubin_lambda) || !(o.taubin_lambda > 0) || o.taubin_lambda > 1)
            fail("taubin_lambda must be in (0, 1]");
        if (!std::isfinite(o.taubin_mu) || !(o.taubin_mu < -o.taubin_lambda) || o.taubin_mu < -1.0)
            fail("taubin_mu must be in [-1, -taubin_lambda)");
        if (o.integration != Integration::Explicit)
            fail("integration must be explicit for taubin (an implicit μ step is not stable)");
    }
    if (!std::isfinite(o.cg_tolerance) || !(o.cg_tolerance > 0))
        fail("cg_tolerance must be finite and > 0");
    if (o.preserve_volume && !is_closed(mesh))
        fail("preserve_volume needs a closed mesh (volume is not defined with a boundary)");
}

/// The implicit system over the free rows of one Laplacian.
struct ImplicitSystem {
    std::vector<Index> free_rows;  ///< free index -> row
    SparseMatrix A;                ///< S_ff + step K_ff (SPD)
    SparseMatrix Kfb;              ///< free rows x all rows, fixed columns only
    Eigen::VectorXd S;             ///< S_ff
    Eigen::SimplicialLDLT<SparseMatrix> ldlt;
    bool factored = false, factor_ok = false;

    void build(const Laplacian& lap, double step) {
        const std::size_t n = lap.map.rows();
        std::vector<Index> free_of(n, kInvalidIndex);
        free_rows.clear();
        for (std::size_t r = 0; r < n; ++r)
            if (!lap.fixed[r]) {
                free_of[r] = Index(free_rows.size());
                free_rows.push_back(Index(r));
            }
        const auto nf = Eigen::Index(free_rows.size());
        factored = factor_ok = false;
        if (std::size_t(nf) == n) {
            // Nothing fixed (a closed mesh): A = S + step·K on K's own pattern, no assembly.
            S = lap.S;
            A = lap.K;
            A *= step;
            for (std::size_t r = 0; r < n; ++r)
                A.valuePtr()[lap.diag_slots[r]] += S[Eigen::Index(r)];
            Kfb.resize(nf, Eigen::Index(n));
            return;
        }
        S.resize(nf);
        std::vector<Triplet> ta, tb;
        for (Eigen::Index f = 0; f < nf; ++f) {
            S[f] = lap.S[free_rows[std::size_t(f)]];
            ta.emplace_back(f, f, S[f]);
        }
        for (Eigen::Index c = 0; c < lap.K.outerSize(); ++c)
            for (SparseMatrix::InnerIterator it(lap.K, c); it; ++it) {
                const Index fr = free_of[std::size_t(it.row())];
                if (fr == kInvalidIndex) continue;
                const Index fc = free_of[std::size_t(it.col())];
                if (fc != kInvalidIndex)
                    ta.emplace_back(fr, fc, step * it.value());
                else
                    tb.emplace_back(fr, it.col(), it.value());
            }
        A.resize(nf, nf);
        A.setFromTriplets(ta.begin(), ta.end());
        Kfb.resize(nf, Eigen::Index(n));
        Kfb.setFromTriplets(tb.begin(), tb.end());
        factored = factor_ok = false;
    }
};

/// Boundary vertices sliding along the input's boundary curves (BoundaryMode::Slide). Each
/// loop keeps its original polyline; a vertex is an arc-length parameter u on it, smoothed by
/// the 1-D umbrella u_i <- u_i + t·((u_{i-1} + u_{i+1})/2 - u_i) (parameters unwrapped across
/// the loop's start), explicitly for t <= 1 and implicitly otherwise (the cyclic system
/// (I + t/2·C)·u' = u + t/2·c, C the cyclic second difference and c the wrap-around terms
/// ∓length at the loop's first and last vertex). Both keep the vertices in order, so each
/// stays on the curve between its neighbours. Positions are the polyline at u (linear between
/// the original vertices).
class BoundarySlider {
public:
    BoundarySlider(const HalfedgeMesh& mesh, const VertexIndexMap& map) {
        std::vector<std::uint8_t> seen(mesh.halfedges_size(), 0);
        for (Halfedge h0 : mesh.halfedges()) {
            if (!mesh.is_boundary(h0) || seen[h0.idx()]) continue;
            Loop loop;
            Halfedge h = h0;
            do {
                seen[h.idx()] = 1;
                const Vertex v = mesh.from_vertex(h);
                loop.rows.push_back(map.row_of[v.idx()]);
                loop.points.push_back(mesh.position(v));
                h = mesh.next(h);
            } while (h != h0 && loop.rows.size() <= mesh.n_halfedges());
            const std::size_t m = loop.rows.size();
            loop.arc.resize(m + 1, 0.0);
            for (std::size_t k = 0; k < m; ++k)
                loop.arc[k + 1] = loop.arc[k] + (loop.points[(k + 1) % m] - loop.points[k]).norm();
            loop.length = loop.arc[m];
            loop.u.assign(loop.arc.begin(), loop.arc.end() - 1);
            if (m >= 3 && loop.length > 0 && std::isfinite(loop.length))
                loops_.push_back(std::move(loop));
        }
    }
    std::size_t loops() const { return loops_.size(); }

    /// One step of size t; writes the new positions into the loops' rows of x.
    void step(double t, bool implicit, Eigen::MatrixXd& x) {
        for (Loop& loop : loops_) {
            const std::size_t m = loop.u.size();
            const std::vector<double> u = loop.u;
            auto prev = [&](std::size_t k) { return k == 0 ? u[m - 1] - loop.length : u[k - 1]; };
            auto next = [&](std::size_t k) { return k + 1 == m ? u[0] + loop.length : u[k + 1]; };
            if (!implicit) {
                for (std::size_t k = 0; k < m; ++k)
                    loop.u[k] = u[k] + t * (0.5 * (prev(k) + next(k)) - u[k]);
            } else {
                std::vector<Triplet> trip;
                Eigen::VectorXd rhs(static_cast<Eigen::Index>(m));
                for (std::size_t k = 0; k < m; ++k) {
                    const auto i = Eigen::Index(k);
                    trip.emplace_back(i, i, 1.0 + t);
                    trip.emplace_back(i, Eigen::Index((k + m - 1) % m), -0.5 * t);
                    trip.emplace_back(i, Eigen::Index((k + 1) % m), -0.5 * t);
                    rhs[i] = u[k];
                }
                rhs[0] -= 0.5 * t * loop.length;
                rhs[Eigen::Index(m - 1)] += 0.5 * t * loop.length;
                SparseMatrix a(static_cast<Eigen::Index>(m), static_cast<Eigen::Index>(m));
                a.setFromTriplets(trip.begin(), trip.end());
                Eigen::SimplicialLDLT<SparseMatrix> ldlt(a);
                const Eigen::VectorXd sol = ldlt.solve(rhs);
                if (ldlt.info() == Eigen::Success && sol.allFinite())
                    for (std::size_t k = 0; k < m; ++k) loop.u[k] = sol[Eigen::Index(k)];
            }
            for (std::size_t k = 0; k < m; ++k)
                x.row(loop.rows[k]) = position_at(loop, loop.u[k]).transpose();
        }
    }

private:
    struct Loop {
        std::vector<Index> rows;    ///< operator rows, in loop order
        std::vector<Point> points;  ///< the original polyline
        std::vector<double> arc;    ///< arc length at each original vertex (m + 1 entries)
        double length = 0;
        std::vector<double> u;  ///< current parameters (unwrapped, increasing)
    };
    static Point position_at(const Loop& loop, double u) {
        double w = std::fmod(u, loop.length);
        if (w < 0) w += loop.length;
        const std::size_t m = loop.points.size();
        const std::size_t k = std::size_t(std::clamp<std::ptrdiff_t>(
            std::upper_bound(loop.arc.begin(), loop.arc.end(), w) - loop.arc.begin() - 1, 0,
            std::ptrdiff_t(m - 1)));
        const double seg = loop.arc[k + 1] - loop.arc[k];
        const double a = seg > 0 ? std::clamp((w - loop.arc[k]) / seg, 0.0, 1.0) : 0.0;
        return (1 - a) * loop.points[k] + a * loop.points[(k + 1) % m];
    }
    std::vector<Loop> loops_;
};

/// Automatic solver choice for implicit steps. The system S + t·K, preconditioned by S, has
/// its condition number bounded by 1 + t·max_i (K_ii + sum_j |K_ij|)/S_i (Gershgorin on
/// S⁻¹K): 1 + 2t for umbrella and curvature flow (normalized, off-diagonals <= 0), a small
/// multiple of t for second order, but large for the scale-dependent improved umbrella
/// (K_ii/S_i ~ 1/h²).
/// Jacobi-preconditioned conjugate gradients warm-started from the current positions need
/// about sqrt(bound)·ln(2/tol)/2 iterations of O(nnz) each, far less than a sparse Cholesky
/// factorization (whose fill grows superlinearly with the mesh) when the bound is moderate.
/// So CG runs unless the bound exceeds kCgConditionLimit, or the weights are fixed
/// (umbrella), the factorization is reused by many iterations and the mesh is small enough
/// for it to be cheap.
constexpr double kCgConditionLimit = 1e3;
constexpr std::size_t kDirectRowsLimit = 60000;
constexpr int kDirectReuseIterations = 8;

/// The bound above over the free rows of `lap`: Gershgorin's 1 + step·max_i (K_ii +
/// sum_j |K_ij|) / S_i (which is 1 + step·2·K_ii/S_i where off-diagonals are all <= 0).
double condition_bound(const Laplacian& lap, double step) {
    double m = 0;
    const int* outer = lap.K.outerIndexPtr();
    const double* value = lap.K.valuePtr();
    for (std::size_t r = 0; r < lap.map.rows(); ++r) {
        if (lap.fixed[r]) continue;
        double row_sum = 0;
        for (int k = outer[r]; k < outer[r + 1]; ++k) row_sum += std::abs(value[k]);
        const double ratio = row_sum / lap.S[Eigen::Index(r)];
        if (std::isfinite(ratio)) m = std::max(m, ratio);
    }
    return 1.0 + step * m;
}

/// lx = L·x for the operator's rows, computed as -S⁻¹(K·x) by gathering along K's columns
/// (K is symmetric, so column r holds row r) from a row-major copy of x: one contiguous
/// 3-vector read per neighbour instead of Eigen's scattered column-major product. Fixed rows
/// get zero.
void apply_laplacian(const Laplacian& lap, const Eigen::MatrixXd& x,
                     Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>& xr,
                     Eigen::MatrixXd& lx) {
    const Eigen::Index n = x.rows();
    xr = x;
    lx.resize(n, 3);
    const int* outer = lap.K.outerIndexPtr();
    const int* inner = lap.K.innerIndexPtr();
    const double* value = lap.K.valuePtr();
    const double* p = xr.data();
    for (Eigen::Index r = 0; r < n; ++r) {
        if (lap.fixed[std::size_t(r)]) {
            lx(r, 0) = lx(r, 1) = lx(r, 2) = 0.0;
            continue;
        }
        double ax = 0, ay = 0, az = 0;
        for (int k = outer[r]; k < outer[r + 1]; ++k) {
            const double w = value[k];
            const double* q = p + 3 * std::ptrdiff_t(inner[k]);
            ax += w * q[0];
            ay += w * q[1];
            az += w * q[2];
        }
        const double s = -1.0 / lap.S[r];
        lx(r, 0) = s * ax;
        lx(r, 1) = s * ay;
        lx(r, 2) = s * az;
    }
}

double ms_between(std::chrono::steady_clock::time_point a,
                  std::chrono::steady_clock::time_point b) {
    return std::chrono::duration<double, std::milli>(b - a).count();
}

const char* kLdlt = "SimplicialLDLT";
const char* kCg = "ConjugateGradient(Jacobi)";

}  // namespace

const char* fairing_operator_name(FairingOperator op) {
    return enum_id<FairingOperator>(kFairingOperators, op);
}

FairingOperator parse_fairing_operator(const std::string& name) {
    return parse_enum<FairingOperator>(kFairingOperators, name, "fairing operator");
}

const char* boundary_mode_name(BoundaryMode mode) {
    return enum_id<BoundaryMode>(kBoundaryModes, mode);
}

BoundaryMode parse_boundary_mode(const std::string& name) {
    return parse_enum<BoundaryMode>(kBoundaryModes, name, "boundary mode");
}

const char* integration_name(Integration integration) {
    return enum_id<Integration>(kIntegrations, integration);
}

Integration parse_integration(const std::string& name) {
    return parse_enum<Integration>(kIntegrations, name, "integration");
}

FairingResult smooth(const HalfedgeMesh& mesh, const FairingOptions& options) {
    NullProgress progress;
    return smooth(mesh, options, progress);
}

FairingResult smooth(const HalfedgeMesh& mesh, const FairingOptions& o, Progress& progress) {
    check_options(mesh, o);
    FairingResult res;
    res.solver = "none";
    const bool taubin = o.op == FairingOperator::Taubin;
    const LaplacianOperator lop = taubin ? LaplacianOperator::Umbrella
                                         : static_cast<LaplacianOperator>(static_cast<int>(o.op));
    const bool weights_fixed = lop == LaplacianOperator::Umbrella;
    const bool implicit = o.integration == Integration::Implicit && !taubin;
    {
        std::ostringstream s;
        s << "operator " << fairing_operator_name(o.op) << ", " << integration_name(o.integration)
          << ", step " << o.step << ", " << o.iterations << " iteration(s)";
        if (taubin) s << ", lambda " << o.taubin_lambda << ", mu " << o.taubin_mu;
        if (o.preserve_volume) s << ", volume preserved";
        res.report.push_back(s.str());
    }
    if (o.preserve_volume || is_closed(mesh)) res.initial_volume = volume(mesh);
    const double v0 = res.initial_volume;

    HalfedgeMesh current = mesh;
    const bool slide = o.boundary == BoundaryMode::Slide && !is_closed(mesh);
    std::optional<BoundarySlider> slider;
    Laplacian lap;
    bool have_lap = false;
    ImplicitSystem sys;
    if (o.keep_steps) res.steps.reserve(std::size_t(o.iterations));
    bool slide_explicit_fallback = false;

    int done = 0;
    Eigen::MatrixXd x, lx, x_good;  // positions of the operator's rows, L·x, last good x
    // The mesh follows x only where something reads it: a kept step, the next build of
    // geometry-dependent weights, the volume, or the end.
    const bool lazy_mesh = !o.keep_steps && weights_fixed && !o.preserve_volume;
    Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> xr;
    bool use_direct = o.solver == ImplicitSolver::Direct;
    for (int it = 0; it < o.iterations; ++it) {
        progress.check_cancelled();
        progress.report(double(it) / o.iterations, "smoothing");
        if (!have_lap || !weights_fixed) {
            if (have_lap)
                refresh_laplacian(current, lap);
            else
                lap = build_laplacian(current, lop);
            auto& d = res.diagnostics;
            const auto& n = lap.diagnostics;
            d.negative_weights_clamped += n.negative_weights_clamped;
            d.degenerate_corners += n.degenerate_corners;
            d.cotangents_clamped += n.cotangents_clamped;
            d.short_edges += n.short_edges;
            d.stalled_vertices = std::max(d.stalled_vertices, n.stalled_vertices);
            have_lap = true;
            if (implicit) {
                sys.build(lap, o.step);
                if (it == 0 && o.solver == ImplicitSolver::Auto) {
                    const double cond = condition_bound(lap, o.step);
                    use_direct = cond > kCgConditionLimit ||
                                 (weights_fixed && o.iterations >= kDirectReuseIterations &&
                                  lap.map.rows() <= kDirectRowsLimit);
                    std::ostringstream s;
                    s << "solver choice: condition bound " << cond << ", " << lap.map.rows()
                      << " rows -> " << (use_direct ? kLdlt : kCg);
                    res.report.push_back(s.str());
                }
            }
            if (slide && !slider) {
                slider.emplace(mesh, lap.map);
                res.report.push_back("boundary: " + std::to_string(slider->loops()) +
                                     " loop(s) sliding along the input's boundary curves");
            }
        }
        if (it == 0) x = gather_positions(current, lap.map);  // x stays in sync from here on
        if (lazy_mesh && it > 0) x_good = x;                  // what the mesh would hold now
        if (slider) {
            const double t = taubin ? o.taubin_lambda : o.step;
            const bool implicit_curve = implicit || t > 1.0;
            slide_explicit_fallback = slide_explicit_fallback || (!implicit && t > 1.0);
            slider->step(t, implicit_curve, x);
        }
        if (taubin) {
            apply_laplacian(lap, x, xr, lx);
            x += o.taubin_lambda * lx;
            apply_laplacian(lap, x, xr, lx);
            x += o.taubin_mu * lx;
        } else if (!implicit) {
            apply_laplacian(lap, x, xr, lx);
            x += o.step * lx;
        } else if (!sys.free_rows.empty()) {
            const auto nf = Eigen::Index(sys.free_rows.size());
            Eigen::MatrixXd xf(nf, 3);
            for (Eigen::Index f = 0; f < nf; ++f) xf.row(f) = x.row(sys.free_rows[std::size_t(f)]);
            const Eigen::MatrixXd rhs = sys.S.asDiagonal() * xf - o.step * (sys.Kfb * x);
            Eigen::MatrixXd y;
            bool ok = false;
            const char* used = kLdlt;
            if (use_direct) {
                if (!sys.factored) {
                    const auto t0 = std::chrono::steady_clock::now();
                    sys.ldlt.compute(sys.A);
                    res.factorization_ms += ms_between(t0, std::chrono::steady_clock::now());
                    sys.factored = true;
                    sys.factor_ok = sys.ldlt.info() == Eigen::Success;
                    ++res.factorizations;
                }
                if (sys.factor_ok) {
                    const auto t0 = std::chrono::steady_clock::now();
                    y = sys.ldlt.solve(rhs);
                    res.solve_ms += ms_between(t0, std::chrono::steady_clock::now());
                    ok = sys.ldlt.info() == Eigen::Success && finite_and_bounded(y);
                    if (!ok) sys.factor_ok = false;
                }
            }
            if (!ok) {
                used = kCg;
                const auto t0 = std::chrono::steady_clock::now();
                Eigen::ConjugateGradient<SparseMatrix, Eigen::Lower | Eigen::Upper,
                                         Eigen::DiagonalPreconditioner<double>>
                    cg;
                cg.setTolerance(o.cg_tolerance);
                cg.setMaxIterations(std::max<Eigen::Index>(1000, 4 * nf));
                cg.compute(sys.A);
                y = cg.solveWithGuess(rhs, xf);
                res.cg_iterations += std::size_t(cg.iterations());
                res.solve_ms += ms_between(t0, std::chrono::steady_clock::now());
            }
            const double rn = rhs.norm();
            const double residual = rn > 0 ? (sys.A * y - rhs).norm() / rn : (sys.A * y).norm();
            res.max_residual =
                std::max(res.max_residual, std::isfinite(residual) ? residual : 1e300);
            if (res.solver == "none" || res.solver == used)
                res.solver = used;
            else
                res.solver = std::string(kLdlt) + " + " + kCg;
            std::ostringstream s;
            s << "iteration " << it + 1 << ": " << used << ", relative residual " << residual;
            res.report.push_back(s.str());
            for (Eigen::Index f = 0; f < nf; ++f) x.row(sys.free_rows[std::size_t(f)]) = y.row(f);
        }
        if (!finite_and_bounded(x)) {
            res.diverged = true;
            if (lazy_mesh && done > 0) scatter_positions(current, lap.map, x_good);
            res.report.push_back("diverged at iteration " + std::to_string(it + 1) +
                                 ": stopped (use a smaller step or implicit integration)");
            break;
        }
        if (!lazy_mesh || it + 1 == o.iterations) scatter_positions(current, lap.map, x);
        if (o.preserve_volume) {
            const double vn = volume(current);
            const double ratio = v0 / vn;
            if (std::isfinite(ratio) && ratio > 0 && lap.map.rows() > 0) {
                const double beta = std::cbrt(ratio);
                const Eigen::RowVector3d c = x.colwise().mean();
                x = ((x.rowwise() - c) * beta).rowwise() + c;
                if (finite_and_bounded(x)) scatter_positions(current, lap.map, x);
            } else {
                res.report.push_back("iteration " + std::to_string(it + 1) +
                                     ": volume could not be restored (volume " +
                                     std::to_string(vn) + ")");
            }
        }
        if (o.keep_steps) res.steps.push_back(current);
        ++done;
    }
    if (!o.keep_steps && done > 0) res.steps.push_back(std::move(current));
    if (slide_explicit_fallback)
        res.report.push_back(
            "boundary: steps above 1 move along the curve implicitly (an "
            "explicit 1-D step above 1 is unstable)");
    progress.report(1.0, "smoothing");
    if (is_closed(mesh) && !res.steps.empty()) res.final_volume = volume(res.steps.back());
    const auto& d = res.diagnostics;
    if (d.total() > 0) {
        std::ostringstream s;
        s << "clamped: " << d.negative_weights_clamped << " negative cotangent weight(s), "
          << d.degenerate_corners << " degenerate corner(s), " << d.cotangents_clamped
          << " large cotangent(s), " << d.short_edges << " short edge(s), " << d.stalled_vertices
          << " vertex(es) fixed for lack of weight";
        res.report.push_back(s.str());
    }
    if (implicit) {
        std::ostringstream s;
        s << "solver " << res.solver << ", " << res.factorizations << " factorization(s), "
          << res.cg_iterations << " CG iteration(s), max relative "
          << "residual " << res.max_residual;
        res.report.push_back(s.str());
    }
    return res;
}

}  // namespace trilab
