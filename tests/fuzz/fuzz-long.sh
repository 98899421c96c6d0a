#!/usr/bin/env bash
# Long fuzzing campaign (not run by CI): runs READER:MINUTES items one after the other at the
# lowest CPU priority, restarting a fuzzer after each failure until its minutes are spent (so
# a fixed and rebuilt target picks up where it stopped, keeping its grown corpus).
#   tests/fuzz/fuzz-long.sh BUILD_DIR ply:40 stl:30 ...
# Logs: BUILD_DIR/long-logs/<reader>.<run>.log; failing inputs: BUILD_DIR/long-artifacts/.
set -uo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
build="$1"
shift
for item in "$@"; do
    r="${item%%:*}"
    end=$(($(date +%s) + ${item##*:} * 60))
    case "$r" in ply | stl | om) max_len=8192 ;; *) max_len=4096 ;; esac
    dict=()
    [ -f "$here/$r.dict" ] && dict=(-dict="$here/$r.dict")
    mkdir -p "$build/fuzz-work/$r" "$build/long-artifacts/$r" "$build/long-logs"
    run=0
    while [ "$(date +%s)" -lt "$end" ]; do
        run=$((run + 1))
        left=$((end - $(date +%s)))
        nice -n 19 "$build/tests/fuzz/fuzz_$r" "$build/fuzz-work/$r" "$here/corpus/$r" \
            "${dict[@]}" -max_len=$max_len -timeout=10 -rss_limit_mb=2048 \
            -max_total_time=$left -print_final_stats=1 \
            -artifact_prefix="$build/long-artifacts/$r/" >"$build/long-logs/$r.$run.log" 2>&1
        [ $? -eq 0 ] || sleep 5
    done
done
