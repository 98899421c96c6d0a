// The selection overlay (RenderStyle::selection_overlay, MeshRenderer::set_vertex_selection):
// on a flat grid facing the camera with the left half selected, the left half is tinted, the
// right half is drawn exactly as without a selection, an outline runs at x = 1/2, and with no
// weights (or the overlay off) the image is bit for bit the one without a selection.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/algorithms/coloring.h"
#include "core/algorithms/generators.h"
#include "core/errors.h"
#include "render/camera.h"
#include "render/mesh_renderer.h"
#include "render/offscreen.h"
#include "render_test_util.h"

using namespace trilab;
using namespace trilab::test;

namespace {

constexpr int kWidth = 320, kHeight = 240;

Camera grid_camera() {
    return front_grid_camera(kWidth, kHeight);
}

glm::vec2 to_pixel(const Camera& camera, double x, double y) {
    return grid_pixel(camera, x, y, kWidth, kHeight);
}

/// Weight 1 where x < 1/2 (strictly left of the middle column), 0 elsewhere.
std::vector<float> left_half(const HalfedgeMesh& grid) {
    std::vector<float> w(grid.vertices_size(), 0.0f);
    for (Vertex v : grid.vertices()) w[v.idx()] = grid.position(v).x() < 0.49 ? 1.0f : 0.0f;
    return w;
}

}  // namespace

TEST_CASE("the selection overlay tints the selection, outlines it and hides nothing else",
          "[render][offscreen][selection]") {
    OffscreenRenderer& r = offscreen();
    MeshRenderer& renderer = r.mesh_renderer();
    const HalfedgeMesh grid = make_grid(20);
    Framebuffer fb;
    fb.create(kWidth, kHeight, 1);
    const Camera camera = grid_camera();
    RenderStyle style;
    style.specular = false;

    for (bool colored : {false, true}) {
        for (bool wires : {false, true}) {
            INFO((colored ? "coloured" : "plain") << (wires ? " with wires" : ""));
            style.wireframe = wires;
            renderer.upload(grid);
            if (colored) renderer.set_vertex_colors(color_vertices(grid, VertexColoring::Mean));
            const Image before = draw(renderer, fb, camera, style);
            CHECK_FALSE(renderer.has_vertex_selection());

            // No weight anywhere: exactly the image without a selection.
            renderer.set_vertex_selection(std::vector<float>(grid.vertices_size(), 0.0f));
            CHECK(renderer.has_vertex_selection());
            CHECK(draw(renderer, fb, camera, style).rgba == before.rgba);

            renderer.set_vertex_selection(left_half(grid));
            const Image selected = draw(renderer, fb, camera, style);
            dump(selected, std::string("selection_") + (colored ? "colored" : "plain") +
                               (wires ? "_wires" : ""));
            // The overlay off: exactly as before.
            RenderStyle off = style;
            off.selection_overlay = false;
            CHECK(draw(renderer, fb, camera, off).rgba == before.rgba);

            // Right of the outline: every pixel unchanged (edges too).
            const int y = int(to_pixel(camera, 0.5, 0.37).y);
            const int x0 = int(to_pixel(camera, 0.55, 0.37).x);
            const int x1 = int(to_pixel(camera, 1.1, 0.37).x);
            for (int row = 0; row < kHeight; ++row)
                for (int x = x0; x <= x1 && x < kWidth; ++x) {
                    const std::size_t i = 4 * (std::size_t(row) * kWidth + std::size_t(x));
                    if (selected.rgba[i] != before.rgba[i] ||
                        selected.rgba[i + 1] != before.rgba[i + 1] ||
                        selected.rgba[i + 2] != before.rgba[i + 2])
                        FAIL("pixel " << x << ", " << row << " changed right of the selection");
                }
            CHECK(mean_difference(selected, before) > 1.0);
            if (wires) continue;  // the pixels below may fall on an edge
            // Left: moved towards the tint, not replaced by it.
            const int x_left = int(to_pixel(camera, 0.2, 0.37).x);
            const Rgba left_before = pixel(before, x_left, y), left = pixel(selected, x_left, y);
            const glm::vec3 tint = style.selection_tint;
            const double d_before = color_distance(left_before, tint);
            const double d_after = color_distance(left, tint);
            CHECK(d_after < d_before);
            CHECK(d_after > 0.2 * d_before);  // a tint: the colour under it still shows
            // The outline: the weight-1/2 contour (x = 0.475, halfway between the grid's
            // columns 0.45 and 0.5), in the outline colour.
            const int x_line = int(std::lround(to_pixel(camera, 0.475, 0.37).x - 0.5));
            double best = 1e9;
            for (int x = x_line - 2; x <= x_line + 2; ++x)
                best =
                    std::min(best, color_distance(pixel(selected, x, y), style.selection_outline));
            CHECK(best < 0.1);
        }
    }
    // The level of detail path, upload() and clear() drop it; a bad size is refused.
    renderer.upload(grid);
    CHECK_FALSE(renderer.has_vertex_selection());
    CHECK_THROWS_AS(renderer.set_vertex_selection(std::vector<float>(3, 1.0f)), InvalidArgument);
    CHECK(glGetError() == GL_NO_ERROR);
}
