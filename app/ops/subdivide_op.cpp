// The "subdivide" operation: Loop, Sqrt3, Butterfly, Modified Butterfly
// (core/algorithms/subdivision.h).
#include <chrono>
#include <cstdio>
#include <limits>
#include <string>
#include <utility>

#include "app/ops/operation_decl.h"
#include "app/ops/operation_entries.h"
#include "core/algorithms/region_subdivision.h"
#include "core/algorithms/subdivision.h"
#include "core/errors.h"
#include "core/number_text.h"

namespace trilab {
namespace {

OperationResult run_subdivide(const SubdivisionOptions& options, const HalfedgeMesh& mesh,
                              Progress& progress, const RunSettings& settings) {
    SubdivisionOptions o = options;
    o.keep_levels = settings.keep_steps;  // the CLI writes the finest level only
    o.morph = settings.morph;
    progress.check_cancelled();
    OperationResult result;
    result.label = "Subdivide";
    // On a region: the selected faces with their closure (core/algorithms/region_subdivision.h).
    RegionSubdivisionReport region;
    SubdivisionResult sub = settings.region
                                ? subdivide_region(mesh, o, *settings.region, progress, region)
                                : subdivide(mesh, o, progress);  // compacts a copy if needed
    result.ms = sub.ms;
    char line[160];
    for (std::size_t i = 0; i < sub.level_counts.size(); ++i) {
        result.report.push_back("level " + std::to_string(i + 1) + ": " +
                                count_text(sub.level_counts[i][0], "vertex", "vertices") + ", " +
                                count_text(sub.level_counts[i][1], "face", "faces"));
    }
    const std::size_t faces_after = sub.levels.empty() ? 0 : sub.levels.back().mesh.n_faces();
    std::snprintf(line, sizeof(line), " in %.1f ms", sub.ms);
    result.report.push_back(std::string(scheme_name(o.scheme)) + ", " +
                            count_text(std::size_t(o.iterations), "iteration", "iterations") +
                            ": " + std::to_string(mesh.n_faces()) + " -> " +
                            count_text(faces_after, "face", "faces") + line);
    for (const std::string& note : sub.notes) result.report.push_back("note: " + note);
    if (settings.region) {
        for (std::size_t i = 0; i < region.closure.size(); ++i) {
            const RegionClosureCounts& c = region.closure[i];
            result.report.push_back(
                "region level " + std::to_string(i + 1) + ": " +
                count_text(c.selected_faces, "selected face", "selected faces") + ", " +
                std::to_string(c.red_faces) +
                (o.scheme == SubdivisionScheme::Sqrt3 ? " split 1-to-3, "
                                                      : " split 1-to-4 (red), ") +
                (o.scheme == SubdivisionScheme::Sqrt3
                     ? count_text(c.flipped_edges, "edge flipped", "edges flipped") + ", " +
                           std::to_string(c.completed_edges) +
                           " earlier closure triangles completed"
                     : std::to_string(c.green_faces) + " split 1-to-2 (green)" +
                           (c.damped_vertices > 0 ? ", " + std::to_string(c.damped_vertices) +
                                                        " edge vertices moved toward their midpoint"
                                                  : std::string())));
        }
        std::snprintf(line, sizeof(line), "minimum angle: %.3f deg before, %.3f deg after",
                      region.min_angle_in, region.min_angle_out);
        result.report.emplace_back(line);
        const RegionClosureCounts& last = region.closure.back();
        if (last.min_angle_closure < 180) {
            std::snprintf(line, sizeof(line),
                          "closure (last level): minimum angle %.3f deg, %.3f deg in the faces it "
                          "replaced; %zu faces grown into, %zu max-min-angle flips",
                          last.min_angle_closure, last.min_angle_touched, last.grown_faces,
                          last.closure_flips);
            result.report.emplace_back(line);
        }
    }
    std::vector<double> level_vertices, level_faces;
    for (const auto& counts : sub.level_counts) {
        level_vertices.push_back(double(counts[0]));
        level_faces.push_back(double(counts[1]));
    }
    result.series = {{"level_vertices", level_vertices}, {"level_faces", level_faces}};
    for (SubdivisionLevel& level : sub.levels)
        result.steps.push_back(
            OperationStep{std::move(level.mesh), std::move(level.correspondence)});
    const HalfedgeMesh& last = result.steps.back().mesh;
    result.values = {{"vertices", double(last.n_vertices())}, {"faces", double(last.n_faces())}};
    if (settings.region) {
        result.values.push_back({"min_angle_in", region.min_angle_in});
        result.values.push_back({"min_angle_out", region.min_angle_out});
        const RegionClosureCounts& c = region.closure.back();
        result.values.push_back({"selected_faces", double(c.selected_faces)});
        result.values.push_back({"red_faces", double(c.red_faces)});
        result.values.push_back({"green_faces", double(c.green_faces)});
        result.values.push_back({"min_angle_closure", c.min_angle_closure});
        result.values.push_back({"min_angle_touched", c.min_angle_touched});
        result.values.push_back({"closure_flips", double(c.closure_flips)});
        result.values.push_back({"grown_faces", double(c.grown_faces)});
        result.values.push_back({"closure_reds", double(c.closure_reds)});
        result.values.push_back({"completed_edges", double(c.completed_edges)});
        result.values.push_back({"damped_vertices", double(c.damped_vertices)});
    }
    sub.levels.clear();  // moved into the steps: the report is the counts, notes and time
    result.typed_report = std::move(sub);
    return result;
}

}  // namespace

std::unique_ptr<OperationDef> subdivide_operation() {
    OperationDecl<SubdivisionOptions> d(
        "subdivide", "Subdivide",
        "Subdivides the triangle mesh N times and keeps every level as a step (Loop 1987; Kobbelt "
        "2000; Dyn, Levin, Gregory 1990; Zorin, Schroeder, Sweldens 1996). Boundaries stay "
        "boundaries; texture coordinates are interpolated.");
    d.choice("scheme", &SubdivisionOptions::scheme, EnumTableView(kSubdivisionSchemes),
             "loop and sqrt3 approximate, the butterflies interpolate");
    d.integer("iterations", &SubdivisionOptions::iterations, 1, 10, "refinement steps")
        .slider(1, 6)
        .counts_steps();
    d.flag("global-closure", &SubdivisionOptions::global_closure,
           "on a region: grow the closure until no closure triangle is flatter than the input (on "
           "an almost regular mesh over the whole surface; by default it stays next to the "
           "selection, and repeated levels split the earlier closure 1-to-4 instead of bisecting "
           "it again)");
    d.choice(
         "features", &SubdivisionOptions::features, EnumTableView(kFeatureSources),
         "sharp edges and corners for the crease rules of every scheme: those stored in the mesh, "
         "none, or "
         "auto (detected at --feature-angle first; on the command line also auto:A)")
        .hide_default();
    d.number("feature-angle", &SubdivisionOptions::feature_angle, 0, 180,
             "with --features auto: the dihedral angle of a sharp edge", " (degrees)")
        .above_min()
        .slider(1, 90)
        .only_if([](const SubdivisionOptions& o) -> const char* {
            return o.features == SubdivisionFeatures::Auto ? nullptr
                                                           : "applies only with --features auto";
        });
    d.flag("local-closure", &SubdivisionOptions::local_closure,
           "on a region: keep the closure next to the selection (the default; accepted for "
           "recipes and sessions written before it was)");
    d.check([](const SubdivisionOptions& o, const auto&) {
        if (o.local_closure && o.global_closure)
            throw InvalidArgument("--local-closure: cannot be given with --global-closure");
    });
    d.run(run_subdivide)
        .acts_on_region(
            "only faces whose three vertices weigh > 0 are refined, with a conforming closure "
            "(red-green for the 1-to-4 schemes, Kobbelt's adaptive rule for sqrt3); vertices of "
            "weight 0 stay; --json adds min_angle_in/out, the closure's face counts, its "
            "minimum angle (min_angle_closure, 180 without a closure) and that of the faces it "
            "replaced (min_angle_touched), and its flips (last iteration)");
    return d.build();
}

}  // namespace trilab
