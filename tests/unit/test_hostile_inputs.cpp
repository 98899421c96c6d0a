// Hostile inputs: meshes with isolated vertices, zero-area faces, duplicated faces,
// non-manifold edges and vertices, several components, huge (1e30) and tiny (1e-30)
// coordinates, a single triangle, and an empty mesh. Built through the PolygonSoup builder
// and round-tripped through every file format; then every registered operation runs on each
// with several parameter sets. Each either works (every step valid, no NaN or infinity) or
// refuses with a trilab::Error carrying a message; nothing else is acceptable.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <future>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "app/ops/operation.h"
#include "app/ops/region_spec.h"
#include "core/algorithms/generators.h"
#include "core/algorithms/mesh_distance.h"
#include "core/errors.h"
#include "core/geometry.h"
#include "core/io/file_util.h"
#include "core/io/image_io.h"
#include "core/io/mesh_io.h"
#include "core/mesh_builder.h"
#include "core/system_memory.h"
#include "test_helpers.h"

using namespace trilab;
using namespace trilab::test;

namespace {

struct Hostile {
    std::string name;
    PolygonSoup soup;
    /// Its coordinates make double overflow on purpose (products of 1e300, quotients by the
    /// areas of 1e-300): the code must find the non-finite results it computes, so it runs
    /// without floating-point traps.
    bool overflows = false;
};

PolygonSoup soup_of(const std::vector<Point>& positions,
                    const std::vector<std::vector<Index>>& faces) {
    PolygonSoup s;
    s.positions = positions;
    for (const auto& f : faces) s.add_face(f);
    return s;
}

const std::vector<Point> kTet = {Point(0, 0, 0), Point(1, 0, 0), Point(0, 1, 0), Point(0, 0, 1)};
const std::vector<std::vector<Index>> kTetFaces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};

std::vector<Point> scaled(const std::vector<Point>& p, double s) {
    std::vector<Point> out;
    for (const Point& q : p) out.push_back(q * s);
    return out;
}

std::vector<Hostile> hostile_meshes() {
    std::vector<Hostile> h;
    {
        std::vector<Point> p = kTet;
        p.push_back(Point(5, 5, 5));
        p.push_back(Point(-5, 0, 2));
        h.push_back({"isolated vertices", soup_of(p, kTetFaces)});
    }
    h.push_back(
        {"zero-area faces", soup_of({Point(0, 0, 0), Point(1, 0, 0), Point(2, 0, 0), Point(1, 1, 0),
                                     Point(1, 1, 0), Point(1, 1, 0)},
                                    {{0, 1, 3}, {1, 2, 3}, {0, 2, 1}, {3, 4, 5}, {0, 1, 4}})});
    h.push_back({"duplicated faces", soup_of(kTet, {{0, 1, 2}, {0, 1, 2}, {0, 2, 1}, {1, 2, 3}})});
    h.push_back({"non-manifold edge", soup_of({Point(0, 0, 0), Point(1, 0, 0), Point(0, 1, 0),
                                               Point(0, -1, 0), Point(0, 0, 1)},
                                              {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}})});
    h.push_back({"non-manifold vertex", soup_of({Point(0, 0, 0), Point(1, 0, 0), Point(1, 1, 0),
                                                 Point(-1, 0, 0), Point(-1, -1, 0)},
                                                {{0, 1, 2}, {0, 3, 4}})});
    {
        std::vector<Point> p = kTet;
        for (const Point& q : kTet) p.push_back(q + Point(3, 0, 0));
        std::vector<std::vector<Index>> f = kTetFaces;
        for (auto face : kTetFaces) {
            for (Index& i : face) i += 4;
            f.push_back(face);
        }
        p.push_back(Point(9, 9, 9));
        f.push_back({8, 8, 8});  // a degenerate face on its own
        h.push_back({"several components", soup_of(p, f)});
    }
    h.push_back({"huge coordinates (1e30)", soup_of(scaled(kTet, 1e30), kTetFaces)});
    h.push_back({"tiny coordinates (1e-30)", soup_of(scaled(kTet, 1e-30), kTetFaces)});
    {
        std::vector<Point> p = scaled(kTet, 1e30);
        for (const Point& q : kTet) p.push_back(q * 1e-30 + Point(1, 1, 1));
        std::vector<std::vector<Index>> f = kTetFaces;
        for (auto face : kTetFaces) {
            for (Index& i : face) i += 4;
            f.push_back(face);
        }
        h.push_back({"huge and tiny together", soup_of(p, f)});
    }
    h.push_back({"coordinates near the largest double (1e300)",
                 soup_of(scaled(kTet, 1e300), kTetFaces), true});
    h.push_back({"coordinates near the largest double (1e308)",
                 soup_of(scaled(kTet, 1e308), kTetFaces), true});
    // Areas underflow to subnormals or zero, and what divides by them overflows.
    h.push_back({"coordinates near the smallest double (1e-300)",
                 soup_of(scaled(kTet, 1e-300), kTetFaces), true});
    h.push_back({"single triangle",
                 soup_of({Point(0, 0, 0), Point(1, 0, 0), Point(0, 1, 0)}, {{0, 1, 2}})});
    h.push_back({"isolated vertices only", soup_of({Point(0, 0, 0), Point(1, 2, 3)}, {})});
    h.push_back({"empty mesh", PolygonSoup{}});
    return h;
}

