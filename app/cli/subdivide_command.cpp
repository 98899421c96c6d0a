// `trilab-cli subdivide`: reads a mesh, runs the "subdivide" operation of the registry
// (run_operation(parse_operation("subdivide ..."))), and writes the finest level. Method: as
// `trilab-cli noise`, the command's own flags (--json, --ascii, --big-endian, --help) are
// taken out and every other "--option" goes, with its value, into the operation text, so the
// CLI accepts exactly what the viewer and `record --op` accept. Guarantees: the options are
// checked before any file is read; the output is written atomically (core's writers) only
// when everything succeeded.
#include "app/cli/subdivide_command.h"

#include <cstdio>
#include <iostream>

#include "app/cli/operation_command.h"
#include "app/ops/operation.h"
#include "core/errors.h"
#include "core/io/mesh_io.h"
#include "core/progress.h"
#include "core/subdivision.h"

namespace trilab::cli {
namespace {

constexpr const char* kSubdivideUsage =
    R"(usage: trilab-cli subdivide [--scheme S] [--iterations N] IN OUT [--json] [--ascii]
                              [--big-endian]

Subdivides the triangle mesh IN N times with scheme S and writes the finest level to OUT
(format by extension). Boundaries stay boundaries; texture coordinates are interpolated.

options:
  --scheme S            loop (approximating, 1-to-4; default), sqrt3 (approximating,
                        Kobbelt), butterfly (interpolating, w = 1/16) or
                        modified-butterfly (interpolating, Zorin et al.)
  --iterations N        whole number, 1 to 10 (default 1)
  --ascii, --big-endian how to write .ply and .stl (as for `trilab-cli convert`)
  --json                print one JSON object: "ms" (the subdivision itself, file reading
                        and writing excluded), "scheme", "iterations", "vertices",
                        "faces", "levels" (vertices and faces per level), ...
)";

}  // namespace

int run_subdivide_command(const std::vector<std::string>& args) {
    return run_operation_command(
        "subdivide", kSubdivideUsage, args, [](JsonObject& j, const OperationResult& result) {
            for (const auto& [key, value] : result.values) {
                if (key == "scheme")  // the registry gives its index; JSON gets the name
                    j.add(key, scheme_name(static_cast<SubdivisionScheme>(int(value))));
                else if (key == "iterations")
                    j.add(key, static_cast<std::size_t>(value));
            }
            std::vector<double> level_vertices, level_faces;
            for (const OperationStep& step : result.steps) {
                level_vertices.push_back(double(step.mesh.n_vertices()));
                level_faces.push_back(double(step.mesh.n_faces()));
            }
            JsonObject levels;
            levels.add("vertices", level_vertices).add("faces", level_faces);
            j.add("levels", levels);
        });
}

}  // namespace trilab::cli
