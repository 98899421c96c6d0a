#include "core/validate.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "core/prefetch.h"
#include "core/two_threads.h"

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

namespace {

// validate() in three stages, one method each: the halfedges, the faces, the vertices (their
// fans walked side by side). Each returns the first broken invariant ("" when none). A large
// mesh's stage runs as two halves on two threads, the stages one after the other (a stage
// reads only what the stages before it proved in range).
//
// The vertex stage first walks each vertex's fan and counts its boundary halfedges without
// knowing the vertex's degree (walk_fans): once the halfedges are proven, rotation around a
// vertex is a permutation of its outgoing halfedges, so every fan comes back, and the fans
// hold every outgoing halfedge exactly when their sizes sum to the number of live halfedges.
// When that sum is short, or a fan breaks a rule, the exact per-vertex walk (check_vertices,
// with the degrees counted first) runs to name the first broken vertex, as it always did.
class Validator {
public:
    explicit Validator(const HalfedgeMesh& m)
        : m_(m),
          nv_(m.vertices_size()),
          nh_(m.halfedges_size()),
          nf_(m.faces_size()),
          // The built-in arrays, read directly.
          to_(m.halfedge_to_array()),
          next_(m.halfedge_next_array()),
          prev_(m.halfedge_prev_array()),
          face_(m.halfedge_face_array()),
          fhalfedge_(m.face_halfedge_array()),
          garbage_(m.has_garbage()) {}

    /// The halfedges in [begin, end); `live` gets how many of them are live.
    std::string check_halfedges(std::size_t begin, std::size_t end, std::size_t& live) const;
    /// The faces in [begin, end).
    std::string check_faces(std::size_t begin, std::size_t end) const;
    /// The vertices in [begin, end), without their degrees: false when some fan breaks a
    /// rule; `walked` gets the sum of the fans' sizes.
    bool walk_fans(std::size_t begin, std::size_t end, std::size_t& walked) const;
    /// The vertices, each fan against its degree (naming the first broken vertex).
    std::string check_vertices();
    std::size_t n_halfedges() const { return nh_; }
    std::size_t n_faces() const { return nf_; }
    std::size_t n_vertices() const { return nv_; }

private:
    bool live_v(Vertex v) const { return v.idx() < nv_ && !(garbage_ && m_.is_deleted(v)); }
    bool live_h(Halfedge h) const { return h.idx() < nh_ && !(garbage_ && m_.is_deleted(h)); }
    bool live_f(Face f) const { return f.idx() < nf_ && !(garbage_ && m_.is_deleted(f)); }

    // The vertex stage: a fan is walked by a chain of dependent reads, so kLanes vertices are
    // walked side by side, one step each in turn, and each step prefetches what the lane
    // reads next. A lane keeps the neighbours it met: up to kShort in place (a duplicate is
    // found by a scan), more in a list sorted at the end.
    static constexpr std::size_t kLanes = 8, kShort = 16;
    struct Lane {
        Vertex v;
        Halfedge h, x;
        unsigned count = 0, degree = 0;
        std::array<Index, kShort> near{};
        std::vector<Index> many;
    };
    void count_outgoing();
    bool start(Lane& lane);
    bool step(Lane& lane);
    bool finish(Lane& lane);

