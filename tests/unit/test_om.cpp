// OpenMesh .om reader and writer: the reference files in ../shared/om-reference, round trips
// of generated meshes, the bytes we write, and damaged or hand-made files (built in a
// temporary folder by the tests; see OmBytes below).
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "core/algorithms/generators.h"
#include "core/errors.h"
#include "core/geometry.h"
#include "core/io/file_util.h"
#include "core/io/mesh_io.h"
#include "test_helpers.h"

using namespace trilab;
using namespace trilab::test;
using Catch::Matchers::Contains;

namespace {

std::string om_ref(const std::string& name) {
    return shared_dir() + "/om-reference/" + name;
}

std::string read_bytes(const std::string& path) {
    return read_file_bytes(path);
}

void write_bytes(const std::string& path, const std::string& bytes) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), std::streamsize(bytes.size()));
    REQUIRE(out.good());
}

/// The message of the IoError that reading `path` throws, or "" if it loads.
std::string om_error(const std::string& path) {
    return error_text<IoError>([&] { read_om(path); });
}

/// A hand-made .om file, byte by byte (little-endian).
struct OmBytes {
    std::string s;
    OmBytes& u8(unsigned v) {
        s += char(v & 0xFF);
        return *this;
    }
    OmBytes& u16(unsigned v) { return u8(v).u8(v >> 8); }
    OmBytes& u32(std::uint32_t v) { return u16(v & 0xFFFF).u16(v >> 16); }
    OmBytes& i64(std::int64_t v) {
        const auto u = std::uint64_t(v);
        return u32(std::uint32_t(u)).u32(std::uint32_t(u >> 32));
    }
    OmBytes& f32(float v) {
        std::uint32_t u;
        std::memcpy(&u, &v, 4);
        return u32(u);
    }
    OmBytes& str(const std::string& t) {
        u8(unsigned(t.size()));
        s += t;
        return *this;
    }
    OmBytes& header(char kind, unsigned version, std::uint32_t nv, std::uint32_t nf,
                    std::uint32_t ne) {
        s += "OM";
        s += kind;
        return u8(version).u32(nv).u32(nf).u32(ne);
    }
    /// f32 positions of the unit square of om-format.md §12.
    OmBytes& square_positions() {
        u16(0x1600);
        const float p[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
        for (const auto& v : p) f32(v[0]).f32(v[1]).f32(v[2]);
        return *this;
    }
};

/// The halfedge arrays of tri_default.om (om-format.md §12): (next, to, face) per halfedge.
const int kSquareHalfedges[10][3] = {{2, 1, 0}, {9, 0, -1}, {4, 2, 0},  {1, 1, -1}, {0, 0, 0},
                                     {6, 2, 1}, {8, 3, 1},  {3, 2, -1}, {5, 0, 1},  {7, 3, -1}};
const int kSquareVertexHalfedges[4] = {9, 1, 3, 7};
const int kSquareFaceHalfedges[2] = {4, 8};

/// tri_default.om rebuilt with index width `width` bytes (1, 2, 4 or 8), optionally with
/// one halfedge array entry replaced.
std::string square_file(unsigned width, int patch_h = -1, int patch_k = 0, int patch_value = 0) {
    const unsigned bits = width == 1 ? 0 : width == 2 ? 1 : width == 4 ? 2 : 3;
    OmBytes b;
    b.header('T', 0x42, 4, 2, 5).square_positions();
    auto index = [&](std::int64_t v) {
        for (unsigned i = 0; i < width; ++i) b.u8(unsigned(std::uint64_t(v) >> (8 * i)));
    };
    b.u16(0x16F8 | (bits << 14));
    for (int h = 0; h < 10; ++h)
        for (int k = 0; k < 3; ++k)
            index(h == patch_h && k == patch_k ? patch_value : kSquareHalfedges[h][k]);
    b.u16(0x06E0 | (bits << 14));
    for (int v : kSquareVertexHalfedges) index(v);
    b.u16(0x06E8 | (bits << 14));
    for (int f : kSquareFaceHalfedges) index(f);
    b.u16(0x001C);
    return b.s;
}

/// The two-triangle unit square of om-format.md §12, built with build_mesh.
HalfedgeMesh unit_square() {
    PolygonSoup soup;
    soup.positions = {Point(0, 0, 0), Point(1, 0, 0), Point(1, 1, 0), Point(0, 1, 0)};
    soup.add_face({0, 1, 2});
    soup.add_face({0, 2, 3});
    LoadReport r;
    return build_mesh(soup, r);
}

/// Adds normals, exactly representable colours, vertex and corner texture coordinates.
void decorate(HalfedgeMesh& m) {
    compute_vertex_normals(m);
    auto color = m.vertex_property<Color>("v:color");
    auto uv = m.vertex_property<TexCoord>("v:texcoord");
    auto corner = m.halfedge_property<TexCoord>("h:texcoord");
    for (Vertex v : m.vertices()) {
        const Point& p = m.position(v);
        color[v] = Color(float(v.idx() % 256) / 255.0f, 128 / 255.0f, 1.0f);
        uv[v] = TexCoord(0.5 + 0.25 * p.x(), 0.5 - 0.25 * p.y());
    }
    for (Face f : m.faces()) {
        int k = 0;
        for (Halfedge h : m.halfedges_of(f))
            corner[h] = TexCoord(f.idx() * 0.001 + 0.1 * k++, 0.3 + m.position(m.to_vertex(h)).z());
    }
}

/// x rounded to float. Through a volatile: GCC 12 at -O2 folds double(float(x)) away when
/// its SLP vectorizer pairs two such conversions (a miscompilation seen in this very test).
double f32(double x) {
    volatile float f = static_cast<float>(x);
    return f;
}

/// Everything the format carries, compared through to_soup (live vertices in order, faces
/// as vertex lists starting at to_vertex(halfedge(f)), attributes per vertex and corner).
void require_same(const HalfedgeMesh& a, const HalfedgeMesh& b, bool attributes = true) {
    REQUIRE(a.n_vertices() == b.n_vertices());
    REQUIRE(a.n_faces() == b.n_faces());
    REQUIRE(a.n_edges() == b.n_edges());
    const PolygonSoup sa = to_soup(a), sb = to_soup(b);
    REQUIRE(sa.positions == sb.positions);  // f64 on disk: exact
    REQUIRE(sa.corners == sb.corners);
    if (!attributes) return;
    REQUIRE(sa.normals == sb.normals);  // f64 on disk: exact
    REQUIRE(sa.colors == sb.colors);    // k / 255 survives u8 exactly
    // f32 on disk: compare with the values rounded to float.
    auto rounded = [](std::vector<TexCoord> v) {
        for (TexCoord& t : v) t = TexCoord(f32(t.x()), f32(t.y()));
        return v;
    };
    REQUIRE(rounded(sa.texcoords) == sb.texcoords);
    REQUIRE(rounded(sa.corner_texcoords) == sb.corner_texcoords);
}

/// Header line counts "nV=.. nF=.." per file, from dumps.txt.
std::map<std::string, std::pair<std::size_t, std::size_t>> dump_counts() {
    std::map<std::string, std::pair<std::size_t, std::size_t>> out;
    std::ifstream in(om_ref("dumps.txt"));
    std::string line;
    while (std::getline(in, line)) {
        const auto colon = line.find(".om: magic=");
        if (colon == std::string::npos) continue;
        const std::string name = line.substr(0, colon + 3);
        const auto nv = line.find(" nV="), nf = line.find(" nF=");
        out[name] = {std::stoul(line.substr(nv + 4)), std::stoul(line.substr(nf + 4))};
    }
    return out;
}

}  // namespace

