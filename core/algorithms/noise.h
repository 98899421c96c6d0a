#pragma once
// Add noise: displaces every vertex along its (area-weighted) normal by a uniform random
// amount in [-a, a], a = amount_percent / 100 x the mean edge length; the reference report
// made its noisy test models this way. Reproducible from the seed (own generator, the same
// on every platform). Isolated vertices and vertices without a normal do not move.
// Normals are taken from the positions before any vertex moves. A mesh that carries
// "v:normal" gets it recomputed afterwards, so the renderer does not shade with stale normals.
// Complexity: O(vertices + faces).
#include <cstdint>
#include <vector>

#include "core/halfedge_mesh.h"

namespace trilab {

/// The largest accepted NoiseOptions::amount_percent.
inline constexpr double kMaxNoiseAmountPercent = 1000.0;

struct NoiseOptions {
    double amount_percent = 1.0;  ///< in [0, 1000]
    std::uint32_t seed = 1;
    /// The region (core/algorithms/selection.h): one weight in [0, 1] per vertex storage index,
    /// or nullptr for the whole mesh. A vertex's offset is scaled by its weight (the random
    /// amounts and the mean edge length are the whole mesh's, so weight 1 moves a vertex exactly
    /// as without a region); weight-0 vertices are not touched. Not owned.
    const std::vector<float>* region = nullptr;
};

struct NoiseReport {
    double mean_edge_length = 0;
    double max_displacement = 0;     ///< largest |offset| applied
    std::size_t moved_vertices = 0;  ///< vertices with a non-zero offset
};

/// Moves the vertices of `mesh` (connectivity unchanged). Throws InvalidArgument naming
/// `amount_percent` when it is negative, above 1000 or not finite, or naming the region when
/// it does not fit the mesh (check_selection()); the mesh is unchanged then.
NoiseReport add_noise(HalfedgeMesh& mesh, const NoiseOptions& options);

}  // namespace trilab
