#include "core/io/image_io.h"

#include <stb/stb_image.h>
#include <stb/stb_image_write.h>
#include <zlib.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>
#include <ostream>
#include <string_view>
#include <unordered_map>

#include "core/errors.h"
#include "core/io/file_util.h"
#include "core/io/text_scanner.h"
#include "core/io/x11_colors.h"
#include "core/system_memory.h"

// Readers:
//  - PNG and BMP go through stb_image, after our own checks: the signature; the dimensions
//    against the pixel budget and the available memory, read from the header before stb
//    allocates; for PNG the chunk structure and the image data inflated once with zlib into
//    a small scratch buffer (nothing kept), so that data inflating past the size the header
//    declares (a "zlib bomb": stb would grow its buffer to whatever the data holds) or ending
//    before it is refused; for BMP a check that the pixel data is all there (stb quietly
//    reads zeros past the end of a truncated BMP). stb decodes to the file's own channels,
//    which we expand to RGBA (no second RGBA copy).
//  - RLE-compressed BMP (RLE8, RLE4: stb has no RLE) is our own reader.
//  - PNM (P1-P6) is our own reader: stb reads only binary P5/P6, and we want line numbers in
//    the errors of the ASCII variants.
//  - XBM and XPM are our own readers over TextScanner's C mode (core/io/text_scanner.h:
//    comments, identifiers, numbers, string literals, punctuation), so errors name the line.
// Every reader checks the declared size against the limits and against what the file can
// hold before it allocates the pixels.

