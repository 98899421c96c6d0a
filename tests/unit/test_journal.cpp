// The crash journal (app/history/journal.h): every history change (push, undo, redo, jump,
// a push that drops the redo entries, budget trims, a reset) is restored bit for bit; a
// journal cut at any byte or damaged restores a prefix of the changes (or nothing, refused),
// saying what was lost; a process killed (SIGKILL) at random moments leaves exactly the
// changes it completed; an unwritable folder warns once and never throws; a clean close
// removes the file; journals of dead processes are found.
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <chrono>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "app/history/journal.h"
#include "app/history/session_file.h"
#include "core/errors.h"
#include "core/io/file_util.h"
#include "session_test_util.h"

using namespace trilab;

namespace {

std::string temp_dir(const std::string& name) {
    const std::string dir = test::temp_path(name);
    mkdir(dir.c_str(), 0700);
    return dir;
}

void remove_dir(const std::string& dir) {
    const std::string cmd = "rm -rf '" + dir + "'";
    REQUIRE(std::system(cmd.c_str()) == 0);
}

/// The scripted changes: after each, the history is recorded. Deterministic.
std::vector<History::Snapshot> scripted_run(History& h, Journal* journal, bool flush_each) {
    std::vector<History::Snapshot> states;
    const auto record = [&] {
        states.push_back(h.snapshot());
        if (journal) {
            journal->record(states.back());
            if (flush_each) journal->flush();
        }
    };
    h.reset(make_icosphere(4), "Load sphere");
    record();
    test::push_operation(h, "noise --amount 2 --seed 1");
    record();
    test::push_operation(h, "smooth --iterations 3");
    record();
    h.undo();
    record();
    h.redo();
    record();
    test::push_operation(h, "subdivide --scheme loop --iterations 1");
    record();
    h.jump(1);
    record();
    test::push_operation(h, "decimate --target-vertices 80");  // drops the redo entries
    record();
    h.set_budget(h.bytes() / 2);  // drops the oldest entries
    h.trim_to_budget();
    record();
    h.set_budget(std::size_t(-1));
    test::push_operation(h, "smooth --iterations 1");
    record();
    h.reset(make_tetrahedron(), "Load tetrahedron");  // a new document
    record();
    test::push_operation(h, "noise --amount 4 --seed 9");
    record();
    return states;
}

History from_snapshot(const History::Snapshot& s) {
    History h(std::size_t(-1));
    std::vector<History::EntryRecord> records;
    for (const auto& e : s.entries) records.push_back(*e);
    h.restore(records, s.current);
    return h;
}

}  // namespace

TEST_CASE("the journal restores every kind of history change bit for bit", "[journal]") {
    const std::string dir = temp_dir("journal-changes");
    JournalOptions options;
    options.directory = dir;
    options.sync = false;
    Journal journal(options);
    History h(std::size_t(-1));
    const std::vector<History::Snapshot> states = scripted_run(h, &journal, true);
    journal.record_viewer_settings("camera=1 2 3\n");
    journal.flush();
    REQUIRE(journal.take_warning() == "");
    const std::string path = journal.path();
    REQUIRE(path == dir + "/trilab-" + std::to_string(getpid()) + ".journal");
    const SessionContents s = read_journal(path);
    CHECK(s.journal);
    CHECK(s.complete);
    CHECK(s.bytes_discarded == 0);
    CHECK(s.records >= states.size() - 1);
    CHECK(s.pid == std::uint32_t(getpid()));
    CHECK(s.extras.viewer_settings == "camera=1 2 3\n");
    test::require_same_history(h, s.history);
    const Journal::Stats stats = journal.stats();
    CHECK(stats.records == states.size());
    CHECK(stats.bytes == s.file_bytes);
    journal.close();
    struct stat st {};
    CHECK(stat(path.c_str(), &st) != 0);  // a clean close removes it
    remove_dir(dir);
}

TEST_CASE("a journal cut at any byte restores a prefix of the changes", "[journal]") {
    const std::string dir = temp_dir("journal-cut");
    JournalOptions options;
    options.directory = dir;
    options.sync = false;
    std::vector<History::Snapshot> states;
    std::string bytes;
    History h(std::size_t(-1));
    {
        Journal journal(options);
        states = scripted_run(h, &journal, true);
        journal.flush();
        bytes = read_file_bytes(journal.path());
    }
    std::vector<History> expected;
    for (const History::Snapshot& s : states) expected.push_back(from_snapshot(s));
    std::size_t last_records = 0;
    std::size_t restored = 0;
    // Every byte in the first 4 KiB and near the end, every 97th elsewhere.
    for (std::size_t n = 0; n <= bytes.size(); ++n) {
        if (n > 4096 && n + 4096 < bytes.size() && n % 97 != 0) continue;
        INFO("cut at " << n << " of " << bytes.size());
        try {
            const SessionContents s = read_journal_bytes(std::string_view(bytes).substr(0, n), "j");
            REQUIRE(s.records >= 1);
            REQUIRE(s.records <= expected.size());
            REQUIRE(s.records >= last_records);  // a longer prefix never restores less
            last_records = s.records;
            test::require_same_history(expected[s.records - 1], s.history);
            REQUIRE(s.bytes_discarded <= n);
            REQUIRE(s.complete == (s.bytes_discarded == 0 && s.stop_reason.empty()));
            ++restored;
        } catch (const IoError& e) {
            REQUIRE(last_records == 0);  // refused only before the first complete entry
            REQUIRE(std::string(e.what()).rfind("j: ", 0) == 0);
        }
    }
    CHECK(restored > 0);
    CHECK(last_records == states.size());
    remove_dir(dir);
}

