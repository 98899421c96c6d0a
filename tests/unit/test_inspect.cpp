// The inspector (core/algorithms/inspect.h): its numbers against independent computations
// (the colouring arrays, build_laplacian() over the whole mesh, the decimator's own decisions
// on a short run, a hand-made triangle, brute-force nearest faces) and the provenance the
// subdivision and decimation leave on their outputs.
#include <algorithm>
#include <cmath>
#include <vector>

#include "core/algorithms/coloring.h"
#include "core/algorithms/components.h"
#include "core/algorithms/curvature.h"
#include "core/algorithms/decimation.h"
#include "core/algorithms/feature_detection.h"
#include "core/algorithms/generators.h"
#include "core/algorithms/inspect.h"
#include "core/algorithms/laplacian.h"
#include "core/algorithms/mesh_distance.h"
#include "core/algorithms/subdivision.h"
#include "core/errors.h"
#include "core/features.h"
#include "core/geometry.h"
#include "core/io/mesh_io.h"
#include "core/mesh_builder.h"
#include "test_helpers.h"

using namespace trilab;

namespace {

HalfedgeMesh soup_mesh(const std::vector<Point>& points,
                       const std::vector<std::vector<Index>>& faces) {
    PolygonSoup soup;
    soup.positions = points;
    for (const auto& f : faces) soup.add_face(f);
    LoadReport report;
    return build_mesh(soup, report);
}

/// |(L X)_v| for every vertex from build_laplacian() over the whole mesh (0 on fixed rows).
std::vector<double> laplacian_lengths(const HalfedgeMesh& mesh, LaplacianOperator op) {
    const Laplacian lap = build_laplacian(mesh, op);
    const Eigen::MatrixXd lx = lap.L * gather_positions(mesh, lap.map);
    std::vector<double> out(mesh.vertices_size(), 0.0);
    for (std::size_t r = 0; r < lap.map.rows(); ++r)
        out[lap.map.vertex_of[r].idx()] = lap.fixed[r] ? 0.0 : lx.row(Eigen::Index(r)).norm();
    return out;
}

void check_vertices_against_whole_mesh(const HalfedgeMesh& mesh, std::size_t stride) {
    const VertexCurvatures c = compute_curvatures(mesh);
    std::vector<std::vector<double>> lengths;
    for (const auto& op : kLaplacianOperators) lengths.push_back(laplacian_lengths(mesh, op.value));
    for (Vertex v : mesh.vertices()) {
        if (v.idx() % stride != 0) continue;
        const VertexInspection x = inspect_vertex(mesh, v);
        const Index i = v.idx();
        INFO("vertex " << i);
        CHECK(x.curvature_valid == (c.valid[i] != 0));
        CHECK(x.k1 == c.k1[i]);  // the same faces in the same order: the same bits
        CHECK(x.k2 == c.k2[i]);
        CHECK(x.mean == c.mean[i]);
        CHECK(x.gaussian == c.gaussian[i]);
        CHECK(x.shape_index == c.shape_index[i]);
        for (std::size_t k = 0; k < lengths.size(); ++k) {
            INFO("operator " << kLaplacianOperators[k].id);
            CHECK(x.laplacian_length[k] ==
                  Approx(lengths[k][i]).epsilon(1e-9).margin(1e-14 * (1 + lengths[k][i])));
        }
    }
}

/// The decimator's order: the cost as it keys the heap (a float, -0 made +0), then the edge.
bool key_less(const std::pair<float, Index>& a, const std::pair<float, Index>& b) {
    return a < b;
}

}  // namespace

TEST_CASE("inspect_vertex: curvatures equal the colouring arrays, Laplacians build_laplacian's",
          "[inspect]") {
    HalfedgeMesh sphere = make_noisy_sphere(3, 0.05, 7);
    REQUIRE(validate(sphere));
    check_vertices_against_whole_mesh(sphere, 1);
    HalfedgeMesh grid = make_grid(8);  // open: boundary vertices are fixed, no curvature
    check_vertices_against_whole_mesh(grid, 1);
    const VertexInspection corner = inspect_vertex(grid, Vertex(0));
    CHECK(corner.boundary);
    CHECK_FALSE(corner.curvature_valid);
    CHECK(corner.laplacian_fixed);
    const std::string bunny = test::shared_mesh("stanford-bunny.obj");
    if (test::exists(bunny)) check_vertices_against_whole_mesh(read_mesh(bunny).mesh, 997);
}

