// Isotropic remeshing (see core/algorithms/remesh.h).
//
// The work happens on the mesh itself through the kernel's split, collapse and flip (which keep
// its invariants); the remesher keeps a few flat arrays beside it, indexed by vertex storage
// index and grown with each split: the weight (region and seams: 0 = frozen), the input
// triangle each vertex was last projected onto, and whether its attributes must be
// interpolated again at the end. Nothing is hashed; every pass is a sweep over the storage.
#include "core/algorithms/remesh.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "core/algorithms/curvature.h"
#include "core/algorithms/feature_detection.h"
#include "core/algorithms/mesh_distance.h"
#include "core/algorithms/spatial_order.h"
#include "core/algorithms/texcoords.h"
#include "core/enum_table.h"
#include "core/errors.h"
#include "core/features.h"
#include "core/geometry.h"
#include "core/number_text.h"
#include "core/system_memory.h"
#include "core/two_threads.h"

namespace trilab {
namespace {

constexpr double kIdealTriangleArea = 0.4330127018922193;  // sqrt(3) / 4
/// The split and collapse thresholds are Botsch and Kobbelt's for this multiple of L (see
/// Remesher::Remesher).
constexpr double kWorkingLength = 1.06;
/// Bytes per output face: the mesh (about 80: 1.5 edges of 2 halfedges of 16 bytes, half a
/// vertex of 29, a face of 5, and their deleted flags), the remesher's per-vertex arrays, the
/// copy the caller keeps, and the growth of the arrays (a vector doubles).
constexpr double kBytesPerOutputFace = 400;
/// Bytes per input face: the tree over the input surface (triangles, nodes, order).
constexpr double kBytesPerInputFace = 200;

std::string text_of(double v) {
    char buf[40];
    std::snprintf(buf, sizeof(buf), "%.6g", v);
    return buf;
}

// ---- the input surface ----------------------------------------------------------------------

/// The closest point to p on triangle t and its barycentric weights (Ericson, Real-Time
/// Collision Detection, 5.1.5): a weight is 0 exactly where the point is on the opposite side
/// or corner. A degenerate triangle gives equal weights (its whole star is searched).
struct Closest {
    Point q = Point::Zero();
    double b[3] = {0, 0, 0};
};

Closest closest_with_weights(const Point& p, const std::array<Point, 3>& t) {
    const Point &a = t[0], &b = t[1], &c = t[2];
    Closest r;
    const Vector3 ab = b - a, ac = c - a, ap = p - a;
    const double d1 = ab.dot(ap), d2 = ac.dot(ap);
    if (d1 <= 0 && d2 <= 0) return {a, {1, 0, 0}};
    const Vector3 bp = p - b;
    const double d3 = ab.dot(bp), d4 = ac.dot(bp);
    if (d3 >= 0 && d4 <= d3) return {b, {0, 1, 0}};
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0 && d1 - d3 > 0) {
        const double v = d1 / (d1 - d3);
        return {a + v * ab, {1 - v, v, 0}};
    }
    const Vector3 cp = p - c;
    const double d5 = ab.dot(cp), d6 = ac.dot(cp);
    if (d6 >= 0 && d5 <= d6) return {c, {0, 0, 1}};
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0 && d2 - d6 > 0) {
        const double w = d2 / (d2 - d6);
        return {a + w * ac, {1 - w, 0, w}};
    }
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0 && (d4 - d3) + (d5 - d6) > 0) {
        const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return {b + w * (c - b), {0, 1 - w, w}};
    }
    const double sum = va + vb + vc;
    if (!(sum > 0) || !std::isfinite(sum)) {
        r.q = closest_point_on_triangle(p, a, b, c);
        r.b[0] = r.b[1] = r.b[2] = 1.0 / 3.0;
        return r;
    }
    const double v = vb / sum, w = vc / sum;
    return {a + ab * v + ac * w, {1 - v - w, v, w}};
}

/// An axis-aligned bounding-box tree over the input's triangles, for closest points.
class SurfaceTree {
public:
    struct Hit {
        Point point = Point::Zero();
        std::uint32_t face = 0;
    };

    void build(std::vector<std::array<Point, 3>> triangles) {
        tri_ = std::move(triangles);
        order_.resize(tri_.size());
        centroid_.resize(tri_.size());
        for (std::size_t i = 0; i < tri_.size(); ++i) {
            order_[i] = std::uint32_t(i);
            centroid_[i] = (tri_[i][0] + tri_[i][1] + tri_[i][2]) / 3.0;
        }
        nodes_.clear();
        nodes_.reserve(2 * tri_.size() / kLeaf + 2);
        if (!tri_.empty()) build_nodes();
        centroid_ = {};
    }
    std::size_t size() const { return tri_.size(); }
    const std::array<Point, 3>& triangle(std::uint32_t i) const { return tri_[i]; }

    /// The triangles' corners (input vertex indices below n_vertices), for the local walk.
    void set_corners(std::vector<std::array<std::uint32_t, 3>> corners, std::size_t n_vertices) {
        corners_ = std::move(corners);
        star_begin_.assign(n_vertices + 1, 0);
        for (const auto& c : corners_)
            for (std::uint32_t v : c) ++star_begin_[v + 1];
        for (std::size_t i = 0; i < n_vertices; ++i) star_begin_[i + 1] += star_begin_[i];
        star_.resize(star_begin_.back());
        std::vector<std::uint32_t> fill(star_begin_.begin(), star_begin_.end() - 1);
        for (std::uint32_t f = 0; f < corners_.size(); ++f)
            for (std::uint32_t v : corners_[f]) star_[fill[v]++] = f;
    }

    /// The closest point to p found by walking over the input from triangle `hint`: while the
    /// closest point of the current triangle is on its border, the triangles around the
    /// corners it touches are tried and the best taken. A point that moved a little from the
    /// surface costs a triangle or two; a walk that does not settle within a few steps falls
    /// back to the tree. Stays on the sheet the vertex came from where the input folds close
    /// to itself (the tree would take the nearest sheet).
    Hit walk(const Point& p, std::uint32_t hint) const {
        if (hint >= tri_.size() || corners_.empty()) return closest(p, hint);
        std::uint32_t f = hint;
        Closest best = closest_with_weights(p, tri_[f]);
        double best_d2 = (best.q - p).squaredNorm();
        for (int step = 0; step < 8; ++step) {
            if (best.b[0] > 0 && best.b[1] > 0 && best.b[2] > 0) break;
            std::uint32_t next = f;
            Closest next_c = best;
            double next_d2 = best_d2;
            for (int k = 0; k < 3; ++k) {
                if (!(best.b[k] > 0)) continue;
                const std::uint32_t v = corners_[f][k];
                for (std::uint32_t i = star_begin_[v]; i < star_begin_[v + 1]; ++i) {
                    const std::uint32_t g = star_[i];
                    if (g == f) continue;
                    const Closest c = closest_with_weights(p, tri_[g]);
                    const double d2 = (c.q - p).squaredNorm();
                    if (d2 < next_d2) {
                        next_d2 = d2;
                        next_c = c;
                        next = g;
                    }
                }
            }
            if (next == f) return {best.q, f};
            f = next;
            best = next_c;
            best_d2 = next_d2;
            if (best.b[0] > 0 && best.b[1] > 0 && best.b[2] > 0) return {best.q, f};
        }
        return {best.q, f};
    }

