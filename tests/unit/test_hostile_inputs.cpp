// Hostile inputs: meshes with isolated vertices, zero-area faces, duplicated faces,
// non-manifold edges and vertices, several components, huge (1e30) and tiny (1e-30)
// coordinates, a single triangle, and an empty mesh. Built through the PolygonSoup builder
// and round-tripped through every file format; then every registered operation runs on each
// with several parameter sets. Each either works (every step valid, no NaN or infinity) or
// refuses with a trilab::Error carrying a message; nothing else is acceptable.
#include <sys/stat.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "app/ops/operation.h"
#include "core/errors.h"
#include "core/io/mesh_io.h"
#include "core/mesh_builder.h"
#include "test_helpers.h"

using namespace trilab;
using namespace trilab::test;

namespace {

struct Hostile {
    std::string name;
    PolygonSoup soup;
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
        {"noise", {"", "--amount 1000 --seed 3"}},
        {"subdivide",
         {"--scheme loop", "--scheme sqrt3 --iterations 2", "--scheme butterfly",
          "--scheme modified-butterfly"}},
        {"smooth",
         {"", "--operator improved-umbrella --integration implicit",
          "--operator curvature-flow --iterations 3", "--operator second-order --step 0.1",
          "--operator taubin --preserve-volume",
          "--operator curvature-flow --integration implicit --preserve-volume"}},
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
