#pragma once
// Progress reporting and cancellation for long operations. An operation that may take long
// takes a `Progress&` (default: a NullProgress that never cancels), calls report() now and
// then, and throws Cancelled from check_cancelled() when asked to stop. The viewer's job
// runner implements Progress with atomics, so report() is cheap from a worker thread.
#include <string>

#include "core/errors.h"

namespace trilab {

/// Thrown by an operation that noticed a cancellation request; the operation's input is
/// left as it was.
class Cancelled : public Error {
public:
    Cancelled() : Error("cancelled") {}
};

class Progress {
public:
    virtual ~Progress() = default;
    /// `fraction` in [0, 1] (or negative when unknown), and what is being done.
    virtual void report(double fraction, const char* stage) = 0;
    /// Whether the user asked to stop.
    virtual bool cancel_requested() const = 0;
    /// Throws Cancelled when the user asked to stop.
    void check_cancelled() const {
        if (cancel_requested()) throw Cancelled();
    }
};

/// A Progress that ignores reports and never cancels.
class NullProgress final : public Progress {
public:
    void report(double, const char*) override {}
    bool cancel_requested() const override { return false; }
};

}  // namespace trilab
