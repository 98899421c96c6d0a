#pragma once
// `trilab-cli decimate`: edge-collapse decimation (core/decimation.h) through the operation
// registry.
#include <string>
#include <vector>

namespace trilab::cli {

/// Runs `trilab-cli decimate ARGS...`. Returns the exit code; throws trilab::Error for bad
/// arguments or files (nothing is written then).
int run_decimate_command(const std::vector<std::string>& args);

}  // namespace trilab::cli
