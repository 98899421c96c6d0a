// The spectral lens (core/algorithms/transfer_function.h): transfer curves of the fairing
// settings, measured gains, the spectral prediction and the multiplet check.
//
// Every function here works on the decomposition's rows (spectral.h): positions are gathered
// from per-vertex arrays through d.map, coefficients are α = Eᵀ·S·X with E the S-orthonormal
// eigenvectors, so E·α is the S-orthogonal projection of X onto the computed frequencies.
#include "core/algorithms/transfer_function.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "core/errors.h"
#include "core/two_threads.h"

namespace trilab {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr float kFloatInf = std::numeric_limits<float>::infinity();

bool is_taubin(const FairingOptions& o) {
    return o.op == FairingOperator::Taubin;
}

bool is_implicit(const FairingOptions& o) {
    return !is_taubin(o) && o.integration == Integration::Implicit;
}

/// Taubin's gain per iteration for λ_T = a, μ = mu at eigenvalue x.
double taubin_gain(double a, double mu, double x) {
    return (1 - a * x) * (1 - mu * x);
}

void check_positions(const SpectralDecomposition& d, const std::vector<Point>& p,
                     const char* caller, const char* what) {
    if (p.size() != d.base_positions.size())
        throw InvalidArgument(std::string(caller) + ": " + what + " has " +
                              std::to_string(p.size()) + " vertices, the decomposed mesh has " +
                              std::to_string(d.base_positions.size()));
}

/// The rows' positions (rows x 3).
Eigen::MatrixXd gather(const SpectralDecomposition& d, const std::vector<Point>& p) {
    Eigen::MatrixXd x(Eigen::Index(d.rows()), 3);
    for (std::size_t r = 0; r < d.rows(); ++r)
        x.row(Eigen::Index(r)) = p[d.map.vertex_of[r].idx()].transpose();
    return x;
}

/// α = Eᵀ·S·X (k x 3).
Eigen::MatrixXd coefficients_of(const SpectralDecomposition& d, const Eigen::MatrixXd& x) {
    return d.eigenvectors.transpose() * (d.S.asDiagonal() * x);
}

/// W = (g - g_edge) ∘ α (k x 3) for the fairing `o`, and g_edge, the gain at the computed
/// frequency nearest the rest.
Eigen::MatrixXd filter_weights(const SpectralDecomposition& d, const FairingOptions& o,
                               const Eigen::MatrixXd& alpha, double& g_edge) {
    const std::vector<double> g = fairing_gains(o, d.eigenvalues);
    g_edge = d.end == SpectrumEnd::Smallest ? g.back() : g.front();
    Eigen::MatrixXd w(alpha.rows(), 3);
    for (Eigen::Index i = 0; i < alpha.rows(); ++i)
        w.row(i) = (g[std::size_t(i)] - g_edge) * alpha.row(i);
    return w;
}

/// store(r, (E·W)[r]) for every row r of E (rows x k, by columns) and W (k x 3): E is read
/// once, in blocks of rows whose three sums stay in cache while the k columns pass (Eigen's
/// general product re-reads E for its small right-hand side), on two threads for large E. Each
/// row's sum runs over k in order, so the result does not depend on the thread count.
template <typename Store>
void rows_times(const Eigen::MatrixXd& e_all, const Eigen::MatrixXd& w, const Store& store) {
    const std::size_t rows = std::size_t(e_all.rows());
    const Eigen::Index k = e_all.cols();
    constexpr std::size_t kBlock = 1024;
    const auto rows_from_to = [&](std::size_t begin, std::size_t end) {
        double sum[3][kBlock];
        for (std::size_t r0 = begin; r0 < end; r0 += kBlock) {
            const std::size_t n = std::min(kBlock, end - r0);
            for (auto& column : sum) std::fill(column, column + n, 0.0);
            for (Eigen::Index i = 0; i < k; ++i) {
                const double* e = e_all.col(i).data() + r0;
                const double w0 = w(i, 0), w1 = w(i, 1), w2 = w(i, 2);
                for (std::size_t r = 0; r < n; ++r) {
                    sum[0][r] += w0 * e[r];
                    sum[1][r] += w1 * e[r];
                    sum[2][r] += w2 * e[r];
                }
            }
            for (std::size_t r = 0; r < n; ++r)
                store(r0 + r, Point(sum[0][r], sum[1][r], sum[2][r]));
        }
    };
    // The halves split at a block boundary.
    const std::size_t half = std::min(rows, (rows / 2 + kBlock - 1) / kBlock * kBlock);
    on_two_threads(worth_two_threads(rows * std::size_t(std::max<Eigen::Index>(k, 1)) / 16),
                   [&](int part) {
                       if (part == 0)
                           rows_from_to(0, half);
                       else
                           rows_from_to(half, rows);
                   });
}

/// out[v] = g_edge·input[v] + (E·W)[r] for every row r (vertex v = d.map.vertex_of[r]).
void apply_basis(const SpectralDecomposition& d, const Eigen::MatrixXd& w, double g_edge,
                 const std::vector<Point>& input, std::vector<Point>& out) {
    rows_times(d.eigenvectors, w, [&](std::size_t r, const Point& moved) {
        const Index v = d.map.vertex_of[r].idx();
        out[v] = g_edge * input[v] + moved;
    });
}

std::string band_text(const MultipletSplit::Band& b) {
    return std::to_string(b.first) + ":" + std::to_string(b.second);
}

}  // namespace

