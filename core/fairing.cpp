#include "core/fairing.h"

#include <algorithm>
#include <cmath>
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

const char* kLdlt = "SimplicialLDLT";
const char* kCg = "ConjugateGradient(Jacobi)";

}  // namespace

const char* fairing_operator_name(FairingOperator op) {
    switch (op) {
        case FairingOperator::Umbrella:
            return "umbrella";
        case FairingOperator::ImprovedUmbrella:
            return "improved-umbrella";
        case FairingOperator::CurvatureFlow:
            return "curvature-flow";
        case FairingOperator::SecondOrder:
            return "second-order";
        case FairingOperator::Taubin:
            return "taubin";
    }
    return "?";
}

FairingOperator parse_fairing_operator(const std::string& name) {
    for (auto op :
         {FairingOperator::Umbrella, FairingOperator::ImprovedUmbrella,
          FairingOperator::CurvatureFlow, FairingOperator::SecondOrder, FairingOperator::Taubin})
        if (name == fairing_operator_name(op)) return op;
    throw InvalidArgument("parse_fairing_operator: unknown operator '" + name +
                          "' (expected umbrella, improved-umbrella, curvature-flow, "
                          "second-order, taubin)");
}

const char* integration_name(Integration integration) {
    return integration == Integration::Explicit ? "explicit" : "implicit";
}

Integration parse_integration(const std::string& name) {
    if (name == "explicit") return Integration::Explicit;
    if (name == "implicit") return Integration::Implicit;
    throw InvalidArgument("parse_integration: unknown integration '" + name +
                          "' (expected explicit, implicit)");
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
    Laplacian lap;
    bool have_lap = false;
    ImplicitSystem sys;
    res.steps.reserve(std::size_t(o.iterations));

    for (int it = 0; it < o.iterations; ++it) {
        progress.check_cancelled();
        progress.report(double(it) / o.iterations, "smoothing");
        if (!have_lap || !weights_fixed) {
            lap = build_laplacian(current, lop);
            auto& d = res.diagnostics;
            const auto& n = lap.diagnostics;
            d.negative_weights_clamped += n.negative_weights_clamped;
            d.degenerate_corners += n.degenerate_corners;
            d.cotangents_clamped += n.cotangents_clamped;
            d.short_edges += n.short_edges;
            d.stalled_vertices = std::max(d.stalled_vertices, n.stalled_vertices);
            have_lap = true;
            if (implicit) sys.build(lap, o.step);
        }
        Eigen::MatrixXd x = gather_positions(current, lap.map);
        if (taubin) {
            x += o.taubin_lambda * (lap.L * x);
            x += o.taubin_mu * (lap.L * x);
        } else if (!implicit) {
            x += o.step * (lap.L * x);
        } else if (!sys.free_rows.empty()) {
            const auto nf = Eigen::Index(sys.free_rows.size());
            Eigen::MatrixXd xf(nf, 3);
            for (Eigen::Index f = 0; f < nf; ++f) xf.row(f) = x.row(sys.free_rows[std::size_t(f)]);
            const Eigen::MatrixXd rhs = sys.S.asDiagonal() * xf - o.step * (sys.Kfb * x);
            Eigen::MatrixXd y;
            bool ok = false;
            const char* used = kLdlt;
            if (o.solver != ImplicitSolver::Iterative) {
                if (!sys.factored) {
                    sys.ldlt.compute(sys.A);
                    sys.factored = true;
                    sys.factor_ok = sys.ldlt.info() == Eigen::Success;
                    ++res.factorizations;
                }
                if (sys.factor_ok) {
                    y = sys.ldlt.solve(rhs);
                    ok = sys.ldlt.info() == Eigen::Success && finite_and_bounded(y);
                    if (!ok) sys.factor_ok = false;
                }
            }
            if (!ok) {
                used = kCg;
                Eigen::ConjugateGradient<SparseMatrix, Eigen::Lower | Eigen::Upper,
                                         Eigen::DiagonalPreconditioner<double>>
                    cg;
                cg.setTolerance(o.cg_tolerance);
                cg.setMaxIterations(std::max<Eigen::Index>(1000, 4 * nf));
                cg.compute(sys.A);
                y = cg.solveWithGuess(rhs, xf);
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
            res.report.push_back("diverged at iteration " + std::to_string(it + 1) +
                                 ": stopped (use a smaller step or implicit integration)");
            break;
        }
        scatter_positions(current, lap.map, x);
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
        res.steps.push_back(current);
    }
    progress.report(1.0, "smoothing");
    if (is_closed(mesh)) res.final_volume = volume(current);
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
        s << "solver " << res.solver << ", " << res.factorizations
          << " factorization(s), max relative residual " << res.max_residual;
        res.report.push_back(s.str());
    }
    return res;
}

}  // namespace trilab