TEST_CASE("inspect_vertex reports the fields, the smoothing distance and the band", "[inspect]") {
    HalfedgeMesh mesh = make_icosphere(2);
    const Vertex v(5);
    std::vector<double> field(mesh.vertices_size(), 0.0);
    field[5] = 0.25;
    std::vector<Point> reference = mesh.positions();
    for (Point& p : reference) p *= 0.9;
    std::vector<Vector3> band(mesh.vertices_size(), Vector3(1, 2, 2));
    InspectionInputs inputs;
    inputs.fields.push_back({"Frequency 3", &field});
    inputs.reference = &reference;
    inputs.displacement = &band;
    const VertexInspection x = inspect_vertex(mesh, v, inputs);
    REQUIRE(x.field_values.size() == 1);
    CHECK(x.field_values[0].second == 0.25);
    REQUIRE(x.smoothing_distance);
    CHECK(*x.smoothing_distance == smoothing_distance(mesh, reference)[5]);
    REQUIRE(x.displacement);
    CHECK(x.displacement->norm() == Approx(3));
    CHECK(x.valence == mesh.valence(v));
    const auto fields = inspection_fields(x);
    const auto has = [&](const std::string& key) {
        return std::any_of(fields.begin(), fields.end(),
                           [&](const InspectionField& f) { return f.key == key; });
    };
    CHECK(has("mean_curvature"));
    CHECK(has("laplacian_second_order"));
    CHECK(has("field_frequency_3"));
    CHECK(has("smoothing_distance"));
    CHECK(has("band_displacement"));
    CHECK_THROWS_AS(inspect_vertex(mesh, Vertex(Index(mesh.vertices_size()))), InvalidArgument);
}

TEST_CASE("inspect_edge answers as the decimator decides on a short run", "[inspect]") {
    // The decimator pops edges cheapest first and refuses or collapses each; nothing changes
    // until the first collapse. Replaying that order from the inspector's answers must give
    // the same refusal counts and the same first collapse.
    HalfedgeMesh mesh = make_noisy_sphere(4, 0.3, 11);
    DecimationOptions o;
    o.target_vertices = mesh.n_vertices() - 1;
    auto scenario = GENERATE(0, 1, 2, 3);
    if (scenario == 2) {
        o.roundness = true;  // the cheapest quadric collapses make slivers
        o.min_roundness = 0.5;
    } else if (scenario == 3) {
        o.cost = DecimationCost::Roundness;
        o.roundness = true;
        o.min_roundness = 0.3;
    }
    INFO("scenario " << scenario);
    DecimationResult run = decimate(mesh, o);
    if (scenario == 1) {
        // A small normal angle on a noisy sphere: a run whose cheapest collapses flip normals.
        bool found = false;
        for (std::uint32_t seed = 1; seed < 40 && !found; ++seed) {
            for (double angle : {3.0, 4.0, 6.0}) {
                mesh = make_noisy_sphere(3, 0.4, seed);
                o.target_vertices = mesh.n_vertices() - 1;
                o.max_normal_angle = angle;
                run = decimate(mesh, o);
                if (run.report.collapses == 1 && run.report.refused_normal_flip > 0) {
                    found = true;
                    break;
                }
            }
        }
        REQUIRE(found);
    }
    REQUIRE(validate(mesh));
    REQUIRE(run.report.collapses == 1);
    const auto first = next_collapses(mesh, o);
    REQUIRE(first.size() == 1);

    std::vector<std::pair<float, Index>> order;
    std::vector<CollapseExplanation> why(mesh.edges_size());
    for (Edge e : mesh.edges()) {
        const EdgeInspection x = inspect_edge(mesh, e, o);
        REQUIRE(x.costs.size() == 2);
        const CostInspection& c = x.costs[std::size_t(o.cost)];
        why[e.idx()] = c.collapse;
        if (c.collapse.possible) order.push_back({float(c.collapse.cost) + 0.0f, e.idx()});
    }
    std::sort(order.begin(), order.end(), key_less);
    std::size_t topology = 0, normal_flip = 0, roundness = 0;
    Edge collapsed;
    for (const auto& [cost, e] : order) {
        const CollapseExplanation& x = why[e];
        if (x.refusal == CollapseRefusal::None) {
            collapsed = Edge(e);
            break;
        }
        topology += x.refusal == CollapseRefusal::Topology;
        normal_flip += x.refusal == CollapseRefusal::NormalFlip;
        roundness += x.refusal == CollapseRefusal::Roundness;
        // The numbers are past the limits of the constraint that refuses.
        if (x.refusal == CollapseRefusal::NormalFlip) {
            CHECK(x.normal_flip_refuses);
            CHECK((x.degenerate_face || x.largest_normal_change > x.max_normal_angle));
        }
        if (x.refusal == CollapseRefusal::Roundness) {
            CHECK(x.roundness_refuses);
            CHECK(x.roundness < x.min_roundness);
        }
    }
    REQUIRE(collapsed.is_valid());
    CHECK(topology == run.report.refused_topology);
    CHECK(normal_flip == run.report.refused_normal_flip);
    CHECK(roundness == run.report.refused_roundness);
    const CollapseExplanation& x = why[collapsed.idx()];
    CHECK(x.removed == first[0][0]);
    CHECK(x.kept == first[0][1]);
    CHECK(x.topology_ok);
    CHECK_FALSE(x.normal_flip_refuses);
    CHECK(x.largest_normal_change <= o.max_normal_angle);
    if (scenario == 1) CHECK(normal_flip > 0);
    if (scenario == 2) CHECK(roundness > 0);
    if (scenario >= 2) CHECK(x.roundness >= o.min_roundness);
    CHECK(validate(run.levels.back().mesh));
}

