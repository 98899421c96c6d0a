// Subdivision of a region (core/algorithms/region_subdivision.h): on closed meshes every scheme
// gives a valid closed manifold with the Euler characteristic kept, the face count the closure
// predicts (computed here independently from the selection), vertices of weight 0 bit for
// bit where they were, the selection carried, the minimum angles reported as they are, and an
// all-ones selection gives exactly the unselected result.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <set>
#include <utility>

#include "app/ops/operation.h"
#include "core/algorithms/coincident.h"
#include "core/algorithms/generators.h"
#include "core/algorithms/region_subdivision.h"
#include "core/algorithms/selection.h"
#include "core/algorithms/subdivision.h"
#include "core/geometry.h"
#include "core/io/mesh_io.h"
#include "core/validate.h"
#include "test_helpers.h"

using namespace trilab;

namespace {

bool same_point(const Point& a, const Point& b) {
    return std::memcmp(a.data(), b.data(), sizeof(Point)) == 0;
}

long euler(const HalfedgeMesh& m) {
    return long(m.n_vertices()) - long(m.n_edges()) + long(m.n_faces());
}

/// The red-green face count, computed on vertex pairs (independently of the implementation):
/// split the edges of the selected faces, then the third edge of every face with two, until
/// nothing changes; F + 3 red + 1 green.
std::size_t predicted_red_green_faces(const HalfedgeMesh& m, const Selection& w) {
    std::vector<std::array<Index, 3>> tris;
    for (Face f : m.faces()) {
        const auto v = m.face_vertices(f);
        tris.push_back({v[0].idx(), v[1].idx(), v[2].idx()});
    }
    const auto key = [](Index a, Index b) {
        return std::make_pair(std::min(a, b), std::max(a, b));
    };
    std::set<std::pair<Index, Index>> split;
    for (const auto& t : tris)
        if (w[t[0]] > 0 && w[t[1]] > 0 && w[t[2]] > 0)
            for (int k = 0; k < 3; ++k) split.insert(key(t[k], t[(k + 1) % 3]));
    for (bool changed = true; changed;) {
        changed = false;
        for (const auto& t : tris) {
            int n = 0;
            for (int k = 0; k < 3; ++k) n += int(split.count(key(t[k], t[(k + 1) % 3])));
            if (n == 2) {
                for (int k = 0; k < 3; ++k) split.insert(key(t[k], t[(k + 1) % 3]));
                changed = true;
            }
        }
    }
    std::size_t faces = tris.size();
    for (const auto& t : tris) {
        int n = 0;
        for (int k = 0; k < 3; ++k) n += int(split.count(key(t[k], t[(k + 1) % 3])));
        faces += n == 3 ? 3 : (n == 1 ? 1 : 0);
    }
    return faces;
}

std::size_t count_selected_faces(const HalfedgeMesh& m, const Selection& w) {
    std::size_t n = 0;
    for (Face f : m.faces()) {
        const auto v = m.face_vertices(f);
        n += (w[v[0].idx()] > 0 && w[v[1].idx()] > 0 && w[v[2].idx()] > 0) ? 1 : 0;
    }
    return n;
}

/// The smallest corner angle of face f in degrees, every corner by atan2 (a second
/// implementation).
double brute_face_min_angle(const HalfedgeMesh& m, Face f) {
    double smallest = 180;
    const auto v = m.face_vertices(f);
    for (int k = 0; k < 3; ++k) {
        const Vector3 a = m.position(v[(k + 1) % 3]) - m.position(v[k]);
        const Vector3 b = m.position(v[(k + 2) % 3]) - m.position(v[k]);
        smallest = std::min(smallest, std::atan2(a.cross(b).norm(), a.dot(b)) * 180 / M_PI);
    }
    return smallest;
}

double brute_min_angle(const HalfedgeMesh& m) {
    double smallest = 180;
    for (Face f : m.faces()) smallest = std::min(smallest, brute_face_min_angle(m, f));
    return smallest;
}

struct Fixture {
    std::string name;
    HalfedgeMesh mesh;
};

}  // namespace

