// Connected components and removing the small ones (core/algorithms/components.h, and the
// "remove-components" operation).
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "app/ops/operation.h"
#include "core/algorithms/components.h"
#include "core/algorithms/generators.h"
#include "core/algorithms/mesh_stats.h"
#include "core/algorithms/morph.h"
#include "core/errors.h"
#include "core/io/mesh_io.h"
#include "core/mesh_builder.h"
#include "test_helpers.h"

using namespace trilab;

namespace {

/// A piece of a combined mesh: a mesh scaled by `scale`, then moved by `offset`.
struct Piece {
    HalfedgeMesh mesh;
    double scale = 1;
    Point offset = Point::Zero();
};

/// The pieces side by side in one mesh, in order (their vertices, edges and faces in that
/// order), plus `isolated` vertices at the end.
HalfedgeMesh combine(const std::vector<Piece>& pieces, const std::vector<Point>& isolated = {}) {
    PolygonSoup all;
    for (const Piece& p : pieces) {
        const PolygonSoup s = to_soup(p.mesh);
        const Index base = Index(all.positions.size());
        for (const Point& x : s.positions) all.positions.push_back(p.scale * x + p.offset);
        for (Index c : s.corners) all.corners.push_back(base + c);
        for (std::size_t f = 1; f < s.face_offsets.size(); ++f)
            all.face_offsets.push_back(all.face_offsets.back() + 3);
    }
    for (const Point& x : isolated) all.positions.push_back(x);
    LoadReport report;
    return build_mesh(all, report);
}

/// One triangle.
HalfedgeMesh triangle(const Point& a, const Point& b, const Point& c) {
    PolygonSoup s;
    s.positions = {a, b, c};
    s.add_face({0, 1, 2});
    LoadReport report;
    return build_mesh(s, report);
}

/// A sphere of 320 faces (radius 1), one of 20 (radius 0.2, at x = 3), a loose triangle and
/// an isolated vertex.
HalfedgeMesh scan_like() {
    return combine(
        {{make_icosphere(4), 1, Point::Zero()},
         {make_icosphere(1), 0.2, Point(3, 0, 0)},
         {triangle(Point(0, 3, 0), Point(0.1, 3, 0), Point(0, 3.1, 0)), 1, Point::Zero()}},
        {Point(-2, 0, 0)});
}

RemoveComponentsOptions min_faces(std::size_t n) {
    RemoveComponentsOptions o;
    o.min_faces = n;
    return o;
}
RemoveComponentsOptions min_diameter(double f) {
    RemoveComponentsOptions o;
    o.min_diameter = f;
    return o;
}

}  // namespace

TEST_CASE("label_face_components counts and measures each piece", "[components]") {
    const HalfedgeMesh mesh = scan_like();
    REQUIRE_VALID(mesh);
    const ComponentLabels labels = label_face_components(mesh);
    REQUIRE(labels.components.size() == 3);
    REQUIRE(labels.components.size() == compute_stats(mesh).components);
    REQUIRE(labels.isolated_vertices == 1);
    // In the order of their first vertex: the big sphere, the small one, the triangle.
    REQUIRE(labels.components[0].faces == 320);
    REQUIRE(labels.components[0].vertices == 162);
    REQUIRE(labels.components[1].faces == 20);
    REQUIRE(labels.components[1].vertices == 12);
    REQUIRE(labels.components[2].faces == 1);
    REQUIRE(labels.components[2].vertices == 3);
    REQUIRE(labels.components[1].bbox.center().isApprox(Point(3, 0, 0)));
    REQUIRE(labels.components[2].bbox.diagonal() == Approx(0.1 * std::sqrt(2.0)));
    // Every face's component holds its three vertices.
    for (Face f : mesh.faces())
        for (Vertex v : mesh.vertices_of(f))
            REQUIRE(labels.of_vertex[v.idx()] == labels.of_face[f.idx()]);
    REQUIRE(labels.of_vertex.back() == kInvalidIndex);  // the isolated vertex
}

