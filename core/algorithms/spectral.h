#pragma once
// Frequency decomposition of a mesh's geometry (sections 1.2.2, 1.2.11 and 1.2.12 of the
// reference report): eigenvectors of a fairing Laplacian ("manifold harmonics"), the
// coefficients of the positions in that basis, and reconstruction from a band of frequencies.
//
// Method. Every operator of core/algorithms/laplacian.h is L = -S⁻¹K with K symmetric positive
// semi-definite and S positive diagonal, so the reference's nonsymmetric eigenproblem
// -L·x = λ·x is the generalized symmetric problem K·x = λ·S·x: its spectrum is real and
// non-negative and its eigenvectors are S-orthonormal (Taubin 1995 for the signal-processing
// view; Vallet & Lévy 2008, "Spectral geometry processing with manifold harmonics"). With
// y = S^½·x it is the standard problem A·y = λ·y, A = S^-½·K·S^-½ (exact: S is diagonal).
//  - Partial, smallest k: shift-invert Lanczos (Lehoucq, Sorensen, Yang: ARPACK's implicitly
//    restarted Lanczos, in Spectra 1.0 SymEigsShiftSolver) on (A - σI)⁻¹ with one sparse LDLᵀ
//    of A - σI per shift (Eigen SimplicialLDLT; the rows are numbered once in the approximate
//    minimum degree order of K, so the factors need no permutation, and the solves run
//    straight over the factor's arrays). A - σI = S^-½ (K - σS) S^-½ is congruent to K - σS.
//    σ is first strictly negative (-1e-8 x the largest diagonal of A), so A - σI is SPD even
//    with several zero eigenvalues (disconnected meshes). More than `band_size` frequencies
//    are computed band by band (Vallet & Lévy 2008): each band is the band_size eigenvalues
//    nearest a shift (both sides); the next shift lies 35% of the band's width above a cut in
//    the widest gap of the band's top fifth, so consecutive bands overlap (and it moves past
//    a band that is one cluster of repeated eigenvalues); eigenvectors found twice are
//    de-duplicated by S-orthogonal projection against accepted ones of the same eigenvalue.
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
//    remaining eigenvalues, one factorization counts the eigenvalues below τ, and the two
//    slices are swept band by band on two threads at once (`threads`; 0: two when the
//    machine has two cores). Each slice is verified at its ends; should either fail (a split
//    among close eigenvalues, a repair that needed the other slice's vectors), the whole
//    range is swept once on one thread. The results do not depend on thread timing.
//  - Partial, largest k: Lanczos on A itself (sparse products only), checked the same way.
//  - Full: Eigen's dense SelfAdjointEigenSolver on A, refused above max_full_rows (default
//    5,000) rows: O(n²) memory and O(n³) time. Also refused (InvalidArgument, with the
//    numbers) when its peak, two n x n matrices of doubles (16·n² bytes), exceeds the memory
//    available now (available_memory_bytes(), core/platform.h).
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
#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/algorithms/laplacian.h"
#include "core/enum_table.h"
#include "core/halfedge_mesh.h"
#include "core/progress.h"

