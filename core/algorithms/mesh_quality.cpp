// Triangle and mesh quality figures (see core/algorithms/mesh_quality.h).
#include "core/algorithms/mesh_quality.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "core/errors.h"
#include "core/geometry.h"

namespace trilab {
namespace {

constexpr double kDegrees = 180.0 / 3.14159265358979323846;

/// The three angles of a triangle in degrees (0 at a corner with a zero-length side).
struct Angles {
    double a[3] = {0, 0, 0};
};

Angles angles_of(const Point& p0, const Point& p1, const Point& p2) {
    const Point* p[3] = {&p0, &p1, &p2};
    Angles out;
    for (int i = 0; i < 3; ++i) {
        const Vector3 u = *p[(i + 1) % 3] - *p[i], w = *p[(i + 2) % 3] - *p[i];
        const double c = u.cross(w).norm(), d = u.dot(w);
        // atan2 is accurate for tiny and near-straight angles alike; 0 for a zero side.
        out.a[i] = (c == 0 && d == 0) ? 0.0 : std::atan2(c, d) * kDegrees;
    }
    return out;
}

std::array<Point, 3> corners(const HalfedgeMesh& mesh, Face f) {
    const auto c = mesh.face_vertices(f);
    return {mesh.position(c[0]), mesh.position(c[1]), mesh.position(c[2])};
}

double quality_of(const Point& a, const Point& b, const Point& c) {
    const double l0 = (b - a).norm(), l1 = (c - b).norm(), l2 = (a - c).norm();
    const double area = 0.5 * (b - a).cross(c - a).norm();
    const double den = (l0 + l1 + l2) * std::max({l0, l1, l2});
    if (!(den > 0) || !std::isfinite(den) || !std::isfinite(area)) return 0.0;
    return std::min(1.0, 4.0 * std::sqrt(3.0) * area / den);
}

}  // namespace

double triangle_min_angle(const HalfedgeMesh& mesh, Face f) {
    const auto p = corners(mesh, f);
    const Angles a = angles_of(p[0], p[1], p[2]);
    return std::min({a.a[0], a.a[1], a.a[2]});
}

double triangle_quality(const HalfedgeMesh& mesh, Face f) {
    const auto p = corners(mesh, f);
    return quality_of(p[0], p[1], p[2]);
}

std::vector<double> face_quality_field(const HalfedgeMesh& mesh, bool min_angle) {
    std::vector<double> out(mesh.faces_size(), std::numeric_limits<double>::quiet_NaN());
    for (Face f : mesh.faces())
        out[f.idx()] = min_angle ? triangle_min_angle(mesh, f) : triangle_quality(mesh, f);
    return out;
}

MeshQuality mesh_quality(const HalfedgeMesh& mesh, std::optional<double> length) {
    if (length && !(std::isfinite(*length) && *length > 0)) {
        char buf[64];
        std::snprintf(buf, sizeof(buf), "%g", *length);
        throw InvalidArgument(
            std::string("mesh_quality: length must be positive and finite, got ") + buf);
    }
    MeshQuality q;
    double sum_min = 0, sum_q = 0;
    std::size_t under30 = 0;
    q.min_angle = 180;
    q.min_q = 1;
    for (Face f : mesh.faces()) {
        const auto p = corners(mesh, f);
        const Angles a = angles_of(p[0], p[1], p[2]);
        const double m = std::min({a.a[0], a.a[1], a.a[2]});
        for (double x : a.a) under30 += x < 30.0;
        const double qq = quality_of(p[0], p[1], p[2]);
        q.min_angle = std::min(q.min_angle, m);
        q.min_q = std::min(q.min_q, qq);
        sum_min += m;
        sum_q += qq;
        ++q.faces;
    }
    if (q.faces) {
        q.mean_min_angle = sum_min / double(q.faces);
        q.mean_q = sum_q / double(q.faces);
        q.angles_under_30 = double(under30) / double(3 * q.faces);
    } else {
        q.min_angle = 0;
        q.min_q = 0;
    }
    std::vector<double> lengths;
    lengths.reserve(mesh.n_edges());
    double sum_len = 0;
    q.min_edge = std::numeric_limits<double>::infinity();
    for (Edge e : mesh.edges()) {
        const double l =
            (mesh.position(mesh.vertex(e, 0)) - mesh.position(mesh.vertex(e, 1))).norm();
        lengths.push_back(l);
        sum_len += l;
        q.min_edge = std::min(q.min_edge, l);
        q.max_edge = std::max(q.max_edge, l);
    }
    q.edges = lengths.size();
    if (q.edges == 0) q.min_edge = 0;
    q.mean_edge = q.edges ? sum_len / double(q.edges) : 0.0;
    q.length = length ? *length : q.mean_edge;
    std::size_t in_band = 0;
    for (double l : lengths) in_band += l >= 0.8 * q.length && l <= 4.0 / 3.0 * q.length;
    q.edges_in_band = q.edges ? double(in_band) / double(q.edges) : 0.0;
    std::size_t v6 = 0, v4 = 0;
    for (Vertex v : mesh.vertices()) {
        if (mesh.is_isolated(v)) continue;
        const unsigned k = mesh.valence(v);
        if (mesh.is_boundary(v)) {
            ++q.boundary_vertices;
            v4 += k == 4;
        } else {
            ++q.interior_vertices;
            v6 += k == 6;
        }
    }
    q.valence6 = q.interior_vertices ? double(v6) / double(q.interior_vertices) : 0.0;
    q.valence4_boundary = q.boundary_vertices ? double(v4) / double(q.boundary_vertices) : 0.0;
    return q;
}

namespace {

/// The cotangent of the corner opposite to halfedge h, or nothing for a face without area.
std::optional<double> opposite_cotangent(const HalfedgeMesh& mesh, Halfedge h) {
    const Point& a = mesh.position(mesh.from_vertex(h));
    const Point& b = mesh.position(mesh.to_vertex(h));
    const Point& c = mesh.position(mesh.to_vertex(mesh.next(h)));
    const Vector3 u = a - c, w = b - c;
    const double sin_scaled = u.cross(w).norm();
    if (!(sin_scaled > 0) || !std::isfinite(sin_scaled)) return std::nullopt;
    return u.dot(w) / sin_scaled;
}

/// The largest over the smallest positive value of `v` (0 when none is positive).
double positive_ratio(const std::vector<double>& v) {
    double low = std::numeric_limits<double>::infinity(), high = 0;
    for (double x : v)
        if (x > 0) {
            low = std::min(low, x);
            high = std::max(high, x);
        }
    return high > 0 ? high / low : 0.0;
}

}  // namespace

CotangentSpread cotangent_spread(const HalfedgeMesh& mesh) {
    CotangentSpread s;
    std::vector<double> diagonal(mesh.vertices_size(), 0.0), mass(mesh.vertices_size(), 0.0);
    for (Face f : mesh.faces()) {
        const auto c = mesh.face_vertices(f);
        const double third = face_area(mesh, f) / 3.0;
        for (Vertex v : c) mass[v.idx()] += third;
    }
    std::vector<double> magnitude;
    magnitude.reserve(mesh.n_edges());
    bool first = true;
    for (Edge e : mesh.edges()) {
        double w = 0;
        for (unsigned side = 0; side < 2; ++side) {
            const Halfedge h = HalfedgeMesh::halfedge(e, side);
            if (mesh.is_boundary(h)) continue;
            const std::optional<double> cot = opposite_cotangent(mesh, h);
            if (cot)
                w += 0.5 * *cot;
            else
                ++s.degenerate_corners;
        }
        ++s.edges;
        s.negative_weights += w < 0;
        s.min_weight = first ? w : std::min(s.min_weight, w);
        s.max_weight = first ? w : std::max(s.max_weight, w);
        first = false;
        magnitude.push_back(std::abs(w));
        diagonal[mesh.vertex(e, 0).idx()] += w;
        diagonal[mesh.vertex(e, 1).idx()] += w;
    }
    s.negative_share = s.edges ? double(s.negative_weights) / double(s.edges) : 0.0;
    if (!magnitude.empty()) {
        auto middle = magnitude.begin() + std::ptrdiff_t(magnitude.size() / 2);
        std::nth_element(magnitude.begin(), middle, magnitude.end());
        const double median = *middle;
        const double largest = *std::max_element(magnitude.begin(), magnitude.end());
        s.weight_ratio = median > 0 ? largest / median : 0.0;
    }
    std::vector<double> k, normalized;
    for (Vertex v : mesh.vertices()) {
        if (mesh.is_isolated(v)) continue;
        ++s.vertices;
        const double d = diagonal[v.idx()];
        if (!(d > 0)) {
            ++s.nonpositive_diagonal;
            continue;
        }
        k.push_back(d);
        if (mass[v.idx()] > 0) normalized.push_back(d / mass[v.idx()]);
    }
    s.diagonal_ratio = positive_ratio(k);
    s.normalized_diagonal_ratio = positive_ratio(normalized);
    return s;
}

}  // namespace trilab
