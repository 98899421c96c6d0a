// Frequency-decomposition benchmark (not a test): the three cases with
// core/algorithms/spectral.h, median wall time and the ratio to each floor.
//
//   trilab_spectral_bench [--runs N] [--check] [--operator OP] [--band-size B] [--krylov F]
//                         [--tol T] [--threads T] [--skip-1000] [--baseline]
//
//  - 150 lowest frequencies of the reference's 11,610-vertex cow: ../shared/meshes/cow.obj
//    (the loader splits its one non-manifold vertex: 2,904 vertices, checked) Loop-subdivided
//    once (11,610 vertices, checked). Floor 1 s (the reference program: about 15 minutes).
//  - 150 lowest frequencies of the Stanford bunny (34,834 vertices in faces, 1,113 isolated
//    ones left out). Floor 4 s.
//  - 1,000 lowest frequencies of the bunny, band by band, progress on stderr; one run.
//    Floor 120 s.
// Medians over N runs (default 3) of one decompose() call each (operator build, shifts,
// factorizations, Lanczos, coefficients; loading and subdividing are not timed). The
// operator is the cotangent curvature flow by default (--operator names another). The
// figures are wall-clock times: run it on an otherwise idle machine (the CPU time of the
// process is printed too). --check exits non-zero when a floor is missed. --baseline adds the
// 150-frequency cases computed as one band (about the straightforward solver) for comparison;
// --band-size, --krylov and --tol override the solver's band size, Krylov factor and
// Lanczos tolerance; --threads 1 turns spectrum slicing off (default: two threads when the
// machine has two cores). With two slices the CPU time exceeds the wall time, and the
// factorization and solve times are summed over both threads.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <string>
#include <vector>

#include "app/platform/heap_tuning.h"
#include "core/algorithms/spectral.h"
#include "core/algorithms/subdivision.h"
#include "core/io/mesh_io.h"
#include "core/progress.h"

using namespace trilab;

namespace {

/// Prints the stage and percentage to stderr when they change.
class PrintProgress final : public Progress {
public:
    void report(double fraction, const char* stage) override {
        const int pct = fraction < 0 ? -1 : int(fraction * 100);
        if (pct == last_) return;
        last_ = pct;
        std::fprintf(stderr, "\r    %3d%%  %-40s", pct, stage);
        std::fflush(stderr);
    }
    bool cancel_requested() const override { return false; }
    ~PrintProgress() override { std::fprintf(stderr, "\n"); }

private:
    int last_ = -2;
};

struct Case {
    std::string name;
    const HalfedgeMesh* mesh;
    std::size_t k;
    double floor_ms;
    int runs;
};

}  // namespace

