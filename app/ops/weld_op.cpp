// The "weld" operation: joins coincident vertices where the mesh stays manifold
// (core/algorithms/weld.h).
#include <chrono>
#include <cstdio>
#include <string>
#include <utility>

#include "app/ops/operation_decl.h"
#include "app/ops/operation_entries.h"
#include "core/algorithms/coincident.h"
#include "core/algorithms/weld.h"
#include "core/number_text.h"

namespace trilab {
namespace {

OperationResult run_weld(const WeldOptions& options, const HalfedgeMesh& mesh, Progress& progress,
                         const RunSettings& settings) {
    WeldOptions o = options;
    o.region = settings.region;
    progress.check_cancelled();
    progress.report(0, "welding coincident vertices");
    OperationResult result;
    result.label = "Weld coincident vertices";
    const auto t0 = std::chrono::steady_clock::now();
    WeldResult weld = weld_coincident_vertices(mesh, o);
    result.ms = ms_since(t0);
    progress.report(1, "welding coincident vertices");
    const WeldReport& r = weld.report;
    // Every vertex starts where the first of the vertices it joins was.
    OperationStep step;
    step.correspondence.kind = MorphCorrespondence::Kind::FromEarlier;
    step.correspondence.positions.assign(weld.mesh.vertices_size(), Point::Zero());
    std::vector<std::uint8_t> seen(weld.mesh.vertices_size(), 0);
    for (Vertex v : mesh.vertices()) {
        const Index w = weld.vertex_map[v.idx()];
        if (!seen[w]) step.correspondence.positions[w] = mesh.position(v);
        seen[w] = 1;
    }
    const BoundaryPairing before = pair_boundary_edges(mesh);
    step.mesh = std::move(weld.mesh);
    const BoundaryPairing after = pair_boundary_edges(step.mesh);
    char line[200];
    result.report.push_back(
        count_text(r.coincident_vertices, "coincident vertex", "coincident vertices") + " in " +
        count_text(r.groups, "group", "groups") + "; " +
        count_text(r.vertices_joined, "vertex", "vertices") + " joined, " +
        count_text(r.edges_glued, "boundary edge pair", "boundary edge pairs") + " glued");
    std::snprintf(line, sizeof(line), "boundary edges %zu -> %zu (%zu -> %zu on seams)",
                  before.boundary_edges, after.boundary_edges, before.paired_edges,
                  after.paired_edges);
    result.report.emplace_back(line);
    for (const std::string& note : r.notes) result.report.push_back("note: " + note);
    if (r.vertices_joined == 0)
        result.report.emplace_back("nothing to weld: the mesh is unchanged");
    result.steps.push_back(std::move(step));
    result.values = {{"tolerance", o.tolerance},
                     {"groups", double(r.groups)},
                     {"coincident_vertices", double(r.coincident_vertices)},
                     {"vertices_joined", double(r.vertices_joined)},
                     {"edges_glued", double(r.edges_glued)},
                     {"vertices_left_apart", double(r.vertices_left_apart)},
                     {"edges_left_open", double(r.edges_left_open)},
                     {"boundary_edges_before", double(before.boundary_edges)},
                     {"boundary_edges_after", double(after.boundary_edges)}};
    result.typed_report = r;
    return result;
}

}  // namespace

std::unique_ptr<OperationDef> weld_operation() {
    OperationDecl<WeldOptions> d(
        "weld", "Weld coincident vertices",
        "Joins vertices at the same position (within --tolerance) where the mesh stays "
        "manifold: pairs of coincident boundary edges (the seams of a patch model, the copies of "
        "a split non-manifold vertex) become interior edges. What would be non-manifold (surfaces "
        "touching at a point, three sheets at an edge, faces running the same way) is left apart "
        "and explained.");
    d.number("tolerance", &WeldOptions::tolerance, 0, 1e12,
             "distance below which vertices coincide; 0: exactly the same position")
        .slider(0, 0.01)
        .default_note("0 (exact)");
    d.run(run_weld).acts_on_region("only vertices of positive weight are welded");
    return d.build();
}

}  // namespace trilab
