// `trilab-cli render`: one offscreen image of a mesh (render/offscreen.h: an EGL surfaceless
// context, no X server needed), written as a PNG.
#include "app/cli/render_command.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <string>

#include "app/cli/arg_reader.h"
#include "app/cli/json_writer.h"
#include "app/cli/legend_output.h"
#include "core/algorithms/coloring.h"
#include "core/algorithms/texcoords.h"
#include "core/errors.h"
#include "core/io/image_io.h"
#include "core/io/mesh_io.h"

#ifdef TRILAB_HAS_RENDER
#include "render/offscreen.h"
#endif

namespace trilab::cli {
namespace {

constexpr const char* kRenderUsage =
    R"(usage: trilab-cli render MESH --out FILE.png [options]

Renders MESH without a window (EGL surfaceless context; Mesa's llvmpipe on machines without
a GPU) and writes a PNG. The camera frames the mesh's bounding box.

options:
  --out FILE.png        the image to write (required; PNG only, so it must end in .png)
  --size WxH            image size in pixels (default 1280x800)
  --mode MODE           gouraud (default), flat, wireframe, hidden-line, points, textured
  --color QUANTITY      colour the vertices: none (default), normal, k1, k2, mean,
                        gaussian, shape-index, subdivision (categorical: one colour per
                        level), smoothing-distance
  --reference MESH      the state before smoothing, for --color smoothing-distance: each
                        vertex's displacement from it, signed along the normal (MESH must
                        have the same vertices, e.g. the input of trilab-cli smooth)
  --texture IMG         texture image for --mode textured (BMP, PNG, PNM, XBM, XPM); implies
                        --mode textured when no --mode is given. Without it textured mode
                        uses a built-in checkerboard. Meshes without texture coordinates get
                        a spherical projection.
  --view AZ,EL          view direction in degrees: azimuth around the up axis from the
                        front, elevation above the horizontal plane (default 0,0: the
                        front view; +y up: looking along -z)
  --up y|z              the model's up axis (default y): +y up with the front at +z, or
                        +z up with the front at -y; also the pole axis of the spherical
                        projection of textured mode
  --transparent         alpha 0 where no surface is drawn
  --json                print one JSON object (with "ms": the time spent rendering, file
                        reading and writing excluded)
)";

[[maybe_unused]] double ms_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

/// Parses a whole string as a number; false on garbage or trailing characters.
bool parse_double(const std::string& s, double& out) {
    if (s.empty()) return false;
    char* end = nullptr;
    out = std::strtod(s.c_str(), &end);
    return end == s.c_str() + s.size() && std::isfinite(out);
}

bool parse_int(const std::string& s, int& out) {
    double d = 0;
    if (!parse_double(s, d) || d != std::floor(d) || std::abs(d) > 1e9) return false;
    out = int(d);
    return true;
}

struct RenderArgs {
    std::string mesh, out, texture, reference;
    int width = 1280, height = 800;
    std::string mode = "gouraud";
    bool mode_given = false;
    std::string color = "none";
    std::string up = "y";
    double azimuth = 0, elevation = 0;
    bool transparent = false, json = false, help = false;
};

RenderArgs parse_args(const std::vector<std::string>& args) {
    RenderArgs r;
    ArgReader reader(args, "render");
    while (reader.next()) {
        if (reader.is_help()) {
            r.help = true;
        } else if (reader.is("--json")) {
            r.json = reader.flag();
        } else if (reader.is("--transparent")) {
            r.transparent = reader.flag();
        } else if (reader.is("--out")) {
            r.out = reader.value();
        } else if (reader.is("--reference")) {
            r.reference = reader.value();
        } else if (reader.is("--texture")) {
            r.texture = reader.value();
        } else if (reader.is("--mode")) {
            r.mode = reader.value();
            r.mode_given = true;
        } else if (reader.is("--color")) {
            r.color = reader.value();
        } else if (reader.is("--up")) {
            r.up = reader.value();
        } else if (reader.is("--size")) {
            const std::string v = reader.value();
            const std::size_t x = v.find_first_of("xX");
            if (x == std::string::npos || !parse_int(v.substr(0, x), r.width) ||
                !parse_int(v.substr(x + 1), r.height) || r.width < 1 || r.height < 1 ||
                r.width > 16384 || r.height > 16384)
                throw InvalidArgument(
                    "--size: expected WxH with whole numbers from 1 to 16384, "
                    "got '" +
                    v + "'");
        } else if (reader.is("--view")) {
            const std::string v = reader.value();
            const std::size_t comma = v.find(',');
            if (comma == std::string::npos || !parse_double(v.substr(0, comma), r.azimuth) ||
                !parse_double(v.substr(comma + 1), r.elevation))
                throw InvalidArgument(
                    "--view: expected AZIMUTH,ELEVATION in degrees (e.g. "
                    "30,20), got '" +
                    v + "'");
        } else if (reader.is_option()) {
            reader.refuse_unknown();
        } else if (r.mesh.empty()) {
            r.mesh = reader.arg();
        } else {
            throw InvalidArgument("unexpected argument '" + reader.arg() +
                                  "': expected one MESH file");
        }
    }
    return r;
}

}  // namespace

