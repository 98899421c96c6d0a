#pragma once
// `trilab-cli smooth`: fairing (core/fairing.h) through the operation registry.
#include <string>
#include <vector>

namespace trilab::cli {

/// Runs `trilab-cli smooth ARGS...`. Returns the exit code; throws trilab::Error for bad
/// arguments or files (nothing is written then).
int run_smooth_command(const std::vector<std::string>& args);

}  // namespace trilab::cli
