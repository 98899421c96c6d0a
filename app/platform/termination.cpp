// SIGTERM and SIGHUP as a normal end; see termination.h.
#include "app/platform/termination.h"

#include <pthread.h>
#include <signal.h>

#include <atomic>
#include <thread>
#include <utility>

namespace trilab {
namespace {

std::atomic<const char*> g_signal{nullptr};

}  // namespace

void watch_termination(std::function<void()> wake) {
    sigset_t set;
    sigemptyset(&set);
    sigaddset(&set, SIGTERM);
    sigaddset(&set, SIGHUP);
    if (pthread_sigmask(SIG_BLOCK, &set, nullptr) != 0) return;
    try {
        std::thread([set, wake = std::move(wake)] {
            int received = 0;
            if (sigwait(&set, &received) != 0) return;
            g_signal.store(received == SIGHUP ? "SIGHUP" : "SIGTERM");
            if (wake) wake();
        }).detach();
    } catch (const std::exception&) {
        pthread_sigmask(SIG_UNBLOCK, &set, nullptr);  // no watcher: the default action then
    }
}

const char* termination_signal() {
    return g_signal.load();
}

}  // namespace trilab