namespace trilab {

namespace {

constexpr long long kMaxSide = 32768;
/// The pixel budget: 64 Mpixel (2^26, e.g. 8192 x 8192), 256 MiB as RGBA.
constexpr long long kMaxPixels = 1LL << 26;

// ---- shared helpers -------------------------------------------------------------------------

std::string lower(std::string s) {
    for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

std::string extension_of(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    if (!ext.empty() && ext[0] == '.') ext.erase(0, 1);
    return lower(ext);
}

std::string mebibytes(double bytes) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.0f MiB", std::ceil(bytes / double(1 << 20)));
    return buf;
}

/// Refuses sizes that are not positive or exceed the limits, and images whose decoding
/// would need more than half the memory available now: the RGBA image, a decoder's buffer
/// of the same size, and `extra_bytes` (a PNG's inflated data). Called before anything of
/// the image's size is allocated.
void check_dimensions(long long width, long long height, const std::string& path, std::size_t line,
                      double extra_bytes = 0) {
    const std::string size = std::to_string(width) + " x " + std::to_string(height);
    if (width <= 0 || height <= 0)
        throw IoError(path, line, "invalid image size " + size + " (must be positive)");
    if (width > kMaxSide || height > kMaxSide)
        throw IoError(path, line,
                      "image size " + size + " exceeds the limit of " + std::to_string(kMaxSide) +
                          " pixels per side");
    if (width * height > kMaxPixels)
        throw IoError(path, line,
                      "image size " + size + " (" + std::to_string(width * height) +
                          " pixels) exceeds the limit of " + std::to_string(kMaxPixels) +
                          " pixels (64 Mpixel)");
    const double need = 2.0 * 4.0 * double(width) * double(height) + extra_bytes;
    const AvailableMemory memory = available_memory();
    const double available = double(memory.bytes);
    if (need > available / 2)
        throw IoError(path, line,
                      "decoding the " + size + " image needs about " + mebibytes(need) +
                          ", more than half of the " + mebibytes(available) +
                          " this process may still allocate (" + memory.limit + ")");
}

Image make_image(long long width, long long height) {
    Image image;
    image.width = int(width);
    image.height = int(height);
    image.rgba.assign(std::size_t(width) * std::size_t(height) * 4, 0);
    return image;
}

void put(Image& image, std::size_t pixel, std::uint32_t r, std::uint32_t g, std::uint32_t b,
         std::uint32_t a = 255) {
    std::uint8_t* p = image.rgba.data() + 4 * pixel;
    p[0] = std::uint8_t(r);
    p[1] = std::uint8_t(g);
    p[2] = std::uint8_t(b);
    p[3] = std::uint8_t(a);
}

/// `value` in [0, max] scaled to [0, 255], rounded to nearest.
std::uint32_t scale_to_8bit(std::uint32_t value, std::uint32_t max) {
    if (max == 255) return value;
    return std::uint32_t((std::uint64_t(value) * 255 + max / 2) / max);
}

// ---- PNG and BMP through stb_image ----------------------------------------------------------

std::string stb_reason() {
    const char* r = stbi_failure_reason();
    return r ? r : "unknown error";
}

std::uint32_t le_u32(const std::string& b, std::size_t at) {
    return std::uint32_t(std::uint8_t(b[at])) | std::uint32_t(std::uint8_t(b[at + 1])) << 8 |
           std::uint32_t(std::uint8_t(b[at + 2])) << 16 |
           std::uint32_t(std::uint8_t(b[at + 3])) << 24;
}
std::uint32_t be_u32(const std::string& b, std::size_t at) {
    return std::uint32_t(std::uint8_t(b[at])) << 24 | std::uint32_t(std::uint8_t(b[at + 1])) << 16 |
           std::uint32_t(std::uint8_t(b[at + 2])) << 8 | std::uint32_t(std::uint8_t(b[at + 3]));
}
std::uint32_t le_u16(const std::string& b, std::size_t at) {
    return std::uint32_t(std::uint8_t(b[at])) | std::uint32_t(std::uint8_t(b[at + 1])) << 8;
}

/// What the BMP headers say (the fields the readers use).
struct BmpHeader {
    std::uint64_t offset = 0;  ///< where the pixel data starts
    std::uint32_t header_size = 0;
    long long width = 0, height = 0;  ///< height < 0: rows top to bottom
    std::uint32_t bpp = 0, compression = 0, colours_used = 0;
};

BmpHeader read_bmp_header(const std::string& bytes, const std::string& path) {
    if (bytes.size() < 2 || bytes.compare(0, 2, "BM") != 0)
        throw IoError(path, 0, "not a BMP file (the signature 'BM' is missing)");
    if (bytes.size() < 26) throw IoError(path, 0, "truncated BMP header");
    BmpHeader h;
    h.offset = le_u32(bytes, 10);
    h.header_size = le_u32(bytes, 14);
    if (h.header_size == 12) {
        h.width = le_u16(bytes, 18);
        h.height = le_u16(bytes, 20);
        h.bpp = le_u16(bytes, 24);
    } else if (h.header_size >= 40 && h.header_size <= 124) {
        if (bytes.size() < 54) throw IoError(path, 0, "truncated BMP header");
        h.width = std::int32_t(le_u32(bytes, 18));
        h.height = std::int32_t(le_u32(bytes, 22));
        h.bpp = le_u16(bytes, 28);
        h.compression = le_u32(bytes, 30);
        h.colours_used = le_u32(bytes, 46);
    } else {
        throw IoError(path, 0, "unsupported BMP info header size " + std::to_string(h.header_size));
    }
    check_dimensions(h.width, h.height < 0 ? -h.height : h.height, path, 0);
    if (h.bpp != 1 && h.bpp != 4 && h.bpp != 8 && h.bpp != 16 && h.bpp != 24 && h.bpp != 32)
        throw IoError(path, 0, "unsupported BMP bit depth " + std::to_string(h.bpp));
    return h;
}

/// Checks an uncompressed BMP for stb_image: that the pixel data is complete (stb_image
/// reads zeros past the end of a truncated file instead of failing).
void check_bmp(const std::string& bytes, const std::string& path, const BmpHeader& h) {
    const bool uncompressed = h.compression == 0 || h.compression == 3 || h.compression == 6;
    if (!uncompressed)
        throw IoError(path, 0,
                      "unsupported BMP compression " + std::to_string(h.compression) +
                          " (RLE8, RLE4, bit fields and uncompressed are read; not embedded "
                          "JPEG/PNG)");
    const long long rows = h.height < 0 ? -h.height : h.height;
    const std::uint64_t stride = (std::uint64_t(h.width) * h.bpp + 31) / 32 * 4;
    const std::uint64_t needed = h.offset + stride * std::uint64_t(rows);
    if (bytes.size() < needed)
        throw IoError(path, 0,
                      "truncated: the pixel data ends at byte " + std::to_string(needed) +
                          ", the file has " + std::to_string(bytes.size()) + " bytes");
}

/// RLE8 (compression 1) and RLE4 (compression 2) BMP: runs of one palette index (RLE4: two
/// alternating ones), absolute runs (padded to 16 bits), and the escapes end of line, end of
/// bitmap and delta (skip right and up). Rows run bottom to top. Pixels the data skips stay
/// transparent black. Refused: a run past the end of a row or past the last row, a palette
/// index outside the palette, data that ends before the end-of-bitmap escape.
Image read_bmp_rle(const std::string& bytes, const std::string& path, const BmpHeader& h) {
    const bool rle8 = h.compression == 1;
    const std::uint32_t want_bpp = rle8 ? 8 : 4;
    const char* kind = rle8 ? "RLE8" : "RLE4";
    if (h.bpp != want_bpp)
        throw IoError(path, 0,
                      std::string(kind) + " compression needs " + std::to_string(want_bpp) +
                          " bits per pixel, the header says " + std::to_string(h.bpp));
    if (h.height < 0)
        throw IoError(path, 0, std::string("a top-down BMP (negative height) cannot be ") + kind);
    // The palette: B, G, R, reserved per entry, after the info header.
    const std::uint32_t max_colours = 1u << want_bpp;
    const std::uint32_t n_colours = h.colours_used == 0 ? max_colours : h.colours_used;
    if (n_colours > max_colours)
        throw IoError(path, 0,
                      "the header declares " + std::to_string(n_colours) + " palette colours, " +
                          kind + " has at most " + std::to_string(max_colours));
    const std::uint64_t palette = 14 + std::uint64_t(h.header_size);
    if (palette + 4 * std::uint64_t(n_colours) > bytes.size())
        throw IoError(path, 0,
                      "truncated: the palette of " + std::to_string(n_colours) +
                          " colours ends past the end of the file");
    if (h.offset >= bytes.size())
        throw IoError(path, 0,
                      "the pixel data offset " + std::to_string(h.offset) +
                          " is past the end of the file (" + std::to_string(bytes.size()) +
                          " bytes)");
    const auto* b = reinterpret_cast<const std::uint8_t*>(bytes.data());
    const std::size_t width = std::size_t(h.width), height = std::size_t(h.height);
    Image image = make_image(h.width, h.height);  // all transparent black
    std::size_t x = 0, y = 0;                     // y counts rows from the bottom
    std::size_t p = std::size_t(h.offset);
    auto need = [&](std::size_t n) {
        if (bytes.size() - p < n)
            throw IoError(path, 0,
                          std::string("truncated ") + kind + " data: it ends at byte " +
                              std::to_string(bytes.size()) + " before the end-of-bitmap escape");
    };
    auto put_index = [&](std::uint32_t index) {
        if (y >= height)
            throw IoError(path, 0,
                          std::string(kind) + " data at byte " + std::to_string(p) +
                              " runs past the last row (the image has " + std::to_string(height) +
                              " rows)");
        if (x >= width)
            throw IoError(path, 0,
                          std::string(kind) + " data at byte " + std::to_string(p) +
                              " runs past the end of row " + std::to_string(y) +
                              " from the bottom (width " + std::to_string(width) + ")");
        if (index >= n_colours)
            throw IoError(path, 0,
                          "palette index " + std::to_string(index) + " at byte " +
                              std::to_string(p) + " is outside the " + std::to_string(n_colours) +
                              " colours of the palette");
        const std::uint8_t* c = b + palette + 4 * index;
        put(image, (height - 1 - y) * width + x, c[2], c[1], c[0]);
        ++x;
    };
    for (;;) {
        need(2);
        const std::uint32_t count = b[p], value = b[p + 1];
        p += 2;
        if (count > 0) {  // a run: one index (RLE4: two, alternating, high nibble first)
            for (std::uint32_t k = 0; k < count; ++k)
                put_index(rle8 ? value : (k % 2 == 0 ? value >> 4 : value & 15));
        } else if (value == 0) {  // end of line
            x = 0;
            ++y;
        } else if (value == 1) {  // end of bitmap
            break;
        } else if (value == 2) {  // delta: right and up
            need(2);
            x += b[p];
            y += b[p + 1];
            p += 2;
            if (x > width || y > height)
                throw IoError(path, 0,
                              std::string(kind) + " delta at byte " + std::to_string(p - 4) +
                                  " moves past the image (to column " + std::to_string(x) +
                                  ", row " + std::to_string(y) + " from the bottom)");
        } else {  // absolute run of `value` indices, padded to a 16-bit boundary
            const std::size_t n = value, data = rle8 ? n : (n + 1) / 2;
            need((data + 1) / 2 * 2);
            const std::size_t start = p;
            for (std::size_t k = 0; k < n; ++k) {
                const std::uint32_t byte = b[start + (rle8 ? k : k / 2)];
                put_index(rle8 ? byte : (k % 2 == 0 ? byte >> 4 : byte & 15));
            }
            p = start + (data + 1) / 2 * 2;
        }
    }
    return image;
}

/// Bytes of the inflated PNG image data that a header declares: per row a filter byte and
/// the row's packed samples; an interlaced (Adam7) image has seven passes of smaller rows.
std::uint64_t png_raw_size(std::uint64_t width, std::uint64_t height, std::uint64_t bits,
                           bool interlaced) {
    auto rows = [&](std::uint64_t cols, std::uint64_t n_rows) {
        return cols == 0 || n_rows == 0 ? 0 : n_rows * (1 + (cols * bits + 7) / 8);
    };
    if (!interlaced) return rows(width, height);
    // Adam7 passes: first column and row, then the steps between columns and rows.
    static const std::uint64_t pass[7][4] = {{0, 0, 8, 8}, {4, 0, 8, 8}, {0, 4, 4, 8}, {2, 0, 4, 4},
                                             {0, 2, 2, 4}, {1, 0, 2, 2}, {0, 1, 1, 2}};
    std::uint64_t total = 0;
    for (const auto& q : pass) {
        const std::uint64_t cols = width > q[0] ? (width - q[0] + q[2] - 1) / q[2] : 0;
        const std::uint64_t n_rows = height > q[1] ? (height - q[1] + q[3] - 1) / q[3] : 0;
        total += rows(cols, n_rows);
    }
    return total;
}

/// Checks a PNG before stb_image decodes it: the chunk structure, the dimensions (limits and
/// memory, with the inflated data), and the image data inflated once with zlib into a 64 KiB
/// scratch buffer, counting bytes: data that inflates past the size the header declares is
/// refused as soon as it does, and so is data that is corrupt or ends before that size.
void check_png(const std::string& bytes, const std::string& path) {
    static const char kSignature[] = "\x89PNG\r\n\x1a\n";
    if (bytes.size() < 8 || bytes.compare(0, 8, kSignature, 8) != 0)
        throw IoError(path, 0, "not a PNG file (the PNG signature is missing)");
    if (bytes.size() < 33 || bytes.compare(12, 4, "IHDR") != 0 || be_u32(bytes, 8) < 13)
        throw IoError(path, 0, "truncated PNG: the IHDR chunk is missing");
    const std::uint64_t width = be_u32(bytes, 16), height = be_u32(bytes, 20);
    const unsigned depth = std::uint8_t(bytes[24]), colour_type = std::uint8_t(bytes[25]);
    const bool interlaced = bytes[28] != 0;
    // Samples per pixel by colour type: grey, -, RGB, palette, grey + alpha, -, RGBA.
    static const int kChannels[7] = {1, 0, 3, 1, 2, 0, 4};
    const int channels = colour_type < 7 ? kChannels[colour_type] : 0;
    if (channels == 0)
        throw IoError(path, 0, "unsupported PNG colour type " + std::to_string(colour_type));
    if (depth != 1 && depth != 2 && depth != 4 && depth != 8 && depth != 16)
        throw IoError(path, 0, "unsupported PNG bit depth " + std::to_string(depth));
    const std::uint64_t expected =
        png_raw_size(width, height, std::uint64_t(channels) * depth, interlaced);
    check_dimensions(static_cast<long long>(width), static_cast<long long>(height), path, 0,
                     double(expected) + double(bytes.size()));

    // The IDAT chunks' data, in order, through one inflate stream.
    z_stream zs{};
    if (inflateInit(&zs) != Z_OK) throw IoError(path, 0, "cannot start zlib");
    struct End {
        z_stream* zs;
        ~End() { inflateEnd(zs); }
    } end{&zs};
    std::vector<unsigned char> scratch(std::size_t(1) << 16);
    std::uint64_t produced = 0;
    bool stream_end = false, any_idat = false;
    const std::string size = std::to_string(width) + " x " + std::to_string(height);
    for (std::size_t pos = 8; pos + 12 <= bytes.size();) {
        const std::uint64_t length = be_u32(bytes, pos);
        if (length > bytes.size() - pos - 12)
            throw IoError(path, 0,
                          "truncated PNG: chunk '" + printable(bytes.substr(pos + 4, 4)) +
                              "' at byte " + std::to_string(pos) +
                              " ends past the end of the file");
        const std::string type = bytes.substr(pos + 4, 4);
        if (type == "IEND") break;
        // Image data after the end of the zlib stream: a decoder that reads the IDAT chunks as
        // one stream would go on past it (stb_image grows its output buffer then), so refuse.
        if (type == "IDAT" && stream_end && length > 0)
            throw IoError(path, 0,
                          "corrupt PNG: image data (IDAT) continues after the end of its zlib "
                          "stream, at byte " +
                              std::to_string(pos));
        if (type == "IDAT" && !stream_end) {
            any_idat = true;
            zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(bytes.data() + pos + 8));
            zs.avail_in = uInt(length);
            for (;;) {
                zs.next_out = scratch.data();
                zs.avail_out = uInt(scratch.size());
                const int ret = inflate(&zs, Z_NO_FLUSH);
                produced += scratch.size() - zs.avail_out;
                if (produced > expected)
                    throw IoError(path, 0,
                                  "the PNG image data inflates past the " +
                                      std::to_string(expected) + " bytes that its " + size +
                                      " pixels (colour type " + std::to_string(colour_type) + ", " +
                                      std::to_string(depth) + " bits) declare");
                if (ret == Z_STREAM_END) {
                    stream_end = true;
                    if (zs.avail_in != 0)
                        throw IoError(path, 0,
                                      "corrupt PNG: " + std::to_string(zs.avail_in) +
                                          " bytes of image data after the end of its zlib "
                                          "stream");
                    break;
                }
                if (ret == Z_BUF_ERROR) break;  // needs the next chunk's data
                if (ret != Z_OK)
                    throw IoError(path, 0,
                                  std::string("corrupt PNG image data (zlib: ") +
                                      (zs.msg ? zs.msg : "error " + std::to_string(ret)) + ")");
                if (zs.avail_in == 0 && zs.avail_out != 0) break;
            }
        }
        pos += 12 + std::size_t(length);
    }
    if (!any_idat) throw IoError(path, 0, "truncated PNG: no image data (IDAT chunk)");
    if (!stream_end || produced < expected)
        throw IoError(path, 0,
                      "truncated PNG: the image data ends after " + std::to_string(produced) +
                          " of the " + std::to_string(expected) + " bytes that its " + size +
                          " pixels declare");
}

Image read_with_stb(const std::string& bytes, const std::string& path, const char* format) {
    const std::string fmt = format;
    if (bytes.empty()) throw IoError(path, 0, "the file is empty");
    if (bytes.size() > std::size_t(INT_MAX))
        throw IoError(path, 0, "the file is too large (over 2 GiB)");
    if (fmt == "PNG") {
        check_png(bytes, path);
    } else {
        const BmpHeader h = read_bmp_header(bytes, path);
        if (h.compression == 1 || h.compression == 2) return read_bmp_rle(bytes, path, h);
        check_bmp(bytes, path, h);
    }
    const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
    const int length = int(bytes.size());
    int width = 0, height = 0, channels = 0;
    if (!stbi_info_from_memory(data, length, &width, &height, &channels))
        throw IoError(path, 0, "cannot read the " + fmt + " header: " + stb_reason());
    check_dimensions(width, std::abs(height), path, 0);  // stb gives top-down BMPs as < 0
    // The flag is global in stb; trilab's convention is "rows top to bottom", so make sure
    // nobody's earlier call left it on.
    stbi_set_flip_vertically_on_load(0);
    // The file's own channels (1 to 4, 8 bits each), expanded to RGBA here: stb's own RGBA
    // conversion would allocate a second image.
    std::unique_ptr<stbi_uc, void (*)(void*)> pixels(
        stbi_load_from_memory(data, length, &width, &height, &channels, 0), stbi_image_free);
    if (!pixels) throw IoError(path, 0, "cannot decode the " + fmt + " data: " + stb_reason());
    check_dimensions(width, height, path, 0);
    if (channels < 1 || channels > 4)
        throw IoError(path, 0,
                      "the " + fmt + " decoder returned " + std::to_string(channels) + " channels");
    Image image = make_image(width, height);
    const std::size_t n = std::size_t(width) * std::size_t(height);
    const stbi_uc* in = pixels.get();
    for (std::size_t i = 0; i < n; ++i, in += channels) {
        switch (channels) {
            case 1:
                put(image, i, in[0], in[0], in[0]);
                break;
            case 2:
                put(image, i, in[0], in[0], in[0], in[1]);
                break;
            case 3:
                put(image, i, in[0], in[1], in[2]);
                break;
            default:
                put(image, i, in[0], in[1], in[2], in[3]);
                break;
        }
    }
    return image;
}

// ---- PNM: P1-P6 -----------------------------------------------------------------------------

Image read_pnm(const std::string& bytes, const std::string& path) {
    if (bytes.empty()) throw IoError(path, 0, "the file is empty");
    TextScanner sc(bytes, path, '#');
    const std::string_view magic = sc.expect_token("the PNM magic number (P1 to P6)");
    if (magic.size() != 2 || magic[0] != 'P' || magic[1] < '1' || magic[1] > '6')
        sc.fail("not a PNM file: the magic number is '" + printable(magic) +
                "', expected P1 to P6");
    const int kind = magic[1] - '0';
    const bool bitmap = kind == 1 || kind == 4;
    const int channels = (kind == 3 || kind == 6) ? 3 : 1;
    const bool ascii = kind <= 3;
    const long long width = sc.next_integer("the width");
    const long long height = sc.next_integer("the height");
    check_dimensions(width, height, path, sc.line());
    long long maxval = 1;
    if (!bitmap) {
        maxval = sc.next_integer("the maximum value");
        if (maxval < 1 || maxval > 65535)
            sc.fail("the maximum value " + std::to_string(maxval) + " is outside 1 to 65535");
    }
    const std::size_t n_pixels = std::size_t(width) * std::size_t(height);
    const std::size_t n_samples = n_pixels * std::size_t(channels);
    const std::size_t header_end = sc.offset();
    const std::uint32_t max = std::uint32_t(maxval);

    if (ascii) {
        // Every sample takes at least one character.
        check_declared_count(n_samples, 1, bytes.size() - header_end, "samples", path, sc.line());
        Image image = make_image(width, height);
        if (kind == 1) {
            // Plain PBM: '1' is black, '0' white; whitespace between bits is optional.
            std::size_t pixel = 0;
            while (pixel < n_pixels) {
                const std::string_view t = sc.expect_token("more bits (0 or 1)");
                for (char c : t) {
                    if (c != '0' && c != '1')
                        sc.fail("'" + printable(t) + "' is not a sequence of bits (0 or 1)");
                    if (pixel == n_pixels)
                        sc.fail("more than the " + std::to_string(n_pixels) +
                                " bits that the size " + std::to_string(width) + " x " +
                                std::to_string(height) + " declares");
                    const std::uint32_t v = c == '1' ? 0 : 255;
                    put(image, pixel++, v, v, v);
                }
            }
        } else {
            std::uint32_t s[3] = {0, 0, 0};
            for (std::size_t pixel = 0; pixel < n_pixels; ++pixel) {
                for (int k = 0; k < channels; ++k) {
                    const long long v = sc.next_integer("a sample value");
                    if (v < 0 || v > maxval)
                        sc.fail("sample " + std::to_string(v) + " is outside 0 to " +
                                std::to_string(maxval));
                    s[k] = scale_to_8bit(std::uint32_t(v), max);
                }
                if (channels == 1)
                    put(image, pixel, s[0], s[0], s[0]);
                else
                    put(image, pixel, s[0], s[1], s[2]);
            }
        }
        if (!sc.at_end()) {
            sc.next_token();
            sc.fail("more values than the " + std::to_string(width) + " x " +
                    std::to_string(height) + " pixels that the header declares");
        }
        return image;
    }

    // Binary: exactly one whitespace character separates the header from the raster.
    if (header_end >= bytes.size())
        throw IoError(path, sc.line(), "unexpected end of file after the header");
    const char sep = bytes[header_end];
    if (sep != ' ' && sep != '\t' && sep != '\n' && sep != '\r' && sep != '\f' && sep != '\v')
        sc.fail("expected whitespace after the header");
    const std::size_t start = header_end + 1;
    const std::size_t available = bytes.size() - start;
    const std::size_t row_bytes =
        kind == 4 ? (std::size_t(width) + 7) / 8
                  : std::size_t(width) * std::size_t(channels) * (maxval > 255 ? 2 : 1);
    const std::size_t needed = row_bytes * std::size_t(height);
    if (available < needed)
        throw IoError(path, 0,
                      "truncated: the pixel data needs " + std::to_string(needed) +
                          " bytes, the file has " + std::to_string(available) +
                          " after the header");
    // Bytes after the raster are ignored (a Netpbm stream may hold several images).
    Image image = make_image(width, height);
    const auto* raster = reinterpret_cast<const std::uint8_t*>(bytes.data() + start);
    for (std::size_t y = 0; y < std::size_t(height); ++y) {
        const std::uint8_t* row = raster + y * row_bytes;
        for (std::size_t x = 0; x < std::size_t(width); ++x) {
            const std::size_t pixel = y * std::size_t(width) + x;
            if (kind == 4) {
                // Bits packed MSB first, 1 is black.
                const bool black = (row[x / 8] >> (7 - x % 8)) & 1;
                const std::uint32_t v = black ? 0 : 255;
                put(image, pixel, v, v, v);
                continue;
            }
            std::uint32_t s[3] = {0, 0, 0};
            for (int k = 0; k < channels; ++k) {
                const std::size_t i = x * std::size_t(channels) + std::size_t(k);
                std::uint32_t v =
                    maxval > 255 ? std::uint32_t(row[2 * i]) << 8 | row[2 * i + 1] : row[i];
                if (v > max)
                    throw IoError(path, 0,
                                  "sample " + std::to_string(v) + " of pixel (" +
                                      std::to_string(x) + ", " + std::to_string(y) +
                                      ") exceeds the maximum value " + std::to_string(max));
                s[k] = scale_to_8bit(v, max);
            }
            if (channels == 1)
                put(image, pixel, s[0], s[0], s[0]);
            else
                put(image, pixel, s[0], s[1], s[2]);
        }
    }
    return image;
}

// ---- C tokens for XBM and XPM (TextScanner's C mode) -----------------------------------------

std::string describe(const CToken& t) {
    if (t.kind == CToken::End) return "the end of the file";
    return "'" + printable(t.text) + "'";
}

/// A C integer literal (decimal, 0x hexadecimal or 0 octal), or -1 if it is none.
long long parse_c_integer(std::string_view s) {
    int base = 10;
    if (s.size() > 2 && s[0] == '0' && (s[1] == 'x' || s[1] == 'X')) {
        base = 16;
        s.remove_prefix(2);
    } else if (s.size() > 1 && s[0] == '0') {
        base = 8;
        s.remove_prefix(1);
    }
    long long v = 0;
    auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v, base);
    if (ec != std::errc() || ptr != s.data() + s.size() || v < 0) return -1;
    return v;
}

