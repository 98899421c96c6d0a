#pragma once
// Shared helpers for the unit tests: fixture paths, temporary folders, validity checks.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "core/features.h"
#include "core/halfedge_mesh.h"
#include "core/validate.h"
#include "tests/support/cancelling_progress.h"
#include "tests/support/error_text.h"
#include "tests/support/fp_traps.h"
#include "tests/support/skip.h"

namespace trilab::test {

/// The sharp edges of `mesh` (core/features.h: sharpness > 0) as segments.
inline std::vector<std::array<Point, 2>> sharp_segments(const HalfedgeMesh& mesh) {
    std::vector<std::array<Point, 2>> out;
    for (Edge e : mesh.edges())
        if (sharpness(mesh, e) > 0.0f)
            out.push_back({mesh.position(mesh.vertex(e, 0)), mesh.position(mesh.vertex(e, 1))});
    return out;
}

/// The distance from p to segment s (to its first end when it has no length).
inline double segment_distance(const Point& p, const std::array<Point, 2>& s) {
    const Vector3 d = s[1] - s[0];
    const double l2 = d.squaredNorm();
    const double t = l2 > 0 ? std::clamp((p - s[0]).dot(d) / l2, 0.0, 1.0) : 0.0;
    return (s[0] + t * d - p).norm();
}

/// The distance from p to the nearest of the segments (brute force).
inline double segments_distance(const Point& p, const std::vector<std::array<Point, 2>>& segments) {
    double best = std::numeric_limits<double>::infinity();
    for (const auto& s : segments) best = std::min(best, segment_distance(p, s));
    return best;
}

/// ../shared beside the repository, or $TRILAB_SHARED_DIR when set (may be absent: tests using
/// it record a skip, see tests/support/skip.h).
inline std::string shared_dir() {
    const char* env = std::getenv("TRILAB_SHARED_DIR");
    return env && *env ? env : TRILAB_SHARED_DIR;
}
inline std::string shared_mesh(const std::string& name) {
    return shared_dir() + "/meshes/" + name;
}
inline std::string data_file(const std::string& name) {
    return std::string(TRILAB_SOURCE_DIR) + "/tests/data/" + name;
}
inline bool exists(const std::string& path) {
    return std::filesystem::exists(path);
}

/// A sphere with normals, colours and texture coordinates on its vertices.
HalfedgeMesh attributed_sphere();

/// Per cluster, the mean of the positions `x` (one per storage index) of `mesh`'s vertices in
/// it (cluster_of: one cluster below `clusters` per storage index); every cluster must have one.
std::vector<Point> cluster_means(const HalfedgeMesh& mesh, const std::vector<Point>& x,
                                 const std::vector<Index>& cluster_of, std::size_t clusters);

/// Two icospheres (subdivision 2) side by side, the second moved by 3 along x, from one soup:
/// two components, the second's vertices numbered after the first's.
HalfedgeMesh two_spheres();

/// The first edge of `mesh` that can be flipped (HalfedgeMesh::is_flip_ok), or an invalid one.
inline Edge first_flippable_edge(const HalfedgeMesh& mesh) {
    for (Edge e : mesh.edges())
        if (mesh.is_flip_ok(e)) return e;
    return Edge();
}

/// The message of the IoError that reading `path` throws ("" when none is thrown).
std::string read_error(const std::string& path);

/// A fresh folder under the system temp dir, removed when the object dies.
class TempDir {
public:
    TempDir();
    ~TempDir();
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    std::string path(const std::string& name) const { return (dir_ / name).string(); }
    const std::filesystem::path& dir() const { return dir_; }

private:
    std::filesystem::path dir_;
};

}  // namespace trilab::test

/// Asserts validate(mesh) and prints the first violation when it fails.
#define REQUIRE_VALID(mesh)                            \
    do {                                               \
        const auto trilab_vr = trilab::validate(mesh); \
        INFO("validate: " << trilab_vr.message);       \
        REQUIRE(trilab_vr.ok);                         \
    } while (0)