TEST_CASE("remove_small_components by face count keeps the big sphere", "[components]") {
    const HalfedgeMesh mesh = scan_like();
    const RemoveComponentsResult r = remove_small_components(mesh, min_faces(21));
    REQUIRE_VALID(r.mesh);
    REQUIRE(r.mesh.n_faces() == 320);
    REQUIRE(r.mesh.n_vertices() == 162);
    REQUIRE(compute_stats(r.mesh).components == 1);
    REQUIRE(compute_stats(r.mesh).genus == 0);
    const RemoveComponentsReport& rep = r.report;
    REQUIRE(rep.components_before == 3);
    REQUIRE(rep.components_after == 1);
    REQUIRE(rep.faces_removed == 21);
    REQUIRE(rep.isolated_vertices_removed == 1);
    REQUIRE(rep.vertices_removed == 12 + 3 + 1);
    REQUIRE(rep.largest_faces == 320);
    REQUIRE_FALSE(rep.largest_kept_anyway);
    // The kept vertices are the sphere's, in their order and at their places.
    for (Vertex v : r.mesh.vertices()) REQUIRE(r.mesh.position(v) == mesh.position(v));
}

TEST_CASE("a component with exactly min_faces faces stays", "[components]") {
    const HalfedgeMesh mesh = scan_like();
    const RemoveComponentsResult at = remove_small_components(mesh, min_faces(20));
    REQUIRE_VALID(at.mesh);
    REQUIRE(at.report.components_after == 2);  // the small sphere (20 faces) stays
    REQUIRE(at.mesh.n_faces() == 340);
    REQUIRE(remove_small_components(mesh, min_faces(21)).report.components_after == 1);
    // 0 and 1 remove no component, only the isolated vertex.
    for (std::size_t n : {0, 1}) {
        const RemoveComponentsResult r = remove_small_components(mesh, min_faces(n));
        REQUIRE_VALID(r.mesh);
        REQUIRE(r.report.components_after == 3);
        REQUIRE(r.report.vertices_removed == 1);
        REQUIRE(r.mesh.n_faces() == mesh.n_faces());
    }
}

TEST_CASE("a component exactly at min_diameter stays, and the largest is always kept",
          "[components]") {
    // Cubes [0,2]^3 and [3,4]^3: the whole box [0,4]^3 has diagonal 4 sqrt(3), the small
    // cube's is sqrt(3), exactly a quarter (sqrt is correctly rounded; scaling by 4 is exact).
    const HalfedgeMesh mesh =
        combine({{make_cube(), 2, Point::Zero()}, {make_cube(), 1, Point(3, 3, 3)}});
    REQUIRE_VALID(mesh);
    const RemoveComponentsResult at = remove_small_components(mesh, min_diameter(0.25));
    REQUIRE(at.report.mesh_diagonal == std::sqrt(48.0));
    REQUIRE(at.report.min_diagonal == std::sqrt(3.0));
    REQUIRE(at.report.components_after == 2);
    const double above = std::nextafter(0.25, 1.0);
    const RemoveComponentsResult r = remove_small_components(mesh, min_diameter(above));
    REQUIRE_VALID(r.mesh);
    REQUIRE(r.report.components_after == 1);
    REQUIRE(r.mesh.n_faces() == 12);
    REQUIRE(bounding_box(r.mesh).max == Point(2, 2, 2));
    // Both below: the largest (12 faces each; on a tie the first) stays, and the report says
    // the rule would have removed it.
    const RemoveComponentsResult both = remove_small_components(mesh, min_diameter(1));
    REQUIRE_VALID(both.mesh);
    REQUIRE(both.report.components_after == 1);
    REQUIRE(both.report.largest_kept_anyway);
    REQUIRE(bounding_box(both.mesh).max == Point(2, 2, 2));
    RemoveComponentsOptions faces_too = min_diameter(0.25);
    faces_too.min_faces = 13;  // either rule removes: every piece has 12 faces
    const RemoveComponentsResult either = remove_small_components(mesh, faces_too);
    REQUIRE(either.report.components_after == 1);
    REQUIRE(either.report.largest_kept_anyway);
}

