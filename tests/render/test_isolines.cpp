// Bands and isolines of a scalar colouring (RenderStyle::scalar_display): on a flat grid
// facing the camera with the field x, the N - 1 isolines are dark vertical stripes exactly at
// the columns where x = k / N, bands show exactly N colours (the map's colours at the steps'
// centres), Smooth draws bit for bit what it drew without scalars, and the scalars survive
// position updates and the level-of-detail path.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <vector>

#include "core/algorithms/coloring.h"
#include "core/algorithms/decimation.h"
#include "core/algorithms/generators.h"
#include "core/algorithms/level_of_detail.h"
#include "core/progress.h"
#include "render/camera.h"
#include "render/mesh_renderer.h"
#include "render/offscreen.h"
#include "render_test_util.h"

using namespace trilab;
using namespace trilab::test;

namespace {

constexpr int kWidth = 640, kHeight = 480;

Camera grid_camera() {
    return front_grid_camera(kWidth, kHeight);
}

glm::vec2 to_pixel(const Camera& camera, double x, double y) {
    return grid_pixel(camera, x, y, kWidth, kHeight);
}

/// Unlit (ambient 1), no highlight, both sides in the front colour, no multisampling
/// needed: every surface pixel is its base colour, or the isoline's colour over it.
RenderStyle flat_style() {
    RenderStyle s;
    s.ambient = 1.0f;
    s.specular = false;
    s.back_face_color = false;
    s.background = glm::vec3(1.0f);
    return s;
}

double luminance(const Rgba& p) {
    return 0.2126 * p.r + 0.7152 * p.g + 0.0722 * p.b;
}

/// The dark runs of row `y` between columns x0 and x1: their centres (darkness-weighted).
std::vector<double> dark_stripes(const Image& image, int y, int x0, int x1, double threshold) {
    std::vector<double> centres;
    double weight = 0, sum = 0;
    for (int x = x0; x <= x1 + 1; ++x) {
        const double l = x <= x1 ? luminance(pixel(image, x, y)) : 1.0;
        if (l < threshold) {
            weight += threshold - l;
            sum += (threshold - l) * (x + 0.5);
        } else if (weight > 0) {
            centres.push_back(sum / weight);
            weight = sum = 0;
        }
    }
    return centres;
}

/// Checks that rows at 30 %, 50 % and 70 % of the grid's height show exactly the N - 1
/// stripes at the columns where x = k / N (within 0.75 pixels).
void check_isolines(const Image& image, const Camera& camera, int steps, double threshold) {
    const glm::vec2 left = to_pixel(camera, 0.0, 0.5), right = to_pixel(camera, 1.0, 0.5);
    for (double row : {0.3, 0.5, 0.7}) {
        const int y = int(to_pixel(camera, 0.5, row).y);
        INFO("N = " << steps << ", row at y = " << row << " (pixel row " << y << ")");
        // Two pixels in from the grid's sides: their edges are no isolines.
        const std::vector<double> stripes =
            dark_stripes(image, y, int(left.x) + 2, int(right.x) - 2, threshold);
        REQUIRE(stripes.size() == std::size_t(steps - 1));
        for (int k = 1; k < steps; ++k) {
            const double predicted = to_pixel(camera, double(k) / steps, row).x;
            INFO("isoline " << k << ": predicted column " << predicted << ", found "
                            << stripes[std::size_t(k - 1)]);
            CHECK(std::abs(stripes[std::size_t(k - 1)] - predicted) < 0.75);
        }
    }
}

/// x of every vertex: a linear field, so its isolines on a flat grid are straight lines.
std::vector<double> x_field(const HalfedgeMesh& mesh) {
    std::vector<double> x(mesh.vertices_size());
    for (Vertex v : mesh.vertices()) x[v.idx()] = mesh.position(v).x();
    return x;
}

}  // namespace

