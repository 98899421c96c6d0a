// Fairing (core/algorithms/fairing.h): the methods, what `step` means, the health checks.
//
// Fairing (smoothing) by diffusion, dX/dt = L(X) (section 1.2.3 of the reference report), with
// the operators of core/algorithms/laplacian.h:
//  - explicit Euler (1.4/1.6): X <- X + step·L·X;
//  - implicit Euler (1.13-1.14, Desbrun-Meyer-Schröder-Barr 1999): (I - step·L)·X' = X,
//    solved in the symmetric form (S + step·K)·X' = S·X - step·K_fb·X_b (fixed vertices on
//    the right) with Eigen::SimplicialLDLT (reused across iterations when the weights do not
//    depend on the geometry) or Jacobi-preconditioned conjugate gradients warm-started from
//    the current positions, chosen by the system's condition bound and size;
//  - Taubin λ|μ (Taubin 1995): explicit umbrella steps X <- X + λ·L·X then X <- X + μ·L·X
//    per iteration (0 < λ <= 1, -1 <= μ < -λ, pass band k_PB = 1/λ + 1/μ below 1), or μ
//    from k_PB. Taubin uses λ and μ, never `step`;
//  - volume preservation (1.15): after every step the mesh is scaled about the centroid of
//    its vertices by (V0/Vn)^(1/3). Closed meshes only.
//
// What `step` means (every operator is scale-free, so it means the same on any mesh size):
//  - Umbrella, CurvatureFlow: the fraction of the way to the neighbours' (weighted) average
//    each vertex moves; every explicit step <= 1 is stable, the limit is about 1.3 (umbrella)
//    and 1.0-1.3 (curvature flow) on typical meshes.
//  - ImprovedUmbrella: twice that on a mesh of equal edges (lengths in units of the mean edge
//    length); the explicit limit is about 0.4-0.5, and it falls during a run when short edges
//    shorten further (the reference's "numerical instability"): prefer implicit.
//  - SecondOrder: step 1 is the relaxation (1.12), damped per vertex (about 2/3) so that the
//    simultaneous update is stable; every explicit step <= 1 is stable (the limit is about
//    1.2-1.3).
//  - implicit: any step > 0 is stable; step t smooths about like t explicit steps of 1.
// max_stable_explicit_step() estimates the limit for the actual mesh (explicit Euler is stable
// while step < 2/ρ(S⁻¹K)).
//
// Health checks (never a silent failure): an implicit solve whose relative residual is above
// max_relative_residual (1e-8) is retried with the sparse Cholesky factorization; if that
// fails too the run stops. An explicit iteration stops the run when a coordinate is not
// finite, the bounding box grows by more than 10 % in one iteration, the fairing energy xᵀKx
// of the step's own operator grows (explicit Euler below the stable limit never lets it grow;
// Taubin: more than its pass-band gain allows), the surface area falls below 10 % of the
// previous iteration's, or the volume of a closed mesh changes sign (implicit runs check the
// residual, finiteness and the volume's sign). The energy check runs where the step is not
// provably stable (step·G > 2, G Gershgorin's bound on S⁻¹K: 2 for umbrella, curvature flow
// and second order, about 4 for the improved umbrella); the area check with it and for the
// geometry-dependent operators; the volume's sign on every iteration of a closed mesh (even a
// stable step turns a tetrahedron inside out). So a provably stable umbrella or Taubin iteration
// costs one pass over the edges and one over the vertices (and one over the faces on a closed
// mesh). A stopped run keeps the iterations before the failing one: result.mesh is the last good
// state, stopped_early is set and stop_reason names the iteration and the reason (for an explicit
// instability with the stable limit at the last good state).
//
// Boundary vertices stay fixed (or slide along the boundary curve); isolated vertices never
// move. Connectivity and attributes other than positions are copied unchanged.
// Coincident vertices (core/algorithms/coincident.h: a seam between patches, the copies
// build_mesh() makes of a non-manifold vertex) move as one: the run is on the mesh welded where
// that keeps it manifold (core/algorithms/weld.h), so a seam is smoothed as interior surface (its
// curve is a boundary only where no partner lies on it) and a mesh closed up to its seams counts as
// closed (volume preservation applies); copies that cannot be joined (surfaces touching at a
// point) stay where they are. Every copy gets its joined vertex's positions, bit for bit.
// Throws InvalidArgument naming the option (`step`, `iterations`, `taubin_lambda`,
// `taubin_mu`, `taubin_pass_band`, `integration`, `preserve_volume`, `cg_tolerance`,
// `max_relative_residual`, `cg_max_iterations`) before doing anything; Cancelled from the
// progress. The input mesh is never modified.
// Complexity: explicit O(iterations · (V + F)) with one position-sized buffer beyond the
// result (two for Taubin; umbrella and Taubin build no matrix); implicit one factorization per
// iteration (one in all for umbrella) plus a solve per iteration. A region of an explicit
// umbrella or Taubin run (without volume preservation or a sliding boundary) costs O(V + F)
// once, then per iteration only its moving vertices' rings, the faces around them for the
// area and volume checks and the stable-step estimate's products
// (UmbrellaOperator::restrict_to_moving(), MovingFaceSums): the same positions bit for bit.
// A whole-mesh explicit umbrella or Taubin run on a big mesh (from 65,536 vertices; no region,
// slide or volume rescaling) works in a Morton order of the operator
// (UmbrellaOperator::localize(): the neighbour gathers, which bound these passes, close in
// memory), its positions permuted in and out once: the same positions bit for bit.
#include "core/algorithms/fairing.h"

#include <algorithm>
#include <array>
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
#include "core/algorithms/feature_detection.h"
#include "core/algorithms/selection.h"
#include "core/algorithms/weld.h"
#include "core/errors.h"
#include "core/features.h"
#include "core/geometry.h"
#include "core/mesh_builder.h"
#include "core/number_text.h"
#include "core/parallel.h"

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
    return taubin_mu_of(o);
}

void check_options(const HalfedgeMesh& mesh, const FairingOptions& o) {
    auto fail = [](const std::string& what) { throw InvalidArgument("smooth: " + what); };
    if (!std::isfinite(o.step) || o.step < 0)
        fail("step must be finite and >= 0 (got " + number_text(o.step) + ")");
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
        } else if (const double mu = taubin_mu(o);
                   !std::isfinite(mu) || !(mu < -o.taubin_lambda) || mu < -1.0) {
            fail("taubin_mu must be in [-1, -taubin_lambda) (got " + format_number(mu) +
                 (o.taubin_mu == 0 ? " following lambda through the pass band " +
                                         format_number(kDefaultTaubinPassBand)
                                   : std::string()) +
                 ", lambda " + format_number(o.taubin_lambda) + ")");
        } else if (!(1.0 / o.taubin_lambda + 1.0 / mu < 1.0)) {
            // Beyond 1 the pass band covers most of the umbrella's spectrum [0, 2]: the mesh
            // grows instead of being smoothed.
            fail("taubin_mu must put the pass band 1/lambda + 1/mu below 1 (got " +
                 format_number(1.0 / o.taubin_lambda + 1.0 / mu) + " for lambda " +
                 format_number(o.taubin_lambda) + ", mu " + format_number(mu) +
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
    /// Adds every point of `other` (nothing when it is empty).
    void add(const Box& other) {
        if (!(other.lo.x() <= other.hi.x())) return;
        add(other.lo);
        add(other.hi);
    }
    double diagonal() const { return lo.x() <= hi.x() ? (hi - lo).norm() : 0.0; }
    /// Every coordinate within ±kDivergenceBound (true when empty).
    bool bounded() const {
        return !(lo.x() <= hi.x()) ||
               std::max(lo.cwiseAbs().maxCoeff(), hi.cwiseAbs().maxCoeff()) <= kDivergenceBound;
    }
};

/// A block's part of an explicit step's figures: the finiteness sum and the two boxes.
struct StepPart {
    double sum = 0;
    Box before, after;
    static StepPart combine(const StepPart& a, const StepPart& b) {
        StepPart r = a;
        r.sum += b.sum;
        r.before.add(b.before);
        r.after.add(b.after);
        return r;
    }
};

bool all_finite(const Positions& P) {
    for (const Point& p : P)
        if (!p.allFinite()) return false;
    return true;
}

bool finite_and_bounded(const Point& p) {
    return std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z()) &&
           p.cwiseAbs().maxCoeff() <= kDivergenceBound;
}

struct CandidateSums {
    double area = std::numeric_limits<double>::quiet_NaN();  ///< NaN: not computed
    double volume = 0;
};

/// Signed volume (as geometry.h's volume()) over positions P and, with `with_area`, the
/// surface area (the square roots are most of the pass's cost).
/// `map` (optional): P is in another numbering, vertex v at P[map[v]] (the same sums, bit for
/// bit: the faces and corners are visited in the same order).
CandidateSums area_volume(const HalfedgeMesh& mesh, const Positions& P, bool with_area,
                          const Index* map = nullptr) {
    // Over the faces in fixed blocks, the partial sums added in block order (the same bits for
    // any number of threads).
    const Vertex* to = mesh.halfedge_to_array().data();
    const Halfedge* next = mesh.halfedge_next_array().data();
    const Halfedge* fh = mesh.face_halfedge_array().data();
    using Sums = std::pair<double, double>;
    const Sums sums = parallel_reduce(
        0, mesh.faces_size(), Sums{0, 0},
        [&](std::size_t begin, std::size_t end) {
            double area = 0, volume = 0;
            for (std::size_t f = begin; f < end; ++f) {
                if (mesh.is_deleted(Face(Index(f)))) continue;
                const Index h0 = fh[f].idx(), h1 = next[h0].idx(), h2 = next[h1].idx();
                Index i0 = to[h0].idx(), i1 = to[h1].idx(), i2 = to[h2].idx();
                if (map) i0 = map[i0], i1 = map[i1], i2 = map[i2];
                const Point &a = P[i0], &b = P[i1], &c = P[i2];
                const Vector3 n = (b - a).cross(c - a);
                if (with_area) area += 0.5 * n.norm();
                volume += (a + b + c).dot(n);
            }
            return Sums{area, volume};
        },
        [](const Sums& x, const Sums& y) {
            return Sums{x.first + y.first, x.second + y.second};
        });
    CandidateSums r;
    if (with_area) r.area = sums.first;
    r.volume = sums.second / 18.0;
    return r;
}

