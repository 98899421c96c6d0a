#pragma once
// The reference report's figures (chapter 1 of ../shared/reference), one click away: each
// figure's mesh kind and settings in trilab's own terms, for the viewer's Help > Reference
// figures menu, `trilab --figure NAME` and `trilab-cli figures`. No GL, no ImGui.
//
// A figure is a built-in model (core/algorithms/generators.h: the default model stands in
// for the reference's 1,026-vertex noisy sphere and its bunny, the noisy torus for its head,
// the cube for its 20-vertex subdivision model), the operations that make the figure's input
// from it (noise, subdivision), and the operation the figure shows, in the operation syntax
// of app/ops/operation.h. Steps are trilab's scale-free ones (core/algorithms/fairing.h); the
// one the reference gave in its own units is kept beside it with the translation, one
// sentence the user is shown.
#include <cstddef>
#include <string>
#include <vector>

#include "core/halfedge_mesh.h"
#include "core/progress.h"

namespace trilab::viewer {

/// What the figure shows happening, and what running its settings must give.
enum class FigureResult {
    Smoothed,    ///< a fairing run that ends and smooths the noise
    Diverges,    ///< an explicit run that explodes: trilab stops it and keeps nothing
    Filtered,    ///< a band of the frequency decomposition
    Subdivided,  ///< subdivision iterations
    Decimated,   ///< decimation iterations
};

struct ReferenceFigure {
    std::string name;        ///< "1.12b": the figure and its sub-figure letter
    std::string title;       ///< one line, e.g. "Explicit umbrella at step 20 explodes"
    std::string reference;   ///< what the figure used: model, operator, step, iterations
    std::string model;       ///< the built-in model (generate() name) trilab starts from
    std::string model_note;  ///< why that model stands in for the reference's
    /// Operations that make the figure's input from the model (noise on the head's stand-in,
    /// subdivision before a decimation), each one history entry.
    std::vector<std::string> setup;
    std::string operation;  ///< the operation the figure shows, e.g. "smooth --step 20"
    /// The step in the reference's units and in trilab's (equal where the reference's operator
    /// is already scale-free); both 0 for figures without a step.
    double reference_step = 0, step = 0;
    std::string translation;  ///< how the step was translated, shown with the figure
    FigureResult result = FigureResult::Smoothed;
};

/// Every figure, in the reference's order (Figures 1.2, 1.4, 1.7, 1.10, 1.12, 1.13, 1.15,
/// 1.16, 1.20, 1.22, 1.26, 1.29, 1.31 with their sub-figures).
const std::vector<ReferenceFigure>& reference_figures();

/// The figure called `name` ("1.12b"), or for a figure without its letter ("1.12") its first
/// sub-figure; nullptr when there is none.
const ReferenceFigure* find_reference_figure(const std::string& name);

/// "1.2b, 1.2d, ..., 1.31": every name, for error messages and --help.
std::string reference_figure_names();

/// The figure's input: its model with the setup operations applied (the same each time:
/// the noise is seeded). Throws what the operations throw (Cancelled from `progress`).
HalfedgeMesh reference_figure_input(const ReferenceFigure& figure, Progress& progress);

}  // namespace trilab::viewer