TEST_CASE("subdivide_region refines the selected faces with a conforming closure",
          "[subdivision][selection]") {
    const auto scheme =
        GENERATE(SubdivisionScheme::Loop, SubdivisionScheme::Sqrt3, SubdivisionScheme::Butterfly,
                 SubdivisionScheme::ModifiedButterfly);
    const bool use_default = GENERATE(true, false);
    const HalfedgeMesh mesh = use_default ? make_default_model() : make_icosphere(3);
    INFO(scheme_name(scheme) << (use_default ? " on the default model" : " on an icosphere"));
    const Point centre = mesh.position(Vertex(0));
    const Selection region = sphere_selection(mesh, centre, 0.7);
    REQUIRE(count_selected(region) > 10);
    REQUIRE(count_selected(region) < mesh.n_vertices() / 2);
    SubdivisionOptions options;
    options.scheme = scheme;
    // The default closure: next to the selection, as predicted below (issue 38: no longer grown).
    NullProgress progress;
    RegionSubdivisionReport report;
    const SubdivisionResult result = subdivide_region(mesh, options, region, progress, report);
    REQUIRE(result.levels.size() == 1);
    const HalfedgeMesh& out = result.levels.back().mesh;

    // A valid closed manifold, the Euler characteristic kept.
    REQUIRE(validate(out).ok);
    CHECK(is_closed(out));
    CHECK(euler(out) == euler(mesh));

    // The face count of the closure, predicted independently.
    const std::size_t selected = count_selected_faces(mesh, region);
    REQUIRE(report.closure.size() == 1);
    CHECK(report.closure[0].selected_faces == selected);
    // 1-to-4 schemes: the red-green count, plus 3 per face grown into where a bisection of a
    // face with a moving vertex would come within kMovingGreenMargin of the bound (each such
    // face turns from green, +1, into red, +3, and may make its neighbours green).
    if (scheme == SubdivisionScheme::Sqrt3) {
        CHECK(out.n_faces() == mesh.n_faces() + 2 * selected);
    } else {
        const auto& c = report.closure[0];
        CHECK(out.n_faces() == mesh.n_faces() + 3 * c.red_faces + c.green_faces);
        if (c.grown_faces == 0)
            CHECK(out.n_faces() == predicted_red_green_faces(mesh, region));
        else
            CHECK(out.n_faces() > predicted_red_green_faces(mesh, region));
    }
    CHECK(out.n_faces() > mesh.n_faces());
    CHECK(out.n_faces() < (scheme == SubdivisionScheme::Sqrt3 ? 3 : 4) * mesh.n_faces());

    // Vertices of weight 0 stay bit for bit; those inside move as the whole-mesh scheme moves
    // them (Loop, Sqrt3) or stay (the interpolating butterflies).
    SubdivisionOptions whole_options = options;
    const SubdivisionResult whole = subdivide(mesh, whole_options, progress);
    const HalfedgeMesh& uniform = whole.levels.back().mesh;
    for (Vertex v : mesh.vertices()) {
        if (region[v.idx()] == 0.0f)
            CHECK(same_point(out.position(v), mesh.position(v)));
        else
            CHECK(same_point(out.position(v), uniform.position(v)));
    }

    // The selection is carried: old vertices keep theirs, new ones the minimum of their parents.
    const auto carried = out.get_vertex_property<float>(kSelectionProperty);
    const auto parents = out.get_vertex_property<SubdivisionParents>("v:subdivision_parents");
    const auto levels = out.get_vertex_property<int>("v:subdivision_level");
    REQUIRE(carried);
    REQUIRE(parents);
    REQUIRE(levels);
    for (Vertex v : out.vertices()) {
        if (v.idx() < mesh.vertices_size()) {
            CHECK(carried[v] == region[v.idx()]);
            CHECK(levels[v] == 0);
            continue;
        }
        CHECK(levels[v] == 1);
        float least = 1.0f;
        for (int k = 0; k < 3; ++k)
            if (parents[v][k] != kInvalidIndex) least = std::min(least, region[parents[v][k]]);
        CHECK(carried[v] == least);
    }

    // The minimum angles are reported as they are (with the closure kept next to the selection,
    // a green bisection or an unflipped Sqrt3 triangle can be flatter than the input: the
    // report says so, it is not hidden).
    CHECK(report.min_angle_in == Approx(brute_min_angle(mesh)).margin(1e-9));
    CHECK(report.min_angle_out == Approx(brute_min_angle(out)).margin(1e-9));
    CHECK(report.min_angle_out > 0);
    // Local: a few faces grown at most, never the surface.
    CHECK(out.n_faces() < mesh.n_faces() + 20 * selected);
    CHECK(report.closure[0].min_angle_closure >= report.min_angle_out);
}

