// Sampled Hausdorff and RMS distance between two meshes (see core/algorithms/mesh_distance.h).
#include "core/algorithms/mesh_distance.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include "core/algorithms/selection.h"
#include "core/errors.h"
#include "core/geometry.h"

namespace trilab {

Point closest_point_on_triangle(const Point& p, const Point& a, const Point& b, const Point& c) {
    // Voronoi-region walk (Ericson, Real-Time Collision Detection, 5.1.5).
    const Vector3 ab = b - a, ac = c - a, ap = p - a;
    const double d1 = ab.dot(ap), d2 = ac.dot(ap);
    if (d1 <= 0 && d2 <= 0) return a;
    const Vector3 bp = p - b;
    const double d3 = ab.dot(bp), d4 = ac.dot(bp);
    if (d3 >= 0 && d4 <= d3) return b;
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) {
        const double den = d1 - d3;
        return den > 0 ? Point(a + (d1 / den) * ab) : a;
    }
    const Vector3 cp = p - c;
    const double d5 = ab.dot(cp), d6 = ac.dot(cp);
    if (d6 >= 0 && d5 <= d6) return c;
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) {
        const double den = d2 - d6;
        return den > 0 ? Point(a + (d2 / den) * ac) : a;
    }
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
        const double den = (d4 - d3) + (d5 - d6);
        return den > 0 ? Point(b + ((d4 - d3) / den) * (c - b)) : b;
    }
    const double sum = va + vb + vc;
    if (!(sum > 0)) {
        // Degenerate triangle: the closest of its three edges.
        Point best = a;
        double bd = (p - a).squaredNorm();
        const Point* v[3] = {&a, &b, &c};
        for (int i = 0; i < 3; ++i) {
            const Point& s = *v[i];
            const Point& t = *v[(i + 1) % 3];
            const Vector3 st = t - s;
            const double l2 = st.squaredNorm();
            const double u = l2 > 0 ? std::min(1.0, std::max(0.0, (p - s).dot(st) / l2)) : 0.0;
            const Point q = s + u * st;
            const double d = (p - q).squaredNorm();
            if (d < bd) {
                bd = d;
                best = q;
            }
        }
        return best;
    }
    const double denom = 1.0 / sum;
    return a + ab * (vb * denom) + ac * (vc * denom);
}

namespace {

struct Box {
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
    Eigen::Vector3d hi = Eigen::Vector3d::Constant(-std::numeric_limits<double>::infinity());
    void extend(const Point& p) {
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
    }
    void extend(const Box& b) {
        lo = lo.cwiseMin(b.lo);
        hi = hi.cwiseMax(b.hi);
    }
    double squared_distance(const Point& p) const {
        const Eigen::Vector3d d = (lo - p).cwiseMax(p - hi).cwiseMax(0.0);
        return d.squaredNorm();
    }
};

/// An AABB tree over a mesh's triangles.
class TriangleTree {
public:
    explicit TriangleTree(const HalfedgeMesh& mesh) {
        for (Face f : mesh.faces()) {
            const auto c = mesh.face_vertices(f);
            tri_.push_back({mesh.position(c[0]), mesh.position(c[1]), mesh.position(c[2])});
        }
        order_.resize(tri_.size());
        for (std::size_t i = 0; i < order_.size(); ++i) order_[i] = std::uint32_t(i);
        centroid_.resize(tri_.size());
        for (std::size_t i = 0; i < tri_.size(); ++i)
            centroid_[i] = (tri_[i][0] + tri_[i][1] + tri_[i][2]) / 3.0;
        nodes_.reserve(2 * tri_.size() / kLeaf + 2);
        if (!tri_.empty()) build(0, std::uint32_t(tri_.size()));
    }

    /// Squared distance from p to the closest triangle.
    double squared_distance(const Point& p) const {
        double best = std::numeric_limits<double>::infinity();
        std::uint32_t stack[128];
        int top = 0;
        stack[top++] = 0;
        while (top > 0) {
            const Node& n = nodes_[stack[--top]];
            if (n.box.squared_distance(p) >= best) continue;
            if (n.count > 0) {
                for (std::uint32_t i = n.first; i < n.first + n.count; ++i) {
                    const auto& t = tri_[order_[i]];
                    const double d =
                        (closest_point_on_triangle(p, t[0], t[1], t[2]) - p).squaredNorm();
                    best = std::min(best, d);
                }
                continue;
            }
            const std::uint32_t l = n.first, r = n.first + 1;  // children are adjacent
            const double dl = nodes_[l].box.squared_distance(p);
            const double dr = nodes_[r].box.squared_distance(p);
            // Push the farther first so the nearer is visited first.
            if (dl < dr) {
                if (dr < best) stack[top++] = r;
                if (dl < best) stack[top++] = l;
            } else {
                if (dl < best) stack[top++] = l;
                if (dr < best) stack[top++] = r;
            }
        }
        return best;
    }

private:
    static constexpr std::uint32_t kLeaf = 4;
    struct Node {
        Box box;
        std::uint32_t first = 0;  ///< leaf: first triangle in order_; inner: left child
        std::uint32_t count = 0;  ///< leaf: triangle count; inner: 0
    };