LaplacianOperator laplacian_of(FairingOperator op) {
    return op == FairingOperator::Taubin ? LaplacianOperator::Umbrella
                                         : static_cast<LaplacianOperator>(static_cast<int>(op));
}

bool fairing_is_linear(FairingOperator op) {
    return op == FairingOperator::Umbrella || op == FairingOperator::Taubin;
}

double gain_per_iteration(const FairingOptions& o, double lambda) {
    if (is_taubin(o)) return taubin_gain(o.taubin_lambda, taubin_mu_of(o), lambda);
    if (is_implicit(o)) return 1.0 / (1.0 + o.step * lambda);
    return 1.0 - o.step * lambda;
}

double fairing_gain(const FairingOptions& o, double lambda) {
    return std::pow(gain_per_iteration(o, lambda), double(o.iterations));
}

std::vector<double> fairing_gains(const FairingOptions& o, const Eigen::VectorXd& eigenvalues) {
    std::vector<double> g(std::size_t(eigenvalues.size()));
    for (Eigen::Index k = 0; k < eigenvalues.size(); ++k)
        g[std::size_t(k)] = fairing_gain(o, eigenvalues[k]);
    return g;
}

double unstable_eigenvalue(const FairingOptions& o) {
    if (is_taubin(o)) {
        // g(x) = 1 - (a + μ)x + aμx² = -1: aμ < 0, so one root is positive.
        const double a = o.taubin_lambda, mu = taubin_mu_of(o);
        const double p = a * mu, s = a + mu;
        if (!(p < 0)) return kInf;
        return (s - std::sqrt(s * s - 8 * p)) / (2 * p);
    }
    if (is_implicit(o) || !(o.step > 0)) return kInf;
    return 2.0 / o.step;
}

double instability_limit(const FairingOptions& o, double lambda_max) {
    if (!std::isfinite(lambda_max) || lambda_max < 0)
        throw InvalidArgument("instability_limit: lambda_max must be finite and >= 0 (got " +
                              std::to_string(lambda_max) + ")");
    if (!(lambda_max > 0) || is_implicit(o)) return kInf;
    if (!is_taubin(o)) return 2.0 / lambda_max;
    // μ(a) = 1/(k - 1/a) = a/(ka - 1) keeps the pass band k; μ >= -1 while a <= 1/(1 + k).
    const double k = taubin_pass_band_of(o);
    const auto mu_of = [k](double a) { return a / (k * a - 1); };
    const double a_max = std::min(1.0, 1.0 / (1.0 + k));
    if (taubin_gain(a_max, mu_of(a_max), lambda_max) >= -1) return kInf;
    // g(lambda_max) falls from 1 (a -> 0) as a grows: bisection to full precision.
    double lo = 0, hi = a_max;
    for (int i = 0; i < 200 && hi - lo > 1e-15 * hi; ++i) {
        const double mid = 0.5 * (lo + hi);
        (taubin_gain(mid, mu_of(mid), lambda_max) >= -1 ? lo : hi) = mid;
    }
    return lo;
}

double taubin_pass_band_of(const FairingOptions& o) {
    if (!is_taubin(o)) return kNaN;
    return 1.0 / o.taubin_lambda + 1.0 / taubin_mu_of(o);
}