TEST_CASE("subdivide_region with an all-ones selection gives the unselected result bit for bit",
          "[subdivision][selection]") {
    const auto scheme =
        GENERATE(SubdivisionScheme::Loop, SubdivisionScheme::Sqrt3, SubdivisionScheme::Butterfly,
                 SubdivisionScheme::ModifiedButterfly);
    const HalfedgeMesh mesh = make_default_model();
    SubdivisionOptions options;
    options.scheme = scheme;
    options.iterations = 2;
    NullProgress progress;
    RegionSubdivisionReport report;
    const SubdivisionResult a = subdivide(mesh, options, progress);
    const SubdivisionResult b =
        subdivide_region(mesh, options, full_selection(mesh), progress, report);
    REQUIRE(a.levels.size() == b.levels.size());
    for (std::size_t i = 0; i < a.levels.size(); ++i) {
        const HalfedgeMesh& x = a.levels[i].mesh;
        const HalfedgeMesh& y = b.levels[i].mesh;
        REQUIRE(x.vertices_size() == y.vertices_size());
        CHECK(std::memcmp(x.positions().data(), y.positions().data(),
                          x.positions().size() * sizeof(Point)) == 0);
        CHECK(x.halfedge_to_array() == y.halfedge_to_array());
        CHECK(x.face_halfedge_array() == y.face_halfedge_array());
        const auto carried = y.get_vertex_property<float>(kSelectionProperty);
        REQUIRE(carried);
        for (Vertex v : y.vertices()) CHECK(carried[v] == 1.0f);
    }
}

TEST_CASE("subdivide_region over several iterations keeps the region and the mesh valid",
          "[subdivision][selection]") {
    const auto scheme = GENERATE(SubdivisionScheme::Loop, SubdivisionScheme::Sqrt3);
    const HalfedgeMesh mesh = make_default_model();
    Selection region = sphere_selection(mesh, mesh.position(Vertex(5)), 0.6);
    feather_selection(mesh, region, 0.3);  // fractional weights blend
    SubdivisionOptions options;
    options.scheme = scheme;
    options.iterations = 3;
    NullProgress progress;
    RegionSubdivisionReport report;
    const SubdivisionResult result = subdivide_region(mesh, options, region, progress, report);
    REQUIRE(result.levels.size() == 3);
    REQUIRE(report.closure.size() == 3);
    std::size_t faces = mesh.n_faces();
    for (const SubdivisionLevel& level : result.levels) {
        REQUIRE(validate(level.mesh).ok);
        CHECK(is_closed(level.mesh));
        CHECK(euler(level.mesh) == 2);
        CHECK(level.mesh.n_faces() > faces);
        faces = level.mesh.n_faces();
        REQUIRE(level.correspondence.positions.size() == level.mesh.vertices_size());
    }
    const HalfedgeMesh& last = result.levels.back().mesh;
    for (Vertex v : mesh.vertices())
        if (region[v.idx()] == 0.0f) CHECK(same_point(last.position(v), mesh.position(v)));
}

TEST_CASE("subdivide takes a region through the operation and reports the angles",
          "[subdivision][selection][operation]") {
    const HalfedgeMesh mesh = make_default_model();
    const Selection region = sphere_selection(mesh, mesh.position(Vertex(0)), 0.5);
    NullProgress progress;
    RunSettings settings;
    settings.region = &region;
    const OperationResult r =
        run_operation(parse_operation("subdivide --scheme butterfly"), mesh, progress, settings);
    std::map<std::string, double> values(r.values.begin(), r.values.end());
    CHECK(values.at("region_vertices") == double(count_selected(region)));
    CHECK(values.at("faces") == double(r.steps.back().mesh.n_faces()));
    CHECK(values.at("faces") >= double(predicted_red_green_faces(mesh, region)));
    CHECK(values.count("min_angle_in") == 1);
    CHECK(values.count("min_angle_out") == 1);
    CHECK(values.at("grown_faces") <= values.at("selected_faces"));
    CHECK(values.at("min_angle_closure") < values.at("min_angle_in"));  // bisections, kept local
    CHECK(validate(r.steps.back().mesh).ok);
    // --global-closure grows the closure until none of its triangles is flatter than the input.
    const OperationResult g = run_operation(
        parse_operation("subdivide --scheme butterfly --global-closure"), mesh, progress, settings);
    std::map<std::string, double> grown(g.values.begin(), g.values.end());
    CHECK(grown.at("grown_faces") > 0);
    CHECK(grown.at("min_angle_closure") >= grown.at("min_angle_in") - 1e-9);  // rounding
    bool reported = false;
    for (const std::string& line : g.report)
        reported = reported || line.find("closure (last level): minimum angle") == 0;
    CHECK(reported);
    // A selection that does not fit is refused before anything runs.
    Selection wrong(3, 1.0f);
    settings.region = &wrong;
    CHECK_THROWS_AS(run_operation(parse_operation("subdivide"), mesh, progress, settings),
                    InvalidArgument);
}

