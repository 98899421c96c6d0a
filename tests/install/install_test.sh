#!/usr/bin/env bash
# Installs the build to a staging prefix (cmake --install BUILD --prefix TMP) and checks what
# was installed: trilab-cli --version says the project's version, the Python module imports
# from the prefix with the same __version__, and a small C++ program (tests/install/consumer)
# builds against the installed CMake package (find_package(trilab) -> trilab::core) and runs.
# usage: install_test.sh BUILD_DIR VERSION [PYTHON [PYTHON_DIR]]   (PYTHON_DIR relative to the prefix)
set -euo pipefail
build="$1"
version="$2"
python="${3:-}"
python_dir="${4:-}"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
prefix="$tmp/prefix"

cmake --install "$build" --prefix "$prefix" >"$tmp/install.log" || { cat "$tmp/install.log"; exit 1; }
echo "installed to a staging prefix: $(find "$prefix" -type f | wc -l) files"

got="$("$prefix/bin/trilab-cli" --version)"
[ "$got" = "trilab-cli $version" ] || { echo "FAILED: trilab-cli --version said '$got'"; exit 1; }
echo "ok: $got"
if [ -x "$prefix/bin/trilab" ]; then
    got="$("$prefix/bin/trilab" --version)"
    [ "$got" = "trilab $version" ] || { echo "FAILED: trilab --version said '$got'"; exit 1; }
    for f in share/applications/trilab.desktop share/mime/packages/trilab.xml \
             share/icons/hicolor/scalable/apps/trilab.svg; do
        [ -f "$prefix/$f" ] || { echo "FAILED: $f not installed"; exit 1; }
    done
    echo "ok: $got, desktop file, MIME type, icon"
fi

if [ -n "$python" ]; then
    got="$(cd "$tmp" && PYTHONPATH="$prefix/$python_dir" "$python" -c \
        "import trilab, sys; assert trilab.__file__.startswith(sys.argv[1]), trilab.__file__; \
print(trilab.__version__)" "$prefix")"
    [ "$got" = "$version" ] || { echo "FAILED: trilab.__version__ is '$got'"; exit 1; }
    echo "ok: import trilab from $python_dir, __version__ $got"
fi

cmake -S "$here/consumer" -B "$tmp/consumer" -DCMAKE_PREFIX_PATH="$prefix" \
    -DCMAKE_BUILD_TYPE=Release >"$tmp/consumer.log" 2>&1 &&
    cmake --build "$tmp/consumer" >>"$tmp/consumer.log" 2>&1 ||
    { cat "$tmp/consumer.log"; echo "FAILED: the consumer did not build"; exit 1; }
"$tmp/consumer/consumer" "$tmp/icosphere.off"
[ -s "$tmp/icosphere.off" ] || { echo "FAILED: the consumer wrote no mesh"; exit 1; }
echo "ok: a program built against find_package(trilab) -> trilab::core"
