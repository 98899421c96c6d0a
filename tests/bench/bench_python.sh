#!/usr/bin/env bash
# The Python module's cost over the core (issue 42: under 5 % on the 1.1M-face bunny, for
# smoothing and subdivision). The 35k-face Stanford bunny Loop-subdivided twice (557,164
# vertices, 1,111,216 faces) is made once with trilab-cli. For each case, in turn, RUNS times:
#   cli: `trilab-cli OP ... --json`, its "ms" (the operation itself, reading and writing
#        excluded: what run_operation() costs);
#   py:  in one python3 process, the wall time of the method call `m.OP(...)` (parsing the
#        options, running with the GIL released, wrapping the result as a Mesh, the report
#        dict), the mesh loaded once before.
# and prints both medians and their ratio (py / cli - 1). Timings are the user's wait; the
# machine is shared: run it on a quiet machine, and quote the load average it prints.
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
echo "bench_python: $(uname -n), load average $(cut -d' ' -f1-3 /proc/loadavg), $runs runs"

# case name | operation | CLI options | Python keyword arguments
cases=(
    "smooth implicit|smooth|--operator curvature-flow --integration implicit --step 5|operator='curvature-flow', integration='implicit', step=5"
    "smooth explicit x5|smooth|--iterations 5|iterations=5"
    "subdivide loop|subdivide|--scheme loop|scheme='loop'"
)
printf '%-20s %12s %12s %9s\n' case "cli ms" "python ms" "overhead"
for c in "${cases[@]}"; do
    IFS='|' read -r name op args kwargs <<<"$c"
    cli_ms=()
    for _ in $(seq "$runs"); do
        # shellcheck disable=SC2086
        cli_ms+=("$("$cli" "$op" $args "$big" "$work/out.ply" --json |
            "$python" -c 'import json,sys; print(json.load(sys.stdin)["ms"])')")
    done
    py_ms=$(PYTHONPATH="$build/python" "$python" - "$big" "$runs" <<PY
import statistics, sys, time
import trilab
m = trilab.load(sys.argv[1])
times = []
for _ in range(int(sys.argv[2])):
    t = time.perf_counter()
    r = m.$op($kwargs)
    times.append((time.perf_counter() - t) * 1000)
    del r
print(statistics.median(times))
PY
)
    cli_median=$(printf '%s\n' "${cli_ms[@]}" | "$python" -c 'import statistics,sys; print(statistics.median(float(x) for x in sys.stdin))')
    "$python" -c "import sys; c, p = float(sys.argv[2]), float(sys.argv[3]); print('%-20s %12.1f %12.1f %8.1f%%' % (sys.argv[1], c, p, (p / c - 1) * 100))" "$name" "$cli_median" "$py_ms"
done
