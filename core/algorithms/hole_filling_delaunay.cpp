// The Delaunay-restricted search space of hole filling for large loops (Zou, Ju, Carr 2013),
// from a 2-D Delaunay triangulation of the loop projected onto its Newell plane. See
// hole_filling_delaunay.h.
#include "core/algorithms/hole_filling_delaunay.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_map>
#include <utility>
#include <vector>

namespace trilab {
namespace {

struct P2 {
    double x = 0, y = 0;
};

/// Twice the signed area of (a, b, c): positive when counter-clockwise.
double orient(const P2& a, const P2& b, const P2& c) {
    return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

/// Whether d is inside the circle through the counter-clockwise triangle (a, b, c), beyond
/// the rounding of the determinant (Shewchuk's bound on it, relative to its permanent, with a
/// wide margin): near-cocircular points count as outside.
bool in_circle(const P2& a, const P2& b, const P2& c, const P2& d) {
    const double ax = a.x - d.x, ay = a.y - d.y, bx = b.x - d.x, by = b.y - d.y;
    const double cx = c.x - d.x, cy = c.y - d.y;
    const double a2 = ax * ax + ay * ay, b2 = bx * bx + by * by, c2 = cx * cx + cy * cy;
    const double det =
        a2 * (bx * cy - by * cx) + b2 * (cx * ay - cy * ax) + c2 * (ax * by - ay * bx);
    const double permanent = a2 * (std::abs(bx * cy) + std::abs(by * cx)) +
                             b2 * (std::abs(cx * ay) + std::abs(cy * ax)) +
                             c2 * (std::abs(ax * by) + std::abs(ay * bx));
    return det > 1e-12 * permanent;
}

constexpr std::uint32_t kNo = std::numeric_limits<std::uint32_t>::max();

/// A 2-D Delaunay triangulation built by incremental insertion and Lawson's flips, inside a
/// large enclosing triangle (its three vertices are numbered n, n + 1, n + 2).
class Delaunay2 {
public:
    struct Tri {
        std::array<std::uint32_t, 3> v;  ///< counter-clockwise
        std::array<std::uint32_t, 3> n;  ///< n[k]: the triangle across the edge opposite v[k]
    };

    /// Triangulates `p`; false when a point could not be inserted (a duplicate, or a walk
    /// that rounding sent astray).
    bool build(std::vector<P2> p, double scale) {
        pts_ = std::move(p);
        const std::size_t n = pts_.size();
        double lo_x = pts_[0].x, hi_x = lo_x, lo_y = pts_[0].y, hi_y = lo_y;
        for (const P2& q : pts_) {
            lo_x = std::min(lo_x, q.x);
            hi_x = std::max(hi_x, q.x);
            lo_y = std::min(lo_y, q.y);
            hi_y = std::max(hi_y, q.y);
        }
        const double cx = 0.5 * (lo_x + hi_x), cy = 0.5 * (lo_y + hi_y);
        const double r = 1e4 * std::max({hi_x - lo_x, hi_y - lo_y, scale});
        pts_.push_back({cx - r, cy - r});
        pts_.push_back({cx + r, cy - r});
        pts_.push_back({cx, cy + r});
        tris_.push_back(
            {{std::uint32_t(n), std::uint32_t(n + 1), std::uint32_t(n + 2)}, {kNo, kNo, kNo}});
        // A random order (Fisher-Yates with a fixed seed, so the result is reproducible): in
        // loop order a loop's long straight sides would make every insertion's cavity span
        // the whole side (O(n^2)); a random order makes it O(n log n) expected.
        std::vector<std::uint32_t> order(n);
        for (std::uint32_t i = 0; i < n; ++i) order[i] = i;
        std::uint64_t state = 0x9E3779B97F4A7C15ull;
        for (std::size_t i = n; i > 1; --i) {
            state = state * 6364136223846793005ull + 1442695040888963407ull;
            std::swap(order[i - 1], order[std::size_t((state >> 33) % i)]);
        }
        tri_of_.assign(n + 3, kNo);
        inserted_.assign(n, 0);
        for (std::uint32_t i : order) {
            if (!insert(i)) return false;
            inserted_[i] = 1;
        }
        return true;
    }
    const std::vector<Tri>& triangles() const { return tris_; }
    const P2& point(std::uint32_t i) const { return pts_[i]; }

private:
    /// A triangle to start the walk to point i from: one at the nearest point along the loop
    /// inserted already (the loop's points are near in space where they are near along it),
    /// else the last one made. Scanning outwards costs O(n / k) after k insertions in a random
    /// order: O(n log n) in all.
    std::uint32_t start_for(std::uint32_t i) const {
        const std::size_t n = inserted_.size();
        for (std::size_t d = 1; d < n; ++d)
            for (std::size_t j : {(i + d) % n, (i + n - d % n) % n})
                if (inserted_[j]) {
                    const std::uint32_t t = tri_of_[j];
                    const auto& v = tris_[t].v;
                    if (v[0] == j || v[1] == j || v[2] == j) return t;
                    return last_;
                }
        return last_;
    }
    /// Notes triangle t at each of its corners (the walks' starts).
    void note(std::uint32_t t) {
        for (std::uint32_t v : tris_[t].v) tri_of_[v] = t;
    }
    /// The triangle containing p (on its border included), walking from `t`.
    std::uint32_t locate(const P2& p, std::uint32_t t) const {
        for (std::size_t step = 0; step < 4 * tris_.size() + 16; ++step) {
            const Tri& tr = tris_[t];
            std::uint32_t next = kNo;
            for (int k = 0; k < 3 && next == kNo; ++k) {
                const P2 &b = pts_[tr.v[(k + 1) % 3]], &c = pts_[tr.v[(k + 2) % 3]];
                const double l =
                    std::hypot(c.x - b.x, c.y - b.y) * std::hypot(p.x - b.x, p.y - b.y);
                if (orient(b, c, p) < -1e-12 * l) next = tr.n[k];
            }
            if (next == kNo) return t;
            t = next;
        }
        return kNo;
    }
    int edge_to(std::uint32_t t, std::uint32_t neighbour) const {
        for (int k = 0; k < 3; ++k)
            if (tris_[t].n[k] == neighbour) return k;
        return -1;
    }
    void relink(std::uint32_t t, std::uint32_t from, std::uint32_t to) {
        if (t == kNo) return;
        const int k = edge_to(t, from);
        if (k >= 0) tris_[t].n[k] = to;
    }
    bool insert(std::uint32_t i) {
        const P2& p = pts_[i];
        const std::uint32_t t = locate(p, start_for(i));
        if (t == kNo) return false;
        const Tri tr = tris_[t];
        int on_edge = -1;
        for (int k = 0; k < 3; ++k) {
            const P2& a = pts_[tr.v[k]];
            if (a.x == p.x && a.y == p.y) return false;  // a duplicate
            const P2 &b = pts_[tr.v[(k + 1) % 3]], &c = pts_[tr.v[(k + 2) % 3]];
            const double l = std::hypot(c.x - b.x, c.y - b.y) * std::hypot(p.x - b.x, p.y - b.y);
            if (std::abs(orient(b, c, p)) <= 1e-12 * l) on_edge = k;
        }
        std::vector<std::pair<std::uint32_t, int>> stack;
        if (on_edge < 0 || tr.n[on_edge] == kNo)
            split_triangle(t, i, stack);
        else
            split_edge(t, on_edge, i, stack);
        legalize(i, stack);
        last_ = std::uint32_t(tris_.size() - 1);
        return flips_ <= 64 * pts_.size() + 1024;
    }
    /// p inside t: three triangles (t reused). Queues the edges opposite p.
    void split_triangle(std::uint32_t t, std::uint32_t i,
                        std::vector<std::pair<std::uint32_t, int>>& stack) {
        const Tri old = tris_[t];
        const std::uint32_t t1 = std::uint32_t(tris_.size()), t2 = t1 + 1;
        // t: (i, v1, v2) opposite-edge neighbour n0; t1: (i, v2, v0) n1; t2: (i, v0, v1) n2.
        tris_[t] = {{i, old.v[1], old.v[2]}, {old.n[0], t1, t2}};
        tris_.push_back({{i, old.v[2], old.v[0]}, {old.n[1], t2, t}});
        tris_.push_back({{i, old.v[0], old.v[1]}, {old.n[2], t, t1}});
        relink(old.n[1], t, t1);
        relink(old.n[2], t, t2);
        for (std::uint32_t x : {t, t1, t2}) {
            note(x);
            stack.emplace_back(x, 0);
        }
    }
    /// p on the edge of t opposite its corner k (shared with triangle u): four triangles.
    void split_edge(std::uint32_t t, int k, std::uint32_t i,
                    std::vector<std::pair<std::uint32_t, int>>& stack) {
        const Tri a = tris_[t];
        const std::uint32_t u = a.n[k];
        const int ku = edge_to(u, t);
        const Tri b = tris_[u];
        // t = (c, x, y) with c = a.v[k]; u = (d, y, x) with d = b.v[ku].
        const std::uint32_t c = a.v[k], x = a.v[(k + 1) % 3], y = a.v[(k + 2) % 3];
        const std::uint32_t d = b.v[ku];
        const std::uint32_t n_cx = a.n[(k + 2) % 3], n_yc = a.n[(k + 1) % 3];
        const std::uint32_t n_dy = b.n[(ku + 2) % 3], n_xd = b.n[(ku + 1) % 3];
        const std::uint32_t t2 = std::uint32_t(tris_.size()), u2 = t2 + 1;
        // t: (i, c, x); t2: (i, y, c); u: (i, d, y); u2: (i, x, d).
        tris_[t] = {{i, c, x}, {n_cx, u2, t2}};
        tris_.push_back({{i, y, c}, {n_yc, t, u}});
        tris_[u] = {{i, d, y}, {n_dy, t2, u2}};
        tris_.push_back({{i, x, d}, {n_xd, u, t}});
        relink(n_yc, t, t2);
        relink(n_xd, u, u2);
        for (std::uint32_t z : {t, t2, u, u2}) {
            note(z);
            stack.emplace_back(z, 0);
        }
    }
    /// Lawson's flips: each queued (triangle, corner 0 = the new point i) edge opposite i is
    /// flipped while the point across it lies inside the circle.
    void legalize(std::uint32_t i, std::vector<std::pair<std::uint32_t, int>>& stack) {
        while (!stack.empty()) {
            const std::uint32_t t = stack.back().first;
            stack.pop_back();
            const Tri a = tris_[t];
            if (a.v[0] != i) continue;
            const std::uint32_t u = a.n[0];
            if (u == kNo) continue;
            const int ku = edge_to(u, t);
            if (ku < 0) continue;
            const Tri b = tris_[u];
            const std::uint32_t d = b.v[ku];
            const P2 &pa = pts_[a.v[0]], &pb = pts_[a.v[1]], &pc = pts_[a.v[2]], &pd = pts_[d];
            if (!in_circle(pa, pb, pc, pd)) continue;
            if (++flips_ > 64 * pts_.size() + 1024) return;  // rounding cycling: build() fails
            // t = (i, x, y), u = (d, y, x) -> t = (i, x, d), u = (i, d, y).
            const std::uint32_t x = a.v[1], y = a.v[2];
            if (!(orient(pa, pts_[x], pd) > 0 && orient(pa, pd, pts_[y]) > 0)) continue;
            const std::uint32_t n_yi = a.n[1], n_ix = a.n[2];  // across (y, i) and (i, x)
            const std::uint32_t n_xd = b.n[(ku + 1) % 3], n_dy = b.n[(ku + 2) % 3];
            tris_[t] = {{i, x, d}, {n_xd, u, n_ix}};
            tris_[u] = {{i, d, y}, {n_dy, n_yi, t}};
            relink(n_xd, u, t);
            relink(n_yi, t, u);
            note(t);
            note(u);
            stack.emplace_back(t, 0);
            stack.emplace_back(u, 0);
        }
    }

    std::vector<P2> pts_;
    std::vector<Tri> tris_;
    std::uint32_t last_ = 0;
    std::size_t flips_ = 0;              ///< all flips so far (capped: a safeguard against cycling)
    std::vector<std::uint32_t> tri_of_;  ///< per point: a triangle at it (may be stale)
    std::vector<std::uint8_t> inserted_;
};

std::uint64_t key(std::uint32_t a, std::uint32_t b) {
    return (std::uint64_t(a) << 32) | b;
}

/// The loop projected onto the plane of its Newell normal, counter-clockwise; empty when the
/// vector area is zero.
std::vector<P2> project(const std::vector<Point>& loop, double& scale) {
    const std::size_t n = loop.size();
    Vector3 normal = Vector3::Zero();
    Point centre = Point::Zero();
    for (std::size_t i = 0; i < n; ++i) {
        normal += loop[i].cross(loop[(i + 1) % n]);
        centre += loop[i];
    }
    centre /= double(n);
    scale = 0;
    for (std::size_t i = 0; i < n; ++i) scale += (loop[(i + 1) % n] - loop[i]).norm();
    scale /= double(n);
    if (!(normal.norm() > 1e-12 * scale * scale) || !normal.allFinite()) return {};
    normal.normalize();
    const Vector3 u = normal.unitOrthogonal(), v = normal.cross(u);
    std::vector<P2> p(n);
    for (std::size_t i = 0; i < n; ++i)
        p[i] = {(loop[i] - centre).dot(u), (loop[i] - centre).dot(v)};
    return p;
}

/// Whether two segments (ab, cd) meet (touching or overlapping included).
bool segments_meet(const P2& a, const P2& b, const P2& c, const P2& d, double eps) {
    const double o1 = orient(a, b, c), o2 = orient(a, b, d), o3 = orient(c, d, a),
                 o4 = orient(c, d, b);
    const auto sign = [eps](double o) { return o > eps ? 1 : (o < -eps ? -1 : 0); };
    const int s1 = sign(o1), s2 = sign(o2), s3 = sign(o3), s4 = sign(o4);
    if (s1 * s2 < 0 && s3 * s4 < 0) return true;
    // r in the box of pq, widened by a hair (the box of two collinear points has no height).
    const double hair = 1e-6 * std::sqrt(eps);
    const auto within = [hair](const P2& p, const P2& q, const P2& r) {
        return std::min(p.x, q.x) - hair <= r.x && r.x <= std::max(p.x, q.x) + hair &&
               std::min(p.y, q.y) - hair <= r.y && r.y <= std::max(p.y, q.y) + hair;
    };
    return (s1 == 0 && within(a, b, c)) || (s2 == 0 && within(a, b, d)) ||
           (s3 == 0 && within(c, d, a)) || (s4 == 0 && within(c, d, b));
}

/// Whether the closed polygon p is simple: no two rim edges other than neighbours meet. A
/// uniform grid of cells about two edges wide holds the edges; pairs sharing a cell are tested.
bool is_simple(const std::vector<P2>& p, double scale) {
    const std::size_t n = p.size();
    double lo_x = p[0].x, lo_y = p[0].y, hi_x = lo_x, hi_y = lo_y;
    for (const P2& q : p) {
        lo_x = std::min(lo_x, q.x);
        lo_y = std::min(lo_y, q.y);
        hi_x = std::max(hi_x, q.x);
        hi_y = std::max(hi_y, q.y);
    }
    const double cell = std::max({2 * scale, (hi_x - lo_x) / 4096, (hi_y - lo_y) / 4096});
    std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> grid;
    const double eps = 1e-13 * scale * scale;
    for (std::uint32_t i = 0; i < n; ++i) {
        const P2 &a = p[i], &b = p[(i + 1) % n];
        const auto x0 = std::uint32_t((std::min(a.x, b.x) - lo_x) / cell),
                   x1 = std::uint32_t((std::max(a.x, b.x) - lo_x) / cell);
        const auto y0 = std::uint32_t((std::min(a.y, b.y) - lo_y) / cell),
                   y1 = std::uint32_t((std::max(a.y, b.y) - lo_y) / cell);
        for (std::uint32_t x = x0; x <= x1; ++x)
            for (std::uint32_t y = y0; y <= y1; ++y) {
                std::vector<std::uint32_t>& in = grid[key(x, y)];
                for (std::uint32_t j : in) {
                    if ((j + 1) % n == i || (i + 1) % n == j) continue;
                    if (segments_meet(a, b, p[j], p[(j + 1) % n], eps)) return false;
                }
                in.push_back(i);
            }
    }
    return true;
}

/// The Delaunay triangles inside the polygon: a flood from the triangle left of each rim edge
/// i -> i + 1 across the edges that are not rim edges. Empty when a rim edge is missing.
std::vector<std::uint32_t> inside_triangles(const Delaunay2& dt, std::size_t n) {
    const auto& tris = dt.triangles();
    std::unordered_map<std::uint64_t, std::uint32_t> left_of;  // directed edge -> triangle
    left_of.reserve(3 * tris.size());
    for (std::uint32_t t = 0; t < tris.size(); ++t)
        for (int k = 0; k < 3; ++k)
            left_of[key(tris[t].v[(k + 1) % 3], tris[t].v[(k + 2) % 3])] = t;
    const auto is_rim = [n](std::uint32_t a, std::uint32_t b) {
        return a < n && b < n && ((a + 1) % n == b || (b + 1) % n == a);
    };
    std::vector<std::uint8_t> in(tris.size(), 0);
    std::vector<std::uint32_t> stack, out;
    for (std::uint32_t i = 0; i < n; ++i) {
        const auto it = left_of.find(key(i, std::uint32_t((i + 1) % n)));
        if (it == left_of.end()) return {};
        if (!in[it->second]) {
            in[it->second] = 1;
            stack.push_back(it->second);
        }
    }
    while (!stack.empty()) {
        const std::uint32_t t = stack.back();
        stack.pop_back();
        out.push_back(t);
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t a = tris[t].v[(k + 1) % 3], b = tris[t].v[(k + 2) % 3];
            const std::uint32_t u = tris[t].n[k];
            if (is_rim(a, b) || u == kNo || in[u]) continue;
            in[u] = 1;
            stack.push_back(u);
        }
    }
    return out;
}

/// The candidate edges: those of the inside triangles, and the other diagonal of every
/// strictly convex quadrilateral of two inside triangles.
std::vector<std::pair<std::uint32_t, std::uint32_t>> candidate_edges(
    const Delaunay2& dt, const std::vector<std::uint32_t>& inside) {
    const auto& tris = dt.triangles();
    std::vector<std::uint8_t> in(tris.size(), 0);
    for (std::uint32_t t : inside) in[t] = 1;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
    const auto add = [&edges](std::uint32_t a, std::uint32_t b) {
        edges.emplace_back(std::min(a, b), std::max(a, b));
    };
    for (std::uint32_t t : inside)
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t a = tris[t].v[(k + 1) % 3], b = tris[t].v[(k + 2) % 3];
            add(a, b);
            const std::uint32_t u = tris[t].n[k];
            if (u == kNo || !in[u] || u < t) continue;
            std::uint32_t d = kNo;
            for (int j = 0; j < 3; ++j)
                if (tris[u].n[j] == t) d = tris[u].v[j];
            const std::uint32_t c = tris[t].v[k];
            if (d == kNo) continue;
            // The quadrilateral (c, a, d, b) is strictly convex when c and d lie on opposite
            // sides of ab and a and b on opposite sides of cd.
            const P2 &pa = dt.point(a), &pb = dt.point(b), &pc = dt.point(c), &pd = dt.point(d);
            if (orient(pc, pd, pa) * orient(pc, pd, pb) < 0 &&
                orient(pa, pb, pc) * orient(pa, pb, pd) < 0)
                add(c, d);
        }
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    return edges;
}

}  // namespace

