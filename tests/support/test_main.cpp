// The Catch2 runner of every trilab test executable (instead of Catch2WithMain):
//  - enables floating-point traps when built with TRILAB_FP_TRAPS (tests/support/fp_traps.h);
//  - exits with kSkipExitCode when a test case recorded a skip and none failed, so CTest
//    reports it as Skipped (tests/support/skip.h).
#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>

#include <cstdio>

#include "tests/support/fp_traps.h"
#include "tests/support/skip.h"

int main(int argc, char* argv[]) {
#ifdef TRILAB_FP_TRAPS
    trilab::test::enable_fp_traps();
#endif
    const int failed = Catch::Session().run(argc, argv);
    if (failed != 0) return failed == trilab::test::kSkipExitCode ? failed + 1 : failed;
    if (trilab::test::skips_recorded() > 0) {
        std::fprintf(stderr, "%d skip(s) recorded, no failure: exit status %d (skipped)\n",
                     trilab::test::skips_recorded(), trilab::test::kSkipExitCode);
        return trilab::test::kSkipExitCode;
    }
    return 0;
}
