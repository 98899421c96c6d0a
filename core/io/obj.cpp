// Wavefront OBJ.
// Reading: our own single-pass parser for the geometry statements v, vt, vn and f (numbers
// with std::from_chars, which is correctly rounded, so files we write read back bit for bit;
// "nan", "abc" or an index out of range is an error naming the line), and tinyobjloader for
// the material libraries named by `mtllib` (the first material's diffuse texture, map_Kd,
// becomes LoadedMesh::texture_path). tinyobjloader's own OBJ parser was measured at 1.0-1.7 s
// for a 1M-face file (the floor for the whole load is 1.5 s), is off by an ulp on some
// numbers and reads "nan" as 0, which is why the geometry does not go through it.
// Faces: "f a b c ...", with a, a/t, a//n or a/t/n corners, negative indices counting back
// from the last vertex; polygons are triangulated by build_mesh. Other statements (o, g, s,
// usemtl, l, p, ...) are ignored. Texture coordinates become "v:texcoord" when every vertex has
// one texture coordinate, otherwise per-corner "h:texcoord" (seams stay seams); normals become
// "v:normal" (the first normal given for a vertex).
// A UTF-8 byte-order mark is skipped (in the material library too), UTF-16 refused. Material
// libraries are read through read_file_bytes (regular files of at most 64 MiB; anything else
// becomes a note in the report).
// Writing: v (and vt, vn) with shortest round-trip decimals, then f v/vt/vn triples;
// non-finite values are refused.
#include <tiny_obj_loader.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>
#include <ostream>
#include <sstream>
#include <string_view>
#include <unordered_map>

#include "core/errors.h"
#include "core/io/file_util.h"
#include "core/io/mesh_io.h"
#include "core/io/text_scanner.h"