LoopDelaunay loop_delaunay_edges(const std::vector<Point>& loop) {
    LoopDelaunay r;
    const std::size_t n = loop.size();
    double scale = 0;
    std::vector<P2> p = project(loop, scale);
    if (p.empty()) {
        r.why = "its vector area is zero (no plane to project it onto)";
        return r;
    }
    if (!is_simple(p, scale)) {
        r.why = "its projection onto its best-fit (Newell) plane is not a simple polygon";
        return r;
    }
    Delaunay2 dt;
    if (!dt.build(p, scale)) {
        r.why =
            "its 2-D Delaunay triangulation failed (two rim vertices project onto one point, "
            "or rounding kept flipping)";
        return r;
    }
    const std::vector<std::uint32_t> inside = inside_triangles(dt, n);
    if (inside.empty()) {
        r.why = "a rim edge is not an edge of the 2-D Delaunay triangulation";
        return r;
    }
    // The inside triangles must cover the polygon once: n - 2 of them, each counter-clockwise,
    // their areas summing to the polygon's.
    double area = 0, polygon = 0;
    for (std::uint32_t t : inside) {
        const auto& v = dt.triangles()[t].v;
        const double a = orient(dt.point(v[0]), dt.point(v[1]), dt.point(v[2]));
        if (!(a > 0) || v[0] >= n || v[1] >= n || v[2] >= n) {
            r.why = "the 2-D Delaunay triangles inside the rim do not cover it once (rounding)";
            return r;
        }
        area += a;
    }
    for (std::size_t i = 0; i < n; ++i)
        polygon += p[i].x * p[(i + 1) % n].y - p[(i + 1) % n].x * p[i].y;
    if (inside.size() != n - 2 || !(std::abs(area - polygon) <= 1e-9 * std::abs(polygon))) {
        r.why = "the 2-D Delaunay triangles inside the rim do not cover it once (rounding)";
        return r;
    }
    r.edges = candidate_edges(dt, inside);
    return r;
}

}  // namespace trilab
