// The table of mesh formats (core/io/mesh_io.cpp): the lists and messages come from it, and
// each format's capabilities say what its writer and reader keep.
#include <string>
#include <vector>

#include "core/algorithms/generators.h"
#include "core/errors.h"
#include "core/io/mesh_io.h"
#include "test_helpers.h"

using namespace trilab;
using namespace trilab::test;

TEST_CASE("the format list, the extensions and the unknown-format message agree", "[io]") {
    const std::vector<MeshFormatInfo>& formats = mesh_formats();
    const std::vector<std::string> extensions = supported_mesh_extensions();
    REQUIRE(formats.size() == extensions.size());
    REQUIRE(extensions == std::vector<std::string>{"obj", "off", "ply", "stl", "om"});
    for (std::size_t i = 0; i < formats.size(); ++i) {
        CHECK(formats[i].extension == extensions[i]);
        CHECK(std::string(formats[i].name).size() > 0);
    }
    const HalfedgeMesh mesh = make_tetrahedron();
    TempDir dir;
    try {
        write_mesh(mesh, dir.path("m.xyz"));
        FAIL("write_mesh accepted .xyz");
    } catch (const IoError& e) {
        CHECK(std::string(e.what()).find("unknown mesh format '.xyz' (supported: .obj, .off, "
                                         ".ply, .stl, .om)") != std::string::npos);
    }
    CHECK_THROWS_AS(read_mesh(dir.path("m.xyz")), IoError);
    CHECK_THROWS_AS(write_mesh_bytes(mesh, "m.XYZ"), IoError);
}

TEST_CASE("each format keeps exactly the vertex attributes its table entry names", "[io]") {
    HalfedgeMesh mesh = make_icosahedron();
    auto normals = mesh.add_vertex_property<Vector3>("v:normal");
    auto colors = mesh.add_vertex_property<Color>("v:color");
    auto uv = mesh.add_vertex_property<TexCoord>("v:texcoord");
    for (Vertex v : mesh.vertices()) {
        normals[v] = mesh.position(v).normalized();
        colors[v] = Color(0.25f, 0.5f, 1.0f);
        uv[v] = TexCoord(0.25, 0.75);
    }
    TempDir dir;
    for (const MeshFormatInfo& format : mesh_formats()) {
        INFO("format " << format.extension);
        const std::string path = dir.path(std::string("m.") + format.extension);
        write_mesh(mesh, path);
        const LoadedMesh back = read_mesh(path);
        REQUIRE_VALID(back.mesh);
        CHECK(back.mesh.has_vertex_property("v:normal") == format.normals);
        CHECK(back.mesh.has_vertex_property("v:color") == format.colors);
        CHECK((back.mesh.has_vertex_property("v:texcoord") ||
               back.mesh.has_halfedge_property("h:texcoord")) == format.texcoords);
        // The ascii choice changes the bytes exactly where the table says it applies.
        WriteOptions ascii;
        ascii.ascii = true;
        const std::string name = std::string("m.") + format.extension;
        CHECK((write_mesh_bytes(mesh, name, ascii) != write_mesh_bytes(mesh, name)) ==
              format.ascii_choice);
        WriteOptions big;
        big.big_endian = true;
        CHECK((write_mesh_bytes(mesh, name, big) != write_mesh_bytes(mesh, name)) ==
              format.big_endian_choice);
    }
}
