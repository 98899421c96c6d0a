#include "core/validate.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <vector>

#include "core/features.h"
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
// fans). Each returns the first broken invariant ("" when none). A large mesh's stage runs in
// 32 pieces shared by two threads (in_chunks), the stages one after the other (a stage reads
// only what the stages before it proved in range).
//
// The vertex stage first walks the fans without knowing the vertices' degrees (walk_fans):
// once the halfedges are proven, rotation (x -> twin(prev(x))) is a permutation of the live
// halfedges whose cycles each stay at one vertex, so every fan comes back. The cycles are
// walked in storage order, each once from its lowest halfedge; a cycle that holds its
// vertex's halfedge belongs to that vertex alone, so when every cycle holds its vertex's
// halfedge and there are as many cycles as vertices with a halfedge, each such vertex has
// one fan holding all its outgoing halfedges and no other vertex has any. The boundary
// halfedges (listed by the halfedge stage) must then each be their vertex's halfedge: at
// most one a fan, and the vertex's halfedge when there is one. When any of this fails, the
// exact per-vertex walk (check_vertices, with the degrees counted first) runs to name the
// first broken vertex, as it always did.
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

    /// The halfedges in [begin, end); `boundary` gets the live ones without a face.
    std::string check_halfedges(std::size_t begin, std::size_t end,
                                std::vector<Index>& boundary) const;
    /// The faces in [begin, end).
    std::string check_faces(std::size_t begin, std::size_t end) const;
    /// The fans whose lowest halfedge lies in [begin, end), without the vertices' degrees:
    /// false when some fan breaks a rule; `fans` gets how many were walked.
    bool walk_fans(std::size_t begin, std::size_t end, std::size_t& fans) const;
    /// `with_halfedge` gets how many live vertices have a halfedge; false when one of those
    /// halfedges is missing or deleted, or a boundary halfedge is not its vertex's halfedge.
    bool check_vertex_halfedges(const std::vector<Index>& boundary,
                                std::size_t& with_halfedge) const;
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
                                       std::vector<Index>& boundary) const {
    const auto& to = to_;
    const auto& next = next_;
    const auto& prev = prev_;
    const auto& face = face_;
    const std::size_t nh = nh_;
    boundary.clear();
    for (std::size_t i = begin; i < end; ++i) {
        if (garbage_ && m_.is_deleted(Edge(Index(i >> 1)))) continue;
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
        if (!f.is_valid())
            boundary.push_back(Index(i));
        else if (!live_f(f))
            return hs(h) + " lies in a missing or deleted face";
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

// The fans met in the halfedges [begin, end), in storage order (see the file comment): each
// rotation cycle (x -> twin(prev(x))) is walked once, from its lowest halfedge, by the part
// that holds that halfedge; a cycle reaching below `begin` belongs to the part below (walked
// here only to mark it seen). A fan must hold its vertex's halfedge and no two edges to the
// same neighbour. A walk reads only prev and to, and in storage order the fans' lines are
// mostly in cache already (neighbouring faces share vertices), where a walk in vertex order
// misses on most steps.
bool Validator::walk_fans(std::size_t begin, std::size_t end, std::size_t& n_fans) const {
    std::vector<std::uint64_t> seen((end - begin + 63) / 64, 0);  // one bit a halfedge
    std::array<Index, kShort> near{};
    std::vector<Index> many;
    std::size_t fans = 0;  // counted here, stored at the end (no line shared with the other half)
    n_fans = 0;
    for (std::size_t i = begin; i < end; ++i) {
        const std::size_t bit = i - begin;
        if ((seen[bit >> 6] >> (bit & 63)) & 1) continue;
        if (garbage_ && m_.is_deleted(Edge(Index(i >> 1)))) continue;
        const Index h = Index(i);
        const Index vh = m_.halfedge(to_[h ^ 1]).idx();
        bool own = true, holds_vh = false;
        unsigned count = 0;
        many.clear();
        Index x = h;
        do {
            if (x < begin) {
                own = false;
            } else if (x < end) {
                const std::size_t b = x - begin;
                seen[b >> 6] |= std::uint64_t(1) << (b & 63);
            }
            if (own) {
                const Index w = to_[x].idx();
                if (count < kShort) {
                    for (unsigned k = 0; k < count; ++k)
                        if (near[k] == w) return false;
                    near[count] = w;
                } else {
                    many.push_back(w);
                }
                holds_vh = holds_vh || x == vh;
            }
            if (++count > nh_) return false;  // never: rotation is a permutation
            x = prev_[x].idx() ^ 1;           // counter-clockwise
        } while (x != h);
        if (!own) continue;
        ++fans;
        if (!holds_vh) return false;
        if (count > kShort) {
            many.insert(many.end(), near.begin(), near.end());
            std::sort(many.begin(), many.end());
            if (std::adjacent_find(many.begin(), many.end()) != many.end()) return false;
        }
    }
    n_fans = fans;
    return true;
}

// The vertices: how many live ones have a halfedge (false when one of those is missing or
// deleted), and whether each boundary halfedge starts at a different vertex whose halfedge
// it is.
bool Validator::check_vertex_halfedges(const std::vector<Index>& boundary,
                                       std::size_t& with_halfedge) const {
    with_halfedge = 0;
    for (std::size_t i = 0; i < nv_; ++i) {
        const Vertex v{Index(i)};
        if (garbage_ && m_.is_deleted(v)) continue;
        const Halfedge h = m_.halfedge(v);
        if (!h.is_valid()) continue;
        if (!live_h(h)) return false;
        ++with_halfedge;
    }
    for (Index b : boundary)
        if (m_.halfedge(to_[b ^ 1]).idx() != b) return false;
    return true;
}

/// Runs stage(chunk, begin, end) on the pieces of [0, n), kChunks of them on every thread
/// (core/parallel.h; each thread takes the next piece left) for a large n, else one; returns
/// the first piece's error in order, as a pass in one piece would.
constexpr std::size_t kChunks = 32;
template <typename Stage>
std::string in_chunks(std::size_t n, const Stage& stage) {
    const bool parallel = worth_two_threads(n);
    const std::size_t chunks = parallel ? kChunks : 1;
    std::array<std::string, kChunks> error;
    parallel_for(
        0, chunks,
        [&](std::size_t k) { error[k] = stage(k, n * k / chunks, n * (k + 1) / chunks); }, 1);
    for (const std::string& e : error)
        if (!e.empty()) return e;
    return {};
}

}  // namespace

ValidationResult validate(const HalfedgeMesh& m) {
    if (m.halfedges_size() != 2 * m.edges_size())
        return {false, "halfedge storage is not twice the edge storage"};
    Validator check(m);
    std::array<std::vector<Index>, kChunks> boundary;
    std::string error =
        in_chunks(check.n_halfedges(), [&](std::size_t k, std::size_t b, std::size_t e) {
            return check.check_halfedges(b, e, boundary[k]);
        });
    if (error.empty())
        error = in_chunks(check.n_faces(), [&](std::size_t, std::size_t b, std::size_t e) {
            return check.check_faces(b, e);
        });
    if (error.empty()) {
        std::array<std::size_t, kChunks> fans{};
        std::array<std::uint8_t, kChunks> fans_ok{};
        std::size_t with_halfedge = 0;
        fans_ok.fill(1);
        in_chunks(check.n_halfedges(), [&](std::size_t k, std::size_t b, std::size_t e) {
            fans_ok[k] = check.walk_fans(b, e, fans[k]);
            return std::string();
        });
        for (std::size_t k = 1; k < kChunks; ++k)
            boundary[0].insert(boundary[0].end(), boundary[k].begin(), boundary[k].end());
        // Each fan holds its own vertex's halfedge, so the fans are as many as the vertices
        // with a halfedge exactly when each of those has one fan and no other vertex any;
        // each boundary halfedge being its vertex's halfedge leaves one to a fan.
        std::size_t n_fans = 0;
        for (std::size_t f : fans) n_fans += f;
        const bool fans_pass = std::find(fans_ok.begin(), fans_ok.end(), 0) == fans_ok.end() &&
                               check.check_vertex_halfedges(boundary[0], with_halfedge) &&
                               n_fans == with_halfedge;
        if (!fans_pass) error = check.check_vertices();  // names the broken vertex
        if (error.empty() && !fans_pass) error = "the vertices' fans do not hold every halfedge";
    }
    if (error.empty()) error = check_features(m);
    if (!error.empty()) return {false, std::move(error)};
    return {};
}

}  // namespace trilab
