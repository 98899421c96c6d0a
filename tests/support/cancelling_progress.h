#pragma once
// A Progress that asks to stop after a budget, for the cancellation tests. Thread-safe: the
// spectral code reports from worker threads.
#include <atomic>

#include "core/progress.h"

namespace trilab::test {

class CancellingProgress final : public Progress {
public:
    /// Cancels at the first check.
    static CancellingProgress at_once() { return CancellingProgress(Budget::Checks, 0); }
    /// Cancels once cancel_requested() has been asked `n` times (from the (n+1)-th ask on).
    static CancellingProgress after_checks(int n) { return CancellingProgress(Budget::Checks, n); }
    /// Cancels once report() has been called `n` times.
    static CancellingProgress after_reports(int n) {
        return CancellingProgress(Budget::Reports, n);
    }

    void report(double fraction, const char*) override {
        ++reports_;
        // Each fraction is compared with the previous report (meaningful where one thread
        // reports, as in subdivision; with several reporters only the counts are).
        if (fraction < last_fraction_.load() || fraction > 1.0) fractions_ok_ = false;
        last_fraction_ = fraction;
    }
    bool cancel_requested() const override {
        const int asked = checks_++;
        return budget_ == Budget::Checks ? asked >= allowed_ : reports_.load() >= allowed_;
    }

    int checks() const { return checks_.load(); }
    int reports() const { return reports_.load(); }
    /// Whether every reported fraction was at least the one before (starting at 0) and <= 1.
    bool fractions_ok() const { return fractions_ok_.load(); }

private:
    enum class Budget { Checks, Reports };
    CancellingProgress(Budget budget, int allowed) : budget_(budget), allowed_(allowed) {}

    Budget budget_;
    int allowed_;
    mutable std::atomic<int> checks_{0};
    std::atomic<int> reports_{0};
    std::atomic<double> last_fraction_{0.0};
    std::atomic<bool> fractions_ok_{true};
};

}  // namespace trilab::test
