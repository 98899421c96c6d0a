#pragma once
// Mapping the fresh memory of a large array before it is filled, on two threads. A first
// write to a page that the process has never touched costs a page fault, in which the kernel
// finds, clears and maps the page; a large load (17.8M faces: about 1.5 GB) otherwise takes
// those faults one at a time, on whichever thread writes first. MADV_POPULATE_WRITE (Linux
// 5.14) maps a range in one call, without a fault per page; two threads each map half of
// each array. Only a hint: nothing changes where the kernel lacks it.
#include <cstddef>
#include <vector>

#include "core/two_threads.h"

namespace trilab {

/// Has the kernel map the whole pages of half `part` (0: the first, 1: the second) of
/// [data, data + bytes) for writing; does nothing off Linux or where the kernel refuses.
void populate_half(const void* data, std::size_t bytes, int part);

/// Reserves n elements in each array and, when `parallel`, has two threads map the fresh
/// pages of those n elements (populate_half) before the caller's resize or fill writes them.
template <typename... T>
void reserve_prefaulted(std::size_t n, bool parallel, std::vector<T>&... arrays) {
    (arrays.reserve(n), ...);
    if (!parallel) return;
    on_two_threads(true,
                   [&](int part) { (populate_half(arrays.data(), n * sizeof(T), part), ...); });
}

}  // namespace trilab
