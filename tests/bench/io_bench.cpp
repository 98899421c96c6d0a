// File-format benchmark (not a test): loads and writes the shared Stanford bunny and a
// self-built torus of 1,000,000 faces in every format, printing the median time and
// throughput of each; loads 1,000,000-gons (a convex one and a star-shaped one, OBJ and
// binary PLY); optionally times what `trilab-cli info` does on a big file; then prints the
// issues' floors with the ratio measured/floor.
//
//   trilab_bench [--runs N] [--check] [--no-formats] [--big FILE.ply]
//
// --check exits non-zero when a floor is missed. Medians over N runs (default 5).
// --big FILE: read + compute_stats + validate of FILE (issue 17 uses the bunny Loop-subdivided
// four times: `trilab-cli subdivide --iterations 4 stanford-bunny.obj big4.ply`, 17.8M faces).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "app/platform/heap_tuning.h"
#include "core/algorithms/generators.h"
#include "core/algorithms/mesh_stats.h"
#include "core/io/mesh_io.h"
#include "core/validate.h"

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

/// A polygon of n corners on a circle in a tilted plane (star: radii alternating 1 and 0.5),
/// written as one face: OBJ text, or binary PLY with an int-counted index list.
void write_polygon_file(const std::string& path, std::size_t n, bool star) {
    std::vector<float> xyz;
    for (std::size_t i = 0; i < n; ++i) {
        const double a = 2 * M_PI * double(i) / double(n);
        const double r = star && i % 2 ? 0.5 : 1.0;
        const double x = r * std::cos(a), y = r * std::sin(a);
        xyz.insert(xyz.end(), {float(x), float(y), float(0.25 * x)});
    }
    std::ofstream out(path, std::ios::binary);
    if (path.size() > 4 && path.compare(path.size() - 4, 4, ".obj") == 0) {
        std::string text;
        char buf[96];
        for (std::size_t i = 0; i < n; ++i) {
            std::snprintf(buf, sizeof buf, "v %.9g %.9g %.9g\n", xyz[3 * i], xyz[3 * i + 1],
                          xyz[3 * i + 2]);
            text += buf;
        }
        text += "f";
        for (std::size_t i = 0; i < n; ++i) text += " " + std::to_string(i + 1);
        text += "\n";
        out << text;
        return;
    }
    out << "ply\nformat binary_little_endian 1.0\nelement vertex " << n
        << "\nproperty float x\nproperty float y\nproperty float z\nelement face 1\n"
           "property list int int vertex_indices\nend_header\n";
    out.write(reinterpret_cast<const char*>(xyz.data()), std::streamsize(xyz.size() * 4));
    std::vector<std::int32_t> face(n + 1);
    face[0] = std::int32_t(n);
    for (std::size_t i = 0; i < n; ++i) face[i + 1] = std::int32_t(i);
    out.write(reinterpret_cast<const char*>(face.data()), std::streamsize(face.size() * 4));
}

struct Timed {
    std::string what;
    double ms = 0, floor_ms = 0;
};

}  // namespace

int main(int argc, char** argv) {
    tune_heap_for_large_meshes();
    int runs = 5;
    bool check = false, formats = true;
    std::string big;
    for (int i = 1; i < argc; ++i) {
        if (!std::strcmp(argv[i], "--runs") && i + 1 < argc)
            runs = std::max(1, std::atoi(argv[++i]));
        else if (!std::strcmp(argv[i], "--check"))
            check = true;
        else if (!std::strcmp(argv[i], "--no-formats"))
            formats = false;
        else if (!std::strcmp(argv[i], "--big") && i + 1 < argc)
            big = argv[++i];
        else {
            std::fprintf(stderr,
                         "usage: trilab_bench [--runs N] [--check] [--no-formats] [--big FILE]\n");
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

    bool ok = true;
    std::vector<Timed> timed;
    // Issue 17: a 1,000,000-gon loads in under 2 s (it was quadratic ear clipping).
    std::printf("polygons: one face of 1,000,000 corners (median of %d loads)\n", runs);
    for (const char* shape : {"convex", "star"})
        for (const char* ext : {"obj", "ply"}) {
            const std::string path = (dir / (std::string("gon-") + shape + "." + ext)).string();
            write_polygon_file(path, 1000000, std::string(shape) == "star");
            std::size_t faces = 0;
            const double ms = median_ms(runs, [&] { faces = read_mesh(path).mesh.n_faces(); });
            if (faces != 999998) {
                std::printf("  %s %s: %zu faces, expected 999998\n", shape, ext, faces);
                ok = false;
            }
            std::printf("  %-7s %s  load %8.1f ms\n", shape, ext, ms);
            timed.push_back({std::string("1M-gon ") + shape + " " + ext + " load", ms, 2000});
            std::filesystem::remove(path);
        }
    if (!big.empty()) {
        // What `trilab-cli info` does: the load, compute_stats and validate.
        std::size_t faces = 0;
        bool valid = true;
        const double ms = median_ms(runs, [&] {
            const LoadedMesh m = read_mesh(big);
            faces = compute_stats(m.mesh).faces;
            valid = valid && validate(m.mesh).ok;
        });
        std::printf("\nbig: %s, %zu faces: load + stats + validate %8.1f ms%s\n", big.c_str(),
                    faces, ms, valid ? "" : " (INVALID)");
        ok = ok && valid;
        timed.push_back({"big: load + stats + validate", ms, 5000});
    }
    std::printf("\n");

    const std::string bunny = std::string(TRILAB_SHARED_DIR) + "/meshes/stanford-bunny.obj";
    if (!formats) {
        // Only the polygons (and --big).
    } else if (std::filesystem::exists(bunny)) {
        LoadedMesh b = read_mesh(bunny);
        std::printf("bunny: %zu vertices, %zu faces (%s)\n", b.mesh.n_vertices(), b.mesh.n_faces(),
                    bunny.c_str());
        run("bunny", b.mesh, runs, dir, results);
    } else {
        std::printf("bunny: skipped, %s is absent\n", bunny.c_str());
    }
    if (formats) {
        const HalfedgeMesh large = make_torus(1000, 500, 1.0, 0.3);
        std::printf("\nlarge: torus with %zu vertices, %zu faces\n", large.n_vertices(),
                    large.n_faces());
        run("large", large, runs, dir, results);
    }

    std::printf("\nfloors (issue 17):\n");
    for (const Timed& t : timed) {
        const bool pass = t.ms < t.floor_ms;
        ok = ok && pass;
        std::printf("  %-32s < %5.0f ms : %8.1f ms    ratio %5.2f  %s\n", t.what.c_str(),
                    t.floor_ms, t.ms, t.floor_ms / t.ms, pass ? "PASS" : "FAIL");
    }
    if (!formats) {
        std::filesystem::remove_all(dir);
        return check && !ok ? 1 : 0;
    }
    std::printf("\nfloors (issue 2), measured on the large mesh:\n");
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
