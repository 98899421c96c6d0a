// STL reader and writer.
//
// Reading: a file is binary exactly when its size is at least 84 bytes and equals 84 + 50 n,
// n being the little-endian u32 at offset 80 (many binary files start with "solid", so the
// first word decides nothing). Anything else is parsed as ASCII with TextScanner: "solid
// [name]", facets ("facet [normal nx ny nz]", "outer loop", three "vertex x y z", "endloop",
// "endfacet") and "endsolid [name]"; keywords are case-insensitive, several solids may
// follow each other and a missing final endsolid is tolerated. A file that is neither
// (e.g. a truncated binary file) is reported as such. Stored facet normals are ignored.
// Corners with bit-identical coordinates (after mapping -0 to +0) are merged into one vertex
// with an open-addressing hash table; report.merged_vertices counts the corners that reused
// a vertex and report.file_vertices the corners read (3 per facet). Non-finite coordinates
// are errors.
//
// Writing: binary by default (an 80-byte header that does not start with "solid", normals
// computed from the geometry, attribute byte count 0; coordinates are float32 as the format
// requires, and a mesh whose coordinates float32 cannot hold is refused); ASCII with
// options.ascii ("solid trilab" ... "endsolid trilab", coordinates in the shortest form that
// reads back to the same double). A mesh without faces, or with a non-finite position, is
// refused. A file that is not binary may start with a UTF-8 byte-order mark; UTF-16 is
// refused.
#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "core/errors.h"
#include "core/hash.h"
#include "core/io/byte_io.h"
#include "core/io/file_util.h"
#include "core/io/mesh_io.h"
#include "core/io/text_scanner.h"

namespace trilab {
namespace {

/// Little-endian u32 / f32 at p.
std::uint32_t load_u32_le(const unsigned char* p) {
    return std::uint32_t(p[0]) | (std::uint32_t(p[1]) << 8) | (std::uint32_t(p[2]) << 16) |
           (std::uint32_t(p[3]) << 24);
}

float load_f32_le(const unsigned char* p, bool host_le) {
    float f;
    if (host_le) {
        std::memcpy(&f, p, 4);
    } else {
        const std::uint32_t u = load_u32_le(p);
        std::memcpy(&f, &u, 4);
    }
    return f;
}

/// Maps the bit pattern of a position (Word = u32 for float, u64 for double coordinates) to
/// a vertex index: open addressing with linear probing, grown at load factor 1/2.
template <class Word>
class PositionTable {
public:
    using Key = std::array<Word, 3>;

    explicit PositionTable(std::size_t expected) {
        std::size_t cap = 64;
        while (cap < 2 * expected) cap <<= 1;
        slots_.assign(cap, kEmpty);
        keys_.reserve(expected);
    }

