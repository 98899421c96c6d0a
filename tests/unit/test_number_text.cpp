// Numbers and counts in messages (core/number_text.h), and the messages that use them.
#include <string>
#include <vector>

#include "app/ops/operation.h"
#include "core/algorithms/generators.h"
#include "core/algorithms/weld.h"
#include "core/errors.h"
#include "core/mesh_builder.h"
#include "core/number_text.h"
#include "test_helpers.h"

using namespace trilab;

namespace {

bool has_text(const std::vector<std::string>& lines, const std::string& text) {
    for (const std::string& l : lines)
        if (l.find(text) != std::string::npos) return true;
    return false;
}

}  // namespace

TEST_CASE("count_text writes the singular for one and the plural otherwise", "[text]") {
    CHECK(count_text(0, "vertex", "vertices") == "0 vertices");
    CHECK(count_text(1, "vertex", "vertices") == "1 vertex");
    CHECK(count_text(2, "vertex", "vertices") == "2 vertices");
    CHECK(count_text(1, "coincident vertex left apart", "coincident vertices left apart") ==
          "1 coincident vertex left apart");
}

TEST_CASE("number_text writes the shortest text that reads back", "[text]") {
    CHECK(number_text(1e9) == "1e+09");
    CHECK(number_text(0.5) == "0.5");
    CHECK(number_text(-3) == "-3");
    CHECK(number_text(0.1) == "0.1");
    CHECK(std::stod(number_text(1.0 / 3.0)) == 1.0 / 3.0);
}

TEST_CASE("the load report counts in the singular for one", "[text][builder]") {
    LoadReport r;
    r.polygons_triangulated = 1;
    r.triangles_from_polygons = 2;
    r.nonmanifold_vertices_split = 1;
    r.isolated_vertices = 3;
    const std::vector<std::string> lines = r.lines();
    CHECK(has_text(lines, "1 polygon triangulated"));
    CHECK(has_text(lines, "2 triangles made from polygons"));
    CHECK(has_text(lines, "1 non-manifold vertex split"));
    CHECK(has_text(lines, "3 isolated vertices kept"));
}

TEST_CASE("weld says 1 coincident vertex, and its tolerance as people write it", "[text][weld]") {
    // A bow-tie: two fans meeting at one vertex, which the loader splits in two; joining
    // the copies again would make a non-manifold vertex, so one is left apart.
    PolygonSoup s;
    s.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {-1, 0, 0}, {-1, -1, 0}};
    s.add_face({0, 1, 2});
    s.add_face({0, 3, 4});
    LoadReport report;
    const HalfedgeMesh mesh = build_mesh(s, report);
    REQUIRE(mesh.n_vertices() == 6);
    const WeldResult w = weld_coincident_vertices(mesh);
    REQUIRE_VALID(w.mesh);
    REQUIRE(w.report.vertices_left_apart == 1);
    CHECK(has_text(w.report.notes, "1 coincident vertex left apart"));
}

TEST_CASE("weld's refusals write the tolerance as people write it", "[text][weld]") {
    NullProgress progress;
    // Too large: every vertex within reach of every other (4002^2 pairs, above the limit).
    const HalfedgeMesh many =
        run_operation(parse_operation("subdivide"), generate("default"), progress)
            .steps.back()
            .mesh;
    REQUIRE(many.n_vertices() == 4002);
    // Too small: cells of 1e-300 for coordinates of magnitude 1.
    for (const char* text : {"weld --tolerance 1e9", "weld --tolerance 1e-300"}) {
        INFO(text);
        try {
            run_operation(parse_operation(text), many, progress);
            FAIL("refused");
        } catch (const InvalidArgument& e) {
            const std::string m = e.what();
            CHECK((m.find("tolerance 1e+09 is too large") != std::string::npos ||
                   m.find("tolerance 1e-300 is too small") != std::string::npos));
            CHECK(m.find("000000") == std::string::npos);
        }
    }
}

TEST_CASE("operation reports count in the singular for one", "[text][operation]") {
    NullProgress progress;
    const HalfedgeMesh tet = generate("tetrahedron");
    const OperationResult flip = run_operation(parse_operation("flip"), tet, progress);
    CHECK(has_text(flip.report, "reversed 4 faces"));
    const OperationResult sub =
        run_operation(parse_operation("subdivide --iterations 1"), tet, progress);
    CHECK(has_text(sub.report, "1 iteration: 4 -> 16 faces"));
}
