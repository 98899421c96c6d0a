#include "python/python_progress.h"

#include <utility>

namespace py = pybind11;

namespace trilab::python {

PythonProgress::PythonProgress(py::object callback)
    : callback_(std::move(callback)), owner_(std::this_thread::get_id()) {}

PythonProgress::~PythonProgress() {
    // The saved error and the callback are Python objects: released with the GIL held (the
    // destructor runs where the caller holds it, after the run).
    error_.reset();
}

void PythonProgress::report(double fraction, const char* stage) {
    if (std::this_thread::get_id() != owner_) return;
    fraction_ = fraction;
    stage_ = stage ? stage : "";
    poll(false);
}

bool PythonProgress::cancel_requested() const {
    if (std::this_thread::get_id() == owner_ && !stop_.load(std::memory_order_relaxed)) poll(false);
    return stop_.load(std::memory_order_relaxed);
}

void PythonProgress::poll(bool force) const {
    const auto now = std::chrono::steady_clock::now();
    if (!force && now - last_poll_ < std::chrono::milliseconds(20)) return;
    last_poll_ = now;
    py::gil_scoped_acquire gil;
    if (PyErr_CheckSignals() != 0) {
        error_ = std::make_unique<py::error_already_set>();
        stop_ = true;
        return;
    }
    if (callback_.is_none()) return;
    try {
        callback_(fraction_, stage_);
    } catch (py::error_already_set& e) {
        error_ = std::make_unique<py::error_already_set>(std::move(e));
        stop_ = true;
    }
}

void PythonProgress::rethrow_if_stopped() {
    if (!error_) return;
    py::error_already_set e = std::move(*error_);
    error_.reset();
    throw e;
}

}  // namespace trilab::python
