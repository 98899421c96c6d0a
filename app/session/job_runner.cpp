#include "app/session/job_runner.h"

#include <chrono>
#include <exception>

namespace trilab::viewer {

struct JobRunner::State final : Progress {
    std::string name;
    JobKind kind = JobKind::Document;
    std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
    std::atomic<double> fraction{-1.0};
    std::atomic<bool> cancel{false};
    std::atomic<bool> done{false};
    mutable std::mutex mutex;  // guards stage, finish, error
    std::string stage;
    Finish finish;
    std::string error;
    bool was_cancelled = false;
    double seconds = 0;

    void report(double f, const char* s) override {
        fraction.store(f);
        std::lock_guard<std::mutex> lock(mutex);
        stage = s ? s : "";
    }
    bool cancel_requested() const override { return cancel.load(); }
};

JobRunner::~JobRunner() {
    if (state_) state_->cancel = true;
    if (thread_.joinable()) thread_.join();
}

bool JobRunner::start(std::string name, Work work, JobKind kind) {
    if (state_) return false;
    auto state = std::make_shared<State>();
    state->name = std::move(name);
    state->kind = kind;
    state_ = state;
    thread_ = std::thread([state, work = std::move(work)]() {
        Finish finish;
        std::string error;
        bool cancelled = false;
        try {
            finish = work(*state);
        } catch (const Cancelled&) {
            cancelled = true;
        } catch (const std::exception& e) {
            error = e.what();
        } catch (...) {
            error = "unknown error";
        }
        {
            std::lock_guard<std::mutex> lock(state->mutex);
            state->finish = std::move(finish);
            state->error = std::move(error);
            state->was_cancelled = cancelled;
            state->seconds =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - state->start)
                    .count();
        }
        state->done = true;
    });
    return true;
}

void JobRunner::cancel() {
    if (state_) state_->cancel = true;
}

JobRunner::Outcome JobRunner::poll() {
    Outcome out;
    if (!state_ || !state_->done) return out;
    thread_.join();
    std::shared_ptr<State> state = std::move(state_);
    state_.reset();
    out.name = state->name;
    out.job = state->kind;
    out.seconds = state->seconds;
    if (state->cancel || state->was_cancelled) {
        out.kind = Outcome::Kind::Cancelled;
    } else if (!state->error.empty() || !state->finish) {
        out.kind = Outcome::Kind::Failed;
        out.message = state->error.empty() ? "the job returned nothing" : state->error;
    } else {
        try {
            state->finish();
            out.kind = Outcome::Kind::Succeeded;
        } catch (const std::exception& e) {
            out.kind = Outcome::Kind::Failed;
            out.message = e.what();
        }
    }
    return out;
}

JobKind JobRunner::kind() const {
    return state_ ? state_->kind : JobKind::Document;
}

std::string JobRunner::name() const {
    return state_ ? state_->name : std::string();
}

double JobRunner::fraction() const {
    return state_ ? state_->fraction.load() : -1.0;
}

std::string JobRunner::stage() const {
    if (!state_) return {};
    std::lock_guard<std::mutex> lock(state_->mutex);
    return state_->stage;
}

double JobRunner::elapsed_seconds() const {
    if (!state_) return 0;
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - state_->start).count();
}

bool JobRunner::cancel_requested() const {
    return state_ && state_->cancel.load();
}

}  // namespace trilab::viewer
