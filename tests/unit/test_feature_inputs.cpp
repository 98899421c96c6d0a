// Bad feature input (issue 39): a sharpness below 0 or not a number, an edge index past the
// end, a feature file written for another mesh, non-manifold feature junctions. Each gets a
// clear error (or, for the junctions, the corner rule and a line saying so) and changes nothing.
#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "app/ops/operation.h"
#include "core/algorithms/decimation.h"
#include "core/algorithms/fairing.h"
#include "core/algorithms/feature_detection.h"
#include "core/algorithms/generators.h"
#include "core/algorithms/level_of_detail.h"
#include "core/algorithms/subdivision.h"
#include "core/errors.h"
#include "core/features.h"
#include "core/io/mesh_io.h"
#include "core/mesh_builder.h"
#include "core/validate.h"
#include "test_helpers.h"

using namespace trilab;

namespace {

constexpr SubdivisionScheme kSchemes[] = {SubdivisionScheme::Loop, SubdivisionScheme::Sqrt3,
                                          SubdivisionScheme::Butterfly,
                                          SubdivisionScheme::ModifiedButterfly};

const std::string kPlyHead =
    "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
    "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
    "element edge 1\nproperty int vertex1\nproperty int vertex2\nproperty float crease\n"
    "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";

}  // namespace

TEST_CASE("a bad sharpness is refused by every operation that reads the features",
          "[features][creases][errors]") {
    HalfedgeMesh block = make_block(1, 1, 1);
    FeatureDetectionOptions fo;
    fo.angle_deg = 60;
    detect_features(block, fo);
    const test::FpTrapsOff traps_off;  // NaN on purpose
    for (float bad : {-1.0f, std::numeric_limits<float>::quiet_NaN()}) {
        INFO("sharpness " << bad);
        HalfedgeMesh m = block;
        sharpness_property(m)[Edge(3)] = bad;
        const HalfedgeMesh before = m;
        REQUIRE_FALSE(validate(m).ok);
        NullProgress progress;
        for (SubdivisionScheme scheme : kSchemes) {
            SubdivisionOptions so;
            so.scheme = scheme;
            REQUIRE_THROWS_WITH(subdivide(m, so, progress),
                                Catch::Contains("invalid features") && Catch::Contains("edge 3"));
        }
        DecimationOptions d;
        d.percent = 50;
        REQUIRE_THROWS_WITH(decimate(m, d), Catch::Contains("decimate: invalid features") &&
                                                Catch::Contains("edge 3"));
        FairingOptions f;
        REQUIRE_THROWS_WITH(
            smooth(m, f), Catch::Contains("smooth: invalid features") && Catch::Contains("edge 3"));
        // Nothing changed.
        CHECK(m.positions() == before.positions());
        const std::vector<float>& now = m.get_edge_property<float>(kSharpnessProperty).vector();
        const std::vector<float>& was =
            before.get_edge_property<float>(kSharpnessProperty).vector();
        REQUIRE(now.size() == was.size());
        CHECK(std::memcmp(now.data(), was.data(), now.size() * sizeof(float)) == 0);  // NaN too
    }
    // set_sharpness() refuses the same values and an edge past the end or deleted.
    HalfedgeMesh m = block;
    REQUIRE_THROWS_AS(set_sharpness(m, Edge(0), -0.5f), InvalidArgument);
    REQUIRE_THROWS_AS(set_sharpness(m, Edge(0), std::numeric_limits<float>::quiet_NaN()),
                      InvalidArgument);
    REQUIRE_THROWS_AS(set_sharpness(m, Edge(Index(m.edges_size() + 10)), 1.0f), InvalidArgument);
    m.collapse(m.halfedge(Edge(0), 0));
    REQUIRE_THROWS_AS(set_sharpness(m, Edge(0), 1.0f), InvalidArgument);
    Edge live;
    for (Edge e : m.edges()) live = e;
    set_sharpness(m, live, kInfiniteSharpness);  // +inf is a sharpness
    CHECK(sharpness(m, live) == kInfiniteSharpness);
}

TEST_CASE("a feature file with a non-finite crease or written for another mesh is refused",
          "[features][creases][errors][io]") {
    // Not a number, infinity (PLY writes infinite sharpness as 10, OpenSubdiv's infinity).
    REQUIRE_THROWS_WITH(read_ply_bytes(kPlyHead + "0 1 nan\n", "bad.ply"),
                        Catch::Contains("bad.ply") && Catch::Contains("crease"));
    REQUIRE_THROWS_WITH(read_ply_bytes(kPlyHead + "0 1 inf\n", "bad.ply"),
                        Catch::Contains("bad.ply") && Catch::Contains("crease"));
    // The edges of another mesh: a vertex index past this one's end names the edge.
    REQUIRE_THROWS_WITH(read_ply_bytes(kPlyHead + "0 3 1\n", "other.ply"),
                        Catch::Contains("edge 0") && Catch::Contains("vertex index 3"));
    // Vertex pairs that no edge of this mesh joins: dropped, counted in a note, no features.
    const LoadedMesh l = read_ply_bytes(
        "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
        "property float z\nelement face 2\nproperty list uchar int vertex_indices\n"
        "element edge 2\nproperty int vertex1\nproperty int vertex2\nproperty float crease\n"
        "end_header\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n3 0 1 2\n3 1 3 2\n0 3 10\n0 3 2\n",
        "other.ply");
    REQUIRE_VALID(l.mesh);
    CHECK_FALSE(has_features(l.mesh));
    bool noted = false;
    for (const std::string& n : l.report.notes)
        noted = noted || n.find("joins two vertices") != std::string::npos;
    CHECK(noted);
}

