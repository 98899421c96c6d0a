// Hole filling after Liepa 2003: triangulation by dynamic programming (cut by chords for large
// loops), refinement to the surrounding density with Delaunay flips, fairing with the implicit
// Laplacian. See hole_filling.h for the method, its limits and its complexity.
#include "core/algorithms/hole_filling.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/SparseCholesky>

#include "core/algorithms/hole_filling_delaunay.h"
#include "core/algorithms/laplacian.h"
#include "core/algorithms/selection.h"
#include "core/errors.h"
#include "core/geometry.h"
#include "core/mesh_builder.h"

namespace trilab {

namespace {

/// The density factor: a triangle is split while kDensityFactor·|c - v| exceeds the spacing.
/// Liepa's sqrt(2) leaves the fill's edges 13-22 % longer than the old edges within two rings
/// of the rim (the bunny's five holes, holes cut in spot and the horse, a sphere's cap; CGAL's
/// fills, also sqrt(2), 14-20 %), and a coarser fill bends more across its rim than the surface
/// beside it; 1.6 brings the mean edge length within 1-9 % of the old. (On the cow, whose
/// triangles vary widely in size, the fill was 12 % finer and becomes 16 % finer.)
constexpr double kDensityFactor = 1.6;
/// Caps that keep a pathological rim from running away (each hit is reported).
constexpr int kMaxRefineRounds = 60;
constexpr int kMaxRelaxPasses = 50;
constexpr int kSmoothingRounds = 4;
constexpr int kRepairRounds = 3;
constexpr int kOptimizeSweeps = 3;
/// Random moves tried per cluster of new vertices around a triangle still under 20 degrees.
constexpr int kClusterTries = 2000;
/// Rounds of the last fairing, each holding more vertices where a triangle got too narrow.
constexpr int kRefairRounds = 4;
/// Only new vertices with an angle under this around them are moved by the angle optimization.
constexpr double kOptimizeBelowDeg = 25.0;
/// A loop whose best triangulation bends by more than this between neighbouring triangles (or
/// against the old faces) would fold back onto the surface: refused.
constexpr double kMaxFoldDeg = 150.0;
/// The largest fill (estimated faces after refinement) a loop may get; above, it is refused.
constexpr std::size_t kMaxEstimatedFaces = 2000000;
/// New vertices one loop may get (a loop whose rim spacing is tiny against its size).
constexpr Index kMaxPatchVertices = 4000000;
constexpr double kInf = std::numeric_limits<double>::infinity();

using Triangle = std::array<Vertex, 3>;

// ---- loops ------------------------------------------------------------------------------------

double rim_length(const HalfedgeMesh& mesh, const std::vector<Vertex>& rim) {
    double length = 0;
    for (std::size_t i = 0; i < rim.size(); ++i)
        length += (mesh.position(rim[(i + 1) % rim.size()]) - mesh.position(rim[i])).norm();
    return length;
}

// ---- checks -----------------------------------------------------------------------------------

void check_options(const HalfedgeMesh& mesh, const HoleFillingOptions& o, std::size_t n_loops) {
    if (o.max_edges && *o.max_edges < 0)
        throw InvalidArgument("max-edges: must be 0 or more, got " + std::to_string(*o.max_edges));
    if (o.max_diameter && (!std::isfinite(*o.max_diameter) || *o.max_diameter < 0))
        throw InvalidArgument("max-diameter: must be a finite fraction >= 0 of the diagonal");
    for (long long i : o.loops)
        if (i < 0 || std::size_t(i) >= n_loops)
            throw InvalidArgument(
                "loops: index " + std::to_string(i) + " is past the end (the mesh has " +
                std::to_string(n_loops) + " boundary loop" + (n_loops == 1 ? "" : "s") +
                (n_loops ? ", numbered 0 to " + std::to_string(n_loops - 1) : std::string()) + ")");
    if (o.region) check_selection(mesh, *o.region, "region");
}

std::vector<std::uint8_t> choose_loops(const HalfedgeMesh& mesh, const HoleFillingOptions& o,
                                       const std::vector<BoundaryLoop>& loops) {
    std::vector<std::uint8_t> chosen(loops.size(), o.loops.empty() ? 1 : 0);
    for (long long i : o.loops) chosen[std::size_t(i)] = 1;
    const double diagonal = bounding_box(mesh).diagonal();
    for (std::size_t i = 0; i < loops.size(); ++i) {
        const BoundaryLoop& l = loops[i];
        if (o.max_edges && (long long)l.edges() > *o.max_edges) chosen[i] = 0;
        if (o.max_diameter && l.diagonal > *o.max_diameter * diagonal) chosen[i] = 0;
        if (o.region) {
            bool touches = false;
            for (Vertex v : l.vertices) touches = touches || (*o.region)[v.idx()] > 0;
            if (!touches) chosen[i] = 0;
        }
    }
    return chosen;
}

std::string vertex_text(Vertex v) {
    return "vertex " + std::to_string(v.idx());
}

/// Per loop, why its rim is pinched ("" when it is not): a rim vertex at the same position as
/// another rim vertex, of the same loop (the loop touches itself) or of another (two holes
/// meeting at a point). Either is a non-manifold rim as loading splits it (one vertex per fan):
/// filling would close a surface that touches itself there. O(R log R) for R rim vertices.
std::vector<std::string> pinched_rims(const HalfedgeMesh& mesh,
                                      const std::vector<BoundaryLoop>& loops) {
    struct RimVertex {
        std::array<double, 3> key;
        std::size_t loop;
        Vertex v;
    };
    std::vector<RimVertex> all;
    for (std::size_t i = 0; i < loops.size(); ++i)
        for (Vertex v : loops[i].vertices) {
            const Point& p = mesh.position(v);
            all.push_back({{p.x(), p.y(), p.z()}, i, v});
        }
    std::sort(all.begin(), all.end(),
              [](const RimVertex& a, const RimVertex& b) { return a.key < b.key; });
    std::vector<std::string> why(loops.size());
    for (std::size_t k = 1; k < all.size(); ++k) {
        const RimVertex &a = all[k - 1], &b = all[k];
        if (a.key != b.key) continue;
        const std::string pair = vertex_text(a.v) + " and " + vertex_text(b.v);
        if (a.loop == b.loop) {
            if (why[a.loop].empty())
                why[a.loop] =
                    "the loop touches itself: " + pair +
                    " are at the same position (a pinched, non-manifold rim, or an open seam: "
                    "`weld` joins seams)";
            continue;
        }
        for (const auto& [mine, other] : {std::pair(a.loop, b.loop), std::pair(b.loop, a.loop)})
            if (why[mine].empty())
                why[mine] = "the rim touches loop " + std::to_string(other) + ": " + pair +
                            " are at the same position (a pinched, non-manifold rim, or the two "
                            "sides of an open seam: `weld` joins seams; filling would close a "
                            "surface that touches itself)";
    }
    return why;
}

/// Why the rim cannot be filled as it is, or "" when it can.
std::string rim_problem(const HalfedgeMesh& mesh, const BoundaryLoop& loop) {
    const std::vector<Vertex>& rim = loop.vertices;
    for (Vertex v : rim)
        if (!mesh.position(v).allFinite())
            return "a rim position is not finite (" + vertex_text(v) + ")";
    for (std::size_t i = 0; i < rim.size(); ++i) {
        const Vertex a = rim[i], b = rim[(i + 1) % rim.size()];
        if (mesh.position(a) == mesh.position(b))
            return "the rim edge from " + vertex_text(a) + " to " + vertex_text(b) +
                   " has zero length (weld the mesh first)";
    }
    if (rim.size() == 3) {
        const Halfedge h = mesh.find_halfedge(rim[0], rim[1]);
        const Face f = mesh.face(HalfedgeMesh::twin(h));
        const Halfedge g = mesh.find_halfedge(rim[1], rim[2]);
        if (f.is_valid() && f == mesh.face(HalfedgeMesh::twin(g)))
            return "its triangle is a face already (the fill would cover that face twice)";
    }
    return "";
}

// ---- triangulation ------------------------------------------------------------------------

/// Triangulates one loop (stage 1): pieces of at most kMaxDpLoop vertices by Liepa's dynamic
/// programme, larger ones cut by chords first. Triangles come out in an order where each one
/// is an ear of what is left of the hole (two of its edges on the current boundary) or closes
/// it (all three): the order insert_triangle() needs.
class LoopTriangulator {
public:
    LoopTriangulator(const HalfedgeMesh& mesh, const std::vector<Vertex>& rim)
        : mesh_(mesh), rim_(rim), outside_(rim.size(), Vector3::Zero()) {
        for (std::size_t i = 0; i < rim.size(); ++i) {
            const Halfedge h = mesh.find_halfedge(rim[i], rim[(i + 1) % rim.size()]);
            const Face f = mesh.face(HalfedgeMesh::twin(h));
            if (f.is_valid()) outside_[i] = face_normal(mesh, f);
        }
    }
    /// The triangles, or false with `why` set.
    bool run(std::vector<Triangle>& out, std::string& why) {
        if (rim_.size() > kMaxDpLoop && try_delaunay()) {
            out = std::move(triangles_);
            return true;
        }
        std::vector<Index> all(rim_.size());
        std::iota(all.begin(), all.end(), Index(0));
        ok_ = true;
        piece(all);
        if (!ok_) {
            why = why_;
            return false;
        }
        out = std::move(triangles_);
        return true;
    }
    bool was_cut() const { return cut_; }
    bool used_delaunay() const { return delaunay_; }
    /// Why a large loop was not triangulated over its Delaunay edges ("" when it was).
    const std::string& delaunay_fallback() const { return fallback_; }
    /// The largest dihedral angle (degrees) of the triangulation, the old faces across the rim
    /// included.
    double largest_dihedral_deg() const {
        return std::acos(std::clamp(1.0 - largest_measure_, -1.0, 1.0)) * 180.0 /
               3.14159265358979323846;
    }

private:
    const Point& p(Index i) const { return mesh_.position(rim_[i]); }
    /// Whether q[a] -> q[b] is a rim edge (consecutive along the loop).
    bool rim_edge(Index a, Index b) const { return b == (a + 1) % Index(rim_.size()); }
    bool is_edge(Index a, Index b) const {
        return mesh_.find_halfedge(rim_[a], rim_[b]).is_valid();
    }
    void piece(const std::vector<Index>& q) {
        if (!ok_) return;
        if (q.size() <= kMaxDpLoop) {
            dynamic_programme(q);
            return;
        }
        cut_ = true;
        const auto [a, b] = chord(q);
        if (a == b) {
            fail("no chord to cut this loop of " + std::to_string(q.size()) +
                 " vertices avoids the existing edges");
            return;
        }
        piece(std::vector<Index>(q.begin() + a, q.begin() + b + 1));
        std::vector<Index> rest(q.begin(), q.begin() + a + 1);
        rest.insert(rest.end(), q.begin() + b, q.end());
        piece(rest);
    }
    /// The shortest chord q[a] - q[b] with b - a between a third and two thirds of the piece
    /// that is no edge yet; (0, 0) when there is none.
    std::pair<std::size_t, std::size_t> chord(const std::vector<Index>& q) const {
        const std::size_t m = q.size(), lo = m / 3, hi = (2 * m) / 3;
        double best = kInf;
        std::pair<std::size_t, std::size_t> ab{0, 0};
        for (std::size_t a = 0; a < m; ++a)
            for (std::size_t b = a + lo; b <= std::min(a + hi, m - 1); ++b) {
                if (a == 0 && b == m - 1) continue;
                const double d = (p(q[a]) - p(q[b])).squaredNorm();
                if (d < best && !is_edge(q[a], q[b])) {
                    best = d;
                    ab = {a, b};
                }
            }
        return ab;
    }
    void fail(std::string why) {
        if (ok_) why_ = std::move(why);
        ok_ = false;
    }
    void dynamic_programme(const std::vector<Index>& q);
    using CandidateEdges = std::vector<std::pair<std::uint32_t, std::uint32_t>>;
    bool try_delaunay() {
        std::vector<Point> points;
        for (Vertex v : rim_) points.push_back(mesh_.position(v));
        const LoopDelaunay d = loop_delaunay_edges(points);
        if (d.why.empty() && restricted_programme(d.edges)) return delaunay_ = true;
        triangles_.clear();
        fallback_ = d.why.empty() ? "no triangulation over its Delaunay edges avoids the edges "
                                    "that exist already and triangles without area"
                                  : d.why;
        return false;
    }
    bool restricted_programme(const CandidateEdges& edges);
    /// The candidate edge (i, j), i < j, or kNoEdge.
    std::uint32_t find_edge(const CandidateEdges& edges, const std::vector<std::uint32_t>& row,
                            std::uint32_t i, std::uint32_t j) const {
        const auto first = edges.begin() + row[i], last = edges.begin() + row[i + 1];
        const auto it = std::lower_bound(first, last, std::pair(i, j));
        return it != last && it->second == j ? std::uint32_t(it - edges.begin()) : kNoEdge;
    }
    void emit_restricted(const CandidateEdges& edges, const std::vector<std::uint32_t>& row,
                         const std::vector<std::uint32_t>& best, std::uint32_t i, std::uint32_t j) {
        if (j < i + 2) return;
        const std::uint32_t k = best[find_edge(edges, row, i, j)];
        emit_restricted(edges, row, best, i, k);
        emit_restricted(edges, row, best, k, j);
        triangles_.push_back({rim_[i], rim_[k], rim_[j]});
    }
    static constexpr std::uint32_t kNoEdge = std::numeric_limits<std::uint32_t>::max();
    void emit(const std::vector<Index>& q, const std::vector<int>& best, std::size_t m,
              std::size_t i, std::size_t j) {
        if (j < i + 2) return;
        const std::size_t k = std::size_t(best[i * m + j]);
        emit(q, best, m, i, k);
        emit(q, best, m, k, j);
        triangles_.push_back({rim_[q[i]], rim_[q[k]], rim_[q[j]]});
    }

