#!/usr/bin/env bash
# Hole filling against CGAL (issue 41): trilab-cli fill-holes and CGAL 5's
# triangulate_refine_and_fair_hole side by side on the Stanford bunny's five holes (time, closed
# or not, smallest new angle), then trilab alone on a hole of 5,004 boundary vertices.
#   tests/bench/hole_filling_bench.sh [BUILD_DIR]      (default: build)
# Set-up: installs libcgal-dev with apt-get when it is missing (the peer only; trilab never
# links CGAL) and builds tests/bench/hole_filling/cgal_fill_holes.cpp into BUILD_DIR. "ms" is
# the filling alone for both (reading and writing excluded): trilab's --json "ms", the median
# of 5 runs each. Floors (exit 1 when missed): the bunny's five holes under 100 ms, the
# 5,004-vertex hole under 1,000 ms and triangulated over its Delaunay edges (Zou, Ju and Carr
# 2013; not cut by chords), every fill closed, the C1 and C2 fills at least as smooth across their
# rim as CGAL's, over the five together and hole by hole (rim_jump_deg: the mean dihedral angle
# across the rim edges minus the mean over
# the old edges at the rim vertices; `cgal_fill_holes --rim` measures trilab's fill the same way).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/../.."
build="${1:-build}"
cli="$build/trilab-cli"
bunny=../shared/meshes/stanford-bunny.obj
runs=5
[ -x "$cli" ] || { echo "hole_filling_bench: build trilab-cli first ($cli)" >&2; exit 2; }
[ -f "$bunny" ] || { echo "hole_filling_bench: SKIP: $bunny is absent" >&2; exit 0; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# ---- set-up: the peer ------------------------------------------------------------------------
if ! dpkg -s libcgal-dev > /dev/null 2>&1; then
    echo "installing libcgal-dev (the benchmark's peer; not a trilab dependency)"
    sudo apt-get install -y libcgal-dev > /dev/null
fi
cgal="$build/cgal_fill_holes"
if [ ! -x "$cgal" ] || [ tests/bench/hole_filling/cgal_fill_holes.cpp -nt "$cgal" ]; then
    echo "building $cgal"
    nice -n 19 g++ -O2 -DNDEBUG -std=c++17 -I/usr/include/eigen3 \
        tests/bench/hole_filling/cgal_fill_holes.cpp -o "$cgal" -lgmp -lmpfr
fi

# The median "ms" and the last run's JSON of `trilab-cli fill-holes IN OUT ARGS...`.
trilab_runs() {
    local in="$1" out="$2"
    shift 2
    for _ in $(seq "$runs"); do "$cli" fill-holes "$in" "$out" "$@" --json; done > "$work/runs.json"
    python3 - "$work/runs.json" << 'PY'
import json, sys
runs = [json.loads(line) for line in open(sys.argv[1])]
ms = sorted(r["ms"] for r in runs)
last = runs[-1]
print(json.dumps({"loops": last["loops_found"], "filled": last["loops_filled"],
                  "ms": round(ms[len(ms) // 2], 2), "faces_added": last["faces_added"],
                  "vertices_added": last["vertices_added"],
                  "min_new_angle_deg": round(last["min_new_angle_deg"], 2),
                  "new_angles_under_20": last["new_angles_under_20"],
                  "loops_delaunay": last.get("loops_delaunay", 0),
                  "loops_cut": last["loops_cut"]}))
PY
}
closed() { "$cli" info "$1" --json | python3 -c 'import json,sys; print(str(json.load(sys.stdin)["boundary_loops"] == 0).lower())'; }

echo "load average: $(cut -d' ' -f1-3 /proc/loadavg) ($(nproc) cores); median of $runs runs each"
echo "== the Stanford bunny (five holes: 22, 39, 40, 42, 80 edges) =="
# OBJ outputs: their positions read back bit for bit, so --rim can tell the new faces.
t1=$(trilab_runs "$bunny" "$work/bunny-c1.obj" --fairing c1)
t2=$(trilab_runs "$bunny" "$work/bunny-c2.obj" --fairing c2)
c=$("$cgal" "$bunny" "$runs")
echo "trilab c1: $t1, closed: $(closed "$work/bunny-c1.obj")"
r1=$("$cgal" --rim "$bunny" "$work/bunny-c1.obj")
echo "           rim: $r1"
echo "trilab c2: $t2, closed: $(closed "$work/bunny-c2.obj")"
r2=$("$cgal" --rim "$bunny" "$work/bunny-c2.obj")
echo "           rim: $r2"
echo "CGAL     : $c"

echo "== a hole of 5,004 boundary vertices (a 2 x 2,500 slot in an arched grid) =="
python3 - "$work/slot.obj" << 'PY'
import math, sys
nx, ny = 2601, 11   # vertices; spacing 1
with open(sys.argv[1], "w") as f:
    for j in range(ny):
        for i in range(nx):
            f.write("v %d %d %.6f\n" % (i, j, 300 * math.sin(math.pi * i / (nx - 1))))
    for j in range(ny - 1):
        for i in range(nx - 1):
            if 50 <= i < 2550 and 4 <= j < 6:
                continue  # the slot
            a = j * nx + i + 1
            f.write("f %d %d %d\nf %d %d %d\n" % (a, a + 1, a + nx + 1, a, a + nx + 1, a + nx))
PY
s=$(trilab_runs "$work/slot.obj" "$work/slot-filled.ply" --max-edges 10000 --loops 1)
echo "trilab c1: $s, closed slot: $("$cli" info "$work/slot-filled.ply" --json | python3 -c 'import json,sys; print(json.load(sys.stdin)["boundary_loops"] == 1)')"

python3 - "$t1" "$t2" "$s" "$r1" "$r2" "$c" << 'PY'
import json, sys
t1, t2, s, r1, r2, c = (json.loads(a) for a in sys.argv[1:7])
fails = []
# Rim smoothness over the five fills together and hole by hole (a fill is matched to CGAL's by
# its first rim point, an input position both outputs keep).
def same_key(a, b):
    return all(abs(x - y) <= 1e-6 * max(1.0, abs(x)) for x, y in zip(a, b))
for name, r in (("bunny c1", r1), ("bunny c2", r2)):
    if r["rim_jump_deg"] > c["rim_jump_deg"]:
        fails.append("%s: rim jump %.2f deg, CGAL's is %.2f" % (name, r["rim_jump_deg"], c["rim_jump_deg"]))
    if len(r["holes"]) != len(c["holes"]):
        fails.append("%s: %d fills, CGAL has %d" % (name, len(r["holes"]), len(c["holes"])))
        continue
    for k, (h, g) in enumerate(zip(r["holes"], c["holes"])):
        if not same_key(h["key"], g["key"]):
            fails.append("%s: hole %d is not CGAL's hole %d" % (name, k, k))
        elif h["rim_jump_deg"] > g["rim_jump_deg"]:
            fails.append("%s, hole at %s: rim jump %.2f deg, CGAL's is %.2f" %
                         (name, h["key"], h["rim_jump_deg"], g["rim_jump_deg"]))
        print("%s hole %d: rim jump %.2f deg, CGAL's %.2f" % (name, k, h["rim_jump_deg"], g["rim_jump_deg"]))
for name, r in (("bunny c1", t1), ("bunny c2", t2)):
    if r["filled"] != 5: fails.append(name + ": not all five holes filled")
    if r["ms"] >= 100: fails.append(name + ": %.1f ms, the floor is 100 ms" % r["ms"])
if s["filled"] != 1: fails.append("slot: not filled")
if s["ms"] >= 1000: fails.append("slot: %.1f ms, the floor is 1000 ms" % s["ms"])
if s["loops_delaunay"] != 1: fails.append("slot: not triangulated over its Delaunay edges (Zou et al.)")
for f in fails: print("FLOOR MISSED: " + f)
print("floors: " + ("all met" if not fails else "%d missed" % len(fails)))
sys.exit(1 if fails else 0)
PY
