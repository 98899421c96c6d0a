// `trilab-cli smooth`: reads a mesh, runs the "smooth" operation of the registry and writes
// the last iteration (see app/cli/operation_command.h for the shared conventions).
#include "app/cli/smooth_command.h"

#include "app/cli/operation_command.h"

namespace trilab::cli {
namespace {

constexpr const char* kSmoothUsage =
    R"(usage: trilab-cli smooth [--operator OP] [--integration explicit|implicit] [--step T]
                           [--iterations N] [--preserve-volume] [--boundary fixed|slide]
                           IN OUT [--json] [--ascii] [--big-endian]

Fairs the mesh IN (sections 1.2.1-1.2.10 of the reference) and writes the last iteration to
OUT. Boundary vertices stay fixed unless --boundary slide; isolated vertices do not move.

options:
  --operator OP         umbrella (default), improved-umbrella, curvature-flow, second-order,
                        taubin (lambda 0.5, mu -0.53; explicit only)
  --integration I       explicit (default) or implicit (backward Euler; the solver is chosen
                        by the system's condition bound and size: Jacobi-preconditioned
                        conjugate gradients warm-started from the positions, or a sparse
                        Cholesky reused across iterations)
  --step T              lambda * dt (default 0.5)
  --iterations N        1 to 10000 (default 1)
  --preserve-volume     scale back to the initial volume after every step (closed meshes)
  --boundary MODE       fixed (default): boundary vertices do not move; slide: they move
                        along the input's boundary curve (1-D umbrella in arc length)
  --json                one JSON object: "ms" (the fairing itself), "solver",
                        "max_residual", "factorizations", "cg_iterations",
                        "initial_volume", "final_volume", "max_smoothing_distance",
                        "mean_smoothing_distance", ...
)";

}  // namespace

int run_smooth_command(const std::vector<std::string>& args) {
    return run_operation_command("smooth", kSmoothUsage, args, add_operation_values,
                                 {"--preserve-volume"});
}

}  // namespace trilab::cli
