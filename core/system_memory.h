#pragma once
// How much memory this process can still get: the core sizes its buffers and refuses work
// that would not fit (spectral decomposition, file and image reads, session files) against
// it, before allocating.
#include <cstdint>
#include <string>

namespace trilab {

/// What this process may still allocate, and what limits it.
struct AvailableMemory {
    std::uint64_t bytes = 0;
    /// The binding limit, with its figures, for messages: "free memory (MemAvailable)",
    /// "the address-space limit (ulimit -v) of 1.0 GiB, 0.2 GiB of it in use", "the data
    /// limit (ulimit -d) ...", "the memory cgroup's limit of 2.0 GiB, 1.5 GiB of it in use".
    std::string limit;
};

/// The smallest of: MemAvailable in /proc/meminfo (sysconf(_SC_AVPHYS_PAGES) where /proc is
/// absent); the address-space limit (RLIMIT_AS) minus this process's address space
/// (VmSize); the data limit (RLIMIT_DATA) minus its data segment (VmData); and what its
/// memory cgroup leaves (v2 memory.max - memory.current, or v1 memory.limit_in_bytes -
/// memory.usage_in_bytes). 2 GiB when nothing can be read.
AvailableMemory available_memory();

/// available_memory().bytes.
std::uint64_t available_memory_bytes();

/// "1.5 GiB" (or MiB below 1 GiB), for messages.
std::string format_memory_size(double bytes);

}  // namespace trilab