bool all_finite(const HalfedgeMesh& mesh) {
    for (Vertex v : mesh.vertices()) {
        const Point& p = mesh.position(v);
        if (!std::isfinite(p.x()) || !std::isfinite(p.y()) || !std::isfinite(p.z())) return false;
    }
    return true;
}

/// Parameter sets per operation; an operation not listed runs with its defaults.
std::vector<std::string> parameter_sets(const std::string& op) {
    static const std::map<std::string, std::vector<std::string>> sets = {
        {"noise",
         {"", "--amount 1000 --seed 3", "--distribution gaussian --sigma 10 --direction random"}},
        {"subdivide",
         {"--scheme loop", "--scheme sqrt3 --iterations 2", "--scheme butterfly",
          "--scheme modified-butterfly"}},
        {"smooth",
         {"", "--operator improved-umbrella --integration implicit",
          "--operator curvature-flow --iterations 3", "--operator second-order --step 0.1",
          "--operator taubin --preserve-volume",
          "--operator curvature-flow --integration implicit --preserve-volume"}},
        {"remove-components", {"--min-faces 10", "--min-diameter 1", "--min-faces 0"}},
        {"features", {"", "--angle 1 --min-chain 3 --boundary", "--angle 180"}},
        {"fill-holes", {"", "--fairing c2", "--fairing none --max-edges 3", "--max-diameter 0.5"}},

        {"denoise",
         {"", "--method bilateral", "--method guided --sigma-r 0.05 --vertex-iterations 100",
          "--sigma-s 100 --sigma-r 100"}},

        {"remesh",
         {"", "--relative 0.5 --iterations 2", "--relative 3", "--length 1e-12",
          "--adaptive 0.1 --iterations 2"}},
    };
    const auto it = sets.find(op);
    return it == sets.end() ? std::vector<std::string>{""} : it->second;
}

/// Runs every registered operation with every parameter set on `mesh`.
void run_every_operation(const HalfedgeMesh& mesh) {
    NullProgress progress;
    for (const std::string& name : operation_names()) {
        for (const std::string& params : parameter_sets(name)) {
            const std::string text = params.empty() ? name : name + " " + params;
            INFO("operation: " << text);
            OperationResult result;
            try {
                result = run_operation(parse_operation(text), mesh, progress);
            } catch (const Error& e) {
                INFO("refused: " << e.what());
                CHECK_FALSE(std::string(e.what()).empty());
                continue;
            }
            REQUIRE_FALSE(result.steps.empty());
            for (std::size_t i = 0; i < result.steps.size(); ++i) {
                INFO("step " << i);
                REQUIRE_VALID(result.steps[i].mesh);
                CHECK(all_finite(result.steps[i].mesh));
            }
        }
    }
}

}  // namespace