    const HalfedgeMesh& m_;
    const std::size_t nv_, nh_, nf_;
    const std::vector<Vertex>& to_;
    const std::vector<Halfedge>& next_;
    const std::vector<Halfedge>& prev_;
    const std::vector<Face>& face_;
    const std::vector<Halfedge>& fhalfedge_;
    const bool garbage_;
    // The vertex stage's state.
    std::vector<unsigned> out_degree_, out_boundary_;
    std::size_t next_vertex_ = 0;
    std::string error_;
};

// Halfedges: references in range and live, prev(next(h)) == h, no self-loop edges.
// With next and prev mapping live halfedges to live ones, prev(next(h)) == h for every
// h makes next a bijection and prev its inverse, so next(prev(h)) == h needs no check.
std::string Validator::check_halfedges(std::size_t begin, std::size_t end,
                                       std::size_t& live) const {
    const auto& to = to_;
    const auto& next = next_;
    const auto& prev = prev_;
    const auto& face = face_;
    const std::size_t nh = nh_;
    live = 0;
    for (std::size_t i = begin; i < end; ++i) {
        if (garbage_ && m_.is_deleted(Edge(Index(i >> 1)))) continue;
        ++live;
        if (i + kAhead < end) {
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
        if (!live_v(t)) return hs(h) + " points to a missing or deleted vertex";
        if (!live_h(n)) return hs(h) + " has a missing or deleted next";
        if (!live_h(p)) return hs(h) + " has a missing or deleted prev";
        if (prev[n.idx()] != h) return "prev(next(" + hs(h) + ")) is not itself";
        if (to[n.idx() ^ 1] != t) return "next of " + hs(h) + " does not start where it ends";
        if (face[n.idx()] != f) return hs(h) + " and its next lie in different faces";
        if (f.is_valid() && !live_f(f)) return hs(h) + " lies in a missing or deleted face";
        if ((i & 1) && to[i] == to[i ^ 1])
            return "edge " + std::to_string(i >> 1) + " joins a vertex to itself";
    }
    return {};
}

// Faces: triangles whose halfedges point back to them.
std::string Validator::check_faces(std::size_t begin, std::size_t end) const {
    const auto& to = to_;
    const auto& next = next_;
    const auto& face = face_;
    for (std::size_t i = begin; i < end; ++i) {
        const Face f{Index(i)};
        if (garbage_ && m_.is_deleted(f)) continue;
        if (i + kAhead < end) {
            const Index a = fhalfedge_[i + kAhead].idx();
            if (a < nh_) {
                prefetch(&face[a]);
                prefetch(&next[a]);
                prefetch(&to[a]);
            }
        }
        const Halfedge h = fhalfedge_[i];
        if (!live_h(h)) return fs(f) + " has a missing or deleted halfedge";
        if (face[h.idx()] != f) return fs(f) + "'s halfedge belongs to another face";
        const Halfedge h1 = next[h.idx()], h2 = next[h1.idx()];
        if (next[h2.idx()] != h) return fs(f) + " is not a triangle";
        const Vertex c0 = to[h.idx()], c1 = to[h1.idx()], c2 = to[h2.idx()];
        if (c0 == c1 || c1 == c2 || c0 == c2) return fs(f) + " has a repeated corner";
    }
    return {};
}

// Outgoing halfedges and outgoing boundary halfedges per vertex, counted first so that the
// fan walks read only prev and to.
void Validator::count_outgoing() {
    out_degree_.assign(nv_, 0);
    out_boundary_.assign(nv_, 0);
    for (std::size_t i = 0; i < nh_; ++i) {
        if (garbage_ && m_.is_deleted(Edge(Index(i >> 1)))) continue;
        const Index from = to_[i ^ 1].idx();
        ++out_degree_[from];
        if (!face_[i].is_valid()) ++out_boundary_[from];
    }
}

// Starts the lane on the next vertex that has edges (false: an error, in `error_`). That
// its halfedge is outgoing is checked at the first step, when its line has arrived.
bool Validator::start(Lane& lane) {
    lane.v = Vertex();
    while (next_vertex_ < nv_) {
        const Vertex v(Index(next_vertex_++));
        if (garbage_ && m_.is_deleted(v)) continue;
        const Halfedge h = m_.halfedge(v);
        if (!h.is_valid()) {
            if (out_degree_[v.idx()] == 0) continue;
            error_ = vs(v) + " has edges but no outgoing halfedge";
            return false;
        }
        if (!live_h(h)) {
            error_ = vs(v) + " has a missing or deleted halfedge";
            return false;
        }
        lane.v = v;
        lane.h = lane.x = h;
        lane.count = 0;
        lane.degree = out_degree_[v.idx()];
        lane.many.clear();
        prefetch(&prev_[h.idx()]);
        prefetch(&to_[h.idx()]);
        return true;
    }
    return true;
}

// One step of the lane's walk around its vertex (false: an error, in `error_`); at the end
// of the fan, the lane's checks and the next vertex.
bool Validator::step(Lane& lane) {
    const Index x = lane.x.idx();
    if (lane.count == 0 && to_[x ^ 1] != lane.v) {
        error_ = vs(lane.v) + "'s halfedge is not outgoing";
        return false;
    }
    const Index w = to_[x].idx();
    if (lane.count < kShort) {
        for (unsigned i = 0; i < lane.count; ++i)
            if (lane.near[i] == w) {
                error_ = vs(lane.v) + " has two edges to the same neighbour";
                return false;
            }
        lane.near[lane.count] = w;
    } else {
        lane.many.push_back(w);
    }
    if (++lane.count > lane.degree) {
        error_ = "rotating around " + vs(lane.v) + " does not come back";
        return false;
    }
    lane.x = Halfedge(prev_[x].idx() ^ 1);  // counter-clockwise
    if (lane.x != lane.h) {
        prefetch(&prev_[lane.x.idx()]);
        prefetch(&to_[lane.x.idx()]);
        return true;
    }
    return finish(lane) && start(lane);
}

// The checks once the lane's fan is walked (false: an error, in `error_`).
bool Validator::finish(Lane& lane) {
    const Vertex v = lane.v;
    if (lane.count != lane.degree)
        error_ = vs(v) + " is non-manifold: its edges form more than one fan";
    else if (out_boundary_[v.idx()] > 1)
        error_ = vs(v) + " is non-manifold: it lies on the boundary more than once";
    else if (out_boundary_[v.idx()] == 1 && face_[lane.h.idx()].is_valid())
        error_ = vs(v) + " is on the boundary but its halfedge is not";
    if (!error_.empty()) return false;
    if (lane.count > kShort) {
        std::vector<Index>& seen = lane.many;
        seen.insert(seen.end(), lane.near.begin(), lane.near.end());
        std::sort(seen.begin(), seen.end());
        if (std::adjacent_find(seen.begin(), seen.end()) != seen.end()) {
            error_ = vs(v) + " has two edges to the same neighbour";
            return false;
        }
    }
    return true;
}

// Vertices: outgoing halfedge, boundary preference, a single fan holding every outgoing
// halfedge, no two edges to the same neighbour. (Rotation never leaves a vertex: that
// follows from the halfedge checks above.)
std::string Validator::check_vertices() {
    count_outgoing();
    std::array<Lane, kLanes> lanes;
    for (Lane& lane : lanes)
        if (!start(lane)) return error_;
    for (bool busy = true; busy;) {
        busy = false;
        for (Lane& lane : lanes) {
            if (!lane.v.is_valid()) continue;
            busy = true;
            if (!step(lane)) return error_;
        }
    }
    return {};
}

// The fans of the vertices in [begin, end), kLanes side by side, each walked until it comes
// back (see the file comment): a vertex's halfedge is live and outgoing, on the boundary when
// the vertex is, the fan has at most one boundary halfedge and no two edges to the same
// neighbour. A vertex without a halfedge is skipped (the sum of the sizes shows whether it
// has edges).
bool Validator::walk_fans(std::size_t begin, std::size_t end, std::size_t& walked) const {
    struct Walk {
        Index v = kInvalidIndex, h = 0, x = 0;
        unsigned count = 0, boundary = 0;
        std::array<Index, kShort> near{};
        std::vector<Index> many;
    };
    std::array<Walk, kLanes> lanes;
    std::size_t next_vertex = begin;
    walked = 0;
    // Starts the lane on the next vertex with a halfedge (false: a broken one).
    auto start = [&](Walk& w) {
        w.v = kInvalidIndex;
        while (next_vertex < end) {
            const Vertex v(Index(next_vertex++));
            if (garbage_ && m_.is_deleted(v)) continue;
            const Halfedge h = m_.halfedge(v);
            if (!h.is_valid()) continue;
            if (!live_h(h)) return false;
            w.v = v.idx();
            w.h = w.x = h.idx();
            w.count = w.boundary = 0;
            w.many.clear();
            prefetch(&prev_[w.h]);
            prefetch(&to_[w.h]);
            prefetch(&face_[w.h]);
            return true;
        }
        return true;
    };
    // The checks at the end of a fan.
    auto finish = [&](Walk& w) {
        walked += w.count;
        if (w.boundary > 1 || (w.boundary == 1 && face_[w.h].is_valid())) return false;
        if (w.count <= kShort) return true;
        w.many.insert(w.many.end(), w.near.begin(), w.near.end());
        std::sort(w.many.begin(), w.many.end());
        return std::adjacent_find(w.many.begin(), w.many.end()) == w.many.end();
    };
    auto step = [&](Walk& w) {
        const Index x = w.x;
        if (w.count == 0 && to_[x ^ 1].idx() != w.v) return false;
        const Index n = to_[x].idx();
        if (w.count < kShort) {
            for (unsigned i = 0; i < w.count; ++i)
                if (w.near[i] == n) return false;
            w.near[w.count] = n;
        } else {
            w.many.push_back(n);
        }
        ++w.count;
        if (!face_[x].is_valid()) ++w.boundary;
        w.x = prev_[x].idx() ^ 1;  // counter-clockwise
        if (w.x != w.h) {
            prefetch(&prev_[w.x]);
            prefetch(&to_[w.x]);
            prefetch(&face_[w.x]);
            return true;
        }
        return finish(w) && start(w);
    };
    for (Walk& w : lanes)
        if (!start(w)) return false;
    for (bool busy = true; busy;) {
        busy = false;
        for (Walk& w : lanes) {
            if (w.v == kInvalidIndex) continue;
            busy = true;
            if (!step(w)) return false;
        }
    }
    return true;
}

/// Runs stage(part, begin, end) on the two halves of [0, n) (on two threads for a large n);
/// returns the first half's error, else the second's.
template <typename Stage>
std::string in_halves(std::size_t n, const Stage& stage) {
    std::string error[2];
    const std::size_t mid = n / 2;
    on_two_threads(worth_two_threads(n), [&](int part) {
        error[part] = part == 0 ? stage(0, 0, mid) : stage(1, mid, n);
    });
    return error[0].empty() ? error[1] : error[0];
}

}  // namespace

ValidationResult validate(const HalfedgeMesh& m) {
    if (m.halfedges_size() != 2 * m.edges_size())
        return {false, "halfedge storage is not twice the edge storage"};
    Validator check(m);
    std::size_t live[2] = {0, 0};
    std::string error = in_halves(check.n_halfedges(), [&](int part, std::size_t b, std::size_t e) {
        return check.check_halfedges(b, e, live[part]);
    });
    if (error.empty())
        error = in_halves(check.n_faces(), [&](int, std::size_t b, std::size_t e) {
            return check.check_faces(b, e);
        });
    if (error.empty()) {
        std::size_t walked[2] = {0, 0};
        bool fans_ok[2] = {true, true};
        in_halves(check.n_vertices(), [&](int part, std::size_t b, std::size_t e) {
            fans_ok[part] = check.walk_fans(b, e, walked[part]);
            return std::string();
        });
        if (!fans_ok[0] || !fans_ok[1] || walked[0] + walked[1] != live[0] + live[1])
            error = check.check_vertices();  // names the broken vertex
        if (error.empty() &&
            (!fans_ok[0] || !fans_ok[1] || walked[0] + walked[1] != live[0] + live[1]))
            error = "the vertices' fans do not hold every halfedge";
    }
    if (!error.empty()) return {false, std::move(error)};
    return {};
}

}  // namespace trilab
