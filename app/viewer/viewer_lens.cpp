// The spectral lens's data for the Fairing section (app/viewer/transfer_plot.h): the spectrum
// of the panel's operator when the decomposition is of it, the analytic range otherwise, and
// the measured gain of the fairing preview shown or of the current entry when it is a
// smoothing with the panel's settings.
#include <cmath>
#include <cstdio>
#include <string>

#include "app/ops/operation_entries.h"
#include "app/session/reference_figures.h"
#include "app/viewer/viewer.h"
#include "core/algorithms/selection.h"
#include "core/algorithms/transfer_function.h"

namespace trilab::viewer {

void Viewer::update_lens() {
    FairingPanelState& panel = panels_.fairing;
    if (panel.lens.show_diverging_pressed) {  // the button under the curve
        panel.lens.show_diverging_pressed = false;
        if (!session_.busy()) session_.show_diverging_run(panel.op);
    }
    if (session_.prediction_shown())
        panel.preview_note = "showing the spectral prediction; the exact result follows";
    const bool diverging = session_.diverging_run_shown();
    if (diverging) panel.preview_note = "showing the DIVERGED run: not a result (Esc returns)";
    if (!panel.open) return;  // drawn only when the section is open
    // Per frame, whatever the data below: the figure's translation and the diverged mark.
    std::string figure_note;
    const std::string figure_name = session_.figure();
    if (const ReferenceFigure* f =
            figure_name.empty() ? nullptr : find_reference_figure(figure_name);
        f && panel.op.text() == parse_operation(f->operation).text())
        figure_note = "Figure " + f->name + ": " + f->translation;
    const std::string diverging_note = diverging ? session_.diverging_run_note() : "";
    panel.lens.figure_note = figure_note;
    panel.lens.diverging_note = diverging_note;
    const FairingOptions o = options_of<FairingOptions>(panel.op);
    const FrequencyDocument& doc = session_.document().frequency;
    const SpectralDecomposition* d = doc.valid ? doc.decomposition.get() : nullptr;
    const bool same_operator = d && !d->empty() && d->op == laplacian_of(o.op) &&
                               d->mass == MassMatrix::Normalizer && d->end == SpectrumEnd::Smallest;
    // What was run with these settings: the preview on the screen, or the current entry.
    const HalfedgeMesh* result = nullptr;
    std::vector<Point> input;
    const Shown& shown = session_.shown();
    // (Not the spectral prediction: its measured gain is the curve by construction, and
    // measuring it would delay the frame that shows it.)
    if (shown.kind == Shown::Kind::Preview && session_.previewing(panel.op) && shown.mesh &&
        !session_.prediction_shown() && !session_.diverging_run_shown() &&
        shown.mesh->vertices_size() == session_.mesh().vertices_size()) {
        result = shown.mesh;
        input = session_.mesh().positions();
    } else if (session_.history().current() > 0 &&
               session_.history().info(session_.history().current()).operation.text() ==
                   panel.op.text()) {
        result = &session_.mesh();
        input = session_.reference_positions();
    }
    const std::string key = panel.op.text() + " " + std::to_string(d ? std::uintptr_t(d) : 0) +
                            " " + std::to_string(shown.version) + " " +
                            std::to_string(session_.history().current()) + " " +
                            std::to_string(panel.max_stable_step);
    if (key == lens_key_) return;
    lens_key_ = key;
    TransferView& view = panel.lens;
    view = TransferView{};
    view.figure_note = figure_note;
    view.diverging_note = diverging_note;
    view.decomposition_of_other_operator = d && !same_operator;
    if (std::isfinite(panel.max_stable_step) && panel.max_stable_step > 0)
        view.lambda_max = 2.0 / panel.max_stable_step;
    if (same_operator) {
        view.eigenvalues.assign(d->eigenvalues.data(), d->eigenvalues.data() + d->size());
        if (!(view.lambda_max >= view.eigenvalues.back()))
            view.lambda_max = view.eigenvalues.back();
    }
    if (!same_operator || !result || input.size() != result->vertices_size() ||
        input.size() != d->base_positions.size())
        return;
    try {
        const MeasuredGain measured = measured_gain(*d, input, result->positions());
        view.measured = measured.gain;
        double worst = 0;
        const std::vector<double> predicted = fairing_gains(o, d->eigenvalues);
        for (std::size_t k = 0; k < view.measured.size(); ++k)
            if (std::isfinite(view.measured[k]))
                worst = std::max(worst, std::abs(view.measured[k] - predicted[k]));
        char buf[200];
        if (fairing_is_linear(o.op))
            std::snprintf(buf, sizeof buf,
                          "measured (dots): within %.2g of the curve (exact on a closed mesh; "
                          "fixed boundary vertices make the difference on an open one)",
                          worst);
        else
            std::snprintf(buf, sizeof buf,
                          "measured (dots): up to %.2g from the curve, the nonlinearity of this "
                          "operator (its weights follow the positions)",
                          worst);
        view.measured_note = buf;
    } catch (const std::exception& e) {
        view.measured_note = std::string("measured gain: ") + e.what();
    }
}

void Viewer::update_region_notes() {
    const HalfedgeMesh& mesh = session_.mesh();
    const std::uint64_t state = mesh.attribute_revision() ^ (mesh.topology_revision() << 20);
    if (state == region_notes_state_) return;
    region_notes_state_ = state;
    std::string selected, whole;
    if (const std::optional<Selection> s = stored_selection(mesh);
        s && !selects_everything(mesh, *s)) {
        selected = "acts on the selection: " + std::to_string(count_selected(*s)) + " of " +
                   std::to_string(mesh.n_vertices()) + " vertices (weight > 0)";
        whole = "the document has a selection, but this operation acts on the whole mesh";
    }
    for (OperationPanelState* panel : operation_panels())
        panel->region_note = selected.empty()                               ? std::string()
                             : panel->op.def && panel->op.def->takes_region ? selected
                                                                            : whole;
}

}  // namespace trilab::viewer
