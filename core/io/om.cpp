// OpenMesh binary .om reader (formats 1.x to 2.2) and writer (format 2.2).
//
// The format, as described byte by byte in ../shared/docs/om-format.md: a 16-byte header
// ("OM", mesh kind 'T'/'Q'/'P', version byte (major << 5) | minor, then u32 n_v, n_f, n_e),
// followed by chunks. A chunk is a u16 header (bit 1 name, bits 2-4 entity, 5-8 type, 9
// signed, 10 float, 11-13 dim - 1, 14-15 size code; om-format.md §3), an optional name
// string (u8 length + bytes), and a payload whose size follows from the header and the
// element counts (§5, §6); only custom chunks carry a byte count. Little-endian, no
// padding. Entity 7 is the end sentinel; files older than OpenMesh 7 simply end at EOF.
// Format 1.x stores faces as vertex lists (§7); 2.x stores the halfedge structure: per
// halfedge (next, to_vertex, face), per vertex one outgoing halfedge, per face one halfedge,
// as signed integers of width 1 << bits (§6.1, §6.2). Halfedges come in pairs (twin = h ^ 1),
// exactly as in our HalfedgeMesh.
//
// Reader: every read is checked against the file size. Chunks are located first and decoded
// in bulk afterwards, straight from the (memory-mapped) file. The 2.x arrays are validated
// (ranges, next is a permutation of the live halfedges whose loops keep one face and chain
// head to tail, vertex halfedges are outgoing). Elements whose status has the DELETED bit are
// dropped. When the file is already a valid triangle mesh in our sense (triangles only,
// manifold vertices, no deleted elements) its arrays are adopted directly, keeping the
// file's element numbering; otherwise face loops become polygons of a PolygonSoup and
// build_mesh repairs and triangulates. Face normals, face colours and custom properties
// (except a float vertex property "selection", read as "v:selection", a uint8_t vertex
// property "corner", read as "v:corner", and, in 2.x files, a float edge property "sharpness",
// read as "e:sharpness") are skipped (by their computed size or their byte count) and reported.
//
// Writer: format 2.2, kind 'T', chunks in OpenMesh 11's order (§10). Positions and normals
// are written as f64 (0x5600 / 0x5620, allowed since 2.1) so that our doubles round-trip
// exactly; colours are u8, texture coordinates f32 (the only widths the format has for
// them). The index width is the smallest of 1, 2, 4 bytes that holds every index. Custom
// attributes are not written, except the selection "v:selection": a custom vertex property
// "selection" of type float (read back by this reader, and by OpenMesh as a float property),
// and the features (core/features.h) when the mesh has any: a custom vertex property "corner"
// (uint8_t) and a custom edge property "sharpness" (float, +inf kept).
// Non-finite values, and texture coordinates beyond float32's range, are refused; the reader
// refuses NaN and infinity in every attribute.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <ostream>
#include <string>
#include <vector>

#include "core/errors.h"
#include "core/features.h"
#include "core/io/byte_io.h"
#include "core/io/file_util.h"
#include "core/io/mesh_io.h"
#include "core/number_text.h"

namespace trilab {

namespace {

// ---- little-endian scalars ---------------------------------------------------------------

constexpr bool kBigEndianHost = !kLittleEndianHost;

template <class T>
T load_le(const unsigned char* p) {
    return load_bytes<T, kBigEndianHost>(p);
}

template <class T>
void store_le(unsigned char*& p, T v) {
    if constexpr (kBigEndianHost) {
        unsigned char b[sizeof(T)];
        std::memcpy(b, &v, sizeof(T));
        for (std::size_t i = 0; i < sizeof(T); ++i) p[i] = b[sizeof(T) - 1 - i];
    } else {
        std::memcpy(p, &v, sizeof(T));
    }
    p += sizeof(T);
}

// ---- chunk header fields (om-format.md §3) -----------------------------------------------

enum Entity : unsigned { kVertex = 0, kMesh = 1, kFace = 2, kEdge = 4, kHalf = 6, kSentinel = 7 };
enum Type : unsigned {
    kPosition = 0,
    kNormal = 1,
    kTexcoord = 2,
    kStatus = 3,
    kColor = 4,
    kCustom = 6,
    kTopology = 7
};

constexpr std::uint32_t kStatusDeleted = 1;  // §6.6

struct ChunkHeader {
    std::uint16_t raw = 0;
    bool has_name = false;
    unsigned entity = 0, type = 0, dim = 1, bits = 0;
    std::size_t at = 0;  ///< byte offset of the chunk in the file
};

ChunkHeader decode_header(std::uint16_t raw, std::size_t at) {
    ChunkHeader h;
    h.raw = raw;
    h.has_name = (raw >> 1) & 1u;
    h.entity = (raw >> 2) & 7u;
    h.type = (raw >> 5) & 15u;
    h.dim = ((raw >> 11) & 7u) + 1;
    h.bits = (raw >> 14) & 3u;
    h.at = at;
    return h;
}

constexpr std::uint16_t encode_header(unsigned entity, unsigned type, bool is_signed, bool is_float,
                                      unsigned dim, unsigned bits) {
    return std::uint16_t((entity << 2) | (type << 5) | (unsigned(is_signed) << 9) |
                         (unsigned(is_float) << 10) | ((dim - 1) << 11) | (bits << 14));
}

/// The name of the custom vertex property that holds "v:selection" (OpenMesh skips names
/// whose second character is ':', so the "v:" prefix is left out), and the bytes its chunk
/// takes before the data: header, name, type name "float", byte count.
constexpr const char* kOmSelectionName = "selection";
constexpr std::uint64_t kOmSelectionChunkHead = 2 + (1 + 9) + (1 + 5) + 4;
/// The custom edge property that holds "e:sharpness" (float, +inf allowed) and the custom
/// vertex property that holds "v:corner" (uint8_t, 0 or 1), with their chunk heads.
constexpr const char* kOmSharpnessName = "sharpness";
constexpr std::uint64_t kOmSharpnessChunkHead = 2 + (1 + 9) + (1 + 5) + 4;
constexpr const char* kOmCornerName = "corner";
constexpr std::uint64_t kOmCornerChunkHead = 2 + (1 + 6) + (1 + 7) + 4;

std::string hex16(std::uint16_t v) {
    static const char digits[] = "0123456789ABCDEF";
    std::string s = "0x";
    for (int shift = 12; shift >= 0; shift -= 4) s += digits[(v >> shift) & 15u];
    return s;
}

std::string describe(const ChunkHeader& h) {
    static const char* const entities[8] = {"vertex", "mesh",     "face",     "entity 3",
                                            "edge",   "entity 5", "halfedge", "sentinel"};
    static const char* const types[16] = {
        "position", "normal", "texcoord", "status",  "color",   "type 5",  "custom",  "topology",
        "type 8",   "type 9", "type 10",  "type 11", "type 12", "type 13", "type 14", "type 15"};
    return std::string(entities[h.entity]) + " " + types[h.type] + " chunk " + hex16(h.raw) +
           " at byte " + std::to_string(h.at);
}

std::string version_string(unsigned char byte) {
    return std::to_string(byte >> 5) + "." + std::to_string(byte & 31u);
}

// ---- bounds-checked input ----------------------------------------------------------------

class Cursor {
public:
    Cursor(const std::string& path, const unsigned char* data, std::size_t size)
        : path_(path), data_(data), size_(size) {}