/// area_volume() of positions that differ from P0 (given at construction) only at the listed
/// moving vertices: the faces without a moving vertex are summed once (their area on the first
/// call that asks for it), the others on every call. Equal to area_volume() up to rounding (the
/// sums run in another order).
class MovingFaceSums {
public:
    MovingFaceSums(const HalfedgeMesh& mesh, const Positions& P0,
                   const std::vector<Index>& moving) {
        std::vector<std::uint8_t> is_moving(mesh.vertices_size(), 0);
        for (Index v : moving) is_moving[v] = 1;
        for (Face f : mesh.faces()) {
            const auto v = mesh.face_vertices(f);
            const Triangle t{v[0].idx(), v[1].idx(), v[2].idx()};
            (is_moving[t[0]] || is_moving[t[1]] || is_moving[t[2]] ? moving_faces_ : fixed_faces_)
                .push_back(t);
        }
        fixed_ = sums_over(fixed_faces_, P0, false);
    }

    CandidateSums sums(const Positions& P, bool with_area) {
        if (with_area && std::isnan(fixed_.area))
            fixed_.area = sums_over(fixed_faces_, P, true).area;  // P equals P0 there
        const CandidateSums m = sums_over(moving_faces_, P, with_area);
        CandidateSums r;
        if (with_area) r.area = fixed_.area + m.area;
        r.volume = (fixed_.volume + m.volume) / 18.0;
        return r;
    }

private:
    using Triangle = std::array<Index, 3>;
    /// The area (with_area) and 18 times the signed volume of the triangles.
    static CandidateSums sums_over(const std::vector<Triangle>& faces, const Positions& P,
                                   bool with_area) {
        double area = 0, volume = 0;
        for (const Triangle& t : faces) {
            const Point &a = P[t[0]], &b = P[t[1]], &c = P[t[2]];
            const Vector3 n = (b - a).cross(c - a);
            if (with_area) area += 0.5 * n.norm();
            volume += (a + b + c).dot(n);
        }
        CandidateSums r;
        if (with_area) r.area = area;
        r.volume = volume;
        return r;
    }

    std::vector<Triangle> moving_faces_, fixed_faces_;
    CandidateSums fixed_;  ///< of the fixed faces (area NaN until asked for)
};

/// w = D·w and the sum of w_i·q_i over fixed blocks, added in block order: the second half of
/// a Lanczos product for operators that compute K·u apart (the Laplacian's matrix).
double scale_and_dot(const Eigen::VectorXd& d, Eigen::VectorXd& w, const Eigen::VectorXd& q) {
    return parallel_reduce(
        0, std::size_t(w.size()), 0.0,
        [&](std::size_t begin, std::size_t end) {
            double part = 0;
            for (auto i = Eigen::Index(begin); i < Eigen::Index(end); ++i) {
                w[i] = d[i] * w[i];
                part += w[i] * q[i];
            }
            return part;
        },
        [](double x, double y) { return x + y; });
}

