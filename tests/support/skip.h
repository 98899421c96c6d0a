#pragma once
// Skipped tests: a test case that cannot run (all or part of it) because something outside the
// repository is missing (../shared, O_TMPFILE, ffmpeg, ...) records why with skip() and returns.
// The test runner (test_main.cpp) then exits with kSkipExitCode when nothing failed, and CTest
// (SKIP_RETURN_CODE) reports the test as Skipped instead of Passed. A failure in the part that
// did run still exits non-zero with the failure count: failures always win over skips.
#include <sstream>
#include <string>

namespace trilab::test {

/// The runner's exit status when a test was skipped and none failed (CTest's SKIP_RETURN_CODE).
constexpr int kSkipExitCode = 77;

/// Records that the running test case skipped something, and why (printed as a Catch2 warning
/// "skipped: <reason>").
void skip(const std::string& reason);
/// How many skips were recorded in this process.
int skips_recorded();
/// True when `path` exists; otherwise records a skip naming it and returns false.
bool present_or_skip(const std::string& path);

}  // namespace trilab::test

/// Skips the rest of the current test case; `reason` may be a stream expression
/// (`SKIP_TEST(dir << " has no O_TMPFILE")`).
#define SKIP_TEST(reason)                             \
    do {                                              \
        std::ostringstream trilab_skip_reason;        \
        trilab_skip_reason << reason;                 \
        trilab::test::skip(trilab_skip_reason.str()); \
        return;                                       \
    } while (0)

/// Skips the rest of the current test case when `path` (a file under ../shared) is absent.
#define SKIP_IF_MISSING(path)                             \
    do {                                                  \
        if (!trilab::test::present_or_skip(path)) return; \
    } while (0)