    std::size_t pos() const { return pos_; }
    std::size_t left() const { return size_ - pos_; }
    bool at_end() const { return pos_ == size_; }

    /// The next `n` bytes (n is a 64-bit product, so that no overflow goes unseen).
    const unsigned char* take(std::uint64_t n, const std::string& what) {
        if (n > left())
            fail("truncated " + what + " (needs " + std::to_string(n) + " bytes at byte " +
                 std::to_string(pos_) + ", only " + std::to_string(left()) + " left)");
        const unsigned char* p = data_ + pos_;
        pos_ += std::size_t(n);
        return p;
    }
    template <class T>
    T read(const std::string& what) {
        return load_le<T>(take(sizeof(T), what));
    }
    /// A u8-length string (om-format.md §4).
    std::string read_string(const std::string& what) {
        const std::size_t n = read<std::uint8_t>(what + " length");
        const unsigned char* p = take(n, what);
        return std::string(reinterpret_cast<const char*>(p), n);
    }
    [[noreturn]] void fail(const std::string& reason) const { throw IoError(path_, 0, reason); }

private:
    const std::string& path_;
    const unsigned char* data_;
    std::size_t size_;
    std::size_t pos_ = 0;
};

// ---- what the chunks hold, before assembly -----------------------------------------------

/// A chunk payload of fixed-size elements, left in the file until it is decoded.
struct Span {
    const unsigned char* p = nullptr;
    unsigned bits = 0;  ///< positions and normals: 0 = f32, 1 = f64
    explicit operator bool() const { return p != nullptr; }
};

/// Signed indices normalised to 4-byte little-endian integers: the file's bytes themselves
/// when it stores 4-byte indices, a converted copy otherwise.
class IndexArray {
public:
    std::int32_t operator[](std::size_t i) const { return load_le<std::int32_t>(p_ + 4 * i); }
    explicit operator bool() const { return p_ != nullptr; }
    void set(Cursor& in, const ChunkHeader& h, std::uint64_t n) {
        const std::size_t width = std::size_t(1) << h.bits;
        const unsigned char* src = in.take(n * width, describe(h));
        if (width == 4) {
            p_ = src;
            return;
        }
        owned_.resize(std::size_t(4 * n));
        unsigned char* out = owned_.data();
        for (std::size_t i = 0; i < n; ++i) {
            std::int64_t v;
            if (width == 1)
                v = load_le<std::int8_t>(src + i);
            else if (width == 2)
                v = load_le<std::int16_t>(src + 2 * i);
            else
                v = load_le<std::int64_t>(src + 8 * i);
            if (v < -1 || v > std::numeric_limits<std::int32_t>::max())
                in.fail(describe(h) + ": index " + std::to_string(v) + " out of range");
            store_le<std::int32_t>(out, std::int32_t(v));
        }
        p_ = owned_.data();
    }

private:
    const unsigned char* p_ = nullptr;
    std::vector<unsigned char> owned_;
};

struct OmContents {
    unsigned char kind = 'T';
    unsigned char version = 0;
    std::uint32_t n_v = 0, n_f = 0, n_e = 0;
    bool v2 = false;  ///< format 2.x (halfedge topology) rather than 1.x (vertex lists)

    Span positions, normals, colors, texcoords, halfedge_texcoords;
    IndexArray htopo;  ///< 2.x: next, to_vertex, face per halfedge
    IndexArray vtopo;  ///< 2.x: one outgoing halfedge per vertex
    IndexArray ftopo;  ///< 2.x: one halfedge per face

    bool faces_1x = false;  ///< 1.x: faces as vertex lists
    std::vector<Index> corners;
    std::vector<std::size_t> face_offsets;

    // DELETED bits from status chunks (empty when absent or when nothing is deleted).
    std::vector<std::uint8_t> vdeleted, edeleted, hdeleted, fdeleted;

    std::vector<std::string> custom_names;
    /// The custom vertex property "selection" of type float (n_v weights in [0, 1]), read as
    /// "v:selection"; null when absent.
    Span selection;
    /// The custom edge property "sharpness" (float, n_e values, 2.x only) and the custom
    /// vertex property "corner" (uint8_t, n_v values): "e:sharpness", "v:corner".
    Span sharpness, corner;
    bool custom_on_faces_or_halfedges = false;
    bool face_normals = false, face_colors = false, ignored_1x_halfedge_texcoords = false;