    const HalfedgeMesh& mesh_;
    const std::vector<Vertex>& rim_;
    std::vector<Vector3> outside_;  ///< per rim edge i -> i+1: the old face's unit normal
    std::vector<Triangle> triangles_;
    bool ok_ = true, cut_ = false, delaunay_ = false;
    std::string fallback_;
    double largest_measure_ = 0;
    std::string why_;
};

/// Liepa's weight of a sub-polygon: the largest dihedral measure (1 - cos) and the area.
struct Weight {
    double angle = kInf, area = kInf;
    bool better_than(const Weight& o) const {
        constexpr double kTie = 1e-12;
        if (angle < o.angle - kTie) return true;
        if (angle > o.angle + kTie) return false;
        return area < o.area;
    }
};

double dihedral_measure(const Vector3& n, const Vector3& other) {
    if (other.squaredNorm() == 0) return 0;
    return 1.0 - n.dot(other);
}

void LoopTriangulator::dynamic_programme(const std::vector<Index>& q) {
    const std::size_t m = q.size();
    std::vector<Weight> w(m * m);
    std::vector<int> best(m * m, -1);
    std::vector<Vector3> normal(m * m, Vector3::Zero());
    for (std::size_t i = 0; i + 1 < m; ++i) w[i * m + i + 1] = {0, 0};
    // The normal on the far side of edge q[i] - q[k] (k > i): the old face for a rim edge,
    // the sub-polygon's best triangle for a diagonal, none for a chord.
    const auto across = [&](std::size_t i, std::size_t k) -> Vector3 {
        if (k == i + 1) return rim_edge(q[i], q[k]) ? outside_[q[i]] : Vector3::Zero();
        return normal[i * m + k];
    };
    for (std::size_t len = 2; len < m; ++len)
        for (std::size_t i = 0; i + len < m; ++i) {
            const std::size_t j = i + len;
            const bool root = i == 0 && j == m - 1;
            if (!root && is_edge(q[i], q[j])) continue;  // stays infinite
            Weight bw;
            for (std::size_t k = i + 1; k < j; ++k) {
                const Weight& a = w[i * m + k];
                const Weight& b = w[k * m + j];
                if (a.area == kInf || b.area == kInf) continue;
                Vector3 n = (p(q[k]) - p(q[i])).cross(p(q[j]) - p(q[i]));
                const double longest =
                    std::max({(p(q[k]) - p(q[i])).squaredNorm(), (p(q[j]) - p(q[k])).squaredNorm(),
                              (p(q[j]) - p(q[i])).squaredNorm()});
                const double twice_area = n.norm();
                if (!(twice_area > 1e-10 * longest)) continue;  // no area: never used
                n /= twice_area;
                Weight c{std::max({a.angle, b.angle, dihedral_measure(n, across(i, k)),
                                   dihedral_measure(n, across(k, j))}),
                         a.area + b.area + 0.5 * twice_area};
                if (root && rim_edge(q[j], q[i]))
                    c.angle = std::max(c.angle, dihedral_measure(n, outside_[q[j]]));
                if (c.better_than(bw)) {
                    bw = c;
                    best[i * m + j] = int(k);
                    normal[i * m + j] = n;
                }
            }
            w[i * m + j] = bw;
        }
    if (w[m - 1].area == kInf) {
        fail("no triangulation of its " + std::to_string(m) +
             "-vertex rim avoids the edges between rim vertices that exist already and "
             "triangles without area (collinear rim vertices)");
        return;
    }
    largest_measure_ = std::max(largest_measure_, w[m - 1].angle);
    emit(q, best, m, 0, m - 1);
}

/// Liepa's programme over the candidate edges only (Zou, Ju and Carr 2013): the sub-polygon
/// between loop positions i < j exists only where (i, j) is a candidate edge, and is split by
/// a triangle (i, k, j) only where (i, k) and (k, j) are candidates too. Sub-polygons are
/// solved by increasing j - i. False (nothing emitted) when the whole loop has no solution.
bool LoopTriangulator::restricted_programme(const CandidateEdges& edges) {
    const std::uint32_t n = std::uint32_t(rim_.size());
    std::vector<std::uint32_t> row(n + 1, 0);  // edges from i: [row[i], row[i + 1])
    for (const auto& e : edges) ++row[e.first + 1];
    for (std::uint32_t i = 0; i < n; ++i) row[i + 1] += row[i];
    std::vector<std::uint32_t> order(edges.size());
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
        return edges[a].second - edges[a].first < edges[b].second - edges[b].first;
    });
    std::vector<Weight> w(edges.size());
    std::vector<std::uint32_t> best(edges.size(), kNoEdge);
    std::vector<Vector3> normal(edges.size(), Vector3::Zero());
    for (std::uint32_t id : order) {
        const auto [i, j] = edges[id];
        if (j == i + 1) {
            w[id] = {0, 0};
            continue;
        }
        const bool root = i == 0 && j == n - 1;
        if (!root && is_edge(Index(i), Index(j))) continue;  // stays infinite
        for (std::uint32_t r = row[i]; r < row[i + 1]; ++r) {
            const std::uint32_t k = edges[r].second;
            if (k >= j) break;
            const std::uint32_t kj = find_edge(edges, row, k, j);
            if (kj == kNoEdge || w[r].area == kInf || w[kj].area == kInf) continue;
            const Point &pi = p(Index(i)), &pk = p(Index(k)), &pj = p(Index(j));
            Vector3 nrm = (pk - pi).cross(pj - pi);
            const double longest = std::max(
                {(pk - pi).squaredNorm(), (pj - pk).squaredNorm(), (pj - pi).squaredNorm()});
            const double twice_area = nrm.norm();
            if (!(twice_area > 1e-10 * longest)) continue;
            nrm /= twice_area;
            const Vector3 across_ik = k == i + 1 ? outside_[i] : normal[r];
            const Vector3 across_kj = j == k + 1 ? outside_[k] : normal[kj];
            Weight c{std::max({w[r].angle, w[kj].angle, dihedral_measure(nrm, across_ik),
                               dihedral_measure(nrm, across_kj)}),
                     w[r].area + w[kj].area + 0.5 * twice_area};
            if (root) c.angle = std::max(c.angle, dihedral_measure(nrm, outside_[n - 1]));
            if (c.better_than(w[id])) {
                w[id] = c;
                best[id] = k;
                normal[id] = nrm;
            }
        }
    }
    const std::uint32_t root = find_edge(edges, row, 0, n - 1);
    if (root == kNoEdge || w[root].area == kInf) return false;
    largest_measure_ = std::max(largest_measure_, w[root].angle);
    emit_restricted(edges, row, best, 0, n - 1);
    return true;
}

