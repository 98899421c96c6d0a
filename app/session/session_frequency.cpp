// The session's side of the frequency decomposition (the Frequency panel): the decomposition
// job, the live band (positions only, shown() as a Band), and the history entries made when a
// slider is released or Restore is pressed. The decomposition lives in document().frequency.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <utility>

#include "app/ops/spectrum_op.h"
#include "app/session/session.h"
#include "core/errors.h"

namespace trilab::viewer {
namespace {
constexpr const char* kBandLabel = "Frequency band";
constexpr const char* kRestoreLabel = "Frequency restore";
}  // namespace

void Session::update_frequency_document() {
    FrequencyDocument& doc = document_.frequency;
    const HalfedgeMesh& mesh = document_.mesh();
    const auto& d = doc.decomposition;
    doc.valid = d && mesh.vertices_size() == d->base_positions.size() &&
                mesh.topology_revision() == doc.topology_revision;
    // The applied band is the current history entry's, so undo and redo keep it right.
    const History::EntryInfo entry = document_.history.info(document_.history.current());
    std::size_t lo = 0, hi = 0;
    bool band = false;
    if (entry.label == kBandLabel && is_operation<SpectrumOptions>(entry.operation)) {
        if (const auto b = options_of<SpectrumOptions>(entry.operation).band) {
            band = true;
            lo = b->first;
            hi = b->second;
        }
    }
    doc.applied = doc.valid && band && hi < doc.eigenvalues.size();
    doc.applied_lo = lo;
    doc.applied_hi = hi;
}

void Session::decompose(const SpectralOptions& options) {
    const std::string name =
        std::string("Frequency decomposition (") + laplacian_operator_name(options.op) + ", " +
        (options.method == SpectralMethod::Full
             ? std::string("full")
             : std::to_string(options.k) + " " + spectrum_end_name(options.end)) +
        ")";
    // The connectivity decomposed: the decomposition stays valid while the document keeps it.
    const HalfedgeMesh snapshot = document_.mesh();  // copy-on-write: the job's own
    const std::uint64_t topology = snapshot.topology_revision();
    const bool started = jobs_.start(name, [this, options, topology, snapshot](Progress& progress) {
        auto d = std::make_shared<const SpectralDecomposition>(
            trilab::decompose(snapshot, options, progress));
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
            update_frequency_document();
            if (on_decomposed) on_decomposed(0, d->size() - 1);
        });
    });
    if (!started) busy_error();
}

void Session::preview_band(std::size_t lo, std::size_t hi) {
    const FrequencyDocument& doc = document_.frequency;
    if (!doc.valid) return;
    // Stop any morph: the view shows the band now.
    morph_ =
        MorphState{1.0, false, morph_.duration, morph_.easing, morph_.playback, 0.0, morph_.moves};
    try {
        // A band that reaches the end of the computed spectrum takes in the rest (the geometry
        // the computed frequencies do not carry): right after Decompose, the full band is the
        // mesh itself, so the first touch of a slider never makes the shape jump.
        shown_.positions = reconstruct_positions(*doc.decomposition, lo, hi, BandRest::Include);
        shown_.kind = Shown::Kind::Band;
        shown_.mesh = &document_.mesh();
        shown_.level = nullptr;
        bump();
    } catch (const std::exception& e) {
        notify_error(std::string("frequency band: ") + e.what());
    }
}

void Session::push_band(std::size_t lo, std::size_t hi, bool restore) {
    const FrequencyDocument& doc = document_.frequency;
    if (!doc.valid) return;
    const SpectralDecomposition& d = *doc.decomposition;
    HalfedgeMesh mesh = document_.mesh();
    std::string label, parameters;
    Operation band;  // the band as the spectrum operation's typed parameter
    try {
        if (restore) {
            mesh.set_positions(d.base_positions);
            label = kRestoreLabel;
            parameters = "the decomposed shape";
        } else {
            mesh.set_positions(reconstruct_positions(d, lo, hi, BandRest::Include));
            label = kBandLabel;
            SpectrumOptions o;
            o.band = std::pair<std::size_t, std::size_t>(lo, hi);
            o.with_rest = true;  // replays to the same positions
            band = operation_of(o);
            parameters = std::to_string(lo) + ":" + std::to_string(hi) + " of " +
                         std::to_string(d.size()) + " (" + laplacian_operator_name(d.op) + ")";
        }
    } catch (const std::exception& e) {
        notify_error(std::string("frequency band: ") + e.what());
        return;
    }
    // A geometry-only step: the same vertices, so the morph interpolates positions.
    std::vector<HalfedgeMesh> meshes;
    meshes.push_back(std::move(mesh));
    log_history_messages(document_.history.push(label, parameters, 0.0, std::move(meshes),
                                                {MorphCorrespondence{}}, band));
    log_.info(label + " " + parameters);
    on_state_changed(false);
}

}  // namespace trilab::viewer
