#pragma once
// The spectral lens: what a fairing run does to each frequency of the mesh (sections 1.2.2-1.2.3
// and 1.2.10-1.2.12 of the reference report; Taubin 1995, "A signal processing approach to fair
// surface design"; Desbrun, Meyer, Schröder, Barr 1999; Vallet & Lévy 2008).
//
// Convention (one for fairing.h and spectral.h, checked by the tests): the operators of
// core/algorithms/laplacian.h are L = -S⁻¹K, and spectral.h decomposes K·e = λ·S·e with the
// operator's own normalizer as S (MassMatrix::Normalizer), so λ >= 0 is an eigenvalue of S⁻¹K
// and L·e = -λ·e. fairing.h's steps then multiply frequency λ's coefficient per iteration by
//  - explicit Euler X <- X + s·L·X:            g(λ) = 1 - s·λ
//  - implicit Euler (S + s·K)·X' = S·X:         g(λ) = 1 / (1 + s·λ)
//  - Taubin (umbrella steps λ_T, then μ < 0):  g(λ) = (1 - λ_T·λ)·(1 - μ·λ)
// and n iterations by g(λ)^n (fairing_gain()). The gain is exact for operators whose weights
// do not depend on the positions (umbrella, Taubin) on the rows the decomposition and the run
// share: every vertex of a closed mesh; with a boundary the run keeps boundary vertices fixed,
// which the free (Neumann) decomposition does not, and the Dirichlet one (fix_boundary) leaves
// the boundary's pull on the interior out, so the measured gain differs there. For improved
// umbrella, curvature flow and second order the weights follow the positions: the curve is
// the operator at the input linearized, and measured_gain() differs by the nonlinearity.
// Gains are per frequency and dimensionless; a `step` is in the units fairing.h states (the
// fraction of the way to the neighbours' average for umbrella steps).
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "core/algorithms/fairing.h"
#include "core/algorithms/spectral.h"
#include "core/halfedge_mesh.h"