namespace {

/// The coarse faces split by a region step, read back from the output alone: the coarse edges
/// that got a new vertex (its two parents), and for Sqrt3 the faces that got a centroid.
struct SplitsFound {
    std::set<std::pair<Index, Index>> edges;
    std::size_t centroids = 0;
};

SplitsFound splits_in(const HalfedgeMesh& out, std::size_t old_vertices) {
    SplitsFound found;
    const auto parents = out.get_vertex_property<SubdivisionParents>("v:subdivision_parents");
    for (Vertex v : out.vertices()) {
        if (v.idx() < old_vertices) continue;
        if (parents[v][2] != kInvalidIndex) {
            ++found.centroids;
        } else {
            found.edges.insert(std::make_pair(std::min(parents[v][0], parents[v][1]),
                                              std::max(parents[v][0], parents[v][1])));
        }
    }
    return found;
}

struct NamedMesh {
    std::string name;
    HalfedgeMesh mesh;
};

/// The generated default model and the shared bunny, spot and fandisk (skipped when absent).
std::vector<NamedMesh> closure_fixtures() {
    std::vector<NamedMesh> meshes;
    meshes.push_back({"default model", make_default_model()});
    for (const char* name : {"stanford-bunny.obj", "spot.obj", "fandisk.obj"}) {
        const std::string path = test::shared_mesh(name);
        if (!test::present_or_skip(path)) continue;
        HalfedgeMesh m = read_mesh(path).mesh;
        m.garbage_collection();
        meshes.push_back({name, std::move(m)});
    }
    return meshes;
}

}  // namespace

TEST_CASE("subdivide_region's closure is no flatter than the input on real and generated meshes",
          "[subdivision][selection][slow]") {
    NullProgress progress;
    for (const NamedMesh& fixture : closure_fixtures()) {
        const HalfedgeMesh& mesh = fixture.mesh;
        const BoundingBox box = bounding_box(mesh);
        const Selection region = sphere_selection(
            mesh, mesh.position(Vertex(mesh.n_vertices() / 3)), 0.2 * box.size().norm());
        REQUIRE(count_selected(region) > 10);
        REQUIRE(count_selected(region) < mesh.n_vertices());
        const double input_min = brute_min_angle(mesh);
        for (SubdivisionScheme scheme :
             {SubdivisionScheme::Loop, SubdivisionScheme::Butterfly,
              SubdivisionScheme::ModifiedButterfly, SubdivisionScheme::Sqrt3}) {
            INFO(fixture.name << ", " << scheme_name(scheme));
            SubdivisionOptions options;
            options.scheme = scheme;
            options.global_closure = true;  // grown until no closure face is flatter
            RegionSubdivisionReport report;
            const SubdivisionResult result =
                subdivide_region(mesh, options, region, progress, report);
            const HalfedgeMesh& out = result.levels.back().mesh;
            REQUIRE(validate(out).ok);
            CHECK(is_closed(out) == is_closed(mesh));  // the bunny has holes, the others none
            CHECK(euler(out) == euler(mesh));
            for (Vertex v : mesh.vertices())
                if (region[v.idx()] == 0.0f) CHECK(same_point(out.position(v), mesh.position(v)));

            // The face count the closure predicts, from the splits found in the output: no
            // coarse face has two split edges (the closure made it red), the split edges are
            // gone from the output (split on both sides: no T-junction), and the report agrees.
            const SplitsFound splits = splits_in(out, mesh.vertices_size());
            const RegionClosureCounts& c = report.closure[0];
            if (scheme == SubdivisionScheme::Sqrt3) {
                CHECK(splits.edges.empty());
                CHECK(splits.centroids == c.red_faces);
                CHECK(out.n_faces() == mesh.n_faces() + 2 * splits.centroids);
            } else {
                std::size_t red = 0, green = 0;
                for (Face f : mesh.faces()) {
                    const auto v = mesh.face_vertices(f);
                    int n = 0;
                    for (int k = 0; k < 3; ++k) {
                        const Index a = v[k].idx(), b = v[(k + 1) % 3].idx();
                        n += int(splits.edges.count({std::min(a, b), std::max(a, b)}));
                    }
                    CHECK(n != 2);
                    red += n == 3 ? 1 : 0;
                    green += n == 1 ? 1 : 0;
                }
                CHECK(red == c.red_faces);
                CHECK(green == c.green_faces);
                CHECK(out.n_faces() == mesh.n_faces() + 3 * red + green);
                for (const auto& e : splits.edges)
                    CHECK(!out.find_edge(Vertex(e.first), Vertex(e.second)).is_valid());
            }

            // The closure's triangles, found independently: 1-to-4, every face that is not a
            // child of a selected face (its vertices' parents are not one selected face's
            // corners); Sqrt3, every face with at most one centroid (the pattern's triangles
            // have two). Untouched input faces are among them: they pass trivially.
            std::set<std::array<Index, 3>> selected_corners;
            for (Face f : mesh.faces()) {
                const auto v = mesh.face_vertices(f);
                std::array<Index, 3> t = {v[0].idx(), v[1].idx(), v[2].idx()};
                std::sort(t.begin(), t.end());
                if (region[t[0]] > 0 && region[t[1]] > 0 && region[t[2]] > 0)
                    selected_corners.insert(t);
            }
            const auto parents =
                out.get_vertex_property<SubdivisionParents>("v:subdivision_parents");
            double closure_min = 180;
            for (Face f : out.faces()) {
                std::set<Index> corners;
                int centroids = 0;
                for (Vertex v : out.face_vertices(f)) {
                    for (int k = 0; k < 3; ++k)
                        if (parents[v][k] != kInvalidIndex) corners.insert(parents[v][k]);
                    centroids += parents[v][2] != kInvalidIndex ? 1 : 0;
                }
                bool closure;
                if (scheme == SubdivisionScheme::Sqrt3) {
                    closure = centroids <= 1;
                } else {
                    std::array<Index, 3> t{};
                    std::size_t k = 0;
                    for (Index i : corners)
                        if (k < 3) t[k++] = i;
                    closure = corners.size() != 3 || selected_corners.count(t) == 0;
                }
                if (!closure) continue;
                closure_min = std::min(closure_min, brute_face_min_angle(out, f));
            }
            CHECK(closure_min >= input_min - 1e-9);
            CHECK(c.min_angle_closure >= report.min_angle_in - 1e-9);
            CHECK(report.min_angle_in == Approx(input_min).margin(1e-9));

            // All ones: the unselected result, bit for bit.
            RegionSubdivisionReport ones_report;
            const SubdivisionResult ones =
                subdivide_region(mesh, options, full_selection(mesh), progress, ones_report);
            const SubdivisionResult whole = subdivide(mesh, options, progress);
            const HalfedgeMesh& x = whole.levels.back().mesh;
            const HalfedgeMesh& y = ones.levels.back().mesh;
            REQUIRE(x.vertices_size() == y.vertices_size());
            CHECK(std::memcmp(x.positions().data(), y.positions().data(),
                              x.positions().size() * sizeof(Point)) == 0);
            CHECK(x.halfedge_to_array() == y.halfedge_to_array());
        }
    }
}

