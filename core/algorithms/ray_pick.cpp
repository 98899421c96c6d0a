// Picking by ray casting (core/algorithms/ray_pick.h).
#include "core/algorithms/ray_pick.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <string>
#include <thread>

#include "core/errors.h"
#include "core/parallel.h"

namespace trilab {
namespace {

constexpr std::size_t kParallelTriangles = 200000;

/// The best hit so far of one thread: the smallest t, then the lowest triangle index.
struct Candidate {
    double t = std::numeric_limits<double>::infinity();
    Index triangle = kInvalidIndex;
    std::array<Index, 3> corners{};
    double u = 0, v = 0;
    bool back = false;
    bool better_than(const Candidate& o) const {
        return t < o.t || (t == o.t && triangle < o.triangle);
    }
};

/// Möller-Trumbore, both orientations. Updates `best` when this triangle is hit closer.
inline void test_triangle(const Point& origin, const Vector3& dir, double t_min, const Point& a,
                          const Point& b, const Point& c, Index triangle,
                          const std::array<Index, 3>& corners, Candidate& best) {
    const Vector3 e1 = b - a, e2 = c - a;
    const Vector3 p = dir.cross(e2);
    const double det = e1.dot(p);
    if (!(std::abs(det) > 0.0) || !std::isfinite(det)) return;
    const double inv = 1.0 / det;
    const Vector3 s = origin - a;
    const double u = s.dot(p) * inv;
    if (u < 0.0 || u > 1.0) return;
    const Vector3 q = s.cross(e1);
    const double v = dir.dot(q) * inv;
    if (v < 0.0 || u + v > 1.0) return;
    const double t = e2.dot(q) * inv;
    if (!(t > t_min)) return;
    Candidate c_new;
    c_new.t = t;
    c_new.triangle = triangle;
    if (!c_new.better_than(best)) return;
    c_new.corners = corners;
    c_new.u = u;
    c_new.v = v;
    c_new.back = det < 0.0;  // the ray runs along the normal e1 x e2: it meets the back
    best = c_new;
}

void check_ray(const Ray& ray) {
    if (!ray.origin.allFinite() || !ray.direction.allFinite())
        throw InvalidArgument("pick: the ray is not finite");
    if (ray.direction.squaredNorm() == 0.0) throw InvalidArgument("pick: the ray has no direction");
}

/// Runs `scan(begin, end, best)` over [0, n), split over the hardware threads when large,
/// and returns the best candidate.
template <typename Scan>
Candidate scan_all(std::size_t n, Scan scan) {
    const std::size_t threads =
        n < kParallelTriangles ? 1 : std::max(1u, std::min(16u, unsigned(trilab::thread_count())));
    std::vector<Candidate> best(threads);
    if (threads == 1) {
        scan(std::size_t(0), n, best[0]);
        return best[0];
    }
    std::vector<std::thread> workers;
    const std::size_t chunk = (n + threads - 1) / threads;
    for (std::size_t i = 1; i < threads; ++i)
        workers.emplace_back(
            [&, i] { scan(std::min(n, i * chunk), std::min(n, (i + 1) * chunk), best[i]); });
    scan(std::size_t(0), std::min(n, chunk), best[0]);
    for (std::thread& w : workers) w.join();
    Candidate result = best[0];
    for (const Candidate& c : best)
        if (c.better_than(result)) result = c;
    return result;
}

/// Which side of two planes through the ray each point lies on (bits: +u, -u, +w, -w): a
/// triangle whose corners share a bit lies wholly on one side of a plane that holds the
/// ray and cannot meet it. One sequential pass over the points; the faces then read one byte
/// per corner instead of a position, and test only the triangles the ray may cross.
std::vector<std::uint8_t> side_codes(const std::vector<Point>& positions, const Ray& ray) {
    const Vector3 d = ray.direction.normalized();
    const Vector3 helper = std::abs(d.x()) < 0.6 ? Vector3::UnitX() : Vector3::UnitY();
    const Vector3 u = d.cross(helper).normalized();
    const Vector3 w = d.cross(u);
    std::vector<std::uint8_t> codes(positions.size());
    scan_all(positions.size(), [&](std::size_t begin, std::size_t end, Candidate&) {
        for (std::size_t i = begin; i < end; ++i) {
            const Vector3 q = positions[i] - ray.origin;
            const double a = q.dot(u), b = q.dot(w);
            codes[i] =
                std::uint8_t((a > 0 ? 1 : 0) | (a < 0 ? 2 : 0) | (b > 0 ? 4 : 0) | (b < 0 ? 8 : 0));
        }
    });
    return codes;
}

std::optional<RayHit> to_hit(const Candidate& c, const Ray& ray,
                             const std::vector<Point>& positions) {
    if (c.triangle == kInvalidIndex) return std::nullopt;
    RayHit hit;
    hit.triangle = c.triangle;
    hit.corners = c.corners;
    hit.t = c.t;
    hit.barycentric = {1.0 - c.u - c.v, c.u, c.v};
    hit.position = ray.origin + c.t * ray.direction;
    hit.back_face = c.back;
    set_nearest_elements(hit, positions);
    return hit;
}

double segment_distance(const Point& p, const Point& a, const Point& b) {
    const Vector3 ab = b - a;
    const double len2 = ab.squaredNorm();
    const double s = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
    return (p - (a + s * ab)).norm();
}

}  // namespace

void set_nearest_elements(RayHit& hit, const std::vector<Point>& positions) {
    double corner_best = std::numeric_limits<double>::infinity();
    double edge_best = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 3; ++k) {
        const Point& a = positions[hit.corners[k]];
        const Point& b = positions[hit.corners[(k + 1) % 3]];
        const double dc = (hit.position - a).norm();
        if (dc < corner_best) {
            corner_best = dc;
            hit.nearest_corner = k;
        }
        const double de = segment_distance(hit.position, a, b);
        if (de < edge_best) {
            edge_best = de;
            hit.nearest_edge = k;
        }
    }
}