TEST_CASE("inspect_edge: a constraint that refuses every collapse says so with its numbers",
          "[inspect]") {
    HalfedgeMesh mesh = make_noisy_sphere(3, 0.3, 5);
    DecimationOptions o;
    o.roundness = true;
    o.min_roundness = 0.999;  // no collapse of a noisy sphere keeps its triangles this round
    const DecimationResult run = decimate(mesh, o);
    CHECK(run.report.collapses == 0);
    CHECK(run.report.stop == DecimationStop::Constraints);
    std::size_t by_roundness = 0;
    for (Edge e : mesh.edges()) {
        const EdgeInspection x = inspect_edge(mesh, e, o);
        const CollapseExplanation& c = x.costs[0].collapse;
        CHECK(c.refusal != CollapseRefusal::None);
        if (c.refusal == CollapseRefusal::Roundness) {
            ++by_roundness;
            CHECK(c.roundness < 0.999);
        }
        CHECK(c.roundness_refuses == (c.possible && c.roundness < 0.999));
    }
    CHECK(by_roundness > 0);
    // The fields say it in words and numbers.
    const auto fields = inspection_fields(inspect_edge(mesh, Edge(0), o));
    const auto r = std::find_if(fields.begin(), fields.end(),
                                [](const InspectionField& f) { return f.key == "roundness"; });
    REQUIRE(r != fields.end());
    CHECK(r->text.rfind("refuses", 0) == 0);
    REQUIRE(r->numbers.size() == 3);
    CHECK(r->numbers[1] == 0.999);
}

TEST_CASE("inspect_edge: length, dihedral angle and cotangent weight", "[inspect]") {
    // Two right triangles folded at 90 degrees along the x axis.
    HalfedgeMesh mesh =
        soup_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, {{0, 1, 2}, {1, 0, 3}});
    const Edge e = mesh.find_edge(Vertex(0), Vertex(1));
    const EdgeInspection x = inspect_edge(mesh, e);
    CHECK(x.length == Approx(1));
    CHECK_FALSE(x.boundary);
    REQUIRE(x.dihedral_angle);
    CHECK(*x.dihedral_angle == Approx(90));
    CHECK(x.cotangent_weight == Approx(cotangent_weight(mesh, e)));
    CHECK(x.cotangent_weight == Approx(1));  // (cot 45 + cot 45) / 2
    const EdgeInspection b = inspect_edge(mesh, mesh.find_edge(Vertex(1), Vertex(2)));
    CHECK(b.boundary);
    CHECK_FALSE(b.dihedral_angle);
    CHECK_THROWS_AS(inspect_edge(mesh, Edge(99)), InvalidArgument);
}

