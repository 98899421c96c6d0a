#pragma once
// `trilab-cli compare`: sampled Hausdorff and RMS distance between two meshes
// (core/algorithms/mesh_distance.h).
#include <string>
#include <vector>

namespace trilab::cli {

/// Runs `trilab-cli compare A B [--samples N] [--json]`. Returns the exit code; throws
/// trilab::Error for bad arguments or files.
int run_compare_command(const std::vector<std::string>& args);

}  // namespace trilab::cli
