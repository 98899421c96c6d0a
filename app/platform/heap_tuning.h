#pragma once
// Start-up setting of the executables (viewer, CLI, benchmarks): not part of the core, which
// never changes process-wide state.
namespace trilab {

/// Keeps large freed buffers in the heap instead of returning them to the system: glibc
/// otherwise unmaps every buffer above 128 KiB on free, and the next large allocation pays
/// a page fault per 4 KiB again (measured: a 1M-face binary PLY load takes 85 ms instead of
/// 450-700 ms here; llvmpipe frames suffer the same way, see
/// shared/docs/toolchain.md section 5). No effect on other C libraries.
void tune_heap_for_large_meshes();

}  // namespace trilab
