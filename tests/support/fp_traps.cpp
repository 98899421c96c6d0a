#include "tests/support/fp_traps.h"

namespace trilab::test {

// feenableexcept / fedisableexcept / fegetexcept are glibc extensions (<fenv.h>, _GNU_SOURCE,
// which g++ and clang++ define by default).
void enable_fp_traps() {
    std::feclearexcept(FE_ALL_EXCEPT);
    feenableexcept(kTrappedExceptions);
}

void disable_fp_traps() {
    fedisableexcept(FE_ALL_EXCEPT);
    std::feclearexcept(FE_ALL_EXCEPT);
}

FpTrapsOff::FpTrapsOff() : saved_(fegetexcept()) {
    fedisableexcept(FE_ALL_EXCEPT);
}

FpTrapsOff::~FpTrapsOff() {
    // A flag left set by the masked code would fire at the next x87 instruction once unmasked.
    std::feclearexcept(FE_ALL_EXCEPT);
    if (saved_ != 0) feenableexcept(saved_);
}

}  // namespace trilab::test
