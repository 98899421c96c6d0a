#pragma once
// `trilab-cli generate NAME OUT`: writes one of the built-in models
// (core/algorithms/generators.h).
#include <string>
#include <vector>

namespace trilab::cli {

/// Runs `trilab-cli generate ARGS...` (the arguments after the command name). Returns the
/// exit code; throws trilab::Error for bad arguments or files.
int run_generate_command(const std::vector<std::string>& args);

}  // namespace trilab::cli
