#include "core/geometry.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "core/parallel.h"
#include "core/prefetch.h"

namespace trilab {

void BoundingBox::extend(const Point& p) {
    if (empty) {
        min = max = p;
        empty = false;
        return;
    }
    min = min.cwiseMin(p);
    max = max.cwiseMax(p);
}

Vector3 face_area_vector(const HalfedgeMesh& mesh, Face f) {
    const auto c = mesh.face_vertices(f);
    const Point& x0 = mesh.position(c[0]);
    return (mesh.position(c[1]) - x0).cross(mesh.position(c[2]) - x0);
}

Vector3 face_normal(const HalfedgeMesh& mesh, Face f) {
    const Vector3 n = face_area_vector(mesh, f);
    const double len = n.norm();
    return len > 0 && std::isfinite(len) ? Vector3(n / len) : Vector3::Zero();
}

double face_area(const HalfedgeMesh& mesh, Face f) {
    return 0.5 * face_area_vector(mesh, f).norm();
}

Point face_centroid(const HalfedgeMesh& mesh, Face f) {
    const auto c = mesh.face_vertices(f);
    return (mesh.position(c[0]) + mesh.position(c[1]) + mesh.position(c[2])) / 3.0;
}

Vector3 vertex_normal(const HalfedgeMesh& mesh, Vertex v) {
    Vector3 n = Vector3::Zero();
    for (Face f : mesh.faces_around(v)) n += face_area_vector(mesh, f);
    const double len = n.norm();
    return len > 0 && std::isfinite(len) ? Vector3(n / len) : Vector3::Zero();
}

void compute_vertex_normals(HalfedgeMesh& mesh) {
    Vector3* normals = mesh.vertex_property<Vector3>("v:normal", Vector3::Zero()).vector().data();
    const HalfedgeMesh& m = mesh;
    parallel_for(0, m.vertices_size(), [&](std::size_t v) {  // each normal from its own ring
        const Vertex vh(static_cast<Index>(v));
        if (!m.is_deleted(vh)) normals[v] = vertex_normal(m, vh);
    });
}

double edge_length(const HalfedgeMesh& mesh, Edge e) {
    return (mesh.position(mesh.vertex(e, 0)) - mesh.position(mesh.vertex(e, 1))).norm();
}

double mean_edge_length(const HalfedgeMesh& mesh) {
    double sum = 0;
    for (Edge e : mesh.edges()) sum += edge_length(mesh, e);
    return mesh.n_edges() ? sum / double(mesh.n_edges()) : 0.0;
}

BoundingBox bounding_box(const HalfedgeMesh& mesh) {
    BoundingBox box;
    for (Vertex v : mesh.vertices()) box.extend(mesh.position(v));
    return box;
}

namespace {

/// The one area and volume pass: per face, n = (x1 - x0) x (x2 - x0); the area sums |n| / 2
/// (face_area()), the volume centroid . n / 6 (formula (1.15)), over the connectivity arrays
/// with the halfedges of a few faces ahead prefetched (every load runs the volume for its
/// orientation note; `info` both). In fixed blocks of faces on every thread, the blocks' sums
/// added in block order (core/parallel.h): the same bits for any number of threads, and for a
/// mesh of one block (up to kBlock faces) the plain face-order sums.
template <bool WithArea, bool WithVolume>
AreaVolume sum_area_volume(const HalfedgeMesh& mesh) {
    const std::vector<Vertex>& to = mesh.halfedge_to_array();
    const std::vector<Halfedge>& next = mesh.halfedge_next_array();
    const std::vector<Halfedge>& fh = mesh.face_halfedge_array();
    const std::vector<Point>& x = mesh.positions();
    const bool garbage = mesh.has_garbage();
    constexpr std::size_t kAhead = 8;
    using Sums = std::pair<double, double>;
    const Sums sums = parallel_reduce(
        0, fh.size(), Sums{0, 0},
        [&](std::size_t begin, std::size_t end) {
            double area = 0, volume6 = 0;
            for (std::size_t f = begin; f < end; ++f) {
                if (garbage && mesh.is_deleted(Face(Index(f)))) continue;
                if (f + kAhead < fh.size()) {
                    const Index a = fh[f + kAhead].idx();
                    if (a < next.size()) {
                        prefetch(&next[a]);
                        prefetch(&to[a]);
                    }
                }
                const Halfedge h0 = fh[f], h1 = next[h0.idx()], h2 = next[h1.idx()];
                const Point& x0 = x[to[h0.idx()].idx()];
                const Point& x1 = x[to[h1.idx()].idx()];
                const Point& x2 = x[to[h2.idx()].idx()];
                const Vector3 n = (x1 - x0).cross(x2 - x0);
                if (WithArea) area += 0.5 * n.norm();
                if (WithVolume) volume6 += ((x0 + x1 + x2) / 3.0).dot(n);
            }
            return Sums{area, volume6};
        },
        [](const Sums& a, const Sums& b) {
            return Sums{a.first + b.first, a.second + b.second};
        });
    AreaVolume r;
    if (WithArea) r.area = sums.first;
    if (WithVolume) r.volume = sums.second / 6.0;
    return r;
}

}  // namespace

AreaVolume area_and_volume(const HalfedgeMesh& mesh, bool with_area, bool with_volume) {
    if (with_area && with_volume) return sum_area_volume<true, true>(mesh);
    if (with_area) return sum_area_volume<true, false>(mesh);
    if (with_volume) return sum_area_volume<false, true>(mesh);
    return {};
}

double surface_area(const HalfedgeMesh& mesh) {
    return area_and_volume(mesh, true, false).area;
}

double volume(const HalfedgeMesh& mesh) {
    return area_and_volume(mesh, false, true).volume;
}

double min_face_angle(const HalfedgeMesh& mesh, Face f) {
    const std::array<Vertex, 3> v = mesh.face_vertices(f);
    // The smallest angle is the one opposite the shortest side: one atan2 per face.
    int k = 0;
    double shortest = std::numeric_limits<double>::infinity();
    for (int i = 0; i < 3; ++i) {
        const double l =
            (mesh.position(v[(i + 1) % 3]) - mesh.position(v[(i + 2) % 3])).squaredNorm();
        if (l < shortest) {
            shortest = l;
            k = i;
        }
    }
    const Vector3 a = mesh.position(v[(k + 1) % 3]) - mesh.position(v[k]);
    const Vector3 b = mesh.position(v[(k + 2) % 3]) - mesh.position(v[k]);
    const double sine = a.cross(b).norm(), cosine = a.dot(b);
    if (!(sine > 0)) return 0.0;  // degenerate (or a repeated point)
    return std::atan2(sine, cosine) * (180.0 / 3.14159265358979323846);
}

double min_triangle_angle(const HalfedgeMesh& mesh) {
    // The face whose smallest angle has the largest cosine (law of cosines, no trigonometry),
    // then that face's angle exactly.
    const std::vector<Point>& x = mesh.positions();
    double largest_cosine = -2.0;
    Face flattest;
    for (Face f : mesh.faces()) {
        const std::array<Vertex, 3> v = mesh.face_vertices(f);
        const Point &p0 = x[v[0].idx()], &p1 = x[v[1].idx()], &p2 = x[v[2].idx()];
        double l[3] = {(p1 - p2).squaredNorm(), (p2 - p0).squaredNorm(), (p0 - p1).squaredNorm()};
        std::sort(l, l + 3);
        const double denominator = 2.0 * std::sqrt(l[1] * l[2]);
        const double cosine = denominator > 0 ? (l[1] + l[2] - l[0]) / denominator : 1.0;
        if (cosine > largest_cosine || !flattest.is_valid()) {
            largest_cosine = cosine;
            flattest = f;
        }
    }
    return flattest.is_valid() ? min_face_angle(mesh, flattest) : 180.0;
}

bool is_closed(const HalfedgeMesh& mesh) {
    if (mesh.n_faces() == 0) return false;
    for (Edge e : mesh.edges())
        if (mesh.is_boundary(e)) return false;
    return true;
}

double cotangent_opposite(const HalfedgeMesh& mesh, Halfedge h) {
    if (mesh.is_boundary(h)) return 0.0;
    const Point& a = mesh.position(mesh.from_vertex(h));
    const Point& b = mesh.position(mesh.to_vertex(h));
    const Point& c = mesh.position(mesh.to_vertex(mesh.next(h)));
    const Vector3 u = a - c, w = b - c;
    const double sin_scaled = u.cross(w).norm();
    if (!(sin_scaled > 0) || !std::isfinite(sin_scaled)) return 0.0;
    return u.dot(w) / sin_scaled;
}

double cotangent_weight(const HalfedgeMesh& mesh, Edge e) {
    return 0.5 * (cotangent_opposite(mesh, HalfedgeMesh::halfedge(e, 0)) +
                  cotangent_opposite(mesh, HalfedgeMesh::halfedge(e, 1)));
}

}  // namespace trilab
