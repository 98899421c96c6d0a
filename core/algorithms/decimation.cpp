// Edge-collapse decimation (core/algorithms/decimation.h): the method and its guarantees in
// detail, then the loop.
//
// Mesh decimation by edge collapse (section 1.4 of the reference report).
//
// Method: every edge gets a cost and the cheapest collapse goes first, from a binary heap of
// (cost, edge) entries with lazy invalidation (an entry whose cost is no longer its edge's is
// skipped), so the queue stays exact while costs change; after a collapse only the edges at
// the kept vertex are re-priced. Meshes of more than 50,000 vertices are first reduced in
// batches down to max(50,000, 4 x target): each pass selects the cheapest edges, up to half
// the vertex count (nth_element), and collapses them in memory order (for the cache),
// skipping edges re-priced during the pass (a pass marks the edges a collapse changes and
// prices each once: when the pass reaches it, else after the pass, on two threads); the exact
// heap then does the last collapses, the ones that shape the result. Such a mesh is first
// renumbered into a spatial order (core/algorithms/spatial_order.h: vertices along a Morton curve,
// edges and faces by their smallest vertex), unless the progressive record is asked for: the ring
// walks then hit the cache whatever order the input came in, and the result (numbering included) is
// the same for the same mesh in any vertex or face order; "v:decimation_source" and the geomorph
// still speak of the input's indices. Costs:
//  - Quadric (Garland, Heckbert, "Surface simplification using quadric error metrics",
//    SIGGRAPH 1997): per-vertex quadrics of the incident face planes, summed on collapse; the
//    kept vertex moves to the minimizer of Q0 + Q1 (the 3x3 system), or, where that is
//    ill-conditioned or lands far from the edge, to the best of the two ends and the
//    midpoint. Each boundary edge adds a heavily weighted plane through it, perpendicular to
//    its face, to both its ends, so boundaries keep their shape.
//  - Roundness (1.4.2): R = circumradius / shortest edge, normalized as sqrt(1/3) / R (1 for
//    an equilateral triangle, towards 0 for a sliver); a halfedge collapse (the kept vertex
//    stays) is weighted by the smallest normalized roundness among the triangles it changes,
//    and the collapse with the largest such minimum goes first.
// Binary constraints (1.4.3), each switchable: a roundness threshold, normal flipping (no
// changed face normal turns by more than an angle; degenerate results are refused too),
// an independent set (after a collapse the one-ring of the kept vertex is locked until the
// next iteration), and a maximum quadric error (a distance: the collapse is refused when the
// quadric error exceeds its square).
//
// Guarantees: the topology is always protected by the link condition
// (HalfedgeMesh::is_collapse_ok), so every output is a valid manifold mesh with the input's
// boundary loops, components and genus; a boundary vertex only moves along a boundary edge.
// With "v:texcoord" the kept vertex's uv is interpolated along the edge; with per-corner
// "h:texcoord", vertices on a texture seam are never removed and the corners that move keep
// the seam's side (no seam is torn open). Vertices with a coincident copy
// (core/algorithms/coincident.h: the two sides of a patch seam, the copies of a split non-manifold
// vertex) never move alone, so no crack opens between copies: along a seam (a vertex with exactly
// one copy, a boundary edge with exactly one coincident partner) both sides collapse together, each
// into its kept copy, which stays where it is (costed with the quadrics of both sides); every other
// copy (a corner where seams meet, a non-manifold point) is never removed or moved (neighbours may
// collapse into it).
// Other attributes ride along with the kept vertex.
// The input is never modified. Progressive mesh (Hoppe, "Progressive meshes", SIGGRAPH 1996):
// every collapse is recorded with the vertex split that undoes it.
//
// Complexity: O(E) per batch pass (a few dozen passes: the mesh shrinks geometrically), O(E)
// to fill the heap (make_heap), then O(d^2 + d log E) per collapse for valence d; no
// allocation per collapse (amortized); garbage collection once per iteration, and a compaction
// of the working mesh whenever fewer than half of its stored vertices live (compact(): the same
// result, fewer cache misses). The set-up steps that only read the mesh run on a second thread
// where the machine has one (run_pair()).
//
// The loop, per iteration:
//   target = V - floor(P/100 V)   (or the requested vertex count)
//   price every edge: its best collapse direction, placement and cost
//   big meshes: batch passes (the cheapest edges of the moment, in memory order) down to
//               max(50,000, 4 target) vertices
//   fill the heap; while V > target and the heap is not empty:
//     pop the cheapest edge e (an addressable heap: re-pricing an edge moves its key, a
//     deleted edge leaves it, so every key popped is live and current)
//     refuse if: a locked end (independent set), error above max_error, the link condition,
//                a face normal turning too far, a triangle less round than allowed, a seam
//                vertex
//     collapse: record the vertex split, move the kept vertex, add the quadrics, carry the
//               texture coordinates, lock the one-ring (independent set), re-price the edges
//               at the kept vertex
//     when the heap runs dry early: refill once more (refusals may have become legal)
//   give every vertex of the previous mesh its end position (the position of the vertex it
//   collapsed into) for the geomorph; copy the mesh (the last iteration takes it) and collect
//   its garbage.
#include "core/algorithms/decimation.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>
#include <exception>
#include <limits>
#include <thread>

#include "core/algorithms/coincident.h"
#include "core/algorithms/feature_detection.h"
#include "core/algorithms/quadric.h"
#include "core/algorithms/selection.h"
#include "core/algorithms/spatial_order.h"
#include "core/errors.h"
#include "core/features.h"
#include "core/mesh_builder.h"
#include "core/number_text.h"
#include "core/parallel.h"

namespace trilab {

const char* decimation_cost_name(DecimationCost cost) {
    return enum_id<DecimationCost>(kDecimationCosts, cost);
}

DecimationCost parse_decimation_cost(const std::string& name) {
    return parse_enum<DecimationCost>(kDecimationCosts, name, "decimation cost");
}

const char* decimation_stop_name(DecimationStop stop) {
    return enum_id<DecimationStop>(kDecimationStops, stop);
}

const char* collapse_refusal_name(CollapseRefusal refusal) {
    switch (refusal) {
        case CollapseRefusal::None:
            return "none";
        case CollapseRefusal::NoDirection:
            return "no-direction";
        case CollapseRefusal::MaxError:
            return "max-error";
        case CollapseRefusal::IndependentSet:
            return "independent-set";
        case CollapseRefusal::Topology:
            return "topology";
        case CollapseRefusal::TextureSeam:
            return "texture-seam";
        case CollapseRefusal::NormalFlip:
            return "normal-flip";
        case CollapseRefusal::Roundness:
            return "roundness";
    }
    return "?";
}

double normalized_roundness(const Point& a, const Point& b, const Point& c) {
    // R = circumradius / shortest edge = (la lb lc / (4 area)) / lmin; normalized sqrt(1/3)/R.
    const double la = (b - c).norm(), lb = (c - a).norm(), lc = (a - b).norm();
    const double twice_area = (b - a).cross(c - a).norm();
    const double lmin = std::min(la, std::min(lb, lc));
    const double prod = la * lb * lc;
    if (!(twice_area > 0) || !(prod > 0)) return 0;
    // sqrt(1/3) * lmin * 4 area / prod = sqrt(1/3) * lmin * 2 * twice_area / prod
    const double r = std::sqrt(1.0 / 3.0) * lmin * 2.0 * twice_area / prod;
    return std::min(1.0, std::max(0.0, r));
}

namespace {

// Priority of an edge: its cost, then its index, packed into one integer key so that
// comparisons are single integer compares (the float's bits mapped to an order-preserving
// unsigned integer in the upper half, the edge index in the lower half).
using EdgeKey = std::uint64_t;

EdgeKey edge_key(float cost, std::uint32_t edge) {
    std::uint32_t bits;
    std::memcpy(&bits, &cost, sizeof bits);
    bits = (bits & 0x80000000u) ? ~bits : (bits | 0x80000000u);
    return (EdgeKey(bits) << 32) | edge;
}
float key_cost(EdgeKey k) {
    std::uint32_t bits = std::uint32_t(k >> 32);
    bits = (bits & 0x80000000u) ? (bits & 0x7fffffffu) : ~bits;
    float cost;
    std::memcpy(&cost, &bits, sizeof cost);
    return cost;
}
std::uint32_t key_edge(EdgeKey k) {
    return std::uint32_t(k);
}
// Radix buckets of keys for the batch selection: their top bits (sign, exponent and the
// first mantissa bits of the cost), so bucket order is key order.
constexpr unsigned kBucketBits = 16;
std::size_t bucket(EdgeKey k) {
    return std::size_t(k >> (64 - kBucketBits));
}

// Where an edge's key is in the EdgeHeap, kept in the edge's slot of the per-edge costs.
constexpr std::uint32_t kNotInHeap = std::numeric_limits<std::uint32_t>::max();

// An addressable 4-ary min-heap of edge keys (the cheapest edge on top). Every edge is in it
// at most once, at its current cost: re-pricing moves its key, deleting the edge removes it,
// so nothing stale is ever popped. Slot must have a `heap_pos` member: the heap records each
// key's position there. Four children per node: half the depth of a binary heap, and the
// children of a node lie side by side in memory.
template <class Slot>
class EdgeHeap {
public:
    explicit EdgeHeap(std::vector<Slot>& slots) : slots_(slots) {}
    bool empty() const { return a_.empty(); }
    bool contains(std::uint32_t edge) const { return slots_[edge].heap_pos != kNotInHeap; }
    /// Removes every key.
    void clear() {
        for (EdgeKey k : a_) slots_[key_edge(k)].heap_pos = kNotInHeap;
        a_.clear();
    }
    void reserve(std::size_t n) { a_.reserve(n); }
    /// Adds a key without restoring the heap order (call make_heap() after the last one).
    void append(EdgeKey k) {
        slots_[key_edge(k)].heap_pos = std::uint32_t(a_.size());
        a_.push_back(k);
    }
    void make_heap() {
        for (std::size_t i = a_.size() / 4 + 1; i-- > 0;)
            if (i < a_.size()) sift_down(i, a_[i]);
    }
    void push(EdgeKey k) {
        a_.push_back(k);
        sift_up(a_.size() - 1, k);
    }
    /// Removes and returns the smallest key; the heap must not be empty.
    EdgeKey pop() {
        const EdgeKey top = a_[0];
        slots_[key_edge(top)].heap_pos = kNotInHeap;
        const EdgeKey last = a_.back();
        a_.pop_back();
        if (!a_.empty()) sift_down(0, last);
        return top;
    }
    /// Gives an edge in the heap a new key (same edge).
    void update(EdgeKey k) {
        const std::size_t i = slots_[key_edge(k)].heap_pos;
        if (k < a_[i])
            sift_up(i, k);
        else
            sift_down(i, k);
    }
    /// Removes an edge that is in the heap.
    void remove(std::uint32_t edge) {
        const std::size_t i = slots_[edge].heap_pos;
        slots_[edge].heap_pos = kNotInHeap;
        const EdgeKey old = a_[i], last = a_.back();
        a_.pop_back();
        if (i == a_.size()) return;  // it was the last one
        if (last < old)
            sift_up(i, last);
        else
            sift_down(i, last);
    }

private:
    void place(std::size_t i, EdgeKey k) {
        a_[i] = k;
        slots_[key_edge(k)].heap_pos = std::uint32_t(i);
    }
    // Places k at node i or above it.
    void sift_up(std::size_t i, EdgeKey k) {
        while (i > 0) {
            const std::size_t parent = (i - 1) / 4;
            if (!(k < a_[parent])) break;
            place(i, a_[parent]);
            i = parent;
        }
        place(i, k);
    }
    // Places k at node i or below it.
    void sift_down(std::size_t i, EdgeKey k) {
        const std::size_t n = a_.size();
        for (;;) {
            const std::size_t first = 4 * i + 1;
            if (first >= n) break;
            std::size_t best = first;
            const std::size_t end = std::min(first + 4, n);
            for (std::size_t c = first + 1; c < end; ++c)
                if (a_[c] < a_[best]) best = c;
            if (!(a_[best] < k)) break;
            place(i, a_[best]);
            i = best;
        }
        place(i, k);
    }
    std::vector<Slot>& slots_;
    std::vector<EdgeKey> a_;
};

// Runs `a` here and `b` on a second thread where the machine has a second core (else one after
// the other); both must only read what the other writes after. Rethrows an exception of either.
template <class A, class B>
void run_pair(const A& a, const B& b) {
    if (unsigned(trilab::thread_count()) < 2) {
        a();
        b();
        return;
    }
    std::exception_ptr b_error;
    std::thread other([&] {
        try {
            b();
        } catch (...) {
            b_error = std::current_exception();
        }
    });
    try {
        a();
    } catch (...) {
        other.join();
        throw;
    }
    other.join();
    if (b_error) std::rethrow_exception(b_error);
}

// Below this many elements a set-up loop runs on one thread (a thread costs more than it saves).
constexpr std::size_t kParallelMin = 100000;

// Edges per chunk of the passes over all edges that in_chunks() shares out.
constexpr std::size_t kEdgeChunk = std::size_t(1) << 15;

// Runs body(begin, end, worker) over [0, n) in chunks of kEdgeChunk that two workers take in
// turn, this thread (worker 0) and, where `two`, a second one (worker 1): a worker that waits for
// a core (a busy machine) leaves the remaining chunks to the other instead of holding up the
// end. Bodies of different chunks must not write the same data.
template <class Body>
void in_chunks(bool two, std::size_t n, const Body& body) {
    if (!two) {
        for (std::size_t b = 0; b < n; b += kEdgeChunk) body(b, std::min(n, b + kEdgeChunk), 0);
        return;
    }
    std::atomic<std::size_t> next{0};
    const auto work = [&](int worker) {
        for (;;) {
            const std::size_t b = next.fetch_add(kEdgeChunk);
            if (b >= n) return;
            body(b, std::min(n, b + kEdgeChunk), worker);
        }
    };
    run_pair([&] { work(0); }, [&] { work(1); });
}

// Meshes with more vertices than this are first decimated in batches (below), down to
// max(kExactVertices, 4 x target); the exact priority order takes over from there.
constexpr std::size_t kExactVertices = 50000;

// Weight of a boundary constraint plane relative to a face plane (Garland-Heckbert 1997).
constexpr double kBoundaryWeight = 100.0;
// An optimal placement farther than this many edge lengths from the edge's midpoint is
// treated as ill-conditioned.
constexpr double kMaxPlacementDistance = 3.0;
// Features kept (FeatureCurves): the weight of the feature planes (per sharp edge and face, as
// a face's own plane weighs 1), the weight of a curve collapse's chord error against the
// quadric, the placements tried along the curve, and the polyline vertices a chord error reads
// at most. Tuned on fandisk at 5, 10 and 20 % (docs/cli.md).
constexpr double kFeaturePlaneWeight = 1.0;
constexpr double kChordWeight = 0.25;
constexpr int kChordCandidates = 16;
constexpr double kChordSamples = 64.0;

constexpr float kNoCollapse = std::numeric_limits<float>::max();
// The largest cost an edge that can collapse gets (the float below kNoCollapse).
const double kLargestCost = double(std::nextafter(kNoCollapse, 0.0f));

// How many edges ahead the loops over edges ask the cache for their vertices' data.
constexpr std::size_t kPrefetchAhead = 8;
// How many edges of a kept vertex's ring the re-pricing after a collapse lists (and asks the
// cache for) before pricing them; the rest of a larger ring is priced as it is walked.
constexpr unsigned kRingPrefetch = 32;

// The best collapse of an edge: cost, placement, direction (halfedge(e, dir)'s from-vertex
// goes). Only the cost is stored per edge (EdgeCost, 8 bytes); the rest is recomputed when the
// edge comes up.
struct EdgeChoice {
    double cost = 0;
    Point target = Point::Zero();
    std::uint8_t dir = 0;
};
// Per edge: its current cost, and where its key is in the heap (the exact phase).
struct EdgeCost {
    float cost = kNoCollapse;
    std::uint32_t heap_pos = kNotInHeap;
};

// Which edges Decimater::price_and_count() prices before counting.
enum class Pricing { None, Stale, All };

enum class Refusal { None, Topology, NormalFlip, Roundness, IndependentSet, MaxError, Seam };

// The normal change measured for an explanation (Decimater::normals_ok()).
struct NormalChange {
    double smallest_cos = 1;  ///< of the angle between a face's normals before and after
    bool degenerate = false;  ///< a face would have no area
    bool refused = false;     ///< a face turns past the angle
};

// The feature curves of a run that keeps features: the input's chains of sharp edges through
// crease vertices (two sharp edges, no tag), each as its polyline of input positions, and per
// working vertex the curve it lies on and its parameter along it (segment index + fraction;
// corners and curve ends are on none: they never move). A collapse of a crease vertex into its
// neighbour on the same curve places the kept vertex at the minimum of the quadric over the
// input polyline between the two (place()): the feature curve keeps exactly the input's shape
// while its vertices move along it, as the free placement lets the other vertices move.
class FeatureCurves {
public:
    static constexpr Index kNone = kInvalidIndex;
    bool empty() const { return lines_.empty(); }
    Index curve(Vertex v) const { return curve_[v.idx()]; }
    double param(Vertex v) const { return param_[v.idx()]; }
    std::vector<Index>& curves() { return curve_; }
    std::vector<double>& params() { return param_; }