TEST_CASE("inspect_face on hand-made triangles", "[inspect]") {
    const double s3 = std::sqrt(3.0);
    HalfedgeMesh mesh =
        soup_mesh({{0, 0, 0}, {2, 0, 0}, {0, 1, 0}, {5, 0, 0}, {6, 0, 0}, {5.5, s3 / 2, 0}},
                  {{0, 1, 2}, {3, 4, 5}});
    const FaceInspection r = inspect_face(mesh, Face(0));
    CHECK(r.area == Approx(1));
    CHECK(r.angles[0] == Approx(90));
    CHECK(r.angles[1] == Approx(std::atan(0.5) * 180 / M_PI));
    CHECK(r.angles[2] == Approx(std::atan(2.0) * 180 / M_PI));
    CHECK(r.angles[0] + r.angles[1] + r.angles[2] == Approx(180));
    CHECK(r.normal.isApprox(Vector3(0, 0, 1)));
    CHECK(r.aspect_ratio == Approx(s3 * 5 / 4));  // longest sqrt(5), area 1
    CHECK(r.components == 2);
    const FaceInspection eq = inspect_face(mesh, Face(1));
    CHECK(eq.aspect_ratio == Approx(1));
    // Frey-Borouchaki Q = 4 sqrt(3) A / (P h_max): the right triangle's 4 sqrt(3) / ((3 +
    // sqrt(5)) sqrt(5)), the equilateral one's 1 (issue 41, item 3).
    CHECK(r.quality == Approx(4 * s3 / ((3 + std::sqrt(5.0)) * std::sqrt(5.0))));
    CHECK(eq.quality == Approx(1));
    CHECK(eq.component != r.component);
    CHECK(eq.component == label_face_components(mesh).of_face[1]);
    CHECK_THROWS_AS(inspect_face(mesh, Face(2)), InvalidArgument);
}

TEST_CASE("nearest_face is the face closest to the point", "[inspect]") {
    HalfedgeMesh mesh = make_noisy_sphere(3, 0.2, 3);
    std::uint32_t seed = 12345;
    const auto rnd = [&] {
        seed = seed * 1664525u + 1013904223u;
        return double(seed >> 8) / double(1u << 24) * 3.0 - 1.5;
    };
    for (int k = 0; k < 50; ++k) {
        const Point p(rnd(), rnd(), rnd());
        const Face f = nearest_face(mesh, p);
        REQUIRE(f.is_valid());
        double best = 1e300;
        for (Face g : mesh.faces()) {
            const auto c = mesh.face_vertices(g);
            best = std::min(best,
                            (closest_point_on_triangle(p, mesh.position(c[0]), mesh.position(c[1]),
                                                       mesh.position(c[2])) -
                             p)
                                .squaredNorm());
        }
        const auto c = mesh.face_vertices(f);
        CHECK((closest_point_on_triangle(p, mesh.position(c[0]), mesh.position(c[1]),
                                         mesh.position(c[2])) -
               p)
                  .squaredNorm() == best);
        const Vertex corner = nearest_corner(mesh, f, p);
        CHECK((corner == c[0] || corner == c[1] || corner == c[2]));
        const Edge side = nearest_side(mesh, f, p);
        CHECK((mesh.face(HalfedgeMesh::halfedge(side, 0)) == f ||
               mesh.face(HalfedgeMesh::halfedge(side, 1)) == f));
    }
    CHECK_FALSE(nearest_face(HalfedgeMesh(), Point::Zero()).is_valid());
}

