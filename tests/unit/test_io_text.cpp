// OBJ and OFF readers and writers, the format dispatch, atomic saving, and the shared meshes.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <utility>

#include "core/algorithms/generators.h"
#include "core/algorithms/mesh_stats.h"
#include "core/errors.h"
#include "core/geometry.h"
#include "core/io/file_util.h"
#include "core/io/image_io.h"
#include "core/io/mesh_io.h"
#include "test_helpers.h"

using namespace trilab;
using namespace trilab::test;
using Catch::Matchers::Contains;

namespace {
/// Positions and faces (as vertex triples) equal, positions within `tol`.
void require_same_mesh(const HalfedgeMesh& a, const HalfedgeMesh& b, double tol = 0.0) {
    REQUIRE(a.n_vertices() == b.n_vertices());
    REQUIRE(a.n_faces() == b.n_faces());
    const PolygonSoup sa = to_soup(a), sb = to_soup(b);
    for (std::size_t i = 0; i < sa.positions.size(); ++i)
        REQUIRE((sa.positions[i] - sb.positions[i]).norm() <= tol);
    REQUIRE(sa.corners == sb.corners);
}

}  // namespace

TEST_CASE("file_extension and dispatch", "[io]") {
    REQUIRE(file_extension("a/b.c/mesh.OBJ") == "obj");
    REQUIRE(file_extension("a/b.c/mesh") == "");
    REQUIRE(file_extension("x.tar.gz") == "gz");
    TempDir dir;
    REQUIRE_THROWS_WITH(read_mesh(dir.path("m.xyz")), Contains("unknown mesh format"));
    REQUIRE_THROWS_AS(write_mesh(make_cube(), dir.path("m.xyz")), IoError);
    REQUIRE_THROWS_WITH(read_mesh(dir.path("missing.obj")), Contains("cannot open"));
}

TEST_CASE("OBJ round trip keeps positions exactly, faces, normals and texture coordinates",
          "[io][obj]") {
    TempDir dir;
    HalfedgeMesh m = attributed_sphere();
    write_obj(m, dir.path("s.obj"), {});
    LoadedMesh back = read_obj(dir.path("s.obj"));
    REQUIRE_VALID(back.mesh);
    require_same_mesh(m, back.mesh);
    auto uv0 = m.get_vertex_property<TexCoord>("v:texcoord");
    auto uv1 = back.mesh.get_vertex_property<TexCoord>("v:texcoord");
    auto n0 = m.get_vertex_property<Vector3>("v:normal");
    auto n1 = back.mesh.get_vertex_property<Vector3>("v:normal");
    REQUIRE(uv1);
    REQUIRE(n1);
    for (Vertex v : m.vertices()) {
        REQUIRE(uv0[v] == uv1[v]);
        REQUIRE(n0[v] == n1[v]);
    }
    REQUIRE(back.report.format == "obj");
}

TEST_CASE("OBJ keeps texture seams as per-corner coordinates", "[io][obj]") {
    LoadedMesh seams = read_obj(data_file("good/seams.obj"));
    REQUIRE_VALID(seams.mesh);
    REQUIRE(seams.mesh.n_vertices() == 4);  // geometry stays connected across the seam
    REQUIRE(seams.mesh.n_faces() == 2);
    auto corner = seams.mesh.get_halfedge_property<TexCoord>("h:texcoord");
    REQUIRE(corner);
    REQUIRE_FALSE(seams.mesh.has_vertex_property("v:texcoord"));
    // Write and read back: the seam survives.
    TempDir dir;
    write_obj(seams.mesh, dir.path("seams.obj"), {});
    LoadedMesh back = read_obj(dir.path("seams.obj"));
    auto corner_back = back.mesh.get_halfedge_property<TexCoord>("h:texcoord");
    REQUIRE(corner_back);
    REQUIRE(to_soup(back.mesh).corner_texcoords == to_soup(seams.mesh).corner_texcoords);
}

TEST_CASE("OBJ polygons are triangulated with their corner data", "[io][obj]") {
    LoadedMesh l = read_obj(data_file("good/concave_polygon.obj"));
    REQUIRE_VALID(l.mesh);
    REQUIRE(l.mesh.n_faces() == 4);
    REQUIRE(l.report.polygons_triangulated == 1);
    REQUIRE(surface_area(l.mesh) == Approx(3.0));
    // Each vertex has one texture coordinate here, so they are per vertex.
    auto uv = l.mesh.get_vertex_property<TexCoord>("v:texcoord");
    REQUIRE(uv);
    REQUIRE(uv[Vertex(1)] == TexCoord(1, 0));
}

