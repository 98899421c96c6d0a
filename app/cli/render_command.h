#pragma once
// `trilab-cli render`: offscreen rendering of a mesh to a PNG (see README).
#include <string>
#include <vector>

namespace trilab::cli {

/// Runs `trilab-cli render ARGS...` (the arguments after the command name). Returns the
/// exit code; throws trilab::Error for bad arguments or files.
int run_render_command(const std::vector<std::string>& args);

}  // namespace trilab::cli
