// The "fill-holes" operation: closes boundary loops by Liepa's triangulation, refinement and
// fairing (core/algorithms/hole_filling.h). The CLI's --loops I,J (app/cli/command_extras.cpp)
// becomes the run's region: the rims of those loops.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <utility>

#include "app/ops/operation_decl.h"
#include "app/ops/operation_entries.h"
#include "core/algorithms/hole_filling.h"
#include "core/number_text.h"

namespace trilab {
namespace {

std::string degrees_text(double degrees) {
    char text[32];
    std::snprintf(text, sizeof text, "%.1f", degrees);
    return text;
}

std::vector<std::string> report_lines(const HoleFillingReport& r) {
    std::vector<std::string> lines;
    std::string sizes;
    for (std::size_t i = 0; i < r.loop_edges.size(); ++i)
        sizes += (i ? ", " : "") + std::to_string(r.loop_edges[i]);
    lines.push_back(count_text(r.loops_found, "boundary loop", "boundary loops") +
                    (r.loops_found ? " (edges: " + sizes + ")" : std::string()) + "; " +
                    std::to_string(r.loops_chosen) + " chosen, " + std::to_string(r.loops_filled) +
                    " filled, " + std::to_string(r.refused.size()) + " refused");
    for (const RefusedLoop& f : r.refused)
        lines.push_back("refused loop " + std::to_string(f.loop) + " (" +
                        count_text(f.edges, "edge", "edges") + "): " + f.reason);
    if (r.loops_filled)
        lines.push_back("added " + count_text(r.faces_added, "face", "faces") + " and " +
                        count_text(r.vertices_added, "vertex", "vertices") +
                        "; smallest new angle " + degrees_text(r.min_new_angle_deg) + " deg (" +
                        std::to_string(r.new_angles_under_20) + " new triangles under 20 deg)");
    if (r.loops_delaunay)
        lines.push_back(count_text(r.loops_delaunay, "loop", "loops") + " longer than " +
                        std::to_string(kMaxDpLoop) +
                        " vertices triangulated over their Delaunay edges (Zou et al. 2013)");
    if (r.loops_cut)
        lines.push_back(count_text(r.loops_cut, "loop", "loops") + " longer than " +
                        std::to_string(kMaxDpLoop) + " vertices cut by chords first");
    for (const std::string& note : r.notes) lines.push_back(note);
    if (r.vertices_added) lines.emplace_back("the new vertices are the mesh's selection now");
    return lines;
}

OperationResult run_fill_holes(const HoleFillingOptions& options, const HalfedgeMesh& mesh,
                               Progress& progress, const RunSettings& settings) {
    progress.check_cancelled();
    progress.report(0, "filling holes");
    OperationResult result;
    result.label = "Fill holes";
    HoleFillingOptions o = options;
    o.region = settings.region;
    const bool consume = settings.consumable == &mesh;
    OperationStep step{consume ? std::move(*settings.consumable) : mesh,
                       MorphCorrespondence{MorphCorrespondence::Kind::FromEarlier, {}}};
    const auto t0 = std::chrono::steady_clock::now();
    const HoleFillingReport r = fill_holes(step.mesh, o);
    result.ms = ms_since(t0);
    progress.report(1, "filling holes");
    result.changed = r.loops_filled > 0;
    // The old vertices do not move; the new ones appear where they end.
    step.correspondence.positions = step.mesh.positions();
    result.steps.push_back(std::move(step));
    result.report = report_lines(r);
    result.values = {{"loops_found", double(r.loops_found)},
                     {"loops_chosen", double(r.loops_chosen)},
                     {"loops_filled", double(r.loops_filled)},
                     {"loops_refused", double(r.refused.size())},
                     {"loops_delaunay", double(r.loops_delaunay)},
                     {"loops_cut", double(r.loops_cut)},
                     {"faces_added", double(r.faces_added)},
                     {"vertices_added", double(r.vertices_added)},
                     {"min_new_angle_deg", r.min_new_angle_deg},
                     {"new_angles_under_20", double(r.new_angles_under_20)}};
    std::vector<double> edges(r.loop_edges.begin(), r.loop_edges.end());
    result.series.emplace_back("loop_edges", std::move(edges));
    result.typed_report = r;
    return result;
}

}  // namespace

std::unique_ptr<OperationDef> fill_holes_operation() {
    OperationDecl<HoleFillingOptions> d(
        "fill-holes", "Fill holes",
        "Closes boundary loops (holes) after Liepa 2003: each loop is triangulated by dynamic "
        "programming (the largest dihedral angle, then the area, minimised; over loops of more "
        "than " +
            std::to_string(kMaxDpLoop) +
            " vertices restricted to the edges of their 2-D Delaunay triangulation, Zou et "
            "al. 2013), refined to the density around it with "
            "Delaunay flips, and faired with the implicit Laplacian (C1 or C2 at the rim). "
            "Loops are numbered by their smallest vertex index; the --json report lists every "
            "loop's size and what became of it. Degenerate rims are refused with the reason. "
            "The new vertices become the mesh's selection.");
    d.integer("max-edges", &HoleFillingOptions::max_edges, 0,
              double(std::numeric_limits<std::uint32_t>::max()),
              "fill only loops with at most this many edges")
        .slider(3, 1000, true)
        .default_note("any size");
    d.number("max-diameter", &HoleFillingOptions::max_diameter, 0, 1,
             "fill only loops whose bounding-box diagonal is at most this fraction of the "
             "mesh's",
             " (fraction of the bounding-box diagonal)")
        .slider(0.001, 1, true)
        .default_note("any size");
    d.choice("fairing", &HoleFillingOptions::fairing, EnumTableView(kHoleFairings),
             "continuity at the rim: c1 (bi-Laplacian), c2 (tri-Laplacian) or none");
    d.run(run_fill_holes)
        .acts_on_region(
            "fills only the loops with a rim vertex in the region (--loops I,J is such a "
            "region)");
    return d.build();
}

}  // namespace trilab