// ---- insertion --------------------------------------------------------------------------------

/// Adds face (a, b, c) into the hole: two of its edges, a -> b and b -> c in some rotation,
/// are consecutive boundary halfedges; the third is new (an ear) or closes a three-edge hole.
void insert_triangle(HalfedgeMesh& mesh, Triangle t) {
    for (int rotation = 0; rotation < 3; ++rotation) {
        const Vertex a = t[0], b = t[1], c = t[2];
        const Halfedge h1 = mesh.find_halfedge(a, b), h2 = mesh.find_halfedge(b, c);
        if (h1.is_valid() && h2.is_valid() && mesh.is_boundary(h1) && mesh.is_boundary(h2) &&
            mesh.next(h1) == h2) {
            const Face f = mesh.new_face();
            const Halfedge h3 = mesh.next(h2);
            if (mesh.to_vertex(h3) == a && mesh.next(h3) == h1) {  // closes the hole
                for (Halfedge h : {h1, h2, h3}) mesh.set_face(h, f);
                mesh.set_halfedge(f, h1);
                for (Vertex v : {a, b, c}) mesh.adjust_outgoing_halfedge(v);
                return;
            }
            const Halfedge before = mesh.prev(h1);
            const Halfedge x = mesh.new_edge(c, a), y = HalfedgeMesh::twin(x);
            mesh.set_next(h2, x);
            mesh.set_next(x, h1);
            mesh.set_next(before, y);
            mesh.set_next(y, h3);
            for (Halfedge h : {h1, h2, x}) mesh.set_face(h, f);
            mesh.set_face(y, Face());
            mesh.set_halfedge(f, h1);
            mesh.set_halfedge(a, y);
            mesh.adjust_outgoing_halfedge(b);
            return;
        }
        t = {t[1], t[2], t[0]};
    }
    throw std::logic_error("fill_holes: a triangle is not an ear of the hole");
}

// ---- refinement -------------------------------------------------------------------------------

/// The angle at corner `at` of the triangle (at, u, v), in radians.
double corner_angle(const Point& at, const Point& u, const Point& v) {
    const Vector3 a = u - at, b = v - at;
    return std::atan2(a.cross(b).norm(), a.dot(b));
}

/// One patch being refined and faired: its vertices, edges and faces are those at or past
/// the first indices (everything added since the loop's fill began).
class Patch {
public:
    Patch(HalfedgeMesh& mesh, Index v0, Index e0, Index f0, std::vector<double>& spacing)
        : mesh_(mesh), v0_(v0), e0_(e0), f0_(f0), spacing_(spacing) {}

