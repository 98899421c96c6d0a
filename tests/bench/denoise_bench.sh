#!/usr/bin/env bash
# Denoising against MeshDenoiser (Debian meshsdfilter-tools: static/dynamic filtering, Zhang et
# al. 2019, with the upstream DenoisingOptions.txt values) on the same noisy inputs (issue 40):
# fandisk with seeded Gaussian noise of sigma = k x the mean edge length, k = 0.3 and 0.7, along
# the normals and in random directions, and the built-in block at k = 0.4. For each input and
# each denoiser it prints theta (the mean angle to the clean face normals), the share of faces
# flipped (more than 90 degrees off) and the mean distance of the vertices to the clean surface
# over the diagonal (all from `trilab-cli compare CLEAN OUT`), and the denoising time: trilab's
# "ms" from --json, MeshDenoiser's own "timing" line (seconds), file reading and writing
# excluded for both; then, with --big, trilab's time on the bunny after two Loop steps (1.1M
# faces).
#   tests/bench/denoise_bench.sh CLI [--seeds N] [--big] [--peer-big]
# e.g. tests/bench/denoise_bench.sh ./build/trilab-cli --seeds 3 --big
# Set-up: MeshDenoiser is installed with apt-get when it is absent (benchmark only: trilab never
# links or calls it). Meshes from ../shared/meshes (or $TRILAB_SHARED_DIR/meshes); a case
# whose mesh is absent is skipped with a line saying so.
set -euo pipefail
if [ $# -lt 1 ]; then
    sed -n '2,16p' "$0" | sed 's/^# \{0,1\}//'
    exit 2
fi
cli=$1
shift
seeds=1 big=0 peer_big=0
while [ $# -gt 0 ]; do
    case $1 in
    --seeds) seeds=$2; shift 2 ;;
    --big) big=1; shift ;;
    --peer-big) peer_big=1; shift ;;
    *) echo "unknown option $1" >&2; exit 2 ;;
    esac
done
root=$(cd "$(dirname "$0")/../.." && pwd)
shared=${TRILAB_SHARED_DIR:-$root/../shared}

# ---- set-up: the peer -------------------------------------------------------------------------
if ! command -v MeshDenoiser >/dev/null; then
    echo "set-up: installing meshsdfilter-tools (MeshDenoiser) with apt-get"
    sudo_cmd=()
    [ "$(id -u)" -ne 0 ] && sudo_cmd=(sudo)
    "${sudo_cmd[@]}" apt-get install -y meshsdfilter-tools >/dev/null ||
        echo "set-up: could not install meshsdfilter-tools: the peer's columns stay empty"
fi
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
# The upstream DenoisingOptions.txt values (MeshSDFilter's defaults).
cat >"$out/options.txt" <<'EOF'
Lambda 2
Eta 1.5
Mu 1.5
Nu 0.3
MeshUpdateClosenessWeight 0.001
MeshUpdateIterations 20
OuterIterations 5
EOF

json() { python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); print(d.get(sys.argv[2], "nan"))' "$@"; }
measure() {  # measure CLEAN OUT -> "theta flipped% dist%" (or "failed")
    if "$cli" compare "$1" "$2" --samples 1000 --json >"$out/c.json" 2>/dev/null; then
        python3 -c 'import json,sys; d=json.load(open(sys.argv[1]))
if not d["same_connectivity"]: print("(connectivity differs)"); sys.exit()
print("%6.2f  %6.3f%%  %.5f%%" % (d["theta_mean"], 100 * d["flipped_share"],
      100 * d["vertex_distance_mean_relative"]))' "$out/c.json"
    else
        echo "failed"
    fi
}

echo "load average at the start: $(cut -d' ' -f1-3 /proc/loadavg)"
if command -v MeshDenoiser >/dev/null; then
    echo "peer: $(command -v MeshDenoiser) (meshsdfilter-tools $(dpkg-query -W -f='${Version}' meshsdfilter-tools 2>/dev/null || echo '?'))"
