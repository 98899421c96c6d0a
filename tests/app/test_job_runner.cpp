// The viewer's job runner and log: work runs off the calling thread, the finish function
// runs on the polling thread only on success, and failure or cancellation changes nothing.
#include <catch2/catch.hpp>

#include <chrono>
#include <thread>

#include "app/session/job_runner.h"
#include "app/session/log.h"
#include "core/errors.h"

using namespace trilab;
using namespace trilab::viewer;

namespace {
JobRunner::Outcome wait_for(JobRunner& runner) {
    for (int i = 0; i < 2000; ++i) {
        JobRunner::Outcome o = runner.poll();
        if (o.kind != JobRunner::Outcome::Kind::None) return o;
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    FAIL("the job did not finish within 2 s");
    return {};
}
}  // namespace

TEST_CASE("a job runs on another thread and finishes on the polling thread", "[app][jobs]") {
    JobRunner runner;
    int document = 0;
    std::thread::id worker, finisher;
    REQUIRE(runner.start("compute", [&](Progress& p) -> JobRunner::Finish {
        worker = std::this_thread::get_id();
        p.report(0.5, "halfway");
        const int result = 42;
        return [&document, &finisher, result] {
            finisher = std::this_thread::get_id();
            document = result;
        };
    }));
    REQUIRE(runner.busy());
    // A second job is refused while one runs.
    REQUIRE_FALSE(runner.start("other", [](Progress&) { return JobRunner::Finish([] {}); }));
    JobRunner::Outcome o = wait_for(runner);
    REQUIRE(o.kind == JobRunner::Outcome::Kind::Succeeded);
    REQUIRE(o.name == "compute");
    REQUIRE(document == 42);
    REQUIRE(worker != std::this_thread::get_id());
    REQUIRE(finisher == std::this_thread::get_id());
    REQUIRE_FALSE(runner.busy());
}

TEST_CASE("a failing job leaves the document untouched and reports why", "[app][jobs]") {
    JobRunner runner;
    int document = 7;
    runner.start("load", [&](Progress&) -> JobRunner::Finish {
        throw IoError("bad.obj", 3, "not a number");
        return [&document] { document = 0; };
    });
    JobRunner::Outcome o = wait_for(runner);
    REQUIRE(o.kind == JobRunner::Outcome::Kind::Failed);
    REQUIRE(o.message == "bad.obj:3: not a number");
    REQUIRE(document == 7);
}

TEST_CASE("a cancelled job leaves the document untouched", "[app][jobs]") {
    JobRunner runner;
    int document = 7;
    std::atomic<bool> started{false};
    runner.start("long", [&](Progress& p) -> JobRunner::Finish {
        started = true;
        for (int i = 0; i < 10000; ++i) {
            p.report(i / 10000.0, "working");
            p.check_cancelled();
            std::this_thread::sleep_for(std::chrono::microseconds(200));
        }
        return [&document] { document = 0; };
    });
    while (!started) std::this_thread::yield();
    runner.cancel();
    REQUIRE(runner.cancel_requested());
    JobRunner::Outcome o = wait_for(runner);
    REQUIRE(o.kind == JobRunner::Outcome::Kind::Cancelled);
    REQUIRE(document == 7);
    // A job that cannot notice the request still has its result discarded.
    runner.start("uninterruptible", [&](Progress&) -> JobRunner::Finish {
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
        return [&document] { document = 0; };
    });
    runner.cancel();
    REQUIRE(wait_for(runner).kind == JobRunner::Outcome::Kind::Cancelled);
    REQUIRE(document == 7);
}

TEST_CASE("the log keeps levels and order and is bounded", "[app][log]") {
    Log log(false);
    log.info("a");
    log.warning("b");
    log.error("c");
    auto e = log.entries();
    REQUIRE(e.size() == 3);
    REQUIRE(e[0].level == LogEntry::Level::Info);
    REQUIRE(e[2].level == LogEntry::Level::Error);
    REQUIRE(e[1].text == "b");
    for (std::size_t i = 0; i < Log::kMaxEntries + 10; ++i) log.info("x");
    REQUIRE(log.size() == Log::kMaxEntries);
}
