#!/usr/bin/env bash
# The naming rules of STYLE.md (.clang-tidy: readability-identifier-naming only) on the C++ files
# a change touches. CI runs it after the Release build (tests/run-all.sh).
#   tests/lint/check-naming.sh BUILD_DIR [all]
# BUILD_DIR holds compile_commands.json (any configured build). Which files:
#   - "all" (or TRILAB_TIDY_BASE=all): every file of the compile database;
#   - TRILAB_TIDY_BASE=<rev>: the files changed since <rev>;
#   - otherwise the files changed since the merge base with origin/main (or the local main when
#     there is no origin) when HEAD is not on it (a branch), else the files of the last commit
#     (CI on main); no git, or a single commit: every file.
# Uncommitted changes and new files are always added. A changed header is checked through a
# source file that includes it (see source_for). Exit status 1 when a name breaks the rules;
# clang-tidy prints file:line and the expected style.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/../.."
build="${1:?usage: tests/lint/check-naming.sh BUILD_DIR [all]}"
db="$build/compile_commands.json"
[ -f "$db" ] || { echo "check-naming: no $db (configure the build first)" >&2; exit 2; }
if ! command -v clang-tidy >/dev/null; then
    echo "check-naming: clang-tidy is not installed (third_party/install-deps.sh)" >&2
    exit 2
fi
root="$(pwd)"
base="${TRILAB_TIDY_BASE:-}"
[ "${2:-}" = all ] && base=all

# Every source file of the compile database inside the repository (not the generated ones).
mapfile -t sources < <(grep -o '"file": *"[^"]*"' "$db" | sed -e 's/"file": *"//' -e 's/"$//' |
                       grep "^$root/" | grep -v "^$root/build" | sed "s|^$root/||" | sort -u)

if [ -z "$base" ] && ! git rev-parse --git-dir >/dev/null 2>&1; then base=all; fi
if [ -z "$base" ]; then
    upstream="" main_ref=""
    for ref in origin/main main; do
        if git rev-parse -q --verify "$ref" >/dev/null; then
            main_ref="$ref"
            upstream="$(git merge-base HEAD "$ref" || true)"
            break
        fi
    done
    if [ -n "$upstream" ] && [ "$upstream" != "$(git rev-parse HEAD)" ]; then
        base="$upstream"
        what="since the merge base with $main_ref (${base:0:10})"
    elif git rev-parse -q --verify HEAD~1 >/dev/null; then
        base="HEAD~1"
        what="in the last commit"
    else
        base=all
    fi
else
    what="since $base"
fi

in_sources() { printf '%s\n' "${sources[@]}" | grep -qxF "$1"; }
# A source file of the compile database that includes header $1 (the one of the same name,
# else one including it directly, else through up to $2 levels of headers).
source_for() {
    local header="$1" depth="$2" name s h
    if in_sources "${header%.h}.cpp"; then echo "${header%.h}.cpp"; return; fi
    name="$(basename "$header")"
    for s in "${sources[@]}"; do
        if grep -qE "#include \"($header|$name)\"" "$s"; then echo "$s"; return; fi
    done
    [ "$depth" -gt 0 ] || return 0
    while IFS= read -r h; do
        s="$(source_for "$h" $((depth - 1)))"
        if [ -n "$s" ]; then echo "$s"; return; fi
    done < <(grep -rlE "#include \"($header|$name)\"" core app render tests --include='*.h' |
             grep -vxF "$header")
}

if [ "$base" = all ]; then
    files=("${sources[@]}")
    what="all files"
else
    mapfile -t changed < <({ git diff --name-only --diff-filter=d "$base" HEAD;
                             git diff --name-only --diff-filter=d HEAD;
                             git ls-files --others --exclude-standard; } |
                           grep -E '\.(cpp|h)$' | sort -u)
    files=()
    for f in "${changed[@]}"; do
        [ -f "$f" ] || continue
        case "$f" in
        *.cpp)
            if in_sources "$f"; then files+=("$f"); fi ;;
        *.h)
            tu="$(source_for "$f" 3)"
            if [ -n "$tu" ]; then
                files+=("$tu")
            else
                echo "check-naming: $f: no source file includes it, not checked"
            fi ;;
        esac
    done
    mapfile -t files < <(printf '%s\n' "${files[@]}" | grep -v '^$' | sort -u)
fi

echo "check-naming: ${#files[@]} file(s) ($what)"
[ ${#files[@]} -eq 0 ] && exit 0
# Two at a time (CI has two cores). clang-tidy exits non-zero on a broken rule (WarningsAsErrors)
# and on a file it cannot parse; every failing file is reported before the exit.
log="$build/check-naming.log"
status=0
# -Wno-error: a warning clang gives and GCC does not (the builds' -Werror is for GCC and the
# fuzz build) is shown but is not this check's business.
printf '%s\n' "${files[@]}" |
    xargs -P 2 -n 1 clang-tidy -p "$build" --quiet --extra-arg=-Wno-error >"$log" 2>&1 ||
    status=$?
if [ "$status" -ne 0 ]; then
    grep -E '(warning|error):' "$log" | sort -u || cat "$log"
    echo "check-naming: failed (STYLE.md's naming rules, .clang-tidy; full output in $log)" >&2
    exit 1
fi
echo "check-naming: ok"
