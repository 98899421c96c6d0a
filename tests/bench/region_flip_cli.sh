#!/usr/bin/env bash
# Flip on a region against flip on the whole mesh through the command line (issue 26), the
# figure being each run's own "ms" from --json. Alternates whole and region, and with a second
# trilab-cli (an older build, say) alternates the two builds too, so that all four medians come
# from one run on one machine state.
#   tests/bench/region_flip_cli.sh MESH RUNS REGION CLI [CLI2]
# e.g. tests/bench/region_flip_cli.sh bunny.ply 31 sphere:-0.02,0.11,0,0.05 ./build/trilab-cli
set -euo pipefail
if [ $# -lt 4 ]; then
    sed -n '2,7p' "$0" | sed 's/^# \{0,1\}//'
    exit 2
fi
mesh=$1 runs=$2 region=$3
shift 3
clis=("$@")
if [ ! -r "$mesh" ]; then
    echo "SKIP: $mesh is absent"
    exit 0
fi
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
ms() { grep -o '"ms": [0-9.e+-]*' | awk '{print $2}'; }
for ((i = 0; i < runs; ++i)); do
    for k in "${!clis[@]}"; do
        "${clis[$k]}" flip "$mesh" "$out/w.ply" --json | ms >>"$out/whole$k"
        "${clis[$k]}" flip "$mesh" "$out/r.ply" --region "$region" --json | ms >>"$out/region$k"
    done
done
median() { sort -g "$1" | awk '{v[NR] = $1} END {print v[int((NR + 1) / 2)]}'; }
for k in "${!clis[@]}"; do
    w=$(median "$out/whole$k")
    r=$(median "$out/region$k")
    awk -v c="${clis[$k]}" -v w="$w" -v r="$r" -v n="$runs" 'BEGIN {
        printf "%s: whole %.3f ms, region %.3f ms, region / whole %.2f (medians of %d)\n",
               c, w, r, r / w, n }'
done
