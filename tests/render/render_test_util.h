#pragma once
// Helpers for the renderer tests: one headless GL context for the whole test run, and image
// statistics (coverage, centroid, colour averages) so that tests check properties of the
// picture rather than golden pixels.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <functional>
#include <memory>
#include <string>

#include "core/errors.h"
#include "render/camera.h"
#include "render/mesh_renderer.h"
#include "render/offscreen.h"
#include "test_helpers.h"
#include "tests/support/fp_traps.h"

namespace trilab::test {

/// The shared offscreen renderer, created on first use with Mesa's software rasteriser
/// (LIBGL_ALWAYS_SOFTWARE=1 unless the environment says otherwise), so results do not depend
/// on a GPU. No X server or DISPLAY is involved. If EGL cannot be initialised the calling
/// test FAILS with the reason: CI is expected to have Mesa (libegl1, libgl1-mesa-dri).
/// Mesa's llvmpipe raises floating-point exceptions inside its own code, so from the first GL
/// use on, this process runs without floating-point traps (tests/support/fp_traps.h). Each
/// test case is its own process under CTest: only the GL test cases run without them.
inline OffscreenRenderer& offscreen() {
    disable_fp_traps();
    static OffscreenRenderer* renderer = nullptr;  // never deleted: lives until exit
    static std::string error;
    static bool tried = false;
    if (!tried) {
        tried = true;
        ::setenv("LIBGL_ALWAYS_SOFTWARE", "1", 0);
        try {
            renderer = new OffscreenRenderer();
        } catch (const std::exception& e) {
            error = e.what();
        }
    }
    if (!renderer) FAIL("cannot create the EGL offscreen context: " << error);
    renderer->context().make_current();
    return *renderer;
}

/// Writes `image` to $TRILAB_TEST_IMAGES/NAME.png when that variable names a folder (for
/// looking at what a failing test saw); does nothing otherwise.
inline void dump(const Image& image, const std::string& name) {
    const char* dir = std::getenv("TRILAB_TEST_IMAGES");
    if (dir && *dir) write_png(image, std::string(dir) + "/" + name + ".png");
}

struct Rgba {
    double r = 0, g = 0, b = 0, a = 0;  ///< in [0, 1]
};

inline Rgba pixel(const Image& image, int x, int y) {
    const std::size_t i = 4 * (std::size_t(y) * std::size_t(image.width) + std::size_t(x));
    return {image.rgba[i] / 255.0, image.rgba[i + 1] / 255.0, image.rgba[i + 2] / 255.0,
            image.rgba[i + 3] / 255.0};
}

/// Largest per-channel difference of the colour (not alpha).
inline double color_distance(const Rgba& p, const glm::vec3& c) {
    return std::max({std::abs(p.r - c.r), std::abs(p.g - c.g), std::abs(p.b - c.b)});
}

/// Statistics over the pixels that `select` accepts.
struct PixelStats {
    std::size_t count = 0;
    double fraction = 0;    ///< count / all pixels
    double cx = 0, cy = 0;  ///< centroid (pixel centres, y down)
    Rgba mean;
};

inline PixelStats pixel_stats(const Image& image,
                              const std::function<bool(const Rgba&, int, int)>& select) {
    PixelStats s;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const Rgba p = pixel(image, x, y);
            if (!select(p, x, y)) continue;
            ++s.count;
            s.cx += x + 0.5;
            s.cy += y + 0.5;
            s.mean.r += p.r;
            s.mean.g += p.g;
            s.mean.b += p.b;
            s.mean.a += p.a;
        }
    s.fraction = double(s.count) / (double(image.width) * image.height);
    if (s.count > 0) {
        const double n = double(s.count);
        s.cx /= n;
        s.cy /= n;
        s.mean = {s.mean.r / n, s.mean.g / n, s.mean.b / n, s.mean.a / n};
    }
    return s;
}

/// Pixels that differ from the background colour (the drawn mesh).
inline PixelStats foreground(const Image& image, const glm::vec3& background) {
    return pixel_stats(image, [&](const Rgba& p, int, int) {
        return color_distance(p, background) > 2.5 / 255.0;
    });
}

/// `renderer`'s mesh drawn into `fb` from `camera` with `style`, read back.
inline Image draw(const MeshRenderer& renderer, Framebuffer& fb, const Camera& camera,
                  const RenderStyle& style = {}) {
    fb.bind();
    clear_background(style);
    renderer.draw(camera.view(), camera.projection(), style);
    return fb.read_rgba();
}

/// Mean absolute difference of two images of the same size, per channel byte (0 to 255).
inline double mean_difference(const Image& a, const Image& b) {
    double sum = 0;
    for (std::size_t i = 0; i < a.rgba.size(); ++i)
        sum += std::abs(int(a.rgba[i]) - int(b.rgba[i]));
    return sum / double(a.rgba.size());
}

/// The unit grid [0, 1]^2 (z = 0) seen from the front in a width x height image, filling most
/// of it.
inline Camera front_grid_camera(int width, int height) {
    Camera camera;
    camera.set_viewport(float(width), float(height));
    camera.set_view_angles(0.0f, 0.0f);
    camera.fit_sphere(glm::vec3(0.5f, 0.5f, 0.0f), 0.6f);
    return camera;
}

/// Pixel coordinates (x right, y down, pixel centres at +0.5) of the grid point (x, y, 0) in a
/// width x height image.
inline glm::vec2 grid_pixel(const Camera& camera, double x, double y, int width, int height) {
    const glm::vec4 c =
        camera.projection() * camera.view() * glm::vec4(float(x), float(y), 0.0f, 1.0f);
    return {(c.x / c.w * 0.5f + 0.5f) * width, (0.5f - c.y / c.w * 0.5f) * height};
}

}  // namespace trilab::test
