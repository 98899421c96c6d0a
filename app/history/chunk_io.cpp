// Chunks and CRC-32 (app/history/chunk_io.h). The CRC is the reflected IEEE polynomial
// 0xEDB88320 computed eight bytes at a time with eight 256-entry tables ("slicing by eight":
// table k holds the CRC of a byte followed by k zero bytes), about 2 GB/s here.
#include "app/history/chunk_io.h"

#include <array>

namespace trilab {

namespace {

using CrcTables = std::array<std::array<std::uint32_t, 256>, 8>;

CrcTables make_crc_tables() {
    CrcTables t{};
    for (std::uint32_t i = 0; i < 256; ++i) {
        std::uint32_t c = i;
        for (int k = 0; k < 8; ++k) c = (c & 1) ? (c >> 1) ^ 0xEDB88320u : c >> 1;
        t[0][i] = c;
    }
    for (std::uint32_t i = 0; i < 256; ++i)
        for (std::size_t k = 1; k < 8; ++k) t[k][i] = (t[k - 1][i] >> 8) ^ t[0][t[k - 1][i] & 0xFF];
    return t;
}

const CrcTables& crc_tables() {
    static const CrcTables tables = make_crc_tables();
    return tables;
}

}  // namespace

std::uint32_t crc32_update(std::uint32_t crc, const void* data, std::size_t size) {
    const CrcTables& t = crc_tables();
    const auto* p = static_cast<const std::uint8_t*>(data);
    std::uint32_t c = ~crc;
    while (size >= 8) {
        std::uint32_t lo, hi;
        std::memcpy(&lo, p, 4);
        std::memcpy(&hi, p + 4, 4);
        lo ^= c;
        c = t[7][lo & 0xFF] ^ t[6][(lo >> 8) & 0xFF] ^ t[5][(lo >> 16) & 0xFF] ^ t[4][lo >> 24] ^
            t[3][hi & 0xFF] ^ t[2][(hi >> 8) & 0xFF] ^ t[1][(hi >> 16) & 0xFF] ^ t[0][hi >> 24];
        p += 8;
        size -= 8;
    }
    while (size-- > 0) c = (c >> 8) ^ t[0][(c ^ *p++) & 0xFF];
    return ~c;
}

std::string chunk_name(std::uint32_t type) {
    std::string s;
    for (int k = 0; k < 4; ++k) {
        const char c = char((type >> (8 * k)) & 0xFF);
        s += (c >= 32 && c < 127) ? c : '?';
    }
    return s;
}

std::size_t write_chunk(const ByteSink& sink, std::uint32_t type, std::string_view head,
                        const void* tail, std::size_t tail_size) {
    ByteWriter header;
    header.u32(type);
    header.u32(0);
    header.u64(std::uint64_t(head.size() + tail_size));
    std::uint32_t crc = crc32_update(0, header.bytes().data(), header.bytes().size());
    crc = crc32_update(crc, head.data(), head.size());
    if (tail_size) crc = crc32_update(crc, tail, tail_size);
    ByteWriter trailer;
    trailer.u32(crc);
    trailer.u32(0);
    sink(header.bytes().data(), header.bytes().size());
    sink(head.data(), head.size());
    if (tail_size) sink(static_cast<const char*>(tail), tail_size);
    sink(trailer.bytes().data(), trailer.bytes().size());
    return kChunkHeaderBytes + head.size() + tail_size + kChunkTrailerBytes;
}

ChunkView read_chunk(std::string_view bytes, std::size_t offset) {
    if (offset > bytes.size() || bytes.size() - offset < kChunkHeaderBytes)
        throw ChunkError("truncated chunk header (" + std::to_string(bytes.size() - offset) +
                         " of 16 bytes)");
    ByteReader header(bytes.substr(offset, kChunkHeaderBytes));
    ChunkView c;
    c.type = header.u32("chunk type");
    const std::uint32_t zero = header.u32("chunk flags");
    const std::uint64_t size = header.u64("chunk size");
    if (zero != 0) throw ChunkError("chunk flags are not zero");
    const std::size_t left = bytes.size() - offset - kChunkHeaderBytes;
    if (size > left || left - size < kChunkTrailerBytes)
        throw ChunkError("truncated chunk: its header says " + std::to_string(size) +
                         " payload bytes, " + std::to_string(left) + " bytes are left");
    c.payload = bytes.substr(offset + kChunkHeaderBytes, std::size_t(size));
    ByteReader trailer(bytes.substr(offset + kChunkHeaderBytes + size, kChunkTrailerBytes));
    const std::uint32_t stored = trailer.u32("checksum");
    const std::uint32_t trailer_zero = trailer.u32("checksum padding");
    std::uint32_t crc = crc32_update(0, bytes.data() + offset, kChunkHeaderBytes);
    crc = crc32_update(crc, c.payload.data(), c.payload.size());
    if (crc != stored || trailer_zero != 0) throw ChunkError("checksum mismatch (damaged bytes)");
    c.offset = offset;
    c.end = offset + kChunkHeaderBytes + std::size_t(size) + kChunkTrailerBytes;
    return c;
}

}  // namespace trilab
