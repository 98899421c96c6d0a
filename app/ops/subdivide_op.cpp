// The "subdivide" operation: Loop, Sqrt3, Butterfly, Modified Butterfly (core/subdivision.h).
#include <chrono>
#include <cstdio>
#include <limits>
#include <string>
#include <utility>

#include "app/ops/operation_entries.h"
#include "app/ops/operation_entry.h"
#include "core/subdivision.h"

namespace trilab {
namespace {

constexpr const char* kSubdivideUsage =
    "--scheme loop|sqrt3|butterfly|modified-butterfly (default loop), "
    "--iterations N (1 to 10, default 1)";

SubdivisionOptions parse_subdivide(OptionReader& r) {
    SubdivisionOptions o;
    while (r.next()) {
        if (r.is("--scheme"))
            o.scheme = parse_scheme(r.choice({"loop", "sqrt3", "butterfly", "modified-butterfly"}));
        else if (r.is("--iterations"))
            o.iterations = int(r.whole_number(1, 10));
        else
            r.unknown();
    }
    return o;
}

OperationResult run_subdivide(const SubdivisionOptions& o, const HalfedgeMesh& mesh,
                              Progress& progress) {
    progress.check_cancelled();
    OperationResult result;
    result.label = "Subdivide";
    result.parameters = std::string("--scheme ") + scheme_name(o.scheme) + " --iterations " +
                        std::to_string(o.iterations);
    SubdivisionResult sub;
    if (mesh.has_garbage()) {  // subdivide() wants a compact mesh: compact a copy
        HalfedgeMesh compact = mesh;
        compact.garbage_collection();
        sub = subdivide(compact, o, progress);
    } else {
        sub = subdivide(mesh, o, progress);
    }
    result.ms = sub.ms;
    char line[160];
    for (std::size_t i = 0; i < sub.levels.size(); ++i) {
        const HalfedgeMesh& m = sub.levels[i].mesh;
        std::snprintf(line, sizeof(line), "level %zu: %zu vertices, %zu faces", i + 1,
                      m.n_vertices(), m.n_faces());
        result.report.emplace_back(line);
    }
    std::snprintf(line, sizeof(line), "%s, %d iteration%s: %zu -> %zu faces in %.1f ms",
                  scheme_name(o.scheme), o.iterations, o.iterations == 1 ? "" : "s", mesh.n_faces(),
                  sub.levels.empty() ? 0 : sub.levels.back().mesh.n_faces(), sub.ms);
    result.report.emplace_back(line);
    for (SubdivisionLevel& level : sub.levels)
        result.steps.push_back(
            OperationStep{std::move(level.mesh), std::move(level.correspondence)});
    const HalfedgeMesh& last = result.steps.back().mesh;
    // "scheme" as a number: its SubdivisionScheme index (0 loop, 1 sqrt3, 2 butterfly,
    // 3 modified-butterfly); the parameters text carries the name.
    result.values = {{"scheme", double(int(o.scheme))},
                     {"iterations", double(o.iterations)},
                     {"vertices", double(last.n_vertices())},
                     {"faces", double(last.n_faces())}};
    return result;
}

}  // namespace

OperationEntry subdivide_operation() {
    return make_entry<SubdivisionOptions>("subdivide", kSubdivideUsage, parse_subdivide,
                                          run_subdivide);
}

}  // namespace trilab
