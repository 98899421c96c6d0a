// The viewer's side of the Frequency panel (frequency_panel.h): what the panel asked for goes
// to the session (app/session/session_frequency.cpp: the decomposition job, the live band, the
// history entries); the viewer keeps the panel's sliders and the two frequency colourings.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <utility>

#include "app/ops/operation_entries.h"
#include "app/ops/spectrum_op.h"
#include "app/viewer/viewer.h"
#include "core/errors.h"

namespace trilab::viewer {

void Viewer::frequency_actions(FrequencyActions act) {
    const FrequencyDocument& doc = session_.document().frequency;
    scripted_decomposition(act);
    if (act.decompose) session_.decompose(spectral_options(panels_.frequency.op));
    if (!doc.valid || session_.busy()) return;
    FrequencyPanelState& s = panels_.frequency;
    const int last = int(doc.eigenvalues.size()) - 1;
    s.lo = std::clamp(s.lo, 0, last);
    s.hi = std::clamp(s.hi, s.lo, last);
    if (act.restore) session_.push_band(0, 0, true);
    if (act.preview) session_.preview_band(std::size_t(s.lo), std::size_t(s.hi));
    if (act.commit) session_.push_band(std::size_t(s.lo), std::size_t(s.hi), false);
    if (act.visualize_changed && view_.settings.coloring == VertexColoring::Frequency)
        update_coloring();
}

void Viewer::on_decomposed(std::size_t /*lo*/, std::size_t hi) {
    FrequencyPanelState& s = panels_.frequency;
    s.lo = 0;
    s.hi = int(hi);
    s.visualize = std::min(1, s.hi);
    if (coloring_needs_field(view_.settings.coloring)) update_coloring();
}

void Viewer::scripted_decomposition(FrequencyActions& act) {
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
        act.decompose = true;
    } else if (session_.document().frequency.valid) {
        scripted_decompose_ = 2;
        if (n == 3) {
            s.lo = int(lo);
            s.hi = int(hi);
            act.preview = act.commit = true;
        }
    } else {
        scripted_decompose_ = 2;  // the decomposition failed (its error is shown)
    }
}

VertexColors Viewer::frequency_colors(const HalfedgeMesh& mesh) const {
    const FrequencyDocument& doc = session_.document().frequency;
    const auto& d = doc.decomposition;
    if (!d || mesh.vertices_size() != d->base_positions.size() || d->empty()) return {};
    const FrequencyPanelState& s = panels_.frequency;
    const std::size_t last = d->size() - 1;
    const std::vector<double> values =
        view_.settings.coloring == VertexColoring::Frequency
            ? frequency_field(*d, std::min(std::size_t(std::max(s.visualize, 0)), last))
            : band_magnitude_field(*d, std::min(std::size_t(std::max(s.lo, 0)), last),
                                   std::min(std::size_t(std::max(s.hi, 0)), last),
                                   BandRest::Include);
    return color_field(mesh, values, view_.settings.coloring, view_.settings.coloring_options);
}

}  // namespace trilab::viewer