    /// The closest point to p on the surface, starting from triangle `hint` (its distance
    /// bounds the search, so a point that moved a little costs a few boxes).
    Hit closest(const Point& p, std::uint32_t hint) const {
        Hit best;
        double best_d2 = std::numeric_limits<double>::infinity();
        if (hint < tri_.size()) {
            const auto& t = tri_[hint];
            best.point = closest_point_on_triangle(p, t[0], t[1], t[2]);
            best.face = hint;
            best_d2 = (best.point - p).squaredNorm();
        }
        std::uint32_t stack[128];
        int top = 0;
        stack[top++] = 0;
        while (top > 0) {
            const Node& n = nodes_[stack[--top]];
            if (box_d2(n, p) >= best_d2) continue;
            if (n.count > 0) {
                for (std::uint32_t i = n.first; i < n.first + n.count; ++i) {
                    const std::uint32_t f = order_[i];
                    const auto& t = tri_[f];
                    const Point q = closest_point_on_triangle(p, t[0], t[1], t[2]);
                    const double d2 = (q - p).squaredNorm();
                    if (d2 < best_d2) {
                        best_d2 = d2;
                        best.point = q;
                        best.face = f;
                    }
                }
                continue;
            }
            const std::uint32_t l = n.first, r = n.first + 1;
            const double dl = box_d2(nodes_[l], p), dr = box_d2(nodes_[r], p);
            if (dl < dr) {
                if (dr < best_d2) stack[top++] = r;
                if (dl < best_d2) stack[top++] = l;
            } else {
                if (dl < best_d2) stack[top++] = l;
                if (dr < best_d2) stack[top++] = r;
            }
        }
        return best;
    }

private:
    static constexpr std::uint32_t kLeaf = 4;
    struct Node {
        double lo[3], hi[3];
        std::uint32_t first = 0;  ///< leaf: first index into order_; inner: left child
        std::uint32_t count = 0;  ///< leaf: triangles; inner: 0
    };
    static double box_d2(const Node& n, const Point& p) {
        double d2 = 0;
        for (int k = 0; k < 3; ++k) {
            const double d = std::max({n.lo[k] - p[k], p[k] - n.hi[k], 0.0});
            d2 += d * d;
        }
        return d2;
    }
    void build_nodes() {
        struct Task {
            std::uint32_t node, begin, end;
        };
        std::vector<Task> tasks;
        nodes_.push_back(Node());
        tasks.push_back({0, 0, std::uint32_t(tri_.size())});
        while (!tasks.empty()) {
            const Task t = tasks.back();
            tasks.pop_back();
            Node& node = nodes_[t.node];
            Point lo = Point::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
            Point clo = lo, chi = hi;
            for (std::uint32_t i = t.begin; i < t.end; ++i) {
                for (const Point& q : tri_[order_[i]]) {
                    lo = lo.cwiseMin(q);
                    hi = hi.cwiseMax(q);
                }
                clo = clo.cwiseMin(centroid_[order_[i]]);
                chi = chi.cwiseMax(centroid_[order_[i]]);
            }
            for (int k = 0; k < 3; ++k) {
                node.lo[k] = lo[k];
                node.hi[k] = hi[k];
            }
            if (t.end - t.begin <= kLeaf) {
                node.first = t.begin;
                node.count = t.end - t.begin;
                continue;
            }
            const Point ext = chi - clo;
            int axis = 0;
            if (ext.y() > ext[axis]) axis = 1;
            if (ext.z() > ext[axis]) axis = 2;
            const std::uint32_t mid = t.begin + (t.end - t.begin) / 2;
            std::nth_element(order_.begin() + t.begin, order_.begin() + mid, order_.begin() + t.end,
                             [&](std::uint32_t a, std::uint32_t b) {
                                 return centroid_[a][axis] < centroid_[b][axis];
                             });
            const std::uint32_t left = std::uint32_t(nodes_.size());
            nodes_[t.node].first = left;
            nodes_[t.node].count = 0;
            nodes_.push_back(Node());
            nodes_.push_back(Node());
            tasks.push_back({left, t.begin, mid});
            tasks.push_back({left + 1, mid, t.end});
        }
    }

    std::vector<std::array<Point, 3>> tri_;
    std::vector<std::array<std::uint32_t, 3>> corners_;
    std::vector<std::uint32_t> star_begin_, star_;
    std::vector<Point> centroid_;
    std::vector<std::uint32_t> order_;
    std::vector<Node> nodes_;
};

/// Barycentric coordinates of q (on or near the triangle) in t; (1, 0, 0) for a degenerate one.
std::array<double, 3> barycentric(const std::array<Point, 3>& t, const Point& q) {
    const Vector3 e0 = t[1] - t[0], e1 = t[2] - t[0], d = q - t[0];
    const double d00 = e0.dot(e0), d01 = e0.dot(e1), d11 = e1.dot(e1);
    const double d20 = d.dot(e0), d21 = d.dot(e1);
    const double den = d00 * d11 - d01 * d01;
    if (!(den > 1e-300 * (d00 * d11 + 1e-300)) || !std::isfinite(den)) return {1, 0, 0};
    double v = (d11 * d20 - d01 * d21) / den, w = (d00 * d21 - d01 * d20) / den;
    v = std::min(1.0, std::max(0.0, v));
    w = std::min(1.0 - v, std::max(0.0, w));
    return {1 - v - w, v, w};
}

// ---- the attributes that follow the surface ---------------------------------------------------

/// The input's attribute values that new and moved vertices take from the triangle they lie
/// on: per-vertex uv and colour, per-corner uv (seam vertices are frozen, so every corner of a
/// vertex that changes takes one value).
struct InputAttributes {
    std::vector<std::array<Index, 3>> corners;   ///< per input triangle: its vertices
    std::vector<std::array<Index, 3>> corner_h;  ///< per input triangle: its corner halfedges
    std::vector<TexCoord> vuv, huv;
    std::vector<Color> color;
    bool has_vuv = false, has_huv = false, has_color = false;
};

// ---- options and the plan -------------------------------------------------------------------

/// The exponent e such that 2^-e brings the largest coordinate magnitude near 1 when it is
/// far from it (0 otherwise). The mesh is worked on times 2^-e and scaled back by ldexp (1 /
/// 2^-e itself may not be a double: 2^1024).
int working_exponent(const HalfedgeMesh& mesh) {
    double m = 0;
    for (Vertex v : mesh.vertices()) {
        const Point& p = mesh.position(v);
        if (!p.allFinite())
            throw InvalidArgument("remesh: vertex " + std::to_string(v.idx()) +
                                  " has a non-finite position");
        m = std::max(m, p.cwiseAbs().maxCoeff());
    }
    if (!(m > 0x1p100 || (m > 0 && m < 0x1p-100))) return 0;
    int exponent = 0;
    std::frexp(m, &exponent);
    return exponent;
}

void check_options(const RemeshOptions& o) {
    if (o.length && !(std::isfinite(*o.length) && *o.length > 0))
        throw InvalidArgument("remesh: length must be a positive finite number, got " +
                              text_of(*o.length));
    if (!(std::isfinite(o.relative) && o.relative > 0 && o.relative <= 1e6))
        throw InvalidArgument("remesh: relative must be a number in (0, 1e6], got " +
                              text_of(o.relative));
    if (!(o.adaptive >= 0 && o.adaptive <= 0.5))
        throw InvalidArgument("remesh: adaptive must be from 0 to 0.5, got " + text_of(o.adaptive));
    if (o.iterations < 1 || o.iterations > kMaxRemeshIterations)
        throw InvalidArgument("remesh: iterations must be from 1 to " +
                              std::to_string(kMaxRemeshIterations) + ", got " +
                              std::to_string(o.iterations));
    if (o.features != FeatureSource::Stored && o.features != FeatureSource::None &&
        o.features != FeatureSource::Auto)
        throw InvalidArgument("remesh: features must be " +
                              enum_ids(EnumTableView(kFeatureSources)));
    if (o.features == FeatureSource::Auto &&
        !(std::isfinite(o.feature_angle) && o.feature_angle > 0 && o.feature_angle <= 180))
        throw InvalidArgument("remesh: feature_angle must be in (0, 180] degrees, got " +
                              number_text(o.feature_angle));
}

/// Detects the features first where the options ask (Auto).
void detect_if_asked(HalfedgeMesh& mesh, const RemeshOptions& o) {
    if (o.features != FeatureSource::Auto) return;
    FeatureDetectionOptions d;
    d.angle_deg = o.feature_angle;
    detect_features(mesh, d);
}

