#include "core/algorithms/fairing.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <sstream>

#include <Eigen/Eigenvalues>
#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCholesky>

#include "core/algorithms/coincident.h"
#include "core/algorithms/weld.h"
#include "core/errors.h"
#include "core/geometry.h"

namespace trilab {

namespace {

using Triplet = Eigen::Triplet<double>;
using Positions = std::vector<Point>;
/// Per vertex storage index: 1 = kept where it is (copies of a coincident vertex that the
/// weld cannot join); empty: none.
using Pinned = std::vector<std::uint8_t>;

// smooth() maps the first four FairingOperator values onto LaplacianOperator by value.
static_assert(int(FairingOperator::Umbrella) == int(LaplacianOperator::Umbrella));
static_assert(int(FairingOperator::ImprovedUmbrella) == int(LaplacianOperator::ImprovedUmbrella));
static_assert(int(FairingOperator::CurvatureFlow) == int(LaplacianOperator::CurvatureFlow));
static_assert(int(FairingOperator::SecondOrder) == int(LaplacianOperator::SecondOrder));

// Health-check thresholds (see the header). A stable explicit step never lets the fairing
// energy grow (up to rounding: kEnergyRelativeSlack of it, plus kEnergyRoundingSlack of
// sum_i K_ii |x_i|², the size of a rounding error of the coordinates themselves); it can move
// the extreme vertices outwards a little (non-convex weights), far less than kBoxGrowth.
constexpr double kBoxGrowth = 0.10;     ///< largest growth of the bbox diagonal per iteration
constexpr double kAreaCollapse = 0.10;  ///< smallest area ratio to the previous iteration
constexpr double kEnergyRelativeSlack = 1e-9;
constexpr double kEnergyRoundingSlack = 1e-20;
constexpr double kDivergenceBound = 1e100;  ///< larger coordinates count as not finite

std::string format_number(double v) {
    char buffer[32];
    std::snprintf(buffer, sizeof(buffer), "%.3g", v);
    return buffer;
}

std::string format_percent(double ratio) {
    return format_number(100.0 * ratio) + "%";
}

double taubin_mu(const FairingOptions& o) {
    return o.taubin_pass_band > 0 ? 1.0 / (o.taubin_pass_band - 1.0 / o.taubin_lambda)
                                  : o.taubin_mu;
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
            fail("taubin_lambda must be in (0, 1] (got " + format_number(o.taubin_lambda) + ")");
        if (!std::isfinite(o.taubin_pass_band) || o.taubin_pass_band < 0)
            fail("taubin_pass_band must be 0 (use taubin_mu) or in (0, 1/taubin_lambda) (got " +
                 format_number(o.taubin_pass_band) + ")");
        if (o.taubin_pass_band > 0) {
            const double mu = taubin_mu(o);
            if (!(o.taubin_pass_band < 1.0) || !(mu >= -1.0))
                fail(
                    "taubin_pass_band must be in (0, 1) and at most 1/taubin_lambda - 1, so that "
                    "mu = 1/(k_PB - 1/lambda) is in [-1, -lambda) (got k_PB " +
                    format_number(o.taubin_pass_band) + ", lambda " +
                    format_number(o.taubin_lambda) + ")");
        } else if (!std::isfinite(o.taubin_mu) || !(o.taubin_mu < -o.taubin_lambda) ||
                   o.taubin_mu < -1.0) {
            fail("taubin_mu must be in [-1, -taubin_lambda) (got " + format_number(o.taubin_mu) +
                 ", lambda " + format_number(o.taubin_lambda) + ")");
        } else if (!(1.0 / o.taubin_lambda + 1.0 / o.taubin_mu < 1.0)) {
            // Beyond 1 the pass band covers most of the umbrella's spectrum [0, 2]: the mesh
            // grows instead of being smoothed.
            fail("taubin_mu must put the pass band 1/lambda + 1/mu below 1 (got " +
                 format_number(1.0 / o.taubin_lambda + 1.0 / o.taubin_mu) + " for lambda " +
                 format_number(o.taubin_lambda) + ", mu " + format_number(o.taubin_mu) +
                 "; Taubin suggests 0.01 to 0.1)");
        }
        if (o.integration != Integration::Explicit)
            fail("integration must be explicit for taubin (an implicit μ step is not stable)");
    }
    if (!std::isfinite(o.cg_tolerance) || !(o.cg_tolerance > 0))
        fail("cg_tolerance must be finite and > 0");
    if (!std::isfinite(o.max_relative_residual) || !(o.max_relative_residual > 0) ||
        o.max_relative_residual > 1e-2)
        fail("max_relative_residual must be in (0, 1e-2] (got " +
             format_number(o.max_relative_residual) + ")");
    if (o.cg_max_iterations < 0) fail("cg_max_iterations must be >= 0 (0: automatic)");
    if (o.preserve_volume && !is_closed(mesh))
        fail("preserve_volume needs a closed mesh (volume is not defined with a boundary)");
}

// ---- vertex-space helpers ------------------------------------------------------------------

struct Box {
    Point lo = Point::Constant(std::numeric_limits<double>::infinity());
    Point hi = Point::Constant(-std::numeric_limits<double>::infinity());
    void add(const Point& p) {
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
    }
    double diagonal() const { return lo.x() <= hi.x() ? (hi - lo).norm() : 0.0; }
    /// Every coordinate within ±kDivergenceBound (true when empty).
    bool bounded() const {
        return !(lo.x() <= hi.x()) ||
               std::max(lo.cwiseAbs().maxCoeff(), hi.cwiseAbs().maxCoeff()) <= kDivergenceBound;
    }
};

bool finite_and_bounded(const Point& p) {
    return std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z()) &&
           p.cwiseAbs().maxCoeff() <= kDivergenceBound;
}

