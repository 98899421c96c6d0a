// Texture-coordinate projections: planar (PCA) is a similarity of the plane of a flat mesh,
// spherical has v monotone in z, everything lands in [0, 1]^2, and the attribute is created
// or overwritten.
#include <algorithm>
#include <cmath>
#include <limits>

#include "core/algorithms/generators.h"
#include "core/algorithms/texcoords.h"
#include "core/errors.h"
#include "test_helpers.h"

using namespace trilab;
using namespace trilab::test;
using Catch::Matchers::Contains;

namespace {

const double kPi = std::acos(-1.0);

std::vector<Vertex> live_vertices(const HalfedgeMesh& m) {
    std::vector<Vertex> vs;
    for (Vertex v : m.vertices()) vs.push_back(v);
    return vs;
}

void require_unit_square(const HalfedgeMesh& m) {
    const auto uv = m.get_vertex_property<TexCoord>("v:texcoord");
    REQUIRE(uv);
    for (Vertex v : m.vertices()) {
        INFO("vertex " << v.idx() << " uv " << uv[v].transpose());
        REQUIRE(uv[v].allFinite());
        REQUIRE(uv[v].minCoeff() >= 0.0);
        REQUIRE(uv[v].maxCoeff() <= 1.0);
    }
}

/// Asserts |uv(a) - uv(b)| = scale |p(a) - p(b)| for all vertex pairs with one scale;
/// returns that scale.
double require_similarity(const HalfedgeMesh& m) {
    const auto uv = m.get_vertex_property<TexCoord>("v:texcoord");
    std::vector<Vertex> vs = live_vertices(m);
    double scale = -1;
    for (std::size_t i = 0; i < vs.size(); ++i)
        for (std::size_t j = i + 1; j < vs.size(); ++j) {
            const double d3 = (m.position(vs[i]) - m.position(vs[j])).norm();
            const double d2 = (uv[vs[i]] - uv[vs[j]]).norm();
            if (scale < 0) scale = d2 / d3;
            REQUIRE(d2 == Approx(scale * d3).margin(1e-12));
        }
    return scale;
}

/// The extent of the coordinates along u and v.
TexCoord uv_extent(const HalfedgeMesh& m) {
    const auto uv = m.get_vertex_property<TexCoord>("v:texcoord");
    TexCoord lo = TexCoord::Constant(1e9), hi = TexCoord::Constant(-1e9);
    for (Vertex v : m.vertices()) {
        lo = lo.cwiseMin(uv[v]);
        hi = hi.cwiseMax(uv[v]);
    }
    REQUIRE(lo.x() == Approx(0.0).margin(1e-12));
    REQUIRE(lo.y() == Approx(0.0).margin(1e-12));
    return hi - lo;
}

}  // namespace

TEST_CASE("has_texcoords sees vertex and corner coordinates", "[texcoords]") {
    HalfedgeMesh m = make_icosphere(2);
    REQUIRE_FALSE(has_texcoords(m));
    project_texcoords(m, TexCoordProjection::Planar);
    REQUIRE(has_texcoords(m));
    m.remove_vertex_property("v:texcoord");
    REQUIRE_FALSE(has_texcoords(m));
    m.add_halfedge_property<TexCoord>("h:texcoord");
    REQUIRE(has_texcoords(m));
}

TEST_CASE("planar texcoords of a grid are its x and y", "[texcoords]") {
    HalfedgeMesh m = make_grid(8);
    project_texcoords(m, TexCoordProjection::Planar);
    require_unit_square(m);
    // A similarity in general; the grid is axis-aligned, so exactly (x, y).
    REQUIRE(require_similarity(m) == Approx(1.0));
    const auto uv = m.get_vertex_property<TexCoord>("v:texcoord");
    for (Vertex v : m.vertices()) {
        REQUIRE(uv[v].x() == Approx(m.position(v).x()).margin(1e-12));
        REQUIRE(uv[v].y() == Approx(m.position(v).y()).margin(1e-12));
    }
    REQUIRE_VALID(m);
}

