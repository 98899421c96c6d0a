// Decimation: validity and topology after every iteration (closed and open meshes), the
// floor(P/100 V) rule, the normal-flip guarantee per collapse, the tetrahedron's limit, the
// progressive mesh (splits give back the original connectivity), the geomorph, quality on a
// sphere and a cube, texture coordinates and seams, constraints, bad options.
#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <vector>

#include "app/ops/operation.h"
#include "core/algorithms/decimation.h"
#include "core/algorithms/generators.h"
#include "core/algorithms/level_of_detail.h"
#include "core/algorithms/mesh_distance.h"
#include "core/algorithms/mesh_stats.h"
#include "core/algorithms/morph.h"
#include "core/algorithms/quadric.h"
#include "core/errors.h"
#include "core/geometry.h"
#include "core/io/mesh_io.h"
#include "core/mesh_builder.h"
#include "test_helpers.h"

using namespace trilab;

namespace {

/// The surface of the cube [0,1]^3 with an n x n grid of squares (two triangles each) on
/// every side, vertices shared along the cube's edges, outward orientation.
HalfedgeMesh make_fine_cube(int n) {
    PolygonSoup soup;
    std::map<std::array<int, 3>, Index> index;
    const auto vertex = [&](int x, int y, int z) {
        const std::array<int, 3> key{x, y, z};
        auto it = index.find(key);
        if (it != index.end()) return it->second;
        const Index i = Index(soup.positions.size());
        soup.positions.emplace_back(double(x) / n, double(y) / n, double(z) / n);
        index.emplace(key, i);
        return i;
    };
    // For each axis and side: a grid in the two other axes, oriented outward.
    for (int axis = 0; axis < 3; ++axis) {
        for (int side = 0; side < 2; ++side) {
            const int u_axis = (axis + 1) % 3, v_axis = (axis + 2) % 3;
            for (int i = 0; i < n; ++i) {
                for (int j = 0; j < n; ++j) {
                    Index q[4];
                    const int du[4] = {0, 1, 1, 0}, dv[4] = {0, 0, 1, 1};
                    for (int k = 0; k < 4; ++k) {
                        int c[3];
                        c[axis] = side * n;
                        c[u_axis] = i + du[k];
                        c[v_axis] = j + dv[k];
                        q[k] = vertex(c[0], c[1], c[2]);
                    }
                    if (side == 1) {
                        soup.add_face({q[0], q[1], q[2]});
                        soup.add_face({q[0], q[2], q[3]});
                    } else {
                        soup.add_face({q[0], q[2], q[1]});
                        soup.add_face({q[0], q[3], q[2]});
                    }
                }
            }
        }
    }
    LoadReport report;
    return build_mesh(soup, report);
}

DecimationOptions percent_options(DecimationCost cost, double percent, int iterations) {
    DecimationOptions o;
    o.cost = cost;
    o.percent = percent;
    o.iterations = iterations;
    return o;
}

Vector3 triangle_normal(const std::vector<Point>& x, const std::array<Index, 3>& c) {
    return (x[c[1]] - x[c[0]]).cross(x[c[2]] - x[c[0]]);
}

}  // namespace

TEST_CASE("normalized_roundness is 1 for equilateral and 0 for degenerate triangles",
          "[decimation]") {
    const Point a(0, 0, 0), b(1, 0, 0), c(0.5, std::sqrt(3.0) / 2, 0);
    CHECK(normalized_roundness(a, b, c) == Approx(1.0));
    CHECK(normalized_roundness(a, b, Point(2, 0, 0)) == 0.0);
    CHECK(normalized_roundness(a, a, c) == 0.0);
    // A right isosceles triangle: circumradius sqrt(2)/2, shortest edge 1.
    CHECK(normalized_roundness(a, b, Point(0, 1, 0)) ==
          Approx(std::sqrt(1.0 / 3.0) / (std::sqrt(2.0) / 2)));
    // Thinner triangles are less round.
    CHECK(normalized_roundness(a, b, Point(0.5, 0.1, 0)) <
          normalized_roundness(a, b, Point(0.5, 0.5, 0)));
}

TEST_CASE("Quadric measures squared plane distances and finds the corner of three planes",
          "[decimation]") {
    Quadric q = Quadric::plane(Vector3(1, 0, 0), Point(1, 0, 0));
    CHECK(q(Point(3, 5, 7)) == Approx(4.0));
    Point x(9, 9, 9);
    CHECK_FALSE(q.optimize(x));  // one plane: no unique minimum
    CHECK(x == Point(9, 9, 9));
    q += Quadric::plane(Vector3(0, 1, 0), Point(0, 2, 0));
    q += Quadric::plane(Vector3(0, 0, 1), Point(0, 0, -3), 2.0);
    REQUIRE(q.optimize(x));
    CHECK((x - Point(1, 2, -3)).norm() < 1e-12);
    CHECK(q(x) == Approx(0.0).margin(1e-12));
    CHECK(q(Point(1, 2, -2)) == Approx(2.0));
}

