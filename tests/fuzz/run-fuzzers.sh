#!/usr/bin/env bash
# Runs the libFuzzer targets built in BUILD_DIR (cmake -DTRILAB_FUZZ=ON, see README
# "Hardening") for SECONDS each, one after the other, on their seed corpora in
# tests/fuzz/corpus/<reader>/ with the dictionary tests/fuzz/<reader>.dict where there is one.
#   tests/fuzz/run-fuzzers.sh BUILD_DIR SECONDS [READER...]     (default: every reader)
# New interesting inputs go to BUILD_DIR/fuzz-work/<reader>/ (the committed seeds are never
# modified); a failing input is written to BUILD_DIR/fuzz-artifacts/<reader>/ and the script
# exits non-zero after running the rest. Each run's log is BUILD_DIR/fuzz-logs/<reader>.log.
set -uo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
build="${1:?usage: run-fuzzers.sh BUILD_DIR SECONDS [READER...]}"
seconds="${2:?usage: run-fuzzers.sh BUILD_DIR SECONDS [READER...]}"
shift 2
readers=("$@")
[ ${#readers[@]} -gt 0 ] || readers=(obj off ply stl om xbm xpm pnm bmp png builder session)
failed=()
for r in "${readers[@]}"; do
    exe="$build/tests/fuzz/fuzz_$r"
    [ -x "$exe" ] || { echo "run-fuzzers: $exe is not built" >&2; failed+=("$r"); continue; }
    case "$r" in
        ply | stl | om) max_len=8192 ;;
        session) max_len=32768 ;;
        *) max_len=4096 ;;
    esac
    mkdir -p "$build/fuzz-work/$r" "$build/fuzz-artifacts/$r" "$build/fuzz-logs"
    log="$build/fuzz-logs/$r.log"
    dict=()
    [ -f "$here/$r.dict" ] && dict=(-dict="$here/$r.dict")
    "$exe" "$build/fuzz-work/$r" "$here/corpus/$r" "${dict[@]}" \
        -max_len=$max_len -timeout=10 -rss_limit_mb=2048 -max_total_time="$seconds" \
        -print_final_stats=1 -artifact_prefix="$build/fuzz-artifacts/$r/" >"$log" 2>&1
    rc=$?
    stats=$(grep -E '^#[0-9]+.*(DONE|cov)' "$log" | tail -1)
    execs=$(grep -E '^stat::number_of_executed_units' "$log" | awk '{print $2}')
    echo "fuzz_$r: exit $rc, ${execs:-?} executions in ${seconds}s; last: ${stats:-?}"
    if [ $rc -ne 0 ]; then
        failed+=("$r")
        grep -E 'ERROR|SUMMARY|Test unit written' "$log" | head -5
    fi
done
if [ ${#failed[@]} -gt 0 ]; then
    echo "run-fuzzers: FAILED: ${failed[*]} (inputs in $build/fuzz-artifacts/, logs in $build/fuzz-logs/)" >&2
    exit 1
fi
echo "run-fuzzers: all ${#readers[@]} fuzzers ran ${seconds}s each without a failure"
