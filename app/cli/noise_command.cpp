// `trilab-cli noise`: reads a mesh, runs the "noise" operation of the registry
// (run_operation(parse_operation("noise ..."))), and writes the result. Method: the command's
// own flags (--json, --ascii, --big-endian, --help) are taken out and every other "--option"
// goes, with its value, into the operation text, so the CLI accepts exactly what the viewer
// and `record --op` accept. Guarantees: the options are checked before any file is read;
// the output is written atomically (core's writers) only when everything succeeded; the same
// seed gives byte-identical files.
#include "app/cli/noise_command.h"

#include <cstdio>
#include <iostream>

#include "app/cli/json_writer.h"
#include "app/ops/operation.h"
#include "core/errors.h"
#include "core/io/mesh_io.h"
#include "core/progress.h"

namespace trilab::cli {
namespace {

constexpr const char* kNoiseUsage =
    R"(usage: trilab-cli noise [--amount PCT] [--seed S] IN OUT [--json] [--ascii] [--big-endian]

Moves every vertex of IN along its area-weighted normal by a uniform random amount in
[-a, a], a = PCT percent of the mean edge length, and writes OUT (format by extension).
The same seed gives the same result on every platform. Isolated vertices do not move.

options:
  --amount PCT          percent of the mean edge length, 0 to 1000 (default 1)
  --seed S              whole number, 0 to 4294967295 (default 1)
  --ascii, --big-endian how to write .ply and .stl (as for `trilab-cli convert`)
  --json                print one JSON object: "ms" (the operation itself, file reading
                        and writing excluded), "amount", "seed", "vertices",
                        "mean_edge_length", "max_displacement", ...
)";

struct NoiseArgs {
    std::string op_text = "noise";
    std::vector<std::string> files;
    bool json = false, help = false;
    WriteOptions write;
};

NoiseArgs parse_args(const std::vector<std::string>& args) {
    NoiseArgs a;
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

int run_noise_command(const std::vector<std::string>& args) {
    const NoiseArgs a = parse_args(args);
    if (a.help) {
        std::fputs(kNoiseUsage, stdout);
        return 0;
    }
    const Operation op = parse_operation(a.op_text);  // bad options fail before any file
    if (a.files.size() != 2)
        throw InvalidArgument("expected IN and OUT files (see `trilab-cli noise --help`)");

    LoadedMesh loaded = read_mesh(a.files[0]);  // not timed
    NullProgress progress;
    const OperationResult result = run_operation(op, loaded.mesh, progress);
    const HalfedgeMesh& out = result.steps.back().mesh;
    write_mesh(out, a.files[1], a.write);  // not timed

    if (a.json) {
        JsonObject j;
        j.add("input", a.files[0])
            .add("output", a.files[1])
            .add("operation", op.name)
            .add("parameters", result.parameters)
            .add("vertices", out.n_vertices())
            .add("faces", out.n_faces());
        for (const auto& [key, value] : result.values) j.add(key, value);
        j.add("report", result.report).add("ms", result.ms);
        std::cout << j.str() << "\n";
    } else {
        std::printf("wrote %s: %s %s (%.1f ms)\n", a.files[1].c_str(), result.label.c_str(),
                    result.parameters.c_str(), result.ms);
        for (const std::string& line : result.report) std::printf("  %s\n", line.c_str());
    }
    return 0;
}

}  // namespace trilab::cli
