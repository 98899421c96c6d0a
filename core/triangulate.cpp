// Triangulation of one polygon (core/triangulate.h): the method in full.
//
// Triangulation of one polygon (a face of a polygon soup) in its best-fit plane.
//
// The corners are projected onto the plane through their centroid normal to the Newell
// normal (Newell's method; Tampieri, "Newell's method for computing the plane equation of a
// polygon", Graphics Gems III, 1992), in which the polygon runs counter-clockwise, and every
// triangle keeps the corner order's orientation.
//  - Up to kEarClippingCorners corners: ear clipping (Meisters 1975), O(n^3) at worst and
//    tiny for such n: a corner is clipped when it is convex and no other corner lies in its
//    triangle (on its edges included).
//  - More corners: a partition into y-monotone pieces by a plane sweep, and each piece
//    triangulated along its two chains with a stack (Garey, Johnson, Preparata and Tarjan,
//    "Triangulating a simple polygon", IPL 7(4), 1978; de Berg et al., Computational
//    Geometry, 3rd ed., chapter 3). Ties in the sweep order (equal y, then equal x) are
//    broken by corner index, so collinear runs, horizontal edges and repeated positions
//    need no special case. O(n log n) time, O(n) space.
// The monotone result is checked: n - 2 triangles, no repeated corner, none inverted in the
// plane (beyond a rounding tolerance relative to the polygon's extent), and their areas sum
// to the polygon's. A polygon that fails the check (it crosses or folds over itself in the
// plane, or is degenerate) is ear clipped if it has at most kFallbackEarClippingCorners
// corners; otherwise, or when ear clipping finds no ear, it becomes a fan from corner 0
// (the historical fallback), which is reported. Never throws on any finite input.
#include "core/triangulate.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <set>