    /// The vertex with this key, or a new one numbered keys_.size(); `found` tells which.
    Index find_or_insert(const Key& k, bool& found) {
        if (2 * (keys_.size() + 1) > slots_.size()) grow();
        const std::size_t mask = slots_.size() - 1;
        for (std::size_t i = hash(k) & mask;; i = (i + 1) & mask) {
            const Index s = slots_[i];
            if (s == kEmpty) {
                const Index id = Index(keys_.size());
                slots_[i] = id;
                keys_.push_back(k);
                found = false;
                return id;
            }
            if (keys_[s] == k) {
                found = true;
                return s;
            }
        }
    }

private:
    static constexpr Index kEmpty = kInvalidIndex;
    static std::size_t hash(const Key& k) {
        std::uint64_t h = std::uint64_t(k[0]) * 0x9E3779B97F4A7C15ULL;
        h = mix_bits(h ^ std::uint64_t(k[1]));
        h = mix_bits(h ^ std::uint64_t(k[2]) * 0xC2B2AE3D27D4EB4FULL);
        return std::size_t(h);
    }
    void grow() {
        slots_.assign(slots_.size() * 2, kEmpty);
        const std::size_t mask = slots_.size() - 1;
        for (Index id = 0; id < keys_.size(); ++id) {
            std::size_t i = hash(keys_[id]) & mask;
            while (slots_[i] != kEmpty) i = (i + 1) & mask;
            slots_[i] = id;
        }
    }
    std::vector<Index> slots_;
    std::vector<Key> keys_;
};

template <class Word, class Real>
Word bits_of(Real x) {
    static_assert(sizeof(Word) == sizeof(Real), "word size");
    if (x == Real(0)) x = Real(0);  // -0 and +0 are the same position
    Word w;
    std::memcpy(&w, &x, sizeof(Word));
    return w;
}

/// Collects facets into a soup, merging identical corners.
template <class Word>
class SoupMerger {
public:
    explicit SoupMerger(std::size_t expected_faces) : table_(expected_faces / 2 + 16) {
        soup_.positions.reserve(expected_faces / 2 + 16);
        soup_.corners.reserve(3 * expected_faces);
        soup_.face_offsets.reserve(expected_faces + 1);
    }
    template <class Real>
    void add_corner(Real x, Real y, Real z) {
        bool found = false;
        const Index id =
            table_.find_or_insert({bits_of<Word>(x), bits_of<Word>(y), bits_of<Word>(z)}, found);
        if (found)
            ++merged_;
        else
            soup_.positions.emplace_back(double(x), double(y), double(z));
        soup_.corners.push_back(id);
    }
    void end_face() { soup_.face_offsets.push_back(soup_.corners.size()); }
    PolygonSoup& soup() { return soup_; }
    std::size_t merged() const { return merged_; }

private:
    PositionTable<Word> table_;
    PolygonSoup soup_;
    std::size_t merged_ = 0;
};

LoadedMesh finish(const std::string& path, const PolygonSoup& soup, std::size_t merged) {
    LoadedMesh out;
    out.report.file = path;
    out.report.format = "stl";
    out.report.file_vertices = soup.corners.size();
    out.report.file_faces = soup.n_faces();
    out.report.merged_vertices = merged;
    out.mesh = build_mesh_for_file(soup, out.report, path);
    return out;
}

LoadedMesh read_binary_stl(const std::string& path, const std::string& data, std::size_t n) {
    const auto* p = reinterpret_cast<const unsigned char*>(data.data());
    const bool host_le = host_is_little_endian();
    SoupMerger<std::uint32_t> merger(n);
    // The size rule guarantees 84 + 50 n == data.size(): every read below is in bounds.
    for (std::size_t t = 0; t < n; ++t) {
        const unsigned char* rec = p + 84 + 50 * t + 12;  // skip the stored normal
        for (int k = 0; k < 3; ++k, rec += 12) {
            const float x = load_f32_le(rec, host_le), y = load_f32_le(rec + 4, host_le),
                        z = load_f32_le(rec + 8, host_le);
            if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z))
                throw IoError(path, 0,
                              "triangle " + std::to_string(t) + ", corner " + std::to_string(k) +
                                  ": non-finite position (NaN or infinity)");
            merger.add_corner(x, y, z);
        }
        merger.end_face();
    }
    LoadedMesh out = finish(path, merger.soup(), merger.merged());
    out.report.notes.push_back("binary STL");
    return out;
}

bool iequals(std::string_view a, const char* b) {
    const std::size_t n = std::strlen(b);
    if (a.size() != n) return false;
    for (std::size_t i = 0; i < n; ++i) {
        char c = a[i];
        if (c >= 'A' && c <= 'Z') c = char(c - 'A' + 'a');
        if (c != b[i]) return false;
    }
    return true;
}

