#pragma once
// Add noise: displaces every vertex along its (area-weighted) normal, or in a random direction,
// by a random amount:
//  - Uniform (the default): uniform in [-a, a], a = amount_percent / 100 x the mean edge length;
//    the reference report made its noisy test models this way;
//  - Gaussian: normal with standard deviation sigma x the mean edge length (Box-Muller), the
//    noise of the denoising literature (Zheng et al. 2011; Zhang et al. 2015 add "Gaussian noise
//    of sigma = k x the mean edge length").
// A random direction is uniform on the unit sphere; the amount is then the signed length along
// it. Reproducible from the seed (own counter-based generator: the uniform draws are the same
// on every platform; the Gaussian ones go through std::log, std::cos and std::sin).
// Isolated vertices do not move; along the normal, neither do vertices without a normal.
// Normals are taken from the positions before any vertex moves. A mesh that carries
// "v:normal" gets it recomputed afterwards, so the renderer does not shade with stale normals.
// Complexity: O(vertices + faces).
#include <cstdint>
#include <vector>

#include "core/enum_table.h"
#include "core/halfedge_mesh.h"

namespace trilab {

/// The largest accepted NoiseOptions::amount_percent.
inline constexpr double kMaxNoiseAmountPercent = 1000.0;
/// The largest accepted NoiseOptions::sigma (multiples of the mean edge length).
inline constexpr double kMaxNoiseSigma = 10.0;

/// How the random amount is drawn.
enum class NoiseDistribution { Uniform, Gaussian };
inline constexpr EnumEntry<NoiseDistribution> kNoiseDistributions[] = {
    {NoiseDistribution::Uniform, "uniform", "Uniform"},
    {NoiseDistribution::Gaussian, "gaussian", "Gaussian"},
};

/// Along what a vertex moves.
enum class NoiseDirection { Normal, Random };
inline constexpr EnumEntry<NoiseDirection> kNoiseDirections[] = {
    {NoiseDirection::Normal, "normal", "Along the normal"},
    {NoiseDirection::Random, "random", "Random direction"},
};

struct NoiseOptions {
    double amount_percent = 1.0;  ///< in [0, 1000]
    std::uint32_t seed = 1;
    /// The region (core/algorithms/selection.h): one weight in [0, 1] per vertex storage index,
    /// or nullptr for the whole mesh. A vertex's offset is scaled by its weight (the random
    /// amounts and the mean edge length are the whole mesh's, so weight 1 moves a vertex exactly
    /// as without a region); weight-0 vertices are not touched. Not owned.
    const std::vector<float>* region = nullptr;
    NoiseDistribution distribution = NoiseDistribution::Uniform;
    /// Gaussian: the standard deviation in multiples of the mean edge length (k), in [0, 10].
    double sigma = 0.3;
    NoiseDirection direction = NoiseDirection::Normal;
};

struct NoiseReport {
    double mean_edge_length = 0;
    /// The scale of the draw: a (uniform) or the standard deviation (Gaussian), a length.
    double scale = 0;
    double max_displacement = 0;     ///< largest |offset| applied
    std::size_t moved_vertices = 0;  ///< vertices with a non-zero offset
};

/// Moves the vertices of `mesh` (connectivity unchanged). Throws InvalidArgument naming
/// `amount_percent` when it is negative, above 1000 or not finite, `sigma` when it is negative,
/// above 10 or not finite, or naming the region when it does not fit the mesh
/// (check_selection()); the mesh is unchanged then.
NoiseReport add_noise(HalfedgeMesh& mesh, const NoiseOptions& options);

}  // namespace trilab
