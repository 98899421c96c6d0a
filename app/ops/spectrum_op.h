#pragma once
// The options and the report of the "spectrum" operation (app/ops/spectrum_op.cpp), for
// callers that read or write them as typed fields: options_of<SpectrumOptions>(op),
// set_options(op, o), operation_of(o), report_of<SpectrumReport>(result)
// (app/ops/operation.h).
#include <cstddef>
#include <optional>
#include <utility>
#include <vector>

#include "core/algorithms/spectral.h"
#include "core/algorithms/transfer_function.h"

namespace trilab {

/// The operation's options: the core's, with the count, the band and the threads optional.
struct SpectrumOptions {
    SpectralOptions spectral;
    std::optional<std::size_t> k;  ///< unset: 50, or every frequency with --full
    bool full = false;             ///< every frequency, dense (SpectralMethod::Full)
    std::optional<std::pair<std::size_t, std::size_t>> band;  ///< LO:HI; unset: all
    std::optional<std::size_t> threads;                       ///< unset: the machine's
    bool with_rest = false;  ///< the band takes in the rest when it reaches the open end
};

/// What a run computed: the decomposition's report and the band it reconstructed.
struct SpectrumReport {
    std::size_t k = 0;           ///< frequencies computed
    std::size_t rows = 0;        ///< vertices decomposed
    std::size_t lo = 0, hi = 0;  ///< the band reconstructed, 0-based, inclusive
    LaplacianOperator op = LaplacianOperator::Umbrella;
    SpectralMethod method = SpectralMethod::Partial;
    SpectrumEnd end = SpectrumEnd::Smallest;
    std::vector<double> eigenvalues;  ///< ascending, k of them
    /// Whether the band's edges split a multiplet (equal eigenvalues within
    /// kMultipletTolerance, core/algorithms/transfer_function.h) and the nearest whole bands.
    MultipletSplit band_split;
    SpectralReport decomposition;  ///< solver, slices, residual, time
};

/// The core's options of `o`: the method from `full`, the count and threads from their
/// defaults when unset.
SpectralOptions spectral_options(const SpectrumOptions& o);

}  // namespace trilab
