// PLY and STL readers and writers: round trips in every encoding, attributes, header and
// element variants, tristrips, the binary-STL size rule, vertex merging, and bad files.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <functional>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "core/algorithms/generators.h"
#include "core/errors.h"
#include "core/geometry.h"
#include "core/io/file_util.h"
#include "core/io/mesh_io.h"
#include "core/mesh_builder.h"
#include "test_helpers.h"

using namespace trilab;
using namespace trilab::test;
using Catch::Matchers::Contains;

namespace {

void write_bytes(const std::string& path, const std::string& bytes) {
    std::ofstream out(path, std::ios::binary);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    REQUIRE(out.good());
}

/// Same vertex order and faces; positions within `tol`.
void require_same_mesh(const HalfedgeMesh& a, const HalfedgeMesh& b, double tol) {
    REQUIRE(a.n_vertices() == b.n_vertices());
    REQUIRE(a.n_faces() == b.n_faces());
    const PolygonSoup sa = to_soup(a), sb = to_soup(b);
    for (std::size_t i = 0; i < sa.positions.size(); ++i)
        REQUIRE((sa.positions[i] - sb.positions[i]).lpNorm<Eigen::Infinity>() <= tol);
    REQUIRE(sa.corners == sb.corners);
}

/// Same faces in the same order with the same corner positions (up to a rotation of each
/// face's corners) within `tol`: STL renumbers vertices.
void require_same_faces(const HalfedgeMesh& a, const HalfedgeMesh& b, double tol) {
    REQUIRE(a.n_faces() == b.n_faces());
    std::vector<Face> fa, fb;
    for (Face f : a.faces()) fa.push_back(f);
    for (Face f : b.faces()) fb.push_back(f);
    for (std::size_t i = 0; i < fa.size(); ++i) {
        const auto va = a.face_vertices(fa[i]), vb = b.face_vertices(fb[i]);
        bool found = false;
        for (int r = 0; r < 3 && !found; ++r) {
            found = true;
            for (int k = 0; k < 3; ++k) {
                const Vector3 d = a.position(va[k]) - b.position(vb[(k + r) % 3]);
                if (d.lpNorm<Eigen::Infinity>() > tol) found = false;
            }
        }
        INFO("face " << i);
        REQUIRE(found);
    }
}

/// Builds a PLY file in any encoding from a header body and typed values, for tests of the
/// reader's type and layout handling.
class PlyBuilder {
public:
    explicit PlyBuilder(std::string encoding) : encoding_(std::move(encoding)) {}
    PlyBuilder& header(const std::string& lines) {
        header_ += lines;
        return *this;
    }
    /// One value of PLY type `type`.
    PlyBuilder& val(const std::string& type, double v) {
        if (ascii()) {
            std::ostringstream s;
            s.precision(17);
            s << v;
            body_ += s.str() + " ";
            return *this;
        }
        if (type == "char" || type == "int8")
            put(static_cast<std::int8_t>(v));
        else if (type == "uchar" || type == "uint8")
            put(static_cast<std::uint8_t>(v));
        else if (type == "short" || type == "int16")
            put(static_cast<std::int16_t>(v));
        else if (type == "ushort" || type == "uint16")
            put(static_cast<std::uint16_t>(v));
        else if (type == "int" || type == "int32")
            put(static_cast<std::int32_t>(v));
        else if (type == "uint" || type == "uint32")
            put(static_cast<std::uint32_t>(v));
        else if (type == "float" || type == "float32")
            put(static_cast<float>(v));
        else if (type == "double" || type == "float64")
            put(v);
        else
            FAIL("unknown type " << type);
        return *this;
    }
    PlyBuilder& list(const std::string& count_type, const std::string& item_type,
                     const std::vector<double>& items) {
        val(count_type, double(items.size()));
        for (double v : items) val(item_type, v);
        return *this;
    }
    PlyBuilder& end_row() {
        if (ascii()) body_ += "\n";
        return *this;
    }
    std::string bytes() const {
        return "ply\nformat " + encoding_ + " 1.0\ncomment built by a test\n" + header_ +
               "end_header\n" + body_;
    }

private:
    bool ascii() const { return encoding_ == "ascii"; }
    template <class T>
    void put(T v) {
        char b[sizeof(T)];
        std::memcpy(b, &v, sizeof(T));
        const bool big = encoding_ == "binary_big_endian";
        const std::uint16_t one = 1;
        const bool host_little = *reinterpret_cast<const unsigned char*>(&one) == 1;
        if (big == host_little) std::reverse(b, b + sizeof(T));
        body_.append(b, sizeof(T));
    }
    std::string encoding_;
    std::string header_;
    std::string body_;
};

const char* const kEncodings[] = {"ascii", "binary_little_endian", "binary_big_endian"};

}  // namespace

// ---- PLY ---------------------------------------------------------------------------------