TEST_CASE("hostile meshes from the soup builder: every operation works or refuses cleanly",
          "[hostile]") {
    for (const Hostile& h : hostile_meshes()) {
        INFO("mesh: " << h.name);
        std::optional<FpTrapsOff> traps_off;
        if (h.overflows) traps_off.emplace();
        LoadReport report;
        HalfedgeMesh mesh;
        try {
            mesh = build_mesh(h.soup, report);
        } catch (const Error& e) {
            FAIL("the builder refused " << h.name << ": " << e.what());
        }
        REQUIRE_VALID(mesh);
        run_every_operation(mesh);
    }
}

TEST_CASE("hostile meshes survive every file format or are refused with a message",
          "[hostile][io]") {
    TempDir dir;
    struct Format {
        const char* file;
        bool ascii;
    };
    const Format formats[] = {{"m.obj", false}, {"m.off", false}, {"m.ply", false}, {"a.ply", true},
                              {"m.stl", false}, {"a.stl", true},  {"m.om", false}};
    for (const Hostile& h : hostile_meshes()) {
        std::optional<FpTrapsOff> traps_off;
        if (h.overflows) traps_off.emplace();
        LoadReport report;
        const HalfedgeMesh mesh = build_mesh(h.soup, report);
        for (const Format& f : formats) {
            INFO("mesh: " << h.name << ", file: " << f.file);
            WriteOptions options;
            options.ascii = f.ascii;
            const std::string path = dir.path(f.file);
            try {
                write_mesh(mesh, path, options);
            } catch (const IoError& e) {
                INFO("write refused: " << e.what());
                CHECK_FALSE(e.reason().empty());
                continue;
            }
            LoadedMesh loaded;
            try {
                loaded = read_mesh(path);
            } catch (const IoError& e) {
                INFO("read refused: " << e.what());
                CHECK(e.file() == path);
                CHECK_FALSE(e.reason().empty());
                continue;
            }
            REQUIRE_VALID(loaded.mesh);
            CHECK(all_finite(loaded.mesh));
            // STL keeps only faces; the others keep every vertex, isolated ones included.
            if (file_extension(path) != "stl") CHECK(loaded.mesh.n_vertices() == mesh.n_vertices());
            run_every_operation(loaded.mesh);
        }
    }
}

TEST_CASE("an OBJ whose material library is a device, a FIFO or a folder loads without hanging",
          "[hostile][io]") {
    TempDir dir;
    REQUIRE(mkfifo(dir.path("fifo.mtl").c_str(), 0600) == 0);  // opening it would block
    std::filesystem::create_directory(dir.path("folder.mtl"));
    for (const std::string lib : {"/dev/zero", "fifo.mtl", "folder.mtl", "missing.mtl"}) {
        INFO("mtllib " << lib);
        const std::string path = dir.path("m.obj");
        {
            std::ofstream out(path);
            out << "mtllib " << lib << "\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
        }
        const LoadedMesh loaded = read_mesh(path);
        REQUIRE_VALID(loaded.mesh);
        CHECK(loaded.mesh.n_faces() == 1);
        CHECK(loaded.texture_path.empty());
        bool noted = false;
        for (const std::string& note : loaded.report.notes)
            noted = noted || note.find("material library " + lib) != std::string::npos;
        CHECK(noted);
    }
}

// ---- opening: only regular files, within a size limit --------------------------------------

namespace {

void write_file(const std::string& path, const std::string& bytes) {
    std::ofstream out(path, std::ios::binary);
    out.write(bytes.data(), std::streamsize(bytes.size()));
}

/// The IoError of `read` (which must throw one naming `path`).
template <class F>
IoError read_failure(const std::string& path, F&& read) {
    try {
        read();
    } catch (const IoError& e) {
        CHECK(e.file() == path);
        return e;
    }
    FAIL("no IoError for " << path);
    return IoError(path, 0, "");
}

}  // namespace

