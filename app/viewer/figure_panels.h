#pragma once
// The panels' side of a reference figure (app/session/reference_figures.h): the panel of the
// figure's operation takes its settings and opens, so the user sees (and can change) what the
// figure ran. Shared by Help > Reference figures and `trilab --figure NAME`.
#include "app/session/reference_figures.h"
#include "app/viewer/panels.h"

namespace trilab::viewer {

/// Sets the panel of `figure`'s operation to its settings and opens it: the first tool that
/// holds the operation takes it (Tool::show_figure(): Fairing, Frequency decomposition with
/// the band on its sliders, Subdivision, Decimation). Queues nothing (the viewer queues
/// LoadFigure).
void show_figure_in_panels(const ReferenceFigure& figure, const ToolList& tools);

/// Help > Reference figures: one item per figure, "1.12b  Explicit umbrella at step 20
/// explodes", with what the reference used, the model and the step's translation as its
/// tooltip. A press sets the panels (show_figure_in_panels) and queues LoadFigure; the items
/// are disabled while `busy`. Defined in menus.cpp with the other menus.
void reference_figures_menu(const ToolList& tools, bool busy, CommandQueue& commands);

}  // namespace trilab::viewer
