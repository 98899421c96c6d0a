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
#include "app/cli/stopwatch.h"
#include "core/algorithms/coloring.h"
#include "core/algorithms/mesh_distance.h"
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
                        level), smoothing-distance, geodesic-distance (the per-vertex
                        `distance` that trilab-cli geodesic writes to PLY), min-angle,
                        quality (triangle quality: the worst of the vertex's triangles) and
                        surface-distance (to the surface of --reference MESH)
  --bands N             a banded map: the legend range cut into N equal steps (2 to 64),
                        each one colour (the map's colour at the step's centre)
  --isolines N          N isolines (1 to 63), evenly spaced inside the legend range: at
                        min + k (max - min) / (N + 1), over the shading; with --bands B they
                        are the bands' edges, so N must be B - 1. Both need a scalar
                        --color (not none, normal or subdivision)
  --reference MESH      the state before smoothing, for --color smoothing-distance: each
                        vertex's displacement from it, signed along the normal (MESH must
                        have the same vertices, e.g. the input of trilab-cli smooth); for
                        --color surface-distance any other mesh: each vertex's distance to
                        its surface (required there)
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

// The step counts of --bands and --isolines (RenderStyle::scalar_steps; the renderer's
// kMinScalarSteps / kMaxScalarSteps, repeated here for builds without the renderer).
constexpr int kMinSteps = 2, kMaxSteps = 64;

/// The N of --bands (steps, 2 to 64) or --isolines (lines, 1 to 63: `lines_less` 1).
int parse_steps(const std::string& text, const char* option, int lines_less = 0) {
    int n = 0;
    const int lo = kMinSteps - lines_less, hi = kMaxSteps - lines_less;
    if (!parse_int(text, n) || n < lo || n > hi)
        throw InvalidArgument(std::string(option) + ": expected a whole number of " +
                              (lines_less ? "lines" : "steps") + " from " + std::to_string(lo) +
                              " to " + std::to_string(hi) + ", got '" + text + "'");
    return n;
}

