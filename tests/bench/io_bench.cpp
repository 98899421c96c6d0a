// File-format benchmark (not a test): loads and writes the shared Stanford bunny and a
// self-built torus of 1,000,000 faces in every format, printing the median time and
// throughput of each, then the floors with the ratio measured/floor.
//
//   trilab_bench [--runs N] [--faces-only-large] [--check]
//
// --check exits non-zero when a floor is missed. Medians over N runs (default 5).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "core/generators.h"
#include "core/io/mesh_io.h"
#include "core/platform.h"

using namespace trilab;

namespace {

/// Median over `runs` (the first run is also reported through `first`: it pays the page
/// faults of a fresh heap, as a one-shot command-line load does).
double median_ms(int runs, const std::function<void()>& work, double* first = nullptr) {
    std::vector<double> t;
    for (int i = 0; i < runs; ++i) {
        const auto t0 = std::chrono::steady_clock::now();
        work();
        t.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
                        .count());
    }
    if (first) *first = t.front();
    std::sort(t.begin(), t.end());
    return t[t.size() / 2];
}

struct Result {
    std::string mesh, format;
    double mb = 0, read_ms = 0, first_read_ms = 0, write_ms = 0;
};

struct Format {
    const char* name;
    const char* ext;
    WriteOptions options;
};

std::vector<Format> formats() {
    WriteOptions binary, ascii;
    ascii.ascii = true;
    return {{"obj", "obj", binary},        {"off", "off", binary},
            {"ply-binary", "ply", binary}, {"ply-ascii", "ply", ascii},
            {"stl-binary", "stl", binary}, {"stl-ascii", "stl", ascii},
            {"om", "om", binary}};
}

void run(const std::string& label, const HalfedgeMesh& mesh, int runs,
         const std::filesystem::path& dir, std::vector<Result>& results) {
    for (const Format& f : formats()) {
        const std::string path = (dir / (label + "-" + f.name + "." + f.ext)).string();
        Result r;
        r.mesh = label;
        r.format = f.name;
        try {
            r.write_ms = median_ms(runs, [&] { write_mesh(mesh, path, f.options); });
            r.mb = double(std::filesystem::file_size(path)) / 1e6;
            std::size_t faces = 0;
            r.read_ms = median_ms(
                runs, [&] { faces = read_mesh(path).mesh.n_faces(); }, &r.first_read_ms);
            if (faces != mesh.n_faces())
                std::printf("  note: %s %s read back %zu faces of %zu\n", label.c_str(), f.name,
                            faces, mesh.n_faces());
        } catch (const std::exception& e) {
            std::printf("  %s %s failed: %s\n", label.c_str(), f.name, e.what());
            continue;
        }
        std::printf(
            "%-6s %-10s %7.2f MB  read %8.1f ms %7.1f MB/s (first %8.1f ms)  write %8.1f ms "
            "%7.1f MB/s\n",
            label.c_str(), f.name, r.mb, r.read_ms, r.mb / r.read_ms * 1e3, r.first_read_ms,
            r.write_ms, r.mb / r.write_ms * 1e3);
        std::fflush(stdout);
        results.push_back(r);
        std::filesystem::remove(path);
    }
}

const Result* find(const std::vector<Result>& rs, const std::string& mesh, const std::string& f) {
    for (const Result& r : rs)
        if (r.mesh == mesh && r.format == f) return &r;
    return nullptr;
}

}  // namespace

int main(int argc, char** argv) {
    tune_heap_for_large_meshes();
    int runs = 5;
    bool check = false;
    for (int i = 1; i < argc; ++i) {
        if (!std::strcmp(argv[i], "--runs") && i + 1 < argc)
            runs = std::max(1, std::atoi(argv[++i]));
        else if (!std::strcmp(argv[i], "--check"))
            check = true;
        else {
            std::fprintf(stderr, "usage: trilab_bench [--runs N] [--check]\n");
            return 2;
        }
    }
    const auto dir = std::filesystem::temp_directory_path() / "trilab_bench";
    std::filesystem::create_directories(dir);
    std::vector<Result> results;
    std::printf(
        "trilab file-format benchmark: median of %d runs per figure; 'read' is the whole\n"
        "load (parse, build the half-edge mesh, repair checks), 'first' the first run\n\n",
        runs);

    const std::string bunny = std::string(TRILAB_SHARED_DIR) + "/meshes/stanford-bunny.obj";
    if (std::filesystem::exists(bunny)) {
        LoadedMesh b = read_mesh(bunny);
        std::printf("bunny: %zu vertices, %zu faces (%s)\n", b.mesh.n_vertices(), b.mesh.n_faces(),
                    bunny.c_str());
        run("bunny", b.mesh, runs, dir, results);
    } else {
        std::printf("bunny: skipped, %s is absent\n", bunny.c_str());
    }
    const HalfedgeMesh large = make_torus(1000, 500, 1.0, 0.3);
    std::printf("\nlarge: torus with %zu vertices, %zu faces\n", large.n_vertices(),
                large.n_faces());
    run("large", large, runs, dir, results);

    std::printf("\nfloors (issue 2), measured on the large mesh:\n");
    bool ok = true;
    auto floor_rate = [&](const char* format, double floor_mbs) {
        const Result* r = find(results, "large", format);
        if (!r) {
            std::printf("  %-24s MISSING\n", format);
            ok = false;
            return;
        }
        const double rate = r->mb / r->read_ms * 1e3;
        const bool pass = rate >= floor_mbs;
        ok = ok && pass;
        std::printf("  %-10s read >= %5.0f MB/s : %8.1f MB/s  ratio %5.2f  %s\n", format, floor_mbs,
                    rate, rate / floor_mbs, pass ? "PASS" : "FAIL");
    };
    floor_rate("ply-binary", 200);
    floor_rate("om", 200);
    if (const Result* r = find(results, "large", "obj")) {
        const bool pass = r->read_ms < 1500;
        ok = ok && pass;
        std::printf("  obj        load <  1500 ms   : %8.1f ms    ratio %5.2f  %s\n", r->read_ms,
                    1500 / r->read_ms, pass ? "PASS" : "FAIL");
    }
    std::filesystem::remove_all(dir);
    return check && !ok ? 1 : 0;
}