    /// Builds the curves of `m` from its sharp edges (`sharp` > 0) and corner tags.
    void build(const HalfedgeMesh& m, const EdgeProperty<float>& sharp,
               const VertexProperty<std::uint8_t>& corner) {
        curve_.assign(m.vertices_size(), kNone);
        param_.assign(m.vertices_size(), 0.0);
        lines_.clear();
        closed_.clear();
        if (!sharp) return;
        std::vector<std::uint8_t> degree(m.vertices_size(), 0);
        for (Edge e : m.edges())
            if (sharp[e] > 0.0f)
                for (unsigned k = 0; k < 2; ++k) {
                    std::uint8_t& d = degree[m.to_vertex(m.halfedge(e, k)).idx()];
                    d = std::uint8_t(std::min(3, d + 1));
                }
        const auto crease = [&](Vertex v) {
            return degree[v.idx()] == 2 && !(corner && corner[v]);
        };
        std::vector<std::uint8_t> used(m.edges_size(), 0);
        // From vertex `from` along sharp halfedge h through crease vertices.
        const auto walk = [&](Halfedge h, bool closed) {
            const Index id = Index(lines_.size());
            std::vector<Point> line{m.position(m.from_vertex(h))};
            if (closed) {
                curve_[m.from_vertex(h).idx()] = id;
                param_[m.from_vertex(h).idx()] = 0.0;
            }
            while (true) {
                used[HalfedgeMesh::edge(h).idx()] = 1;
                const Vertex w = m.to_vertex(h);
                if (!crease(w) || (closed && curve_[w.idx()] == id)) break;
                curve_[w.idx()] = id;
                param_[w.idx()] = double(line.size());
                line.push_back(m.position(w));
                Halfedge next;
                for (Halfedge g : m.halfedges_around(w))
                    if (sharp[HalfedgeMesh::edge(g)] > 0.0f && !used[HalfedgeMesh::edge(g).idx()])
                        next = g;
                if (!next.is_valid()) break;
                h = next;
            }
            if (!closed) line.push_back(m.position(m.to_vertex(h)));
            lines_.push_back(std::move(line));
            closed_.push_back(closed ? 1 : 0);
        };
        for (Vertex v : m.vertices()) {
            if (degree[v.idx()] == 0 || crease(v)) continue;
            for (Halfedge h : m.halfedges_around(v))
                if (sharp[HalfedgeMesh::edge(h)] > 0.0f && !used[HalfedgeMesh::edge(h).idx()])
                    walk(h, false);
        }
        for (Edge e : m.edges())
            if (sharp[e] > 0.0f && !used[e.idx()]) walk(m.halfedge(e, 0), true);
    }

    /// The minimum of q over the input polyline between the neighbours c (of a) and d (of b)
    /// of crease vertices a and b of one curve, through a and b (c or d invalid, or off the
    /// curve: a curve end, the polyline's end on that side); the point, its parameter and q
    /// there. A small margin keeps the point off c and d.
    struct Placement {
        Point p;
        double t = 0, cost = 0;
        double chord = 0;  ///< squared distance of the input polyline from the new chords
    };
    Placement place(const Quadric& q, Vertex a, Vertex b, Vertex c, Vertex d) const {
        const Index id = curve_[a.idx()];
        const std::vector<Point>& line = lines_[id];
        const double ta = param_[a.idx()], tb = param_[b.idx()];
        const auto on = [&](Vertex v) { return v.is_valid() && curve_[v.idx()] == id; };
        double lo, hi;  // the parameter range, unwrapped
        if (closed_[id]) {
            const double n = double(line.size());
            const auto fwd = [&](double from, double to) { return std::fmod(to - from + n, n); };
            // Forward from a to b, unless that arc holds c (then the curve runs b -> a).
            bool forward = true;
            if (on(c)) forward = !(fwd(ta, param_[c.idx()]) < fwd(ta, tb));
            const double first = forward ? ta : tb, second = forward ? tb : ta;
            const Vertex before = forward ? c : d, after = forward ? d : c;
            lo = on(before) ? param_[before.idx()] : first;
            if (fwd(lo, first) > fwd(lo, second)) lo = first;  // wrapped the wrong way
            hi = lo + fwd(lo, second);
            if (on(after)) hi = std::max(hi, lo + fwd(lo, param_[after.idx()]));
            if (hi > lo + n) hi = lo + n;
        } else {
            const bool forward = ta < tb;
            const Vertex before = forward ? c : d, after = forward ? d : c;
            lo = on(before) ? param_[before.idx()] : 0.0;
            hi = on(after) ? param_[after.idx()] : double(line.size() - 1);
        }
        Placement best = best_on(q, line, closed_[id] != 0, lo, hi);
        if (!std::isfinite(best.cost)) return best;
        const bool closed = closed_[id] != 0;
        const double n = double(line.size());
        double t0 = best.t;
        if (closed)  // back into [lo, hi] (unwrapped)
            t0 = lo + std::fmod(t0 - std::fmod(lo, n) + 2.0 * n, n);
        // The chord error as a quadric-like cost: the quadric's plane count (its trace: unit
        // normals) times the squared error, weighted; the quadric's minimum and evenly spread
        // candidates compete on the larger of the two.
        const double* qd = q.data();
        const double w = kChordWeight * (qd[0] + qd[4] + qd[7]);
        best.chord = chord_error(line, closed, lo, t0, hi);
        best.cost = std::max(best.cost, w * best.chord);
        constexpr double kMargin = 1e-3;
        for (int j = 1; j < kChordCandidates; ++j) {
            const double t =
                std::clamp(lo + (hi - lo) * j / kChordCandidates, lo + kMargin, hi - kMargin);
            Placement x;
            x.p = at_param(line, closed, t);
            x.chord = chord_error(line, closed, lo, t, hi);
            x.cost = std::max(q(x.p), w * x.chord);
            x.t = closed ? std::fmod(t, n) : t;
            if (x.cost < best.cost) best = x;
        }
        return best;
    }

private:
    /// The point of the polyline at (unwrapped) parameter u.
    static Point at_param(const std::vector<Point>& line, bool closed, double u) {
        const std::size_t n = line.size();
        double k = std::floor(u);
        if (!closed && k >= double(n - 1)) k = double(n - 2);
        const double s = u - k;
        const std::size_t i = std::size_t(k) % n;
        return Point((1 - s) * line[i] + s * line[(i + 1) % n]);
    }
    /// The largest squared distance of the polyline's vertices strictly between lo and hi from
    /// the two chords (lo, t) and (t, hi).
    static double chord_error(const std::vector<Point>& line, bool closed, double lo, double t,
                              double hi) {
        const Point a = at_param(line, closed, lo), p = at_param(line, closed, t),
                    b = at_param(line, closed, hi);
        const auto dist2 = [](const Point& x, const Point& s0, const Point& s1) {
            const Vector3 d = s1 - s0;
            const double dd = d.squaredNorm();
            const double u = dd > 0 ? std::clamp((x - s0).dot(d) / dd, 0.0, 1.0) : 0.0;
            return (s0 + u * d - x).squaredNorm();
        };
        const std::size_t n = line.size();
        double worst = 0;
        // Long spans are sampled (at most about kChordSamples vertices: the cost stays O(1)).
        const double stride = std::max(1.0, std::floor((hi - lo) / kChordSamples));
        for (double k = std::floor(lo) + 1; k < hi; k += stride) {
            const Point& x = line[std::size_t(k) % n];
            worst = std::max(worst, k < t ? dist2(x, a, p) : dist2(x, p, b));
        }
        return worst;
    }