    bool any_deleted() const {
        return !vdeleted.empty() || !edeleted.empty() || !hdeleted.empty() || !fdeleted.empty();
    }
};

std::uint64_t element_count(const OmContents& c, unsigned entity) {
    switch (entity) {
        case kVertex:
            return c.n_v;
        case kFace:
            return c.n_f;
        case kEdge:
            return c.n_e;
        case kHalf:
            return 2 * std::uint64_t(c.n_e);
        default:
            return 1;  // mesh
    }
}

/// n 3-vectors of f32 (bits 0) or f64 (bits 1); see §6 "position and normal width".
Span take_vec3(Cursor& in, const ChunkHeader& h, std::uint64_t n) {
    if (h.dim != 3)
        in.fail(describe(h) + ": expected 3 components, the header says " + std::to_string(h.dim));
    if (h.bits > 1)
        in.fail(describe(h) + ": only f32 and f64 are supported (size code " +
                std::to_string(h.bits) + ")");
    return Span{in.take(n * 3 * (h.bits == 0 ? 4 : 8), describe(h)), h.bits};
}

Vector3 vec3_at(const Span& s, std::size_t i) {
    if (s.bits == 0) {
        const unsigned char* p = s.p + 12 * i;
        return Vector3(load_le<float>(p), load_le<float>(p + 4), load_le<float>(p + 8));
    }
    const unsigned char* p = s.p + 24 * i;
    return Vector3(load_le<double>(p), load_le<double>(p + 8), load_le<double>(p + 16));
}

/// Colours are always 3 x u8 and texture coordinates always 2 x f32, whatever the flags
/// say (§6).
Color color_at(const Span& s, std::size_t i) {
    const unsigned char* p = s.p + 3 * i;
    return Color(p[0] / 255.0f, p[1] / 255.0f, p[2] / 255.0f);
}
TexCoord texcoord_at(const Span& s, std::size_t i) {
    const unsigned char* p = s.p + 8 * i;
    return TexCoord(load_le<float>(p), load_le<float>(p + 4));
}

void read_status(Cursor& in, const ChunkHeader& h, std::uint64_t n,
                 std::vector<std::uint8_t>& deleted) {
    const unsigned char* p = in.take(n * 4, describe(h));
    deleted.assign(std::size_t(n), 0);
    bool any = false;
    for (std::size_t i = 0; i < n; ++i) {
        deleted[i] = (load_le<std::uint32_t>(p + 4 * i) & kStatusDeleted) ? 1 : 0;
        any = any || deleted[i];
    }
    if (!any) deleted.clear();
}

/// Format 1.x face chunk: vertex lists of unsigned indices (om-format.md §7).
void read_faces_1x(Cursor& in, const ChunkHeader& h, OmContents& c) {
    const std::size_t width = std::size_t(1) << h.bits;
    bool too_big = false;
    auto index_at = [&](const unsigned char* p) -> Index {
        switch (width) {
            case 1:
                return *p;
            case 2:
                return load_le<std::uint16_t>(p);
            case 4:
                return load_le<std::uint32_t>(p);
            default: {
                const std::uint64_t v = load_le<std::uint64_t>(p);
                if (v >= kInvalidIndex) too_big = true;
                return Index(v);
            }
        }
    };
    c.corners.clear();
    c.face_offsets.assign(1, 0);
    c.face_offsets.reserve(std::size_t(c.n_f) + 1);
    if (c.kind != 'P') {
        const std::size_t k = c.kind == 'Q' ? 4 : 3;
        const unsigned char* p = in.take(std::uint64_t(c.n_f) * k * width, describe(h));
        c.corners.resize(std::size_t(c.n_f) * k);
        for (std::size_t i = 0; i < c.corners.size(); ++i) c.corners[i] = index_at(p + i * width);
        for (std::size_t f = 1; f <= c.n_f; ++f) c.face_offsets.push_back(f * k);
    } else {
        c.corners.reserve(std::size_t(c.n_f) * 3);
        for (std::size_t f = 0; f < c.n_f; ++f) {
            const std::size_t k = in.read<std::uint16_t>("valence of face " + std::to_string(f));
            const unsigned char* p =
                in.take(std::uint64_t(k) * width, "vertex indices of face " + std::to_string(f));
            for (std::size_t i = 0; i < k; ++i) c.corners.push_back(index_at(p + i * width));
            c.face_offsets.push_back(c.corners.size());
        }
    }
    if (too_big) in.fail(describe(h) + ": a vertex index does not fit in 32 bits");
    c.faces_1x = true;
}

/// Custom chunk (§6.4): [type name, format > 2.1], u32 byte count, data; skipped, except the
/// vertex selection (kOmSelectionName, float, one per vertex), which is checked and kept.
void skip_custom(Cursor& in, const ChunkHeader& h, const std::string& name, OmContents& c) {
    std::string type;
    if (c.version > 0x41) type = in.read_string("type name of custom property '" + name + "'");
    const std::uint32_t bytes =
        in.read<std::uint32_t>("byte count of custom property '" + name + "'");
    const unsigned char* data = in.take(bytes, "data of custom property '" + name + "'");
    if (h.entity == kVertex && name == kOmSelectionName && type == "float" &&
        std::uint64_t(bytes) == 4 * std::uint64_t(c.n_v)) {
        for (std::size_t v = 0; v < c.n_v; ++v) {
            const float w = load_le<float>(data + 4 * v);
            if (!(w >= 0.0f && w <= 1.0f))
                in.fail("custom property 'selection': vertex " + std::to_string(v) + ": weight " +
                        number_text(w) + " is not in [0, 1]");
        }
        c.selection = Span{data};
        return;
    }
    if (c.v2 && h.entity == kEdge && name == kOmSharpnessName && type == "float" &&
        std::uint64_t(bytes) == 4 * std::uint64_t(c.n_e)) {
        for (std::size_t e = 0; e < c.n_e; ++e) {
            const float s = load_le<float>(data + 4 * e);
            if (!valid_sharpness(s))
                in.fail("custom property 'sharpness': edge " + std::to_string(e) + ": sharpness " +
                        number_text(s) + " is not >= 0 (or inf)");
        }
        c.sharpness = Span{data};
        return;
    }
    if (h.entity == kVertex && name == kOmCornerName && type == "uint8_t" &&
        std::uint64_t(bytes) == std::uint64_t(c.n_v)) {
        for (std::size_t v = 0; v < c.n_v; ++v)
            if (data[v] > 1)
                in.fail("custom property 'corner': vertex " + std::to_string(v) + ": tag " +
                        std::to_string(unsigned(data[v])) + " is not 0 or 1");
        c.corner = Span{data};
        return;
    }
    c.custom_names.push_back(name);
    if (h.entity == kFace || h.entity == kHalf) c.custom_on_faces_or_halfedges = true;
}

[[noreturn]] void unsupported(Cursor& in, const ChunkHeader& h) {
    in.fail("unsupported " + describe(h) + ": its size is unknown, refusing to guess");
}

/// Parses the header and locates all chunks up to the sentinel or EOF.
void parse(Cursor& in, const std::string& path, OmContents& c) {
    const unsigned char* head = in.take(16, "header");
    if (head[0] != 'O' || head[1] != 'M')
        in.fail("not an .om file (the first bytes are not \"OM\")");
    c.kind = head[2];
    if (c.kind != 'T' && c.kind != 'Q' && c.kind != 'P')
        in.fail("unknown .om mesh kind byte " + std::to_string(unsigned(c.kind)) +
                " (expected 'T', 'Q' or 'P')");
    c.version = head[3];
    if (c.version > 0x42 || c.version < 0x20)
        in.fail("unsupported .om version " + version_string(c.version) +
                " (trilab reads 1.2 to 2.2)");
    c.v2 = c.version >= 0x40;
    c.n_v = load_le<std::uint32_t>(head + 4);
    c.n_f = load_le<std::uint32_t>(head + 8);
    c.n_e = load_le<std::uint32_t>(head + 12);
    // Every vertex needs 12 bytes of positions, every face at least one byte of topology,
    // every 2.x edge two halfedges of three indices. (1.x edge counts are informational.)
    const std::size_t body = in.left();
    check_declared_count(c.n_v, 12, body, "vertices", path, 0);
    check_declared_count(c.n_f, 1, body, "faces", path, 0);
    if (c.v2) check_declared_count(c.n_e, 6, body, "edges", path, 0);

    while (!in.at_end()) {
        const std::size_t at = in.pos();
        const ChunkHeader h = decode_header(in.read<std::uint16_t>("chunk header"), at);
        if (h.entity == kSentinel) break;  // trailing bytes are ignored, as OpenMesh does
        std::string name;
        if (h.has_name) name = in.read_string("property name");
        const std::uint64_t n = element_count(c, h.entity);
        const unsigned key = (h.entity << 4) | h.type;
        switch (key) {
            case (kVertex << 4) | kCustom:
            case (kMesh << 4) | kCustom:
            case (kFace << 4) | kCustom:
            case (kEdge << 4) | kCustom:
            case (kHalf << 4) | kCustom:
                skip_custom(in, h, name, c);
                break;
            case (kVertex << 4) | kPosition:
                c.positions = take_vec3(in, h, n);
                break;
            case (kVertex << 4) | kNormal:
                c.normals = take_vec3(in, h, n);
                break;
            case (kVertex << 4) | kColor:
                c.colors = Span{in.take(n * 3, describe(h))};
                break;
            case (kVertex << 4) | kTexcoord:
                c.texcoords = Span{in.take(n * 8, describe(h))};
                break;
            case (kVertex << 4) | kStatus:
                read_status(in, h, n, c.vdeleted);
                break;
            case (kVertex << 4) | kTopology:
                if (!c.v2) unsupported(in, h);
                c.vtopo.set(in, h, n);
                break;
            case (kFace << 4) | kTopology:
                if (c.v2)
                    c.ftopo.set(in, h, n);
                else
                    read_faces_1x(in, h, c);
                break;
            case (kFace << 4) | kNormal:
                take_vec3(in, h, n);
                c.face_normals = true;
                break;
            case (kFace << 4) | kColor:
                in.take(n * 3, describe(h));
                c.face_colors = true;
                break;
            case (kFace << 4) | kStatus:
                read_status(in, h, n, c.fdeleted);
                break;
            case (kEdge << 4) | kStatus:
                read_status(in, h, n, c.edeleted);
                break;
            case (kHalf << 4) | kTopology:
                if (!c.v2) unsupported(in, h);
                c.htopo.set(in, h, 3 * n);
                break;
            case (kHalf << 4) | kTexcoord:
                c.halfedge_texcoords = Span{in.take(n * 8, describe(h))};
                if (!c.v2) {
                    c.halfedge_texcoords = Span{};
                    c.ignored_1x_halfedge_texcoords = true;
                }
                break;
            case (kHalf << 4) | kStatus:
                read_status(in, h, n, c.hdeleted);
                break;
            default:
                unsupported(in, h);
        }
    }
}

// ---- assembly ----------------------------------------------------------------------------

struct Assembly {
    PolygonSoup soup;
    HalfedgeMesh mesh;
    bool adopted = false;  ///< `mesh` holds the file's arrays directly (no soup)
    std::size_t deleted_vertices = 0, deleted_faces = 0, faceless_edges = 0, isolated = 0;
};

/// Old vertex index -> new index (kInvalidIndex for deleted vertices); empty = identity.
std::vector<Index> vertex_map(const OmContents& c, Assembly& a) {
    std::vector<Index> map;
    if (c.vdeleted.empty()) return map;
    map.assign(c.n_v, kInvalidIndex);
    Index next = 0;
    for (std::size_t v = 0; v < c.n_v; ++v) {
        if (c.vdeleted[v])
            ++a.deleted_vertices;
        else
            map[v] = next++;
    }
    return map;
}

void check_positions_present(const OmContents& c) {
    if (!c.positions && c.n_v > 0)
        throw Error("the file declares " + std::to_string(c.n_v) +
                    " vertices but has no vertex position chunk");
}

/// Live vertices and their attributes into the soup.
void soup_vertices(const OmContents& c, Assembly& a) {
    check_positions_present(c);
    PolygonSoup& s = a.soup;
    auto live = [&](std::size_t v) { return c.vdeleted.empty() || !c.vdeleted[v]; };
    s.positions.reserve(c.n_v);
    for (std::size_t v = 0; v < c.n_v; ++v)
        if (live(v)) s.positions.push_back(vec3_at(c.positions, v));
    for (std::size_t v = 0; v < c.n_v; ++v) {
        if (!live(v)) continue;
        if (c.normals) s.normals.push_back(vec3_at(c.normals, v));
        if (c.colors) s.colors.push_back(color_at(c.colors, v));
        if (c.texcoords) s.texcoords.push_back(texcoord_at(c.texcoords, v));
        if (c.selection) s.selections.push_back(load_le<float>(c.selection.p + 4 * v));
        if (c.corner) s.corner_tags.push_back(c.corner.p[v]);
    }
}

void assemble_1x(const OmContents& c, Assembly& a) {
    if (c.n_f > 0 && !c.faces_1x)
        throw Error("the file declares " + std::to_string(c.n_f) +
                    " faces but has no face topology chunk");
    soup_vertices(c, a);
    const std::vector<Index> vmap = vertex_map(c, a);
    PolygonSoup& soup = a.soup;
    soup.corners.reserve(c.corners.size());
    soup.face_offsets.reserve(std::size_t(c.n_f) + 1);
    for (std::size_t f = 0; f < c.n_f; ++f) {
        if (!c.fdeleted.empty() && c.fdeleted[f]) {
            ++a.deleted_faces;
            continue;
        }
        for (std::size_t i = c.face_offsets[f]; i < c.face_offsets[f + 1]; ++i) {
            const Index v = c.corners[i];
            if (v >= c.n_v)
                throw Error("face " + std::to_string(f) + " uses vertex " + std::to_string(v) +
                            " but the file has only " + std::to_string(c.n_v) + " vertices");
            if (!vmap.empty() && vmap[v] == kInvalidIndex)
                throw Error("face " + std::to_string(f) + " uses deleted vertex " +
                            std::to_string(v));
            soup.corners.push_back(vmap.empty() ? v : vmap[v]);
        }
        soup.face_offsets.push_back(soup.corners.size());
    }
}

/// The 2.x halfedge arrays with liveness, checked by validate_2x().
class Topology2 {
public:
    explicit Topology2(const OmContents& contents)
        : c(contents), n_v(c.n_v), n_f(c.n_f), n_h(c.htopo ? 2 * std::size_t(c.n_e) : 0) {}
    std::size_t next(std::size_t h) const { return std::size_t(c.htopo[3 * h]); }
    std::size_t to(std::size_t h) const { return std::size_t(c.htopo[3 * h + 1]); }
    std::int32_t face(std::size_t h) const { return c.htopo[3 * h + 2]; }
    bool vertex_live(std::size_t v) const { return c.vdeleted.empty() || !c.vdeleted[v]; }
    bool face_live(std::size_t f) const { return c.fdeleted.empty() || !c.fdeleted[f]; }
    /// A halfedge is dead when its edge or either half is marked deleted.
    bool halfedge_live(std::size_t h) const {
        if (!c.edeleted.empty() && c.edeleted[h >> 1]) return false;
        if (!c.hdeleted.empty() && (c.hdeleted[h & ~std::size_t(1)] || c.hdeleted[h | 1]))
            return false;
        return true;
    }