Halfedge face_side(const HalfedgeMesh& mesh, Face face, int k) {
    Halfedge h = mesh.next(mesh.halfedge(face));  // from corner 0 to corner 1
    for (int i = 0; i < k; ++i) h = mesh.next(h);
    return h;
}

std::optional<RayHit> pick_face(const HalfedgeMesh& mesh, const std::vector<Point>& positions,
                                const Ray& ray, double t_min) {
    check_ray(ray);
    if (positions.size() != mesh.vertices_size())
        throw InvalidArgument("pick: " + std::to_string(positions.size()) +
                              " positions for a mesh of " + std::to_string(mesh.vertices_size()) +
                              " vertices");
    const auto& fhalfedge = mesh.face_halfedge_array();
    const auto& hto = mesh.halfedge_to_array();
    const auto& hnext = mesh.halfedge_next_array();
    const Point origin = ray.origin;
    const Vector3 dir = ray.direction;
    const std::vector<std::uint8_t> codes = side_codes(positions, ray);
    const Candidate best =
        scan_all(mesh.faces_size(), [&](std::size_t begin, std::size_t end, Candidate& out) {
            for (std::size_t f = begin; f < end; ++f) {
                if (mesh.is_deleted(Face(Index(f)))) continue;
                const Halfedge h0 = fhalfedge[f];
                if (!h0.is_valid()) continue;
                const Vertex a = hto[h0.idx()];
                Halfedge h = hnext[h0.idx()];
                Vertex b = hto[h.idx()];
                h = hnext[h.idx()];
                // A fan from corner 0 over the face's sides (one triangle for a triangle).
                for (std::size_t guard = 0; h != h0 && guard < 1024; ++guard) {
                    const Vertex c = hto[h.idx()];
                    if ((codes[a.idx()] & codes[b.idx()] & codes[c.idx()]) != 0) {
                        b = c;
                        h = hnext[h.idx()];
                        continue;
                    }
                    test_triangle(origin, dir, t_min, positions[a.idx()], positions[b.idx()],
                                  positions[c.idx()], Index(f), {a.idx(), b.idx(), c.idx()}, out);
                    b = c;
                    h = hnext[h.idx()];
                }
            }
        });
    return to_hit(best, ray, positions);
}

std::optional<RayHit> pick_triangle(const std::vector<std::array<Index, 3>>& triangles,
                                    const std::vector<std::uint8_t>& alive,
                                    const std::vector<Point>& positions, const Ray& ray,
                                    double t_min) {
    check_ray(ray);
    const bool all_alive = alive.empty();
    if (!all_alive && alive.size() != triangles.size())
        throw InvalidArgument("pick: " + std::to_string(alive.size()) + " flags for " +
                              std::to_string(triangles.size()) + " triangles");
    const std::size_t n_points = positions.size();
    const Point origin = ray.origin;
    const Vector3 dir = ray.direction;
    std::atomic<bool> out_of_range{false};
    const std::vector<std::uint8_t> codes = side_codes(positions, ray);
    const Candidate best =
        scan_all(triangles.size(), [&](std::size_t begin, std::size_t end, Candidate& out) {
            for (std::size_t i = begin; i < end; ++i) {
                if (!all_alive && !alive[i]) continue;
                const std::array<Index, 3>& t = triangles[i];
                if (t[0] >= n_points || t[1] >= n_points || t[2] >= n_points) {
                    out_of_range.store(true, std::memory_order_relaxed);
                    continue;
                }
                if ((codes[t[0]] & codes[t[1]] & codes[t[2]]) != 0) continue;
                test_triangle(origin, dir, t_min, positions[t[0]], positions[t[1]], positions[t[2]],
                              Index(i), t, out);
            }
        });
    if (out_of_range.load()) throw InvalidArgument("pick: a triangle's corner is out of range");
    return to_hit(best, ray, positions);
}

}  // namespace trilab
