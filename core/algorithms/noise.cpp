// Add noise (core/algorithms/noise.h): each live vertex moves along its area-weighted normal
// (core's vertex_normal, taken before anything moves) or a random unit direction by r x a:
// uniform, a = amount% x the mean edge length and r uniform in [-1, 1); Gaussian, a = sigma x
// the mean edge length and r standard normal (Box-Muller). Every random number comes from a
// counter-based generator, splitmix64 (Steele, Lea and Flood 2014) of the seed, the vertex's
// storage index and a stream number, so it depends on nothing but those: the same seed gives
// the same positions whatever the order of the vertices' visits (the uniform ones bit-identical
// on every platform and standard library). Guarantees: connectivity is untouched; uniform:
// |offset| <= a; isolated vertices, and along the normal vertices with a zero normal, stay put;
// bad options throw before anything changes.
#include "core/algorithms/noise.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "core/algorithms/selection.h"
#include "core/errors.h"
#include "core/geometry.h"

namespace trilab {
namespace {

/// splitmix64's output function: a bijective mix of 64 bits.
std::uint64_t splitmix64(std::uint64_t x) {
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

/// A uniform number in [-1, 1) for vertex `index` under `seed`: the top 53 bits of the hash,
/// scaled exactly (every step is exact in double precision).
double signed_unit(std::uint32_t seed, std::size_t index) {
    const std::uint64_t key = (std::uint64_t(seed) << 32) ^ std::uint64_t(index);
    const std::uint64_t bits = splitmix64(splitmix64(key)) >> 11;  // 53 bits
    return double(bits) * 0x1.0p-52 - 1.0;
}

/// A uniform number in (0, 1] for vertex `index`, stream `stream` under `seed` (the streams
/// of one vertex are independent draws; stream 0 is not signed_unit()'s draw).
double open_unit(std::uint32_t seed, std::size_t index, std::uint64_t stream) {
    const std::uint64_t key = (std::uint64_t(seed) << 32) ^ std::uint64_t(index);
    const std::uint64_t bits =
        splitmix64(splitmix64(key) ^ splitmix64(0xd1b54a32d192ed03ull * (stream + 1))) >> 11;
    return (double(bits) + 1.0) * 0x1.0p-53;
}

constexpr double kTwoPi = 6.283185307179586476925286766559;

/// A standard normal number (Box-Muller over streams 0 and 1).
double standard_normal(std::uint32_t seed, std::size_t index) {
    const double u1 = open_unit(seed, index, 0), u2 = open_unit(seed, index, 1);
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(kTwoPi * u2);
}

/// A unit vector uniform on the sphere (Archimedes: z uniform in [-1, 1], streams 2 and 3).
Vector3 random_direction(std::uint32_t seed, std::size_t index) {
    const double z = 2.0 * open_unit(seed, index, 2) - 1.0;
    const double phi = kTwoPi * open_unit(seed, index, 3);
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    return Vector3(r * std::cos(phi), r * std::sin(phi), z);
}

std::string number_text(double v) {
    char buf[32];
    std::snprintf(buf, sizeof(buf), "%g", v);
    return buf;
}

}  // namespace

NoiseReport add_noise(HalfedgeMesh& mesh, const NoiseOptions& options) {
    const double pct = options.amount_percent;
    if (!std::isfinite(pct) || pct < 0 || pct > kMaxNoiseAmountPercent)
        throw InvalidArgument("add_noise: amount_percent must be a number from 0 to " +
                              number_text(kMaxNoiseAmountPercent) + ", got " + number_text(pct));
    const bool gaussian = options.distribution == NoiseDistribution::Gaussian;
    const double k = options.sigma;
    if (!std::isfinite(k) || k < 0 || k > kMaxNoiseSigma)
        throw InvalidArgument("add_noise: sigma must be a number from 0 to " +
                              number_text(kMaxNoiseSigma) +
                              " (multiples of the mean edge length), got " + number_text(k));
    const bool along_normal = options.direction == NoiseDirection::Normal;

    const Selection* region = options.region;
    if (region) check_selection(mesh, *region, "add_noise: region");

    NoiseReport report;
    report.mean_edge_length = mean_edge_length(mesh);
    const double amplitude =
        gaussian ? k * report.mean_edge_length : pct / 100.0 * report.mean_edge_length;
    report.scale = amplitude;
    if (!(amplitude > 0) || !std::isfinite(amplitude)) return report;  // nothing moves

    // Offsets first, from the unmoved surface; then move.
    const std::size_t n = mesh.vertices_size();
    std::vector<Vector3> offsets(n, Vector3::Zero());
    for (Vertex v : mesh.vertices()) {
        if (mesh.is_isolated(v) || !(region_weight(region, v.idx()) > 0.0f)) continue;
        const Vector3 normal =
            along_normal ? vertex_normal(mesh, v) : random_direction(options.seed, v.idx());
        if (normal.isZero(0.0)) continue;
        double r = (gaussian ? standard_normal(options.seed, v.idx())
                             : signed_unit(options.seed, v.idx())) *
                   amplitude;
        if (region) r *= double((*region)[v.idx()]);  // exact for weight 1
        if (r == 0) continue;
        offsets[v.idx()] = r * normal;
        report.max_displacement = std::max(report.max_displacement, std::abs(r));
        ++report.moved_vertices;
    }
    for (Vertex v : mesh.vertices())
        if (region_weight(region, v.idx()) > 0.0f) mesh.position(v) += offsets[v.idx()];
    if (mesh.get_vertex_property<Vector3>("v:normal")) compute_vertex_normals(mesh);
    return report;
}

}  // namespace trilab