TEST_CASE("uniform_step_1to4_at gives the uniform step's values bit for bit where it is asked",
          "[subdivision][selection]") {
    NullProgress progress;
    std::vector<NamedMesh> meshes;
    meshes.push_back({"default model", make_default_model()});
    meshes.push_back({"open grid", make_grid(8)});  // boundary rules
    meshes.push_back({"torus", make_torus(24, 12, 1.0, 0.35)});
    const std::string bunny = test::shared_mesh("stanford-bunny.obj");
    if (test::present_or_skip(bunny)) {
        HalfedgeMesh m = read_mesh(bunny).mesh;
        m.garbage_collection();
        meshes.push_back({"bunny", std::move(m)});
    }
    for (const NamedMesh& fixture : meshes) {
        const HalfedgeMesh& mesh = fixture.mesh;
        REQUIRE(find_coincident_vertices(mesh).empty());
        for (SubdivisionScheme scheme : {SubdivisionScheme::Loop, SubdivisionScheme::Butterfly,
                                         SubdivisionScheme::ModifiedButterfly}) {
            INFO(fixture.name << ", " << scheme_name(scheme));
            const UniformStep1to4 all = uniform_step_1to4(mesh, scheme, progress);
            // Every third vertex and every other edge.
            std::vector<std::uint8_t> vertices(mesh.vertices_size()), edges(mesh.edges_size());
            for (std::size_t v = 0; v < vertices.size(); ++v) vertices[v] = v % 3 == 0;
            for (std::size_t e = 0; e < edges.size(); ++e) edges[e] = e % 2 == 1;
            const UniformStep1to4 some =
                uniform_step_1to4_at(mesh, scheme, vertices, edges, progress);
            REQUIRE(some.positions.size() == all.positions.size());
            std::size_t checked = 0, differ = 0;
            const std::size_t nv = mesh.vertices_size();
            for (std::size_t i = 0; i < all.positions.size(); ++i) {
                const bool asked = i < nv ? vertices[i] != 0 : edges[i - nv] != 0;
                if (!asked) continue;
                ++checked;
                differ += same_point(all.positions[i], some.positions[i]) &&
                                  all.stencils[i] == some.stencils[i]
                              ? 0
                              : 1;
            }
            CHECK(checked > 0);
            CHECK(differ == 0);
        }
        // Flags that do not fit are refused.
        CHECK_THROWS_AS(uniform_step_1to4_at(mesh, SubdivisionScheme::Loop, {1}, {1}, progress),
                        InvalidArgument);
    }
}