TEST_CASE("a mesh with one component stays bit for bit", "[components]") {
    const HalfedgeMesh sphere = test::attributed_sphere();
    for (const RemoveComponentsOptions& o : {min_faces(1000000), min_diameter(1)}) {
        const RemoveComponentsResult r = remove_small_components(sphere, o);
        REQUIRE_VALID(r.mesh);
        REQUIRE(r.report.vertices_removed == 0);
        // Below the face count it is kept anyway; at the whole diagonal it stays by right.
        REQUIRE(r.report.largest_kept_anyway == bool(o.min_faces));
        REQUIRE(r.mesh.positions() == sphere.positions());
        REQUIRE(r.mesh.halfedge_next_array() == sphere.halfedge_next_array());
        REQUIRE(r.mesh.halfedge_to_array() == sphere.halfedge_to_array());
        REQUIRE(r.mesh.face_halfedge_array() == sphere.face_halfedge_array());
        REQUIRE(r.mesh.vertex_property_names() == sphere.vertex_property_names());
        const auto a = r.mesh.memory_blocks(), b = sphere.memory_blocks();
        REQUIRE(a.size() == b.size());
        for (std::size_t i = 0; i < a.size(); ++i) REQUIRE(a[i].id == b[i].id);  // shared
    }
}

TEST_CASE("the kept part keeps its boundary, connectivity and attributes", "[components]") {
    // An open grid (the largest) with corner texture coordinates and vertex colours, and a
    // small sphere to remove.
    PolygonSoup soup = to_soup(make_grid(8));
    const std::size_t grid_vertices = soup.positions.size();
    const PolygonSoup ball = to_soup(make_icosphere(1));
    for (const Point& p : ball.positions) soup.positions.push_back(0.1 * p + Point(3, 0, 0));
    for (std::size_t f = 0; f + 1 < ball.face_offsets.size(); ++f) {
        for (int k = 0; k < 3; ++k)
            soup.corners.push_back(Index(grid_vertices) + ball.corners[3 * f + k]);
        soup.face_offsets.push_back(soup.corners.size());
    }
    for (std::size_t i = 0; i < soup.positions.size(); ++i)
        soup.colors.push_back(Color(float(i % 7) / 7, 0.5f, 1.0f));
    for (std::size_t c = 0; c < soup.corners.size(); ++c)
        soup.corner_texcoords.push_back(TexCoord(double(c) / 1000, 1 - double(c) / 1000));
    LoadReport built;
    const HalfedgeMesh mesh = build_mesh(soup, built);
    REQUIRE_VALID(mesh);
    const RemoveComponentsResult r = remove_small_components(mesh, min_faces(21));
    REQUIRE_VALID(r.mesh);
    REQUIRE(r.report.components_after == 1);
    REQUIRE(count_boundary_loops(r.mesh) == 1);
    REQUIRE(r.mesh.n_faces() == 128);
    // The grid came first: its elements are the first ones, renumbered to themselves.
    const auto colors = mesh.get_vertex_property<Color>("v:color");
    const auto kept_colors = r.mesh.get_vertex_property<Color>("v:color");
    REQUIRE(kept_colors);
    for (Vertex v : r.mesh.vertices()) REQUIRE(kept_colors[v] == colors[v]);
    const auto uv = mesh.get_halfedge_property<TexCoord>("h:texcoord");
    const auto kept_uv = r.mesh.get_halfedge_property<TexCoord>("h:texcoord");
    REQUIRE(kept_uv);
    for (Halfedge h : r.mesh.halfedges()) {
        REQUIRE(kept_uv[h] == uv[h]);
        REQUIRE(r.mesh.next(h) == mesh.next(h));
        REQUIRE(r.mesh.to_vertex(h) == mesh.to_vertex(h));
    }
}

