#include "core/validate.h"

#include <algorithm>
#include <cmath>
#include <unordered_set>
#include <vector>

namespace trilab {

namespace {
std::string hs(Halfedge h) {
    return "halfedge " + std::to_string(h.idx());
}
std::string vs(Vertex v) {
    return "vertex " + std::to_string(v.idx());
}
std::string fs(Face f) {
    return "face " + std::to_string(f.idx());
}
}  // namespace

ValidationResult validate(const HalfedgeMesh& m) {
    auto fail = [](std::string msg) { return ValidationResult{false, std::move(msg)}; };
    const std::size_t nv = m.vertices_size(), nh = m.halfedges_size(), nf = m.faces_size();
    if (nh != 2 * m.edges_size()) return fail("halfedge storage is not twice the edge storage");

    // Halfedges: references in range and live, next/prev inverse, no self-loop edges.
    for (Edge e : m.edges()) {
        for (unsigned i = 0; i < 2; ++i) {
            const Halfedge h = HalfedgeMesh::halfedge(e, i);
            const Vertex to = m.to_vertex(h);
            const Halfedge n = m.next(h), p = m.prev(h);
            const Face f = m.face(h);
            if (!to.is_valid() || to.idx() >= nv || m.is_deleted(to))
                return fail(hs(h) + " points to a missing or deleted vertex");
            if (!n.is_valid() || n.idx() >= nh || m.is_deleted(n))
                return fail(hs(h) + " has a missing or deleted next");
            if (!p.is_valid() || p.idx() >= nh || m.is_deleted(p))
                return fail(hs(h) + " has a missing or deleted prev");
            if (m.prev(n) != h) return fail("prev(next(" + hs(h) + ")) is not itself");
            if (m.next(p) != h) return fail("next(prev(" + hs(h) + ")) is not itself");
            if (m.from_vertex(n) != to)
                return fail("next of " + hs(h) + " does not start where it ends");
            if (m.face(n) != f) return fail(hs(h) + " and its next lie in different faces");
            if (f.is_valid() && (f.idx() >= nf || m.is_deleted(f)))
                return fail(hs(h) + " lies in a missing or deleted face");
        }
        if (m.vertex(e, 0) == m.vertex(e, 1))
            return fail("edge " + std::to_string(e.idx()) + " joins a vertex to itself");
    }

    // Faces: triangles whose halfedges point back to them.
    for (Face f : m.faces()) {
        const Halfedge h = m.halfedge(f);
        if (!h.is_valid() || h.idx() >= nh || m.is_deleted(h))
            return fail(fs(f) + " has a missing or deleted halfedge");
        if (m.face(h) != f) return fail(fs(f) + "'s halfedge belongs to another face");
        if (m.next(m.next(m.next(h))) != h) return fail(fs(f) + " is not a triangle");
        const auto c = m.face_vertices(f);
        if (c[0] == c[1] || c[1] == c[2] || c[0] == c[2])
            return fail(fs(f) + " has a repeated corner");
    }

    // Vertices: outgoing halfedge, boundary preference, a single fan holding every outgoing
    // halfedge, no two edges to the same neighbour.
    std::vector<unsigned> out_degree(nv, 0);
    for (Edge e : m.edges()) {
        ++out_degree[m.vertex(e, 0).idx()];
        ++out_degree[m.vertex(e, 1).idx()];
    }
    std::vector<Index> seen_neighbour;
    for (Vertex v : m.vertices()) {
        const Halfedge h = m.halfedge(v);
        if (!h.is_valid()) {
            if (out_degree[v.idx()] != 0)
                return fail(vs(v) + " has edges but no outgoing halfedge");
            continue;
        }
        if (h.idx() >= nh || m.is_deleted(h))
            return fail(vs(v) + " has a missing or deleted halfedge");
        if (m.from_vertex(h) != v) return fail(vs(v) + "'s halfedge is not outgoing");
        unsigned count = 0;
        unsigned n_boundary = 0;
        seen_neighbour.clear();
        Halfedge x = h;
        do {
            if (m.from_vertex(x) != v)
                return fail("rotating around " + vs(v) + " leaves the vertex");
            if (m.is_boundary(x)) ++n_boundary;
            seen_neighbour.push_back(m.to_vertex(x).idx());
            if (++count > out_degree[v.idx()])
                return fail("rotating around " + vs(v) + " does not come back");
            x = m.ccw_rotated(x);
        } while (x != h);
        if (count != out_degree[v.idx()])
            return fail(vs(v) + " is non-manifold: its edges form more than one fan");
        if (n_boundary > 1)
            return fail(vs(v) + " is non-manifold: it lies on the boundary more than once");
        if (n_boundary == 1 && !m.is_boundary(h))
            return fail(vs(v) + " is on the boundary but its halfedge is not");
        std::sort(seen_neighbour.begin(), seen_neighbour.end());
        if (std::adjacent_find(seen_neighbour.begin(), seen_neighbour.end()) !=
            seen_neighbour.end())
            return fail(vs(v) + " has two edges to the same neighbour");
    }
    return {};
}

}  // namespace trilab
