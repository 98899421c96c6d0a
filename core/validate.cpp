#include "core/validate.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "core/prefetch.h"

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

constexpr std::size_t kAhead = 8;
}  // namespace

ValidationResult validate(const HalfedgeMesh& m) {
    auto fail = [](std::string msg) { return ValidationResult{false, std::move(msg)}; };
    const std::size_t nv = m.vertices_size(), nh = m.halfedges_size(), nf = m.faces_size();
    if (nh != 2 * m.edges_size()) return fail("halfedge storage is not twice the edge storage");
    // The built-in arrays, read directly.
    const std::vector<Vertex>& to = m.get_halfedge_property<Vertex>("h:to").vector();
    const std::vector<Halfedge>& next = m.get_halfedge_property<Halfedge>("h:next").vector();
    const std::vector<Halfedge>& prev = m.get_halfedge_property<Halfedge>("h:prev").vector();
    const std::vector<Face>& face = m.get_halfedge_property<Face>("h:face").vector();
    const std::vector<Halfedge>& fhalfedge = m.get_face_property<Halfedge>("f:halfedge").vector();
    const bool garbage = m.has_garbage();
    auto live_v = [&](Vertex v) { return v.idx() < nv && !(garbage && m.is_deleted(v)); };
    auto live_h = [&](Halfedge h) { return h.idx() < nh && !(garbage && m.is_deleted(h)); };
    auto live_f = [&](Face f) { return f.idx() < nf && !(garbage && m.is_deleted(f)); };

    // Halfedges: references in range and live, prev(next(h)) == h, no self-loop edges.
    // With next and prev mapping live halfedges to live ones, prev(next(h)) == h for every
    // h makes next a bijection and prev its inverse, so next(prev(h)) == h needs no check.
    for (std::size_t i = 0; i < nh; ++i) {
        if (garbage && m.is_deleted(Edge(Index(i >> 1)))) continue;
        if (i + kAhead < nh) {
            const Index a = next[i + kAhead].idx();
            if (a < nh) {
                prefetch(&prev[a]);
                prefetch(&to[a ^ 1]);
                prefetch(&face[a]);
            }
        }
        const Halfedge h{Index(i)};
        const Vertex t = to[i];
        const Halfedge n = next[i], p = prev[i];
        const Face f = face[i];
        if (!live_v(t)) return fail(hs(h) + " points to a missing or deleted vertex");
        if (!live_h(n)) return fail(hs(h) + " has a missing or deleted next");
        if (!live_h(p)) return fail(hs(h) + " has a missing or deleted prev");
        if (prev[n.idx()] != h) return fail("prev(next(" + hs(h) + ")) is not itself");
        if (to[n.idx() ^ 1] != t) return fail("next of " + hs(h) + " does not start where it ends");
        if (face[n.idx()] != f) return fail(hs(h) + " and its next lie in different faces");
        if (f.is_valid() && !live_f(f)) return fail(hs(h) + " lies in a missing or deleted face");
        if ((i & 1) && to[i] == to[i ^ 1])
            return fail("edge " + std::to_string(i >> 1) + " joins a vertex to itself");
    }

    // Faces: triangles whose halfedges point back to them.
    for (std::size_t i = 0; i < nf; ++i) {
        const Face f{Index(i)};
        if (garbage && m.is_deleted(f)) continue;
        if (i + kAhead < nf) {
            const Index a = fhalfedge[i + kAhead].idx();
            if (a < nh) {
                prefetch(&face[a]);
                prefetch(&next[a]);
                prefetch(&to[a]);
            }
        }
        const Halfedge h = fhalfedge[i];
        if (!live_h(h)) return fail(fs(f) + " has a missing or deleted halfedge");
        if (face[h.idx()] != f) return fail(fs(f) + "'s halfedge belongs to another face");
        const Halfedge h1 = next[h.idx()], h2 = next[h1.idx()];
        if (next[h2.idx()] != h) return fail(fs(f) + " is not a triangle");
        const Vertex c0 = to[h.idx()], c1 = to[h1.idx()], c2 = to[h2.idx()];
        if (c0 == c1 || c1 == c2 || c0 == c2) return fail(fs(f) + " has a repeated corner");
    }

    // Vertices: outgoing halfedge, boundary preference, a single fan holding every outgoing
    // halfedge, no two edges to the same neighbour. (Rotation never leaves a vertex: that
    // follows from the halfedge checks above.)
    // Outgoing halfedges and outgoing boundary halfedges per vertex, counted here so that
    // the walks below read only prev and to.
    std::vector<unsigned> out_degree(nv, 0), out_boundary(nv, 0);
    for (std::size_t i = 0; i < nh; ++i) {
        if (garbage && m.is_deleted(Edge(Index(i >> 1)))) continue;
        const Index from = to[i ^ 1].idx();
        ++out_degree[from];
        if (!face[i].is_valid()) ++out_boundary[from];
    }
    // A fan is walked by a chain of dependent reads, so kLanes vertices are walked side by
    // side, one step each in turn, and each step prefetches what the lane reads next. A lane
    // keeps the neighbours it met: up to kShort in place (a duplicate is found by a scan),
    // more in a list sorted at the end.
    constexpr std::size_t kLanes = 8, kShort = 16;
    struct Lane {
        Vertex v;
        Halfedge h, x;
        unsigned count = 0, degree = 0;
        std::array<Index, kShort> near{};
        std::vector<Index> many;
    };
    std::array<Lane, kLanes> lanes;
    std::size_t next_vertex = 0;
    std::string error;
    // Starts the lane on the next vertex that has edges (false: an error, in `error`). That
    // its halfedge is outgoing is checked at the first step, when its line has arrived.
    auto start = [&](Lane& lane) {
        lane.v = Vertex();
        while (next_vertex < nv) {
            const Vertex v(Index(next_vertex++));
            if (garbage && m.is_deleted(v)) continue;
            const Halfedge h = m.halfedge(v);
            if (!h.is_valid()) {
                if (out_degree[v.idx()] == 0) continue;
                error = vs(v) + " has edges but no outgoing halfedge";
                return false;
            }
            if (!live_h(h)) {
                error = vs(v) + " has a missing or deleted halfedge";
                return false;
            }
            lane.v = v;
            lane.h = lane.x = h;
            lane.count = 0;
            lane.degree = out_degree[v.idx()];
            lane.many.clear();
            prefetch(&prev[h.idx()]);
            prefetch(&to[h.idx()]);
            return true;
        }
        return true;
    };
    // The checks once the lane's fan is walked (false: an error, in `error`).
    auto finish = [&](Lane& lane) {
        const Vertex v = lane.v;
        if (lane.count != lane.degree)
            error = vs(v) + " is non-manifold: its edges form more than one fan";
        else if (out_boundary[v.idx()] > 1)
            error = vs(v) + " is non-manifold: it lies on the boundary more than once";
        else if (out_boundary[v.idx()] == 1 && face[lane.h.idx()].is_valid())
            error = vs(v) + " is on the boundary but its halfedge is not";
        if (!error.empty()) return false;
        if (lane.count > kShort) {
            std::vector<Index>& seen = lane.many;
            seen.insert(seen.end(), lane.near.begin(), lane.near.end());
            std::sort(seen.begin(), seen.end());
            if (std::adjacent_find(seen.begin(), seen.end()) != seen.end()) {
                error = vs(v) + " has two edges to the same neighbour";
                return false;
            }
        }
        return true;
    };
    for (Lane& lane : lanes)
        if (!start(lane)) return fail(error);
    for (bool busy = true; busy;) {
        busy = false;
        for (Lane& lane : lanes) {
            if (!lane.v.is_valid()) continue;
            busy = true;
            const Index x = lane.x.idx();
            if (lane.count == 0 && to[x ^ 1] != lane.v)
                return fail(vs(lane.v) + "'s halfedge is not outgoing");
            const Index w = to[x].idx();
            if (lane.count < kShort) {
                for (unsigned i = 0; i < lane.count; ++i)
                    if (lane.near[i] == w)
                        return fail(vs(lane.v) + " has two edges to the same neighbour");
                lane.near[lane.count] = w;
            } else {
                lane.many.push_back(w);
            }
            if (++lane.count > lane.degree)
                return fail("rotating around " + vs(lane.v) + " does not come back");
            lane.x = Halfedge(prev[x].idx() ^ 1);  // counter-clockwise
            if (lane.x != lane.h) {
                prefetch(&prev[lane.x.idx()]);
                prefetch(&to[lane.x.idx()]);
            } else if (!finish(lane) || !start(lane)) {
                return fail(error);
            }
        }
    }
    return {};
}

}  // namespace trilab
