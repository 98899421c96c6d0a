#!/usr/bin/env bash
# The Python module's cost over the core (issue 42: under 5 % on the 1.1M-face bunny, for
# smoothing and subdivision). The 35k-face Stanford bunny Loop-subdivided twice (557,164
# vertices, 1,111,216 faces) is made once with trilab-cli; then, for each case, RUNS pairs in
# turn (CLI, Python, CLI, Python, ...: pairing keeps the ratios meaningful on a loaded machine):
#   cli:  `trilab-cli OP ... --json`, its "ms" (the operation itself; reading and writing
#         excluded): what run_operation() costs in the CLI;
#   py:   in one python3 process, the wall time of the method call `m.OP(...)` (the options
#         turned into the CLI's and parsed, the run with the GIL released, the result wrapped
#         as a Mesh, the report dict), the mesh loaded once before;
#   core: that call's own Mesh.ms (the same figure as the CLI's "ms": the algorithm itself);
#   run:  that call's Mesh.run_ms (the whole run_operation(): the algorithm plus the operation
#         layer's report figures, e.g. smooth's smoothing distances, which the CLI computes too,
#         outside its "ms").
# It prints the medians and the overheads: py/run - 1 (the binding alone: the same call, the
# same process), py/core - 1, and the median of the pairs' py/cli - 1 (against the CLI's "ms";
# noisier: two processes). Quote the load average it prints.
#   tests/bench/bench_python.sh [BUILD_DIR] [RUNS]      (from the repository root)
# Needs ../shared/meshes (skips, saying so, without it) and the module built (trilab_python).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/../.."
build="${1:-build}"
runs="${2:-5}"
cli="$build/trilab-cli"
python=/usr/bin/python3
bunny=../shared/meshes/stanford-bunny.obj
[ -x "$cli" ] || { echo "bench_python: build trilab-cli first ($cli)" >&2; exit 2; }
ls "$build"/python/trilab*.so >/dev/null 2>&1 ||
    { echo "bench_python: build trilab_python first" >&2; exit 2; }
[ -f "$bunny" ] || { echo "bench_python: skipped: $bunny is absent"; exit 0; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
big="$work/bunny_loop2.ply"
"$cli" subdivide --iterations 2 "$bunny" "$big" >/dev/null
echo "bench_python: $(uname -n), $(nproc) cores, load average $(cut -d' ' -f1-3 /proc/loadavg)," \
    "$runs pairs per case"

PYTHONPATH="$build/python" "$python" - "$cli" "$big" "$work/out.ply" "$runs" <<'PY'
import json, statistics, subprocess, sys, time
import trilab

cli, big, out, runs = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4])
CASES = [  # name, operation, CLI options, keyword arguments
    ("smooth implicit", "smooth",
     ["--operator", "curvature-flow", "--integration", "implicit", "--step", "5"],
     dict(operator="curvature-flow", integration="implicit", step=5)),
    ("smooth explicit x5", "smooth", ["--iterations", "5"], dict(iterations=5)),
    ("subdivide loop", "subdivide", ["--scheme", "loop"], dict(scheme="loop")),
]
m = trilab.load(big)
print(f"{m.n_faces} faces; trilab {trilab.__version__}")
print(f"{'case':20} {'cli ms':>9} {'py ms':>9} {'run ms':>9} {'core ms':>9} {'py/run':>8} "
      f"{'py/core':>8} {'py/cli':>8}")
for name, op, args, kwargs in CASES:
    cli_ms, py_ms, run_ms, core_ms, pairs = [], [], [], [], []
    for _ in range(runs):
        r = subprocess.run([cli, op, *args, big, out, "--json"], check=True,
                           capture_output=True, text=True)
        cli_ms.append(json.loads(r.stdout)["ms"])
        t = time.perf_counter()
        result = getattr(m, op)(**kwargs)
        py_ms.append((time.perf_counter() - t) * 1000)
        core_ms.append(result.ms)
        run_ms.append(result.run_ms)
        pairs.append(py_ms[-1] / cli_ms[-1])
        del result
    med = statistics.median
    binding = med(p / r for p, r in zip(py_ms, run_ms)) - 1
    over_core = med(p / c for p, c in zip(py_ms, core_ms)) - 1
    print(f"{name:20} {med(cli_ms):9.1f} {med(py_ms):9.1f} {med(run_ms):9.1f} "
          f"{med(core_ms):9.1f} {binding * 100:7.2f}% {over_core * 100:7.1f}% "
          f"{(med(pairs) - 1) * 100:7.1f}%")
PY
