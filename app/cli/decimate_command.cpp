// `trilab-cli decimate`: reads a mesh, runs the "decimate" operation of the registry and
// writes the last iteration (see app/cli/operation_command.h for the shared conventions).
#include "app/cli/decimate_command.h"

#include "app/cli/operation_command.h"

namespace trilab::cli {
namespace {

constexpr const char* kDecimateUsage =
    R"(usage: trilab-cli decimate [--cost quadric|roundness] [--normal-flip DEG|off]
                             [--roundness MIN] [--independent-set] [--max-error D]
                             (--percent P [--iterations N] | --target-vertices K)
                             IN OUT [--json] [--ascii] [--big-endian]

Decimates IN by edge collapses (section 1.4 of the reference) and writes the last iteration
to OUT. The result is always a valid manifold mesh with IN's boundary loops and genus (the
link condition is always enforced); boundary vertices only move along the boundary.

options:
  --cost C              quadric (Garland-Heckbert 1997, optimal placement; default) or
                        roundness (largest minimum normalized roundness first)
  --percent P           remove floor(P/100 * V) of the V vertices in each iteration
                        (0 < P <= 100, default 60)
  --iterations N        1 to 1000 (default 1)
  --target-vertices K   one iteration down to K vertices (instead of --percent)
  --normal-flip DEG     refuse collapses that turn a face normal by more than DEG degrees
                        (default 90); `off` turns the constraint off
  --roundness MIN       refuse collapses that leave a triangle with normalized roundness
                        below MIN (0 < MIN <= 1; off by default)
  --independent-set     lock the one-ring of every collapse until the next iteration
  --max-error D         refuse collapses whose quadric error exceeds D (a distance)
  --json                one JSON object: "surface_vertices" reached, "vertices" (in OUT,
                        isolated ones included), "collapses", "refused_*" per constraint,
                        "stop_reason" (done, max-error, constraints, topology),
                        "stop_message", "ms" (the decimation itself)

Vertex counts are of the vertices with faces: isolated vertices are kept and not counted.
)";

}  // namespace

int run_decimate_command(const std::vector<std::string>& args) {
    return run_operation_command("decimate", kDecimateUsage, args, add_operation_values,
                                 {"--independent-set"});
}

}  // namespace trilab::cli