    void build(std::uint32_t begin, std::uint32_t end) {
        // Iterative with an explicit stack of (node, begin, end).
        struct Task {
            std::uint32_t node, begin, end;
        };
        std::vector<Task> tasks;
        nodes_.push_back(Node());
        tasks.push_back({0, begin, end});
        while (!tasks.empty()) {
            const Task t = tasks.back();
            tasks.pop_back();
            Box box, cbox;
            for (std::uint32_t i = t.begin; i < t.end; ++i) {
                const auto& tri = tri_[order_[i]];
                for (const Point& p : tri) box.extend(p);
                cbox.extend(centroid_[order_[i]]);
            }
            nodes_[t.node].box = box;
            if (t.end - t.begin <= kLeaf) {
                nodes_[t.node].first = t.begin;
                nodes_[t.node].count = t.end - t.begin;
                continue;
            }
            int axis = 0;
            const Eigen::Vector3d ext = cbox.hi - cbox.lo;
            if (ext.y() > ext[axis]) axis = 1;
            if (ext.z() > ext[axis]) axis = 2;
            const std::uint32_t mid = t.begin + (t.end - t.begin) / 2;
            std::nth_element(order_.begin() + t.begin, order_.begin() + mid, order_.begin() + t.end,
                             [&](std::uint32_t x, std::uint32_t y) {
                                 return centroid_[x][axis] < centroid_[y][axis];
                             });
            const std::uint32_t left = std::uint32_t(nodes_.size());
            nodes_.push_back(Node());
            nodes_.push_back(Node());
            nodes_[t.node].first = left;
            nodes_[t.node].count = 0;
            tasks.push_back({left, t.begin, mid});
            tasks.push_back({left + 1, mid, t.end});
        }
    }

