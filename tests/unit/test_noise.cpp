// Add noise: connectivity kept, displacements along the normals and within the bound,
// reproducible from the seed, bad amounts refused before anything moves.
#include <cmath>
#include <cstring>
#include <limits>

#include "core/algorithms/generators.h"
#include "core/algorithms/noise.h"
#include "core/errors.h"
#include "core/geometry.h"
#include "test_helpers.h"

using namespace trilab;

namespace {

bool bit_identical(const std::vector<Point>& a, const std::vector<Point>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(Point)) == 0;
}

HalfedgeMesh fixture(int which) {
    switch (which) {
        case 0:
            return make_icosphere(4);
        case 1:
            return make_torus(24, 12, 1.0, 0.3);
        case 2:
            return make_grid(8);  // open: boundary vertices move along their normals too
        default:
            return make_cylinder(16, 4);
    }
}

}  // namespace

TEST_CASE("add_noise moves vertices along their normals within the bound", "[noise]") {
    const int which = GENERATE(0, 1, 2, 3);
    const double amount = GENERATE(0.5, 2.0, 50.0);
    HalfedgeMesh mesh = fixture(which);
    const HalfedgeMesh original = mesh;
    const NoiseReport report = add_noise(mesh, NoiseOptions{amount, 7});
    REQUIRE_VALID(mesh);
    REQUIRE(mesh.n_vertices() == original.n_vertices());
    REQUIRE(mesh.n_edges() == original.n_edges());
    REQUIRE(mesh.n_faces() == original.n_faces());
    for (Face f : mesh.faces()) REQUIRE(mesh.face_vertices(f) == original.face_vertices(f));

    const double bound = amount / 100.0 * mean_edge_length(original);
    REQUIRE(report.mean_edge_length == Approx(mean_edge_length(original)));
    double largest = 0;
    for (Vertex v : mesh.vertices()) {
        const Vector3 d = mesh.position(v) - original.position(v);
        const Vector3 n = vertex_normal(original, v);
        REQUIRE(d.norm() <= bound * (1 + 1e-12));
        REQUIRE(d.cross(n).norm() <= 1e-12 * std::max(1.0, d.norm()));
        largest = std::max(largest, d.norm());
    }
    REQUIRE(report.max_displacement <= bound);
    REQUIRE(report.max_displacement == Approx(largest).epsilon(1e-9));
    REQUIRE(report.max_displacement > 0.5 * bound);  // a uniform draw over many vertices
    REQUIRE(report.moved_vertices == mesh.n_vertices());
}

TEST_CASE("add_noise is reproducible from the seed", "[noise]") {
    HalfedgeMesh a = make_default_model(), b = make_default_model(), c = make_default_model();
    add_noise(a, NoiseOptions{2.0, 42});
    add_noise(b, NoiseOptions{2.0, 42});
    add_noise(c, NoiseOptions{2.0, 43});
    REQUIRE(bit_identical(a.positions(), b.positions()));
    REQUIRE_FALSE(bit_identical(a.positions(), c.positions()));
    std::size_t differing = 0;
    for (Vertex v : a.vertices()) differing += a.position(v) != c.position(v);
    REQUIRE(differing > a.n_vertices() / 2);
}

TEST_CASE("add_noise gives the same offsets on every platform", "[noise]") {
    // The generator is ours (splitmix64 of seed << 32 ^ vertex index, hashed twice), so the
    // offsets are fixed numbers; these were computed independently of the C++ code.
    HalfedgeMesh m = make_icosahedron();
    const HalfedgeMesh original = m;
    const NoiseReport report = add_noise(m, NoiseOptions{10.0, 1});
    const double amplitude = 0.1 * report.mean_edge_length;
    const double expected[] = {0.4996649577431118, -0.034966945306206254, -0.3293551261528007,
                               0.7632256718603103};
    for (Index i = 0; i < 4; ++i) {
        const Vertex v(i);
        const double r = (m.position(v) - original.position(v)).dot(vertex_normal(original, v));
        REQUIRE(r / amplitude == Approx(expected[i]).margin(1e-12));
    }
}

TEST_CASE("add_noise with amount 0 changes nothing", "[noise]") {
    HalfedgeMesh m = make_default_model();
    const HalfedgeMesh original = m;
    const NoiseReport r = add_noise(m, NoiseOptions{0.0, 5});
    REQUIRE(bit_identical(m.positions(), original.positions()));
    REQUIRE(r.max_displacement == 0);
    REQUIRE(r.moved_vertices == 0);
}

TEST_CASE("add_noise refuses bad amounts, naming amount_percent, and leaves the mesh alone",
          "[noise]") {
    const double bad = GENERATE(-1.0, 2000.0, std::numeric_limits<double>::quiet_NaN(),
                                std::numeric_limits<double>::infinity(), 1000.0001);
    HalfedgeMesh m = make_icosphere(2);
    const HalfedgeMesh original = m;
    REQUIRE_THROWS_AS(add_noise(m, NoiseOptions{bad, 1}), InvalidArgument);
    REQUIRE_THROWS_WITH(add_noise(m, NoiseOptions{bad, 1}), Catch::Contains("amount_percent"));
    REQUIRE(bit_identical(m.positions(), original.positions()));
    // The upper limit itself is accepted.
    REQUIRE_NOTHROW(add_noise(m, NoiseOptions{kMaxNoiseAmountPercent, 1}));
}

