// The panels' side of a reference figure; see figure_panels.h.
#include "app/viewer/figure_panels.h"

#include "app/ops/operation_entries.h"
#include "app/ops/spectrum_op.h"

namespace trilab::viewer {

void show_figure_in_panels(const ReferenceFigure& figure, PanelState& panels) {
    const Operation op = parse_operation(figure.operation);
    if (op.name() == "smooth") {
        panels.fairing.op = op;
        panels.fairing.open = true;
    } else if (op.name() == "spectrum") {
        SpectrumOptions o = options_of<SpectrumOptions>(op);
        if (o.band) {
            panels.frequency.lo = int(o.band->first);
            panels.frequency.hi = int(o.band->second);
        }
        o.band.reset();  // the panel's band is its sliders
        set_options(panels.frequency.op, o);
        panels.frequency.open = true;
    } else if (op.name() == "subdivide") {
        panels.subdivision.op = op;
        panels.subdivision.open = true;
    } else if (op.name() == "decimate") {
        panels.decimation.op = op;
        panels.decimation.open = true;
    }
}

}  // namespace trilab::viewer