struct RenderArgs {
    std::string mesh, out, texture, reference;
    int width = 1280, height = 800;
    std::string mode = "gouraud";
    bool mode_given = false;
    std::string color = "none";
    int bands = 0, isolines = 0;  ///< 0: not given
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
        } else if (reader.is("--bands")) {
            r.bands = parse_steps(reader.value(), "--bands");
        } else if (reader.is("--isolines")) {
            r.isolines = parse_steps(reader.value(), "--isolines", 1) + 1;  // as steps
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

/// Refuses a missing MESH or --out, and an --out that is not a .png in an existing folder.
void check_files(const RenderArgs& a) {
    if (a.mesh.empty())
        throw InvalidArgument("expected a MESH file (see `trilab-cli render --help`)");
    if (a.out.empty()) throw InvalidArgument("--out FILE.png is required");
    if (file_extension(a.out) != "png")
        throw InvalidArgument("--out: '" + a.out +
                              "': only PNG is written, so the file name must end in .png");
    const std::filesystem::path out_dir = std::filesystem::path(a.out).parent_path();
    if (!out_dir.empty() && !std::filesystem::is_directory(out_dir))
        throw InvalidArgument("--out: the folder '" + out_dir.string() + "' does not exist");
}

#ifdef TRILAB_HAS_RENDER

/// The checked options of one image: what the renderer is given, and the colouring.
struct RenderSetup {
    OffscreenOptions options;
    VertexColoring coloring = VertexColoring::None;
    bool textured() const { return options.style.mode == RenderMode::Textured; }
};

/// --bands / --isolines into the style; refuses them without a scalar colouring and with
/// two different counts.
void set_steps(const RenderArgs& a, RenderSetup& setup) {
    if (a.bands == 0 && a.isolines == 0) return;
    const char* option = a.bands ? "--bands" : "--isolines";
    const VertexColoring c = setup.coloring;
    if (c == VertexColoring::None || c == VertexColoring::Normal ||
        c == VertexColoring::SubdivisionLevel)
        throw InvalidArgument(
            std::string(option) + ": needs a scalar --color (k1, k2, mean, " +
            "gaussian, shape-index, smoothing-distance, geodesic-distance, min-angle, quality), " +
            "got --color " + a.color);
    if (a.bands && a.isolines && a.bands != a.isolines)
        throw InvalidArgument("--bands " + std::to_string(a.bands) + " and --isolines " +
                              std::to_string(a.isolines - 1) +
                              ": the isolines are the bands' edges, so --isolines must be " +
                              std::to_string(a.bands - 1));
    RenderStyle& style = setup.options.style;
    style.scalar_steps = a.bands ? a.bands : a.isolines;
    style.scalar_display = a.bands && a.isolines ? ScalarDisplay::BandsAndIsolines
                           : a.bands             ? ScalarDisplay::Bands
                                                 : ScalarDisplay::Isolines;
}

/// Checks the options that need no file and turns them into the renderer's (so that a bad
/// one fails before any file is read).
RenderSetup make_setup(const RenderArgs& a) {
    RenderSetup setup;
    OffscreenOptions& options = setup.options;
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
    try {
        setup.coloring = parse_coloring(a.color);
    } catch (const InvalidArgument& e) {
        throw InvalidArgument(std::string("--color: ") + e.what());
    }
    const bool surface = setup.coloring == VertexColoring::SurfaceDistance;
    if (!a.reference.empty() && setup.coloring != VertexColoring::SmoothingDistance && !surface)
        throw InvalidArgument(
            "--reference: only --color smoothing-distance and surface-distance use a reference "
            "mesh (got --color " +
            a.color + ")");
    if (surface && a.reference.empty())
        throw InvalidArgument(
            "--color surface-distance: give the surface to measure against with --reference "
            "MESH");
    if (coloring_needs_field(setup.coloring) && !surface &&
        setup.coloring != VertexColoring::GeodesicDistance)
        throw InvalidArgument("--color: '" + a.color +
                              "' needs a spectral decomposition (the viewer's Frequency panel)");
    set_steps(a, setup);
    return setup;
}

/// The texture of textured mode (--texture IMG or the built-in checkerboard) into `setup`;
/// returns where it came from ("none" when the mode is not textured).
std::string load_texture(const RenderArgs& a, RenderSetup& setup) {
    if (!setup.textured()) return "none";
    if (a.texture.empty()) {
        setup.options.texture = make_checkerboard();
        return "checkerboard";
    }
    setup.options.texture = read_image(a.texture);
    return a.texture;
}

/// What the mesh got before rendering: texture coordinates, colours, and notes about them.
struct Prepared {
    std::string texcoords;  ///< "mesh", "spherical projection" or "none"
    VertexColors colors;
    std::vector<std::string> notes;
};

/// The colouring of `mesh` by `coloring` (against --reference for the smoothing distance).
VertexColors reference_colors(const RenderArgs& a, const HalfedgeMesh& mesh,
                              VertexColoring coloring) {
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
    if (coloring == VertexColoring::GeodesicDistance &&
        !mesh.get_vertex_property<double>("v:distance"))
        throw InvalidArgument("--color geodesic-distance: " + a.mesh +
                              " has no per-vertex distance (write one with `trilab-cli geodesic " +
                              "IN OUT.ply --from N`)");
    return color_vertices(mesh, coloring, ColoringOptions{},
                          a.reference.empty() ? nullptr : &reference);
}

/// Projects texture coordinates where textured mode needs them and computes the colouring
/// (against --reference for the smoothing distance) into `setup`.
Prepared prepare_mesh(const RenderArgs& a, HalfedgeMesh& mesh, RenderSetup& setup) {
    Prepared p;
    p.texcoords = has_texcoords(mesh) ? "mesh" : "none";
    if (setup.textured() && !has_texcoords(mesh)) {
        project_texcoords(mesh, TexCoordProjection::Spherical, setup.options.up);
        p.texcoords = "spherical projection";
        p.notes.push_back(
            "the mesh has no texture coordinates: textured mode uses a spherical "
            "projection around the centroid (the poles on the up axis, +" +
            std::string(up_axis_name(setup.options.up)) + ")");
    }
    if (setup.coloring == VertexColoring::None) return p;
    if (setup.coloring == VertexColoring::SurfaceDistance) {
        // Any other mesh: each vertex's distance to its surface.
        p.colors = color_field(mesh, vertex_surface_distances(mesh, read_mesh(a.reference).mesh),
                               VertexColoring::SurfaceDistance);
    } else {
        p.colors = reference_colors(a, mesh, setup.coloring);
    }
    setup.options.vertex_colors = p.colors.colors;
    setup.options.vertex_color_blend = color_blend(p.colors.kind);
    if (setup.options.style.scalar_display != ScalarDisplay::Smooth) {
        setup.options.vertex_scalars = p.colors.values;
        setup.options.scalar_range = p.colors.range;
        setup.options.scalar_map = p.colors.kind;
    }
    return p;
}

/// The times of one render, in milliseconds.
struct RenderTimes {
    double prepare = 0, context = 0, render = 0, total = 0;
};

/// The legend's steps as the style shows them.
LegendSteps legend_steps(const RenderStyle& style) {
    if (style.scalar_display == ScalarDisplay::Smooth) return {};
    return {scalar_display_name(style.scalar_display), style.scalar_steps};
}

/// What the command prints: one JSON object, or one line and the notes.
void print_result(const RenderArgs& a, const RenderSetup& setup, const HalfedgeMesh& mesh,
                  const std::string& texture_source, const Prepared& p, const std::string& renderer,
                  const RenderTimes& t) {
    const OffscreenOptions& options = setup.options;
    if (a.json) {
        JsonObject j;
        j.add("input", a.mesh)
            .add("output", a.out)
            .add("width", a.width)
            .add("height", a.height)
            .add("mode", render_mode_name(options.style.mode))
            .add("color", coloring_name(setup.coloring));
        add_legend(j, p.colors, legend_steps(options.style));
        j.add("view", std::vector<double>{a.azimuth, a.elevation})
            .add("up", up_axis_name(options.up))
            .add("transparent", a.transparent)
            .add("texture", texture_source)
            .add("texcoords", p.texcoords)
            .add("vertices", mesh.n_vertices())
            .add("faces", mesh.n_faces())
            .add("renderer", renderer)
            .add("notes", p.notes)
            .add("prepare_ms", t.prepare)
            .add("context_ms", t.context)
            .add("render_ms", t.render)
            .add("ms", t.total);
        std::cout << j.str() << "\n";
        return;
    }
    std::printf("wrote %s: %dx%d, %s", a.out.c_str(), a.width, a.height,
                render_mode_name(options.style.mode));
    if (p.colors.has_legend)
        std::printf(", %s", legend_text(p.colors, legend_steps(options.style)).c_str());
    else if (setup.coloring != VertexColoring::None)
        std::printf(", %s colouring", coloring_name(setup.coloring));
    std::printf(" (%.1f ms; %s)\n", t.total, renderer.c_str());
    for (const std::string& n : p.notes) std::printf("note: %s\n", n.c_str());
}

#endif  // TRILAB_HAS_RENDER

}  // namespace

