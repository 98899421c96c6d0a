// Stanford PLY reader and writer.
//
// Reading: the header (comments and obj_info allowed) is tokenized with TextScanner; the body
// may be ascii, binary_little_endian or binary_big_endian, with elements in any order. The
// elements "vertex" (x, y, z; nx, ny, nz; red, green, blue; u/v, s/t, texture_u/texture_v or
// texture_s/texture_t; distance: the per-vertex scalar "v:distance"; selection: the weight
// "v:selection"; corner: the tag "v:corner"), "edge" (vertex1, vertex2 and crease: the
// sharpness "e:sharpness", 10 or more read as infinity; an edge element without a crease is
// skipped), "face" (a vertex_indices or vertex_index list, polygons allowed, and an
// optional per-face "texcoord" list of two floats per corner) and "tristrips" (a vertex_indices
// list where -1 restarts the strip) are used; every other element and property is skipped, list
// properties included. All PLY scalar types are accepted under both spellings. Binary rows of fixed
// size are decoded with memcpy at precomputed offsets (with a dedicated loop for float x, y, z and
// for uchar/int triangle lists); every declared count is checked against the bytes left before
// anything is reserved, and every read is bounds-checked. Errors name the file and the line (ascii)
// or the element number (binary). A UTF-8 byte-order mark before "ply" is skipped, UTF-16 refused.
// ASCII values must fit their declared type (uchar 0..255, whole numbers for integer types, float
// within float's range; a float value is rounded to float, as a binary file stores it); float-typed
// list lengths and indices must be whole numbers. NaN and infinity in any used property are refused
// (build_mesh_for_file checks the soup, naming the vertex and the attribute).
//
// Writing: binary little-endian by default, ascii or big-endian on request. Positions,
// normals and texture coordinates are float32 (a round trip is exact to float precision,
// ~6e-8 relative), or double for a group whose values float32 cannot hold with full
// precision (float_range_suffices); colours uchar; a "v:distance" scalar as double
// `distance`; a "v:selection" weight as float `selection`; a "v:corner" tag as uchar `corner`;
// faces are "property list uchar int vertex_indices"; sharp edges (sharpness > 0) as an
// element `edge` (int vertex1, int vertex2, float crease; infinity written as 10, OpenSubdiv's
// infinite sharpness). Non-finite values are refused.
#include <algorithm>
#include <atomic>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <exception>
#include <limits>
#include <ostream>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "core/errors.h"
#include "core/features.h"
#include "core/io/byte_io.h"
#include "core/io/file_util.h"
#include "core/io/mesh_io.h"
#include "core/io/text_scanner.h"
#include "core/prefault.h"
#include "core/two_threads.h"

namespace trilab {
namespace {

// ---- scalar types ---------------------------------------------------------------------------

enum class ScalarType : std::uint8_t {
    kInt8,
    kUint8,
    kInt16,
    kUint16,
    kInt32,
    kUint32,
    kF32,
    kF64
};

std::size_t type_size(ScalarType t) {
    switch (t) {
        case ScalarType::kInt8:
        case ScalarType::kUint8:
            return 1;
        case ScalarType::kInt16:
        case ScalarType::kUint16:
            return 2;
        case ScalarType::kInt32:
        case ScalarType::kUint32:
        case ScalarType::kF32:
            return 4;
        case ScalarType::kF64:
            return 8;
    }
    return 1;
}

bool is_float_type(ScalarType t) {
    return t == ScalarType::kF32 || t == ScalarType::kF64;
}

bool parse_type(std::string_view s, ScalarType& t) {
    struct Name {
        const char* name;
        ScalarType type;
    };
    static const Name names[] = {
        {"char", ScalarType::kInt8},     {"int8", ScalarType::kInt8},
        {"uchar", ScalarType::kUint8},   {"uint8", ScalarType::kUint8},
        {"short", ScalarType::kInt16},   {"int16", ScalarType::kInt16},
        {"ushort", ScalarType::kUint16}, {"uint16", ScalarType::kUint16},
        {"int", ScalarType::kInt32},     {"int32", ScalarType::kInt32},
        {"uint", ScalarType::kUint32},   {"uint32", ScalarType::kUint32},
        {"float", ScalarType::kF32},     {"float32", ScalarType::kF32},
        {"double", ScalarType::kF64},    {"float64", ScalarType::kF64},
    };
    for (const Name& n : names)
        if (s == n.name) {
            t = n.type;
            return true;
        }
    return false;
}

template <bool Swap>
double load_double(const unsigned char* p, ScalarType t) {
    switch (t) {
        case ScalarType::kInt8:
            return load_bytes<std::int8_t, Swap>(p);
        case ScalarType::kUint8:
            return load_bytes<std::uint8_t, Swap>(p);
        case ScalarType::kInt16:
            return load_bytes<std::int16_t, Swap>(p);
        case ScalarType::kUint16:
            return load_bytes<std::uint16_t, Swap>(p);
        case ScalarType::kInt32:
            return load_bytes<std::int32_t, Swap>(p);
        case ScalarType::kUint32:
            return load_bytes<std::uint32_t, Swap>(p);
        case ScalarType::kF32:
            return load_bytes<float, Swap>(p);
        case ScalarType::kF64:
            return load_bytes<double, Swap>(p);
    }
    return 0;
}

/// An integer stored in any type; false for a float value that is not a whole number in
/// the range of long long (2.5, NaN, 1e300).
template <bool Swap>
bool load_integer(const unsigned char* p, ScalarType t, long long& out) {
    switch (t) {
        case ScalarType::kInt8:
            out = load_bytes<std::int8_t, Swap>(p);
            return true;
        case ScalarType::kUint8:
            out = load_bytes<std::uint8_t, Swap>(p);
            return true;
        case ScalarType::kInt16:
            out = load_bytes<std::int16_t, Swap>(p);
            return true;
        case ScalarType::kUint16:
            out = load_bytes<std::uint16_t, Swap>(p);
            return true;
        case ScalarType::kInt32:
            out = load_bytes<std::int32_t, Swap>(p);
            return true;
        case ScalarType::kUint32:
            out = load_bytes<std::uint32_t, Swap>(p);
            return true;
        case ScalarType::kF32:
        case ScalarType::kF64: {
            const double d = load_double<Swap>(p, t);
            if (!(d > -9e18 && d < 9e18) || d != std::floor(d)) return false;
            out = static_cast<long long>(d);
            return true;
        }
    }
    return false;
}

/// A number for messages: the shortest text that reads back as it ("2.5", "1e+39", "nan").
std::string number_text(double d) {
    std::string out;
    append_number(out, d);
    return out;
}

// ---- header -----------------------------------------------------------------------------

/// What a property is used for.
enum Role : std::uint8_t {
    kNone,
    kX,
    kY,
    kZ,
    kNx,
    kNy,
    kNz,
    kRed,
    kGreen,
    kBlue,
    kU,
    kV,
    kDistance,   // the per-vertex scalar "v:distance"
    kSelection,  // the per-vertex selection weight "v:selection"
    kCorner,     // the per-vertex corner tag "v:corner"
    kEdgeV1,     // edge element: first vertex
    kEdgeV2,     // edge element: second vertex
    kCrease,     // edge element: the sharpness "e:sharpness"
    kIndices,    // face / tristrips vertex index list
    kTexcoord,   // per-face corner texture coordinate list
    kRoleCount
};

struct PlyProperty {
    std::string name;
    std::string label;  ///< "property 'x'", or "an item of list 'name'", for messages
    ScalarType type = ScalarType::kF32;  ///< the scalar type, or the item type of a list
    ScalarType count_type = ScalarType::kUint8;
    bool is_list = false;
    Role role = kNone;
};

enum class ElementKind { kOther, kVertex, kFace, kTristrips, kEdge };

struct PlyElement {
    std::string name;
    std::uint64_t count = 0;
    std::size_t line = 0;  ///< header line of the element statement
    ElementKind kind = ElementKind::kOther;
    std::vector<PlyProperty> props;