TEST_CASE("only regular files are opened: FIFOs, devices, folders and sockets are named",
          "[hostile][io][open]") {
    TempDir dir;
    // A FIFO without a writer: opening it for reading would block forever.
    REQUIRE(mkfifo(dir.path("fifo.obj").c_str(), 0600) == 0);
    REQUIRE(mkfifo(dir.path("fifo.png").c_str(), 0600) == 0);
    std::filesystem::create_directory(dir.path("folder.ply"));
    std::filesystem::create_symlink("/dev/zero", dir.path("zero.stl"));
    std::filesystem::create_symlink("/dev/urandom", dir.path("random.om"));
    struct Case {
        std::string path, what;
    };
    for (const Case& c : {Case{dir.path("fifo.obj"), "a FIFO (named pipe)"},
                          Case{dir.path("folder.ply"), "a directory"},
                          Case{dir.path("zero.stl"), "a character device"},
                          Case{dir.path("random.om"), "a character device"},
                          Case{"/dev/zero", "a character device"}}) {
        INFO(c.path);
        const IoError e = read_failure(c.path, [&] { read_mesh(c.path); });
        CHECK(e.reason() ==
              "not a regular file: it is " + c.what + " (only regular files are read)");
    }
    // Texture images take the same path.
    const IoError e = read_failure(dir.path("fifo.png"), [&] { read_image(dir.path("fifo.png")); });
    CHECK(e.reason().find("a FIFO") != std::string::npos);
    // A missing file says so.
    CHECK(read_failure(dir.path("missing.obj"), [&] {
              read_mesh(dir.path("missing.obj"));
          }).reason() == "cannot open: No such file or directory");
}

TEST_CASE("reading stops at the size limit, naming the file's size and the limit",
          "[hostile][io][open]") {
    TempDir dir;
    const std::uint64_t limit = max_readable_file_bytes();
    REQUIRE(limit > (std::uint64_t(1) << 20));
    REQUIRE(limit <= available_memory_bytes());

    // A 1 TiB sparse file is refused before a byte is read.
    const std::string big = dir.path("big.obj");
    write_file(big, "v 0 0 0\n");
    std::filesystem::resize_file(big, std::uint64_t(1) << 40);
    IoError e = read_failure(big, [&] { read_mesh(big); });
    CHECK(e.reason().find("1099511627776 bytes (1.0 TiB)") != std::string::npos);
    CHECK(e.reason().find("more than the limit of " + std::to_string(limit / 1024 / 1024)) ==
          std::string::npos);  // the limit is printed in bytes first
    CHECK(e.reason().find("half the memory this process may still allocate") != std::string::npos);

    // An explicit limit.
    const std::string small = dir.path("small.txt");
    write_file(small, std::string(200, 'x'));
    CHECK(read_file_bytes(small, 200).size() == 200);
    e = read_failure(small, [&] { read_file_bytes(small, 100); });
    CHECK(e.reason() == "the file is 200 bytes, more than the limit of 100 bytes");

    // Files whose size is unknown in advance (/proc) are read to their end, within the limit.
    const std::string status = read_file_bytes("/proc/self/status");
    CHECK(status.find("Name:") != std::string::npos);
    e = read_failure("/proc/self/status", [&] { read_file_bytes("/proc/self/status", 10); });
    CHECK_THAT(e.reason(), Catch::Matchers::StartsWith("the file is at least ") &&
                               Catch::Matchers::EndsWith(", more than the limit of 10 bytes"));
}

// ---- non-finite values: every reader refuses them in every attribute -----------------------

namespace {

std::string binary_ply(const std::string& vertex_properties, const std::string& face_properties,
                       const std::vector<std::vector<double>>& vertices, bool double_values,
                       const std::vector<std::vector<double>>& face_uv = {}) {
    std::string h = "ply\nformat binary_little_endian 1.0\nelement vertex " +
                    std::to_string(vertices.size()) + "\n" + vertex_properties +
                    "element face 1\nproperty list uchar int vertex_indices\n" + face_properties +
                    "end_header\n";
    auto put = [&](auto v) { h.append(reinterpret_cast<const char*>(&v), sizeof(v)); };
    for (const auto& row : vertices)
        for (double v : row) double_values ? put(v) : put(float(v));
    put(std::uint8_t(3));
    for (std::int32_t i : {0, 1, 2}) put(i);
    for (const auto& uv : face_uv) {
        put(std::uint8_t(uv.size()));
        for (double v : uv) put(float(v));
    }
    return h;
}

}  // namespace

