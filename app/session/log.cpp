#include "app/session/log.h"

#include <cstdio>

namespace trilab::viewer {

void Log::add(LogEntry::Level level, const std::string& text) {
    if (echo_) {
        std::FILE* out = level == LogEntry::Level::Error ? stderr : stdout;
        const char* prefix = level == LogEntry::Level::Error     ? "error: "
                             : level == LogEntry::Level::Warning ? "warning: "
                                                                 : "";
        std::fprintf(out, "trilab: %s%s\n", prefix, text.c_str());
        std::fflush(out);
    }
    std::lock_guard<std::mutex> lock(mutex_);
    entries_.push_back({level, text});
    if (entries_.size() > kMaxEntries)
        entries_.erase(entries_.begin(), entries_.begin() + (entries_.size() - kMaxEntries));
}

std::vector<LogEntry> Log::entries() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return entries_;
}

std::size_t Log::size() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return entries_.size();
}

void Log::clear() {
    std::lock_guard<std::mutex> lock(mutex_);
    entries_.clear();
}

}  // namespace trilab::viewer
