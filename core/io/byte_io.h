#pragma once
// Byte-level helpers shared by the binary readers and the writers: loads with optional byte
// swapping, and a buffered output that writes text, numbers and binary scalars in large
// blocks.
#include <algorithm>
#include <charconv>
#include <cstring>
#include <ostream>
#include <string>
#include <string_view>

namespace trilab {

#if defined(__BYTE_ORDER__) && defined(__ORDER_BIG_ENDIAN__) && \
    __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__
inline constexpr bool kLittleEndianHost = false;
#else
inline constexpr bool kLittleEndianHost = true;
#endif
constexpr bool host_is_little_endian() {
    return kLittleEndianHost;
}

/// Loads a T stored at p (no alignment needed), byte-swapped when Swap.
template <class T, bool Swap>
inline T load_bytes(const unsigned char* p) {
    T v;
    if constexpr (Swap && sizeof(T) > 1) {
        unsigned char b[sizeof(T)];
        for (std::size_t i = 0; i < sizeof(T); ++i) b[i] = p[sizeof(T) - 1 - i];
        std::memcpy(&v, b, sizeof(T));
    } else {
        std::memcpy(&v, p, sizeof(T));
    }
    return v;
}

/// Buffered output to a stream; binary scalars are byte-swapped when `swap` is set.
class OutBuffer {
public:
    OutBuffer(std::ostream& out, bool swap) : out_(out), swap_(swap) { buf_.reserve(kBlock + 256); }
    void text(std::string_view s) {
        buf_.append(s.data(), s.size());
        maybe_flush();
    }
    template <class T>
    void binary(T v) {
        char b[sizeof(T)];
        std::memcpy(b, &v, sizeof(T));
        if (swap_) std::reverse(b, b + sizeof(T));
        buf_.append(b, sizeof(T));
    }
    /// The shortest decimal text that reads back as exactly v.
    template <class T>
    void number(T v) {
        char b[64];
        const auto r = std::to_chars(b, b + sizeof(b), v);
        buf_.append(b, static_cast<std::size_t>(r.ptr - b));
    }
    void maybe_flush() {
        if (buf_.size() >= kBlock) flush();
    }
    void flush() {
        out_.write(buf_.data(), static_cast<std::streamsize>(buf_.size()));
        buf_.clear();
    }

private:
    static constexpr std::size_t kBlock = 1 << 20;
    std::ostream& out_;
    bool swap_;
    std::string buf_;
};

}  // namespace trilab
