#!/usr/bin/env bash
# Issue 38, item 1, in the viewer, under a display (xvfb-run): a session made with --op, --select
# and --op again gives a recipe that keeps the selection, and `trilab-cli replay --check` finds
# the viewer's state bit for bit (before, the recipe started after the selection and replay ran
# the operations on the whole mesh: exit 5). An empty selection is refused by the operation
# after it (issue 38, item 10), which adds no entry.
# usage: recipe_test.sh TRILAB TRILAB_CLI
set -u
trilab=$1
cli=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export XDG_STATE_HOME="$work/state"
fail() { echo "recipe_test: FAIL: $*"; exit 1; }
cd "$work" || exit 1

"$cli" generate default in.obj > /dev/null || fail "generate"
"$trilab" in.obj --op "noise --amount 20" --select "sphere:0,0,1,0.5,0.1" \
    --op "smooth --operator curvature-flow --integration implicit --step 3" --frames 5 \
    --save-session s.trilab > save.log 2>&1 || fail "save run: $(tail -3 save.log)"
"$cli" session recipe s.trilab r.json > recipe.txt || fail "recipe: $(cat recipe.txt)"
grep -q "2 operations and 1 selections after \"Load in.obj" recipe.txt || fail "$(cat recipe.txt)"
"$cli" replay r.json in.obj out.obj --check s.trilab > replay.txt 2>&1 ||
    fail "replay differs: $(cat replay.txt)"
grep -q "identical to the current state" replay.txt || fail "$(cat replay.txt)"

"$trilab" in.obj --select "sphere:100,100,100,0.1" --op "subdivide" --frames 5 \
    --save-session e.trilab > empty.log 2>&1
grep -q "the region is empty (0 of" empty.log || fail "no refusal: $(tail -5 empty.log)"
if [ -e e.trilab ]; then
    "$cli" session info e.trilab | grep -q "Subdivide" && fail "an entry was added: $(cat empty.log)"
fi
echo "recipe_test: ok"