TEST_CASE("add_noise leaves isolated vertices where they are", "[noise]") {
    HalfedgeMesh m = make_icosphere(2);
    const Vertex lonely = m.add_vertex(Point(3, 4, 5));
    const NoiseReport r = add_noise(m, NoiseOptions{5.0, 9});
    REQUIRE_VALID(m);
    REQUIRE(m.position(lonely) == Point(3, 4, 5));
    REQUIRE(r.moved_vertices == m.n_vertices() - 1);
}

TEST_CASE("add_noise refreshes a stored v:normal", "[noise]") {
    HalfedgeMesh m = make_icosphere(2);
    compute_vertex_normals(m);
    add_noise(m, NoiseOptions{20.0, 3});
    const auto stored = m.get_vertex_property<Vector3>("v:normal");
    REQUIRE(stored);
    for (Vertex v : m.vertices()) REQUIRE(stored[v] == vertex_normal(m, v));
}

namespace {

NoiseOptions gaussian(double k, std::uint32_t seed, NoiseDirection direction) {
    NoiseOptions o;
    o.distribution = NoiseDistribution::Gaussian;
    o.sigma = k;
    o.seed = seed;
    o.direction = direction;
    return o;
}

}  // namespace

TEST_CASE("Gaussian noise along the normals has the standard deviation asked for", "[noise]") {
    const double k = GENERATE(0.3, 0.7);
    HalfedgeMesh m = make_icosphere(16);  // 2,562 vertices
    const HalfedgeMesh original = m;
    const NoiseReport r = add_noise(m, gaussian(k, 5, NoiseDirection::Normal));
    REQUIRE_VALID(m);
    const double sigma = k * mean_edge_length(original);
    REQUIRE(r.scale == Approx(sigma));
    double sum = 0, sum2 = 0, largest = 0;
    std::size_t beyond_one = 0;
    for (Vertex v : m.vertices()) {
        const Vector3 d = m.position(v) - original.position(v);
        const Vector3 n = vertex_normal(original, v);
        REQUIRE(d.cross(n).norm() <= 1e-12 * std::max(1.0, d.norm()));
        const double x = d.dot(n) / sigma;
        sum += x;
        sum2 += x * x;
        beyond_one += std::abs(x) > 1;
        largest = std::max(largest, d.norm());
    }
    const double n = double(m.n_vertices());
    CHECK(std::abs(sum / n) < 0.1);                                // mean 0 (standard error 0.02)
    CHECK(std::sqrt(sum2 / n) == Approx(1.0).epsilon(0.06));       // standard deviation 1
    CHECK(double(beyond_one) / n == Approx(0.3173).margin(0.03));  // P(|x| > 1)
    CHECK(r.max_displacement == Approx(largest));
    CHECK(r.max_displacement > 2.5 * sigma);  // the tail of 2,562 draws
    CHECK(r.moved_vertices == m.n_vertices());
}

TEST_CASE("Gaussian noise in random directions: isotropic, the same from the same seed",
          "[noise]") {
    HalfedgeMesh m = make_icosphere(16), again = m, other = m;
    const HalfedgeMesh original = m;
    add_noise(m, gaussian(0.5, 9, NoiseDirection::Random));
    add_noise(again, gaussian(0.5, 9, NoiseDirection::Random));
    add_noise(other, gaussian(0.5, 10, NoiseDirection::Random));
    REQUIRE(bit_identical(m.positions(), again.positions()));
    REQUIRE_FALSE(bit_identical(m.positions(), other.positions()));
    const double sigma = 0.5 * mean_edge_length(original);
    Vector3 mean_direction = Vector3::Zero();
    double mean_cos = 0, sum2 = 0;
    for (Vertex v : m.vertices()) {
        const Vector3 d = m.position(v) - original.position(v);
        REQUIRE(d.norm() > 0);
        mean_direction += d.normalized();
        mean_cos += std::abs(d.normalized().dot(vertex_normal(original, v)));
        sum2 += d.squaredNorm() / (sigma * sigma);
    }
    const double n = double(m.n_vertices());
    CHECK((mean_direction / n).norm() < 0.06);        // no preferred direction
    CHECK(mean_cos / n == Approx(0.5).margin(0.03));  // E|cos| on the sphere is 1/2
    CHECK(std::sqrt(sum2 / n) == Approx(1.0).epsilon(0.06));
}

TEST_CASE("add_noise refuses a bad sigma, naming it, and leaves the mesh alone", "[noise]") {
    const double bad = GENERATE(-0.1, 10.5, std::numeric_limits<double>::quiet_NaN(),
                                std::numeric_limits<double>::infinity());
    HalfedgeMesh m = make_icosphere(2);
    const HalfedgeMesh original = m;
    NoiseOptions o = gaussian(bad, 1, NoiseDirection::Normal);
    REQUIRE_THROWS_WITH(add_noise(m, o), Catch::Contains("sigma"));
    REQUIRE(bit_identical(m.positions(), original.positions()));
    o.sigma = 0;  // nothing moves
    const NoiseReport r = add_noise(m, o);
    REQUIRE(r.moved_vertices == 0);
    REQUIRE(bit_identical(m.positions(), original.positions()));
}
