// Discrete curvatures (Meyer et al. 2003) against analytic shapes: sphere, cylinder, torus,
// plane; Gauss-Bonnet; orientation; degenerate input never gives NaN.
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "core/algorithms/curvature.h"
#include "core/algorithms/generators.h"
#include "core/geometry.h"
#include "core/mesh_builder.h"
#include "test_helpers.h"

using namespace trilab;

namespace {

constexpr double kPi = 3.14159265358979323846;

/// The field's values at valid vertices.
std::vector<double> valid_values(const VertexCurvatures& c, const std::vector<double>& field) {
    std::vector<double> out;
    for (std::size_t i = 0; i < field.size(); ++i)
        if (c.valid[i]) out.push_back(field[i]);
    return out;
}

/// The p-quantile (p in [0, 1]) by the nearest rank below.
double quantile(std::vector<double> v, double p) {
    REQUIRE_FALSE(v.empty());
    std::sort(v.begin(), v.end());
    return v[std::size_t(p * double(v.size() - 1))];
}

/// Checks that the median and the 5th / 95th percentiles of `values` lie within `tolerance`
/// (absolute) of `expected`.
void require_near(const std::vector<double>& values, double expected, double tolerance) {
    INFO("expected " << expected << " +- " << tolerance);
    for (double p : {0.05, 0.5, 0.95}) {
        INFO("quantile " << p);
        REQUIRE(std::abs(quantile(values, p) - expected) <= tolerance);
    }
}

double total_curvature(const VertexCurvatures& c) {
    double sum = 0;
    for (std::size_t i = 0; i < c.valid.size(); ++i)
        if (c.valid[i]) sum += c.gaussian[i] * c.area[i];
    return sum;
}

void require_all_finite(const VertexCurvatures& c) {
    for (const auto* field : {&c.mean, &c.gaussian, &c.k1, &c.k2, &c.shape_index, &c.area})
        for (double x : *field) REQUIRE(std::isfinite(x));
}

void require_zero_where_invalid(const VertexCurvatures& c) {
    for (std::size_t i = 0; i < c.valid.size(); ++i) {
        if (c.valid[i]) continue;
        REQUIRE(c.mean[i] == 0);
        REQUIRE(c.gaussian[i] == 0);
        REQUIRE(c.k1[i] == 0);
        REQUIRE(c.k2[i] == 0);
        REQUIRE(c.shape_index[i] == 0);
        REQUIRE(c.area[i] == 0);
    }
}

HalfedgeMesh sphere_of_radius(double r) {
    HalfedgeMesh m = make_icosphere(30);
    for (Vertex v : m.vertices()) m.position(v) *= r;
    return m;
}

/// The same mesh with every face's orientation reversed.
HalfedgeMesh flipped(const HalfedgeMesh& mesh) {
    PolygonSoup soup = to_soup(mesh);
    for (std::size_t f = 0; f < soup.n_faces(); ++f)
        std::swap(soup.corners[soup.face_offsets[f]], soup.corners[soup.face_offsets[f] + 1]);
    LoadReport report;
    return build_mesh(soup, report);
}

}  // namespace

TEST_CASE("compute_curvatures on a sphere of radius 2: k1 = k2 = H = 1/r, K = 1/r^2",
          "[curvature]") {
    const double r = 2.0;
    const HalfedgeMesh m = sphere_of_radius(r);
    const VertexCurvatures c = compute_curvatures(m);
    REQUIRE(c.valid.size() == m.vertices_size());
    for (Vertex v : m.vertices()) REQUIRE(c.valid[v.idx()] == 1);
    require_near(valid_values(c, c.k1), 1 / r, 0.02 / r);
    require_near(valid_values(c, c.k2), 1 / r, 0.02 / r);
    require_near(valid_values(c, c.mean), 1 / r, 0.02 / r);
    require_near(valid_values(c, c.gaussian), 1 / (r * r), 0.02 / (r * r));
    // Every vertex is (numerically) an umbilic with the sign of a convex cap.
    for (double s : valid_values(c, c.shape_index)) REQUIRE(s == Approx(1.0).margin(1e-3));
    require_all_finite(c);
}