    /// Liepa's refinement; false when a cap was hit (said in `note`).
    bool refine(std::string& note) {
        // A worklist of faces to test: every split and every flip after it queues the faces
        // it touched, so a refinement that travels along a thin hole goes on in one sweep
        // (Lawson's flips keep the patch Delaunay after each split).
        std::vector<Face> work;
        for (Index fi = f0_; fi < Index(mesh_.faces_size()); ++fi) work.push_back(Face(fi));
        for (int round = 0; round < kMaxRefineRounds; ++round) {
            std::size_t splits = 0;
            while (!work.empty()) {
                const Face f = work.back();
                work.pop_back();
                splits += split_if_coarse(f, work) ? 1 : 0;
                if (mesh_.vertices_size() > std::size_t(kMaxPatchVertices) + v0_) {
                    note = "refinement stopped at " + std::to_string(kMaxPatchVertices) +
                           " new vertices";
                    return false;
                }
            }
            const Index edges_end = Index(mesh_.edges_size());
            for (Index e = e0_; e < edges_end; ++e)
                if (split_if_long(Edge(e), work)) ++splits;
            if (splits == 0) return true;
        }
        note = "refinement stopped after " + std::to_string(kMaxRefineRounds) + " rounds";
        return false;
    }
    /// Flips every new edge that is not Delaunay, until none is (or kMaxRelaxPasses).
    void relax_all() {
        for (int pass = 0; pass < kMaxRelaxPasses; ++pass) {
            std::size_t flips = 0;
            for (Index e = e0_; e < Index(mesh_.edges_size()); ++e) flips += relax(Edge(e)) ? 1 : 0;
            if (flips == 0) return;
        }
    }
    /// Tangential smoothing of the new vertices (each towards the area-weighted centroid of
    /// its triangles, in its tangent plane), each round followed by the flips that raise the
    /// smallest angles: lifts the small angles refinement and fairing leave. With
    /// `only_if_better` a vertex moves only where that raises the smallest angle around it.
    void smooth_tangentially(bool only_if_better) {
        for (int round = 0; round < kSmoothingRounds; ++round) {
            for (Index vi = v0_; vi < Index(mesh_.vertices_size()); ++vi) {
                const Vertex v(vi);
                const Point old = mesh_.position(v);
                const double before = only_if_better ? fan_min_angle(v) : 0;
                mesh_.position(v) = centroid_target(v);
                if (only_if_better && !(fan_min_angle(v) > before)) mesh_.position(v) = old;
            }
            raise_min_angles();
        }
    }
    /// Flips new edges wherever that raises the smallest angle of their two triangles and
    /// keeps them from folding: the clean-up after fairing. Returns the flips made.
    std::size_t raise_min_angles() {
        std::size_t total = 0;
        for (int pass = 0; pass < kMaxRelaxPasses; ++pass) {
            std::size_t flips = 0;
            for (Index e = e0_; e < Index(mesh_.edges_size()); ++e)
                flips += flip_if_better(Edge(e)) ? 1 : 0;
            total += flips;
            if (flips == 0) break;
        }
        return total;
    }