int run_render_command(const std::vector<std::string>& args) {
    const RenderArgs a = parse_args(args);
    if (a.help) {
        std::fputs(kRenderUsage, stdout);
        return 0;
    }
    if (a.mesh.empty())
        throw InvalidArgument("expected a MESH file (see `trilab-cli render --help`)");
    if (a.out.empty()) throw InvalidArgument("--out FILE.png is required");
    if (file_extension(a.out) != "png")
        throw InvalidArgument("--out: '" + a.out +
                              "': only PNG is written, so the file name must end in .png");
    const std::filesystem::path out_dir = std::filesystem::path(a.out).parent_path();
    if (!out_dir.empty() && !std::filesystem::is_directory(out_dir))
        throw InvalidArgument("--out: the folder '" + out_dir.string() + "' does not exist");

#ifndef TRILAB_HAS_RENDER
    throw Error("this trilab-cli was built without the renderer (TRILAB_BUILD_VIEWER=OFF)");
#else
    // Options first, so that a bad one fails before any file is read.
    OffscreenOptions options;
    options.width = a.width;
    options.height = a.height;
    options.azimuth = float(a.azimuth);
    options.elevation = float(a.elevation);
    options.transparent = a.transparent;
    options.up = parse_up_axis(a.up, "--up");
    try {
        options.style.mode = parse_render_mode(a.mode);
    } catch (const InvalidArgument& e) {
        throw InvalidArgument(std::string("--mode: ") + e.what());
    }
    if (!a.texture.empty()) {
        if (!a.mode_given)
            options.style.mode = RenderMode::Textured;
        else if (options.style.mode != RenderMode::Textured)
            throw InvalidArgument("--texture: only --mode textured uses a texture (got --mode " +
                                  a.mode + ")");
    }
    VertexColoring coloring = VertexColoring::None;
    try {
        coloring = parse_coloring(a.color);
    } catch (const InvalidArgument& e) {
        throw InvalidArgument(std::string("--color: ") + e.what());
    }
    if (!a.reference.empty() && coloring != VertexColoring::SmoothingDistance)
        throw InvalidArgument(
            "--reference: only --color smoothing-distance uses a reference "
            "mesh (got --color " +
            a.color + ")");
    if (coloring_needs_field(coloring))
        throw InvalidArgument("--color: '" + a.color +
                              "' needs a spectral decomposition (the viewer's Frequency panel)");
    const bool textured = options.style.mode == RenderMode::Textured;

    // File input (not timed).
    LoadedMesh loaded = read_mesh(a.mesh);
    HalfedgeMesh& mesh = loaded.mesh;
    std::string texture_source = "none";
    if (textured) {
        if (!a.texture.empty()) {
            options.texture = read_image(a.texture);
            texture_source = a.texture;
        } else {
            options.texture = make_checkerboard();
            texture_source = "checkerboard";
        }
    }

    const auto t0 = std::chrono::steady_clock::now();
    std::vector<std::string> notes;
    std::string texcoords = has_texcoords(mesh) ? "mesh" : "none";
    if (textured && !has_texcoords(mesh)) {
        project_texcoords(mesh, TexCoordProjection::Spherical, options.up);
        texcoords = "spherical projection";
        notes.push_back(
            "the mesh has no texture coordinates: textured mode uses a spherical "
            "projection around the centroid (the poles on the up axis, +" +
            std::string(up_axis_name(options.up)) + ")");
    }
    VertexColors colors;
    if (coloring != VertexColoring::None) {
        std::vector<Point> reference;
        if (!a.reference.empty()) {
            const LoadedMesh before = read_mesh(a.reference);
            if (before.mesh.vertices_size() != mesh.vertices_size())
                throw InvalidArgument("--reference: " + a.reference + " has " +
                                      std::to_string(before.mesh.vertices_size()) + " vertices, " +
                                      a.mesh + " has " + std::to_string(mesh.vertices_size()) +
                                      " (it must be the same mesh before smoothing)");
            reference = before.mesh.positions();
        }
        colors = color_vertices(mesh, coloring, ColoringOptions{},
                                a.reference.empty() ? nullptr : &reference);
        options.vertex_colors = colors.colors;
    }
    const double prepare_ms = ms_since(t0);

    const auto t1 = std::chrono::steady_clock::now();
    OffscreenRenderer renderer;
    const double context_ms = ms_since(t1);
    const auto t2 = std::chrono::steady_clock::now();
    const Image image = renderer.render(mesh, options);
    const double render_ms = ms_since(t2);
    const double ms = ms_since(t0);

    write_png(image, a.out);  // file output (not timed)

    if (a.json) {
        JsonObject j;
        j.add("input", a.mesh)
            .add("output", a.out)
            .add("width", a.width)
            .add("height", a.height)
            .add("mode", render_mode_name(options.style.mode))
            .add("color", coloring_name(coloring));
        add_legend(j, colors);
        j.add("view", std::vector<double>{a.azimuth, a.elevation})
            .add("up", up_axis_name(options.up))
            .add("transparent", a.transparent)
            .add("texture", texture_source)
            .add("texcoords", texcoords)
            .add("vertices", mesh.n_vertices())
            .add("faces", mesh.n_faces())
            .add("renderer", renderer.context().description())
            .add("notes", notes)
            .add("prepare_ms", prepare_ms)
            .add("context_ms", context_ms)
            .add("render_ms", render_ms)
            .add("ms", ms);
        std::cout << j.str() << "\n";
    } else {
        std::printf("wrote %s: %dx%d, %s", a.out.c_str(), a.width, a.height,
                    render_mode_name(options.style.mode));
        if (colors.has_legend)
            std::printf(", %s", legend_text(colors).c_str());
        else if (coloring != VertexColoring::None)
            std::printf(", %s colouring", coloring_name(coloring));
        std::printf(" (%.1f ms; %s)\n", ms, renderer.context().description().c_str());
        for (const std::string& n : notes) std::printf("note: %s\n", n.c_str());
    }
    return 0;
#endif
}

}  // namespace trilab::cli
