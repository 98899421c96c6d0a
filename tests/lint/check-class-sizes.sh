#!/usr/bin/env bash
# The viewer stays a window and a loop (issue 37): class Viewer has at most 30 methods and 40
# fields, and the Session and each of its owners at most 50 methods and 40 fields, counting
# their nested structs, wherever they are defined (universal-ctags over app/
# and render/: a method is a distinct name declared or defined in the class's scope; a field is
# a member of the class or of a class nested in it). Prints the counts of the classes below and
# exits 1 when one is over its limit.
#   tests/lint/check-class-sizes.sh
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/../.."
command -v ctags >/dev/null || { echo "check-class-sizes: ctags (universal-ctags) is not installed" >&2; exit 2; }
ctags --version | grep -q "Universal Ctags" ||
    { echo "check-class-sizes: ctags is not universal-ctags" >&2; exit 2; }
# CLASS METHODS FIELDS: the limits. The Session is a facade over owners of one concern each,
# none over 50 methods (issue 37, part 3).
limits="trilab::viewer::Viewer 30 40"
for c in Session SessionCore SessionDocument SessionPreviews SessionLevels SessionSelection \
         SessionPicking SessionFrequency SessionFiles SessionFigures SessionColoring SessionMorph \
         SessionGuidance; do
    limits="$limits trilab::viewer::$c 50 40"
done
ctags -R --languages=C++ --kinds-C++=+p-l --extras=-q -x --_xformat="%{kind}|%{scope}|%N" app render |
    awk -F'|' -v limits="$limits" '
($1 == "function" || $1 == "prototype") { methods[$2 SUBSEP $3] = 1 }
($1 == "member") { fields[$2]++ }
END {
    n = split(limits, l, " ")
    status = 0
    for (i = 1; i <= n; i += 3) {
        c = l[i]; m = 0; f = 0
        for (k in methods) { split(k, a, SUBSEP); if (a[1] == c) m++ }
        for (s in fields) if (s == c || index(s, c "::") == 1) f += fields[s]
        over = (m > l[i + 1] || f > l[i + 2])
        printf "%s: %d methods (at most %d), %d fields with its nested structs (at most %d)%s\n",
               c, m, l[i + 1], f, l[i + 2], over ? ": TOO MANY" : ""
        if (m == 0) { print c ": not found by ctags"; status = 1 }
        if (over) status = 1
    }
    exit status
}'
