#!/usr/bin/env bash
# The layering of README "Architecture", checked on the #include lines:
#   core/             the mesh kernel: includes only other kernel headers;
#   core/algorithms/  includes the kernel and other algorithms, never core/io/;
#   core/ (all)       never app/, render/, GL, glad, GLFW or ImGui;
#   render/           never app/ or ImGui.
# Prints every include that breaks a rule (file:line) and exits 1 when there is one.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/../.."
status=0
# check PATTERN REASON FILES...: every include matching PATTERN in FILES is a violation.
check() {
    local pattern="$1" reason="$2"
    shift 2
    local hits
    hits="$(grep -nE "^[[:space:]]*#[[:space:]]*include[[:space:]]*[<\"]($pattern)" "$@" || true)"
    if [ -n "$hits" ]; then
        printf '%s\n' "$hits" | sed "s|\$|   <- $reason|"
        status=1
    fi
}
shopt -s nullglob
kernel=(core/*.h core/*.cpp)
algorithms=(core/algorithms/*.h core/algorithms/*.cpp)
core_all=("${kernel[@]}" "${algorithms[@]}" core/io/*.h core/io/*.cpp)
render=(render/*.h render/*.cpp)
check 'core/[a-z_]+/' "the kernel includes only kernel headers" "${kernel[@]}"
check 'core/io/' "algorithms never include files (core/io/)" "${algorithms[@]}"
check 'app/|render/|glad/|GL/|GLFW/|EGL/|imgui' "core never includes app, render, GL or ImGui" \
    "${core_all[@]}"
check 'app/|imgui' "render never includes app or ImGui" "${render[@]}"
[ "$status" = 0 ] && echo "check-layers: ${#core_all[@]} core and ${#render[@]} render files keep the layers"
exit "$status"
