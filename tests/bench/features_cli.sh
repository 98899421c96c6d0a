#!/usr/bin/env bash
# Features (issue 39) through the command line, each figure a run's own "ms" (`--json`), medians
# of RUNS, every pair alternating in one run on one machine state:
#  - fandisk with its features at 60 degrees (infinitely sharp): Loop x3 with the creases, plain
#    Loop x3 (--features none) and OpenSubdiv 3.5's Loop x3 with the same creases (the oracle
#    program built from tests/oracle/osd_loop_oracle.cpp where libosd-dev is installed, its own
#    "ms": topology, refinement and every level's positions); Sqrt3, Butterfly and Modified
#    Butterfly x3 with and without the creases;
#  - the bunny Loop-subdivided twice (1.1M faces) with 1 % of its edges (every 100th in face
#    order) infinitely sharp: one Loop step with the creases against plain (issue 39: at most
#    1.2 times);
#  - decimation of fandisk to 5, 10 and 20 % with its features kept against without: the
#    Hausdorff distance to the input (issue 39: at most the featureless run's at 10 %);
#  - with `big`, feature detection at 40 degrees on the bunny subdivided four times (17.8M faces,
#    about 2 GB of memory; issue 39: under 1 s).
# Correctness (trilab's Loop equals OpenSubdiv's to 1e-9 of the diagonal, the crease schemes keep
# the curves' dihedral angles) is in tests/unit/test_features.cpp and test_subdivision_creases.cpp.
#   tests/bench/features_cli.sh CLI OSD_ORACLE|- RUNS [MESHES_DIR] [big]
# e.g. tests/bench/features_cli.sh ./build/trilab-cli ./build/tests/trilab_osd_loop_oracle 7
set -euo pipefail
if [ $# -lt 3 ]; then
    sed -n '2,19p' "$0" | sed 's/^# \{0,1\}//'
    exit 2
fi
cli=$1 osd=$2 runs=$3 meshes=${4:-../shared/meshes} big=${5:-}
fandisk=$meshes/fandisk.obj bunny=$meshes/stanford-bunny.obj
for m in "$fandisk" "$bunny"; do
    if [ ! -r "$m" ]; then
        echo "SKIP: $m is absent"
        exit 0
    fi
done
if [ "$osd" != "-" ] && [ ! -x "$osd" ]; then
    echo "note: no OpenSubdiv oracle at $osd (install libosd-dev and build trilab_tests): skipped"
    osd=-
fi
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
ms() { grep -o '"ms": [0-9.e+-]*' | awk '{print $2}'; }
median() { sort -g "$1" | awk '{v[NR] = $1} END {print v[int((NR + 1) / 2)]}'; }

# fandisk with its features, as PLY (trilab) and as the oracle's text (vertices, faces, creases).
"$cli" features --angle 60 "$fandisk" "$out/fd.ply" --ascii >/dev/null
python3 - "$out/fd.ply" "$out/fd.txt" <<'EOF'
import sys
lines = open(sys.argv[1]).read().split("\n")
end = lines.index("end_header")
counts = {}
for l in lines[:end]:
    w = l.split()
    if w and w[0] == "element":
        counts[w[1]] = int(w[2])
nv, nf, ne = counts["vertex"], counts["face"], counts.get("edge", 0)
body = lines[end + 1:]
verts = body[:nv]
faces = [" ".join(l.split()[1:4]) for l in body[nv:nv + nf]]
edges = []
for l in body[nv + nf:nv + nf + ne]:
    a, b, s = l.split()
    edges.append("%s %s %s" % (a, b, "inf" if float(s) >= 10 or s == "inf" else s))
with open(sys.argv[2], "w") as f:
    f.write("%d %d %d 0\n" % (nv, nf, len(edges)))
    f.write("\n".join(verts + faces + edges) + "\n")
EOF

# The 1.1M-face bunny with every 100th edge (in face order) infinitely sharp.
"$cli" subdivide --scheme loop --iterations 2 "$bunny" "$out/b2.ply" --ascii >/dev/null
python3 - "$out/b2.ply" "$out/b2s.ply" <<'EOF'
import sys
src = open(sys.argv[1])
header = []
for l in src:
    header.append(l)
    if l.strip() == "end_header":
        break
nv = nf = 0
for l in header:
    w = l.split()
    if w[:2] == ["element", "vertex"]:
        nv = int(w[2])
    if w[:2] == ["element", "face"]:
        nf = int(w[2])
body = src.read().split("\n")
seen, sharp = set(), []
for l in body[nv:nv + nf]:
    c = [int(x) for x in l.split()[1:4]]
    for k in range(3):
        e = (min(c[k], c[(k + 1) % 3]), max(c[k], c[(k + 1) % 3]))
        if e not in seen:
            if len(seen) % 100 == 0:
                sharp.append(e)
            seen.add(e)
with open(sys.argv[2], "w") as f:
    for l in header[:-1]:
        if not l.startswith("element edge") and not l.startswith("property int vertex") \
                and not l.startswith("property float crease"):
            f.write(l)
    f.write("element edge %d\nproperty int vertex1\nproperty int vertex2\n"
            "property float crease\nend_header\n" % len(sharp))
    f.write("\n".join(body[:nv + nf]) + "\n")
    f.write("".join("%d %d 10\n" % e for e in sharp))
print("bunny: %d of %d edges sharp" % (len(sharp), len(seen)), file=sys.stderr)
EOF

for ((i = 0; i < runs; ++i)); do
    for scheme in loop sqrt3 butterfly modified-butterfly; do
        "$cli" subdivide --scheme $scheme --iterations 3 "$out/fd.ply" "$out/s.ply" --json |
            ms >>"$out/fd_${scheme}_crease"
        "$cli" subdivide --scheme $scheme --iterations 3 --features none "$out/fd.ply" \
            "$out/s.ply" --json | ms >>"$out/fd_${scheme}_plain"
    done
    if [ "$osd" != "-" ]; then
        "$osd" 3 "$out/fd.txt" "$out/osd.bin" --ms | awk '{print $2}' >>"$out/fd_osd"
    fi
    "$cli" subdivide --iterations 1 "$out/b2s.ply" "$out/b.ply" --json | ms >>"$out/b_crease"
    "$cli" subdivide --iterations 1 --features none "$out/b2s.ply" "$out/b.ply" --json |
        ms >>"$out/b_plain"
done
echo "fandisk, 700 edges at 60 degrees infinitely sharp, x3 (medians of $runs, ms):"
for scheme in loop sqrt3 butterfly modified-butterfly; do
    c=$(median "$out/fd_${scheme}_crease") p=$(median "$out/fd_${scheme}_plain")
    awk -v s=$scheme -v c="$c" -v p="$p" 'BEGIN {
        printf "  %-18s with creases %8.1f   plain %8.1f   ratio %.2f\n", s, c, p, c / p }'
