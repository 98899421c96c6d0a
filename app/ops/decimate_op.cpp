// The "decimate" operation: edge collapse with quadric or roundness costs and binary
// constraints (core/decimation.h). One step per iteration, each with its geomorph.
#include <charconv>
#include <chrono>
#include <cstdio>
#include <string>
#include <utility>

#include "app/ops/operation_entries.h"
#include "app/ops/operation_entry.h"
#include "core/decimation.h"

namespace trilab {
namespace {

constexpr const char* kDecimateUsage =
    "--cost quadric|roundness (default quadric), --percent P (0 to 100, default 60) "
    "--iterations N (1 to 1000, default 1) or --target-vertices K, --normal-flip DEG|off "
    "(default 90), --roundness MIN (0 to 1; off by default), --independent-set, "
    "--max-error D (0: none)";

DecimationOptions parse_decimate(OptionReader& r) {
    DecimationOptions o;
    bool amount_by_percent = false;
    while (r.next()) {
        if (r.is("--cost")) {
            o.cost = parse_decimation_cost(r.choice({"quadric", "roundness"}));
        } else if (r.is("--percent")) {
            o.percent = r.number(0, 100);
            if (o.percent <= 0) throw r.bad_value("a number from 0 to 100 (above 0)", "0");
            amount_by_percent = true;
        } else if (r.is("--iterations")) {
            o.iterations = int(r.whole_number(1, 1000));
            amount_by_percent = true;
        } else if (r.is("--target-vertices")) {
            o.target_vertices = std::size_t(r.whole_number(1, 4000000000ull));
        } else if (r.is("--normal-flip")) {
            const std::string text = r.value();
            if (text == "off") {
                o.normal_flip = false;
            } else {
                double deg = 0;
                const char* end = text.data() + text.size();
                const auto [ptr, ec] = std::from_chars(text.data(), end, deg);
                if (text.empty() || ec != std::errc() || ptr != end || !(deg > 0 && deg <= 180))
                    throw r.bad_value("a number of degrees above 0 and up to 180, or off", text);
                o.max_normal_angle = deg;
                o.normal_flip = true;
            }
        } else if (r.is("--roundness")) {
            o.min_roundness = r.number(0, 1);
            if (o.min_roundness <= 0) throw r.bad_value("a number from 0 to 1 (above 0)", "0");
            o.roundness = true;
        } else if (r.is("--independent-set")) {
            o.independent_set = true;
        } else if (r.is("--max-error")) {
            o.max_error = r.number(0, 1e300);
        } else {
            r.unknown();
        }
    }
    if (amount_by_percent && o.target_vertices > 0)
        throw InvalidArgument(
            "--target-vertices: give either --target-vertices or --percent/--iterations");
    return o;
}

std::string canonical_parameters(const DecimationOptions& o) {
    std::string s = std::string("--cost ") + decimation_cost_name(o.cost);
    if (o.target_vertices > 0)
        s += " --target-vertices " + std::to_string(o.target_vertices);
    else
        s += " --percent " + OptionReader::format_number(o.percent) + " --iterations " +
             std::to_string(o.iterations);
    s += " --normal-flip " +
         (o.normal_flip ? OptionReader::format_number(o.max_normal_angle) : std::string("off"));
    if (o.roundness) s += " --roundness " + OptionReader::format_number(o.min_roundness);
    if (o.independent_set) s += " --independent-set";
    if (o.max_error > 0) s += " --max-error " + OptionReader::format_number(o.max_error);
    return s;
}

OperationResult run_decimate(const DecimationOptions& o, const HalfedgeMesh& mesh,
                             Progress& progress) {
    DecimationOptions options = o;
    options.record_progressive = false;  // the steps carry the geomorphs
    DecimationResult d = decimate(mesh, options, progress);
    const DecimationReport& rep = d.report;
    OperationResult result;
    result.ms = rep.ms;
    result.label = "Decimate";
    result.parameters = canonical_parameters(o);
    char line[200];
    for (std::size_t i = 0; i < d.levels.size(); ++i) {
        const HalfedgeMesh& m = d.levels[i].mesh;
        std::snprintf(line, sizeof(line), "iteration %zu: %zu vertices (aimed at %zu), %zu faces",
                      i + 1, m.n_vertices(), d.levels[i].target_vertices, m.n_faces());
        result.report.emplace_back(line);
    }
    std::snprintf(line, sizeof(line), "%s: %zu -> %zu vertices, %zu collapses in %.1f ms",
                  decimation_cost_name(o.cost), rep.input_vertices, rep.output_vertices,
                  rep.collapses, rep.ms);
    result.report.emplace_back(line);
    std::snprintf(line, sizeof(line),
                  "refused: link condition %zu, normal flip %zu, roundness %zu, independent set "
                  "%zu, max error %zu, texture seam %zu",
                  rep.refused_topology, rep.refused_normal_flip, rep.refused_roundness,
                  rep.refused_independent_set, rep.refused_max_error, rep.refused_texture_seam);
    result.report.emplace_back(line);
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
                     {"iterations_done", double(d.levels.size())},
                     {"collapses", double(rep.collapses)},
                     {"refused_link_condition", double(rep.refused_topology)},
                     {"refused_normal_flip", double(rep.refused_normal_flip)},
                     {"refused_roundness", double(rep.refused_roundness)},
                     {"refused_independent_set", double(rep.refused_independent_set)},
                     {"refused_max_error", double(rep.refused_max_error)},
                     {"refused_texture_seam", double(rep.refused_texture_seam)}};
    result.texts = {{"cost", decimation_cost_name(o.cost)},
                    {"stop_reason", decimation_stop_name(rep.stop)},
                    {"stop_message", rep.stop_message}};
    return result;
}

}  // namespace

OperationEntry decimate_operation() {
    return make_entry<DecimationOptions>("decimate", kDecimateUsage, parse_decimate, run_decimate);
}

}  // namespace trilab
