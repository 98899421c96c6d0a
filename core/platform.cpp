#include "core/platform.h"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace trilab {

void tune_heap_for_large_meshes() {
#if defined(__GLIBC__)
    mallopt(M_MMAP_THRESHOLD, 256 << 20);
    mallopt(M_TRIM_THRESHOLD, 512 << 20);
#endif
}

}  // namespace trilab