/// The weight of each vertex storage index: the region's, 1 without one; 0 for deleted
/// vertices and for the vertices of a texture seam (frozen).
std::vector<float> initial_weights(const HalfedgeMesh& mesh, const RemeshOptions& o) {
    std::vector<float> w(mesh.vertices_size(), 0.0f);
    if (o.region && o.region->size() != w.size())
        throw InvalidArgument("remesh: the region has " + std::to_string(o.region->size()) +
                              " weights for " + std::to_string(w.size()) + " vertices");
    for (Vertex v : mesh.vertices()) {
        const float x = o.region ? (*o.region)[v.idx()] : 1.0f;
        if (!(x >= 0.0f && x <= 1.0f))
            throw InvalidArgument("remesh: region weight of vertex " + std::to_string(v.idx()) +
                                  " is not in [0, 1]");
        w[v.idx()] = x;
    }
    const auto huv = mesh.get_halfedge_property<TexCoord>("h:texcoord");
    if (!huv) return w;
    for (Vertex v : mesh.vertices())
        if (on_texture_seam(mesh, huv, v)) w[v.idx()] = 0.0f;
    return w;
}

bool face_free(const HalfedgeMesh& mesh, const std::vector<float>& w, Face f) {
    for (Vertex v : mesh.vertices_of(f))
        if (!(w[v.idx()] > 0.0f)) return false;
    return true;
}

/// What the plan measures: the target length and the face count, in working (scaled) units.
struct Plan {
    RemeshReport report;
    double scale = 1.0;  ///< 2^-exponent
    int exponent = 0;
    double unscale(double x) const { return std::ldexp(x, exponent); }
    double unscale_area(double x) const { return std::ldexp(x, 2 * exponent); }
    /// Adaptive sizing: each vertex's target length as a fraction of L (empty: 1 everywhere).
    std::vector<float> size;
};

/// Dunyach et al. 2013: the longest edge whose chord stays within `error` of a surface of
/// curvature k is sqrt(6 error / k - 3 error^2); per vertex, as a fraction of `length`, from
/// the larger absolute principal curvature, in [0.1, 1] (1 where the curvature is unknown).
std::vector<float> adaptive_sizes(const HalfedgeMesh& mesh, double length, double error) {
    const VertexCurvatures k = compute_curvatures(mesh);
    std::vector<float> size(mesh.vertices_size(), 1.0f);
    for (Vertex v : mesh.vertices()) {
        const std::size_t i = v.idx();
        if (!k.valid[i]) continue;
        // With e = error / length and kl = k length: s / length = sqrt(6 e / kl - 3 e^2).
        const double kl = std::max(std::abs(k.k1[i]), std::abs(k.k2[i])) * length;
        if (!(std::isfinite(kl) && kl > 0)) continue;
        const double e = error;
        const double f2 = 6 * e / kl - 3 * e * e;
        const double f = f2 > 0 ? std::sqrt(f2) : 0.0;
        size[i] = float(std::min(1.0, std::max(0.1, f)));
    }
    return size;
}

Plan make_plan(const HalfedgeMesh& mesh, const RemeshOptions& o, const std::vector<float>& w) {
    check_options(o);
    if (mesh.n_faces() == 0) throw InvalidArgument("remesh: the mesh has no faces to remesh");
    Plan plan;
    plan.exponent = working_exponent(mesh);
    plan.scale = std::ldexp(1.0, -plan.exponent);
    RemeshReport& r = plan.report;
    r.input_faces = mesh.n_faces();
    double len_sum = 0;
    std::size_t n_len = 0;
    for (Edge e : mesh.edges()) {
        const Halfedge h = HalfedgeMesh::halfedge(e, 0);
        const Face f0 = mesh.face(h), f1 = mesh.face(HalfedgeMesh::twin(h));
        if ((f0.is_valid() && face_free(mesh, w, f0)) ||
            (f1.is_valid() && face_free(mesh, w, f1))) {
            len_sum +=
                plan.scale *
                (mesh.position(mesh.to_vertex(h)) - mesh.position(mesh.from_vertex(h))).norm();
            ++n_len;
        }
    }
    std::size_t kept_faces = 0;
    for (Face f : mesh.faces()) {
        if (!face_free(mesh, w, f)) {
            ++kept_faces;
            continue;
        }
        const auto c = mesh.face_vertices(f);
        const Point a = plan.scale * mesh.position(c[0]), b = plan.scale * mesh.position(c[1]),
                    d = plan.scale * mesh.position(c[2]);
        r.remeshed_area += 0.5 * (b - a).cross(d - a).norm();
    }
    r.input_mean_edge = n_len ? len_sum / double(n_len) : 0.0;
    const double length = o.length ? *o.length * plan.scale : o.relative * r.input_mean_edge;
    if (o.adaptive > 0 && n_len > 0)
        plan.size = adaptive_sizes(mesh, plan.unscale(length), o.adaptive);
    // The ideal triangle's area at each face: (L times the mean of its corners' sizes)^2.
    double faces = 0;
    for (Face f : mesh.faces()) {
        if (!face_free(mesh, w, f)) continue;
        const auto c = mesh.face_vertices(f);
        const Point a = plan.scale * mesh.position(c[0]), b = plan.scale * mesh.position(c[1]),
                    d = plan.scale * mesh.position(c[2]);
        double s = 1;
        if (!plan.size.empty())
            s = (plan.size[c[0].idx()] + plan.size[c[1].idx()] + plan.size[c[2].idx()]) / 3.0;
        faces += 0.5 * (b - a).cross(d - a).norm() / (s * s);
    }
    if (n_len == 0)
        throw InvalidArgument(
            "remesh: the region has no face whose three corners are selected (weight above 0): "
            "nothing to remesh");
    if (!(length > 0))
        throw InvalidArgument(
            "remesh: the mean edge length is 0 (every edge has length 0): "
            "give --length");
    r.target_length = length;
    faces /= kIdealTriangleArea * length * length;
    const double predicted = (std::isfinite(faces) ? faces : 1e300) + double(kept_faces);
    r.predicted_faces = predicted < 1e18 ? std::size_t(predicted) : std::size_t(1e18);
    const double bytes =
        predicted * kBytesPerOutputFace + double(mesh.n_faces()) * kBytesPerInputFace;
    const AvailableMemory avail = available_memory();
    r.available_bytes = avail.bytes;
    r.predicted_bytes = bytes < 1e18 ? std::size_t(bytes) : std::size_t(1e18);
    if (predicted > 1.0e9 || bytes > double(avail.bytes))
        throw InvalidArgument(
            "remesh: length " + text_of(plan.unscale(length)) + " would make about " +
            text_of(predicted) + " faces (" + text_of(plan.unscale_area(r.remeshed_area)) +
            " of area over " + text_of(plan.unscale_area(kIdealTriangleArea * length * length)) +
            " per ideal triangle), needing about " + format_memory_size(bytes) + "; " +
            avail.limit + " leaves " + format_memory_size(double(avail.bytes)) +
            ": give a larger --length or --relative");
    return plan;
}

// ---- the remesher ---------------------------------------------------------------------------

class Remesher {
public:
    Remesher(HalfedgeMesh& mesh, double length, std::vector<float> weights,
             std::vector<float> sizes, bool features, RemeshReport& report)
        : m_(mesh),
          cm_(mesh),
          r_(report),
          w_(std::move(weights)),
          size_(std::move(sizes)),
          use_features_(features) {
        if (size_.empty()) size_.assign(m_.vertices_size(), 1.0f);
        // Botsch and Kobbelt's thresholds for a working length of kWorkingLength L: with L
        // itself the output's edges come out about 4 % short on average (collapses that would
        // make an edge longer than 4/3 L are refused, so the vertices end up too many), and the
        // band [0.8 L, 4/3 L] less full.
        const double work = kWorkingLength * length;
        lo2_ = (0.8 * work) * (0.8 * work);
        hi2_ = (4.0 / 3.0 * work) * (4.0 / 3.0 * work);
        hint_.assign(m_.vertices_size(), kNone);
        dirty_.assign(m_.vertices_size(), 0);
    }

    void set_up_surface() {
        std::vector<std::array<Point, 3>> tris;
        std::vector<std::array<std::uint32_t, 3>> corners;
        tris.reserve(m_.n_faces());
        corners.reserve(m_.n_faces());
        for (Face f : m_.faces()) {
            const auto c = m_.face_vertices(f);
            tris.push_back({cm_.position(c[0]), cm_.position(c[1]), cm_.position(c[2])});
            corners.push_back({c[0].idx(), c[1].idx(), c[2].idx()});
            for (Vertex v : c)
                if (hint_[v.idx()] == kNone) hint_[v.idx()] = std::uint32_t(tris.size() - 1);
        }
        tree_.build(std::move(tris));
        tree_.set_corners(std::move(corners), m_.vertices_size());
        mark_corners();
        set_up_features();
        record_attributes();
    }