namespace trilab {

namespace {

/// An edge in the sweep status, with its corners' coordinates (so that comparisons read
/// only the tree nodes). Edge e runs from corner e, its upper end (only edges going down
/// the left side of the interior enter the status), to corner e + 1.
struct StatusEdge {
    double ux, uy, lx, ly;
    Index upper_rank;
    Index e;
};

/// A corner given to the sweep status's lower_bound: "the edges left of this corner".
struct Probe {
    double x, y;
};

/// Which side of the line from (ax, ay) through (bx, by) the point (cx, cy) lies on:
/// positive to the left, negative to the right, zero on the line.
inline double orient2d(double ax, double ay, double bx, double by, double cx, double cy) {
    return (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
}

/// Orders the status edges from left to right. Of two edges, the one whose upper corner
/// the sweep met first spans the other's upper corner, which is then left or right of it
/// (a downward edge has its right side to the west); a tie (the corner on the line, only
/// in a polygon that touches itself) goes by index, so the order stays antisymmetric
/// whatever the input and the tree stays well formed.
struct EdgeLess {
    using is_transparent = void;
    /// Whether edge a is left of edge b.
    bool operator()(const StatusEdge& a, const StatusEdge& b) const {
        if (a.e == b.e) return false;
        if (a.upper_rank < b.upper_rank) {
            const double s = orient2d(a.ux, a.uy, a.lx, a.ly, b.ux, b.uy);
            if (s != 0) return s > 0;  // b's upper corner is right of a
        } else {
            const double s = orient2d(b.ux, b.uy, b.lx, b.ly, a.ux, a.uy);
            if (s != 0) return s < 0;  // a's upper corner is left of b
        }
        return a.e < b.e;
    }
    /// Whether edge e is left of the corner (strictly).
    bool operator()(const StatusEdge& e, Probe p) const {
        return orient2d(e.ux, e.uy, e.lx, e.ly, p.x, p.y) > 0;
    }
    bool operator()(Probe p, const StatusEdge& e) const {
        return orient2d(e.ux, e.uy, e.lx, e.ly, p.x, p.y) < 0;
    }
};

/// An order-preserving unsigned image of a double (negative zero counts as zero).
inline std::uint64_t order_key(double d) {
    d += 0.0;  // -0 -> +0
    std::uint64_t bits;
    std::memcpy(&bits, &d, sizeof bits);
    return (bits >> 63) ? ~bits : bits | (std::uint64_t(1) << 63);
}

}  // namespace

TriangulationMethod PolygonTriangulator::triangulate(const std::vector<Point>& p,
                                                     std::vector<PolygonTriangle>& out) {
    const std::size_t n = p.size();
    const std::size_t before = out.size();
    auto fan = [&] {
        out.resize(before);
        for (Index i = 1; i + 1 < n; ++i) out.push_back({0, i, i + 1});
        return TriangulationMethod::kFan;
    };
    if (n < 3) return TriangulationMethod::kFan;
    if (n == 3) {
        out.push_back({0, 1, 2});
        return TriangulationMethod::kEarClipping;
    }
    // Newell's normal: the polygon's area vector, pointing where the corners turn
    // counter-clockwise.
    auto newell = [&](auto&& corner) {
        Vector3 normal = Vector3::Zero();
        for (std::size_t i = 0; i < n; ++i) {
            const Point a = corner(i), b = corner(i + 1 == n ? 0 : i + 1);
            normal += Vector3((a.y() - b.y()) * (a.z() + b.z()), (a.z() - b.z()) * (a.x() + b.x()),
                              (a.x() - b.x()) * (a.y() + b.y()));
        }
        return normal;
    };
    // The corners relative to their bounding box's centre, scaled into [-1, 1] (in halves,
    // so that no difference overflows even for coordinates near the largest double).
    Point lo = p[0], hi = p[0];
    for (const Point& q : p) {
        lo = lo.cwiseMin(q);
        hi = hi.cwiseMax(q);
    }
    const Point centre = 0.5 * lo + 0.5 * hi;
    const double half_extent = (0.5 * hi - 0.5 * lo).maxCoeff();
    if (!(half_extent > 0) || !std::isfinite(half_extent)) return fan();
    const double scale = 1.0 / half_extent;
    auto scaled = [&](std::size_t i) -> Point { return (0.5 * p[i] - 0.5 * centre) * scale; };

    // The raw corners give the historical normal; the scaled ones one that cannot overflow,
    // taken where the raw products of coordinates could (chosen before computing, so that
    // nothing overflows on the way).
    const double largest = std::max(lo.cwiseAbs().maxCoeff(), hi.cwiseAbs().maxCoeff());
    Vector3 normal =
        largest < 0x1p400 ? newell([&](std::size_t i) { return p[i]; }) : newell(scaled);
    if (!normal.allFinite()) normal = newell(scaled);
    if (!(normal.norm() > 0) || !normal.allFinite()) return fan();
    normal.normalize();

    if (n <= kEarClippingCorners)
        return ear_clip(p, normal, out) ? TriangulationMethod::kEarClipping : fan();

    // A right-handed frame (t1, t2, normal): the polygon runs counter-clockwise in (t1, t2).
    int axis = 0;
    for (int k = 1; k < 3; ++k)
        if (std::abs(normal[k]) < std::abs(normal[axis])) axis = k;
    const Vector3 t1 = normal.cross(Vector3::Unit(axis)).normalized();
    const Vector3 t2 = normal.cross(t1);
    xy_.resize(2 * n);
    for (std::size_t i = 0; i < n; ++i) {
        const Point q = scaled(i);
        xy_[2 * i] = q.dot(t1);
        xy_[2 * i + 1] = q.dot(t2);
        if (!std::isfinite(xy_[2 * i]) || !std::isfinite(xy_[2 * i + 1])) return fan();
    }
    if (monotone(out)) return TriangulationMethod::kMonotone;
    out.resize(before);
    if (n <= kFallbackEarClippingCorners && ear_clip(p, normal, out))
        return TriangulationMethod::kEarClipping;
    return fan();
}

bool PolygonTriangulator::ear_clip(const std::vector<Point>& p, const Vector3& normal,
                                   std::vector<PolygonTriangle>& out) {
    const std::size_t n = p.size();
    ring_.resize(n);
    for (Index i = 0; i < n; ++i) ring_[i] = i;
    auto cross_n = [&](Index a, Index b, Index c) {
        return (p[b] - p[a]).cross(p[c] - p[a]).dot(normal);
    };
    while (ring_.size() > 3) {
        const std::size_t m = ring_.size();
        bool clipped = false;
        for (std::size_t i = 0; i < m && !clipped; ++i) {
            const Index a = ring_[(i + m - 1) % m], b = ring_[i], c = ring_[(i + 1) % m];
            if (!(cross_n(a, b, c) > 0)) continue;  // reflex or degenerate corner
            bool inside = false;
            for (std::size_t j = 0; j < m && !inside; ++j) {
                const Index q = ring_[j];
                if (q == a || q == b || q == c) continue;
                inside = cross_n(a, b, q) >= 0 && cross_n(b, c, q) >= 0 && cross_n(c, a, q) >= 0;
            }
            if (inside) continue;
            out.push_back({a, b, c});
            ring_.erase(ring_.begin() + static_cast<std::ptrdiff_t>(i));
            clipped = true;
        }
        if (!clipped) return false;
    }
    out.push_back({ring_[0], ring_[1], ring_[2]});
    return true;
}

void PolygonTriangulator::sort_sweep() {
    const std::size_t n = sweep_.size();
    auto less = [](const SweepKey& a, const SweepKey& b) {
        if (a.high != b.high) return a.high < b.high;
        if (a.low != b.low) return a.low < b.low;
        return a.corner < b.corner;
    };
    constexpr std::size_t kRadixFrom = std::size_t(1) << 14;
    if (n < kRadixFrom) {
        std::sort(sweep_.begin(), sweep_.end(), less);
        return;
    }
    // Least significant digit first radix sort, 16 bits a pass, low key then high key; the
    // keys start in corner order and every pass is stable. A pass whose digit is the same
    // for every key is skipped.
    constexpr std::size_t kDigits = 8, kBuckets = std::size_t(1) << 16;
    auto digit = [](const SweepKey& k, std::size_t d) {
        const std::uint64_t word = d < 4 ? k.low : k.high;
        return std::size_t((word >> (16 * (d % 4))) & 0xffff);
    };
    digit_count_.assign(kDigits * kBuckets, 0);
    for (const SweepKey& k : sweep_)
        for (std::size_t d = 0; d < kDigits; ++d) ++digit_count_[d * kBuckets + digit(k, d)];
    sweep_scratch_.resize(n);
    for (std::size_t d = 0; d < kDigits; ++d) {
        Index* count = digit_count_.data() + d * kBuckets;
        if (count[digit(sweep_[0], d)] == n) continue;
        Index sum = 0;
        for (std::size_t b = 0; b < kBuckets; ++b) {
            const Index c = count[b];
            count[b] = sum;
            sum += c;
        }
        for (const SweepKey& k : sweep_) sweep_scratch_[count[digit(k, d)]++] = k;
        sweep_.swap(sweep_scratch_);
    }
}

namespace {
/// The corners before and after corner v of a polygon of n corners.
inline Index corner_before(Index v, Index n) {
    return v == 0 ? n - 1 : v - 1;
}
inline Index corner_after(Index v, Index n) {
    return v + 1 == n ? 0 : v + 1;
}
}  // namespace

bool PolygonTriangulator::monotone(std::vector<PolygonTriangle>& out) {
    const std::size_t before = out.size();
    sort_corners_for_sweep();
    if (!find_monotone_diagonals()) return false;
    if (!link_pieces()) return false;
    if (!triangulate_pieces(out)) return false;
    return is_valid_triangulation(out, before);
}

// 1. The sweep order, top to bottom: larger y first, then smaller x, then lower index
//    (a symbolic rotation of the sweep line that leaves no two corners level).
void PolygonTriangulator::sort_corners_for_sweep() {
    const Index n = Index(xy_.size() / 2);
    const double* xy = xy_.data();
    sweep_.resize(n);
    for (Index i = 0; i < n; ++i) sweep_[i] = {~order_key(xy[2 * i + 1]), order_key(xy[2 * i]), i};
    sort_sweep();
    order_.resize(n);
    rank_.resize(n);
    for (Index i = 0; i < n; ++i) {
        order_[i] = sweep_[i].corner;
        rank_[order_[i]] = i;
    }
}

// 2. Diagonals that split the polygon into y-monotone pieces (de Berg et al., 3.2).
bool PolygonTriangulator::find_monotone_diagonals() {
    const Index n = Index(xy_.size() / 2);
    const double* xy = xy_.data();
    helper_.assign(n, kInvalidIndex);
    is_merge_.assign(n, 0);
    diagonals_.clear();
    using Tree = std::set<StatusEdge, EdgeLess>;
    Tree tree;
    std::vector<Tree::iterator> where(n, tree.end());
    auto insert = [&](Index e, Index helper) {
        const Index l = corner_after(e, n);
        const StatusEdge key{xy[2 * e], xy[2 * e + 1], xy[2 * l], xy[2 * l + 1], rank_[e], e};
        const auto [it, inserted] = tree.insert(key);
        if (!inserted) return false;
        where[e] = it;
        helper_[e] = helper;
        return true;
    };
    auto erase = [&](Index e) {
        if (where[e] == tree.end()) return false;
        tree.erase(where[e]);
        where[e] = tree.end();
        return true;
    };
    auto left_edge = [&](Index v) {
        auto it = tree.lower_bound(Probe{xy[2 * v], xy[2 * v + 1]});
        return it == tree.begin() ? kInvalidIndex : std::prev(it)->e;
    };
    auto connect_if_merge = [&](Index v, Index e) {
        if (is_merge_[helper_[e]]) diagonals_.push_back({v, helper_[e]});
    };
    for (Index v : order_) {
        const Index p = corner_before(v, n), q = corner_after(v, n);
        const bool p_below = rank_[p] > rank_[v], q_below = rank_[q] > rank_[v];
        const bool convex = orient(p, v, q) > 0;
        if (p_below && q_below) {
            if (!convex) {  // split corner: join it to the helper of the edge on its left
                const Index e = left_edge(v);
                if (e == kInvalidIndex) return false;
                diagonals_.push_back({v, helper_[e]});
                helper_[e] = v;
            }
            if (!insert(v, v)) return false;  // start or split corner
        } else if (!p_below && !q_below) {    // end or merge corner
            if (where[p] == tree.end()) return false;
            connect_if_merge(v, p);
            erase(p);
            if (!convex) {
                is_merge_[v] = 1;
                const Index e = left_edge(v);
                if (e == kInvalidIndex) return false;
                connect_if_merge(v, e);
                helper_[e] = v;
            }
        } else if (!p_below) {  // on a left chain: the interior lies to the right
            if (where[p] == tree.end()) return false;
            connect_if_merge(v, p);
            erase(p);
            if (!insert(v, v)) return false;
        } else {  // on a right chain
            const Index e = left_edge(v);
            if (e == kInvalidIndex) return false;
            connect_if_merge(v, e);
            helper_[e] = v;
        }
    }
    return true;
}

// 3a. The pieces: halfedge h < n runs along the polygon from corner h; diagonal d gives
//     n + 2d (from its first corner) and n + 2d + 1. Around each corner, the halfedges
//     leaving it sorted counter-clockwise from the polygon edge give the next halfedge
//     of each piece (the one clockwise after the way back).
bool PolygonTriangulator::link_pieces() {
    const Index n = Index(xy_.size() / 2);
    const double* xy = xy_.data();
    const Index n_diag = Index(diagonals_.size());
    const Index n_half = n + 2 * n_diag;
    auto origin = [&](Index h) { return h < n ? h : diagonals_[(h - n) / 2][(h - n) & 1]; };
    auto target = [&](Index h) {
        return h < n ? corner_after(h, n) : diagonals_[(h - n) / 2][1 - ((h - n) & 1)];
    };
    out_begin_.assign(n + 1, 0);
    for (const auto& d : diagonals_) {
        if (d[0] == d[1]) return false;
        ++out_begin_[d[0] + 1];
        ++out_begin_[d[1] + 1];
    }
    for (Index v = 0; v < n; ++v) out_begin_[v + 1] += out_begin_[v];
    out_list_.resize(2 * std::size_t(n_diag));
    {
        std::vector<Index>& fill = stack_;
        fill.assign(out_begin_.begin(), out_begin_.end() - 1);
        for (Index h = n; h < n_half; ++h) out_list_[fill[origin(h)]++] = h;
    }
    half_next_.assign(n_half, kInvalidIndex);
    for (Index v = 0; v < n; ++v) {
        const auto first = out_list_.begin() + out_begin_[v];
        const auto last = out_list_.begin() + out_begin_[v + 1];
        if (first == last) {
            half_next_[corner_before(v, n)] = v;
            continue;
        }
        const Index w = corner_after(v, n);
        const double rx = xy[2 * w] - xy[2 * v], ry = xy[2 * w + 1] - xy[2 * v + 1];
        auto half = [&](double dx, double dy) {
            const double c = rx * dy - ry * dx;
            return (c > 0 || (c == 0 && rx * dx + ry * dy > 0)) ? 0 : 1;
        };
        std::sort(first, last, [&](Index a, Index b) {
            const double ax = xy[2 * target(a)] - xy[2 * v];
            const double ay = xy[2 * target(a) + 1] - xy[2 * v + 1];
            const double bx = xy[2 * target(b)] - xy[2 * v];
            const double by = xy[2 * target(b) + 1] - xy[2 * v + 1];
            const int ha = half(ax, ay), hb = half(bx, by);
            if (ha != hb) return ha < hb;
            const double c = ax * by - ay * bx;
            if (c != 0) return c > 0;
            return a < b;
        });
        half_next_[corner_before(v, n)] = *(last - 1);
        for (auto it = first; it != last; ++it) {
            const Index back = n + ((*it - n) ^ 1);  // the diagonal's other half, into v
            half_next_[back] = it == first ? v : *(it - 1);
        }
    }
    return true;
}

// 3b. Each piece walked along half_next_ and triangulated; false unless the diagonals cut
//     the polygon into exactly n_diag + 1 pieces (a plane map).
bool PolygonTriangulator::triangulate_pieces(std::vector<PolygonTriangle>& out) {
    const Index n = Index(xy_.size() / 2);
    const Index n_diag = Index(diagonals_.size());
    const Index n_half = n + 2 * n_diag;
    auto origin = [&](Index h) { return h < n ? h : diagonals_[(h - n) / 2][(h - n) & 1]; };
    visited_.assign(n_half, 0);
    Index n_pieces = 0;
    for (Index h0 = 0; h0 < n_half; ++h0) {
        if (visited_[h0]) continue;
        piece_.clear();
        Index h = h0;
        do {
            if (h == kInvalidIndex || visited_[h]) return false;
            visited_[h] = 1;
            piece_.push_back(origin(h));
            h = half_next_[h];
        } while (h != h0);
        ++n_pieces;
        if (!triangulate_piece(out)) return false;
    }
    return n_pieces == n_diag + 1;
}

// 4. The check: n - 2 triangles, no repeated corner, none inverted, the polygon's area.
bool PolygonTriangulator::is_valid_triangulation(const std::vector<PolygonTriangle>& out,
                                                 std::size_t before) const {
    const Index n = Index(xy_.size() / 2);
    const double* xy = xy_.data();
    if (out.size() - before != std::size_t(n) - 2) return false;
    double area2 = 0, sum = 0, sum_abs = 0;
    for (Index i = 0; i < n; ++i) {
        const Index j = corner_after(i, n);
        area2 += xy[2 * i] * xy[2 * j + 1] - xy[2 * j] * xy[2 * i + 1];
    }
    constexpr double kInvertedTolerance = 1e-14;  // coordinates are scaled to about [-1, 1]
    for (std::size_t t = before; t < out.size(); ++t) {
        const PolygonTriangle& tri = out[t];
        if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2]) return false;
        const double a = orient(tri[0], tri[1], tri[2]);
        if (!(a >= -kInvertedTolerance)) return false;
        sum += a;
        sum_abs += std::abs(a);
    }
    return area2 > 0 && std::abs(sum - area2) <= 1e-9 * std::max(sum_abs, area2);
}

