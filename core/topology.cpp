// Topological operators of HalfedgeMesh: edge collapse, edge flip, edge split, face split,
// orientation reversal.
// Each keeps every invariant listed in halfedge_mesh.h; the legality checks say when.
#include <algorithm>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

#include "core/errors.h"
#include "core/halfedge_mesh.h"

namespace trilab {

namespace {
// The corner opposite to h in its face (invalid for a boundary halfedge).
Vertex opposite_vertex(const HalfedgeMesh& m, Halfedge h) {
    return m.is_boundary(h) ? Vertex() : m.to_vertex(m.next(h));
}
// Whether the triangle {a, b, c} exists (in either orientation).
bool has_triangle(const HalfedgeMesh& m, Vertex a, Vertex b, Vertex c) {
    Halfedge h = m.find_halfedge(a, b);
    if (!h.is_valid()) return false;
    return opposite_vertex(m, h) == c || opposite_vertex(m, HalfedgeMesh::twin(h)) == c;
}
}  // namespace

bool HalfedgeMesh::is_collapse_ok(Halfedge h) const {
    if (!is_valid(h) || is_deleted(h)) return false;
    const Halfedge o = twin(h);
    const Vertex v0 = from_vertex(h), v1 = to_vertex(h);
    Vertex vl, vr;
    // A triangle whose two other edges are both on the boundary would vanish into a dangling
    // edge.
    if (!is_boundary(h)) {
        const Halfedge h1 = next(h), h2 = next(h1);
        vl = to_vertex(h1);
        if (is_boundary(twin(h1)) && is_boundary(twin(h2))) return false;
    }
    if (!is_boundary(o)) {
        const Halfedge o1 = next(o), o2 = next(o1);
        vr = to_vertex(o1);
        if (is_boundary(twin(o1)) && is_boundary(twin(o2))) return false;
    }
    if (vl == vr) return false;
    // An interior edge between two boundary vertices would pinch the surface.
    if (is_boundary(v0) && is_boundary(v1) && !is_boundary(h) && !is_boundary(o)) return false;
    // Link condition on vertices: the only common neighbours may be vl and vr. v1's ring is
    // gathered once (a small local array; the nested walk for very high valences).
    constexpr unsigned kRing = 64;
    Vertex ring1[kRing];
    unsigned n1 = 0;
    for (Vertex b : vertices_around(v1)) {
        if (n1 == kRing) {
            n1 = kRing + 1;
            break;
        }
        ring1[n1++] = b;
    }
    for (Vertex a : vertices_around(v0)) {
        if (a == v1 || a == vl || a == vr) continue;
        if (n1 <= kRing) {
            for (unsigned i = 0; i < n1; ++i)
                if (ring1[i] == a) return false;
        } else {
            for (Vertex b : vertices_around(v1))
                if (a == b) return false;
        }
    }
    // Link condition on edges: the triangles {v0, vl, vr} and {v1, vl, vr} must not both
    // exist (a tetrahedron would collapse into a doubly covered triangle).
    if (vl.is_valid() && vr.is_valid() && has_triangle(*this, v0, vl, vr) &&
        has_triangle(*this, v1, vl, vr))
        return false;
    return true;
}

void HalfedgeMesh::collapse(Halfedge h) {
    if (!is_collapse_ok(h))
        throw TopologyError("collapse: halfedge " + std::to_string(h.idx()) +
                            " fails the link condition");
    collapse_unchecked(h);
}

void HalfedgeMesh::collapse_unchecked(Halfedge h) {
    const Halfedge o = twin(h);
    const Vertex v0 = from_vertex(h), v1 = to_vertex(h);
    const Halfedge hn = next(h), hp = prev(h), on = next(o), op = prev(o);
    const Face fh = face(h), fo = face(o);
    // v1 ends on the boundary exactly when one of the two ends was on it; only then can its
    // outgoing halfedge need adjusting (the ring walks are the costly part of a collapse).
    const bool boundary = is_boundary(v0) || is_boundary(v1);

    // Every halfedge that pointed to v0 now points to v1.
    for (Halfedge x : halfedges_around(v0)) set_to_vertex(twin(x), v1);

    // Unlink h and o from their loops.
    set_next(hp, hn);
    set_next(op, on);
    if (fh.is_valid()) set_halfedge(fh, hn);
    if (fo.is_valid()) set_halfedge(fo, on);
    if (halfedge(v1) == o) set_halfedge(v1, hn);
    if (boundary) adjust_outgoing_halfedge(v1);

    mark_deleted(v0);
    mark_deleted(edge(h));

    // The faces at the edge have become loops of two halfedges: remove them.
    if (fh.is_valid() && next(next(hn)) == hn) remove_loop(hn);
    if (fo.is_valid() && next(next(on)) == on) remove_loop(on);
}

// Removes a face that has degenerated into a loop of two halfedges h0 (v1 -> v0) and
// h1 (v0 -> v1): h1 takes the place of twin(h0), and h0's edge and the face are deleted.
void HalfedgeMesh::remove_loop(Halfedge h0) {
    const Halfedge h1 = next(h0), o0 = twin(h0), o1 = twin(h1);
    const Vertex v0 = to_vertex(h0), v1 = to_vertex(h1);
    const Face fh = face(h0), fo = face(o0);
    // Removing the loop changes neither vertex's boundary status (halfedge(v) is up to date
    // here): an interior vertex needs no search for a boundary halfedge.
    const bool boundary0 = is_boundary(v0), boundary1 = is_boundary(v1);

    set_next(prev(o0), h1);
    set_next(h1, next(o0));
    set_face(h1, fo);
    set_halfedge(v0, h1);
    if (boundary0) adjust_outgoing_halfedge(v0);
    set_halfedge(v1, o1);
    if (boundary1) adjust_outgoing_halfedge(v1);
    if (fo.is_valid() && halfedge(fo) == o0) set_halfedge(fo, h1);

    mark_deleted(fh);
    mark_deleted(edge(h0));
}

bool HalfedgeMesh::is_flip_ok(Edge e) const {
    if (!is_valid(e) || is_deleted(e) || is_boundary(e)) return false;
    const Halfedge h = halfedge(e, 0), o = halfedge(e, 1);
    const Vertex c = to_vertex(next(h)), d = to_vertex(next(o));
    if (c == d) return false;
    return !find_halfedge(c, d).is_valid();
}

void HalfedgeMesh::flip(Edge e) {
    if (!is_flip_ok(e))
        throw TopologyError("flip: edge " + std::to_string(e.idx()) +
                            " is on the boundary or its flipped edge exists already");
    // Before: h = a->b in (a, b, c), o = b->a in (b, a, d). After: h = d->c, o = c->d.
    const Halfedge h = halfedge(e, 0), o = halfedge(e, 1);
    const Halfedge h1 = next(h), h2 = next(h1), o1 = next(o), o2 = next(o1);
    const Vertex a = from_vertex(h), b = to_vertex(h);
    const Vertex c = to_vertex(h1), d = to_vertex(o1);
    const Face fh = face(h), fo = face(o);

    if (halfedge(a) == h) set_halfedge(a, o1);
    if (halfedge(b) == o) set_halfedge(b, h1);

    set_to_vertex(h, c);
    set_to_vertex(o, d);
    set_next(h, h2);
    set_next(h2, o1);
    set_next(o1, h);
    set_next(o, o2);
    set_next(o2, h1);
    set_next(h1, o);
    set_face(o1, fh);
    set_face(h1, fo);
    set_halfedge(fh, h);
    set_halfedge(fo, o);
}

Vertex HalfedgeMesh::split(Edge e, const Point& p) {
    if (!is_valid(e) || is_deleted(e))
        throw TopologyError("split: edge " + std::to_string(e.idx()) + " does not exist");
    // h0 = a->b becomes a->v, the new h1 = v->b; o0 = b->a becomes v->a, the new o1 = b->v.
    const Halfedge h0 = halfedge(e, 0), o0 = halfedge(e, 1);
    const Vertex b = to_vertex(h0);
    const Halfedge hn = next(h0), op = prev(o0), on = next(o0);
    const Face fh = face(h0), fo = face(o0);

    const Vertex v = add_vertex(p);
    const Halfedge h1 = new_edge(v, b), o1 = twin(h1);
    eprops_.copy_element(e.idx(), edge(h1).idx());  // both halves keep e's attributes
    set_to_vertex(h0, v);
    set_next(h1, hn);
    set_next(h0, h1);
    set_face(h1, fh);
    set_next(op, o1);
    set_next(o1, o0);
    set_face(o1, fo);
    set_halfedge(v, h1);
    if (halfedge(b) == o0) set_halfedge(b, o1);

    if (fh.is_valid()) {
        // Loop a->v (h0), v->b (h1), b->c (hn), c->a (hc): cut along v->c.
        const Halfedge hc = next(hn);
        const Vertex c = to_vertex(hn);
        const Halfedge x = new_edge(v, c), y = twin(x);
        const Face f2 = new_face();
        set_next(h0, x);
        set_next(x, hc);
        set_face(x, fh);
        set_halfedge(fh, h0);
        set_next(h1, hn);
        set_next(hn, y);
        set_next(y, h1);
        set_face(h1, f2);
        set_face(hn, f2);
        set_face(y, f2);
        set_halfedge(f2, h1);
    }
    if (fo.is_valid()) {
        // Loop b->v (o1), v->a (o0), a->d (on), d->b (op): cut along v->d.
        const Vertex d = to_vertex(on);
        const Halfedge x = new_edge(v, d), y = twin(x);
        const Face f3 = new_face();
        set_next(on, y);
        set_next(y, o0);
        set_face(y, fo);
        set_halfedge(fo, o0);
        set_next(o1, x);
        set_next(x, op);
        set_next(op, o1);
        set_face(o1, f3);
        set_face(x, f3);
        set_face(op, f3);
        set_halfedge(f3, o1);
    }
    adjust_outgoing_halfedge(v);
    return v;
}

Vertex HalfedgeMesh::split(Face f, const Point& p) {
    if (!is_valid(f) || is_deleted(f))
        throw TopologyError("split: face " + std::to_string(f.idx()) + " does not exist");
    // Corners: h0 = c->a, h1 = a->b, h2 = b->c; spokes x* = v->*, y* = *->v.
    const Halfedge h0 = halfedge(f), h1 = next(h0), h2 = next(h1);
    const Vertex a = to_vertex(h0), b = to_vertex(h1), c = to_vertex(h2);
    const Vertex v = add_vertex(p);
    const Halfedge xa = new_edge(v, a), ya = twin(xa);
    const Halfedge xb = new_edge(v, b), yb = twin(xb);
    const Halfedge xc = new_edge(v, c), yc = twin(xc);
    const Face f1 = new_face(), f2 = new_face();

    set_next(h0, ya);
    set_next(ya, xc);
    set_next(xc, h0);
    set_next(h1, yb);
    set_next(yb, xa);
    set_next(xa, h1);
    set_next(h2, yc);
    set_next(yc, xb);
    set_next(xb, h2);
    set_face(ya, f);
    set_face(xc, f);
    set_face(h1, f1);
    set_face(yb, f1);
    set_face(xa, f1);
    set_face(h2, f2);
    set_face(yc, f2);
    set_face(xb, f2);
    set_halfedge(f, h0);
    set_halfedge(f1, h1);
    set_halfedge(f2, h2);
    set_halfedge(v, xa);
    return v;
}

void HalfedgeMesh::reverse_orientation() {
    reverse_edges(nullptr);
}

void HalfedgeMesh::reverse_orientation(const std::vector<std::uint8_t>& edge_mask) {
    if (edge_mask.size() != edges_size())
        throw InvalidArgument("reverse_orientation: expected one mask entry per edge (" +
                              std::to_string(edges_size()) + "), got " +
                              std::to_string(edge_mask.size()));
    reverse_edges(&edge_mask);
}

namespace {
// Rewrites edge (h, t = h + 1) reversed, from its halfedges' old next and prev (see
// reverse_edges()): its new values depend on these four only.
inline void reverse_edge_rows(std::vector<Halfedge>& next, std::vector<Halfedge>& prev,
                              std::vector<Face>& face, std::size_t h, Halfedge next_h,
                              Halfedge prev_h, Halfedge next_t, Halfedge prev_t) {
    const std::size_t t = h + 1;
    next[h] = HalfedgeMesh::twin(prev_t);
    prev[h] = HalfedgeMesh::twin(next_t);
    next[t] = HalfedgeMesh::twin(prev_h);
    prev[t] = HalfedgeMesh::twin(next_h);
    std::swap(face[h], face[t]);
}
}  // namespace

template <class Reversed>
std::size_t HalfedgeMesh::finish_reversal(Reversed reversed, std::vector<Vertex>* listed) {
    // From the new values, since prev(twin(h)) = twin(next'(h)): halfedge(v) becomes
    // twin(prev(halfedge(v))) = next'(twin(halfedge(v))), which keeps a boundary vertex's
    // halfedge on the boundary; halfedge(f) becomes twin(halfedge(f)); and the corner
    // (to_vertex(g), face'(g)) was the old corner of prev(twin(g)) = twin(next'(g)), so
    // halfedge attributes are gathered from there.
    const std::vector<Halfedge>& next = std::as_const(hnext_).vector();
    std::vector<Halfedge>& vertex_halfedge = vhalfedge_.vector();
    if (listed) listed->reserve(vertices_size());  // only what is filled is touched
    for (Vertex v : vertices()) {
        const Halfedge h = vertex_halfedge[v.idx()];
        if (!h.is_valid() || !reversed(h.idx() >> 1)) continue;
        vertex_halfedge[v.idx()] = next[h.idx() ^ 1];
        if (listed) listed->push_back(v);
    }
    std::vector<Halfedge>& face_halfedge = fhalfedge_.vector();
    std::size_t faces_reversed = 0;
    for (Face f : faces()) {
        const Halfedge h = face_halfedge[f.idx()];
        if (!reversed(h.idx() >> 1)) continue;
        face_halfedge[f.idx()] = twin(h);
        ++faces_reversed;
    }
    if (hprops_.n_properties() > 4) {  // attributes beyond the connectivity
        std::vector<Index> corner_source(halfedges_size());
        for (std::size_t h = 0; h < corner_source.size(); ++h)
            corner_source[h] = reversed(h >> 1) ? twin(next[h]).idx() : Index(h);
        const BasePropertyArray* connectivity[] = {hto_.array(), hnext_.array(), hprev_.array(),
                                                   hface_.array()};
        hprops_.gather_except(corner_source, [&](const BasePropertyArray* a) {
            return std::find(std::begin(connectivity), std::end(connectivity), a) !=
                   std::end(connectivity);
        });
    }
    return faces_reversed;
}

void HalfedgeMesh::reverse_edges(const std::vector<std::uint8_t>* edge_mask) {
    // Halfedge h keeps its direction (to_vertex) and moves to the other side of its edge:
    //   face'(h) = face(twin(h)),  next'(h) = twin(prev(twin(h))),  prev'(h) = twin(next(twin(h))).
    // Face f then consists of the twins of its old halfedges, in reverse order; a boundary loop
    // likewise. The new values of an edge's two halfedges depend on the old values of those two
    // only, so each edge is rewritten in place; finish_reversal() then sets what depends on
    // more than one edge.
    const std::size_t ne = edges_size();
    const bool garbage = has_garbage();
    std::vector<Halfedge>& next = hnext_.vector();
    std::vector<Halfedge>& prev = hprev_.vector();
    std::vector<Face>& face = hface_.vector();
    // Captures by value, as the flood's: finish_reversal() keeps its own copy in registers
    // across the vertex list's push_back.
    const auto reversed = [this, garbage,
                           mask = edge_mask ? edge_mask->data() : nullptr](std::size_t e) {
        return (!mask || mask[e] != 0) && !(garbage && is_deleted(Edge(Index(e))));
    };
    for (std::size_t e = 0; e < ne; ++e) {
        if (!reversed(e)) continue;
        const std::size_t h = 2 * e, t = h + 1;
        reverse_edge_rows(next, prev, face, h, next[h], prev[h], next[t], prev[t]);
    }
    finish_reversal(reversed, nullptr);
}

HalfedgeMesh::ReversedPart HalfedgeMesh::reverse_orientation_from(const std::vector<Vertex>& seeds,
                                                                  bool list_vertices) {
    // A breadth-first flood over the edges. An edge is rewritten as reverse_edges() rewrites
    // it when it is taken from the queue; first the edges of next(h) and next(twin(h)) are
    // queued, read from its own values, which no other edge's rewrite touches. Following next
    // goes around every face and boundary loop the edge borders, and both halves of each edge
    // are followed, so the flood reaches the whole component. A queue rather than a stack:
    // the edge taken next was queued long before, so consecutive edges do not wait on each
    // other's loads. The vertex and face halfedges and the corner attributes are set after the
    // flood, in storage order, by finish_reversal(). (Setting them in the flood costs more:
    // random reads, and a vertex's new halfedge lies on an edge still to come.)
    for (Vertex v : seeds)
        if (!v.is_valid() || v.idx() >= vertices_size())
            throw InvalidArgument("reverse_orientation_from: seed vertex " +
                                  std::to_string(v.idx()) + " is out of range (" +
                                  std::to_string(vertices_size()) + " vertices)");
    ReversedPart part;
    // A byte per edge, not a bit: two pushes into one word would wait on each other.
    std::vector<std::uint8_t> reached(edges_size(), 0);
    // The queue is a ring that holds the flood's front (about the square root of a
    // component's edges on a surface), doubled when it could fill up: from 64 entries, so
    // that every flood beyond the smallest meshes goes through the doubling.
    std::vector<Index> queue(std::size_t(1) << 6);
    std::size_t mask = queue.size() - 1, head = 0, tail = 0;
    // Writes unconditionally and keeps the entry only for an unreached edge: no branch on the
    // mesh in the flood.
    const auto push = [&](std::size_t e) {
        queue[tail & mask] = Index(e);
        tail += reached[e] ^ 1u;
        reached[e] = 1;
    };
    std::vector<Halfedge>& next = hnext_.vector();
    std::vector<Halfedge>& prev = hprev_.vector();
    std::vector<Face>& face = hface_.vector();
    for (Vertex seed : seeds) {
        const Halfedge start = halfedge(seed);
        if (is_deleted(seed) || !start.is_valid() || reached[start.idx() >> 1]) continue;
        ++part.components;
        push(start.idx() >> 1);
        while (head != tail) {
            if (tail - head + 3 > queue.size()) {  // room for the two pushes below
                std::vector<Index> larger(2 * queue.size());
                for (std::size_t k = head; k != tail; ++k) larger[k - head] = queue[k & mask];
                tail -= head;
                head = 0;
                queue.swap(larger);
                mask = queue.size() - 1;
            }
            {  // the edge queued 32 places later: its halfedges' rows, ahead of their use
                const std::size_t ahead = 2 * std::size_t(queue[(head + 32) & mask]);
                __builtin_prefetch(&next[ahead], 1);
                __builtin_prefetch(&prev[ahead], 1);
                __builtin_prefetch(&face[ahead], 1);
            }
            const std::size_t h = 2 * std::size_t(queue[head++ & mask]), t = h + 1;
            const Halfedge next_h = next[h], prev_h = prev[h], next_t = next[t], prev_t = prev[t];
            push(next_h.idx() >> 1);
            push(next_t.idx() >> 1);
            reverse_edge_rows(next, prev, face, h, next_h, prev_h, next_t, prev_t);
        }
    }
    part.faces = finish_reversal([r = reached.data()](std::size_t e) { return r[e] != 0; },
                                 list_vertices ? &part.vertices : nullptr);
    return part;
}

}  // namespace trilab