    /// Corners of the input's boundary at the scale of L: where the directions to the points
    /// half a working length back and ahead along the boundary turn by more than 60 degrees
    /// (a square's corner; not the zigzag of a scan's ragged hole, finer than L). They stay.
    void mark_corners() {
        corner_.assign(m_.vertices_size(), 0);
        const double reach = 0.5 * std::sqrt(hi2_) * 0.75;
        std::vector<std::uint8_t> seen(m_.halfedges_size(), 0);
        std::vector<Vertex> loop;
        for (Halfedge start : m_.halfedges()) {
            if (!m_.is_boundary(start) || seen[start.idx()]) continue;
            loop.clear();
            Halfedge h = start;
            do {
                seen[h.idx()] = 1;
                loop.push_back(m_.from_vertex(h));
                h = m_.next(h);
            } while (h != start && loop.size() <= m_.halfedges_size());
            mark_loop_corners(loop, reach);
        }
    }
    void mark_loop_corners(const std::vector<Vertex>& loop, double reach) {
        const std::size_t n = loop.size();
        // The point `reach` along the loop from vertex i, backwards (dir -1) or forwards.
        const auto along = [&](std::size_t i, int dir) {
            std::size_t j = i;
            double left = reach;
            for (std::size_t k = 0; k + 1 < n; ++k) {
                const std::size_t next = (j + n + std::size_t(dir)) % n;
                const Point& a = cm_.position(loop[j]);
                const Point& b = cm_.position(loop[next]);
                const double l = (b - a).norm();
                if (l >= left) return Point(a + (left / l) * (b - a));
                left -= l;
                j = next;
            }
            return cm_.position(loop[j]);
        };
        // The cosine of the turn at each vertex; a corner turns by more than 60 degrees and
        // more than every other vertex within `reach` along the loop (the sharpest point of
        // a bend, not its neighbours that see it within their reach).
        std::vector<double> turn(n);
        for (std::size_t i = 0; i < n; ++i) {
            const Point& p = cm_.position(loop[i]);
            const Vector3 in = p - along(i, -1), out = along(i, 1) - p;
            const double l = in.norm() * out.norm();
            turn[i] = l > 0 ? in.dot(out) / l : 1.0;
        }
        for (std::size_t i = 0; i < n; ++i) {
            if (!(turn[i] < 0.5)) continue;
            bool sharpest = true;
            for (int dir : {-1, 1}) {
                double gone = 0;
                for (std::size_t j = i, k = 0; k + 1 < n && sharpest; ++k) {
                    const std::size_t next = (j + n + std::size_t(dir)) % n;
                    gone += (cm_.position(loop[next]) - cm_.position(loop[j])).norm();
                    if (gone > reach) break;
                    // Ties go to the first vertex of the loop.
                    if (turn[next] < turn[i] || (turn[next] == turn[i] && next < i))
                        sharpest = false;
                    j = next;
                }
            }
            if (sharpest) corner_[loop[i].idx()] = 1;
        }
    }

    void iterate(bool project) {
        split_long_edges();
        collapse_short_edges();
        // Two sweeps: the first one's flips make more flips worth it.
        equalize_valences();
        equalize_valences();
        relax(project);
    }
    /// Renumbers the mesh into a spatial order (dropping deleted elements), so that ring walks
    /// stay in the cache; the per-vertex arrays follow.
    void compact() {
        const IndexRemap map = renumber_spatially(m_);
        const auto remap = [&](auto& a) {
            std::remove_reference_t<decltype(a)> out(m_.vertices_size());
            for (std::size_t i = 0; i < map.vertices.size() && i < a.size(); ++i)
                if (map.vertices[i] != kInvalidIndex) out[map.vertices[i]] = a[i];
            a = std::move(out);
        };
        remap(w_);
        remap(hint_);
        remap(dirty_);
        remap(corner_);
        remap(size_);
        remap(feat_);
        remap(seg_);
        if (sharp_) sharp_ = m_.get_edge_property<float>(kSharpnessProperty);
    }
    void finish() {
        improve_small_angles();
        remove_small_angles();
        improve_small_angles();
        interpolate_attributes();
        m_.garbage_collection();
    }

private:
    static constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

    bool is_free(Vertex v) const { return w_[v.idx()] > 0.0f; }
    /// Every face at the edge is free (all corners of positive weight).
    bool edge_free(Halfedge h) const {
        if (!is_free(m_.from_vertex(h)) || !is_free(m_.to_vertex(h))) return false;
        const Halfedge o = HalfedgeMesh::twin(h);
        if (!m_.is_boundary(h) && !is_free(m_.to_vertex(m_.next(h)))) return false;
        if (!m_.is_boundary(o) && !is_free(m_.to_vertex(m_.next(o)))) return false;
        return true;
    }
    double length2(Halfedge h) const {
        return (cm_.position(m_.to_vertex(h)) - cm_.position(m_.from_vertex(h))).squaredNorm();
    }
    void grow_vertex_arrays(Vertex from, Vertex to) {
        size_.push_back(0.5f * (size_[from.idx()] + size_[to.idx()]));
        w_.push_back(w_[from.idx()]);
        hint_.push_back(hint_[from.idx()]);
        dirty_.push_back(1);
        corner_.push_back(0);
        feat_.push_back(0);
        seg_.push_back(kNone);
    }
    /// (Mean size of the two ends)^2: the thresholds' factor for an edge between them.
    double size2(Vertex a, Vertex b) const {
        const double f = 0.5 * (double(size_[a.idx()]) + double(size_[b.idx()]));
        return f * f;
    }
    double size2(Halfedge h) const { return size2(m_.from_vertex(h), m_.to_vertex(h)); }

    // (1) Splits, repeated until no edge is longer than 4/3 L.
    void split_long_edges() {
        for (int pass = 0; pass < 64; ++pass) {
            std::size_t splits = 0;
            const std::size_t n = m_.edges_size();
            for (std::size_t i = 0; i < n; ++i) {
                const Edge e{Index(i)};
                if (m_.is_deleted(e)) continue;
                const Halfedge h = HalfedgeMesh::halfedge(e, 0);
                if (length2(h) <= hi2_ * size2(h) || !edge_free(h)) continue;
                const Vertex a = m_.from_vertex(h), b = m_.to_vertex(h);
                const Point mid = 0.5 * (cm_.position(a) + cm_.position(b));
                const Vertex c = m_.is_boundary(h) ? Vertex() : m_.to_vertex(m_.next(h));
                const Halfedge o = HalfedgeMesh::twin(h);
                const Vertex d = m_.is_boundary(o) ? Vertex() : m_.to_vertex(m_.next(o));
                // A pillow (two faces on the same three corners) would get its new vertex joined
                // twice to the third corner.
                if (c.is_valid() && c == d) continue;
                const bool sharp = is_sharp(e);
                const Vertex nv = m_.split(e, mid);
                grow_vertex_arrays(a, b);
                if (sharp) put_on_curve(nv, a, b);
                for (Vertex x : {a, b, c, d})
                    if (x.is_valid()) dirty_[x.idx()] = 1;
                ++splits;
            }
            r_.splits += splits;
            if (splits == 0) break;
        }
    }