TEST_CASE("every .om reference file loads with its dumps.txt counts", "[om]") {
    SKIP_IF_MISSING(om_ref("dumps.txt"));
    const auto counts = dump_counts();
    struct Expect {
        std::size_t vertices, faces;  ///< of the loaded mesh
    };
    // Faces after triangulation (quads -> 2 triangles) and after dropping deleted elements.
    const std::map<std::string, Expect> expected = {
        {"openmesh-testfiles/cube-minimal-texCoords.om", {8, 12}},
        {"openmesh-testfiles/cube-minimal-vertexColors.om", {8, 12}},
        {"openmesh-testfiles/cube-minimal.om", {8, 12}},
        {"openmesh-testfiles/cube1_customProps.om", {7526, 15048}},
        {"openmesh-testfiles/cube_poly_version_1_2.om", {8, 12}},
        {"openmesh-testfiles/cube_poly_version_2_0.om", {8, 12}},
        {"openmesh-testfiles/cube_tri_version_1_2.om", {8, 12}},
        {"openmesh-testfiles/cube_tri_version_2_0.om", {8, 12}},
        {"openmesh-testfiles/cube_tri_with_properties_2_1.om", {8, 12}},
        {"openmesh-testfiles/cylinder.om", {66, 128}},
        {"generated-openmesh11/independent_writer_w32.om", {4, 2}},
        {"generated-openmesh11/points_only.om", {1, 0}},
        {"generated-openmesh11/poly_isolated.om", {6, 3}},
        {"generated-openmesh11/tri_all.om", {4, 2}},
        {"generated-openmesh11/tri_default.om", {4, 2}},
        {"generated-openmesh11/tri_deleted_nogc.om", {3, 1}},
        {"generated-openmesh11/tri_double.om", {4, 2}},
    };
    std::size_t checked = 0;
    for (const auto& [name, header] : counts) {
        if (name == "openmesh-testfiles/cube_tri_version_7_5.om") continue;
        INFO(name);
        const auto it = expected.find(name);
        REQUIRE(it != expected.end());  // a new reference file: add its counts above
        const LoadedMesh l = read_om(om_ref(name));
        REQUIRE_VALID(l.mesh);
        REQUIRE(l.report.format == "om");
        REQUIRE(l.report.file == om_ref(name));
        REQUIRE(l.report.file_vertices == header.first);
        REQUIRE(l.report.file_faces == header.second);
        REQUIRE(l.mesh.n_vertices() == it->second.vertices);
        REQUIRE(l.mesh.n_faces() == it->second.faces);
        ++checked;
    }
    REQUIRE(checked == expected.size());
}

