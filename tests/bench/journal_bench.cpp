// The crash journal's cost against an operation (issue 27: at most 5 %). On the bunny (or an
// icosphere when ../shared is absent), N smoothing steps are run and pushed as the viewer
// does; after each push the history is handed to the journal. Measured: the operation's
// time, the caller's time in History::snapshot() + Journal::record() (what the render thread
// pays), and the writer thread's time encoding, writing and syncing (off the caller's
// thread). Exits 1 when the caller's or the writer's encode + write time exceeds 5 % of the
// operation's.
//   trilab_journal_bench [--steps N] [--mesh FILE] [--no-sync]
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>

#include "app/history/journal.h"
#include "app/ops/operation.h"
#include "app/platform/heap_tuning.h"
#include "core/algorithms/generators.h"
#include "core/io/mesh_io.h"
#include "core/progress.h"

using namespace trilab;
using Clock = std::chrono::steady_clock;

static double ms(Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double, std::milli>(b - a).count();
}

/// This thread's CPU time in milliseconds (the wall clock also counts the writer thread
/// running on this core when the machine's cores are busy).
static double thread_cpu_ms() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return double(t.tv_sec) * 1e3 + double(t.tv_nsec) * 1e-6;
}

int main(int argc, char** argv) {
    tune_heap_for_large_meshes();
    int steps = 10;
    bool sync = true;
    std::string mesh_path = std::string(TRILAB_SHARED_DIR) + "/meshes/stanford-bunny.obj";
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--steps" && i + 1 < argc)
            steps = std::atoi(argv[++i]);
        else if (a == "--mesh" && i + 1 < argc)
            mesh_path = argv[++i];
        else if (a == "--no-sync")
            sync = false;
    }
    HalfedgeMesh mesh;
    std::string name = mesh_path;
    if (access(mesh_path.c_str(), R_OK) == 0) {
        mesh = read_mesh(mesh_path).mesh;
    } else {
        mesh = make_icosphere(60);
        name = "icosphere(60) (" + mesh_path + " is absent)";
    }
    char dir_template[] = "/tmp/trilab-journal-bench-XXXXXX";
    const char* dir = mkdtemp(dir_template);
    if (!dir) return 2;
    JournalOptions options;
    options.directory = dir;
    options.sync = sync;
    Journal journal(options);
    History history(std::size_t(-1));
    history.reset(mesh, "Load");
    journal.record(history.snapshot());
    journal.flush();
    const Journal::Stats base = journal.stats();

    const Operation smooth = parse_operation("smooth --iterations 1");
    double op_ms = 0, caller_ms = 0, caller_wall_ms = 0;
    for (int k = 0; k < steps; ++k) {
        NullProgress progress;
        const auto t0 = Clock::now();
        OperationResult r = run_operation(smooth, history.current_mesh(), progress);
        history.push(r.label, r.parameters, r.ms, {std::move(r.steps.back().mesh)},
                     {std::move(r.steps.back().correspondence)}, smooth);
        const auto t1 = Clock::now();
        const double c0 = thread_cpu_ms();
        journal.record(history.snapshot());
        const double c1 = thread_cpu_ms();
        const auto t2 = Clock::now();
        op_ms += ms(t0, t1);
        caller_ms += c1 - c0;
        caller_wall_ms += ms(t1, t2);
        journal.flush();  // one record per step, as when operations are seconds apart
    }
    const Journal::Stats s = journal.stats();
    const double encode = s.encode_ms - base.encode_ms, write = s.write_ms - base.write_ms,
                 syncing = s.sync_ms - base.sync_ms;
    journal.close();
    rmdir(dir);
    std::printf("journal on %s (%zu vertices), %d smoothing steps, sync %s\n", name.c_str(),
                mesh.n_vertices(), steps, sync ? "on" : "off");
    std::printf("  operation (run + push)    %8.3f ms/step\n", op_ms / steps);
    std::printf("  caller: snapshot + record %8.4f ms/step CPU (%.3f %%), %.4f ms wall\n",
                caller_ms / steps, 100 * caller_ms / op_ms, caller_wall_ms / steps);
    std::printf("  writer: encode + write    %8.3f ms/step  (%.2f %%)\n", (encode + write) / steps,
                100 * (encode + write) / op_ms);
    std::printf("  writer: fdatasync         %8.3f ms/step  (waits on the disk, off the caller)\n",
                syncing / steps);
    std::printf("  journal bytes per step    %8zu (positions %zu)\n",
                (s.bytes - base.bytes) / std::size_t(steps), mesh.vertices_size() * 24);
    const bool ok = caller_ms <= 0.05 * op_ms && encode + write <= 0.05 * op_ms;
    std::printf("%s: the journal costs at most 5 %% of the operation\n", ok ? "PASS" : "FAIL");
    return ok ? 0 : 1;
}
