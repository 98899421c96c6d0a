// Fairing benchmark (not a test): times core/algorithms/fairing.h's smooth() on the shared Stanford
// bunny (35,947 vertices), on the bunny Loop-subdivided twice (556k vertices, the large
// mesh) and on a torus of 1,000,000 vertices, and prints medians against the floors:
//   - one explicit umbrella iteration on 1M vertices under 50 ms;
//   - one implicit cotangent step on the bunny under 150 ms, factorization included;
//   - one implicit step on the 556k-vertex mesh under 1.5 s;
// and the ratio of one implicit step to 20 explicit iterations (the reference found ~15x).
//
//   trilab_fairing_bench [--runs N] [--check] [--quick]
//
// A timed call is one smooth() call on a mesh already in memory, with keep_steps off (only
// the result is kept, as trilab-cli smooth does) and the stable-step estimate off (its rows
// time max_stable_explicit_step() on its own); "per iteration" divides a 10-iteration
// call by 10. Every explicit operator, and every implicit operator with each solver (the
// sparse Cholesky with its factorization and solve timed apart, the conjugate gradients, and
// the automatic choice), is timed (on the large mesh, the sparse Cholesky only through the
// automatic choice, and CG only where that choice is CG; -1 marks a column not timed). --quick uses
// a 40k-vertex torus instead of the large meshes (for a smoke run); --check exits non-zero when a
// floor is missed.
//
// Peers, compiled in when found at configure time (benchmark-only, see
// third_party/cmake/dependencies.cmake): OpenMesh 9's JacobiLaplaceSmootherT (uniform and
// cotangent, 10 iterations, tangential and normal, no boundary fixing needed on closed
// meshes) on the 556k mesh (aim: trilab 3x faster), and CGAL 5.5's smooth_shape (one
// implicit mean-curvature-flow step) on the bunny (aim: 2x).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "app/platform/heap_tuning.h"
#include "core/algorithms/fairing.h"
#include "core/algorithms/generators.h"
#include "core/algorithms/subdivision.h"
#include "core/io/mesh_io.h"
#include "core/progress.h"
#include "fairing_bench_peers.h"

using namespace trilab;

namespace {

using Clock = std::chrono::steady_clock;

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/// CPU time of this process (user + system) in milliseconds: on a machine shared with other
/// jobs it is steadier than the wall clock (all of trilab's work here is single-threaded).
double cpu_ms() {
    return 1000.0 * double(std::clock()) / CLOCKS_PER_SEC;
}

double g_last_cpu_ms = 0;  ///< the CPU-time median of the last time_ms() call

/// Median wall-clock milliseconds of `runs` calls after a warm-up (CPU median in
/// g_last_cpu_ms).
double time_ms(const std::function<void()>& f, int runs) {
    f();  // warm-up
    std::vector<double> t, c;
    for (int i = 0; i < runs; ++i) {
        const double c0 = cpu_ms();
        const auto t0 = Clock::now();
        f();
        t.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
        c.push_back(cpu_ms() - c0);
    }
    g_last_cpu_ms = median(c);
    return median(t);
}

FairingOptions options(FairingOperator op, Integration integration, double step, int iterations,
                       ImplicitSolver solver = ImplicitSolver::Auto) {
    FairingOptions o;
    o.op = op;
    o.integration = integration;
    o.step = step;
    o.iterations = iterations;
    o.solver = solver;
    o.keep_steps = false;
    o.estimate_max_stable_step = false;  // timed on its own (stable-step rows)
    return o;
}

const FairingOperator kOperators[] = {FairingOperator::Umbrella, FairingOperator::ImprovedUmbrella,
                                      FairingOperator::CurvatureFlow, FairingOperator::SecondOrder,
                                      FairingOperator::Taubin};

struct Floors {
    bool ok = true;
    void check(const char* what, double ms, double cpu, double floor_ms) {
        const bool met = ms < floor_ms;
        ok = ok && met;
        std::printf("  floor %-50s %8.1f ms (cpu %8.1f) < %6.0f ms  ratio %5.2f  %s\n", what, ms,
                    cpu, floor_ms, floor_ms / ms, met ? "met" : "MISSED");
    }
};

/// Times every explicit operator (1 iteration and 10 iterations) on `mesh`.
void explicit_table(const char* name, const HalfedgeMesh& mesh, int runs) {
    std::printf("\n%s (%zu vertices): explicit, step 0.5\n", name, mesh.n_vertices());
    std::printf("  %-18s %12s %16s\n", "operator", "1 call", "per iter (x10)");
    for (FairingOperator op : kOperators) {
        const double one =
            time_ms([&] { smooth(mesh, options(op, Integration::Explicit, 0.5, 1)); }, runs);
        const double ten =
            time_ms([&] { smooth(mesh, options(op, Integration::Explicit, 0.5, 10)); }, runs);
        std::printf("  %-18s %9.1f ms %13.1f ms\n", fairing_operator_name(op), one, ten / 10);
    }
}

/// Times one implicit step of every operator with each solver on `mesh`.
void implicit_table(const char* name, const HalfedgeMesh& mesh, int runs, bool with_direct) {
    std::printf("\n%s (%zu vertices): one implicit step, step 1\n", name, mesh.n_vertices());
    std::printf("  %-18s %10s %10s %10s %10s %10s  %s\n", "operator", "auto", "LDLT", "factor",
                "solve", "CG", "auto ran");
    for (FairingOperator op : kOperators) {
        if (op == FairingOperator::Taubin) continue;
        FairingResult last;
        const double autom =
            time_ms([&] { last = smooth(mesh, options(op, Integration::Implicit, 1.0, 1)); }, runs);
        double direct = 0, factor = 0, solve = 0;
        if (with_direct) {
            FairingResult d;
            direct = time_ms(
                [&] {
                    d = smooth(mesh,
                               options(op, Integration::Implicit, 1.0, 1, ImplicitSolver::Direct));
                },
                runs);
            factor = d.factorization_ms;
            solve = d.solve_ms;
        }
        // Where the automatic choice is the factorization (a scale-dependent operator whose
        // system is badly conditioned), CG on a large mesh takes minutes: not timed there.
        double cg = -1;
        if (with_direct || last.solver == "ConjugateGradient(Jacobi)")
            cg = time_ms(
                [&] {
                    smooth(mesh,
                           options(op, Integration::Implicit, 1.0, 1, ImplicitSolver::Iterative));
                },
                runs);
        std::printf("  %-18s %7.1f ms %7.1f ms %7.1f ms %7.1f ms %7.1f ms  %s\n",
                    fairing_operator_name(op), autom, direct, factor, solve, cg,
                    last.solver.c_str());
    }
}

}  // namespace

