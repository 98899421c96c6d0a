// The cost of the layer between the core and the user (issue 14, "No hidden cost"): each
// operation timed three ways in one run on the same input,
//   core  the core function called as the operation layer calls it for the CLI;
//   op    run_operation() with the CLI's settings (no intermediate steps, no morphs);
//   cli   `trilab-cli NAME ... --json`, its "ms" (the operation itself; reading and writing
//         the files are not in it), and the process's peak memory;
// with the ratios op/core and cli/core (floor 1.2), and the peers in the same run when
// OpenMesh is installed (floors: Loop, Sqrt3 and Butterfly steps at least 2x OpenMesh 9's
// uniform subdividers with double points; 10 explicit umbrella iterations at least 3x
// OpenMesh's JacobiLaplaceSmootherT), decimation of the 1.1M-face mesh to 1 % under 2 s and
// the cow's 150 frequencies under 1 s through the CLI, and the peak memory of a 10-iteration
// smooth at most 1.5x that of a 1-iteration one.
//
//   ./build/tests/trilab_operation_bench [--runs N] [--quick]
// --quick: the bunny instead of the 1.1M-face mesh (a smoke run; the floors are not judged).
// Inputs: ../shared/meshes/stanford-bunny.obj Loop-subdivided twice (556,051 vertices,
// 1,111,216 faces) and ../shared/meshes/cow.obj Loop-subdivided once (11,610 vertices), made
// in the run and written as binary PLY to a temporary folder for the CLI.
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "app/ops/operation.h"
#include "core/algorithms/decimation.h"
#include "core/algorithms/fairing.h"
#include "core/algorithms/spectral.h"
#include "core/algorithms/subdivision.h"
#include "core/io/mesh_io.h"

#ifdef TRILAB_HAS_OPENMESH
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include "openmesh_mesh.h"  // first: the tools need the mesh kernel

#include <OpenMesh/Tools/Smoother/JacobiLaplaceSmootherT.hh>
#include <OpenMesh/Tools/Subdivider/Uniform/LoopT.hh>
#include <OpenMesh/Tools/Subdivider/Uniform/ModifiedButterFlyT.hh>
#include <OpenMesh/Tools/Subdivider/Uniform/Sqrt3T.hh>
#endif

using namespace trilab;
namespace fs = std::filesystem;

namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0 : v[v.size() / 2];
}

/// Median of `runs` timings of `work` (which returns its own milliseconds).
[[maybe_unused]] double median_ms(int runs, const std::function<double()>& work) {
    std::vector<double> t;
    for (int i = 0; i < runs; ++i) t.push_back(work());
    return median(t);
}

struct CliRun {
    double ms = -1;      ///< the JSON's "ms"
    double peak_mb = 0;  ///< the process's peak resident memory
    bool ok = false;
};

/// Runs trilab-cli with `args`, reads "ms" from its JSON and its peak memory from wait4().
CliRun run_cli(const std::string& cli, const std::vector<std::string>& args) {
    int out[2];
    CliRun r;
    if (pipe(out) != 0) return r;
    const pid_t pid = fork();
    if (pid == 0) {
        dup2(out[1], 1);
        close(out[0]);
        close(out[1]);
        std::vector<char*> argv{const_cast<char*>(cli.c_str())};
        for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
        argv.push_back(nullptr);
        execv(cli.c_str(), argv.data());
        _exit(127);
    }
    close(out[1]);
    std::string text;
    char buf[4096];
    for (ssize_t n; (n = read(out[0], buf, sizeof buf)) > 0;) text.append(buf, std::size_t(n));
    close(out[0]);
    int status = 0;
    rusage usage{};
    wait4(pid, &status, 0, &usage);
    r.ok = WIFEXITED(status) && WEXITSTATUS(status) == 0;
    r.peak_mb = double(usage.ru_maxrss) / 1024.0;
    const std::size_t at = text.rfind("\"ms\": ");
    if (at != std::string::npos) r.ms = std::atof(text.c_str() + at + 6);
    if (!r.ok) std::printf("  trilab-cli failed: %s\n", text.c_str());
    return r;
}