    /// The placement on [lo, hi] (unwrapped; kept a little off both ends) that minimizes q: on
    /// each segment the minimum of q (a parabola) or an end.
    static Placement best_on(const Quadric& q, const std::vector<Point>& line, bool closed,
                             double lo, double hi) {
        constexpr double kMargin = 1e-3;
        const double ta = lo + kMargin, tb = hi - kMargin;
        Placement best;
        best.cost = std::numeric_limits<double>::infinity();
        const std::size_t n = line.size();
        for (double k = std::floor(ta); k < tb; k += 1.0) {
            const double s0 = std::max(ta, k) - k, s1 = std::min(tb, k + 1.0) - k;
            const Point& p0 = line[std::size_t(k) % n];
            const Point& p1 = line[(std::size_t(k) + 1) % n];
            // q along the segment is a parabola in s: its minimum on [s0, s1].
            const auto at = [&](double s) { return Point(p0 + s * (p1 - p0)); };
            const double f0 = q(at(0.0)), fh = q(at(0.5)), f1 = q(at(1.0));
            const double a2 = 2.0 * (f0 - 2.0 * fh + f1);  // the parabola's s^2 coefficient
            double s = s0;
            if (a2 > 0) s = std::clamp((3.0 * f0 - 4.0 * fh + f1) / (2.0 * a2), s0, s1);
            for (double cand : {s, s0, s1}) {
                const double f = q(at(cand));
                if (f < best.cost) {
                    best.cost = f;
                    best.p = at(cand);
                    best.t = closed ? std::fmod(k + cand, double(n)) : k + cand;
                }
            }
        }
        return best;
    }

    std::vector<Index> curve_;
    std::vector<double> param_;
    std::vector<std::vector<Point>> lines_;
    std::vector<std::uint8_t> closed_;
};

class Decimater {
public:
    /// Sets the decimator up on `mesh`; with price_edges false (explain()) no edge is priced.
    /// With `before` (decimate()), the decimator may compact the working mesh's storage
    /// between passes (compact()); `before` then follows it (see compact()).
    Decimater(HalfedgeMesh& mesh, const DecimationOptions& options, ProgressiveMesh* pm,
              DecimationReport& report, bool price_edges = true,
              std::vector<Index>* before = nullptr)
        : m_(mesh), c_(mesh), o_(options), pm_(pm), report_(report), before_(before) {
        cos_max_angle_ = std::cos(o_.max_normal_angle * M_PI / 180.0);
        max_error2_ = o_.max_error > 0 ? o_.max_error * o_.max_error
                                       : std::numeric_limits<double>::infinity();
        vuv_ = m_.get_vertex_property<TexCoord>("v:texcoord");
        huv_ = m_.get_halfedge_property<TexCoord>("h:texcoord");
        fetch_features();
        if (sharp_) curves_.build(m_, sharp_, corner_);
        if (sharp_ || corner_) {
            fcount_.assign(m_.vertices_size(), 0);
            for (Vertex v : c_.vertices()) fcount_[v.idx()] = std::uint8_t(count_features_at(v));
        }
        // Vertices with a coincident copy (a seam's two sides, the copies of a split vertex)
        // never move alone: a seam vertex with exactly one copy goes together with it, along
        // the seam on both sides (seam_partner()), every other copy stays where it is.
        // The coincident vertices (with the per-element arrays) and the quadrics read the mesh
        // only: side by side.
        const auto setup = [&] {
            edge_.assign(m_.edges_size(), EdgeCost());
            stale_.assign(m_.edges_size(), 0);
            boundary_.assign(m_.vertices_size(), 0);
            for (Vertex v : c_.vertices()) boundary_[v.idx()] = c_.is_boundary(v) ? 1 : 0;
            locked_.assign(m_.vertices_size(), 0);
            parent_.assign(m_.vertices_size(), Vertex());
            groups_ = find_coincident_vertices(c_);
        };
        if (m_.n_vertices() >= kParallelMin)
            run_pair(setup, [&] { init_quadrics(); });
        else {
            setup();
            init_quadrics();
        }
        const CoincidentGroups& groups = groups_;
        coincident_.assign(m_.vertices_size(), 0);
        group_.assign(m_.vertices_size(), kInvalidIndex);
        copy_.assign(m_.vertices_size(), Vertex());
        for (std::size_t g = 0; g < groups.size(); ++g) {
            const Index* b = groups.begin(g);
            const bool pair = groups.end(g) - b == 2;
            for (const Index* v = b; v != groups.end(g); ++v) {
                coincident_[*v] = 1;
                group_[*v] = Index(g);
                if (pair) copy_[*v] = Vertex(*v == b[0] ? b[1] : b[0]);
            }
        }
        report_.coincident_vertices = groups.members.size();
        // Compaction renumbers vertices, so it is off where something outside the mesh
        // speaks of the working indices and would need remapping too: the progressive record,
        // the coincident groups, and deleted input vertices the geomorph still names.
        may_compact_ = before_ && !pm_ && groups_.empty() && !m_.has_garbage();
        if (o_.region) {
            region_ = *o_.region;
            region_ptr_ = &region_;
        }
        if (!price_edges) return;
        // Each edge's price reads the mesh and writes the edge's own cost: two halves at once,
        // each counting its costs for the first batch selection.
        price_and_count(Pricing::All);
    }

    /// Runs one iteration down to `target` vertices; returns whether it got there, and
    /// otherwise sets `stop`.
    bool iterate(std::size_t target, Progress& progress, double progress_base, double progress_span,
                 DecimationStop& stop) {
        ++iteration_;
        const std::size_t start = m_.n_vertices();
        std::size_t constraint_refusals = 0;
        bool hit_max_error = false;
        const auto report_progress = [&]() {
            if ((report_.collapses & 1023u) != 0) return;
            progress.check_cancelled();
            const double done =
                double(start - m_.n_vertices()) / double(std::max<std::size_t>(1, start - target));
            progress.report(progress_base + progress_span * done, "collapsing edges");
        };
        // Batches on big meshes: every pass selects the cheapest edges (nth_element, O(E)),
        // half of the vertices' worth at most, and collapses them in memory order, skipping
        // those whose cost changed since the selection (re-priced by an earlier collapse of
        // the pass: they wait for the next pass). The exact heap does the last, most visible
        // collapses.
        const std::size_t batch_floor = std::max(kExactVertices, 4 * target);
        target_ = batch_floor;
        while (m_.n_vertices() > batch_floor && !hit_max_error) {
            const std::size_t done = batch_pass(batch_floor, hit_max_error, report_progress);
            compact_if_sparse();
            if (done == 0) break;
        }
        compact_if_sparse();
        counted_ = false;  // the heap re-prices edges from here on
        target_ = target;
        for (int round = 0; m_.n_vertices() > target && !hit_max_error; ++round) {
            fill_heap();
            std::size_t collapses_this_round = 0;
            constraint_refusals = 0;
            while (!heap_.empty() && m_.n_vertices() > target) {
                // The cheapest live edge, at its current cost.
                const Edge e(key_edge(heap_.pop()));
                EdgeChoice choice;  // as priced: nothing around e changed since
                if (!evaluate(e, choice)) continue;
                const Halfedge h = HalfedgeMesh::halfedge(e, choice.dir);
                const Point p = choice.target;
                if (above_max_error(choice)) {
                    ++report_.refused_max_error;
                    hit_max_error = true;
                    break;
                }
                const Refusal r = check(h, p);
                if (r != Refusal::None) {
                    count(r);
                    if (r != Refusal::Topology) ++constraint_refusals;
                    continue;
                }
                collapse(h, p);
                ++collapses_this_round;
                report_progress();
            }
            heap_.clear();
            heap_active_ = false;
            if (hit_max_error || m_.n_vertices() <= target) break;
            // The heap ran dry: refill once more only if this round changed something (a
            // refused collapse may have become legal) and locks do not forbid it anyway.
            if (collapses_this_round == 0 || o_.independent_set || round >= 8) break;
        }
        heap_.clear();
        if (m_.n_vertices() <= target) return true;
        stop = hit_max_error             ? DecimationStop::MaxError
               : constraint_refusals > 0 ? DecimationStop::Constraints
                                         : DecimationStop::Topology;
        return false;
    }

    /// The region in the working mesh's current numbering (compact() renumbers it), or null.
    const std::vector<float>* region() const { return region_ptr_; }

    /// The vertex that `v` (alive at some point) finally collapsed into.
    Vertex representative(Vertex v) {
        Vertex r = v;
        while (parent_[r.idx()].is_valid()) r = parent_[r.idx()];
        // Path compression.
        while (parent_[v.idx()].is_valid()) {
            const Vertex next = parent_[v.idx()];
            parent_[v.idx()] = r;
            v = next;
        }
        return r;
    }

    /// What the decimator would decide about e as the first collapse of an iteration: the
    /// same evaluate(), max-error test and check() as a run, every constraint answered.
    CollapseExplanation explain(Edge e) {
        ++iteration_;  // as iterate(): nothing is locked at the start of an iteration
        target_ = 0;
        CollapseExplanation x;
        x.normal_flip_on = o_.normal_flip;
        x.max_normal_angle = o_.max_normal_angle;
        x.roundness_on = o_.roundness;
        x.min_roundness = o_.min_roundness;
        x.independent_set_on = o_.independent_set;
        x.max_error_on = o_.max_error > 0;
        x.max_error = o_.max_error;
        EdgeChoice choice;
        if (!evaluate(e, choice)) return x;  // refusal NoDirection
        const Halfedge h = HalfedgeMesh::halfedge(e, choice.dir);
        x.possible = true;
        x.removed = m_.from_vertex(h);
        x.kept = m_.to_vertex(h);
        x.target = choice.target;
        x.cost = choice.cost;
        x.topology_ok = true;
        x.max_error_refuses = above_max_error(choice);
        if (o_.cost == DecimationCost::Quadric) x.error = std::sqrt(std::max(0.0, choice.cost));
        const Refusal r = check(h, choice.target, &x);
        x.refusal = x.max_error_refuses ? CollapseRefusal::MaxError : public_refusal(r);
        return x;
    }

private:
    // ---- compaction -------------------------------------------------------------------------
    // Collapses leave dead vertices and edges spread through the storage, so the ring walks
    // and per-edge scans of later passes touch ever more cache lines per live element. Once
    // fewer than half of the stored vertices live, compact() gathers the live ones.
    void compact_if_sparse() {
        if (may_compact_ && 2 * m_.n_vertices() < m_.vertices_size()) compact();
    }

