#!/usr/bin/env bash
# Sessions in the viewer (issue 27), under a display (xvfb-run):
#  1. `trilab --op A --op B --save-session s.trilab` applies both, in order, and writes them;
#     `trilab-cli session info` lists both entries;
#  2. `trilab s.trilab` restores the history, the current state and the settings (the log's
#     last-frame line shows the state; no setting is refused);
#  3. a viewer killed with SIGKILL leaves its journal: a scripted run says so, `--restore`
#     restores it (the same last state) and removes it; --no-recovery writes no journal;
#  4. SIGTERM ends the viewer at once and keeps its journal, marked as unsaved work.
# usage: session_test.sh TRILAB TRILAB_CLI
set -u
trilab=$1
cli=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export XDG_STATE_HOME="$work/state"
recovery="$XDG_STATE_HOME/trilab/recovery"
fail() { echo "session_test: FAIL: $*"; exit 1; }
cd "$work" || exit 1

"$trilab" --op "noise --amount 2 --seed 5" --op "smooth --iterations 3" --mode flat \
    --color mean --save-session s.trilab --frames 2 > save.log 2>&1 || fail "save run: $(tail -3 save.log)"
grep -q "last frame: state 2 of 3: Smooth" save.log || fail "the two --op did not run: $(grep 'last frame' save.log)"
"$cli" session info s.trilab > info.txt || fail "session info failed"
grep -q "Add noise *noise --amount 2 --seed 5" info.txt || fail "no noise entry: $(cat info.txt)"
grep -q "^> *2 *Smooth *smooth " info.txt || fail "no current smooth entry: $(cat info.txt)"
[ -z "$(ls "$recovery" 2> /dev/null)" ] || fail "a clean exit left a journal: $(ls "$recovery")"

"$trilab" s.trilab --frames 2 --save-session again.trilab > open.log 2>&1 || fail "open run failed"
grep -q "opened session s.trilab: 3 entries" open.log || fail "not opened: $(head -5 open.log)"
grep -q "last frame: state 2 of 3: Smooth --operator umbrella" open.log ||
    fail "the state is not restored: $(grep 'last frame' open.log)"
grep -q "warning" open.log && fail "a setting was refused: $(grep warning open.log)"
# The settings come back as they were: the same text in the session written again.
"$cli" session info s.trilab --json | grep -o '"viewer_settings_bytes": [0-9]*' > a.txt
"$cli" session info again.trilab --json | grep -o '"viewer_settings_bytes": [0-9]*' > b.txt
cmp -s a.txt b.txt || fail "the settings changed: $(cat a.txt b.txt)"
for i in 0 1 2; do
    "$cli" session export s.trilab --entry $i a.ply > /dev/null
    "$cli" session export again.trilab --entry $i b.ply > /dev/null
    cmp -s a.ply b.ply || fail "entry $i is not restored bit for bit"
done

# A crash: kill the viewer once its journal holds the two operations.
for attempt in 1 2 3 4 5 6 7 8 9 10; do
    rm -rf "$recovery"
    "$trilab" --op "noise --amount 2 --seed 5" --op "smooth --iterations 3" --frames 400 \
        > crash.log 2>&1 &
    pid=$!
    for ((w = 0; w < 500; ++w)); do
        j=$(ls "$recovery"/*.journal 2> /dev/null | head -1)
        [ -n "$j" ] && "$cli" session info "$j" 2> /dev/null | grep -q "3 entries" && break
        sleep 0.01
    done
    kill -KILL $pid 2> /dev/null
    wait $pid 2> /dev/null
    j=$(ls "$recovery"/*.journal 2> /dev/null | head -1)
    [ -n "$j" ] && "$cli" session info "$j" | grep -q "3 entries" && break
done
[ -n "$j" ] || fail "no journal after SIGKILL"
"$trilab" --frames 2 > found.log 2>&1
grep -q "a crash journal was found: .*trilab --restore restores it" found.log ||
    fail "the orphan journal is not noticed: $(head -5 found.log)"
[ -f "$j" ] || fail "a scripted run removed the orphan journal"
"$trilab" --restore --frames 2 > restore.log 2>&1 || fail "--restore failed"
grep -q "recovered .*: 3 entries" restore.log || fail "not recovered: $(head -5 restore.log)"
grep -q "last frame: state 2 of 3: Smooth" restore.log ||
    fail "--restore: $(grep 'last frame' restore.log)"
[ -f "$j" ] && fail "--restore kept the journal it restored"
# A normal end from outside (SIGTERM: a logout): the viewer stops at once, keeps its journal
# for recovery and marks it, and the next start says the work was not saved, not a crash.
rm -rf "$recovery"
"$trilab" --op "noise --amount 2 --seed 5" --op "smooth --iterations 3" --frames 100000 \
    > term.log 2>&1 &
pid=$!
for ((w = 0; w < 1000; ++w)); do
    j=$(ls "$recovery"/*.journal 2> /dev/null | head -1)
    [ -n "$j" ] && "$cli" session info "$j" 2> /dev/null | grep -q "3 entries" && break
    sleep 0.01
done
kill -TERM $pid
for ((w = 0; w < 500; ++w)); do kill -0 $pid 2> /dev/null || break; sleep 0.02; done
kill -0 $pid 2> /dev/null && { kill -KILL $pid; fail "SIGTERM did not end the viewer"; }
wait $pid
grep -q "ended by SIGTERM after .* frames: the work is kept for recovery" term.log ||
    fail "SIGTERM: $(tail -3 term.log)"
[ -f "$j" ] && [ -f "$j.ended" ] || fail "SIGTERM: the journal or its note is gone: $(ls "$recovery")"
"$trilab" --frames 2 > term-found.log 2>&1
grep -q "unsaved work was found (its viewer was ended by SIGTERM before saving): .*--restore" \
    term-found.log || fail "the ended journal is not told apart: $(grep found term-found.log)"
"$trilab" --restore --frames 2 > term-restore.log 2>&1 || fail "--restore after SIGTERM failed"
grep -q "last frame: state 2 of 3: Smooth" term-restore.log ||
    fail "--restore after SIGTERM: $(grep 'last frame' term-restore.log)"
[ -e "$j" ] || [ -e "$j.ended" ] && fail "--restore kept the journal or its note"
rm -rf "$recovery"
"$trilab" --no-recovery --op "noise --amount 2" --frames 400 > nojournal.log 2>&1 &
pid=$!
sleep 1
[ -z "$(ls "$recovery" 2> /dev/null)" ] || fail "--no-recovery wrote a journal"
kill -KILL $pid 2> /dev/null
wait $pid 2> /dev/null
echo "session_test: save, open, crash journal, SIGTERM, --restore and --no-recovery work"