TEST_CASE("decimate follows the floor(P/100 V) rule and keeps closed meshes valid",
          "[decimation]") {
    const HalfedgeMesh sphere = make_icosphere(12);  // 1442 vertices
    const DecimationCost cost = GENERATE(DecimationCost::Quadric, DecimationCost::Roundness);
    const double percent = cost == DecimationCost::Quadric ? 60.0 : 30.0;
    DecimationOptions o = percent_options(cost, percent, 4);
    o.normal_flip = false;
    const DecimationResult r = decimate(sphere, o);
    INFO(decimation_cost_name(cost) << ": " << r.report.stop_message);
    REQUIRE(r.levels.size() == 4);
    CHECK(r.report.stop == DecimationStop::Done);
    std::size_t v = sphere.n_vertices();
    const MeshStats before = compute_stats(sphere);
    const HalfedgeMesh* previous = &sphere;
    for (const DecimationLevel& level : r.levels) {
        const std::size_t expected = v - std::size_t(std::floor(percent / 100.0 * double(v)));
        CHECK(level.mesh.n_vertices() == expected);
        CHECK_FALSE(level.mesh.has_garbage());
        REQUIRE_VALID(level.mesh);
        const MeshStats s = compute_stats(level.mesh);
        CHECK(s.euler == before.euler);
        CHECK(s.boundary_loops == 0);
        CHECK(s.components == 1);
        CHECK_NOTHROW(check_correspondence(*previous, level.mesh, level.correspondence));
        previous = &level.mesh;
        v = expected;
    }
    CHECK(r.report.output_vertices == r.levels.back().mesh.n_vertices());
    CHECK(r.report.collapses == sphere.n_vertices() - r.report.output_vertices);
}

TEST_CASE("decimate keeps boundary loops, genus and components on open and toroidal meshes",
          "[decimation]") {
    const HalfedgeMesh mesh =
        GENERATE(make_grid(20), make_cylinder(24, 12), make_torus(24, 12, 1.0, 0.3));
    const DecimationCost cost = GENERATE(DecimationCost::Quadric, DecimationCost::Roundness);
    const MeshStats before = compute_stats(mesh);
    DecimationOptions o;
    o.cost = cost;
    o.target_vertices = 12;  // far below what the topology allows
    const DecimationResult r = decimate(mesh, o);
    REQUIRE_FALSE(r.levels.empty());
    const HalfedgeMesh& out = r.levels.back().mesh;
    REQUIRE_VALID(out);
    const MeshStats after = compute_stats(out);
    CHECK(after.boundary_loops == before.boundary_loops);
    CHECK(after.genus == before.genus);
    CHECK(after.euler == before.euler);
    CHECK(after.components == before.components);
    CHECK(out.n_vertices() < mesh.n_vertices() / 2);
}

TEST_CASE("decimate keeps a grid's boundary on its square", "[decimation]") {
    const HalfedgeMesh grid = make_grid(16);
    DecimationOptions o;
    o.target_vertices = 30;
    const DecimationResult r = decimate(grid, o);
    REQUIRE_FALSE(r.levels.empty());
    const HalfedgeMesh& out = r.levels.back().mesh;
    REQUIRE_VALID(out);
    for (Vertex v : out.vertices()) {
        const Point& p = out.position(v);
        CHECK(std::abs(p.z()) < 1e-9);
        if (out.is_boundary(v)) {
            const double d = std::min({p.x(), 1 - p.x(), p.y(), 1 - p.y()});
            CHECK(std::abs(d) < 1e-6);
        }
    }
    // The four corners survive.
    std::size_t corners = 0;
    for (Vertex v : out.vertices()) {
        const Point& p = out.position(v);
        if ((std::abs(p.x()) < 1e-9 || std::abs(p.x() - 1) < 1e-9) &&
            (std::abs(p.y()) < 1e-9 || std::abs(p.y() - 1) < 1e-9))
            ++corners;
    }
    CHECK(corners == 4);
}

TEST_CASE("a tetrahedron cannot go below 4 vertices and the report says why", "[decimation]") {
    const HalfedgeMesh tet = make_tetrahedron();
    DecimationOptions o;
    o.target_vertices = 2;
    const DecimationResult r = decimate(tet, o);
    CHECK(r.levels.empty());
    CHECK(r.report.output_vertices == 4);
    CHECK(r.report.stop == DecimationStop::Topology);
    CHECK(r.report.refused_topology > 0);
    CHECK(r.report.stop_message.find("4 vertices") != std::string::npos);
    // An octahedron goes down to a tetrahedron and no further.
    const DecimationResult oct = decimate(make_octahedron(), o);
    REQUIRE(oct.levels.size() == 1);
    CHECK(oct.levels[0].mesh.n_vertices() == 4);
    REQUIRE_VALID(oct.levels[0].mesh);
}

TEST_CASE("with the normal-flip constraint no collapse turns a face further than its angle",
          "[decimation]") {
    const HalfedgeMesh mesh = make_noisy_sphere(10, 0.2, 3);
    const double angle = GENERATE(20.0, 45.0, 90.0);
    DecimationOptions o = percent_options(DecimationCost::Quadric, 50, 3);
    o.record_progressive = true;
    o.normal_flip = true;
    o.max_normal_angle = angle;
    const DecimationResult r = decimate(mesh, o);
    REQUIRE_FALSE(r.levels.empty());
    for (const auto& level : r.levels) REQUIRE_VALID(level.mesh);
    // Replay the collapses one by one and compare the normal of every face at the kept vertex
    // (v0's moved faces and v1's own: the faces the collapse changes).
    LevelOfDetail lod(r.progressive);
    const double cos_max = std::cos(angle * M_PI / 180.0);
    double worst = 1;
    for (std::size_t k = 0; k < r.progressive.collapses.size(); ++k) {
        const std::vector<Point> x0 = lod.positions();
        const auto faces0 = lod.faces();
        lod.set_level(k + 1);
        const VertexSplit& s = r.progressive.collapses[k];
        for (std::uint32_t i = s.moved_begin; i < s.ring_end; ++i) {
            const Index f = lod.face_of(r.progressive.ring_faces[i].idx());
            const Vector3 a = triangle_normal(x0, faces0[f]);
            const Vector3 b = triangle_normal(lod.positions(), lod.faces()[f]);
            worst = std::min(worst, a.normalized().dot(b.normalized()));
        }
    }
    INFO("angle " << angle << ", worst cosine " << worst);
    CHECK(worst >= cos_max - 1e-9);
    if (angle < 30) CHECK(r.report.refused_normal_flip > 0);
}