TEST_CASE("a journal with damaged bytes restores the changes before them", "[journal]") {
    const std::string dir = temp_dir("journal-damaged");
    JournalOptions options;
    options.directory = dir;
    options.sync = false;
    std::vector<History::Snapshot> states;
    std::string bytes;
    History h(std::size_t(-1));
    {
        Journal journal(options);
        states = scripted_run(h, &journal, true);
        journal.flush();
        bytes = read_file_bytes(journal.path());
    }
    std::vector<History> expected;
    for (const History::Snapshot& s : states) expected.push_back(from_snapshot(s));
    std::mt19937 rng(11);
    for (int trial = 0; trial < 300; ++trial) {
        std::string damaged = bytes;
        const std::size_t at = rng() % damaged.size();
        damaged[at] = char(damaged[at] ^ char(1 + rng() % 255));
        INFO("byte " << at);
        try {
            const SessionContents s = read_journal_bytes(damaged, "j");
            REQUIRE_FALSE(s.complete);
            REQUIRE(s.bytes_discarded > 0);
            REQUIRE(s.bytes_discarded >= damaged.size() - at);
            test::require_same_history(expected[s.records - 1], s.history);
        } catch (const IoError&) {
            // Only the header or the first entry can be damaged for this.
        }
    }
    remove_dir(dir);
}

TEST_CASE("a process killed at random moments leaves exactly its complete changes",
          "[journal][slow]") {
    // The expected states, computed here: the child runs the same deterministic script.
    History reference(std::size_t(-1));
    const std::vector<History::Snapshot> states = scripted_run(reference, nullptr, false);
    std::vector<History> expected;
    for (const History::Snapshot& s : states) expected.push_back(from_snapshot(s));
    std::mt19937 rng(2024);
    int kills = 0, restored = 0;
    for (int run = 0; run < 30; ++run) {
        const std::string dir = temp_dir("journal-kill-" + std::to_string(run));
        const pid_t child = fork();
        REQUIRE(child >= 0);
        if (child == 0) {
            JournalOptions options;
            options.directory = dir;
            Journal journal(options);
            History h(std::size_t(-1));
            scripted_run(h, &journal, false);
            journal.flush();
            pause();  // waits for the kill
            _exit(0);
        }
        std::this_thread::sleep_for(std::chrono::microseconds(rng() % 60000));
        kill(child, SIGKILL);
        int status = 0;
        waitpid(child, &status, 0);
        kills += WIFSIGNALED(status) ? 1 : 0;
        const std::vector<OrphanJournal> orphans = find_orphan_journals(dir);
        INFO("run " << run);
        if (!orphans.empty()) {
            REQUIRE(orphans.size() == 1);
            REQUIRE(orphans[0].pid == std::uint32_t(child));
            try {
                const SessionContents s = read_journal(orphans[0].path);
                // Coalesced records: the restored history is one of the scripted states.
                bool found = false;
                for (const History& e : expected) {
                    if (e.size() != s.history.size() || e.current() != s.history.current())
                        continue;
                    bool same = true;
                    for (std::size_t i = 0; i < e.size() && same; ++i)
                        same = e.info(i).label == s.history.info(i).label &&
                               e.info(i).operation == s.history.info(i).operation;
                    if (!same) continue;
                    test::require_same_history(e, s.history, false);
                    found = true;
                    break;
                }
                REQUIRE(found);
                ++restored;
            } catch (const IoError& e) {
                // Killed before the first entry was complete (or before the 16-byte header was:
                // a kill right after the file was created, seen under the sanitizers' slower
                // start).
                const std::string what = e.what();
                INFO(what);
                REQUIRE((what.find("no complete entry") != std::string::npos ||
                         what.find("shorter than the 16-byte header") != std::string::npos));
            }
        }
        remove_dir(dir);
    }
    CHECK(kills == 30);
    CHECK(restored > 0);
}

TEST_CASE("an unwritable journal folder warns once and never throws", "[journal]") {
    JournalOptions options;
    options.directory = "/proc/version/trilab";  // under a file: cannot be created
    Journal journal(options);
    History h(std::size_t(-1));
    scripted_run(h, &journal, true);
    journal.flush();
    CHECK(journal.failed());
    const std::string warning = journal.take_warning();
    CHECK(warning.find("Crash journal: cannot create /proc/version/trilab") != std::string::npos);
    CHECK(journal.take_warning() == "");
    CHECK(journal.path() == "");
    CHECK_NOTHROW(journal.close());
}