struct Case {
    std::string name;
    std::string op_text;           ///< the operation as the CLI and run_operation take it
    std::function<double()> core;  ///< one timed core run, ms
    double floor_ms = 0;           ///< absolute floor through the CLI (0: none)
    std::optional<double> peer_ms;
    double peer_floor = 0;  ///< trilab through the CLI at least this many times faster
    std::string peer_name;
};

#ifdef TRILAB_HAS_OPENMESH
using OMMesh = bench::OpenMeshDouble;
using bench::to_openmesh;

double openmesh_subdivide_ms(const OMMesh& source, SubdivisionScheme scheme, int runs) {
    return median_ms(runs, [&] {
        OMMesh m = source;  // not timed
        const auto t0 = Clock::now();
        if (scheme == SubdivisionScheme::Loop) {
            OpenMesh::Subdivider::Uniform::LoopT<OMMesh> s;
            s(m, 1);
        } else if (scheme == SubdivisionScheme::Sqrt3) {
            OpenMesh::Subdivider::Uniform::Sqrt3T<OMMesh> s;
            s(m, 1);
        } else {  // OpenMesh has no plain Butterfly: its modified one is the peer
            OpenMesh::Subdivider::Uniform::ModifiedButterflyT<OMMesh> s;
            s(m, 1);
        }
        return ms_since(t0);
    });
}

/// 10 iterations of uniform Laplacian smoothing (damping 0.5 = trilab's umbrella, step 0.5).
double openmesh_jacobi_ms(const OMMesh& source, int runs) {
    return median_ms(runs, [&] {
        OMMesh m = source;
        m.request_vertex_normals();
        m.request_face_normals();
        m.update_normals();
        const auto t0 = Clock::now();
        OpenMesh::Smoother::JacobiLaplaceSmootherT<OMMesh> smoother(m);
        smoother.initialize(OpenMesh::Smoother::SmootherT<OMMesh>::Tangential_and_Normal,
                            OpenMesh::Smoother::SmootherT<OMMesh>::C0);
        smoother.smooth(10);
        return ms_since(t0);
    });
}
#endif

std::string cli_path(const char* argv0) {
    const fs::path self = fs::absolute(argv0);
    return (self.parent_path().parent_path() / "trilab-cli").string();
}

}  // namespace