bool ends_with(std::string_view s, std::string_view suffix) {
    return s.size() >= suffix.size() && s.substr(s.size() - suffix.size()) == suffix;
}

// ---- XBM ------------------------------------------------------------------------------------

Image read_xbm(const std::string& text, const std::string& path) {
    TextScanner lex = TextScanner::c_source(text, path);
    long long width = -1, height = -1;
    std::size_t size_line = 1;
    CToken t = lex.next_c_token();
    if (t.kind == CToken::End) throw IoError(path, 0, "the file is empty");
    // #define name_width W / name_height H / name_x_hot X / name_y_hot Y
    while (t.kind == CToken::Punct && t.text == "#") {
        const CToken directive = lex.next_c_token();
        if (directive.kind != CToken::Identifier || directive.text != "define")
            lex.fail_at(directive.line, "expected #define, found " + describe(directive));
        const CToken name = lex.next_c_token();
        if (name.kind != CToken::Identifier)
            lex.fail_at(name.line, "expected a name after #define, found " + describe(name));
        const CToken value = lex.next_c_token();
        const long long v = value.kind == CToken::Number ? parse_c_integer(value.text) : -1;
        if (v < 0)
            lex.fail_at(value.line, "expected a non-negative number for " + printable(name.text) +
                                        ", found " + describe(value));
        if (ends_with(name.text, "_width")) {
            width = v;
            size_line = name.line;
        } else if (ends_with(name.text, "_height")) {
            height = v;
            size_line = name.line;
        }  // the hot spot and any other define are not needed
        t = lex.next_c_token();
    }
    if (width < 0) lex.fail_at(t.line, "missing '#define <name>_width' before the bits");
    if (height < 0) lex.fail_at(t.line, "missing '#define <name>_height' before the bits");
    check_dimensions(width, height, path, size_line);

    // static [const] [unsigned] char|short name_bits[] = {
    bool is_short = false, is_char = false;
    std::size_t decl_line = t.line;
    while (t.kind == CToken::Identifier) {
        if (t.text == "short") is_short = true;
        if (t.text == "char") is_char = true;
        t = lex.next_c_token();
    }
    if (!(t.kind == CToken::Punct && t.text == "["))
        lex.fail_at(t.line, "expected the declaration 'static char <name>_bits[] = {', found " +
                                describe(t));
    if (is_short == is_char) lex.fail_at(decl_line, "the bits array must be of type char or short");
    t = lex.next_c_token();
    if (t.kind == CToken::Number) t = lex.next_c_token();
    if (!(t.kind == CToken::Punct && t.text == "]"))
        lex.fail_at(t.line, "expected ']', found " + describe(t));
    t = lex.next_c_token();
    if (!(t.kind == CToken::Punct && t.text == "="))
        lex.fail_at(t.line, "expected '=', found " + describe(t));
    t = lex.next_c_token();
    if (!(t.kind == CToken::Punct && t.text == "{"))
        lex.fail_at(t.line, "expected '{', found " + describe(t));

    // X11 XBM: bytes; X10 XBM: 16-bit words. Bits LSB first, rows padded to whole units.
    const int unit_bits = is_short ? 16 : 8;
    const long long max_value = is_short ? 0xffff : 0xff;
    const std::size_t units_per_row = (std::size_t(width) + unit_bits - 1) / unit_bits;
    const std::size_t n_units = units_per_row * std::size_t(height);
    // Each value takes at least one character.
    check_declared_count(n_units, 1, text.size(), "bit values", path, size_line);
    Image image = make_image(width, height);
    std::size_t count = 0;
    for (;;) {
        t = lex.next_c_token();
        if (t.kind == CToken::Punct && t.text == "}") break;
        if (t.kind != CToken::Number)
            lex.fail_at(t.line, "expected a number or '}', found " + describe(t));
        const long long v = parse_c_integer(t.text);
        if (v < 0 || v > max_value)
            lex.fail_at(t.line, "'" + printable(t.text) + "' is not a " +
                                    (is_short ? "16-bit" : "byte") + " value");
        if (count == n_units)
            lex.fail_at(t.line, "more than the " + std::to_string(n_units) + " values that " +
                                    std::to_string(width) + " x " + std::to_string(height) +
                                    " pixels need");
        const std::size_t y = count / units_per_row;
        const std::size_t x0 = (count % units_per_row) * std::size_t(unit_bits);
        for (int bit = 0; bit < unit_bits && x0 + std::size_t(bit) < std::size_t(width); ++bit) {
            const std::uint32_t c = ((v >> bit) & 1) ? 0 : 255;  // 1 is black
            put(image, y * std::size_t(width) + x0 + std::size_t(bit), c, c, c);
        }
        ++count;
        t = lex.next_c_token();
        if (t.kind == CToken::Punct && t.text == "}") break;
        if (!(t.kind == CToken::Punct && t.text == ","))
            lex.fail_at(t.line, "expected ',' or '}', found " + describe(t));
    }
    if (count != n_units)
        lex.fail_at(t.line, "found " + std::to_string(count) + " values, but " +
                                std::to_string(width) + " x " + std::to_string(height) +
                                " pixels need " + std::to_string(n_units));
    t = lex.next_c_token();
    if (t.kind == CToken::Punct && t.text == ";") t = lex.next_c_token();
    if (t.kind != CToken::End)
        lex.fail_at(t.line, "unexpected " + describe(t) + " after the bits array");
    return image;
}