    bool has_lists() const {
        for (const PlyProperty& p : props)
            if (p.is_list) return true;
        return false;
    }
    /// Bytes of a binary row without lists; the minimum bytes of a row with lists.
    std::size_t min_row_bytes() const {
        std::size_t n = 0;
        for (const PlyProperty& p : props) n += type_size(p.is_list ? p.count_type : p.type);
        return n;
    }
    bool has_role(Role r) const {
        for (const PlyProperty& p : props)
            if (p.role == r) return true;
        return false;
    }
};

enum class Encoding { kAscii, kBinaryLittle, kBinaryBig };

const char* element_label(const PlyElement& e) {
    switch (e.kind) {
        case ElementKind::kVertex:
            return "vertex";
        case ElementKind::kFace:
            return "face";
        case ElementKind::kEdge:
            return "edge";
        case ElementKind::kTristrips:
            return "tristrips";
        case ElementKind::kOther:
            break;
    }
    return "entry";
}

// ---- reader -----------------------------------------------------------------------------

class PlyReader {
public:
    PlyReader(const std::string& path, std::string_view data)
        : path_(path), data_(data), sc_(data, path, '\0') {}

    /// Parses the file into `out.report` and returns its soup; the mesh is not built yet
    /// (read_ply releases the file's bytes first).
    PolygonSoup read(LoadedMesh& out) {
        parse_header();
        assign_roles();
        if (encoding_ == Encoding::kAscii) {
            read_ascii();
        } else {
            const bool file_little = encoding_ == Encoding::kBinaryLittle;
            if (file_little == host_is_little_endian())
                read_binary<false>();
            else
                read_binary<true>();
        }
        finish_soup();
        out.report.file = path_;
        out.report.format = "ply";
        out.report.file_vertices = soup_.positions.size();
        out.report.file_faces = file_faces_;
        out.report.notes = notes_;
        return std::move(soup_);
    }

private:
    // ---- header ---------------------------------------------------------------------------
    void parse_header() {
        if (data_.compare(0, 3, "ply") != 0 ||
            (data_.size() > 3 && data_[3] != '\n' && data_[3] != '\r' && data_[3] != ' ' &&
             data_[3] != '\t'))
            throw IoError(path_, 1, "not a PLY file (it must start with a 'ply' line)");
        sc_.next_token();
        bool have_format = false;
        for (;;) {
            const std::size_t last_line = sc_.line();
            const std::string_view kw = sc_.next_token();
            if (kw.empty()) throw IoError(path_, last_line, "the header has no end_header line");
            if (kw == "comment" || kw == "obj_info") {
                sc_.rest_of_line();
            } else if (kw == "format") {
                const std::string_view enc = sc_.expect_token("the format's encoding");
                if (enc == "ascii")
                    encoding_ = Encoding::kAscii;
                else if (enc == "binary_little_endian")
                    encoding_ = Encoding::kBinaryLittle;
                else if (enc == "binary_big_endian")
                    encoding_ = Encoding::kBinaryBig;
                else
                    sc_.fail("unknown PLY encoding '" + printable(enc) +
                             "' (expected ascii, binary_little_endian or binary_big_endian)");
                const std::string_view version = sc_.expect_token("the format's version");
                if (version != "1.0" && version != "1")
                    sc_.fail("unsupported PLY version '" + printable(version) + "'");
                have_format = true;
            } else if (kw == "element") {
                PlyElement e;
                e.name = std::string(sc_.expect_token("an element name"));
                e.line = sc_.line();
                const long long count = sc_.next_integer("the element count");
                if (count < 0) sc_.fail("negative element count for '" + printable(e.name) + "'");
                e.count = static_cast<std::uint64_t>(count);
                elements_.push_back(std::move(e));
            } else if (kw == "property") {
                if (elements_.empty()) sc_.fail("'property' before any 'element'");
                PlyProperty p;
                std::string_view t = sc_.expect_token("a property type");
                if (t == "list") {
                    p.is_list = true;
                    t = sc_.expect_token("the list's count type");
                    if (!parse_type(t, p.count_type))
                        sc_.fail("unknown property type '" + printable(t) + "'");
                    t = sc_.expect_token("the list's item type");
                }
                if (!parse_type(t, p.type))
                    sc_.fail("unknown property type '" + printable(t) + "'");
                p.name = std::string(sc_.expect_token("a property name"));
                p.label = (p.is_list ? "an item of list '" : "property '") + p.name + "'";
                elements_.back().props.push_back(std::move(p));
            } else if (kw == "end_header") {
                sc_.rest_of_line();
                break;
            } else {
                sc_.fail("unexpected '" + printable(kw) + "' in the PLY header");
            }
        }
        if (!have_format) sc_.fail("the header has no 'format' line");
        data_offset_ = sc_.offset();
    }

