// The panels' side of a reference figure; see figure_panels.h.
#include "app/viewer/figure_panels.h"

#include "app/ops/decimate_op.h"
#include "app/ops/operation_entries.h"
#include "app/ops/smooth_op.h"
#include "app/ops/spectrum_op.h"
#include "core/algorithms/subdivision.h"

namespace trilab::viewer {

void show_figure_in_panels(const ReferenceFigure& figure, PanelState& panels) {
    const Operation op = parse_operation(figure.operation);
    if (is_operation<FairingOptions>(op)) {
        panels.fairing.op = op;
        panels.fairing.open = true;
    } else if (is_operation<SpectrumOptions>(op)) {
        SpectrumOptions o = options_of<SpectrumOptions>(op);
        if (o.band) {
            panels.frequency.lo = int(o.band->first);
            panels.frequency.hi = int(o.band->second);
        }
        o.band.reset();  // the panel's band is its sliders
        set_options(panels.frequency.op, o);
        panels.frequency.open = true;
    } else if (is_operation<SubdivisionOptions>(op)) {
        panels.subdivision.op = op;
        panels.subdivision.open = true;
    } else if (is_operation<DecimateOptions>(op)) {
        panels.decimation.op = op;
        panels.decimation.open = true;
    }
}

}  // namespace trilab::viewer
