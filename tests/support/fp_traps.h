#pragma once
// Floating-point traps in the test runs (libigl's tests do the same). With -DTRILAB_FP_TRAPS=ON
// (the default for Debug builds; CI's sanitizer job turns it on) the test runner enables
// FE_INVALID, FE_DIVBYZERO and FE_OVERFLOW before any test runs, so the first operation that
// makes a NaN, divides by zero or overflows raises SIGFPE there (Catch2 names the test case).
// Threads inherit the setting from the thread that creates them.
#include <cfenv>

namespace trilab::test {

constexpr int kTrappedExceptions = FE_INVALID | FE_DIVBYZERO | FE_OVERFLOW;

/// Unmasks kTrappedExceptions in the calling thread (the runner calls it once at start-up).
void enable_fp_traps();
/// Masks every trap in the calling thread for good, for code we do not own that raises
/// floating-point exceptions as a matter of course (Mesa's llvmpipe, see render_test_util.h).
void disable_fp_traps();

/// Masks every floating-point trap for its lifetime, for a test that feeds deliberately
/// non-finite input (NaN, inf, a diverging run) to code that must detect it. Restores the
/// traps that were enabled, after clearing the flags the masked code raised.
class FpTrapsOff {
public:
    FpTrapsOff();
    ~FpTrapsOff();
    FpTrapsOff(const FpTrapsOff&) = delete;
    FpTrapsOff& operator=(const FpTrapsOff&) = delete;

private:
    int saved_;
};

}  // namespace trilab::test
