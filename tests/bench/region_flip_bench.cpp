// Flip on a region against flip on the whole mesh, as the viewer runs them (issue 26: a region
// costs no more than the whole mesh). The session (app/session, the viewer's model without
// its window) loads the bunny, selects the region, and runs `flip` N times on the region and
// N times on the whole mesh, alternating, each undone after; the figure is each run's own
// time (the history entry's "ms", what the status line shows). The viewer keeps its state's
// component labels from the statistics it computes for every state, so the region's flip does
// not search for the components; `trilab-cli flip --region` does (a fresh process knows
// nothing of the mesh), which docs/benchmarks.md measures beside this.
//   trilab_region_flip_bench [--runs N] [--mesh FILE] [--region SPEC]
// Exits 1 when the region's median exceeds the whole mesh's.
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "app/ops/operation.h"
#include "app/platform/heap_tuning.h"
#include "app/session/session.h"

using namespace trilab;
using namespace trilab::viewer;

namespace {

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
}

/// Runs flip on the session's current selection (or the whole mesh), returns its "ms", undoes.
double flip_ms(Session& s) {
    s.execute(RunOperation{parse_operation("flip")});
    s.finish_jobs();
    const double ms = s.history().info(s.history().current()).ms;
    s.execute(Undo{});
    return ms;
}

}  // namespace

int main(int argc, char** argv) {
    tune_heap_for_large_meshes();
    int runs = 25;
    std::string mesh_path = std::string(TRILAB_SHARED_DIR) + "/meshes/stanford-bunny.obj";
    std::string region = "sphere:-0.02,0.11,0,0.05";
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--runs" && i + 1 < argc)
            runs = std::max(1, std::atoi(argv[++i]));
        else if (a == "--mesh" && i + 1 < argc)
            mesh_path = argv[++i];
        else if (a == "--region" && i + 1 < argc)
            region = argv[++i];
    }
    if (access(mesh_path.c_str(), R_OK) != 0) {
        std::printf("SKIP: %s is absent\n", mesh_path.c_str());
        return 0;
    }
    // The session's log goes to stdout: this program's figures go to the original stdout,
    // the log to /dev/null.
    FILE* report = fdopen(dup(1), "w");
    if (!report || !std::freopen("/dev/null", "w", stdout)) return 2;
    Session s;
    s.execute(LoadFile{mesh_path});
    s.finish_jobs();
    s.execute(SelectSpec{region});
    const std::size_t selected = s.selections().count();
    std::vector<double> on_region, whole;
    flip_ms(s);  // warm-up
    for (int k = 0; k < runs; ++k) {
        on_region.push_back(flip_ms(s));
        s.execute(EditSelection{EditSelection::Kind::Clear});
        whole.push_back(flip_ms(s));
        s.execute(Undo{});  // the selection again
    }
    const double r = median(on_region), w = median(whole);
    std::fprintf(report, "flip on %s (%zu vertices), region %s (%zu selected), %d runs each\n",
                 mesh_path.c_str(), s.mesh().n_vertices(), region.c_str(), selected, runs);
    std::fprintf(report, "  region %8.3f ms   whole %8.3f ms   region / whole %.2f\n", r, w, r / w);
    const bool ok = r <= w;
    std::fprintf(report, "%s: a region costs no more than the whole mesh\n", ok ? "PASS" : "FAIL");
    std::fclose(report);
    return ok ? 0 : 1;
}
