#pragma once
// Texture coordinates for meshes that have none: a planar projection onto the plane of the
// two largest principal axes of the vertex positions, or a spherical projection around the
// centroid (longitude, latitude). Computed once, on the current positions, so later vertex
// drift (smoothing) shows as moving texture.
#include "core/halfedge_mesh.h"
#include "core/up_axis.h"

namespace trilab {

enum class TexCoordProjection { Planar, Spherical };

/// Whether the mesh carries texture coordinates ("v:texcoord" or "h:texcoord" of type
/// TexCoord; an attribute of that name but another type does not count).
bool has_texcoords(const HalfedgeMesh& mesh);

/// Whether the corners at `v` carry more than one texture coordinate (`corner_uv`, the mesh's
/// "h:texcoord", read at v's incoming interior halfedges): a texture seam runs through v.
/// False without per-corner coordinates or for an isolated vertex.
bool on_texture_seam(const HalfedgeMesh& mesh, const HalfedgeProperty<const TexCoord>& corner_uv,
                     Vertex v);
/// Writes "v:texcoord" (created if needed) from the projection, in [0, 1]^2.
///
/// Planar: principal component analysis of the live vertex positions (eigenvectors of their
/// covariance, Eigen's SelfAdjointEigenSolver); u runs along the largest axis, v along the
/// second, and the larger extent maps to [0, 1] with the aspect ratio kept (the smaller one
/// maps to [0, extent ratio]). Where eigenvalues tie (a square, a disc, a sphere) the
/// coordinate axes break the tie, so an axis-aligned grid gets u = x, v = y. The frame is
/// oriented so the texture reads unmirrored from the side the faces face.
///
/// Spherical: around the centroid of the vertices with the up axis `up` (core/up_axis.h) as
/// the pole axis, u = longitude / 2pi + 0.5 with longitude 0 towards the front
/// (front_vector(up): +z for y-up, -y for z-up) and growing towards +x, and
/// v = latitude / pi + 0.5, so v grows along the up axis. Vertices on the axis (the poles)
/// get u = 0.5. Seam: per-vertex coordinates cannot split a vertex, so the triangles that
/// cross the date line (longitude +-pi, at the back: -z for y-up, +y for z-up) interpolate u
/// from near 1 back to near 0 and show the whole texture squeezed into one strip; triangles
/// at the poles are similarly pinched. Splitting the seam needs per-corner ("h:texcoord")
/// coordinates, which this function does not write.
///
/// Isolated vertices are projected too; deleted ones are skipped. A "v:texcoord" of another
/// type is replaced; an existing "h:texcoord" is left untouched. A mesh whose vertices all
/// coincide gets (0, 0) (planar) everywhere. Throws InvalidArgument, before changing the
/// mesh, if a position is not finite. Linear in the number of vertices and faces.
/// `up` matters only to the spherical projection.
void project_texcoords(HalfedgeMesh& mesh, TexCoordProjection projection, UpAxis up = UpAxis::Y);

}  // namespace trilab