// ---- XPM ------------------------------------------------------------------------------------

struct Rgba {
    std::uint8_t r = 0, g = 0, b = 0, a = 255;
};

int hex_digit(char c) {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
}

/// An XPM colour: None, #RGB / #RRGGBB / #RRRGGGBBB / #RRRRGGGGBBBB (each component scaled
/// to 8 bits, so #fff is white), or any X11 colour name (x11-common's rgb.txt, embedded at
/// build time: core/io/x11_colors.h), ignoring case and spaces as X11 does.
bool parse_xpm_color(const std::string& spec, Rgba& out) {
    if (spec.empty()) return false;
    if (spec[0] == '#') {
        const std::size_t n = spec.size() - 1;
        if (n == 0 || n % 3 != 0 || n > 12) return false;
        const std::size_t digits = n / 3;
        const std::uint32_t max = (1u << (4 * digits)) - 1;
        std::uint32_t c[3];
        for (int k = 0; k < 3; ++k) {
            std::uint32_t v = 0;
            for (std::size_t i = 0; i < digits; ++i) {
                const int d = hex_digit(spec[1 + std::size_t(k) * digits + i]);
                if (d < 0) return false;
                v = v * 16 + std::uint32_t(d);
            }
            c[k] = scale_to_8bit(v, max);
        }
        out = {std::uint8_t(c[0]), std::uint8_t(c[1]), std::uint8_t(c[2]), 255};
        return true;
    }
    std::string key;
    for (char ch : spec)
        if (ch != ' ' && ch != '\t') key += char(std::tolower(static_cast<unsigned char>(ch)));
    if (key == "none") {
        out = {0, 0, 0, 0};
        return true;
    }
    if (const X11Color* c = find_x11_color(key)) {
        out = {c->r, c->g, c->b, 255};
        return true;
    }
    return false;
}