    /// Sets element kinds and property roles; checks what the known elements need.
    void assign_roles() {
        bool seen_vertex = false;
        for (PlyElement& e : elements_) {
            if (e.name == "vertex") {
                if (seen_vertex)
                    throw IoError(path_, e.line, "a second 'vertex' element (only one allowed)");
                seen_vertex = true;
                e.kind = ElementKind::kVertex;
                n_vertices_declared_ = e.count;
                for (PlyProperty& p : e.props) {
                    if (p.is_list) continue;
                    const std::string& n = p.name;
                    Role r = kNone;
                    if (n == "x")
                        r = kX;
                    else if (n == "y")
                        r = kY;
                    else if (n == "z")
                        r = kZ;
                    else if (n == "nx")
                        r = kNx;
                    else if (n == "ny")
                        r = kNy;
                    else if (n == "nz")
                        r = kNz;
                    else if (n == "red")
                        r = kRed;
                    else if (n == "green")
                        r = kGreen;
                    else if (n == "blue")
                        r = kBlue;
                    else if (n == "u" || n == "s" || n == "texture_u" || n == "texture_s")
                        r = kU;
                    else if (n == "v" || n == "t" || n == "texture_v" || n == "texture_t")
                        r = kV;
                    else if (n == "distance")
                        r = kDistance;
                    else if (n == "selection")
                        r = kSelection;
                    else if (n == "corner")
                        r = kCorner;
                    if (r != kNone && !e.has_role(r)) p.role = r;
                    if (r == kRed || r == kGreen || r == kBlue) color_type_ = p.type;
                }
                if (!e.has_role(kX) || !e.has_role(kY) || !e.has_role(kZ))
                    throw IoError(path_, e.line, "element 'vertex' lacks an x, y or z property");
                has_normals_ = e.has_role(kNx) && e.has_role(kNy) && e.has_role(kNz);
                has_colors_ = e.has_role(kRed) && e.has_role(kGreen) && e.has_role(kBlue);
                has_uv_ = e.has_role(kU) && e.has_role(kV);
                has_distance_ = e.has_role(kDistance);
                has_selection_ = e.has_role(kSelection);
                has_corner_ = e.has_role(kCorner);
            } else if (e.name == "face" || e.name == "tristrips") {
                e.kind = e.name == "face" ? ElementKind::kFace : ElementKind::kTristrips;
                for (PlyProperty& p : e.props) {
                    if (!p.is_list) continue;
                    if ((p.name == "vertex_indices" || p.name == "vertex_index") &&
                        !e.has_role(kIndices))
                        p.role = kIndices;
                    else if (e.kind == ElementKind::kFace && p.name == "texcoord" &&
                             !e.has_role(kTexcoord))
                        p.role = kTexcoord;
                }
                if (!e.has_role(kIndices) && e.count > 0)
                    throw IoError(path_, e.line,
                                  "element '" + e.name + "' lacks a vertex_indices list property");
            } else if (e.name == "edge" && assign_edge_roles(e)) {
                e.kind = ElementKind::kEdge;
            } else if (e.count > 0) {
                notes_.push_back("skipped PLY element '" + e.name + "' (" +
                                 std::to_string(e.count) + " entries)");
            }
        }
    }

    /// Roles of an `edge` element's vertex1, vertex2 and crease; false (roles unset) when it
    /// lacks one of them (a wireframe without creases: skipped as any other element).
    static bool assign_edge_roles(PlyElement& e) {
        for (PlyProperty& p : e.props) {
            if (p.is_list) continue;
            const Role r = p.name == "vertex1"   ? kEdgeV1
                           : p.name == "vertex2" ? kEdgeV2
                           : p.name == "crease"  ? kCrease
                                                 : kNone;
            if (r != kNone && !e.has_role(r)) p.role = r;
        }
        if (e.has_role(kEdgeV1) && e.has_role(kEdgeV2) && e.has_role(kCrease)) return true;
        for (PlyProperty& p : e.props) p.role = kNone;
        return false;
    }

    /// One row of the `edge` element: a sharp edge of the soup (checked: whole indices in
    /// range, two different vertices, a crease >= 0; 10 or more reads as infinity, see the
    /// writer). A crease of 0 adds nothing.
    void store_edge(std::uint64_t row, const double* v, std::size_t line) {
        const std::string where = "edge " + std::to_string(row);
        long long ends[2];
        for (int k = 0; k < 2; ++k) {
            const double x = v[k == 0 ? kEdgeV1 : kEdgeV2];
            if (x != std::floor(x) || !(x >= 0) || x >= double(n_vertices_declared_))
                throw IoError(path_, line,
                              where + ": vertex index " + number_text(x) +
                                  " is not a vertex (the file declares " +
                                  std::to_string(n_vertices_declared_) + " vertices)");
            ends[k] = static_cast<long long>(x);
        }
        if (ends[0] == ends[1])
            throw IoError(path_, line,
                          where + ": joins vertex " + std::to_string(ends[0]) + " to itself");
        const double c = v[kCrease];
        if (!(c >= 0))
            throw IoError(path_, line,
                          where + ": crease " + number_text(c) + " is not >= 0 (a sharpness)");
        if (c == 0) return;
        const float s = c >= double(kSharpnessActsInfinite) ? kInfiniteSharpness : float(c);
        soup_.sharp_edges.push_back({Index(ends[0]), Index(ends[1]), s});
    }