    /// Splits, at its midpoint, the longest new edge of every new triangle with an angle under
    /// 20 degrees (a triangle whose small angle faces a short rim edge has no flip that helps:
    /// a vertex more does). Returns the splits made.
    std::size_t split_small_angles() {
        std::vector<Edge> to_split;
        for (Index fi = f0_; fi < Index(mesh_.faces_size()); ++fi) {
            if (min_face_angle(mesh_, Face(fi)) >= 20.0) continue;
            // Its new edges, longest first; the first whose split leaves every rim corner
            // room for one more triangle.
            std::vector<std::pair<double, Edge>> edges;
            for (Halfedge h : mesh_.halfedges_of(Face(fi))) {
                const Edge e = HalfedgeMesh::edge(h);
                if (e.idx() >= e0_) edges.emplace_back(edge_length(mesh_, e), e);
            }
            std::sort(edges.begin(), edges.end(),
                      [](const auto& a, const auto& b) { return a.first > b.first; });
            for (const auto& [length, e] : edges)
                if (split_leaves_room(e)) {
                    to_split.push_back(e);
                    break;
                }
        }
        std::sort(to_split.begin(), to_split.end());
        to_split.erase(std::unique(to_split.begin(), to_split.end()), to_split.end());
        for (Edge e : to_split) {
            const Vertex a = mesh_.vertex(e, 0), b = mesh_.vertex(e, 1);
            const Vertex nv = mesh_.split(e, 0.5 * (mesh_.position(a) + mesh_.position(b)));
            if (spacing_.size() <= nv.idx()) spacing_.resize(nv.idx() + 1, 0);
            spacing_[nv.idx()] = 0.5 * (spacing_[a.idx()] + spacing_[b.idx()]);
        }
        return to_split.size();
    }
    /// Whether splitting e (which gives the vertex opposite it in each of its faces one more
    /// new triangle) leaves every such rim vertex its angle: the new triangles at a rim vertex
    /// span a fixed angle there, so k + 1 of them have an angle of at most span / (k + 1). A
    /// split that brings that bound under 20 degrees is made only where the bound stays well
    /// above the smallest angle the vertex's triangles have now (a corner too narrow for its
    /// rim edges: a third triangle may still help, a fourth no more).
    bool split_leaves_room(Edge e) const {
        for (int side = 0; side < 2; ++side) {
            const Halfedge h = HalfedgeMesh::halfedge(e, unsigned(side));
            if (mesh_.is_boundary(h)) continue;
            const Vertex c = mesh_.to_vertex(mesh_.next(h));
            if (c.idx() >= v0_) continue;
            double span = 0, smallest = 180;
            int count = 0;
            for (Face f : mesh_.faces_around(c)) {
                if (f.idx() < f0_) continue;
                const std::array<Vertex, 3> v = mesh_.face_vertices(f);
                const int k = v[0] == c ? 0 : (v[1] == c ? 1 : 2);
                span += corner_angle(mesh_.position(c), mesh_.position(v[(k + 1) % 3]),
                                     mesh_.position(v[(k + 2) % 3])) *
                        180.0 / 3.14159265358979323846;
                smallest = std::min(smallest, min_face_angle(mesh_, f));
                ++count;
            }
            const double bound = span / (count + 1);
            if (bound < 20.0 && !(bound > 1.15 * smallest)) return false;
        }
        return true;
    }
    /// Moves every new vertex, within its tangent plane, to where the smallest angle of its
    /// triangles (all three angles of each, so also those at its rim and new neighbours) is
    /// largest: a compass search (eight directions, the step halved when none is better),
    /// never folding a triangle. `sweeps` passes over the new vertices; returns the moves.
    std::size_t optimize_positions(int sweeps) {
        std::size_t moves = 0;
        for (int sweep = 0; sweep < sweeps; ++sweep) {
            std::size_t moved = 0;
            for (Index vi = v0_; vi < Index(mesh_.vertices_size()); ++vi)
                if (fan_min_angle(Vertex(vi)) < kOptimizeBelowDeg)
                    moved += optimize_vertex(Vertex(vi)) ? 1 : 0;
            moves += moved;
            if (moved == 0) break;
        }
        return moves;
    }
    /// Moves small groups of new vertices together, each within its tangent plane, where a new
    /// triangle is still under 20 degrees: the new neighbours of each of its rim corners (or
    /// its own new corners when it has no rim corner). Where the smallest angle sits at a narrow
    /// rim corner, it is shared by two new vertices of the corner's fan, and moving one alone
    /// (optimize_positions()) cannot raise it. A random search with a fixed seed: a move is kept
    /// when the group's triangles under 20 degrees, sorted by their smallest angle, compare
    /// larger (leximin) and are no more; no triangle turns by more than 60 degrees. Returns
    /// the groups improved.
    std::size_t optimize_clusters() {
        std::vector<std::vector<Vertex>> clusters;
        for (Index fi = f0_; fi < Index(mesh_.faces_size()); ++fi) {
            if (min_face_angle(mesh_, Face(fi)) >= 20.0) continue;
            const std::array<Vertex, 3> corners = mesh_.face_vertices(Face(fi));
            bool rim_corner = false;
            for (Vertex c : corners) {
                if (c.idx() >= v0_) continue;
                rim_corner = true;
                std::vector<Vertex> cluster;
                for (Vertex u : mesh_.vertices_around(c))
                    if (u.idx() >= v0_) cluster.push_back(u);
                std::sort(cluster.begin(), cluster.end());
                if (!cluster.empty()) clusters.push_back(std::move(cluster));
            }
            if (!rim_corner) clusters.push_back({corners.begin(), corners.end()});
        }
        std::sort(clusters.begin(), clusters.end());
        clusters.erase(std::unique(clusters.begin(), clusters.end()), clusters.end());
        std::mt19937 random(20031);  // fixed: the same fill on every run
        std::size_t improved = 0;
        for (const auto& cluster : clusters) improved += optimize_cluster(cluster, random) ? 1 : 0;
        return improved;
    }
    /// New triangles with an angle under 20 degrees.
    std::size_t count_small_angles() const {
        std::size_t n = 0;
        for (Index fi = f0_; fi < Index(mesh_.faces_size()); ++fi)
            n += min_face_angle(mesh_, Face(fi)) < 20.0 ? 1 : 0;
        return n;
    }

private:
    /// The smallest angle (degrees) of v's triangles with v at p, or -1 where one of them
    /// would turn by more than 60 degrees from its normal before the move (a fold).
    double fan_min_angle_at(Vertex v, const Point& p,
                            const std::vector<std::pair<Face, Vector3>>& fan) const {
        double worst = 180;
        for (const auto& [f, normal] : fan) {
            std::array<Point, 3> c;
            int k = 0;
            for (Vertex u : mesh_.face_vertices(f)) c[k++] = u == v ? p : mesh_.position(u);
            const Vector3 n = (c[1] - c[0]).cross(c[2] - c[0]);
            const double l = n.norm();
            if (!(l > 0) || !(n.dot(normal) > 0.5 * l)) return -1;
            worst = std::min(worst, min_angle(c[0], c[1], c[2]) * 180.0 / 3.14159265358979323846);
        }
        return worst;
    }
    bool optimize_vertex(Vertex v) {
        std::vector<std::pair<Face, Vector3>> fan;
        double spacing = 0;
        int k = 0;
        for (Face f : mesh_.faces_around(v)) fan.emplace_back(f, face_normal(mesh_, f));
        for (Vertex u : mesh_.vertices_around(v)) {
            spacing += (mesh_.position(u) - mesh_.position(v)).norm();
            ++k;
        }
        const Vector3 normal = vertex_normal(mesh_, v);
        if (fan.empty() || k == 0 || !(normal.squaredNorm() > 0)) return false;
        // Two directions spanning the tangent plane.
        Vector3 t1 = normal.unitOrthogonal(), t2 = normal.cross(t1);
        const std::array<Vector3, 8> directions{t1,
                                                -t1,
                                                t2,
                                                -t2,
                                                (t1 + t2).normalized(),
                                                (-t1 - t2).normalized(),
                                                (t1 - t2).normalized(),
                                                (t2 - t1).normalized()};
        Point p = mesh_.position(v);
        double value = fan_min_angle_at(v, p, fan);
        if (value < 0) return false;
        const Point start = p;
        double step = 0.25 * spacing / k;
        const double smallest = 1e-3 * step;
        for (int it = 0; it < 40 && step > smallest; ++it) {
            double best = value;
            Point best_p = p;
            for (const Vector3& d : directions) {
                const Point q = p + step * d;
                const double a = fan_min_angle_at(v, q, fan);
                if (a > best + 1e-9) {
                    best = a;
                    best_p = q;
                }
            }
            if (best > value) {
                value = best;
                p = best_p;
            } else {
                step *= 0.5;
            }
        }
        mesh_.position(v) = p;
        return p != start;
    }
    /// A triangle of a group: its corners and its unit normal before the moves.
    struct GroupFace {
        std::array<Vertex, 3> corners;
        Vector3 normal;
    };
    /// The smallest angles (degrees, ascending) of `faces` that are under 20 degrees, each
    /// face's smallest, into `small`; {-1} where one turned by more than 60 degrees from its
    /// normal.
    void small_angles(const std::vector<GroupFace>& faces, std::vector<double>& small) const {
        small.clear();
        for (const GroupFace& f : faces) {
            const Point &a = mesh_.position(f.corners[0]), &b = mesh_.position(f.corners[1]),
                        &c = mesh_.position(f.corners[2]);
            const Vector3 n = (b - a).cross(c - a);
            const double l = n.norm();
            if (!(l > 0) || !(n.dot(f.normal) > 0.5 * l)) {
                small.assign(1, -1.0);
                return;
            }
            const double angle = min_angle(a, b, c) * 180.0 / 3.14159265358979323846;
            if (angle < 20.0) small.push_back(angle);
        }
        std::sort(small.begin(), small.end());
    }
    /// Whether `now` is better than `before` (small_angles()): no more of them, and the first
    /// that differs by more than a tolerance is larger (a missing entry counts as 20).
    static bool leximin_better(const std::vector<double>& now, const std::vector<double>& before) {
        if (now.size() > before.size() || (!now.empty() && now[0] < 0)) return false;
        for (std::size_t i = 0; i < before.size(); ++i) {
            const double x = i < now.size() ? now[i] : 20.0;
            if (x > before[i] + 1e-9) return true;
            if (x < before[i] - 1e-9) return false;
        }
        return false;
    }
    /// optimize_clusters() for one group; true when it moved.
    bool optimize_cluster(const std::vector<Vertex>& cluster, std::mt19937& random) {
        std::vector<Face> around;
        std::vector<std::array<Vector3, 2>> tangents;
        double length = 0;
        int k = 0;
        for (Vertex v : cluster) {
            for (Face f : mesh_.faces_around(v)) around.push_back(f);
            for (Vertex u : mesh_.vertices_around(v)) {
                length += (mesh_.position(u) - mesh_.position(v)).norm();
                ++k;
            }
            const Vector3 n = vertex_normal(mesh_, v);
            if (!(n.squaredNorm() > 0)) return false;
            const Vector3 t1 = n.unitOrthogonal();
            tangents.push_back({t1, n.cross(t1)});
        }
        std::sort(around.begin(), around.end());
        around.erase(std::unique(around.begin(), around.end()), around.end());
        std::vector<GroupFace> faces;
        for (Face f : around) faces.push_back({mesh_.face_vertices(f), face_normal(mesh_, f)});
        std::vector<double> value, now;
        small_angles(faces, value);
        if (k == 0 || value.empty() || value[0] < 0) return false;
        bool moved = false;
        std::vector<Point> old(cluster.size());
        const auto uniform = [&random] { return 2.0 * double(random()) / 4294967295.0 - 1.0; };
        double step = 0.1 * length / k;
        for (int it = 0; it < kClusterTries && !value.empty(); ++it) {
            if (it > 0 && it % (kClusterTries / 10) == 0) step *= 0.6;
            for (std::size_t i = 0; i < cluster.size(); ++i) {
                old[i] = mesh_.position(cluster[i]);
                const double a = uniform(), b = uniform();
                mesh_.position(cluster[i]) += step * (a * tangents[i][0] + b * tangents[i][1]);
            }
            small_angles(faces, now);
            if (leximin_better(now, value)) {
                std::swap(value, now);
                moved = true;
                continue;
            }
            for (std::size_t i = 0; i < cluster.size(); ++i) mesh_.position(cluster[i]) = old[i];
        }
        return moved;
    }
    Point centroid_target(Vertex v) const {
        Point c = Point::Zero();
        double weight = 0;
        for (Face f : mesh_.faces_around(v)) {
            const double area = face_area(mesh_, f);
            c += area * face_centroid(mesh_, f);
            weight += area;
        }
        if (!(weight > 0)) return mesh_.position(v);
        const Vector3 normal = vertex_normal(mesh_, v);
        Vector3 d = c / weight - mesh_.position(v);
        d -= normal.dot(d) * normal;
        return mesh_.position(v) + d;
    }
    double fan_min_angle(Vertex v) const {
        double a = 180;
        for (Face f : mesh_.faces_around(v)) a = std::min(a, min_face_angle(mesh_, f));
        return a;
    }
    /// The smallest angle of triangle (a, b, c) in radians: the one opposite the shortest side.
    static double min_angle(const Point& a, const Point& b, const Point& c) {
        const double ab = (b - a).squaredNorm(), bc = (c - b).squaredNorm(),
                     ca = (a - c).squaredNorm();
        if (bc <= ab && bc <= ca) return corner_angle(a, b, c);
        if (ca <= ab) return corner_angle(b, c, a);
        return corner_angle(c, a, b);
    }
    bool flip_if_better(Edge e) {
        if (mesh_.is_boundary(e) || !mesh_.is_flip_ok(e)) return false;
        const Halfedge h = HalfedgeMesh::halfedge(e, 0), o = HalfedgeMesh::halfedge(e, 1);
        const Point& a = mesh_.position(mesh_.from_vertex(h));
        const Point& b = mesh_.position(mesh_.to_vertex(h));
        const Point& c = mesh_.position(mesh_.to_vertex(mesh_.next(h)));
        const Point& d = mesh_.position(mesh_.to_vertex(mesh_.next(o)));
        const double before = std::min(min_angle(a, b, c), min_angle(b, a, d));
        const double after = std::min(min_angle(c, d, b), min_angle(d, c, a));
        if (!(after > before + 1e-6)) return false;
        // The flipped pair (d, c, a) and (c, d, b) must not fold onto each other.
        const Vector3 n1 = (c - d).cross(a - d), n2 = (d - c).cross(b - c);
        if (!(n1.dot(n2) > 0.5 * n1.norm() * n2.norm())) return false;
        mesh_.flip(e);
        return true;
    }
    /// Splits a new edge longer than twice its ends' mean spacing at its midpoint: Liepa's
    /// face splits leave long edges where a sliver's centroid sits close to its corners.
    bool split_if_long(Edge e, std::vector<Face>& work) {
        const Vertex a = mesh_.vertex(e, 0), b = mesh_.vertex(e, 1);
        const double s = 0.5 * (spacing_[a.idx()] + spacing_[b.idx()]);
        const Point pa = mesh_.position(a), pb = mesh_.position(b);
        if (!((pa - pb).norm() > 2.0 * s)) return false;
        const Vertex nv = mesh_.split(e, 0.5 * (pa + pb));
        if (spacing_.size() <= nv.idx()) spacing_.resize(nv.idx() + 1, 0);
        spacing_[nv.idx()] = s;
        for (Face g : mesh_.faces_around(nv)) work.push_back(g);
        return true;
    }
    bool split_if_coarse(Face f, std::vector<Face>& work) {
        const std::array<Vertex, 3> v = mesh_.face_vertices(f);
        const Point c = (mesh_.position(v[0]) + mesh_.position(v[1]) + mesh_.position(v[2])) / 3;
        const double sc = (spacing_[v[0].idx()] + spacing_[v[1].idx()] + spacing_[v[2].idx()]) / 3;
        for (Vertex m : v) {
            const double d = kDensityFactor * (c - mesh_.position(m)).norm();
            if (!(d > sc && d > spacing_[m.idx()])) return false;
        }
        std::array<Edge, 3> edges;
        int k = 0;
        for (Halfedge h : mesh_.halfedges_of(f)) edges[k++] = HalfedgeMesh::edge(h);
        const Vertex nv = mesh_.split(f, c);
        if (spacing_.size() <= nv.idx()) spacing_.resize(nv.idx() + 1, 0);
        spacing_[nv.idx()] = sc;
        for (Face g : mesh_.faces_around(nv)) work.push_back(g);
        for (Edge e : edges) relax_around(e, work);
        return true;
    }
    /// Lawson's flips from e outwards: each flip queues the four edges around it (and its two
    /// faces on `work`).
    void relax_around(Edge first, std::vector<Face>& work) {
        std::vector<Edge> edges{first};
        std::size_t budget = 64;  // flips per call; relax_all() finishes anything left
        while (!edges.empty() && budget > 0) {
            const Edge e = edges.back();
            edges.pop_back();
            if (!relax(e)) continue;
            --budget;
            for (int side = 0; side < 2; ++side) {
                const Halfedge h = HalfedgeMesh::halfedge(e, unsigned(side));
                work.push_back(mesh_.face(h));
                edges.push_back(HalfedgeMesh::edge(mesh_.next(h)));
                edges.push_back(HalfedgeMesh::edge(mesh_.prev(h)));
            }
        }
    }
    /// Flips e when it is new and the angles opposite it sum to more than 180 degrees.
    bool relax(Edge e) {
        if (e.idx() < e0_ || mesh_.is_boundary(e) || !mesh_.is_flip_ok(e)) return false;
        const Halfedge h = HalfedgeMesh::halfedge(e, 0), o = HalfedgeMesh::halfedge(e, 1);
        const Point& a = mesh_.position(mesh_.from_vertex(h));
        const Point& b = mesh_.position(mesh_.to_vertex(h));
        const Point& c = mesh_.position(mesh_.to_vertex(mesh_.next(h)));
        const Point& d = mesh_.position(mesh_.to_vertex(mesh_.next(o)));
        // alpha + beta > 180 degrees exactly when cot(alpha) + cot(beta) < 0.
        const Vector3 ca = a - c, cb = b - c, da = a - d, db = b - d;
        const double sc = ca.cross(cb).norm(), sd = da.cross(db).norm();
        if (!(sc > 0 && sd > 0)) return false;
        if (ca.dot(cb) / sc + da.dot(db) / sd >= -1e-9) return false;
        // The flipped triangles (c, d, a) and (d, c, b) must have area.
        const double l = std::max((c - d).squaredNorm(), (a - b).squaredNorm());
        if ((d - c).cross(a - c).norm() <= 1e-12 * l || (c - d).cross(b - d).norm() <= 1e-12 * l)
            return false;
        mesh_.flip(e);
        return true;
    }