TEST_CASE("a .om file of version 7.5 is refused, naming the version", "[om]") {
    const std::string path = om_ref("openmesh-testfiles/cube_tri_version_7_5.om");
    SKIP_IF_MISSING(path);
    REQUIRE_THROWS_AS(read_om(path), IoError);
    REQUIRE_THAT(om_error(path), Contains("7.5") && Contains("unsupported .om version"));
    REQUIRE_THAT(om_error(path), Contains("1.2 to 2.2"));
}

TEST_CASE("tri_all.om: vertex normals, colours, texcoords and corner texcoords", "[om]") {
    const std::string path = om_ref("generated-openmesh11/tri_all.om");
    SKIP_IF_MISSING(path);
    const LoadedMesh l = read_om(path);
    const HalfedgeMesh& m = l.mesh;
    REQUIRE_VALID(m);
    REQUIRE(m.n_vertices() == 4);
    REQUIRE(m.n_faces() == 2);
    auto normal = m.get_vertex_property<Vector3>("v:normal");
    auto color = m.get_vertex_property<Color>("v:color");
    auto uv = m.get_vertex_property<TexCoord>("v:texcoord");
    auto corner = m.get_halfedge_property<TexCoord>("h:texcoord");
    REQUIRE(normal);
    REQUIRE(color);
    REQUIRE(uv);
    REQUIRE(corner);
    const unsigned char rgb[4][3] = {{0, 20, 30}, {10, 20, 30}, {20, 20, 30}, {30, 20, 30}};
    for (Index i = 0; i < 4; ++i) {
        const Vertex v(i);
        REQUIRE(normal[v] == Vector3(0, 0, 1));
        REQUIRE(color[v] == Color(rgb[i][0] / 255.0f, rgb[i][1] / 255.0f, rgb[i][2] / 255.0f));
        REQUIRE(uv[v] == TexCoord(0.5 * i, 0.25));  // (0, 0.25), (0.5, 0.25), ...
    }
    REQUIRE(m.position(Vertex(2)) == Point(1, 1, 0));
    // Halfedge h of the file carries (h, -1). Face 0 = (v0, v1, v2) has its corners on file
    // halfedges 4, 0, 2; face 1 = (v0, v2, v3) on 8, 5, 6.
    const std::map<std::set<Index>, std::map<Index, double>> corner_u = {
        {{0, 1, 2}, {{0, 4}, {1, 0}, {2, 2}}}, {{0, 2, 3}, {{0, 8}, {2, 5}, {3, 6}}}};
    for (Face f : m.faces()) {
        std::set<Index> key;
        for (Vertex v : m.vertices_of(f)) key.insert(v.idx());
        INFO("face " << f.idx());
        REQUIRE(corner_u.count(key) == 1);
        for (Halfedge h : m.halfedges_of(f))
            REQUIRE(corner[h] == TexCoord(corner_u.at(key).at(m.to_vertex(h).idx()), -1));
    }
    // Face normals and colours, statuses and the eight custom properties were skipped.
    const std::string notes = [&] {
        std::string s;
        for (const auto& n : l.report.notes) s += n + "\n";
        return s;
    }();
    REQUIRE_THAT(notes, Contains("8 custom properties skipped"));
    REQUIRE_THAT(notes, Contains("face normals ignored"));
}

TEST_CASE("tri_double.om: f64 positions and normals", "[om]") {
    const std::string path = om_ref("generated-openmesh11/tri_double.om");
    SKIP_IF_MISSING(path);
    const LoadedMesh l = read_om(path);
    REQUIRE_VALID(l.mesh);
    const Point expected[4] = {Point(0, 0, 0), Point(1, 0, 0), Point(1, 1, 0), Point(0, 1, 0)};
    auto normal = l.mesh.get_vertex_property<Vector3>("v:normal");
    REQUIRE(normal);
    for (Index i = 0; i < 4; ++i) {
        REQUIRE(l.mesh.position(Vertex(i)) == expected[i]);
        REQUIRE(normal[Vertex(i)] == Vector3(0, 0, 1));
    }
    REQUIRE(surface_area(l.mesh) == Approx(1.0));
}

TEST_CASE("tri_deleted_nogc.om loads as its live part", "[om]") {
    const std::string path = om_ref("generated-openmesh11/tri_deleted_nogc.om");
    SKIP_IF_MISSING(path);
    const LoadedMesh l = read_om(path);
    REQUIRE_VALID(l.mesh);
    REQUIRE(l.mesh.n_vertices() == 3);
    REQUIRE(l.mesh.n_faces() == 1);
    // Vertex 1 was deleted: the live face is (v0, v2, v3) of the square.
    REQUIRE(l.mesh.position(Vertex(0)) == Point(0, 0, 0));
    REQUIRE(l.mesh.position(Vertex(1)) == Point(1, 1, 0));
    REQUIRE(l.mesh.position(Vertex(2)) == Point(0, 1, 0));
    REQUIRE(l.report.file_vertices == 4);
    REQUIRE(l.report.file_faces == 2);
    const auto lines = l.report.lines();
    REQUIRE(std::find(lines.begin(), lines.end(), "1 deleted face dropped") != lines.end());
    REQUIRE(std::find(lines.begin(), lines.end(), "1 deleted vertex dropped") != lines.end());
}