int main(int argc, char** argv) {
    int runs = 3;
    bool quick = false;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--runs" && i + 1 < argc)
            runs = std::max(1, std::atoi(argv[++i]));
        else if (a == "--quick")
            quick = true;
        else {
            std::fprintf(stderr, "usage: trilab_operation_bench [--runs N] [--quick]\n");
            return 2;
        }
    }
    const std::string shared = TRILAB_SHARED_DIR "/meshes/";
    if (!fs::exists(shared + "stanford-bunny.obj") || !fs::exists(shared + "cow.obj")) {
        std::printf("skipped: %s has no stanford-bunny.obj or cow.obj\n", shared.c_str());
        return 0;
    }
    const std::string cli = cli_path(argv[0]);
    const fs::path tmp = fs::temp_directory_path() / ("trilab-opbench-" + std::to_string(getpid()));
    fs::create_directories(tmp);

    // The inputs, made here; the CLI reads the same meshes from binary PLY.
    HalfedgeMesh big = read_mesh(shared + "stanford-bunny.obj").mesh;
    if (!quick) {
        SubdivisionOptions two;
        two.iterations = 2;
        NullProgress none;
        big = std::move(subdivide(big, two, none).levels.back().mesh);
    }
    big.garbage_collection();
    const std::string big_ply = (tmp / "big.ply").string();
    write_mesh(big, big_ply);
    big = read_mesh(big_ply).mesh;  // exactly what the CLI reads (float32 positions)
    HalfedgeMesh cow = read_mesh(shared + "cow.obj").mesh;
    NullProgress no_progress;
    cow = std::move(subdivide(cow, SubdivisionOptions{}, no_progress).levels.back().mesh);
    const std::string cow_ply = (tmp / "cow.ply").string();
    write_mesh(cow, cow_ply);
    cow = read_mesh(cow_ply).mesh;
    std::printf("inputs: %zu vertices / %zu faces (%s), cow %zu vertices; %d runs, medians\n",
                big.n_vertices(), big.n_faces(), quick ? "bunny" : "bunny Loop x2",
                cow.n_vertices(), runs);

    std::size_t surface = 0;
    for (Vertex v : big.vertices()) surface += big.is_isolated(v) ? 0 : 1;
    const std::size_t target = std::max<std::size_t>(surface / 100, 4);

    std::vector<Case> cases;
    for (SubdivisionScheme s : {SubdivisionScheme::Loop, SubdivisionScheme::Sqrt3,
                                SubdivisionScheme::Butterfly, SubdivisionScheme::ModifiedButterfly})
        cases.push_back({std::string("subdivide ") + scheme_name(s),
                         std::string("subdivide --scheme ") + scheme_name(s),
                         [&big, s] {
                             SubdivisionOptions o;
                             o.scheme = s;
                             o.keep_levels = false;
                             o.morph = false;
                             NullProgress quiet;
                             const auto t0 = Clock::now();
                             const SubdivisionResult r = subdivide(big, o, quiet);
                             return ms_since(t0) + 0 * double(r.levels.size());
                         },
                         0,
                         {},
                         s == SubdivisionScheme::ModifiedButterfly ? 0.0 : 2.0,
                         "OpenMesh 9"});
    cases.push_back({"smooth umbrella x10",
                     "smooth --iterations 10",
                     [&big] {
                         FairingOptions o;
                         o.iterations = 10;
                         o.keep_steps = false;
                         const auto t0 = Clock::now();
                         const FairingResult r = smooth(big, o);
                         return ms_since(t0);
                     },
                     0,
                     {},
                     3.0,
                     "OpenMesh JacobiLaplaceSmootherT"});
    cases.push_back({"smooth cotangent implicit x1",
                     "smooth --operator curvature-flow --integration implicit --step 1",
                     [&big] {
                         FairingOptions o;
                         o.op = FairingOperator::CurvatureFlow;
                         o.integration = Integration::Implicit;
                         o.step = 1;
                         o.keep_steps = false;
                         const auto t0 = Clock::now();
                         const FairingResult r = smooth(big, o);
                         return ms_since(t0);
                     },
                     0,
                     {},
                     0,
                     ""});
    cases.push_back({"decimate to 1 %",
                     "decimate --target-vertices " + std::to_string(target),
                     [&big, target] {
                         DecimationOptions o;  // as the decimate operation asks for the CLI
                         o.target_vertices = target;
                         o.record_progressive = false;
                         o.levels = DecimationLevels::Last;
                         o.record_geomorph = false;
                         const auto t0 = Clock::now();
                         const DecimationResult r = decimate(big, o);
                         return ms_since(t0);
                     },
                     2000,
                     {},
                     0,
                     ""});
    cases.push_back({"spectrum cow 150",
                     "spectrum --operator curvature-flow --k 150",
                     [&cow] {
                         SpectralOptions o;
                         o.op = LaplacianOperator::CurvatureFlow;
                         o.k = 150;
                         const auto t0 = Clock::now();
                         const SpectralDecomposition d = decompose(cow, o);
                         const HalfedgeMesh out = reconstruct(cow, d, 0, d.size() - 1);
                         return ms_since(t0);
                     },
                     1000,
                     {},
                     0,
                     ""});

