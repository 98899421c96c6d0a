// The crash journal (app/history/journal.h): a writer thread that appends the differences
// between consecutive history snapshots as session-file chunks.
#include "app/history/journal.h"

#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <optional>
#include <thread>

#include "app/history/chunk_io.h"
#include "app/history/session_encoder.h"

namespace trilab {

namespace {

using Clock = std::chrono::steady_clock;

double ms_between(Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double, std::milli>(b - a).count();
}

/// Field 22 of /proc/PID/stat: the process's start time in clock ticks (0 if unknown).
std::uint64_t process_start_ticks(long pid) {
    char path[64];
    std::snprintf(path, sizeof path, "/proc/%ld/stat", pid);
    std::FILE* f = std::fopen(path, "r");
    if (!f) return 0;
    char buf[1024];
    const std::size_t n = std::fread(buf, 1, sizeof buf - 1, f);
    std::fclose(f);
    buf[n] = 0;
    const char* p = std::strrchr(buf, ')');  // the name may hold spaces
    if (!p) return 0;
    // Fields 3.. follow the name; the start time is field 22.
    int field = 2;
    for (; *p && field < 21; ++p)
        if (*p == ' ') ++field;
    return std::strtoull(p, nullptr, 10);
}

/// Creates `dir` and its parents (mode 0700).
bool make_directories(const std::string& dir) {
    std::string partial;
    for (std::size_t i = 0; i <= dir.size(); ++i) {
        if (i == dir.size() || (dir[i] == '/' && i > 0)) {
            partial = dir.substr(0, i);
            if (mkdir(partial.c_str(), 0700) != 0 && errno != EEXIST) return false;
        }
    }
    struct stat s {};
    return stat(dir.c_str(), &s) == 0 && S_ISDIR(s.st_mode);
}

/// The pid in "trilab-PID.journal", or 0.
std::uint32_t journal_pid(const std::string& name) {
    const std::string prefix = "trilab-", suffix = ".journal";
    if (name.size() <= prefix.size() + suffix.size() || name.rfind(prefix, 0) != 0 ||
        name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0)
        return 0;
    const std::string digits =
        name.substr(prefix.size(), name.size() - prefix.size() - suffix.size());
    if (digits.empty() || digits.size() > 10 ||
        digits.find_first_not_of("0123456789") != std::string::npos)
        return 0;
    const unsigned long long v = std::strtoull(digits.c_str(), nullptr, 10);
    return v > 0 && v < 0xFFFFFFFFull ? std::uint32_t(v) : 0;
}

/// The process start time recorded in a journal's JRNL chunk (0 if unreadable).
std::uint64_t recorded_start_ticks(const std::string& path) {
    const int fd = open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
    if (fd < 0) return 0;
    std::string bytes(4096, '\0');
    const ssize_t n = read(fd, bytes.data(), bytes.size());
    close(fd);
    if (n < 0) return 0;
    bytes.resize(std::size_t(n));
    try {
        const ChunkView c = read_chunk(bytes, kFileHeaderBytes);
        if (c.type != session_chunk::kJournal) return 0;
        ByteReader r(c.payload);
        r.u32("pid");
        return r.u64("start");
    } catch (const ChunkError&) {
        return 0;
    }
}

}  // namespace

std::string default_recovery_directory() {
    const char* state = std::getenv("XDG_STATE_HOME");
    if (state && *state == '/') return std::string(state) + "/trilab/recovery";
    const char* home = std::getenv("HOME");
    if (home && *home) return std::string(home) + "/.local/state/trilab/recovery";
    return "";
}

// ---- the writer ------------------------------------------------------------------------------

struct Journal::Impl {
    explicit Impl(JournalOptions o) : options(std::move(o)) {
        if (options.directory.empty()) options.directory = default_recovery_directory();
        thread = std::thread([this] { run(); });
    }

    JournalOptions options;
    mutable std::mutex mutex;
    std::condition_variable wake, idle;
    std::optional<History::Snapshot> pending;
    std::optional<std::string> pending_settings;
    bool stopping = false, busy = false;
    std::string file_path, warning;
    bool failed = false, warned = false;
    Stats stats;
    std::thread thread;

    // The writer thread's own state.
    int fd = -1;
    std::unique_ptr<SessionEncoder> encoder;
    std::string buffer;
    History::Snapshot written;     ///< the last snapshot written (keeps its arrays alive)
    std::size_t file_current = 0;  ///< the current entry as a reader of the file sees it

