// Roofline benchmark (not a test, issue 43): how far each core operation is from what the
// memory allows, and how it scales from one thread to all of them.
//
//   trilab_roofline_bench [--runs N] [--quick] [--mesh FILE]
//
// 1. The machine's bandwidth: memcpy of a 256 MiB buffer (64 MiB with --quick) in fixed blocks
//    on every thread (core/parallel.h), best of N; the bandwidth counts the bytes read plus the
//    bytes written (2 x the size), as the operations' bytes below do.
// 2. For each operation, the bytes it must move: counted from the arrays it has to read and
//    the arrays it has to write, each once (the bound of a pass that streams every array
//    once; gathers through the connectivity read more). bound = bytes / bandwidth.
// 3. Its time (median of N) with every thread and with one, the ratio time / bound, and the
//    scaling (one thread's time over all threads').
// The mesh: the shared Stanford bunny Loop-subdivided twice (1.1M faces, 557k vertices), or
// --mesh FILE; --quick: an icosphere of 82k faces (a smoke run). Loading is not timed.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <functional>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <sys/mman.h>

#include "app/platform/heap_tuning.h"
#include "core/algorithms/fairing.h"
#include "core/algorithms/generators.h"
#include "core/algorithms/mesh_stats.h"
#include "core/algorithms/subdivision.h"
#include "core/geometry.h"
#include "core/io/mesh_io.h"
#include "core/parallel.h"
#include "core/progress.h"
#include "core/validate.h"

using namespace trilab;