TEST_CASE("uniform_step_1to4_listed gives the uniform step's values bit for bit, packed",
          "[subdivision][selection]") {
    NullProgress progress;
    std::vector<NamedMesh> meshes;
    meshes.push_back({"default model", make_default_model()});
    meshes.push_back({"open grid", make_grid(8)});  // boundary rules
    const std::string bunny = test::shared_mesh("stanford-bunny.obj");
    if (test::present_or_skip(bunny)) {
        HalfedgeMesh m = read_mesh(bunny).mesh;
        m.garbage_collection();
        meshes.push_back({"bunny", std::move(m)});
    }
    for (const NamedMesh& fixture : meshes) {
        const HalfedgeMesh& mesh = fixture.mesh;
        const std::size_t nv = mesh.vertices_size();
        // Every third vertex and every other edge, in the order of the lists.
        std::vector<Index> vertices, edges;
        for (std::size_t v = 0; v < nv; v += 3) vertices.push_back(Index(v));
        for (std::size_t e = 1; e < mesh.edges_size(); e += 2) edges.push_back(Index(e));
        for (SubdivisionScheme scheme : {SubdivisionScheme::Loop, SubdivisionScheme::Butterfly,
                                         SubdivisionScheme::ModifiedButterfly}) {
            INFO(fixture.name << ", " << scheme_name(scheme));
            const UniformStep1to4 all = uniform_step_1to4(mesh, scheme, progress);
            const UniformStep1to4 listed =
                uniform_step_1to4_listed(mesh, scheme, vertices, edges, progress);
            REQUIRE(listed.positions.size() == vertices.size() + edges.size());
            REQUIRE(listed.stencils.size() == listed.positions.size());
            std::size_t differ = 0;
            for (std::size_t i = 0; i < listed.positions.size(); ++i) {
                const std::size_t j =
                    i < vertices.size() ? vertices[i] : nv + edges[i - vertices.size()];
                differ += same_point(all.positions[j], listed.positions[i]) &&
                                  all.stencils[j] == listed.stencils[i]
                              ? 0
                              : 1;
            }
            CHECK(differ == 0);
        }
        // With the listed vertices' rings listed (ascending), Loop's even rule sums over the
        // edges: the same bits again.
        {
            std::vector<std::uint8_t> listed_vertex(nv, 0);
            for (Index v : vertices) listed_vertex[v] = 1;
            std::vector<Index> ring_edges;
            for (Edge e : mesh.edges())
                if (listed_vertex[mesh.vertex(e, 0).idx()] ||
                    listed_vertex[mesh.vertex(e, 1).idx()])
                    ring_edges.push_back(e.idx());
            const UniformStep1to4 all = uniform_step_1to4(mesh, SubdivisionScheme::Loop, progress);
            const UniformStep1to4 listed = uniform_step_1to4_listed(
                mesh, SubdivisionScheme::Loop, vertices, ring_edges, progress, true);
            REQUIRE(listed.positions.size() == vertices.size() + ring_edges.size());
            std::size_t differ = 0;
            for (std::size_t i = 0; i < listed.positions.size(); ++i) {
                const std::size_t j =
                    i < vertices.size() ? vertices[i] : nv + ring_edges[i - vertices.size()];
                differ += same_point(all.positions[j], listed.positions[i]) &&
                                  all.stencils[j] == listed.stencils[i]
                              ? 0
                              : 1;
            }
            INFO(fixture.name << ", loop over the listed rings");
            CHECK(differ == 0);
        }
        // Indices out of range and Sqrt3 are refused.
        CHECK_THROWS_AS(
            uniform_step_1to4_listed(mesh, SubdivisionScheme::Loop, {Index(nv)}, {}, progress),
            InvalidArgument);
        CHECK_THROWS_AS(uniform_step_1to4_listed(mesh, SubdivisionScheme::Sqrt3, {}, {}, progress),
                        InvalidArgument);
    }
}

