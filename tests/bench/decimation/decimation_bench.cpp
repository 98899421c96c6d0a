// Decimation benchmark (not a test): trilab's quadric decimation (core/algorithms/decimation.h)
// against OpenMesh 9 (DecimaterT + ModQuadricT), CGAL 5.5 (edge_collapse, Garland-Heckbert plane
// policies) and meshoptimizer (meshopt_simplify), in the same run, on the same meshes.
//
//   trilab_decimation_bench [--runs N] [--peer-runs N] [--samples N] [--quick] [--check]
//                           [--speed-only]
//
// Speed: the shared bunny and the bunny Loop-subdivided twice (~556k vertices, 1.1M faces;
// a 1M-face torus when the bunny is absent), down to 10 % and 1 % of the vertices: median
// milliseconds over N runs (default 3; peers --peer-runs, default 1, they are slow). Only the
// decimation call is timed (trilab: decimate(), which copies the input and compacts the
// output; peers: their decimate call on their own mesh, built beforehand, untimed).
// Quality: bunny, horse and fandisk at 10 % and 1 %: sampled two-sided Hausdorff and RMS
// distance to the input (core/algorithms/mesh_distance.h, --samples per mesh, default 200000)
// relative to the bounding-box diagonal. trilab is run at CGAL's actual output vertex count for the
// ratio. Manifoldness of every output: trilab's passes validate(); peers' soups are checked
// for edges with more than two faces and duplicate triangles (and what build_mesh repaired).
//
// Floors (issue 8): the 1.1M-face mesh to 1 % in under 2000 ms; Hausdorff at most 1.1x
// CGAL's at the same vertex count on bunny, horse and fandisk at 10 % and 1 %; never a
// non-manifold output. --check exits non-zero when a floor is missed; --quick runs only the
// bunny at 10 % without peers (a smoke test); --speed-only runs the speed cases for trilab
// alone, without peers, distances or the quality table (quick before/after timings).
//
// Options used for trilab: the defaults of DecimationOptions (quadric, normal flip 90 deg).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "app/platform/heap_tuning.h"
#include "core/algorithms/decimation.h"
#include "core/algorithms/generators.h"
#include "core/algorithms/mesh_distance.h"
#include "core/algorithms/subdivision.h"
#include "core/io/mesh_io.h"
#include "core/mesh_builder.h"
#include "core/validate.h"
#include "peers.h"

using namespace trilab;
using namespace trilab::bench;

namespace {

constexpr double kTimeFloorMs = 2000.0;
constexpr double kQualityFloor = 1.1;

struct Config {
    int runs = 3, peer_runs = 1;
    std::size_t samples = 200000;
    bool quick = false, check = false, speed_only = false;
};

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0 : v[v.size() / 2];
}

Soup to_bench_soup(const HalfedgeMesh& m) {
    const PolygonSoup p = to_soup(m);
    Soup s;
    for (const Point& x : p.positions) s.positions.push_back({x.x(), x.y(), x.z()});
    for (std::size_t f = 0; f < p.n_faces(); ++f) {
        const std::size_t o = p.face_offsets[f];
        s.faces.push_back({p.corners[o], p.corners[o + 1], p.corners[o + 2]});
    }
    return s;
}

struct Built {
    HalfedgeMesh mesh;
    std::size_t nonmanifold_edges = 0, duplicate_faces = 0, repaired = 0;
    bool manifold() const {
        return nonmanifold_edges == 0 && duplicate_faces == 0 && repaired == 0;
    }
};

Built from_bench_soup(const Soup& s) {
    Built b;
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> edge_faces;
    std::set<std::array<std::uint32_t, 3>> seen;
    PolygonSoup p;
    for (const auto& x : s.positions) p.positions.emplace_back(x[0], x[1], x[2]);
    for (const auto& f : s.faces) {
        for (int i = 0; i < 3; ++i) {
            const std::uint32_t a = f[i], c = f[(i + 1) % 3];
            ++edge_faces[{std::min(a, c), std::max(a, c)}];
        }
        std::array<std::uint32_t, 3> key = f;
        std::sort(key.begin(), key.end());
        if (!seen.insert(key).second) ++b.duplicate_faces;
        p.add_face({f[0], f[1], f[2]});
    }
    for (const auto& [e, n] : edge_faces)
        if (n > 2) ++b.nonmanifold_edges;
    LoadReport report;
    b.mesh = build_mesh(p, report);
    b.repaired =
        report.detached_faces + report.nonmanifold_vertices_split + report.degenerate_faces_dropped;
    return b;
}