    // A boundary vertex v0 = from_vertex(h) may go only along a boundary edge h, never when it
    // is a corner of the input's boundary (mark_corners()), and only when it is at most 0.3 L
    // from the new boundary edge (from its other boundary neighbour to to_vertex(h)).
    bool boundary_vertex_removable(Halfedge h) const {
        if (corner_[m_.from_vertex(h).idx()]) return false;
        if (!m_.is_boundary(HalfedgeMesh::edge(h))) return false;
        // The boundary halfedge at v0 that is not h's edge: its other neighbour on the loop.
        const Halfedge b = m_.is_boundary(h) ? m_.prev(h) : HalfedgeMesh::twin(h);
        const Halfedge other = m_.is_boundary(h) ? b : m_.next(b);
        const Vertex v0 = m_.from_vertex(h);
        const Vertex n = m_.is_boundary(h) ? m_.from_vertex(other) : m_.to_vertex(other);
        if (n == v0 || n == m_.to_vertex(h)) return false;
        const Point& a = cm_.position(n);
        const Point& c = cm_.position(m_.to_vertex(h));
        const Point& p = cm_.position(v0);
        const Vector3 ac = c - a;
        const double l2 = ac.squaredNorm();
        const double t = l2 > 0 ? std::min(1.0, std::max(0.0, (p - a).dot(ac) / l2)) : 0.0;
        // hi2_ is (4/3 L)^2 of the working length: 0.3 L is 0.225 of 4/3 L.
        return (a + t * ac - p).squaredNorm() <= 0.225 * 0.225 * hi2_;
    }

    // Whether collapsing h (from_vertex into to_vertex) is allowed: the removed vertex is free
    // with all its faces, a boundary vertex moves only along the boundary into a boundary
    // vertex, no new edge is longer than 4/3 L, the link condition holds and no face folds.
    bool may_collapse(Halfedge h) const {
        const Vertex v0 = m_.from_vertex(h), v1 = m_.to_vertex(h);
        const bool b0 = m_.is_boundary(v0);
        if (b0 && !boundary_vertex_removable(h)) return false;
        if (!feature_collapse_ok(h)) return false;
        const Point& p1 = cm_.position(v1);
        const Point& p0 = cm_.position(v0);
        for (Halfedge g : m_.halfedges_around(v0)) {
            const Vertex n = m_.to_vertex(g);
            if (!is_free(n)) return false;
            if (n != v1 && (cm_.position(n) - p1).squaredNorm() > hi2_ * size2(n, v1)) return false;
        }
        if (!m_.is_collapse_ok(h)) return false;
        // No fold: every face of v0 that stays keeps its orientation and some area.
        for (Halfedge g : m_.halfedges_around(v0)) {
            if (m_.is_boundary(g)) continue;
            const Vertex a = m_.to_vertex(g), b = m_.to_vertex(m_.next(g));
            if (a == v1 || b == v1) continue;
            const Point& pa = cm_.position(a);
            const Point& pb = cm_.position(b);
            const Vector3 before = (pa - p0).cross(pb - p0);
            const Vector3 after = (pa - p1).cross(pb - p1);
            if (!(before.dot(after) > 0.2 * before.norm() * after.norm())) return false;
        }
        return within_collapse_error(h);
    }
    // The removed vertex is at most 0.1 L' from the faces that replace its ring, so that a
    // collapse does not cut across a crease (the surface keeps its shape to a tenth of L').
    bool within_collapse_error(Halfedge h) const {
        const Vertex v0 = m_.from_vertex(h), v1 = m_.to_vertex(h);
        const Point& p0 = cm_.position(v0);
        const Point& p1 = cm_.position(v1);
        double best = std::numeric_limits<double>::infinity();
        for (Halfedge g : m_.halfedges_around(v0)) {
            if (m_.is_boundary(g)) continue;
            const Vertex a = m_.to_vertex(g), b = m_.to_vertex(m_.next(g));
            if (a == v1 || b == v1) continue;
            const Point q = closest_point_on_triangle(p0, cm_.position(a), cm_.position(b), p1);
            best = std::min(best, (q - p0).squaredNorm());
        }
        // hi2_ is (4/3 L')^2: (0.1 L')^2 is 0.075^2 of it.
        return !std::isfinite(best) || best <= 0.075 * 0.075 * hi2_;
    }

    // (2) Collapses of the edges shorter than 4/5 L.
    void collapse_short_edges() {
        const std::size_t n = m_.edges_size();
        for (std::size_t i = 0; i < n; ++i) {
            const Edge e{Index(i)};
            if (m_.is_deleted(e)) continue;
            Halfedge h = HalfedgeMesh::halfedge(e, 0);
            if (length2(h) >= lo2_ * size2(h) || !is_free(m_.from_vertex(h)) ||
                !is_free(m_.to_vertex(h)))
                continue;
            // Remove the end of lower valence first (it is the one with less to spread).
            if (m_.valence(m_.to_vertex(h)) < m_.valence(m_.from_vertex(h)))
                h = HalfedgeMesh::twin(h);
            Halfedge pick;
            if (may_collapse(h))
                pick = h;
            else if (may_collapse(HalfedgeMesh::twin(h)))
                pick = HalfedgeMesh::twin(h);
            if (!pick.is_valid()) continue;
            collapse(pick);
        }
    }
    void collapse(Halfedge h) {
        const Vertex v1 = m_.to_vertex(h);
        const CollapseSharpness keep = merged_sharpness(h);
        // The faces' surviving halfedges take over a neighbour face's corner at v1 (see
        // HalfedgeMesh::remove_loop): keep that corner's uv.
        if (huv_) {
            const Halfedge o = HalfedgeMesh::twin(h);
            Halfedge s0, s1;
            TexCoord uv0 = TexCoord::Zero(), uv1 = TexCoord::Zero();
            if (!m_.is_boundary(h)) {
                s0 = m_.prev(h);
                uv0 = huv_[HalfedgeMesh::twin(m_.next(h))];
            }
            if (!m_.is_boundary(o)) {
                s1 = m_.prev(o);
                uv1 = huv_[HalfedgeMesh::twin(m_.next(o))];
            }
            m_.collapse_unchecked(h);
            if (s0.is_valid() && !m_.is_deleted(s0)) huv_[s0] = uv0;
            if (s1.is_valid() && !m_.is_deleted(s1)) huv_[s1] = uv1;
        } else {
            m_.collapse_unchecked(h);
        }
        restore_sharpness(keep);
        dirty_[v1.idx()] = 1;
        ++r_.collapses;
    }

    /// Whether flipping the edge of h gives two triangles that neither fold over nor
    /// degenerate, on a surface not bent too sharply there.
    bool flip_keeps_shape(Halfedge h) const {
        const Halfedge o = HalfedgeMesh::twin(h);
        const Point& a = cm_.position(m_.from_vertex(h));
        const Point& b = cm_.position(m_.to_vertex(h));
        const Point& c = cm_.position(m_.to_vertex(m_.next(h)));
        const Point& d = cm_.position(m_.to_vertex(m_.next(o)));
        const Vector3 n_abc = (b - a).cross(c - a), n_bad = (a - b).cross(d - b);
        const Vector3 n_dca = (c - d).cross(a - d), n_cdb = (d - c).cross(b - c);
        const double s_old = n_abc.norm() * n_bad.norm();
        // A crease (the two faces bent by more than about 45 degrees) is kept.
        if (!(n_abc.dot(n_bad) > 0.7 * s_old)) return false;
        const Vector3 sum = n_abc + n_bad;
        const double l1 = n_dca.norm(), l2 = n_cdb.norm(), ls = sum.norm();
        return n_dca.dot(sum) > 0.5 * l1 * ls && n_cdb.dot(sum) > 0.5 * l2 * ls &&
               n_dca.dot(n_cdb) > 0.5 * l1 * l2;
    }

    void count_valences() {
        valence_.assign(m_.vertices_size(), 0);
        for (Halfedge h : m_.halfedges()) ++valence_[m_.to_vertex(h).idx()];
    }
    int target_valence(Vertex v) const { return m_.is_boundary(v) ? 4 : 6; }