    HalfedgeMesh& mesh_;
    Index v0_, e0_, f0_;
    std::vector<double>& spacing_;
};

// ---- fairing ----------------------------------------------------------------------------------

/// The faces within `rings` rings of the new vertices (index >= v0), as a soup over local
/// vertex numbers; `local` maps local numbers to mesh vertices.
PolygonSoup neighbourhood(const HalfedgeMesh& mesh, Index v0, int rings,
                          std::vector<Vertex>& local) {
    std::vector<Index> depth(mesh.vertices_size(), kInvalidIndex);
    std::vector<Vertex> frontier;
    for (Index vi = v0; vi < Index(mesh.vertices_size()); ++vi) {
        depth[vi] = 0;
        frontier.push_back(Vertex(vi));
    }
    std::vector<Vertex> reached = frontier;
    for (int r = 1; r < rings; ++r) {
        std::vector<Vertex> next;
        for (Vertex v : frontier)
            for (Vertex u : mesh.vertices_around(v))
                if (depth[u.idx()] == kInvalidIndex) {
                    depth[u.idx()] = Index(r);
                    next.push_back(u);
                }
        reached.insert(reached.end(), next.begin(), next.end());
        frontier = std::move(next);
    }
    std::vector<std::uint8_t> face_taken(mesh.faces_size(), 0);
    std::vector<Index> local_of(mesh.vertices_size(), kInvalidIndex);
    PolygonSoup soup;
    for (Vertex v : reached)
        for (Face f : mesh.faces_around(v)) {
            if (face_taken[f.idx()]) continue;
            face_taken[f.idx()] = 1;
            std::vector<Index> corners;
            for (Vertex u : mesh.face_vertices(f)) {
                if (local_of[u.idx()] == kInvalidIndex) {
                    local_of[u.idx()] = Index(local.size());
                    local.push_back(u);
                    soup.positions.push_back(mesh.position(u));
                }
                corners.push_back(local_of[u.idx()]);
            }
            soup.add_face(corners);
        }
    return soup;
}

