#pragma once
// A normal end the user did not ask for in the window: SIGTERM (a logout, `systemctl stop`,
// `kill`) or SIGHUP (the terminal closed). The viewer treats it as a quit without the
// unsaved-changes question: its crash journal is kept for recovery and marked as an end
// without saving (Journal::end_unsaved), so the next start says the work was not saved rather
// than that the viewer crashed.
#include <functional>

namespace trilab {

/// Blocks SIGTERM and SIGHUP in the calling thread (call it first in main(), before any other
/// thread starts, so that every thread inherits the mask) and starts a thread that waits for
/// them; on one, termination_signal() names it and `wake` runs on that thread (the viewer
/// wakes its event loop). Never throws; does nothing when the signals cannot be blocked.
void watch_termination(std::function<void()> wake);

/// "SIGTERM" or "SIGHUP" once one arrived, else nullptr. Thread-safe.
const char* termination_signal();

}  // namespace trilab