MeasuredGain measured_gain(const SpectralDecomposition& d, const std::vector<Point>& input,
                           const std::vector<Point>& result, double tolerance) {
    check_positions(d, input, "measured_gain", "the input");
    check_positions(d, result, "measured_gain", "the result");
    if (!(tolerance >= 0 && tolerance < 1))
        throw InvalidArgument("measured_gain: tolerance must be in [0, 1) (got " +
                              std::to_string(tolerance) + ")");
    const Eigen::MatrixXd a = coefficients_of(d, gather(d, input));
    const Eigen::MatrixXd b = coefficients_of(d, gather(d, result));
    MeasuredGain m;
    m.tolerance = tolerance;
    const std::size_t k = d.size();
    m.gain.assign(k, kNaN);
    m.mixing.assign(k, kNaN);
    const double largest = k > 0 ? a.rowwise().norm().maxCoeff() : 0.0;
    for (std::size_t i = 0; i < k; ++i) {
        const auto r = Eigen::Index(i);
        const double n2 = a.row(r).squaredNorm();
        if (!(std::sqrt(n2) > tolerance * largest) || !(n2 > 0)) {
            ++m.undefined;
            continue;
        }
        const double g = a.row(r).dot(b.row(r)) / n2;
        m.gain[i] = g;
        m.mixing[i] = (b.row(r) - g * a.row(r)).norm() / std::sqrt(n2);
    }
    return m;
}

std::vector<Point> predict_fairing(const SpectralDecomposition& d, const FairingOptions& o,
                                   const std::vector<Point>& input) {
    check_positions(d, input, "predict_fairing", "the input");
    std::vector<Point> out = input;
    if (d.empty()) return out;
    // The decomposed shape itself (a panel previewing on the state it decomposed): its
    // coefficients are stored, which halves the cost of a prediction.
    const bool decomposed_shape =
        d.coefficients.rows() == Eigen::Index(d.size()) && input == d.base_positions;
    const Eigen::MatrixXd alpha =
        decomposed_shape ? d.coefficients : coefficients_of(d, gather(d, input));
    // X' = E·(g∘α) + g_edge·(X - E·α) = g_edge·X + E·W with W = (g - g_edge)∘α: one pass
    // over E, the only large operand (rows x k doubles: 446 MB for 557k rows and k = 100).
    double g_edge = 0;
    const Eigen::MatrixXd w = filter_weights(d, o, alpha, g_edge);
    apply_basis(d, w, g_edge, input, out);
    return out;
}

ClusteredBasis cluster_basis(const SpectralDecomposition& d, const std::vector<Index>& cluster_of,
                             std::size_t clusters) {
    const std::vector<Point>& x = d.base_positions;
    if (cluster_of.size() != x.size())
        throw InvalidArgument("cluster_basis: " + std::to_string(cluster_of.size()) +
                              " clusters given for " + std::to_string(x.size()) + " vertices");
    for (std::size_t v = 0; v < cluster_of.size(); ++v)
        if (cluster_of[v] != kInvalidIndex && cluster_of[v] >= clusters)
            throw InvalidArgument("cluster_basis: vertex " + std::to_string(v) + " has cluster " +
                                  std::to_string(cluster_of[v]) + " of " +
                                  std::to_string(clusters));
    const Eigen::Index nc = Eigen::Index(clusters), k = Eigen::Index(d.size());
    ClusteredBasis b;
    b.vectors = Eigen::MatrixXd::Zero(nc, k);
    b.positions = Eigen::MatrixXd::Zero(nc, 3);
    b.others = Eigen::MatrixXd::Zero(nc, 3);
    b.spread.assign(clusters, 0.0);
    b.vector_spread = Eigen::MatrixXf::Zero(nc, k);
    b.others_spread.assign(clusters, 0.0);
    b.decomposed.assign(clusters, 0);
    b.other.assign(clusters, 0);
    const std::vector<Index>& row_of = d.map.row_of;
    const auto in_rows = [&](std::size_t v) {
        return v < row_of.size() && row_of[v] != kInvalidIndex;
    };
    for (std::size_t v = 0; v < x.size(); ++v) {
        const Index c = cluster_of[v];
        if (c == kInvalidIndex) continue;
        if (in_rows(v)) {
            b.positions.row(c) += x[v].transpose();
            ++b.decomposed[c];
        } else {
            b.others.row(c) += x[v].transpose();
            ++b.other[c];
        }
    }
    for (Eigen::Index c = 0; c < nc; ++c) {
        if (b.decomposed[std::size_t(c)])
            b.positions.row(c) /= double(b.decomposed[std::size_t(c)]);
        if (b.other[std::size_t(c)]) b.others.row(c) /= double(b.other[std::size_t(c)]);
    }
    for (std::size_t v = 0; v < x.size(); ++v) {
        const Index c = cluster_of[v];
        if (c == kInvalidIndex) continue;
        double& s = in_rows(v) ? b.spread[c] : b.others_spread[c];
        const Eigen::RowVector3d mean = in_rows(v) ? b.positions.row(c) : b.others.row(c);
        s = std::max(s, (x[v].transpose() - mean).norm());
    }
    // The eigenvectors: column by column (E is stored by columns), first the means, then each
    // row's squared distance from its cluster's mean, summed over k.
    const std::size_t rows = d.rows();
    std::vector<Index> cluster_of_row(rows);
    for (std::size_t r = 0; r < rows; ++r) cluster_of_row[r] = cluster_of[d.map.vertex_of[r].idx()];
    for (Eigen::Index i = 0; i < k; ++i) {
        const double* e = d.eigenvectors.col(i).data();
        double* mean = b.vectors.col(i).data();
        for (std::size_t r = 0; r < rows; ++r)
            if (cluster_of_row[r] != kInvalidIndex) mean[cluster_of_row[r]] += e[r];
        for (Eigen::Index c = 0; c < nc; ++c)
            if (b.decomposed[std::size_t(c)]) mean[c] /= double(b.decomposed[std::size_t(c)]);
    }
    for (Eigen::Index i = 0; i < k; ++i) {
        const double* e = d.eigenvectors.col(i).data();
        const double* mean = b.vectors.col(i).data();
        float* spread = b.vector_spread.col(i).data();
        for (std::size_t r = 0; r < rows; ++r) {
            const Index c = cluster_of_row[r];
            if (c == kInvalidIndex) continue;
            // Rounded up to the next float: a bound stays a bound.
            const float t = std::nextafter(float(std::abs(e[r] - mean[c])), kFloatInf);
            spread[c] = std::max(spread[c], t);
        }
    }
    return b;
}