LoadedMesh read_ascii_stl(const std::string& path, std::string_view data) {
    TextScanner sc(data, path, '\0');
    // A facet takes well over 100 bytes of text; this is only a reservation hint.
    SoupMerger<std::uint64_t> merger(data.size() / 128);
    auto expect = [&](const char* keyword) {
        const std::string_view t = sc.expect_token(keyword);
        if (!iequals(t, keyword))
            sc.fail("expected '" + std::string(keyword) + "', found '" + printable(t) + "'");
    };
    std::string_view tok = sc.next_token();
    if (!iequals(tok, "solid"))
        sc.fail(tok.empty() ? "empty file: not an STL file"
                            : "not an STL file: ASCII STL starts with 'solid', found '" +
                                  printable(tok) + "'");
    sc.rest_of_line();
    bool in_solid = true;
    for (;;) {
        tok = sc.next_token();
        if (tok.empty()) break;
        if (iequals(tok, "endsolid")) {
            if (!in_solid) sc.fail("'endsolid' without 'solid'");
            in_solid = false;
            sc.rest_of_line();
            continue;
        }
        if (iequals(tok, "solid")) {
            if (in_solid) sc.fail("'solid' inside a solid (missing 'endsolid')");
            in_solid = true;
            sc.rest_of_line();
            continue;
        }
        if (!iequals(tok, "facet"))
            sc.fail("expected 'facet' or 'endsolid', found '" + printable(tok) + "'");
        if (!in_solid) sc.fail("'facet' outside a solid");
        const std::size_t facet_line = sc.line();
        tok = sc.expect_token("'normal' or 'outer'");
        if (iequals(tok, "normal")) {
            // The stored normal is not used (and may be "nan" for degenerate facets).
            for (int k = 0; k < 3; ++k) sc.expect_token("a normal component");
            expect("outer");
        } else if (!iequals(tok, "outer")) {
            sc.fail("expected 'normal' or 'outer', found '" + printable(tok) + "'");
        }
        expect("loop");
        double v[3][3];
        int count = 0;
        for (;;) {
            tok = sc.expect_token("'vertex' or 'endloop'");
            if (iequals(tok, "endloop")) break;
            if (!iequals(tok, "vertex"))
                sc.fail("expected 'vertex' or 'endloop', found '" + printable(tok) + "'");
            double p[3];
            for (double& c : p) c = sc.next_double("a vertex coordinate");
            if (count < 3)
                for (int k = 0; k < 3; ++k) v[count][k] = p[k];
            ++count;
        }
        if (count != 3)
            throw IoError(path, facet_line,
                          "facet has " + std::to_string(count) + " vertices, expected 3");
        expect("endfacet");
        for (const auto& c : v) merger.add_corner(c[0], c[1], c[2]);
        merger.end_face();
    }
    LoadedMesh out = finish(path, merger.soup(), merger.merged());
    out.report.notes.push_back("ASCII STL");
    if (in_solid) out.report.notes.push_back("the last solid has no 'endsolid' line");
    return out;
}

bool starts_with_solid(std::string_view data) {
    std::size_t i = 0;
    while (i < data.size() &&
           (data[i] == ' ' || data[i] == '\t' || data[i] == '\r' || data[i] == '\n'))
        ++i;
    return data.size() - i >= 5 && iequals(data.substr(i, 5), "solid");
}

// ---- writing ------------------------------------------------------------------------------

Vector3 face_normal(const Point& a, const Point& b, const Point& c) {
    // Coordinates far from 1 are taken in units of the largest one first, so that the cross
    // product neither overflows (1e300) nor underflows (1e-300); the direction is the same.
    const double s =
        std::max({a.cwiseAbs().maxCoeff(), b.cwiseAbs().maxCoeff(), c.cwiseAbs().maxCoeff()});
    if (s == 0 || !std::isfinite(s)) return Vector3::Zero();
    const bool far = s > 0x1p400 || s < 0x1p-400;
    const Vector3 n = far ? (b / s - a / s).cross(c / s - a / s) : (b - a).cross(c - a);
    const double len = n.norm();
    if (len > 0 && std::isfinite(len)) return n / len;
    return Vector3::Zero();
}

}  // namespace

LoadedMesh read_stl(const std::string& path) {
    return read_stl_bytes(read_file_bytes(path), path);
}

