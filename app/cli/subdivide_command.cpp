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

#include "app/cli/json_writer.h"
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

struct SubdivideArgs {
    std::string op_text = "subdivide";
    std::vector<std::string> files;
    bool json = false, help = false;
    WriteOptions write;
};

SubdivideArgs parse_args(const std::vector<std::string>& args) {
    SubdivideArgs a;
    for (std::size_t i = 0; i < args.size(); ++i) {
        const std::string& s = args[i];
        if (s == "--help" || s == "-h") {
            a.help = true;
        } else if (s == "--json") {
            a.json = true;
        } else if (s == "--ascii") {
            a.write.ascii = true;
        } else if (s == "--big-endian") {
            a.write.big_endian = true;
        } else if (s.rfind("--", 0) == 0) {
            // An operation option: it and its value go to the operation, which checks both.
            a.op_text += " " + s;
            if (s.find('=') == std::string::npos && i + 1 < args.size())
                a.op_text += " " + args[++i];
        } else {
            a.files.push_back(s);
        }
    }
    return a;
}

}  // namespace

int run_subdivide_command(const std::vector<std::string>& args) {
    const SubdivideArgs a = parse_args(args);
    if (a.help) {
        std::fputs(kSubdivideUsage, stdout);
        return 0;
    }
    const Operation op = parse_operation(a.op_text);  // bad options fail before any file
    if (a.files.size() != 2)
        throw InvalidArgument("expected IN and OUT files (see `trilab-cli subdivide --help`)");

    const LoadedMesh loaded = read_mesh(a.files[0]);  // not timed
    NullProgress progress;
    const OperationResult result = run_operation(op, loaded.mesh, progress);
    const HalfedgeMesh& out = result.steps.back().mesh;
    write_mesh(out, a.files[1], a.write);  // not timed

    if (a.json) {
        JsonObject j;
        j.add("input", a.files[0])
            .add("output", a.files[1])
            .add("operation", op.name)
            .add("parameters", result.parameters);
        for (const auto& [key, value] : result.values) {
            if (key == "scheme")  // the registry gives its index; JSON gets the name
                j.add(key, scheme_name(static_cast<SubdivisionScheme>(int(value))));
            else if (key == "vertices" || key == "faces" || key == "iterations")
                j.add(key, static_cast<std::size_t>(value));
            else
                j.add(key, value);
        }
        std::vector<double> level_vertices, level_faces;
        for (const OperationStep& step : result.steps) {
            level_vertices.push_back(double(step.mesh.n_vertices()));
            level_faces.push_back(double(step.mesh.n_faces()));
        }
        JsonObject levels;
        levels.add("vertices", level_vertices).add("faces", level_faces);
        j.add("levels", levels).add("report", result.report).add("ms", result.ms);
        std::cout << j.str() << "\n";
    } else {
        std::printf("wrote %s: %s %s (%.1f ms)\n", a.files[1].c_str(), result.label.c_str(),
                    result.parameters.c_str(), result.ms);
        for (const std::string& line : result.report) std::printf("  %s\n", line.c_str());
    }
    return 0;
}

}  // namespace trilab::cli