    // ---- shared row handling ---------------------------------------------------------------
    void begin_vertices(const PlyElement& e) {
        const std::size_t n = static_cast<std::size_t>(e.count);
        soup_.positions.resize(n);
        if (has_normals_) soup_.normals.resize(n);
        if (has_colors_) soup_.colors.resize(n);
        if (has_uv_) soup_.texcoords.resize(n);
        if (has_distance_) soup_.distances.resize(n);
        if (has_selection_) soup_.selections.resize(n);
        if (has_corner_) soup_.corner_tags.resize(n);
    }

    float color_channel(double c) const {
        double scale = 1.0;
        if (!is_float_type(color_type_))
            scale = (color_type_ == ScalarType::kUint16 || color_type_ == ScalarType::kInt16)
                        ? 1.0 / 65535.0
                        : 1.0 / 255.0;
        return static_cast<float>(std::clamp(c * scale, 0.0, 1.0));
    }

    void store_vertex(std::size_t i, const double* v) {
        soup_.positions[i] = Point(v[kX], v[kY], v[kZ]);
        if (has_normals_) soup_.normals[i] = Vector3(v[kNx], v[kNy], v[kNz]);
        if (has_colors_)
            soup_.colors[i] =
                Color(color_channel(v[kRed]), color_channel(v[kGreen]), color_channel(v[kBlue]));
        if (has_uv_) soup_.texcoords[i] = TexCoord(v[kU], v[kV]);
        if (has_distance_) soup_.distances[i] = v[kDistance];
        if (has_selection_) soup_.selections[i] = float(v[kSelection]);
        if (has_corner_) soup_.corner_tags[i] = v[kCorner] != 0 ? 1 : 0;
    }

    /// Checks one index of face / strip `row` of element e (-1 allowed in strips).
    /// Returns false for a strip restart.
    bool check_index(long long v, const PlyElement& e, std::uint64_t row, std::size_t line) {
        if (v >= 0 && static_cast<std::uint64_t>(v) < n_vertices_declared_) return true;
        if (v == -1 && e.kind == ElementKind::kTristrips) return false;
        index_error(v, e, row, line);
    }

    [[noreturn]] void index_error(long long v, const PlyElement& e, std::uint64_t row,
                                  std::size_t line) const {
        const std::string where = std::string(element_label(e)) + " " + std::to_string(row);
        if (v < 0)
            throw IoError(path_, line, where + ": negative vertex index " + std::to_string(v));
        throw IoError(path_, line,
                      where + ": vertex index " + std::to_string(v) +
                          " is out of range (the file declares " +
                          std::to_string(n_vertices_declared_) + " vertices)");
    }

    /// Ends a face row whose indices were appended to soup_.corners; row_uv_ holds the row's
    /// texcoord list (if the element has one).
    void end_face_row(bool has_texcoord_list) {
        const std::size_t n = soup_.corners.size() - soup_.face_offsets.back();
        soup_.face_offsets.push_back(soup_.corners.size());
        ++file_faces_;
        if (has_texcoord_list) {
            if (row_uv_.size() == 2 * n) {
                for (std::size_t k = 0; k < n; ++k)
                    soup_.corner_texcoords.emplace_back(row_uv_[2 * k], row_uv_[2 * k + 1]);
            } else {
                corner_uv_ok_ = false;
            }
        } else {
            faces_without_uv_ = true;
        }
    }

    /// Turns the strip in strip_ (with -1 restarts) into triangles.
    void end_strip_row() {
        std::size_t start = 0;
        for (std::size_t i = 0; i <= strip_.size(); ++i) {
            if (i < strip_.size() && strip_[i] >= 0) continue;
            // strip_[start, i) is one strip
            for (std::size_t k = start; k + 2 < i; ++k) {
                Index a = Index(strip_[k]), b = Index(strip_[k + 1]);
                const Index c = Index(strip_[k + 2]);
                if ((k - start) % 2 == 1) std::swap(a, b);
                if (a == b || b == c || a == c) continue;  // stitching triangle
                soup_.corners.push_back(a);
                soup_.corners.push_back(b);
                soup_.corners.push_back(c);
                soup_.face_offsets.push_back(soup_.corners.size());
                ++file_faces_;
                faces_without_uv_ = true;
            }
            start = i + 1;
        }
        strip_.clear();
    }

    void finish_soup() {
        if (soup_.corner_texcoords.empty()) return;
        if (!corner_uv_ok_ || faces_without_uv_ ||
            soup_.corner_texcoords.size() != soup_.corners.size()) {
            soup_.corner_texcoords.clear();
            notes_.push_back(
                "per-face texcoord lists ignored: not every face has two values per corner");
        }
    }

    // ---- ascii -----------------------------------------------------------------------------
    /// The next ASCII value, checked against its declared type: an integer type needs a
    /// whole number within its range (uchar 300 and int 2.5 are refused), float a value
    /// within float's range; every value is finite.
    double ascii_value(ScalarType t, const char* what) {
        const double d = sc_.next_double(what);
        struct Range {
            double lo, hi;
            const char* name;
        };
        static const Range ranges[] = {
            {-128.0, 127.0, "char"},
            {0.0, 255.0, "uchar"},
            {-32768.0, 32767.0, "short"},
            {0.0, 65535.0, "ushort"},
            {-2147483648.0, 2147483647.0, "int"},
            {0.0, 4294967295.0, "uint"},
            {-double(std::numeric_limits<float>::max()), double(std::numeric_limits<float>::max()),
             "float"},
        };
        if (t == ScalarType::kF64) return d;
        const Range& r = ranges[static_cast<int>(t)];
        auto text = [&] { return number_text(d); };
        if (t != ScalarType::kF32 && d != std::floor(d))
            sc_.fail(std::string(what) + ": " + text() + " is not a whole number, as type " +
                     r.name + " requires");
        if (d < r.lo || d > r.hi)
            sc_.fail(
                std::string(what) + ": " + text() + " is out of range for type " + r.name + " (" +
                (t == ScalarType::kF32 ? std::string("at most 3.4e38 in magnitude")
                                       : std::to_string(static_cast<long long>(r.lo)) + " to " +
                                             std::to_string(static_cast<long long>(r.hi))) +
                ")");
        // A float property holds a float: the decimal text rounded as the binary encodings
        // would store it, so that ASCII and binary files of the same values read the same.
        return t == ScalarType::kF32 ? double(static_cast<float>(d)) : d;
    }

