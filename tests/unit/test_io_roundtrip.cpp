// Property test of the writers and readers: every fixture (the built-in models, attributed
// meshes, the test data files, meshes at the ends of double's range), written in every
// format and encoding and read back, keeps its counts, its positions within the format's
// precision and the attributes the format carries. A writer may refuse only what its format
// cannot hold (STL: a mesh without faces, float32 overflow), and never writes a file its
// reader refuses.
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "core/algorithms/generators.h"
#include "core/errors.h"
#include "core/geometry.h"
#include "core/io/mesh_io.h"
#include "core/mesh_builder.h"
#include "test_helpers.h"

using namespace trilab;
using namespace trilab::test;

namespace {

struct Fixture {
    std::string name;
    HalfedgeMesh mesh;
};

HalfedgeMesh scaled(HalfedgeMesh m, double s) {
    for (Point& p : m.positions()) p *= s;
    return m;
}

/// A sphere whose texture coordinates have seams: per-corner ("h:texcoord") only.
HalfedgeMesh seamed_sphere() {
    HalfedgeMesh m = make_icosphere(2);
    auto uv = m.halfedge_property<TexCoord>("h:texcoord", TexCoord::Zero());
    for (Face f : m.faces()) {
        Halfedge h = m.halfedge(f);
        for (int k = 0; k < 3; ++k, h = m.next(h)) {
            const Point& p = m.position(m.to_vertex(h));
            uv[h] = TexCoord(0.5 + 0.5 * p.x() + 0.01 * k, 0.5 + 0.25 * p.y() + 0.001 * f.idx());
        }
    }
    return m;
}

std::vector<Fixture> fixtures() {
    std::vector<Fixture> out;
    for (const std::string& name : generator_names()) out.push_back({name, generate(name)});
    out.push_back({"attributed sphere", attributed_sphere()});
    out.push_back({"seamed sphere", seamed_sphere()});
    out.push_back({"sphere at 1e300", scaled(attributed_sphere(), 1e300)});
    out.push_back({"sphere at 1e-35", scaled(attributed_sphere(), 1e-35)});
    out.push_back({"sphere at 1e30 and 1e-30 offsets", [] {
                       HalfedgeMesh m = attributed_sphere();
                       for (Point& p : m.positions()) p = p * 1e30 + Point(1e-30, 0, 0);
                       return m;
                   }()});
    for (const auto& entry : std::filesystem::directory_iterator(data_file("good"))) {
        const std::string path = entry.path().string();
        const std::string ext = file_extension(path);
        if (ext != "obj" && ext != "off") continue;
        out.push_back({entry.path().filename().string(), read_mesh(path).mesh});
    }
    return out;
}

struct Format {
    const char* name;  // the file name: its extension chooses the format
    bool ascii, big_endian;
    bool exact;    // positions bit for bit (doubles), else float32 where it suffices
    bool indexed;  // vertices kept in order (not STL, which merges by position)
    bool normals, colors, texcoords, corner_texcoords;
    double color_step;  // colour quantisation (0: exact)
    bool float_texcoords;
};

const Format kFormats[] = {
    {"m.obj", false, false, true, true, true, false, true, true, 0, false},
    {"m.off", false, false, true, true, true, true, true, false, 0, false},
    {"m.ply", false, false, false, true, true, true, true, true, 1.0 / 255, true},
    {"b.ply", false, true, false, true, true, true, true, true, 1.0 / 255, true},
    {"a.ply", true, false, false, true, true, true, true, true, 1.0 / 255, true},
    {"m.stl", false, false, false, false, false, false, false, false, 0, false},
    {"a.stl", true, false, true, false, false, false, false, false, 0, false},
    {"m.om", false, false, true, true, true, true, true, true, 1.0 / 255, true},
};

/// |a - b| within float32's rounding of a (or exact).
bool close(double a, double b, bool exact) {
    if (exact) return a == b;
    return std::abs(a - b) <= std::ldexp(std::abs(a), -24) + 0x1p-149;
}

template <class V>
bool close(const V& a, const V& b, bool exact) {
    for (Eigen::Index k = 0; k < a.size(); ++k)
        if (!close(double(a[k]), double(b[k]), exact)) return false;
    return true;
}

/// Per face corner, in face order: the corner texture coordinate, else the vertex one.
std::vector<TexCoord> corner_uvs(const PolygonSoup& s) {
    std::vector<TexCoord> out;
    if (!s.corner_texcoords.empty()) return s.corner_texcoords;
    if (s.texcoords.empty()) return out;
    for (Index v : s.corners) out.push_back(s.texcoords[v]);
    return out;
}

std::string check_round_trip(const HalfedgeMesh& mesh, const Format& f) {
    WriteOptions options;
    options.ascii = f.ascii;
    options.big_endian = f.big_endian;
    std::string bytes;
    try {
        bytes = write_mesh_bytes(mesh, f.name, options);
    } catch (const IoError& e) {
        return e.reason();  // the caller decides whether the refusal is legitimate
    }
    LoadedMesh back;
    const std::string ext = file_extension(f.name);
    if (ext == "obj") back = read_obj_bytes(bytes, f.name);
    if (ext == "off") back = read_off_bytes(bytes, f.name);
    if (ext == "ply") back = read_ply_bytes(bytes, f.name);
    if (ext == "stl") back = read_stl_bytes(bytes, f.name);
    if (ext == "om") back = read_om_bytes(bytes, f.name);
    REQUIRE_VALID(back.mesh);
    const PolygonSoup a = to_soup(mesh), b = to_soup(back.mesh);
    REQUIRE(b.n_faces() == a.n_faces());
    // Positions: by vertex where vertices are kept, else by face corner (up to a rotation).
    double max_abs = 0;
    for (const Point& p : a.positions) max_abs = std::max(max_abs, p.cwiseAbs().maxCoeff());
    const bool float_positions = !f.exact && max_abs <= 3.4e38 && max_abs >= 2e-31;
    if (f.indexed) {
        REQUIRE(b.positions.size() == a.positions.size());
        REQUIRE(b.corners == a.corners);
        for (std::size_t i = 0; i < a.positions.size(); ++i) {
            INFO("vertex " << i << ": " << a.positions[i].transpose() << " read back as "
                           << b.positions[i].transpose());
            REQUIRE(close(a.positions[i], b.positions[i], !float_positions));
        }
    } else {
        for (std::size_t face = 0; face < a.n_faces(); ++face) {
            bool found = false;
            for (int r = 0; r < 3 && !found; ++r) {
                found = true;
                for (int k = 0; k < 3; ++k)
                    found = found &&
                            close(a.positions[a.corners[3 * face + k]],
                                  b.positions[b.corners[3 * face + (k + r) % 3]], !float_positions);
            }
            INFO("face " << face);
            REQUIRE(found);
        }
    }
    // Attributes the format carries: present again, within its precision.
    if (f.normals && !a.normals.empty()) {
        REQUIRE(b.normals.size() == a.normals.size());
        const bool exact = ext != "ply";  // PLY normals are float32 (double if needed)
        for (std::size_t i = 0; i < a.normals.size(); ++i)
            REQUIRE(close(a.normals[i], b.normals[i], exact));
    }
    if (f.colors && !a.colors.empty()) {
        REQUIRE(b.colors.size() == a.colors.size());
        for (std::size_t i = 0; i < a.colors.size(); ++i)
            for (int k = 0; k < 3; ++k)
                REQUIRE(std::abs(a.colors[i][k] - b.colors[i][k]) <= f.color_step / 2 + 1e-6);
    }
    const bool has_corner_uv = !a.corner_texcoords.empty();
    if ((f.texcoords && !a.texcoords.empty()) || (f.corner_texcoords && has_corner_uv)) {
        const std::vector<TexCoord> ua = corner_uvs(a), ub = corner_uvs(b);
        REQUIRE(ub.size() == ua.size());
        for (std::size_t c = 0; c < ua.size(); ++c)
            REQUIRE(close(ua[c], ub[c], !f.float_texcoords));
    }
    return "";
}

}  // namespace

TEST_CASE("every fixture survives every format: counts, positions, attributes", "[io][roundtrip]") {
    const std::vector<Fixture> all = fixtures();
    REQUIRE(all.size() >= 20);
    std::size_t round_trips = 0;
    for (const Fixture& fx : all) {
        REQUIRE_VALID(fx.mesh);
        for (const Format& f : kFormats) {
            INFO(fx.name << " as " << f.name << (f.ascii ? " (ascii)" : "")
                         << (f.big_endian ? " (big endian)" : ""));
            const std::string refusal = check_round_trip(fx.mesh, f);
            if (refusal.empty()) {
                ++round_trips;
                continue;
            }
            // The only legitimate refusals: what STL cannot hold.
            INFO("refused: " << refusal);
            const bool stl = file_extension(f.name) == "stl";
            const bool no_faces = fx.mesh.n_faces() == 0;
            const bool float_overflow = !f.ascii && fx.name.find("1e300") != std::string::npos;
            const bool float_underflow = !f.ascii && fx.name.find("1e-35") != std::string::npos;
            CHECK(stl);
            CHECK((no_faces || float_overflow || float_underflow));
        }
    }
    CHECK(round_trips >= all.size() * (std::size(kFormats) - 1));
}