TEST_CASE("compute_curvatures on an open cylinder: k1 = 1/r, k2 = K = 0, H = 1/(2r)",
          "[curvature]") {
    const HalfedgeMesh m = make_cylinder(128, 64);  // radius 1
    const VertexCurvatures c = compute_curvatures(m);
    std::size_t interior = 0;
    for (Vertex v : m.vertices()) {
        REQUIRE(c.valid[v.idx()] == (m.is_boundary(v) ? 0 : 1));
        interior += m.is_boundary(v) ? 0 : 1;
    }
    REQUIRE(interior == 128 * 63);
    require_zero_where_invalid(c);
    require_near(valid_values(c, c.k1), 1.0, 0.02);
    require_near(valid_values(c, c.k2), 0.0, 0.02);
    require_near(valid_values(c, c.gaussian), 0.0, 0.02);
    require_near(valid_values(c, c.mean), 0.5, 0.01);
    // A cylinder is a ridge: S = (2/pi) atan(1) = 1/2.
    require_near(valid_values(c, c.shape_index), 0.5, 0.02);
}

TEST_CASE("compute_curvatures on a torus: sign of K, analytic values, Gauss-Bonnet",
          "[curvature]") {
    const double R = 1.0, r = 0.3;
    const HalfedgeMesh m = make_torus(200, 100, R, r);
    const VertexCurvatures c = compute_curvatures(m);
    std::size_t outer = 0, inner = 0;
    std::vector<double> mean_error, gaussian_error;
    for (Vertex v : m.vertices()) {
        const std::size_t i = v.idx();
        REQUIRE(c.valid[i] == 1);
        const Point& p = m.position(v);
        const double rho = std::hypot(p.x(), p.y());
        // cos of the angle around the tube, and the analytic curvatures.
        const double cw = std::clamp((rho - R) / r, -1.0, 1.0);
        const double gaussian = cw / (r * (R + r * cw));
        const double mean = (R + 2 * r * cw) / (2 * r * (R + r * cw));
        mean_error.push_back(std::abs(c.mean[i] - mean) / mean);
        gaussian_error.push_back(std::abs(c.gaussian[i] - gaussian));
        if (std::abs(p.z()) < 1e-9 && rho > R) {
            ++outer;
            REQUIRE(c.gaussian[i] > 0);
            REQUIRE(c.gaussian[i] == Approx(1 / (r * (R + r))).epsilon(0.02));
        }
        if (std::abs(p.z()) < 1e-9 && rho < R) {
            ++inner;
            REQUIRE(c.gaussian[i] < 0);
            REQUIRE(c.gaussian[i] == Approx(-1 / (r * (R - r))).epsilon(0.02));
        }
        // k1 is the tube's curvature 1/r everywhere.
        REQUIRE(c.k1[i] == Approx(1 / r).epsilon(0.02));
    }
    REQUIRE(outer == 200);
    REQUIRE(inner == 200);
    REQUIRE(quantile(mean_error, 0.5) < 0.01);
    REQUIRE(quantile(mean_error, 0.95) < 0.02);
    REQUIRE(quantile(gaussian_error, 0.95) < 0.02 / (r * (R - r)));
    // Gauss-Bonnet: the total curvature of a torus is 2 pi chi = 0 (exact for the deficit).
    REQUIRE(std::abs(total_curvature(c)) < 1e-8);
}

TEST_CASE("Gauss-Bonnet: total curvature of a closed genus-0 mesh is 4 pi", "[curvature]") {
    const auto mesh = GENERATE(as<int>{}, 0, 1, 2, 3, 4);
    HalfedgeMesh m;
    switch (mesh) {
        case 0:
            m = sphere_of_radius(2.0);
            break;
        case 1:
            m = make_tetrahedron();
            break;
        case 2:
            m = make_cube();
            break;
        case 3:
            m = make_icosahedron();
            break;
        default:
            m = make_noisy_sphere(10, 0.2, 7);
            break;
    }
    INFO("mesh " << mesh);
    const VertexCurvatures c = compute_curvatures(m);
    for (Vertex v : m.vertices()) REQUIRE(c.valid[v.idx()] == 1);
    REQUIRE(total_curvature(c) == Approx(4 * kPi).epsilon(1e-10));
    // The mixed areas tile the surface exactly.
    double area = 0;
    for (double a : c.area) area += a;
    REQUIRE(area == Approx(surface_area(m)).epsilon(1e-10));
}