TEST_CASE("subdivision records each vertex's stencil and parents", "[inspect][subdivision]") {
    const HalfedgeMesh tet = make_tetrahedron();
    SubdivisionOptions o;
    o.iterations = 2;
    NullProgress progress;
    const SubdivisionResult r = subdivide(tet, o, progress);
    REQUIRE(r.levels.size() == 2);
    const HalfedgeMesh* coarse = &tet;
    for (const SubdivisionLevel& level : r.levels) {
        const HalfedgeMesh& fine = level.mesh;
        REQUIRE(validate(fine));
        const auto stencil = fine.get_vertex_property<int>("v:subdivision_stencil");
        const auto parents = fine.get_vertex_property<SubdivisionParents>("v:subdivision_parents");
        REQUIRE(stencil);
        REQUIRE(parents);
        for (Vertex v : fine.vertices()) {
            const auto st = SubdivisionStencil(stencil[v]);
            const SubdivisionParents p = parents[v];
            if (v.idx() < coarse->vertices_size()) {
                CHECK(is_even_stencil(st));
                CHECK(p[0] == v.idx());  // an even vertex's parent is itself
                CHECK(p[1] == kInvalidIndex);
                const unsigned n = coarse->valence(Vertex(p[0]));
                CHECK(st == (n == 6 ? SubdivisionStencil::EvenRegular
                                    : SubdivisionStencil::EvenExtraordinary));
            } else {
                CHECK(st == SubdivisionStencil::OddRegular);
                REQUIRE(p[0] < coarse->vertices_size());
                REQUIRE(p[1] < coarse->vertices_size());
                CHECK(p[2] == kInvalidIndex);
                // Loop's edge rule: 3/8 of the parents, 1/8 of the two opposite corners.
                const Halfedge h = coarse->find_halfedge(Vertex(p[0]), Vertex(p[1]));
                REQUIRE(h.is_valid());
                const Point& c = coarse->position(coarse->to_vertex(coarse->next(h)));
                const Point& d =
                    coarse->position(coarse->to_vertex(coarse->next(HalfedgeMesh::twin(h))));
                const Point expected =
                    0.375 * (coarse->position(Vertex(p[0])) + coarse->position(Vertex(p[1]))) +
                    0.125 * (c + d);
                CHECK((fine.position(v) - expected).norm() < 1e-12);
                // and the morph starts at the parents' midpoint
                CHECK((level.correspondence.positions[v.idx()] -
                       0.5 * (coarse->position(Vertex(p[0])) + coarse->position(Vertex(p[1]))))
                          .norm() < 1e-12);
            }
        }
        const VertexInspection x = inspect_vertex(fine, Vertex(Index(fine.vertices_size() - 1)));
        REQUIRE(x.subdivision);
        CHECK_FALSE(x.subdivision->even);
        CHECK(x.subdivision->parents.size() == 2);
        coarse = &fine;
    }
}

TEST_CASE("subdivision provenance on open meshes and Sqrt3", "[inspect][subdivision]") {
    NullProgress progress;
    const HalfedgeMesh grid = make_grid(3);
    SubdivisionOptions o;
    o.scheme = SubdivisionScheme::ModifiedButterfly;
    const SubdivisionResult r = subdivide(grid, o, progress);
    const HalfedgeMesh& fine = r.levels.back().mesh;
    REQUIRE(validate(fine));
    const auto stencil = fine.get_vertex_property<int>("v:subdivision_stencil");
    const auto parents = fine.get_vertex_property<SubdivisionParents>("v:subdivision_parents");
    std::size_t boundary_odd = 0;
    for (Vertex v : fine.vertices()) {
        const auto st = SubdivisionStencil(stencil[v]);
        if (v.idx() < grid.vertices_size()) {
            CHECK(st == SubdivisionStencil::EvenKept);  // interpolating
            CHECK(fine.position(v) == grid.position(v));
        } else if (st == SubdivisionStencil::OddBoundary) {
            ++boundary_odd;
            CHECK(grid.is_boundary(grid.find_edge(Vertex(parents[v][0]), Vertex(parents[v][1]))));
        }
    }
    CHECK(boundary_odd == 12);  // a 3 x 3 grid has 12 boundary edges

    const HalfedgeMesh cube = make_cube();
    o.scheme = SubdivisionScheme::Sqrt3;
    const SubdivisionResult r3 = subdivide(cube, o, progress);
    const HalfedgeMesh& s3 = r3.levels.back().mesh;
    REQUIRE(validate(s3));
    const auto st3 = s3.get_vertex_property<int>("v:subdivision_stencil");
    const auto pa3 = s3.get_vertex_property<SubdivisionParents>("v:subdivision_parents");
    for (Vertex v : s3.vertices()) {
        if (v.idx() < cube.vertices_size()) {
            CHECK(SubdivisionStencil(st3[v]) == SubdivisionStencil::EvenRelaxed);
            continue;
        }
        CHECK(SubdivisionStencil(st3[v]) == SubdivisionStencil::OddFace);
        const SubdivisionParents p = pa3[v];
        const Point centroid = (cube.position(Vertex(p[0])) + cube.position(Vertex(p[1])) +
                                cube.position(Vertex(p[2]))) /
                               3.0;
        CHECK((s3.position(v) - centroid).norm() < 1e-12);
    }
}

