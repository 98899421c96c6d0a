#pragma once
// The Frequency panel (Algorithms -> Frequency decomposition, section 1.2.11 of the reference):
// operator, method (full / partial), number of frequencies, smallest or largest, Decompose,
// Restore, a frequency bar with the computed and applied ranges, the two band sliders (the
// mesh follows live while dragging; releasing a slider makes one history entry), the
// frequency to visualize, a spectrum plot (eigenvalue against index) and a coefficient plot
// (log10 |alpha_k| against k), both with axes and tick labels (app/viewer/plots.h). The bar
// and the plots share one x range: the band's shading covers exactly its share of it, and
// a red marker shows the visualized frequency in all three. The panel owns only its controls; the
// decomposition lives in the viewer's FrequencyDocument, and the panel reports what the user did as
// commands, as every panel does.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "app/ops/operation.h"
#include "app/session/session.h"
#include "core/algorithms/spectral.h"

namespace trilab::viewer {

/// The Frequency panel's controls.
struct FrequencyPanelState {
    bool open = false;
    /// The decomposition's parameters: the "spectrum" operation's declaration (its band is
    /// the sliders below, set when a band is pushed).
    Operation op = make_operation("spectrum");
    int lo = 0, hi = 0;  ///< the band used for the reconstruction
    int visualize = 1;   ///< the frequency the "Frequency" colouring shows
};

/// The "Frequency decomposition" section of the sidebar (its header, and its body when open);
/// `busy`: a job runs (Decompose and the sliders disabled). Queues Decompose, PreviewBand
/// (a slider moves), CommitBand (a slider is released), RestoreDecomposed, and UpdateColoring
/// (the frequency to visualize changed), like every panel.
void frequency_window(FrequencyPanelState& state, const FrequencyDocument& doc, bool busy,
                      CommandQueue& commands);

}  // namespace trilab::viewer