    // Compacts the working mesh (HalfedgeMesh::garbage_collection(), which keeps the live
    // elements in their order) and the decimator's per-element arrays with it. Every decision
    // of the decimator depends on element indices only through their order (heap keys tie by
    // edge index, batches run in memory order), so the result is the same bit for bit, and so
    // is the output's numbering (a later garbage collection of an order-kept compaction is the
    // one garbage collection). `before_` (the geomorph's vertices of the previous mesh, in
    // working indices) moves to each one's representative, renumbered, when the geomorph is
    // asked for (else nothing reads it before decimate() rebuilds it): parent_ starts afresh.
    // The heap must be empty (it is between passes).
    void compact() {
        // Old index -> new index of the live vertices and edges, in their order: the numbering
        // garbage_collection() gives them.
        const auto live_order = [](std::size_t n, const auto& is_deleted) {
            std::vector<Index> old_to_new(n, kInvalidIndex);
            Index next = 0;
            for (std::size_t i = 0; i < n; ++i)
                if (!is_deleted(Index(i))) old_to_new[i] = next++;
            return std::make_pair(std::move(old_to_new), std::size_t(next));
        };
        const auto [vmap, nv] =
            live_order(m_.vertices_size(), [&](Index v) { return c_.is_deleted(Vertex(v)); });
        const auto [emap, ne] =
            live_order(m_.edges_size(), [&](Index e) { return c_.is_deleted(Edge(e)); });
        // In place: the order is kept, so no element moves up.
        const auto gather = [](auto& values, const std::vector<Index>& old_to_new,
                               std::size_t n_new) {
            for (std::size_t i = 0; i < old_to_new.size(); ++i)
                if (old_to_new[i] != kInvalidIndex) values[old_to_new[i]] = values[i];
            values.resize(n_new);
        };
        // The mesh here, the decimator's own arrays on the other thread (they do not read it).
        const auto compact_mine = [&, &vmap = vmap, &emap = emap, nv = nv, ne = ne] {
            // Without the geomorph nothing reads before_ again (decimate() rebuilds it after a
            // level): one chase through parent_ per input vertex saved.
            if (o_.record_geomorph) {
                for (Index& v : *before_) {
                    const Vertex r =
                        vmap[v] == kInvalidIndex ? representative(Vertex(v)) : Vertex(v);
                    v = vmap[r.idx()];
                }
            }
            gather(quadric_, vmap, nv);
            gather(boundary_, vmap, nv);
            gather(coincident_, vmap, nv);
            gather(group_, vmap, nv);
            gather(copy_, vmap, nv);  // all invalid: there are no groups here
            gather(locked_, vmap, nv);
            if (region_ptr_) gather(region_, vmap, nv);
            if (!fcount_.empty()) gather(fcount_, vmap, nv);
            if (!curves_.empty()) {
                gather(curves_.curves(), vmap, nv);
                gather(curves_.params(), vmap, nv);
            }
            parent_.assign(nv, Vertex());
            gather(edge_, emap, ne);
            stale_.assign(ne, 0);  // none between passes
        };
        if (nv >= kParallelMin)
            run_pair([&] { m_.garbage_collection(); }, compact_mine);
        else {
            m_.garbage_collection();
            compact_mine();
        }
        vuv_ = m_.get_vertex_property<TexCoord>("v:texcoord");
        huv_ = m_.get_halfedge_property<TexCoord>("h:texcoord");
        fetch_features();
    }

    // The features (core/features.h) the run keeps, when the options ask and the mesh has any.
    void fetch_features() {
        sharp_ = EdgeProperty<float>();
        corner_ = VertexProperty<std::uint8_t>();
        if (o_.features == FeatureSource::None || !has_features(m_)) return;
        sharp_ = m_.get_edge_property<float>(kSharpnessProperty);
        corner_ = m_.get_vertex_property<std::uint8_t>(kCornerProperty);
    }

    // ---- setup ------------------------------------------------------------------------------
    void init_quadrics() {
        quadric_.assign(c_.vertices_size(), Quadric());
        for (Face f : c_.faces()) {
            const auto c = c_.face_vertices(f);
            const Point &a = c_.position(c[0]), &b = c_.position(c[1]), &d = c_.position(c[2]);
            Vector3 n = (b - a).cross(d - a);
            const double len = n.norm();
            if (!(len > 0)) continue;
            const Quadric q = Quadric::plane(n / len, a);
            for (Vertex v : c) quadric_[v.idx()] += q;
        }
        for (Edge e : c_.edges()) {
            for (unsigned i = 0; i < 2; ++i) {
                const Halfedge h = HalfedgeMesh::halfedge(e, i);
                if (!c_.is_boundary(h) || c_.is_boundary(HalfedgeMesh::twin(h))) continue;
                add_edge_plane(h, c_.face(HalfedgeMesh::twin(h)), kBoundaryWeight);
            }
        }
        if (sharp_) add_feature_planes();
    }

    // Feature planes (Garland and Heckbert's boundary constraint, along the sharp edges): each
    // interior sharp edge adds, to both its ends, the plane through it perpendicular to each of
    // its two faces, so a collapse that bends a feature curve or pulls the surface across it
    // costs its distance to the curve.
    void add_feature_planes() {
        for (Edge e : c_.edges()) {
            if (!(sharp_[e] > 0.0f) || c_.is_boundary(e)) continue;
            const Halfedge h = HalfedgeMesh::halfedge(e, 0);
            for (Halfedge g : {h, HalfedgeMesh::twin(h)})
                add_edge_plane(h, c_.face(g), kFeaturePlaneWeight);
        }
    }

    // Adds to both ends of h the plane through h perpendicular to face f (none when h and f's
    // normal are parallel or f is degenerate).
    void add_edge_plane(Halfedge h, Face f, double weight) {
        const auto c = c_.face_vertices(f);
        const Vector3 fn =
            (c_.position(c[1]) - c_.position(c[0])).cross(c_.position(c[2]) - c_.position(c[0]));
        const Point& a = c_.position(c_.from_vertex(h));
        const Point& b = c_.position(c_.to_vertex(h));
        const Vector3 n = (b - a).cross(fn);
        const double len = n.norm();
        if (!(len > 0)) return;
        const Quadric q = Quadric::plane(n / len, a, weight);
        quadric_[c_.from_vertex(h).idx()] += q;
        quadric_[c_.to_vertex(h).idx()] += q;
    }

    // Prices the live edges of [begin, end) (no heap yet).
    void price_range(Index begin, Index end) {
        for (Index i = begin; i < end; ++i) {
            if (i + kPrefetchAhead < end) prefetch(Edge(i + kPrefetchAhead));
            if (!c_.is_deleted(Edge(i))) price(Edge(i));
        }
    }

    // Prices the stale edges of [begin, end) (see defer_).
    void price_stale_range(Index begin, Index end) {
        for (Index i = begin; i < end; ++i) {
            if (i + kPrefetchAhead < end && stale_[i + kPrefetchAhead])
                prefetch(Edge(i + kPrefetchAhead));
            if (stale_[i]) {  // forget() unmarks the edges a collapse deletes
                stale_[i] = 0;
                price(Edge(i));
            }
        }
    }

    // Counts the keys of the candidate edges of [begin, end) per bucket (the batch selection's
    // histogram) into `counts` (zeroed first), and the candidates into `n`.
    void count_keys(Index begin, Index end, std::vector<std::uint32_t>& counts,
                    std::size_t& n) const {
        for (Index e = begin; e < end; ++e) {
            const float cost = edge_[e].cost;
            if (cost < kNoCollapse) {
                ++counts[bucket(edge_key(cost, e))];
                ++n;
            }
        }
    }

    // Prices the edges `what` names, then counts the keys of the next batch selection
    // (bucket_count_, candidates_), chunk by chunk in memory order, on two threads for big
    // meshes (in_chunks()): each pricing reads the mesh and writes its own edge's cost only
    // (the heap is not in use), and each chunk counts the costs it priced, into its worker's
    // histogram. One meeting of the threads.
    void price_and_count(Pricing what) {
        const Index n_edges = Index(m_.edges_size());
        const std::size_t n_buckets = std::size_t(1) << kBucketBits;
        bucket_count_.assign(n_buckets, 0);
        bucket_count2_.assign(n_buckets, 0);
        std::size_t n[2] = {0, 0};
        in_chunks(n_edges >= kParallelMin, n_edges, [&](std::size_t b, std::size_t e, int w) {
            if (what == Pricing::All)
                price_range(Index(b), Index(e));
            else if (what == Pricing::Stale)
                price_stale_range(Index(b), Index(e));
            count_keys(Index(b), Index(e), w == 0 ? bucket_count_ : bucket_count2_, n[w]);
        });
        for (std::size_t i = 0; i < n_buckets; ++i) bucket_count_[i] += bucket_count2_[i];
        candidates_ = n[0] + n[1];
        counted_ = true;
    }

    void fill_heap() {
        heap_.clear();
        heap_.reserve(m_.n_edges());
        for (Edge e : m_.edges())
            if (edge_[e.idx()].cost < kNoCollapse)
                heap_.append(edge_key(edge_[e.idx()].cost, e.idx()));
        heap_.make_heap();
        heap_active_ = true;
    }

    // One batch pass (see iterate()); returns the number of collapses.
    template <class Report>
    std::size_t batch_pass(std::size_t floor, bool& hit_max_error, const Report& report) {
        ++pass_;
        const std::size_t surplus = m_.n_vertices() - floor;
        // Selection by radix: a histogram of the keys' top bits finds the bucket of the
        // budget-th cheapest edge, nth_element finds it among that bucket's keys alone. Deleted
        // edges and those that cannot collapse cost kNoCollapse.
        const Index n_edges = Index(m_.edges_size());
        // The histogram: made by the previous pass's last step (or here, for the first pass);
        // compaction keeps it (a bucket is a cost's top bits, deleted edges are not counted).
        if (!counted_) price_and_count(Pricing::None);
        counted_ = false;
        const std::size_t candidates = candidates_;
        // At most half of the vertices per pass.
        const std::size_t budget =
            std::min({surplus, candidates, std::max<std::size_t>(1, m_.n_vertices() / 2)});
        if (budget == 0) return 0;
        std::size_t below = 0, b = 0;  // keys in the buckets before b
        while (below + bucket_count_[b] < budget) below += bucket_count_[b++];
        // One scan lists the keys of the buckets up to b in memory order (far fewer cache
        // misses than cost order, the same quality in the benchmark) and bucket b's apart:
        // chunk by chunk on two threads for big meshes (in_chunks()), each chunk's keys kept
        // apart and then appended in chunk order.
        const std::size_t n_chunks = (std::size_t(n_edges) + kEdgeChunk - 1) / kEdgeChunk;
        if (chunk_keys_.size() < n_chunks) chunk_keys_.resize(n_chunks);
        in_chunks(n_edges >= kParallelMin, n_edges, [&](std::size_t begin, std::size_t end, int) {
            std::vector<EdgeKey>& keys = chunk_keys_[begin / kEdgeChunk];
            keys.clear();
            for (Index e = Index(begin); e < Index(end); ++e) {
                const float cost = edge_[e].cost;
                if (!(cost < kNoCollapse)) continue;
                const EdgeKey k = edge_key(cost, e);
                if (bucket(k) <= b) keys.push_back(k);
            }
        });
        batch_.clear();
        threshold_bucket_.clear();
        for (std::size_t c = 0; c < n_chunks; ++c) {
            batch_.insert(batch_.end(), chunk_keys_[c].begin(), chunk_keys_[c].end());
            for (const EdgeKey k : chunk_keys_[c])
                if (bucket(k) == b) threshold_bucket_.push_back(k);
        }
        const auto nth = threshold_bucket_.begin() + std::ptrdiff_t(budget - 1 - below);
        std::nth_element(threshold_bucket_.begin(), nth, threshold_bucket_.end());
        const EdgeKey threshold = *nth;
        std::size_t done = 0;
        defer_ = groups_.empty();
        for (std::size_t i = 0; i < batch_.size(); ++i) {
            if (i + kPrefetchAhead < batch_.size())
                prefetch(Edge(key_edge(batch_[i + kPrefetchAhead])));
            const EdgeKey k = batch_[i];
            if (k > threshold) continue;
            const Edge e(key_edge(k));
            if (m_.is_deleted(e)) continue;
            if (stale_[e.idx()]) {  // changed by an earlier collapse of the pass: price it now
                stale_[e.idx()] = 0;
                price(e);
            }
            // Re-priced by an earlier collapse of the pass: the next pass.
            if (edge_[e.idx()].cost != key_cost(k)) continue;
            EdgeChoice choice;
            if (!evaluate(e, choice)) continue;
            const Halfedge h = HalfedgeMesh::halfedge(e, choice.dir);
            const Point p = choice.target;
            if (above_max_error(choice)) {
                hit_max_error = true;
                ++report_.refused_max_error;
                break;
            }
            const Refusal r = check(h, p);
            if (r != Refusal::None) {
                count(r);
                continue;
            }
            collapse(h, p);
            ++done;
            report();
            if (m_.n_vertices() <= floor) break;
        }
        defer_ = false;
        price_and_count(Pricing::Stale);  // for the next pass
        return done;
    }

