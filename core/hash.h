#pragma once
// A 64-bit mixer for the core's hash tables over bit patterns (positions, grid cells).
#include <cstdint>

namespace trilab {

/// MurmurHash3's 64-bit finalizer (Appleby): a bijection whose every input bit affects every
/// output bit, so that nearby keys spread over the table.
inline std::uint64_t mix_bits(std::uint64_t h) {
    h ^= h >> 33;
    h *= 0xff51afd7ed558ccdULL;
    h ^= h >> 33;
    h *= 0xc4ceb9fe1a85ec53ULL;
    h ^= h >> 33;
    return h;
}

}  // namespace trilab