else
    echo "peer: MeshDenoiser absent: its rows are left out"
fi
printf '%-28s %-10s %8s %9s %10s %10s\n' input denoiser theta flipped "dist/diag" time
run_case() {  # run_case NAME CLEAN K METHOD_ARGS...
    local name=$1 clean=$2 k=$3
    shift 3
    for ((seed = 1; seed <= seeds; ++seed)); do
        for dir in normal random; do
            local label="$name k=$k $dir s$seed"
            "$cli" noise --distribution gaussian --sigma "$k" --direction "$dir" --seed "$seed" \
                "$clean" "$out/noisy.obj" >/dev/null
            printf '%-28s %-10s %s\n' "$label" noisy "$(measure "$clean" "$out/noisy.obj")"
            if "$cli" denoise "$@" "$out/noisy.obj" "$out/t.obj" --json >"$out/t.json" 2>"$out/t.err"; then
                printf '%-28s %-10s %s %8.1f ms\n' "$label" trilab "$(measure "$clean" "$out/t.obj")" \
                    "$(json "$out/t.json" ms)"
            else
                printf '%-28s %-10s %s\n' "$label" trilab "failed: $(head -c 150 "$out/t.err")"
            fi
            if command -v MeshDenoiser >/dev/null; then
                if MeshDenoiser "$out/options.txt" "$out/noisy.obj" "$out/m.obj" >"$out/m.log" 2>&1; then
                    local secs
                    secs=$(sed -n 's/.*timing: *\([0-9.e+-]*\).*/\1/p' "$out/m.log" | tail -1)
                    printf '%-28s %-10s %s %8.1f ms\n' "$label" MeshDenoiser \
                        "$(measure "$clean" "$out/m.obj")" "$(awk -v s="${secs:-nan}" 'BEGIN { print s * 1000 }')"
                else
                    printf '%-28s %-10s %s\n' "$label" MeshDenoiser "failed"
                fi
            fi
        done
    done
}

fandisk=$shared/meshes/fandisk.obj
if [ -r "$fandisk" ]; then
    run_case fandisk "$fandisk" 0.3
    run_case fandisk "$fandisk" 0.7 --method guided
else
    echo "SKIP: $fandisk is absent"
fi
"$cli" generate block "$out/block.obj" >/dev/null
run_case block "$out/block.obj" 0.4

if [ "$big" = 1 ]; then
    bunny=$shared/meshes/stanford-bunny.obj
    if [ -r "$bunny" ]; then
        "$cli" subdivide --scheme loop --iterations 2 "$bunny" "$out/big.ply" >/dev/null
        "$cli" noise --distribution gaussian --sigma 0.3 --seed 1 "$out/big.ply" "$out/bign.ply" >/dev/null
        faces=$("$cli" info "$out/bign.ply" --json | python3 -c 'import json,sys; print(json.load(sys.stdin)["faces"])')
        for run in 1 2 3; do
            "$cli" denoise "$out/bign.ply" "$out/bigd.ply" --json >"$out/b.json"
            printf '%-28s %-10s %28s %8.1f ms\n' "bunny Loop x2 ($faces faces)" trilab "run $run" "$(json "$out/b.json" ms)"
        done
        if [ "$peer_big" = 1 ] && command -v MeshDenoiser >/dev/null; then
            "$cli" convert "$out/bign.ply" "$out/bign.obj" >/dev/null
            MeshDenoiser "$out/options.txt" "$out/bign.obj" "$out/bigm.obj" >"$out/m.log" 2>&1 || true
            printf '%-28s %-10s %28s %s s\n' "bunny Loop x2" MeshDenoiser "" \
                "$(sed -n 's/.*timing: *\([0-9.e+-]*\).*/\1/p' "$out/m.log" | tail -1)"
        fi
    else
        echo "SKIP: $bunny is absent"
    fi
fi
echo "load average at the end: $(cut -d' ' -f1-3 /proc/loadavg)"
