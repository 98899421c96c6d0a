#pragma once
// Geometric quantities of a triangle mesh: normals, areas, lengths, bounding box, volume,
// cotangent weights. All functions are O(size of what they touch) and never produce NaN on
// degenerate triangles: a zero-area face has a zero normal and zero cotangents.
#include <utility>

#include "core/halfedge_mesh.h"

namespace trilab {

struct BoundingBox {
    Point min = Point::Constant(0), max = Point::Constant(0);
    bool empty = true;
    void extend(const Point& p);
    Point center() const { return 0.5 * (min + max); }
    Vector3 size() const { return max - min; }
    double diagonal() const { return empty ? 0.0 : (max - min).norm(); }
};

/// (x1 - x0) x (x2 - x0): twice the area times the unit normal.
Vector3 face_area_vector(const HalfedgeMesh& mesh, Face f);
/// Unit face normal (zero for a degenerate face).
Vector3 face_normal(const HalfedgeMesh& mesh, Face f);
double face_area(const HalfedgeMesh& mesh, Face f);
Point face_centroid(const HalfedgeMesh& mesh, Face f);
/// Area-weighted vertex normal: the normalized sum of the incident faces' area vectors
/// (zero for isolated vertices and fully degenerate fans).
Vector3 vertex_normal(const HalfedgeMesh& mesh, Vertex v);
/// Stores vertex_normal() for every vertex in "v:normal" (created if needed).
void compute_vertex_normals(HalfedgeMesh& mesh);
double edge_length(const HalfedgeMesh& mesh, Edge e);
double mean_edge_length(const HalfedgeMesh& mesh);
BoundingBox bounding_box(const HalfedgeMesh& mesh);
double surface_area(const HalfedgeMesh& mesh);
/// Signed enclosed volume, formula (1.15) of the reference report:
/// V = 1/6 sum_k g_k . N_k with g_k the centroid and N_k the area vector of triangle k.
/// Only meaningful for closed meshes (see is_closed()).
double volume(const HalfedgeMesh& mesh);
/// surface_area() and volume() (the same to the bit) in one pass over the faces; only the
/// sums asked for are made (the other stays 0). O(faces).
struct AreaVolume {
    double area = 0, volume = 0;
};
AreaVolume area_and_volume(const HalfedgeMesh& mesh, bool with_area, bool with_volume);
/// The smallest interior angle of face f, in degrees (0 for a degenerate face). O(1).
double min_face_angle(const HalfedgeMesh& mesh, Face f);
/// The smallest interior angle over all live faces, in degrees (180 for a mesh without faces:
/// nothing is flatter than anything). O(faces).
double min_triangle_angle(const HalfedgeMesh& mesh);
/// Whether the mesh has faces and no boundary edges.
bool is_closed(const HalfedgeMesh& mesh);
/// Cotangent of the corner opposite to h in face(h) (0 for boundary h or a degenerate face).
double cotangent_opposite(const HalfedgeMesh& mesh, Halfedge h);
/// (cot alpha + cot beta) / 2 for edge e, alpha and beta opposite to it. Can be negative
/// for obtuse configurations; callers that need positivity clamp.
double cotangent_weight(const HalfedgeMesh& mesh, Edge e);

}  // namespace trilab
