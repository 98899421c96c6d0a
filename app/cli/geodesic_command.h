#pragma once
// `trilab-cli geodesic`: heat-method geodesic distances from source vertices
// (core/algorithms/geodesic.h), written as the per-vertex `distance` of a PLY file.
#include <string>
#include <vector>

namespace trilab::cli {

/// Runs `trilab-cli geodesic IN OUT --from N[,N...] [--to M] [--json]`. Returns the exit code;
/// throws trilab::Error for bad arguments or files.
int run_geodesic_command(const std::vector<std::string>& args);

}  // namespace trilab::cli
