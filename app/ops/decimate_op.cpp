// The "decimate" operation: edge collapse with quadric or roundness costs and binary
// constraints (core/algorithms/decimation.h). One step per iteration, each with its geomorph.
#include <chrono>
#include <cstdio>
#include <optional>
#include <string>
#include <utility>

#include "app/ops/decimate_op.h"
#include "app/ops/operation_decl.h"
#include "app/ops/operation_entries.h"
#include "core/algorithms/decimation.h"
#include "core/number_text.h"

namespace trilab {
namespace {

OperationResult run_decimate(const DecimateOptions& d_options, const HalfedgeMesh& mesh,
                             Progress& progress, const RunSettings& settings) {
    const DecimationOptions& o = d_options.core;
    DecimationOptions options = decimation_options(d_options);
    options.record_progressive = false;  // the steps carry the geomorphs
    options.levels = settings.keep_steps ? DecimationLevels::All : DecimationLevels::Last;
    options.record_geomorph = settings.morph;
    options.region = settings.region;
    DecimationResult d = decimate(mesh, options, progress);
    const DecimationReport& rep = d.report;
    OperationResult result;
    result.ms = rep.ms;
    result.label = "Decimate";
    char line[200];
    for (std::size_t i = 0; i < d.levels.size(); ++i) {
        const HalfedgeMesh& m = d.levels[i].mesh;
        result.report.push_back("iteration " + std::to_string(i + 1) + ": " +
                                count_text(m.n_vertices(), "vertex", "vertices") + " (aimed at " +
                                std::to_string(d.levels[i].target_vertices) + "), " +
                                count_text(m.n_faces(), "face", "faces"));
    }
    std::snprintf(line, sizeof(line), " in %.1f ms", rep.ms);
    result.report.push_back(std::string(decimation_cost_name(o.cost)) + ": " +
                            std::to_string(rep.input_vertices) + " -> " +
                            count_text(rep.output_vertices, "vertex", "vertices") + ", " +
                            count_text(rep.collapses, "collapse", "collapses") + line);
    std::snprintf(line, sizeof(line),
                  "refused: link condition %zu, normal flip %zu, roundness %zu, independent set "
                  "%zu, max error %zu, texture seam %zu",
                  rep.refused_topology, rep.refused_normal_flip, rep.refused_roundness,
                  rep.refused_independent_set, rep.refused_max_error, rep.refused_texture_seam);
    result.report.emplace_back(line);
    if (rep.coincident_vertices > 0) {
        result.report.push_back(
            count_text(rep.coincident_vertices, "vertex", "vertices") +
            " with a coincident copy (seams, split non-manifold vertices): collapsed only "
            "together with it");
    }
    if (rep.stop != DecimationStop::Done) result.report.push_back(rep.stop_message);
    for (DecimationLevel& level : d.levels)
        result.steps.push_back(
            OperationStep{std::move(level.mesh), std::move(level.correspondence)});
    if (result.steps.empty())  // nothing could be collapsed: the mesh as it was
        result.steps.push_back(OperationStep{mesh, MorphCorrespondence{}});
    const HalfedgeMesh& last = result.steps.back().mesh;
    result.values = {{"vertices", double(last.n_vertices())},
                     {"faces", double(last.n_faces())},
                     {"input_vertices", double(rep.input_vertices)},
                     {"surface_vertices", double(rep.output_vertices)},
                     {"isolated_vertices", double(rep.isolated_vertices)},
                     {"iterations_done", double(rep.iterations_done)},
                     {"collapses", double(rep.collapses)},
                     {"refused_link_condition", double(rep.refused_topology)},
                     {"refused_normal_flip", double(rep.refused_normal_flip)},
                     {"refused_roundness", double(rep.refused_roundness)},
                     {"refused_independent_set", double(rep.refused_independent_set)},
                     {"refused_max_error", double(rep.refused_max_error)},
                     {"refused_texture_seam", double(rep.refused_texture_seam)},
                     {"coincident_vertices", double(rep.coincident_vertices)}};
    result.texts = {{"cost", decimation_cost_name(o.cost)},
                    {"stop_reason", decimation_stop_name(rep.stop)},
                    {"stop_message", rep.stop_message}};
    result.typed_report = rep;
    return result;
}

}  // namespace

DecimationOptions decimation_options(const DecimateOptions& o) {
    DecimationOptions core = o.core;
    core.target_vertices = o.target_vertices.value_or(0);
    return core;
}

DecimationOptions decimation_options(const Operation& op) {
    return decimation_options(options_of<DecimateOptions>(op));
}

std::unique_ptr<OperationDef> decimate_operation() {
    OperationDecl<DecimateOptions> d(
        "decimate", "Decimate",
        "Collapses edges in the order of a cost (Garland, Heckbert 1997 quadrics, or normalized "
        "roundness), vetoed by binary constraints; each iteration is a step with its geomorph. "
        "The result is a valid manifold with the input's boundary loops and genus.");
    const auto without_target = [](const DecimateOptions& o) -> const char* {
        return o.target_vertices ? "does not apply with --target-vertices (give one or the other)"
                                 : nullptr;
    };
    d.choice(
        "cost", [](DecimateOptions & o) -> auto& { return o.core.cost; },
        EnumTableView(kDecimationCosts), "the collapse order");
    d.number(
         "percent", [](DecimateOptions & o) -> auto& { return o.core.percent; }, 0, 100,
         "vertices removed per iteration, in percent")
        .above_min()
        .label("percent per iteration")
        .slider(1, 100)
        .only_if(without_target);
    d.integer(
         "iterations", [](DecimateOptions & o) -> auto& { return o.core.iterations; }, 1, 1000,
         "iterations, each a step")
        .slider(1, 20)
        .counts_steps()
        .only_if(without_target);
    d.integer("target-vertices", &DecimateOptions::target_vertices, 1, 4e9,
              "one iteration down to K vertices")
        .default_note("none (--percent and --iterations)");
    d.switchable(
         "normal-flip", [](DecimateOptions & o) -> auto& { return o.core.normal_flip; },
         [](DecimateOptions & o) -> auto& { return o.core.max_normal_angle; }, 0, 180, "off",
         "largest angle a face normal may turn", " degrees")
        .above_min()
        .label("normal flipping, max angle");
    d.switchable(
         "roundness", [](DecimateOptions & o) -> auto& { return o.core.roundness; },
         [](DecimateOptions & o) -> auto& { return o.core.min_roundness; }, 0, 1, "off",
         "smallest normalized roundness a new triangle may have")
        .above_min()
        .label("roundness, min");
    d.flag(
        "independent-set", [](DecimateOptions & o) -> auto& { return o.core.independent_set; },
        "lock the one-ring of each collapse for the rest of the iteration");
    d.number(
         "max-error", [](DecimateOptions & o) -> auto& { return o.core.max_error; }, 0, 1e300,
         "largest quadric error as a distance (0: no limit)")
        .hide_default();
    d.choice(
         "features", [](DecimateOptions & o) -> auto& { return o.core.features; },
         EnumTableView(kFeatureSources),
         "sharp edges and corners kept: those stored in the mesh, none, or auto (detected at "
         "--feature-angle first; on the command line also auto:A)")
        .hide_default();
    d.number(
         "feature-angle", [](DecimateOptions & o) -> auto& { return o.core.feature_angle; }, 0, 180,
         "with --features auto: the dihedral angle of a sharp edge", " (degrees)")
        .above_min()
        .slider(1, 90)
        .only_if([](const DecimateOptions& o) -> const char* {
            return o.core.features == FeatureSource::Auto ? nullptr
                                                          : "applies only with --features auto";
        });
    d.run(run_decimate)
        .acts_on_region(
            "only edges with both ends of positive weight collapse; --percent counts the region's "
            "vertices");
    return d.build();
}

}  // namespace trilab