TEST_CASE("polygon .om files are triangulated, isolated vertices are kept", "[om]") {
    const std::string poly = om_ref("generated-openmesh11/poly_isolated.om");
    SKIP_IF_MISSING(poly);
    const LoadedMesh p = read_om(poly);
    REQUIRE_VALID(p.mesh);
    REQUIRE(p.report.polygons_triangulated == 1);
    REQUIRE(p.report.isolated_vertices == 1);
    REQUIRE(p.mesh.is_isolated(Vertex(5)));
    for (const char* name : {"openmesh-testfiles/cube_poly_version_1_2.om",
                             "openmesh-testfiles/cube_poly_version_2_0.om"}) {
        const LoadedMesh c = read_om(om_ref(name));
        REQUIRE_VALID(c.mesh);
        REQUIRE(c.report.polygons_triangulated == 6);
        REQUIRE(c.mesh.n_faces() == 12);
        REQUIRE(is_closed(c.mesh));
        REQUIRE(surface_area(c.mesh) == Approx(24.0));  // the cube spans [-1, 1]^3
    }
}

TEST_CASE("format 1.2 files: colours and texcoords", "[om]") {
    const std::string tex = om_ref("openmesh-testfiles/cube-minimal-texCoords.om");
    const std::string col = om_ref("openmesh-testfiles/cube-minimal-vertexColors.om");
    SKIP_IF_MISSING(tex);
    const LoadedMesh t = read_om(tex);
    auto uv = t.mesh.get_vertex_property<TexCoord>("v:texcoord");
    REQUIRE(uv);
    REQUIRE(uv[Vertex(0)] == TexCoord(10, 10));
    REQUIRE(uv[Vertex(1)] == TexCoord(12, 12));
    // The 1.2 colour chunk has float = 1 in its header; it is 3 x u8 nevertheless.
    const LoadedMesh c = read_om(col);
    REQUIRE_VALID(c.mesh);
    REQUIRE(c.mesh.has_vertex_property("v:color"));
    REQUIRE(c.mesh.n_faces() == 12);
}

TEST_CASE(".om round trips of generated meshes keep everything exactly", "[om]") {
    TempDir dir;
    std::vector<std::pair<std::string, HalfedgeMesh>> meshes;
    meshes.emplace_back("icosphere", make_icosphere(3));
    meshes.emplace_back("grid", make_grid(9));  // open, one boundary loop
    meshes.emplace_back("torus", make_torus(24, 12, 1.0, 0.3));
    meshes.emplace_back("cylinder", make_cylinder(16, 4));
    {
        // Isolated vertices, and more vertices than halfedges (index width from n_v).
        PolygonSoup soup;
        for (int i = 0; i < 200; ++i) soup.positions.emplace_back(0.01 * i, std::sin(i), 0.5);
        soup.add_face({0, 1, 2});
        soup.add_face({0, 2, 3});
        soup.add_face({5, 7, 6});
        LoadReport r;
        meshes.emplace_back("isolated", build_mesh(soup, r));
        REQUIRE(r.isolated_vertices == 193);
    }
    for (auto& [name, m] : meshes) {
        INFO(name);
        decorate(m);
        REQUIRE_VALID(m);
        const std::string path = dir.path(name + ".om");
        write_om(m, path, {});
        const LoadedMesh back = read_om(path);
        REQUIRE_VALID(back.mesh);
        require_same(m, back.mesh);
        REQUIRE(back.report.format == "om");
        REQUIRE(back.report.file_vertices == m.n_vertices());
        REQUIRE(back.report.file_faces == m.n_faces());
        // Boundary vertices and isolated vertices keep their state.
        for (Vertex v : m.vertices()) {
            REQUIRE(back.mesh.is_boundary(v) == m.is_boundary(v));
            REQUIRE(back.mesh.is_isolated(v) == m.is_isolated(v));
        }
        // Writing what we read gives the same bytes.
        write_om(back.mesh, dir.path(name + "2.om"), {});
        REQUIRE(read_bytes(dir.path(name + "2.om")) == read_bytes(path));
    }
}