bool PolygonTriangulator::triangulate_piece(std::vector<PolygonTriangle>& out) {
    // A y-monotone piece, counter-clockwise: from its top corner the left chain runs down
    // to the bottom corner, the right chain comes back up (de Berg et al., 3.3).
    const std::size_t k = piece_.size();
    if (k < 3) return false;
    if (k == 3) {
        out.push_back({piece_[0], piece_[1], piece_[2]});
        return true;
    }
    std::size_t top = 0, bottom = 0;
    for (std::size_t i = 1; i < k; ++i) {
        if (rank_[piece_[i]] < rank_[piece_[top]]) top = i;
        if (rank_[piece_[i]] > rank_[piece_[bottom]]) bottom = i;
    }
    // The two chains, each in sweep order if the piece is monotone, merged into one order
    // (a piece that is not monotone, only possible for a polygon that is not simple, fails).
    on_left_.assign(k, 0);
    sorted_.clear();
    sorted_.push_back(Index(top));
    std::size_t left = (top + 1) % k, right = (top + k - 1) % k;
    Index last_left = rank_[piece_[top]], last_right = last_left;
    while (left != bottom || right != bottom) {
        const bool take_left =
            left != bottom && (right == bottom || rank_[piece_[left]] < rank_[piece_[right]]);
        if (take_left) {
            if (rank_[piece_[left]] <= last_left) return false;
            last_left = rank_[piece_[left]];
            on_left_[left] = 1;
            sorted_.push_back(Index(left));
            left = (left + 1) % k;
        } else {
            if (rank_[piece_[right]] <= last_right) return false;
            last_right = rank_[piece_[right]];
            sorted_.push_back(Index(right));
            right = (right + k - 1) % k;
        }
    }
    sorted_.push_back(Index(bottom));
    // The triangle of corner u with two consecutive stack corners, `upper` met before
    // `lower`, counter-clockwise. `lower` lies on the stack's chain and u on the interior
    // side of it (east of a left chain, west of a right one), whichever chain u is on.
    auto triangle = [&](Index u, Index upper, Index lower) {
        const Index a = piece_[u], b = piece_[upper], c = piece_[lower];
        return on_left_[lower] ? PolygonTriangle{a, b, c} : PolygonTriangle{a, c, b};
    };
    stack_.clear();
    stack_.push_back(sorted_[0]);
    stack_.push_back(sorted_[1]);
    for (std::size_t j = 2; j + 1 < k; ++j) {
        const Index u = sorted_[j];
        if (on_left_[u] != on_left_[stack_.back()]) {
            // Opposite chains: u sees the whole stack.
            for (std::size_t i = 0; i + 1 < stack_.size(); ++i)
                out.push_back(triangle(u, stack_[i], stack_[i + 1]));
            const Index last = stack_.back();
            stack_.clear();
            stack_.push_back(last);
            stack_.push_back(u);
        } else {
            // Same chain: cut off the corners that u sees inside the piece (those where the
            // chain turns away from the interior).
            Index last = stack_.back();
            stack_.pop_back();
            while (!stack_.empty()) {
                const PolygonTriangle t = triangle(u, stack_.back(), last);
                if (!(orient(t[0], t[1], t[2]) > 0)) break;
                out.push_back(t);
                last = stack_.back();
                stack_.pop_back();
            }
            stack_.push_back(last);
            stack_.push_back(u);
        }
    }
    // The bottom corner ends both chains and sees the whole stack.
    const Index u = sorted_[k - 1];
    for (std::size_t i = 0; i + 1 < stack_.size(); ++i)
        out.push_back(triangle(u, stack_[i], stack_[i + 1]));
    return true;
}

std::vector<PolygonTriangle> triangulate_polygon(const std::vector<Point>& corners,
                                                 TriangulationMethod* method) {
    PolygonTriangulator triangulator;
    std::vector<PolygonTriangle> out;
    const TriangulationMethod m = triangulator.triangulate(corners, out);
    if (method) *method = m;
    return out;
}

}  // namespace trilab
