#!/usr/bin/env bash
# The crash journal survives SIGKILL (issue 27): the viewer runs a scripted history (--op
# several times) and is killed at random moments, at least KILLS times; after each kill the
# journal (read by `trilab-cli session info`, i.e. read_journal) must hold a prefix of the
# scripted history: the same labels, and every state's mesh bit for bit the same as in the
# session a clean run saved (--save-session), compared through binary PLY exports.
# Run under a display (xvfb-run). usage: kill_test.sh TRILAB TRILAB_CLI [KILLS]
set -u
trilab=$1
cli=$2
kills_wanted=${3:-30}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export XDG_STATE_HOME="$work/state"
recovery="$XDG_STATE_HOME/trilab/recovery"
ops=(--op "noise --amount 1 --seed 1" --op "smooth --iterations 2"
     --op "subdivide --iterations 1" --op "noise --amount 1 --seed 2"
     --op "smooth --iterations 2 --step 0.3" --op "decimate --percent 30")

fail() { echo "kill_test: FAIL: $*"; exit 1; }

# The reference: a clean run of the same script (its journal is removed at the exit).
"$trilab" --no-recovery "${ops[@]}" --frames 2 --save-session "$work/ref.trilab" \
    > "$work/ref.log" 2>&1 || fail "the clean run failed: $(tail -3 "$work/ref.log")"
ref_n=$("$cli" session info "$work/ref.trilab" --json | grep -o '"entries_recovered": [0-9]*' |
        grep -o '[0-9]*$')
[ "$ref_n" = 7 ] || fail "the reference has $ref_n entries, expected 7"
labels() { "$cli" session info "$1" --json | grep -o '"label": "[^"]*"'; }
labels "$work/ref.trilab" > "$work/ref.labels"
for ((i = 0; i < ref_n; ++i)); do
    "$cli" session export "$work/ref.trilab" --entry $i "$work/ref_$i.ply" > /dev/null ||
        fail "cannot export entry $i of the reference"
done
# How long a run takes: the kills fall anywhere inside it.
t0=$(date +%s%N)
"$trilab" --no-recovery "${ops[@]}" --frames 2 > /dev/null 2>&1
run_ms=$(( ($(date +%s%N) - t0) / 1000000 + 50 ))

kills=0 attempts=0 with_operations=0 prefixes=""
while (( kills < kills_wanted )); do
    (( ++attempts > 4 * kills_wanted )) && fail "only $kills kills in $attempts runs"
    rm -rf "$recovery"
    "$trilab" "${ops[@]}" --frames 2 > "$work/run.log" 2>&1 &
    pid=$!
    # A quarter of the kills anywhere (start-up included); the others once the journal
    # exists, while the operations run.
    if (( RANDOM % 4 != 0 )); then
        for ((w = 0; w < 200; ++w)); do
            ls "$recovery"/*.journal > /dev/null 2>&1 && break
            sleep 0.01
        done
    fi
    sleep "$(awk -v r=$RANDOM -v ms=$run_ms 'BEGIN { printf "%.3f", r / 32768 * ms / 2000 }')"
    kill -KILL $pid 2> /dev/null || { wait $pid; continue; }  # it had ended: no kill
    wait $pid 2> /dev/null
    (( ++kills ))
    journal=$(ls "$recovery"/*.journal 2> /dev/null | head -1)
    if [ -z "$journal" ]; then prefixes+=" -"; continue; fi  # killed before the first write
    if ! "$cli" session info "$journal" --json > "$work/info.json" 2> "$work/info.err"; then
        grep -q "complete" "$work/info.err" ||
            fail "kill $kills: the journal is refused: $(cat "$work/info.err")"
        prefixes+=" 0"
        continue
    fi
    n=$(grep -o '"entries_recovered": [0-9]*' "$work/info.json" | grep -o '[0-9]*$')
    labels "$journal" > "$work/run.labels"
    # Before the load of the default model the viewer's first entry is that model too.
    (( n <= ref_n )) || fail "kill $kills: $n entries, more than the script's $ref_n"
    head -n "$n" "$work/ref.labels" | cmp -s - "$work/run.labels" ||
        fail "kill $kills: the labels are no prefix: $(tr '\n' ' ' < "$work/run.labels")"
    for ((i = 0; i < n; ++i)); do
        "$cli" session export "$journal" --entry $i "$work/run_$i.ply" > /dev/null ||
            fail "kill $kills: cannot export entry $i of $journal"
        cmp -s "$work/ref_$i.ply" "$work/run_$i.ply" ||
            fail "kill $kills: entry $i differs from the clean run's"
    done
    prefixes+=" $n"
    (( n >= 2 )) && (( ++with_operations ))
done
# Without a journal every kill would find nothing: most kills must find operations.
(( with_operations >= kills_wanted / 3 )) ||
    fail "only $with_operations of $kills journals held an operation:$prefixes"
echo "kill_test: $kills kills in $attempts runs (run ${run_ms} ms); entries recovered:$prefixes"
echo "kill_test: every journal restored a prefix of the scripted history bit for bit"
