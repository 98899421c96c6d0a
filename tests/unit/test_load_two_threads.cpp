// The load's two-thread passes against their one-thread passes (detail::set_build_threads):
// build_mesh's edge pairing (stage 2's fast path), its fan search (stage 3a) and the PLY reader's
// triangle rows (each thread half of the rows) must give the same mesh element for element, the
// same report and the same errors. The meshes are over 65,536 halfedges and rows, so that the
// two-thread passes run.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "core/algorithms/generators.h"
#include "core/errors.h"
#include "core/io/mesh_io.h"
#include "core/mesh_builder.h"
#include "core/validate.h"
#include "test_helpers.h"

using namespace trilab;

namespace {

/// Runs `load` on one thread, then on two, restoring two threads at the end.
template <typename Load>
auto on_one_then_two_threads(const Load& load) {
    struct Restore {
        ~Restore() { detail::set_build_threads(2); }
    } restore;
    detail::set_build_threads(1);
    auto one = load();
    detail::set_build_threads(2);
    auto two = load();
    return std::make_pair(std::move(one), std::move(two));
}

void check_same_mesh(const HalfedgeMesh& a, const HalfedgeMesh& b) {
    CHECK(a.positions() == b.positions());
    CHECK(a.halfedge_to_array() == b.halfedge_to_array());
    CHECK(a.halfedge_next_array() == b.halfedge_next_array());
    CHECK(a.halfedge_prev_array() == b.halfedge_prev_array());
    CHECK(a.halfedge_face_array() == b.halfedge_face_array());
    CHECK(a.face_halfedge_array() == b.face_halfedge_array());
    CHECK(a.vertex_halfedge_array() == b.vertex_halfedge_array());
}

void check_same_report(const LoadReport& a, const LoadReport& b) {
    CHECK(a.lines() == b.lines());
    CHECK(a.file_faces == b.file_faces);
    CHECK(a.nonmanifold_vertices_split == b.nonmanifold_vertices_split);
    CHECK(a.vertex_copies_added == b.vertex_copies_added);
    CHECK(a.isolated_vertices == b.isolated_vertices);
}

/// Two copies of a 120 x 120 grid (open: boundary fans) that share every 7th vertex and
/// no edge, so that those vertices have two fans each (split into copies); a few vertices
/// are used by no face. `mixed`: the faces in an order mixing the two sheets; else the
/// first sheet's faces, then the second's, so that each shared vertex has its first fan in
/// the lower half of the halfedges and its second in the upper half (the two-thread fan
/// search's merge).
PolygonSoup two_sheets_sharing_vertices(bool mixed) {
    const PolygonSoup sheet = to_soup(make_grid(120));
    const Index n = Index(sheet.positions.size());
    PolygonSoup soup;
    soup.positions = sheet.positions;
    for (const Point& p : sheet.positions) soup.positions.push_back(p + Point(0, 0, 1));
    for (int k = 0; k < 5; ++k) soup.positions.push_back(Point(k, -1, 0));  // isolated
    auto other = [&](Index v) { return v % 7 == 0 ? v : v + n; };
    std::vector<std::vector<Index>> later;
    for (std::size_t f = 0; f < sheet.n_faces(); ++f) {
        std::vector<Index> mine, theirs;
        for (std::size_t c = sheet.face_offsets[f]; c < sheet.face_offsets[f + 1]; ++c) {
            mine.push_back(sheet.corners[c]);
            theirs.push_back(other(sheet.corners[c]));
        }
        // The second sheet's faces first for odd faces (a vertex's lowest halfedge is then
        // in one sheet or the other).
        if (f % 2 && mixed) std::swap(mine, theirs);
        soup.add_face(mine);
        if (mixed)
            soup.add_face(theirs);
        else
            later.push_back(theirs);
    }
    for (const std::vector<Index>& face : later) soup.add_face(face);
    return soup;
}

/// A little-endian binary PLY: float x y z, then faces as a uchar-counted int list.
std::string binary_ply(const std::vector<Point>& positions,
                       const std::vector<std::vector<std::int32_t>>& faces) {
    std::string out =
        "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(positions.size()) +
        "\nproperty float x\nproperty float y\nproperty float z\nelement face " +
        std::to_string(faces.size()) + "\nproperty list uchar int vertex_indices\nend_header\n";
    auto put = [&](const void* p, std::size_t n) { out.append(static_cast<const char*>(p), n); };
    for (const Point& p : positions) {
        const float xyz[3] = {float(p.x()), float(p.y()), float(p.z())};
        put(xyz, sizeof(xyz));
    }
    for (const auto& f : faces) {
        const std::uint8_t k = std::uint8_t(f.size());
        put(&k, 1);
        put(f.data(), 4 * f.size());
    }
    return out;
}

std::vector<std::vector<std::int32_t>> faces_of(const PolygonSoup& soup) {
    std::vector<std::vector<std::int32_t>> faces;
    for (std::size_t f = 0; f < soup.n_faces(); ++f)
        faces.emplace_back(soup.corners.begin() + std::ptrdiff_t(soup.face_offsets[f]),
                           soup.corners.begin() + std::ptrdiff_t(soup.face_offsets[f + 1]));
    return faces;
}

/// read_ply_bytes' error message, or "" when it reads.
std::string ply_error(const std::string& bytes) {
    try {
        read_ply_bytes(bytes, "big.ply");
    } catch (const IoError& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST_CASE("build_mesh builds on two threads exactly what it builds on one", "[core][builder]") {
    const std::string name =
        GENERATE(as<std::string>(), "two sheets", "two sheets in turn", "icosphere");
    INFO(name);
    const bool sheets = name != "icosphere";
    const PolygonSoup soup =
        sheets ? two_sheets_sharing_vertices(name == "two sheets") : to_soup(make_icosphere(60));
    REQUIRE(soup.corners.size() > 65536);
    const auto [one, two] = on_one_then_two_threads([&] {
        LoadReport report;
        HalfedgeMesh mesh = build_mesh(soup, report);
        return std::make_pair(std::move(mesh), report);
    });
    REQUIRE(validate(one.first).ok);
    REQUIRE(validate(two.first).ok);
    check_same_mesh(one.first, two.first);
    check_same_report(one.second, two.second);
    if (sheets) {
        // 121 x 121 grid vertices, every 7th shared: each gets one copy.
        CHECK(two.second.nonmanifold_vertices_split == (121 * 121 + 6) / 7);
        CHECK(two.second.vertex_copies_added == (121 * 121 + 6) / 7);
        // The five unused points and the second sheet's own copies of the shared vertices.
        CHECK(two.second.isolated_vertices == 5 + (121 * 121 + 6) / 7);
    }
}

TEST_CASE("the PLY reader decodes triangle rows on two threads exactly as on one", "[io][ply]") {
    const PolygonSoup soup = to_soup(make_icosphere(60));
    std::vector<std::vector<std::int32_t>> faces = faces_of(soup);
    REQUIRE(faces.size() > 65536);
    const std::size_t late = faces.size() - 100;  // in the second thread's half

    SECTION("every row a triangle") {
        const std::string bytes = binary_ply(soup.positions, faces);
        const auto [one, two] = on_one_then_two_threads([&] { return read_ply_bytes(bytes, "a"); });
        REQUIRE(validate(two.mesh).ok);
        check_same_mesh(one.mesh, two.mesh);
        check_same_report(one.report, two.report);
        CHECK(two.mesh.n_faces() == faces.size());
    }
    SECTION("a row of four corners late in the file: read row by row, the same mesh") {
        // A repeated corner: the row is dropped as degenerate, either way.
        faces[late].push_back(faces[late][2]);
        const std::string bytes = binary_ply(soup.positions, faces);
        const auto [one, two] = on_one_then_two_threads([&] { return read_ply_bytes(bytes, "a"); });
        REQUIRE(validate(two.mesh).ok);
        check_same_mesh(one.mesh, two.mesh);
        check_same_report(one.report, two.report);
        CHECK(two.report.degenerate_faces_dropped == 1);
        CHECK(two.mesh.n_faces() == faces.size() - 1);
    }
    SECTION("an index out of range late in the file: the same error, naming the face") {
        faces[late][1] = std::int32_t(soup.positions.size()) + 3;
        const std::string bytes = binary_ply(soup.positions, faces);
        const auto [one, two] = on_one_then_two_threads([&] { return ply_error(bytes); });
        CHECK(one == two);
        CHECK_THAT(two, Catch::Contains("face " + std::to_string(late)));
        CHECK_THAT(two, Catch::Contains("out of range"));
    }
    SECTION("a file that ends inside the faces: the same error") {
        std::string bytes = binary_ply(soup.positions, faces);
        bytes.resize(bytes.size() - 7);
        const auto [one, two] = on_one_then_two_threads([&] { return ply_error(bytes); });
        CHECK(one == two);
        CHECK_THAT(two, Catch::Contains("truncated"));
    }
}

TEST_CASE(
    "build_mesh checks a large soup on two threads and names the problem one pass names first",
    "[core][builder]") {
    const PolygonSoup good = to_soup(make_icosphere(90));  // both over 65,536
    REQUIRE(good.n_faces() > 65536);
    REQUIRE(good.positions.size() > 65536);
    const std::size_t early = 10, late = good.n_faces() - 10;
    const auto error_of = [](const PolygonSoup& soup) {
        const auto [one, two] = on_one_then_two_threads([&] {
            try {
                LoadReport report;
                build_mesh(soup, report);
            } catch (const InvalidArgument& e) {
                return std::string(e.what());
            }
            return std::string();
        });
        CHECK(one == two);
        return two;
    };
    const Index nv = Index(good.positions.size());
    SECTION("a vertex out of range in each half: the earlier face") {
        PolygonSoup soup = good;
        soup.corners[soup.face_offsets[late] + 1] = nv + 1;
        soup.corners[soup.face_offsets[early]] = nv + 7;
        CHECK_THAT(error_of(soup), Catch::Contains("face " + std::to_string(early) +
                                                   " uses vertex " + std::to_string(nv + 7)));
    }
    SECTION("a face in the upper half before a position in the lower half") {
        PolygonSoup soup = good;
        soup.positions[3].x() = std::nan("");
        soup.corners[soup.face_offsets[late]] = nv;
        CHECK_THAT(error_of(soup), Catch::Contains("face " + std::to_string(late)));
    }
    SECTION("a non-finite position in each half: the lower vertex") {
        PolygonSoup soup = good;
        soup.positions[nv - 2].y() = std::numeric_limits<double>::infinity();
        soup.positions[5].z() = std::nan("");
        CHECK_THAT(error_of(soup), Catch::Contains("vertex 5 has a non-finite coordinate"));
    }
    SECTION("a clean soup builds the same on both") {
        CHECK(error_of(good).empty());
    }
}