TEST_CASE("non-manifold feature junctions are corners, and the report says so",
          "[features][creases][errors]") {
    // Two tetrahedra sharing one vertex (a non-manifold point: the builder splits it into two
    // copies at the same place); every edge is sharp (70.5 degrees), so at each vertex three
    // feature curves meet.
    PolygonSoup soup;
    soup.positions = {Point(0, 0, 0),  Point(1, 0, 0),  Point(0, 1, 0), Point(0, 0, 1),
                      Point(-1, 0, 0), Point(0, -1, 0), Point(0, 0, -1)};
    for (const std::vector<Index>& f : std::vector<std::vector<Index>>{{0, 2, 1},
                                                                       {0, 1, 3},
                                                                       {0, 3, 2},
                                                                       {1, 2, 3},
                                                                       {0, 4, 5},
                                                                       {0, 6, 4},
                                                                       {0, 5, 6},
                                                                       {4, 6, 5}})
        soup.add_face(f);
    LoadReport lr;
    const HalfedgeMesh base = build_mesh(soup, lr);
    REQUIRE(lr.nonmanifold_vertices_split == 1);
    NullProgress progress;
    const OperationResult r = run_operation(parse_operation("features --angle 40"), base, progress);
    const FeatureDetectionReport* report = report_of<FeatureDetectionReport>(r);
    REQUIRE(report);
    CHECK(report->corners == 8);
    CHECK(report->junctions == 8);
    bool said = false;
    for (const std::string& line : r.report)
        said = said || line.find("non-manifold junctions") != std::string::npos;
    CHECK(said);
    const HalfedgeMesh& m = r.steps.back().mesh;
    const VertexClassification c = classify_vertices(m, false);
    CHECK(c.corners == m.n_vertices());
    // Every scheme keeps them where they are.
    for (SubdivisionScheme scheme : kSchemes) {
        INFO(scheme_name(scheme));
        SubdivisionOptions so;
        so.scheme = scheme;
        so.iterations = 2;
        const SubdivisionResult s = subdivide(m, so, progress);
        for (const SubdivisionLevel& l : s.levels) REQUIRE_VALID(l.mesh);
        for (Vertex v : m.vertices()) CHECK(s.levels.back().mesh.position(v) == m.position(v));
    }
}

TEST_CASE("the level-of-detail slider keeps the features at every level",
          "[features][creases][lod]") {
    HalfedgeMesh block = make_block(3, 3, 3);
    FeatureDetectionOptions fo;
    fo.angle_deg = 60;
    detect_features(block, fo);
    // The block spans [-1, 1]^3: a vertex keeps the box's shape when its largest coordinate is
    // 1 in magnitude; a corner when all three are.
    const auto on_box = [](const Point& p) {
        return std::abs(p.lpNorm<Eigen::Infinity>() - 1.0) < 1e-12;
    };
    const auto corners_at = [](const LevelOfDetail& lod) {
        std::size_t n = 0;
        for (Index v : lod.live_vertices()) {
            const Point& p = lod.positions()[v];
            n += std::abs(std::abs(p.x()) - 1) < 1e-12 && std::abs(std::abs(p.y()) - 1) < 1e-12 &&
                         std::abs(std::abs(p.z()) - 1) < 1e-12
                     ? 1
                     : 0;
        }
        return n;
    };
    NullProgress progress;
    for (FeatureSource source : {FeatureSource::Stored, FeatureSource::None}) {
        DecimationOptions o;
        o.features = source;
        const ProgressiveBuild pb = build_progressive_mesh(block, o, 10, progress);
        LevelOfDetail lod(pb.progressive);
        bool all_on_box = true;
        std::size_t fewest_corners = 8;
        for (std::size_t level : {std::size_t(0), lod.max_level() / 2, lod.max_level()}) {
            lod.set_level(level);
            for (Index v : lod.live_vertices())
                all_on_box = all_on_box && on_box(lod.positions()[v]);
            fewest_corners = std::min(fewest_corners, corners_at(lod));
        }
        if (source == FeatureSource::Stored) {
            CHECK(all_on_box);
            CHECK(fewest_corners == 8);
        } else {  // without the features the slider wears the box down
            CHECK_FALSE((all_on_box && fewest_corners == 8));
        }
    }
}