    // ---- pricing ----------------------------------------------------------------------------
    // Asks the cache for what pricing e reads about its two vertices: positions, quadrics
    // (two cache lines each), boundary flags. No effect where unsupported.
    void prefetch(Edge e) const {
        for (unsigned i = 0; i < 2; ++i)
            prefetch_vertex(m_.to_vertex(HalfedgeMesh::halfedge(e, i)));
    }
    void prefetch_vertex(Vertex v) const {
#if defined(__GNUC__)
        __builtin_prefetch(&c_.position(v));
        const char* q = reinterpret_cast<const char*>(&quadric_[v.idx()]);
        __builtin_prefetch(q);
        __builtin_prefetch(q + sizeof(Quadric) - 1);
        __builtin_prefetch(&boundary_[v.idx()]);
#else
        (void)v;
#endif
    }

    // Whether v's corners carry more than one per-corner texture coordinate.
    bool on_seam(Vertex v) const {
        if (!huv_) return false;
        const Halfedge start = m_.halfedge(v);
        if (!start.is_valid()) return false;
        bool have = false;
        TexCoord uv;
        Halfedge g = start;
        do {
            const Halfedge in = HalfedgeMesh::twin(g);
            if (!m_.is_boundary(in)) {
                if (!have) {
                    uv = huv_[in];
                    have = true;
                } else if (huv_[in] != uv) {
                    return true;
                }
            }
            g = m_.ccw_rotated(g);
        } while (g != start);
        return false;
    }

    // The number of sharp edges at v (3 for a tagged corner; at most 3); 0 without features.
    // Cached per vertex (fcount_, refreshed around each collapse): the legality checks ask it
    // for both ends of every edge they price.
    unsigned feature_count(Vertex v) const {
        if (!sharp_ && !corner_) return 0;
        return fcount_[v.idx()];
    }
    // The same, counted on v's ring.
    unsigned count_features_at(Vertex v) const {
        if (corner_ && corner_[v]) return 3;
        if (!sharp_) return 0;
        const Halfedge start = m_.halfedge(v);
        if (!start.is_valid()) return 0;
        unsigned n = 0;
        Halfedge g = start;
        do {
            if (sharp_[HalfedgeMesh::edge(g)] > 0.0f && ++n == 3) return n;
            g = m_.ccw_rotated(g);
        } while (g != start);
        return n;
    }

    // Whether v stays where it is: a texture seam vertex, one with a coincident copy, or a
    // feature vertex (on a sharp edge, or a tagged corner).
    bool pinned(Vertex v) const {
        return coincident_[v.idx()] || on_seam(v) || feature_count(v) > 0;
    }

    // Whether h (from_vertex moves into to_vertex) is an allowed direction: a boundary vertex
    // only moves along a boundary edge; a feature vertex only when it is a crease (two sharp
    // edges) and h runs along one of them (corners and the ends of feature curves never move);
    // other pinned vertices never move.
    bool direction_allowed(Halfedge h, bool boundary_edge) const {
        const Vertex from = m_.from_vertex(h);
        if (boundary_[from.idx()] && !boundary_edge) return false;
        if (coincident_[from.idx()]) return !on_seam(from) && seam_partner(h).is_valid();
        if (const unsigned k = feature_count(from); k > 0)
            return k == 2 && sharp_[HalfedgeMesh::edge(h)] > 0.0f && !on_seam(from);
        return !pinned(from);
    }

    // The other side of a seam collapse: for h = a -> b along a boundary edge, where a has
    // exactly one copy a' and a' has exactly one boundary edge to a copy b' of b, the
    // halfedge a' -> b' (collapsing both keeps a' on a and b' on b); invalid otherwise.
    Halfedge seam_partner(Halfedge h) const {
        const Vertex a = m_.from_vertex(h), b = m_.to_vertex(h);
        const Vertex a2 = copy_[a.idx()];
        const Index gb = group_[b.idx()];
        if (!a2.is_valid() || gb == kInvalidIndex || !m_.is_boundary(HalfedgeMesh::edge(h)) ||
            on_seam(a2))
            return Halfedge();
        Halfedge found;
        const Halfedge start = m_.halfedge(a2);
        Halfedge g = start;
        do {
            if (group_[m_.to_vertex(g).idx()] == gb && m_.is_boundary(HalfedgeMesh::edge(g))) {
                if (found.is_valid()) return Halfedge();  // ambiguous
                found = g;
            }
            g = m_.ccw_rotated(g);
        } while (g != start);
        return found;
    }

    // The link condition on the welded surface (core/algorithms/weld.h: every coincident group as
    // one vertex) of collapsing h, with h2 the other side of a seam collapse (else invalid): the
    // only vertices next to both ends are the third corners of the faces at the edge, which
    // differ. So the result can still be welded: no two faces folded onto each other, no edge
    // doubled between two groups.
    bool welded_link_ok(Halfedge h, Halfedge h2) const {
        const auto id = [&](Vertex v) {
            const Index g = group_[v.idx()];
            return g != kInvalidIndex ? std::uint64_t(g) : std::uint64_t(kInvalidIndex) + v.idx();
        };
        std::uint64_t ends[2];
        unsigned n_ends = 0;
        for (Halfedge k : {h, h2}) {
            if (!k.is_valid()) continue;
            for (Halfedge f : {k, HalfedgeMesh::twin(k)})
                if (!m_.is_boundary(f)) ends[n_ends++] = id(m_.to_vertex(m_.next(f)));
        }
        if (n_ends == 2 && ends[0] == ends[1]) return false;
        const Vertex kept = m_.to_vertex(h);
        const std::uint64_t a = id(m_.from_vertex(h)), b = id(kept);
        std::uint64_t around_a[128];
        unsigned n = 0;
        for (Halfedge k : {h, h2}) {
            if (!k.is_valid()) continue;
            for (Vertex w : m_.vertices_around(m_.from_vertex(k))) {
                if (n == 128) return false;
                around_a[n++] = id(w);
            }
        }
        // The kept end's copies (itself when it has none).
        const Index g = group_[kept.idx()];
        const Index self = kept.idx();
        const Index* copies = g == kInvalidIndex ? &self : groups_.begin(g);
        const Index* copies_end = g == kInvalidIndex ? &self + 1 : groups_.end(g);
        for (const Index* c = copies; c != copies_end; ++c) {
            const Vertex copy(*c);
            if (m_.is_deleted(copy) || m_.is_isolated(copy)) continue;
            for (Vertex w : m_.vertices_around(copy)) {
                const std::uint64_t x = id(w);
                if (x == a || x == b || std::find(ends, ends + n_ends, x) != ends + n_ends)
                    continue;
                if (std::find(around_a, around_a + n, x) != around_a + n) return false;
            }
        }
        return true;
    }

    // Whether the one-rings of a and b (with a and b) share no vertex: then collapsing an
    // edge at a leaves the link condition at b as it was.
    bool rings_apart(Vertex a, Vertex b) const {
        Vertex ring[64];
        unsigned n = 0;
        ring[n++] = a;
        for (Vertex w : m_.vertices_around(a)) {
            if (n == 64) return false;
            ring[n++] = w;
        }
        if (std::find(ring, ring + n, b) != ring + n) return false;
        for (Vertex w : m_.vertices_around(b))
            if (std::find(ring, ring + n, w) != ring + n) return false;
        return true;
    }

    // Smallest normalized roundness of the faces at v (other than f0, f1) with v at p.
    double min_roundness_at(Vertex v, const Point& p, Face f0, Face f1) const {
        double r = 1.0;
        const Halfedge start = m_.halfedge(v);
        Halfedge g = start;
        do {
            const Face f = m_.face(g);
            if (f.is_valid() && f != f0 && f != f1) {
                const Halfedge n = m_.next(g);
                r = std::min(r, normalized_roundness(p, c_.position(m_.to_vertex(g)),
                                                     c_.position(m_.to_vertex(n))));
            }
            g = m_.ccw_rotated(g);
        } while (g != start);
        return r;
    }

    // Whether collapsing `from` into `kept` along edge e moves the kept vertex along their
    // feature curve (both crease vertices of one input curve, e sharp): FeatureCurves.
    bool along_curve(Vertex from, Vertex kept, Edge e) const {
        if (curves_.empty() || !(sharp_[e] > 0.0f)) return false;
        const Index c = curves_.curve(from);
        return c != FeatureCurves::kNone && c == curves_.curve(kept);
    }
    // The placement of such a collapse: the quadric's minimum over the input curve between them.
    FeatureCurves::Placement curve_placement(Vertex from, Vertex kept) const {
        // The other neighbours along the curve: of from, and of kept.
        const auto beyond = [&](Vertex v, Vertex other) {
            for (Halfedge g : m_.halfedges_around(v))
                if (sharp_[HalfedgeMesh::edge(g)] > 0.0f && m_.to_vertex(g) != other)
                    return m_.to_vertex(g);
            return Vertex();
        };
        return curves_.place(quadric_[from.idx()] + quadric_[kept.idx()], from, kept,
                             beyond(from, kept), beyond(kept, from));
    }

    // The best collapse of edge e: false when no direction is allowed.
    bool evaluate(Edge e, EdgeChoice& out) const {
        const Halfedge h0 = HalfedgeMesh::halfedge(e, 0), h1 = HalfedgeMesh::halfedge(e, 1);
        if (coincident_[m_.to_vertex(h0).idx()] && coincident_[m_.to_vertex(h1).idx()])
            return evaluate_seam(e, out);
        const bool be = m_.is_boundary(e);
        const bool ok0 = direction_allowed(h0, be), ok1 = direction_allowed(h1, be);
        if (!ok0 && !ok1) return false;
        const Vertex a = m_.from_vertex(h0), b = m_.to_vertex(h0);
        const Point &xa = c_.position(a), &xb = c_.position(b);
        double cost;
        if (o_.cost == DecimationCost::Quadric) {
            const Quadric q = quadric_[a.idx()] + quadric_[b.idx()];
            unsigned dir = ok0 ? 0 : 1;
            Point p;
            if (ok0 && along_curve(a, b, e)) {
                // (No room between the outer neighbours: b stays where it is.)
                const FeatureCurves::Placement pl = curve_placement(a, b);
                p = std::isfinite(pl.cost) ? pl.p : xb;
                cost = std::isfinite(pl.cost) ? pl.cost : q(xb);
            } else if (ok0 && ok1 && !pinned(a) && !pinned(b)) {
                // Both may move: optimal placement, else the best of the ends and midpoint
                // (two crease vertices may each move along their curve, but stay on it: the
                // branches below keep one where it is).
                const Point mid = 0.5 * (xa + xb);
                const double len = (xb - xa).norm();
                if (q.optimize(p) && (p - mid).norm() <= kMaxPlacementDistance * len) {
                    cost = q(p);
                } else {
                    const double ca = q(xa), cb = q(xb), cm = q(mid);
                    if (ca < cb && ca < cm) {
                        p = xa;
                        cost = ca;
                        dir = 1;  // keep a
                    } else if (cb <= cm) {
                        p = xb;
                        cost = cb;
                    } else {
                        p = mid;
                        cost = cm;
                    }
                }
            } else if (ok0 && (!boundary_[b.idx()] || be) && !pinned(b)) {
                // Only a may move, b is free: optimal placement still applies to b... unless b
                // is pinned (boundary vertex at an interior edge, a seam or coincident vertex).
                if (!(q.optimize(p) &&
                      (p - 0.5 * (xa + xb)).norm() <= kMaxPlacementDistance * (xb - xa).norm()))
                    p = xb;
                cost = q(p);
            } else if (ok1 && (!boundary_[a.idx()] || be) && !pinned(a)) {
                if (!(q.optimize(p) &&
                      (p - 0.5 * (xa + xb)).norm() <= kMaxPlacementDistance * (xb - xa).norm()))
                    p = xa;
                cost = q(p);
            } else {
                p = ok0 ? xb : xa;  // the kept vertex is pinned where it is
                cost = q(p);
            }
            out.dir = std::uint8_t(dir);
            out.target = p;
        } else {
            // Roundness: halfedge collapses (the kept vertex stays); the rounder one.
            double r0 = -1, r1 = -1;
            const Face fa = m_.face(h0), fb = m_.face(h1);
            if (ok0) r0 = min_roundness_at(a, xb, fa, fb);
            if (ok1) r1 = min_roundness_at(b, xa, fa, fb);
            const unsigned dir = r0 >= r1 ? 0 : 1;
            out.dir = std::uint8_t(dir);
            out.target = dir == 0 ? xb : xa;
            cost = -(dir == 0 ? r0 : r1);  // largest minimum roundness first
        }
        out.cost = cost;
        return true;
    }