#ifdef TRILAB_HAS_OPENMESH
    {
        const OMMesh om = to_openmesh(big);
        for (Case& c : cases) {
            if (c.name.rfind("subdivide", 0) == 0 && c.peer_floor > 0) {
                const SubdivisionScheme s = parse_scheme(c.name.substr(10));
                c.peer_ms = openmesh_subdivide_ms(om, s, runs);
                if (s == SubdivisionScheme::Butterfly)
                    c.peer_name = "OpenMesh 9 ModifiedButterflyT";
            }
            if (c.name == "smooth umbrella x10") c.peer_ms = openmesh_jacobi_ms(om, runs);
        }
    }
#endif

    std::printf("\n%-30s %9s %9s %9s %7s %7s %9s  %s\n", "case", "core ms", "op ms", "cli ms",
                "op/core", "cli/core", "cli MB", "floors");
    bool all_ok = true;
    for (Case& c : cases) {
        const std::string in = c.name.rfind("spectrum", 0) == 0 ? cow_ply : big_ply;
        const HalfedgeMesh& mesh = c.name.rfind("spectrum", 0) == 0 ? cow : big;
        std::vector<double> core, op, cli_ms, peak;
        RunSettings settings;
        settings.keep_steps = false;
        settings.morph = false;
        const Operation operation = parse_operation(c.op_text);
        // Alternate the three ways so that machine noise falls on all of them.
        for (int i = 0; i < runs; ++i) {
            core.push_back(c.core());
            NullProgress quiet;
            const OperationResult r = run_operation(operation, mesh, quiet, settings);
            op.push_back(r.ms);
            std::vector<std::string> args;
            std::string word;
            for (char ch : c.op_text + " ") {
                if (ch == ' ') {
                    if (!word.empty()) args.push_back(word);
                    word.clear();
                } else {
                    word += ch;
                }
            }
            args.push_back(in);
            args.push_back((tmp / "out.ply").string());
            args.push_back("--json");
            const CliRun run = run_cli(cli, args);
            all_ok = all_ok && run.ok;
            cli_ms.push_back(run.ms);
            peak.push_back(run.peak_mb);
        }
        const double mc = median(core), mo = median(op), ml = median(cli_ms);
        std::string floors;
        char buf[200];
        const bool layer_ok = ml <= 1.2 * mc;
        std::snprintf(buf, sizeof buf, "cli/core <= 1.2 %s", layer_ok ? "met" : "MISSED");
        floors = buf;
        if (c.floor_ms > 0) {
            std::snprintf(buf, sizeof buf, "; < %.0f ms %s", c.floor_ms,
                          ml < c.floor_ms ? "met" : "MISSED");
            floors += buf;
        }
        if (c.peer_ms) {
            const double ratio = *c.peer_ms / ml;
            std::snprintf(buf, sizeof buf, "; %s %.0f ms: %.2fx (floor %.1fx) %s",
                          c.peer_name.c_str(), *c.peer_ms, ratio, c.peer_floor,
                          ratio >= c.peer_floor ? "met" : "MISSED");
            floors += buf;
        }
        std::printf("%-30s %9.1f %9.1f %9.1f %7.2f %7.2f %9.0f  %s\n", c.name.c_str(), mc, mo, ml,
                    mo / mc, ml / mc, median(peak), floors.c_str());
    }
    // Peak memory of 1 against 10 explicit iterations through the CLI.
    const CliRun one = run_cli(
        cli, {"smooth", "--iterations", "1", big_ply, (tmp / "out.ply").string(), "--json"});
    const CliRun ten = run_cli(
        cli, {"smooth", "--iterations", "10", big_ply, (tmp / "out.ply").string(), "--json"});
    std::printf(
        "\nsmooth peak memory through the CLI: 1 iteration %.0f MB, 10 iterations %.0f MB: "
        "%.2fx (floor 1.5x) %s\n",
        one.peak_mb, ten.peak_mb, ten.peak_mb / one.peak_mb,
        ten.peak_mb <= 1.5 * one.peak_mb ? "met" : "MISSED");
    std::error_code ec;
    fs::remove_all(tmp, ec);
    return all_ok ? 0 : 1;
}