TEST_CASE("subdivide_region splits boundary edges of an open mesh into a valid boundary",
          "[subdivision][selection]") {
    const HalfedgeMesh mesh = make_grid(8);
    REQUIRE(!is_closed(mesh));
    // A region at a corner of the grid: its boundary edges are split.
    const Selection region = sphere_selection(mesh, mesh.position(Vertex(0)), 0.45);
    REQUIRE(count_selected(region) > 3);
    NullProgress progress;
    for (SubdivisionScheme scheme : {SubdivisionScheme::Loop, SubdivisionScheme::Butterfly,
                                     SubdivisionScheme::ModifiedButterfly}) {
        for (bool local : {true, false}) {
            INFO(scheme_name(scheme) << (local ? ", local closure" : ", grown closure"));
            SubdivisionOptions options;
            options.scheme = scheme;
            options.global_closure = !local;
            options.iterations = 2;
            RegionSubdivisionReport report;
            const SubdivisionResult result =
                subdivide_region(mesh, options, region, progress, report);
            const HalfedgeMesh& first_level = result.levels.front().mesh;
            const HalfedgeMesh& out = result.levels.back().mesh;
            REQUIRE(validate(first_level).ok);
            REQUIRE(validate(out).ok);
            CHECK(euler(out) == euler(mesh));
            const SplitsFound splits = splits_in(first_level, mesh.vertices_size());
            std::size_t boundary_splits = 0;
            for (const auto& e : splits.edges) {
                const Edge coarse = mesh.find_edge(Vertex(e.first), Vertex(e.second));
                REQUIRE(coarse.is_valid());
                boundary_splits += mesh.is_boundary(coarse) ? 1 : 0;
            }
            CHECK(boundary_splits > 0);
            std::size_t boundary_edges = 0;
            for (Edge e : first_level.edges()) boundary_edges += first_level.is_boundary(e);
            std::size_t coarse_boundary = 0;
            for (Edge e : mesh.edges()) coarse_boundary += mesh.is_boundary(e);
            CHECK(boundary_edges == coarse_boundary + boundary_splits);
            for (Vertex v : mesh.vertices())
                if (region[v.idx()] == 0.0f) CHECK(same_point(out.position(v), mesh.position(v)));
        }
    }
    // Sqrt3 at the boundary: faces on it are split 1-to-3, the boundary edges stay.
    for (bool local : {true, false}) {
        SubdivisionOptions options;
        options.scheme = SubdivisionScheme::Sqrt3;
        options.global_closure = !local;
        options.iterations = 2;
        RegionSubdivisionReport report;
        const SubdivisionResult result = subdivide_region(mesh, options, region, progress, report);
        for (const SubdivisionLevel& level : result.levels) {
            REQUIRE(validate(level.mesh).ok);
            CHECK(euler(level.mesh) == euler(mesh));
            std::size_t boundary_edges = 0, coarse_boundary = 0;
            for (Edge e : level.mesh.edges()) boundary_edges += level.mesh.is_boundary(e);
            for (Edge e : mesh.edges()) coarse_boundary += mesh.is_boundary(e);
            CHECK(boundary_edges == coarse_boundary);
        }
        CHECK(result.levels.front().mesh.n_faces() ==
              mesh.n_faces() + 2 * report.closure[0].red_faces);
    }
}

