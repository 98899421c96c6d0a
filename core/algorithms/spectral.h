#pragma once
// Frequency decomposition of a mesh's geometry, "manifold harmonics" (sections 1.2.2, 1.2.11
// and 1.2.12 of the reference report; Vallet & Lévy 2008, "Spectral geometry processing with
// manifold harmonics"; Taubin 1995): the eigenpairs of K·x = λ·S·x for an operator
// L = -S⁻¹K of core/algorithms/laplacian.h (real, λ >= 0, S-orthonormal eigenvectors), the
// positions' coefficients α_k = e_kᵀ·S·X, and reconstruction Σ_{lo<=k<=hi} e_k·α_kᵀ from a
// band. With every frequency of a full decomposition it returns the mesh (~1e-12 relative);
// of a partial one, with the rest (BandRest: the part the computed frequencies miss) too.
//  - Partial: the smallest k by shift-invert Lanczos band by band (thick restarts, ARPACK's;
//    two spectrum slices on two threads, Campos & Roman 2012), the largest k by Lanczos. The
//    number of eigenvalues found is verified exactly (Sylvester's law of inertia): none is
//    missed, even of high multiplicity. Deterministic, whatever the threads' timing. From
//    kBlockMinRows rows (SpectralSolver) all k at once by block shift-invert Lanczos with one
//    factorization and one count, falling back to the bands should it not verify.
//  - Full: dense, refused above max_full_rows (default 5,000) rows or the memory available.
//  - Rows: the Laplacian's free rows (free, Neumann boundary by default; fix_boundary: the
//    Dirichlet problem). Isolated and fixed vertices keep their positions in reconstructions.
// Errors: InvalidArgument naming the option before any work, or "the mesh is degenerate: ..."
// (tiny area, vertex mass or a zero K); Error when the solver fails (after one retry with a
// larger Krylov space), saying what to change; Cancelled from the progress. The input mesh is
// never modified; every loop is bounded.
// Complexity: one sparse factorization per shift (about O(V^1.5) on surfaces), O(V·k·band)
// for the Lanczos bases, O(V·k²) for the final orthonormalization; memory O(V·k).
// The method, its verification and its heuristics (band sizes, where the next shift lies,
// where the slices split) are explained in spectral.cpp.
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

/// How the partial method computes the smallest frequencies (see spectral.cpp).
///  - Bands: band by band, one sparse factorization per band (and per slice).
///  - Block: all k at once by block shift-invert Lanczos with one factorization (plus one for
///    the eigenvalue count); should it not converge or its count differ, the bands take over.
///  - Auto: Block from kBlockMinRows rows up (where a factorization costs more than the
///    Lanczos basis), else Bands.
enum class SpectralSolver { Auto, Bands, Block };
/// Auto chooses the block solver from this many rows up.
inline constexpr std::size_t kBlockMinRows = 50000;

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
    SpectralSolver solver = SpectralSolver::Auto;  ///< smallest end, partial
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

/// Whether a band takes in the rest: the part of the rows' geometry X that the computed
/// frequencies do not carry, R = X - Σ_{k<size()} e_k·α_kᵀ (the S-orthogonal projection of X
/// onto the uncomputed eigenvectors, so R = Σ e_k·α_kᵀ over the frequencies not computed).
/// Include adds R to a band that reaches the open end of the computed spectrum (see
/// band_reaches_rest()): the band then runs on through the uncomputed frequencies, so
/// [0, size() - 1] with the rest is the decomposed mesh and a band stays contiguous in the
/// whole spectrum. A band short of the open end is the same with Include as with Exclude.
enum class BandRest { Exclude, Include };

/// Whether [lo, hi] reaches the open end of the computed spectrum, beyond which the rest
/// lies: hi == size() - 1 when the smallest frequencies were computed (the rest: the higher
/// ones), lo == 0 when the largest were (the rest: the lower ones, the constant among them).
/// For a full decomposition of all rows the rest is zero up to rounding. Throws
/// InvalidArgument unless lo <= hi < size().
bool band_reaches_rest(const SpectralDecomposition& d, std::size_t lo, std::size_t hi);

/// The rest R = X - E·A (rows x 3; see BandRest). O(rows · size()).
Eigen::MatrixXd rest_positions(const SpectralDecomposition& d);

/// Positions (rows x 3) of the band [lo, hi] (0-based indices into the computed, ascending
/// frequencies), plus the rest with BandRest::Include when the band reaches the open end:
/// then computed as X minus the computed frequencies outside the band, so [0, size() - 1]
/// with the rest is X exactly. Exclude: Σ_{lo<=k<=hi} e_k·α_kᵀ. Throws InvalidArgument
/// unless lo <= hi < size(). O(rows · (hi - lo + 1)), with the rest O(rows · (size() - (hi -
/// lo + 1))).
Eigen::MatrixXd band_positions(const SpectralDecomposition& d, std::size_t lo, std::size_t hi,
                               BandRest rest = BandRest::Exclude);

/// Every vertex's position (storage index) after reconstruction from [lo, hi] (and the rest,
/// as band_positions()): rows get their band positions, other vertices their base position.
/// With a `region` (core/algorithms/selection.h: one weight in [0, 1] per vertex storage
/// index) each vertex's displacement from its base position is scaled by its weight: weight 1
/// gives the band position exactly, weight 0 the base position bit for bit. Throws
/// InvalidArgument naming the region when it does not fit (check_selection()).
std::vector<Point> reconstruct_positions(const SpectralDecomposition& d, std::size_t lo,
                                         std::size_t hi, BandRest rest = BandRest::Exclude,
                                         const std::vector<float>* region = nullptr);

/// A copy of `mesh` with reconstruct_positions() (and its region). Throws InvalidArgument
/// when `mesh` does not have the decomposed mesh's vertices (vertices_size differs).
HalfedgeMesh reconstruct(const HalfedgeMesh& mesh, const SpectralDecomposition& d, std::size_t lo,
                         std::size_t hi, BandRest rest = BandRest::Exclude,
                         const std::vector<float>* region = nullptr);

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
/// lo <= hi < size(). O(rows · (hi - lo + 1)). With BandRest::Include the band carries the
/// rest as in band_positions() ([0, size() - 1] with the rest: |X - c| exactly), so the
/// colouring agrees with the shape of the same band.
std::vector<double> band_magnitude_field(const SpectralDecomposition& d, std::size_t lo,
                                         std::size_t hi, BandRest rest = BandRest::Exclude);

/// max |EᵀSE - I| over the computed eigenvectors (O(rows · k²): for tests and reports).
double s_orthonormality_error(const SpectralDecomposition& d);

}  // namespace trilab