TEST_CASE("remove_small_components is deterministic and idempotent", "[components]") {
    const HalfedgeMesh mesh = scan_like();
    const RemoveComponentsResult a = remove_small_components(mesh, min_diameter(0.2));
    const RemoveComponentsResult b = remove_small_components(mesh, min_diameter(0.2));
    REQUIRE(a.mesh.positions() == b.mesh.positions());
    REQUIRE(a.mesh.halfedge_next_array() == b.mesh.halfedge_next_array());
    // The whole box spans the isolated vertex at x = -2 to the small sphere at x = 3.2: the big
    // sphere's diagonal is about half of it, the small sphere's and the triangle's far less.
    REQUIRE(a.report.components_after == 1);
    const RemoveComponentsResult again = remove_small_components(a.mesh, min_diameter(0.2));
    REQUIRE(again.report.vertices_removed == 0);
}

TEST_CASE("remove_small_components refuses bad options and leaves faceless meshes",
          "[components]") {
    const HalfedgeMesh mesh = scan_like();
    REQUIRE_THROWS_AS(remove_small_components(mesh, {}), InvalidArgument);
    REQUIRE_THROWS_WITH(remove_small_components(mesh, {}), Catch::Contains("min_faces"));
    for (double bad : {-0.1, 1.5, std::nan(""), std::numeric_limits<double>::infinity()})
        REQUIRE_THROWS_WITH(remove_small_components(mesh, min_diameter(bad)),
                            Catch::Contains("min_diameter"));
    PolygonSoup points;
    points.positions = {Point(0, 0, 0), Point(1, 0, 0)};
    LoadReport report;
    const HalfedgeMesh cloud = build_mesh(points, report);
    const RemoveComponentsResult r = remove_small_components(cloud, min_faces(10));
    REQUIRE_VALID(r.mesh);
    REQUIRE(r.mesh.n_vertices() == 2);  // removing them would leave nothing
    REQUIRE(r.report.components_before == 0);
    REQUIRE(r.report.vertices_removed == 0);
    NullProgress progress;
    const OperationResult op =
        run_operation(parse_operation("remove-components --min-faces 10"), cloud, progress);
    REQUIRE(op.report.size() == 2);
    REQUIRE(op.report.back() ==
            "no faces: the mesh is unchanged (removing its vertices would leave nothing)");
}

TEST_CASE("the remove-components operation parses, runs, reports and morphs",
          "[components][operation]") {
    REQUIRE_THROWS_WITH(parse_operation("remove-components"),
                        Catch::Contains("--min-faces") && Catch::Contains("--min-diameter"));
    REQUIRE_THROWS_WITH(parse_operation("remove-components --min-diameter 2"),
                        Catch::Contains("--min-diameter"));
    REQUIRE_THROWS_WITH(parse_operation("remove-components --min-faces -1"),
                        Catch::Contains("--min-faces"));
    const Operation op = parse_operation("remove-components --min-faces 21 --min-diameter 0.01");
    REQUIRE(op.parameters() == "--min-faces 21 --min-diameter 0.01");
    REQUIRE(parse_operation("remove-components --min-faces 5").parameters() == "--min-faces 5");

    const HalfedgeMesh mesh = scan_like();
    NullProgress progress;
    const OperationResult r = run_operation(op, mesh, progress);
    REQUIRE(r.label == "Remove small components");
    REQUIRE(r.steps.size() == 1);
    const OperationStep& step = r.steps[0];
    REQUIRE_VALID(step.mesh);
    REQUIRE(step.mesh.n_faces() == 320);
    REQUIRE(r.report.at(0) ==
            "removed 2 of 3 components (21 faces), 1 isolated vertex; 16 vertices removed in all");
    const auto value = [&](const std::string& key) {
        for (const auto& [k, v] : r.values)
            if (k == key) return v;
        FAIL("no value " << key);
        return 0.0;
    };
    REQUIRE(value("components_removed") == 2);
    REQUIRE(value("vertices_removed") == 16);
    REQUIRE(value("largest_faces") == 320);
    // The morph: the kept vertices stay, each removed piece shrinks into its centre.
    REQUIRE(step.correspondence.kind == MorphCorrespondence::Kind::ToLater);
    REQUIRE_NOTHROW(check_correspondence(mesh, step.mesh, step.correspondence));
    const ComponentLabels labels = label_face_components(mesh);
    for (Vertex v : mesh.vertices()) {
        const Index c = labels.of_vertex[v.idx()];
        const Point& end = step.correspondence.positions[v.idx()];
        if (c == 1 || c == 2)
            REQUIRE(end == labels.components[c].bbox.center());
        else
            REQUIRE(end == mesh.position(v));
    }
    REQUIRE(morph_frame(mesh, step.mesh, step.correspondence, 1).topology == &step.mesh);

    // Nothing to remove: the same vertices, and the run says so.
    const OperationResult same = run_operation(parse_operation("remove-components --min-faces 1"),
                                               make_icosphere(2), progress);
    REQUIRE_FALSE(same.changed);
    REQUIRE(same.steps[0].correspondence.kind == MorphCorrespondence::Kind::SameVertices);
    REQUIRE(same.report.back() == "nothing to remove: the mesh is unchanged");
}