TEST_CASE("every reader refuses NaN and infinity in every attribute, naming where",
          "[hostile][io][nonfinite]") {
    const FpTrapsOff traps_off;  // NaN and infinity on purpose
    TempDir dir;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    struct TextCase {
        std::string file, text;
        std::size_t line;
        std::string attribute;
    };
    // Text formats: the line and the attribute.
    const std::vector<TextCase> text_cases = {
        {"p.obj", "v 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n", 2, "(position)"},
        {"n.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 inf\nf 1//1 2//1 3//1\n", 4, "(normal)"},
        {"t.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt -inf 0\nf 1/1 2/1 3/1\n", 4,
         "(texture coordinate)"},
        {"n.off", "NOFF\n3 1 0\n0 0 0 0 0 1\n1 0 0 nan 0 1\n0 1 0 0 0 1\n3 0 1 2\n", 4,
         "(normal x)"},
        {"c.off", "COFF\n3 1 0\n0 0 0 1 0 0 1\n1 0 0 nan 0 0 1\n0 1 0 1 0 0 1\n3 0 1 2\n", 4,
         "(colour)"},
        {"t.off", "STOFF\n3 1 0\n0 0 0 0 0\n1 0 0 0 inf\n0 1 0 0 0\n3 0 1 2\n", 4,
         "(texture coordinate)"},
        {"n.ply",
         "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
         "property float z\nproperty float nx\nproperty float ny\nproperty float nz\n"
         "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
         "0 0 0 0 0 1\n1 0 0 0 nan 1\n0 1 0 0 0 1\n3 0 1 2\n",
         14, "(property 'ny')"},
        {"c.ply",
         "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
         "property float z\nproperty float red\nproperty float green\nproperty float blue\n"
         "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
         "0 0 0 1 1 1\n1 0 0 1 1 1\n0 1 0 inf 1 1\n3 0 1 2\n",
         15, "(property 'red')"},
        {"t.ply",
         "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
         "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
         "property list uchar float texcoord\nend_header\n"
         "0 0 0\n1 0 0\n0 1 0\n3 0 1 2 6 0 0 1 0 nan 1\n",
         14, "(a texture coordinate)"},
        {"p.stl",
         "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 inf\nvertex 0 1 0\n"
         "endloop\nendfacet\nendsolid s\n",
         5, "(a vertex coordinate)"},
    };
    for (const TextCase& c : text_cases) {
        INFO(c.file);
        const std::string path = dir.path(c.file);
        write_file(path, c.text);
        const IoError e = read_failure(path, [&] { read_mesh(path); });
        CHECK(e.line() == c.line);
        CHECK(e.reason().find("is not a finite number " + c.attribute) != std::string::npos);
    }

    // Binary formats: the element and the attribute, in the same words everywhere.
    const std::string xyz = "property float x\nproperty float y\nproperty float z\n";
    const std::string dxyz = "property double x\nproperty double y\nproperty double z\n";
    struct BinaryCase {
        std::string file, bytes, reason;
    };
    std::vector<BinaryCase> binary_cases = {
        {"p.ply", binary_ply(dxyz, "", {{0, 0, 0}, {1, inf, 0}, {0, 1, 0}}, true),
         "vertex 1: non-finite position (1 inf 0)"},
        {"n.ply",
         binary_ply(xyz + "property float nx\nproperty float ny\nproperty float nz\n", "",
                    {{0, 0, 0, 0, 0, 1}, {1, 0, 0, 0, 0, 1}, {0, 1, 0, nan, 0, 1}}, false),
         "vertex 2: non-finite normal (nan 0 1)"},
        {"c.ply",
         binary_ply(xyz + "property float red\nproperty float green\nproperty float blue\n", "",
                    {{0, 0, 0, 1, 1, 1}, {1, 0, 0, 1, nan, 1}, {0, 1, 0, 1, 1, 1}}, false),
         "vertex 1: non-finite colour (1 nan 1)"},
        {"t.ply",
         binary_ply(xyz + "property float u\nproperty float v\n", "",
                    {{0, 0, 0, 0, 0}, {1, 0, 0, -inf, 0}, {0, 1, 0, 0, 1}}, false),
         "vertex 1: non-finite texture coordinate (-inf 0)"},
        {"ct.ply",
         binary_ply(xyz, "property list uchar float texcoord\n", {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}},
                    false, {{0, 0, 1, nan, 0, 1}}),
         "face corner 1: non-finite texture coordinate (1 nan)"},
    };
    {
        // Binary STL: 80-byte header, count, one facet whose second corner has a NaN.
        std::string stl(80, ' ');
        auto put = [&](auto v) { stl.append(reinterpret_cast<const char*>(&v), sizeof(v)); };
        put(std::uint32_t(1));
        for (float v : {0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, float(nan), 0.f, 0.f, 1.f, 0.f}) put(v);
        put(std::uint16_t(0));
        binary_cases.push_back(
            {"p.stl", stl, "triangle 0, corner 1: non-finite position (NaN or infinity)"});
    }
    {
        // .om: a tetrahedron with normals and texture coordinates, then one value broken.
        HalfedgeMesh tet = make_tetrahedron();
        compute_vertex_normals(tet);
        auto uv = tet.vertex_property<TexCoord>("v:texcoord");
        for (Vertex v : tet.vertices()) uv[v] = TexCoord(0.25 * v.idx(), 0.5);
        const std::string om = write_mesh_bytes(tet, "t.om");
        const std::size_t nv = tet.n_vertices();
        const std::size_t positions = 16 + 2, normals = positions + 24 * nv + 2,
                          texcoords = normals + 24 * nv + 2;
        auto broken = [&](std::size_t offset, auto value) {
            std::string b = om;
            std::memcpy(&b[offset], &value, sizeof(value));
            return b;
        };
        binary_cases.push_back(
            {"p.om", broken(positions + 24 * 2 + 8, inf), "vertex 2: non-finite position"});
        binary_cases.push_back(
            {"n.om", broken(normals + 24 * 1, nan), "vertex 1: non-finite normal (nan"});
        binary_cases.push_back({"t.om", broken(texcoords + 8 * 3 + 4, float(inf)),
                                "vertex 3: non-finite texture coordinate (0.75 inf)"});
    }
    for (const BinaryCase& c : binary_cases) {
        INFO(c.file);
        const std::string path = dir.path(c.file);
        write_file(path, c.bytes);
        const IoError e = read_failure(path, [&] { read_mesh(path); });
        CHECK(e.line() == 0);
        CHECK(e.reason().rfind(c.reason, 0) == 0);
    }
}

