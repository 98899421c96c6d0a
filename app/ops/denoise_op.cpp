// The "denoise" operation: bilateral or guided normal filtering, then the vertex update
// (core/algorithms/denoise.h).
#include <chrono>
#include <cstdio>
#include <string>
#include <utility>

#include "app/ops/operation_decl.h"
#include "app/ops/operation_entries.h"
#include "core/algorithms/denoise.h"
#include "core/number_text.h"

namespace trilab {
namespace {

void add_report_lines(const DenoiseReport& r, const HalfedgeMesh& mesh, OperationResult& result) {
    char line[200];
    std::snprintf(line, sizeof(line),
                  "%d normal and %d vertex iterations; normals filtered on %zu of %zu faces",
                  r.normal_iterations_done, r.vertex_iterations_done, r.filtered_faces,
                  mesh.n_faces());
    result.report.emplace_back(line);
    std::snprintf(line, sizeof(line), "sigma_r %.3g (measured noise level %.3g)", r.sigma_r,
                  r.noise_level);
    result.report.emplace_back(line);
    if (r.feature_edges > 0)
        result.report.push_back("features: no normal filtered across " +
                                count_text(r.feature_edges, "sharp edge", "sharp edges") + " (" +
                                count_text(r.feature_vertices, "vertex", "vertices") +
                                " on them or tagged corners)");
    if (r.held_vertices > 0)
        result.report.push_back(count_text(r.held_vertices, "vertex", "vertices") +
                                " held back towards the last state without folds (the last "
                                "vertex iteration folded faces there)");
    if (r.inverted_left_faces > 0)
        result.report.push_back(
            count_text(r.inverted_left_faces, "face", "faces") +
            " turned over by the noise still on the far side of the filtered normal");
    if (r.degenerate_faces > 0)
        result.report.push_back(
            count_text(r.degenerate_faces, "degenerate face", "degenerate faces") +
            " (no normal) took no part");
    std::snprintf(line, sizeof(line),
                  "face normals turned by %.3g degrees on average, %.3g at most",
                  r.mean_normal_change_degrees, r.max_normal_change_degrees);
    result.report.emplace_back(line);
    std::snprintf(line, sizeof(line),
                  "moved %zu of %zu vertices, the farthest by %.6g (mean edge %.6g)",
                  r.moved_vertices, mesh.n_vertices(), r.max_displacement, r.mean_edge_length);
    result.report.emplace_back(line);
}

OperationResult run_denoise(const DenoiseOptions& options, const HalfedgeMesh& mesh,
                            Progress& progress, const RunSettings& settings) {
    DenoiseOptions o = options;
    o.region = settings.region;
    OperationResult result;
    result.label = "Denoise";
    const bool consume = settings.consumable == &mesh;
    OperationStep step{consume ? std::move(*settings.consumable) : mesh,
                       MorphCorrespondence{MorphCorrespondence::Kind::SameVertices, {}}};
    const auto t0 = std::chrono::steady_clock::now();
    const DenoiseReport report = denoise(step.mesh, o, progress);
    result.ms = ms_since(t0);
    add_report_lines(report, step.mesh, result);  // positions only: the input's counts
    if (report.stopped_early) {
        result.stopped_early = true;
        result.stop_reason = report.stop_reason;
        result.report.push_back("stopped early: " + report.stop_reason);
        result.changed = report.vertex_iterations_done > 0;
    }
    result.steps.push_back(std::move(step));
    result.values = {{"normal_iterations_done", double(report.normal_iterations_done)},
                     {"vertex_iterations_done", double(report.vertex_iterations_done)},
                     {"filtered_faces", double(report.filtered_faces)},
                     {"degenerate_faces", double(report.degenerate_faces)},
                     {"inverted_faces", double(report.inverted_faces)},
                     {"side_corrected_faces", double(report.side_corrected_faces)},
                     {"inverted_left_faces", double(report.inverted_left_faces)},
                     {"folded_faces", double(report.folded_faces)},
                     {"held_vertices", double(report.held_vertices)},
                     {"feature_edges", double(report.feature_edges)},
                     {"feature_vertices", double(report.feature_vertices)},
                     {"mean_normal_change_degrees", report.mean_normal_change_degrees},
                     {"max_normal_change_degrees", report.max_normal_change_degrees},
                     {"max_displacement", report.max_displacement},
                     {"moved_vertices", double(report.moved_vertices)},
                     {"mean_edge_length", report.mean_edge_length},
                     {"noise_level", report.noise_level},
                     {"sigma_r", report.sigma_r}};
    result.typed_report = report;
    return result;
}

}  // namespace

std::unique_ptr<OperationDef> denoise_operation() {
    OperationDecl<DenoiseOptions> d(
        "denoise", "Denoise",
        "Removes noise and keeps sharp edges: filters the face normals (bilateral: Zheng, Fu, "
        "Au, Tai 2011; guided: Zhang, Deng, Zhang, Bouaziz, Liu 2015), then moves the vertices "
        "so that the faces follow them (Sun et al. 2007). A run whose vertex update leaves "
        "folded faces goes back to its last vertex iteration without any and says how many "
        "faces folded.");
    d.choice("method", &DenoiseOptions::method, EnumTableView(kDenoiseMethods),
             "bilateral normal filter, or guided (the guidance normal from the most consistent "
             "patch around each face: keeps edges under stronger noise)");
    d.integer("normal-iterations", &DenoiseOptions::normal_iterations, 0, kMaxDenoiseIterations,
              "normal filtering passes")
        .slider(0, 100);
    d.integer("vertex-iterations", &DenoiseOptions::vertex_iterations, 0, kMaxDenoiseIterations,
              "vertex update passes")
        .slider(0, 100);
    d.number("sigma-s", &DenoiseOptions::sigma_s, 0, kMaxDenoiseSigmaS,
             "the spatial Gaussian's standard deviation", " (multiples of the mean edge length)")
        .above_min()
        .label("sigma s (x mean edge)")
        .slider(0.1, 5, true);
    d.switchable("sigma-r", &DenoiseOptions::fixed_sigma_r, &DenoiseOptions::sigma_r, 0,
                 kMaxDenoiseSigmaR, "auto",
                 "the range Gaussian's standard deviation on the normal difference (smaller "
                 "keeps more edges, larger smooths more), or auto: " +
                     number_text(kDenoiseSigmaRPerNoise) +
                     " x the measured noise (the median normal difference across the edges), "
                     "within [" +
                     number_text(kDenoiseAutoSigmaRMin) + ", " +
                     number_text(kDenoiseAutoSigmaRMax) + "]")
        .above_min()
        .label("sigma r (off: auto)")
        .slider(0.05, 2, true);
    d.choice("features", &DenoiseOptions::features, EnumTableView(kFeatureSources),
             "sharp edges and corners honoured (no normal filtered across a sharp edge): those "
             "stored in the mesh, none, or auto (detected at --feature-angle first)")
        .hide_default();
    d.number("feature-angle", &DenoiseOptions::feature_angle, 0, 180,
             "with --features auto: the dihedral angle of a sharp edge", " (degrees)")
        .above_min()
        .slider(1, 90)
        .only_if([](const DenoiseOptions& o) -> const char* {
            return o.features == FeatureSource::Auto ? nullptr
                                                     : "applies only with --features auto";
        });
    d.run(run_denoise)
        .may_stop_early()
        .acts_on_region(
            "faces without a selected vertex keep their normals; each vertex moves by its "
            "weight times its update");
    return d.build();
}

}  // namespace trilab
