#pragma once
// A coarse stand-in for a large mesh, drawn while the view moves: vertex clustering on a
// uniform grid (Rossignac and Borrel, "Multi-resolution 3D approximations for rendering
// complex scenes", 1993).
#include <array>
#include <cstddef>
#include <vector>

#include "core/halfedge_mesh.h"
#include "core/mesh_builder.h"

namespace trilab {

struct ProxyMeshOptions {
    /// About how many triangles the proxy may have: the grid's cell is sized from the mesh's
    /// area for this count and enlarged (a further pass) while the proxy has more than it.
    /// At least 16; at most 2,000,000 (cluster numbers are packed in 21 bits).
    std::size_t target_triangles = 200000;
    /// Keep ProxyMesh::cluster_of (one index per mesh vertex), which moved_proxy_mesh needs.
    bool keep_clusters = false;
};

/// The proxy: a triangle list over the clusters' vertices.
struct ProxyMesh {
    /// One vertex per occupied grid cell: the mean of the mesh vertices in the cell (not the
    /// quadric-optimal point: the mean is inside the cell, which is what bounds the error).
    /// Numbered in the order of the lowest mesh vertex in each cell.
    std::vector<Point> positions;
    /// Triangles over `positions`, in the mesh's orientation, each once per orientation (a
    /// thin sheet collapsed into one layer keeps both sides), in the order of the first mesh
    /// face that maps onto them. Triangles with two corners in one cell are dropped.
    std::vector<std::array<Index, 3>> triangles;
    /// Per proxy vertex: the mesh vertex of its cell nearest to the proxy vertex (the lowest
    /// index among equally near ones). A per-vertex colouring of the mesh, whatever its mode,
    /// is sampled for the proxy through it, with no new clustering.
    std::vector<Index> representative;
    /// The grid's cell edge length.
    double cell_size = 0;
    /// The cell's diagonal (cell_size * sqrt(3)): no mesh vertex is farther than this from
    /// its proxy vertex. A viewer turns it into pixels with its projection.
    double error_bound = 0;
    /// How many grid sizes were tried (1 when the first estimate fitted the target).
    unsigned passes = 0;
    /// With ProxyMeshOptions::keep_clusters: per mesh vertex storage index its proxy vertex
    /// (kInvalidIndex for a deleted vertex); empty otherwise.
    std::vector<Index> cluster_of;
};

/// Makes the proxy of `mesh`'s live vertices and faces (isolated vertices become proxy
/// vertices without triangles). The grid is aligned to the bounding box's minimum corner.
/// Deterministic: the same mesh and target give the same proxy, with any thread count.
/// A mesh without vertices gives an empty proxy. Throws InvalidArgument for a target outside
/// [16, 2,000,000]. Complexity: O(V + F) a pass, the face pass on core/parallel.h's
/// threads (thread_count(); the same proxy for any count); about
/// 0.3 s for 17.8M faces on two cores.
ProxyMesh make_proxy_mesh(const HalfedgeMesh& mesh, const ProxyMeshOptions& options = {});

/// The proxy of `mesh` when it has the connectivity `proxy` was made for and other positions
/// (a smoothing's result, a spectral prediction): the same clusters and triangles, each proxy
/// vertex the mean of its cluster's vertices at their new positions, the representatives
/// kept, and error_bound the largest distance from a vertex to its proxy vertex (measured:
/// the moved clusters are no longer grid cells). Throws InvalidArgument when `proxy` has no
/// cluster_of or one for another vertex count. O(V), about a twentieth of make_proxy_mesh.
ProxyMesh moved_proxy_mesh(const ProxyMesh& proxy, const HalfedgeMesh& mesh);

/// The same clustering over a polygon soup as a file reader gives it, before any half-edge
/// mesh is built (the viewer's picture of a file still loading). Every position is a vertex;
/// a polygon is clustered as the fan from its first corner, a face of fewer than three corners
/// adds nothing. For the soup of a mesh whose faces are the soup's triangles in order and whose
/// vertices are the soup's positions (what build_mesh makes of a clean manifold triangle soup)
/// the result equals make_proxy_mesh of that mesh. Throws InvalidArgument for a corner index
/// out of range or a target outside [16, 2,000,000]. Complexity: as make_proxy_mesh.
ProxyMesh make_soup_proxy_mesh(const PolygonSoup& soup, const ProxyMeshOptions& options = {});

}  // namespace trilab