    // An edge between two coincident vertices: only a seam collapse (both sides at once, the
    // kept copies staying where they are), costed with the quadrics of both sides (the welded
    // vertex's) or the smaller roundness of the two sides.
    bool evaluate_seam(Edge e, EdgeChoice& out) const {
        bool any = false;
        for (unsigned dir = 0; dir < 2; ++dir) {
            const Halfedge h = HalfedgeMesh::halfedge(e, dir);
            if (!direction_allowed(h, true)) continue;
            const Halfedge h2 = seam_partner(h);
            const Vertex a = m_.from_vertex(h), b = m_.to_vertex(h);
            const Vertex a2 = m_.from_vertex(h2), b2 = m_.to_vertex(h2);
            double cost;
            if (o_.cost == DecimationCost::Quadric) {
                const Quadric q =
                    quadric_[a.idx()] + quadric_[b.idx()] + quadric_[a2.idx()] + quadric_[b2.idx()];
                cost = q(c_.position(b));
            } else {
                cost = -std::min(
                    min_roundness_at(a, c_.position(b), m_.face(h), m_.face(HalfedgeMesh::twin(h))),
                    min_roundness_at(a2, c_.position(b2), m_.face(h2),
                                     m_.face(HalfedgeMesh::twin(h2))));
            }
            if (!any || cost < out.cost) {
                out.cost = cost;
                out.dir = std::uint8_t(dir);
                out.target = c_.position(b);
            }
            any = true;
        }
        return any;
    }

    // Prices edge e: stores its cost (direction and placement are recomputed when the edge
    // comes up, which keeps this array at 8 bytes an edge) and, when the heap is in use,
    // moves its key there; cost kNoCollapse (out of the heap) when no direction is allowed.
    void price(Edge e) {
        EdgeChoice c;
        EdgeCost& ec = edge_[e.idx()];
        if (outside_region(e) || !evaluate(e, c)) {
            ec.cost = kNoCollapse;
            if (heap_active_ && heap_.contains(e.idx())) heap_.remove(e.idx());
            return;
        }
        // +0.0f turns a -0 into +0 (the heap key orders the two apart). A cost beyond float's
        // range (coordinates near 1e30 give quadric errors near 1e60) saturates just below
        // kNoCollapse: the edge stays a candidate instead of overflowing to infinity, which
        // compares as kNoCollapse or above and would take it out of the heap.
        const float cost = float(std::min(c.cost, kLargestCost)) + 0.0f;
        ec.cost = cost;
        if (!heap_active_) return;
        if (heap_.contains(e.idx()))
            heap_.update(edge_key(cost, e.idx()));
        else
            heap_.push(edge_key(cost, e.idx()));
    }

    // Whether e has an end of weight 0 (outside the region): it never collapses.
    bool outside_region(Edge e) const {
        if (!region_ptr_) return false;
        const Halfedge h = HalfedgeMesh::halfedge(e, 0);
        const std::vector<float>& w = *region_ptr_;
        return !(w[m_.from_vertex(h).idx()] > 0.0f && w[m_.to_vertex(h).idx()] > 0.0f);
    }

    // ---- legality ---------------------------------------------------------------------------
    // Whether every face at v (other than f0, f1) keeps its normal within the angle when v
    // moves to p, and does not degenerate.
    // With `turn` (explain()), every face is measured instead of stopping at the first
    // refusal: the smallest cosine of a normal change, and whether a face degenerates.
    bool normals_ok(Vertex v, const Point& p, Face f0, Face f1,
                    NormalChange* turn = nullptr) const {
        const Point& x = c_.position(v);
        const Halfedge start = m_.halfedge(v);
        bool ok = true;
        Halfedge g = start;
        do {
            const Face f = m_.face(g);
            if (f.is_valid() && f != f0 && f != f1) {
                const Point& a = c_.position(m_.to_vertex(g));
                const Point& b = c_.position(m_.to_vertex(m_.next(g)));
                const Vector3 before = (a - x).cross(b - x);
                const Vector3 after = (a - p).cross(b - p);
                const double nb = before.norm(), na = after.norm();
                const bool degenerate = !(na > 1e-14 * (a - b).squaredNorm());
                const bool turned = nb > 0 && before.dot(after) < cos_max_angle_ * nb * na;
                if (turn) {
                    turn->degenerate |= degenerate;
                    turn->refused |= turned;
                    if (nb > 0 && na > 0)
                        turn->smallest_cos =
                            std::min(turn->smallest_cos, before.dot(after) / (nb * na));
                }
                if (degenerate || turned) {
                    if (!turn) return false;
                    ok = false;
                }
            }
            g = m_.ccw_rotated(g);
        } while (g != start);
        return ok;
    }

    // Whether the collapse chosen for an edge is above max_error (Quadric: its cost is the
    // error; Roundness checks the error in check()).
    bool above_max_error(const EdgeChoice& c) const {
        return o_.cost == DecimationCost::Quadric && c.cost > max_error2_;
    }

    // The binary constraints and the link condition for collapsing h to p, in this order;
    // returns the first refusal. With `why` every constraint is evaluated (none stops the
    // others) and its answer and numbers are written there (explain()); without, the first
    // refusal returns at once (the run).
    Refusal check(Halfedge h, const Point& p, CollapseExplanation* why = nullptr) const {
        Refusal first = Refusal::None;
        // Records a refusal; true: return now.
        const auto refuse = [&](Refusal r) {
            if (first == Refusal::None) first = r;
            return why == nullptr;
        };
        const Vertex v0 = m_.from_vertex(h), v1 = m_.to_vertex(h);
        if (o_.independent_set &&
            (locked_[v0.idx()] == iteration_ || locked_[v1.idx()] == iteration_)) {
            if (why) why->independent_set_refuses = true;
            if (refuse(Refusal::IndependentSet)) return first;
        }
        if (o_.cost == DecimationCost::Roundness && (o_.max_error > 0 || why)) {
            const double err2 = (quadric_[v0.idx()] + quadric_[v1.idx()])(p);
            if (why) why->error = std::sqrt(std::max(0.0, err2));
            if (o_.max_error > 0 && err2 > max_error2_) {
                if (why) why->max_error_refuses = true;
                if (refuse(Refusal::MaxError)) return first;
            }
        }
        if (!m_.is_collapse_ok(h)) {
            if (why) why->topology_ok = false;
            if (refuse(Refusal::Topology)) return first;
        }
        if (huv_ && on_seam(v0)) {
            if (why) why->texture_seam = true;
            if (refuse(Refusal::Seam)) return first;
        }
        NormalChange turn;  // the largest normal change (explain() only)
        double roundness = 1;
        NormalChange* const turn_out = why ? &turn : nullptr;
        if (coincident_[v0.idx()]) {
            // A seam collapse: the other side must be legal at the same time, and the pair
            // may not overshoot the target.
            const Halfedge h2 = seam_partner(h);
            if (!h2.is_valid() || outside_region(HalfedgeMesh::edge(h2)) ||
                m_.n_vertices() < target_ + 2 || !m_.is_collapse_ok(h2) ||
                !rings_apart(v0, m_.from_vertex(h2)) || !welded_link_ok(h, h2)) {
                if (why) why->topology_ok = false;
                if (refuse(Refusal::Topology) || !h2.is_valid()) return first;
            }
            const Vertex w0 = m_.from_vertex(h2), w1 = m_.to_vertex(h2);
            if (o_.independent_set &&
                (locked_[w0.idx()] == iteration_ || locked_[w1.idx()] == iteration_)) {
                if (why) why->independent_set_refuses = true;
                if (refuse(Refusal::IndependentSet)) return first;
            }
            const Point& p2 = c_.position(w1);
            const Face g0 = m_.face(h2), g1 = m_.face(HalfedgeMesh::twin(h2));
            if ((o_.normal_flip || why) &&
                (!normals_ok(w0, p2, g0, g1, turn_out) || !normals_ok(w1, p2, g0, g1, turn_out))) {
                if (o_.normal_flip && refuse(Refusal::NormalFlip)) return first;
            }
            if (o_.roundness || why) {
                roundness =
                    std::min(min_roundness_at(w0, p2, g0, g1), min_roundness_at(w1, p2, g0, g1));
                if (o_.roundness && roundness < o_.min_roundness && refuse(Refusal::Roundness))
                    return first;
            }
        } else if (!groups_.empty() && !welded_link_ok(h, Halfedge())) {
            if (why) why->topology_ok = false;
            if (refuse(Refusal::Topology)) return first;
        }
        const Face f0 = m_.face(h), f1 = m_.face(HalfedgeMesh::twin(h));
        if ((o_.normal_flip || why) &&
            (!normals_ok(v0, p, f0, f1, turn_out) || !normals_ok(v1, p, f0, f1, turn_out))) {
            if (o_.normal_flip && refuse(Refusal::NormalFlip)) return first;
        }
        if (o_.roundness || why) {
            roundness = std::min(roundness, std::min(min_roundness_at(v0, p, f0, f1),
                                                     min_roundness_at(v1, p, f0, f1)));
            if (o_.roundness && roundness < o_.min_roundness && refuse(Refusal::Roundness))
                return first;
        }
        if (why) {
            why->largest_normal_change =
                std::acos(std::min(1.0, std::max(-1.0, turn.smallest_cos))) * 180.0 / M_PI;
            why->degenerate_face = turn.degenerate;
            why->normal_flip_refuses = o_.normal_flip && (turn.refused || turn.degenerate);
            why->roundness = roundness;
            why->roundness_refuses = o_.roundness && roundness < o_.min_roundness;
        }
        return first;
    }

    static CollapseRefusal public_refusal(Refusal r) {
        switch (r) {
            case Refusal::None:
                return CollapseRefusal::None;
            case Refusal::Topology:
                return CollapseRefusal::Topology;
            case Refusal::NormalFlip:
                return CollapseRefusal::NormalFlip;
            case Refusal::Roundness:
                return CollapseRefusal::Roundness;
            case Refusal::IndependentSet:
                return CollapseRefusal::IndependentSet;
            case Refusal::MaxError:
                return CollapseRefusal::MaxError;
            case Refusal::Seam:
                return CollapseRefusal::TextureSeam;
        }
        return CollapseRefusal::None;
    }

    void count(Refusal r) {
        switch (r) {
            case Refusal::Topology:
                ++report_.refused_topology;
                break;
            case Refusal::NormalFlip:
                ++report_.refused_normal_flip;
                break;
            case Refusal::Roundness:
                ++report_.refused_roundness;
                break;
            case Refusal::IndependentSet:
                ++report_.refused_independent_set;
                break;
            case Refusal::MaxError:
                ++report_.refused_max_error;
                break;
            case Refusal::Seam:
                ++report_.refused_texture_seam;
                break;
            case Refusal::None:
                break;
        }
    }

