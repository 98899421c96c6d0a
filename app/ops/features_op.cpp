// The "features" operation: sharp edges by the dihedral angle, with the angle histogram and its
// plateau (core/algorithms/feature_detection.h).
#include <chrono>
#include <cstdio>
#include <string>
#include <utility>

#include "app/ops/operation_decl.h"
#include "app/ops/operation_entries.h"
#include "core/algorithms/feature_detection.h"
#include "core/number_text.h"

namespace trilab {
namespace {

OperationResult run_features(const FeatureDetectionOptions& o, const HalfedgeMesh& mesh,
                             Progress& progress, const RunSettings&) {
    progress.check_cancelled();
    progress.report(0, "detecting features");
    OperationResult result;
    result.label = "Detect features";
    OperationStep step{mesh, MorphCorrespondence{MorphCorrespondence::Kind::SameVertices, {}}};
    const FeatureDetectionReport r = detect_features(step.mesh, o);
    result.ms = r.ms;
    progress.report(1, "detecting features");
    result.steps.push_back(std::move(step));
    result.report.push_back(count_text(r.feature_edges, "feature edge", "feature edges") + " in " +
                            count_text(r.chains, "chain", "chains") +
                            " (angle >= " + number_text(o.angle_deg) + " deg" +
                            (o.boundary ? ", boundary included" : "") + ")");
    if (r.dropped_chains > 0)
        result.report.push_back("dropped " + count_text(r.dropped_chains, "chain", "chains") +
                                " of fewer than " + std::to_string(o.min_chain) + " edges (" +
                                count_text(r.dropped_edges, "edge", "edges") + ")");
    result.report.push_back(count_text(r.corners, "corner", "corners") +
                            (r.junctions ? " (" + std::to_string(r.junctions) +
                                               " where three or more sharp edges meet: "
                                               "non-manifold junctions of the feature curves, "
                                               "kept as corners)"
                                         : std::string()) +
                            ", " + count_text(r.creases, "crease vertex", "crease vertices") +
                            ", " + count_text(r.darts, "dart", "darts"));
    result.report.push_back(r.verdict);
    if (r.histogram.degenerate_edges > 0)
        result.report.push_back(count_text(r.histogram.degenerate_edges, "edge", "edges") +
                                " next to a degenerate face (no angle, never a feature)");
    const AngleHistogram& h = r.histogram;
    result.values = {{"edges", double(r.feature_edges)},
                     {"chains", double(r.chains)},
                     {"corners", double(r.corners)},
                     {"creases", double(r.creases)},
                     {"darts", double(r.darts)},
                     {"junctions", double(r.junctions)},
                     {"dropped_chains", double(r.dropped_chains)},
                     {"dropped_edges", double(r.dropped_edges)},
                     {"boundary_edges", double(r.boundary_edges)},
                     {"interior_edges", double(h.interior_edges)},
                     {"plateau", h.plateau ? 1.0 : 0.0},
                     {"plateau_lo", double(h.plateau_lo)},
                     {"plateau_hi", double(h.plateau_hi)},
                     {"plateau_edges", double(h.plateau_edges)}};
    result.texts = {{"verdict", r.verdict}};
    result.series = {{"histogram", std::vector<double>(h.counts.begin(), h.counts.end())}};
    result.typed_report = r;
    return result;
}

}  // namespace

std::unique_ptr<OperationDef> features_operation() {
    OperationDecl<FeatureDetectionOptions> d(
        "features", "Detect features",
        "Marks the sharp edges: those whose faces' normals differ by at least the angle. The "
        "histogram of the angles has a plateau where the count barely changes (the natural "
        "threshold); a noisy mesh has none (denoise first). The edges become infinitely sharp "
        "for subdivision (every scheme), decimation and smoothing.");
    d.number("angle", &FeatureDetectionOptions::angle_deg, 0, 180, "dihedral angle threshold",
             " (degrees)")
        .above_min()
        .slider(1, 90);
    d.integer("min-chain", &FeatureDetectionOptions::min_chain, 0, 1e9,
              "drop chains of fewer feature edges (0: keep all)")
        .slider(0, 20);
    d.flag("boundary", &FeatureDetectionOptions::boundary, "boundary edges are features too");
    d.run(run_features);
    return d.build();
}

}  // namespace trilab