int main(int argc, char** argv) {
    int runs = 5;
    bool check = false, quick = false;
    for (int i = 1; i < argc; ++i) {
        if (!std::strcmp(argv[i], "--runs") && i + 1 < argc)
            runs = std::max(1, std::atoi(argv[++i]));
        else if (!std::strcmp(argv[i], "--check"))
            check = true;
        else if (!std::strcmp(argv[i], "--quick"))
            quick = true;
        else {
            std::fprintf(stderr, "usage: trilab_fairing_bench [--runs N] [--check] [--quick]\n");
            return 2;
        }
    }
    std::setvbuf(stdout, nullptr, _IOLBF, 0);  // lines appear as they are measured
    tune_heap_for_large_meshes();
    Floors floors;

    const std::filesystem::path bunny_path =
        std::filesystem::path(TRILAB_SHARED_DIR) / "meshes" / "stanford-bunny.obj";
    HalfedgeMesh bunny, large;
    const bool have_bunny = std::filesystem::exists(bunny_path);
    if (have_bunny) {
        bunny = read_mesh(bunny_path.string()).mesh;
    } else {
        std::printf("%s not found: the bunny rows are skipped and the large mesh is a torus\n",
                    bunny_path.string().c_str());
    }
    const HalfedgeMesh huge =
        quick ? make_torus(200, 200, 1.0, 0.3) : make_torus(1000, 1000, 1.0, 0.3);
    if (quick) {
        large = make_torus(200, 200, 1.0, 0.3);
    } else if (have_bunny) {
        SubdivisionOptions so;
        so.scheme = SubdivisionScheme::Loop;
        so.iterations = 2;
        NullProgress np;
        large = subdivide(bunny, so, np).levels.back().mesh;
    } else {
        large = make_torus(745, 745, 1.0, 0.3);
    }
    std::printf("trilab_fairing_bench: medians of %d runs after one warm-up\n", runs);

    // Explicit iterations.
    if (have_bunny) explicit_table("bunny", bunny, runs);
    explicit_table(quick ? "torus 40k" : "large", large, runs);
    const double umbrella_huge_10 = time_ms(
        [&] { smooth(huge, options(FairingOperator::Umbrella, Integration::Explicit, 0.5, 10)); },
        runs);
    const double umbrella_huge_10_cpu = g_last_cpu_ms;
    const double umbrella_huge_1 = time_ms(
        [&] { smooth(huge, options(FairingOperator::Umbrella, Integration::Explicit, 0.5, 1)); },
        runs);
    const double umbrella_huge_1_cpu = g_last_cpu_ms;
    // The cost of one more iteration, without the call's fixed part (copying the input mesh,
    // building the operator's pattern, volumes): (10 iterations - 1 iteration) / 9.
    const double marginal = (umbrella_huge_10 - umbrella_huge_1) / 9;
    const double marginal_cpu = (umbrella_huge_10_cpu - umbrella_huge_1_cpu) / 9;
    std::printf(
        "\ntorus (%zu vertices): explicit umbrella: 1 call %.1f ms, 10 iterations %.1f ms "
        "(%.1f per iteration), one more iteration %.1f ms\n",
        huge.n_vertices(), umbrella_huge_1, umbrella_huge_10, umbrella_huge_10 / 10, marginal);

    // The stable-step estimate (20 Lanczos products; smooth() runs it by default).
    std::printf("\nlargest stable explicit step (max_stable_explicit_step, 20 Lanczos steps):\n");
    for (const auto& [name, mesh] : {std::pair<const char*, const HalfedgeMesh*>{"bunny", &bunny},
                                     {quick ? "torus 40k" : "large", &large}}) {
        if (mesh->n_vertices() == 0) continue;
        for (FairingOperator op : {FairingOperator::Umbrella, FairingOperator::CurvatureFlow,
                                   FairingOperator::SecondOrder}) {
            double limit = 0;
            // (a structured binding is captured by name only from C++20 on: copy the pointer)
            const double ms =
                time_ms([&, m = mesh] { limit = max_stable_explicit_step(*m, op); }, runs);
            std::printf("  %-10s %-16s %8.1f ms  limit %.4g\n", name, fairing_operator_name(op), ms,
                        limit);
        }
    }

    // Implicit steps.
    if (have_bunny) implicit_table("bunny", bunny, runs, true);
    implicit_table(quick ? "torus 40k" : "large", large, quick ? runs : std::min(runs, 3), quick);

    std::printf("\nfloors:\n");
    floors.check("explicit umbrella iteration, 1M vertices", marginal, marginal_cpu, 50);
    std::printf(
        "  (per iteration of a 10-iteration call, fixed part included: %.1f ms, cpu "
        "%.1f; a 1-iteration call: %.1f ms, cpu %.1f)\n",
        umbrella_huge_10 / 10, umbrella_huge_10_cpu / 10, umbrella_huge_1, umbrella_huge_1_cpu);
    if (have_bunny) {
        const double imp = time_ms(
            [&] {
                smooth(bunny,
                       options(FairingOperator::CurvatureFlow, Integration::Implicit, 1.0, 1));
            },
            runs);
        floors.check("implicit cotangent step, bunny, incl. factorization", imp, g_last_cpu_ms,
                     150);
        const double exp20 = time_ms(
            [&] {
                smooth(bunny,
                       options(FairingOperator::CurvatureFlow, Integration::Explicit, 0.5, 20));
            },
            runs);
        std::printf(
            "  implicit cotangent step / 20 explicit iterations: %.1f / %.1f ms = %.2f "
            "(reference: about 15)\n",
            imp, exp20, imp / exp20);
        const double direct = time_ms(
            [&] {
                smooth(bunny, options(FairingOperator::CurvatureFlow, Integration::Implicit, 1.0, 1,
                                      ImplicitSolver::Direct));
            },
            runs);
        std::printf("  the same with the sparse Cholesky forced: %.1f / %.1f ms = %.2f\n", direct,
                    exp20, direct / exp20);
    }
    for (FairingOperator op : {FairingOperator::Umbrella, FairingOperator::CurvatureFlow}) {
        const double imp = time_ms(
            [&] { smooth(large, options(op, Integration::Implicit, 1.0, 1)); }, std::min(runs, 3));
        const std::string what = std::string("implicit ") + fairing_operator_name(op) + " step, " +
                                 std::to_string(large.n_vertices()) + " vertices";
        floors.check(what.c_str(), imp, g_last_cpu_ms, 1500);
    }

    run_peers(have_bunny ? &bunny : nullptr, large, runs);
    if (check && !floors.ok) return 1;
    return 0;
}
