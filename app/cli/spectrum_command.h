#pragma once
// `trilab-cli spectrum`: frequency decomposition (core/spectral.h) through the operation
// registry, writing the reconstruction from a band and optionally the eigenvalues.
#include <string>
#include <vector>

namespace trilab::cli {

/// Runs `trilab-cli spectrum ARGS...`. Returns the exit code; throws trilab::Error for bad
/// arguments or files (nothing is written then).
int run_spectrum_command(const std::vector<std::string>& args);

}  // namespace trilab::cli
