#include "core/algorithms/mesh_stats.h"

#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

#include "core/parallel.h"

namespace trilab {

namespace {

/// The boundary scan's block: big, since few halfedges are on the boundary.
constexpr std::size_t kScanBlock = std::size_t(1) << 16;

/// Union-find root with path halving.
Index find_root(std::vector<Index>& parent, Index v) {
    while (parent[v] != v) {
        parent[v] = parent[parent[v]];
        v = parent[v];
    }
    return v;
}

}  // namespace

std::size_t count_boundary_loops(const HalfedgeMesh& mesh) {
    // The boundary halfedges, found by one sequential pass over the halfedges' faces (a
    // large scan has a few thousand among tens of millions), then each loop walked once from
    // its lowest one; seen is kept for those halfedges only (sorted, searched).
    const std::vector<Face>& face = mesh.halfedge_face_array();
    const bool garbage = mesh.has_garbage();
    // The scan in fixed blocks on every thread, each block's list appended in block order.
    std::vector<std::vector<Index>> found(block_count(0, face.size(), kScanBlock));
    parallel_for_blocks(
        0, face.size(),
        [&](std::size_t begin, std::size_t end) {
            std::vector<Index>& list = found[begin / kScanBlock];
            for (std::size_t h = begin; h < end; ++h)
                if (!face[h].is_valid() && !(garbage && mesh.is_deleted(Halfedge(Index(h)))))
                    list.push_back(Index(h));
        },
        kScanBlock);
    std::vector<Index> boundary;
    for (const std::vector<Index>& list : found)
        boundary.insert(boundary.end(), list.begin(), list.end());
    std::vector<std::uint8_t> seen(boundary.size(), 0);
    const auto index_of = [&](Halfedge x) {  // boundary.size() when x is not a boundary one
        return std::size_t(std::lower_bound(boundary.begin(), boundary.end(), x.idx()) -
                           boundary.begin());
    };
    std::size_t loops = 0;
    for (std::size_t i = 0; i < boundary.size(); ++i) {
        if (seen[i]) continue;
        ++loops;
        const Halfedge h(boundary[i]);
        Halfedge x = h;
        do {
            const std::size_t k = index_of(x);
            if (k == boundary.size() || boundary[k] != x.idx() || seen[k]) break;
            seen[k] = 1;
            x = mesh.next(x);
        } while (x != h);
    }
    return loops;
}

std::size_t label_components(const HalfedgeMesh& mesh, std::vector<Index>& component) {
    // Union-find over the edges, a root always being the smallest vertex of its set, so
    // that numbering the roots in vertex order numbers the components by their first
    // vertex. Linear in practice; reads the edges in storage order.
    std::vector<Index> parent(mesh.vertices_size());
    for (Index v = 0; v < parent.size(); ++v) parent[v] = v;
    const std::vector<Vertex>& to = mesh.halfedge_to_array();  // edge e: halfedges 2e, 2e+1
    for (Edge e : mesh.edges()) {
        Index a = find_root(parent, to[2 * std::size_t(e.idx())].idx());
        Index b = find_root(parent, to[2 * std::size_t(e.idx()) + 1].idx());
        if (a == b) continue;
        if (a > b) std::swap(a, b);
        parent[b] = a;
    }
    component.assign(mesh.vertices_size(), kInvalidIndex);
    Index n = 0;
    for (Vertex v : mesh.vertices()) {
        const Index root = find_root(parent, v.idx());
        component[v.idx()] = root == v.idx() ? n++ : component[root];
    }
    return n;
}

MeshStats compute_stats(const HalfedgeMesh& mesh, std::vector<Index>* component_of_vertex) {
    MeshStats s;
    s.vertices = mesh.n_vertices();
    s.edges = mesh.n_edges();
    s.faces = mesh.n_faces();
    // The isolated vertices and the bounding box: one pass over the vertices in fixed blocks
    // on every thread (a count and a min/max: the same for any order).
    const std::vector<Point>& x = mesh.positions();
    const std::vector<Halfedge>& vh = mesh.vertex_halfedge_array();
    const bool garbage = mesh.has_garbage();
    struct VertexPart {
        std::size_t isolated = 0;
        BoundingBox box;
    };
    const VertexPart vp = parallel_reduce(
        0, x.size(), VertexPart{},
        [&](std::size_t begin, std::size_t end) {
            VertexPart part;
            for (std::size_t v = begin; v < end; ++v) {
                if (garbage && mesh.is_deleted(Vertex(Index(v)))) continue;
                if (!vh[v].is_valid()) ++part.isolated;
                part.box.extend(x[v]);
            }
            return part;
        },
        [](VertexPart a, const VertexPart& b) {
            a.isolated += b.isolated;
            if (!b.box.empty) {
                a.box.extend(b.box.min);
                a.box.extend(b.box.max);
            }
            return a;
        });
    s.isolated_vertices = vp.isolated;
    s.bbox = vp.box;
    s.boundary_loops = count_boundary_loops(mesh);
    std::vector<Index> component;
    s.components = label_components(mesh, component) - s.isolated_vertices;
    if (component_of_vertex) *component_of_vertex = std::move(component);
    s.euler = (long long)s.vertices - (long long)s.edges + (long long)s.faces;
    const long long chi_surface = s.euler - (long long)s.isolated_vertices;
    s.genus = (2 * (long long)s.components - chi_surface - (long long)s.boundary_loops) / 2;
    // Area and volume in one pass over the faces (the volume only for a closed mesh). Closed:
    // faces and no boundary loop, which is no boundary halfedge (is_closed(), without its scan).
    const bool closed = s.faces > 0 && s.boundary_loops == 0;
    const AreaVolume sums = area_and_volume(mesh, true, closed);
    s.area = sums.area;
    if (closed) s.volume = sums.volume;
    return s;
}

}  // namespace trilab