/// Solves L^order x = 0 for the new vertices over `op`'s weights; false with `why` on failure.
bool solve_fairing(HalfedgeMesh& mesh, Index v0, int order, LaplacianOperator op, std::string& why,
                   const std::vector<std::uint8_t>* held = nullptr) {
    std::vector<Vertex> local;
    PolygonSoup soup = neighbourhood(mesh, v0, order, local);
    LoadReport load;
    const HalfedgeMesh sub = build_mesh(soup, load);
    LaplacianOptions lo;
    lo.fix_boundary = false;
    lo.mass = op == LaplacianOperator::Umbrella ? MassMatrix::Normalizer : MassMatrix::Voronoi;
    const Laplacian lap = build_laplacian(sub, op, lo);
    Eigen::VectorXd s_inv(lap.S.size());
    for (Eigen::Index i = 0; i < lap.S.size(); ++i) s_inv[i] = lap.S[i] > 0 ? 1.0 / lap.S[i] : 0.0;
    SparseMatrix a = lap.K * s_inv.asDiagonal() * lap.K;
    if (order == 3) a = SparseMatrix(a * s_inv.asDiagonal() * lap.K);
    // Unknowns: the rows of new vertices; the rest is known.
    const std::size_t rows = lap.map.rows();
    std::vector<Index> unknown_of(rows, kInvalidIndex);
    std::vector<Index> row_of_unknown;
    for (std::size_t r = 0; r < rows; ++r) {
        const Index li = lap.map.vertex_of[r].idx();
        if (li < local.size() && local[li].idx() >= v0 &&
            !(held && (*held)[local[li].idx() - v0])) {
            unknown_of[r] = Index(row_of_unknown.size());
            row_of_unknown.push_back(Index(r));
        }
    }
    const Eigen::MatrixXd x = gather_positions(sub, lap.map);
    const Eigen::Index n = Eigen::Index(row_of_unknown.size());
    Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(n, 3);
    std::vector<Eigen::Triplet<double>> entries;
    for (int c = 0; c < a.outerSize(); ++c)
        for (SparseMatrix::InnerIterator it(a, c); it; ++it) {
            const Index ur = unknown_of[it.row()];
            if (ur == kInvalidIndex) continue;
            const Index uc = unknown_of[it.col()];
            if (uc == kInvalidIndex)
                rhs.row(ur) -= it.value() * x.row(it.col());
            else
                entries.emplace_back(ur, uc, it.value());
        }
    SparseMatrix a_ff(n, n);
    a_ff.setFromTriplets(entries.begin(), entries.end());
    Eigen::SimplicialLDLT<SparseMatrix> solver(a_ff);
    if (solver.info() != Eigen::Success) {
        why = "the factorization failed";
        return false;
    }
    const Eigen::MatrixXd y = solver.solve(rhs);
    const double residual = (a_ff * y - rhs).norm();
    if (!y.allFinite() || !(residual <= 1e-6 * std::max(rhs.norm(), 1e-300))) {
        why = "the solve gave no finite, accurate result";
        return false;
    }
    for (Eigen::Index u = 0; u < n; ++u) {
        const Vertex v = local[lap.map.vertex_of[row_of_unknown[u]].idx()];
        mesh.position(v) = y.row(u).transpose();
    }
    return true;
}

/// Fairs the patch, falling back to the umbrella and then to nothing; a note says which.
void fair_patch(HalfedgeMesh& mesh, Index v0, HoleFairing fairing, std::size_t loop,
                std::vector<std::string>& notes) {
    if (fairing == HoleFairing::None || v0 >= mesh.vertices_size()) return;
    const int order = fairing == HoleFairing::C2 ? 3 : 2;
    const std::vector<Point> before(mesh.positions().begin() + v0, mesh.positions().end());
    std::string why;
    if (solve_fairing(mesh, v0, order, LaplacianOperator::CurvatureFlow, why)) return;
    std::string why_umbrella;
    if (solve_fairing(mesh, v0, order, LaplacianOperator::Umbrella, why_umbrella)) {
        notes.push_back("loop " + std::to_string(loop) + ": cotangent fairing failed (" + why +
                        "); faired with uniform weights");
        return;
    }
    std::copy(before.begin(), before.end(), mesh.positions().begin() + v0);
    notes.push_back("loop " + std::to_string(loop) + ": fairing failed (" + why_umbrella +
                    "); the patch is refined but not faired");
}

/// A last fairing of the patch after the angle repairs (which moved vertices off the faired
/// surface): new vertices of any triangle it would take under 20 degrees, or under its smallest
/// angle now when that is under 20, are held where they are and the rest faired again (up to
/// kRefairRounds rounds); nothing changes where that does not settle or the solve fails.
void refair_keeping_angles(HalfedgeMesh& mesh, Index v0, Index f0, HoleFairing fairing) {
    if (fairing == HoleFairing::None || v0 >= mesh.vertices_size()) return;
    const int order = fairing == HoleFairing::C2 ? 3 : 2;
    const std::vector<Point> before(mesh.positions().begin() + v0, mesh.positions().end());
    std::vector<double> angle_before;
    for (Index fi = f0; fi < Index(mesh.faces_size()); ++fi)
        angle_before.push_back(min_face_angle(mesh, Face(fi)));
    std::vector<std::uint8_t> held(before.size(), 0);
    for (int round = 0; round < kRefairRounds; ++round) {
        std::string why;
        if (!solve_fairing(mesh, v0, order, LaplacianOperator::CurvatureFlow, why, &held)) break;
        bool worse = false;
        for (Index fi = f0; fi < Index(mesh.faces_size()); ++fi) {
            const double a = min_face_angle(mesh, Face(fi)), b = angle_before[fi - f0];
            if (!(a < 20.0 && a < b - 1e-9) && !std::isnan(a)) continue;
            worse = true;
            for (Vertex v : mesh.face_vertices(Face(fi)))
                if (v.idx() >= v0) held[v.idx() - v0] = 1;
        }
        if (!worse) return;
        std::copy(before.begin(), before.end(), mesh.positions().begin() + v0);
    }
    std::copy(before.begin(), before.end(), mesh.positions().begin() + v0);
}

// ---- attributes -------------------------------------------------------------------------------

void set_attributes(HalfedgeMesh& mesh, Index v0, const std::vector<std::vector<Vertex>>& rims,
                    bool select_new) {
    const Index n = Index(mesh.vertices_size());
    if (mesh.has_vertex_property("v:normal")) {
        auto normals = mesh.vertex_property<Vector3>("v:normal");
        for (Index vi = v0; vi < n; ++vi) normals[Vertex(vi)] = vertex_normal(mesh, Vertex(vi));
        for (const auto& rim : rims)
            for (Vertex v : rim) normals[v] = vertex_normal(mesh, v);
    }
    if (mesh.has_vertex_property("v:color") && !rims.empty()) {
        auto colors = mesh.vertex_property<Color>("v:color");
        Color mean = Color::Zero();
        std::size_t k = 0;
        for (const auto& rim : rims)
            for (Vertex v : rim) {
                mean += colors[v];
                ++k;
            }
        if (k) mean /= float(k);
        for (Index vi = v0; vi < n; ++vi) colors[Vertex(vi)] = mean;
    }
    if (select_new) {
        Selection s(n, 0.0f);
        for (Index vi = v0; vi < n; ++vi) s[vi] = 1.0f;
        store_selection(mesh, s);
    }
}

