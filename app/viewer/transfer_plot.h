#pragma once
// The spectral lens in the Fairing section (issue 28): the gain of the current fairing
// settings at each frequency of this mesh's operator (core/algorithms/transfer_function.h),
// on a log scale of the eigenvalue, with where the gain grows (|g| > 1) or oscillates (g < 0)
// shaded, the eigenvalue above which the step is unstable marked, Taubin's pass band marked,
// and the measured gain of the last run or preview over it. Drawn from the panel's options
// every frame, so it follows a parameter as it is dragged.
#include <limits>
#include <string>
#include <vector>

#include "core/algorithms/fairing.h"

namespace trilab::viewer {

/// What the curve is drawn over, prepared by the viewer (the panel computes nothing heavy).
struct TransferView {
    /// The decomposition's eigenvalues when it is of the Fairing panel's operator; empty:
    /// the analytic range [0, lambda_max] is drawn.
    std::vector<double> eigenvalues;
    /// The largest eigenvalue: the decomposition's last, or 2 / (largest stable explicit
    /// step) from the stability estimate (NaN: not known yet).
    double lambda_max = std::numeric_limits<double>::quiet_NaN();
    /// The measured gain per frequency of the last fairing run or preview (NaN: undefined),
    /// empty when there is none for these settings.
    std::vector<double> measured;
    std::string measured_note;  ///< e.g. "differs by the nonlinearity of curvature flow"
    bool decomposition_of_other_operator = false;
    /// The reference figure whose settings the panel holds: its step's translation (empty:
    /// none), shown under the curve.
    std::string figure_note;
    /// The diverging run on the screen (Session::show_diverging_run): its note, drawn in red
    /// instead of the button.
    std::string diverging_note;
};

/// What a press under the curve asks for.
enum class TransferPlotRequest {
    None,
    Decompose,         ///< "Decompose for this operator"
    ShowDivergingRun,  ///< "Show the diverging run" (offered when the settings are unstable)
};

/// Draws the curve for options `o` over `view` (test hook ids: "lens: area", "lens: unstable",
/// "lens: pass band", "lens: grows", "lens: oscillates", "lens: measured", "lens: figure",
/// "lens: diverged"). Returns what the user asked for with the buttons under the curve (a
/// decomposition of the panel's operator, the diverging run), for the section to queue.
TransferPlotRequest transfer_plot(const FairingOptions& o, const TransferView& view);

}  // namespace trilab::viewer
