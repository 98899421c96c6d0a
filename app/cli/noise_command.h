#pragma once
// `trilab-cli noise`: displaces the vertices of a mesh along their normals (core/noise.h),
// through the operation registry (app/ops/operation.h) that the viewer uses too.
#include <string>
#include <vector>

namespace trilab::cli {

/// Runs `trilab-cli noise ARGS...` (the arguments after the command name). Returns the exit
/// code; throws trilab::Error for bad arguments or files (nothing is written then).
int run_noise_command(const std::vector<std::string>& args);

}  // namespace trilab::cli