TEST_CASE("the progressive mesh replays to the decimated mesh and splits back to the original",
          "[decimation]") {
    const HalfedgeMesh mesh = make_noisy_sphere(8, 0.1, 5);
    DecimationOptions o = percent_options(DecimationCost::Quadric, 60, 3);
    o.record_progressive = true;
    const DecimationResult r = decimate(mesh, o);
    REQUIRE(r.levels.size() == 3);
    const ProgressiveMesh& pm = r.progressive;
    CHECK(pm.collapses.size() == r.report.collapses);
    LevelOfDetail lod(pm);
    const auto original = lod.faces();
    lod.set_level(pm.collapses.size());
    const HalfedgeMesh coarse = lod.mesh();
    REQUIRE_VALID(coarse);
    const HalfedgeMesh& out = r.levels.back().mesh;
    CHECK(coarse.n_vertices() == out.n_vertices());
    CHECK(coarse.n_faces() == out.n_faces());
    // Same positions in the same order (garbage collection and the LOD both keep the order).
    for (Vertex v : out.vertices()) CHECK((coarse.position(v) - out.position(v)).norm() < 1e-12);
    // Same triangles.
    std::set<std::array<Index, 3>> a, b;
    for (Face f : out.faces()) {
        auto c = out.face_vertices(f);
        std::array<Index, 3> t{c[0].idx(), c[1].idx(), c[2].idx()};
        std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
        a.insert(t);
    }
    for (Face f : coarse.faces()) {
        auto c = coarse.face_vertices(f);
        std::array<Index, 3> t{c[0].idx(), c[1].idx(), c[2].idx()};
        std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
        b.insert(t);
    }
    CHECK(a == b);
    // Splits all the way back: the original connectivity and positions.
    lod.set_level(0);
    CHECK(lod.faces() == original);
    const HalfedgeMesh fine = lod.mesh();
    REQUIRE_VALID(fine);
    CHECK(fine.n_faces() == mesh.n_faces());
    for (Vertex v : mesh.vertices()) CHECK(fine.position(v) == mesh.position(v));
    // Any level in between is a valid mesh too.
    lod.set_level(pm.collapses.size() / 3);
    REQUIRE_VALID(lod.mesh());
    CHECK(lod.mesh().n_vertices() == mesh.n_vertices() - pm.collapses.size() / 3);
}

TEST_CASE("the decimation geomorph starts at the fine shape and ends at the coarse one",
          "[decimation]") {
    const HalfedgeMesh mesh = make_noisy_sphere(8, 0.1, 9);
    const DecimationResult r = decimate(mesh, percent_options(DecimationCost::Quadric, 60, 2));
    REQUIRE(r.levels.size() == 2);
    const HalfedgeMesh* before = &mesh;
    for (const DecimationLevel& level : r.levels) {
        const MorphCorrespondence& c = level.correspondence;
        CHECK(c.kind == MorphCorrespondence::Kind::ToLater);
        const MorphFrame start = morph_frame(*before, level.mesh, c, 0.0);
        CHECK(start.topology == before);
        for (Vertex v : before->vertices()) CHECK(start.positions[v.idx()] == before->position(v));
        const MorphFrame end = morph_frame(*before, level.mesh, c, 1.0);
        CHECK(end.topology == &level.mesh);
        // Just before the end the fine mesh sits on the coarse mesh's vertices: every end
        // position is one of them.
        std::set<std::array<double, 3>> coarse;
        for (Vertex v : level.mesh.vertices()) {
            const Point& p = level.mesh.position(v);
            coarse.insert({p.x(), p.y(), p.z()});
        }
        for (Vertex v : before->vertices()) {
            const Point& p = c.positions[v.idx()];
            CHECK(coarse.count({p.x(), p.y(), p.z()}) == 1);
        }
        before = &level.mesh;
    }
}

TEST_CASE("quadric decimation of a finely tessellated cube keeps exactly its corners",
          "[decimation]") {
    const HalfedgeMesh cube = make_fine_cube(6);
    REQUIRE_VALID(cube);
    DecimationOptions o;
    o.target_vertices = 8;
    const DecimationResult r = decimate(cube, o);
    INFO(r.report.stop_message);
    REQUIRE_FALSE(r.levels.empty());
    const HalfedgeMesh& out = r.levels.back().mesh;
    REQUIRE_VALID(out);
    CHECK(out.n_vertices() == 8);
    CHECK(out.n_faces() == 12);
    for (Vertex v : out.vertices()) {
        const Point& p = out.position(v);
        for (int i = 0; i < 3; ++i) CHECK(std::min(std::abs(p[i]), std::abs(p[i] - 1)) < 1e-9);
    }
    const MeshDistance d = mesh_distance(cube, out, {20000});
    CHECK(d.hausdorff < 1e-9);
    CHECK(volume(out) == Approx(1.0).epsilon(1e-9));
}

