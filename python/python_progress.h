#pragma once
// The Progress of an operation that Python runs with the GIL released (python/module.cpp):
// on the thread that called it, every 20 ms at most, it takes the GIL back for a moment to
// run Python's signal handlers (PyErr_CheckSignals(): Ctrl+C raises KeyboardInterrupt) and
// the optional `progress=callback(fraction, stage)`. Either raising asks the operation to
// stop (it throws Cancelled, leaving its input unchanged); rethrow_if_stopped() then raises
// that Python error. Worker threads of the operation only read the stop flag.
#include <pybind11/pybind11.h>

#include <atomic>
#include <chrono>
#include <memory>
#include <string>
#include <thread>

#include "core/progress.h"

namespace trilab::python {

class PythonProgress final : public Progress {
public:
    /// `callback`: None, or a callable taking (fraction, stage).
    explicit PythonProgress(pybind11::object callback);
    ~PythonProgress() override;
    PythonProgress(const PythonProgress&) = delete;
    PythonProgress& operator=(const PythonProgress&) = delete;

    void report(double fraction, const char* stage) override;
    bool cancel_requested() const override;
    /// With the GIL held: raises the Python error that stopped the run, if one did.
    void rethrow_if_stopped();

private:
    /// Takes the GIL, runs the signal handlers and the callback (at most every 20 ms).
    void poll(bool force) const;

    pybind11::object callback_;
    std::thread::id owner_;
    mutable std::chrono::steady_clock::time_point last_poll_{};
    mutable double fraction_ = -1;
    mutable std::string stage_;
    mutable std::atomic<bool> stop_{false};
    mutable std::unique_ptr<pybind11::error_already_set> error_;
};

}  // namespace trilab::python