TEST_CASE("read_ply round-trips every encoding with normals, colours and texcoords", "[ply]") {
    const HalfedgeMesh m = attributed_sphere();
    TempDir dir;
    struct Mode {
        const char* name;
        bool ascii, big;
        const char* format_line;
    };
    const Mode modes[] = {{"ascii", true, false, "format ascii 1.0"},
                          {"little", false, false, "format binary_little_endian 1.0"},
                          {"big", false, true, "format binary_big_endian 1.0"}};
    for (const Mode& mode : modes) {
        INFO(mode.name);
        WriteOptions o;
        o.ascii = mode.ascii;
        o.big_endian = mode.big;
        const std::string path = dir.path(std::string(mode.name) + ".ply");
        write_ply(m, path, o);
        REQUIRE_THAT(read_file_bytes(path).substr(0, 64), Contains(mode.format_line));
        const LoadedMesh l = read_ply(path);
        REQUIRE_VALID(l.mesh);
        REQUIRE(l.report.format == "ply");
        REQUIRE(l.report.file == path);
        REQUIRE(l.report.file_vertices == m.n_vertices());
        REQUIRE(l.report.file_faces == m.n_faces());
        // Positions, normals and texcoords are written as float32.
        require_same_mesh(m, l.mesh, 1e-6);
        auto n0 = m.get_vertex_property<Vector3>("v:normal");
        auto n1 = l.mesh.get_vertex_property<Vector3>("v:normal");
        auto c0 = m.get_vertex_property<Color>("v:color");
        auto c1 = l.mesh.get_vertex_property<Color>("v:color");
        auto t0 = m.get_vertex_property<TexCoord>("v:texcoord");
        auto t1 = l.mesh.get_vertex_property<TexCoord>("v:texcoord");
        REQUIRE(n1);
        REQUIRE(c1);
        REQUIRE(t1);
        for (Vertex v : m.vertices()) {
            REQUIRE((n0[v] - n1[v]).norm() < 1e-6);
            REQUIRE((c0[v] - c1[v]).lpNorm<Eigen::Infinity>() <= 0.5f / 255.0f + 1e-6f);
            REQUIRE((t0[v] - t1[v]).norm() < 1e-6);
        }
    }
}

TEST_CASE("write_ply round-trips open and closed generated meshes", "[ply]") {
    TempDir dir;
    const HalfedgeMesh meshes[] = {make_grid(7), make_torus(12, 8, 1.0, 0.3), make_cube(),
                                   make_cylinder(10, 3)};
    for (const HalfedgeMesh& m : meshes) {
        for (bool ascii : {false, true}) {
            WriteOptions o;
            o.ascii = ascii;
            write_ply(m, dir.path("m.ply"), o);
            const LoadedMesh l = read_mesh(dir.path("m.ply"));
            REQUIRE_VALID(l.mesh);
            require_same_mesh(m, l.mesh, 1e-6);
            REQUIRE_FALSE(l.mesh.has_vertex_property("v:normal"));
            REQUIRE_FALSE(l.mesh.has_vertex_property("v:color"));
        }
    }
}

TEST_CASE("write_ply leaves out attributes the options switch off", "[ply]") {
    TempDir dir;
    WriteOptions o;
    o.write_normals = false;
    o.write_colors = false;
    o.write_texcoords = false;
    write_ply(attributed_sphere(), dir.path("plain.ply"), o);
    const LoadedMesh l = read_ply(dir.path("plain.ply"));
    REQUIRE_VALID(l.mesh);
    REQUIRE_FALSE(l.mesh.has_vertex_property("v:normal"));
    REQUIRE_FALSE(l.mesh.has_vertex_property("v:color"));
    REQUIRE_FALSE(l.mesh.has_vertex_property("v:texcoord"));
    REQUIRE(read_file_bytes(dir.path("plain.ply")).find("property list uchar int vertex_indices") !=
            std::string::npos);
}

TEST_CASE("read_ply reads binary big-endian", "[ply]") {
    TempDir dir;
    PlyBuilder b("binary_big_endian");
    b.header(
        "element vertex 4\nproperty double x\nproperty double y\nproperty double z\n"
        "element face 2\nproperty list uchar uint vertex_indices\n");
    const double p[4][3] = {{0, 0, 0}, {1.5, 0, 0}, {1.5, 2.25, 0}, {0, 2.25, -1e-3}};
    for (const auto& q : p) b.val("double", q[0]).val("double", q[1]).val("double", q[2]);
    b.list("uchar", "uint", {0, 1, 2}).list("uchar", "uint", {0, 2, 3});
    write_bytes(dir.path("be.ply"), b.bytes());
    const LoadedMesh l = read_ply(dir.path("be.ply"));
    REQUIRE_VALID(l.mesh);
    REQUIRE(l.mesh.n_vertices() == 4);
    REQUIRE(l.mesh.n_faces() == 2);
    for (Index i = 0; i < 4; ++i)
        REQUIRE(l.mesh.position(Vertex(i)) == Point(p[i][0], p[i][1], p[i][2]));
}

TEST_CASE("read_ply accepts every scalar type under both spellings", "[ply]") {
    const char* const types[] = {"char",   "int8",    "uchar",  "uint8",  "short", "int16",
                                 "ushort", "uint16",  "int",    "int32",  "uint",  "uint32",
                                 "float",  "float32", "double", "float64"};
    const char* const index_types[] = {"char", "uchar", "int16", "ushort", "int", "uint32"};
    TempDir dir;
    const double p[4][3] = {{0, 0, 0}, {3, 0, 0}, {0, 3, 0}, {0, 0, 3}};
    const std::vector<std::vector<double>> faces = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
    for (const char* enc : kEncodings) {
        for (std::size_t t = 0; t < std::size(types); ++t) {
            const std::string type = types[t];
            const std::string count_type = index_types[t % std::size(index_types)];
            const std::string index_type = index_types[(t + 1) % std::size(index_types)];
            INFO(enc << " positions " << type << ", list " << count_type << " " << index_type);
            PlyBuilder b(enc);
            b.header("element vertex 4\nproperty " + type + " x\nproperty " + type +
                     " y\nproperty " + type + " z\nelement face 4\nproperty list " + count_type +
                     " " + index_type + " vertex_indices\n");
            for (const auto& q : p) b.val(type, q[0]).val(type, q[1]).val(type, q[2]).end_row();
            for (const auto& f : faces) b.list(count_type, index_type, f).end_row();
            write_bytes(dir.path("t.ply"), b.bytes());
            const LoadedMesh l = read_ply(dir.path("t.ply"));
            REQUIRE_VALID(l.mesh);
            REQUIRE(l.mesh.n_vertices() == 4);
            REQUIRE(l.mesh.n_faces() == 4);
            REQUIRE(is_closed(l.mesh));
            REQUIRE(volume(l.mesh) == Approx(4.5));
            for (Index i = 0; i < 4; ++i)
                REQUIRE(l.mesh.position(Vertex(i)) == Point(p[i][0], p[i][1], p[i][2]));
        }
    }
}

