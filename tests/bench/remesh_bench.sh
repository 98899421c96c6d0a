#!/usr/bin/env bash
# Isotropic remeshing against CGAL, side by side (issue 41): the 35k-face Stanford bunny and its
# 1.1M-face Loop x2 refinement, each at L = its mean edge length, 10 iterations.
#   tests/bench/remesh_bench.sh [BUILD_DIR] [bunny|big|both]   (from the repository root)
# Set-up: installs libcgal-dev (apt-get; the peer only, never linked into trilab) and builds
# tests/bench/remesh_cgal.cpp with it. For each mesh and each tool it prints the time of the
# remeshing itself (trilab: `remesh --json` "ms"; CGAL: around isotropic_remeshing()), the share
# of edges within [0.8 L, 4/3 L], the smallest angle, the mean of the per-triangle smallest
# angles, the share of interior vertices of valence 6 (all from `trilab-cli info --quality
# --length L`, the same code for both) and the sampled Hausdorff distance to the input over its
# bounding-box diagonal (`trilab-cli compare`). Then it checks the issue's floors, which the
# issue sets for the 1.1M-face mesh: at least 85 % in the band, a smallest angle of at least 20
# degrees, a mean smallest angle of at least 45, Hausdorff at most 0.1 % of the diagonal, each
# at least as good as CGAL's, and at least 3 times faster than CGAL in the same run; it exits 1
# when one fails there. On the 35k bunny the same checks are printed but do not fail the run
# (its flat base meets the sides at a sharp crease that neither tool keeps without feature
# edges: both land near 0.3 % Hausdorff there). Needs ../shared/meshes.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/../.."
build="${1:-build}"
which="${2:-both}"
cli="$build/trilab-cli"
bunny=../shared/meshes/stanford-bunny.obj
[ -x "$cli" ] || { echo "remesh_bench: build trilab-cli first ($cli)" >&2; exit 2; }
[ -f "$bunny" ] || { echo "remesh_bench: skipped: $bunny is absent" >&2; exit 0; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# ---- set-up: the peer ------------------------------------------------------------------------
if ! dpkg -s libcgal-dev >/dev/null 2>&1; then
    echo "set-up: installing libcgal-dev (the peer, for this benchmark only)"
    sudo_cmd=""
    [ "$(id -u)" -eq 0 ] || sudo_cmd=sudo
    $sudo_cmd apt-get install -y --no-install-recommends libcgal-dev >/dev/null
fi
cgal_bin="$build/remesh_cgal"
if [ ! -x "$cgal_bin" ] || [ tests/bench/remesh_cgal.cpp -nt "$cgal_bin" ]; then
    echo "set-up: building $cgal_bin"
    nice -n 19 g++ -std=c++17 -O2 -DNDEBUG -DCGAL_NDEBUG tests/bench/remesh_cgal.cpp \
        -o "$cgal_bin" -lgmp -lmpfr
fi

json() {  # json FILE KEY [SUBKEY]: one number from a JSON object
    python3 -c "import json,sys; d=json.load(open(sys.argv[1]))
for k in sys.argv[2:]: d=d[k]
print(d)" "$@"
}

# measure NAME INPUT: runs both tools on INPUT and prints their rows; appends the checks.
failures=0
measure() {
    local name="$1" input="$2"
    local off="$work/$name.off"
    "$cli" convert "$input" "$off" >/dev/null
    "$cli" remesh "$input" "$work/$name-trilab.ply" --relative 1 --iterations 10 --json \
        > "$work/$name-trilab.json"
    local length ms_t ms_c
    length=$(json "$work/$name-trilab.json" target_length)
    ms_t=$(json "$work/$name-trilab.json" ms)
    ms_c=$("$cgal_bin" "$off" "$work/$name-cgal.off" "$length" 10 | awk '{print $2}')
    printf '%s (%s faces in), L = %s, 10 iterations, load %s\n' "$name" \
        "$(json "$work/$name-trilab.json" input_faces)" "$length" "$(cut -d' ' -f1-3 /proc/loadavg)"
    printf '  %-7s %10s %8s %8s %10s %12s %9s %12s\n' tool ms faces band% "min angle" \
        "mean min" valence6% "hausdorff%"
    local tool
    for tool in trilab cgal; do
        local out="$work/$name-$tool.ply"
        [ "$tool" = cgal ] && out="$work/$name-cgal.off"
        "$cli" info "$out" --quality --length "$length" --json > "$work/$name-$tool-q.json"
        "$cli" compare "$input" "$out" --json > "$work/$name-$tool-d.json"
        local ms="$ms_t"
        [ "$tool" = cgal ] && ms="$ms_c"
        python3 - "$work/$name-$tool-q.json" "$work/$name-$tool-d.json" "$tool" "$ms" \
            > "$work/$name-$tool.row" <<'PY'
import json, sys
q = json.load(open(sys.argv[1]))
d = json.load(open(sys.argv[2]))
k = q["quality"]
print(sys.argv[3], float(sys.argv[4]), q["faces"], 100 * k["edges_in_band"], k["min_angle"],
      k["mean_min_angle"], 100 * k["valence6"], 100 * d["hausdorff_relative"])
PY
        read -r t ms faces band minang meanmin v6 haus < "$work/$name-$tool.row"
        printf '  %-7s %10.0f %8s %8.2f %10.2f %12.2f %9.2f %12.4f\n' "$t" "$ms" "$faces" \
            "$band" "$minang" "$meanmin" "$v6" "$haus"
    done
    python3 - "$work/$name-trilab.row" "$work/$name-cgal.row" "$name" <<'PY' || [ "$name" != big ] || failures=$((failures + 1))
import sys
t = sys.argv[1]; c = sys.argv[2]; name = sys.argv[3]
tr = open(t).read().split(); cr = open(c).read().split()
ms_t, band_t, min_t, mean_t, v6_t, h_t = map(float, (tr[1], tr[3], tr[4], tr[5], tr[6], tr[7]))
ms_c, band_c, min_c, mean_c, v6_c, h_c = map(float, (cr[1], cr[3], cr[4], cr[5], cr[6], cr[7]))
checks = [
    ("band >= 85 %", band_t >= 85), ("band >= CGAL's", band_t >= band_c),
    ("min angle >= 20", min_t >= 20), ("min angle >= CGAL's", min_t >= min_c),
    ("mean min angle >= 45", mean_t >= 45), ("mean min angle >= CGAL's", mean_t >= mean_c),
    ("valence 6 >= CGAL's", v6_t >= v6_c),
    ("Hausdorff <= 0.1 %", h_t <= 0.1), ("Hausdorff <= CGAL's", h_t <= h_c),
    ("3x faster than CGAL", 3 * ms_t <= ms_c),
]
bad = [n for n, ok in checks if not ok]
print("  %s: speed-up %.2fx; %s" % (name, ms_c / ms_t if ms_t > 0 else float("inf"),
      "every floor holds" if not bad else "FAILED: " + ", ".join(bad)))
sys.exit(1 if bad else 0)
PY
}

if [ "$which" = bunny ] || [ "$which" = both ]; then measure bunny "$bunny"; fi
if [ "$which" = big ] || [ "$which" = both ]; then
    "$cli" subdivide --scheme loop --iterations 2 "$bunny" "$work/big.ply" >/dev/null
    measure big "$work/big.ply"
fi
exit $((failures > 0))