TEST_CASE(".om writer options, index widths and compaction", "[om]") {
    TempDir dir;
    SECTION("attributes can be left out") {
        HalfedgeMesh m = make_icosphere(2);
        decorate(m);
        WriteOptions o;
        o.write_normals = false;
        o.write_colors = false;
        o.write_texcoords = false;
        write_om(m, dir.path("plain.om"), o);
        const LoadedMesh back = read_om(dir.path("plain.om"));
        require_same(m, back.mesh, false);
        REQUIRE_FALSE(back.mesh.has_vertex_property("v:normal"));
        REQUIRE_FALSE(back.mesh.has_vertex_property("v:color"));
        REQUIRE_FALSE(back.mesh.has_vertex_property("v:texcoord"));
        REQUIRE_FALSE(back.mesh.has_halfedge_property("h:texcoord"));
        // Header, positions, then three topology chunks and the sentinel.
        const std::size_t nv = m.n_vertices(), nh = m.n_halfedges(), nf = m.n_faces();
        const std::size_t w = 2;  // 240 halfedges need 2 bytes
        REQUIRE(read_bytes(dir.path("plain.om")).size() ==
                16 + 2 + 24 * nv + 2 + 3 * w * nh + 2 + w * nv + 2 + w * nf + 2);
    }
    SECTION("the index width follows the largest index") {
        struct Case {
            HalfedgeMesh mesh;
            unsigned expected_header;  // halfedge topology chunk
        };
        std::vector<Case> cases;
        cases.push_back({make_tetrahedron(), 0x16F8});              // 12 halfedges: 1 byte
        cases.push_back({make_icosphere(4), 0x56F8});               // 960: 2 bytes
        cases.push_back({make_torus(100, 100, 1.0, 0.3), 0x96F8});  // 60,000: 4 bytes
        for (Case& c : cases) {
            write_om(c.mesh, dir.path("w.om"), {});
            const std::string bytes = read_bytes(dir.path("w.om"));
            const std::size_t at = 16 + 2 + 24 * c.mesh.n_vertices();
            REQUIRE((unsigned char)bytes[16] == 0x00);
            REQUIRE((unsigned char)bytes[17] == 0x56);  // f64 positions
            REQUIRE(unsigned((unsigned char)bytes[at] | ((unsigned char)bytes[at + 1] << 8)) ==
                    c.expected_header);
            const LoadedMesh back = read_om(dir.path("w.om"));
            REQUIRE_VALID(back.mesh);
            require_same(c.mesh, back.mesh, false);
        }
    }
    SECTION("deleted elements are compacted away before writing") {
        HalfedgeMesh m = make_icosphere(2);
        decorate(m);
        for (int k = 0; k < 2; ++k)
            for (Edge e : m.edges())
                if (m.is_collapse_ok(HalfedgeMesh::halfedge(e, 0))) {
                    m.collapse(HalfedgeMesh::halfedge(e, 0));
                    break;
                }
        REQUIRE(m.has_garbage());
        write_om(m, dir.path("gc.om"), {});
        const LoadedMesh back = read_om(dir.path("gc.om"));
        REQUIRE_VALID(back.mesh);
        REQUIRE_FALSE(back.mesh.has_garbage());
        require_same(m, back.mesh);
    }
    SECTION("an empty mesh is written, but refused on reading like every empty file") {
        write_om(HalfedgeMesh(), dir.path("empty.om"), {});
        REQUIRE(read_bytes(dir.path("empty.om")).size() == 16 + 2 + 2 + 2);
        REQUIRE_THAT(om_error(dir.path("empty.om")), Contains("no vertices"));
    }
    SECTION("a failed write leaves no file") {
        REQUIRE_THROWS_AS(write_om(make_cube(), dir.path("no/such/dir/x.om"), {}), IoError);
    }
}

TEST_CASE("writing the unit square of om-format.md §12: bytes and read-back", "[om]") {
    TempDir dir;
    const HalfedgeMesh m = unit_square();
    write_om(m, dir.path("square.om"), {});
    const std::string b = read_bytes(dir.path("square.om"));
    REQUIRE(b.size() == 158);  // 16 + (2 + 96) + (2 + 30) + (2 + 4) + (2 + 2) + 2
    REQUIRE(b.substr(0, 4) == std::string("OMT\x42"));
    const std::string counts("\x04\0\0\0\x02\0\0\0\x05\0\0\0", 12);
    REQUIRE(b.substr(4, 12) == counts);
    REQUIRE(b.substr(16, 2) == std::string("\x00\x56", 2));   // f64 positions
    REQUIRE(b.substr(114, 2) == std::string("\xF8\x16", 2));  // halfedge topology, W = 1
    REQUIRE(b.substr(146, 2) == std::string("\xE0\x06", 2));  // vertex topology
    REQUIRE(b.substr(152, 2) == std::string("\xE8\x06", 2));  // face topology
    REQUIRE(b.substr(156, 2) == std::string("\x1C\x00", 2));  // sentinel
    // The arrays are the mesh's own: (next, to_vertex, face) per halfedge, -1 as 0xFF;
    // every vertex stores an outgoing boundary halfedge (OpenMesh's invariant).
    auto index = [](const HalfedgeMesh&, Index i) { return i == kInvalidIndex ? -1 : int(i); };
    auto at = [&](std::size_t i) { return int(static_cast<signed char>(b[i])); };
    for (Index h = 0; h < 10; ++h) {
        const Halfedge he(h);
        REQUIRE(at(116 + 3 * h) == index(m, m.next(he).idx()));
        REQUIRE(at(117 + 3 * h) == index(m, m.to_vertex(he).idx()));
        REQUIRE(at(118 + 3 * h) == index(m, m.face(he).idx()));
    }
    for (Index v = 0; v < 4; ++v) {
        REQUIRE(at(148 + v) == int(m.halfedge(Vertex(v)).idx()));
        REQUIRE(m.is_boundary(Halfedge(Index(at(148 + v)))));
        REQUIRE(m.from_vertex(Halfedge(Index(at(148 + v)))) == Vertex(v));
    }
    for (Index f = 0; f < 2; ++f) REQUIRE(at(154 + f) == int(m.halfedge(Face(f)).idx()));
    const LoadedMesh back = read_om(dir.path("square.om"));
    REQUIRE_VALID(back.mesh);
    REQUIRE(back.mesh.n_vertices() == 4);
    REQUIRE(back.mesh.n_faces() == 2);
    REQUIRE(back.mesh.n_edges() == 5);
    require_same(m, back.mesh, false);

    // Reading OpenMesh's own file and writing it again gives OpenMesh's bytes after the
    // position chunk (which we write as f64 instead of f32).
    const std::string ref = om_ref("generated-openmesh11/tri_default.om");
    SKIP_IF_MISSING(ref);
    write_om(read_om(ref).mesh, dir.path("again.om"), {});
    const std::string ours = read_bytes(dir.path("again.om")), theirs = read_bytes(ref);
    REQUIRE(ours.substr(0, 16) == theirs.substr(0, 16));
    REQUIRE(ours.substr(114) == theirs.substr(66));
}

