#!/usr/bin/env bash
# No function longer than 120 lines in core/, render/ or app/ (issue 24): a long function is split
# into named stages (small functions, or a small class in the .cpp with one method per stage;
# see core/mesh_builder.cpp). A function's length runs from the line of its name to the line of
# its closing brace. Prints every function over the limit (file:line, name, length) that the
# allow-list below does not name, and exits 1 when there is one.
#   tests/lint/check-function-length.sh [LIMIT]     (default 120)
# The scan needs only python3: comments, string and character literals and preprocessor lines
# are blanked, then braces are matched; a brace opens a function body when the text before it
# ends with a parameter list (and qualifiers, a trailing return type or a constructor's
# initializer list). Lambdas and local classes count towards the function around them.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/../.."
limit="${1:-120}"

# Functions still over the limit, as PATH:NAME, one a line, each with the reason it is here.
# Keep this list short: split a function and remove its line.
allowed=(
    # (none)
)

command -v python3 >/dev/null || { echo "check-function-length: python3 is not installed" >&2; exit 2; }
shopt -s nullglob globstar
files=(core/**/*.h core/**/*.cpp render/**/*.h render/**/*.cpp app/**/*.h app/**/*.cpp)
python3 - "$limit" "${#files[@]}" "${files[@]}" "${allowed[@]}" <<'PY'
import re
import sys

limit = int(sys.argv[1])
n_files = int(sys.argv[2])
files = sys.argv[3:3 + n_files]
allowed = set(sys.argv[3 + n_files:])

KEYWORDS = {"if", "for", "while", "switch", "catch", "do", "else", "namespace", "class",
            "struct", "enum", "union", "return", "try"}


def blank(text):
    """The text with comments, literals and preprocessor lines replaced by spaces (newlines
    kept, so line numbers stay)."""
    out = []
    i, n = 0, len(text)
    line_start = True
    while i < n:
        c = text[i]
        if line_start and c in " \t":
            out.append(c)
            i += 1
            continue
        if line_start and c == "#":  # a preprocessor line, with its continuations
            while i < n and text[i] != "\n":
                if text[i] == "\\" and i + 1 < n and text[i + 1] == "\n":
                    out.append(" \n")
                    i += 2
                    continue
                out.append(" ")
                i += 1
            continue
        line_start = False
        if c == "\n":
            line_start = True
            out.append(c)
            i += 1
        elif text.startswith("//", i):
            while i < n and text[i] != "\n":
                out.append(" ")
                i += 1
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif c == "R" and i + 1 < n and text[i + 1] == '"' and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")):
            k = text.find("(", i + 2)
            delim = ")" + text[i + 2:k] + '"'
            j = text.find(delim, k)
            j = n if j < 0 else j + len(delim)
            out.append('""' + re.sub(r"[^\n]", " ", text[i + 2:j]))
            i = j
        elif c in "\"'":
            if c == "'" and i > 0 and text[i - 1].isalnum():  # a digit separator: 1'000
                out.append(" ")
                i += 1
                continue
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            j = min(j + 1, n)
            out.append(c + " " * (j - i - 2) + c if j - i >= 2 else " " * (j - i))
            i = j
        else:
            out.append(c)
            i += 1
    return "".join(out)


QUALIFIED = re.compile(r"\)\s*(?:const|noexcept(?:\s*\([^)]*\))?|override|final|mutable|volatile|&&|&|\s)*(?:->[^;{}]*)?$")
INIT_LIST = re.compile(r"\)\s*:(?!:)")


def function_name(header):
    """The name before the parameter list of a function header (text up to its body)."""
    cut = INIT_LIST.search(header)
    if cut:  # a constructor: the parameter list ends where its initializer list starts
        header = header[:cut.start() + 1]
    m = QUALIFIED.search(header)
    end = m.start() if m else len(header) - 1
    depth = 0
    for k in range(end, -1, -1):  # back to the '(' that opens the parameter list
        if header[k] == ")":
            depth += 1
        elif header[k] == "(":
            depth -= 1
            if depth == 0:
                name = re.search(r"(~?[A-Za-z_][\w:~]*(?:\s*<[^()]*>)?|operator\s*\S+)\s*$", header[:k])
                return (name.group(1) if name else "lambda"), k
    return "?", 0


def is_function_header(header):
    h = header.strip()
    if not h or ")" not in h:
        return False
    first = re.match(r"[A-Za-z_]\w*", h)
    if first and first.group(0) in KEYWORDS:
        return False
    return bool(QUALIFIED.search(h) or INIT_LIST.search(h))


failures = []
checked = 0
for path in files:
    text = blank(open(path, encoding="utf-8", errors="replace").read())
    checked += 1
    line = 1
    header, header_start = "", 0  # text since the last ; { or } at this level, its offset
    depth = 0
    func = None  # (name, line of the name, depth at which the body opened)
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if c == "\n":
            line += 1
        if func is None and c == "{" and INIT_LIST.search(header) and re.search(r"[\w>]\s*$", header):
            # A brace initializer in a constructor's initializer list: skip it.
            d, j = 0, i
            while j < n:
                if text[j] == "{":
                    d += 1
                elif text[j] == "}":
                    d -= 1
                    if d == 0:
                        break
                elif text[j] == "\n":
                    line += 1
                j += 1
            header += "{}"
            i = j + 1
            continue
        if c == "{":
            if func is None and is_function_header(header):
                name, k = function_name(header)
                name_line = line - header[k:].count("\n")
                func = (name, name_line, depth)
            depth += 1
            header, header_start = "", i + 1
        elif c == "}":
            depth -= 1
            if func is not None and depth == func[2]:
                length = line - func[1] + 1
                key = f"{path}:{func[0].split('::')[-1]}"
                if length > limit and key not in allowed and f"{path}:{func[0]}" not in allowed:
                    failures.append(f"{path}:{func[1]}: {func[0]} is {length} lines (limit {limit})")
                func = None
            header, header_start = "", i + 1
        elif c == ";":
            if func is None:
                header, header_start = "", i + 1
        elif func is None:
            header += c
        i += 1

for f in failures:
    print(f)
if failures:
    print(f"check-function-length: {len(failures)} functions over {limit} lines; split them into "
          "named stages (see core/mesh_builder.cpp)")
    sys.exit(1)
print(f"check-function-length: no function over {limit} lines in {checked} files "
      f"({len(allowed)} allowed in app/)")
PY
