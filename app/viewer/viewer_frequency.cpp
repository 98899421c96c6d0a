// The viewer's side of the Frequency panel (frequency_panel.h): the panel queues its commands
// for the session (app/session/session_frequency.cpp: the decomposition job, the live band,
// the history entries); the viewer sets the sliders after a decomposition, runs --decompose
// by queueing the same commands, and computes the two frequency colourings.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <utility>

#include "app/ops/operation_entries.h"
#include "app/ops/spectrum_op.h"
#include "app/session/reference_figures.h"
#include "app/viewer/figure_panels.h"
#include "app/viewer/viewer.h"

#include "core/algorithms/transfer_function.h"
#include "core/errors.h"

namespace trilab::viewer {

void Viewer::on_decomposed(std::size_t /*lo*/, std::size_t hi) {
    FrequencyPanelState& s = panels_.frequency;
    s.lo = 0;
    s.hi = int(hi);
    s.visualize = std::min(1, s.hi);
    if (coloring_needs_field(view_.settings.coloring)) update_coloring();
}

bool Viewer::scripted_figure() {
    if (options_.figure.empty() || scripted_figure_ == 2) return true;
    if (!ready_for_script()) return false;
    if (scripted_figure_ == 1) {  // queued, and its job has ended
        scripted_figure_ = 2;
        return true;
    }
    scripted_figure_ = 1;
    const ReferenceFigure* figure = find_reference_figure(options_.figure);
    if (!figure) {
        scripted_figure_ = 2;
        exit_status_ = 1;
        session_.notify_error("--figure: no reference figure '" + options_.figure +
                              "'; the figures are " + reference_figure_names());
        return true;
    }
    show_figure_in_panels(*figure, panels_);
    commands_.push_back(LoadFigure{figure->name});
    return false;
}

void Viewer::scripted_decomposition() {
    // --figure first: its model is what a --decompose decomposes.
    if (!scripted_figure()) return;
    if (options_.decompose.empty() || scripted_decompose_ == 2) return;
    // Wait for the initial load (a job) and operation before decomposing.
    if (!ready_for_script()) return;
    unsigned k = 0, lo = 0, hi = 0;
    const int n = std::sscanf(options_.decompose.c_str(), "%u:%u:%u", &k, &lo, &hi);
    FrequencyPanelState& s = panels_.frequency;
    if (scripted_decompose_ == 0) {
        scripted_decompose_ = 1;
        if (n < 1 || k < 1) {
            scripted_decompose_ = 2;
            session_.notify_error("--decompose: expected K or K:LO:HI, got '" + options_.decompose +
                                  "'");
            return;
        }
        SpectrumOptions o = options_of<SpectrumOptions>(s.op);
        o.k = k;
        set_options(s.op, o);
        commands_.push_back(Decompose{s.op});
    } else if (session_.document().frequency.valid) {
        scripted_decompose_ = 2;
        if (n == 3) {
            s.lo = int(lo);
            s.hi = int(hi);
            commands_.push_back(PreviewBand{lo, hi});
            commands_.push_back(CommitBand{lo, hi});
        }
    } else {
        scripted_decompose_ = 2;  // the decomposition failed (its error is shown)
    }
}

VertexColors Viewer::frequency_colors(const HalfedgeMesh& mesh) const {
    if (view_.settings.coloring == VertexColoring::GeodesicDistance) {
        // A mesh that carries its distances ("v:distance", written by trilab-cli geodesic)
        // shows them; otherwise the distance from the picks, once measured on this state.
        if (mesh.has_vertex_property("v:distance"))
            return color_vertices(mesh, VertexColoring::GeodesicDistance,
                                  view_.settings.coloring_options);
        const PickSet& picks = session_.picks();
        if (picks.distances.size() != mesh.vertices_size() ||
            picks.mesh.topology_revision() != mesh.topology_revision())
            return {};
        return color_field(mesh, picks.distances, VertexColoring::GeodesicDistance,
                           view_.settings.coloring_options);
    }
    const FrequencyDocument& doc = session_.document().frequency;
    const auto& d = doc.decomposition;
    if (!d || mesh.vertices_size() != d->base_positions.size() || d->empty()) return {};
    const FrequencyPanelState& s = panels_.frequency;
    const std::size_t last = d->size() - 1;
    const VertexColoring coloring = view_.settings.coloring;
    if (coloring == VertexColoring::RemovedBelow || coloring == VertexColoring::RemovedAbove) {
        // What the current entry changed, split at the top of the band: below it is shape,
        // above it detail and noise (core/algorithms/transfer_function.h).
        const std::vector<Point> before = session_.reference_positions();
        if (before.size() != mesh.vertices_size()) return {};
        const std::size_t split = std::min(std::size_t(std::max(s.hi, 0)) + 1, d->size());
        try {
            const ChangeByFrequency change =
                change_by_frequency(*d, before, mesh.positions(), split);
            return color_field(
                mesh, coloring == VertexColoring::RemovedBelow ? change.below : change.above,
                coloring, view_.settings.coloring_options);
        } catch (const std::exception&) {
            return {};  // e.g. a decomposition of the largest end: the notice says what is needed
        }
    }
    const std::vector<double> values =
        view_.settings.coloring == VertexColoring::Frequency
            ? frequency_field(*d, std::min(std::size_t(std::max(s.visualize, 0)), last))
            : band_magnitude_field(*d, std::min(std::size_t(std::max(s.lo, 0)), last),
                                   std::min(std::size_t(std::max(s.hi, 0)), last),
                                   BandRest::Include);
    return color_field(mesh, values, view_.settings.coloring, view_.settings.coloring_options);
}

}  // namespace trilab::viewer