struct Outcome {
    bool ran = false;
    double ms = 0, cpu_ms = 0;
    std::size_t vertices = 0, faces = 0;
    double hausdorff = 0, rms = 0;  // relative to the diagonal
    bool manifold = true;
    std::string note;
};

double run_trilab(const HalfedgeMesh& mesh, std::size_t target, HalfedgeMesh* out, double* cpu_ms) {
    DecimationOptions o;
    o.target_vertices = target;
    o.record_progressive = false;
    const auto t0 = std::chrono::steady_clock::now();
    const std::clock_t c0 = std::clock();
    DecimationResult r = decimate(mesh, o);
    *cpu_ms = 1000.0 * double(std::clock() - c0) / CLOCKS_PER_SEC;
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    if (out) *out = r.levels.empty() ? mesh : std::move(r.levels.back().mesh);
    return ms;
}

void measure(Outcome& o, const HalfedgeMesh& input, const HalfedgeMesh& out, const Config& c) {
    const MeshDistance d = mesh_distance(input, out, {c.samples});
    o.hausdorff = d.hausdorff / d.diagonal;
    o.rms = d.rms / d.diagonal;
    o.vertices = out.n_vertices();
    o.faces = out.n_faces();
}

Outcome trilab_outcome(const HalfedgeMesh& mesh, std::size_t target, const Config& c, int runs,
                       bool quality) {
    Outcome o;
    o.ran = true;
    std::vector<double> ms, cpu;
    HalfedgeMesh out;
    for (int i = 0; i < runs; ++i) {
        double cpu_ms = 0;
        ms.push_back(run_trilab(mesh, target, &out, &cpu_ms));
        cpu.push_back(cpu_ms);
    }
    o.ms = median(ms);
    o.cpu_ms = median(cpu);
    o.vertices = out.n_vertices();
    o.faces = out.n_faces();
    o.manifold = validate(out).ok;
    if (quality) measure(o, mesh, out, c);
    return o;
}

enum class Peer { OpenMesh, Cgal, Meshopt };
const char* peer_name(Peer p) {
    return p == Peer::OpenMesh ? "OpenMesh 9" : p == Peer::Cgal ? "CGAL 5.5" : "meshoptimizer";
}
bool have(Peer p) {
    return p == Peer::OpenMesh ? have_openmesh() : p == Peer::Cgal ? have_cgal() : have_meshopt();
}

Outcome peer_outcome(Peer p, const HalfedgeMesh& mesh, const Soup& soup, std::size_t target,
                     const Config& c, bool quality) {
    Outcome o;
    if (!have(p)) return o;
    o.ran = true;
    // Closed or not: each collapse removes one vertex and about two faces.
    const std::size_t removed = mesh.n_vertices() - target;
    const std::size_t target_faces =
        mesh.n_faces() > 2 * removed ? mesh.n_faces() - 2 * removed : 4;
    const std::size_t target_edges =
        mesh.n_edges() > 3 * removed ? mesh.n_edges() - 3 * removed + 1 : 6;
    std::vector<double> ms, cpu;
    PeerRun run;
    for (int i = 0; i < c.peer_runs; ++i) {
        run = p == Peer::OpenMesh ? openmesh_decimate(soup, target)
              : p == Peer::Cgal   ? cgal_decimate(soup, target_edges)
                                  : meshopt_decimate(soup, target_faces);
        ms.push_back(run.ms);
        cpu.push_back(run.cpu_ms);
    }
    o.ms = median(ms);
    o.cpu_ms = median(cpu);
    Built b = from_bench_soup(run.soup);
    o.manifold = b.manifold();
    if (!o.manifold)
        o.note = std::to_string(b.nonmanifold_edges) + " non-manifold edges, " +
                 std::to_string(b.duplicate_faces) + " duplicate faces";
    o.vertices = run.soup.positions.size();
    o.faces = run.soup.faces.size();
    if (quality) measure(o, mesh, b.mesh, c);
    o.vertices = run.soup.positions.size();
    o.faces = run.soup.faces.size();
    return o;
}