    const OmContents& c;
    const std::size_t n_v, n_f, n_h;
    std::vector<Index> face_size;  ///< live halfedges per face
    std::size_t faceless_edges = 0, self_loops = 0;
};

std::string hs(std::size_t h) {
    return "halfedge " + std::to_string(h);
}

/// Validates the 2.x arrays (om-format.md §6.2); throws Error naming the first problem.
void validate_2x(Topology2& t) {
    const OmContents& c = t.c;
    const std::size_t n_v = t.n_v, n_f = t.n_f, n_h = t.n_h;
    if (n_f > 0 && !c.ftopo)
        throw Error("the file declares " + std::to_string(n_f) +
                    " faces but has no face topology chunk");
    if (!c.htopo)
        for (std::size_t f = 0; f < n_f; ++f)
            if (t.face_live(f)) throw Error("the file has faces but no halfedge topology chunk");
    const bool all_live = c.edeleted.empty() && c.hdeleted.empty();

    // Ranges and liveness; next is injective on the live halfedges (hence a permutation)
    // and keeps the face.
    t.face_size.assign(n_f, 0);
    std::vector<std::uint8_t> has_prev(n_h, 0);
    for (std::size_t h = 0; h < n_h; ++h) {
        if (!all_live && !t.halfedge_live(h)) continue;
        const std::int32_t nx = c.htopo[3 * h], tv = c.htopo[3 * h + 1], fc = c.htopo[3 * h + 2];
        if (nx < 0 || std::size_t(nx) >= n_h)
            throw Error(hs(h) + ": next " + std::to_string(nx) + " out of range");
        if (tv < 0 || std::size_t(tv) >= n_v)
            throw Error(hs(h) + ": to_vertex " + std::to_string(tv) + " out of range");
        if (fc < -1 || (fc >= 0 && std::size_t(fc) >= n_f))
            throw Error(hs(h) + ": face " + std::to_string(fc) + " out of range");
        if (!all_live && !t.halfedge_live(std::size_t(nx)))
            throw Error(hs(h) + ": next is the deleted " + hs(std::size_t(nx)));
        if (!t.vertex_live(std::size_t(tv)))
            throw Error(hs(h) + " points to the deleted vertex " + std::to_string(tv));
        if (fc >= 0 && !t.face_live(std::size_t(fc)))
            throw Error(hs(h) + " belongs to the deleted face " + std::to_string(fc));
        if (has_prev[std::size_t(nx)])
            throw Error("next is not a permutation: two halfedges precede " + hs(std::size_t(nx)));
        has_prev[std::size_t(nx)] = 1;
        if (t.face(std::size_t(nx)) != fc)
            throw Error(hs(h) + " and its next " + hs(std::size_t(nx)) +
                        " belong to different faces");
        if (fc >= 0) ++t.face_size[std::size_t(fc)];
    }
    // Head to tail: from_vertex(next(h)) == to_vertex(h); every to() is now in range.
    for (std::size_t h = 0; h < n_h; ++h) {
        if (!all_live && !t.halfedge_live(h)) continue;
        if (t.to(t.next(h) ^ 1) != t.to(h))
            throw Error(hs(h) + " ends at vertex " + std::to_string(t.to(h)) + " but its next " +
                        hs(t.next(h)) + " starts at vertex " + std::to_string(t.to(t.next(h) ^ 1)));
        if ((h & 1) == 0) {
            if (t.face(h) < 0 && t.face(h + 1) < 0) ++t.faceless_edges;
            if (t.to(h) == t.to(h + 1)) ++t.self_loops;
        }
    }

    // Vertex halfedges are outgoing, or -1.
    if (c.vtopo) {
        for (std::size_t v = 0; v < n_v; ++v) {
            if (!t.vertex_live(v)) continue;
            const std::int32_t vh = c.vtopo[v];
            if (vh == -1) continue;
            const std::string vs = "vertex " + std::to_string(v);
            if (vh < 0 || std::size_t(vh) >= n_h)
                throw Error(vs + ": halfedge " + std::to_string(vh) + " out of range");
            if (!all_live && !t.halfedge_live(std::size_t(vh)))
                throw Error(vs + " stores the deleted " + hs(std::size_t(vh)));
            if (t.to(std::size_t(vh) ^ 1) != v)
                throw Error(vs + ": its " + hs(std::size_t(vh)) + " is not outgoing");
        }
    }

    // Face halfedges belong to their face, and each face's halfedges form one loop.
    for (std::size_t f = 0; f < n_f; ++f) {
        if (!t.face_live(f)) continue;
        const std::int32_t fh = c.ftopo[f];
        const std::string fs = "face " + std::to_string(f);
        if (fh < 0 || std::size_t(fh) >= n_h)
            throw Error(fs + ": halfedge " + std::to_string(fh) + " out of range");
        if (!all_live && !t.halfedge_live(std::size_t(fh)))
            throw Error(fs + " stores the deleted " + hs(std::size_t(fh)));
        if (t.face(std::size_t(fh)) != std::int32_t(f))
            throw Error(fs + ": its " + hs(std::size_t(fh)) + " belongs to face " +
                        std::to_string(t.face(std::size_t(fh))));
        // The loop through fh holds only halfedges of f; it must hold all of them.
        std::size_t len = 0, h = std::size_t(fh);
        do {
            h = t.next(h);
            ++len;
        } while (h != std::size_t(fh) && len <= t.face_size[f]);
        if (len != t.face_size[f]) throw Error(fs + ": its halfedges form more than one loop");
    }
}

/// Adopts validated 2.x arrays directly when they already satisfy our mesh's invariants
/// (see core/halfedge_mesh.h); returns false, with `a.mesh` cleared, when they do not.
bool adopt_2x(const Topology2& t, Assembly& a) {
    const OmContents& c = t.c;
    if (c.any_deleted() || !c.vtopo || t.n_v == 0 || t.faceless_edges > 0 || t.self_loops > 0)
        return false;
    for (Index s : t.face_size)
        if (s != 3) return false;
    const std::size_t n_v = t.n_v, n_f = t.n_f, n_h = t.n_h, n_e = n_h / 2;

    HalfedgeMesh& m = a.mesh;
    m.resize_elements(n_v, n_e, n_f);
    std::vector<Point>& pos = m.positions();
    for (std::size_t v = 0; v < n_v; ++v) {
        pos[v] = vec3_at(c.positions, v);
        const std::int32_t vh = c.vtopo[v];
        if (vh >= 0) m.set_halfedge(Vertex(Index(v)), Halfedge(Index(vh)));
    }
    for (std::size_t h = 0; h < n_h; ++h) {
        const Halfedge he(static_cast<Index>(h));
        m.set_to_vertex(he, Vertex(Index(t.to(h))));
        m.set_next(he, Halfedge(Index(t.next(h))));
        const std::int32_t f = t.face(h);
        if (f >= 0) m.set_face(he, Face(Index(f)));
    }
    for (std::size_t f = 0; f < n_f; ++f)
        m.set_halfedge(Face(Index(f)), Halfedge(Index(c.ftopo[f])));

    // Vertices must be manifold: one rotation visits every outgoing halfedge, at most one
    // of them is a boundary halfedge (and then it is the stored one), no two go to the same
    // neighbour.
    std::vector<Index> out_degree(n_v, 0);
    for (std::size_t h = 0; h < n_h; ++h) ++out_degree[t.to(h ^ 1)];
    std::vector<Index> stamp(n_v, kInvalidIndex);
    bool ok = true;
    for (std::size_t v = 0; v < n_v && ok; ++v) {
        const Halfedge start = m.halfedge(Vertex(Index(v)));
        if (!start.is_valid()) {
            ok = out_degree[v] == 0;
            ++a.isolated;
            continue;
        }
        Index count = 0, n_boundary = 0;
        Halfedge x = start;
        do {
            const Index w = m.to_vertex(x).idx();
            if (stamp[w] == Index(v)) {
                ok = false;  // two edges to the same neighbour
                break;
            }
            stamp[w] = Index(v);
            if (m.is_boundary(x)) ++n_boundary;
            if (++count > out_degree[v]) {
                ok = false;
                break;
            }
            x = m.ccw_rotated(x);
        } while (x != start);
        ok = ok && count == out_degree[v] && n_boundary <= 1 &&
             (n_boundary == 0 || m.is_boundary(start));
    }
    if (!ok) {
        m = HalfedgeMesh();
        a.isolated = 0;
        return false;
    }

    if (c.normals) {
        auto p = m.vertex_property<Vector3>("v:normal");
        for (std::size_t v = 0; v < n_v; ++v) p.vector()[v] = vec3_at(c.normals, v);
    }
    if (c.colors) {
        auto p = m.vertex_property<Color>("v:color");
        for (std::size_t v = 0; v < n_v; ++v) p.vector()[v] = color_at(c.colors, v);
    }
    if (c.texcoords) {
        auto p = m.vertex_property<TexCoord>("v:texcoord");
        for (std::size_t v = 0; v < n_v; ++v) p.vector()[v] = texcoord_at(c.texcoords, v);
    }
    if (c.selection) {
        auto p = m.vertex_property<float>("v:selection");
        for (std::size_t v = 0; v < n_v; ++v) p.vector()[v] = load_le<float>(c.selection.p + 4 * v);
    }
    if (c.corner) {
        auto p = corner_property(m);
        for (std::size_t v = 0; v < n_v; ++v) p.vector()[v] = c.corner.p[v];
    }
    if (c.sharpness) {
        auto p = sharpness_property(m);
        for (std::size_t e = 0; e < n_e; ++e) p.vector()[e] = load_le<float>(c.sharpness.p + 4 * e);
    }
    if (c.halfedge_texcoords) {
        // Boundary halfedges carry no corner; they get zero, as build_mesh gives them.
        auto p = m.halfedge_property<TexCoord>("h:texcoord", TexCoord::Zero());
        for (std::size_t h = 0; h < n_h; ++h)
            if (t.face(h) >= 0) p.vector()[h] = texcoord_at(c.halfedge_texcoords, h);
    }
    a.adopted = true;
    return true;
}

/// Face loops of validated 2.x arrays as polygons of the soup.
void soup_faces_2x(const Topology2& t, Assembly& a) {
    const OmContents& c = t.c;
    soup_vertices(c, a);
    const std::vector<Index> vmap = vertex_map(c, a);
    a.faceless_edges = t.faceless_edges;
    PolygonSoup& soup = a.soup;
    const bool uv = bool(c.halfedge_texcoords);
    soup.corners.reserve(std::size_t(3) * t.n_f);
    soup.face_offsets.reserve(t.n_f + 1);
    if (uv) soup.corner_texcoords.reserve(std::size_t(3) * t.n_f);
    for (std::size_t f = 0; f < t.n_f; ++f) {
        if (!t.face_live(f)) {
            ++a.deleted_faces;
            continue;
        }
        // Corners start at from_vertex(fh), so that the face's halfedge after build_mesh
        // is the one stored in the file; the corner at to_vertex(h) gets h's texcoord.
        const std::size_t fh = std::size_t(c.ftopo[f]), begin = soup.corners.size();
        std::size_t h = fh;
        do {
            const Index v = Index(t.to(h));
            soup.corners.push_back(vmap.empty() ? v : vmap[v]);
            if (uv) soup.corner_texcoords.push_back(texcoord_at(c.halfedge_texcoords, h));
            h = t.next(h);
        } while (h != fh);
        std::rotate(soup.corners.begin() + std::ptrdiff_t(begin), soup.corners.end() - 1,
                    soup.corners.end());
        if (uv)
            std::rotate(soup.corner_texcoords.begin() + std::ptrdiff_t(begin),
                        soup.corner_texcoords.end() - 1, soup.corner_texcoords.end());
        soup.face_offsets.push_back(soup.corners.size());
    }
    if (c.sharpness) {  // by their end vertices: build_mesh finds the edges again
        for (std::size_t e = 0; e < t.n_h / 2; ++e) {
            const float s = load_le<float>(c.sharpness.p + 4 * e);
            if (!(s > 0.0f) || !t.halfedge_live(2 * e)) continue;
            const Index a0 = Index(t.to(2 * e + 1)), b0 = Index(t.to(2 * e));
            const Index a1 = vmap.empty() ? a0 : vmap[a0], b1 = vmap.empty() ? b0 : vmap[b0];
            if (a1 != kInvalidIndex && b1 != kInvalidIndex && a1 != b1)
                soup.sharp_edges.push_back({a1, b1, s});
        }
    }
}

void assemble_2x(const OmContents& c, Assembly& a) {
    check_positions_present(c);
    Topology2 t(c);
    validate_2x(t);
    if (!adopt_2x(t, a)) soup_faces_2x(t, a);
}

// ---- writer helpers ----------------------------------------------------------------------

template <class S>
void put_index(unsigned char*& p, Index i) {
    store_le<S>(p, i == kInvalidIndex ? S(-1) : S(i));
}

/// Calls f with a value of the signed integer type of `width` bytes (1, 2 or 4).
template <class F>
void with_index_type(std::size_t width, F&& f) {
    if (width == 1)
        f(std::int8_t());
    else if (width == 2)
        f(std::int16_t());
    else
        f(std::int32_t());
}

std::uint8_t to_u8(float c) {
    if (!(c > 0.0f)) return 0;
    if (c >= 1.0f) return 255;
    return std::uint8_t(std::lround(c * 255.0f));
}

}  // namespace

LoadedMesh read_om(const std::string& path) {
    return read_om_bytes(read_file_bytes(path), path);
}

LoadedMesh read_om_bytes(const std::string& bytes, const std::string& path) {
    Cursor in(path, reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size());
    OmContents c;
    parse(in, path, c);

    Assembly a;
    try {
        if (c.v2)
            assemble_2x(c, a);
        else
            assemble_1x(c, a);
    } catch (const IoError&) {
        throw;
    } catch (const Error& e) {
        throw IoError(path, 0, std::string("invalid .om data: ") + e.what());
    }

    LoadedMesh out;
    LoadReport& report = out.report;
    report.file = path;
    report.format = "om";
    report.file_vertices = c.n_v;
    report.file_faces = c.n_f;
    if (a.adopted) {
        check_finite_mesh(a.mesh, path);  // what build_mesh_for_file checks for a soup
        out.mesh = std::move(a.mesh);
        report.isolated_vertices = a.isolated;
    } else {
        out.mesh = build_mesh_for_file(a.soup, report, path);
    }

    auto note = [&](std::size_t n, const char* one, const char* many) {
        if (n) report.notes.push_back(count_text(n, one, many) + " dropped");
    };
    note(a.deleted_faces, "deleted face", "deleted faces");
    note(a.deleted_vertices, "deleted vertex", "deleted vertices");
    note(a.faceless_edges, "edge without faces", "edges without faces");
    if (!c.custom_names.empty()) {
        std::string names;
        for (std::size_t i = 0; i < c.custom_names.size() && i < 5; ++i)
            names += (i ? ", '" : "'") + c.custom_names[i] + "'";
        if (c.custom_names.size() > 5) names += ", ...";
        report.notes.push_back(
            count_text(c.custom_names.size(), "custom property", "custom properties") +
            " skipped (" + names + ")");
    }
    if (c.face_normals) report.notes.push_back("face normals ignored");
    if (c.face_colors) report.notes.push_back("face colors ignored");
    if (c.ignored_1x_halfedge_texcoords)
        report.notes.push_back("halfedge texcoords ignored (1.x halfedge order is unreliable)");
    if (c.custom_on_faces_or_halfedges && report.polygons_triangulated > 0)
        report.notes.push_back("triangulated polygons invalidate face/halfedge custom properties");
    return out;
}

namespace {

// write_om_to() in stages: the plan (sizes, index width, which attributes, the checks), then
// the chunks into one buffer of the planned size: the vertex attributes, the connectivity.

/// What write_om_to() writes: element counts, the index width, the attributes written, the
/// file size.
struct OmWritePlan {
    std::uint64_t n_v = 0, n_e = 0, n_f = 0, n_h = 0;
    unsigned bits = 0;      ///< index width code: 0, 1, 2 for 1, 2, 4 bytes
    std::size_t width = 1;  ///< index width in bytes
    VertexProperty<const Vector3> normals;
    VertexProperty<const Color> colors;
    VertexProperty<const TexCoord> texcoords;
    HalfedgeProperty<const TexCoord> corner_uv;
    VertexProperty<const float> selection;      ///< "v:selection", a custom chunk
    EdgeProperty<const float> sharpness;        ///< "e:sharpness", a custom chunk
    VertexProperty<const std::uint8_t> corner;  ///< "v:corner", a custom chunk
    bool write_corner_uv = false;
    std::uint64_t total = 0;  ///< bytes
};

/// The plan for `mesh` (no garbage); throws IoError for a mesh .om cannot hold.
OmWritePlan plan_om_write(const HalfedgeMesh& mesh, const std::string& path,
                          const WriteOptions& options) {
    OmWritePlan w;
    w.n_v = mesh.vertices_size();
    w.n_e = mesh.edges_size();
    w.n_f = mesh.faces_size();
    w.n_h = 2 * w.n_e;
    const std::uint64_t n_v = w.n_v, n_f = w.n_f, n_h = w.n_h;
    constexpr std::uint64_t kMaxIndex = std::uint64_t(std::numeric_limits<std::int32_t>::max());
    if (n_v > kMaxIndex || n_f > kMaxIndex || n_h > kMaxIndex + 1)
        throw IoError(path, 0, "the mesh is too large for .om's 32-bit indices");
    // Smallest width W in {1, 2, 4} whose signed range holds every index (om-format.md §6.1).
    const std::uint64_t max_index =
        std::max({n_h ? n_h - 1 : 0, n_v ? n_v - 1 : 0, n_f ? n_f - 1 : 0});
    w.bits = max_index <= 127 ? 0 : max_index <= 32767 ? 1 : 2;
    w.width = std::size_t(1) << w.bits;

    w.normals = options.write_normals ? mesh.get_vertex_property<Vector3>("v:normal")
                                      : VertexProperty<const Vector3>();
    w.colors = options.write_colors ? mesh.get_vertex_property<Color>("v:color")
                                    : VertexProperty<const Color>();
    w.texcoords = options.write_texcoords ? mesh.get_vertex_property<TexCoord>("v:texcoord")
                                          : VertexProperty<const TexCoord>();
    w.corner_uv = options.write_texcoords ? mesh.get_halfedge_property<TexCoord>("h:texcoord")
                                          : HalfedgeProperty<const TexCoord>();
    w.write_corner_uv = w.corner_uv && w.n_e > 0;
    w.selection = mesh.get_vertex_property<float>("v:selection");
    if (w.selection)
        for (std::size_t v = 0; v < n_v; ++v)
            if (!(w.selection.vector()[v] >= 0.0f && w.selection.vector()[v] <= 1.0f))
                throw IoError(path, 0,
                              "vertex " + std::to_string(v) +
                                  ": selection weight not in [0, 1] (not written)");
    check_finite_for_writing(mesh, path, bool(w.normals), bool(w.colors),
                             bool(w.texcoords) || w.write_corner_uv);
    // Texture coordinates are float32 in .om (the format has no other width): values beyond
    // its range are refused (tiny ones only lose precision that texture lookups never see).
    constexpr double kFloatMax = double(std::numeric_limits<float>::max());
    if ((w.texcoords && max_abs_component(w.texcoords.vector()) > kFloatMax) ||
        (w.write_corner_uv && max_abs_component(w.corner_uv.vector()) > kFloatMax))
        throw IoError(path, 0,
                      ".om stores texture coordinates as float32, which cannot hold these "
                      "(beyond 3.4e38); not written: use OBJ, OFF or PLY");

    w.total = 16 + (2 + 24 * n_v) + 2;  // header, positions, sentinel
    if (w.normals) w.total += 2 + 24 * n_v;
    if (w.colors) w.total += 2 + 3 * n_v;
    if (w.texcoords) w.total += 2 + 8 * n_v;
    if (w.n_e > 0) w.total += 2 + 3 * w.width * n_h;
    if (w.write_corner_uv) w.total += 2 + 8 * n_h;
    if (n_v > 0) w.total += 2 + w.width * n_v;
    w.total += 2 + w.width * n_f;
    if (w.selection) w.total += kOmSelectionChunkHead + 4 * n_v;
    if (has_features(mesh)) {
        w.sharpness = mesh.get_edge_property<float>(kSharpnessProperty);
        w.corner = mesh.get_vertex_property<std::uint8_t>(kCornerProperty);
    }
    if (w.corner) w.total += kOmCornerChunkHead + n_v;
    if (w.sharpness) w.total += kOmSharpnessChunkHead + 4 * w.n_e;
    return w;
}

void put_vec3d(unsigned char*& p, const Vector3& v) {
    store_le<double>(p, v.x());
    store_le<double>(p, v.y());
    store_le<double>(p, v.z());
}

void put_uv(unsigned char*& p, const TexCoord& x) {
    store_le<float>(p, float(x.x()));
    store_le<float>(p, float(x.y()));
}

/// The header, the positions and the planned vertex attributes.
void put_om_vertices(unsigned char*& p, const HalfedgeMesh& mesh, const OmWritePlan& w) {
    const unsigned char magic[4] = {'O', 'M', 'T', 0x42};  // triangle mesh, version 2.2
    std::memcpy(p, magic, 4);
    p += 4;
    store_le<std::uint32_t>(p, std::uint32_t(w.n_v));
    store_le<std::uint32_t>(p, std::uint32_t(w.n_f));
    store_le<std::uint32_t>(p, std::uint32_t(w.n_e));
    store_le<std::uint16_t>(p, encode_header(kVertex, kPosition, true, true, 3, 1));  // 0x5600
    for (const Point& x : mesh.positions()) put_vec3d(p, x);
    if (w.normals) {
        store_le<std::uint16_t>(p, encode_header(kVertex, kNormal, true, true, 3, 1));  // 0x5620
        for (const Vector3& x : w.normals.vector()) put_vec3d(p, x);
    }
    if (w.colors) {
        store_le<std::uint16_t>(p, encode_header(kVertex, kColor, false, false, 3, 0));  // 0x1080
        for (const Color& x : w.colors.vector()) {
            *p++ = to_u8(x.x());
            *p++ = to_u8(x.y());
            *p++ = to_u8(x.z());
        }
    }
    if (w.texcoords) {
        store_le<std::uint16_t>(p, encode_header(kVertex, kTexcoord, true, true, 2, 0));  // 0x0E40
        for (const TexCoord& x : w.texcoords.vector()) put_uv(p, x);
    }
}

/// A custom chunk's property name and type name (u8 length + bytes each).
void put_names(unsigned char*& p, const std::string& name, const std::string& type) {
    for (const std::string* text : {&name, &type}) {
        *p++ = static_cast<unsigned char>(text->size());
        std::memcpy(p, text->data(), text->size());
        p += text->size();
    }
}

/// The connectivity chunks (halfedges with their corner texture coordinates, vertices,
/// faces) and the sentinel.
void put_om_connectivity(unsigned char*& p, const HalfedgeMesh& mesh, const OmWritePlan& w) {
    const std::uint64_t n_v = w.n_v, n_f = w.n_f, n_h = w.n_h;
    const unsigned bits = w.bits;
    // Topology chunks carry float = 1, as OpenMesh writes them (om-format.md §3).
    if (w.n_e > 0) {
        store_le<std::uint16_t>(p, encode_header(kHalf, kTopology, true, true, 3, bits));
        with_index_type(w.width, [&](auto s) {
            for (std::size_t h = 0; h < n_h; ++h) {
                const Halfedge he(static_cast<Index>(h));
                put_index<decltype(s)>(p, mesh.next(he).idx());
                put_index<decltype(s)>(p, mesh.to_vertex(he).idx());
                put_index<decltype(s)>(p, mesh.face(he).idx());
            }
        });
    }
    if (w.write_corner_uv) {
        store_le<std::uint16_t>(p, encode_header(kHalf, kTexcoord, true, true, 2, 0));  // 0x0E58
        for (const TexCoord& x : w.corner_uv.vector()) put_uv(p, x);
    }
    if (n_v > 0) {
        store_le<std::uint16_t>(p, encode_header(kVertex, kTopology, true, true, 1, bits));
        with_index_type(w.width, [&](auto s) {
            for (std::size_t v = 0; v < n_v; ++v)
                put_index<decltype(s)>(p, mesh.halfedge(Vertex(Index(v))).idx());
        });
    }
    store_le<std::uint16_t>(p, encode_header(kFace, kTopology, true, true, 1, bits));
    with_index_type(w.width, [&](auto s) {
        for (std::size_t f = 0; f < n_f; ++f)
            put_index<decltype(s)>(p, mesh.halfedge(Face(Index(f))).idx());
    });
    if (w.selection) {
        // A custom vertex chunk (§6.4) as OpenMesh writes a float property: header 0x00C2 (the
        // name bit set; the size field is 4 mod 4 = 0), name, type name, byte count, data.
        store_le<std::uint16_t>(
            p, std::uint16_t(encode_header(kVertex, kCustom, false, false, 1, 0) | 2u));
        for (const std::string& text : {std::string(kOmSelectionName), std::string("float")}) {
            *p++ = static_cast<unsigned char>(text.size());
            std::memcpy(p, text.data(), text.size());
            p += text.size();
        }
        store_le<std::uint32_t>(p, std::uint32_t(4 * n_v));
        for (const float x : w.selection.vector()) store_le<float>(p, x);
    }
    if (w.corner) {  // custom vertex chunk of uint8_t (size code 0 = 1 byte)
        store_le<std::uint16_t>(
            p, std::uint16_t(encode_header(kVertex, kCustom, false, false, 1, 0) | 2u));
        put_names(p, kOmCornerName, "uint8_t");
        store_le<std::uint32_t>(p, std::uint32_t(n_v));
        for (const std::uint8_t x : w.corner.vector()) *p++ = x;
    }
    if (w.sharpness) {  // custom edge chunk of float (header 0x00D2), after the vertex ones
        store_le<std::uint16_t>(
            p, std::uint16_t(encode_header(kEdge, kCustom, false, false, 1, 0) | 2u));
        put_names(p, kOmSharpnessName, "float");
        store_le<std::uint32_t>(p, std::uint32_t(4 * w.n_e));
        for (const float x : w.sharpness.vector()) store_le<float>(p, x);
    }
    store_le<std::uint16_t>(p, encode_header(kSentinel, 0, false, false, 1, 0));  // 0x001C
}

}  // namespace

void write_om_to(const HalfedgeMesh& input, std::ostream& os, const std::string& path,
                 const WriteOptions& options) {
    HalfedgeMesh compacted;
    const HalfedgeMesh* source = &input;
    if (input.has_garbage()) {
        compacted = input;
        compacted.garbage_collection();
        source = &compacted;
    }
    const HalfedgeMesh& mesh = *source;
    const OmWritePlan plan = plan_om_write(mesh, path, options);
    std::vector<unsigned char> buffer(static_cast<std::size_t>(plan.total));
    unsigned char* p = buffer.data();
    put_om_vertices(p, mesh, plan);
    put_om_connectivity(p, mesh, plan);
    if (std::uint64_t(p - buffer.data()) != plan.total)
        throw IoError(path, 0, "internal error: .om size mismatch");
    os.write(reinterpret_cast<const char*>(buffer.data()), std::streamsize(buffer.size()));
}

void write_om(const HalfedgeMesh& mesh, const std::string& path, const WriteOptions& options) {
    write_file_atomically(path, [&](std::ostream& os) { write_om_to(mesh, os, path, options); });
}

}  // namespace trilab