    // ---- the collapse -----------------------------------------------------------------------
    // An edge about to be deleted: no cost, out of the heap.
    void forget(Edge e) {
        if (heap_.contains(e.idx())) heap_.remove(e.idx());
        edge_[e.idx()].cost = kNoCollapse;
        stale_[e.idx()] = 0;
    }

    // Collapses h to p; a seam collapse (from a coincident vertex) collapses the other side
    // too, and re-prices the first side's edges again (their cost reads both sides).
    void collapse(Halfedge h, const Point& p) {
        if (!coincident_[m_.from_vertex(h).idx()]) {
            collapse_one(h, p);
            return;
        }
        const Halfedge h2 = seam_partner(h);  // check() made sure it exists
        const Vertex kept = m_.to_vertex(h), kept2 = m_.to_vertex(h2);
        collapse_one(h, p);
        collapse_one(h2, c_.position(kept2));
        const Halfedge start = m_.halfedge(kept);
        Halfedge g = start;
        do {
            price(HalfedgeMesh::edge(g));
            g = m_.ccw_rotated(g);
        } while (g != start);
    }

    // Before collapsing h (faces f0 at h, f1 at its twin): the edge that survives in each face
    // (prev(h), prev(o)) keeps the larger sharpness of the two edges it merges with (next(h),
    // next(o)), so feature curves stay. Returns the faces' third corners (invalid where a face
    // is missing): with the kept vertex, the vertices whose sharp edges may have merged.
    std::array<Vertex, 2> merge_sharpness(Halfedge h, Face f0, Face f1) {
        const Halfedge o = HalfedgeMesh::twin(h);
        const Vertex third0 = f0.is_valid() ? m_.to_vertex(m_.next(h)) : Vertex();
        const Vertex third1 = f1.is_valid() ? m_.to_vertex(m_.next(o)) : Vertex();
        // The edge that survives in each face at h (prev(h), prev(o)) keeps the larger
        // sharpness of the two edges it merges with (next(h), next(o)): feature curves stay.
        if (sharp_) {
            if (f0.is_valid()) {
                float& s = sharp_[HalfedgeMesh::edge(m_.prev(h))];
                s = std::max(s, sharp_[HalfedgeMesh::edge(m_.next(h))]);
            }
            if (f1.is_valid()) {
                float& s = sharp_[HalfedgeMesh::edge(m_.prev(o))];
                s = std::max(s, sharp_[HalfedgeMesh::edge(m_.next(o))]);
            }
        }
        return {third0, third1};
    }

    void collapse_one(Halfedge h, const Point& p) {
        const Halfedge o = HalfedgeMesh::twin(h);
        const Vertex v0 = m_.from_vertex(h), v1 = m_.to_vertex(h);
        const Face f0 = m_.face(h), f1 = m_.face(o);
        // Along a feature curve the kept vertex takes the parameter of its new place.
        if (along_curve(v0, v1, HalfedgeMesh::edge(h)))
            if (const FeatureCurves::Placement pl = curve_placement(v0, v1); std::isfinite(pl.cost))
                curves_.params()[v1.idx()] = pl.t;

        if (pm_) {
            VertexSplit s;
            s.removed = v0;
            s.kept = v1;
            s.removed_position = c_.position(v0);
            s.kept_before = c_.position(v1);
            s.kept_after = p;
            s.faces = {f0, f1};
            // The faces at v1 after the collapse: v0's (moved to v1), then v1's own.
            s.moved_begin = std::uint32_t(pm_->ring_faces.size());
            for (int side = 0; side < 2; ++side) {
                const Halfedge start = m_.halfedge(side == 0 ? v0 : v1);
                Halfedge g = start;
                do {
                    const Face f = m_.face(g);
                    if (f.is_valid() && f != f0 && f != f1) pm_->ring_faces.push_back(f);
                    g = m_.ccw_rotated(g);
                } while (g != start);
                if (side == 0) s.moved_end = std::uint32_t(pm_->ring_faces.size());
            }
            s.ring_end = std::uint32_t(pm_->ring_faces.size());
            if (pm_->ring_faces.size() >= std::numeric_limits<std::uint32_t>::max())
                throw Error("decimate: the progressive mesh outgrew its 32-bit face list");
            pm_->collapses.push_back(s);
        }

        // Texture coordinates: per vertex, interpolated along the edge at p's projection.
        const Point x0 = c_.position(v0), x1 = c_.position(v1);
        const double len2 = (x1 - x0).squaredNorm();
        const double t =
            len2 > 0 ? std::min(1.0, std::max(0.0, (p - x0).dot(x1 - x0) / len2)) : 1.0;
        if (vuv_) vuv_[v1] = (1 - t) * vuv_[v0] + t * vuv_[v1];
        // Per corner: v0 is not on a seam (checked), so all its corners share one uv.
        bool pinned_corners = false;
        TexCoord corner_uv = TexCoord::Zero();
        if (huv_) {
            const TexCoord uv1 =
                f0.is_valid() ? huv_[h] : huv_[m_.prev(o)];  // v1's corner at the edge
            const TexCoord uv0 = f0.is_valid() ? huv_[m_.prev(h)] : huv_[o];
            if (on_seam(v1)) {
                pinned_corners = true;
                corner_uv = uv1;
            } else {
                corner_uv = (1 - t) * uv0 + t * uv1;
            }
            if (pinned_corners) {
                // v0's corners take v1's uv on this side of the seam.
                const Halfedge start = m_.halfedge(v0);
                Halfedge g = start;
                do {
                    const Halfedge in = HalfedgeMesh::twin(g);
                    if (!m_.is_boundary(in)) huv_[in] = corner_uv;
                    g = m_.ccw_rotated(g);
                } while (g != start);
            }
        }

        // The degenerate faces' surviving halfedges take over a neighbour face's corner at v1
        // (HalfedgeMesh::remove_loop): prev(h) replaces twin(next(h)), prev(o) replaces
        // twin(next(o)), a corner of v0's side.
        const Halfedge survivor0 = f0.is_valid() ? m_.prev(h) : Halfedge();
        const Halfedge survivor1 = f1.is_valid() ? m_.prev(o) : Halfedge();
        const TexCoord survivor0_uv =
            huv_ && f0.is_valid() ? huv_[HalfedgeMesh::twin(m_.next(h))] : TexCoord::Zero();

        const std::array<Vertex, 2> thirds = merge_sharpness(h, f0, f1);
        // The edges the collapse deletes: h's, and one more per face at it (remove_loop).
        forget(HalfedgeMesh::edge(h));
        if (f0.is_valid()) forget(HalfedgeMesh::edge(m_.next(h)));
        if (f1.is_valid()) forget(HalfedgeMesh::edge(m_.next(o)));
        m_.collapse_unchecked(h);  // check() ran is_collapse_ok(h)
        if (!fcount_.empty())
            for (Vertex v : {v1, thirds[0], thirds[1]})
                if (v.is_valid()) fcount_[v.idx()] = std::uint8_t(count_features_at(v));
        if (pinned_corners) {
            if (survivor0.is_valid() && !m_.is_deleted(survivor0)) huv_[survivor0] = survivor0_uv;
            if (survivor1.is_valid() && !m_.is_deleted(survivor1)) huv_[survivor1] = corner_uv;
        }
        m_.position(v1) = p;
        quadric_[v1.idx()] += quadric_[v0.idx()];
        boundary_[v1.idx()] |= boundary_[v0.idx()];
        parent_[v0.idx()] = v1;
        ++report_.collapses;

        const Halfedge start = m_.halfedge(v1);
        if (!start.is_valid()) return;
        Halfedge g = start;
        if ((huv_ && !pinned_corners) || o_.independent_set) {
            do {
                if (huv_ && !pinned_corners) {
                    const Halfedge in = HalfedgeMesh::twin(g);
                    if (!m_.is_boundary(in)) huv_[in] = corner_uv;
                }
                if (o_.independent_set) locked_[m_.to_vertex(g).idx()] = iteration_;
                g = m_.ccw_rotated(g);
            } while (g != start);
        }
        if (o_.independent_set) locked_[v1.idx()] = iteration_;

        reprice_around(v1, start);
    }

    // Re-prices after a collapse into v1 (start: an outgoing halfedge of v1).
    void reprice_around(Vertex v1, Halfedge start) {
        Halfedge g = start;
        if (defer_) {  // a batch pass: mark the same edges stale
            do {
                stale_[HalfedgeMesh::edge(g).idx()] = 1;
                if (o_.cost == DecimationCost::Roundness) {
                    const Halfedge ws = m_.halfedge(m_.to_vertex(g));
                    Halfedge k = ws;
                    do {
                        stale_[HalfedgeMesh::edge(k).idx()] = 1;
                        k = m_.ccw_rotated(k);
                    } while (k != ws);
                }
                g = m_.ccw_rotated(g);
            } while (g != start);
            return;
        }
        // Re-price: the edges at v1 (and, for roundness, at its neighbours, whose faces
        // changed shape). One walk lists the ring and asks the cache for the neighbours'
        // data, so the misses overlap instead of coming one pricing after the other.
        Edge ring[kRingPrefetch];
        unsigned n_ring = 0;
        do {
            if (n_ring < kRingPrefetch) {
                ring[n_ring++] = HalfedgeMesh::edge(g);
                prefetch_vertex(m_.to_vertex(g));
            }
            g = m_.ccw_rotated(g);
        } while (g != start);
        for (unsigned i = 0; i < n_ring; ++i) price(ring[i]);
        if (n_ring == kRingPrefetch) {  // a valence above the list: price the rest in place
            unsigned i = 0;
            do {
                if (i++ >= kRingPrefetch) price(HalfedgeMesh::edge(g));
                g = m_.ccw_rotated(g);
            } while (g != start);
        }
        if (o_.cost == DecimationCost::Roundness) {
            do {
                const Vertex w = m_.to_vertex(g);
                const Halfedge ws = m_.halfedge(w);
                Halfedge k = ws;
                do {
                    if (m_.to_vertex(k) != v1) price(HalfedgeMesh::edge(k));
                    k = m_.ccw_rotated(k);
                } while (k != ws);
                g = m_.ccw_rotated(g);
            } while (g != start);
        }
    }