TEST_CASE("compare works on finite coordinates near the ends of double's range",
          "[hostile][distance]") {
    // The same two shapes at scale 1 and near the ends of double's range: the distances
    // scale with them (at 1e200 the areas overflow double unless the measurement scales the
    // meshes back). Power-of-two scales change no rounding: the results are the same to the
    // bit; decimal ones round differently, so a sample or two may move.
    HalfedgeMesh a = make_icosphere(2), b = make_icosphere(2);
    for (Point& p : b.positions()) p *= 1.25;
    MeshDistanceOptions options;
    options.samples = 5000;
    const MeshDistance unit = mesh_distance(a, b, options);
    REQUIRE(unit.hausdorff > 0.2);
    for (const double scale : {0x1p660, 0x1p-660, 0x1p1000, 1e200, 1e-200, 1e300}) {
        INFO("scale " << scale);
        HalfedgeMesh sa = a, sb = b;
        for (Point& p : sa.positions()) p *= scale;
        for (Point& p : sb.positions()) p *= scale;
        const MeshDistance d = mesh_distance(sa, sb, options);
        if (std::exp2(std::round(std::log2(scale))) == scale) {
            CHECK(d.samples == unit.samples);
            CHECK(d.hausdorff / scale == unit.hausdorff);
            CHECK(d.rms / scale == unit.rms);
        } else {
            CHECK(std::abs(double(d.samples) - double(unit.samples)) <= 2);
            CHECK(d.hausdorff / scale == Approx(unit.hausdorff).epsilon(1e-3));
            CHECK(d.rms / scale == Approx(unit.rms).epsilon(1e-3));
        }
        CHECK(d.diagonal / scale == Approx(unit.diagonal).epsilon(1e-12));
    }
    // Distances beyond the largest double are refused, not returned as infinity.
    HalfedgeMesh far = a, near = a;
    for (Point& p : far.positions()) p = p * 1e300 + Point(1.5e308, 0, 0);
    for (Point& p : near.positions()) p = p * 1e300 - Point(1.5e308, 0, 0);
    CHECK_THROWS_AS(mesh_distance(far, near, options), InvalidArgument);
}