namespace trilab {

enum class SpectralMethod { Partial, Full };
/// The one table of SpectralMethod (core/enum_table.h): identifier and label of each value.
inline constexpr EnumEntry<SpectralMethod> kSpectralMethods[] = {
    {SpectralMethod::Partial, "partial", "Partial"},
    {SpectralMethod::Full, "full", "Full"},
};
enum class SpectrumEnd { Smallest, Largest };
/// The one table of SpectrumEnd (core/enum_table.h): identifier and label of each value.
inline constexpr EnumEntry<SpectrumEnd> kSpectrumEnds[] = {
    {SpectrumEnd::Smallest, "smallest", "Smallest"},
    {SpectrumEnd::Largest, "largest", "Largest"},
};

const char* spectral_method_name(SpectralMethod method);  ///< "partial", "full"
const char* spectrum_end_name(SpectrumEnd end);           ///< "smallest", "largest"
/// Throws InvalidArgument listing the names.
SpectrumEnd parse_spectrum_end(const std::string& name);

/// The default largest mesh (rows) for the dense full decomposition.
inline constexpr std::size_t kDefaultMaxFullRows = 5000;

struct SpectralOptions {
    LaplacianOperator op = LaplacianOperator::Umbrella;
    MassMatrix mass = MassMatrix::Normalizer;  ///< S; Barycentric/Voronoi: lumped mass
    bool fix_boundary = false;                 ///< false: free (Neumann) boundary
    SpectralMethod method = SpectralMethod::Partial;
    SpectrumEnd end = SpectrumEnd::Smallest;  ///< which end of the spectrum
    /// Number of frequencies (partial: 1 to rows - 1; full: 0 keeps all rows).
    std::size_t k = 50;
    std::size_t max_full_rows = kDefaultMaxFullRows;  ///< full is refused above this
    /// Smallest end: frequencies per shift-invert band (more are computed band by band);
    /// 0 chooses automatically: one band up to 60 frequencies, bands of 40 above (30 above
    /// 20,000 rows): the Lanczos basis of a band costs O(rows · band²) memory traffic per
    /// restart, which dominates for large bands; each band costs one sparse factorization.
    std::size_t band_size = 0;
    double tolerance = 1e-10;    ///< Lanczos relative tolerance on the Ritz values
    double krylov_factor = 2.0;  ///< Krylov space size (ncv) per wanted eigenpair, >= 1.2
    int max_iterations = 1000;   ///< Lanczos restarts per band
    /// Smallest end: threads for spectrum slicing (1 or 2); 0: two when the machine has them.
    std::size_t threads = 0;
};

/// What a decomposition computed and how.
struct SpectralReport {
    std::string solver;                  ///< e.g. "Spectra shift-invert Lanczos + SimplicialLDLT"
    std::size_t bands = 0;               ///< shift-invert bands (partial smallest)
    std::size_t factorizations = 0;      ///< sparse LDLᵀ factorizations
    std::size_t operations = 0;          ///< operator applications (solves or products)
    std::size_t restarts = 0;            ///< Lanczos restarts, all bands
    std::size_t duplicates_removed = 0;  ///< overlap eigenvectors dropped between bands
    std::size_t repairs = 0;  ///< deflated runs that looked for eigenvalues a band missed
    std::size_t slices = 1;   ///< spectrum slices swept at once (threads)
    double max_residual = 0;  ///< max_k |K e_k - λ_k S e_k| / (|K|_inf |e_k|), relative
    double ms = 0;            ///< wall time
    double factor_ms = 0;     ///< sparse factorizations (summed over the slices' threads)
    double solve_ms = 0;      ///< operator applications: solves, products (summed likewise)
    LaplacianDiagnostics diagnostics;
};

/// Eigenpairs of K·x = λ·S·x and the positions' coefficients.
struct SpectralDecomposition {
    LaplacianOperator op = LaplacianOperator::Umbrella;
    MassMatrix mass = MassMatrix::Normalizer;
    SpectralMethod method = SpectralMethod::Partial;
    SpectrumEnd end = SpectrumEnd::Smallest;
    VertexIndexMap map;                 ///< rows of the eigenproblem <-> vertices
    Eigen::VectorXd S;                  ///< the mass diagonal per row
    Eigen::VectorXd eigenvalues;        ///< ascending, >= 0 (up to rounding)
    Eigen::MatrixXd eigenvectors;       ///< rows x k, S-orthonormal columns
    Eigen::MatrixXd coefficients;       ///< k x 3: α_k = e_kᵀ S X
    std::vector<Point> base_positions;  ///< every vertex (storage index) when decomposed
    SpectralReport report;

    std::size_t rows() const { return map.rows(); }
    std::size_t size() const { return std::size_t(eigenvalues.size()); }
    bool empty() const { return size() == 0; }
};

/// Decomposes `mesh`'s geometry; see the file comment.
SpectralDecomposition decompose(const HalfedgeMesh& mesh, const SpectralOptions& options,
                                Progress& progress);
SpectralDecomposition decompose(const HalfedgeMesh& mesh, const SpectralOptions& options);

/// Positions (rows x 3) of the band [lo, hi] (0-based indices into the computed, ascending
/// frequencies). Throws InvalidArgument unless lo <= hi < size(). O(rows · (hi - lo + 1)).
Eigen::MatrixXd band_positions(const SpectralDecomposition& d, std::size_t lo, std::size_t hi);

/// Every vertex's position (storage index) after reconstruction from [lo, hi]: rows get
/// their band positions, other vertices their base position.
std::vector<Point> reconstruct_positions(const SpectralDecomposition& d, std::size_t lo,
                                         std::size_t hi);

/// A copy of `mesh` with reconstruct_positions(). Throws InvalidArgument when `mesh` does
/// not have the decomposed mesh's vertices (vertices_size differs).
HalfedgeMesh reconstruct(const HalfedgeMesh& mesh, const SpectralDecomposition& d, std::size_t lo,
                         std::size_t hi);

/// Per vertex (storage index) the value of eigenvector `index`; NaN for vertices outside the
/// eigenproblem. For the "Frequency" colouring (signed: a diverging map).
std::vector<double> frequency_field(const SpectralDecomposition& d, std::size_t index);

/// Per vertex (storage index) the length of the part of its position relative to the
/// centroid that the band carries: |Σ_{lo<=k<=hi} e_k(v)·α'_k| with α'_k the coefficients
/// of X - 1·cᵀ, c the S-weighted centroid of the rows (α'_k = α_k - (e_kᵀ·S·1)·cᵀ); NaN
/// outside the eigenproblem. For "Frequency mass". Invariant under rigid motions: without
/// the centring, the constant frequency (λ = 0 on a connected mesh with a free boundary)
/// carries the centroid, and every band that holds it would show the distance from the world
/// origin; with it, that frequency carries nothing. Throws InvalidArgument unless
/// lo <= hi < size(). O(rows · (hi - lo + 1)).
std::vector<double> band_magnitude_field(const SpectralDecomposition& d, std::size_t lo,
                                         std::size_t hi);

/// max |EᵀSE - I| over the computed eigenvectors (O(rows · k²): for tests and reports).
double s_orthonormality_error(const SpectralDecomposition& d);

}  // namespace trilab