    HalfedgeMesh& m_;
    // The same mesh for reading: m_'s mutable accessors (chosen even in const members, m_
    // being a reference) are write accesses that check the array's sharing and mark a change.
    const HalfedgeMesh& c_;
    const DecimationOptions& o_;
    ProgressiveMesh* pm_;
    DecimationReport& report_;
    std::vector<Index>* before_ = nullptr;  ///< see compact()
    bool may_compact_ = false;
    std::vector<float> region_;                       ///< the region, compacted with the mesh
    const std::vector<float>* region_ptr_ = nullptr;  ///< &region_, or null: no region
    double cos_max_angle_ = 0, max_error2_ = 0;
    std::vector<Quadric> quadric_;
    FeatureCurves curves_;                  ///< the input's feature curves, when features are kept
    std::vector<std::uint8_t> fcount_;      ///< feature_count() per vertex, when features are kept
    std::vector<EdgeCost> edge_;            ///< per edge: cost of its best collapse, heap position
    std::vector<std::uint8_t> boundary_;    ///< per vertex; v1 inherits v0's on collapse
    std::vector<std::uint8_t> coincident_;  ///< per vertex: has a coincident copy
    CoincidentGroups groups_;               ///< of the input
    std::vector<Index> group_;              ///< per vertex: its coincident group, if any
    std::vector<Vertex> copy_;              ///< per vertex: its only copy (groups of two)
    std::size_t target_ = 0;                ///< vertex count the current phase aims at
    std::vector<EdgeKey> batch_;
    std::vector<EdgeKey> threshold_bucket_;    ///< batch selection: the keys of one bucket
    std::vector<std::uint32_t> bucket_count_;  ///< batch selection: keys per bucket
    std::size_t candidates_ = 0;               ///< batch selection: edges that may collapse
    bool counted_ = false;  ///< bucket_count_ and candidates_ hold the current costs' counts
    std::vector<std::vector<EdgeKey>> chunk_keys_;  ///< batch selection: each chunk's keys
    std::vector<std::uint32_t> bucket_count2_;      ///< the second worker's histogram
    std::uint32_t pass_ = 0;
    std::vector<std::uint32_t> locked_;
    std::vector<Vertex> parent_;
    EdgeHeap<EdgeCost> heap_{edge_};
    bool heap_active_ = false;  ///< the exact phase: re-priced edges go into the heap
    // A batch pass defers re-pricing: a collapse marks the edges it changes stale instead, and
    // each stale edge is priced once, when the pass reaches it or after the pass (on two
    // threads). The same costs: an edge's price reads only its ends' quadrics, positions,
    // flags and rings, which change only in a collapse into one of its ends (or, for
    // roundness, a neighbour), and that collapse marks it. Not with coincident vertices, whose
    // price also reads a copy's ring.
    bool defer_ = false;
    std::vector<std::uint8_t> stale_;  ///< per edge: its cost awaits re-pricing (defer_)
    VertexProperty<TexCoord> vuv_;
    HalfedgeProperty<TexCoord> huv_;
    EdgeProperty<float> sharp_;            ///< "e:sharpness" when features are kept
    VertexProperty<std::uint8_t> corner_;  ///< "v:corner" when features are kept
    std::uint32_t iteration_ = 0;
};

void check_options(const DecimationOptions& o) {
    if (!(o.percent > 0 && o.percent <= 100))
        throw InvalidArgument("decimate: percent must be in (0, 100], got " +
                              number_text(o.percent));
    if (o.iterations < 1 || o.iterations > 1000)
        throw InvalidArgument("decimate: iterations must be from 1 to 1000, got " +
                              std::to_string(o.iterations));
    if (!(o.max_normal_angle > 0 && o.max_normal_angle <= 180))
        throw InvalidArgument("decimate: max_normal_angle must be in (0, 180] degrees, got " +
                              number_text(o.max_normal_angle));
    if (!(o.min_roundness > 0 && o.min_roundness <= 1))
        throw InvalidArgument("decimate: min_roundness must be in (0, 1], got " +
                              number_text(o.min_roundness));
    if (o.features == FeatureSource::Auto &&
        !(std::isfinite(o.feature_angle) && o.feature_angle > 0 && o.feature_angle <= 180))
        throw InvalidArgument("decimate: feature_angle must be in (0, 180] degrees, got " +
                              number_text(o.feature_angle));
    if (!(o.max_error >= 0) || !std::isfinite(o.max_error))
        throw InvalidArgument("decimate: max_error must be >= 0, got " + number_text(o.max_error));
}

std::string stop_text(DecimationStop stop, const DecimationReport& r, std::size_t target) {
    std::string s = "stopped at " + std::to_string(r.output_vertices) + " vertices (aimed at " +
                    std::to_string(target) + "): ";
    switch (stop) {
        case DecimationStop::MaxError:
            return s + "the next collapse would exceed the maximum error";
        case DecimationStop::Constraints:
            return s + "every remaining collapse was refused by a constraint (normal flip " +
                   std::to_string(r.refused_normal_flip) + ", roundness " +
                   std::to_string(r.refused_roundness) + ", independent set " +
                   std::to_string(r.refused_independent_set) + ", texture seam " +
                   std::to_string(r.refused_texture_seam) + " refusals in all)";
        case DecimationStop::Topology:
            return s +
                   "no remaining collapse keeps the mesh manifold with its topology (link "
                   "condition)";
        case DecimationStop::Done:
            break;
    }
    return "reached " + std::to_string(r.output_vertices) + " vertices";
}

/// The fine state of the progressive record: positions, faces and liveness of `work`.
void start_progressive_mesh(const HalfedgeMesh& work, ProgressiveMesh& pm) {
    pm.positions = work.positions();
    pm.faces.assign(work.faces_size(), {Vertex(), Vertex(), Vertex()});
    pm.face_alive.assign(work.faces_size(), 0);
    pm.vertex_alive.assign(work.vertices_size(), 0);
    for (Face f : work.faces()) {
        pm.faces[f.idx()] = work.face_vertices(f);
        pm.face_alive[f.idx()] = 1;
    }
    for (Vertex v : work.vertices()) pm.vertex_alive[v.idx()] = 1;
}

/// The vertices a percentage counts: the region's (with faces), or all `with_faces`.
std::size_t percent_base(const HalfedgeMesh& work, const DecimationOptions& options,
                         const std::vector<float>* region, std::size_t with_faces) {
    if (!region || options.target_vertices > 0) return with_faces;
    std::size_t counted = 0;
    for (Vertex u : work.vertices())
        if ((*region)[u.idx()] > 0.0f && !work.is_isolated(u)) ++counted;
    return counted;
}

/// Prepares the working copy: every vertex's input index in kDecimationSourceName, and a big
/// mesh (one the batches reduce) renumbered into the spatial order
/// (core/algorithms/spatial_order.h) for the cache and independence of the input's numbering,
/// unless the progressive record (in the input's numbering) is asked for or the input has garbage.
/// Returns each input vertex's working index; a region moves to `region` in the working numbering
/// (options.region then points there).
std::vector<Index> prepare_work_mesh(HalfedgeMesh& work, DecimationOptions& options,
                                     std::vector<float>& region) {
    {
        auto source = work.vertex_property<Index>(kDecimationSourceName);
        std::vector<Index>& s = source.vector();
        for (Index i = 0; i < s.size(); ++i) s[i] = i;
    }
    if (work.n_vertices() <= kExactVertices || options.record_progressive || work.has_garbage()) {
        std::vector<Index> identity(work.vertices_size());
        for (Index i = 0; i < identity.size(); ++i) identity[i] = i;
        return identity;
    }
    IndexRemap remap = renumber_spatially(work);
    if (options.region) {
        region.assign(work.vertices_size(), 0.0f);
        for (Index i = 0; i < remap.vertices.size(); ++i)
            region[remap.vertices[i]] = (*options.region)[i];
        options.region = &region;
    }
    return std::move(remap.vertices);
}

}  // namespace

DecimationResult decimate(const HalfedgeMesh& mesh, const DecimationOptions& options,
                          Progress& progress) {
    check_options(options);
    if (options.region) check_selection(mesh, *options.region, "decimate: region");
    if (options.features == FeatureSource::Stored)
        if (const std::string bad = check_features(mesh); !bad.empty())
            throw InvalidArgument("decimate: invalid features: " + bad);
    const auto t0 = std::chrono::steady_clock::now();
    DecimationResult result;
    DecimationReport& report = result.report;
    HalfedgeMesh work = mesh;
    if (options.features == FeatureSource::Auto) {
        FeatureDetectionOptions d;
        d.angle_deg = options.feature_angle;
        detect_features(work, d);
    }
    // before_to_work[i]: the working index of vertex i of the mesh before the iteration.
    DecimationOptions work_options = options;
    std::vector<float> work_region;
    std::vector<Index> before_to_work = prepare_work_mesh(work, work_options, work_region);
    ProgressiveMesh* pm = options.record_progressive ? &result.progressive : nullptr;
    if (pm) start_progressive_mesh(work, *pm);
    Decimater decimater(work, work_options, pm, report, true, &before_to_work);

    // Isolated vertices are kept and not counted: V is the number of vertices with faces.
    std::size_t isolated = 0;
    for (Vertex v : work.vertices())
        if (work.is_isolated(v)) ++isolated;
    report.isolated_vertices = isolated;
    report.input_vertices = work.n_vertices() - isolated;
    const int iterations = options.target_vertices > 0 ? 1 : options.iterations;
    std::size_t last_target = report.input_vertices;
    std::size_t final_vertices = work.n_vertices();
    bool any_collapse = false;
    std::size_t level_target = 0;  ///< the target of the last iteration that collapsed
    // One level from the working mesh: its geomorph from the mesh before (before_to_work
    // maps that mesh's vertices to working indices; updated for the next level).
    const auto make_level = [&](HalfedgeMesh& w, bool take, Decimater& d,
                                std::vector<Index>& before, std::size_t target) {
        DecimationLevel level;
        level.target_vertices = target;
        level.correspondence.kind = MorphCorrespondence::Kind::ToLater;
        if (options.record_geomorph) {
            level.correspondence.positions.resize(before.size());
            for (Index i = 0; i < before.size(); ++i) {
                const Vertex v(before[i]);
                level.correspondence.positions[i] =
                    w.position(w.is_deleted(v) ? d.representative(v) : v);
            }
        }
        if (take)
            level.mesh = std::move(w);
        else
            level.mesh = w;
        const IndexRemap remap = level.mesh.garbage_collection();
        if (!take) {
            std::vector<Index> next(level.mesh.vertices_size(), kInvalidIndex);
            for (Index v = 0; v < remap.vertices.size(); ++v)
                if (remap.vertices[v] != kInvalidIndex) next[remap.vertices[v]] = v;
            before = std::move(next);
        }
        return level;
    };
    for (int it = 0; it < iterations; ++it) {
        progress.check_cancelled();
        const std::size_t v = work.n_vertices() - isolated;
        const std::size_t counted = percent_base(work, work_options, decimater.region(), v);
        const std::size_t target =
            options.target_vertices > 0
                ? options.target_vertices
                : v - std::size_t(std::floor(options.percent / 100.0 * double(counted)));
        last_target = target;
        if (target >= v) break;  // nothing to remove (already small enough)
        const std::size_t collapses_before = report.collapses;
        DecimationStop stop = DecimationStop::Done;
        const bool reached = decimater.iterate(target + isolated, progress, double(it) / iterations,
                                               1.0 / iterations, stop);
        if (report.collapses > collapses_before) {
            final_vertices = work.n_vertices();
            any_collapse = true;
            level_target = target;
            ++report.iterations_done;
            if (options.levels == DecimationLevels::All) {
                // The last iteration takes the working mesh itself (no copy of a big mesh).
                result.levels.push_back(
                    make_level(work, it + 1 == iterations, decimater, before_to_work, target));
            }
        }
        if (!reached) {
            report.stop = stop;
            // Locks last one iteration: the next one may go on where this one stopped.
            const bool locked_only = options.independent_set &&
                                     stop == DecimationStop::Constraints &&
                                     report.collapses > collapses_before;
            if (!locked_only) break;
        } else {
            report.stop = DecimationStop::Done;
        }
    }
    if (options.levels == DecimationLevels::Last && any_collapse)
        result.levels.push_back(make_level(work, true, decimater, before_to_work, level_target));
    report.output_vertices = final_vertices - isolated;
    report.stop_message = stop_text(report.stop, report, last_target);
    report.ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    progress.report(1.0, "decimated");
    return result;
}

DecimationResult decimate(const HalfedgeMesh& mesh, const DecimationOptions& options) {
    NullProgress progress;
    return decimate(mesh, options, progress);
}

CollapseExplanation explain_collapse(const HalfedgeMesh& mesh, Edge e,
                                     const DecimationOptions& options) {
    check_options(options);
    if (!mesh.is_valid(e) || mesh.is_deleted(e))
        throw InvalidArgument("explain_collapse: edge " + std::to_string(e.idx()) +
                              " is not an edge of the mesh (" +
                              count_text(mesh.n_edges(), "edge", "edges") + ")");
    HalfedgeMesh work = mesh;  // shares the arrays (copy on write): nothing of `mesh` changes
    DecimationReport report;
    Decimater decimater(work, options, nullptr, report, false);
    return decimater.explain(e);
}

std::vector<std::array<Vertex, 2>> next_collapses(const HalfedgeMesh& mesh,
                                                  const DecimationOptions& options) {
    DecimationOptions o = options;
    o.iterations = 1;
    o.record_progressive = true;
    const DecimationResult r = decimate(mesh, o);
    std::vector<std::array<Vertex, 2>> pairs;
    pairs.reserve(r.progressive.collapses.size());
    for (const VertexSplit& s : r.progressive.collapses) pairs.push_back({s.removed, s.kept});
    return pairs;
}

}  // namespace trilab
