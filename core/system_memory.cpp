#include "core/system_memory.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

namespace trilab {

namespace {

/// The first number in a small text file (a cgroup limit), or false ("max", absent).
bool read_number(const char* path, std::uint64_t& value) {
    std::FILE* f = std::fopen(path, "r");
    if (!f) return false;
    unsigned long long v = 0;
    const bool ok = std::fscanf(f, "%llu", &v) == 1;
    std::fclose(f);
    value = v;
    return ok;
}

/// MemAvailable from /proc/meminfo in bytes, or false.
bool meminfo_available(std::uint64_t& bytes) {
    std::FILE* f = std::fopen("/proc/meminfo", "r");
    if (!f) return false;
    char line[256];
    bool found = false;
    while (std::fgets(line, sizeof(line), f)) {
        unsigned long long kb = 0;
        if (std::sscanf(line, "MemAvailable: %llu kB", &kb) == 1) {
            bytes = std::uint64_t(kb) * 1024;
            found = true;
            break;
        }
    }
    std::fclose(f);
    return found;
}

/// What a cgroup limit leaves (limit - usage), or false when there is no limit.
bool cgroup_left(const char* limit_path, const char* usage_path, std::uint64_t& left) {
    std::uint64_t limit = 0, usage = 0;
    if (!read_number(limit_path, limit) || limit >= (std::uint64_t(1) << 60)) return false;
    if (!read_number(usage_path, usage)) usage = 0;
    left = limit > usage ? limit - usage : 0;
    return true;
}

}  // namespace

std::uint64_t available_memory_bytes() {
    std::uint64_t best = 0;
    bool known = meminfo_available(best);
    if (!known) {
        const long pages = sysconf(_SC_AVPHYS_PAGES);
        const long page_size = sysconf(_SC_PAGESIZE);
        if (pages > 0 && page_size > 0) {
            best = std::uint64_t(pages) * std::uint64_t(page_size);
            known = true;
        }
    }
    std::uint64_t left = 0;
    if (cgroup_left("/sys/fs/cgroup/memory.max", "/sys/fs/cgroup/memory.current", left) ||
        cgroup_left("/sys/fs/cgroup/memory/memory.limit_in_bytes",
                    "/sys/fs/cgroup/memory/memory.usage_in_bytes", left)) {
        best = known ? std::min(best, left) : left;
        known = true;
    }
    return known ? best : std::uint64_t(2) << 30;
}

}  // namespace trilab
