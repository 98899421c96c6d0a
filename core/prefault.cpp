// Mapping fresh memory on two threads; see prefault.h.
#include "core/prefault.h"

#include <cstdint>

#if defined(__linux__)
#include <sys/mman.h>
#include <unistd.h>
#endif

namespace trilab {

void populate_half(const void* data, std::size_t bytes, int part) {
#if defined(__linux__) && defined(MADV_POPULATE_WRITE)
    const std::uintptr_t page = std::uintptr_t(::sysconf(_SC_PAGESIZE));
    const std::uintptr_t begin = reinterpret_cast<std::uintptr_t>(data);
    const std::uintptr_t mid = begin + bytes / 2;
    const std::uintptr_t from = ((part == 0 ? begin : mid) + page - 1) & ~(page - 1);
    const std::uintptr_t to = (part == 0 ? mid : begin + bytes) & ~(page - 1);
    if (to > from) ::madvise(reinterpret_cast<void*>(from), to - from, MADV_POPULATE_WRITE);
#else
    (void)data;
    (void)bytes;
    (void)part;
#endif
}

}  // namespace trilab