TEST_CASE("OFF round trip with every header variant", "[io][off]") {
    TempDir dir;
    HalfedgeMesh m = attributed_sphere();
    for (int variant = 0; variant < 4; ++variant) {
        WriteOptions o;
        o.write_normals = variant & 1;
        o.write_colors = variant & 2;
        o.write_texcoords = variant != 0;
        write_off(m, dir.path("s.off"), o);
        LoadedMesh back = read_off(dir.path("s.off"));
        REQUIRE_VALID(back.mesh);
        require_same_mesh(m, back.mesh);
        REQUIRE(back.mesh.has_vertex_property("v:normal") == o.write_normals);
        REQUIRE(back.mesh.has_vertex_property("v:color") == o.write_colors);
        REQUIRE(back.mesh.has_vertex_property("v:texcoord") == o.write_texcoords);
        if (o.write_colors) {
            auto c0 = m.get_vertex_property<Color>("v:color");
            auto c1 = back.mesh.get_vertex_property<Color>("v:color");
            for (Vertex v : m.vertices()) REQUIRE((c0[v] - c1[v]).norm() < 1e-6f);
        }
    }
}

TEST_CASE("OFF header variants: comments, counts on the keyword line, COFF bytes, polygons",
          "[io][off]") {
    LoadedMesh l = read_off(data_file("good/header_variants.off"));
    REQUIRE_VALID(l.mesh);
    REQUIRE(l.mesh.n_vertices() == 4);
    REQUIRE(l.mesh.n_faces() == 3);  // a quad (two triangles) and a triangle
    auto c = l.mesh.get_vertex_property<Color>("v:color");
    REQUIRE(c);
    REQUIRE(c[Vertex(0)].x() == Approx(1.0f));
    REQUIRE(c[Vertex(1)].y() == Approx(1.0f));
    REQUIRE(l.report.polygons_triangulated == 1);
}

TEST_CASE("repairable inputs load as valid meshes with a report", "[io][repair]") {
    SECTION("non-manifold vertex") {
        LoadedMesh l = read_mesh(data_file("good/bowtie.off"));
        REQUIRE_VALID(l.mesh);
        REQUIRE(l.report.nonmanifold_vertices_split == 1);
        REQUIRE(l.mesh.n_faces() == 2);
    }
    SECTION("non-manifold edge") {
        LoadedMesh l = read_mesh(data_file("good/nonmanifold_edge.off"));
        REQUIRE_VALID(l.mesh);
        REQUIRE(l.report.detached_faces == 1);
        REQUIRE(l.mesh.n_faces() == 3);
    }
    SECTION("duplicated face") {
        LoadedMesh l = read_mesh(data_file("good/duplicated_face.off"));
        REQUIRE_VALID(l.mesh);
        REQUIRE(l.report.detached_faces == 1);
    }
    SECTION("flipped neighbour") {
        LoadedMesh l = read_mesh(data_file("good/flipped_neighbour.off"));
        REQUIRE_VALID(l.mesh);
        REQUIRE(l.report.detached_faces == 1);
    }
    SECTION("degenerate face and isolated vertex") {
        LoadedMesh l = read_mesh(data_file("good/degenerate_and_isolated.off"));
        REQUIRE_VALID(l.mesh);
        REQUIRE(l.report.degenerate_faces_dropped == 1);
        REQUIRE(l.report.isolated_vertices == 1);
        REQUIRE(l.mesh.n_vertices() == 5);
    }
    SECTION("zero faces") {
        LoadedMesh l = read_mesh(data_file("good/zero_faces.off"));
        REQUIRE_VALID(l.mesh);
        REQUIRE(l.mesh.n_faces() == 0);
        REQUIRE(l.report.isolated_vertices == 3);
    }
}