namespace trilab {

namespace {

bool is_space(char c) {
    return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

/// Everything the geometry statements of an OBJ file hold.
struct ObjContents {
    std::vector<double> v, vt, vn;          // 3, 2 and 3 numbers per statement
    std::vector<Index> corners;             // vertex index per face corner
    std::vector<int> corner_vt, corner_vn;  // -1 where absent
    std::vector<std::size_t> face_offsets{0};
    std::vector<std::string> mtllibs;
    std::size_t ignored_statements = 0;
};

class ObjParser {
public:
    ObjParser(std::string_view text, const std::string& path) : text_(text), path_(path) {}

    ObjContents parse() {
        std::size_t pos = 0;
        while (pos < text_.size()) {
            ++line_;
            std::size_t end = text_.find('\n', pos);
            if (end == std::string_view::npos) end = text_.size();
            statement(pos, end);
            pos = end + 1;
        }
        return std::move(out_);
    }

private:
    [[noreturn]] void fail(const std::string& reason) const { throw IoError(path_, line_, reason); }

    void skip_space(std::size_t& i, std::size_t end) const {
        while (i < end && is_space(text_[i])) ++i;
    }
    /// The next token on the line, or an empty view.
    std::string_view token(std::size_t& i, std::size_t end) const {
        skip_space(i, end);
        if (i >= end || text_[i] == '#') return {};
        const std::size_t t0 = i;
        while (i < end && !is_space(text_[i]) && text_[i] != '#') ++i;
        return text_.substr(t0, i - t0);
    }

    void statement(std::size_t i, std::size_t end) {
        const std::string_view key = token(i, end);
        if (key.empty()) return;
        if (key == "v")
            numbers(i, end, out_.v, 3, 3, "v", "position");
        else if (key == "vt")
            numbers(i, end, out_.vt, 1, 2, "vt", "texture coordinate");
        else if (key == "vn")
            numbers(i, end, out_.vn, 3, 3, "vn", "normal");
        else if (key == "f")
            face(i, end);
        else if (key == "mtllib") {
            for (std::string_view t = token(i, end); !t.empty(); t = token(i, end))
                out_.mtllibs.emplace_back(t);
        } else if (key == "o" || key == "g" || key == "s" || key == "usemtl") {
            // grouping and material statements carry no geometry
        } else {
            ++out_.ignored_statements;
        }
    }

    /// Reads at least `min` numbers, keeps the first `keep` (missing ones are 0).
    void numbers(std::size_t i, std::size_t end, std::vector<double>& dst, int min, int keep,
                 const char* what, const char* attribute) {
        double values[3] = {0, 0, 0};
        int count = 0;
        for (std::string_view t = token(i, end); !t.empty(); t = token(i, end)) {
            const char* first = t.data();
            const char* last = t.data() + t.size();
            if (*first == '+') ++first;
            double value = 0;
            const auto res = std::from_chars(first, last, value);
            if (res.ec != std::errc() || res.ptr != last || !std::isfinite(value))
                fail("'" + printable(t) + "' is not a finite number (" + attribute + ")");
            if (count < keep) values[count] = value;
            ++count;
        }
        if (count < min)
            fail(std::string(what) + " needs at least " + std::to_string(min) + " numbers");
        dst.insert(dst.end(), values, values + keep);
    }

    /// An OBJ index (1-based, or negative counting back) resolved against `count` elements.
    int index(std::string_view t, std::size_t count, const char* what) const {
        long long value = 0;
        const auto res = std::from_chars(t.data(), t.data() + t.size(), value);
        if (res.ec != std::errc() || res.ptr != t.data() + t.size())
            fail("'" + printable(t) + "' is not a " + what + " index");
        if (value == 0)
            fail(std::string("index 0 is invalid (OBJ ") + what + " indices start at 1)");
        const long long resolved = value > 0 ? value - 1 : (long long)count + value;
        if (resolved < 0 || resolved >= (long long)count)
            fail("face refers to " + std::string(what) + " " + std::to_string(value) +
                 " but the file has " + std::to_string(count) + " so far");
        return int(resolved);
    }

    void face(std::size_t i, std::size_t end) {
        const std::size_t nv = out_.v.size() / 3, nt = out_.vt.size() / 2, nn = out_.vn.size() / 3;
        for (std::string_view t = token(i, end); !t.empty(); t = token(i, end)) {
            const std::size_t s1 = t.find('/');
            const std::string_view a = t.substr(0, s1);
            std::string_view b, c;
            if (s1 != std::string_view::npos) {
                const std::size_t s2 = t.find('/', s1 + 1);
                b = t.substr(s1 + 1,
                             s2 == std::string_view::npos ? std::string_view::npos : s2 - s1 - 1);
                if (s2 != std::string_view::npos) c = t.substr(s2 + 1);
            }
            out_.corners.push_back(Index(index(a, nv, "vertex")));
            out_.corner_vt.push_back(b.empty() ? -1 : index(b, nt, "texture coordinate"));
            out_.corner_vn.push_back(c.empty() ? -1 : index(c, nn, "normal"));
        }
        out_.face_offsets.push_back(out_.corners.size());
    }

    std::string_view text_;
    const std::string& path_;
    std::size_t line_ = 0;
    ObjContents out_;
};

constexpr std::uintmax_t kMaxMaterialLibraryBytes = 64u << 20;

/// The diffuse texture of the first material that names one, resolved against `folder`.
std::string find_texture(const std::vector<std::string>& mtllibs,
                         const std::filesystem::path& folder, LoadReport& report) {
    for (const std::string& lib : mtllibs) {
        const std::filesystem::path mtl_path = folder / lib;
        // Only regular files of a sane size (read_file_bytes refuses devices, FIFOs and
        // folders without opening them): `mtllib /dev/zero` must not hang or exhaust memory.
        std::string text;
        try {
            text = std::string(strip_utf8_bom(
                read_file_bytes(mtl_path.string(), kMaxMaterialLibraryBytes), mtl_path.string()));
        } catch (const IoError& e) {
            report.notes.push_back("material library " + lib + " not read: " + e.reason());
            continue;
        }
        std::istringstream in(text);
        std::vector<tinyobj::material_t> materials;
        std::map<std::string, int> names;
        std::string warning, error;
        tinyobj::LoadMtl(&names, &materials, &in, &warning, &error);
        for (const tinyobj::material_t& m : materials)
            if (!m.diffuse_texname.empty()) return (folder / m.diffuse_texname).string();
    }
    return {};
}

}  // namespace

namespace {

/// Reads OBJ text; the material libraries it names are returned in `mtllibs`.
LoadedMesh read_obj_text(const std::string& text, const std::string& path,
                         std::vector<std::string>& mtllibs) {
    ObjContents obj = ObjParser(strip_utf8_bom(text, path), path).parse();
    const std::size_t nv = obj.v.size() / 3;

    PolygonSoup soup;
    soup.positions.resize(nv);
    for (std::size_t i = 0; i < nv; ++i)
        soup.positions[i] = Point(obj.v[3 * i], obj.v[3 * i + 1], obj.v[3 * i + 2]);
    soup.corners = std::move(obj.corners);
    soup.face_offsets = std::move(obj.face_offsets);

    LoadReport report;
    report.file = path;
    report.format = "obj";
    report.file_vertices = nv;
    report.file_faces = soup.n_faces();
    if (obj.ignored_statements)
        report.notes.push_back(std::to_string(obj.ignored_statements) +
                               " statements of unsupported kinds ignored");

    const bool any_uv =
        std::any_of(obj.corner_vt.begin(), obj.corner_vt.end(), [](int i) { return i >= 0; });
    const bool any_normal =
        std::any_of(obj.corner_vn.begin(), obj.corner_vn.end(), [](int i) { return i >= 0; });
    if (any_uv) {
        // Per vertex when every corner of a vertex uses the same coordinate, else per corner.
        std::vector<int> uv_of_vertex(nv, -2);  // -2: unseen
        bool per_vertex = true;
        for (std::size_t c = 0; c < soup.corners.size() && per_vertex; ++c) {
            int& u = uv_of_vertex[soup.corners[c]];
            if (u == -2) u = obj.corner_vt[c];
            per_vertex = u == obj.corner_vt[c] && u >= 0;
        }
        auto uv = [&](int i) {
            return i < 0 ? TexCoord(0, 0)
                         : TexCoord(obj.vt[2 * std::size_t(i)], obj.vt[2 * std::size_t(i) + 1]);
        };
        if (per_vertex) {
            soup.texcoords.assign(nv, TexCoord(0, 0));
            for (std::size_t v = 0; v < nv; ++v)
                if (uv_of_vertex[v] >= 0) soup.texcoords[v] = uv(uv_of_vertex[v]);
        } else {
            soup.corner_texcoords.reserve(soup.corners.size());
            std::size_t missing = 0;
            for (int i : obj.corner_vt) {
                soup.corner_texcoords.push_back(uv(i));
                missing += i < 0;
            }
            if (missing)
                report.notes.push_back(std::to_string(missing) +
                                       " corners without texture coordinates got (0, 0)");
        }
    }
    if (any_normal) {
        soup.normals.assign(nv, Vector3::Zero());
        std::vector<int> normal_of_vertex(nv, -1);
        std::size_t conflicting = 0;
        for (std::size_t c = 0; c < soup.corners.size(); ++c) {
            const int i = obj.corner_vn[c];
            if (i < 0) continue;
            int& n = normal_of_vertex[soup.corners[c]];
            if (n < 0) {
                n = i;
                soup.normals[soup.corners[c]] =
                    Vector3(obj.vn[3 * std::size_t(i)], obj.vn[3 * std::size_t(i) + 1],
                            obj.vn[3 * std::size_t(i) + 2]);
            } else if (n != i) {
                ++conflicting;
            }
        }
        if (conflicting)
            report.notes.push_back(std::to_string(conflicting) +
                                   " corners had a second normal for their vertex (first kept)");
    }

    LoadedMesh out;
    out.mesh = build_mesh_for_file(soup, report, path);
    out.report = std::move(report);
    mtllibs = std::move(obj.mtllibs);
    return out;
}

}  // namespace

LoadedMesh read_obj(const std::string& path) {
    std::vector<std::string> mtllibs;
    LoadedMesh out = read_obj_text(read_file_bytes(path), path, mtllibs);
    out.texture_path = find_texture(mtllibs, std::filesystem::path(path).parent_path(), out.report);
    return out;
}

LoadedMesh read_obj_bytes(const std::string& bytes, const std::string& name) {
    std::vector<std::string> mtllibs;
    return read_obj_text(bytes, name, mtllibs);
}

void write_obj_to(const HalfedgeMesh& mesh, std::ostream& os, const std::string& path,
                  const WriteOptions& options) {
    const PolygonSoup soup = to_soup(mesh);
    const bool normals = options.write_normals && !soup.normals.empty();
    const bool vertex_uv = options.write_texcoords && !soup.texcoords.empty();
    const bool corner_uv = options.write_texcoords && !vertex_uv && !soup.corner_texcoords.empty();
    check_finite_for_writing(soup, path, normals, false, vertex_uv || corner_uv);

    std::string out;
    out.reserve(soup.positions.size() * 40 + soup.corners.size() * 12 + 64);
    out += "# written by trilab\n";
    for (const Point& p : soup.positions) {
        out += "v ";
        append_number(out, p.x());
        out += ' ';
        append_number(out, p.y());
        out += ' ';
        append_number(out, p.z());
        out += '\n';
    }
    // Corner texture coordinates: one vt per distinct value.
    std::vector<std::size_t> corner_vt;
    auto write_vt = [&](const TexCoord& t) {
        out += "vt ";
        append_number(out, t.x());
        out += ' ';
        append_number(out, t.y());
        out += '\n';
    };
    if (vertex_uv) {
        for (const TexCoord& t : soup.texcoords) write_vt(t);
    } else if (corner_uv) {
        struct Hash {
            std::size_t operator()(const std::pair<double, double>& p) const {
                return std::hash<double>()(p.first) * 31 + std::hash<double>()(p.second);
            }
        };
        std::unordered_map<std::pair<double, double>, std::size_t, Hash> ids;
        corner_vt.reserve(soup.corner_texcoords.size());
        for (const TexCoord& t : soup.corner_texcoords) {
            auto [it, inserted] = ids.emplace(std::make_pair(t.x(), t.y()), ids.size());
            if (inserted) write_vt(t);
            corner_vt.push_back(it->second);
        }
    }
    if (normals) {
        for (const Vector3& n : soup.normals) {
            out += "vn ";
            append_number(out, n.x());
            out += ' ';
            append_number(out, n.y());
            out += ' ';
            append_number(out, n.z());
            out += '\n';
        }
    }
    for (std::size_t f = 0; f < soup.n_faces(); ++f) {
        out += 'f';
        for (std::size_t c = soup.face_offsets[f]; c < soup.face_offsets[f + 1]; ++c) {
            const std::size_t v = std::size_t(soup.corners[c]) + 1;
            out += ' ';
            append_number(out, v);
            if (vertex_uv || corner_uv || normals) {
                out += '/';
                if (vertex_uv) append_number(out, v);
                if (corner_uv) append_number(out, corner_vt[c] + 1);
                if (normals) {
                    out += '/';
                    append_number(out, v);
                }
            }
        }
        out += '\n';
    }
    os.write(out.data(), std::streamsize(out.size()));
}

void write_obj(const HalfedgeMesh& mesh, const std::string& path, const WriteOptions& options) {
    write_file_atomically(path, [&](std::ostream& os) { write_obj_to(mesh, os, path, options); });
}

}  // namespace trilab
