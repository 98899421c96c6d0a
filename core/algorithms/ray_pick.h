#pragma once
// Picking: the triangle hit first by a ray (the ray through a pixel), and the nearest corner
// and edge of that triangle to the hit point.
//
// Exact: every triangle is tested (Möller, Trumbore, "Fast, minimum storage ray/triangle
// intersection", 1997, in double precision), both orientations, so a back face in front is
// hit as it is drawn; the nearest hit with t > t_min wins, ties going to the lower triangle
// index (deterministic). Degenerate triangles (zero area) are never hit. No acceleration
// structure: nothing to build or keep in step with the positions, so a pick is right on any
// state the moment it is shown (a morph frame, a preview, a level of detail). A first pass
// over the points files each by the side of two planes through the ray; a triangle whose
// corners lie on one side of either plane is skipped without touching its positions (a
// conservative test: it never skips a triangle the ray meets). Both passes are split over
// the hardware threads above 200,000 elements.
// Complexity: O(V + F) per pick, divided by the threads.
#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "core/halfedge_mesh.h"

namespace trilab {

/// origin + t·direction for t >= 0; `direction` need not be unit length (t is then in its
/// units).
struct Ray {
    Point origin = Point::Zero();
    Vector3 direction = Vector3::UnitZ();
};

/// What a ray hit: the triangle (a face storage index, or an index into a triangle list), its
/// corners in order, the ray parameter, the hit point and its barycentric coordinates
/// (weights of corners 0, 1, 2), and the corner and edge nearest to the hit point (edge k runs
/// from corner k to corner (k + 1) mod 3).
struct RayHit {
    Index triangle = kInvalidIndex;
    std::array<Index, 3> corners{kInvalidIndex, kInvalidIndex, kInvalidIndex};
    double t = 0;
    Point position = Point::Zero();
    std::array<double, 3> barycentric{0, 0, 0};
    int nearest_corner = 0;  ///< 0, 1 or 2
    int nearest_edge = 0;    ///< 0, 1 or 2: corners (k, k + 1)
    /// Whether the ray meets the triangle's back (against the corners' counter-clockwise
    /// normal).
    bool back_face = false;
};

/// The first face of `mesh` (deleted faces skipped) hit by `ray` at t > t_min, with the
/// vertices at `positions` (one per vertex storage index: the mesh's own positions, or a
/// morph frame's). Corners are the face's vertices in its halfedge order, starting at
/// to_vertex(halfedge(face)). Polygons are not expected (the mesh is triangulated): a face
/// with more than three sides is tested as a fan. Throws InvalidArgument when
/// positions.size() != mesh.vertices_size() or the direction is zero or not finite.
std::optional<RayHit> pick_face(const HalfedgeMesh& mesh, const std::vector<Point>& positions,
                                const Ray& ray, double t_min = 0.0);

/// The same over a triangle list (a level of detail's faces): triangles whose `alive` entry
/// is 0 are skipped (`alive` empty: all count). Throws InvalidArgument when a corner is out of
/// range of `positions` or as pick_face().
std::optional<RayHit> pick_triangle(const std::vector<std::array<Index, 3>>& triangles,
                                    const std::vector<std::uint8_t>& alive,
                                    const std::vector<Point>& positions, const Ray& ray,
                                    double t_min = 0.0);

/// Fills the hit's nearest corner and edge (world distance from the hit point to each corner
/// and to each edge segment) from its corners at `positions`. pick_face() and
/// pick_triangle() call it; exposed for tests.
void set_nearest_elements(RayHit& hit, const std::vector<Point>& positions);

/// The halfedge of `face` from corner k to corner k + 1, in the order pick_face() lists the
/// corners (k in 0..2).
Halfedge face_side(const HalfedgeMesh& mesh, Face face, int k);

}  // namespace trilab
