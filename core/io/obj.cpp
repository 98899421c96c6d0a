// Wavefront OBJ. Reading uses tinyobjloader (double precision build) for the statements and
// faces, with checks of our own that it does not make: every number on v/vt/vn lines must be
// a finite number (tinyobjloader silently reads "nan" or "abc" as 0; we also re-parse them
// with std::from_chars, which is correctly rounded, so written files read back bit for bit),
// and every index must be in range (reported with the line of the offending `f` statement). Polygons are triangulated by
// build_mesh. Texture coordinates become "v:texcoord" when every vertex has one texture
// coordinate, otherwise per-corner "h:texcoord" (seams stay seams); normals become "v:normal"
// (the first normal given for a vertex). Materials are ignored.
// Writing: v (and vt, vn) with shortest round-trip decimals, then f v/vt/vn triples.
#include <tiny_obj_loader.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <ostream>
#include <string_view>
#include <unordered_map>

#include "core/errors.h"
#include "core/io/file_util.h"
#include "core/io/mesh_io.h"
#include "core/io/text_scanner.h"

namespace trilab {

namespace {

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

/// Numbers of the v, vt and vn statements, parsed exactly (correctly rounded).
struct ObjNumbers {
    std::vector<double> v, vt, vn;
};

/// Parses every number on v/vt/vn lines with std::from_chars (tinyobjloader's own parser is
/// off by an ulp at times, and reads "nan" or "abc" as 0). Throws IoError naming the line of
/// the first token that is not a finite number, or of a statement with too few numbers.
ObjNumbers scan_obj_numbers(std::string_view text, const std::string& path) {
    ObjNumbers out;
    std::size_t line = 0;
    std::size_t pos = 0;
    double values[4];
    while (pos < text.size()) {
        ++line;
        std::size_t end = text.find('\n', pos);
        if (end == std::string_view::npos) end = text.size();
        std::size_t i = pos;
        while (i < end && is_space(text[i])) ++i;
        int kind = -1;  // 0: v, 1: vt, 2: vn
        if (i + 1 < end && text[i] == 'v') {
            if (is_space(text[i + 1])) kind = 0;
            else if (i + 2 < end && is_space(text[i + 2]))
                kind = text[i + 1] == 't' ? 1 : text[i + 1] == 'n' ? 2 : -1;
        }
        if (kind >= 0) {
            i += kind == 0 ? 1 : 2;
            const int want = kind == 1 ? 2 : 3;
            int count = 0;
            while (i < end) {
                while (i < end && is_space(text[i])) ++i;
                if (i >= end || text[i] == '#' || text[i] == '\r') break;
                std::size_t t0 = i;
                while (i < end && !is_space(text[i])) ++i;
                const char* first = text.data() + t0;
                const char* last = text.data() + i;
                if (*first == '+') ++first;
                double value = 0;
                auto res = std::from_chars(first, last, value);
                if (res.ec != std::errc() || res.ptr != last || !std::isfinite(value))
                    throw IoError(path, line,
                                  "'" + printable(text.substr(t0, i - t0)) +
                                      "' is not a finite number");
                if (count < 4) values[count] = value;
                ++count;
            }
            if (count < (kind == 1 ? 1 : 3))
                throw IoError(path, line,
                              std::string(kind == 0 ? "v" : kind == 1 ? "vt" : "vn") +
                                  " needs at least " + std::to_string(kind == 1 ? 1 : 3) +
                                  " numbers");
            if (kind == 1 && count < 2) values[1] = 0.0;
            std::vector<double>& dst = kind == 0 ? out.v : kind == 1 ? out.vt : out.vn;
            dst.insert(dst.end(), values, values + want);
        }
        pos = end + 1;
    }
    return out;
}

/// Line number of the n-th (0-based) face statement, for error messages.
std::size_t face_line(std::string_view text, std::size_t n) {
    std::size_t line = 0, pos = 0, seen = 0;
    while (pos < text.size()) {
        ++line;
        std::size_t end = text.find('\n', pos);
        if (end == std::string_view::npos) end = text.size();
        std::size_t i = pos;
        while (i < end && is_space(text[i])) ++i;
        if (i + 1 < end && text[i] == 'f' && is_space(text[i + 1]) && seen++ == n) return line;
        pos = end + 1;
    }
    return 0;
}

std::size_t line_in_message(const std::string& msg) {
    const std::size_t at = msg.find("line ");
    if (at == std::string::npos) return 0;
    return std::strtoul(msg.c_str() + at + 5, nullptr, 10);
}

std::string first_line(std::string s) {
    const std::size_t nl = s.find('\n');
    if (nl != std::string::npos) s.resize(nl);
    return s;
}

}  // namespace

LoadedMesh read_obj(const std::string& path) {
    const std::string text = read_file_bytes(path);
    const ObjNumbers exact = scan_obj_numbers(text, path);

    tinyobj::ObjReaderConfig config;
    config.triangulate = false;  // build_mesh triangulates (ear clipping, keeps corner data)
    config.vertex_color = false;
    tinyobj::ObjReader reader;
    if (!reader.ParseFromString(text, "", config)) {
        const std::string msg = first_line(reader.Error());
        throw IoError(path, line_in_message(msg), msg.empty() ? "not a valid OBJ file" : msg);
    }
    tinyobj::attrib_t attrib = reader.GetAttrib();
    // Use the exactly parsed numbers where our scan saw the same statements as tinyobjloader.
    if (exact.v.size() == attrib.vertices.size()) attrib.vertices = exact.v;
    if (exact.vt.size() == attrib.texcoords.size()) attrib.texcoords = exact.vt;
    if (exact.vn.size() == attrib.normals.size()) attrib.normals = exact.vn;
    const std::size_t nv = attrib.vertices.size() / 3;
    const std::size_t nt = attrib.texcoords.size() / 2;
    const std::size_t nn = attrib.normals.size() / 3;

    PolygonSoup soup;
    soup.positions.resize(nv);
    for (std::size_t i = 0; i < nv; ++i)
        soup.positions[i] = Point(attrib.vertices[3 * i], attrib.vertices[3 * i + 1],
                                  attrib.vertices[3 * i + 2]);

    // Faces, with per-corner texture-coordinate and normal indices.
    std::vector<int> corner_uv, corner_normal;
    std::size_t face_index = 0;
    bool any_uv = false, any_normal = false;
    for (const tinyobj::shape_t& shape : reader.GetShapes()) {
        const auto& m = shape.mesh;
        std::size_t offset = 0;
        for (std::size_t f = 0; f < m.num_face_vertices.size(); ++f, ++face_index) {
            const std::size_t n = m.num_face_vertices[f];
            if (offset + n > m.indices.size())
                throw IoError(path, face_line(text, face_index), "face list is inconsistent");
            for (std::size_t k = 0; k < n; ++k) {
                const tinyobj::index_t& idx = m.indices[offset + k];
                if (idx.vertex_index < 0 || std::size_t(idx.vertex_index) >= nv)
                    throw IoError(path, face_line(text, face_index),
                                  "face refers to vertex " + std::to_string(idx.vertex_index + 1) +
                                      " but the file has " + std::to_string(nv) + " vertices");
                if (idx.texcoord_index >= 0 && std::size_t(idx.texcoord_index) >= nt)
                    throw IoError(path, face_line(text, face_index),
                                  "face refers to texture coordinate " +
                                      std::to_string(idx.texcoord_index + 1) + " but the file has " +
                                      std::to_string(nt));
                if (idx.normal_index >= 0 && std::size_t(idx.normal_index) >= nn)
                    throw IoError(path, face_line(text, face_index),
                                  "face refers to normal " + std::to_string(idx.normal_index + 1) +
                                      " but the file has " + std::to_string(nn));
                soup.corners.push_back(Index(idx.vertex_index));
                corner_uv.push_back(idx.texcoord_index);
                corner_normal.push_back(idx.normal_index);
                any_uv = any_uv || idx.texcoord_index >= 0;
                any_normal = any_normal || idx.normal_index >= 0;
            }
            soup.face_offsets.push_back(soup.corners.size());
            offset += n;
        }
    }

    LoadReport report;
    report.file = path;
    report.format = "obj";
    report.file_vertices = nv;
    report.file_faces = soup.n_faces();

    if (any_uv) {
        // Per vertex when every corner of a vertex uses the same coordinate, else per corner.
        std::vector<int> uv_of_vertex(nv, -2);  // -2: unseen
        bool per_vertex = true;
        for (std::size_t c = 0; c < soup.corners.size() && per_vertex; ++c) {
            int& u = uv_of_vertex[soup.corners[c]];
            if (u == -2) u = corner_uv[c];
            per_vertex = u == corner_uv[c] && u >= 0;
        }
        auto uv = [&](int i) {
            return i < 0 ? TexCoord(0, 0)
                         : TexCoord(attrib.texcoords[2 * std::size_t(i)],
                                    attrib.texcoords[2 * std::size_t(i) + 1]);
        };
        if (per_vertex) {
            soup.texcoords.assign(nv, TexCoord(0, 0));
            for (std::size_t v = 0; v < nv; ++v)
                if (uv_of_vertex[v] >= 0) soup.texcoords[v] = uv(uv_of_vertex[v]);
        } else {
            soup.corner_texcoords.reserve(soup.corners.size());
            std::size_t missing = 0;
            for (int i : corner_uv) {
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
            const int i = corner_normal[c];
            if (i < 0) continue;
            int& n = normal_of_vertex[soup.corners[c]];
            if (n < 0) {
                n = i;
                soup.normals[soup.corners[c]] =
                    Vector3(attrib.normals[3 * std::size_t(i)], attrib.normals[3 * std::size_t(i) + 1],
                            attrib.normals[3 * std::size_t(i) + 2]);
            } else if (n != i) {
                ++conflicting;
            }
        }
        if (conflicting)
            report.notes.push_back(std::to_string(conflicting) +
                                   " corners had a second normal for their vertex (first kept)");
    }
    const std::string warn = first_line(reader.Warning());
    if (!warn.empty()) report.notes.push_back("tinyobjloader: " + warn);

    LoadedMesh out;
    out.mesh = build_mesh_for_file(soup, report, path);
    out.report = std::move(report);
    return out;
}

void write_obj(const HalfedgeMesh& mesh, const std::string& path, const WriteOptions& options) {
    const PolygonSoup soup = to_soup(mesh);
    const bool normals = options.write_normals && !soup.normals.empty();
    const bool vertex_uv = options.write_texcoords && !soup.texcoords.empty();
    const bool corner_uv = options.write_texcoords && !vertex_uv && !soup.corner_texcoords.empty();

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
    write_file_atomically(path, [&](std::ostream& os) { os.write(out.data(), std::streamsize(out.size())); });
}

}  // namespace trilab