TEST_CASE("read_ply skips unknown elements and properties in every encoding", "[ply]") {
    TempDir dir;
    for (const char* enc : kEncodings) {
        INFO(enc);
        PlyBuilder b(enc);
        b.header(
            "obj_info made by hand\n"
            "element material 2\nproperty list uchar float values\nproperty uchar id\n"
            "element vertex 4\nproperty float x\nproperty double quality\nproperty float y\n"
            "property list int short junk\nproperty float z\nproperty uchar alpha\n"
            "element face 2\nproperty uchar flags\nproperty list uchar uint vertex_indices\n"
            "property list ushort double weird\n"
            "element edge 1\nproperty int vertex1\nproperty int vertex2\n");
        b.list("uchar", "float", {1, 2, 3}).val("uchar", 7).end_row();
        b.list("uchar", "float", {}).val("uchar", 8).end_row();
        const double p[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
        for (const auto& q : p)
            b.val("float", q[0])
                .val("double", -5.5)
                .val("float", q[1])
                .list("int", "short", {9, -9, 300})
                .val("float", q[2])
                .val("uchar", 255)
                .end_row();
        b.val("uchar", 1).list("uchar", "uint", {0, 1, 2}).list("ushort", "double", {}).end_row();
        b.val("uchar", 2)
            .list("uchar", "uint", {0, 2, 3})
            .list("ushort", "double", {1e300, -2, 0.5})
            .end_row();
        b.val("int", 0).val("int", 1).end_row();
        write_bytes(dir.path("unknown.ply"), b.bytes());
        const LoadedMesh l = read_ply(dir.path("unknown.ply"));
        REQUIRE_VALID(l.mesh);
        REQUIRE(l.mesh.n_vertices() == 4);
        REQUIRE(l.mesh.n_faces() == 2);
        for (Index i = 0; i < 4; ++i)
            REQUIRE(l.mesh.position(Vertex(i)) == Point(p[i][0], p[i][1], p[i][2]));
        REQUIRE(surface_area(l.mesh) == Approx(1.0));
    }
}

TEST_CASE("read_ply reads faces before vertices, polygons and vertex_index lists", "[ply]") {
    TempDir dir;
    for (const char* enc : kEncodings) {
        INFO(enc);
        PlyBuilder b(enc);
        b.header(
            "element face 1\nproperty list int int vertex_index\n"
            "element vertex 5\nproperty float x\nproperty float y\nproperty float z\n");
        b.list("int", "int", {0, 1, 2, 3, 4}).end_row();
        const double p[5][2] = {{0, 0}, {2, 0}, {2, 2}, {1, 1}, {0, 2}};  // concave pentagon
        for (const auto& q : p) b.val("float", q[0]).val("float", q[1]).val("float", 0).end_row();
        write_bytes(dir.path("poly.ply"), b.bytes());
        const LoadedMesh l = read_ply(dir.path("poly.ply"));
        REQUIRE_VALID(l.mesh);
        REQUIRE(l.report.file_faces == 1);
        REQUIRE(l.report.polygons_triangulated == 1);
        REQUIRE(l.mesh.n_faces() == 3);
        REQUIRE(surface_area(l.mesh) == Approx(3.0));
    }
}

TEST_CASE("read_ply reads tristrips with restarts and alternating orientation", "[ply]") {
    TempDir dir;
    for (const char* enc : kEncodings) {
        INFO(enc);
        // Two rows of four vertices: y = 0 (0..3) and y = 1 (4..7).
        PlyBuilder b(enc);
        b.header(
            "element vertex 8\nproperty float x\nproperty float y\nproperty float z\n"
            "element tristrips 1\nproperty list int int vertex_indices\n");
        for (int r = 0; r < 2; ++r)
            for (int c = 0; c < 4; ++c) b.val("float", c).val("float", r).val("float", 0).end_row();
        // Strip over the first two quads, a restart, then the third quad.
        b.list("int", "int", {0, 4, 1, 5, 2, 6, -1, 2, 6, 3, 7}).end_row();
        write_bytes(dir.path("strip.ply"), b.bytes());
        const LoadedMesh l = read_ply(dir.path("strip.ply"));
        REQUIRE_VALID(l.mesh);
        REQUIRE(l.mesh.n_faces() == 6);
        REQUIRE(l.report.file_faces == 6);
        REQUIRE(l.report.detached_faces == 0);
        REQUIRE(surface_area(l.mesh) == Approx(3.0));
        // Consistent orientation: every face normal points the same way.
        for (Face f : l.mesh.faces()) REQUIRE(face_normal(l.mesh, f).z() == Approx(-1.0));
    }
}

TEST_CASE("read_ply reads colour, normal and texcoord spellings", "[ply]") {
    TempDir dir;
    const char* const uv_names[][2] = {
        {"u", "v"}, {"s", "t"}, {"texture_u", "texture_v"}, {"texture_s", "texture_t"}};
    for (const char* enc : kEncodings) {
        for (const auto& uv : uv_names) {
            INFO(enc << " " << uv[0]);
            PlyBuilder b(enc);
            b.header(std::string("element vertex 3\nproperty float x\nproperty float y\n"
                                 "property float z\nproperty float red\nproperty float green\n"
                                 "property float blue\nproperty double nx\nproperty double ny\n"
                                 "property double nz\nproperty float ") +
                     uv[0] + "\nproperty float " + uv[1] +
                     "\nelement face 1\nproperty list uchar int vertex_indices\n");
            const double p[3][2] = {{0, 0}, {1, 0}, {0, 1}};
            for (const auto& q : p)
                b.val("float", q[0])
                    .val("float", q[1])
                    .val("float", 0)
                    .val("float", 0.25)
                    .val("float", 0.5)
                    .val("float", 2.0)
                    .val("double", 0)
                    .val("double", 0)
                    .val("double", 1)
                    .val("float", q[0] * 0.5)
                    .val("float", q[1] * 0.25)
                    .end_row();
            b.list("uchar", "int", {0, 1, 2}).end_row();
            write_bytes(dir.path("attr.ply"), b.bytes());
            LoadedMesh l = read_ply(dir.path("attr.ply"));
            REQUIRE_VALID(l.mesh);
            auto color = l.mesh.get_vertex_property<Color>("v:color");
            auto normal = l.mesh.get_vertex_property<Vector3>("v:normal");
            auto tex = l.mesh.get_vertex_property<TexCoord>("v:texcoord");
            REQUIRE(color);
            REQUIRE(normal);
            REQUIRE(tex);
            // Float colours stay in [0, 1] (2.0 is clamped).
            REQUIRE(color[Vertex(1)] == Color(0.25f, 0.5f, 1.0f));
            REQUIRE(normal[Vertex(2)] == Vector3(0, 0, 1));
            REQUIRE(tex[Vertex(1)] == TexCoord(0.5, 0));
            REQUIRE(tex[Vertex(2)] == TexCoord(0, 0.25));
        }
    }
}

TEST_CASE("read_ply reads uchar colours and per-face texcoord lists", "[ply]") {
    TempDir dir;
    const std::string text =
        "ply\r\nformat ascii 1.0\r\ncomment CRLF header\r\n"
        "element vertex 4\r\nproperty float x\r\nproperty float y\r\nproperty float z\r\n"
        "property uchar red\r\nproperty uchar green\r\nproperty uchar blue\r\n"
        "element face 2\r\nproperty list uchar int vertex_indices\r\n"
        "property list uchar float texcoord\r\nend_header\r\n"
        "0 0 0 255 0 51\r\n1 0 0 0 255 0\r\n1 1 0 0 0 255\r\n0 1 0 10 20 30\r\n"
        "3 0 1 2 6 0 0 1 0 1 1\r\n3 0 2 3 6 0 0 1 1 0 1\r\n";
    write_bytes(dir.path("uv.ply"), text);
    LoadedMesh l = read_ply(dir.path("uv.ply"));
    REQUIRE_VALID(l.mesh);
    auto color = l.mesh.get_vertex_property<Color>("v:color");
    REQUIRE(color);
    REQUIRE(color[Vertex(0)].isApprox(Color(1.0f, 0.0f, 0.2f)));
    auto huv = l.mesh.get_halfedge_property<TexCoord>("h:texcoord");
    REQUIRE(huv);
    // The corner texture coordinate equals the (planar) position here.
    for (Face f : l.mesh.faces())
        for (Halfedge h : l.mesh.halfedges_of(f)) {
            const Point& p = l.mesh.position(l.mesh.to_vertex(h));
            REQUIRE(huv[h] == TexCoord(p.x(), p.y()));
        }
}

TEST_CASE("read_ply loads the shared horse", "[ply][shared]") {
    const std::string path = shared_mesh("horse.ply");
    SKIP_IF_MISSING(path);
    const LoadedMesh l = read_ply(path);
    REQUIRE_VALID(l.mesh);
    REQUIRE(l.mesh.n_vertices() == 48485);
    REQUIRE(l.mesh.n_faces() == 96966);
    REQUIRE(l.mesh.has_vertex_property("v:normal"));
    TempDir dir;
    write_ply(l.mesh, dir.path("horse.ply"), {});
    const LoadedMesh back = read_ply(dir.path("horse.ply"));
    require_same_mesh(l.mesh, back.mesh, 0.0);  // float positions round-trip exactly
}

// ---- STL ---------------------------------------------------------------------------------

TEST_CASE("write_stl and read_stl round-trip binary and ASCII", "[stl]") {
    TempDir dir;
    const HalfedgeMesh meshes[] = {make_icosphere(4), make_grid(6), make_torus(16, 9, 1.0, 0.3),
                                   make_cube()};
    for (const HalfedgeMesh& m : meshes) {
        for (bool ascii : {false, true}) {
            INFO((ascii ? "ascii" : "binary") << " " << m.n_faces() << " faces");
            WriteOptions o;
            o.ascii = ascii;
            write_stl(m, dir.path("m.stl"), o);
            const std::string bytes = read_file_bytes(dir.path("m.stl"));
            if (ascii) {
                REQUIRE(bytes.rfind("solid trilab\n", 0) == 0);
                REQUIRE_THAT(bytes, Contains("endsolid trilab"));
            } else {
                REQUIRE(bytes.size() == 84 + 50 * m.n_faces());
                REQUIRE(bytes.rfind("solid", 0) == std::string::npos);
            }
            const LoadedMesh l = read_mesh(dir.path("m.stl"));
            REQUIRE_VALID(l.mesh);
            REQUIRE(l.report.format == "stl");
            REQUIRE(l.mesh.n_vertices() == m.n_vertices());
            REQUIRE(l.mesh.n_faces() == m.n_faces());
            REQUIRE(l.report.file_faces == m.n_faces());
            REQUIRE(l.report.file_vertices == 3 * m.n_faces());
            REQUIRE(l.report.merged_vertices == 3 * m.n_faces() - m.n_vertices());
            REQUIRE(l.report.detached_faces == 0);
            // ASCII keeps doubles exactly; binary STL stores float32.
            require_same_faces(m, l.mesh, ascii ? 0.0 : 1e-6);
            REQUIRE(surface_area(l.mesh) == Approx(surface_area(m)).epsilon(1e-6));
        }
    }
}

TEST_CASE("write_stl computes facet normals and zero attribute counts", "[stl]") {
    TempDir dir;
    const HalfedgeMesh m = make_cube();
    write_stl(m, dir.path("cube.stl"), {});
    const std::string bytes = read_file_bytes(dir.path("cube.stl"));
    REQUIRE(bytes.size() == 84 + 50 * 12);
    std::uint32_t n = 0;
    std::memcpy(&n, bytes.data() + 80, 4);
    REQUIRE(n == 12);
    std::size_t f = 0;
    for (Face face : m.faces()) {
        const char* rec = bytes.data() + 84 + 50 * f++;
        float normal[3];
        std::memcpy(normal, rec, 12);
        const Vector3 expected = face_normal(m, face);
        for (int k = 0; k < 3; ++k) REQUIRE(normal[k] == Approx(expected[k]).margin(1e-6));
        REQUIRE(rec[48] == 0);
        REQUIRE(rec[49] == 0);
    }
}

TEST_CASE("read_stl reads a binary file whose header starts with solid as binary", "[stl]") {
    TempDir dir;
    const HalfedgeMesh m = make_icosphere(2);
    write_stl(m, dir.path("a.stl"), {});
    std::string bytes = read_file_bytes(dir.path("a.stl"));
    const std::string fake = "solid pretending to be text\nfacet normal 0 0 1\n";
    bytes.replace(0, fake.size(), fake);
    write_bytes(dir.path("solid.stl"), bytes);
    const LoadedMesh l = read_stl(dir.path("solid.stl"));
    REQUIRE_VALID(l.mesh);
    REQUIRE(l.mesh.n_faces() == m.n_faces());
    REQUIRE(l.mesh.n_vertices() == m.n_vertices());
}

TEST_CASE("read_stl is lenient about ASCII layout and merges identical corners", "[stl]") {
    TempDir dir;
    // Upper-case keywords, no names, odd whitespace, no normal, -0 versus +0, two solids and
    // no final endsolid.
    const std::string text =
        "SOLID\n"
        "  FACET NORMAL 0 0 1\n  OUTER LOOP\n\tVERTEX 0 0 0\n VERTEX 1 0 0\n"
        "   vertex   0   1   0   \n ENDLOOP\nENDFACET\n"
        "endsolid\r\n"
        "solid second part\r\n"
        "facet normal nan nan nan\r\nouter loop\r\n"
        "vertex 1 0 -0\r\nvertex 1 1 0\r\nvertex -0.0 1e0 0\r\nendloop\r\nendfacet\r\n"
        "facet outer loop vertex 1 0 0 vertex 1 1 1e-300 vertex 1 1 0 endloop endfacet\n";
    write_bytes(dir.path("lenient.stl"), text);
    const LoadedMesh l = read_stl(dir.path("lenient.stl"));
    REQUIRE_VALID(l.mesh);
    REQUIRE(l.mesh.n_faces() == 3);
    REQUIRE(l.mesh.n_vertices() == 5);
    REQUIRE(l.report.file_vertices == 9);
    REQUIRE(l.report.merged_vertices == 4);
}

TEST_CASE("read_stl merges the corners of a larger binary file", "[stl]") {
    TempDir dir;
    const HalfedgeMesh m = make_torus(200, 100, 1.0, 0.3);
    write_stl(m, dir.path("torus.stl"), {});
    const LoadedMesh l = read_stl(dir.path("torus.stl"));
    REQUIRE_VALID(l.mesh);
    REQUIRE(l.mesh.n_vertices() == m.n_vertices());
    REQUIRE(l.report.merged_vertices == 3 * m.n_faces() - m.n_vertices());
}

// ---- errors --------------------------------------------------------------------------------

TEST_CASE("bad PLY and STL files give an IoError naming the file, the line and the reason",
          "[ply][stl][bad]") {
    struct Case {
        const char* file;
        const char* line;  // ":N" expected right after the file name, or "" for none
        const char* reason;
    };
    const Case cases[] = {
        {"ply_nan_coordinate.ply", ":11", "not a finite number"},
        {"ply_index_out_of_range.ply", ":13", "vertex index 7 is out of range"},
        {"ply_negative_index.ply", ":13", "negative vertex index -1"},
        {"ply_bad_number.ply", ":11", "not a number"},
        {"ply_ascii_truncated.ply", ":13", "unexpected end of file"},
        {"ply_absurd_count.ply", ":3", "declares 4000000000"},
        {"ply_missing_end_header.ply", ":7", "in the PLY header"},
        {"ply_header_eof.ply", ":4", "no end_header"},
        {"ply_bad_format.ply", ":2", "unknown PLY encoding"},
        {"ply_unknown_type.ply", ":4", "unknown property type 'flaot'"},
        {"ply_no_xyz.ply", ":3", "lacks an x, y or z"},
        {"ply_not_ply.ply", ":1", "not a PLY file"},
        {"ply_garbage.ply", ":1", "not a PLY file"},
        {"ply_empty.ply", ":1", "not a PLY file"},
        {"ply_truncated_binary.ply", "", "ends inside face 1"},
        {"ply_truncated_vertices.ply", ":3", "declares 3 'vertex' elements, more than"},
        {"ply_binary_out_of_range.ply", "", "face 1: vertex index 3 is out of range"},
        {"ply_binary_negative_index.ply", "", "face 0: negative vertex index -5"},
        {"ply_binary_negative_index_le.ply", "", "face 1: negative vertex index -1"},
        {"ply_binary_nan.ply", "", "non-finite"},
        {"ply_binary_absurd_count.ply", ":7", "declares 4000000000"},
        {"ply_binary_huge_list.ply", "", "ends inside entry 0 of element 'junk'"},
        {"stl_truncated_binary.stl", "", "declares 2 triangles"},
        {"stl_truncated_solid_header.stl", "", "declares 3 triangles"},
        {"stl_binary_nan.stl", "", "triangle 1, corner 1: non-finite"},
        {"stl_garbage.stl", ":1", "not an STL file"},
        {"stl_empty.stl", ":1", "empty file"},
        {"stl_nan_coordinate.stl", ":5", "not a finite number"},
        {"stl_four_vertices.stl", ":9", "facet has 4 vertices"},
        {"stl_two_vertices.stl", ":2", "facet has 2 vertices"},
        {"stl_missing_endloop.stl", ":6", "unexpected end of file"},
        {"stl_bad_keyword.stl", ":6", "found 'vortex'"},
    };
    for (const Case& c : cases) {
        INFO(c.file);
        const std::string path = data_file(std::string("bad/") + c.file);
        REQUIRE(exists(path));
        const std::string msg = read_error(path);
        REQUIRE_THAT(msg, Contains(c.file));
        REQUIRE_THAT(msg, Contains(c.reason));
        if (*c.line)
            REQUIRE_THAT(msg, Contains(std::string(c.file) + c.line + ":"));
        else
            REQUIRE_THAT(msg, Contains(std::string(c.file) + ": "));
    }
}

TEST_CASE("every ply_ and stl_ file in tests/data/bad throws IoError", "[ply][stl][bad]") {
    std::size_t n = 0;
    for (const auto& entry : std::filesystem::directory_iterator(data_file("bad"))) {
        const std::string name = entry.path().filename().string();
        if (name.rfind("ply_", 0) != 0 && name.rfind("stl_", 0) != 0) continue;
        INFO(name);
        REQUIRE_THROWS_WITH(read_mesh(entry.path().string()), Contains(name));
        ++n;
    }
    REQUIRE(n >= 20);
}

TEST_CASE("write_ply and write_stl into a missing folder throw IoError", "[ply][stl]") {
    TempDir dir;
    const HalfedgeMesh m = make_cube();
    WriteOptions ascii;
    ascii.ascii = true;
    for (const WriteOptions& o : {WriteOptions{}, ascii}) {
        REQUIRE_THROWS_AS(write_ply(m, dir.path("missing/folder/m.ply"), o), IoError);
        REQUIRE_THROWS_AS(write_stl(m, dir.path("missing/folder/m.stl"), o), IoError);
    }
    REQUIRE_THROWS_WITH(write_mesh(m, dir.path("missing/m.stl")), Contains("missing/m.stl"));
}

// ---- values out of their type's range, non-integral indices ---------------------------------

namespace {

/// A one-triangle PLY whose third vertex carries `type name` = `value` (ascii) after x y z.
std::string ply_with_value(const std::string& encoding, const std::string& type,
                           const std::string& name, double value) {
    PlyBuilder b(encoding);
    b.header("element vertex 3\nproperty float x\nproperty float y\nproperty float z\nproperty " +
             type + " " + name + "\nelement face 1\nproperty list uchar int vertex_indices\n");
    b.val("float", 0).val("float", 0).val("float", 0).val(type, 0).end_row();
    b.val("float", 1).val("float", 0).val("float", 0).val(type, 0).end_row();
    b.val("float", 0).val("float", 1).val("float", 0).val(type, value).end_row();
    b.list("uchar", "int", {0, 1, 2}).end_row();
    return b.bytes();
}

}  // namespace

TEST_CASE("ASCII PLY refuses values outside their declared type", "[ply][range]") {
    struct Case {
        std::string type, name;
        double value;
        std::string reason;
    };
    const Case bad[] = {
        {"uchar", "red", 300, "property 'red': 300 is out of range for type uchar (0 to 255)"},
        {"uchar", "red", -1, "property 'red': -1 is out of range for type uchar (0 to 255)"},
        {"char", "quality", -129,
         "property 'quality': -129 is out of range for type char (-128 to 127)"},
        {"ushort", "id", 70000,
         "property 'id': 70000 is out of range for type ushort (0 to 65535)"},
        {"int", "id", 2.5, "property 'id': 2.5 is not a whole number, as type int requires"},
        {"uint", "id", 4294967296.0,
         "property 'id': 4294967296 is out of range for type uint (0 to 4294967295)"},
        {"float", "nx", 1e39,
         "property 'nx': 1e+39 is out of range for type float (at most 3.4e38 "
         "in magnitude)"},
    };
    for (const Case& c : bad) {
        INFO(c.type << " " << c.value);
        const std::string msg = [&] {
            try {
                read_ply_bytes(ply_with_value("ascii", c.type, c.name, c.value), "r.ply");
            } catch (const IoError& e) {
                CHECK(e.line() == 14);  // the third vertex row
                return e.reason();
            }
            return std::string();
        }();
        CHECK(msg == c.reason);
    }
    // The extremes themselves are fine, used or skipped.
    for (const Case& c : {Case{"uchar", "red", 255, ""}, Case{"char", "quality", -128, ""},
                          Case{"double", "nx", 1e300, ""}, Case{"float", "s", 3.4e38, ""}}) {
        INFO(c.type << " " << c.value);
        CHECK(read_ply_bytes(ply_with_value("ascii", c.type, c.name, c.value), "r.ply")
                  .mesh.n_faces() == 1);
    }
    // List lengths and indices are whole numbers in their type's range too.
    PlyBuilder b("ascii");
    b.header(
        "element vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face "
        "1\nproperty list uchar float vertex_indices\n");
    b.val("float", 0).val("float", 0).val("float", 0).end_row();
    b.val("float", 1).val("float", 0).val("float", 0).end_row();
    b.val("float", 0).val("float", 1).val("float", 0).end_row();
    b.list("uchar", "float", {0, 1.5, 2}).end_row();
    CHECK_THROWS_WITH(read_ply_bytes(b.bytes(), "i.ply"),
                      Contains("i.ply:14: a vertex index: 1.5 is not a whole number"));
}

TEST_CASE("binary PLY refuses float vertex indices that are not whole numbers", "[ply][range]") {
    for (const char* enc : {"binary_little_endian", "binary_big_endian"}) {
        for (const char* type : {"float", "double"}) {
            INFO(enc << " " << type);
            auto ply = [&](double index) {
                PlyBuilder b(enc);
                b.header(std::string("element vertex 3\nproperty float x\nproperty float y\n"
                                     "property float z\nelement face 2\nproperty list uchar ") +
                         type + " vertex_indices\n");
                b.val("float", 0).val("float", 0).val("float", 0);
                b.val("float", 1).val("float", 0).val("float", 0);
                b.val("float", 0).val("float", 1).val("float", 0);
                b.list("uchar", type, {0, 1, 2}).list("uchar", type, {0, index, 1});
                return b.bytes();
            };
            // 2.0 is a whole number: a second face (a detached duplicate)
            CHECK(read_ply_bytes(ply(2.0), "f.ply").mesh.n_faces() == 2);
            CHECK_THROWS_WITH(read_ply_bytes(ply(2.5), "f.ply"),
                              Contains("f.ply: face 1: vertex index 2.5 is not a whole number"));
            const FpTrapsOff traps_off;  // a NaN index on purpose
            CHECK_THROWS_WITH(read_ply_bytes(ply(std::nan("")), "f.ply"),
                              Contains("face 1: vertex index nan is not a whole number"));
        }
    }
}

// ---- writers never write what their readers refuse ------------------------------------------

namespace {

/// A tetrahedron scaled by `s`, with normals, colours and texture coordinates.
HalfedgeMesh attributed_tetrahedron(double s = 1) {
    HalfedgeMesh m = make_tetrahedron();
    auto n = m.vertex_property<Vector3>("v:normal");
    auto c = m.vertex_property<Color>("v:color");
    auto uv = m.vertex_property<TexCoord>("v:texcoord");
    // Unit normals from the unscaled corners (the same directions; at 1e300 their squared
    // norms would overflow).
    for (Vertex v : m.vertices()) n[v] = m.position(v).normalized();
    for (Point& p : m.positions()) p *= s;
    for (Vertex v : m.vertices()) {
        c[v] = Color(0.25f, 0.5f, 1.0f);
        uv[v] = TexCoord(0.1 * v.idx(), 0.5);
    }
    return m;
}

/// The reason of the IoError writing `mesh` to `name` throws ("" when none).
std::string write_refusal(const HalfedgeMesh& mesh, const std::string& name,
                          const WriteOptions& options = {}) {
    try {
        write_mesh_bytes(mesh, name, options);
    } catch (const IoError& e) {
        CHECK(e.file() == name);
        return e.reason();
    }
    return "";
}

}  // namespace

TEST_CASE("writers refuse non-finite values in what they write", "[ply][stl][io][nonfinite]") {
    const FpTrapsOff traps_off;  // NaN and infinity on purpose
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const char* const formats[] = {"m.obj", "m.off", "m.ply", "m.stl", "m.om"};
    for (const char* name : formats) {
        INFO(name);
        HalfedgeMesh m = attributed_tetrahedron();
        m.position(Vertex(2)) = Point(0, std::numeric_limits<double>::infinity(), 0);
        CHECK(write_refusal(m, name).find("vertex 2: non-finite position") == 0);
        CHECK(write_refusal(m, name).find("not written") != std::string::npos);
    }
    struct Attribute {
        const char* name;
        std::function<void(HalfedgeMesh&)> spoil;
        const char* reason;
        std::vector<std::string> carriers;  // the formats that write it
    };
    const Attribute attributes[] = {
        {"normal",
         [&](HalfedgeMesh& m) { m.vertex_property<Vector3>("v:normal")[Vertex(1)].x() = nan; },
         "vertex 1: non-finite normal",
         {"m.obj", "m.off", "m.ply", "m.om"}},
        {"colour",
         [&](HalfedgeMesh& m) { m.vertex_property<Color>("v:color")[Vertex(3)].y() = NAN; },
         "vertex 3: non-finite colour",
         {"m.off", "m.ply", "m.om"}},
        {"texcoord",
         [&](HalfedgeMesh& m) { m.vertex_property<TexCoord>("v:texcoord")[Vertex(0)].y() = nan; },
         "vertex 0: non-finite texture coordinate",
         {"m.obj", "m.off", "m.ply", "m.om"}},
    };
    for (const Attribute& a : attributes) {
        HalfedgeMesh m = attributed_tetrahedron();
        a.spoil(m);
        for (const char* name : formats) {
            INFO(a.name << " " << name);
            const bool carried =
                std::find(a.carriers.begin(), a.carriers.end(), name) != a.carriers.end();
            if (carried)
                CHECK(write_refusal(m, name).find(a.reason) == 0);
            else
                CHECK(write_refusal(m, name).empty());  // not written, so not refused
        }
        // Switched off, the attribute is not written and not refused.
        WriteOptions off;
        off.write_normals = off.write_colors = off.write_texcoords = false;
        for (const char* name : formats) CHECK(write_refusal(m, name, off).empty());
    }
}

TEST_CASE("values float32 cannot hold: PLY writes doubles, binary STL and .om refuse",
          "[ply][stl][om][range]") {
    for (const double scale : {1e300, 1e-35, 1e39}) {
        INFO("scale " << scale);
        const HalfedgeMesh m = attributed_tetrahedron(scale);
        for (const bool ascii : {false, true}) {
            WriteOptions options;
            options.ascii = ascii;
            const std::string ply = write_mesh_bytes(m, "m.ply", options);
            CHECK(ply.find("property double x\nproperty double y\nproperty double z\n") !=
                  std::string::npos);
            CHECK(ply.find("property float nx") != std::string::npos);  // unit normals fit
            const LoadedMesh back = read_ply_bytes(ply, "m.ply");
            require_same_mesh(m, back.mesh, 0.0);  // doubles: exact
        }
        // Binary STL: float32 only.
        const std::string reason = write_refusal(m, "m.stl");
        CHECK(reason.find("binary STL stores float32 coordinates") == 0);
        CHECK(reason.find("--ascii") != std::string::npos);
        // ASCII STL: shortest decimals of the doubles, exact.
        WriteOptions ascii;
        ascii.ascii = true;
        require_same_faces(m, read_stl_bytes(write_mesh_bytes(m, "a.stl", ascii), "a.stl").mesh,
                           0.0);
    }
    // Ordinary values stay float32.
    CHECK(write_mesh_bytes(attributed_tetrahedron(), "m.ply").find("property float x") !=
          std::string::npos);
    // Normals and texture coordinates too big for float: doubles in PLY, refused by .om
    // (texture coordinates; its normals are doubles already).
    HalfedgeMesh m = attributed_tetrahedron();
    m.vertex_property<Vector3>("v:normal")[Vertex(0)] = Vector3(1e300, 0, 0);
    m.vertex_property<TexCoord>("v:texcoord")[Vertex(1)] = TexCoord(1e40, 0);
    const std::string ply = write_mesh_bytes(m, "m.ply");
    CHECK(ply.find("property double nx") != std::string::npos);
    CHECK(ply.find("property double u") != std::string::npos);
    const LoadedMesh back = read_ply_bytes(ply, "m.ply");
    CHECK(back.mesh.get_vertex_property<Vector3>("v:normal")[Vertex(0)] == Vector3(1e300, 0, 0));
    CHECK(back.mesh.get_vertex_property<TexCoord>("v:texcoord")[Vertex(1)] == TexCoord(1e40, 0));
    CHECK(write_refusal(m, "m.om").find(".om stores texture coordinates as float32") == 0);
    CHECK(read_om_bytes(write_mesh_bytes(attributed_tetrahedron(1e300), "m.om"), "m.om")
              .mesh.position(Vertex(1)) == attributed_tetrahedron(1e300).position(Vertex(1)));
}

TEST_CASE("STL refuses a mesh without faces, saying why", "[stl]") {
    PolygonSoup soup;
    soup.positions = {Point(0, 0, 0), Point(1, 2, 3)};
    LoadReport report;
    const HalfedgeMesh points = build_mesh(soup, report);
    for (const bool ascii : {false, true}) {
        WriteOptions options;
        options.ascii = ascii;
        CHECK(write_refusal(points, "p.stl", options) ==
              "STL holds only triangles and the mesh has no faces (2 vertices): not written; use "
              "OBJ, OFF, PLY or .om for points");
    }
    TempDir dir;
    CHECK_THROWS_AS(write_mesh(points, dir.path("p.stl")), IoError);
    CHECK_FALSE(exists(dir.path("p.stl")));
}