struct XpmString {
    std::string text;
    std::size_t line;
};

std::vector<std::string_view> split_words(std::string_view s) {
    std::vector<std::string_view> words;
    std::size_t i = 0;
    while (i < s.size()) {
        while (i < s.size() && (s[i] == ' ' || s[i] == '\t')) ++i;
        const std::size_t begin = i;
        while (i < s.size() && s[i] != ' ' && s[i] != '\t') ++i;
        if (i > begin) words.push_back(s.substr(begin, i - begin));
    }
    return words;
}

std::uint64_t pixel_code(std::string_view chars) {
    std::uint64_t code = 0;
    for (char c : chars) code = code << 8 | std::uint8_t(c);
    return code;
}

/// Refuses a text that does not start with the XPM3 comment /* XPM */ (after space).
void check_xpm_marker(const std::string& text, const std::string& path) {
    std::size_t i = 0, line = 1;
    while (i < text.size() && std::isspace(static_cast<unsigned char>(text[i])))
        line += text[i++] == '\n';
    const std::size_t end =
        text.compare(i, 2, "/*") == 0 ? text.find("*/", i + 2) : std::string::npos;
    if (end == std::string::npos ||
        std::string_view(text).substr(i, end - i).find("XPM") == std::string_view::npos)
        throw IoError(path, line, "not an XPM file (it must start with /* XPM */)");
}

