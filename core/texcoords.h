#pragma once
// Texture coordinates for meshes that have none: a planar projection onto the plane of the
// two largest principal axes of the vertex positions, or a spherical projection around the
// centroid (longitude, latitude). Computed once, on the current positions, so later vertex
// drift (smoothing) shows as moving texture.
#include "core/halfedge_mesh.h"

namespace trilab {

enum class TexCoordProjection { Planar, Spherical };

/// Whether the mesh carries texture coordinates ("v:texcoord" or "h:texcoord").
bool has_texcoords(const HalfedgeMesh& mesh);
/// Writes "v:texcoord" (created if needed) from the projection, in [0, 1]^2.
void project_texcoords(HalfedgeMesh& mesh, TexCoordProjection projection);

}  // namespace trilab