int main(int argc, char** argv) {
    tune_heap_for_large_meshes();
    int runs = 3;
    bool check = false, skip_1000 = false, baseline = false, cow_only = false;
    SpectralOptions base;
    base.op = LaplacianOperator::CurvatureFlow;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--runs" && i + 1 < argc)
            runs = std::max(1, std::atoi(argv[++i]));
        else if (a == "--check")
            check = true;
        else if (a == "--baseline")
            baseline = true;
        else if (a == "--skip-1000")
            skip_1000 = true;
        else if (a == "--cow-only")
            cow_only = true;
        else if (a == "--solver" && i + 1 < argc) {
            const std::string v = argv[++i];
            base.solver = v == "block"   ? SpectralSolver::Block
                          : v == "bands" ? SpectralSolver::Bands
                                         : SpectralSolver::Auto;
        } else if (a == "--operator" && i + 1 < argc)
            base.op = parse_laplacian_operator(argv[++i]);
        else if (a == "--tol" && i + 1 < argc)
            base.tolerance = std::atof(argv[++i]);
        else if (a == "--krylov" && i + 1 < argc)
            base.krylov_factor = std::atof(argv[++i]);
        else if (a == "--band-size" && i + 1 < argc)
            base.band_size = std::size_t(std::atoi(argv[++i]));
        else if (a == "--threads" && i + 1 < argc)
            base.threads = std::size_t(std::atoi(argv[++i]));
        else {
            std::fprintf(stderr,
                         "usage: trilab_spectral_bench [--runs N] [--check] [--operator OP] "
                         "[--band-size B] [--krylov F] [--tol T] [--threads T] [--skip-1000] "
                         "[--baseline] [--cow-only] [--solver auto|bands|block]\n");
            return 2;
        }
    }
    const std::string dir = std::string(TRILAB_SHARED_DIR) + "/meshes/";
    HalfedgeMesh cow, bunny;
    try {
        cow = read_mesh(dir + "cow.obj").mesh;
        std::printf("cow.obj: %zu vertices after the loader's repair (expected 2,904)\n",
                    cow.n_vertices());
        if (cow.n_vertices() != 2904) return 1;
        NullProgress none;
        cow = subdivide(cow, SubdivisionOptions{}, none).levels.back().mesh;
        std::printf("cow Loop-subdivided once: %zu vertices (expected 11,610)\n", cow.n_vertices());
        if (cow.n_vertices() != 11610) return 1;
        bunny = read_mesh(dir + "stanford-bunny.obj").mesh;
        std::printf("bunny: %zu vertices\n", bunny.n_vertices());
    } catch (const std::exception& e) {
        std::fprintf(stderr, "cannot load the shared meshes: %s\n", e.what());
        return 1;
    }
    std::printf("operator %s, band size %s, %d runs (median)\n\n", laplacian_operator_name(base.op),
                base.band_size ? std::to_string(base.band_size).c_str() : "auto", runs);

    std::vector<Case> cases = {{"cow 11,610 V, 150 lowest", &cow, 150, 1000, runs},
                               {"bunny 34,834 V, 150 lowest", &bunny, 150, 4000, runs}};
    if (cow_only) cases.pop_back();
    if (!skip_1000 && !cow_only)
        cases.push_back({"bunny 34,834 V, 1,000 lowest", &bunny, 1000, 120000, 1});
    bool ok = true;
    std::printf("%-30s %10s %10s %7s %6s %6s %8s %7s %10s\n", "case", "median ms", "floor ms",
                "ratio", "bands", "facts", "ops", "repairs", "residual");
    for (const Case& c : cases) {
        std::vector<double> t, cpu;
        SpectralDecomposition d;
        for (int r = 0; r < c.runs; ++r) {
            SpectralOptions o = base;
            o.k = c.k;
            const auto t0 = std::chrono::steady_clock::now();
            const std::clock_t c0 = std::clock();
            if (c.k >= 1000) {
                PrintProgress progress;
                d = decompose(*c.mesh, o, progress);
            } else {
                d = decompose(*c.mesh, o);
            }
            t.push_back(
                std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
                    .count());
            cpu.push_back(1000.0 * double(std::clock() - c0) / CLOCKS_PER_SEC);
        }
        std::sort(t.begin(), t.end());
        std::sort(cpu.begin(), cpu.end());
        const double med = t[t.size() / 2];
        ok = ok && med <= c.floor_ms;
        std::printf(
            "%-30s %10.0f %10.0f %7.2f %6zu %6zu %8zu %7zu %10.1e   (runs: %.0f..%.0f ms)\n",
            c.name.c_str(), med, c.floor_ms, med / c.floor_ms, d.report.bands,
            d.report.factorizations, d.report.operations, d.report.repairs, d.report.max_residual,
            t.front(), t.back());
        std::printf(
            "%-30s CPU time median %.0f ms over %zu slice(s) (wall > CPU: the machine is "
            "shared; CPU > wall: both slices ran at once)\n",
            "", cpu[cpu.size() / 2], d.report.slices);
        std::printf(
            "%-30s lambda_0 = %.3g, lambda_%zu = %.6g; last run, summed over threads: "
            "factorizations %.0f ms, solves %.0f ms\n",
            "", d.eigenvalues[0], c.k - 1, d.eigenvalues[Eigen::Index(c.k - 1)], d.report.factor_ms,
            d.report.solve_ms);
        std::fflush(stdout);
    }
    if (baseline) {
        // The same 150-frequency cases as one shift-invert band (nev 150 + a few, ncv ~ 2 nev):
        // close to the straightforward Spectra + SimplicialLDLT solver the issue quotes
        // (0.6 s for 150 frequencies of a 10k-vertex mesh, 4.2 s for the bunny on an idle
        // machine), measured here under the same conditions as the rows above.
        std::printf("\none band (about the straightforward solver), one run each:\n");
        for (const Case& c : cases) {
            if (c.k != 150) continue;
            SpectralOptions o = base;
            o.k = c.k;
            o.band_size = c.k + 8;
            o.threads = 1;
            const auto t0 = std::chrono::steady_clock::now();
            const std::clock_t c0 = std::clock();
            const SpectralDecomposition d = decompose(*c.mesh, o);
            const double wall =
                std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
                    .count();
            const double cpu = 1000.0 * double(std::clock() - c0) / CLOCKS_PER_SEC;
            std::printf("%-30s %10.0f ms wall, %.0f ms CPU, %zu operations\n", c.name.c_str(), wall,
                        cpu, d.report.operations);
        }
    }
    std::printf("\nratio = median / floor (below 1 meets the floor): %s\n",
                ok ? "all floors met" : "a floor was missed");
    return check && !ok ? 1 : 0;
}