/// The C declaration `static [const] char *name[] = { "...", ... };`: its strings, adjacent
/// literals concatenated as in C, each with the line it starts on.
std::vector<XpmString> read_xpm_strings(TextScanner& lex) {
    CToken t = lex.next_c_token();
    while (!(t.kind == CToken::Punct && t.text == "{")) {
        const bool declaration_part = t.kind == CToken::Identifier || t.kind == CToken::Number ||
                                      (t.kind == CToken::Punct && (t.text == "*" || t.text == "[" ||
                                                                   t.text == "]" || t.text == "="));
        if (!declaration_part)
            lex.fail_at(t.line, "expected the declaration 'static char* <name>[] = {', found " +
                                    describe(t));
        t = lex.next_c_token();
    }
    std::vector<XpmString> strings;
    t = lex.next_c_token();
    while (!(t.kind == CToken::Punct && t.text == "}")) {
        if (t.kind != CToken::String)
            lex.fail_at(t.line, "expected a string or '}', found " + describe(t));
        XpmString s{std::move(t.value), t.line};
        t = lex.next_c_token();
        while (t.kind == CToken::String) {
            s.text += t.value;
            t = lex.next_c_token();
        }
        strings.push_back(std::move(s));
        if (t.kind == CToken::Punct && t.text == ",") {
            t = lex.next_c_token();
        } else if (!(t.kind == CToken::Punct && t.text == "}")) {
            lex.fail_at(t.line, "expected ',' or '}', found " + describe(t));
        }
    }
    const std::size_t close_line = t.line;
    t = lex.next_c_token();
    if (t.kind == CToken::Punct && t.text == ";") t = lex.next_c_token();
    if (t.kind != CToken::End)
        lex.fail_at(t.line, "unexpected " + describe(t) + " after the string array");
    if (strings.empty()) lex.fail_at(close_line, "the string array is empty");
    return strings;
}