TEST_CASE("mean curvature matches the cotangent Laplacian of geometry.h", "[curvature]") {
    // A noisy sphere has obtuse triangles and negative cotangents: an independent check of
    // the per-face accumulation against cotangent_weight() and vertex_normal().
    const HalfedgeMesh m = make_noisy_sphere(10, 0.1, 3);
    const VertexCurvatures c = compute_curvatures(m);
    for (Vertex v : m.vertices()) {
        Vector3 laplace = Vector3::Zero();
        for (Halfedge h : m.halfedges_around(v))
            laplace += 2 * cotangent_weight(m, HalfedgeMesh::edge(h)) *
                       (m.position(v) - m.position(m.to_vertex(h)));
        const double h_abs = laplace.norm() / (4 * c.area[v.idx()]);
        const double sign = laplace.dot(vertex_normal(m, v)) < 0 ? -1.0 : 1.0;
        REQUIRE(c.mean[v.idx()] == Approx(sign * h_abs).epsilon(1e-9).margin(1e-12));
        REQUIRE(c.k1[v.idx()] >= c.k2[v.idx()]);
        REQUIRE(c.k1[v.idx()] + c.k2[v.idx()] == Approx(2 * c.mean[v.idx()]).margin(1e-9));
    }
}

TEST_CASE("compute_curvatures on a flat grid is exactly zero at interior vertices", "[curvature]") {
    // In the z = 0 plane, and moved to a general plane where rounding noise appears.
    const bool moved = GENERATE(false, true);
    HalfedgeMesh m = make_grid(12);
    if (moved) {
        const Eigen::Matrix3d rotation =
            Eigen::AngleAxisd(0.7, Vector3(1, 2, 3).normalized()).toRotationMatrix();
        for (Vertex v : m.vertices())
            m.position(v) = 5.0 * (rotation * m.position(v)) + Point(-3.1, 7.3, 0.2);
    }
    INFO("moved " << moved);
    const VertexCurvatures c = compute_curvatures(m);
    const double area = (moved ? 25.0 : 1.0) / (12 * 12);
    std::size_t interior = 0;
    for (Vertex v : m.vertices()) {
        const std::size_t i = v.idx();
        REQUIRE(c.valid[i] == (m.is_boundary(v) ? 0 : 1));
        if (!c.valid[i]) continue;
        ++interior;
        REQUIRE(c.mean[i] == 0);
        REQUIRE(c.gaussian[i] == 0);
        REQUIRE(c.k1[i] == 0);
        REQUIRE(c.k2[i] == 0);
        REQUIRE(c.shape_index[i] == 0);
        REQUIRE(c.area[i] == Approx(area));
    }
    REQUIRE(interior == 11 * 11);
    require_zero_where_invalid(c);
}

TEST_CASE("flipping the orientation flips the sign of H, k1, k2 and S but not K", "[curvature]") {
    const HalfedgeMesh m = make_noisy_sphere(8, 0.1, 5);
    const HalfedgeMesh f = flipped(m);
    REQUIRE(f.vertices_size() == m.vertices_size());
    const VertexCurvatures a = compute_curvatures(m), b = compute_curvatures(f);
    for (std::size_t i = 0; i < m.vertices_size(); ++i) {
        REQUIRE(b.valid[i] == a.valid[i]);
        REQUIRE(b.mean[i] == Approx(-a.mean[i]).margin(1e-12));
        REQUIRE(b.gaussian[i] == Approx(a.gaussian[i]).margin(1e-12));
        REQUIRE(b.k1[i] == Approx(-a.k2[i]).margin(1e-12));
        REQUIRE(b.k2[i] == Approx(-a.k1[i]).margin(1e-12));
        REQUIRE(b.shape_index[i] == Approx(-a.shape_index[i]).margin(1e-12));
    }
    // An inward-oriented sphere is a concave cup: H < 0, S = -1.
    const VertexCurvatures s = compute_curvatures(flipped(make_icosphere(6)));
    for (double h : valid_values(s, s.mean)) REQUIRE(h == Approx(-1.0).epsilon(0.01));
    for (double x : valid_values(s, s.shape_index)) REQUIRE(x == Approx(-1.0).margin(1e-3));
}

TEST_CASE("curvatures scale as 1/length and K as 1/length^2, S is scale invariant", "[curvature]") {
    HalfedgeMesh m = make_torus(40, 20, 1.0, 0.4);
    const VertexCurvatures a = compute_curvatures(m);
    for (Vertex v : m.vertices()) m.position(v) *= 3.0;
    const VertexCurvatures b = compute_curvatures(m);
    for (std::size_t i = 0; i < m.vertices_size(); ++i) {
        REQUIRE(b.mean[i] == Approx(a.mean[i] / 3).margin(1e-12));
        REQUIRE(b.gaussian[i] == Approx(a.gaussian[i] / 9).margin(1e-12));
        REQUIRE(b.shape_index[i] == Approx(a.shape_index[i]).margin(1e-9));
        REQUIRE(b.area[i] == Approx(a.area[i] * 9));
    }
}