TEST_CASE("planar texcoords of a tilted rectangle keep distances and the aspect ratio",
          "[texcoords]") {
    // A 2 x 1 grid rotated about a skew axis and moved: the map must be a similarity, the
    // long side must span [0, 1] and the short side [0, 0.5].
    HalfedgeMesh m = make_grid(6);
    const Eigen::Matrix3d r =
        Eigen::AngleAxisd(0.7, Vector3(1, 2, 3).normalized()).toRotationMatrix();
    for (Vertex v : m.vertices()) {
        Point& p = m.position(v);
        p = r * Point(3.0 * p.x(), 1.5 * p.y(), 0.0) + Point(5, -2, 1);
    }
    project_texcoords(m, TexCoordProjection::Planar);
    require_unit_square(m);
    REQUIRE(require_similarity(m) == Approx(1.0 / 3.0));
    const TexCoord extent = uv_extent(m);
    REQUIRE(extent.x() == Approx(1.0));
    REQUIRE(extent.y() == Approx(0.5));
}

TEST_CASE("planar texcoords of a curved mesh stay in the unit square", "[texcoords]") {
    for (HalfedgeMesh m : {make_icosphere(3), make_torus(24, 12, 2.0, 0.5), make_cylinder(16, 4),
                           make_noisy_sphere(4, 0.1, 3)}) {
        project_texcoords(m, TexCoordProjection::Planar);
        require_unit_square(m);
        const TexCoord extent = uv_extent(m);
        REQUIRE(extent.maxCoeff() == Approx(1.0));
    }
}

TEST_CASE("spherical texcoords: v grows with y (up), u with longitude", "[texcoords]") {
    HalfedgeMesh m = make_icosphere(6);
    project_texcoords(m, TexCoordProjection::Spherical);
    require_unit_square(m);
    const auto uv = m.get_vertex_property<TexCoord>("v:texcoord");
    std::vector<Vertex> vs = live_vertices(m);
    std::sort(vs.begin(), vs.end(),
              [&](Vertex a, Vertex b) { return m.position(a).y() < m.position(b).y(); });
    for (std::size_t i = 1; i < vs.size(); ++i) {
        REQUIRE(uv[vs[i]].y() >= uv[vs[i - 1]].y() - 1e-12);
        if (m.position(vs[i]).y() > m.position(vs[i - 1]).y() + 1e-9)
            REQUIRE(uv[vs[i]].y() > uv[vs[i - 1]].y());
    }
    for (Vertex v : m.vertices()) {
        const Point& p = m.position(v);
        REQUIRE(uv[v].y() ==
                Approx(std::asin(std::clamp(p.y(), -1.0, 1.0)) / kPi + 0.5).margin(1e-9));
        if (std::hypot(p.z(), p.x()) > 1e-6)
            REQUIRE(uv[v].x() == Approx(std::atan2(p.x(), p.z()) / (2 * kPi) + 0.5).margin(1e-9));
    }
}

TEST_CASE("spherical texcoords with +z up: the poles on the z axis, the seam at the back (+y)",
          "[texcoords]") {
    // The octahedron has a vertex on each axis: the poles are the vertices on the up axis.
    for (const UpAxis up : {UpAxis::Y, UpAxis::Z}) {
        HalfedgeMesh m = make_octahedron();
        project_texcoords(m, TexCoordProjection::Spherical, up);
        const auto uv = m.get_vertex_property<TexCoord>("v:texcoord");
        const Vector3 axis = up_vector(up);
        for (Vertex v : m.vertices()) {
            const Point p = m.position(v).normalized();
            INFO("up " << up_axis_name(up) << ", vertex " << p.transpose());
            if (p.dot(axis) > 0.99)
                REQUIRE(uv[v].y() == Approx(1.0).margin(1e-12));  // the north pole
            else if (p.dot(axis) < -0.99)
                REQUIRE(uv[v].y() == Approx(0.0).margin(1e-12));
            else
                REQUIRE(uv[v].y() == Approx(0.5).margin(1e-12));  // the equator
        }
    }
    // On a sphere: v = latitude above the xy plane, u = longitude from the front (-y).
    HalfedgeMesh m = make_icosphere(6);
    project_texcoords(m, TexCoordProjection::Spherical, UpAxis::Z);
    require_unit_square(m);
    const auto uv = m.get_vertex_property<TexCoord>("v:texcoord");
    for (Vertex v : m.vertices()) {
        const Point& p = m.position(v);
        REQUIRE(uv[v].y() ==
                Approx(std::asin(std::clamp(p.z(), -1.0, 1.0)) / kPi + 0.5).margin(1e-9));
        if (std::hypot(p.x(), p.y()) > 1e-6)
            REQUIRE(uv[v].x() == Approx(std::atan2(p.x(), -p.y()) / (2 * kPi) + 0.5).margin(1e-9));
        // The front (-y) is the middle of the texture; the seam (u = 0 or 1) is at +y.
        if (p.y() < -0.99) REQUIRE(std::abs(uv[v].x() - 0.5) < 0.05);
    }
    REQUIRE(parse_up_axis("+z") == UpAxis::Z);
    REQUIRE(parse_up_axis("y") == UpAxis::Y);
    REQUIRE_THROWS_WITH(parse_up_axis("x", "--up"), Contains("--up") && Contains("y or z"));
}

