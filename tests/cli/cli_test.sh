#!/usr/bin/env bash
# End-to-end checks of trilab-cli: exit codes, one-line errors, JSON keys, round trips.
# usage: cli_test.sh path/to/trilab-cli path/to/tests/data
set -u
cli="$1"
data="$2"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
passed=0
failed=0
check() {  # check NAME COMMAND... : passes when the command succeeds
    local name="$1"
    shift
    if "$@" >"$tmp/out" 2>"$tmp/err"; then
        passed=$((passed + 1))
    else
        failed=$((failed + 1))
        echo "FAILED: $name"
        sed 's/^/  out: /' "$tmp/out" | head -5
        sed 's/^/  err: /' "$tmp/err" | head -5
    fi
}
json_has() {  # json_has FILE KEY...
    local f="$1"
    shift
    for k in "$@"; do grep -q "\"$k\": " "$f" || { echo "missing key $k"; return 1; }; done
}

check "generate writes the default model" "$cli" generate default "$tmp/d.obj"
check "info --json has every documented key" bash -c \
    "'$cli' info '$tmp/d.obj' --json > '$tmp/info.json' && \
     $(declare -f json_has); json_has '$tmp/info.json' vertices edges faces boundary_loops \
     components euler genus manifold bbox_min bbox_max area volume load_report ms"
check "info counts the default model" bash -c \
    "'$cli' info '$tmp/d.obj' --json | grep -q '\"vertices\": 1002, \"edges\": 3000, \"faces\": 2000'"
check "open meshes have a null volume" bash -c \
    "'$cli' generate grid '$tmp/g.ply' && '$cli' info '$tmp/g.ply' --json | grep -q '\"volume\": null'"
check "the load report counts repairs" bash -c \
    "'$cli' info '$data/good/bowtie.off' --json | grep -q '\"nonmanifold_vertices_split\": 1'"
for ext in obj off ply stl om; do
    check "convert to .$ext and back keeps the faces" bash -c \
        "'$cli' convert '$tmp/d.obj' '$tmp/c.$ext' && \
         '$cli' info '$tmp/c.$ext' --json | grep -q '\"faces\": 2000'"
done
check "convert --ascii writes an ASCII STL" bash -c \
    "'$cli' convert '$tmp/d.obj' '$tmp/a.stl' --ascii && head -c 5 '$tmp/a.stl' | grep -q solid"
check "a bad file fails with one line naming file and line" bash -c \
    "! '$cli' info '$data/bad/off_out_of_range.off' 2> '$tmp/e' && [ \$(wc -l < '$tmp/e') -eq 1 ] \
     && grep -q 'off_out_of_range.off:6: ' '$tmp/e'"
check "a missing file fails" bash -c "! '$cli' info '$tmp/nothing.obj' 2>/dev/null"
check "an unknown command fails" bash -c "! '$cli' frobnicate 2>/dev/null"
check "an unknown option fails" bash -c "! '$cli' info '$tmp/d.obj' --bogus 2>/dev/null"
check "an unknown model fails and lists the names" bash -c \
    "! '$cli' generate nope '$tmp/x.obj' 2> '$tmp/e' && grep -q 'known:' '$tmp/e'"
check "a failed save leaves the old file intact" bash -c \
    "cp '$tmp/d.obj' '$tmp/keep.obj' && ! '$cli' convert '$data/bad/off_nan.off' '$tmp/keep.obj' \
     2>/dev/null && cmp -s '$tmp/d.obj' '$tmp/keep.obj'"
if "$cli" render --help >/dev/null 2>&1; then
    check "render writes a PNG of the requested size" bash -c \
        "'$cli' render '$tmp/d.obj' --out '$tmp/r.png' --size 320x200 --json > '$tmp/r.json' && \
         $(declare -f json_has); json_has '$tmp/r.json' ms && \
         head -c 24 '$tmp/r.png' | od -An -tx1 | tr -d ' \n' | grep -q '00000140000000c8'"
    check "render refuses an unknown mode naming the option" bash -c \
        "! '$cli' render '$tmp/d.obj' --out '$tmp/x.png' --mode nope 2> '$tmp/e' && \
         grep -q -- 'mode' '$tmp/e' && [ ! -e '$tmp/x.png' ]"
fi
echo "cli: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
