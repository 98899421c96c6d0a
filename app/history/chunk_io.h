#pragma once
// The byte layer of session files and crash journals (docs/file-formats.md#session-files):
// little-endian numbers, length-prefixed strings, a CRC-32 checksum, and chunks
//   u32 type (four ASCII letters), u32 zero, u64 payload size, payload, u32 CRC-32, u32 zero
// where the CRC covers the type, the size and the payload. Everything that reads is bounds
// checked and throws ChunkError with the reason; nothing here allocates more than the bytes
// it was given can describe.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <functional>
#include <stdexcept>
#include <string>
#include <string_view>

namespace trilab {

static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__,
              "session files are written in the host's byte order, which must be little-endian");

/// A malformed chunk or field: the reason, without the file name (the reader adds it).
class ChunkError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// CRC-32 (the IEEE 802.3 polynomial, reflected, as zlib and PNG use it), continued from
/// `crc` (0 to start). Table-driven, eight bytes per step.
std::uint32_t crc32_update(std::uint32_t crc, const void* data, std::size_t size);

/// Bytes are handed to a sink as they are made (a file stream, a buffer).
using ByteSink = std::function<void(const char* data, std::size_t size)>;

/// Builds one payload in memory (small chunks) or streams a large array through write_raw.
class ByteWriter {
public:
    void u8(std::uint8_t v) { bytes_.push_back(char(v)); }
    void u32(std::uint32_t v) { raw(&v, 4); }
    void u64(std::uint64_t v) { raw(&v, 8); }
    void f64(double v) { raw(&v, 8); }
    void str(std::string_view s) {
        u32(std::uint32_t(s.size()));
        bytes_.append(s.data(), s.size());
    }
    void raw(const void* p, std::size_t n) { bytes_.append(static_cast<const char*>(p), n); }
    const std::string& bytes() const { return bytes_; }
    std::string& bytes() { return bytes_; }

private:
    std::string bytes_;
};

/// Reads a payload; every read checks the bounds (ChunkError "truncated FIELD").
class ByteReader {
public:
    explicit ByteReader(std::string_view bytes) : bytes_(bytes) {}
    std::uint8_t u8(const char* what) {
        need(1, what);
        return std::uint8_t(bytes_[pos_++]);
    }
    std::uint32_t u32(const char* what) {
        std::uint32_t v;
        copy(&v, 4, what);
        return v;
    }
    std::uint64_t u64(const char* what) {
        std::uint64_t v;
        copy(&v, 8, what);
        return v;
    }
    double f64(const char* what) {
        double v;
        copy(&v, 8, what);
        return v;
    }
    /// A string of at most `max` bytes.
    std::string str(const char* what, std::size_t max = std::size_t(1) << 30) {
        const std::uint32_t n = u32(what);
        if (n > max)
            throw ChunkError(std::string(what) + ": " + std::to_string(n) +
                             " bytes, more than the " + std::to_string(max) + " allowed");
        return std::string(view(n, what));
    }
    std::string_view view(std::size_t n, const char* what) {
        need(n, what);
        std::string_view v = bytes_.substr(pos_, n);
        pos_ += n;
        return v;
    }
    std::size_t left() const { return bytes_.size() - pos_; }
    /// Throws unless every byte was read ("N bytes after FIELD").
    void finish(const char* what) const {
        if (left() != 0)
            throw ChunkError(std::to_string(left()) + " unexpected bytes after the " + what);
    }

private:
    void need(std::size_t n, const char* what) const {
        if (n > bytes_.size() - pos_) throw ChunkError(std::string("truncated ") + what);
    }
    void copy(void* out, std::size_t n, const char* what) {
        need(n, what);
        std::memcpy(out, bytes_.data() + pos_, n);
        pos_ += n;
    }
    std::string_view bytes_;
    std::size_t pos_ = 0;
};

/// Four letters as a chunk type: chunk_type("ARRY").
constexpr std::uint32_t chunk_type(const char (&name)[5]) {
    return std::uint32_t(std::uint8_t(name[0])) | std::uint32_t(std::uint8_t(name[1])) << 8 |
           std::uint32_t(std::uint8_t(name[2])) << 16 | std::uint32_t(std::uint8_t(name[3])) << 24;
}
/// "ARRY" from its number; unprintable bytes as '?'.
std::string chunk_name(std::uint32_t type);

inline constexpr std::size_t kChunkHeaderBytes = 16;
inline constexpr std::size_t kChunkTrailerBytes = 8;

/// Writes a chunk whose payload is `head` followed by `tail_size` bytes at `tail` (a large
/// array written without copying it). Returns the bytes written.
std::size_t write_chunk(const ByteSink& sink, std::uint32_t type, std::string_view head,
                        const void* tail = nullptr, std::size_t tail_size = 0);

/// One chunk found in a byte range.
struct ChunkView {
    std::uint32_t type = 0;
    std::string_view payload;
    std::size_t offset = 0;  ///< of its header in the whole file
    std::size_t end = 0;     ///< one past its trailer
};

/// The chunk at `offset` of `bytes`; throws ChunkError for a truncated chunk or a wrong
/// checksum (the reason says which).
ChunkView read_chunk(std::string_view bytes, std::size_t offset);

}  // namespace trilab