TEST_CASE("isolines of a linear field are N - 1 dark stripes at the predicted columns",
          "[render][offscreen][isolines]") {
    OffscreenRenderer& r = offscreen();
    MeshRenderer& renderer = r.mesh_renderer();
    const HalfedgeMesh grid = make_grid(23);  // levels k / N mostly between grid lines
    renderer.upload(grid);
    renderer.set_vertex_scalars(x_field(grid), ValueRange{0.0, 1.0}, ColorMapKind::Sequential);
    CHECK(renderer.has_vertex_scalars());
    Framebuffer fb;
    fb.create(kWidth, kHeight, 1);
    const Camera camera = grid_camera();

    // Over the plain shading (no vertex colours): the front colour, lines much darker.
    RenderStyle style = flat_style();
    style.scalar_display = ScalarDisplay::Isolines;
    const double surface = 0.2126 * 0.5 + 0.7152 * 0.62 + 0.0722 * 0.8;
    for (int steps : {2, 5, 10, 64}) {
        style.scalar_steps = steps;
        const Image image = draw(renderer, fb, camera, style);
        dump(image, "isolines_" + std::to_string(steps));
        check_isolines(image, camera, steps, 0.5 * surface);
    }
    // Out-of-range counts are clamped to 2..64.
    style.scalar_steps = 1;
    check_isolines(draw(renderer, fb, camera, style), camera, 2, 0.5 * surface);
    style.scalar_steps = 1000;
    check_isolines(draw(renderer, fb, camera, style), camera, 64, 0.5 * surface);

    // With the edge overlay (the geometry-stage program) the same stripes, away from the
    // edges: the wire colour is dark too, so look at the columns only through a wide grid.
    const HalfedgeMesh coarse = make_grid(1);
    renderer.upload(coarse);
    renderer.set_vertex_scalars(x_field(coarse), ValueRange{0.0, 1.0}, ColorMapKind::Sequential);
    style.wireframe = true;
    style.scalar_steps = 7;
    const Image wired = draw(renderer, fb, camera, style);
    dump(wired, "isolines_wireframe");
    // Row 30 % crosses the diagonal edge of the two triangles at x = 0.3: skip that row by
    // checking the stripes of the rows at 10 % and 90 % only through their column count.
    {
        const glm::vec2 left = to_pixel(camera, 0.0, 0.5), right = to_pixel(camera, 1.0, 0.5);
        const int y = int(to_pixel(camera, 0.5, 0.1).y);
        const std::vector<double> stripes =
            dark_stripes(wired, y, int(left.x) + 3, int(right.x) - 3, 0.5 * surface);
        // 6 isolines and the diagonal edge.
        CHECK(stripes.size() == 7);
    }
    CHECK(glGetError() == GL_NO_ERROR);
}

