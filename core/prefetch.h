#pragma once
// prefetch(p): a hint that the memory at `p` will be read soon, for loops that know a few
// elements ahead where they will read (the connectivity passes of the builder, the statistics
// and the validator), so that the memory latency overlaps the work. No effect where the
// compiler has no such builtin.

namespace trilab {

inline void prefetch(const void* p) {
#if defined(__GNUC__) || defined(__clang__)
    __builtin_prefetch(p);
#else
    (void)p;
#endif
}

}  // namespace trilab