    // (3) Flips towards valence 6 (4 on the boundary).
    void equalize_valences() {
        count_valences();
        const std::size_t n = m_.edges_size();
        for (std::size_t i = 0; i < n; ++i) {
            const Edge e{Index(i)};
            if (m_.is_deleted(e) || m_.is_boundary(e)) continue;
            const Halfedge h = HalfedgeMesh::halfedge(e, 0);
            if (!edge_free(h) || is_sharp(e)) continue;
            const Vertex a = m_.from_vertex(h), b = m_.to_vertex(h);
            const Vertex c = m_.to_vertex(m_.next(h));
            const Vertex d = m_.to_vertex(m_.next(HalfedgeMesh::twin(h)));
            const int da = valence_[a.idx()] - target_valence(a);
            const int db = valence_[b.idx()] - target_valence(b);
            const int dc = valence_[c.idx()] - target_valence(c);
            const int dd = valence_[d.idx()] - target_valence(d);
            const int before = std::abs(da) + std::abs(db) + std::abs(dc) + std::abs(dd);
            const int after =
                std::abs(da - 1) + std::abs(db - 1) + std::abs(dc + 1) + std::abs(dd + 1);
            if (after >= before || !m_.is_flip_ok(e) || !flip_keeps_shape(h)) continue;
            m_.flip(e);
            --valence_[a.idx()];
            --valence_[b.idx()];
            ++valence_[c.idx()];
            ++valence_[d.idx()];
            for (Vertex x : {a, b, c, d}) dirty_[x.idx()] = 1;
            ++r_.flips;
        }
    }

    // (4) + (5): tangential relaxation of every interior free vertex whose neighbours are all
    // free, then its projection onto the input surface.
    void relax(bool project) {
        const std::size_t nv = m_.vertices_size();
        normals_.assign(nv, Vector3::Zero());
        for (Face f : m_.faces()) {
            const auto c = m_.face_vertices(f);
            const Point &p0 = cm_.position(c[0]), &p1 = cm_.position(c[1]),
                        &p2 = cm_.position(c[2]);
            const Vector3 n = (p1 - p0).cross(p2 - p0);
            for (Vertex v : c) normals_[v.idx()] += n;
        }
        target_.resize(nv);
        moves_.assign(nv, 0);
        const bool parallel = worth_two_threads(nv);
        constexpr std::size_t kPiece = 4096;
        in_pieces(parallel, (nv + kPiece - 1) / kPiece, [&](std::size_t k) {
            const std::size_t end = std::min(nv, (k + 1) * kPiece);
            for (std::size_t i = k * kPiece; i < end; ++i) relax_vertex(Vertex(Index(i)), project);
        });
        std::vector<Point>& positions = m_.positions();
        for (std::size_t i = 0; i < nv; ++i) {
            if (!moves_[i]) continue;
            positions[i] = target_[i];
            dirty_[i] = 1;
        }
    }
    void relax_vertex(Vertex v, bool project) {
        if (m_.is_deleted(v) || m_.is_isolated(v) || !is_free(v) || m_.is_boundary(v)) return;
        if (feat_[v.idx()] != kSmooth) {
            relax_along_curve(v);
            return;
        }
        const Point& p = cm_.position(v);
        Point sum = Point::Zero();
        int k = 0;
        for (Halfedge g : m_.halfedges_around(v)) {
            const Vertex n = m_.to_vertex(g);
            if (!is_free(n)) return;
            sum += cm_.position(n);
            ++k;
        }
        const double nn = normals_[v.idx()].squaredNorm();
        if (k == 0 || !(nn > 0)) return;
        const Vector3 n = normals_[v.idx()] / std::sqrt(nn);
        Vector3 u = sum / double(k) - p;
        u -= n.dot(u) * n;
        Point q = p + double(w_[v.idx()]) * u;
        if (project) {
            const SurfaceTree::Hit hit = tree_.walk(q, hint_[v.idx()]);
            hint_[v.idx()] = hit.face;
            q = hit.point;
        }
        if (!q.allFinite()) return;
        target_[v.idx()] = q;
        moves_[v.idx()] = 1;
    }

    // The last pass: an edge facing an angle under 25 degrees is flipped when that makes the
    // smallest angle of its two triangles larger (and nothing folds).
    static double min_angle_cos(const Point& a, const Point& b, const Point& c) {
        // The largest cosine of the three angles (the smallest angle).
        const auto cosine = [](const Point& x, const Point& y, const Point& z) {
            const Vector3 u = y - x, w = z - x;
            const double l = u.norm() * w.norm();
            return l > 0 ? u.dot(w) / l : 1.0;
        };
        return std::max({cosine(a, b, c), cosine(b, c, a), cosine(c, a, b)});
    }
    // The smallest-angle cosine over the faces around v0 as they are (before), and as they
    // would be with v0 at p1 without the faces that contain v1 (after); false when a face
    // would fold or an edge grow past 1.6 L.
    bool collapse_angles(Halfedge h, double& before, double& after) const {
        const Vertex v0 = m_.from_vertex(h), v1 = m_.to_vertex(h);
        const Point& p0 = cm_.position(v0);
        const Point& p1 = cm_.position(v1);
        before = -1;
        after = -1;
        for (Halfedge g : m_.halfedges_around(v0)) {
            if (!is_free(m_.to_vertex(g))) return false;
            if (m_.is_boundary(g)) continue;
            const Vertex a = m_.to_vertex(g), b = m_.to_vertex(m_.next(g));
            const Point& pa = cm_.position(a);
            const Point& pb = cm_.position(b);
            before = std::max(before, min_angle_cos(p0, pa, pb));
            if (a == v1 || b == v1) continue;
            if ((pa - p1).squaredNorm() > 1.44 * hi2_ || (pb - p1).squaredNorm() > 1.44 * hi2_)
                return false;
            const Vector3 n0 = (pa - p0).cross(pb - p0), n1 = (pa - p1).cross(pb - p1);
            if (!(n0.dot(n1) > 0.5 * n0.norm() * n1.norm())) return false;
            after = std::max(after, min_angle_cos(p1, pa, pb));
        }
        return true;
    }
    // Faces with an angle under 25 degrees: their shortest edge is collapsed (either way the
    // rules allow, the new edges up to 1.6 L) where that makes the smallest angle around it
    // larger.
    void remove_small_angles() {
        const double small_cos = std::cos(25.0 * 3.14159265358979323846 / 180.0);
        for (std::size_t i = 0, n = m_.faces_size(); i < n; ++i) {
            const Face f{Index(i)};
            if (m_.is_deleted(f)) continue;
            Halfedge shortest = m_.halfedge(f);
            double worst = -1, best_len = std::numeric_limits<double>::infinity();
            for (Halfedge h : m_.halfedges_of(f)) {
                const Point& a = cm_.position(m_.from_vertex(h));
                const Point& b = cm_.position(m_.to_vertex(h));
                const Point& c = cm_.position(m_.to_vertex(m_.next(h)));
                worst = std::max(worst, min_angle_cos(c, a, b));
                if (length2(h) < best_len) {
                    best_len = length2(h);
                    shortest = h;
                }
            }
            if (worst < small_cos) continue;
            double best_after = 2;
            Halfedge pick;
            for (Halfedge h : {shortest, HalfedgeMesh::twin(shortest)}) {
                const Vertex v0 = m_.from_vertex(h);
                if (!is_free(v0) || !is_free(m_.to_vertex(h))) continue;
                if (m_.is_boundary(v0) && !boundary_vertex_removable(h)) continue;
                if (!feature_collapse_ok(h)) continue;
                double before = 0, after = 0;
                if (!collapse_angles(h, before, after) || !(after < before - 1e-9) ||
                    !(after < best_after) || !m_.is_collapse_ok(h))
                    continue;
                best_after = after;
                pick = h;
            }
            if (pick.is_valid()) collapse(pick);
        }
    }
    void improve_small_angles() {
        const double small_cos = std::cos(25.0 * 3.14159265358979323846 / 180.0);
        for (int pass = 0; pass < 3; ++pass) {
            std::size_t flips = 0;
            for (std::size_t i = 0, n = m_.edges_size(); i < n; ++i) {
                const Edge e{Index(i)};
                if (m_.is_deleted(e) || m_.is_boundary(e)) continue;
                const Halfedge h = HalfedgeMesh::halfedge(e, 0);
                if (!edge_free(h) || is_sharp(e)) continue;
                const Vertex va = m_.from_vertex(h), vb = m_.to_vertex(h);
                const Vertex vc = m_.to_vertex(m_.next(h));
                const Vertex vd = m_.to_vertex(m_.next(HalfedgeMesh::twin(h)));
                const Point &a = cm_.position(va), &b = cm_.position(vb), &c = cm_.position(vc),
                            &d = cm_.position(vd);
                const double before = std::max(min_angle_cos(a, b, c), min_angle_cos(b, a, d));
                if (before < small_cos) continue;
                const double after = std::max(min_angle_cos(d, c, a), min_angle_cos(c, d, b));
                if (!(after < before - 1e-9) || !m_.is_flip_ok(e) || !flip_keeps_shape(h)) continue;
                m_.flip(e);
                for (Vertex x : {va, vb, vc, vd}) dirty_[x.idx()] = 1;
                ++flips;
            }
            r_.angle_flips += flips;
            if (flips == 0) break;
        }
    }

