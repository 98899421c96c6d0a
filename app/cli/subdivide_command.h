#pragma once
// `trilab-cli subdivide`: refines a mesh with Loop, Sqrt3, Butterfly or Modified Butterfly
// subdivision (core/subdivision.h), through the operation registry (app/ops/operation.h)
// that the viewer uses too.
#include <string>
#include <vector>

namespace trilab::cli {

/// Runs `trilab-cli subdivide ARGS...` (the arguments after the command name). Returns the
/// exit code; throws trilab::Error for bad arguments or files (nothing is written then).
int run_subdivide_command(const std::vector<std::string>& args);

}  // namespace trilab::cli
