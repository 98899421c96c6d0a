#pragma once
// `trilab-cli convert IN OUT`: reads a mesh and writes it in the format of OUT's extension.
#include <string>
#include <vector>

namespace trilab::cli {

/// Runs `trilab-cli convert ARGS...` (the arguments after the command name). Returns the exit
/// code; throws trilab::Error for bad arguments or files.
int run_convert_command(const std::vector<std::string>& args);

}  // namespace trilab::cli
