#include "core/mesh_stats.h"

#include <vector>

namespace trilab {

std::size_t count_boundary_loops(const HalfedgeMesh& mesh) {
    std::vector<std::uint8_t> seen(mesh.halfedges_size(), 0);
    std::size_t loops = 0;
    for (Halfedge h : mesh.halfedges()) {
        if (seen[h.idx()] || !mesh.is_boundary(h)) continue;
        ++loops;
        Halfedge x = h;
        do {
            seen[x.idx()] = 1;
            x = mesh.next(x);
        } while (x != h && !seen[x.idx()]);
    }
    return loops;
}

std::size_t label_components(const HalfedgeMesh& mesh, std::vector<Index>& component) {
    component.assign(mesh.vertices_size(), kInvalidIndex);
    std::vector<Vertex> stack;
    Index n = 0;
    for (Vertex seed : mesh.vertices()) {
        if (component[seed.idx()] != kInvalidIndex) continue;
        component[seed.idx()] = n;
        stack.push_back(seed);
        while (!stack.empty()) {
            const Vertex v = stack.back();
            stack.pop_back();
            for (Vertex w : mesh.vertices_around(v)) {
                if (component[w.idx()] != kInvalidIndex) continue;
                component[w.idx()] = n;
                stack.push_back(w);
            }
        }
        ++n;
    }
    return n;
}

MeshStats compute_stats(const HalfedgeMesh& mesh) {
    MeshStats s;
    s.vertices = mesh.n_vertices();
    s.edges = mesh.n_edges();
    s.faces = mesh.n_faces();
    for (Vertex v : mesh.vertices())
        if (mesh.is_isolated(v)) ++s.isolated_vertices;
    s.boundary_loops = count_boundary_loops(mesh);
    std::vector<Index> component;
    s.components = label_components(mesh, component) - s.isolated_vertices;
    s.euler = (long long)s.vertices - (long long)s.edges + (long long)s.faces;
    const long long chi_surface = s.euler - (long long)s.isolated_vertices;
    s.genus = (2 * (long long)s.components - chi_surface - (long long)s.boundary_loops) / 2;
    s.bbox = bounding_box(mesh);
    s.area = surface_area(mesh);
    if (is_closed(mesh)) s.volume = volume(mesh);
    return s;
}

}  // namespace trilab
