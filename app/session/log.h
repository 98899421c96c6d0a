#pragma once
// Log: the messages the viewer shows in its Log panel and also prints to the console (the
// reference program posted its information messages to the console). Thread-safe, so jobs
// may log from their worker thread. Errors go to stderr, the rest to stdout.
#include <cstddef>
#include <mutex>
#include <string>
#include <vector>

namespace trilab::viewer {

struct LogEntry {
    enum class Level { Info, Warning, Error };
    Level level = Level::Info;
    std::string text;
};

class Log {
public:
    explicit Log(bool echo_to_console = true) : echo_(echo_to_console) {}
    void info(const std::string& text) { add(LogEntry::Level::Info, text); }
    void warning(const std::string& text) { add(LogEntry::Level::Warning, text); }
    void error(const std::string& text) { add(LogEntry::Level::Error, text); }
    void add(LogEntry::Level level, const std::string& text);
    /// A copy of the entries (at most the newest kMaxEntries).
    std::vector<LogEntry> entries() const;
    std::size_t size() const;
    void clear();

    static constexpr std::size_t kMaxEntries = 5000;

private:
    mutable std::mutex mutex_;
    std::vector<LogEntry> entries_;
    bool echo_;
};

}  // namespace trilab::viewer