TEST_CASE("decimation: every surviving vertex knows its index in the input",
          "[inspect][decimation]") {
    const HalfedgeMesh mesh = make_noisy_sphere(4, 0.1, 9);
    DecimationOptions o;
    o.cost = DecimationCost::Roundness;  // halfedge collapses: kept vertices do not move
    o.iterations = 2;
    o.percent = 40;
    const DecimationResult r = decimate(mesh, o);
    REQUIRE(r.levels.size() == 2);
    for (const DecimationLevel& level : r.levels) {
        REQUIRE(validate(level.mesh));
        const auto source = level.mesh.get_vertex_property<Index>(kDecimationSourceName);
        REQUIRE(source);
        std::vector<Index> seen;
        for (Vertex v : level.mesh.vertices()) {
            REQUIRE(source[v] < mesh.vertices_size());
            CHECK(level.mesh.position(v) == mesh.position(Vertex(source[v])));
            seen.push_back(source[v]);
        }
        std::sort(seen.begin(), seen.end());
        CHECK(std::adjacent_find(seen.begin(), seen.end()) == seen.end());
        const VertexInspection x = inspect_vertex(level.mesh, Vertex(3));
        REQUIRE(x.decimation_source);
        CHECK(*x.decimation_source == source[Vertex(3)]);
    }
    CHECK_FALSE(mesh.has_vertex_property(kDecimationSourceName));  // the input is untouched
}

TEST_CASE("The Inspector says a vertex's feature class and why, and an edge's sharpness",
          "[inspect][features]") {
    // Issue 39: which rule made a vertex and why (a corner because three sharp edges meet).
    HalfedgeMesh cube = generate("cube");
    CHECK_FALSE(inspect_vertex(cube, Vertex(0)).feature);  // no features stored: no row
    FeatureDetectionOptions o;
    o.angle_deg = 60;
    detect_features(cube, o);
    // Every cube corner has three sharp edges.
    const VertexInspection corner = inspect_vertex(cube, Vertex(0));
    REQUIRE(corner.feature);
    CHECK(corner.feature->cls == VertexClass::Corner);
    CHECK(corner.feature->sharp_edges == 3);
    CHECK(feature_role_text(*corner.feature) ==
          "corner: 3 sharp edges meet (Loop keeps it where it is)");
    bool shown = false;
    for (const InspectionField& f : inspection_fields(corner))
        shown = shown || (f.key == "feature_class" && f.text.rfind("corner: 3 sharp", 0) == 0);
    CHECK(shown);
    // Classes from the counts, as classify_vertices() gives them.
    const VertexClassification classes = classify_vertices(cube, false);
    for (Vertex v : cube.vertices()) {
        const VertexInspection i = inspect_vertex(cube, v);
        REQUIRE(i.feature);
        CHECK(i.feature->cls == classes.classes[v.idx()]);
    }
    VertexInspection::FeatureRole crease{VertexClass::Crease, 2, false};
    CHECK(feature_role_text(crease).rfind("crease: 2 sharp edges", 0) == 0);
    VertexInspection::FeatureRole tagged{VertexClass::Corner, 0, true};
    CHECK(feature_role_text(tagged) == "corner: tagged (Loop keeps it where it is)");
    // An edge's sharpness in words.
    Edge sharp_edge, smooth_edge;
    for (Edge e : cube.edges()) (sharpness(cube, e) > 0 ? sharp_edge : smooth_edge) = e;
    const EdgeInspection se = inspect_edge(cube, sharp_edge, DecimationOptions{});
    REQUIRE(se.sharpness);
    CHECK(std::isinf(*se.sharpness));
    set_sharpness(cube, sharp_edge, 2.5f);
    bool semi = false;
    for (const InspectionField& f :
         inspection_fields(inspect_edge(cube, sharp_edge, DecimationOptions{})))
        semi = semi || (f.key == "sharpness" &&
                        f.text == "2.5 (semi-sharp: the sharp rule for 2 levels, then blended)");
    CHECK(semi);
    CHECK(*inspect_edge(cube, smooth_edge, DecimationOptions{}).sharpness == 0.0f);
}
