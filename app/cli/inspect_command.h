#pragma once
// `trilab-cli inspect`: what the viewer's inspector shows for one vertex, edge or face
// (core/algorithms/inspect.h), as text or JSON.
#include <string>
#include <vector>

namespace trilab::cli {

/// Runs `trilab-cli inspect IN (--vertex N | --edge N | --face N | --point X,Y,Z) [--json]`.
/// Returns the exit code; throws trilab::Error for bad arguments or files.
int run_inspect_command(const std::vector<std::string>& args);

}  // namespace trilab::cli
