#pragma once
// Process-wide settings the executables (viewer, CLI, benchmark) apply at start-up, and the
// few facts about the machine the core needs.
#include <cstdint>

namespace trilab {

/// Keeps large freed buffers in the heap instead of returning them to the system: glibc
/// otherwise unmaps every buffer above 128 KiB on free, and the next large allocation pays
/// a page fault per 4 KiB again (measured: a 1M-face binary PLY load takes 85 ms instead of
/// 450-700 ms here; llvmpipe frames suffer the same way, see
/// shared/docs/toolchain.md section 5). No effect on other C libraries.
void tune_heap_for_large_meshes();

/// Bytes of memory this process can still get now: the smaller of MemAvailable in
/// /proc/meminfo and what the memory cgroup (v2 memory.max - memory.current, or v1
/// memory.limit_in_bytes - memory.usage_in_bytes) leaves; sysconf(_SC_AVPHYS_PAGES) where
/// /proc is absent; 2 GiB when nothing can be read.
std::uint64_t available_memory_bytes();

}  // namespace trilab