/// The XPM values line, checked against the limits and against the strings there are.
struct XpmValues {
    long long width = 0, height = 0, n_colors = 0, cpp = 0;
    bool extensions = false;  ///< XPMEXT: extension data may follow the rows
};

/// Refuses too few strings for the declared colours and rows, and strings after the rows
/// other than extension data ("XPMEXT name ...", free lines, "XPMENDEXT"), which is skipped.
void check_xpm_string_count(const std::vector<XpmString>& strings, const XpmValues& x,
                            const TextScanner& lex) {
    const std::size_t n_rows = std::size_t(x.height);
    if (std::size_t(x.n_colors) > strings.size() ||
        1 + std::size_t(x.n_colors) + n_rows > strings.size())
        lex.fail_at(strings.back().line,
                    "the values line declares " + std::to_string(x.n_colors) + " colours and " +
                        std::to_string(x.height) + " rows, but the file holds only " +
                        std::to_string(strings.size() - 1) + " strings after it");
    const std::size_t end_rows = 1 + std::size_t(x.n_colors) + n_rows;
    if (end_rows < strings.size() &&
        (!x.extensions || strings[end_rows].text.rfind("XPMEXT", 0) != 0))
        lex.fail_at(strings[end_rows].line, "more strings than the " + std::to_string(x.n_colors) +
                                                " colours and " + std::to_string(x.height) +
                                                " rows that the values line declares");
}

/// Parses "width height ncolors chars_per_pixel [x_hot y_hot] [XPMEXT]" (strings[0]) and
/// checks it against the limits and the number of strings.
XpmValues parse_xpm_values(const std::vector<XpmString>& strings, const TextScanner& lex,
                           const std::string& path) {
    const XpmString& header = strings[0];
    const auto values = split_words(header.text);
    auto header_number = [&](std::size_t i, const char* what) {
        if (i >= values.size())
            lex.fail_at(header.line, std::string("the values line lacks the ") + what);
        long long v = 0;
        auto [ptr, ec] = std::from_chars(values[i].data(), values[i].data() + values[i].size(), v);
        if (ec != std::errc() || ptr != values[i].data() + values[i].size())
            lex.fail_at(header.line,
                        "'" + printable(values[i]) + "' is not an integer (" + what + ")");
        return v;
    };
    XpmValues x;
    x.width = header_number(0, "width");
    x.height = header_number(1, "height");
    x.n_colors = header_number(2, "number of colours");
    x.cpp = header_number(3, "characters per pixel");
    std::size_t next_value = 4;
    if (values.size() > 4 && values[4] != "XPMEXT") {
        header_number(4, "hot spot x");
        header_number(5, "hot spot y");
        next_value = 6;
    }
    x.extensions = next_value < values.size() && values[next_value] == "XPMEXT";
    if (x.extensions) ++next_value;
    if (next_value < values.size())
        lex.fail_at(header.line,
                    "unexpected '" + printable(values[next_value]) + "' in the values line");
    check_dimensions(x.width, x.height, path, header.line);
    if (x.cpp < 1 || x.cpp > 8)
        lex.fail_at(header.line,
                    "characters per pixel " + std::to_string(x.cpp) + " is outside 1 to 8");
    if (x.n_colors < 1) lex.fail_at(header.line, "the number of colours must be at least 1");
    check_xpm_string_count(strings, x, lex);
    return x;
}

/// One colour line: "<chars> <key> <colour> [<key> <colour>]..."; keys c, m, s, g4, g. The
/// colour key c is used, else g, g4, m; symbolic names (s) are ignored.
Rgba parse_xpm_color_line(const XpmString& s, std::size_t chars, const TextScanner& lex) {
    const std::string_view code = std::string_view(s.text).substr(0, chars);
    const auto words = split_words(std::string_view(s.text).substr(chars));
    auto is_key = [](std::string_view w) {
        return w == "c" || w == "m" || w == "s" || w == "g" || w == "g4";
    };
    std::string by_key[4];  // c, g, g4, m
    for (std::size_t w = 0; w < words.size();) {
        const std::string_view key = words[w++];
        if (!is_key(key))
            lex.fail_at(s.line,
                        "expected a colour key (c, m, s, g or g4), found '" + printable(key) + "'");
        std::string value;
        while (w < words.size() && !is_key(words[w])) {
            if (!value.empty()) value += ' ';
            value += words[w++];
        }
        if (value.empty()) lex.fail_at(s.line, "the key '" + std::string(key) + "' has no colour");
        if (key == "c") by_key[0] = value;
        if (key == "g") by_key[1] = value;
        if (key == "g4") by_key[2] = value;
        if (key == "m") by_key[3] = value;
    }
    const std::string* spec = nullptr;
    for (const std::string& v : by_key)
        if (!spec && !v.empty()) spec = &v;
    if (!spec)
        lex.fail_at(s.line,
                    "no colour (key c, g, g4 or m) for the pixel code '" + printable(code) + "'");
    Rgba rgba;
    if (!parse_xpm_color(*spec, rgba))
        lex.fail_at(s.line, "unknown colour '" + printable(*spec) +
                                "' (neither None, #hex, nor one of the " +
                                std::to_string(kX11ColorCount) + " X11 colour names)");
    return rgba;
}

/// The colour table: pixel code -> colour, from strings 1 to n_colors.
std::unordered_map<std::uint64_t, Rgba> read_xpm_colors(const std::vector<XpmString>& strings,
                                                        const XpmValues& x,
                                                        const TextScanner& lex) {
    const std::size_t chars = std::size_t(x.cpp);
    std::unordered_map<std::uint64_t, Rgba> table;
    for (std::size_t i = 1; i < 1 + std::size_t(x.n_colors); ++i) {
        const XpmString& s = strings[i];
        if (s.text.size() < chars)
            lex.fail_at(s.line, "the colour line is shorter than the " + std::to_string(chars) +
                                    " characters of a pixel");
        const std::string_view code = std::string_view(s.text).substr(0, chars);
        const Rgba rgba = parse_xpm_color_line(s, chars, lex);
        if (!table.emplace(pixel_code(code), rgba).second)
            lex.fail_at(s.line, "the pixel code '" + printable(code) + "' is defined twice");
    }
    return table;
}