void measure_new_faces(const HalfedgeMesh& mesh, Index f0, HoleFillingReport& r) {
    r.min_new_angle_deg = std::numeric_limits<double>::quiet_NaN();
    for (Index fi = f0; fi < Index(mesh.faces_size()); ++fi) {
        const double a = min_face_angle(mesh, Face(fi));
        if (std::isnan(a)) continue;  // no ordered comparison with NaN (FP traps)
        if (std::isnan(r.min_new_angle_deg) || a < r.min_new_angle_deg) r.min_new_angle_deg = a;
        if (a < 20.0) ++r.new_angles_under_20;
    }
}

/// Mean length of the edges at each vertex of the rims (the spacing refinement matches).
std::vector<double> rim_spacing(const HalfedgeMesh& mesh) {
    std::vector<double> spacing(mesh.vertices_size(), 0.0);
    for (Vertex v : mesh.vertices()) {
        if (!mesh.is_boundary(v) || mesh.is_isolated(v)) continue;
        double sum = 0;
        int k = 0;
        for (Vertex u : mesh.vertices_around(v)) {
            sum += (mesh.position(u) - mesh.position(v)).norm();
            ++k;
        }
        spacing[v.idx()] = k ? sum / k : 0;
    }
    return spacing;
}

/// About how many faces refinement would give the coarse triangulation: its area over that of
/// an equilateral triangle with the rim's mean spacing as its side.
double estimated_faces(const HalfedgeMesh& mesh, const BoundaryLoop& loop,
                       const std::vector<Triangle>& triangles, const std::vector<double>& spacing) {
    double area = 0, s = 0;
    for (const Triangle& t : triangles)
        area += 0.5 * (mesh.position(t[1]) - mesh.position(t[0]))
                          .cross(mesh.position(t[2]) - mesh.position(t[0]))
                          .norm();
    for (Vertex v : loop.vertices) s += spacing[v.idx()];
    s /= double(loop.vertices.size());
    return s > 0 ? area / (0.4330127018922193 * s * s) : 0.0;
}

/// Fills one loop whose rim passed rim_problem(); "" or the reason it was refused.
std::string fill_loop(HalfedgeMesh& mesh, const BoundaryLoop& loop, std::size_t index,
                      const HoleFillingOptions& o, std::vector<double>& spacing,
                      HoleFillingReport& r) {
    LoopTriangulator triangulator(mesh, loop.vertices);
    std::vector<Triangle> triangles;
    std::string why;
    if (!triangulator.run(triangles, why)) return why;
    if (triangulator.largest_dihedral_deg() > kMaxFoldDeg)
        return "every triangulation of it folds back by " +
               std::to_string(std::lround(triangulator.largest_dihedral_deg())) +
               " degrees or more onto itself or the surface (over " +
               std::to_string(std::lround(kMaxFoldDeg)) +
               "): it is the outer border of an open sheet, not a hole";
    if (o.refine) {
        const double estimate = estimated_faces(mesh, loop, triangles, spacing);
        if (estimate > double(kMaxEstimatedFaces))
            return "refined to the density around it, the fill would have about " +
                   std::to_string(std::llround(estimate)) + " faces, over the limit of " +
                   std::to_string(kMaxEstimatedFaces) +
                   " (a mesh's outer border, or a hole far larger than its triangles: choose "
                   "loops with --loops, --max-edges or --max-diameter)";
    }
    if (triangulator.was_cut()) ++r.loops_cut;
    if (triangulator.used_delaunay()) ++r.loops_delaunay;
    if (!triangulator.delaunay_fallback().empty())
        r.notes.push_back("loop " + std::to_string(index) + " (" + std::to_string(loop.edges()) +
                          " edges): not restricted to Delaunay "
                          "edges (" +
                          triangulator.delaunay_fallback() + "); cut by chords instead");
    const Index v0 = Index(mesh.vertices_size()), e0 = Index(mesh.edges_size()),
                f0 = Index(mesh.faces_size());
    for (const Triangle& t : triangles) insert_triangle(mesh, t);
    if (!o.refine) return "";
    Patch patch(mesh, v0, e0, f0, spacing);
    patch.relax_all();
    std::string note;
    if (!patch.refine(note)) r.notes.push_back("loop " + std::to_string(index) + ": " + note);
    patch.relax_all();
    patch.smooth_tangentially(false);
    fair_patch(mesh, v0, o.fairing, index, r.notes);
    patch.smooth_tangentially(false);
    fair_patch(mesh, v0, o.fairing, index, r.notes);
    patch.raise_min_angles();
    patch.optimize_positions(kOptimizeSweeps);
    for (int round = 0; round < kRepairRounds && patch.count_small_angles() > 0; ++round) {
        if (patch.split_small_angles() == 0) break;
        fair_patch(mesh, v0, o.fairing, index, r.notes);
        patch.raise_min_angles();
        patch.optimize_positions(kOptimizeSweeps);
        patch.raise_min_angles();
        patch.optimize_positions(kOptimizeSweeps);
    }
    refair_keeping_angles(mesh, v0, f0, o.fairing);
    if (patch.count_small_angles() > 0) patch.optimize_clusters();
    return "";
}

}  // namespace

std::vector<BoundaryLoop> boundary_loops(const HalfedgeMesh& mesh) {
    std::vector<BoundaryLoop> loops;
    std::vector<std::uint8_t> seen(mesh.halfedges_size(), 0);
    for (Vertex v : mesh.vertices()) {
        const Halfedge start = mesh.halfedge(v);
        if (!start.is_valid() || !mesh.is_boundary(start) || seen[start.idx()]) continue;
        BoundaryLoop loop;
        BoundingBox box;
        Halfedge h = start;
        do {
            seen[h.idx()] = 1;
            loop.vertices.push_back(mesh.from_vertex(h));
            box.extend(mesh.position(mesh.from_vertex(h)));
            h = mesh.next(h);
        } while (h != start && loop.vertices.size() <= mesh.halfedges_size());
        loop.length = rim_length(mesh, loop.vertices);
        loop.diagonal = box.diagonal();
        loops.push_back(std::move(loop));
    }
    return loops;
}

HoleFillingReport fill_holes(HalfedgeMesh& mesh, const HoleFillingOptions& options) {
    const std::vector<BoundaryLoop> loops = boundary_loops(mesh);
    check_options(mesh, options, loops.size());
    HoleFillingReport r;
    r.loops_found = loops.size();
    for (const BoundaryLoop& l : loops) r.loop_edges.push_back(l.edges());
    const std::vector<std::uint8_t> chosen = choose_loops(mesh, options, loops);
    const Index v0 = Index(mesh.vertices_size()), f0 = Index(mesh.faces_size());
    const std::size_t n_vertices = mesh.n_vertices(), n_faces = mesh.n_faces();
    std::vector<double> spacing = rim_spacing(mesh);
    std::vector<std::vector<Vertex>> rims;
    const std::vector<std::string> pinched = pinched_rims(mesh, loops);
    for (std::size_t i = 0; i < loops.size(); ++i) {
        if (!chosen[i]) continue;
        ++r.loops_chosen;
        std::string why = rim_problem(mesh, loops[i]);
        if (why.empty()) why = pinched[i];
        if (why.empty()) why = fill_loop(mesh, loops[i], i, options, spacing, r);
        if (!why.empty()) {
            r.refused.push_back({i, loops[i].edges(), why});
            continue;
        }
        ++r.loops_filled;
        r.filled.push_back(i);
        rims.push_back(loops[i].vertices);
    }
    r.vertices_added = mesh.n_vertices() - n_vertices;
    r.faces_added = mesh.n_faces() - n_faces;
    measure_new_faces(mesh, f0, r);
    if (r.loops_filled > 0) set_attributes(mesh, v0, rims, options.select_new);
    return r;
}

}  // namespace trilab