namespace {

using Clock = std::chrono::steady_clock;

double ms_of(const std::function<void()>& f) {
    const auto t0 = Clock::now();
    f();
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/// Bytes read plus written per second by memcpy in fixed blocks on thread_count() threads.
double copy_bandwidth(std::size_t bytes, int runs) {
    std::vector<char> a(bytes, 1), b(bytes, 2);
    constexpr std::size_t kCopyBlock = std::size_t(1) << 20;
    double best = 1e300;
    for (int r = 0; r < runs + 1; ++r) {
        const double ms = ms_of([&] {
            parallel_for_blocks(
                0, bytes,
                [&](std::size_t s, std::size_t e) {
                    std::memcpy(b.data() + s, a.data() + s, e - s);
                },
                kCopyBlock);
        });
        if (r > 0) best = std::min(best, ms);  // the first run pages the buffers in
    }
    volatile char sink = b[bytes / 2];
    (void)sink;
    return 2.0 * double(bytes) / (best / 1000.0);
}

/// Bytes per second written by memset in fixed blocks on thread_count() threads into a fresh
/// allocation (its pages mapped, and zeroed by the kernel, as they are first written: what a new
/// subdivision level pays), and the same bytes written again.
std::pair<double, double> fresh_and_warm_write(std::size_t bytes) {
    // mmap itself, not the heap: tune_heap_for_large_meshes() keeps freed buffers, whose pages
    // are mapped already.
    void* mapped = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (mapped == MAP_FAILED) return {0.0, 0.0};
    char* const fresh = static_cast<char*>(mapped);
    constexpr std::size_t kBlock = std::size_t(1) << 20;
    double ms[2];
    for (int pass = 0; pass < 2; ++pass)
        ms[pass] = ms_of([&] {
            parallel_for_blocks(
                0, bytes,
                [&](std::size_t s, std::size_t e) { std::memset(fresh + s, pass + 1, e - s); },
                kBlock);
        });
    volatile char sink = fresh[bytes / 2];
    (void)sink;
    munmap(mapped, bytes);
    return {double(bytes) / (ms[0] / 1000.0), double(bytes) / (ms[1] / 1000.0)};
}

struct Op {
    std::string name;
    double bytes;  ///< what it must move: its arrays read plus written, once each
    std::function<void()> run;
};

/// The bytes of the arrays each operation must stream (V vertices, E edges, F faces): a
/// position 24 bytes, a halfedge's to/next/prev/face 16, a vertex's or face's halfedge 4.
struct Sizes {
    double v, e, f;
    explicit Sizes(const HalfedgeMesh& m)
        : v(double(m.vertices_size())), e(double(m.edges_size())), f(double(m.faces_size())) {}
    /// Loop, one step: reads the connectivity (to, next, face per halfedge: 12 B; vh, fh) and
    /// the positions; writes the refined mesh's connectivity (16 B per halfedge, vh, fh, the
    /// deleted flags: 1 B per element), positions, and its vertex properties (level 4 B,
    /// stencil 4 B, parents 12 B).
    double loop() const {
        const double read = 2 * e * 12 + v * 4 + f * 4 + v * 24;
        const double v1 = v + e, e1 = 2 * e + 3 * f, f1 = 4 * f;
        const double write =
            2 * e1 * (16 + 1) + v1 * (4 + 1 + 24 + 4 + 4 + 12) + e1 * 1 + f1 * (4 + 1);
        return read + write;
    }
    /// Sqrt3, one (odd) step: the same reads; the refined mesh has V + F vertices, E + 3F
    /// edges and 3F faces, written as for Loop.
    double sqrt3() const {
        const double read = 2 * e * 12 + v * 4 + f * 4 + v * 24;
        const double v1 = v + f, e1 = e + 3 * f, f1 = 3 * f;
        const double write =
            2 * e1 * (16 + 1) + v1 * (4 + 1 + 24 + 4 + 4 + 12) + e1 * 1 + f1 * (4 + 1);
        return read + write;
    }
    /// The stable-step estimate (20 Lanczos steps): per step the rows (4 B per neighbour,
    /// 8 B offsets, valence and fixed flag) and three passes over 8-byte vectors (the product
    /// reads u, d, q and writes w; the update reads w, q, q_prev and writes w; the next vector
    /// reads w, d and writes q, u: 12 vector accesses per row).
    double estimate() const { return 20 * (2 * e * 4 + v * 13 + v * 12 * 8); }
    /// One explicit umbrella iteration: the positions read, the rows (4 B per neighbour, 8 B
    /// offsets), valence and fixed flags (5 B), the candidate written; the volume check reads
    /// the faces' three corners (fh, next, to: 4 + 2 x 4 + 3 x 4 B) and the candidate again.
    double umbrella() const {
        return v * 24 + 2 * e * 4 + v * 8 + v * 5 + v * 24 + f * 24 + v * 24;
    }
    /// Vertex normals: the rotation around each vertex (to, prev, face per halfedge; the face
    /// corners), the positions read, the normals written.
    double normals() const { return 2 * e * 12 + f * 4 + v * 4 + v * 24 + v * 24; }
    /// validate(): every connectivity array read once.
    double validate() const { return 2 * e * 16 + v * 4 + f * 4 + v + e + f; }
    /// Statistics: the halfedges' faces, the vertices' halfedges and positions, the edges' ends,
    /// the faces' corners (area and volume).
    double stats() const { return 2 * e * 4 + v * 4 + v * 24 + 2 * e * 4 + f * 4 + 2 * e * 8; }
};

std::vector<Op> operations(const HalfedgeMesh& mesh) {
    const Sizes s(mesh);
    std::vector<Op> ops;
    ops.push_back({"Loop, one step", s.loop(), [&mesh] {
                       SubdivisionOptions o;
                       o.keep_levels = false;
                       o.morph = false;
                       NullProgress progress;
                       const SubdivisionResult r = subdivide(mesh, o, progress);
                       if (r.levels.back().mesh.n_faces() != 4 * mesh.n_faces()) std::abort();
                   }});
    for (const auto& [name, scheme, bytes] :
         {std::tuple{"Sqrt3, one step", SubdivisionScheme::Sqrt3, s.sqrt3()},
          std::tuple{"Butterfly, one step", SubdivisionScheme::Butterfly, s.loop()}})
        ops.push_back({name, bytes, [&mesh, scheme = scheme] {
                           SubdivisionOptions o;
                           o.scheme = scheme;
                           o.keep_levels = false;
                           o.morph = false;
                           NullProgress progress;
                           const SubdivisionResult r = subdivide(mesh, o, progress);
                           if (r.levels.back().mesh.n_faces() < 3 * mesh.n_faces()) std::abort();
                       }});
    ops.push_back({"umbrella, 10 explicit iterations", 10 * s.umbrella(), [&mesh] {
                       FairingOptions o;
                       o.iterations = 10;
                       o.estimate_max_stable_step = false;
                       const FairingResult r = smooth(mesh, o);
                       if (r.iterations_done != 10) std::abort();
                   }});
    ops.push_back({"umbrella, 10 iterations + stable-step estimate (CLI, step > 1)",
                   10 * s.umbrella() + s.estimate(), [&mesh] {
                       FairingOptions o;
                       o.iterations = 10;
                       o.keep_steps = false;
                       HalfedgeMesh copy = mesh;
                       NullProgress progress;
                       const FairingResult r = smooth(std::move(copy), o, progress);
                       if (r.iterations_done != 10 || !(r.max_stable_step > 0)) std::abort();
                   }});
    ops.push_back({"vertex normals", s.normals(), [&mesh] {
                       HalfedgeMesh m = mesh;
                       compute_vertex_normals(m);
                   }});
    ops.push_back({"validate()", s.validate(), [&mesh] {
                       if (!validate(mesh).ok) std::abort();
                   }});
    ops.push_back({"statistics (info)", s.stats(), [&mesh] { (void)compute_stats(mesh); }});
    return ops;
}

}  // namespace

int main(int argc, char** argv) {
    tune_heap_for_large_meshes();
    int runs = 5;
    bool quick = false;
    std::string mesh_path = std::string(TRILAB_SHARED_DIR) + "/meshes/stanford-bunny.obj";
    bool subdivide_twice = true;
    for (int i = 1; i < argc; ++i) {
        if (!std::strcmp(argv[i], "--runs") && i + 1 < argc)
            runs = std::max(1, std::atoi(argv[++i]));
        else if (!std::strcmp(argv[i], "--quick"))
            quick = true;
        else if (!std::strcmp(argv[i], "--mesh") && i + 1 < argc) {
            mesh_path = argv[++i];
            subdivide_twice = false;
        } else {
            std::fprintf(stderr,
                         "usage: trilab_roofline_bench [--runs N] [--quick] [--mesh FILE]\n");
            return 2;
        }
    }
    HalfedgeMesh mesh;
    if (quick) {
        mesh = make_icosphere(64);
    } else {
        if (!std::filesystem::exists(mesh_path)) {
            std::printf("%s: skipped, not found\n", mesh_path.c_str());
            return 0;
        }
        mesh = read_mesh(mesh_path).mesh;
        if (subdivide_twice) {
            SubdivisionOptions o;
            o.iterations = 2;
            o.keep_levels = false;
            o.morph = false;
            NullProgress progress;
            mesh = std::move(subdivide(mesh, o, progress).levels.back().mesh);
        }
    }
    const int all = thread_count();
    const double bw = copy_bandwidth(quick ? std::size_t(64) << 20 : std::size_t(256) << 20, runs);
    set_thread_count(1);
    const double bw1 = copy_bandwidth(quick ? std::size_t(64) << 20 : std::size_t(256) << 20, runs);
    set_thread_count(all);
    std::printf("mesh: %zu vertices, %zu edges, %zu faces; %d threads (of %d hardware)\n",
                mesh.n_vertices(), mesh.n_edges(), mesh.n_faces(), all, hardware_threads());
    std::printf("memcpy bandwidth (read + write): %.2f GB/s on %d threads, %.2f GB/s on 1\n",
                bw / 1e9, all, bw1 / 1e9);
    const std::size_t fresh_bytes = quick ? std::size_t(64) << 20 : std::size_t(350) << 20;
    const auto [fresh, warm] = fresh_and_warm_write(fresh_bytes);
    std::printf(
        "writing %zu MB on %d threads: %.2f GB/s into fresh pages (%.1f ms: the kernel maps and "
        "zeroes each page first), %.2f GB/s again (%.1f ms)\n",
        fresh_bytes >> 20, all, fresh / 1e9, 1000.0 * double(fresh_bytes) / fresh, warm / 1e9,
        1000.0 * double(fresh_bytes) / warm);
    std::printf(
        "\n| operation | MB moved | bound ms | ms, %d threads | ratio | ms, 1 thread | "
        "scaling |\n|---|---:|---:|---:|---:|---:|---:|\n",
        all);
    for (const Op& op : operations(mesh)) {
        std::vector<double> t_all, t_one;
        op.run();                         // warm-up
        for (int r = 0; r < runs; ++r) {  // alternating, so that a change of load hits both
            set_thread_count(all);
            t_all.push_back(ms_of(op.run));
            set_thread_count(1);
            t_one.push_back(ms_of(op.run));
        }
        set_thread_count(all);
        const double bound = op.bytes / bw * 1000.0;
        const double m_all = median(t_all), m_one = median(t_one);
        std::printf("| %s | %.0f | %.1f | %.1f | %.1f | %.1f | %.2f |\n", op.name.c_str(),
                    op.bytes / 1e6, bound, m_all, m_all / bound, m_one, m_one / m_all);
        std::fflush(stdout);
    }
    return 0;
}