ClusteredPrediction predict_clustered(const ClusteredBasis& b, const SpectralDecomposition& d,
                                      const FairingOptions& o) {
    if (d.coefficients.rows() != Eigen::Index(d.size()) || d.coefficients.cols() != 3)
        throw InvalidArgument("predict_clustered: the decomposition has no stored coefficients");
    if (b.vectors.cols() != Eigen::Index(d.size()) || b.positions.rows() != b.vectors.rows())
        throw InvalidArgument("predict_clustered: the clustered basis has " +
                              std::to_string(b.vectors.cols()) +
                              " frequencies, the decomposition " + std::to_string(d.size()));
    double g_edge = 0;
    const Eigen::MatrixXd w = filter_weights(d, o, d.coefficients, g_edge);
    // Σ_k |W_k|·vector_spread_k per cluster, column by column.
    std::vector<double> spread_moved(b.clusters(), 0.0);
    for (Eigen::Index i = 0; i < w.rows(); ++i) {
        const double wk = w.row(i).norm();
        const float* s = b.vector_spread.col(i).data();
        for (std::size_t c = 0; c < b.clusters(); ++c) spread_moved[c] += wk * double(s[c]);
    }
    std::vector<Point> moved(b.clusters());
    rows_times(b.vectors, w, [&](std::size_t c, const Point& m) { moved[c] = m; });
    ClusteredPrediction p;
    p.positions.resize(b.clusters());
    for (std::size_t c = 0; c < b.clusters(); ++c) {
        const auto i = Eigen::Index(c);
        const double n = b.decomposed[c], m = b.other[c];
        const Point ref = g_edge * Point(b.positions.row(i).transpose()) + moved[c];
        const Point others = b.others.row(i).transpose();
        const Point mean = n + m > 0 ? Point((n * ref + m * others) / (n + m)) : Point::Zero();
        p.positions[c] = mean;
        double bound = 0;
        if (n > 0) bound = std::abs(g_edge) * b.spread[c] + spread_moved[c] + (ref - mean).norm();
        if (m > 0) bound = std::max(bound, b.others_spread[c] + (others - mean).norm());
        p.bound = std::max(p.bound, bound);
    }
    return p;
}