TEST_CASE("bands show exactly N colours, the map's colours at the steps' centres",
          "[render][offscreen][isolines]") {
    OffscreenRenderer& r = offscreen();
    MeshRenderer& renderer = r.mesh_renderer();
    const HalfedgeMesh grid = make_grid(23);
    const std::vector<double> xs = x_field(grid);
    std::vector<double> field(xs.size());
    for (std::size_t i = 0; i < xs.size(); ++i) field[i] = 4.0 * xs[i] - 1.0;  // in [-1, 3]
    VertexColors colors =
        color_field(grid, field, VertexColoring::FrequencyMass, ColoringOptions{0.0, 100.0});
    REQUIRE(colors.range.min == -1.0);
    REQUIRE(colors.range.max == 3.0);
    renderer.upload(grid);
    renderer.set_vertex_colors(colors);
    REQUIRE(renderer.has_vertex_scalars());
    Framebuffer fb;
    fb.create(kWidth, kHeight, 1);
    const Camera camera = grid_camera();
    RenderStyle style = flat_style();
    style.scalar_display = ScalarDisplay::Bands;
    for (int steps : {2, 6, 13}) {
        INFO("N = " << steps);
        style.scalar_steps = steps;
        const Image image = draw(renderer, fb, camera, style);
        dump(image, "bands_" + std::to_string(steps));
        // Every surface pixel (not the white background) by colour.
        std::map<std::array<std::uint8_t, 3>, std::size_t> seen;
        for (std::size_t i = 0; i < image.rgba.size(); i += 4) {
            const std::array<std::uint8_t, 3> c{image.rgba[i], image.rgba[i + 1],
                                                image.rgba[i + 2]};
            if (c[0] == 255 && c[1] == 255 && c[2] == 255) continue;
            ++seen[c];
        }
        CHECK(seen.size() == std::size_t(steps));
        for (int k = 0; k < steps; ++k) {
            const Color expected = map_color(colors.range.min + (k + 0.5) / steps * 4.0,
                                             colors.range, ColorMapKind::Sequential);
            const std::array<std::uint8_t, 3> c{std::uint8_t(std::lround(expected.x() * 255)),
                                                std::uint8_t(std::lround(expected.y() * 255)),
                                                std::uint8_t(std::lround(expected.z() * 255))};
            INFO("band " << k);
            bool found = false;
            for (const auto& [colour, count] : seen)
                if (std::abs(colour[0] - c[0]) <= 1 && std::abs(colour[1] - c[1]) <= 1 &&
                    std::abs(colour[2] - c[2]) <= 1 && count > 100)
                    found = true;
            CHECK(found);
        }
        // The step boundaries: the colour changes between the columns around x = k / N.
        const int y = int(to_pixel(camera, 0.5, 0.5).y);
        for (int k = 1; k < steps; ++k) {
            const double column = to_pixel(camera, double(k) / steps, 0.5).x;
            const Rgba before = pixel(image, int(column - 1.5), y);
            const Rgba after = pixel(image, int(column + 1.5), y);
            INFO("boundary " << k << " at column " << column);
            CHECK(std::max({std::abs(before.r - after.r), std::abs(before.g - after.g),
                            std::abs(before.b - after.b)}) > 1.5 / 255.0);
        }
    }

    // Bands and isolines: the lines lie on the band boundaries.
    style.scalar_display = ScalarDisplay::BandsAndIsolines;
    style.scalar_steps = 6;
    const Image both = draw(renderer, fb, camera, style);
    dump(both, "bands_isolines");
    const glm::vec2 left = to_pixel(camera, 0.0, 0.5), right = to_pixel(camera, 1.0, 0.5);
    const int y = int(to_pixel(camera, 0.5, 0.5).y);
    // Lines are dark over light bands and light over dark ones: find them as pixels far
    // from both neighbours 3 pixels away.
    std::vector<int> line_columns;
    for (int x = int(left.x) + 4; x < int(right.x) - 4; ++x) {
        const Rgba p = pixel(both, x, y), a = pixel(both, x - 3, y), b = pixel(both, x + 3, y);
        const auto far = [&](const Rgba& q) {
            return std::abs(luminance(p) - luminance(q)) > 0.15;
        };
        if (far(a) && far(b)) line_columns.push_back(x);
    }
    for (int k = 1; k < 6; ++k) {
        const double column = to_pixel(camera, double(k) / 6, 0.5).x;
        INFO("isoline " << k << " at column " << column);
        CHECK(std::any_of(line_columns.begin(), line_columns.end(),
                          [&](int x) { return std::abs(x + 0.5 - column) < 1.5; }));
    }
    CHECK(glGetError() == GL_NO_ERROR);
}

TEST_CASE("Smooth draws exactly what it drew without scalars, and categorical colours get none",
          "[render][offscreen][isolines]") {
    OffscreenRenderer& r = offscreen();
    const HalfedgeMesh mesh = make_torus(48, 24, 1.0, 0.35);
    const VertexColors colors = color_vertices(mesh, VertexColoring::Mean);
    OffscreenOptions o;
    o.width = 240;
    o.height = 180;
    o.azimuth = 25;
    o.elevation = 30;
    o.vertex_colors = colors.colors;
    for (RenderMode mode : {RenderMode::Smooth, RenderMode::Flat, RenderMode::Points}) {
        for (bool wire : {false, true}) {
            INFO(render_mode_name(mode) << (wire ? " with wires" : ""));
            o.style.mode = mode;
            o.style.wireframe = wire;
            o.vertex_scalars.clear();
            const Image before = r.render(mesh, o);
            o.vertex_scalars = colors.values;
            o.scalar_range = colors.range;
            o.scalar_map = colors.kind;
            o.style.scalar_display = ScalarDisplay::Smooth;
            const Image smooth = r.render(mesh, o);
            CHECK(smooth.rgba == before.rgba);
            o.style.scalar_display = ScalarDisplay::Isolines;
            const Image lines = r.render(mesh, o);
            if (mode == RenderMode::Points)
                CHECK(lines.rgba == before.rgba);  // points ignore the display
            else
                CHECK(mean_difference(lines, before) > 0.5);
            o.style.scalar_display = ScalarDisplay::Smooth;
        }
    }

    // A categorical colouring uploads no scalars: bands and isolines change nothing.
    MeshRenderer& renderer = r.mesh_renderer();
    renderer.upload(mesh);
    const VertexColors levels = color_vertices(mesh, VertexColoring::SubdivisionLevel);
    renderer.set_vertex_colors(levels);
    CHECK_FALSE(renderer.has_vertex_scalars());
    CHECK(renderer.vertex_color_blend() == ColorBlend::NearestCorner);
    CHECK_THROWS_AS(
        renderer.set_vertex_scalars(levels.values, levels.range, ColorMapKind::Categorical),
        InvalidArgument);
    // Normal colours have no values either.
    renderer.set_vertex_colors(color_vertices(mesh, VertexColoring::Normal));
    CHECK_FALSE(renderer.has_vertex_scalars());
    // Colours given alone drop the scalars; so do clear_vertex_colors() and upload().
    renderer.set_vertex_colors(colors);
    CHECK(renderer.has_vertex_scalars());
    renderer.set_vertex_colors(colors.colors);
    CHECK_FALSE(renderer.has_vertex_scalars());
    renderer.set_vertex_colors(colors);
    renderer.clear_vertex_colors();
    CHECK_FALSE(renderer.has_vertex_scalars());
    renderer.set_vertex_colors(colors);
    renderer.upload(mesh);
    CHECK_FALSE(renderer.has_vertex_scalars());
    // Bad input: named.
    CHECK_THROWS_AS(
        renderer.set_vertex_scalars(std::vector<double>(3), colors.range, ColorMapKind::Diverging),
        InvalidArgument);
    CHECK_THROWS_AS(
        renderer.set_vertex_scalars(colors.values, ValueRange{1.0, 1.0}, ColorMapKind::Diverging),
        InvalidArgument);
    CHECK(parse_scalar_display("bands-isolines") == ScalarDisplay::BandsAndIsolines);
    CHECK(scalar_display_name(ScalarDisplay::Isolines) == std::string("isolines"));
    CHECK_THROWS_AS(parse_scalar_display("contours"), InvalidArgument);
}