    // ---- features: sharp edges split and collapse only along their curves -------------
    /// A feature vertex slides along its curve (a crease: two sharp edges) or stays (a tagged
    /// corner, the end of a curve, a meeting of three or more, a feature on the boundary).
    static constexpr std::uint8_t kSmooth = 0, kCrease = 1, kFixed = 2;

    bool is_sharp(Edge e) const { return sharp_ && sharp_[e] > 0.0f; }

    /// Classifies the vertices and records the input's sharp edges (the curves new and moved
    /// feature vertices are projected onto).
    void set_up_features() {
        feat_.assign(m_.vertices_size(), kSmooth);
        seg_.assign(m_.vertices_size(), kNone);
        if (use_features_) sharp_ = m_.get_edge_property<float>(kSharpnessProperty);
        if (!sharp_) return;
        const auto tag = m_.get_vertex_property<std::uint8_t>(kCornerProperty);
        std::vector<int> count(m_.vertices_size(), 0);
        curve_star_begin_.assign(m_.vertices_size() + 1, 0);
        for (Edge e : m_.edges()) {
            if (!is_sharp(e)) continue;
            const Vertex a = m_.vertex(e, 0), b = m_.vertex(e, 1);
            for (Vertex x : {a, b}) {
                ++count[x.idx()];
                ++curve_star_begin_[x.idx() + 1];
                seg_[x.idx()] = std::uint32_t(curve_.size());
            }
            curve_.push_back({cm_.position(a), cm_.position(b), a.idx(), b.idx()});
        }
        for (std::size_t i = 0; i + 1 < curve_star_begin_.size(); ++i)
            curve_star_begin_[i + 1] += curve_star_begin_[i];
        curve_star_.resize(curve_star_begin_.back());
        std::vector<std::uint32_t> fill(curve_star_begin_.begin(), curve_star_begin_.end() - 1);
        for (std::uint32_t i = 0; i < curve_.size(); ++i)
            for (std::uint32_t x : {curve_[i].va, curve_[i].vb}) curve_star_[fill[x]++] = i;
        for (Vertex v : m_.vertices()) {
            const int c = count[v.idx()];
            const bool tagged = tag && tag[v] != 0;
            if (tagged || (c > 0 && (c != 2 || m_.is_boundary(v))))
                feat_[v.idx()] = kFixed;
            else if (c == 2)
                feat_[v.idx()] = kCrease;
            if (feat_[v.idx()] == kFixed) corner_[v.idx()] = 1;
        }
    }
    /// The closest point to p on input curve segment i, with its parameter t in [0, 1].
    Point closest_on_segment(const Point& p, std::uint32_t i, double& t) const {
        const Vector3 d = curve_[i].b - curve_[i].a;
        const double l2 = d.squaredNorm();
        t = l2 > 0 ? std::min(1.0, std::max(0.0, (p - curve_[i].a).dot(d) / l2)) : 0.0;
        return curve_[i].a + t * d;
    }
    /// The closest point to p on the input's sharp edges, walking along them from segment
    /// `seg` (updated); every segment when `seg` is none.
    Point project_to_curve(const Point& p, std::uint32_t& seg) const {
        double t = 0;
        if (seg >= curve_.size()) {
            double best = std::numeric_limits<double>::infinity();
            Point q = p;
            for (std::uint32_t i = 0; i < curve_.size(); ++i) {
                const Point c = closest_on_segment(p, i, t);
                if ((c - p).squaredNorm() < best) {
                    best = (c - p).squaredNorm();
                    q = c;
                    seg = i;
                }
            }
            return q;
        }
        Point q = closest_on_segment(p, seg, t);
        double d2 = (q - p).squaredNorm();
        for (std::size_t step = 0; step < curve_.size() && (t <= 0 || t >= 1); ++step) {
            const std::uint32_t w = t <= 0 ? curve_[seg].va : curve_[seg].vb;
            std::uint32_t next = seg;
            double next_t = t;
            for (std::uint32_t k = curve_star_begin_[w]; k < curve_star_begin_[w + 1]; ++k) {
                double tk = 0;
                const Point c = closest_on_segment(p, curve_star_[k], tk);
                if ((c - p).squaredNorm() < d2) {
                    d2 = (c - p).squaredNorm();
                    q = c;
                    next = curve_star_[k];
                    next_t = tk;
                }
            }
            if (next == seg) break;
            seg = next;
            t = next_t;
        }
        return q;
    }
    /// A vertex new on a sharp edge between a and b: a crease vertex on the input's curve.
    void put_on_curve(Vertex v, Vertex a, Vertex b) {
        feat_[v.idx()] = kCrease;
        std::uint32_t seg = seg_[a.idx()] < curve_.size() ? seg_[a.idx()] : seg_[b.idx()];
        m_.position(v) = project_to_curve(cm_.position(v), seg);
        seg_[v.idx()] = seg;
    }
    /// The two vertices joined to v by sharp edges; false unless there are exactly two.
    bool curve_neighbours(Vertex v, Vertex& a, Vertex& b) const {
        int k = 0;
        for (Halfedge g : m_.halfedges_around(v)) {
            if (!is_sharp(HalfedgeMesh::edge(g))) continue;
            if (k == 0) a = m_.to_vertex(g);
            if (k == 1) b = m_.to_vertex(g);
            ++k;
        }
        return k == 2;
    }
    /// Tangential relaxation of a crease vertex: towards the midpoint of its two curve
    /// neighbours, back onto the input's curve. Fixed vertices stay.
    void relax_along_curve(Vertex v) {
        Vertex a, b;
        if (feat_[v.idx()] != kCrease || !curve_neighbours(v, a, b)) return;
        for (Halfedge g : m_.halfedges_around(v))  // a region's border stays (see relax())
            if (!is_free(m_.to_vertex(g))) return;
        const Point& p = cm_.position(v);
        const Point mid = 0.5 * (cm_.position(a) + cm_.position(b));
        std::uint32_t seg = seg_[v.idx()];
        const Point q = project_to_curve(p + double(w_[v.idx()]) * (mid - p), seg);
        if (!q.allFinite()) return;
        seg_[v.idx()] = seg;
        target_[v.idx()] = q;
        moves_[v.idx()] = 1;
    }
    /// Whether the features allow collapsing h: a fixed vertex is never removed, a crease
    /// vertex only along its curve (a sharp edge), into its neighbour there, when it is at
    /// most 0.1 L' from the curve's new edge.
    bool feature_collapse_ok(Halfedge h) const {
        const Vertex v0 = m_.from_vertex(h), v1 = m_.to_vertex(h);
        const std::uint8_t f0 = feat_[v0.idx()];
        if (f0 == kSmooth) return true;
        if (f0 == kFixed || !is_sharp(HalfedgeMesh::edge(h))) return false;
        Vertex a, b;
        if (!curve_neighbours(v0, a, b)) return false;
        const Vertex u = a == v1 ? b : a;
        const Point &p = cm_.position(v0), &pu = cm_.position(u), &p1 = cm_.position(v1);
        const Vector3 d = p1 - pu;
        const double l2 = d.squaredNorm();
        const double t = l2 > 0 ? std::min(1.0, std::max(0.0, (p - pu).dot(d) / l2)) : 0.0;
        return (pu + t * d - p).squaredNorm() <= 0.075 * 0.075 * hi2_;
    }
    /// A collapse merges, in each face at the edge, the removed vertex's edge into the kept
    /// vertex's (HalfedgeMesh::remove_loop keeps the former): the survivor takes the larger
    /// sharpness, so no sharp edge is lost.
    struct CollapseSharpness {
        Edge keep[2];
        float value[2] = {0, 0};
    };
    CollapseSharpness merged_sharpness(Halfedge h) const {
        CollapseSharpness c;
        if (!sharp_) return c;
        const Halfedge o = HalfedgeMesh::twin(h);
        if (!m_.is_boundary(h)) {
            c.keep[0] = HalfedgeMesh::edge(m_.prev(h));
            c.value[0] = std::max(sharp_[c.keep[0]], sharp_[HalfedgeMesh::edge(m_.next(h))]);
        }
        if (!m_.is_boundary(o)) {
            c.keep[1] = HalfedgeMesh::edge(m_.prev(o));
            c.value[1] = std::max(sharp_[c.keep[1]], sharp_[HalfedgeMesh::edge(m_.next(o))]);
        }
        return c;
    }
    void restore_sharpness(const CollapseSharpness& c) {
        for (int k = 0; k < 2; ++k)
            if (c.keep[k].is_valid() && !m_.is_deleted(c.keep[k])) sharp_[c.keep[k]] = c.value[k];
    }