    std::vector<std::array<Point, 3>> tri_;
    std::vector<Point> centroid_;
    std::vector<std::uint32_t> order_;
    std::vector<Node> nodes_;
};

/// Vertices (with a face) plus area-proportional face samples on the R2 low-discrepancy
/// sequence (Roberts 2018), folded into each triangle.
/// `mask` (one flag per face storage index, or nullptr: all) limits both to the flagged faces
/// and their vertices.
std::vector<Point> sample_surface(const HalfedgeMesh& mesh, std::size_t n,
                                  const std::vector<std::uint8_t>* mask) {
    std::vector<Point> samples;
    const auto sampled = [mask](Face f) { return !mask || (*mask)[f.idx()]; };
    double total = 0;
    if (!mask) {
        for (Vertex v : mesh.vertices())
            if (!mesh.is_isolated(v)) samples.push_back(mesh.position(v));
        total = surface_area(mesh);
    } else {
        std::vector<std::uint8_t> taken(mesh.vertices_size(), 0);
        for (Face f : mesh.faces()) {
            if (!sampled(f)) continue;
            const auto c = mesh.face_vertices(f);
            for (Vertex v : c) taken[v.idx()] = 1;
            const Point &x0 = mesh.position(c[0]), &x1 = mesh.position(c[1]);
            total += 0.5 * (x1 - x0).cross(mesh.position(c[2]) - x0).norm();
        }
        for (Vertex v : mesh.vertices())
            if (taken[v.idx()]) samples.push_back(mesh.position(v));
    }
    if (!(total > 0)) return samples;
    const double g = 1.32471795724474602596;  // plastic number
    const double a1 = 1.0 / g, a2 = 1.0 / (g * g);
    double carry = 0;
    std::size_t k = 0;
    for (Face f : mesh.faces()) {
        if (!sampled(f)) continue;
        const auto c = mesh.face_vertices(f);
        const Point &x0 = mesh.position(c[0]), &x1 = mesh.position(c[1]), &x2 = mesh.position(c[2]);
        const double want = double(n) * 0.5 * (x1 - x0).cross(x2 - x0).norm() / total + carry;
        // The caller scales the coordinates so that areas are finite: want is in [0, n + 1].
        if (!(want >= 0 && want <= double(n) + 1))
            throw InvalidArgument("mesh_distance: the face areas cannot be computed (overflow)");
        const std::size_t m = std::size_t(want);
        carry = want - double(m);
        for (std::size_t i = 0; i < m; ++i, ++k) {
            double u = std::fmod(0.5 + a1 * double(k), 1.0);
            double w = std::fmod(0.5 + a2 * double(k), 1.0);
            if (u + w > 1) {
                u = 1 - u;
                w = 1 - w;
            }
            samples.push_back(x0 + u * (x1 - x0) + w * (x2 - x0));
        }
    }
    return samples;
}

void one_side(const std::vector<Point>& samples, const TriangleTree& tree, double& max,
              double& sum2) {
    max = 0;
    sum2 = 0;
    for (const Point& p : samples) {
        const double d2 = tree.squared_distance(p);
        sum2 += d2;
        max = std::max(max, d2);
    }
    max = std::sqrt(max);
}

MeshDistance distance_unscaled(const HalfedgeMesh& a, const HalfedgeMesh& b,
                               const MeshDistanceOptions& options) {
    MeshDistance d;
    d.diagonal = bounding_box(a).diagonal();
    const TriangleTree ta(a), tb(b);
    const std::vector<Point> sa = sample_surface(a, options.samples, options.a_faces);
    const std::vector<Point> sb = sample_surface(b, options.samples, options.b_faces);
    double s_ab = 0, s_ba = 0;
    one_side(sa, tb, d.a_to_b_max, s_ab);
    one_side(sb, ta, d.b_to_a_max, s_ba);
    d.a_to_b_rms = sa.empty() ? 0 : std::sqrt(s_ab / double(sa.size()));
    d.b_to_a_rms = sb.empty() ? 0 : std::sqrt(s_ba / double(sb.size()));
    d.samples = sa.size() + sb.size();
    d.hausdorff = std::max(d.a_to_b_max, d.b_to_a_max);
    d.rms = d.samples ? std::sqrt((s_ab + s_ba) / double(d.samples)) : 0;
    return d;
}

std::string number_text(double v) {
    char buf[32];
    std::snprintf(buf, sizeof(buf), "%g", v);
    return buf;
}

/// The largest coordinate magnitude; throws for a non-finite one.
double max_abs_coordinate(const HalfedgeMesh& m, const char* which) {
    double r = 0;
    for (Vertex v : m.vertices()) {
        const Point& p = m.position(v);
        if (!p.allFinite())
            throw InvalidArgument(std::string("mesh_distance: ") + which +
                                  " mesh has a non-finite "
                                  "position at vertex " +
                                  std::to_string(v.idx()));
        r = std::max(r, p.cwiseAbs().maxCoeff());
    }
    return r;
}

HalfedgeMesh scaled_copy(const HalfedgeMesh& m, double s) {
    HalfedgeMesh out = m;
    for (Point& p : out.positions()) p *= s;
    return out;
}

void check_face_mask(const HalfedgeMesh& mesh, const std::vector<std::uint8_t>* mask,
                     const char* name) {
    if (!mask) return;
    if (mask->size() != mesh.faces_size())
        throw InvalidArgument(std::string("mesh_distance: ") + name + " has " +
                              std::to_string(mask->size()) + " flags for " +
                              std::to_string(mesh.faces_size()) + " face slots");
    for (Face f : mesh.faces())
        if ((*mask)[f.idx()]) return;
    throw InvalidArgument(std::string("mesh_distance: ") + name + " flags no face");
}

/// The power of two that brings the coordinates of `a` and `b` near 1, or 0 when they need none.
int scale_exponent(const HalfedgeMesh& a, const HalfedgeMesh& b) {
    const double m =
        std::max(max_abs_coordinate(a, "the first"), max_abs_coordinate(b, "the second"));
    if (!(m > 0x1p100 || (m > 0 && m < 0x1p-100))) return 0;
    int exponent = 0;
    std::frexp(m, &exponent);
    return exponent;
}

constexpr double kDegrees = 57.295779513082320876798154814105;

}  // namespace

bool same_connectivity(const HalfedgeMesh& a, const HalfedgeMesh& b) {
    if (a.vertices_size() != b.vertices_size() || a.n_faces() != b.n_faces()) return false;
    auto fb = b.faces().begin();
    for (Face f : a.faces()) {
        if (a.face_vertices(f) != b.face_vertices(*fb)) return false;
        ++fb;
    }
    return true;
}