namespace trilab {

/// The Laplacian whose spectrum a fairing operator filters (Taubin: the umbrella).
LaplacianOperator laplacian_of(FairingOperator op);
/// Whether the operator's weights are fixed (umbrella, Taubin): then the gain is exact.
bool fairing_is_linear(FairingOperator op);

/// The gain of one iteration of `o` at eigenvalue `lambda` (see the file comment); o.step,
/// o.taubin_lambda and Taubin's μ (taubin_mu_of()) as smooth() reads them. O(1).
double gain_per_iteration(const FairingOptions& o, double lambda);
/// The gain of the whole run, gain_per_iteration()^o.iterations. O(log iterations).
double fairing_gain(const FairingOptions& o, double lambda);
/// fairing_gain() at each eigenvalue. O(k).
std::vector<double> fairing_gains(const FairingOptions& o, const Eigen::VectorXd& eigenvalues);

/// The smallest eigenvalue above which one iteration's gain is below -1 (the frequencies
/// that grow and oscillate): explicit 2/step, Taubin the root of g(λ) = -1 beyond its pass
/// band; +inf for implicit runs and a zero step. Taubin's gain also exceeds 1 slightly inside
/// its pass band (0, k_PB): that is its design, not an instability.
double unstable_eigenvalue(const FairingOptions& o);

/// The instability limit of `o` on a spectrum whose largest eigenvalue is `lambda_max`: the
/// largest parameter value for which |gain per iteration| <= 1 at lambda_max. Explicit: the
/// step 2/lambda_max (fairing.h's max_stable_explicit_step() estimates the same from below);
/// Taubin: the λ_T at which g(lambda_max) = -1 with the pass band k_PB held (μ following λ_T),
/// or +inf when every λ_T that keeps μ >= -1 is stable; implicit: +inf. Throws
/// InvalidArgument unless lambda_max is finite and >= 0.
double instability_limit(const FairingOptions& o, double lambda_max);

/// Taubin's pass-band frequency k_PB = 1/λ_T + 1/μ of `o` (where g(k_PB) = 1 again); NaN for
/// the other operators.
double taubin_pass_band_of(const FairingOptions& o);

/// The measured gain per frequency of a run: the coefficients of the result divided by those
/// of the input on the decomposition's basis with its S inner product, α'_k = e_kᵀ·S·X'.
struct MeasuredGain {
    /// Per computed frequency: (α'_k · α_k) / |α_k|² (the least-squares ratio over x, y, z;
    /// exactly g(λ_k) when α'_k = g·α_k). NaN where |α_k| <= tolerance · max_j |α_j|: the
    /// input carries (almost) nothing of that frequency (a symmetric shape's missing
    /// frequencies), so no ratio is defined.
    std::vector<double> gain;
    std::size_t undefined = 0;  ///< NaN entries
    /// Per computed frequency: |α'_k - gain_k·α_k| / |α_k|, the part of the result's
    /// coefficient that is not a multiple of the input's (0 for a linear filter; NaN where
    /// the gain is).
    std::vector<double> mixing;
    double tolerance = 1e-9;
};

/// measured_gain(): rows of the decomposition gathered from `input` and `result` (one
/// position per vertex storage index, as mesh.positions()). Throws InvalidArgument when a
/// size differs from the decomposed mesh's vertices_size or tolerance is not in [0, 1).
/// O(k · rows).
MeasuredGain measured_gain(const SpectralDecomposition& d, const std::vector<Point>& input,
                           const std::vector<Point>& result, double tolerance = 1e-9);

/// The spectral prediction of a fairing result (the instant preview): with α = EᵀS·X and the
/// rest R = X - E·α (the part of `input` the computed frequencies miss), X' = E·(g ∘ α) +
/// g_edge·R, g = fairing_gains() and g_edge the gain at the computed frequency nearest the rest
/// (the band's top for the smallest end, its bottom for the largest). Exact for a linear
/// operator with every frequency (then R = 0); a prediction otherwise. Vertices outside the
/// eigenproblem keep their positions. Throws InvalidArgument when input.size() differs from
/// the decomposed mesh's vertices_size. O(k · rows), no factorization.
std::vector<Point> predict_fairing(const SpectralDecomposition& d, const FairingOptions& o,
                                   const std::vector<Point>& input);

/// A decomposition averaged over clusters of vertices (a stand-in's, ProxyMesh::cluster_of):
/// what predict_clustered() needs for the clusters' means of a prediction of the decomposed
/// shape in O(clusters · k) instead of O(rows · k), with a bound on how far any vertex's
/// predicted position is from its cluster's mean. A view draws that while a fairing slider
/// moves on a large mesh. Per cluster c, over its members in the eigenproblem ("decomposed",
/// n_c of them) and the others (isolated vertices, m_c):
struct ClusteredBasis {
    Eigen::MatrixXd vectors;     ///< clusters x k: the decomposed members' mean of e_k
    Eigen::MatrixXd positions;   ///< clusters x 3: the decomposed members' mean base position
    Eigen::MatrixXd others;      ///< clusters x 3: the other members' mean position
    std::vector<double> spread;  ///< max |x_v - mean| over the decomposed members
    /// clusters x k: max |e_k(v) - mean e_k| over the decomposed members (single precision,
    /// rounded up: a bound only)
    Eigen::MatrixXf vector_spread;
    std::vector<double> others_spread;             ///< max |x_v - mean| over the other members
    std::vector<std::uint32_t> decomposed, other;  ///< n_c and m_c
    std::size_t clusters() const { return decomposed.size(); }
};

/// The clustered basis of `d` for `cluster_of` (one cluster per vertex storage index of the
/// decomposed mesh, kInvalidIndex for none; clusters numbered below `clusters`). Two passes over
/// the eigenvectors. Throws InvalidArgument when cluster_of does not fit the decomposed mesh
/// or names a cluster out of range.
ClusteredBasis cluster_basis(const SpectralDecomposition& d, const std::vector<Index>& cluster_of,
                             std::size_t clusters);

/// The clusters' means of predict_fairing(d, o, d.base_positions) (the decomposed shape, from
/// its stored coefficients) and `bound`, no less than the distance of any member's predicted
/// position from its cluster's mean: |g_edge|·spread + Σ_k |W_k|·vector_spread_k (W = (g -
/// g_edge) ∘ α) plus how far the decomposed members' mean lies from the cluster's.
/// Throws InvalidArgument when the decomposition has no stored coefficients or `b` is not of
/// its size.
struct ClusteredPrediction {
    std::vector<Point> positions;
    double bound = 0;
};
ClusteredPrediction predict_clustered(const ClusteredBasis& b, const SpectralDecomposition& d,
                                      const FairingOptions& o);

/// What an operation removed, split by frequency: the displacement D = result - input of each
/// vertex as the part carried by the frequencies below `split` (0-based index into the
/// computed ones: frequencies [0, split) of the smallest end) and the rest above it.
struct ChangeByFrequency {
    std::vector<double> below;  ///< per vertex storage index |D_below(v)|; NaN outside the rows
    std::vector<double> above;  ///< |D(v) - D_below(v)|: the higher frequencies, the rest included
    double below_norm = 0;      ///< |D_below|_S over the rows (the S norm)
    double above_norm = 0;      ///< |D - D_below|_S
};

/// change_by_frequency(): D_below = Σ_{k<split} e_k·(e_kᵀ·S·D), the S-orthogonal projection of
/// the displacement onto the frequencies below `split`. For "Removed below / above" colourings:
/// smoothing that took away noise leaves `below` near zero. Needs a decomposition of the
/// smallest end (the largest: InvalidArgument). Throws InvalidArgument for split > size() or
/// sizes that differ from the decomposed mesh's. O(split · rows).
ChangeByFrequency change_by_frequency(const SpectralDecomposition& d,
                                      const std::vector<Point>& input,
                                      const std::vector<Point>& result, std::size_t split);

/// The default relative tolerance of band_splits_multiplet(): neighbouring eigenvalues closer
/// than 1 % of the larger count as one multiplet (a sphere's three-fold λ_1 stays within it
/// under the default model's noise, while its neighbours lie 50 % and more apart).
inline constexpr double kMultipletTolerance = 0.01;

/// Which multiplet a band's edge cuts, and the nearest bands that cut none.
struct MultipletSplit {
    using Band = std::pair<std::size_t, std::size_t>;  ///< [lo, hi], 0-based, inclusive
    bool splits = false;
    /// The multiplet (first, last index) that LO cuts (it starts below LO), and HI's (it ends
    /// above HI), where one does.
    std::optional<Band> cut_at_lo, cut_at_hi;
    /// The nearest bands that cut no multiplet: the band shrunk to whole multiplets, and grown
    /// to them (either may be missing: a band inside one multiplet has no shrunk form).
    std::optional<Band> narrower, wider;
};

/// Whether the band [lo, hi] of `eigenvalues` (ascending) splits a set of equal eigenvalues:
/// neighbours i, i+1 belong to one multiplet when λ_{i+1} - λ_i <= relative_tolerance ·
/// max(|λ_{i+1}|, 1e-300) (chained). An edge at the end of the computed spectrum cuts nothing
/// there (what lies beyond is unknown). Throws InvalidArgument unless lo <= hi < size and the
/// tolerance is in [0, 1). O(size) at most.
MultipletSplit band_splits_multiplet(const Eigen::VectorXd& eigenvalues, std::size_t lo,
                                     std::size_t hi,
                                     double relative_tolerance = kMultipletTolerance);
/// One line for a flagged band, e.g. "band 0:2 splits the multiplet 1:3 (equal eigenvalues
/// within 1 %): use 0:0 or 0:3"; empty when it splits none.
std::string multiplet_split_text(const MultipletSplit& split, std::size_t lo, std::size_t hi,
                                 double relative_tolerance = kMultipletTolerance);

}  // namespace trilab
