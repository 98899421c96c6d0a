// The viewer's side of the Frequency panel (frequency_panel.h): the decomposition job, the
// live band preview (positions-only uploads), the history entries made when a slider is
// released or Restore is pressed, and the two frequency colourings. The decomposition lives
// in document_.frequency; the panel holds only its controls.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <utility>

#include "app/ops/operation_entries.h"
#include "app/viewer/viewer.h"
#include "core/errors.h"

namespace trilab::viewer {

namespace {
constexpr const char* kBandLabel = "Frequency band";
constexpr const char* kRestoreLabel = "Frequency restore";
}  // namespace

void Viewer::update_frequency_document() {
    FrequencyDocument& doc = document_.frequency;
    const HalfedgeMesh& mesh = document_.mesh();
    const auto& d = doc.decomposition;
    doc.valid = d && mesh.vertices_size() == d->base_positions.size() &&
                mesh.topology_revision() == doc.topology_revision;
    // The applied band is the current history entry's, so undo and redo keep it right.
    const History::EntryInfo entry = document_.history.info(document_.history.current());
    std::size_t lo = 0, hi = 0;
    if (entry.label == kBandLabel && entry.operation.def) {
        const ParamValue& band = entry.operation.value("band");
        lo = std::size_t(band.x);
        hi = std::size_t(band.y);
    }
    doc.applied = doc.valid && entry.label == kBandLabel && entry.operation.def &&
                  hi < doc.eigenvalues.size();
    doc.applied_lo = lo;
    doc.applied_hi = hi;
}

void Viewer::frequency_actions(FrequencyActions act) {
    FrequencyDocument& doc = document_.frequency;
    scripted_decomposition(act);
    if (act.decompose) start_decomposition();
    if (!doc.valid || jobs_.busy()) return;
    FrequencyPanelState& s = panels_.frequency;
    const int last = int(doc.eigenvalues.size()) - 1;
    s.lo = std::clamp(s.lo, 0, last);
    s.hi = std::clamp(s.hi, s.lo, last);
    if (act.restore) push_frequency_state(true);
    if (act.preview) preview_band();
    if (act.commit) push_frequency_state(false);
    if (act.visualize_changed && view_.settings.coloring == VertexColoring::Frequency)
        update_coloring();
}

void Viewer::scripted_decomposition(FrequencyActions& act) {
    if (options_.decompose.empty() || scripted_decompose_ == 2 || jobs_.busy()) return;
    // Wait for the initial load (a job) and operation before decomposing.
    if (!initial_load_ended_) return;
    if (!options_.operation.empty() && !initial_op_done_ && !options_.mesh_path.empty()) return;
    unsigned k = 0, lo = 0, hi = 0;
    const int n = std::sscanf(options_.decompose.c_str(), "%u:%u:%u", &k, &lo, &hi);
    FrequencyPanelState& s = panels_.frequency;
    if (scripted_decompose_ == 0) {
        scripted_decompose_ = 1;
        if (n < 1 || k < 1) {
            scripted_decompose_ = 2;
            notify_error("--decompose: expected K or K:LO:HI, got '" + options_.decompose + "'");
            return;
        }
        ParamValue& count = s.op.value("k");
        count.x = double(k);
        count.on = count.given = true;
        act.decompose = true;
    } else if (document_.frequency.valid) {
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

void Viewer::start_decomposition() {
    const SpectralOptions options = spectral_options(panels_.frequency.op);
    const std::string name =
        std::string("Frequency decomposition (") + laplacian_operator_name(options.op) + ", " +
        (options.method == SpectralMethod::Full
             ? std::string("full")
             : std::to_string(options.k) + " " + spectrum_end_name(options.end)) +
        ")";
    // The connectivity decomposed: the decomposition stays valid while the document keeps it.
    const std::uint64_t topology = document_.mesh().topology_revision();
    const bool started = jobs_.start(name, [this, options, topology](Progress& progress) {
        auto d = std::make_shared<const SpectralDecomposition>(
            decompose(document_.mesh(), options, progress));
        return JobRunner::Finish([this, d, topology] {
            FrequencyDocument& doc = document_.frequency;
            doc = FrequencyDocument{};
            doc.decomposition = d;
            doc.topology_revision = topology;
            doc.valid = true;
            doc.eigenvalues.assign(d->eigenvalues.data(), d->eigenvalues.data() + d->size());
            for (Eigen::Index k = 0; k < d->coefficients.rows(); ++k)
                doc.log_coefficients.push_back(
                    float(std::log10(std::max(d->coefficients.row(k).norm(), 1e-300))));
            char buf[256];
            std::snprintf(buf, sizeof buf,
                          "%zu frequencies (%s) of %zu vertices, lambda %.4g .. %.4g, %.0f ms, "
                          "%s, max residual %.1e",
                          d->size(), spectrum_end_name(d->end), d->rows(),
                          double(d->eigenvalues[0]),
                          double(d->eigenvalues[d->eigenvalues.size() - 1]), d->report.ms,
                          d->report.solver.c_str(), d->report.max_residual);
            doc.summary = buf;
            log_.info(std::string("Frequency decomposition: ") + buf);
            notice_ =
                Notice{Notice::Level::Info,
                       "Frequency decomposition: " + std::to_string(d->size()) + " frequencies",
                       {buf},
                       false};
            FrequencyPanelState& s = panels_.frequency;
            s.lo = 0;
            s.hi = int(d->size()) - 1;
            s.visualize = std::min(1, s.hi);
            if (coloring_needs_field(view_.settings.coloring)) update_coloring();
        });
    });
    if (!started) notify_error("busy: wait for \"" + jobs_.name() + "\" or cancel it");
}

void Viewer::preview_band() {
    const FrequencyPanelState& s = panels_.frequency;
    const SpectralDecomposition& d = *document_.frequency.decomposition;
    // Stop any morph: the view shows the band now.
    morph_ =
        MorphState{1.0, false, morph_.duration, morph_.easing, morph_.playback, 0.0, morph_.moves};
    if (morph_shown_) {
        morph_shown_ = false;
        show_document();
    }
    try {
        renderer_->update_positions(document_.mesh(),
                                    reconstruct_positions(d, std::size_t(s.lo), std::size_t(s.hi)));
    } catch (const std::exception& e) {
        notify_error(std::string("frequency band: ") + e.what());
    }
    active_frames_ = std::max(active_frames_, 2);
}

void Viewer::push_frequency_state(bool restore) {
    const FrequencyPanelState& s = panels_.frequency;
    const SpectralDecomposition& d = *document_.frequency.decomposition;
    HalfedgeMesh mesh = document_.mesh();
    std::string label, parameters;
    Operation band;  // the band as the spectrum operation's typed parameter
    if (restore) {
        mesh.set_positions(d.base_positions);
        label = kRestoreLabel;
        parameters = "the decomposed shape";
    } else {
        mesh.set_positions(reconstruct_positions(d, std::size_t(s.lo), std::size_t(s.hi)));
        label = kBandLabel;
        band = make_operation("spectrum");
        ParamValue& v = band.value("band");
        v.x = double(s.lo);
        v.y = double(s.hi);
        v.on = v.given = true;
        parameters = std::to_string(s.lo) + ":" + std::to_string(s.hi) + " of " +
                     std::to_string(d.size()) + " (" + laplacian_operator_name(d.op) + ")";
    }
    // A geometry-only step: the same vertices, so the morph interpolates positions.
    std::vector<HalfedgeMesh> meshes;
    meshes.push_back(std::move(mesh));
    log_history_messages(document_.history.push(label, parameters, 0.0, std::move(meshes),
                                                {MorphCorrespondence{}}, band));
    log_.info(label + " " + parameters);
    on_state_changed(false);
}

VertexColors Viewer::frequency_colors(const HalfedgeMesh& mesh) const {
    const FrequencyDocument& doc = document_.frequency;
    const auto& d = doc.decomposition;
    if (!d || mesh.vertices_size() != d->base_positions.size() || d->empty()) return {};
    const FrequencyPanelState& s = panels_.frequency;
    const std::size_t last = d->size() - 1;
    const std::vector<double> values =
        view_.settings.coloring == VertexColoring::Frequency
            ? frequency_field(*d, std::min(std::size_t(std::max(s.visualize, 0)), last))
            : band_magnitude_field(*d, std::min(std::size_t(std::max(s.lo, 0)), last),
                                   std::min(std::size_t(std::max(s.hi, 0)), last));
    return color_field(mesh, values, view_.settings.coloring, view_.settings.coloring_options);
}

}  // namespace trilab::viewer