    long long ascii_integer(ScalarType t, const char* what) {
        const double d = ascii_value(t, what);
        if (d != std::floor(d) || !(d > -9e18 && d < 9e18))
            sc_.fail(std::string(what) + ": " + number_text(d) + " is not a whole number");
        return static_cast<long long>(d);
    }

    long long ascii_list_count(const PlyElement& e, const PlyProperty& p) {
        const long long n = ascii_integer(p.count_type, "a list length");
        if (n < 0)
            sc_.fail("negative list length " + std::to_string(n) + " for property '" + p.name +
                     "' of element '" + e.name + "'");
        return n;
    }

    void read_ascii() {
        for (const PlyElement& e : elements_) {
            if (e.count == 0 || e.props.empty()) continue;
            const std::size_t remaining = data_.size() - sc_.offset();
            check_declared_count(static_cast<std::size_t>(std::min<std::uint64_t>(
                                     e.count, std::numeric_limits<std::size_t>::max())),
                                 2 * e.props.size(), remaining + 1,
                                 ("'" + e.name + "' elements").c_str(), path_, e.line);
            double vals[kRoleCount] = {};
            if (e.kind == ElementKind::kVertex) begin_vertices(e);
            if (e.kind == ElementKind::kFace) reserve_faces(e, remaining / 2, remaining / 2);
            const bool has_uv_list = e.has_role(kTexcoord);
            for (std::uint64_t row = 0; row < e.count; ++row) {
                for (const PlyProperty& p : e.props) {
                    if (!p.is_list) {
                        const double value = ascii_value(p.type, p.label.c_str());
                        if (p.role != kNone) vals[p.role] = value;
                        continue;
                    }
                    const long long n = ascii_list_count(e, p);
                    if (p.role == kIndices) {
                        for (long long k = 0; k < n; ++k) {
                            const long long v = ascii_integer(p.type, "a vertex index");
                            const bool ok = check_index(v, e, row, sc_.line());
                            if (e.kind == ElementKind::kFace)
                                soup_.corners.push_back(Index(v));
                            else
                                strip_.push_back(ok ? v : -1);
                        }
                    } else if (p.role == kTexcoord) {
                        row_uv_.clear();
                        for (long long k = 0; k < n; ++k)
                            row_uv_.push_back(ascii_value(p.type, "a texture coordinate"));
                    } else {
                        for (long long k = 0; k < n; ++k) ascii_value(p.type, p.label.c_str());
                    }
                }
                if (e.kind == ElementKind::kVertex)
                    store_vertex(static_cast<std::size_t>(row), vals);
                else if (e.kind == ElementKind::kEdge)
                    store_edge(row, vals, sc_.line());
                else if (e.kind == ElementKind::kFace)
                    end_face_row(has_uv_list);
                else if (e.kind == ElementKind::kTristrips)
                    end_strip_row();
            }
        }
    }

    void reserve_faces(const PlyElement& e, std::size_t max_faces, std::size_t max_corners) {
        const std::size_t n = static_cast<std::size_t>(e.count);
        soup_.face_offsets.reserve(soup_.face_offsets.size() + std::min(n, max_faces));
        soup_.corners.reserve(soup_.corners.size() + std::min(3 * n, max_corners));
    }

    // ---- binary ----------------------------------------------------------------------------
    [[noreturn]] void truncated(const PlyElement& e, std::uint64_t row) const {
        throw IoError(path_, 0,
                      "the file ends inside " + std::string(element_label(e)) + " " +
                          std::to_string(row) + " of element '" + e.name + "' (truncated?)");
    }

    template <bool Swap>
    void read_binary() {
        const auto* base = reinterpret_cast<const unsigned char*>(data_.data());
        std::size_t pos = data_offset_;
        // Fixed-size vertex rows of a large file are decoded on a second thread while the
        // elements after them are read here (the decoding cannot fail: the counts were
        // checked); joined before returning or throwing.
        std::thread vertex_thread;
        std::exception_ptr vertex_error;
        struct Join {
            std::thread& t;
            ~Join() {
                if (t.joinable()) t.join();
            }
        } join{vertex_thread};
        for (const PlyElement& e : elements_) {
            if (e.count == 0 || e.props.empty()) continue;
            const std::size_t remaining = data_.size() - pos;
            const std::size_t min_row = e.min_row_bytes();
            check_declared_count(static_cast<std::size_t>(std::min<std::uint64_t>(
                                     e.count, std::numeric_limits<std::size_t>::max())),
                                 min_row, remaining, ("'" + e.name + "' elements").c_str(), path_,
                                 e.line);
            const std::size_t n = static_cast<std::size_t>(e.count);
            if (!e.has_lists() && e.kind != ElementKind::kEdge) {
                // Fixed-size rows: the check above guarantees n * min_row <= remaining.
                if (e.kind == ElementKind::kVertex) {
                    begin_vertices(e);
                    const unsigned char* rows = base + pos;
                    if (n >= (std::size_t(1) << 20) && !vertex_thread.joinable())
                        vertex_thread = std::thread([this, &e, rows, &vertex_error] {
                            try {
                                read_fixed_vertices<Swap>(e, rows);
                            } catch (...) {
                                vertex_error = std::current_exception();
                            }
                        });
                    else
                        read_fixed_vertices<Swap>(e, rows);
                }
                pos += n * min_row;
            } else if (!Swap && e.kind == ElementKind::kFace && e.props.size() == 1 &&
                       e.props[0].count_type == ScalarType::kUint8 &&
                       (e.props[0].type == ScalarType::kInt32 ||
                        e.props[0].type == ScalarType::kUint32)) {
                pos = read_simple_faces(e, base, pos);
            } else {
                pos = read_rows<Swap>(e, base, pos);
            }
        }
        if (vertex_thread.joinable()) vertex_thread.join();
        if (vertex_error) std::rethrow_exception(vertex_error);
    }

