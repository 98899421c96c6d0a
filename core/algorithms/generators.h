#pragma once
// Built-in procedural models: the viewer's default model and test fixtures. Every generator
// returns a valid mesh (validate() passes) with consistent outward orientation.
#include <cstdint>
#include <string>
#include <vector>

#include "core/halfedge_mesh.h"

namespace trilab {

HalfedgeMesh make_tetrahedron();
HalfedgeMesh make_octahedron();
HalfedgeMesh make_icosahedron();
/// Unit cube, 8 vertices, 12 triangles.
HalfedgeMesh make_cube();
/// Geodesic unit sphere: each icosahedron face split into frequency^2 triangles and
/// projected; 10 f^2 + 2 vertices.
HalfedgeMesh make_icosphere(unsigned frequency);
/// make_icosphere with every vertex moved radially by a uniform random amount in
/// [-amplitude, amplitude] (relative to the radius), reproducible from `seed`.
HalfedgeMesh make_noisy_sphere(unsigned frequency, double amplitude, std::uint32_t seed);
/// Torus around the z axis: major_segments x minor_segments quads, each split in two.
HalfedgeMesh make_torus(unsigned major_segments, unsigned minor_segments, double major_radius,
                        double minor_radius);
/// Square grid [0,1]^2 in the z = 0 plane with n x n quads split in two (open, one boundary).
HalfedgeMesh make_grid(unsigned n);
/// Closed box of nx x ny x nz unit cells scaled so that the longest side is 2, centred at the
/// origin: each side a grid of squares split in two along alternating diagonals (a
/// checkerboard, so no direction is preferred); 2 (nx ny + ny nz + nz nx) squares. A
/// cube-like block with sharp edges and corners, the denoising tests' CAD-like fixture.
/// Throws InvalidArgument when a count is 0 or above 1000.
HalfedgeMesh make_block(unsigned nx, unsigned ny, unsigned nz);
/// Open cylinder around the z axis (two boundary loops).
HalfedgeMesh make_cylinder(unsigned segments, unsigned rings);

/// The viewer's default model: a noisy sphere of 1,002 vertices (like the reference's
/// 1,026-vertex test sphere).
HalfedgeMesh make_default_model();

/// Names accepted by generate(): "default", "sphere", "noisy-sphere", "tetrahedron",
/// "octahedron", "icosahedron", "cube", "torus", "grid", "cylinder", "block" (make_block(24,
/// 18, 12): 3,744 faces).
std::vector<std::string> generator_names();
/// The built-in model of that name. Throws InvalidArgument listing the names otherwise.
HalfedgeMesh generate(const std::string& name);

}  // namespace trilab
