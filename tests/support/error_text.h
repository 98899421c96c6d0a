#pragma once
// The text of the error an expression throws, for tests that match error messages.
#include <string>

#include "core/errors.h"

namespace trilab::test {

/// The what() of the `E` that `f()` throws, "" when it throws none; any other exception
/// propagates (and fails the test).
template <class E = Error, class F>
std::string error_text(F&& f) {
    try {
        f();
    } catch (const E& e) {
        return e.what();
    }
    return "";
}

}  // namespace trilab::test