TEST_CASE("hand-made .om files: versions, widths, 1.x kinds, custom chunks, EOF", "[om]") {
    TempDir dir;
    auto load = [&](const std::string& bytes) {
        write_bytes(dir.path("om_case.om"), bytes);
        return read_om(dir.path("om_case.om"));
    };
    SECTION("every index width, 8 bytes included, gives the square") {
        for (unsigned w : {1u, 2u, 4u, 8u}) {
            INFO("width " << w);
            const LoadedMesh l = load(square_file(w));
            REQUIRE_VALID(l.mesh);
            REQUIRE(l.mesh.n_faces() == 2);
            REQUIRE(surface_area(l.mesh) == Approx(1.0));
        }
    }
    SECTION("EOF after a chunk, without the sentinel, is valid") {
        std::string s = square_file(1);
        s.resize(s.size() - 2);
        REQUIRE(load(s).mesh.n_faces() == 2);
    }
    SECTION("bytes after the sentinel are ignored") {
        REQUIRE(load(square_file(1) + "trailing junk").mesh.n_faces() == 2);
    }
    SECTION("custom chunks: no type name up to 2.1, a type name in 2.2") {
        for (unsigned version : {0x40u, 0x41u, 0x42u}) {
            INFO("version " << version);
            std::string s = square_file(1);
            s[3] = char(version);
            s.resize(s.size() - 2);  // drop the sentinel, append custom chunks
            OmBytes c;
            c.u16(0xC0C2).str("vflag");  // vertex custom, junk size bits
            if (version > 0x41) c.str("bool");
            c.u32(1).u8(0x0A);
            c.u16(0x00C6).str("mesh");  // mesh custom: one element
            if (version > 0x41) c.str("std::string");
            c.u32(7).u16(5);
            c.s += "hello";
            c.u16(0x001C);
            const LoadedMesh l = load(s + c.s);
            REQUIRE_VALID(l.mesh);
            REQUIRE(l.mesh.n_faces() == 2);
            const auto lines = l.report.lines();
            REQUIRE(std::any_of(lines.begin(), lines.end(), [](const std::string& x) {
                return x.find("2 custom properties skipped") != std::string::npos;
            }));
        }
    }
    SECTION("format 1.2 'Q' and 'P' vertex lists with 2-byte indices") {
        OmBytes q;
        q.header('Q', 0x22, 6, 2, 7).u16(0x1600);
        for (int i = 0; i < 6; ++i) q.f32(float(i % 3)).f32(float(i / 3)).f32(0);
        q.u16(0x40E8);  // face topology, bits 1: 2-byte unsigned indices
        for (int v : {0, 1, 4, 3, 1, 2, 5, 4}) q.u16(unsigned(v));
        const LoadedMesh lq = load(q.s);  // no sentinel: EOF
        REQUIRE_VALID(lq.mesh);
        REQUIRE(lq.mesh.n_faces() == 4);
        REQUIRE(lq.report.polygons_triangulated == 2);
        REQUIRE(surface_area(lq.mesh) == Approx(2.0));

        OmBytes p;
        p.header('P', 0x22, 6, 2, 7).u16(0x1600);
        for (int i = 0; i < 6; ++i) p.f32(float(i % 3)).f32(float(i / 3)).f32(0);
        p.u16(0x00E8);
        p.u16(4).u8(0).u8(1).u8(4).u8(3);  // a quad
        p.u16(3).u8(1).u8(2).u8(5);        // a triangle
        p.u16(0x001C);
        const LoadedMesh lp = load(p.s);
        REQUIRE_VALID(lp.mesh);
        REQUIRE(lp.mesh.n_faces() == 3);
        REQUIRE(surface_area(lp.mesh) == Approx(1.5));
    }
    SECTION("corner texcoords on a polygon follow the triangulation") {
        // poly_isolated-like: one quad as a 2.2 file with a halfedge texcoord chunk.
        OmBytes b;
        b.header('P', 0x42, 4, 1, 4).u16(0x1600);
        const float pos[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
        for (const auto& x : pos) b.f32(x[0]).f32(x[1]).f32(0);
        // Edge e joins v_e -> v_{e+1}: halfedge 2e inside, 2e + 1 outside.
        b.u16(0x16F8);
        for (int e = 0; e < 4; ++e) {
            b.u8(unsigned(2 * ((e + 1) % 4))).u8(unsigned((e + 1) % 4)).u8(0);
            b.u8(unsigned(2 * ((e + 3) % 4) + 1)).u8(unsigned(e)).u8(0xFF);
        }
        b.u16(0x0E58);
        for (int h = 0; h < 8; ++h) b.f32(float(h)).f32(h % 2 ? -1.0f : 0.5f);
        b.u16(0x06E0);
        for (int v = 0; v < 4; ++v) b.u8(unsigned(2 * ((v + 3) % 4) + 1));
        b.u16(0x06E8).u8(0).u16(0x001C);
        const LoadedMesh l = load(b.s);
        REQUIRE_VALID(l.mesh);
        REQUIRE(l.mesh.n_faces() == 2);
        auto corner = l.mesh.get_halfedge_property<TexCoord>("h:texcoord");
        REQUIRE(corner);
        // The corner at v_k of the quad is on file halfedge 2(k - 1): u = 2(k - 1) mod 8.
        for (Face f : l.mesh.faces())
            for (Halfedge h : l.mesh.halfedges_of(f)) {
                const Index k = l.mesh.to_vertex(h).idx();
                REQUIRE(corner[h] == TexCoord(float(2 * ((k + 3) % 4)), 0.5));
            }
    }
}

TEST_CASE("bad .om files throw IoError with a reason", "[om]") {
    TempDir dir;
    auto error = [&](const std::string& name, const std::string& bytes) {
        write_bytes(dir.path(name), bytes);
        return om_error(dir.path(name));
    };
    const std::string good = square_file(1);
    REQUIRE(error("om_good.om", good).empty());

    std::string s = good;
    s[0] = 'X';
    REQUIRE_THAT(error("om_magic.om", s), Contains("not an .om file"));
    s = good;
    s[2] = 'Z';
    REQUIRE_THAT(error("om_kind.om", s), Contains("mesh kind"));
    s = good;
    s[3] = char(0x60);
    REQUIRE_THAT(error("om_version.om", s), Contains("unsupported .om version 3.0"));
    s = good;
    s[3] = char(0x43);
    REQUIRE_THAT(error("om_version23.om", s), Contains("2.3"));
    s = good;
    s[4] = s[5] = s[6] = s[7] = char(0xFF);  // 4 billion vertices
    REQUIRE_THAT(error("om_huge.om", s), Contains("declares 4294967295 vertices"));
    s = good;
    s[12] = char(0xFF);  // 255 edges cannot fit in 94 bytes
    REQUIRE_THAT(error("om_edges.om", s), Contains("declares 255 edges"));
    s[12] = 15;  // 15 edges could, but then the halfedge chunk runs past the end
    REQUIRE_THAT(error("om_edges15.om", s),
                 Contains("truncated halfedge topology chunk 0x16F8 at byte 66") &&
                     Contains("needs 90 bytes at byte 68, only 42 left"));
    REQUIRE_THAT(error("om_empty.om", ""), Contains("truncated header") && Contains("at byte 0"));
    REQUIRE_THAT(error("om_short.om", good.substr(0, 65)),
                 Contains("truncated vertex position chunk 0x1600 at byte 16") &&
                     Contains("needs 48 bytes at byte 18, only 47 left"));
    REQUIRE_THAT(error("om_half_header.om", OmBytes().header('T', 0x42, 0, 0, 0).u8(0).s),
                 Contains("truncated chunk header") && Contains("at byte 16"));

    // Unknown built-in chunks are refused, not skipped.
    const std::string head0 = OmBytes().header('T', 0x42, 0, 0, 0).s;
    REQUIRE_THAT(error("om_entity3.om", head0 + std::string("\x0C\x00", 2)),
                 Contains("unsupported") && Contains("0x000C"));
    REQUIRE_THAT(error("om_type5.om", head0 + std::string("\xA0\x00", 2)), Contains("unsupported"));
    REQUIRE_THAT(error("om_edge_pos.om", head0 + std::string("\x10\x00", 2)),
                 Contains("unsupported edge position chunk"));
    REQUIRE_THAT(error("om_pos_ld.om", head0 + std::string("\x00\x96", 2)),
                 Contains("only f32 and f64"));
    REQUIRE_THAT(error("om_pos_2d.om", head0 + std::string("\x00\x0E", 2)),
                 Contains("expected 3 components"));
    // Custom data longer than the file.
    OmBytes c;
    c.s = good.substr(0, good.size() - 2);
    c.u16(0x00C2).str("p").str("int32_t").u32(1000).u32(0);
    REQUIRE_THAT(error("om_custom.om", c.s), Contains("truncated data of custom property 'p'"));
    // A missing position or face chunk.
    REQUIRE_THAT(
        error("om_no_pos.om", good.substr(0, 16) + good.substr(66) + std::string(64, '\0')),
        Contains("no vertex position chunk"));
    REQUIRE_THAT(error("om_no_faces.om", good.substr(0, 104)), Contains("no face topology chunk"));

    // Topology that is not a halfedge structure.
    REQUIRE_THAT(error("om_next_range.om", square_file(1, 0, 0, 10)),
                 Contains("invalid .om data") && Contains("next 10 out of range"));
    REQUIRE_THAT(error("om_to_range.om", square_file(1, 3, 1, 4)),
                 Contains("to_vertex 4 out of range"));
    REQUIRE_THAT(error("om_face_range.om", square_file(1, 3, 2, 2)),
                 Contains("face 2 out of range"));
    REQUIRE_THAT(error("om_next_perm.om", square_file(1, 0, 0, 4)), Contains("not a permutation"));
    REQUIRE_THAT(error("om_next_face.om", square_file(1, 1, 2, 0)), Contains("different faces"));
    REQUIRE_THAT(error("om_head_tail.om", square_file(4, 7, 1, 1)), Contains("starts at vertex"));
    // Vertex 1 storing halfedge 0 (v0 -> v1) is incoming, not outgoing.
    std::string v = good;
    v[100 + 1] = 0;
    REQUIRE_THAT(error("om_vertex_in.om", v), Contains("vertex 1: its halfedge 0 is not outgoing"));
    // Face 0 storing a halfedge of face 1.
    std::string f = good;
    f[106] = 5;
    REQUIRE_THAT(error("om_face_he.om", f), Contains("belongs to face 1"));
    // Index 200 does not fit a signed byte: -56 is out of range.
    REQUIRE_THAT(error("om_negative.om", square_file(1, 2, 0, 200)), Contains("out of range"));
    REQUIRE_THAT(error("om_wide.om", square_file(8, 2, 0, std::numeric_limits<int>::min())),
                 Contains("out of range"));
}

TEST_CASE("truncated .om files throw IoError at every length", "[om]") {
    TempDir dir;
    HalfedgeMesh m = make_icosphere(1);
    decorate(m);
    write_om(m, dir.path("full.om"), {});
    std::vector<std::string> files = {read_bytes(dir.path("full.om")), square_file(4)};
    const std::string all = om_ref("generated-openmesh11/tri_all.om");
    if (present_or_skip(all)) files.push_back(read_bytes(all));
    for (const std::string& full : files) {
        std::size_t loaded = 0;
        for (std::size_t len = 0; len < full.size(); ++len) {
            INFO("cut at " << len << " of " << full.size());
            write_bytes(dir.path("om_cut.om"), full.substr(0, len));
            try {
                // A cut between two chunks after the face chunk is a valid shorter file.
                const LoadedMesh l = read_om(dir.path("om_cut.om"));
                REQUIRE_VALID(l.mesh);
                ++loaded;
            } catch (const IoError& e) {
                REQUIRE(std::string(e.what()).find("om_cut.om") != std::string::npos);
            }
        }
        REQUIRE(loaded < 20);
    }
}

TEST_CASE("damaged .om files never crash: flipped bytes and garbage", "[om]") {
    const FpTrapsOff traps_off;  // flipped bytes decode to any value, NaN and infinity included
    TempDir dir;
    HalfedgeMesh m = make_grid(3);
    decorate(m);
    write_om(m, dir.path("grid.om"), {});
    std::vector<std::string> sources = {read_bytes(dir.path("grid.om")), square_file(1)};
    for (const char* name :
         {"generated-openmesh11/tri_all.om", "generated-openmesh11/tri_deleted_nogc.om",
          "openmesh-testfiles/cube_poly_version_1_2.om"})
        if (present_or_skip(om_ref(name))) sources.push_back(read_bytes(om_ref(name)));
    std::mt19937 rng(12345);
    std::size_t ok = 0, refused = 0;
    for (const std::string& source : sources) {
        for (int trial = 0; trial < 400; ++trial) {
            std::string s = source;
            const int flips = 1 + int(rng() % 4);
            for (int i = 0; i < flips; ++i) {
                // Mostly in the topology and chunk headers, sometimes in the file header.
                const std::size_t at = trial % 10 == 0 ? rng() % 16 : rng() % s.size();
                s[at] = char(rng() % 4 == 0 ? 0xFF : rng() & 0xFF);
            }
            write_bytes(dir.path("om_fuzz.om"), s);
            try {
                const LoadedMesh l = read_om(dir.path("om_fuzz.om"));
                REQUIRE_VALID(l.mesh);
                ++ok;
            } catch (const IoError&) {
                ++refused;
            }
        }
    }
    REQUIRE(refused > 0);
    for (int trial = 0; trial < 200; ++trial) {
        std::string s = trial % 2 ? std::string("OMT\x42", 4) : std::string();
        const std::size_t n = rng() % 300;
        for (std::size_t i = 0; i < n; ++i) s += char(rng() & 0xFF);
        write_bytes(dir.path("om_garbage.om"), s);
        try {
            const LoadedMesh l = read_om(dir.path("om_garbage.om"));
            REQUIRE_VALID(l.mesh);
        } catch (const IoError&) {
        }
    }
    INFO(ok << " damaged files loaded, " << refused << " refused");
    SUCCEED();
}
