// The "remesh" operation: isotropic remeshing to a target edge length
// (core/algorithms/remesh.h).
#include <chrono>
#include <cstdio>
#include <string>
#include <utility>

#include "app/ops/operation_decl.h"
#include "app/ops/operation_entries.h"
#include "core/algorithms/remesh.h"
#include "core/number_text.h"

namespace trilab {
namespace {

OperationResult run_remesh(const RemeshOptions& options, const HalfedgeMesh& mesh,
                           Progress& progress, const RunSettings& settings) {
    RemeshOptions o = options;
    o.region = settings.region;
    progress.check_cancelled();
    OperationResult result;
    result.label = "Remesh";
    // Says the size before it runs (and refuses what would not fit, changing nothing).
    const RemeshReport plan = remesh_plan(mesh, o);
    char line[240];
    std::snprintf(line, sizeof(line),
                  "target edge length %.6g (mean edge length %.6g): about %zu faces from %zu",
                  plan.target_length, plan.input_mean_edge, plan.predicted_faces, plan.input_faces);
    result.report.emplace_back(line);
    const bool consume = settings.consumable == &mesh;
    OperationStep step{consume ? std::move(*settings.consumable) : mesh, MorphCorrespondence{}};
    const auto t0 = std::chrono::steady_clock::now();
    const RemeshReport r = remesh(step.mesh, o, progress);
    result.ms = ms_since(t0);
    // New connectivity: the morph starts from the result itself (nothing moves).
    step.correspondence.kind = MorphCorrespondence::Kind::FromEarlier;
    step.correspondence.positions = step.mesh.positions();
    std::snprintf(line, sizeof(line),
                  "%d iterations: %zu splits, %zu collapses, %zu flips (%zu for small angles)",
                  r.iterations_done, r.splits, r.collapses, r.flips, r.angle_flips);
    result.report.emplace_back(line);
    result.report.push_back(count_text(r.input_faces, "face", "faces") + " -> " +
                            count_text(r.output_faces, "face", "faces") + ", " +
                            count_text(r.output_vertices, "vertex", "vertices"));
    if (r.locked_vertices > 0)
        result.report.push_back(count_text(r.locked_vertices, "vertex", "vertices") +
                                " kept as they are (outside the region, on a texture seam, or "
                                "on a sharp edge or corner: " +
                                std::to_string(r.feature_vertices) + ")");
    result.steps.push_back(std::move(step));
    result.values = {{"target_length", r.target_length},
                     {"input_mean_edge", r.input_mean_edge},
                     {"input_faces", double(r.input_faces)},
                     {"predicted_faces", double(r.predicted_faces)},
                     {"faces", double(r.output_faces)},
                     {"vertices", double(r.output_vertices)},
                     {"iterations_done", double(r.iterations_done)},
                     {"splits", double(r.splits)},
                     {"collapses", double(r.collapses)},
                     {"flips", double(r.flips)},
                     {"angle_flips", double(r.angle_flips)},
                     {"locked_vertices", double(r.locked_vertices)},
                     {"feature_vertices", double(r.feature_vertices)}};
    result.typed_report = r;
    return result;
}

}  // namespace

std::unique_ptr<OperationDef> remesh_operation() {
    OperationDecl<RemeshOptions> d(
        "remesh", "Remesh",
        "Isotropic remeshing (Botsch, Kobbelt 2004): splits, collapses and flips edges towards "
        "one target length and valence 6, relaxes the vertices tangentially and projects them "
        "back onto the input surface. Boundaries and texture seams are kept; the face count is "
        "estimated first and a run that would not fit in memory is refused.");
    d.number("length", &RemeshOptions::length, 0, 1e300, "target edge length", " (mesh units)")
        .above_min()
        .default_note("none (--relative)");
    d.number("relative", &RemeshOptions::relative, 0, 1e6,
             "target edge length as a multiple of the mean edge length")
        .above_min()
        .slider(0.1, 10, true)
        .only_if([](const RemeshOptions& o) -> const char* {
            return o.length ? "does not apply with --length (give one or the other)" : nullptr;
        });
    d.number("adaptive", &RemeshOptions::adaptive, 0, 0.5,
             "adaptive sizing (Dunyach et al. 2013): the chord error allowed, as a fraction of "
             "the length; edges shrink where the surface curves, down to a tenth (0: uniform)")
        .hide_default()
        .slider(0, 0.2);
    d.integer("iterations", &RemeshOptions::iterations, 1, kMaxRemeshIterations,
              "split-collapse-flip-relax rounds")
        .slider(1, 20);
    d.choice("features", &RemeshOptions::features, EnumTableView(kFeatureSources),
             "sharp edges and corners kept as they are, with the faces around them: those "
             "stored in the mesh, none, or auto (detected at --feature-angle first)")
        .hide_default();
    d.number("feature-angle", &RemeshOptions::feature_angle, 0, 180,
             "with --features auto: the dihedral angle of a sharp edge", " (degrees)")
        .above_min()
        .slider(1, 90)
        .only_if([](const RemeshOptions& o) -> const char* {
            return o.features == FeatureSource::Auto ? nullptr
                                                     : "applies only with --features auto";
        });
    d.run(run_remesh)
        .acts_on_region(
            "only faces with three corners of positive weight change, with a conforming border; "
            "the relaxation is scaled by each vertex's weight");
    return d.build();
}

}  // namespace trilab