TEST_CASE("isolated vertices get texcoords too", "[texcoords]") {
    HalfedgeMesh m = make_grid(4);
    const Vertex iso = m.add_vertex(Point(2, 0.5, 0));
    project_texcoords(m, TexCoordProjection::Planar);
    require_unit_square(m);
    const auto uv = m.get_vertex_property<TexCoord>("v:texcoord");
    // The x extent is now 2: the isolated vertex is at the far end of u.
    REQUIRE(uv[iso].x() == Approx(1.0));
    REQUIRE(uv[iso].y() == Approx(0.25));
    REQUIRE(require_similarity(m) == Approx(0.5));

    HalfedgeMesh s = make_icosphere(3);
    const Vertex top = s.add_vertex(Point(0, 5, 0));  // above the north pole (y is up)
    project_texcoords(s, TexCoordProjection::Spherical);
    require_unit_square(s);
    REQUIRE(s.get_vertex_property<TexCoord>("v:texcoord")[top].y() == Approx(1.0).margin(1e-2));
}

TEST_CASE("project_texcoords overwrites existing coordinates", "[texcoords]") {
    HalfedgeMesh m = make_icosphere(3);
    project_texcoords(m, TexCoordProjection::Planar);
    const auto names = m.vertex_property_names();
    const auto planar = m.get_vertex_property<TexCoord>("v:texcoord").vector();
    project_texcoords(m, TexCoordProjection::Spherical);
    REQUIRE(m.vertex_property_names() == names);
    REQUIRE(m.get_vertex_property<TexCoord>("v:texcoord").vector() != planar);
    require_unit_square(m);

    // A "v:texcoord" of another type is replaced by one of the right type.
    HalfedgeMesh g = make_grid(2);
    g.add_vertex_property<float>("v:texcoord", 7.0f);
    REQUIRE_FALSE(has_texcoords(g));
    project_texcoords(g, TexCoordProjection::Planar);
    REQUIRE_FALSE(g.get_vertex_property<float>("v:texcoord"));
    require_unit_square(g);
}

TEST_CASE("project_texcoords skips deleted vertices and refuses non-finite positions",
          "[texcoords]") {
    HalfedgeMesh m = make_icosphere(3);
    for (Edge e : m.edges()) {
        const Halfedge h = HalfedgeMesh::halfedge(e, 0);
        if (m.is_collapse_ok(h)) {
            m.collapse(h);
            break;
        }
    }
    REQUIRE(m.has_garbage());
    project_texcoords(m, TexCoordProjection::Spherical);
    require_unit_square(m);

    HalfedgeMesh bad = make_grid(2);
    bad.position(Vertex(3)) = Point(std::numeric_limits<double>::quiet_NaN(), 0, 0);
    REQUIRE_THROWS_WITH(project_texcoords(bad, TexCoordProjection::Planar),
                        Contains("project_texcoords") && Contains("vertex 3"));
    REQUIRE_FALSE(has_texcoords(bad));
}

TEST_CASE("project_texcoords handles tiny meshes", "[texcoords]") {
    HalfedgeMesh one;
    one.add_vertex(Point(1, 2, 3));
    for (auto p : {TexCoordProjection::Planar, TexCoordProjection::Spherical}) {
        project_texcoords(one, p);
        require_unit_square(one);
    }
    HalfedgeMesh empty;
    project_texcoords(empty, TexCoordProjection::Planar);
    REQUIRE(has_texcoords(empty));
}
