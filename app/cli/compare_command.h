#pragma once
// `trilab-cli compare`: sampled Hausdorff and RMS distance between two meshes, the distance of
// B's vertices to A's surface, and for two states of one mesh the face-normal deviation θ
// and the flipped faces (core/algorithms/mesh_distance.h).
#include <string>
#include <vector>

namespace trilab::cli {

/// Runs `trilab-cli compare A B [--samples N] [--region SPEC] [--json]`. Returns the exit code;
/// throws trilab::Error for bad arguments or files.
int run_compare_command(const std::vector<std::string>& args);

}  // namespace trilab::cli
