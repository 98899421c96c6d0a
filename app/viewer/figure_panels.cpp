// The panels' side of a reference figure; see figure_panels.h.
#include "app/viewer/figure_panels.h"

#include "app/ops/operation_entries.h"
#include "app/viewer/tool.h"

namespace trilab::viewer {

void show_figure_in_panels(const ReferenceFigure& figure, const ToolList& tools) {
    const Operation op = parse_operation(figure.operation);
    for (Tool* tool : tools)
        if (tool->show_figure(op)) return;
}

}  // namespace trilab::viewer