struct AreaVolume {
    double area = std::numeric_limits<double>::quiet_NaN();  ///< NaN: not computed
    double volume = 0;
};

/// Signed volume (as geometry.h's volume()) over positions P and, with `with_area`, the
/// surface area (the square roots are most of the pass's cost).
AreaVolume area_volume(const HalfedgeMesh& mesh, const Positions& P, bool with_area) {
    AreaVolume r;
    double area = 0, volume = 0;
    for (Face f : mesh.faces()) {
        const auto v = mesh.face_vertices(f);
        const Point &a = P[v[0].idx()], &b = P[v[1].idx()], &c = P[v[2].idx()];
        const Vector3 n = (b - a).cross(c - a);
        if (with_area) area += 0.5 * n.norm();
        volume += (a + b + c).dot(n);
    }
    if (with_area) r.area = area;
    r.volume = volume / 18.0;
    return r;
}

/// Lanczos estimate of the largest eigenvalue of D·K·D (D = S^-½ on free entries, 0 on fixed
/// ones), i.e. of S⁻¹K over the free entries: the largest Ritz value after `steps` steps (no
/// reorthogonalization: only the extreme Ritz value is used). The start vector is a fixed
/// pseudo-random sign pattern. Returns 0 when nothing is free.
template <class ApplyK>
double lanczos_largest(const Eigen::VectorXd& d, const ApplyK& apply_k, int steps) {
    const Eigen::Index n = d.size();
    Eigen::VectorXd q = Eigen::VectorXd::Zero(n), q_prev = q, u(n), w(n);
    std::uint64_t state = 0x9E3779B97F4A7C15ull;
    for (Eigen::Index i = 0; i < n; ++i) {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        if (d[i] > 0) q[i] = (state & 1) ? 1.0 : -1.0;
    }
    const double qn = q.norm();
    if (!(qn > 0)) return 0;
    q /= qn;
    std::vector<double> alpha, beta;
    double beta_prev = 0;
    for (int j = 0; j < steps; ++j) {
        u = d.cwiseProduct(q);
        apply_k(u, w);
        w = d.cwiseProduct(w);
        const double a = w.dot(q);
        alpha.push_back(a);
        w -= a * q + beta_prev * q_prev;
        const double b = w.norm();
        if (!std::isfinite(b) || b <= 1e-12 * std::abs(a)) break;
        if (j + 1 < steps) beta.push_back(b);
        q_prev.swap(q);
        q = w / b;
        beta_prev = b;
    }
    const auto k = Eigen::Index(alpha.size());
    Eigen::MatrixXd t = Eigen::MatrixXd::Zero(k, k);
    for (Eigen::Index i = 0; i < k; ++i) {
        t(i, i) = alpha[std::size_t(i)];
        if (i + 1 < k) t(i, i + 1) = t(i + 1, i) = beta[std::size_t(i)];
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(t, Eigen::EigenvaluesOnly);
    return std::max(0.0, eig.eigenvalues().maxCoeff());
}

double stable_step_of(double rho) {
    return rho > 0 ? 2.0 / rho : std::numeric_limits<double>::infinity();
}

/// The umbrella operator in vertex space, without a matrix: per vertex storage index its
/// valence and whether it is fixed (found by the first product, one pass over the edges
/// either way; `pinned` vertices too); products by one pass over the edges.
class UmbrellaOperator {
public:
    explicit UmbrellaOperator(const HalfedgeMesh& mesh, const Pinned* pinned = nullptr)
        : mesh_(mesh), pinned_(pinned) {}

    /// out = P + t·L·P (fixed vertices copied); the bounding boxes of P and out over the
    /// vertices with edges, and whether every new coordinate is finite and bounded.
    bool step(const Positions& P, double t, Positions& out, Box& box_before, Box& box_after) {
        const std::size_t nv = P.size();
        out.assign(nv, Point::Zero());
        if (!known_) {
            // The first product also counts valences and finds the boundary.
            valence_.assign(nv, 0);
            fixed_.assign(nv, 0);
            for (Edge e : mesh_.edges()) {
                const Halfedge h = HalfedgeMesh::halfedge(e, 0), g = HalfedgeMesh::twin(h);
                const Index i = mesh_.to_vertex(g).idx(), j = mesh_.to_vertex(h).idx();
                out[i] += P[j];
                out[j] += P[i];
                ++valence_[i];
                ++valence_[j];
                if (mesh_.is_boundary(h) || mesh_.is_boundary(g)) fixed_[i] = fixed_[j] = 1;
            }
            for (std::size_t v = 0; v < nv; ++v)
                if (valence_[v] == 0 || (pinned_ && (*pinned_)[v])) fixed_[v] = 1;
            known_ = true;
        } else {
            for (Edge e : mesh_.edges()) {
                const Halfedge h = HalfedgeMesh::halfedge(e, 0);
                const Index i = mesh_.to_vertex(HalfedgeMesh::twin(h)).idx();
                const Index j = mesh_.to_vertex(h).idx();
                out[i] += P[j];
                out[j] += P[i];
            }
        }
        // NaN and infinities propagate into the sum; the box bounds the magnitude.
        double sum = 0;
        for (std::size_t v = 0; v < nv; ++v) {
            const Point& p = P[v];
            if (fixed_[v]) {
                out[v] = p;
                if (valence_[v] == 0) continue;
            } else {
                out[v] = p + t * (out[v] / double(valence_[v]) - p);
                sum += out[v].x() + out[v].y() + out[v].z();
            }
            box_before.add(p);
            box_after.add(out[v]);
        }
        return std::isfinite(sum) && box_after.bounded();
    }

    /// The energy xᵀKx = sum over edges |x_i - x_j|² and the rounding scale sum_i K_ii |x_i|².
    std::pair<double, double> energy(const Positions& P) const {
        double e = 0, q = 0;
        for (Edge ed : mesh_.edges()) {
            const Halfedge h = HalfedgeMesh::halfedge(ed, 0);
            const Point& a = P[mesh_.to_vertex(HalfedgeMesh::twin(h)).idx()];
            const Point& b = P[mesh_.to_vertex(h).idx()];
            e += (a - b).squaredNorm();
            q += a.squaredNorm() + b.squaredNorm();
        }
        return {e, q};
    }

    /// The Lanczos estimate of the largest stable explicit step.
    double max_stable_step(int steps) {
        if (!known_) {
            Positions scratch;
            Box a, b;
            step(mesh_.positions(), 0.0, scratch, a, b);
        }
        const std::size_t nv = valence_.size();
        Eigen::VectorXd d = Eigen::VectorXd::Zero(Eigen::Index(nv));
        for (std::size_t v = 0; v < nv; ++v)
            if (!fixed_[v]) d[Eigen::Index(v)] = 1.0 / std::sqrt(double(valence_[v]));
        return stable_step_of(lanczos_largest(
            d, [&](const Eigen::VectorXd& u, Eigen::VectorXd& w) { apply_k(u, w); }, steps));
    }

private:
    /// w = K·u (all entries).
    void apply_k(const Eigen::VectorXd& u, Eigen::VectorXd& w) const {
        for (std::size_t v = 0; v < valence_.size(); ++v)
            w[Eigen::Index(v)] = double(valence_[v]) * u[Eigen::Index(v)];
        for (Edge e : mesh_.edges()) {
            const Halfedge h = HalfedgeMesh::halfedge(e, 0);
            const auto i = Eigen::Index(mesh_.to_vertex(HalfedgeMesh::twin(h)).idx());
            const auto j = Eigen::Index(mesh_.to_vertex(h).idx());
            w[i] -= u[j];
            w[j] -= u[i];
        }
    }

    const HalfedgeMesh& mesh_;
    const Pinned* pinned_;
    bool known_ = false;
    std::vector<std::uint32_t> valence_;  ///< 0: isolated or deleted
    std::vector<std::uint8_t> fixed_;     ///< 1: does not move (boundary, isolated, deleted)
};

double max_stable_step_laplacian(const Laplacian& lap, int steps) {
    const auto n = Eigen::Index(lap.map.rows());
    Eigen::VectorXd d = Eigen::VectorXd::Zero(n);
    for (Eigen::Index r = 0; r < n; ++r)
        if (!lap.fixed[std::size_t(r)]) d[r] = 1.0 / std::sqrt(lap.S[r]);
    return stable_step_of(lanczos_largest(
        d, [&](const Eigen::VectorXd& u, Eigen::VectorXd& w) { w.noalias() = lap.K * u; }, steps));
}

/// Gershgorin's bound on the eigenvalues of S⁻¹K over the free rows: max_i sum_j |K_ij| / S_i
/// (explicit steps up to 2 over it are stable for sure).
double gershgorin_bound(const Laplacian& lap) {
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
    return m;
}

/// out = P + t·L·P for the operator's rows (other vertices copied); boxes and finiteness as
/// UmbrellaOperator::step, and Gershgorin's bound (gershgorin_bound()) from the same pass.
/// `rows` is scratch: the rows' positions gathered contiguously.
bool laplacian_step(const Laplacian& lap, const Positions& P, double t, Positions& out,
                    std::vector<Point>& rows, Box& box_before, Box& box_after, double& gershgorin) {
    out = P;
    const std::size_t n = lap.map.rows();
    const auto& vertex_of = lap.map.vertex_of;
    rows.resize(n);
    for (std::size_t r = 0; r < n; ++r) rows[r] = P[vertex_of[r].idx()];
    const int* outer = lap.K.outerIndexPtr();
    const int* inner = lap.K.innerIndexPtr();
    const double* value = lap.K.valuePtr();
    double sum = 0;
    gershgorin = 0;
    for (std::size_t r = 0; r < n; ++r) {
        const Index v = vertex_of[r].idx();
        const Point& p = rows[r];
        if (!lap.fixed[r]) {
            Vector3 kx = Vector3::Zero();
            double abs_sum = 0;
            for (int k = outer[r]; k < outer[r + 1]; ++k) {
                kx += value[k] * rows[std::size_t(inner[k])];
                abs_sum += std::abs(value[k]);
            }
            const double s = lap.S[Eigen::Index(r)];
            out[v] = p - (t / s) * kx;
            sum += out[v].x() + out[v].y() + out[v].z();
            if (std::isfinite(abs_sum / s)) gershgorin = std::max(gershgorin, abs_sum / s);
        }
        box_before.add(p);
        box_after.add(out[v]);
    }
    return std::isfinite(sum) && box_after.bounded();
}

/// xᵀKx over the operator's rows and the rounding scale sum_i (sum_j |K_ij|) |x_i|².
std::pair<double, double> laplacian_energy(const Laplacian& lap, const Positions& P) {
    const int* outer = lap.K.outerIndexPtr();
    const int* inner = lap.K.innerIndexPtr();
    const double* value = lap.K.valuePtr();
    const auto& vertex_of = lap.map.vertex_of;
    double e = 0, q = 0;
    for (std::size_t r = 0; r < lap.map.rows(); ++r) {
        const Point& p = P[vertex_of[r].idx()];
        Vector3 kx = Vector3::Zero();
        double abs_sum = 0;
        for (int k = outer[r]; k < outer[r + 1]; ++k) {
            kx += value[k] * P[vertex_of[std::size_t(inner[k])].idx()];
            abs_sum += std::abs(value[k]);
        }
        e += p.dot(kx);
        q += abs_sum * p.squaredNorm();
    }
    return {e, q};
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
    explicit BoundarySlider(const HalfedgeMesh& mesh, const Pinned& pinned) {
        std::vector<std::uint8_t> seen(mesh.halfedges_size(), 0);
        for (Halfedge h0 : mesh.halfedges()) {
            if (!mesh.is_boundary(h0) || seen[h0.idx()]) continue;
            Loop loop;
            Halfedge h = h0;
            do {
                seen[h.idx()] = 1;
                const Vertex v = mesh.from_vertex(h);
                loop.vertices.push_back(v.idx());
                loop.points.push_back(mesh.position(v));
                loop.pinned.push_back(pinned.empty() ? 0 : pinned[v.idx()]);
                h = mesh.next(h);
            } while (h != h0 && loop.vertices.size() <= mesh.n_halfedges());
            const std::size_t m = loop.vertices.size();
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

    /// One step of size t; writes the new positions of the loops' vertices into out.
    void step(double t, bool implicit, Positions& out) {
        for (Loop& loop : loops_) {
            const std::size_t m = loop.u.size();
            const std::vector<double> u = loop.u;
            auto prev = [&](std::size_t k) { return k == 0 ? u[m - 1] - loop.length : u[k - 1]; };
            auto next = [&](std::size_t k) { return k + 1 == m ? u[0] + loop.length : u[k + 1]; };
            if (!implicit) {
                for (std::size_t k = 0; k < m; ++k)
                    if (!loop.pinned[k]) loop.u[k] = u[k] + t * (0.5 * (prev(k) + next(k)) - u[k]);
            } else {
                std::vector<Triplet> trip;
                Eigen::VectorXd rhs(static_cast<Eigen::Index>(m));
                for (std::size_t k = 0; k < m; ++k) {
                    const auto i = Eigen::Index(k);
                    rhs[i] = u[k];
                    if (loop.pinned[k]) {
                        trip.emplace_back(i, i, 1.0);
                        continue;
                    }
                    trip.emplace_back(i, i, 1.0 + t);
                    trip.emplace_back(i, Eigen::Index((k + m - 1) % m), -0.5 * t);
                    trip.emplace_back(i, Eigen::Index((k + 1) % m), -0.5 * t);
                }
                if (!loop.pinned[0]) rhs[0] -= 0.5 * t * loop.length;
                if (!loop.pinned[m - 1]) rhs[Eigen::Index(m - 1)] += 0.5 * t * loop.length;
                SparseMatrix a(static_cast<Eigen::Index>(m), static_cast<Eigen::Index>(m));
                a.setFromTriplets(trip.begin(), trip.end());
                Eigen::SimplicialLDLT<SparseMatrix> ldlt(a);
                const Eigen::VectorXd sol = ldlt.solve(rhs);
                if (ldlt.info() == Eigen::Success && sol.allFinite())
                    for (std::size_t k = 0; k < m; ++k) loop.u[k] = sol[Eigen::Index(k)];
            }
            for (std::size_t k = 0; k < m; ++k)
                if (!loop.pinned[k]) out[loop.vertices[k]] = position_at(loop, loop.u[k]);
        }
    }

private:
    struct Loop {
        std::vector<Index> vertices;  ///< vertex indices, in loop order
        std::vector<Point> points;    ///< the original polyline
        std::vector<double> arc;      ///< arc length at each original vertex (m + 1 entries)
        double length = 0;
        std::vector<double> u;             ///< current parameters (unwrapped, increasing)
        std::vector<std::uint8_t> pinned;  ///< per loop vertex: 1 = stays where it is
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
/// its condition number bounded by 1 + t·G with G Gershgorin's bound on S⁻¹K (2 for umbrella
/// curvature flow and second order, about 4 for the improved umbrella).
/// Jacobi-preconditioned conjugate gradients warm-started from the current positions need
/// about sqrt(bound)·ln(2/tol)/2 iterations of O(nnz) each, far less than a sparse Cholesky
/// factorization (whose fill grows superlinearly with the mesh) when the bound is moderate.
/// So CG runs unless the bound exceeds kCgConditionLimit, or the weights are fixed
/// (umbrella), the factorization is reused by many iterations and the mesh is small enough
/// for it to be cheap.
constexpr double kCgConditionLimit = 1e3;
constexpr std::size_t kDirectRowsLimit = 60000;
constexpr int kDirectReuseIterations = 8;
constexpr int kLanczosSteps = 20;

double ms_between(std::chrono::steady_clock::time_point a,
                  std::chrono::steady_clock::time_point b) {
    return std::chrono::duration<double, std::milli>(b - a).count();
}

constexpr const char* kLdlt = "SimplicialLDLT";
constexpr const char* kCg = "ConjugateGradient(Jacobi)";

/// Taubin's transfer function f(k) = (1 - λk)(1 - μk) over the umbrella's spectrum [0, 2]:
/// its largest value (the pass-band gain, >= 1) and its value at k = 2.
struct TaubinGain {
    double gain = 1, at_two = 1;
};
TaubinGain taubin_gain(double lambda, double mu) {
    auto f = [&](double k) { return (1 - lambda * k) * (1 - mu * k); };
    TaubinGain g;
    g.at_two = f(2.0);
    g.gain = std::max(1.0, g.at_two);
    const double k_star = (lambda + mu) / (2 * lambda * mu);  // f is concave (λμ < 0)
    if (k_star > 0 && k_star < 2) g.gain = std::max(g.gain, f(k_star));
    return g;
}

/// One smooth() run on res.mesh (the caller's copy or moved-in mesh).
void run_fairing(const FairingOptions& o, Progress& progress, FairingResult& res,
                 const Pinned& pinned) {
    HalfedgeMesh& mesh = res.mesh;
    res.solver = "none";
    const bool taubin = o.op == FairingOperator::Taubin;
    const double mu = taubin_mu(o);
    const LaplacianOperator lop = taubin ? LaplacianOperator::Umbrella
                                         : static_cast<LaplacianOperator>(static_cast<int>(o.op));
    const bool weights_fixed = lop == LaplacianOperator::Umbrella;
    const bool implicit = o.integration == Integration::Implicit && !taubin;
    const bool fast = weights_fixed && !implicit;  // vertex-space umbrella, no matrix
    {
        std::ostringstream s;
        s << "operator " << fairing_operator_name(o.op) << ", " << integration_name(o.integration);
        if (taubin)
            s << ", lambda " << o.taubin_lambda << ", mu " << mu
              << (o.taubin_pass_band > 0 ? " (from the pass band k_PB " : "")
              << (o.taubin_pass_band > 0 ? format_number(o.taubin_pass_band) + ")" : "");
        else
            s << ", step " << o.step;
        s << ", " << o.iterations << " iteration(s)";
        if (o.preserve_volume) s << ", volume preserved";
        res.report.push_back(s.str());
    }
    const bool closed = is_closed(mesh);
    AreaVolume last;  // of the last good positions, where known (area: NaN when not)
    bool last_known = false;
    if (closed) {
        last = area_volume(mesh, mesh.positions(), true);
        last_known = true;
        res.initial_volume = last.volume;
    }
    const double v0 = res.initial_volume;
    // The volume's sign is checked where it is well defined: a closed mesh whose volume is
    // not negligible against its bounding box.
    const double diag0 = closed ? bounding_box(mesh).diagonal() : 0.0;
    const bool check_volume_sign = closed && std::abs(v0) > 1e-9 * diag0 * diag0 * diag0;

    LaplacianOptions lap_options;
    lap_options.fixed_vertices = pinned;
    std::optional<UmbrellaOperator> umbrella;
    if (fast) umbrella.emplace(mesh, pinned.empty() ? nullptr : &pinned);
    Laplacian lap;
    bool have_lap = false;
    ImplicitSystem sys;
    const bool slide = o.boundary == BoundaryMode::Slide && !closed;
    std::optional<BoundarySlider> slider;
    if (slide) {
        slider.emplace(mesh, pinned);
        res.report.push_back("boundary: " + std::to_string(slider->loops()) +
                             " loop(s) sliding along the input's boundary curves");
    }
    bool slide_explicit_fallback = false;
    bool use_direct = o.solver == ImplicitSolver::Direct;
    bool used_ldlt = false, used_cg = false;
    const TaubinGain gain = taubin ? taubin_gain(o.taubin_lambda, mu) : TaubinGain{};
    if (fast && o.estimate_max_stable_step)
        res.max_stable_step = umbrella->max_stable_step(kLanczosSteps);
    if (o.keep_steps) res.step_positions.reserve(std::size_t(o.iterations));

    Positions cand, tmp;
    // The energy of the current positions under a fixed operator (reused by the next check).
    std::pair<double, double> energy_now{0, 0};
    bool energy_known = false;

    auto stop = [&](int iteration, const std::string& why) {
        res.stopped_early = true;
        res.stopped_at_iteration = iteration;
        res.stop_reason = "iteration " + std::to_string(iteration) + ": " + why;
        res.report.push_back("stopped: " + res.stop_reason);
    };
    // The hint for an explicit instability, with the stable limit at the last good state.
    auto instability_hint = [&]() {
        const double limit = fast ? umbrella->max_stable_step(kLanczosSteps)
                                  : max_stable_step_laplacian(lap, kLanczosSteps);
        if (taubin)
            return " (lambda " + format_number(o.taubin_lambda) + " and mu " + format_number(mu) +
                   " are unstable on this mesh: the umbrella's stable step here is about " +
                   format_number(limit) + "; keep lambda and |mu| below it)";
        if (o.step > limit)
            return " (step " + format_number(o.step) + " is above the stable limit " +
                   format_number(limit) +
                   " of this mesh; use a smaller step or implicit integration)";
        return " (step " + format_number(o.step) + ", stable limit about " + format_number(limit) +
               " on this mesh; use a smaller step or implicit integration)";
    };

    for (int it = 0; it < o.iterations; ++it) {
        const int iteration = it + 1;
        progress.check_cancelled();
        progress.report(double(it) / o.iterations, "smoothing");
        const Positions& P = mesh.positions();
        if (!fast && (!have_lap || !weights_fixed)) {
            if (have_lap)
                refresh_laplacian(mesh, lap);
            else
                lap = build_laplacian(mesh, lop, lap_options);
            auto& d = res.diagnostics;
            const auto& n = lap.diagnostics;
            d.negative_weights_clamped += n.negative_weights_clamped;
            d.degenerate_corners += n.degenerate_corners;
            d.cotangents_clamped += n.cotangents_clamped;
            d.short_edges += n.short_edges;
            d.stalled_vertices = std::max(d.stalled_vertices, n.stalled_vertices);
            if (!have_lap && o.estimate_max_stable_step)
                res.max_stable_step = max_stable_step_laplacian(lap, kLanczosSteps);
            have_lap = true;
            energy_known = false;
            if (implicit) {
                sys.build(lap, o.step);
                if (it == 0 && o.solver == ImplicitSolver::Auto) {
                    const double cond = 1.0 + o.step * gershgorin_bound(lap);
                    use_direct = cond > kCgConditionLimit ||
                                 (weights_fixed && o.iterations >= kDirectReuseIterations &&
                                  lap.map.rows() <= kDirectRowsLimit);
                    std::ostringstream s;
                    s << "solver choice: condition bound " << cond << ", " << lap.map.rows()
                      << " rows -> " << (use_direct ? kLdlt : kCg);
                    res.report.push_back(s.str());
                }
            }
        }

        // The candidate positions of this iteration.
        Box box_before, box_after;
        bool finite = true;
        bool check_energy = false;  // the step is not provably stable
        double energy_gain = 1;     // the largest energy factor a stable step allows
        if (fast && taubin) {
            Box unused;
            finite = umbrella->step(P, o.taubin_lambda, tmp, box_before, unused);
            finite = umbrella->step(tmp, mu, cand, unused, box_after) && finite;
            energy_gain = gain.gain * gain.gain;
            check_energy = gain.at_two < -gain.gain;
        } else if (fast) {
            finite = umbrella->step(P, o.step, cand, box_before, box_after);
            check_energy = o.step > 1.0;  // Gershgorin: the umbrella's spectrum is in [0, 2]
        } else if (!implicit) {
            double g = 0;
            finite = laplacian_step(lap, P, o.step, cand, tmp, box_before, box_after, g);
            check_energy = o.step * g > 2.0;
        } else {
            cand = P;
            const auto nf = Eigen::Index(sys.free_rows.size());
            if (nf > 0) {
                const auto n = Eigen::Index(lap.map.rows());
                Eigen::MatrixXd x(n, 3), xf(nf, 3);
                for (Eigen::Index r = 0; r < n; ++r)
                    x.row(r) = P[lap.map.vertex_of[std::size_t(r)].idx()].transpose();
                for (Eigen::Index f = 0; f < nf; ++f)
                    xf.row(f) = x.row(sys.free_rows[std::size_t(f)]);
                Eigen::MatrixXd rhs = sys.S.asDiagonal() * xf;
                if (sys.Kfb.nonZeros() > 0) rhs -= o.step * (sys.Kfb * x);
                const double rn = rhs.norm();
                const bool direct_first = use_direct;
                Eigen::MatrixXd y;
                bool accepted = false;
                std::string failures;
                for (int attempt = 0; attempt < 2 && !accepted; ++attempt) {
                    const bool direct = (attempt == 0) == direct_first;
                    double residual = std::numeric_limits<double>::infinity();
                    std::ostringstream line;
                    line << "iteration " << iteration << ": " << (direct ? kLdlt : kCg);
                    if (direct) {
                        if (!sys.factored) {
                            const auto t0 = std::chrono::steady_clock::now();
                            sys.ldlt.compute(sys.A);
                            res.factorization_ms +=
                                ms_between(t0, std::chrono::steady_clock::now());
                            sys.factored = true;
                            sys.factor_ok = sys.ldlt.info() == Eigen::Success;
                            ++res.factorizations;
                        }
                        if (sys.factor_ok) {
                            const auto t0 = std::chrono::steady_clock::now();
                            y = sys.ldlt.solve(rhs);
                            res.solve_ms += ms_between(t0, std::chrono::steady_clock::now());
                            if (sys.ldlt.info() != Eigen::Success) y.resize(0, 0);
                        } else {
                            y.resize(0, 0);
                            line << " (the factorization failed)";
                        }
                    } else {
                        const auto t0 = std::chrono::steady_clock::now();
                        Eigen::ConjugateGradient<SparseMatrix, Eigen::Lower | Eigen::Upper,
                                                 Eigen::DiagonalPreconditioner<double>>
                            cg;
                        cg.setTolerance(o.cg_tolerance);
                        cg.setMaxIterations(o.cg_max_iterations > 0
                                                ? Eigen::Index(o.cg_max_iterations)
                                                : std::max<Eigen::Index>(1000, 4 * nf));
                        cg.compute(sys.A);
                        y = cg.solveWithGuess(rhs, xf);
                        res.cg_iterations += std::size_t(cg.iterations());
                        res.solve_ms += ms_between(t0, std::chrono::steady_clock::now());
                        line << " (" << cg.iterations() << " iteration(s))";
                    }
                    if (y.rows() == nf && y.allFinite())
                        residual = rn > 0 ? (sys.A * y - rhs).norm() / rn : (sys.A * y).norm();
                    if (!std::isfinite(residual))
                        residual = std::numeric_limits<double>::infinity();
                    line << ", relative residual " << residual;
                    accepted = residual <= o.max_relative_residual;
                    if (!accepted) {
                        line << " above " << o.max_relative_residual;
                        if (attempt == 0) line << "; retrying with " << (direct ? kCg : kLdlt);
                        failures += std::string(failures.empty() ? "" : ", ") +
                                    (direct ? kLdlt : kCg) + " relative residual " +
                                    format_number(residual);
                    } else {
                        (direct ? used_ldlt : used_cg) = true;
                        res.max_residual = std::max(res.max_residual, residual);
                    }
                    res.report.push_back(line.str());
                }
                if (!accepted) {
                    stop(iteration, "the implicit solve failed (" + failures + "; required " +
                                        format_number(o.max_relative_residual) + ")");
                    break;
                }
                for (Eigen::Index f = 0; f < nf; ++f) {
                    const Index v =
                        lap.map.vertex_of[std::size_t(sys.free_rows[std::size_t(f)])].idx();
                    cand[v] = y.row(f).transpose();
                    finite = finite && finite_and_bounded(cand[v]);
                }
            }
        }

        // Health checks of the step itself (before the boundary slides and the volume is
        // restored, which are not part of the operator).
        if (!finite) {
            stop(iteration, std::string("a coordinate is not finite or above 1e100") +
                                (implicit ? "" : instability_hint()));
            break;
        }
        if (!implicit) {
            const double d0 = box_before.diagonal(), d1 = box_after.diagonal();
            if (d0 > 0 && d1 > (1 + kBoxGrowth) * d0) {
                stop(iteration, "the bounding box grew by " + format_percent(d1 / d0 - 1) +
                                    " in one iteration" + instability_hint());
                break;
            }
            if (check_energy) {
                if (!energy_known)
                    energy_now = fast ? umbrella->energy(P) : laplacian_energy(lap, P);
                const auto next = fast ? umbrella->energy(cand) : laplacian_energy(lap, cand);
                const double e0 = energy_now.first, limit = energy_gain * e0;
                if (!(next.first <= limit + kEnergyRelativeSlack * limit +
                                        kEnergyRoundingSlack * energy_now.second)) {
                    stop(iteration,
                         "the fairing energy grew by " +
                             (e0 > 0 ? format_percent(next.first / e0 - 1) : std::string("?")) +
                             instability_hint());
                    break;
                }
                energy_now = next;  // valid for the next iteration only with fixed weights
                energy_known = weights_fixed;
            }
        }
        if (slider) {
            const double t = taubin ? o.taubin_lambda : o.step;
            const bool implicit_curve = implicit || t > 1.0;
            slide_explicit_fallback = slide_explicit_fallback || (!implicit && t > 1.0);
            slider->step(t, implicit_curve, cand);
            energy_known = false;
        }
        // The area collapse check runs with the energy check and for the geometry-dependent
        // operators; the volume's sign is checked on every iteration of a closed mesh (a
        // provably stable step can still turn a very coarse mesh inside out: umbrella step 1
        // maps a tetrahedron to its reflection scaled by 1/3).
        const bool area_check = !implicit && (!weights_fixed || check_energy);
        if (area_check || check_volume_sign || o.preserve_volume) {
            if (area_check && !(last_known && last.area >= 0))
                last = area_volume(mesh, P, true);  // the last good state's area, once
            const AreaVolume g = area_volume(mesh, cand, area_check);
            if (area_check && last.area > 0 && g.area < kAreaCollapse * last.area) {
                stop(iteration, "the surface area fell to " + format_percent(g.area / last.area) +
                                    " of the previous iteration's" + instability_hint());
                break;
            }
            if (check_volume_sign && !(g.volume * v0 > 0)) {
                stop(iteration, "the volume changed sign (from " + format_number(v0) + " to " +
                                    format_number(g.volume) + ")" +
                                    (implicit ? "" : instability_hint()));
                break;
            }
            last = g;
            last_known = true;
        } else {
            last_known = false;
        }
        if (o.preserve_volume) {
            // Scale about the centroid of the vertices with edges by (V0/Vn)^(1/3).
            const double beta = std::cbrt(v0 / last.volume);
            Point c = Point::Zero();
            std::size_t count = 0;
            for (Vertex v : mesh.vertices())
                if (!mesh.is_isolated(v)) {
                    c += cand[v.idx()];
                    ++count;
                }
            if (count > 0) c /= double(count);
            bool ok = std::isfinite(beta) && beta > 0;
            for (Vertex v : mesh.vertices()) {
                if (!ok || mesh.is_isolated(v)) continue;
                Point& p = cand[v.idx()];
                p = c + beta * (p - c);
                ok = finite_and_bounded(p);
            }
            if (!ok) {
                stop(iteration, "the volume could not be restored (volume " +
                                    format_number(last.volume) + ")");
                break;
            }
            last.area *= beta * beta;
            last.volume = v0;
            energy_known = false;
        }
        // Commit: the candidate becomes the mesh's positions (a swap, no copy).
        std::swap(mesh.positions(), cand);
        ++res.iterations_done;
        if (o.keep_steps) res.step_positions.push_back(mesh.positions());
    }
    if (slide_explicit_fallback)
        res.report.push_back(
            "boundary: steps above 1 move along the curve implicitly (an "
            "explicit 1-D step above 1 is unstable)");
    progress.report(1.0, "smoothing");
    if (closed) res.final_volume = last_known ? last.volume : volume(mesh);
    if (!std::isnan(res.max_stable_step))
        res.report.push_back("largest stable explicit step at the input: about " +
                             format_number(res.max_stable_step) +
                             (taubin ? " (the umbrella's, which bounds lambda)" : ""));
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
        res.solver = used_ldlt && used_cg ? std::string(kLdlt) + " + " + kCg
                     : used_ldlt          ? kLdlt
                     : used_cg            ? kCg
                                          : "none";
        std::ostringstream s;
        s << "solver " << res.solver << ", " << res.factorizations << " factorization(s), "
          << res.cg_iterations << " CG iteration(s), max relative "
          << "residual " << res.max_residual;
        res.report.push_back(s.str());
    }
}

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

namespace {

/// smooth() of res.mesh, which has coincident vertices: the run is on its weld
/// (core/algorithms/weld.h), where a seam is interior and the copies of a split vertex are one
/// vertex, with the copies that the weld cannot join fixed; every copy then takes its welded
/// vertex's positions.
void smooth_coincident(FairingResult& res, const FairingOptions& o, Progress& progress) {
    WeldResult weld = weld_coincident_vertices(res.mesh);
    check_options(weld.mesh, o);  // closed when welded: volume preservation applies
    Pinned pinned(weld.mesh.vertices_size(), 0);
    const CoincidentGroups apart = find_coincident_vertices(weld.mesh);
    for (Index v : apart.members) pinned[v] = 1;
    FairingResult welded;
    welded.mesh = std::move(weld.mesh);
    run_fairing(o, progress, welded, pinned);
    HalfedgeMesh mesh = std::move(res.mesh);
    auto unweld = [&](const Positions& pw) {
        Positions p = mesh.positions();
        for (Vertex v : mesh.vertices())  // isolated vertices stay (the weld may join them)
            if (!mesh.is_isolated(v)) p[v.idx()] = pw[weld.vertex_map[v.idx()]];
        return p;
    };
    mesh.positions() = unweld(welded.mesh.positions());
    for (Positions& step : welded.step_positions) step = unweld(step);
    res = std::move(welded);
    res.mesh = std::move(mesh);
    std::ostringstream s;
    s << "coincident vertices (seams, copies of split vertices): "
      << weld.report.coincident_vertices << " in " << weld.report.groups
      << " groups smoothed as one surface (" << weld.report.vertices_joined
      << " joined for the operator)";
    if (!apart.empty())
        s << ", " << apart.members.size() << " kept where they are (they cannot be joined)";
    res.report.insert(res.report.begin() + 1, s.str());
}

FairingResult smooth_mesh(FairingResult res, const FairingOptions& options, Progress& progress) {
    if (find_coincident_vertices(res.mesh).empty()) {
        check_options(res.mesh, options);
        run_fairing(options, progress, res, Pinned());
    } else {
        smooth_coincident(res, options, progress);
    }
    return res;
}

}  // namespace

FairingResult smooth(const HalfedgeMesh& mesh, const FairingOptions& options, Progress& progress) {
    FairingResult res;
    res.mesh = mesh;
    return smooth_mesh(std::move(res), options, progress);
}

FairingResult smooth(HalfedgeMesh&& mesh, const FairingOptions& options, Progress& progress) {
    FairingResult res;
    res.mesh = std::move(mesh);
    return smooth_mesh(std::move(res), options, progress);
}

double max_stable_explicit_step(const HalfedgeMesh& mesh, FairingOperator op, int lanczos_steps) {
    if (lanczos_steps < 1 || lanczos_steps > 1000)
        throw InvalidArgument("max_stable_explicit_step: lanczos_steps must be in [1, 1000] (got " +
                              std::to_string(lanczos_steps) + ")");
    if (op == FairingOperator::Umbrella || op == FairingOperator::Taubin) {
        UmbrellaOperator umbrella(mesh);
        return umbrella.max_stable_step(lanczos_steps);
    }
    const Laplacian lap =
        build_laplacian(mesh, static_cast<LaplacianOperator>(static_cast<int>(op)));
    return max_stable_step_laplacian(lap, lanczos_steps);
}

}  // namespace trilab