    // ---- attributes ---------------------------------------------------------------------
    void record_attributes() {
        auto vuv = m_.get_vertex_property<TexCoord>("v:texcoord");
        auto color = m_.get_vertex_property<Color>("v:color");
        huv_ = m_.get_halfedge_property<TexCoord>("h:texcoord");
        in_.has_vuv = bool(vuv);
        in_.has_color = bool(color);
        in_.has_huv = bool(huv_);
        if (!in_.has_vuv && !in_.has_color && !in_.has_huv) return;
        for (Face f : m_.faces()) {
            const Halfedge h0 = m_.halfedge(f), h1 = m_.next(h0), h2 = m_.next(h1);
            in_.corners.push_back(
                {m_.to_vertex(h0).idx(), m_.to_vertex(h1).idx(), m_.to_vertex(h2).idx()});
            if (in_.has_huv)
                for (Halfedge h : {h0, h1, h2}) in_.huv.push_back(std::as_const(huv_)[h]);
        }
        if (in_.has_vuv) in_.vuv = std::as_const(vuv).vector();
        if (in_.has_color) in_.color = std::as_const(color).vector();
    }
    void interpolate_attributes() {
        auto vuv = m_.get_vertex_property<TexCoord>("v:texcoord");
        auto color = m_.get_vertex_property<Color>("v:color");
        if (m_.has_vertex_property("v:normal")) compute_vertex_normals(m_);
        if (!in_.has_vuv && !in_.has_color && !in_.has_huv) return;
        for (Vertex v : m_.vertices()) {
            if (!dirty_[v.idx()] || !is_free(v) || m_.is_isolated(v)) continue;
            const SurfaceTree::Hit hit = tree_.walk(cm_.position(v), hint_[v.idx()]);
            const auto bc = barycentric(tree_.triangle(hit.face), hit.point);
            const auto& c = in_.corners[hit.face];
            if (in_.has_vuv && vuv)
                vuv[v] = bc[0] * in_.vuv[c[0]] + bc[1] * in_.vuv[c[1]] + bc[2] * in_.vuv[c[2]];
            if (in_.has_color && color)
                color[v] = (bc[0] * in_.color[c[0]].cast<double>() +
                            bc[1] * in_.color[c[1]].cast<double>() +
                            bc[2] * in_.color[c[2]].cast<double>())
                               .cast<float>();
            if (in_.has_huv && huv_) {
                const std::size_t k = 3 * std::size_t(hit.face);
                const TexCoord uv =
                    bc[0] * in_.huv[k] + bc[1] * in_.huv[k + 1] + bc[2] * in_.huv[k + 2];
                for (Halfedge g : m_.halfedges_around(v)) {
                    const Halfedge in = HalfedgeMesh::twin(g);
                    if (!m_.is_boundary(in)) huv_[in] = uv;
                }
            }
        }
    }

    HalfedgeMesh& m_;
    const HalfedgeMesh& cm_;  ///< the same mesh, read only (no write access, no copy)
    RemeshReport& r_;
    double lo2_ = 0, hi2_ = 0;
    std::vector<float> w_, size_;
    std::vector<std::uint32_t> hint_;
    std::vector<std::uint8_t> dirty_, moves_, corner_;
    std::vector<int> valence_;
    std::vector<Vector3> normals_;
    std::vector<Point> target_;
    SurfaceTree tree_;
    InputAttributes in_;
    HalfedgeProperty<TexCoord> huv_;
    // Features: the class of each vertex, the input curve segment it was last projected
    // onto, the input's sharp edges (with their ends' input indices) and, per input vertex,
    // the segments at it.
    struct CurveSegment {
        Point a, b;
        std::uint32_t va = 0, vb = 0;
    };
    bool use_features_ = true;
    EdgeProperty<float> sharp_;
    std::vector<std::uint8_t> feat_;
    std::vector<std::uint32_t> seg_;
    std::vector<CurveSegment> curve_;
    std::vector<std::uint32_t> curve_star_begin_, curve_star_;
};

/// Every position times 2^exponent (exact, unless it leaves the range of double).
void scale_positions(HalfedgeMesh& mesh, int exponent) {
    if (exponent == 0) return;
    for (Point& p : mesh.positions())
        for (int k = 0; k < 3; ++k) p[k] = std::ldexp(p[k], exponent);
}

void unscale_report(RemeshReport& r, const Plan& plan) {
    r.target_length = plan.unscale(r.target_length);
    r.input_mean_edge = plan.unscale(r.input_mean_edge);
    r.remeshed_area = plan.unscale_area(r.remeshed_area);
}

}  // namespace

RemeshReport remesh_plan(const HalfedgeMesh& mesh, const RemeshOptions& options) {
    check_options(options);
    if (options.features == FeatureSource::Auto) {  // detect on a copy: the plan changes nothing
        HalfedgeMesh detected = mesh;
        detect_if_asked(detected, options);
        Plan plan = make_plan(detected, options, initial_weights(detected, options));
        unscale_report(plan.report, plan);
        return plan.report;
    }
    Plan plan = make_plan(mesh, options, initial_weights(mesh, options));
    unscale_report(plan.report, plan);
    return plan.report;
}

RemeshReport remesh(HalfedgeMesh& mesh, const RemeshOptions& options, Progress& progress) {
    const auto t0 = std::chrono::steady_clock::now();
    check_options(options);
    if (options.features == FeatureSource::Auto) {
        HalfedgeMesh detected = mesh;  // the mesh changes only once the plan holds
        detect_if_asked(detected, options);
        make_plan(detected, options, initial_weights(detected, options));
        mesh = std::move(detected);
    }
    std::vector<float> weights = initial_weights(mesh, options);
    Plan plan = make_plan(mesh, options, weights);
    RemeshReport& r = plan.report;
    if (options.features != FeatureSource::None && has_features(mesh)) {
        const std::vector<float> near = feature_neighbourhood(mesh, 0);
        for (Vertex v : mesh.vertices()) r.feature_vertices += near[v.idx()] > 0;
    }
    for (float x : weights)
        if (!(x > 0.0f)) ++r.locked_vertices;
    r.locked_vertices -= mesh.vertices_size() - mesh.n_vertices();
    scale_positions(mesh, -plan.exponent);
    try {
        Remesher remesher(mesh, r.target_length, std::move(weights), std::move(plan.size),
                          options.features != FeatureSource::None, r);
        progress.report(0, "remeshing: the input surface");
        remesher.set_up_surface();
        remesher.compact();
        for (int i = 0; i < options.iterations; ++i) {
            progress.check_cancelled();
            progress.report(double(i) / options.iterations, "remeshing");
            remesher.iterate(options.project);
            if (i == 0 && options.iterations > 1) remesher.compact();
            r.iterations_done = i + 1;
        }
        remesher.finish();
    } catch (...) {
        if (mesh.has_garbage()) mesh.garbage_collection();
        scale_positions(mesh, plan.exponent);
        throw;
    }
    scale_positions(mesh, plan.exponent);
    unscale_report(r, plan);
    r.output_faces = mesh.n_faces();
    r.output_vertices = mesh.n_vertices();
    r.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    return r;
}

RemeshReport remesh(HalfedgeMesh& mesh, const RemeshOptions& options) {
    NullProgress progress;
    return remesh(mesh, options, progress);
}

}  // namespace trilab
