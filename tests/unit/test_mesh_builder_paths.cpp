// build_mesh's two ways of pairing the corner edges (mesh_builder.cpp, stage 2): the fast
// path, taken when every edge has at most two triangles in opposite directions, must give
// the mesh that the ordered pass gives. A soup with one duplicated face appended at its end
// takes the ordered pass (the duplicate is detached, with its own vertex copies, after every
// other face), so the mesh of the soup without it must be that mesh's prefix, array for array.
#include <algorithm>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "core/algorithms/generators.h"
#include "core/io/mesh_io.h"
#include "core/mesh_builder.h"
#include "core/validate.h"
#include "test_helpers.h"

using namespace trilab;

namespace {

/// The soup with its vertices renumbered and its faces reordered by a fixed seed (so that
/// edges are met in no particular order); each face keeps its corner order.
PolygonSoup shuffled(const PolygonSoup& soup, unsigned seed) {
    std::mt19937 rng(seed);
    std::vector<Index> new_index(soup.positions.size());
    std::iota(new_index.begin(), new_index.end(), Index(0));
    std::shuffle(new_index.begin(), new_index.end(), rng);
    std::vector<std::size_t> order(soup.n_faces());
    std::iota(order.begin(), order.end(), std::size_t(0));
    std::shuffle(order.begin(), order.end(), rng);
    PolygonSoup out;
    out.positions.resize(soup.positions.size());
    for (std::size_t v = 0; v < soup.positions.size(); ++v)
        out.positions[new_index[v]] = soup.positions[v];
    for (std::size_t f : order) {
        std::vector<Index> face;
        for (std::size_t c = soup.face_offsets[f]; c < soup.face_offsets[f + 1]; ++c)
            face.push_back(new_index[soup.corners[c]]);
        out.add_face(face);
    }
    return out;
}

template <typename T>
bool is_prefix(const std::vector<T>& part, const std::vector<T>& whole) {
    return part.size() <= whole.size() && std::equal(part.begin(), part.end(), whole.begin());
}

void check_fast_path_equals_ordered_pass(const PolygonSoup& soup) {
    LoadReport fast_report;
    const HalfedgeMesh fast = build_mesh(soup, fast_report);
    REQUIRE(validate(fast).ok);
    CHECK(fast_report.detached_faces == 0);

    PolygonSoup with_duplicate = soup;
    with_duplicate.add_face({soup.corners[0], soup.corners[1], soup.corners[2]});
    LoadReport ordered_report;
    const HalfedgeMesh ordered = build_mesh(with_duplicate, ordered_report);
    REQUIRE(validate(ordered).ok);
    REQUIRE(ordered_report.detached_faces == 1);
    CHECK(ordered.halfedges_size() == fast.halfedges_size() + 6);
    CHECK(ordered.faces_size() == fast.faces_size() + 1);
    CHECK(is_prefix(fast.positions(), ordered.positions()));
    CHECK(is_prefix(fast.halfedge_to_array(), ordered.halfedge_to_array()));
    CHECK(is_prefix(fast.halfedge_next_array(), ordered.halfedge_next_array()));
    CHECK(is_prefix(fast.halfedge_prev_array(), ordered.halfedge_prev_array()));
    CHECK(is_prefix(fast.halfedge_face_array(), ordered.halfedge_face_array()));
    CHECK(is_prefix(fast.face_halfedge_array(), ordered.face_halfedge_array()));
    CHECK(is_prefix(fast.vertex_halfedge_array(), ordered.vertex_halfedge_array()));
}

}  // namespace

TEST_CASE("build_mesh pairs edges on two threads exactly as its ordered pass does",
          "[core][builder]") {
    // Large enough (over 65,536 corners) for the two-thread path; open and closed.
    const std::string name = GENERATE(as<std::string>(), "grid", "torus", "icosphere");
    HalfedgeMesh mesh = name == "grid"    ? make_grid(120)
                        : name == "torus" ? make_torus(200, 100, 2.0, 0.5)
                                          : make_icosphere(60);
    INFO(name);
    const PolygonSoup soup = to_soup(mesh);
    REQUIRE(soup.corners.size() > 65536);
    check_fast_path_equals_ordered_pass(soup);
    check_fast_path_equals_ordered_pass(shuffled(soup, 29));
}

TEST_CASE("build_mesh pairs the bunny's edges on two threads as its ordered pass does",
          "[core][builder][shared]") {
    const std::string path = test::shared_mesh("stanford-bunny.obj");
    SKIP_IF_MISSING(path);
    const PolygonSoup soup = to_soup(read_mesh(path).mesh);
    check_fast_path_equals_ordered_pass(soup);
    check_fast_path_equals_ordered_pass(shuffled(soup, 7));
}
