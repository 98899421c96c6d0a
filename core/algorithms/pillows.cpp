#include "core/algorithms/pillows.h"

#include <string>

#include "core/errors.h"
#include "core/mesh_builder.h"

namespace trilab {

std::vector<Face> pillow_faces(const HalfedgeMesh& mesh) {
    std::vector<Face> out;
    for (Face f : mesh.faces()) {
        // No two edges join the same two vertices, so two faces share their three vertices
        // exactly when they share their three edges.
        const Halfedge h0 = mesh.halfedge(f), h1 = mesh.next(h0), h2 = mesh.next(h1);
        const Face g = mesh.face(HalfedgeMesh::twin(h0));
        if (g.is_valid() && g == mesh.face(HalfedgeMesh::twin(h1)) &&
            g == mesh.face(HalfedgeMesh::twin(h2)))
            out.push_back(f);
    }
    return out;
}

PillowSplit split_off_pillows(const HalfedgeMesh& mesh) {
    PillowSplit split;
    std::vector<std::uint8_t> in_pillow(mesh.faces_size(), 0);
    for (Face f : pillow_faces(mesh)) in_pillow[f.idx()] = 1;
    const PolygonSoup all = to_soup(mesh);
    // to_soup numbers the live faces in storage order.
    std::vector<std::uint8_t> face_pillow;
    for (Face f : mesh.faces()) face_pillow.push_back(in_pillow[f.idx()]);
    std::vector<std::uint8_t> vertex_pillow(all.positions.size(), 0);
    for (std::size_t f = 0; f < all.n_faces(); ++f)
        if (face_pillow[f])
            for (std::size_t c = all.face_offsets[f]; c < all.face_offsets[f + 1]; ++c)
                vertex_pillow[all.corners[c]] = 1;
    PolygonSoup parts[2];  // 0: rest, 1: pillows
    std::vector<Index> index(all.positions.size());
    for (std::size_t v = 0; v < all.positions.size(); ++v) {
        PolygonSoup& s = parts[vertex_pillow[v]];
        index[v] = Index(s.positions.size());
        s.positions.push_back(all.positions[v]);
        if (!all.normals.empty()) s.normals.push_back(all.normals[v]);
        if (!all.colors.empty()) s.colors.push_back(all.colors[v]);
        if (!all.texcoords.empty()) s.texcoords.push_back(all.texcoords[v]);
    }
    for (std::size_t f = 0; f < all.n_faces(); ++f) {
        PolygonSoup& s = parts[face_pillow[f]];
        for (std::size_t c = all.face_offsets[f]; c < all.face_offsets[f + 1]; ++c) {
            s.corners.push_back(index[all.corners[c]]);
            if (!all.corner_texcoords.empty())
                s.corner_texcoords.push_back(all.corner_texcoords[c]);
        }
        s.face_offsets.push_back(s.corners.size());
        split.count += face_pillow[f];
    }
    split.count /= 2;
    LoadReport unused;
    split.rest = build_mesh(parts[0], unused);
    split.pillows = build_mesh(parts[1], unused);
    return split;
}

Index append_mesh(HalfedgeMesh& mesh, const HalfedgeMesh& part) {
    if (part.has_garbage()) throw InvalidArgument("append_mesh: collect the part's garbage first");
    const Index v0 = Index(mesh.vertices_size());
    const Index h0 = Index(mesh.halfedges_size());
    const Index f0 = Index(mesh.faces_size());
    for (Vertex v : part.vertices()) mesh.add_vertex(part.position(v));
    for (Edge e : part.edges())
        mesh.new_edge(Vertex(v0 + part.vertex(e, 1).idx()), Vertex(v0 + part.vertex(e, 0).idx()));
    for (std::size_t f = 0; f < part.faces_size(); ++f) mesh.new_face();
    for (Halfedge h : part.halfedges()) {
        const Halfedge g(h0 + h.idx());
        mesh.set_next(g, Halfedge(h0 + part.next(h).idx()));
        const Face f = part.face(h);
        mesh.set_face(g, f.is_valid() ? Face(f0 + f.idx()) : Face());
    }
    for (Vertex v : part.vertices()) {
        const Halfedge h = part.halfedge(v);
        mesh.set_halfedge(Vertex(v0 + v.idx()), h.is_valid() ? Halfedge(h0 + h.idx()) : Halfedge());
    }
    for (Face f : part.faces())
        mesh.set_halfedge(Face(f0 + f.idx()), Halfedge(h0 + part.halfedge(f).idx()));
    auto vuv = mesh.get_vertex_property<TexCoord>("v:texcoord");
    const auto part_vuv = part.get_vertex_property<TexCoord>("v:texcoord");
    if (vuv && part_vuv)
        for (Vertex v : part.vertices()) vuv[Vertex(v0 + v.idx())] = part_vuv[v];
    auto huv = mesh.get_halfedge_property<TexCoord>("h:texcoord");
    const auto part_huv = part.get_halfedge_property<TexCoord>("h:texcoord");
    if (huv && part_huv)
        for (Halfedge h : part.halfedges()) huv[Halfedge(h0 + h.idx())] = part_huv[h];
    return v0;
}

std::string pillow_note(std::size_t n) {
    return std::to_string(n) + (n == 1 ? " component" : " components") +
           " left as it is: two triangles on the same three vertices";
}

}  // namespace trilab
