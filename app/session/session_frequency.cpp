// The frequency document; see session_frequency.h.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <utility>

#include "app/ops/spectrum_op.h"
#include "app/session/session_frequency.h"
#include "core/errors.h"

namespace trilab::viewer {
namespace {
constexpr const char* kBandLabel = "Frequency band";
constexpr const char* kRestoreLabel = "Frequency restore";
}  // namespace

void SessionFrequency::follow_document() {
    FrequencyDocument& doc = core_.document.frequency;
    const HalfedgeMesh& mesh = core_.document.mesh();
    const auto& d = doc.decomposition;
    doc.valid = d && mesh.vertices_size() == d->base_positions.size() &&
                mesh.topology_revision() == doc.topology_revision;
    // The applied band is the current history entry's, so undo and redo keep it right.
    const History::EntryInfo entry = core_.document.history.info(core_.document.history.current());
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

void SessionFrequency::decompose(const SpectralOptions& options) {
    const std::string name =
        std::string("Frequency decomposition (") + laplacian_operator_name(options.op) + ", " +
        (options.method == SpectralMethod::Full
             ? std::string("full")
             : std::to_string(options.k) + " " + spectrum_end_name(options.end)) +
        ")";
    // The connectivity decomposed: the decomposition stays valid while the document keeps it.
    const HalfedgeMesh snapshot = core_.document.mesh();  // copy-on-write: the job's own
    const std::uint64_t topology = snapshot.topology_revision();
    const bool started =
        core_.jobs.start(name, [this, options, topology, snapshot](Progress& progress) {
            auto d = std::make_shared<const SpectralDecomposition>(
                trilab::decompose(snapshot, options, progress));
            return JobRunner::Finish([this, d, topology] {
                FrequencyDocument& doc = core_.document.frequency;
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
                core_.log.info(std::string("Frequency decomposition: ") + buf);
                core_.notice =
                    Notice{Notice::Level::Info,
                           "Frequency decomposition: " + std::to_string(d->size()) + " frequencies",
                           {buf},
                           false};
                follow_document();
                core_.events.decomposed_hi = d->size() - 1;
            });
        });
    if (!started) core_.busy_error();
}

void SessionFrequency::preview_band(std::size_t lo, std::size_t hi) {
    const FrequencyDocument& doc = core_.document.frequency;
    if (!doc.valid) return;
    // Stop any morph: the view shows the band now.
    morph_.reset(core_.morph.moves);
    try {
        // A band that reaches the end of the computed spectrum takes in the rest (the geometry
        // the computed frequencies do not carry): right after Decompose, the full band is the
        // mesh itself, so the first touch of a slider never makes the shape jump.
        std::vector<Point> positions =
            reconstruct_positions(*doc.decomposition, lo, hi, BandRest::Include);
        core_.show(Shown::Kind::Band, &core_.mesh());
        core_.shown.positions = std::move(positions);
    } catch (const std::exception& e) {
        core_.notify_error(std::string("frequency band: ") + e.what());
    }
}

void SessionFrequency::push_band(std::size_t lo, std::size_t hi, bool restore) {
    const FrequencyDocument& doc = core_.document.frequency;
    if (!doc.valid) return;
    const SpectralDecomposition& d = *doc.decomposition;
    HalfedgeMesh mesh = core_.document.mesh();
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
        core_.notify_error(std::string("frequency band: ") + e.what());
        return;
    }
    // A geometry-only step: the same vertices, so the morph interpolates positions.
    std::vector<HalfedgeMesh> meshes;
    meshes.push_back(std::move(mesh));
    core_.log.info(label + " " + parameters);
    core_.push_entry(label, parameters, 0.0, std::move(meshes), {MorphCorrespondence{}}, band);
}

}  // namespace trilab::viewer