TEST_CASE("quadric decimation of a sphere stays close to it", "[decimation]") {
    const HalfedgeMesh sphere = make_icosphere(16);  // 2562 vertices
    DecimationOptions o;
    o.target_vertices = sphere.n_vertices() / 10;
    const DecimationResult r = decimate(sphere, o);
    REQUIRE(r.levels.size() == 1);
    const HalfedgeMesh& out = r.levels[0].mesh;
    REQUIRE_VALID(out);
    CHECK(out.n_vertices() == o.target_vertices);
    const MeshDistance d = mesh_distance(sphere, out, {50000});
    INFO("Hausdorff " << d.hausdorff << ", RMS " << d.rms << ", diagonal " << d.diagonal);
    // 256 vertices on a unit sphere: triangles of edge ~0.25 have a sagitta of about 0.01.
    CHECK(d.hausdorff < 0.02);
    CHECK(d.rms < 0.006);
    CHECK(d.rms < d.hausdorff);
    // Roundness (no repositioning) is worse but still near.
    o.cost = DecimationCost::Roundness;
    const DecimationResult rr = decimate(sphere, o);
    REQUIRE(rr.levels.size() == 1);
    const MeshDistance dr = mesh_distance(sphere, rr.levels[0].mesh, {50000});
    CHECK(dr.hausdorff < 0.1);
}

TEST_CASE("vertex texture coordinates are carried and per-corner seams stay closed",
          "[decimation]") {
    SECTION("v:texcoord") {
        const HalfedgeMesh sphere = test::attributed_sphere();
        DecimationOptions o;
        o.target_vertices = 60;
        const DecimationResult r = decimate(sphere, o);
        REQUIRE_FALSE(r.levels.empty());
        const HalfedgeMesh& out = r.levels.back().mesh;
        REQUIRE_VALID(out);
        auto uv = out.get_vertex_property<TexCoord>("v:texcoord");
        REQUIRE(uv);
        // uv was 0.5 + 0.5 x, 0.25 + 0.5 y on the unit sphere: interpolation keeps it close.
        for (Vertex v : out.vertices()) {
            CHECK(uv[v].x() == Approx(0.5 + 0.5 * out.position(v).x()).margin(0.1));
            CHECK(uv[v].y() == Approx(0.25 + 0.5 * out.position(v).y()).margin(0.1));
        }
    }
    SECTION("h:texcoord with a seam down the middle") {
        HalfedgeMesh grid = make_grid(16);
        auto huv = grid.halfedge_property<TexCoord>("h:texcoord");
        for (Face f : grid.faces()) {
            const double side = face_centroid(grid, f).x() < 0.5 ? 0.0 : 10.0;
            for (Halfedge h : grid.halfedges_of(f)) {
                const Point& p = grid.position(grid.to_vertex(h));
                huv[h] = TexCoord(p.x() + side, p.y());
            }
        }
        DecimationOptions o;
        o.target_vertices = 20;
        const DecimationResult r = decimate(grid, o);
        REQUIRE_FALSE(r.levels.empty());
        const HalfedgeMesh& out = r.levels.back().mesh;
        REQUIRE_VALID(out);
        auto uv = out.get_halfedge_property<TexCoord>("h:texcoord");
        REQUIRE(uv);
        std::size_t seam_vertices = 0;
        for (Face f : out.faces()) {
            // Every face lies on one side of the seam, and its uvs say the same side.
            const double cx = face_centroid(out, f).x();
            for (Halfedge h : out.halfedges_of(f)) {
                CHECK((uv[h].x() >= 5.0) == (cx >= 0.5));
                const Point& p = out.position(out.to_vertex(h));
                CHECK(uv[h].x() - (cx >= 0.5 ? 10.0 : 0.0) == Approx(p.x()).margin(1e-9));
            }
        }
        for (Vertex v : out.vertices())
            if (std::abs(out.position(v).x() - 0.5) < 1e-12) ++seam_vertices;
        CHECK(seam_vertices == 17);  // the seam's vertices are never removed
    }
}

TEST_CASE("binary constraints stop decimation early and say why", "[decimation]") {
    const HalfedgeMesh sphere = make_icosphere(8);
    SECTION("independent set: one iteration removes at most a fraction") {
        DecimationOptions o = percent_options(DecimationCost::Quadric, 90, 1);
        o.independent_set = true;
        o.record_progressive = true;
        const DecimationResult r = decimate(sphere, o);
        CHECK(r.report.stop == DecimationStop::Constraints);
        CHECK(r.report.refused_independent_set > 0);
        REQUIRE(r.levels.size() == 1);
        REQUIRE_VALID(r.levels[0].mesh);
        CHECK(r.levels[0].mesh.n_vertices() > sphere.n_vertices() / 2);
        CHECK(r.report.stop_message.find("constraint") != std::string::npos);
        // No two collapses touched each other's one-ring: every kept vertex and removed vertex
        // appears in one collapse only.
        std::set<Index> touched;
        for (const VertexSplit& s : r.progressive.collapses) {
            CHECK(touched.insert(s.removed.idx()).second);
            CHECK(touched.insert(s.kept.idx()).second);
        }
        // The next iteration unlocks.
        o.iterations = 2;
        const DecimationResult r2 = decimate(sphere, o);
        CHECK(r2.report.output_vertices < r.report.output_vertices);
    }
    SECTION("roundness threshold") {
        DecimationOptions o = percent_options(DecimationCost::Quadric, 95, 1);
        o.roundness = true;
        o.min_roundness = 0.6;
        const DecimationResult r = decimate(sphere, o);
        CHECK(r.report.refused_roundness > 0);
        REQUIRE_FALSE(r.levels.empty());
        const HalfedgeMesh& out = r.levels.back().mesh;
        REQUIRE_VALID(out);
        for (Face f : out.faces()) {
            const auto c = out.face_vertices(f);
            CHECK(normalized_roundness(out.position(c[0]), out.position(c[1]),
                                       out.position(c[2])) >= 0.6 - 1e-12);
        }
    }
    SECTION("maximum error") {
        DecimationOptions o = percent_options(DecimationCost::Quadric, 95, 1);
        o.max_error = 0.05;
        const DecimationResult r = decimate(sphere, o);
        CHECK(r.report.stop == DecimationStop::MaxError);
        REQUIRE_FALSE(r.levels.empty());
        CHECK(r.levels[0].mesh.n_vertices() > sphere.n_vertices() / 20);
        const MeshDistance d = mesh_distance(sphere, r.levels[0].mesh, {20000});
        CHECK(d.hausdorff < 0.03);
    }
}