TEST_CASE("region and selection files are read from regular files only, within a budget",
          "[hostile][io][open][selection]") {
    // Issue 38, item 15: `--region file:/dev/zero` read without end, a FIFO hung for ever.
    TempDir dir;
    const HalfedgeMesh mesh = make_icosahedron();
    REQUIRE(mkfifo(dir.path("fifo").c_str(), 0600) == 0);
    // If a reader opened the FIFO (and blocked), a writer opened after a while ends the read
    // at once, so a regression fails this test instead of hanging it.
    std::promise<void> done;
    std::thread unblock([&, finished = done.get_future()] {
        if (finished.wait_for(std::chrono::seconds(2)) == std::future_status::ready) return;
        const int fd = ::open(dir.path("fifo").c_str(), O_WRONLY | O_NONBLOCK);
        if (fd >= 0) ::close(fd);
    });
    std::filesystem::create_directory(dir.path("folder"));
    struct Case {
        std::string path, what;
    };
    for (const Case& c :
         {Case{"/dev/zero", "a character device"}, Case{dir.path("fifo"), "a FIFO (named pipe)"},
          Case{dir.path("folder"), "a directory"}}) {
        INFO(c.path);
        const auto t0 = std::chrono::steady_clock::now();
        const RegionSpec spec = parse_region_spec("file:" + c.path);
        const IoError e = read_failure(c.path, [&] { make_region(mesh, spec); });
        CHECK(std::chrono::steady_clock::now() - t0 < std::chrono::seconds(1));
        CHECK_THAT(e.reason(), Catch::StartsWith("not a regular file: it is " + c.what) &&
                                   Catch::Contains("--region file:" + c.path));
    }
    done.set_value();
    unblock.join();
    // A regular file past the budget (sparse: nothing is written) is refused before reading,
    // naming its size and the limit.
    const std::uint64_t budget = weight_file_budget(mesh.vertices_size());
    CHECK(budget >= (std::uint64_t(1) << 20));
    CHECK(budget < (std::uint64_t(2) << 20));  // 12 vertices: 1 MiB and a little
    {
        std::ofstream(dir.path("big.txt")) << "1\n";
        std::filesystem::resize_file(dir.path("big.txt"), budget + 1);
    }
    const IoError e = read_failure(dir.path("big.txt"), [&] {
        make_region(mesh, parse_region_spec("file:" + dir.path("big.txt")));
    });
    CHECK_THAT(e.reason(), Catch::Contains(std::to_string(budget + 1)) &&
                               Catch::Contains(std::to_string(budget)));
    // Within the budget the weights read as before; one too many is refused naming the line.
    std::string ones;
    for (std::size_t i = 0; i < mesh.vertices_size(); ++i) ones += "# vertex\n1\n";
    std::ofstream(dir.path("ones.txt")) << ones;
    CHECK(count_selected(make_region(mesh, parse_region_spec("file:" + dir.path("ones.txt")))) ==
          mesh.n_vertices());
    std::ofstream(dir.path("more.txt")) << ones << "0\n";
    CHECK_THROWS_WITH(make_region(mesh, parse_region_spec("file:" + dir.path("more.txt"))),
                      Catch::Contains("more.txt:25: more weights than the mesh's 12 vertices"));
}