LoadedMesh read_stl_bytes(const std::string& data, const std::string& path) {
    if (data.size() >= 84) {
        const std::uint64_t n =
            load_u32_le(reinterpret_cast<const unsigned char*>(data.data()) + 80);
        const std::uint64_t expected = 84 + 50 * n;
        if (data.size() == expected) return read_binary_stl(path, data, std::size_t(n));
    }
    // Not binary: text, after a UTF-8 byte-order mark (UTF-16 is refused).
    const std::string_view text = strip_utf8_bom(data, path);
    if (data.size() >= 84) {
        const std::uint64_t n =
            load_u32_le(reinterpret_cast<const unsigned char*>(data.data()) + 80);
        const std::uint64_t expected = 84 + 50 * n;
        // Neither text nor a binary file of the right size: report it as a binary STL of the
        // wrong size rather than as garbage text.
        if (!starts_with_solid(text) || std::memchr(data.data(), '\0', data.size()) != nullptr)
            throw IoError(path, 0,
                          "not an ASCII STL, and as binary STL its header declares " +
                              std::to_string(n) + " triangles (" + std::to_string(expected) +
                              " bytes) but the file has " + std::to_string(data.size()) +
                              " bytes (truncated or corrupt?)");
    }
    return read_ascii_stl(path, text);
}

void write_stl_to(const HalfedgeMesh& mesh, std::ostream& os, const std::string& path,
                  const WriteOptions& options) {
    if (mesh.n_faces() == 0)
        throw IoError(path, 0,
                      "STL holds only triangles and the mesh has no faces (" +
                          std::to_string(mesh.n_vertices()) +
                          " vertices): not written; use OBJ, OFF, PLY or .om for points");
    if (!options.ascii && mesh.n_faces() > std::numeric_limits<std::uint32_t>::max())
        throw IoError(path, 0, "too many faces for binary STL");
    // Positions of the vertices the faces use (STL has nothing else).
    double max_abs = 0;
    for (Face f : mesh.faces())
        for (Vertex v : mesh.face_vertices(f)) {
            const Point& p = mesh.position(v);
            if (!p.allFinite())
                throw IoError(path, 0,
                              "vertex " + std::to_string(v.idx()) +
                                  ": non-finite position; not written: no reader accepts it");
            max_abs = std::max(max_abs, p.cwiseAbs().maxCoeff());
        }
    if (!options.ascii && !float_range_suffices(max_abs)) {
        char buf[64];
        std::snprintf(buf, sizeof(buf), "%g", max_abs);
        throw IoError(path, 0,
                      std::string("binary STL stores float32 coordinates, which cannot hold "
                                  "this mesh's (largest magnitude ") +
                          buf + "); not written: use ASCII STL (--ascii), PLY, OBJ, OFF or .om");
    }
    {
        OutBuffer out(os, !host_is_little_endian());
        if (options.ascii) {
            out.text("solid trilab\n");
        } else {
            char header[80] = {};
            const char title[] = "trilab binary STL";
            std::memcpy(header, title, sizeof(title) - 1);
            out.text(std::string_view(header, sizeof(header)));
            out.binary<std::uint32_t>(static_cast<std::uint32_t>(mesh.n_faces()));
        }
        for (Face f : mesh.faces()) {
            const auto vs = mesh.face_vertices(f);
            const Point& a = mesh.position(vs[0]);
            const Point& b = mesh.position(vs[1]);
            const Point& c = mesh.position(vs[2]);
            const Vector3 n = face_normal(a, b, c);
            if (options.ascii) {
                out.text("  facet normal ");
                for (int k = 0; k < 3; ++k) {
                    if (k) out.text(" ");
                    out.number(n[k]);
                }
                out.text("\n    outer loop\n");
                for (const Point* p : {&a, &b, &c}) {
                    out.text("      vertex ");
                    for (int k = 0; k < 3; ++k) {
                        if (k) out.text(" ");
                        out.number((*p)[k]);
                    }
                    out.text("\n");
                }
                out.text("    endloop\n  endfacet\n");
            } else {
                for (int k = 0; k < 3; ++k) out.binary<float>(static_cast<float>(n[k]));
                for (const Point* p : {&a, &b, &c})
                    for (int k = 0; k < 3; ++k) out.binary<float>(static_cast<float>((*p)[k]));
                out.text(std::string_view("\0\0", 2));
            }
            out.maybe_flush();
        }
        if (options.ascii) out.text("endsolid trilab\n");
        out.flush();
    }
}

void write_stl(const HalfedgeMesh& mesh, const std::string& path, const WriteOptions& options) {
    write_file_atomically(path, [&](std::ostream& os) { write_stl_to(mesh, os, path, options); });
}

}  // namespace trilab