ChangeByFrequency change_by_frequency(const SpectralDecomposition& d,
                                      const std::vector<Point>& input,
                                      const std::vector<Point>& result, std::size_t split) {
    check_positions(d, input, "change_by_frequency", "the input");
    check_positions(d, result, "change_by_frequency", "the result");
    if (d.end != SpectrumEnd::Smallest)
        throw InvalidArgument(
            "change_by_frequency: needs a decomposition of the smallest frequencies (this one "
            "holds the largest)");
    if (split > d.size())
        throw InvalidArgument("change_by_frequency: split must be at most " +
                              std::to_string(d.size()) + " (the frequencies computed), got " +
                              std::to_string(split));
    const Eigen::MatrixXd disp = gather(d, result) - gather(d, input);
    const auto e = d.eigenvectors.leftCols(Eigen::Index(split));
    const Eigen::MatrixXd below = e * (e.transpose() * (d.S.asDiagonal() * disp));
    const Eigen::MatrixXd above = disp - below;
    ChangeByFrequency c;
    c.below.assign(d.base_positions.size(), kNaN);
    c.above.assign(d.base_positions.size(), kNaN);
    double nb = 0, na = 0;
    for (std::size_t r = 0; r < d.rows(); ++r) {
        const auto i = Eigen::Index(r);
        const Index v = d.map.vertex_of[r].idx();
        c.below[v] = below.row(i).norm();
        c.above[v] = above.row(i).norm();
        nb += d.S[i] * below.row(i).squaredNorm();
        na += d.S[i] * above.row(i).squaredNorm();
    }
    c.below_norm = std::sqrt(nb);
    c.above_norm = std::sqrt(na);
    return c;
}

MultipletSplit band_splits_multiplet(const Eigen::VectorXd& eigenvalues, std::size_t lo,
                                     std::size_t hi, double relative_tolerance) {
    const auto n = std::size_t(eigenvalues.size());
    if (!(lo <= hi && hi < n))
        throw InvalidArgument("band_splits_multiplet: expected 0 <= lo <= hi < " +
                              std::to_string(n) + ", got " + std::to_string(lo) + ":" +
                              std::to_string(hi));
    if (!(relative_tolerance >= 0 && relative_tolerance < 1))
        throw InvalidArgument("band_splits_multiplet: relative_tolerance must be in [0, 1) (got " +
                              std::to_string(relative_tolerance) + ")");
    // Rounding leaves eigenvalues of zero at ±1e-16: an absolute floor relative to the largest
    // one joins those.
    const double scale = eigenvalues.cwiseAbs().maxCoeff();
    const auto joined = [&](std::size_t i) {  // i and i + 1 are one multiplet
        const double a = eigenvalues[Eigen::Index(i)], b = eigenvalues[Eigen::Index(i + 1)];
        return std::abs(b - a) <=
               relative_tolerance * std::max(std::abs(a), std::abs(b)) + 1e-12 * scale;
    };
    const auto multiplet = [&](std::size_t i) {
        std::size_t first = i, last = i;
        while (first > 0 && joined(first - 1)) --first;
        while (last + 1 < n && joined(last)) ++last;
        return MultipletSplit::Band{first, last};
    };
    MultipletSplit s;
    if (lo > 0 && joined(lo - 1)) s.cut_at_lo = multiplet(lo);
    if (hi + 1 < n && joined(hi)) s.cut_at_hi = multiplet(hi);
    s.splits = s.cut_at_lo || s.cut_at_hi;
    if (!s.splits) return s;
    const std::size_t wide_lo = s.cut_at_lo ? s.cut_at_lo->first : lo;
    const std::size_t wide_hi = s.cut_at_hi ? s.cut_at_hi->second : hi;
    s.wider = MultipletSplit::Band{wide_lo, wide_hi};
    const std::size_t narrow_lo = s.cut_at_lo ? s.cut_at_lo->second + 1 : lo;
    if (!s.cut_at_hi || s.cut_at_hi->first > 0) {
        const std::size_t narrow_hi = s.cut_at_hi ? s.cut_at_hi->first - 1 : hi;
        if (narrow_lo <= narrow_hi) s.narrower = MultipletSplit::Band{narrow_lo, narrow_hi};
    }
    return s;
}

std::string multiplet_split_text(const MultipletSplit& split, std::size_t lo, std::size_t hi,
                                 double relative_tolerance) {
    if (!split.splits) return {};
    char tol[32];
    std::snprintf(tol, sizeof tol, "%g %%", 100 * relative_tolerance);
    std::string text = "band " + band_text({lo, hi}) + " splits ";
    if (split.cut_at_lo && split.cut_at_hi && *split.cut_at_lo != *split.cut_at_hi)
        text +=
            "the multiplets " + band_text(*split.cut_at_lo) + " and " + band_text(*split.cut_at_hi);
    else
        text += "the multiplet " + band_text(split.cut_at_lo ? *split.cut_at_lo : *split.cut_at_hi);
    text += std::string(" (eigenvalues equal within ") + tol + "): use ";
    if (split.narrower) text += band_text(*split.narrower) + " or ";
    text += band_text(*split.wider);
    return text;
}

}  // namespace trilab
