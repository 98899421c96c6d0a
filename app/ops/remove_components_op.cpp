// The "remove-components" operation: drops the connected components below a face count or a
// fraction of the bounding-box diagonal, and the isolated vertices, keeping the largest
// component always (core/algorithms/components.h).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <utility>

#include "app/ops/operation_decl.h"
#include "app/ops/operation_entries.h"
#include "core/algorithms/components.h"
#include "core/number_text.h"

namespace trilab {
namespace {

/// The morph: the kept vertices stay where they are, each removed component shrinks into the
/// centre of its bounding box (isolated vertices stay: they are not drawn).
MorphCorrespondence shrink_removed(const HalfedgeMesh& mesh, const RemoveComponentsResult& r) {
    MorphCorrespondence c{MorphCorrespondence::Kind::ToLater, {}};
    c.positions.resize(mesh.vertices_size(), Point::Zero());
    for (Vertex v : mesh.vertices()) {
        const Index k = r.labels.of_vertex[v.idx()];
        const bool goes = k != kInvalidIndex && r.removed[k];
        c.positions[v.idx()] = goes ? r.labels.components[k].bbox.center() : mesh.position(v);
    }
    return c;
}

std::vector<std::string> report_lines(const RemoveComponentsReport& r, const HalfedgeMesh& mesh) {
    std::vector<std::string> lines;
    const std::size_t removed = r.components_before - r.components_after;
    lines.push_back(
        "removed " + std::to_string(removed) + " of " +
        count_text(r.components_before, "component", "components") + " (" +
        count_text(r.faces_removed, "face", "faces") + "), " +
        count_text(r.isolated_vertices_removed, "isolated vertex", "isolated vertices") + "; " +
        count_text(r.vertices_removed, "vertex", "vertices") + " removed in all");
    if (r.components_before > 0)
        lines.push_back("kept " + count_text(r.components_after, "component", "components") +
                        "; the largest has " + count_text(r.largest_faces, "face", "faces"));
    if (r.min_diagonal > 0)
        lines.push_back("size threshold: a bounding-box diagonal of " +
                        number_text(r.min_diagonal) + " (the mesh's is " +
                        number_text(r.mesh_diagonal) + ")");
    if (r.largest_kept_anyway)
        lines.emplace_back(
            "the largest component is below the thresholds too: kept anyway (the largest is "
            "never removed)");
    if (mesh.n_faces() == 0)
        lines.emplace_back(
            "no faces: the mesh is unchanged (removing its vertices would leave "
            "nothing)");
    else if (r.faces_removed == 0 && r.isolated_vertices_removed == 0)
        lines.emplace_back("nothing to remove: the mesh is unchanged");
    return lines;
}

OperationResult run_remove_components(const RemoveComponentsOptions& o, const HalfedgeMesh& mesh,
                                      Progress& progress, const RunSettings& settings) {
    progress.check_cancelled();
    progress.report(0, "removing small components");
    OperationResult result;
    result.label = "Remove small components";
    const auto t0 = std::chrono::steady_clock::now();
    RemoveComponentsResult removal = remove_small_components(mesh, o);
    result.ms = ms_since(t0);
    progress.report(1, "removing small components");
    const RemoveComponentsReport& r = removal.report;
    result.changed = r.vertices_removed > 0;
    OperationStep step;
    if (!result.changed)
        step.correspondence.kind = MorphCorrespondence::Kind::SameVertices;
    else if (settings.morph)
        step.correspondence = shrink_removed(mesh, removal);
    else
        step.correspondence.kind = MorphCorrespondence::Kind::ToLater;  // no morph asked for
    step.mesh = std::move(removal.mesh);
    result.steps.push_back(std::move(step));
    result.report = report_lines(r, mesh);
    result.values = {{"components_before", double(r.components_before)},
                     {"components_after", double(r.components_after)},
                     {"components_removed", double(r.components_before - r.components_after)},
                     {"faces_removed", double(r.faces_removed)},
                     {"vertices_removed", double(r.vertices_removed)},
                     {"isolated_vertices_removed", double(r.isolated_vertices_removed)},
                     {"largest_faces", double(r.largest_faces)},
                     {"largest_kept_anyway", r.largest_kept_anyway ? 1.0 : 0.0},
                     {"mesh_diagonal", r.mesh_diagonal},
                     {"min_diagonal", o.min_diameter ? r.min_diagonal : std::nan("")}};
    return result;
}

}  // namespace

std::unique_ptr<OperationDef> remove_components_operation() {
    OperationDecl<RemoveComponentsOptions> d(
        "remove-components", "Remove small components",
        "Removes the connected components (faces joined through edges) with fewer faces than "
        "--min-faces or a bounding-box diagonal below --min-diameter times the whole mesh's, "
        "and the isolated vertices: the loose pieces a scan leaves around the object. Give "
        "one or both; a component failing either goes. The largest component is always kept.");
    d.integer("min-faces", &RemoveComponentsOptions::min_faces, 0,
              double(std::numeric_limits<std::uint32_t>::max()),
              "remove components with fewer faces")
        .slider(1, 10000, true)
        .default_note("not set");
    d.number("min-diameter", &RemoveComponentsOptions::min_diameter, 0, 1,
             "remove components whose bounding-box diagonal is below this fraction of the "
             "mesh's",
             " (fraction of the bounding-box diagonal)")
        .slider(0.001, 1, true)
        .default_note("not set");
    d.check([](const RemoveComponentsOptions& o, const auto&) {
        if (!o.min_faces && !o.min_diameter)
            throw InvalidArgument(
                "remove-components: give --min-faces N and/or --min-diameter F (neither is "
                "set, so nothing would be removed)");
    });
    d.run(run_remove_components);
    return d.build();
}

}  // namespace trilab