TEST_CASE("remove-components on the shared meshes with several components",
          "[components][shared]") {
    // Suzanne is a head and two eyes; the teapot's patches are separate components until
    // welded; the bunny is one component and 1,113 isolated vertices.
    const std::string dir = test::shared_dir() + "/meshes";
    SKIP_IF_MISSING(dir);
    std::size_t several = 0;
    for (const char* name : {"cow.obj", "fandisk.obj", "horse.ply", "spot.obj",
                             "stanford-bunny.obj", "suzanne.obj", "teapot.obj"}) {
        const std::string path = dir + "/" + name;
        if (!test::exists(path)) continue;
        const HalfedgeMesh mesh = read_mesh(path).mesh;
        const ComponentLabels labels = label_face_components(mesh);
        INFO(name << ": " << labels.components.size() << " components");
        REQUIRE(labels.components.size() == compute_stats(mesh).components);
        if (labels.components.size() < 2 && labels.isolated_vertices == 0) continue;
        ++several;
        for (const RemoveComponentsOptions& o : {min_faces(100), min_diameter(0.3)}) {
            const RemoveComponentsResult r = remove_small_components(mesh, o);
            REQUIRE_VALID(r.mesh);
            REQUIRE(r.report.components_after >= 1);
            REQUIRE(r.report.components_after == compute_stats(r.mesh).components);
            REQUIRE(r.mesh.n_faces() + r.report.faces_removed == mesh.n_faces());
            REQUIRE(r.mesh.n_vertices() + r.report.vertices_removed == mesh.n_vertices());
            REQUIRE(compute_stats(r.mesh).isolated_vertices == 0);
        }
    }
    const std::string suzanne = dir + "/suzanne.obj";
    if (test::exists(suzanne)) {
        const HalfedgeMesh mesh = read_mesh(suzanne).mesh;
        const RemoveComponentsResult r = remove_small_components(mesh, min_faces(100));
        REQUIRE(r.report.components_before == 3);
        REQUIRE(r.report.components_after == 1);  // the eyes go
        REQUIRE(r.report.faces_removed == 112);
        REQUIRE(r.mesh.n_faces() == 856);
    }
    const std::string bunny = dir + "/stanford-bunny.obj";
    if (test::exists(bunny)) {
        const HalfedgeMesh mesh = read_mesh(bunny).mesh;
        const RemoveComponentsResult r = remove_small_components(mesh, min_faces(1));
        REQUIRE(r.report.isolated_vertices_removed == 1113);
        REQUIRE(r.report.faces_removed == 0);
        REQUIRE(r.mesh.n_faces() == mesh.n_faces());
    }
    if (several == 0) SKIP_TEST("no shared mesh has several components or isolated vertices");
}