    template <bool Swap>
    void read_fixed_vertices(const PlyElement& e, const unsigned char* p) {
        const std::size_t n = static_cast<std::size_t>(e.count);
        const std::size_t stride = e.min_row_bytes();
        struct Field {
            std::size_t offset;
            ScalarType type;
            Role role;
        };
        std::vector<Field> fields;
        std::size_t off = 0;
        for (const PlyProperty& prop : e.props) {
            if (prop.role != kNone) fields.push_back({off, prop.type, prop.role});
            off += type_size(prop.type);
        }
        const bool plain_xyz =
            !Swap && fields.size() == 3 && fields[0].role == kX && fields[1].role == kY &&
            fields[2].role == kZ && fields[0].type == ScalarType::kF32 &&
            fields[1].type == ScalarType::kF32 && fields[2].type == ScalarType::kF32 &&
            fields[0].offset == 0 && fields[1].offset == 4 && fields[2].offset == 8;
        if (plain_xyz) {
            Point* out = soup_.positions.data();
            for (std::size_t i = 0; i < n; ++i, p += stride) {
                float xyz[3];
                std::memcpy(xyz, p, sizeof(xyz));
                out[i] = Point(xyz[0], xyz[1], xyz[2]);
            }
            return;
        }
        double vals[kRoleCount] = {};
        for (std::size_t i = 0; i < n; ++i, p += stride) {
            for (const Field& f : fields) vals[f.role] = load_double<Swap>(p + f.offset, f.type);
            store_vertex(i, vals);
        }
    }

    /// Faces as one uchar-counted list of native-endian 32-bit indices.
    std::size_t read_simple_faces(const PlyElement& e, const unsigned char* base, std::size_t pos) {
        const std::size_t size = data_.size();
        const std::size_t n = static_cast<std::size_t>(e.count);
        reserve_faces(e, n, (size - pos) / 4);
        const bool is_signed = e.props[0].type == ScalarType::kInt32;
        const std::uint64_t nv = n_vertices_declared_;
        auto index_at = [&](std::size_t at, std::size_t row) {
            std::uint32_t u;
            std::memcpy(&u, base + at, 4);
            if (u >= nv)
                index_error(
                    is_signed ? static_cast<long long>(std::int32_t(u)) : static_cast<long long>(u),
                    e, row, 0);
            return u;
        };
        std::vector<std::size_t>& offsets = soup_.face_offsets;
        std::vector<Index>& corners = soup_.corners;
        if (read_triangle_rows(e, base, pos)) {
            file_faces_ += n;
            faces_without_uv_ = true;
            return pos + 13 * n;
        }
        // The arrays are written in place: the offsets have one entry a row, the corners
        // grow (by doubling) only for rows of more than three.
        std::size_t n_offsets = offsets.size(), n_corners = corners.size();
        offsets.resize(n_offsets + n);
        corners.resize(corners.capacity());  // as reserve_faces bounded it by the bytes left
        for (std::size_t row = 0; row < n; ++row) {
            if (pos >= size) truncated(e, row);
            const std::size_t k = base[pos++];
            if (4 * k > size - pos) truncated(e, row);
            if (n_corners + k > corners.size()) corners.resize(2 * (n_corners + k));
            Index* out = corners.data() + n_corners;
            if (k == 3) {
                out[0] = index_at(pos, row);
                out[1] = index_at(pos + 4, row);
                out[2] = index_at(pos + 8, row);
                pos += 12;
            } else {
                for (std::size_t j = 0; j < k; ++j, pos += 4) out[j] = index_at(pos, row);
            }
            n_corners += k;
            offsets[n_offsets++] = n_corners;
        }
        corners.resize(n_corners);
        file_faces_ += n;
        faces_without_uv_ = true;
        return pos;
    }

    /// read_simple_faces for a large element whose rows are all triangles (13 bytes each,
    /// every index in range), on two threads, each taking half of the rows: true when it
    /// applied, the rows then appended to the soup exactly as the row-by-row pass appends
    /// them. False, with the soup as it was, for a small element or at the first row that is
    /// not such a triangle (another corner count, an index out of range, the end of the
    /// file), so that the row-by-row pass reads the element again and reports the first
    /// problem in the file.
    bool read_triangle_rows(const PlyElement& e, const unsigned char* base, std::size_t pos) {
        const std::size_t n = static_cast<std::size_t>(e.count);
        if (!worth_two_threads(n) || detail::build_threads() < 2 || n > (data_.size() - pos) / 13)
            return false;
        std::vector<std::size_t>& offsets = soup_.face_offsets;
        std::vector<Index>& corners = soup_.corners;
        const std::size_t n_offsets = offsets.size(), n_corners = corners.size();
        // Their pages mapped on two threads, each thread sizing one array (prefault.h).
        reserve_prefaulted(n_offsets + n, true, offsets);
        reserve_prefaulted(n_corners + 3 * n, true, corners);
        on_two_threads(true, [&](int part) {
            if (part == 0)
                offsets.resize(n_offsets + n);
            else
                corners.resize(n_corners + 3 * n);
        });
        const std::uint64_t nv = n_vertices_declared_;
        std::atomic<bool> irregular{false};
        on_two_threads(true, [&](int part) {
            const std::size_t from = part == 0 ? 0 : n / 2, to = part == 0 ? n / 2 : n;
            const unsigned char* row = base + pos + 13 * from;
            Index* out = corners.data() + n_corners + 3 * from;
            std::size_t* offset = offsets.data() + n_offsets + from;
            for (std::size_t r = from; r < to; ++r, row += 13, out += 3) {
                std::uint32_t u[3];
                std::memcpy(u, row + 1, sizeof(u));
                if (row[0] != 3 || u[0] >= nv || u[1] >= nv || u[2] >= nv) {
                    irregular.store(true, std::memory_order_relaxed);
                    return;
                }
                out[0] = u[0];
                out[1] = u[1];
                out[2] = u[2];
                *offset++ = n_corners + 3 * (r + 1);
                if ((r & 0xffff) == 0 && irregular.load(std::memory_order_relaxed)) return;
            }
        });
        if (irregular.load()) {
            offsets.resize(n_offsets);
            corners.resize(n_corners);
            return false;
        }
        return true;
    }