TEST_CASE("bad OBJ and OFF files give an error naming the file, the line and the reason",
          "[io][bad]") {
    struct Case {
        const char* file;
        const char* line;  // ":N" expected in the message, or "" for no line
        const char* reason;
    };
    const Case cases[] = {
        {"obj_nan.obj", ":2", "not a finite number"},
        {"obj_garbage_number.obj", ":3", "not a finite number"},
        {"obj_out_of_range.obj", ":5", "refers to vertex 7 but the file has 3"},
        {"obj_negative_index.obj", ":4", "refers to vertex -9"},
        {"obj_zero_index.obj", ":4", "index 0 is invalid"},
        {"obj_empty.obj", "", "no vertices"},
        {"off_truncated.off", ":7", "unexpected end of file"},
        {"off_absurd_count.off", ":2", "declares 4000000000 vertices"},
        {"off_negative_index.off", ":6", "refers to vertex -2"},
        {"off_out_of_range.off", ":6", "refers to vertex 3"},
        {"off_nan.off", ":4", "not a finite number"},
        {"off_garbage.off", ":1", "is not an OFF header keyword"},
        {"off_wrong_keyword.off", ":1", "not an OFF header"},
        {"off_absurd_face_size.off", ":6", "corners"},
        {"off_4d.off", ":1", "3-dimensional"},
    };
    for (const Case& c : cases) {
        INFO(c.file);
        const std::string msg = read_error(data_file(std::string("bad/") + c.file));
        REQUIRE_THAT(msg, Contains(c.file));
        REQUIRE_THAT(msg, Contains(c.reason));
        if (*c.line) REQUIRE_THAT(msg, Contains(std::string(c.file) + c.line));
    }
}

TEST_CASE("saving is atomic: a failed save leaves the old file intact", "[io][atomic]") {
    TempDir dir;
    const std::string path = dir.path("keep.obj");
    write_mesh(make_cube(), path);
    const std::string before = read_file_bytes(path);
    REQUIRE_THROWS_AS(write_file_atomically(path,
                                            [](std::ostream& os) {
                                                os << "partial";
                                                throw IoError("x", 0, "simulated failure");
                                            }),
                      IoError);
    REQUIRE(read_file_bytes(path) == before);
    // No temporary file is left behind.
    std::size_t files = 0;
    for (const auto& entry : std::filesystem::directory_iterator(dir.dir())) {
        (void)entry;
        ++files;
    }
    REQUIRE(files == 1);
    REQUIRE_THROWS_AS(write_mesh(make_cube(), dir.path("no/such/folder/x.obj")), IoError);
}

TEST_CASE("the shared Stanford bunny loads with its isolated vertices", "[io][shared]") {
    const std::string path = shared_mesh("stanford-bunny.obj");
    SKIP_IF_MISSING(path);
    LoadedMesh l = read_mesh(path);
    REQUIRE_VALID(l.mesh);
    REQUIRE(l.mesh.n_vertices() == 35947);
    REQUIRE(l.mesh.n_faces() == 69451);
    REQUIRE(l.report.isolated_vertices == 1113);
    const MeshStats s = compute_stats(l.mesh);
    REQUIRE(s.isolated_vertices == 1113);
    REQUIRE(s.components == 1);
    REQUIRE(s.boundary_loops == 5);
}

TEST_CASE("every shared mesh loads valid and survives OBJ and OFF round trips", "[io][shared]") {
    const std::string dir = shared_dir() + "/meshes";
    SKIP_IF_MISSING(dir);
    TempDir tmp;
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
        const std::string path = entry.path().string();
        const std::string ext = file_extension(path);
        if (ext != "obj" && ext != "off") continue;
        INFO(path);
        LoadedMesh l = read_mesh(path);
        REQUIRE_VALID(l.mesh);
        for (const char* out : {"r.obj", "r.off"}) {
            write_mesh(l.mesh, tmp.path(out));
            LoadedMesh back = read_mesh(tmp.path(out));
            REQUIRE_VALID(back.mesh);
            require_same_mesh(l.mesh, back.mesh);
        }
    }
}