NormalDeviation normal_deviation(const HalfedgeMesh& a, const HalfedgeMesh& b,
                                 const std::vector<float>* region) {
    if (!same_connectivity(a, b))
        throw InvalidArgument(
            "normal_deviation: the meshes differ in connectivity (" + std::to_string(a.n_faces()) +
            " and " + std::to_string(b.n_faces()) +
            " faces): face normals can only be compared between states of one mesh");
    if (region) check_selection(a, *region, "normal_deviation: region");
    NormalDeviation d;
    double sum = 0;
    auto fb = b.faces().begin();
    for (Face f : a.faces()) {
        const Face g = *fb;
        ++fb;
        if (region) {
            bool inside = true;
            for (Vertex v : a.face_vertices(f)) inside = inside && (*region)[v.idx()] > 0.0f;
            if (!inside) {
                ++d.outside;
                continue;
            }
        }
        const Vector3 na = face_normal(a, f), nb = face_normal(b, g);
        if (na.isZero(0.0) || nb.isZero(0.0)) {
            ++d.degenerate;
            continue;
        }
        // atan2 of |a x b| and a . b: exact 0 for equal normals, accurate for small angles.
        const double angle = std::atan2(na.cross(nb).norm(), na.dot(nb)) * kDegrees;
        sum += angle;
        d.max_degrees = std::max(d.max_degrees, angle);
        d.flipped += angle > 90.0;
        ++d.faces;
    }
    d.mean_degrees = d.faces ? sum / double(d.faces) : 0.0;
    return d;
}

std::vector<double> vertex_surface_distances(const HalfedgeMesh& from, const HalfedgeMesh& to) {
    if (to.n_faces() == 0)
        throw InvalidArgument("vertex_surface_distances: the mesh measured against has no faces");
    const int exponent = scale_exponent(from, to);
    const double s = std::ldexp(1.0, -exponent);
    const TriangleTree tree(exponent ? scaled_copy(to, s) : to);
    std::vector<double> out(from.vertices_size(), std::numeric_limits<double>::quiet_NaN());
    for (Vertex v : from.vertices()) {
        if (from.is_isolated(v)) continue;
        const Point p = exponent ? Point(from.position(v) * s) : from.position(v);
        out[v.idx()] = std::ldexp(std::sqrt(tree.squared_distance(p)), exponent);
    }
    return out;
}

MeshDistance mesh_distance(const HalfedgeMesh& a, const HalfedgeMesh& b,
                           const MeshDistanceOptions& options) {
    if (a.n_faces() == 0 || b.n_faces() == 0)
        throw InvalidArgument("mesh_distance: both meshes need faces (got " +
                              std::to_string(a.n_faces()) + " and " + std::to_string(b.n_faces()) +
                              ")");
    if (options.samples == 0) throw InvalidArgument("mesh_distance: samples must be at least 1");
    check_face_mask(a, options.a_faces, "a_faces");
    check_face_mask(b, options.b_faces, "b_faces");
    // Squared distances and areas of coordinates far from 1 overflow (1e200) or underflow
    // (1e-200): such meshes are measured scaled by a power of two (exact), and the distances
    // scaled back.
    const double m =
        std::max(max_abs_coordinate(a, "the first"), max_abs_coordinate(b, "the second"));
    if (!(m > 0x1p100 || (m > 0 && m < 0x1p-100))) return distance_unscaled(a, b, options);
    int exponent = 0;
    std::frexp(m, &exponent);
    MeshDistance d = distance_unscaled(scaled_copy(a, std::ldexp(1.0, -exponent)),
                                       scaled_copy(b, std::ldexp(1.0, -exponent)), options);
    for (double* x : {&d.hausdorff, &d.rms, &d.a_to_b_max, &d.a_to_b_rms, &d.b_to_a_max,
                      &d.b_to_a_rms, &d.diagonal}) {
        // Checked before scaling back (*x = f 2^e with 0.5 <= f < 1), so that nothing
        // overflows on the way.
        int e = 0;
        std::frexp(*x, &e);
        if (!std::isfinite(*x) ||
            (*x != 0 && e + exponent > std::numeric_limits<double>::max_exponent))
            throw InvalidArgument(
                "mesh_distance: the distances between these meshes exceed the largest double "
                "(coordinates up to " +
                number_text(m) + ")");
        *x = std::ldexp(*x, exponent);
    }
    return d;
}

}  // namespace trilab