    /// Any element, row by row, with a bounds check before every read.
    template <bool Swap>
    std::size_t read_rows(const PlyElement& e, const unsigned char* base, std::size_t pos) {
        const std::size_t size = data_.size();
        const std::size_t n = static_cast<std::size_t>(e.count);
        if (e.kind == ElementKind::kVertex) begin_vertices(e);
        if (e.kind == ElementKind::kFace) reserve_faces(e, n, (size - pos) / 4);
        const bool has_uv_list = e.has_role(kTexcoord);
        double vals[kRoleCount] = {};
        for (std::size_t row = 0; row < n; ++row) {
            for (const PlyProperty& p : e.props) {
                if (!p.is_list) {
                    const std::size_t s = type_size(p.type);
                    if (s > size - pos) truncated(e, row);
                    if (p.role != kNone) vals[p.role] = load_double<Swap>(base + pos, p.type);
                    pos += s;
                    continue;
                }
                const std::size_t cs = type_size(p.count_type);
                if (cs > size - pos) truncated(e, row);
                long long count = 0;
                if (!load_integer<Swap>(base + pos, p.count_type, count) || count < 0)
                    throw IoError(path_, 0,
                                  std::string(element_label(e)) + " " + std::to_string(row) +
                                      ": invalid list length " +
                                      number_text(load_double<Swap>(base + pos, p.count_type)) +
                                      " for property '" + p.name + "'");
                pos += cs;
                const std::size_t is = type_size(p.type);
                const std::size_t items = static_cast<std::size_t>(count);
                if (items > (size - pos) / is) truncated(e, row);
                if (p.role == kIndices) {
                    for (std::size_t k = 0; k < items; ++k, pos += is) {
                        long long v = -2;
                        if (!load_integer<Swap>(base + pos, p.type, v))
                            throw IoError(path_, 0,
                                          std::string(element_label(e)) + " " +
                                              std::to_string(row) + ": vertex index " +
                                              number_text(load_double<Swap>(base + pos, p.type)) +
                                              " is not a whole number");
                        const bool ok = check_index(v, e, row, 0);
                        if (e.kind == ElementKind::kFace)
                            soup_.corners.push_back(Index(v));
                        else
                            strip_.push_back(ok ? v : -1);
                    }
                } else if (p.role == kTexcoord) {
                    row_uv_.clear();
                    for (std::size_t k = 0; k < items; ++k, pos += is)
                        row_uv_.push_back(load_double<Swap>(base + pos, p.type));
                } else {
                    pos += items * is;
                }
            }
            if (e.kind == ElementKind::kVertex)
                store_vertex(row, vals);
            else if (e.kind == ElementKind::kEdge)
                store_edge(row, vals, 0);
            else if (e.kind == ElementKind::kFace)
                end_face_row(has_uv_list);
            else if (e.kind == ElementKind::kTristrips)
                end_strip_row();
        }
        return pos;
    }

