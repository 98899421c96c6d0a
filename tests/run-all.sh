#!/usr/bin/env bash
# Every test, as CI runs it (.ci/run calls this script; it is README's set-up command 2):
#  1. installs the Debian packages that are missing (third_party/install-deps.sh);
#  2. Release build of everything and the whole CTest suite (build/), the Python module's
#     pytest files (label `python`, /usr/bin/python3) and the staging install included;
#  3. naming check: clang-tidy with .clang-tidy on the C++ files the change touches
#     (tests/lint/check-naming.sh; TRILAB_TIDY_BASE=all checks every file);
#  4. sanitizer job: RelWithDebInfo build with AddressSanitizer and UndefinedBehaviorSanitizer
#     (-DTRILAB_SANITIZE=ON) and floating-point traps in the tests (-DTRILAB_FP_TRAPS=ON), and
#     the whole CTest suite again (build-asan/); the Python module and the staging install are
#     not built or registered there (CMakeLists.txt: an uninstrumented python3 cannot load an
#     ASan module without LD_PRELOAD);
#  5. ThreadSanitizer job: RelWithDebInfo build with -DTRILAB_TSAN=ON of the tests labelled
#     `tsan` only (the job runner, the log, the panels, the headless session: target
#     trilab_tsan_tests), run with `ctest -L tsan`; any race report fails the run (build-tsan/);
#  6. fuzz job: the libFuzzer targets built with clang (-DTRILAB_FUZZ=ON, build-fuzz/), each
#     run for TRILAB_FUZZ_SECONDS (default 15) on its seed corpus; any failure fails the run.
# The sanitizer, ThreadSanitizer and fuzz builds keep line tables only (-g1): their reports
# name files and lines, and the builds take less of CI's 45 minutes than with full -g.
# Every build has -DTRILAB_WERROR=ON: a warning in our code fails the run.
# Stops at the first failing step. See README "Tests" and "Hardening".
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
fuzz_seconds="${TRILAB_FUZZ_SECONDS:-15}"
line_tables=(-DCMAKE_C_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG"
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG")

./third_party/install-deps.sh

echo "== Release build and tests"
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DTRILAB_WERROR=ON
cmake --build build -j2
ctest --test-dir build --output-on-failure -j2

echo "== Naming check (clang-tidy, the changed files)"
tests/lint/check-naming.sh build

echo "== Sanitizer job (ASan + UBSan, floating-point traps)"
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo "${line_tables[@]}" -DTRILAB_SANITIZE=ON \
    -DTRILAB_WERROR=ON -DTRILAB_FP_TRAPS=ON
cmake --build build-asan -j2
ctest --test-dir build-asan --output-on-failure -j2

echo "== ThreadSanitizer job (the app's threads: job runner, log, panels, session)"
cmake -S . -B build-tsan -DCMAKE_BUILD_TYPE=RelWithDebInfo "${line_tables[@]}" -DTRILAB_TSAN=ON \
    -DTRILAB_WERROR=ON
cmake --build build-tsan -j2 --target trilab_tsan_tests
# halt_on_error: the first report ends the test with a failure (exit status 66).
TSAN_OPTIONS="halt_on_error=1 second_deadlock_stack=1" \
    ctest --test-dir build-tsan -L tsan --no-tests=error --output-on-failure -j2

echo "== Fuzz job (${fuzz_seconds} s per reader)"
cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo "${line_tables[@]}" -DCMAKE_C_COMPILER=clang \
    -DCMAKE_CXX_COMPILER=clang++ -DTRILAB_FUZZ=ON -DTRILAB_BUILD_VIEWER=OFF \
    -DTRILAB_BUILD_TESTS=OFF -DTRILAB_WERROR=ON
cmake --build build-fuzz -j2 --target trilab_fuzzers
tests/fuzz/run-fuzzers.sh build-fuzz "$fuzz_seconds"