/// Lanczos estimate of the largest eigenvalue of D·K·D (D = S^-½ on free entries, 0 on fixed
/// ones), i.e. of S⁻¹K over the free entries: the largest Ritz value after `steps` steps (no
/// reorthogonalization: only the extreme Ritz value is used). The start vector is a fixed
/// pseudo-random sign pattern. Returns 0 when nothing is free.
/// `apply_dk_dot(u, w, q)` sets w = D·K·u and returns the sum of w_i·q_i over fixed blocks of
/// kBlock rows, added in block order (scale_and_dot()), so that an operator can fuse the
/// product with the scaling and the dot product (one pass instead of two).
/// `order` (optional): entry i stands for vertex order[i] (a renumbered operator,
/// UmbrellaOperator::localize()), which gets the sign the pattern gives that vertex.
template <class ApplyDKDot>
double lanczos_largest(const Eigen::VectorXd& d, const ApplyDKDot& apply_dk_dot, int steps,
                       const std::vector<Index>* order = nullptr) {
    const Eigen::Index n = d.size();
    Eigen::VectorXd q = Eigen::VectorXd::Zero(n), q_prev = q, u(n), w(n);
    std::vector<double> sign(static_cast<std::size_t>(n));
    std::uint64_t state = 0x9E3779B97F4A7C15ull;
    for (std::size_t i = 0; i < std::size_t(n); ++i) {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        sign[i] = (state & 1) ? 1.0 : -1.0;
    }
    for (Eigen::Index i = 0; i < n; ++i)
        if (d[i] > 0) q[i] = sign[order ? (*order)[std::size_t(i)] : std::size_t(i)];
    const double qn = q.norm();
    if (!(qn > 0)) return 0;
    q /= qn;
    std::vector<double> alpha, beta;
    double beta_prev = 0;
    // The vector steps fused into three passes (the product with its scaling and dot product;
    // the update with its norm; the next vector with the next product's input), each in fixed
    // blocks on every thread with its sums added in block order (core/parallel.h): the same
    // bits for any number of threads.
    const auto sum = [](double x, double y) { return x + y; };
    const auto rows = std::size_t(n);
    parallel_for(0, rows, [&](std::size_t i) {
        u[Eigen::Index(i)] = d[Eigen::Index(i)] * q[Eigen::Index(i)];
    });
    for (int j = 0; j < steps; ++j) {
        const double a = apply_dk_dot(u, w, q);
        alpha.push_back(a);
        const double b = std::sqrt(parallel_reduce(
            0, rows, 0.0,
            [&](std::size_t begin, std::size_t end) {
                double part = 0;
                for (auto i = Eigen::Index(begin); i < Eigen::Index(end); ++i) {
                    w[i] -= a * q[i] + beta_prev * q_prev[i];
                    part += w[i] * w[i];
                }
                return part;
            },
            sum));
        if (!std::isfinite(b) || b <= 1e-12 * std::abs(a) || j + 1 == steps) break;
        beta.push_back(b);
        q_prev.swap(q);
        parallel_for(0, rows, [&](std::size_t i) {
            const auto e = Eigen::Index(i);
            q[e] = w[e] / b;
            u[e] = d[e] * q[e];
        });
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

/// Vertices from this many on: explicit umbrella and Taubin runs renumber the operator
/// (UmbrellaOperator::localize()); fairing_detail::set_locality_threshold() changes it.
std::size_t g_locality_threshold = std::size_t(1) << 16;

/// 10 bits spread to every third bit (bit k to bit 3k).
inline std::uint32_t spread_bits(std::uint32_t x) {
    x &= 0x3FFu;
    x = (x | (x << 16)) & 0x030000FFu;
    x = (x | (x << 8)) & 0x0300F00Fu;
    x = (x | (x << 4)) & 0x030C30C3u;
    x = (x | (x << 2)) & 0x09249249u;
    return x;
}

/// The vertices in the order of a Morton (Z-order) curve through their positions quantized to
/// 2^10 steps per axis of the bounding box of the finite ones (ties, and non-finite positions,
/// which go first, in storage order): entry k is the storage index of the k-th. A stable LSD
/// radix sort (two 15-bit digits), O(V), on one thread: the same order for any thread count.
std::vector<Index> morton_order(const Positions& P) {
    const std::size_t n = P.size();
    Box box;
    for (const Point& p : P)
        if (p.allFinite()) box.add(p);
    Point scale = Point::Zero();
    for (int a = 0; a < 3 && box.lo.x() <= box.hi.x(); ++a) {
        const double extent = box.hi[a] - box.lo[a];
        if (extent > 0 && std::isfinite(extent)) scale[a] = 1023.0 / extent;
    }
    std::vector<std::uint32_t> code(n);
    parallel_for(0, n, [&](std::size_t i) {
        const Point& p = P[i];
        std::uint32_t c = 0;
        if (p.allFinite())
            for (int a = 0; a < 3; ++a) {
                const double q = std::min(1023.0, std::max(0.0, (p[a] - box.lo[a]) * scale[a]));
                c |= spread_bits(std::uint32_t(q)) << a;
            }
        code[i] = c;
    });
    constexpr std::uint32_t kDigit = 15, kBuckets = 1u << kDigit;
    std::vector<Index> order(n), from(n);
    for (std::size_t i = 0; i < n; ++i) from[i] = Index(i);
    std::vector<std::size_t> count(kBuckets);
    for (std::uint32_t shift = 0; shift < 2 * kDigit; shift += kDigit) {
        std::fill(count.begin(), count.end(), 0);
        for (std::size_t i = 0; i < n; ++i) ++count[(code[from[i]] >> shift) & (kBuckets - 1)];
        std::size_t sum = 0;
        for (std::size_t& c : count) {
            const std::size_t here = c;
            c = sum;
            sum += here;
        }
        for (std::size_t i = 0; i < n; ++i)
            order[count[(code[from[i]] >> shift) & (kBuckets - 1)]++] = from[i];
        order.swap(from);
    }
    return from;
}

/// The umbrella operator in vertex space, without a matrix: per vertex storage index its
/// valence and whether it is fixed (found by the first product, one pass over the edges
/// either way; `pinned` vertices too); products by one pass over the edges.
class UmbrellaOperator {
public:
    /// `gather`: the whole-mesh products gather each vertex's row (built once, on every thread)
    /// instead of scattering over the edges on one thread; worth it from a few products on (a
    /// run of several iterations, the stable-step estimate). The same bits either way.
    explicit UmbrellaOperator(const HalfedgeMesh& mesh, const Pinned* pinned = nullptr,
                              bool gather = true)
        : mesh_(mesh), pinned_(pinned), gather_(gather) {}

    /// Renumbers the operator along a Morton curve of P (morton_order()): its rows (in the new
    /// numbering, each still in edge order), valences and fixed flags, so that a product gathers
    /// neighbours that lie close in memory (on a big mesh whose numbering does not follow the
    /// surface, such as a subdivided one, about twice as fast). Afterwards step(), energy() and
    /// the stable-step estimate take positions in that order (to_local(), to_storage()); each
    /// vertex sums the same neighbours in the same order, so the positions are those of the
    /// storage order bit for bit (the estimate's sums run in the new order: equal up to
    /// rounding). Whole-mesh gathering operators on meshes without garbage only.
    void localize(const Positions& P) {
        if (!known_) find_fixed();
        const std::size_t nv = valence_.size(), ne = mesh_.edges_size();
        order_ = morton_order(P);
        rank_.resize(nv);
        std::vector<std::uint32_t> valence(nv);
        std::vector<std::uint8_t> fixed(nv);
        parallel_for(0, nv, [&](std::size_t k) {
            rank_[order_[k]] = Index(k);
            valence[k] = valence_[order_[k]];
            fixed[k] = fixed_[order_[k]];
        });
        valence_.swap(valence);
        fixed_.swap(fixed);
        row_offset_.assign(nv + 1, 0);
        for (std::size_t k = 0; k < nv; ++k) row_offset_[k + 1] = row_offset_[k] + valence_[k];
        row_.resize(row_offset_[nv]);
        // The rows in the new numbering by an owner scan over the edges (as build_rows()): each
        // row in edge order.
        const Vertex* to = mesh_.halfedge_to_array().data();
        const bool garbage = mesh_.has_garbage();
        parallel_ranges(0, nv, [&](std::size_t lo, std::size_t hi) {
            std::vector<std::size_t> fill(row_offset_.begin() + std::ptrdiff_t(lo),
                                          row_offset_.begin() + std::ptrdiff_t(hi));
            for (std::size_t e = 0; e < ne; ++e) {
                if (garbage && mesh_.is_deleted(Edge(Index(e)))) continue;
                const Index i = rank_[to[2 * e + 1].idx()], j = rank_[to[2 * e].idx()];
                if (i - lo < hi - lo) row_[fill[i - lo]++] = j;
                if (j - lo < hi - lo) row_[fill[j - lo]++] = i;
            }
        });
        rows_built_ = true;
        local_ = true;
    }
    bool local() const { return local_; }
    /// localize(): the new number of each storage index (null before).
    const Index* rank() const { return local_ ? rank_.data() : nullptr; }
    /// Positions in storage order to the localize() order, and back.
    void to_local(const Positions& in, Positions& out) const {
        out.resize(in.size());
        parallel_for(0, in.size(), [&](std::size_t k) { out[k] = in[order_[k]]; });
    }
    void to_storage(const Positions& in, Positions& out) const {
        out.resize(in.size());
        parallel_for(0, in.size(), [&](std::size_t k) { out[order_[k]] = in[k]; });
    }

    /// out = P + t·L·P (fixed vertices copied); the bounding boxes of P and out over the
    /// vertices with edges, and whether every new coordinate is finite and bounded.
    bool step(const Positions& P, double t, Positions& out, Box& box_before, Box& box_after) {
        if (restricted_) return step_moving(P, t, out, box_before, box_after);
        if (!gather_) return step_scatter(P, t, out, box_before, box_after);
        if (!known_) find_fixed();
        if (!rows_built_) build_rows();
        const std::size_t nv = P.size();
        out.resize(nv);  // every entry is written below
        // Each vertex sums its row (its neighbours in edge order: the bits of the edge-order
        // scatter), in fixed blocks on every thread; the finiteness sum and the boxes are
        // reduced in block order. NaN and infinities propagate into the sum; the box bounds
        // the magnitude.
        return finish_step(
            P, t, out,
            [&](std::size_t v) {
                Point ring = Point::Zero();
                for (std::size_t r = row_offset_[v]; r < row_offset_[v + 1]; ++r)
                    ring += P[row_[r]];
                return ring;
            },
            box_before, box_after);
    }

    /// out[v] = p + t·(ring(v) / valence - p) for the moving vertices, p for the fixed ones,
    /// in fixed blocks on every thread; the finiteness sum and the boxes of P and out over the
    /// vertices with edges reduced in block order (NaN and infinities propagate into the sum;
    /// the box bounds the magnitude). ring(v) is read before out[v] is written.
    template <typename Ring>
    bool finish_step(const Positions& P, double t, Positions& out, const Ring& ring,
                     Box& box_before, Box& box_after) {
        const StepPart all = parallel_reduce(
            0, P.size(), StepPart{},
            [&](std::size_t begin, std::size_t end) {
                StepPart part;
                for (std::size_t v = begin; v < end; ++v) {
                    const Point& p = P[v];
                    if (fixed_[v]) {
                        out[v] = p;
                        if (valence_[v] == 0) continue;
                    } else {
                        out[v] = p + t * (ring(v) / double(valence_[v]) - p);
                        part.sum += out[v].x() + out[v].y() + out[v].z();
                    }
                    part.before.add(p);
                    part.after.add(out[v]);
                }
                return part;
            },
            StepPart::combine);
        box_before.add(all.before);
        box_after.add(all.after);
        return std::isfinite(all.sum) && box_after.bounded();
    }

    /// The energy xᵀKx = sum over edges |x_i - x_j|² and the rounding scale sum_i K_ii |x_i|².
    std::pair<double, double> energy(const Positions& P) const {
        if (restricted_) {
            auto [e, q] = fixed_energy_;
            for (const auto& [i, j] : moving_edges_) {
                e += (P[i] - P[j]).squaredNorm();
                q += P[i].squaredNorm() + P[j].squaredNorm();
            }
            return {e, q};
        }
        // Over the edges in fixed blocks, the partial sums added in block order.
        const Vertex* to = mesh_.halfedge_to_array().data();
        const std::size_t ne = mesh_.edges_size();
        using Sums = std::pair<double, double>;
        return parallel_reduce(
            0, ne, Sums{0, 0},
            [&](std::size_t begin, std::size_t end) {
                double e = 0, q = 0;
                for (std::size_t ed = begin; ed < end; ++ed) {
                    if (mesh_.is_deleted(Edge(Index(ed)))) continue;
                    Index i = to[2 * ed + 1].idx(), j = to[2 * ed].idx();
                    if (local_) i = rank_[i], j = rank_[j];
                    const Point& a = P[i];
                    const Point& b = P[j];
                    e += (a - b).squaredNorm();
                    q += a.squaredNorm() + b.squaredNorm();
                }
                return Sums{e, q};
            },
            [](const Sums& x, const Sums& y) {
                return Sums{x.first + y.first, x.second + y.second};
            });
    }

    /// The Lanczos estimate of the largest stable explicit step.
    double max_stable_step(int steps) {
        if (!known_) find_fixed();
        if (!restricted_ && !rows_built_) build_rows();  // apply_k() reads them
        const std::size_t nv = valence_.size();
        Eigen::VectorXd d = Eigen::VectorXd::Zero(Eigen::Index(nv));
        for (std::size_t v = 0; v < nv; ++v)
            if (!fixed_[v]) d[Eigen::Index(v)] = 1.0 / std::sqrt(double(valence_[v]));
        return stable_step_of(lanczos_largest(
            d,
            [&](const Eigen::VectorXd& u, Eigen::VectorXd& w, const Eigen::VectorXd& q) {
                return apply_dk_dot(d, u, w, q);
            },
            steps, local_ ? &order_ : nullptr));
    }

    /// Restricts every later step, energy and stable-step estimate to the vertices that move
    /// (neither fixed nor pinned) and the edges around them, when those vertices are at most
    /// kRestrictedShare of the vertices with edges: one pass over the edges builds, per moving
    /// vertex, its neighbours in edge order, so that a step costs O(their valences) instead of
    /// O(V + E). The products are those of the whole-mesh passes bit for bit (each vertex sums
    /// the same terms in the same order); the energies are equal up to rounding (the fixed
    /// edges' part is summed once, apart). Valid only while the fixed vertices keep the
    /// positions they have in P here (the caller's promise: no boundary slide, no volume
    /// rescaling). Returns whether it restricted.
    bool restrict_to_moving(const Positions& P) {
        if (!known_) find_fixed();
        const std::size_t nv = valence_.size();
        std::vector<Index> slot(nv, kInvalidIndex);
        std::size_t with_edges = 0, ring_size = 0;
        for (std::size_t v = 0; v < nv; ++v) {
            if (valence_[v] > 0) ++with_edges;
            if (fixed_[v]) continue;
            slot[v] = Index(moving_.size());
            moving_.push_back(Index(v));
            ring_size += valence_[v];
        }
        if (double(moving_.size()) > kRestrictedShare * double(with_edges)) {
            moving_.clear();
            return false;
        }
        ring_offset_.assign(moving_.size() + 1, 0);
        for (std::size_t k = 0; k < moving_.size(); ++k)
            ring_offset_[k + 1] = ring_offset_[k] + valence_[moving_[k]];
        ring_.resize(ring_size);
        std::vector<std::size_t> fill(ring_offset_.begin(), ring_offset_.end() - 1);
        for (Edge e : mesh_.edges()) {
            const Halfedge h = HalfedgeMesh::halfedge(e, 0);
            const Index i = mesh_.to_vertex(HalfedgeMesh::twin(h)).idx();
            const Index j = mesh_.to_vertex(h).idx();
            if (slot[i] != kInvalidIndex) ring_[fill[slot[i]]++] = j;
            if (slot[j] != kInvalidIndex) ring_[fill[slot[j]]++] = i;
            if (slot[i] != kInvalidIndex || slot[j] != kInvalidIndex) {
                moving_edges_.emplace_back(i, j);
            } else {
                fixed_energy_.first += (P[i] - P[j]).squaredNorm();
                fixed_energy_.second += P[i].squaredNorm() + P[j].squaredNorm();
            }
        }
        for (std::size_t v = 0; v < nv; ++v)
            if (fixed_[v] && valence_[v] > 0) fixed_box_.add(P[v]);
        restricted_ = true;
        return true;
    }

    /// The moving vertices in index order (restrict_to_moving(); empty before).
    const std::vector<Index>& moving() const { return moving_; }

    /// Above this share of the vertices with edges moving, the whole-mesh passes are as cheap.
    static constexpr double kRestrictedShare = 0.75;

private:
    /// The valences, the fixed vertices (boundary, isolated, pinned) and every vertex's row
    /// (its neighbours in the order of their edges' indices: row_offset_, row_), by two owner
    /// scans over the edges (core/parallel.h, parallel_ranges(): each thread reads every edge
    /// in order and writes only its own vertices), the same arrays for any number of threads.
    void find_fixed() {
        const std::size_t nv = mesh_.vertices_size(), ne = mesh_.edges_size();
        valence_.assign(nv, 0);
        fixed_.assign(nv, 0);
        const Vertex* to = mesh_.halfedge_to_array().data();
        const Face* face = mesh_.halfedge_face_array().data();
        const bool garbage = mesh_.has_garbage();
        const auto live = [&](std::size_t e) {
            return !garbage || !mesh_.is_deleted(Edge(Index(e)));
        };
        parallel_ranges(0, nv, [&](std::size_t lo, std::size_t hi) {
            for (std::size_t e = 0; e < ne; ++e) {
                const Index i = to[2 * e + 1].idx(), j = to[2 * e].idx();
                const bool in_i = i - lo < hi - lo, in_j = j - lo < hi - lo;
                if (!(in_i || in_j) || !live(e)) continue;
                const bool border = !face[2 * e].is_valid() || !face[2 * e + 1].is_valid();
                if (in_i) {
                    ++valence_[i];
                    if (border) fixed_[i] = 1;
                }
                if (in_j) {
                    ++valence_[j];
                    if (border) fixed_[j] = 1;
                }
            }
            for (std::size_t v = lo; v < hi; ++v)
                if (valence_[v] == 0 || (pinned_ && (*pinned_)[v])) fixed_[v] = 1;
        });
        known_ = true;
    }

    /// Every vertex's row (its neighbours in the order of their edges' indices: row_offset_,
    /// row_) by an owner scan over the edges, after find_fixed().
    void build_rows() {
        const std::size_t nv = mesh_.vertices_size(), ne = mesh_.edges_size();
        const Vertex* to = mesh_.halfedge_to_array().data();
        const bool garbage = mesh_.has_garbage();
        const auto live = [&](std::size_t e) {
            return !garbage || !mesh_.is_deleted(Edge(Index(e)));
        };
        row_offset_.assign(nv + 1, 0);
        for (std::size_t v = 0; v < nv; ++v) row_offset_[v + 1] = row_offset_[v] + valence_[v];
        row_.resize(row_offset_[nv]);
        parallel_ranges(0, nv, [&](std::size_t lo, std::size_t hi) {
            std::vector<std::size_t> fill(row_offset_.begin() + std::ptrdiff_t(lo),
                                          row_offset_.begin() + std::ptrdiff_t(hi));
            for (std::size_t e = 0; e < ne; ++e) {
                const Index i = to[2 * e + 1].idx(), j = to[2 * e].idx();
                const bool in_i = i - lo < hi - lo, in_j = j - lo < hi - lo;
                if (!(in_i || in_j) || !live(e)) continue;
                if (in_i) row_[fill[i - lo]++] = j;
                if (in_j) row_[fill[j - lo]++] = i;
            }
        });
        rows_built_ = true;
    }

    /// step() over the whole mesh by an owner scan of the edges (a run of one product: building
    /// the rows would cost more than it saves): each thread reads every edge in order and sums
    /// the neighbours of its own range of vertices only (core/parallel.h, parallel_ranges()), so
    /// that each sum runs in edge order, the bits of the one-thread scatter, for any number of
    /// threads; the first product also counts the valences and finds the boundary.
    bool step_scatter(const Positions& P, double t, Positions& out, Box& box_before,
                      Box& box_after) {
        const std::size_t nv = P.size(), ne = mesh_.edges_size();
        out.resize(nv);
        const Vertex* to = mesh_.halfedge_to_array().data();
        const Face* face = mesh_.halfedge_face_array().data();
        const bool garbage = mesh_.has_garbage();
        const bool count = !known_;
        if (count) {
            valence_.assign(nv, 0);
            fixed_.assign(nv, 0);
        }
        parallel_ranges(0, nv, [&](std::size_t lo, std::size_t hi) {
            std::fill(out.begin() + std::ptrdiff_t(lo), out.begin() + std::ptrdiff_t(hi),
                      Point::Zero());
            for (std::size_t e = 0; e < ne; ++e) {
                const Index i = to[2 * e + 1].idx(), j = to[2 * e].idx();
                const bool in_i = i - lo < hi - lo, in_j = j - lo < hi - lo;
                if (!(in_i || in_j) || (garbage && mesh_.is_deleted(Edge(Index(e))))) continue;
                const bool border =
                    count && (!face[2 * e].is_valid() || !face[2 * e + 1].is_valid());
                if (in_i) {
                    out[i] += P[j];
                    if (count) {
                        ++valence_[i];
                        if (border) fixed_[i] = 1;
                    }
                }
                if (in_j) {
                    out[j] += P[i];
                    if (count) {
                        ++valence_[j];
                        if (border) fixed_[j] = 1;
                    }
                }
            }
            if (count)
                for (std::size_t v = lo; v < hi; ++v)
                    if (valence_[v] == 0 || (pinned_ && (*pinned_)[v])) fixed_[v] = 1;
        });
        known_ = true;
        // The update in fixed blocks, the finiteness sum and the boxes reduced in block order
        // (as step()).
        return finish_step(
            P, t, out, [&](std::size_t v) { return Point(out[v]); }, box_before, box_after);
    }

    /// step() on the moving vertices only: out keeps the fixed vertices' positions from the
    /// call before (copied from P on the first call), the boxes add the fixed vertices' box.
    bool step_moving(const Positions& P, double t, Positions& out, Box& box_before,
                     Box& box_after) const {
        if (out.size() != P.size()) out = P;
        box_before.add(fixed_box_);
        box_after.add(fixed_box_);
        double sum = 0;
        for (std::size_t k = 0; k < moving_.size(); ++k) {
            const Index v = moving_[k];
            Point ring = Point::Zero();
            for (std::size_t r = ring_offset_[k]; r < ring_offset_[k + 1]; ++r) ring += P[ring_[r]];
            const Point& p = P[v];
            out[v] = p + t * (ring / double(valence_[v]) - p);
            sum += out[v].x() + out[v].y() + out[v].z();
            box_before.add(p);
            box_after.add(out[v]);
        }
        return std::isfinite(sum) && box_after.bounded();
    }

    /// w = D·K·u and the sum of w_i·q_i over fixed blocks, added in block order (the product of
    /// lanczos_largest(), its scaling and dot product in one pass over the rows; the same bits
    /// as apply_k() then scale_and_dot()).
    double apply_dk_dot(const Eigen::VectorXd& d, const Eigen::VectorXd& u, Eigen::VectorXd& w,
                        const Eigen::VectorXd& q) const {
        if (restricted_) {
            apply_k(u, w);
            return scale_and_dot(d, w, q);
        }
        return parallel_reduce(
            0, valence_.size(), 0.0,
            [&](std::size_t begin, std::size_t end) {
                double part = 0;
                for (std::size_t v = begin; v < end; ++v) {
                    const auto i = Eigen::Index(v);
                    double kv = double(valence_[v]) * u[i];
                    for (std::size_t r = row_offset_[v]; r < row_offset_[v + 1]; ++r)
                        kv -= u[Eigen::Index(row_[r])];
                    w[i] = d[i] * kv;
                    part += w[i] * q[i];
                }
                return part;
            },
            [](double x, double y) { return x + y; });
    }

    /// w = K·u (all entries).
    void apply_k(const Eigen::VectorXd& u, Eigen::VectorXd& w) const {
        if (restricted_) {
            // The fixed entries only ever meet a zero of D·K·D: left at zero.
            w.setZero();
            for (std::size_t k = 0; k < moving_.size(); ++k) {
                const Index v = moving_[k];
                double kv = double(valence_[v]) * u[Eigen::Index(v)];
                for (std::size_t r = ring_offset_[k]; r < ring_offset_[k + 1]; ++r)
                    kv -= u[Eigen::Index(ring_[r])];
                w[Eigen::Index(v)] = kv;
            }
            return;
        }
        // Each entry from its row (the bits of the edge-order scatter), on every thread.
        parallel_for(0, valence_.size(), [&](std::size_t v) {
            double kv = double(valence_[v]) * u[Eigen::Index(v)];
            for (std::size_t r = row_offset_[v]; r < row_offset_[v + 1]; ++r)
                kv -= u[Eigen::Index(row_[r])];
            w[Eigen::Index(v)] = kv;
        });
    }

    const HalfedgeMesh& mesh_;
    const Pinned* pinned_;
    bool known_ = false;
    std::vector<std::uint32_t> valence_;   ///< 0: isolated or deleted
    std::vector<std::uint8_t> fixed_;      ///< 1: does not move (boundary, isolated, deleted)
    std::vector<std::size_t> row_offset_;  ///< per vertex: its neighbours in row_
    std::vector<Index> row_;               ///< neighbours, each vertex's in edge order
    bool gather_ = true;                   ///< products by rows (else the one-thread scatter)
    bool rows_built_ = false;
    // restrict_to_moving():
    bool restricted_ = false;
    std::vector<Index> moving_;             ///< the vertices that move, in index order
    std::vector<std::size_t> ring_offset_;  ///< per moving vertex: its neighbours in ring_
    std::vector<Index> ring_;               ///< neighbours, each vertex's in edge order
    std::vector<std::pair<Index, Index>> moving_edges_;  ///< edges with a moving end
    std::pair<double, double> fixed_energy_{0, 0};       ///< energy() of the other edges
    Box fixed_box_;                                      ///< the fixed vertices with edges
    // localize():
    bool local_ = false;
    std::vector<Index> order_;  ///< new number -> storage index
    std::vector<Index> rank_;   ///< storage index -> new number
};

double max_stable_step_laplacian(const Laplacian& lap, int steps) {
    const auto n = Eigen::Index(lap.map.rows());
    Eigen::VectorXd d = Eigen::VectorXd::Zero(n);
    for (Eigen::Index r = 0; r < n; ++r)
        if (!lap.fixed[std::size_t(r)]) d[r] = 1.0 / std::sqrt(lap.S[r]);
    return stable_step_of(lanczos_largest(
        d,
        [&](const Eigen::VectorXd& u, Eigen::VectorXd& w, const Eigen::VectorXd& q) {
            w.noalias() = lap.K * u;
            return scale_and_dot(d, w, q);
        },
        steps));
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

/// The health figures of one iteration's candidate positions, checked by check_step().
struct StepFigures {
    Box box_before, box_after;
    bool finite = true;
    bool check_energy = false;  ///< the step is not provably stable
    double energy_gain = 1;     ///< the largest energy factor a stable step allows
};

/// One smooth() run on res.mesh (the caller's copy or moved-in mesh): the settings derived
/// from the options, and the state one iteration hands to the next.
class FairingRun {
public:
    FairingRun(const FairingOptions& o, Progress& progress, FairingResult& res,
               const Pinned& pinned, const Selection* weights, const FeatureCurveFairing* curves);
    /// The iterations (until one stops the run), then the summary lines of the report.
    void run();

private:
    void report_settings();
    void set_up(const Pinned& pinned);
    void update_laplacian(int it);
    StepFigures candidate_step(const Positions& P);
    bool implicit_step(int iteration, const Positions& P, StepFigures& s);
    bool solve(int iteration, const Eigen::MatrixXd& rhs, const Eigen::MatrixXd& xf,
               Eigen::MatrixXd& y);
    double solve_once(double rn, bool direct, const Eigen::MatrixXd& rhs, const Eigen::MatrixXd& xf,
                      Eigen::MatrixXd& y, std::ostringstream& line);
    bool check_step(int iteration, const Positions& P, const StepFigures& s);
    void slide_boundary();
    bool slide_features(int iteration, const Positions& P);
    bool check_area_and_volume(int iteration, const Positions& P, bool check_energy);
    bool restore_volume(int iteration);
    void report_summary();
    std::string instability_hint();
    void stop(int iteration, const std::string& why);
    void blend_by_region(const Positions& P);
    CandidateSums area_volume_of(const Positions& X, bool with_area);

    const FairingOptions& o_;
    const Selection* weights_;           ///< the region's weights on res.mesh; nullptr: everything
    const FeatureCurveFairing* curves_;  ///< sliding features (FeatureMode::Slide), or null
    Progress& progress_;
    FairingResult& res_;
    HalfedgeMesh& mesh_;
    const bool taubin_;
    const double mu_;
    const LaplacianOperator lop_;
    const bool weights_fixed_;
    const bool implicit_;
    const bool fast_;  ///< vertex-space umbrella, no matrix
    /// fast_ on a region: the umbrella and the checks work on the moving vertices only
    /// (UmbrellaOperator::restrict_to_moving()); the other vertices' positions never change.
    bool restricted_ = false;
    /// fast_ on a big mesh (UmbrellaOperator::localize()): during run() the mesh's positions
    /// are in the operator's order (restored before the summary).
    bool local_ = false;
    std::optional<MovingFaceSums> moving_sums_;  ///< restricted_: the area and volume sums
    bool closed_ = false;
    CandidateSums last_;  ///< of the last good positions, where known (area: NaN when not)
    bool last_known_ = false;
    double v0_ = 0;
    bool check_volume_sign_ = false;
    LaplacianOptions lap_options_;
    std::optional<UmbrellaOperator> umbrella_;
    Laplacian lap_;
    bool have_lap_ = false;
    ImplicitSystem sys_;
    std::optional<BoundarySlider> slider_;
    bool slide_explicit_fallback_ = false;
    bool use_direct_;
    bool used_ldlt_ = false, used_cg_ = false;
    TaubinGain gain_;
    Positions cand_, tmp_;
    /// The energy of the current positions under a fixed operator (reused by the next check).
    std::pair<double, double> energy_now_{0, 0};
    bool energy_known_ = false;
};

FairingRun::FairingRun(const FairingOptions& o, Progress& progress, FairingResult& res,
                       const Pinned& pinned, const Selection* weights,
                       const FeatureCurveFairing* curves)
    : o_(o),
      weights_(weights),
      curves_(curves),
      progress_(progress),
      res_(res),
      mesh_(res.mesh),
      taubin_(o.op == FairingOperator::Taubin),
      mu_(taubin_mu(o)),
      lop_(taubin_ ? LaplacianOperator::Umbrella
                   : static_cast<LaplacianOperator>(static_cast<int>(o.op))),
      weights_fixed_(lop_ == LaplacianOperator::Umbrella),
      implicit_(o.integration == Integration::Implicit && !taubin_),
      fast_(weights_fixed_ && !implicit_),
      use_direct_(o.solver == ImplicitSolver::Direct),
      gain_(taubin_ ? taubin_gain(o.taubin_lambda, mu_) : TaubinGain{}) {
    res_.solver = "none";
    report_settings();
    set_up(pinned);
}

/// The report's first line: the operator, integration, step and iterations.
void FairingRun::report_settings() {
    std::ostringstream s;
    s << "operator " << fairing_operator_name(o_.op) << ", " << integration_name(o_.integration);
    if (taubin_) {
        s << ", lambda " << o_.taubin_lambda << ", mu " << mu_;
        if (o_.taubin_pass_band > 0)
            s << " (from the pass band k_PB " << format_number(o_.taubin_pass_band) << ")";
        else if (o_.taubin_mu == 0)
            s << " (following lambda through the pass band k_PB "
              << format_number(kDefaultTaubinPassBand)
              << (mu_ == -1.0
                      ? ", raised to -1: k_PB " + format_number(1.0 / o_.taubin_lambda - 1.0) + ")"
                      : std::string(")"));
    } else
        s << ", step " << o_.step;
    s << ", " << o_.iterations << " iteration(s)";
    if (o_.preserve_volume) s << ", volume preserved";
    res_.report.push_back(s.str());
}

/// The input's volume (closed meshes), the umbrella operator or boundary slider where used,
/// and the stable step estimate of the fast path.
void FairingRun::set_up(const Pinned& pinned) {
    closed_ = is_closed(mesh_);
    if (closed_) {
        last_ = area_volume(mesh_, mesh_.positions(), true);
        last_known_ = true;
        res_.initial_volume = last_.volume;
    }
    v0_ = res_.initial_volume;
    // The volume's sign is checked where it is well defined: a closed mesh whose volume is
    // not negligible against its bounding box.
    const double diag0 = closed_ ? bounding_box(mesh_).diagonal() : 0.0;
    check_volume_sign_ = closed_ && std::abs(v0_) > 1e-9 * diag0 * diag0 * diag0;
    lap_options_.fixed_vertices = pinned;
    // The rows pay from two products on: several iterations, or the stable-step estimate.
    const bool gather = o_.iterations >= 2 || o_.estimate_max_stable_step;
    if (fast_) umbrella_.emplace(mesh_, pinned.empty() ? nullptr : &pinned, gather);
    if (o_.boundary == BoundaryMode::Slide && !closed_) {
        slider_.emplace(mesh_, pinned);
        res_.report.push_back("boundary: " + std::to_string(slider_->loops()) +
                              " loop(s) sliding along the input's boundary curves");
    }
    // A region whose unselected vertices keep their positions throughout (no slide, no volume
    // rescaling) runs on its moving vertices only: the same positions bit for bit.
    if (fast_ && weights_ && !pinned.empty() && o_.restrict_to_region && !slider_ &&
        !o_.preserve_volume && all_finite(mesh_.positions()))
        restricted_ = umbrella_->restrict_to_moving(mesh_.positions());
    // A whole-mesh run whose steps read no per-vertex data in storage order (no region
    // weights, slide or volume rescaling) runs in the operator's Morton order: the same
    // positions bit for bit, the gathers close in memory.
    if (fast_ && gather && !restricted_ && !weights_ && !slider_ && !o_.preserve_volume &&
        !mesh_.has_garbage() && mesh_.vertices_size() >= g_locality_threshold) {
        umbrella_->localize(mesh_.positions());
        Positions local;
        umbrella_->to_local(mesh_.positions(), local);
        mesh_.positions().swap(local);
        local_ = true;
    }
    if (fast_ && o_.estimate_max_stable_step)
        res_.max_stable_step = umbrella_->max_stable_step(kLanczosSteps);
    if (o_.keep_steps) res_.step_positions.reserve(std::size_t(o_.iterations));
}

void FairingRun::stop(int iteration, const std::string& why) {
    res_.stopped_early = true;
    res_.stopped_at_iteration = iteration;
    res_.stop_reason = "iteration " + std::to_string(iteration) + ": " + why;
    res_.report.push_back("stopped: " + res_.stop_reason);
}

/// The hint for an explicit instability, with the stable limit at the last good state.
std::string FairingRun::instability_hint() {
    const double limit = fast_ ? umbrella_->max_stable_step(kLanczosSteps)
                               : max_stable_step_laplacian(lap_, kLanczosSteps);
    if (taubin_)
        return " (lambda " + format_number(o_.taubin_lambda) + " and mu " + format_number(mu_) +
               " are unstable on this mesh: the umbrella's stable step here is about " +
               format_number(limit) + "; keep lambda and |mu| below it)";
    if (o_.step > limit)
        return " (step " + format_number(o_.step) + " is above the stable limit " +
               format_number(limit) + " of this mesh; use a smaller step or implicit integration)";
    return " (step " + format_number(o_.step) + ", stable limit about " + format_number(limit) +
           " on this mesh; use a smaller step or implicit integration)";
}

void FairingRun::run() {
    for (int it = 0; it < o_.iterations; ++it) {
        const int iteration = it + 1;
        progress_.check_cancelled();
        progress_.report(double(it) / o_.iterations, "smoothing");
        const Positions& P = mesh_.positions();
        if (!fast_ && (!have_lap_ || !weights_fixed_)) update_laplacian(it);
        StepFigures s;
        if (!implicit_)
            s = candidate_step(P);
        else if (!implicit_step(iteration, P, s))
            break;
        if (!check_step(iteration, P, s)) break;
        if (slider_) slide_boundary();
        if (curves_ && !slide_features(iteration, P)) break;
        if (!check_area_and_volume(iteration, P, s.check_energy)) break;
        if (o_.preserve_volume && !restore_volume(iteration)) break;
        if (weights_) blend_by_region(P);
        // Commit: the candidate becomes the mesh's positions (a swap, no copy).
        std::swap(mesh_.positions(), cand_);
        ++res_.iterations_done;
        if (o_.keep_steps) {
            res_.step_positions.emplace_back();
            if (local_)
                umbrella_->to_storage(mesh_.positions(), res_.step_positions.back());
            else
                res_.step_positions.back() = mesh_.positions();
        }
    }
    if (local_) {  // back to storage order
        umbrella_->to_storage(mesh_.positions(), cand_);
        std::swap(mesh_.positions(), cand_);
        local_ = false;
    }
    report_summary();
}

/// The region: every candidate position blended with the last by its vertex's weight (weight
/// 1 keeps the candidate, weight 0 the old position, bit for bit). The area, volume and energy
/// of the blended positions are not those measured on the candidate: measured again.
void FairingRun::blend_by_region(const Positions& P) {
    const Selection& w = *weights_;
    if (restricted_) {  // the others' candidates are their old positions
        for (Index v : umbrella_->moving()) cand_[v] = blend_by_weight(P[v], cand_[v], w[v]);
    } else {
        for (std::size_t v = 0; v < cand_.size(); ++v)
            cand_[v] = blend_by_weight(P[v], cand_[v], w[v]);
    }
    last_known_ = false;
    energy_known_ = false;
}

/// Builds the Laplacian (first iteration) or refreshes its weights (geometry-dependent
/// operators), accumulates its diagnostics, and (implicit) rebuilds the system and, on the
/// first iteration, makes the automatic solver choice.
void FairingRun::update_laplacian(int it) {
    if (have_lap_)
        refresh_laplacian(mesh_, lap_);
    else
        lap_ = build_laplacian(mesh_, lop_, lap_options_);
    auto& d = res_.diagnostics;
    const auto& n = lap_.diagnostics;
    d.negative_weights_clamped += n.negative_weights_clamped;
    d.degenerate_corners += n.degenerate_corners;
    d.cotangents_clamped += n.cotangents_clamped;
    d.short_edges += n.short_edges;
    d.stalled_vertices = std::max(d.stalled_vertices, n.stalled_vertices);
    if (!have_lap_ && o_.estimate_max_stable_step)
        res_.max_stable_step = max_stable_step_laplacian(lap_, kLanczosSteps);
    have_lap_ = true;
    energy_known_ = false;
    if (!implicit_) return;
    sys_.build(lap_, o_.step);
    res_.solved_rows = sys_.free_rows.size();
    res_.operator_rows = lap_.map.rows();
    if (it == 0 && o_.solver == ImplicitSolver::Auto) {
        const double cond = 1.0 + o_.step * gershgorin_bound(lap_);
        use_direct_ = cond > kCgConditionLimit ||
                      (weights_fixed_ && o_.iterations >= kDirectReuseIterations &&
                       lap_.map.rows() <= kDirectRowsLimit);
        std::ostringstream s;
        s << "solver choice: condition bound " << cond << ", " << sys_.free_rows.size()
          << " rows solved (of " << lap_.map.rows() << " built) -> " << (use_direct_ ? kLdlt : kCg);
        res_.report.push_back(s.str());
    }
}

/// The explicit candidate positions of this iteration (Taubin's pair of umbrella steps, one
/// umbrella step, or one step of the Laplacian) and their health figures.
StepFigures FairingRun::candidate_step(const Positions& P) {
    StepFigures s;
    if (fast_ && taubin_) {
        Box unused;
        s.finite = umbrella_->step(P, o_.taubin_lambda, tmp_, s.box_before, unused);
        s.finite = umbrella_->step(tmp_, mu_, cand_, unused, s.box_after) && s.finite;
        s.energy_gain = gain_.gain * gain_.gain;
        s.check_energy = gain_.at_two < -gain_.gain;
    } else if (fast_) {
        s.finite = umbrella_->step(P, o_.step, cand_, s.box_before, s.box_after);
        s.check_energy = o_.step > 1.0;  // Gershgorin: the umbrella's spectrum is in [0, 2]
    } else {
        double g = 0;
        s.finite = laplacian_step(lap_, P, o_.step, cand_, tmp_, s.box_before, s.box_after, g);
        s.check_energy = o_.step * g > 2.0;
    }
    return s;
}

/// The implicit candidate positions: (S_ff + step K_ff) x_f = S_ff x_f - step K_fb x_b over
/// the free rows. False when the solve failed (the run is stopped).
bool FairingRun::implicit_step(int iteration, const Positions& P, StepFigures& s) {
    cand_ = P;
    const auto nf = Eigen::Index(sys_.free_rows.size());
    if (nf == 0) return true;
    const auto n = Eigen::Index(lap_.map.rows());
    Eigen::MatrixXd x(n, 3), xf(nf, 3);
    for (Eigen::Index r = 0; r < n; ++r)
        x.row(r) = P[lap_.map.vertex_of[std::size_t(r)].idx()].transpose();
    for (Eigen::Index f = 0; f < nf; ++f) xf.row(f) = x.row(sys_.free_rows[std::size_t(f)]);
    Eigen::MatrixXd rhs = sys_.S.asDiagonal() * xf;
    if (sys_.Kfb.nonZeros() > 0) rhs -= o_.step * (sys_.Kfb * x);
    Eigen::MatrixXd y;
    if (!solve(iteration, rhs, xf, y)) return false;
    for (Eigen::Index f = 0; f < nf; ++f) {
        const Index v = lap_.map.vertex_of[std::size_t(sys_.free_rows[std::size_t(f)])].idx();
        cand_[v] = y.row(f).transpose();
        s.finite = s.finite && finite_and_bounded(cand_[v]);
    }
    return true;
}

/// Solves the implicit system with the chosen solver, and with the other one when the first
/// misses the residual bound; one report line per attempt. False (the run stopped) when
/// neither meets it.
bool FairingRun::solve(int iteration, const Eigen::MatrixXd& rhs, const Eigen::MatrixXd& xf,
                       Eigen::MatrixXd& y) {
    const double rn = rhs.norm();
    const bool direct_first = use_direct_;
    bool accepted = false;
    std::string failures;
    for (int attempt = 0; attempt < 2 && !accepted; ++attempt) {
        const bool direct = (attempt == 0) == direct_first;
        std::ostringstream line;
        line << "iteration " << iteration << ": " << (direct ? kLdlt : kCg);
        const double residual = solve_once(rn, direct, rhs, xf, y, line);
        line << ", relative residual " << residual;
        accepted = residual <= o_.max_relative_residual;
        if (!accepted) {
            line << " above " << o_.max_relative_residual;
            if (attempt == 0) line << "; retrying with " << (direct ? kCg : kLdlt);
            failures += std::string(failures.empty() ? "" : ", ") + (direct ? kLdlt : kCg) +
                        " relative residual " + format_number(residual);
        } else {
            (direct ? used_ldlt_ : used_cg_) = true;
            res_.max_residual = std::max(res_.max_residual, residual);
        }
        res_.report.push_back(line.str());
    }
    if (!accepted)
        stop(iteration, "the implicit solve failed (" + failures + "; required " +
                            format_number(o_.max_relative_residual) + ")");
    return accepted;
}

/// One solve, direct (factoring once per system) or by Jacobi-preconditioned CG started at
/// xf; returns the residual relative to rn = |rhs| (infinite when there is no finite solution).
double FairingRun::solve_once(double rn, bool direct, const Eigen::MatrixXd& rhs,
                              const Eigen::MatrixXd& xf, Eigen::MatrixXd& y,
                              std::ostringstream& line) {
    const auto nf = Eigen::Index(sys_.free_rows.size());
    if (direct) {
        if (!sys_.factored) {
            const auto t0 = std::chrono::steady_clock::now();
            sys_.ldlt.compute(sys_.A);
            res_.factorization_ms += ms_between(t0, std::chrono::steady_clock::now());
            sys_.factored = true;
            sys_.factor_ok = sys_.ldlt.info() == Eigen::Success;
            ++res_.factorizations;
        }
        if (sys_.factor_ok) {
            const auto t0 = std::chrono::steady_clock::now();
            y = sys_.ldlt.solve(rhs);
            res_.solve_ms += ms_between(t0, std::chrono::steady_clock::now());
            if (sys_.ldlt.info() != Eigen::Success) y.resize(0, 0);
        } else {
            y.resize(0, 0);
            line << " (the factorization failed)";
        }
    } else {
        const auto t0 = std::chrono::steady_clock::now();
        Eigen::ConjugateGradient<SparseMatrix, Eigen::Lower | Eigen::Upper,
                                 Eigen::DiagonalPreconditioner<double>>
            cg;
        cg.setTolerance(o_.cg_tolerance);
        cg.setMaxIterations(o_.cg_max_iterations > 0 ? Eigen::Index(o_.cg_max_iterations)
                                                     : std::max<Eigen::Index>(1000, 4 * nf));
        cg.compute(sys_.A);
        y = cg.solveWithGuess(rhs, xf);
        res_.cg_iterations += std::size_t(cg.iterations());
        res_.solve_ms += ms_between(t0, std::chrono::steady_clock::now());
        line << " (" << cg.iterations() << " iteration(s))";
    }
    double residual = std::numeric_limits<double>::infinity();
    if (y.rows() == nf && y.allFinite())
        residual = rn > 0 ? (sys_.A * y - rhs).norm() / rn : (sys_.A * y).norm();
    if (!std::isfinite(residual)) residual = std::numeric_limits<double>::infinity();
    return residual;
}

/// Health checks of the step itself (before the boundary slides and the volume is restored,
/// which are not part of the operator): finite coordinates, and for explicit steps the
/// bounding box's growth and (where the step is not provably stable) the fairing energy.
/// False when the run is stopped.
bool FairingRun::check_step(int iteration, const Positions& P, const StepFigures& s) {
    if (!s.finite) {
        stop(iteration, std::string("a coordinate is not finite or above 1e100") +
                            (implicit_ ? "" : instability_hint()));
        return false;
    }
    if (implicit_) return true;
    const double d0 = s.box_before.diagonal(), d1 = s.box_after.diagonal();
    if (d0 > 0 && d1 > (1 + kBoxGrowth) * d0) {
        stop(iteration, "the bounding box grew by " + format_percent(d1 / d0 - 1) +
                            " in one iteration" + instability_hint());
        return false;
    }
    if (!s.check_energy) return true;
    if (!energy_known_) energy_now_ = fast_ ? umbrella_->energy(P) : laplacian_energy(lap_, P);
    const auto next = fast_ ? umbrella_->energy(cand_) : laplacian_energy(lap_, cand_);
    const double e0 = energy_now_.first, limit = s.energy_gain * e0;
    if (!(next.first <=
          limit + kEnergyRelativeSlack * limit + kEnergyRoundingSlack * energy_now_.second)) {
        stop(iteration, "the fairing energy grew by " +
                            (e0 > 0 ? format_percent(next.first / e0 - 1) : std::string("?")) +
                            instability_hint());
        return false;
    }
    energy_now_ = next;  // valid for the next iteration only with fixed weights
    energy_known_ = weights_fixed_;
    return true;
}

/// Moves the boundary vertices of the candidate along the input's boundary curves.
void FairingRun::slide_boundary() {
    const double t = taubin_ ? o_.taubin_lambda : o_.step;
    const bool implicit_curve = implicit_ || t > 1.0;
    slide_explicit_fallback_ = slide_explicit_fallback_ || (!implicit_ && t > 1.0);
    slider_->step(t, implicit_curve, cand_);
    energy_known_ = false;
}

/// Moves the crease vertices of the candidate along their feature curves with the curve's 1-D
/// Laplacian (core/algorithms/feature_fairing.h); implicit above an explicit step of 1. False
/// when the run is stopped.
bool FairingRun::slide_features(int iteration, const Positions& P) {
    CurveStep s;
    s.t = taubin_ ? o_.taubin_lambda : o_.step;
    s.mu = taubin_ ? mu_ : 0.0;
    s.implicit = implicit_ || (!taubin_ && s.t > 1.0);
    s.length_weighted =
        lop_ == LaplacianOperator::CurvatureFlow || lop_ == LaplacianOperator::ImprovedUmbrella;
    energy_known_ = false;
    if (curves_->step(s, P, cand_)) return true;
    stop(iteration, "a feature curve's step is not finite");
    return false;
}

/// The area collapse check runs with the energy check and for the geometry-dependent
/// operators; the volume's sign is checked on every iteration of a closed mesh (a provably
/// stable step can still turn a very coarse mesh inside out: umbrella step 1 maps a
/// tetrahedron to its reflection scaled by 1/3). False when the run is stopped.
bool FairingRun::check_area_and_volume(int iteration, const Positions& P, bool check_energy) {
    const bool area_check = !implicit_ && (!weights_fixed_ || check_energy);
    if (!(area_check || check_volume_sign_ || o_.preserve_volume)) {
        last_known_ = false;
        return true;
    }
    if (area_check && !(last_known_ && last_.area >= 0))
        last_ = area_volume_of(P, true);  // the last good state's area, once
    const CandidateSums g = area_volume_of(cand_, area_check);
    if (area_check && last_.area > 0 && g.area < kAreaCollapse * last_.area) {
        stop(iteration, "the surface area fell to " + format_percent(g.area / last_.area) +
                            " of the previous iteration's" + instability_hint());
        return false;
    }
    if (check_volume_sign_ && !(g.volume * v0_ > 0)) {
        stop(iteration, "the volume changed sign (from " + format_number(v0_) + " to " +
                            format_number(g.volume) + ")" + (implicit_ ? "" : instability_hint()));
        return false;
    }
    last_ = g;
    last_known_ = true;
    return true;
}

/// area_volume() of the mesh at positions X (the last good state or the candidate); over the
/// faces around the moving vertices plus a constant for the others when restricted_.
CandidateSums FairingRun::area_volume_of(const Positions& X, bool with_area) {
    if (!restricted_) return area_volume(mesh_, X, with_area, local_ ? umbrella_->rank() : nullptr);
    if (!moving_sums_) moving_sums_.emplace(mesh_, X, umbrella_->moving());
    return moving_sums_->sums(X, with_area);
}

/// Volume preservation: scales the candidate about the centroid of the vertices with edges
/// by (V0/Vn)^(1/3). False when the run is stopped.
bool FairingRun::restore_volume(int iteration) {
    const double beta = std::cbrt(v0_ / last_.volume);
    Point c = Point::Zero();
    std::size_t count = 0;
    for (Vertex v : mesh_.vertices())
        if (!mesh_.is_isolated(v)) {
            c += cand_[v.idx()];
            ++count;
        }
    if (count > 0) c /= double(count);
    bool ok = std::isfinite(beta) && beta > 0;
    for (Vertex v : mesh_.vertices()) {
        if (!ok || mesh_.is_isolated(v)) continue;
        Point& p = cand_[v.idx()];
        p = c + beta * (p - c);
        ok = finite_and_bounded(p);
    }
    if (!ok) {
        stop(iteration,
             "the volume could not be restored (volume " + format_number(last_.volume) + ")");
        return false;
    }
    last_.area *= beta * beta;
    last_.volume = v0_;
    energy_known_ = false;
    return true;
}

/// The closing lines of the report: the boundary's implicit fallback, the final volume, the
/// stable step estimate, the clamping diagnostics and the solvers used.
void FairingRun::report_summary() {
    if (slide_explicit_fallback_)
        res_.report.push_back(
            "boundary: steps above 1 move along the curve implicitly (an "
            "explicit 1-D step above 1 is unstable)");
    progress_.report(1.0, "smoothing");
    if (closed_) res_.final_volume = last_known_ ? last_.volume : volume(mesh_);
    if (!std::isnan(res_.max_stable_step))
        res_.report.push_back("largest stable explicit step at the input: about " +
                              format_number(res_.max_stable_step) +
                              (taubin_ ? " (the umbrella's, which bounds lambda)" : ""));
    const auto& d = res_.diagnostics;
    if (d.total() > 0) {
        std::ostringstream s;
        s << "clamped: " << d.negative_weights_clamped << " negative cotangent weight(s), "
          << d.degenerate_corners << " degenerate corner(s), " << d.cotangents_clamped
          << " large cotangent(s), " << d.short_edges << " short edge(s), " << d.stalled_vertices
          << " vertex(es) fixed for lack of weight";
        res_.report.push_back(s.str());
    }
    if (implicit_) {
        res_.solver = used_ldlt_ && used_cg_ ? std::string(kLdlt) + " + " + kCg
                      : used_ldlt_           ? kLdlt
                      : used_cg_             ? kCg
                                             : "none";
        std::ostringstream s;
        s << "solver " << res_.solver << ", " << res_.factorizations << " factorization(s), "
          << res_.cg_iterations << " CG iteration(s), max relative "
          << "residual " << res_.max_residual;
        res_.report.push_back(s.str());
    }
}

/// One smooth() run on res.mesh (the caller's copy or moved-in mesh).
void run_fairing(const FairingOptions& o, Progress& progress, FairingResult& res,
                 const Pinned& pinned, const Selection* weights = nullptr,
                 const FeatureCurveFairing* curves = nullptr) {
    FairingRun(o, progress, res, pinned, weights, curves).run();
}

/// Pins the live vertices of weight 0 (in `pinned`, sized on demand).
void pin_unselected(const HalfedgeMesh& mesh, const Selection& weights, Pinned& pinned) {
    for (Vertex v : mesh.vertices())
        if (!(weights[v.idx()] > 0.0f)) {
            if (pinned.empty()) pinned.assign(weights.size(), 0);
            pinned[v.idx()] = 1;
        }
}

}  // namespace

double taubin_mu_of(const FairingOptions& o) {
    if (o.taubin_pass_band > 0) return 1.0 / (o.taubin_pass_band - 1.0 / o.taubin_lambda);
    if (o.taubin_mu != 0) return o.taubin_mu;
    return std::max(-1.0, 1.0 / (kDefaultTaubinPassBand - 1.0 / o.taubin_lambda));
}

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
void smooth_coincident(FairingResult& res, const FairingOptions& o, Progress& progress,
                       std::optional<FeatureCurveFairing> curves) {
    WeldResult weld = weld_coincident_vertices(res.mesh);
    check_options(weld.mesh, o);  // closed when welded: volume preservation applies
    Pinned pinned(weld.mesh.vertices_size(), 0);
    const CoincidentGroups apart = find_coincident_vertices(weld.mesh);
    for (Index v : apart.members) pinned[v] = 1;
    // The region on the weld: a welded vertex weighs the least of its copies (so a copy of
    // weight 0 keeps all of them where they are).
    std::optional<Selection> welded_weights;
    if (o.region) {
        welded_weights.emplace(weld.mesh.vertices_size(), 1.0f);
        for (Vertex v : res.mesh.vertices()) {
            const Index w = weld.vertex_map[v.idx()];
            (*welded_weights)[w] = std::min((*welded_weights)[w], (*o.region)[v.idx()]);
        }
        pin_unselected(weld.mesh, *welded_weights, pinned);
    }
    if (curves) {  // sliding features, renumbered onto the weld and fixed for the operator
        curves->remap(weld.vertex_map);
        for (Index v : curves->moving()) pinned[v] = 1;
    }
    FairingResult welded;
    welded.mesh = std::move(weld.mesh);
    run_fairing(o, progress, welded, pinned, welded_weights ? &*welded_weights : nullptr,
                curves ? &*curves : nullptr);
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

/// The faces an implicit region run needs (those with a moving vertex, and for second order
/// the faces that share a vertex with those: the hinges of the moving rows reach that far),
/// as flags per face storage index; empty when the run cannot be restricted (see smooth()).
std::vector<std::uint8_t> region_run_faces(const HalfedgeMesh& mesh, const FairingOptions& o) {
    const bool applies =
        o.region && o.restrict_to_region && o.integration == Integration::Implicit &&
        (o.op == FairingOperator::Umbrella || o.op == FairingOperator::CurvatureFlow ||
         o.op == FairingOperator::SecondOrder) &&
        o.boundary == BoundaryMode::Fixed && !o.preserve_volume;
    if (!applies) return {};
    const Selection& w = *o.region;
    std::vector<std::uint8_t> marked(mesh.vertices_size(), 0), faces(mesh.faces_size(), 0);
    for (Vertex v : mesh.vertices()) marked[v.idx()] = w[v.idx()] > 0.0f;
    const int rings = o.op == FairingOperator::SecondOrder ? 2 : 1;
    std::size_t count = 0;
    for (int ring = 0; ring < rings; ++ring) {
        for (Face f : mesh.faces()) {
            if (faces[f.idx()]) continue;
            for (Vertex v : mesh.face_vertices(f))
                if (marked[v.idx()] == 1) {
                    faces[f.idx()] = 1;
                    ++count;
                    break;
                }
        }
        if (ring + 1 < rings)  // the next ring: every vertex of the faces so far
            for (Face f : mesh.faces())
                if (faces[f.idx()])
                    for (Vertex v : mesh.face_vertices(f)) marked[v.idx()] = 1;
    }
    if (4 * count > 3 * mesh.n_faces()) return {};
    return faces;
}

/// The whole mesh's volume at each step of a region run (positions differ from P0 only at
/// `moving`); stops the run at the first step whose volume's sign differs from the input's,
/// as the whole-mesh run does.
void check_region_run_volume(FairingResult& res, const Positions& p0,
                             const std::vector<Index>& moving, const std::vector<Positions>& steps,
                             const Positions& last) {
    MovingFaceSums sums(res.mesh, p0, moving);
    res.initial_volume = sums.sums(p0, false).volume;
    const BoundingBox box = bounding_box(res.mesh);
    const double diag = box.diagonal();
    const bool check = std::abs(res.initial_volume) > 1e-9 * diag * diag * diag;
    const std::size_t n = std::min(steps.size(), std::size_t(res.iterations_done));
    for (std::size_t k = 0; k < n && check; ++k) {
        const double vk = sums.sums(steps[k], false).volume;
        if (vk * res.initial_volume > 0) continue;
        res.stopped_early = true;
        res.stopped_at_iteration = int(k) + 1;
        res.stop_reason = "iteration " + std::to_string(k + 1) +
                          ": the volume changed sign (from " + format_number(res.initial_volume) +
                          " to " + format_number(vk) + ")";
        res.report.push_back("stopped: " + res.stop_reason);
        res.iterations_done = int(k);
        res.mesh.positions() = k == 0 ? p0 : steps[k - 1];
        res.final_volume = k == 0 ? res.initial_volume : sums.sums(steps[k - 1], false).volume;
        return;
    }
    res.final_volume = sums.sums(last, false).volume;
}

/// smooth() of a region whose outside is fixed, on the submesh of `faces`
/// (region_run_faces()): the same rows, values and solver choices as on the whole mesh, its
/// positions written back to the moving vertices. False (nothing done) when the submesh is not
/// a plain copy of those faces (the builder would repair something).
bool smooth_region_on_faces(FairingResult& res, const FairingOptions& o,
                            const std::vector<std::uint8_t>& faces, Progress& progress) {
    const HalfedgeMesh& mesh = res.mesh;
    const Selection& w = *o.region;
    std::vector<Index> sub_of(mesh.vertices_size(), kInvalidIndex);
    for (Face f : mesh.faces())
        if (faces[f.idx()])
            for (Vertex v : mesh.face_vertices(f)) sub_of[v.idx()] = 0;
    PolygonSoup soup;
    std::size_t n_faces = 0;
    std::vector<Index> whole_of;  // sub vertex -> vertex, ascending
    Selection sub_w;
    for (Vertex v : mesh.vertices()) {
        if (sub_of[v.idx()] == kInvalidIndex) continue;
        sub_of[v.idx()] = Index(whole_of.size());
        whole_of.push_back(v.idx());
        soup.positions.push_back(mesh.position(v));
        sub_w.push_back(w[v.idx()]);
    }
    for (Face f : mesh.faces()) {
        if (!faces[f.idx()]) continue;
        const auto c = mesh.face_vertices(f);
        soup.add_face({sub_of[c[0].idx()], sub_of[c[1].idx()], sub_of[c[2].idx()]});
        ++n_faces;
    }
    LoadReport load;
    HalfedgeMesh sub = build_mesh(std::move(soup), load);
    if (sub.vertices_size() != whole_of.size() || sub.n_faces() != n_faces ||
        load.vertex_copies_added || load.nonmanifold_vertices_split || load.detached_faces ||
        load.degenerate_faces_dropped || !find_coincident_vertices(sub).empty())
        return false;
    FairingOptions so = o;
    so.region = &sub_w;
    so.restrict_to_region = false;  // already restricted: the whole-mesh path on the submesh
    so.keep_steps = true;           // the region's positions per step, for the volume check
    FairingResult r = smooth(std::move(sub), so, progress);
    const Positions p0 = mesh.positions();
    std::vector<Index> moving;
    for (std::size_t k = 0; k < whole_of.size(); ++k)
        if (sub_w[k] > 0.0f) moving.push_back(whole_of[k]);
    const auto whole_positions = [&](const Positions& ps) {
        Positions p = p0;
        for (std::size_t k = 0; k < whole_of.size(); ++k)
            if (sub_w[k] > 0.0f) p[whole_of[k]] = ps[k];
        return p;
    };
    std::vector<Positions> steps;
    steps.reserve(r.step_positions.size());
    for (const Positions& ps : r.step_positions) steps.push_back(whole_positions(ps));
    HalfedgeMesh whole = std::move(res.mesh);
    whole.positions() = whole_positions(r.mesh.positions());
    r.mesh = std::move(whole);
    r.step_positions = std::move(steps);
    r.report.insert(
        r.report.begin() + 1,
        "region: " + std::to_string(moving.size()) + " vertices move; the system is built on the " +
            std::to_string(n_faces) + " faces around them, the other " +
            std::to_string(r.mesh.n_vertices() - moving.size()) + " vertices stay fixed");
    res = std::move(r);
    if (is_closed(res.mesh)) {
        const Positions last = res.mesh.positions();
        check_region_run_volume(res, p0, moving, res.step_positions, last);
        res.step_positions.resize(std::size_t(res.iterations_done));
    }
    if (!o.keep_steps) res.step_positions.clear();
    return true;
}

/// The region with the feature vertices (ends of sharp edges, tagged corners) at weight 0, or
/// nothing when the options keep no features or the mesh has none; detects them first (Auto).
std::optional<Selection> fix_features(HalfedgeMesh& mesh, const FairingOptions& o,
                                      std::string& line) {
    if (o.features == FeatureSource::None) return std::nullopt;
    if (o.features == FeatureSource::Stored)
        if (const std::string bad = check_features(mesh); !bad.empty())
            throw InvalidArgument("smooth: invalid features: " + bad);
    if (o.features == FeatureSource::Auto) {
        if (!(std::isfinite(o.feature_angle) && o.feature_angle > 0 && o.feature_angle <= 180))
            throw InvalidArgument("smooth: feature_angle must be in (0, 180] degrees (got " +
                                  number_text(o.feature_angle) + ")");
        FeatureDetectionOptions d;
        d.angle_deg = o.feature_angle;
        detect_features(mesh, d);
    }
    if (!has_features(mesh)) return std::nullopt;
    Selection w = o.region ? *o.region : Selection(mesh.vertices_size(), 1.0f);
    const std::vector<float> near = feature_neighbourhood(mesh, 0);
    std::size_t fixed = 0;
    for (std::size_t v = 0; v < w.size(); ++v)
        if (near[v] > 0) {
            w[v] = 0.0f;
            ++fixed;
        }
    line = "features: " + count_text(fixed, "vertex", "vertices") +
           " on sharp edges or corners kept where they are";
    return w;
}

/// Sliding features: the crease vertices that slide (feature_fairing.h) get their region weight
/// back in `weights` (fix_features() set every feature vertex to 0), so the blend keeps their
/// curve step; they stay fixed rows of the surface operator (the caller pins them).
FeatureCurveFairing sliding_curves(const HalfedgeMesh& mesh, const FairingOptions& o,
                                   Selection& weights, std::string& line) {
    FeatureCurveFairing curves(mesh, o.region);
    const std::vector<float> near = feature_neighbourhood(mesh, 0);
    const auto on =
        std::size_t(std::count_if(near.begin(), near.end(), [](float w) { return w > 0; }));
    for (Index v : curves.moving()) weights[v] = o.region ? (*o.region)[v] : 1.0f;
    line =
        "features: " + count_text(on, "vertex", "vertices") + " on sharp edges or corners: " +
        count_text(curves.moving().size(), "crease vertex slides", "crease vertices slide") +
        " along their curves, the other " + std::to_string(on - curves.moving().size()) +
        " stay where they are (1-D Laplacian" +
        (o.op != FairingOperator::Taubin && o.integration == Integration::Explicit && o.step > 1.0
             ? ", implicit: an explicit step above 1 is unstable on a curve)"
             : ")");
    return curves;
}

FairingResult smooth_mesh(FairingResult res, const FairingOptions& given, Progress& progress) {
    if (given.region) check_selection(res.mesh, *given.region, "smooth: region");
    std::string feature_line;
    std::optional<Selection> weights = fix_features(res.mesh, given, feature_line);
    std::optional<FeatureCurveFairing> curves;
    if (weights && given.feature_mode == FeatureMode::Slide)
        curves = sliding_curves(res.mesh, given, *weights, feature_line);
    FairingOptions options = given;
    if (weights) options.region = &*weights;
    if (curves) options.restrict_to_region = false;  // the fixed rows move: the whole mesh
    if (find_coincident_vertices(res.mesh).empty()) {
        check_options(res.mesh, options);
        const std::vector<std::uint8_t> faces = region_run_faces(res.mesh, options);
        if (!faces.empty() && smooth_region_on_faces(res, options, faces, progress)) return res;
        Pinned pinned;
        if (options.region) pin_unselected(res.mesh, *options.region, pinned);
        if (curves && pinned.empty()) pinned.assign(res.mesh.vertices_size(), 0);
        if (curves)
            for (Index v : curves->moving()) pinned[v] = 1;  // for the surface operator
        run_fairing(options, progress, res, pinned, options.region, curves ? &*curves : nullptr);
    } else {
        smooth_coincident(res, options, progress, std::move(curves));
    }
    if (!feature_line.empty()) res.report.push_back(feature_line);
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

namespace fairing_detail {
std::size_t set_locality_threshold(std::size_t vertices) {
    const std::size_t before = g_locality_threshold;
    g_locality_threshold = vertices;
    return before;
}
}  // namespace fairing_detail

double max_stable_explicit_step(const HalfedgeMesh& mesh, FairingOperator op, int lanczos_steps) {
    if (lanczos_steps < 1 || lanczos_steps > 1000)
        throw InvalidArgument("max_stable_explicit_step: lanczos_steps must be in [1, 1000] (got " +
                              std::to_string(lanczos_steps) + ")");
    if (op == FairingOperator::Umbrella || op == FairingOperator::Taubin) {
        UmbrellaOperator umbrella(mesh);
        if (!mesh.has_garbage() && mesh.vertices_size() >= g_locality_threshold)
            umbrella.localize(mesh.positions());  // as smooth() does
        return umbrella.max_stable_step(lanczos_steps);
    }
    const Laplacian lap =
        build_laplacian(mesh, static_cast<LaplacianOperator>(static_cast<int>(op)));
    return max_stable_step_laplacian(lap, lanczos_steps);
}

}  // namespace trilab