TEST_CASE("isolines follow position updates and the level-of-detail path",
          "[render][offscreen][isolines][lod]") {
    OffscreenRenderer& r = offscreen();
    MeshRenderer& renderer = r.mesh_renderer();
    Framebuffer fb;
    fb.create(kWidth, kHeight, 1);
    const Camera camera = grid_camera();
    RenderStyle style = flat_style();
    style.scalar_display = ScalarDisplay::Isolines;
    style.scalar_steps = 8;
    const double threshold = 0.5 * (0.2126 * 0.5 + 0.7152 * 0.62 + 0.0722 * 0.8);

    // update_positions keeps the scalars: squash the grid in y (x unchanged), same columns.
    HalfedgeMesh grid = make_grid(23);
    renderer.upload(grid);
    renderer.set_vertex_scalars(x_field(grid), ValueRange{0.0, 1.0}, ColorMapKind::Sequential);
    for (Vertex v : grid.vertices()) grid.position(v).y() = 0.2 + 0.6 * grid.position(v).y();
    CHECK(renderer.show(grid) == MeshRenderer::Update::Positions);
    CHECK(renderer.has_vertex_scalars());
    check_isolines(draw(renderer, fb, camera, style), camera, 8, threshold);

    // The level-of-detail path: scalars per fine vertex, kept by update_level. A decimated
    // flat grid interpolates the linear field exactly, so every level shows the same lines.
    const HalfedgeMesh fine = make_grid(23);
    NullProgress progress;
    const ProgressiveBuild pb = build_progressive_mesh(fine, DecimationOptions(), 1.0, progress);
    LevelOfDetail lod(pb.progressive);
    renderer.upload_level(lod);
    CHECK_FALSE(renderer.has_vertex_scalars());
    std::vector<double> x(lod.positions().size());
    for (std::size_t i = 0; i < x.size(); ++i) x[i] = lod.positions()[i].x();
    renderer.set_vertex_scalars(x, ValueRange{0.0, 1.0}, ColorMapKind::Sequential);
    check_isolines(draw(renderer, fb, camera, style), camera, 8, threshold);
    for (double percent : {40.0, 10.0, 60.0}) {
        INFO("level at " << percent << " %");
        lod.set_level(lod.level_for_percent(percent));
        renderer.update_level(lod);
        REQUIRE(renderer.has_vertex_scalars());
        const Image image = draw(renderer, fb, camera, style);
        dump(image, "isolines_lod_" + std::to_string(int(percent)));
        check_isolines(image, camera, 8, threshold);
    }
    CHECK(glGetError() == GL_NO_ERROR);
}