/// The pixel rows (strings after the colours): every row's length is checked before the
/// image is allocated; each pixel code is looked up in `table`.
Image decode_xpm_rows(const std::vector<XpmString>& strings, const XpmValues& x,
                      const std::unordered_map<std::uint64_t, Rgba>& table,
                      const TextScanner& lex) {
    const std::size_t chars = std::size_t(x.cpp), n_rows = std::size_t(x.height);
    const std::size_t first_row = 1 + std::size_t(x.n_colors);
    const std::size_t width = std::size_t(x.width), row_length = width * chars;
    for (std::size_t y = 0; y < n_rows; ++y) {
        const XpmString& s = strings[first_row + y];
        if (s.text.size() != row_length)
            lex.fail_at(s.line, "the pixel row has " + std::to_string(s.text.size()) +
                                    " characters, expected " + std::to_string(row_length) + " (" +
                                    std::to_string(x.width) + " pixels of " +
                                    std::to_string(chars) + ")");
    }
    Image image = make_image(x.width, x.height);
    for (std::size_t y = 0; y < n_rows; ++y) {
        const XpmString& s = strings[first_row + y];
        for (std::size_t col = 0; col < width; ++col) {
            const std::string_view code = std::string_view(s.text).substr(col * chars, chars);
            const auto it = table.find(pixel_code(code));
            if (it == table.end())
                lex.fail_at(s.line, "unknown pixel code '" + printable(code) + "' in column " +
                                        std::to_string(col + 1));
            const Rgba& c = it->second;
            put(image, y * width + col, c.r, c.g, c.b, c.a);
        }
    }
    return image;
}

/// An XPM3 image: the marker, the string array, the values line, the colours, the rows.
Image read_xpm(const std::string& text, const std::string& path) {
    if (text.empty()) throw IoError(path, 0, "the file is empty");
    check_xpm_marker(text, path);
    TextScanner lex = TextScanner::c_source(text, path);
    const std::vector<XpmString> strings = read_xpm_strings(lex);
    const XpmValues values = parse_xpm_values(strings, lex, path);
    const auto table = read_xpm_colors(strings, values, lex);
    return decode_xpm_rows(strings, values, table, lex);
}

}  // namespace

std::vector<std::string> supported_image_extensions() {
    return {"bmp", "png", "pnm", "ppm", "pgm", "pbm", "xbm", "xpm"};
}

namespace {
bool is_supported_image_extension(const std::string& ext) {
    const std::vector<std::string> all = supported_image_extensions();
    return std::find(all.begin(), all.end(), ext) != all.end();
}
}  // namespace

Image read_image(const std::string& path) {
    const std::string ext = extension_of(path);
    if (is_supported_image_extension(ext)) return read_image_bytes(read_file_bytes(path), path);
    std::string list;
    for (const std::string& e : supported_image_extensions())
        list += (list.empty() ? "" : ", ") + e;
    throw IoError(path, 0,
                  (ext.empty() ? std::string("the file name has no extension")
                               : "unsupported image extension '." + ext + "'") +
                      " (supported: " + list + ")");
}

Image read_image_bytes(const std::string& bytes, const std::string& name) {
    const std::string ext = extension_of(name);
    // The text formats (and PNM, which starts as text) skip a UTF-8 byte-order mark and
    // refuse UTF-16/32, as the mesh readers do.
    if (ext == "xpm" || ext == "xbm" || ext == "pnm" || ext == "ppm" || ext == "pgm" ||
        ext == "pbm") {
        const std::string_view text = strip_utf8_bom(bytes, name);
        if (text.size() != bytes.size()) return read_image_bytes(std::string(text), name);
    }
    if (ext == "png") return read_with_stb(bytes, name, "PNG");
    if (ext == "bmp") return read_with_stb(bytes, name, "BMP");
    if (ext == "pnm" || ext == "ppm" || ext == "pgm" || ext == "pbm") return read_pnm(bytes, name);
    if (ext == "xbm") return read_xbm(bytes, name);
    if (ext == "xpm") return read_xpm(bytes, name);
    throw IoError(name, 0, "unsupported image extension '." + ext + "'");
}

void write_png(const Image& image, const std::string& path) {
    if (image.empty())
        throw IoError(path, 0,
                      "cannot write an empty image (" + std::to_string(image.width) + " x " +
                          std::to_string(image.height) + ")");
    check_dimensions(image.width, image.height, path, 0);
    const std::size_t expected = std::size_t(image.width) * std::size_t(image.height) * 4;
    if (image.rgba.size() != expected)
        throw IoError(path, 0,
                      "the image holds " + std::to_string(image.rgba.size()) + " bytes, but " +
                          std::to_string(image.width) + " x " + std::to_string(image.height) +
                          " RGBA pixels need " + std::to_string(expected));
    // Encode in memory first: the callback runs inside C code, where nothing may throw.
    struct Sink {
        std::string bytes;
        bool failed = false;
    } sink;
    auto append = [](void* context, void* data, int size) {
        auto* s = static_cast<Sink*>(context);
        try {
            s->bytes.append(static_cast<const char*>(data), std::size_t(size));
        } catch (...) {
            s->failed = true;
        }
    };
    // The flag is global in stb and the viewer's screenshot turns it on: rows go top down.
    stbi_flip_vertically_on_write(0);
    const int ok = stbi_write_png_to_func(append, &sink, image.width, image.height, 4,
                                          image.rgba.data(), image.width * 4);
    if (!ok || sink.failed) throw IoError(path, 0, "PNG encoding failed (out of memory?)");
    write_file_atomically(path, [&](std::ostream& out) {
        out.write(sink.bytes.data(), std::streamsize(sink.bytes.size()));
    });
}

Image make_checkerboard(int size, int squares) {
    if (size < 1 || size > kMaxSide)
        throw InvalidArgument("make_checkerboard: size " + std::to_string(size) +
                              " is outside 1 to " + std::to_string(kMaxSide));
    if (squares < 1 || squares > size)
        throw InvalidArgument("make_checkerboard: squares " + std::to_string(squares) +
                              " is outside 1 to size (" + std::to_string(size) + ")");
    constexpr std::uint32_t kLight = 204, kDark = 122;
    Image image = make_image(size, size);
    const auto n = std::size_t(size), k = std::size_t(squares);
    for (std::size_t y = 0; y < n; ++y)
        for (std::size_t x = 0; x < n; ++x) {
            const bool light = ((x * k / n) + (y * k / n)) % 2 == 0;
            const std::uint32_t v = light ? kLight : kDark;
            put(image, y * n + x, v, v, v);
        }
    return image;
}

}  // namespace trilab