    const std::string& path_;
    std::string_view data_;
    TextScanner sc_;
    Encoding encoding_ = Encoding::kAscii;
    std::vector<PlyElement> elements_;
    std::size_t data_offset_ = 0;
    std::uint64_t n_vertices_declared_ = 0;
    bool has_normals_ = false, has_colors_ = false, has_uv_ = false, has_distance_ = false;
    bool has_selection_ = false, has_corner_ = false;
    ScalarType color_type_ = ScalarType::kUint8;
    PolygonSoup soup_;
    std::size_t file_faces_ = 0;
    std::vector<double> row_uv_;
    std::vector<long long> strip_;
    bool corner_uv_ok_ = true;
    bool faces_without_uv_ = false;
    std::vector<std::string> notes_;
};

// ---- writer -----------------------------------------------------------------------------

std::uint8_t color_byte(float c) {
    return static_cast<std::uint8_t>(std::lround(std::clamp(c, 0.0f, 1.0f) * 255.0f));
}

}  // namespace

LoadedMesh read_ply(const std::string& path) {
    LoadedMesh out;
    PolygonSoup soup;
    {
        const FileBytes data = read_large_file(path);
        PlyReader reader(path, strip_utf8_bom(data.view(), path));
        soup = reader.read(out);
    }  // the file's bytes are released before the mesh is built (peak memory)
    out.mesh = build_mesh_for_file(std::move(soup), out.report, path);
    return out;
}

LoadedMesh read_ply_bytes(const std::string& data, const std::string& path) {
    LoadedMesh out;
    PlyReader reader(path, strip_utf8_bom(data, path));
    out.mesh = build_mesh_for_file(reader.read(out), out.report, path);
    return out;
}

namespace {

/// The face rows (triangles; with their corner texture coordinates when `corner_uv`, each
/// written by put_uv).
template <class PutUv>
void put_ply_faces(OutBuffer& out, const PolygonSoup& soup, bool ascii, bool corner_uv,
                   const PutUv& put_uv) {
    for (std::size_t f = 0; f < soup.n_faces(); ++f) {
        const std::size_t b = soup.face_offsets[f], e = soup.face_offsets[f + 1];
        const std::uint8_t n = static_cast<std::uint8_t>(e - b);  // triangles: always 3
        if (ascii) {
            out.number(int(n));
            for (std::size_t c = b; c < e; ++c) {
                out.text(" ");
                out.number(static_cast<std::int32_t>(soup.corners[c]));
            }
            if (corner_uv) {
                out.text(" ");
                out.number(int(2 * n));
                for (std::size_t c = b; c < e; ++c)
                    for (int k = 0; k < 2; ++k) put_uv(soup.corner_texcoords[c][k]);
            }
            out.text("\n");
        } else {
            out.binary(n);
            for (std::size_t c = b; c < e; ++c)
                out.binary(static_cast<std::int32_t>(soup.corners[c]));
            if (corner_uv) {
                out.binary(static_cast<std::uint8_t>(2 * n));
                for (std::size_t c = b; c < e; ++c)
                    for (int k = 0; k < 2; ++k) put_uv(soup.corner_texcoords[c][k]);
            }
        }
        out.maybe_flush();
    }
}

/// The rows of the `edge` element: the sharp edges.
void put_ply_sharp_edges(OutBuffer& out, const PolygonSoup& soup, bool ascii) {
    // Sharp edges; an infinite sharpness is written as 10 (OpenSubdiv's infinite, read back as
    // infinity), which every reader can hold.
    for (const PolygonSoup::SharpEdge& se : soup.sharp_edges) {
        const float crease = std::min(se.sharpness, kSharpnessActsInfinite);
        if (ascii) {
            out.number(static_cast<std::int32_t>(se.a));
            out.text(" ");
            out.number(static_cast<std::int32_t>(se.b));
            out.text(" ");
            out.number(crease);
            out.text("\n");
        } else {
            out.binary(static_cast<std::int32_t>(se.a));
            out.binary(static_cast<std::int32_t>(se.b));
            out.binary(crease);
        }
        out.maybe_flush();
    }
}

}  // namespace

void write_ply_to(const HalfedgeMesh& mesh, std::ostream& os, const std::string& path,
                  const WriteOptions& options) {
    const PolygonSoup soup = to_soup(mesh);
    if (soup.positions.size() > std::size_t(std::numeric_limits<std::int32_t>::max()))
        throw IoError(path, 0, "too many vertices for PLY int indices");
    const bool normals = options.write_normals && !soup.normals.empty();
    const bool colors = options.write_colors && !soup.colors.empty();
    const bool uv = options.write_texcoords && !soup.texcoords.empty();
    // Texture seams (per-corner coordinates only): the per-face `texcoord` list MeshLab uses.
    const bool corner_uv = options.write_texcoords && !uv && !soup.corner_texcoords.empty();
    const bool distance = !soup.distances.empty();
    const bool selection = !soup.selections.empty();
    const bool corner = !soup.corner_tags.empty();
    const bool edges = !soup.sharp_edges.empty();
    for (std::size_t i = 0; i < soup.selections.size(); ++i)
        if (!(soup.selections[i] >= 0.0f && soup.selections[i] <= 1.0f))
            throw IoError(
                path, 0,
                "vertex " + std::to_string(i) + ": selection weight not in [0, 1] (not written)");
    for (std::size_t i = 0; i < soup.distances.size(); ++i)
        if (!std::isfinite(soup.distances[i]))
            throw IoError(path, 0,
                          "vertex " + std::to_string(i) + ": non-finite distance (not written)");
    check_finite_for_writing(soup, path, normals, colors, uv || corner_uv);
    const bool ascii = options.ascii;
    const bool big = options.big_endian;
    // float32 where it holds the values with full precision, else double (PLY has both).
    const bool pos_d = !float_range_suffices(max_abs_component(soup.positions));
    const bool nrm_d = normals && !float_range_suffices(max_abs_component(soup.normals));
    const bool uv_d = uv && !float_range_suffices(max_abs_component(soup.texcoords));
    const bool cuv_d = corner_uv && !float_range_suffices(max_abs_component(soup.corner_texcoords));
    auto type = [](bool d) { return d ? "double" : "float"; };

    std::string header = "ply\nformat ";
    header += ascii ? "ascii" : big ? "binary_big_endian" : "binary_little_endian";
    header += " 1.0\ncomment written by trilab\n";
    header += "element vertex " + std::to_string(soup.positions.size()) + "\n";
    for (const char* n : {"x", "y", "z"})
        header += std::string("property ") + type(pos_d) + " " + n + "\n";
    if (normals)
        for (const char* n : {"nx", "ny", "nz"})
            header += std::string("property ") + type(nrm_d) + " " + n + "\n";
    if (colors) header += "property uchar red\nproperty uchar green\nproperty uchar blue\n";
    if (uv)
        for (const char* n : {"u", "v"})
            header += std::string("property ") + type(uv_d) + " " + n + "\n";
    if (distance) header += "property double distance\n";
    if (selection) header += "property float selection\n";
    if (corner) header += "property uchar corner\n";
    header += "element face " + std::to_string(soup.n_faces()) + "\n";
    header += "property list uchar int vertex_indices\n";
    if (corner_uv) header += std::string("property list uchar ") + type(cuv_d) + " texcoord\n";
    if (edges) {
        header += "element edge " + std::to_string(soup.sharp_edges.size()) + "\n";
        header += "property int vertex1\nproperty int vertex2\nproperty float crease\n";
    }
    header += "end_header\n";

    OutBuffer out(os, !ascii && big == host_is_little_endian());
    // One value as float or double, as text or binary.
    auto put = [&](double v, bool as_double, bool first) {
        if (ascii) {
            if (!first) out.text(" ");
            if (as_double)
                out.number(v);
            else
                out.number(static_cast<float>(v));
        } else if (as_double) {
            out.binary(v);
        } else {
            out.binary(static_cast<float>(v));
        }
    };
    out.text(header);
    const std::size_t nv = soup.positions.size();
    for (std::size_t i = 0; i < nv; ++i) {
        const Point& p = soup.positions[i];
        for (int k = 0; k < 3; ++k) put(p[k], pos_d, k == 0);
        if (normals)
            for (int k = 0; k < 3; ++k) put(soup.normals[i][k], nrm_d, false);
        if (colors)
            for (int k = 0; k < 3; ++k) {
                const std::uint8_t c = color_byte(soup.colors[i][k]);
                if (ascii) {
                    out.text(" ");
                    out.number(int(c));
                } else {
                    out.binary(c);
                }
            }
        if (uv)
            for (int k = 0; k < 2; ++k) put(soup.texcoords[i][k], uv_d, false);
        if (distance) put(soup.distances[i], true, false);
        if (selection) put(soup.selections[i], false, false);
        if (corner) {
            if (ascii) {
                out.text(" ");
                out.number(int(soup.corner_tags[i]));
            } else {
                out.binary(soup.corner_tags[i]);
            }
        }
        if (ascii) out.text("\n");
        out.maybe_flush();
    }
    put_ply_faces(out, soup, ascii, corner_uv, [&](double v) { put(v, cuv_d, false); });
    put_ply_sharp_edges(out, soup, ascii);
    out.flush();
}

void write_ply(const HalfedgeMesh& mesh, const std::string& path, const WriteOptions& options) {
    write_file_atomically(path, [&](std::ostream& os) { write_ply_to(mesh, os, path, options); });
}

}  // namespace trilab