void print_row(const char* who, const Outcome& o, bool quality) {
    if (!o.ran) {
        std::printf("    %-14s (not built: library not found at configure time)\n", who);
        return;
    }
    std::printf("    %-14s %9.1f ms (CPU %9.1f ms)  %7zu V %8zu F", who, o.ms, o.cpu_ms, o.vertices,
                o.faces);
    if (quality) std::printf("  Hausdorff %.4f%%  RMS %.5f%%", 100 * o.hausdorff, 100 * o.rms);
    std::printf("  %s%s%s\n", o.manifold ? "manifold" : "NON-MANIFOLD", o.note.empty() ? "" : ": ",
                o.note.c_str());
}

HalfedgeMesh load(const std::string& name, bool& ok) {
    const std::string path = std::string(TRILAB_SHARED_DIR) + "/meshes/" + name;
    try {
        ok = true;
        // Without isolated vertices (the bunny has 1,113): every library counts the same.
        return from_bench_soup(compact(to_bench_soup(read_mesh(path).mesh))).mesh;
    } catch (const Error& e) {
        std::printf("  (%s: %s)\n", name.c_str(), e.what());
        ok = false;
        return {};
    }
}

}  // namespace

int main(int argc, char** argv) {
    tune_heap_for_large_meshes();
    Config c;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--runs" && i + 1 < argc)
            c.runs = std::max(1, std::atoi(argv[++i]));
        else if (a == "--peer-runs" && i + 1 < argc)
            c.peer_runs = std::max(1, std::atoi(argv[++i]));
        else if (a == "--samples" && i + 1 < argc)
            c.samples = std::size_t(std::max(1, std::atoi(argv[++i])));
        else if (a == "--quick")
            c.quick = true;
        else if (a == "--check")
            c.check = true;
        else if (a == "--speed-only")
            c.speed_only = true;
        else {
            std::fprintf(stderr,
                         "usage: trilab_decimation_bench [--runs N] [--peer-runs N] "
                         "[--samples N] [--quick] [--check] [--speed-only]\n");
            return 2;
        }
    }
    bool missed = false;
    std::printf("peers: OpenMesh %s, CGAL %s, meshoptimizer %s\n", have_openmesh() ? "yes" : "no",
                have_cgal() ? "yes" : "no", have_meshopt() ? "yes" : "no");

    bool have_bunny = false;
    const HalfedgeMesh bunny = load("stanford-bunny.obj", have_bunny);

    if (c.quick) {
        const HalfedgeMesh m = have_bunny ? bunny : make_icosphere(40);
        const Outcome o = trilab_outcome(m, m.n_vertices() / 10, c, 1, true);
        std::printf("quick: %zu -> %zu vertices in %.1f ms, Hausdorff %.4f%% of the diagonal\n",
                    m.n_vertices(), o.vertices, o.ms, 100 * o.hausdorff);
        return o.manifold ? 0 : 1;
    }

    // ---- speed -------------------------------------------------------------------------------
    HalfedgeMesh big;
    if (have_bunny) {
        SubdivisionOptions so;
        so.iterations = 2;
        NullProgress np;
        big = std::move(subdivide(bunny, so, np).levels.back().mesh);
    } else {
        big = make_torus(1000, 500, 1.0, 0.3);
    }
    std::printf("\n== speed (median of %d trilab runs, %d peer runs) ==\n", c.runs, c.peer_runs);
    struct SpeedCase {
        const char* name;
        const HalfedgeMesh* mesh;
    };
    std::vector<SpeedCase> speed;
    if (have_bunny) speed.push_back({"bunny", &bunny});
    speed.push_back({have_bunny ? "bunny-loop2" : "torus-1M", &big});
    double floor_ms = 0, floor_cpu_ms = 0;
    for (const SpeedCase& s : speed) {
        const Soup soup = to_bench_soup(*s.mesh);
        for (double fraction : {0.1, 0.01}) {
            const std::size_t target = std::size_t(fraction * double(s.mesh->n_vertices()));
            std::printf("  %s: %zu V, %zu F -> %zu V (%g %%)\n", s.name, s.mesh->n_vertices(),
                        s.mesh->n_faces(), target, 100 * fraction);
            // Small meshes: see the quality table.
            const bool quality = s.mesh == &big && !c.speed_only;
            const Outcome t = trilab_outcome(*s.mesh, target, c, c.runs, quality);
            print_row("trilab", t, quality);
            if (!t.manifold) missed = true;
            for (Peer p : {Peer::OpenMesh, Peer::Cgal, Peer::Meshopt}) {
                if (c.speed_only) break;
                const Outcome o = peer_outcome(p, *s.mesh, soup, target, c, quality);
                print_row(peer_name(p), o, quality);
                if (o.ran)
                    std::printf("      trilab is %.1fx faster than %s (CPU time %.1fx)\n",
                                o.ms / t.ms, peer_name(p), o.cpu_ms / t.cpu_ms);
            }
            if (s.mesh == &big && fraction == 0.01) {
                floor_ms = t.ms;
                floor_cpu_ms = t.cpu_ms;
            }
        }
    }
    // The floor is judged on CPU time: on a shared machine the wall clock also counts the
    // time other processes held the core (both are printed).
    std::printf(
        "  floor: 1.1M faces to 1 %% in %.0f ms CPU, %.0f ms wall (floor < %.0f ms: "
        "%s, %.2fx of the budget)\n",
        floor_cpu_ms, floor_ms, kTimeFloorMs, floor_cpu_ms < kTimeFloorMs ? "met" : "MISSED",
        floor_cpu_ms / kTimeFloorMs);
    if (floor_cpu_ms >= kTimeFloorMs) missed = true;
    if (c.speed_only) {
        std::printf("\n%s\n", missed ? "some floors MISSED" : "all floors met");
        return c.check && missed ? 1 : 0;
    }

    // ---- quality -----------------------------------------------------------------------------
    std::printf(
        "\n== quality (Hausdorff and RMS relative to the bounding-box diagonal, %zu "
        "samples per mesh) ==\n",
        c.samples);
    for (const char* name : {"stanford-bunny.obj", "horse.ply", "fandisk.obj"}) {
        bool ok = false;
        const HalfedgeMesh mesh = load(name, ok);
        if (!ok) continue;
        const Soup soup = to_bench_soup(mesh);
        for (double fraction : {0.1, 0.01}) {
            const std::size_t target = std::size_t(fraction * double(mesh.n_vertices()));
            std::printf("  %s: %zu V -> %zu V (%g %%)\n", name, mesh.n_vertices(), target,
                        100 * fraction);
            const Outcome t = trilab_outcome(mesh, target, c, 1, true);
            print_row("trilab", t, true);
            if (!t.manifold) missed = true;
            Outcome cgal;
            for (Peer p : {Peer::OpenMesh, Peer::Cgal, Peer::Meshopt}) {
                const Outcome o = peer_outcome(p, mesh, soup, target, c, true);
                print_row(peer_name(p), o, true);
                if (p == Peer::Cgal) cgal = o;
            }
            if (cgal.ran) {
                // Same vertex count as CGAL's output for the ratio.
                const Outcome same = cgal.vertices == t.vertices
                                         ? t
                                         : trilab_outcome(mesh, cgal.vertices, c, 1, true);
                if (cgal.vertices != t.vertices) print_row("trilab @CGAL V", same, true);
                const double ratio = same.hausdorff / cgal.hausdorff;
                std::printf(
                    "      Hausdorff trilab / CGAL = %.3f (floor <= %.1f: %s), RMS "
                    "ratio %.3f\n",
                    ratio, kQualityFloor, ratio <= kQualityFloor ? "met" : "MISSED",
                    same.rms / cgal.rms);
                if (ratio > kQualityFloor) missed = true;
            }
        }
    }
    std::printf("\n%s\n", missed ? "some floors MISSED" : "all floors met");
    return c.check && missed ? 1 : 0;
}
