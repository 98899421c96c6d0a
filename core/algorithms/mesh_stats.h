#pragma once
// Topological and geometric summary of a mesh, as `trilab-cli info` prints it.
#include <optional>

#include "core/geometry.h"
#include "core/halfedge_mesh.h"

namespace trilab {

struct MeshStats {
    std::size_t vertices = 0, edges = 0, faces = 0;
    std::size_t isolated_vertices = 0;
    std::size_t boundary_loops = 0;
    /// Connected components of the surface (isolated vertices not counted).
    std::size_t components = 0;
    /// V - E + F over all vertices (isolated vertices count as points).
    long long euler = 0;
    /// Total genus of the surface: (2 C - chi_surface - B) / 2, with chi_surface excluding
    /// isolated vertices.
    long long genus = 0;
    BoundingBox bbox;
    double area = 0;
    /// Enclosed volume (1.15); empty when the mesh is not closed.
    std::optional<double> volume;
};

/// The summary; `component_of_vertex`, when given, gets the labels it counts the components
/// with (label_components()), for a caller that keeps them (the viewer, for a region's flip).
MeshStats compute_stats(const HalfedgeMesh& mesh,
                        std::vector<Index>* component_of_vertex = nullptr);
/// Number of boundary loops (cycles of boundary halfedges).
std::size_t count_boundary_loops(const HalfedgeMesh& mesh);
/// Connected component index for every vertex ("components" ignores isolated vertices, but
/// each isolated vertex gets its own index here). Returns the number of indices used.
std::size_t label_components(const HalfedgeMesh& mesh, std::vector<Index>& component_of_vertex);

}  // namespace trilab
