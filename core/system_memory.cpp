#include "core/system_memory.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstring>

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

/// A "Name:   N kB" line of /proc/self/status in bytes, or false.
bool status_bytes(const char* name, std::uint64_t& bytes) {
    std::FILE* f = std::fopen("/proc/self/status", "r");
    if (!f) return false;
    char line[256];
    bool found = false;
    const std::size_t n = std::strlen(name);
    while (std::fgets(line, sizeof(line), f)) {
        unsigned long long kb = 0;
        if (std::strncmp(line, name, n) == 0 && line[n] == ':' &&
            std::sscanf(line + n + 1, " %llu kB", &kb) == 1) {
            bytes = std::uint64_t(kb) * 1024;
            found = true;
            break;
        }
    }
    std::fclose(f);
    return found;
}

/// What a resource limit leaves beyond what is in use (`status` names the /proc/self/status
/// line of the usage), or false when the limit is infinite.
bool rlimit_left(int resource, const char* status, std::uint64_t& limit, std::uint64_t& used) {
    struct rlimit r {};
    if (getrlimit(resource, &r) != 0 || r.rlim_cur == RLIM_INFINITY) return false;
    limit = std::uint64_t(r.rlim_cur);
    if (!status_bytes(status, used)) used = 0;
    return true;
}

}  // namespace

std::string format_memory_size(double bytes) {
    char buf[48];
    if (bytes >= double(1u << 30))
        std::snprintf(buf, sizeof buf, "%.1f GiB", bytes / double(1u << 30));
    else
        std::snprintf(buf, sizeof buf, "%.0f MiB", bytes / double(1u << 20));
    return buf;
}

AvailableMemory available_memory() {
    AvailableMemory best;
    bool known = meminfo_available(best.bytes);
    if (known) {
        best.limit = "free memory (MemAvailable)";
    } else {
        const long pages = sysconf(_SC_AVPHYS_PAGES);
        const long page_size = sysconf(_SC_PAGESIZE);
        if (pages > 0 && page_size > 0) {
            best = {std::uint64_t(pages) * std::uint64_t(page_size), "free memory"};
            known = true;
        }
    }
    const auto consider = [&](std::uint64_t left, const std::string& what) {
        if (!known || left < best.bytes) best = {left, what};
        known = true;
    };
    const auto in_use = [](const char* what, std::uint64_t limit, std::uint64_t used) {
        return std::string(what) + " of " + format_memory_size(double(limit)) + ", " +
               format_memory_size(double(used)) + " of it in use";
    };
    std::uint64_t limit = 0, used = 0;
    if (rlimit_left(RLIMIT_AS, "VmSize", limit, used))
        consider(limit > used ? limit - used : 0,
                 in_use("the address-space limit (ulimit -v)", limit, used));
    if (rlimit_left(RLIMIT_DATA, "VmData", limit, used))
        consider(limit > used ? limit - used : 0,
                 in_use("the data limit (ulimit -d)", limit, used));
    std::uint64_t left = 0;
    if (cgroup_left("/sys/fs/cgroup/memory.max", "/sys/fs/cgroup/memory.current", left) ||
        cgroup_left("/sys/fs/cgroup/memory/memory.limit_in_bytes",
                    "/sys/fs/cgroup/memory/memory.usage_in_bytes", left))
        consider(left, "what the memory cgroup's limit leaves");
    if (!known) best = {std::uint64_t(2) << 30, "an assumed 2 GiB (nothing could be read)"};
    return best;
}

std::uint64_t available_memory_bytes() {
    return available_memory().bytes;
}

}  // namespace trilab