done
if [ "$osd" != "-" ]; then
    awk -v o="$(median "$out/fd_osd")" -v c="$(median "$out/fd_loop_crease")" 'BEGIN {
        printf "  OpenSubdiv 3.5 Loop with the same creases %.1f (trilab / OpenSubdiv %.2f)\n",
               o, c / o }'
fi
awk -v c="$(median "$out/b_crease")" -v p="$(median "$out/b_plain")" 'BEGIN {
    printf "bunny 1.1M faces, 1 %% sharp, Loop x1: with creases %.1f, plain %.1f, ratio %.2f\n",
           c, p, c / p }'
# Decimation of fandisk with its features kept against without (issue 39): the Hausdorff
# distance to the input (compare, 200,000 samples a side) at 5, 10 and 20 % of its vertices, and
# each run's own "ms" (one run each: the figure that matters is the distance).
nv=$(awk '/^element vertex/ {print $3; exit}' "$out/fd.ply")
hd() { grep -o '"hausdorff": [0-9.e+-]*' | awk '{print $2}'; }
echo "decimation of fandisk (features at 60 degrees): Hausdorff to the input, with / without:"
for pct in 5 10 20; do
    target=$((nv * pct / 100))
    wm=$("$cli" decimate --target-vertices $target "$out/fd.ply" "$out/dw.ply" --json | ms)
    pm=$("$cli" decimate --target-vertices $target --features none "$out/fd.ply" "$out/dp.ply" \
        --json | ms)
    w=$("$cli" compare "$out/fd.ply" "$out/dw.ply" --json | hd)
    p=$("$cli" compare "$out/fd.ply" "$out/dp.ply" --json | hd)
    awk -v t=$target -v w="$w" -v p="$p" -v wm="$wm" -v pm="$pm" 'BEGIN {
        printf "  %5d vertices: with features %.5f (%.0f ms)   without %.5f (%.0f ms)   ratio %.2f\n",
               t, w, wm, p, pm, w / p }'
done
if [ "$big" = "big" ]; then
    "$cli" subdivide --scheme loop --iterations 4 "$bunny" "$out/b17.ply" >/dev/null
    for ((i = 0; i < runs; ++i)); do
        "$cli" features --angle 40 "$out/b17.ply" "$out/f.ply" --json | ms >>"$out/detect"
    done
    awk -v d="$(median "$out/detect")" 'BEGIN {
        printf "detection at 40 degrees, 17.8M faces: %.1f ms\n", d }'
fi