TEST_CASE("a small region's closure stays local by default and repeated levels do not degrade it",
          "[subdivision][selection]") {
    // Issue 38, item 4: 88 selected faces of 2,000 gave 8,000 faces (the closure grew over the
    // whole surface), and with the local closure every level halved the closure's angles again
    // (27.8, 14.3, 9.5, 7.3 degrees from 54). Now the local closure is the default, an earlier
    // level's closure is split 1-to-4 instead of bisected again, and a bisection that would cut
    // below half the input's smallest angle is split 1-to-4 too.
    const HalfedgeMesh mesh = make_default_model();
    const Selection region = sphere_selection(mesh, Point(0, 0, 1), 0.5);
    const double input_min = brute_min_angle(mesh);
    NullProgress progress;
    for (SubdivisionScheme scheme : {SubdivisionScheme::Loop, SubdivisionScheme::Butterfly}) {
        INFO(scheme_name(scheme));
        SubdivisionOptions options;
        options.scheme = scheme;
        options.iterations = 3;
        RegionSubdivisionReport report;
        const SubdivisionResult result = subdivide_region(mesh, options, region, progress, report);
        REQUIRE(result.levels.size() == 3);
        // Local: the first level adds a few hundred faces, not the whole surface's 6,000.
        CHECK(result.levels[0].mesh.n_faces() < mesh.n_faces() + 600);
        CHECK(report.closure[1].closure_reds > 0);  // level 1's closure refined 1-to-4
        for (std::size_t k = 0; k < result.levels.size(); ++k) {
            INFO("level " << k + 1);
            const HalfedgeMesh& out = result.levels[k].mesh;
            REQUIRE(validate(out).ok);
            CHECK(is_closed(out));
            CHECK(report.closure[k].min_angle_closure >= 0.5 * input_min - 1e-6);
            CHECK(brute_min_angle(out) >= 0.5 * input_min - 1e-6);
        }
        // The global closure is still there when asked for: the whole surface refined.
        SubdivisionOptions global = options;
        global.iterations = 1;
        global.global_closure = true;
        RegionSubdivisionReport global_report;
        const SubdivisionResult g = subdivide_region(mesh, global, region, progress, global_report);
        CHECK(g.levels[0].mesh.n_faces() == 4 * mesh.n_faces());
        CHECK(global_report.closure[0].min_angle_closure >= input_min - 1e-9);
    }
    // More levels: no angle under half the input's smallest at any of five levels, where before
    // the closure halved its angles with every level. (The region's border vertices move with
    // every level, so a bisection of a face with such a vertex keeps a margin above the bound:
    // without it Loop's closure drifted to 26.4 degrees at level 4 for a bound of 27.02.)
    // On the default model and on the generated sphere (`trilab-cli generate sphere`, the
    // issue's input). Modified Butterfly on the default model fell to 16.4 degrees at level 3
    // (its extraordinary-vertex stencils at the region's border read the closure's flat,
    // irregular ring): its edge vertices that would make a triangle that flat are now moved
    // toward their edge's midpoint (damped_vertices).
    const HalfedgeMesh sphere = make_icosphere(10);
    const Selection cap = sphere_selection(sphere, Point(0, 0, 1), 0.5);
    const double sphere_min = brute_min_angle(sphere);
    struct Case {
        const HalfedgeMesh* mesh;
        const Selection* region;
        double input_min;
        SubdivisionScheme scheme;
    };
    for (const Case& c : {Case{&mesh, &region, input_min, SubdivisionScheme::Loop},
                          Case{&mesh, &region, input_min, SubdivisionScheme::Butterfly},
                          Case{&mesh, &region, input_min, SubdivisionScheme::ModifiedButterfly},
                          Case{&sphere, &cap, sphere_min, SubdivisionScheme::Loop},
                          Case{&sphere, &cap, sphere_min, SubdivisionScheme::Butterfly},
                          Case{&sphere, &cap, sphere_min, SubdivisionScheme::ModifiedButterfly}}) {
        INFO(scheme_name(c.scheme)
             << (c.mesh == &mesh ? " on the default model" : " on the sphere"));
        SubdivisionOptions five;
        five.scheme = c.scheme;
        five.iterations = 5;
        RegionSubdivisionReport report;
        const SubdivisionResult r = subdivide_region(*c.mesh, five, *c.region, progress, report);
        REQUIRE(r.levels.size() == 5);
        for (std::size_t k = 0; k < report.closure.size(); ++k) {
            INFO("level " << k + 1);
            CHECK(report.closure[k].min_angle_closure >= 0.5 * c.input_min - 1e-9);
            CHECK(brute_min_angle(r.levels[k].mesh) >= 0.5 * c.input_min - 1e-9);
        }
        CHECK(report.min_angle_out >= 0.5 * c.input_min - 1e-9);
        CHECK(validate(r.levels.back().mesh).ok);
        std::size_t damped = 0;
        for (const RegionClosureCounts& counts : report.closure) damped += counts.damped_vertices;
        if (c.scheme == SubdivisionScheme::Loop) CHECK(damped == 0);  // Loop's vertices all move
        if (c.mesh == &mesh && c.scheme == SubdivisionScheme::ModifiedButterfly) {
            CHECK(damped > 0);  // the case that fell to 16.4 degrees
            // Each one says so in its provenance (the Inspector's "which rule made it").
            std::size_t marked = 0;
            for (const SubdivisionLevel& l : r.levels) {
                const auto st = l.mesh.get_vertex_property<int>("v:subdivision_stencil");
                REQUIRE(st);
                for (Vertex v : l.mesh.vertices())
                    marked += st[v] == int(SubdivisionStencil::OddDamped);
            }
            CHECK(marked >= report.closure.back().damped_vertices);
            CHECK(marked > 0);
        }
    }
    // Sqrt3: the earlier levels' closure triangles are completed (Kobbelt's odd generation)
    // before they are refined again. Without it the sphere's cap went 29.2, 26.2, 15.7, 13.9,
    // 12.3 degrees over five levels; with it the region stays valid, closed, and above a third
    // of the input's smallest angle (27.0, 21.4, 21.3, 18.7 from level 2 on).
    SubdivisionOptions sqrt3;
    sqrt3.scheme = SubdivisionScheme::Sqrt3;
    sqrt3.iterations = 5;
    RegionSubdivisionReport sqrt3_report;
    const SubdivisionResult s3 = subdivide_region(sphere, sqrt3, cap, progress, sqrt3_report);
    REQUIRE(s3.levels.size() == 5);
    std::size_t completed = 0;
    for (std::size_t k = 0; k < s3.levels.size(); ++k) {
        INFO("Sqrt3 level " << k + 1);
        const HalfedgeMesh& out = s3.levels[k].mesh;
        REQUIRE(validate(out).ok);
        CHECK(is_closed(out));
        CHECK(euler(out) == 2);
        CHECK(brute_min_angle(out) >= sphere_min / 3);
        CHECK(sqrt3_report.closure[k].min_angle_closure >= sphere_min / 3);
        completed += sqrt3_report.closure[k].completed_edges;
        // The outside stays bit for bit.
        for (Vertex v : sphere.vertices())
            if (cap[v.idx()] == 0.0f) CHECK(same_point(out.position(v), sphere.position(v)));
    }
    CHECK(sqrt3_report.closure[0].completed_edges == 0);
    CHECK(completed > 0);
}