TEST_CASE("decimate handles isolated vertices and garbage, and rejects bad options",
          "[decimation]") {
    HalfedgeMesh mesh = make_icosphere(4);
    const Vertex lonely = mesh.add_vertex(Point(5, 5, 5));
    mesh.collapse(mesh.halfedge(Vertex(0)));  // leaves garbage
    REQUIRE(mesh.has_garbage());
    DecimationOptions o;
    o.target_vertices = 20;
    const DecimationResult r = decimate(mesh, o);
    REQUIRE(r.levels.size() == 1);
    const HalfedgeMesh& out = r.levels[0].mesh;
    REQUIRE_VALID(out);
    CHECK(out.n_vertices() == 21);  // 20 with faces, and the isolated one
    CHECK(r.report.output_vertices == 20);
    CHECK(r.report.isolated_vertices == 1);
    std::size_t isolated = 0;
    for (Vertex v : out.vertices())
        if (out.is_isolated(v)) {
            ++isolated;
            CHECK(out.position(v) == mesh.position(lonely));
        }
    CHECK(isolated == 1);
    CHECK_NOTHROW(check_correspondence(mesh, out, r.levels[0].correspondence));

    const auto bad = [&](auto edit) {
        DecimationOptions b;
        edit(b);
        CHECK_THROWS_AS(decimate(mesh, b), InvalidArgument);
    };
    bad([](DecimationOptions& b) { b.percent = 0; });
    bad([](DecimationOptions& b) { b.percent = 101; });
    bad([](DecimationOptions& b) { b.iterations = 0; });
    bad([](DecimationOptions& b) { b.max_normal_angle = 0; });
    bad([](DecimationOptions& b) { b.min_roundness = 1.5; });
    bad([](DecimationOptions& b) { b.max_error = -1; });
    CHECK_THROWS_AS(parse_decimation_cost("qem"), InvalidArgument);
    CHECK(parse_decimation_cost("roundness") == DecimationCost::Roundness);
}

TEST_CASE("next_collapses lists the next iteration's edges", "[decimation]") {
    const HalfedgeMesh sphere = make_icosphere(6);
    const DecimationOptions o = percent_options(DecimationCost::Quadric, 30, 1);
    const auto pairs = next_collapses(sphere, o);
    CHECK(pairs.size() == std::size_t(std::floor(0.3 * double(sphere.n_vertices()))));
    // The first one is an edge of the mesh.
    REQUIRE_FALSE(pairs.empty());
    CHECK(sphere.find_edge(pairs[0][0], pairs[0][1]).is_valid());
}

TEST_CASE("decimate cancels when asked", "[decimation]") {
    auto cancel = test::CancellingProgress::at_once();
    CHECK_THROWS_AS(decimate(make_icosphere(6), DecimationOptions(), cancel), Cancelled);
}

TEST_CASE("decimating the shared bunny, horse and fandisk keeps them valid and close",
          "[decimation][shared]") {
    const std::string name =
        GENERATE(as<std::string>(), "stanford-bunny.obj", "horse.ply", "fandisk.obj");
    const std::string path = test::shared_mesh(name);
    SKIP_IF_MISSING(path);
    const HalfedgeMesh mesh = read_mesh(path).mesh;
    const MeshStats before = compute_stats(mesh);
    const std::size_t surface_vertices = before.vertices - before.isolated_vertices;
    for (double fraction : {0.1, 0.01}) {
        DecimationOptions o;
        o.target_vertices = std::size_t(fraction * double(surface_vertices));
        const DecimationResult r = decimate(mesh, o);
        REQUIRE(r.levels.size() == 1);
        const HalfedgeMesh& out = r.levels[0].mesh;
        REQUIRE_VALID(out);
        CHECK(r.report.output_vertices == o.target_vertices);
        const MeshStats after = compute_stats(out);
        CHECK(after.euler == before.euler);
        CHECK(after.boundary_loops == before.boundary_loops);
        const MeshDistance d = mesh_distance(mesh, out, {100000});
        WARN(name << " at " << fraction * 100 << "% (" << r.report.output_vertices
                  << " vertices): Hausdorff " << 100 * d.hausdorff / d.diagonal << "%, RMS "
                  << 100 * d.rms / d.diagonal << "% of the diagonal, " << r.report.ms << " ms");
        CHECK(d.hausdorff / d.diagonal < (fraction > 0.05 ? 0.01 : 0.03));
    }
}

