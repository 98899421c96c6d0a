#pragma once
// How much memory this process can still get: the core sizes its buffers and refuses work
// that would not fit (spectral decomposition, file and image reads) against it.
#include <cstdint>

namespace trilab {

/// Bytes of memory this process can still get now: the smaller of MemAvailable in
/// /proc/meminfo and what the memory cgroup (v2 memory.max - memory.current, or v1
/// memory.limit_in_bytes - memory.usage_in_bytes) leaves; sysconf(_SC_AVPHYS_PAGES) where
/// /proc is absent; 2 GiB when nothing can be read.
std::uint64_t available_memory_bytes();

}  // namespace trilab