int run_render_command(const std::vector<std::string>& args) {
    const RenderArgs a = parse_args(args);
    if (a.help) {
        std::fputs(kRenderUsage, stdout);
        return 0;
    }
    check_files(a);
#ifndef TRILAB_HAS_RENDER
    throw Error("this trilab-cli was built without the renderer (TRILAB_BUILD_VIEWER=OFF)");
#else
    RenderSetup setup = make_setup(a);      // options first: a bad one fails before any file
    LoadedMesh loaded = read_mesh(a.mesh);  // file input (not timed)
    HalfedgeMesh& mesh = loaded.mesh;
    const std::string texture_source = load_texture(a, setup);

    RenderTimes t;
    const auto t0 = std::chrono::steady_clock::now();
    const Prepared prepared = prepare_mesh(a, mesh, setup);
    t.prepare = ms_since(t0);
    const auto t1 = std::chrono::steady_clock::now();
    OffscreenRenderer renderer;
    t.context = ms_since(t1);
    const auto t2 = std::chrono::steady_clock::now();
    const Image image = renderer.render(mesh, setup.options);
    t.render = ms_since(t2);
    t.total = ms_since(t0);

    write_png(image, a.out);  // file output (not timed)
    print_result(a, setup, mesh, texture_source, prepared, renderer.context().description(), t);
    return 0;
#endif
}

}  // namespace trilab::cli
