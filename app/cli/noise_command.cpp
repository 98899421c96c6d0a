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

#include "app/cli/operation_command.h"
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

}  // namespace

int run_noise_command(const std::vector<std::string>& args) {
    return run_operation_command("noise", kNoiseUsage, args);
}

}  // namespace trilab::cli