TEST_CASE("degenerate triangles never give NaN or inf", "[curvature]") {
    SECTION("coincident and collinear corners inside a closed mesh") {
        PolygonSoup soup = to_soup(make_icosphere(4));
        LoadReport report;
        const HalfedgeMesh sphere = build_mesh(soup, report);
        // Vertex 0 moved onto a neighbour: the two faces of their edge lose all area.
        const Vertex a(0);
        const Vertex b = *sphere.vertices_around(a).begin();
        soup.positions[a.idx()] = soup.positions[b.idx()];
        // A face (c, d, e) made exactly collinear: all three on one line parallel to z.
        const Vertex c(100);
        const Halfedge h = sphere.halfedge(c);
        const Vertex d = sphere.to_vertex(h), e = sphere.to_vertex(sphere.next(h));
        soup.positions[c.idx()] = soup.positions[d.idx()] + Point(0, 0, 0.005);
        soup.positions[e.idx()] = soup.positions[d.idx()] + Point(0, 0, 0.01);
        const HalfedgeMesh m = build_mesh(soup, report);
        REQUIRE_VALID(m);
        std::size_t zero_area_faces = 0;
        for (Face f : m.faces()) zero_area_faces += face_area(m, f) == 0 ? 1 : 0;
        REQUIRE(zero_area_faces >= 3);
        const VertexCurvatures k = compute_curvatures(m);
        require_all_finite(k);
        require_zero_where_invalid(k);
        // Each degenerate face's angles still sum to pi, so Gauss-Bonnet stays exact.
        for (Vertex v : m.vertices()) REQUIRE(k.valid[v.idx()] == 1);
        REQUIRE(total_curvature(k) == Approx(4 * kPi).epsilon(1e-10));
    }
    SECTION("every face degenerate: no vertex has an area") {
        PolygonSoup soup = to_soup(make_tetrahedron());
        for (auto& p : soup.positions) p = Point(1, 2, 3);
        LoadReport report;
        const HalfedgeMesh m = build_mesh(soup, report);
        REQUIRE(m.n_faces() == 4);
        const VertexCurvatures k = compute_curvatures(m);
        for (Vertex v : m.vertices()) REQUIRE(k.valid[v.idx()] == 0);
        require_all_finite(k);
        require_zero_where_invalid(k);
    }
    SECTION("a collinear triangle, an isolated vertex and non-finite positions") {
        PolygonSoup soup;
        soup.positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {5, 5, 5}};
        soup.add_face({0, 1, 2});
        LoadReport report;
        HalfedgeMesh m = build_mesh(soup, report);
        VertexCurvatures k = compute_curvatures(m);
        for (Vertex v : m.vertices()) REQUIRE(k.valid[v.idx()] == 0);
        require_all_finite(k);
        require_zero_where_invalid(k);

        // NaN, and coordinates whose products overflow, on purpose: the curvatures find them
        // non-finite and mark the vertices invalid.
        const test::FpTrapsOff traps_off;
        HalfedgeMesh s = make_icosphere(3);
        s.position(Vertex(7)) = Point(std::nan(""), 0, 0);
        s.position(Vertex(20)) = Point(1e308, -1e308, 1e308);
        k = compute_curvatures(s);
        require_all_finite(k);
        require_zero_where_invalid(k);
        REQUIRE(k.valid[7] == 0);
        REQUIRE(k.valid[20] == 0);
    }
}

TEST_CASE("compute_curvatures on an empty mesh and skips deleted elements", "[curvature]") {
    const VertexCurvatures empty = compute_curvatures(HalfedgeMesh());
    REQUIRE(empty.valid.empty());
    REQUIRE(empty.mean.empty());
    REQUIRE(empty.area.empty());

    HalfedgeMesh m = make_icosphere(4);
    const Halfedge h = HalfedgeMesh::halfedge(Edge(10), 0);
    const Vertex removed = m.from_vertex(h);
    REQUIRE(m.is_collapse_ok(h));
    m.collapse(h);
    REQUIRE(m.has_garbage());
    const VertexCurvatures c = compute_curvatures(m);
    REQUIRE(c.valid.size() == m.vertices_size());
    require_all_finite(c);
    require_zero_where_invalid(c);
    REQUIRE(c.valid[removed.idx()] == 0);
    for (Vertex v : m.vertices()) REQUIRE(c.valid[v.idx()] == 1);
    REQUIRE(total_curvature(c) == Approx(4 * kPi).epsilon(1e-10));
}