TEST_CASE("the decimate operation parses, names bad options and gives one step per iteration",
          "[decimation]") {
    const auto message = [](const std::string& text) {
        try {
            parse_operation(text);
        } catch (const InvalidArgument& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    CHECK(message("decimate --percent 150").find("--percent: expected a number from 0 to 100") !=
          std::string::npos);
    CHECK(message("decimate --percent 0").find("--percent") != std::string::npos);
    CHECK(message("decimate --cost qem").find("--cost") != std::string::npos);
    CHECK(message("decimate --normal-flip 200").find("--normal-flip") != std::string::npos);
    CHECK(message("decimate --roundness 2").find("--roundness") != std::string::npos);
    CHECK(message("decimate --percent 50 --target-vertices 10").find("--target-vertices") !=
          std::string::npos);
    CHECK(message("decimate --cost roundness --normal-flip off --independent-set --roundness 0.3 "
                  "--percent 30 --iterations 2")
              .empty());

    const HalfedgeMesh sphere = make_icosphere(8);
    NullProgress progress;
    const OperationResult r = run_operation(
        parse_operation("decimate --cost quadric --percent 60 --iterations 3"), sphere, progress);
    REQUIRE(r.steps.size() == 3);
    const HalfedgeMesh* before = &sphere;
    for (const OperationStep& step : r.steps) {
        REQUIRE_VALID(step.mesh);
        CHECK(step.correspondence.kind == MorphCorrespondence::Kind::ToLater);
        CHECK_NOTHROW(check_correspondence(*before, step.mesh, step.correspondence));
        before = &step.mesh;
    }
    CHECK(r.parameters == "--cost quadric --percent 60 --iterations 3 --normal-flip 90");
    // The canonical parameters parse back to the same operation.
    CHECK_NOTHROW(parse_operation("decimate " + r.parameters));
    bool has_stop = false;
    for (const auto& [key, text] : r.texts)
        has_stop = has_stop || (key == "stop_reason" && text == "done");
    CHECK(has_stop);
    // A tetrahedron: nothing to collapse, one unchanged step, the reason in the report.
    const OperationResult t = run_operation(parse_operation("decimate --target-vertices 3"),
                                            make_tetrahedron(), progress);
    REQUIRE(t.steps.size() == 1);
    CHECK(t.steps[0].mesh.n_vertices() == 4);
    CHECK(t.report.back().find("link condition") != std::string::npos);
}

// ---- what a run records, and the level of detail -------------------------------------------

namespace {

/// Live triangles of a HalfedgeMesh as rotated, sorted vertex triples.
std::vector<std::array<Index, 3>> mesh_triangles(const HalfedgeMesh& m) {
    std::vector<std::array<Index, 3>> t;
    for (Face f : m.faces()) {
        const auto c = m.face_vertices(f);
        std::array<Index, 3> x{c[0].idx(), c[1].idx(), c[2].idx()};
        std::rotate(x.begin(), std::min_element(x.begin(), x.end()), x.end());
        t.push_back(x);
    }
    std::sort(t.begin(), t.end());
    return t;
}

/// The live triangles of the level of detail, in the fine mesh's vertex indices, as
/// rotated, sorted triples.
std::vector<std::array<Index, 3>> live_triangles(const LevelOfDetail& lod) {
    std::vector<std::array<Index, 3>> t = lod.triangles();
    for (auto& x : t) {
        for (Index& v : x) v = lod.fine_vertex(v);
        std::rotate(x.begin(), std::min_element(x.begin(), x.end()), x.end());
    }
    std::sort(t.begin(), t.end());
    return t;
}

/// Area-weighted unit vertex normals of the current level, in doubles, from the live
/// triangles.
std::vector<Vector3> direct_normals(const LevelOfDetail& lod) {
    std::vector<Vector3> n(lod.positions().size(), Vector3::Zero());
    for (const auto& t : lod.triangles()) {
        const Vector3 fn = triangle_normal(lod.positions(), t);
        for (Index v : t) n[v] += fn;
    }
    for (Vector3& x : n)
        if (x.norm() > 0) x.normalize();
    return n;
}

}  // namespace

TEST_CASE("the amount of output: all levels, the last one only, or none", "[decimation]") {
    const HalfedgeMesh mesh = make_noisy_sphere(8, 0.1, 11);
    DecimationOptions o = percent_options(DecimationCost::Quadric, 40, 3);
    const DecimationResult all = decimate(mesh, o);
    REQUIRE(all.levels.size() == 3);
    CHECK(all.progressive.collapses.empty());  // not recorded unless asked for
    CHECK(all.progressive.faces.empty());

    o.levels = DecimationLevels::Last;
    const DecimationResult last = decimate(mesh, o);
    REQUIRE(last.levels.size() == 1);
    const HalfedgeMesh& a = all.levels.back().mesh;
    const HalfedgeMesh& b = last.levels[0].mesh;
    REQUIRE_VALID(b);
    CHECK(last.report.collapses == all.report.collapses);
    CHECK(last.levels[0].target_vertices == all.levels.back().target_vertices);
    REQUIRE(a.vertices_size() == b.vertices_size());
    for (Vertex v : a.vertices()) CHECK(a.position(v) == b.position(v));
    CHECK(mesh_triangles(a) == mesh_triangles(b));
    // Its geomorph starts at the input: every input vertex ends on the last mesh.
    CHECK_NOTHROW(check_correspondence(mesh, b, last.levels[0].correspondence));
    CHECK(last.levels[0].correspondence.positions.size() == mesh.vertices_size());

    o.record_geomorph = false;
    const DecimationResult bare = decimate(mesh, o);
    REQUIRE(bare.levels.size() == 1);
    CHECK(bare.levels[0].correspondence.positions.empty());
    CHECK(mesh_triangles(bare.levels[0].mesh) == mesh_triangles(a));

    o.levels = DecimationLevels::None;
    o.record_progressive = true;
    const DecimationResult none = decimate(mesh, o);
    CHECK(none.levels.empty());
    CHECK(none.report.output_vertices == all.report.output_vertices);
    CHECK(none.progressive.collapses.size() == all.report.collapses);
    // The progressive mesh alone gives the same coarse mesh.
    LevelOfDetail lod(none.progressive);
    lod.set_level(lod.max_level());
    const HalfedgeMesh coarse = lod.mesh();
    REQUIRE_VALID(coarse);
    CHECK(mesh_triangles(coarse) == mesh_triangles(a));
}

TEST_CASE("build_progressive_mesh goes down to the smallest level and maps percentages to levels",
          "[decimation][lod]") {
    const HalfedgeMesh mesh = make_noisy_sphere(12, 0.1, 13);  // 1442 vertices
    const std::size_t v = mesh.n_vertices();
    NullProgress progress;
    const ProgressiveBuild pb = build_progressive_mesh(mesh, DecimationOptions(), 1.0, progress);
    const std::size_t keep = (v + 99) / 100;  // ceil(1 % of V)
    CHECK(pb.report.stop == DecimationStop::Done);
    CHECK(pb.report.output_vertices == keep);
    REQUIRE(pb.progressive.collapses.size() == v - keep);

    LevelOfDetail lod(pb.progressive);
    CHECK(lod.fine_vertices() == v);
    CHECK(lod.max_level() == v - keep);
    CHECK(lod.level_for_percent(100) == 0);
    CHECK(lod.level_for_percent(1) == lod.max_level());
    CHECK(lod.level_for_percent(0) == lod.max_level());
    CHECK(lod.level_for_percent(50) == v - (v + 1) / 2);
    CHECK(lod.level_for_percent(10) == v - std::size_t(std::ceil(0.1 * double(v))));
    std::size_t previous = 0;
    for (int p = 100; p >= 1; --p) {
        const std::size_t level = lod.level_for_percent(p);
        CHECK(level >= previous);  // fewer vertices, higher level
        previous = level;
        // The level keeps at least p % of the vertices, and not one more than needed.
        const double kept = lod.percent_at_level(level);
        CHECK(kept >= p - 1e-9);
        CHECK(kept - 100.0 / double(v) < p);
    }
    CHECK(lod.percent_at_level(0) == 100);
    CHECK_THROWS_AS(lod.level_for_percent(-1), InvalidArgument);
    CHECK_THROWS_AS(lod.level_for_percent(100.5), InvalidArgument);
    {
        const test::FpTrapsOff traps_off;  // NaN on purpose
        CHECK_THROWS_AS(lod.level_for_percent(std::nan("")), InvalidArgument);
    }

    lod.set_level(lod.level_for_percent(1));
    CHECK(lod.vertices() == keep);
    const HalfedgeMesh coarse = lod.mesh();
    REQUIRE_VALID(coarse);
    CHECK(coarse.n_vertices() == keep);

    CHECK_THROWS_AS(build_progressive_mesh(mesh, DecimationOptions(), 0.0, progress),
                    InvalidArgument);
    CHECK_THROWS_AS(build_progressive_mesh(mesh, DecimationOptions(), 101.0, progress),
                    InvalidArgument);
    DecimationOptions bad;
    bad.max_normal_angle = 0;
    CHECK_THROWS_AS(build_progressive_mesh(mesh, bad, 1.0, progress), InvalidArgument);
    // Where constraints stop early the progressive mesh ends there and the report says so.
    DecimationOptions strict;
    strict.max_error = 1e-3;
    const ProgressiveBuild limited = build_progressive_mesh(mesh, strict, 1.0, progress);
    CHECK(limited.report.stop == DecimationStop::MaxError);
    CHECK(limited.progressive.collapses.size() == limited.report.collapses);
    CHECK(limited.progressive.collapses.size() < v - keep);
    LevelOfDetail limited_lod(limited.progressive);
    CHECK(limited_lod.level_for_percent(1) == limited_lod.max_level());
}

TEST_CASE("a level of the progressive mesh is the mesh that decimating to its vertex count gives",
          "[decimation][lod]") {
    // Below 50,000 vertices decimation runs in exact priority order, so stopping at K
    // vertices is a prefix of the run down to 1 %.
    const HalfedgeMesh mesh = GENERATE(make_noisy_sphere(10, 0.15, 17), make_grid(24));
    NullProgress progress;
    const ProgressiveBuild pb = build_progressive_mesh(mesh, DecimationOptions(), 1.0, progress);
    LevelOfDetail lod(pb.progressive);
    for (double percent : {90.0, 55.0, 20.0, 5.0}) {
        lod.set_level(lod.level_for_percent(percent));
        const HalfedgeMesh level = lod.mesh();
        REQUIRE_VALID(level);
        DecimationOptions o;
        o.target_vertices = lod.vertices();
        const DecimationResult r = decimate(mesh, o);
        REQUIRE(r.levels.size() == 1);
        const HalfedgeMesh& direct = r.levels[0].mesh;
        INFO(percent << " %: " << lod.vertices() << " vertices");
        REQUIRE(level.vertices_size() == direct.vertices_size());
        for (Vertex v : direct.vertices()) CHECK(level.position(v) == direct.position(v));
        CHECK(mesh_triangles(level) == mesh_triangles(direct));
    }
}

TEST_CASE(
    "the level of detail gives the same level whatever the path, with its normals and changes",
    "[decimation][lod]") {
    const HalfedgeMesh mesh = GENERATE(make_noisy_sphere(10, 0.2, 19), make_grid(20));
    NullProgress progress;
    const ProgressiveBuild pb = build_progressive_mesh(mesh, DecimationOptions(), 1.0, progress);
    const ProgressiveMesh& pm = pb.progressive;
    REQUIRE(pm.collapses.size() > 100);
    LevelOfDetail lod(pm);
    CHECK(lod.all_changed());  // nothing consumed yet
    // A renderer's copy of positions and normals, kept right for the live vertices from the
    // change reports alone.
    std::vector<Point> seen_positions(lod.positions().size());
    std::vector<Vector3> seen_normals(lod.positions().size());
    const auto consume = [&]() {
        const std::vector<Index>& which =
            lod.all_changed() ? lod.live_vertices() : lod.changed_vertices();
        for (Index v : which) {
            seen_positions[v] = lod.positions()[v];
            seen_normals[v] = lod.vertex_normal(v);
        }
        lod.clear_changes();
    };
    consume();
    CHECK_FALSE(lod.all_changed());
    CHECK(lod.changed_vertices().empty());

    std::uint32_t seed = 12345;
    const auto random = [&](std::size_t n) {
        seed = seed * 1664525u + 1013904223u;
        return std::size_t(seed >> 8) % n;
    };
    bool stepwise = false, recomputed = false;
    for (int move = 0; move < 40; ++move) {
        // Long jumps and short steps both.
        const std::size_t target = move % 2 == 0
                                       ? random(pm.collapses.size() + 1)
                                       : std::min(pm.collapses.size(), lod.level() + random(8));
        lod.set_level(target);
        (lod.all_changed() ? recomputed : stepwise) = true;
        consume();
        INFO("move " << move << " to level " << target);
        // The same as replaying from the fine mesh straight to that level, bit for bit
        // (fixed-point normals: whatever the path).
        LevelOfDetail fresh(pm);
        fresh.set_level(target);
        REQUIRE(lod.level() == target);
        CHECK(lod.vertices() == lod.fine_vertices() - target);
        CHECK(lod.n_live_vertices() == mesh.n_vertices() - target);
        CHECK(lod.faces() == fresh.faces());
        CHECK(lod.face_alive() == fresh.face_alive());
        CHECK(lod.vertex_alive() == fresh.vertex_alive());
        CHECK(lod.positions() == fresh.positions());
        CHECK(lod.triangles() == fresh.triangles());
        CHECK(lod.triangles().size() == lod.n_triangles());
        std::vector<Index> alive;
        for (Index v = 0; v < lod.vertex_alive().size(); ++v)
            if (lod.vertex_alive()[v]) alive.push_back(v);
        CHECK(lod.live_vertices() == alive);
        const HalfedgeMesh level = lod.mesh();
        CHECK(level.n_vertices() == lod.n_live_vertices());
        CHECK(level.n_faces() == lod.n_triangles());
        const std::vector<Vector3> direct = direct_normals(lod);
        double worst_normal = 0;
        std::size_t stale = 0;
        for (Index v : alive) {
            CHECK(lod.vertex_normal(v) == fresh.vertex_normal(v));
            worst_normal = std::max(worst_normal, (lod.vertex_normal(v) - direct[v]).norm());
            if (seen_positions[v] != lod.positions()[v] || seen_normals[v] != lod.vertex_normal(v))
                ++stale;
        }
        CHECK(worst_normal < 1e-9);
        CHECK(stale == 0);  // the change reports covered every change
    }
    CHECK(stepwise);
    CHECK(recomputed);
    // And back to the fine mesh: its triangles, in the fine mesh's vertex order.
    lod.set_level(0);
    CHECK(mesh_triangles(lod.mesh()) == mesh_triangles(mesh));
    CHECK(live_triangles(lod) == mesh_triangles(mesh));
}

TEST_CASE("the level of detail refuses an inconsistent progressive mesh", "[decimation][lod]") {
    NullProgress progress;
    const ProgressiveBuild pb =
        build_progressive_mesh(make_icosphere(6), DecimationOptions(), 10.0, progress);
    REQUIRE(pb.progressive.collapses.size() > 10);
    const auto message = [](const ProgressiveMesh& pm) {
        try {
            LevelOfDetail lod(pm);
        } catch (const InvalidArgument& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    CHECK(message(pb.progressive).empty());
    ProgressiveMesh pm = pb.progressive;
    pm.ring_faces[3] = Face(Index(pm.faces.size() + 5));
    CHECK(message(pm).find("ring") != std::string::npos);
    pm = pb.progressive;
    pm.collapses[5].removed = pm.collapses[2].removed;  // already gone by then
    CHECK(message(pm).find("collapse 5") != std::string::npos);
    pm = pb.progressive;
    pm.collapses[4].ring_end = pm.collapses[4].moved_begin;  // before moved_end
    CHECK(message(pm).find("collapse 4") != std::string::npos);
    pm = pb.progressive;
    REQUIRE(pm.collapses[6].ring_end > pm.collapses[6].moved_end);
    --pm.collapses[6].ring_end;  // one face at the kept vertex left out
    CHECK(message(pm).find("collapse 6: its ring does not list") != std::string::npos);
    pm = pb.progressive;
    pm.collapses[7].kept_before.x() += 1e-9;  // not where the vertex is
    CHECK(message(pm).find("collapse 7: its positions") != std::string::npos);
    pm = pb.progressive;
    pm.face_alive.pop_back();
    CHECK(message(pm).find("sizes") != std::string::npos);
    pm = pb.progressive;
    pm.collapses[1].kept_after = Point(std::nan(""), 0, 0);
    CHECK(message(pm).find("non-finite") != std::string::npos);
}
