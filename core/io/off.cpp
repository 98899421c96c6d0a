// Object File Format (Geomview OFF). Reads the header keyword [ST][C][N]OFF (any subset, in
// that order), with the counts "nv nf ne" on the keyword line or a later one; comments (#)
// anywhere; vertex lines "x y z [nx ny nz] [r g b [a]] [s t]" with colours as 0..255
// integers or 0..1 floats; faces "n i0 .. in-1 [colour]" with any n (polygons are
// triangulated by build_mesh, face colours ignored). 4OFF, nOFF and binary OFF are refused
// with a message; so are colour components outside 0..255 and (as everywhere) NaN and
// infinity. A UTF-8 byte-order mark is skipped, UTF-16 refused. Writing emits the same header
// letters for what the mesh carries (colours clamped to 0..1, non-finite values refused).
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <ostream>
#include <string_view>

#include "core/errors.h"
#include "core/io/file_util.h"
#include "core/io/mesh_io.h"
#include "core/io/text_scanner.h"

namespace trilab {

namespace {

std::string shortest(double v) {
    std::string out;
    append_number(out, v);
    return out;
}

std::vector<double> parse_tail(std::string_view tail, TextScanner& scanner, const char* what) {
    const std::size_t hash = tail.find('#');
    if (hash != std::string_view::npos) tail = tail.substr(0, hash);
    std::vector<double> values;
    TextScanner sub(tail, scanner.file(), '\0');
    while (!sub.at_end()) {
        try {
            values.push_back(sub.next_double(what));
        } catch (const IoError& e) {
            scanner.fail(e.reason());
        }
    }
    return values;
}

}  // namespace

LoadedMesh read_off(const std::string& path) {
    return read_off_bytes(read_file_bytes(path), path);
}

namespace {

// read_off_bytes() in three stages: the header (keyword and counts), the vertex lines, the
// face lines; then the report.

/// What the header announces: the keyword's letters and the counts.
struct OffHeader {
    bool st = false, color = false, normal = false;
    std::size_t nv = 0, nf = 0;
};

OffHeader read_off_header(TextScanner& in, std::string_view text, const std::string& path) {
    OffHeader h;
    std::string_view keyword = in.next_token();
    if (keyword.empty()) in.fail("empty file, expected the OFF header");
    const std::string_view full = keyword;
    if (keyword.substr(0, 2) == "ST") {
        h.st = true;
        keyword.remove_prefix(2);
    }
    if (!keyword.empty() && keyword[0] == 'C') {
        h.color = true;
        keyword.remove_prefix(1);
    }
    if (!keyword.empty() && keyword[0] == 'N') {
        h.normal = true;
        keyword.remove_prefix(1);
    }
    if (!keyword.empty() && (keyword[0] == '4' || keyword[0] == 'n'))
        in.fail("'" + printable(full) + "': only 3-dimensional OFF is supported");
    if (keyword != "OFF") in.fail("'" + printable(full) + "' is not an OFF header keyword");

    std::string_view first = in.next_token();
    if (first == "BINARY") in.fail("binary OFF is not supported; convert it to ASCII OFF");
    auto to_count = [&](std::string_view t, const char* what) -> std::size_t {
        long long value = 0;
        TextScanner one(t, path, '\0');
        try {
            value = one.next_integer(what);
        } catch (const IoError&) {
            in.fail("'" + printable(t) + "' is not a count (" + what + ")");
        }
        if (value < 0) in.fail(std::string("negative ") + what);
        return std::size_t(value);
    };
    if (first.empty()) in.fail("unexpected end of file, expected the vertex count");
    const std::size_t header_line = in.line();
    h.nv = to_count(first, "vertex count");
    h.nf = to_count(in.expect_token("face count"), "face count");
    in.rest_of_line();
    const std::size_t remaining = text.size() - in.offset();
    check_declared_count(h.nv, 6, remaining, "vertices", path, header_line);
    check_declared_count(h.nf, 2, remaining, "faces", path, header_line);
    return h;
}

/// Reads the vertex lines into `soup` (colours scaled to 0..1); returns how many lines had
/// values the header does not announce.
std::size_t read_off_vertices(TextScanner& in, const OffHeader& h, const std::string& path,
                              PolygonSoup& soup) {
    const bool st = h.st, color = h.color, normal = h.normal;
    const std::size_t nv = h.nv;
    soup.positions.resize(nv);
    if (normal) soup.normals.resize(nv);
    if (color) soup.colors.resize(nv);
    if (st) soup.texcoords.resize(nv);
    bool colors_are_bytes = false;
    std::size_t ignored_extra = 0;
    for (std::size_t v = 0; v < nv; ++v) {
        const double x = in.next_double("vertex x");
        const double y = in.next_double("vertex y");
        const double z = in.next_double("vertex z");
        soup.positions[v] = Point(x, y, z);
        if (normal) {
            const double a = in.next_double("normal x"), b = in.next_double("normal y"),
                         c = in.next_double("normal z");
            soup.normals[v] = Vector3(a, b, c);
        }
        const std::size_t line = in.line();
        std::vector<double> tail =
            parse_tail(in.rest_of_line(), in,
                       color ? (st ? "colour or texture coordinate" : "colour")
                             : (st ? "texture coordinate" : "vertex attribute"));
        std::size_t k = 0;
        if (color) {
            const std::size_t want = tail.size() - (st ? 2 : 0);
            if (tail.size() < (st ? 5u : 3u) || (want != 3 && want != 4))
                throw IoError(path, line,
                              "vertex " + std::to_string(v) + ": expected an RGB or RGBA colour");
            for (int i = 0; i < 3; ++i) {
                if (!(tail[i] >= 0 && tail[i] <= 255))
                    throw IoError(path, line,
                                  "vertex " + std::to_string(v) + ": colour component " +
                                      shortest(tail[i]) +
                                      " is outside 0 to 1 (or 0 to 255 for byte colours)");
                colors_are_bytes = colors_are_bytes || tail[i] > 1.0;
            }
            soup.colors[v] = Color(float(tail[0]), float(tail[1]), float(tail[2]));
            k = want;
        }
        if (st) {
            if (tail.size() < k + 2)
                throw IoError(path, line,
                              "vertex " + std::to_string(v) + ": expected texture coordinates s t");
            soup.texcoords[v] = TexCoord(tail[k], tail[k + 1]);
            k += 2;
        }
        if (tail.size() > k) ++ignored_extra;
    }
    if (colors_are_bytes)
        for (Color& c : soup.colors) c /= 255.0f;
    return ignored_extra;
}

/// Reads the face lines "n i0 .. in-1 [colour]" into `soup`.
void read_off_faces(TextScanner& in, std::string_view text, const OffHeader& h,
                    const std::string& path, PolygonSoup& soup) {
    const std::size_t nv = h.nv;
    const std::size_t corner_budget = text.size() - in.offset();
    for (std::size_t f = 0; f < h.nf; ++f) {
        const long long n = in.next_integer("face corner count");
        const std::size_t line = in.line();
        if (n < 0 || std::size_t(n) > corner_budget)
            throw IoError(
                path, line,
                "face " + std::to_string(f) + " declares " + std::to_string(n) + " corners");
        for (long long k = 0; k < n; ++k) {
            const long long i = in.next_integer("face vertex index");
            if (i < 0 || std::size_t(i) >= nv)
                throw IoError(path, in.line(),
                              "face " + std::to_string(f) + " refers to vertex " +
                                  std::to_string(i) + " but the file has " + std::to_string(nv) +
                                  " vertices (indices start at 0)");
            soup.corners.push_back(Index(i));
        }
        soup.face_offsets.push_back(soup.corners.size());
        if (in.line() == line) in.rest_of_line();  // face colour, if any
    }
}

}  // namespace

LoadedMesh read_off_bytes(const std::string& bytes, const std::string& path) {
    const std::string_view text = strip_utf8_bom(bytes, path);
    TextScanner in(text, path);
    const OffHeader header = read_off_header(in, text, path);
    PolygonSoup soup;
    const std::size_t ignored_extra = read_off_vertices(in, header, path, soup);
    read_off_faces(in, text, header, path, soup);

    LoadReport report;
    report.file = path;
    report.format = "off";
    report.file_vertices = header.nv;
    report.file_faces = header.nf;
    if (ignored_extra)
        report.notes.push_back(
            std::to_string(ignored_extra) +
            " vertex lines had extra values the header does not announce (ignored)");
    LoadedMesh out;
    out.mesh = build_mesh_for_file(soup, report, path);
    out.report = std::move(report);
    return out;
}

void write_off_to(const HalfedgeMesh& mesh, std::ostream& os, const std::string& path,
                  const WriteOptions& options) {
    const PolygonSoup soup = to_soup(mesh);
    const bool st = options.write_texcoords && !soup.texcoords.empty();
    const bool color = options.write_colors && !soup.colors.empty();
    const bool normal = options.write_normals && !soup.normals.empty();
    check_finite_for_writing(soup, path, normal, color, st);
    std::string out;
    out.reserve(soup.positions.size() * 48 + soup.corners.size() * 8 + 64);
    if (st) out += "ST";
    if (color) out += "C";
    if (normal) out += "N";
    out += "OFF\n# written by trilab\n";
    append_number(out, soup.positions.size());
    out += ' ';
    append_number(out, soup.n_faces());
    out += " 0\n";
    for (std::size_t v = 0; v < soup.positions.size(); ++v) {
        const Point& p = soup.positions[v];
        append_number(out, p.x());
        out += ' ';
        append_number(out, p.y());
        out += ' ';
        append_number(out, p.z());
        if (normal) {
            for (int i = 0; i < 3; ++i) {
                out += ' ';
                append_number(out, soup.normals[v][i]);
            }
        }
        if (color) {
            for (int i = 0; i < 3; ++i) {
                out += ' ';
                // In 0..1: the reader takes any value above 1 as a 0..255 byte colour.
                append_number(out, std::clamp(soup.colors[v][i], 0.0f, 1.0f));
            }
            out += " 1";
        }
        if (st) {
            out += ' ';
            append_number(out, soup.texcoords[v].x());
            out += ' ';
            append_number(out, soup.texcoords[v].y());
        }
        out += '\n';
    }
    for (std::size_t f = 0; f < soup.n_faces(); ++f) {
        append_number(out, soup.face_offsets[f + 1] - soup.face_offsets[f]);
        for (std::size_t c = soup.face_offsets[f]; c < soup.face_offsets[f + 1]; ++c) {
            out += ' ';
            append_number(out, std::size_t(soup.corners[c]));
        }
        out += '\n';
    }
    os.write(out.data(), std::streamsize(out.size()));
}

void write_off(const HalfedgeMesh& mesh, const std::string& path, const WriteOptions& options) {
    write_file_atomically(path, [&](std::ostream& os) { write_off_to(mesh, os, path, options); });
}

}  // namespace trilab