TEST_CASE("a full disk stops the journal with one warning", "[journal]") {
    const std::string dir = temp_dir("journal-full");
    // A file size limit stands for a full disk: write() fails with EFBIG past it.
    struct rlimit old {};
    getrlimit(RLIMIT_FSIZE, &old);
    const auto old_handler = signal(SIGXFSZ, SIG_IGN);
    struct rlimit small = old;
    small.rlim_cur = 40000;
    REQUIRE(setrlimit(RLIMIT_FSIZE, &small) == 0);
    JournalOptions options;
    options.directory = dir;
    options.sync = false;
    Journal journal(options);
    History h(std::size_t(-1));
    CHECK_NOTHROW(scripted_run(h, &journal, true));
    journal.flush();
    setrlimit(RLIMIT_FSIZE, &old);
    signal(SIGXFSZ, old_handler);
    CHECK(journal.failed());
    CHECK(journal.take_warning().find("cannot write") != std::string::npos);
    CHECK(journal.take_warning() == "");
    // What was written restores a prefix.
    const SessionContents s = read_journal(journal.path());
    CHECK(s.history.size() >= 1);
    journal.close();
    remove_dir(dir);
}

TEST_CASE("the recovery folder follows XDG_STATE_HOME", "[journal]") {
    const char* old_state = std::getenv("XDG_STATE_HOME");
    const std::string saved = old_state ? old_state : "";
    setenv("XDG_STATE_HOME", "/var/tmp/state", 1);
    CHECK(default_recovery_directory() == "/var/tmp/state/trilab/recovery");
    unsetenv("XDG_STATE_HOME");
    setenv("HOME", std::getenv("HOME") ? std::getenv("HOME") : "/root", 1);
    CHECK(default_recovery_directory() ==
          std::string(std::getenv("HOME")) + "/.local/state/trilab/recovery");
    if (old_state) setenv("XDG_STATE_HOME", saved.c_str(), 1);
}

TEST_CASE("find_orphan_journals lists journals of processes that are gone", "[journal]") {
    const std::string dir = temp_dir("journal-orphans");
    // A process that is gone: a child that exited.
    const pid_t child = fork();
    REQUIRE(child >= 0);
    if (child == 0) _exit(0);
    waitpid(child, nullptr, 0);
    const auto touch = [&](const std::string& name) {
        std::FILE* f = std::fopen((dir + "/" + name).c_str(), "w");
        REQUIRE(f);
        std::fputs("x", f);
        std::fclose(f);
    };
    touch("trilab-" + std::to_string(child) + ".journal");
    touch("trilab-" + std::to_string(getpid()) + ".journal");  // this process: not an orphan
    touch("trilab-1.journal");  // init runs, and its start time cannot be told: not listed
    touch("notes.txt");
    const std::vector<OrphanJournal> orphans = find_orphan_journals(dir);
    REQUIRE(orphans.size() == 1);
    CHECK(orphans[0].pid == std::uint32_t(child));
    CHECK(orphans[0].ended.empty());  // no note: a crash
    CHECK(find_orphan_journals(dir + "/missing").empty());
    remove_dir(dir);
}

TEST_CASE("a journal ended without saving is kept, marked, and removed with its note",
          "[journal]") {
    const std::string dir = temp_dir("journal-ended");
    // A viewer ended by SIGTERM: its journal holds the history and says how it ended.
    const pid_t child = fork();
    REQUIRE(child >= 0);
    if (child == 0) {
        JournalOptions options;
        options.directory = dir;
        options.sync = false;
        Journal journal(options);
        History h(std::size_t(-1));
        scripted_run(h, &journal, true);
        journal.end_unsaved("SIGTERM");
        _exit(journal.path().empty() ? 1 : 0);
    }
    int status = 0;
    waitpid(child, &status, 0);
    REQUIRE(WIFEXITED(status));
    REQUIRE(WEXITSTATUS(status) == 0);
    std::vector<OrphanJournal> orphans = find_orphan_journals(dir);
    REQUIRE(orphans.size() == 1);  // the note is no journal of its own
    CHECK(orphans[0].ended == "SIGTERM");
    const SessionContents contents = read_journal(orphans[0].path);
    CHECK(contents.complete);
    CHECK(contents.history.size() > 1);
    // A note that is no regular file (a FIFO) is not read: the journal counts as a crash.
    const std::string note = orphans[0].path + ".ended";
    REQUIRE(std::remove(note.c_str()) == 0);
    REQUIRE(mkfifo(note.c_str(), 0600) == 0);
    orphans = find_orphan_journals(dir);
    REQUIRE(orphans.size() == 1);
    CHECK(orphans[0].ended.empty());
    remove_journal(orphans[0].path);
    struct stat st {};
    CHECK(stat(orphans[0].path.c_str(), &st) != 0);
    CHECK(stat(note.c_str(), &st) != 0);
    CHECK(find_orphan_journals(dir).empty());
    remove_dir(dir);
}
