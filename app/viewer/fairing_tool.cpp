#include "app/viewer/fairing_tool.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "app/ops/operation.h"
#include "app/ops/operation_entries.h"
#include "app/ops/smooth_op.h"
#include "app/session/reference_figures.h"
#include "core/algorithms/fairing.h"
#include "core/algorithms/transfer_function.h"
#include "core/features.h"

namespace trilab::viewer {

FairingTool::FairingTool(ViewerContext& context) : OperationTool(context, {}) {
    set_panels({&panel_});
}

void FairingTool::section(const SidebarContext& context, CommandQueue& commands) {
    fairing_section(panel_, context, commands);
}

PanelEntries FairingTool::panels() {
    PanelEntry entry;
    entry.name = "fairing";
    entry.title = "Fairing";
    entry.open = &panel_.open;
    entry.menu = PanelMenu::Algorithms;
    return {entry};
}

void FairingTool::update() {
    OperationTool::update();
    update_stable_step();
    update_lens();
}

void FairingTool::update_stable_step() {
    FairingPanelState& f = panel_;
    if (!f.open) return;
    Session& session = context_.session;
    const FairingOperator op = options_of<FairingOptions>(f.op).op;
    const HalfedgeMesh::Revision state = session.mesh().revision();
    // A preview of this state reports it (where the run estimated it).
    const OperationResult* preview = session.previews().result();
    const std::optional<Operation>& requested = session.previews().requested();
    if (preview && requested && is_operation<FairingOptions>(*requested) &&
        options_of<FairingOptions>(*requested).op == op) {
        if (const SmoothReport* r = report_of<SmoothReport>(*preview);
            r && std::isfinite(r->max_stable_step)) {
            f.max_stable_step = r->max_stable_step;
            f.stable_step_state = state;
            f.stable_step_operator = op;
            return;
        }
        // A large mesh's preview of an umbrella step up to 1 does not estimate it: below.
    }
    if (f.stable_step_state == state && f.stable_step_operator == op) return;
    // Otherwise the session estimates it off the render thread (SessionGuidance): NaN (not
    // known) until the estimate of this state and operator arrives.
    session.execute(EstimateStableStep{op});
    const SessionGuidance::StableStep* estimate = session.guidance().stable_step();
    if (estimate && estimate->state == state && estimate->op == op) {
        f.max_stable_step = estimate->step;
        f.stable_step_state = state;
        f.stable_step_operator = op;
    } else {
        f.max_stable_step = std::numeric_limits<double>::quiet_NaN();
    }
}

void FairingTool::update_lens() {
    FairingPanelState& panel = panel_;
    if (context_.session.previews().prediction_shown())
        panel.preview_note = "showing the spectral prediction; the exact result follows";
    const bool diverging = context_.session.figures().diverging_run_shown();
    if (diverging) panel.preview_note = "showing the DIVERGED run: not a result (Esc returns)";
    if (!panel.open) return;  // drawn only when the section is open
    // Per frame, whatever the data below: the figure's translation and the diverged mark.
    std::string figure_note;
    const std::string figure_name = context_.session.figures().figure();
    if (const ReferenceFigure* f =
            figure_name.empty() ? nullptr : find_reference_figure(figure_name);
        f && panel.op.text() == parse_operation(f->operation).text())
        figure_note = "Figure " + f->name + ": " + f->translation;
    const std::string diverging_note =
        diverging ? context_.session.figures().diverging_run_note() : "";
    panel.lens.figure_note = figure_note;
    panel.lens.diverging_note = diverging_note;
    const FairingOptions o = options_of<FairingOptions>(panel.op);
    const FrequencyDocument& doc = context_.session.document().frequency;
    const SpectralDecomposition* d = doc.valid ? doc.decomposition.get() : nullptr;
    const bool same_operator = d && !d->empty() && d->op == laplacian_of(o.op) &&
                               d->mass == MassMatrix::Normalizer && d->end == SpectrumEnd::Smallest;
    // What was run with these settings: the preview on the screen, or the current entry.
    const HalfedgeMesh* result = nullptr;
    std::vector<Point> input;
    const Shown& shown = context_.session.shown();
    // (Not the spectral prediction: its measured gain is the curve by construction, and
    // measuring it would delay the frame that shows it.)
    if (shown.kind == Shown::Kind::Preview && context_.session.previews().previewing(panel.op) &&
        shown.mesh && !context_.session.previews().prediction_shown() &&
        !context_.session.figures().diverging_run_shown() &&
        shown.mesh->vertices_size() == context_.session.mesh().vertices_size()) {
        result = shown.mesh;
        input = context_.session.mesh().positions();
    } else if (context_.session.history().current() > 0 &&
               context_.session.history()
                       .info(context_.session.history().current())
                       .operation.text() == panel.op.text()) {
        result = &context_.session.mesh();
        input = context_.session.editing().reference_positions();
    }
    const std::string key = panel.op.text() + " " + std::to_string(d ? std::uintptr_t(d) : 0) +
                            " " + std::to_string(shown.version) + " " +
                            std::to_string(context_.session.history().current()) + " " +
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
        const bool features =
            o.features == FeatureSource::Auto ||
            (o.features == FeatureSource::Stored && has_features(context_.session.mesh()));
        if (features)
            std::snprintf(
                buf, sizeof buf,
                "measured (dots): up to %.2g from the curve: the feature vertices %s, "
                "which the spectrum does not know",
                worst,
                o.feature_mode == FeatureMode::Slide ? "slide along their curves" : "stay fixed");
        else if (fairing_is_linear(o.op))
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

}  // namespace trilab::viewer