    void run();
    void write_one(const std::optional<History::Snapshot>& snapshot,
                   const std::optional<std::string>& settings);
    bool open_file();
    void encode(const History::Snapshot& s);
    bool append_and_sync();
    void fail(const std::string& what, int error);
};

void Journal::Impl::fail(const std::string& what, int error) {
    std::lock_guard<std::mutex> lock(mutex);
    failed = true;
    if (!warned) {
        warning = "Crash journal: " + what + ": " + std::strerror(error) +
                  "; the session is not journaled from now on (save it to keep it)";
        warned = true;
    }
}

bool Journal::Impl::open_file() {
    if (options.directory.empty()) {
        fail("no folder for the journal (neither XDG_STATE_HOME nor HOME is set)", ENOENT);
        return false;
    }
    if (!make_directories(options.directory)) {
        fail("cannot create " + options.directory, errno);
        return false;
    }
    const std::string path = options.directory + "/trilab-" + std::to_string(getpid()) + ".journal";
    fd = open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
    if (fd < 0) {
        fail("cannot create " + path, errno);
        return false;
    }
    {
        std::lock_guard<std::mutex> lock(mutex);
        file_path = path;
    }
    encoder = std::make_unique<SessionEncoder>(
        [this](const char* data, std::size_t size) { buffer.append(data, size); });
    encoder->file_header(true);
    encoder->journal_info(std::uint32_t(getpid()), process_start_ticks(long(getpid())),
                          options.program);
    return true;
}

void Journal::Impl::encode(const History::Snapshot& s) {
    const auto& old = written.entries;
    const auto& now = s.entries;
    if (now.empty()) return;
    std::size_t from = 0;  // the first entry of `now` to write
    const auto first = std::find(old.begin(), old.end(), now.front());
    if (first == old.end()) {
        from = 0;  // a new history (a reset, or everything before was dropped)
    } else {
        const std::size_t dropped = std::size_t(first - old.begin());
        if (dropped > 0) {
            encoder->drop_front(std::uint32_t(dropped));
            file_current -= std::min(file_current, dropped);
        }
        std::size_t common = 0;
        while (common < now.size() && dropped + common < old.size() &&
               old[dropped + common] == now[common])
            ++common;
        if (common == now.size() && dropped + common < old.size()) {
            encoder->keep(std::uint32_t(common));
            file_current = std::min(file_current, common - 1);
        }
        from = common;
    }
    for (std::size_t i = from; i < now.size(); ++i) {
        encoder->entry(std::uint32_t(i), *now[i]);
        file_current = i;
    }
    if (file_current != s.current) {
        encoder->current(std::uint32_t(s.current));
        file_current = s.current;
    }
}

bool Journal::Impl::append_and_sync() {
    const auto t0 = Clock::now();
    std::size_t done = 0;
    while (done < buffer.size()) {
        const ssize_t n = write(fd, buffer.data() + done, buffer.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            fail("cannot write " + file_path, n < 0 ? errno : ENOSPC);
            return false;
        }
        done += std::size_t(n);
    }
    const auto t1 = Clock::now();
    if (options.sync && fdatasync(fd) != 0) {
        fail("cannot sync " + file_path, errno);
        return false;
    }
    const auto t2 = Clock::now();
    std::lock_guard<std::mutex> lock(mutex);
    stats.write_ms += ms_between(t0, t1);
    stats.sync_ms += ms_between(t1, t2);
    stats.bytes += buffer.size();
    return true;
}

void Journal::Impl::write_one(const std::optional<History::Snapshot>& snapshot,
                              const std::optional<std::string>& settings) {
    if (failed) return;
    if (fd < 0 && !open_file()) return;
    const auto t0 = Clock::now();
    try {
        if (snapshot) encode(*snapshot);
        if (settings) encoder->viewer_settings(*settings);
    } catch (const std::exception& e) {
        fail(std::string("cannot encode the history (") + e.what() + ")", ENOMEM);
        return;
    }
    {
        std::lock_guard<std::mutex> lock(mutex);
        stats.encode_ms += ms_between(t0, Clock::now());
    }
    if (!append_and_sync()) return;
    buffer.clear();
    if (snapshot) {
        encoder->retain_only(*snapshot);
        written = *snapshot;  // releases the previous snapshot's arrays
        std::lock_guard<std::mutex> lock(mutex);
        ++stats.records;
    }
}

void Journal::Impl::run() {
    std::unique_lock<std::mutex> lock(mutex);
    for (;;) {
        wake.wait(lock, [this] { return stopping || pending || pending_settings; });
        if (!pending && !pending_settings) break;  // stopping, nothing left
        std::optional<History::Snapshot> snapshot = std::move(pending);
        std::optional<std::string> settings = std::move(pending_settings);
        pending.reset();
        pending_settings.reset();
        busy = true;
        lock.unlock();
        write_one(snapshot, settings);
        snapshot.reset();
        lock.lock();
        busy = false;
        idle.notify_all();
    }
    if (fd >= 0) ::close(fd);
    fd = -1;
    written = History::Snapshot{};
    idle.notify_all();
}

Journal::Journal(JournalOptions options) : impl_(std::make_unique<Impl>(std::move(options))) {}

Journal::~Journal() {
    stop();
}

void Journal::stop() {
    if (!impl_) return;
    {
        std::lock_guard<std::mutex> lock(impl_->mutex);
        impl_->stopping = true;
    }
    impl_->wake.notify_all();
    if (impl_->thread.joinable()) impl_->thread.join();
}

void Journal::record(History::Snapshot snapshot) noexcept {
    try {
        {
            std::lock_guard<std::mutex> lock(impl_->mutex);
            if (impl_->failed || impl_->stopping) return;
            impl_->pending = std::move(snapshot);  // coalesces with one not written yet
        }
        impl_->wake.notify_one();
    } catch (...) {
        // Out of memory for the queue: this change is journaled with the next one.
    }
}

void Journal::record_viewer_settings(std::string text) noexcept {
    try {
        {
            std::lock_guard<std::mutex> lock(impl_->mutex);
            if (impl_->failed || impl_->stopping) return;
            impl_->pending_settings = std::move(text);
        }
        impl_->wake.notify_one();
    } catch (...) {
    }
}

void Journal::flush() {
    std::unique_lock<std::mutex> lock(impl_->mutex);
    impl_->idle.wait(lock, [this] {
        return (!impl_->pending && !impl_->pending_settings && !impl_->busy) ||
               !impl_->thread.joinable();
    });
}

void Journal::close() {
    if (!impl_) return;
    stop();
    const std::string p = path();
    if (!p.empty()) unlink(p.c_str());
}

void Journal::end_unsaved(const std::string& how) {
    if (!impl_) return;
    stop();
    const std::string p = path();
    if (p.empty()) return;
    const std::string note = p + ".ended";
    if (FILE* f = std::fopen(note.c_str(), "w")) {
        std::fputs(how.c_str(), f);
        std::fclose(f);
    }
}

void remove_journal(const std::string& path) {
    unlink(path.c_str());
    unlink((path + ".ended").c_str());
}

std::string Journal::path() const {
    std::lock_guard<std::mutex> lock(impl_->mutex);
    return impl_->file_path;
}

std::string Journal::take_warning() {
    std::lock_guard<std::mutex> lock(impl_->mutex);
    return std::exchange(impl_->warning, std::string());
}

bool Journal::failed() const {
    std::lock_guard<std::mutex> lock(impl_->mutex);
    return impl_->failed;
}

Journal::Stats Journal::stats() const {
    std::lock_guard<std::mutex> lock(impl_->mutex);
    return impl_->stats;
}

// ---- finding journals ------------------------------------------------------------------------

std::vector<OrphanJournal> find_orphan_journals(const std::string& directory) {
    std::vector<OrphanJournal> out;
    const std::string dir = directory.empty() ? default_recovery_directory() : directory;
    if (dir.empty()) return out;
    DIR* d = opendir(dir.c_str());
    if (!d) return out;
    while (const dirent* e = readdir(d)) {
        const std::uint32_t pid = journal_pid(e->d_name);
        if (pid == 0 || pid == std::uint32_t(getpid())) continue;
        const std::string path = dir + "/" + e->d_name;
        struct stat s {};
        if (stat(path.c_str(), &s) != 0 || !S_ISREG(s.st_mode)) continue;
        const bool exists = kill(pid_t(pid), 0) == 0 || errno == EPERM;
        if (exists) {
            // The same id may belong to a new process: compare the start times.
            const std::uint64_t recorded = recorded_start_ticks(path);
            if (recorded == 0 || recorded == process_start_ticks(long(pid))) continue;
        }
        OrphanJournal orphan{path, pid, std::uint64_t(s.st_size), std::int64_t(s.st_mtime), ""};
        const std::string note = path + ".ended";
        struct stat ns {};
        if (stat(note.c_str(), &ns) != 0 || !S_ISREG(ns.st_mode)) {
            out.push_back(std::move(orphan));
            continue;
        }
        orphan.ended = "ended";  // a note that cannot be read still says so
        if (FILE* f = std::fopen(note.c_str(), "r")) {
            char how[64] = {};
            const std::size_t n = std::fread(how, 1, sizeof how - 1, f);
            std::fclose(f);
            if (n > 0) orphan.ended.assign(how, n);
        }
        out.push_back(std::move(orphan));
    }
    closedir(d);
    std::sort(out.begin(), out.end(), [](const OrphanJournal& a, const OrphanJournal& b) {
        return a.modified != b.modified ? a.modified > b.modified : a.path < b.path;
    });
    return out;
}

}  // namespace trilab
