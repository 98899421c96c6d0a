#pragma once
// The decimation benchmark's peers (benchmark only, each compiled in when its library was
// found at configure time): OpenMesh 9's DecimaterT with ModQuadricT, CGAL 5.5's
// edge_collapse with the Garland-Heckbert plane policies, meshoptimizer's meshopt_simplify.
// Each takes a triangle soup and a target, times only its own decimation call, and returns
// the soup it produced (vertices unreferenced by any face are dropped).
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace trilab::bench {

struct Soup {
    std::vector<std::array<double, 3>> positions;
    std::vector<std::array<std::uint32_t, 3>> faces;
};

struct PeerRun {
    Soup soup;
    double ms = 0;      ///< wall clock
    double cpu_ms = 0;  ///< process CPU time (the machine may be shared)
};

/// Down to `target_vertices` (OpenMesh decimates to a vertex count).
PeerRun openmesh_decimate(const Soup& in, std::size_t target_vertices);
/// Down to fewer than `target_edges` edges (CGAL 5.5's Count_stop_predicate).
PeerRun cgal_decimate(const Soup& in, std::size_t target_edges);
/// Down to `target_faces` (meshopt_simplify's target index count / 3), no error limit.
PeerRun meshopt_decimate(const Soup& in, std::size_t target_faces);

bool have_openmesh();
bool have_cgal();
bool have_meshopt();

/// Drops unreferenced vertices and renumbers.
Soup compact(const Soup& s);

}  // namespace trilab::bench