TEST_CASE("OBJ material libraries give the texture file", "[io][obj]") {
    LoadedMesh l = read_obj(data_file("good/textured.obj"));
    REQUIRE_VALID(l.mesh);
    REQUIRE_THAT(l.texture_path, Contains("checker.png"));
    REQUIRE(std::filesystem::path(l.texture_path).parent_path() ==
            std::filesystem::path(data_file("good/textured.obj")).parent_path());
    // A missing library is a note, not an error.
    TempDir dir;
    {
        std::ofstream out(dir.path("m.obj"));
        out << "mtllib nowhere.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    }
    LoadedMesh m = read_obj(dir.path("m.obj"));
    REQUIRE(m.texture_path.empty());
    REQUIRE(m.report.notes.size() == 1);
}

TEST_CASE("OBJ negative indices count back from the last vertex", "[io][obj]") {
    TempDir dir;
    {
        std::ofstream out(dir.path("n.obj"));
        out << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\nv 1 1 0\nf 2 -1 3\n";
    }
    LoadedMesh m = read_obj(dir.path("n.obj"));
    REQUIRE_VALID(m.mesh);
    REQUIRE(m.mesh.n_faces() == 2);
    REQUIRE(m.report.detached_faces == 0);
}

TEST_CASE("texture coordinates survive every format that can carry them", "[io][texcoords]") {
    TempDir dir;
    // Per-vertex coordinates: OBJ, OFF (STOFF), PLY, OM.
    HalfedgeMesh m = attributed_sphere();
    auto uv = m.get_vertex_property<TexCoord>("v:texcoord");
    for (const char* name : {"v.obj", "v.off", "v.ply", "v.om"}) {
        INFO(name);
        write_mesh(m, dir.path(name));
        LoadedMesh back = read_mesh(dir.path(name));
        REQUIRE_VALID(back.mesh);
        auto uv_back = back.mesh.get_vertex_property<TexCoord>("v:texcoord");
        REQUIRE(uv_back);
        for (Vertex v : m.vertices()) REQUIRE((uv[v] - uv_back[v]).norm() < 1e-6);
    }
    // Per-corner coordinates (a seam): OBJ, PLY (face texcoord lists, every encoding), OM.
    LoadedMesh seams = read_obj(data_file("good/seams.obj"));
    const auto corners = to_soup(seams.mesh).corner_texcoords;
    REQUIRE(corners.size() == 6);
    for (const char* name : {"s.obj", "s.ply", "s.om"}) {
        for (int variant = 0; variant < 3; ++variant) {
            if (variant > 0 && std::string(name) != "s.ply") continue;
            INFO(name << " variant " << variant);
            WriteOptions o;
            o.ascii = variant == 1;
            o.big_endian = variant == 2;
            write_mesh(seams.mesh, dir.path(name), o);
            LoadedMesh back = read_mesh(dir.path(name));
            REQUIRE_VALID(back.mesh);
            REQUIRE(back.mesh.has_halfedge_property("h:texcoord"));
            const auto back_corners = to_soup(back.mesh).corner_texcoords;
            REQUIRE(back_corners.size() == corners.size());
            for (std::size_t i = 0; i < corners.size(); ++i)
                REQUIRE((corners[i] - back_corners[i]).norm() < 1e-6);
        }
    }
}

// ---- byte-order marks ----------------------------------------------------------------------

namespace {

const std::string kUtf8Bom = "\xEF\xBB\xBF";

/// `text` as UTF-16 with a byte-order mark (ASCII only).
std::string utf16(const std::string& text, bool little_endian) {
    std::string out = little_endian ? std::string("\xFF\xFE") : std::string("\xFE\xFF");
    for (char c : text) {
        if (little_endian) {
            out += c;
            out += '\0';
        } else {
            out += '\0';
            out += c;
        }
    }
    return out;
}

std::string file_text(const std::string& path) {
    return read_file_bytes(path);
}

}  // namespace

TEST_CASE("text formats skip a UTF-8 byte-order mark and keep every vertex", "[io][bom]") {
    // Every text format, with and without the mark: the same mesh, the first vertex kept and
    // the indices unshifted (an OBJ used to lose its first vertex).
    const HalfedgeMesh source = attributed_sphere();
    struct Format {
        const char* name;
        bool ascii;
    };
    for (const Format& f : {Format{"m.obj", false}, Format{"m.off", false}, Format{"m.ply", true},
                            Format{"m.stl", true}}) {
        INFO(f.name);
        WriteOptions options;
        options.ascii = f.ascii;
        const std::string text = write_mesh_bytes(source, f.name, options);
        const LoadedMesh plain = [&] {
            const std::string ext = file_extension(f.name);
            if (ext == "obj") return read_obj_bytes(text, f.name);
            if (ext == "off") return read_off_bytes(text, f.name);
            if (ext == "ply") return read_ply_bytes(text, f.name);
            return read_stl_bytes(text, f.name);
        }();
        TempDir dir;
        const std::string path = dir.path(f.name);
        {
            std::ofstream out(path, std::ios::binary);
            out << kUtf8Bom << text;
        }
        const LoadedMesh with_bom = read_mesh(path);
        REQUIRE_VALID(with_bom.mesh);
        require_same_mesh(plain.mesh, with_bom.mesh);
        CHECK(with_bom.report.lines() == plain.report.lines());
    }
    // The OBJ of the issue: three vertices, one face, a mark in front.
    const LoadedMesh obj =
        read_obj_bytes(kUtf8Bom + "v 1 2 3\nv 4 5 6\nv 7 8 10\nf 1 2 3\n", "bom.obj");
    REQUIRE(obj.mesh.n_vertices() == 3);
    CHECK(obj.mesh.position(Vertex(0)) == Point(1, 2, 3));
    CHECK(obj.mesh.n_faces() == 1);
    // A binary PLY may carry the mark before its header, too.
    const std::string binary = write_mesh_bytes(source, "b.ply");
    require_same_mesh(read_ply_bytes(kUtf8Bom + binary, "b.ply").mesh,
                      read_ply_bytes(binary, "b.ply").mesh);
    // A binary STL is recognised by its size first: its 80-byte header may hold anything,
    // the mark included.
    std::string stl = write_mesh_bytes(source, "b.stl");
    stl.replace(0, 3, kUtf8Bom);
    CHECK(read_stl_bytes(stl, "b.stl").mesh.n_faces() == source.n_faces());
}

TEST_CASE("a material library with a byte-order mark gives its texture", "[io][bom][obj]") {
    TempDir dir;
    {
        std::ofstream mtl(dir.path("m.mtl"), std::ios::binary);
        mtl << kUtf8Bom << "newmtl skin\nmap_Kd skin.png\n";
        std::ofstream obj(dir.path("m.obj"), std::ios::binary);
        obj << kUtf8Bom << "mtllib m.mtl\nusemtl skin\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    }
    const LoadedMesh l = read_mesh(dir.path("m.obj"));
    CHECK(l.texture_path == dir.path("skin.png"));
}

TEST_CASE("text formats refuse UTF-16 and UTF-32 with a clear message", "[io][bom]") {
    const std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    const std::string off = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    const std::string ply =
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
        "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
        "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    const std::string stl =
        "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
        "endloop\nendfacet\nendsolid s\n";
    TempDir dir;
    for (const bool little : {true, false}) {
        for (const auto& [name, text] : {std::pair<std::string, std::string>{"m.obj", obj},
                                         {"m.off", off},
                                         {"m.ply", ply},
                                         {"m.stl", stl}}) {
            INFO(name << (little ? " UTF-16LE" : " UTF-16BE"));
            const std::string path = dir.path(name);
            {
                std::ofstream out(path, std::ios::binary);
                out << utf16(text, little);
            }
            try {
                read_mesh(path);
                FAIL("no error");
            } catch (const IoError& e) {
                CHECK(e.file() == path);
                CHECK(e.line() == 1);
                CHECK(e.reason() == std::string("the file is UTF-16 ") +
                                        (little ? "little-endian (byte-order mark FF FE)"
                                                : "big-endian (byte-order mark FE FF)") +
                                        " text, which is not supported; save it as UTF-8 or ASCII");
            }
        }
    }
    CHECK_THROWS_WITH(read_obj_bytes(std::string("\xFF\xFE\0\0", 4) + "v", "u32.obj"),
                      Contains("UTF-32 little-endian"));
}

TEST_CASE("text images skip a UTF-8 byte-order mark and refuse UTF-16", "[io][bom][image]") {
    for (const char* name :
         {"bits_4x3.xbm", "rgba_4x3.xpm", "gray_p2.pgm", "rgb_p3.ppm", "bits_p1.pbm"}) {
        INFO(name);
        const std::string text = file_text(data_file(std::string("images/") + name));
        const Image plain = read_image_bytes(text, name);
        const Image with_bom = read_image_bytes(kUtf8Bom + text, name);
        CHECK(with_bom.width == plain.width);
        CHECK(with_bom.height == plain.height);
        CHECK(with_bom.rgba == plain.rgba);
        CHECK_THROWS_WITH(read_image_bytes(utf16(text, true), name), Contains("UTF-16"));
    }
}
