#pragma once
// `trilab-cli info MESH`: counts, topology, seams, bounding box, area, volume (null for an
// open mesh) and what the loader repaired.
#include <string>
#include <vector>

namespace trilab::cli {

/// Runs `trilab-cli info ARGS...` (the arguments after the command name). Returns the exit
/// code; throws trilab::Error for bad arguments or files.
int run_info_command(const std::vector<std::string>& args);

}  // namespace trilab::cli
