// Offscreen rendering (EGL surfaceless + FBO, Mesa llvmpipe): every check is a statistic of
// the picture (coverage, centroid, colour averages) that fails when the picture is wrong, not
// a comparison with golden pixels.
#include <algorithm>
#include <cmath>

#include "core/algorithms/coloring.h"
#include "core/algorithms/generators.h"
#include "core/algorithms/texcoords.h"
#include "core/geometry.h"
#include "core/mesh_builder.h"
#include "render/mesh_renderer.h"
#include "render/offscreen.h"
#include "render_test_util.h"

using namespace trilab;
using namespace trilab::test;

namespace {

/// Small, fast images; no multisampling unless a test asks (exact colours at silhouettes).
OffscreenOptions small_options(int width = 320, int height = 240) {
    OffscreenOptions o;
    o.width = width;
    o.height = height;
    o.samples = 1;
    return o;
}

/// A style for counting edge pixels: white background, black lines, bright surfaces.
RenderStyle line_counting_style(RenderMode mode) {
    RenderStyle s;
    s.mode = mode;
    s.background = glm::vec3(1.0f);
    s.line_color = glm::vec3(0.0f);
    s.wire_color = glm::vec3(0.0f);
    s.wire_width = 1.5f;
    s.ambient = 0.6f;
    s.specular = false;
    return s;
}

std::size_t dark_pixels(const Image& image) {
    return pixel_stats(image,
                       [](const Rgba& p, int, int) {
                           return std::max({p.r, p.g, p.b}) < 0.3;
                       })
        .count;
}

/// r / (r + g + b): invariant under the brightness changes that lighting makes.
double red_share(const Rgba& p) {
    const double sum = p.r + p.g + p.b;
    return sum > 0 ? p.r / sum : 0.0;
}

double blue_minus_red(const Rgba& p) {
    const double sum = p.r + p.g + p.b;
    return sum > 0 ? (p.b - p.r) / sum : 0.0;
}

}  // namespace

TEST_CASE("the offscreen context runs without a window system", "[render][offscreen]") {
    OffscreenRenderer& renderer = offscreen();
    INFO(renderer.context().description());
    CHECK(renderer.context().description().find("EGL") != std::string::npos);
    CHECK(glGetString(GL_VERSION) != nullptr);
}

TEST_CASE("Framebuffer reads back top-down rows, with and without multisampling",
          "[render][offscreen]") {
    offscreen();
    for (int samples : {1, 4}) {
        Framebuffer fb;
        fb.create(64, 32, samples);
        REQUIRE(fb.is_valid());
        fb.bind();
        glClearColor(0, 0, 1, 1);
        glClear(GL_COLOR_BUFFER_BIT);
        // GL's y runs upwards: the scissor box y in [16, 32) is the image's top half.
        glEnable(GL_SCISSOR_TEST);
        glScissor(0, 16, 64, 16);
        glClearColor(1, 0, 0, 1);
        glClear(GL_COLOR_BUFFER_BIT);
        glDisable(GL_SCISSOR_TEST);
        const Image image = fb.read_rgba();
        Framebuffer::bind_default();
        INFO("samples " << samples);
        REQUIRE(image.width == 64);
        REQUIRE(image.height == 32);
        REQUIRE(image.rgba.size() == 64u * 32u * 4u);
        CHECK(pixel(image, 5, 0).r == 1.0);  // first row: top, red
        CHECK(pixel(image, 5, 0).b == 0.0);
        CHECK(pixel(image, 5, 31).b == 1.0);  // last row: bottom, blue
        CHECK(pixel(image, 5, 31).r == 0.0);
        CHECK(glGetError() == GL_NO_ERROR);
    }
    Framebuffer fb;
    CHECK_THROWS_AS(fb.create(0, 10), InvalidArgument);
    CHECK_THROWS_AS(fb.create(1 << 20, 10), InvalidArgument);
    CHECK_THROWS_AS(fb.read_rgba(), GlError);
}

TEST_CASE("a sphere at the default view covers a centred disc of the expected radius",
          "[render][offscreen]") {
    const HalfedgeMesh sphere = make_icosphere(24);  // unit sphere
    for (auto size : {glm::ivec2(320, 240), glm::ivec2(200, 300)}) {
        OffscreenOptions o = small_options(size.x, size.y);
        o.samples = 4;
        const Image image = offscreen().render(sphere, o);
        const PixelStats fg = foreground(image, o.style.background);

        // A sphere of radius 1 at distance d subtends asin(1 / d); on screen that is
        // tan(asin(1 / d)) / tan(fov / 2) of the half-height.
        const Camera camera = offscreen_camera(sphere, o);
        const double d = camera.distance();
        const double expected_radius =
            0.5 * size.y * std::tan(std::asin(1.0 / d)) / std::tan(0.5 * camera.fov_y());
        const double radius = std::sqrt(double(fg.count) / M_PI);
        INFO("size " << size.x << "x" << size.y << ": disc radius " << radius << " px, expected "
                     << expected_radius << " px");
        CHECK(radius == Approx(expected_radius).epsilon(0.03));
        CHECK(fg.cx == Approx(0.5 * size.x).margin(1.0));
        CHECK(fg.cy == Approx(0.5 * size.y).margin(1.0));
        // A disc, not an ellipse or a box: the widest row spans the diameter.
        int widest = 0;
        for (int y = 0; y < image.height; ++y) {
            int row = 0;
            for (int x = 0; x < image.width; ++x)
                row += color_distance(pixel(image, x, y), o.style.background) > 2.5 / 255.0;
            widest = std::max(widest, row);
        }
        CHECK(widest == Approx(2.0 * expected_radius).margin(3.0));
        // The framing is sensible: the box fit leaves the disc a large part of the frame.
        CHECK(2.0 * expected_radius > 0.5 * std::min(size.x, size.y));
    }
}

TEST_CASE("wireframe, hidden-line, flat and points modes differ as they should",
          "[render][offscreen]") {
    const HalfedgeMesh sphere = make_icosphere(6);
    OffscreenOptions o = small_options();
    o.azimuth = 20;
    o.elevation = 15;
    auto render = [&](RenderMode mode, bool overlay = false) {
        o.style = line_counting_style(mode);
        o.style.wireframe = overlay;
        return offscreen().render(sphere, o);
    };
    const Image flat = render(RenderMode::Flat);
    const Image smooth = render(RenderMode::Smooth);
    const Image overlay = render(RenderMode::Flat, true);
    const Image wireframe = render(RenderMode::Wireframe);
    const Image hidden = render(RenderMode::HiddenLine);
    const Image points = render(RenderMode::Points);
    dump(flat, "modes_flat");
    dump(smooth, "modes_smooth");
    dump(overlay, "modes_overlay");
    dump(wireframe, "modes_wireframe");
    dump(hidden, "modes_hidden_line");
    dump(points, "modes_points");

    const std::size_t n_pixels = std::size_t(o.width) * o.height;
    // Shaded modes without edges have no dark pixels (ambient 0.6); edges are dark.
    CHECK(dark_pixels(flat) == 0);
    CHECK(dark_pixels(smooth) == 0);
    CHECK(dark_pixels(overlay) > n_pixels / 50);
    CHECK(dark_pixels(wireframe) > n_pixels / 40);
    // Hidden-line removes the back half of the edges (a closed convex mesh: about half).
    const glm::vec3 white(1.0f);
    const double hidden_ratio =
        double(foreground(hidden, white).count) / double(foreground(wireframe, white).count);
    INFO("hidden-line / wireframe edge pixels: " << hidden_ratio);
    CHECK(hidden_ratio > 0.3);
    CHECK(hidden_ratio < 0.75);
    // The hidden-line surface is the background: only edges are not white.
    CHECK(foreground(hidden, white).count < 3 * dark_pixels(hidden));  // edges + their AA
    CHECK(foreground(hidden, white).count < foreground(flat, white).count);
    // Wireframe: the front edges are as dark as in hidden-line mode (drawn last, on top); the
    // back ones are faded towards the background.
    CHECK(double(dark_pixels(wireframe)) == Approx(double(dark_pixels(hidden))).epsilon(0.1));
    // Points cover less than the surface, but something.
    const double point_ratio =
        double(foreground(points, white).count) / double(foreground(flat, white).count);
    INFO("points / flat coverage: " << point_ratio);
    CHECK(point_ratio > 0.02);
    CHECK(point_ratio < 0.6);
    // Flat and smooth shading differ (facets) with the default lighting.
    o.style = RenderStyle();
    o.style.mode = RenderMode::Flat;
    const Image flat_default = offscreen().render(sphere, o);
    o.style.mode = RenderMode::Smooth;
    const Image smooth_default = offscreen().render(sphere, o);
    const double differ = pixel_stats(flat_default, [&](const Rgba& p, int x, int y) {
                              const Rgba q = pixel(smooth_default, x, y);
                              return color_distance(p, glm::vec3(q.r, q.g, q.b)) > 0.02;
                          }).fraction;
    INFO("flat and smooth differ in " << differ << " of the frame");
    CHECK(differ > 0.05);
}

TEST_CASE("points mode hides the points behind the surface unless asked not to",
          "[render][offscreen]") {
    const HalfedgeMesh sphere = make_icosphere(8);
    OffscreenOptions o = small_options();
    o.style.mode = RenderMode::Points;
    o.style.back_face_color = true;
    const Image occluded = offscreen().render(sphere, o);
    o.style.occlude_points = false;
    const Image all = offscreen().render(sphere, o);
    // Back-facing points are drawn in the back colour (orange: red > blue) when not occluded.
    auto orange = [&](const Image& image) {
        return pixel_stats(image,
                           [&](const Rgba& p, int, int) {
                               return color_distance(p, o.style.background) > 0.05 &&
                                      p.r > p.b + 0.1;
                           })
            .count;
    };
    dump(occluded, "points_occluded");
    dump(all, "points_all");
    // (Only back-facing points at the silhouette, which the surface does not hide, remain.)
    INFO("orange pixels: occluded " << orange(occluded) << ", all " << orange(all));
    CHECK(orange(occluded) * 10 < orange(all));
    CHECK(orange(all) > 500);
}

TEST_CASE("shape index colouring of a sphere is uniform", "[render][offscreen][color]") {
    const HalfedgeMesh sphere = make_icosphere(16);
    OffscreenOptions o = small_options();
    o.style.specular = false;
    o.vertex_colors = color_vertices(sphere, VertexColoring::ShapeIndex).colors;
    const Image image = offscreen().render(sphere, o);
    const PixelStats fg = foreground(image, o.style.background);
    REQUIRE(fg.fraction > 0.2);
    const double mean_share = red_share(fg.mean);
    const PixelStats off_hue = pixel_stats(image, [&](const Rgba& p, int, int) {
        return color_distance(p, o.style.background) > 2.5 / 255.0 &&
               std::abs(red_share(p) - mean_share) > 0.03;
    });
    INFO("mean red share " << mean_share << ", pixels off the mean hue: " << off_hue.count);
    CHECK(off_hue.count < fg.count / 100);
    CHECK(mean_share > 0.5);  // shape index +1 (a cap) is at the red end of the diverging map
}

TEST_CASE("Gaussian curvature colouring of a torus: red outside, blue inside",
          "[render][offscreen][color]") {
    const HalfedgeMesh torus = make_torus(96, 48, 1.0, 0.4);
    OffscreenOptions o = small_options(300, 300);
    o.style.specular = false;
    o.vertex_colors = color_vertices(torus, VertexColoring::Gaussian).colors;
    const Image image = offscreen().render(torus, o);  // looking down the axis (z)
    dump(image, "torus_gaussian");
    const PixelStats fg = foreground(image, o.style.background);
    // Outer silhouette radius (major + minor radius) in pixels.
    double outer = 0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
            if (color_distance(pixel(image, x, y), o.style.background) > 2.5 / 255.0)
                outer = std::max(outer, std::hypot(x + 0.5 - fg.cx, y + 0.5 - fg.cy));
    // Distance from the axis 1.4 at the silhouette, 1.0 on the ridge circle (K = 0).
    auto band = [&](double lo, double hi) {
        return pixel_stats(image, [&](const Rgba& p, int x, int y) {
            const double r = std::hypot(x + 0.5 - fg.cx, y + 0.5 - fg.cy) / outer;
            return r >= lo && r <= hi && color_distance(p, o.style.background) > 2.5 / 255.0;
        });
    };
    const PixelStats outside = band(0.82, 0.97);  // K > 0
    const PixelStats inside = band(0.35, 0.6);    // K < 0
    REQUIRE(outside.count > 500);
    REQUIRE(inside.count > 500);
    INFO("blue - red share: outside " << blue_minus_red(outside.mean) << ", inside "
                                      << blue_minus_red(inside.mean));
    // The symmetric range makes the outside pale red (K there is about half of the inside's
    // magnitude) and the inside saturated blue.
    CHECK(blue_minus_red(outside.mean) < -0.04);
    CHECK(blue_minus_red(inside.mean) > 0.1);
}

TEST_CASE("normal colouring: the right half of a sphere is redder than the left",
          "[render][offscreen][color]") {
    const HalfedgeMesh sphere = make_icosphere(16);
    OffscreenOptions o = small_options();
    o.style.specular = false;
    o.vertex_colors = color_vertices(sphere, VertexColoring::Normal).colors;
    const Image image = offscreen().render(sphere, o);
    const PixelStats fg = foreground(image, o.style.background);
    auto half = [&](bool right) {
        return pixel_stats(image, [&](const Rgba& p, int x, int) {
            return (right ? x + 0.5 > fg.cx + 5 : x + 0.5 < fg.cx - 5) &&
                   color_distance(p, o.style.background) > 2.5 / 255.0;
        });
    };
    const double left = red_share(half(false).mean), right = red_share(half(true).mean);
    INFO("red share left " << left << ", right " << right);
    CHECK(right > left + 0.1);  // n.x > 0 on the right: red = (n.x + 1) / 2 > 0.5
}

TEST_CASE("textured mode samples the texture, without coordinates it draws plain shading",
          "[render][offscreen][texture]") {
    HalfedgeMesh sphere = make_icosphere(16);
    OffscreenOptions o = small_options();
    o.azimuth = 90;  // from +x, away from the spherical projection's seam (-x)
    o.style.mode = RenderMode::Textured;
    o.texture = make_checkerboard();
    const Image untextured_textured = offscreen().render(sphere, o);
    CHECK_FALSE(offscreen().mesh_renderer().has_texcoords());
    OffscreenOptions plain = o;
    plain.style.mode = RenderMode::Smooth;
    CHECK(untextured_textured.rgba == offscreen().render(sphere, plain).rgba);

    project_texcoords(sphere, TexCoordProjection::Spherical);
    o.style.texture_mode = TextureMode::Replace;
    const Image replaced = offscreen().render(sphere, o);
    dump(replaced, "textured_replace");
    CHECK(offscreen().mesh_renderer().has_texcoords());
    const PixelStats fg = foreground(replaced, o.style.background);
    // The checker's two greys (read from the texture itself).
    const Rgba light = pixel(o.texture, 0, 0), dark = pixel(o.texture, o.texture.width - 1, 0);
    REQUIRE(light.r != dark.r);
    auto near = [&](const Rgba& c) {
        return pixel_stats(replaced,
                           [&](const Rgba& p, int, int) {
                               return color_distance(p, glm::vec3(c.r, c.g, c.b)) < 3.5 / 255.0;
                           })
            .count;
    };
    INFO("light " << near(light) << ", dark " << near(dark) << " of " << fg.count);
    CHECK(near(light) > fg.count / 5);
    CHECK(near(dark) > fg.count / 5);
    CHECK(near(light) + near(dark) > fg.count * 8 / 10);

    // Modulate: lit checker (the two greys scaled by the same shading).
    o.style.texture_mode = TextureMode::Modulate;
    const Image modulated = offscreen().render(sphere, o);
    dump(modulated, "textured_modulate");
    CHECK(modulated.rgba != replaced.rgba);
    // Off: Smooth shading exactly.
    o.style.texture_mode = TextureMode::Off;
    plain.style.mode = RenderMode::Smooth;
    CHECK(offscreen().render(sphere, o).rgba == offscreen().render(sphere, plain).rgba);
}

TEST_CASE("a z-up model with --up z looks like its y-up twin, texture projection included",
          "[render][offscreen][texture]") {
    // A tall, bent shape standing on +y, and its twin standing on +z: world (x, y, z) of the
    // z-up frame reads as (x, z, -y) in the y-up frame (core/up_axis.h).
    HalfedgeMesh y_up = make_icosphere(12);
    for (Vertex v : y_up.vertices()) {
        Point& p = y_up.position(v);
        p.y() *= 2.0;
        p.x() += 0.3 * p.y() * p.y() + 0.2 * p.z();
    }
    HalfedgeMesh z_up = y_up;
    for (Vertex v : z_up.vertices()) {
        const Point p = y_up.position(v);
        z_up.position(v) = Point(p.x(), -p.z(), p.y());
    }
    project_texcoords(y_up, TexCoordProjection::Spherical, UpAxis::Y);
    project_texcoords(z_up, TexCoordProjection::Spherical, UpAxis::Z);
    for (const auto& [az, el] : {std::pair<float, float>{0, 0}, {40, 25}}) {
        OffscreenOptions o = small_options();
        o.style.mode = RenderMode::Textured;
        o.texture = make_checkerboard();
        o.azimuth = az;
        o.elevation = el;
        const Image a = offscreen().render(y_up, o);
        o.up = UpAxis::Z;
        const Image b = offscreen().render(z_up, o);
        // Seen with +y up, the z-up twin lies on its back: a different picture.
        o.up = UpAxis::Y;
        const Image lying = offscreen().render(z_up, o);
        dump(a, "up_y");
        dump(b, "up_z");
        INFO("view " << az << "," << el << ": y-up vs z-up " << mean_difference(a, b)
                     << ", vs lying " << mean_difference(a, lying));
        CHECK(mean_difference(a, b) < 0.5);
        CHECK(mean_difference(a, lying) > 5.0);
    }
}

TEST_CASE("per-corner texture coordinates keep seams sharp", "[render][offscreen][texture]") {
    // Every triangle of a cube maps into one checker square, alternating light and dark, so
    // every vertex has corners in both kinds of square: shared vertices would smear them.
    HalfedgeMesh cube = make_cube();
    const Image checker = make_checkerboard();
    auto corner_uv = cube.add_halfedge_property<TexCoord>("h:texcoord");
    const double offsets[3][2] = {{-1.0 / 64, -1.0 / 64}, {1.0 / 64, -1.0 / 64}, {0, 1.0 / 64}};
    for (Face f : cube.faces()) {
        const double u = f.idx() % 2 == 0 ? 1.0 / 16 : 3.0 / 16, v = 1.0 / 16;
        int k = 0;
        for (Halfedge h : cube.halfedges_of(f)) {
            corner_uv[h] = TexCoord(u + offsets[k][0], v + offsets[k][1]);
            ++k;
        }
    }
    OffscreenOptions o = small_options();
    o.azimuth = 35;
    o.elevation = 25;
    o.style.mode = RenderMode::Textured;
    o.style.texture_mode = TextureMode::Replace;
    o.texture = checker;
    const Image image = offscreen().render(cube, o);
    dump(image, "seams_cube");
    CHECK(offscreen().mesh_renderer().n_gpu_vertices() > cube.n_vertices());
    // Texel of (u, v): texture coordinate (0, 0) is the image's bottom-left corner.
    auto texel = [&](double u, double v) {
        return pixel(checker, int(u * checker.width), int((1 - v) * checker.height));
    };
    const Rgba a = texel(1.0 / 16, 1.0 / 16), b = texel(3.0 / 16, 1.0 / 16);
    REQUIRE(a.r != b.r);
    const PixelStats fg = foreground(image, o.style.background);
    auto near = [&](const Rgba& c) {
        return pixel_stats(image,
                           [&](const Rgba& p, int, int) {
                               return color_distance(p, glm::vec3(c.r, c.g, c.b)) < 3.5 / 255.0;
                           })
            .count;
    };
    INFO("a " << near(a) << ", b " << near(b) << " of " << fg.count);
    CHECK(near(a) > fg.count / 10);
    CHECK(near(b) > fg.count / 10);
    CHECK(near(a) + near(b) > fg.count * 99 / 100);
}

TEST_CASE("a transparent background has alpha 0 where no surface is", "[render][offscreen]") {
    const HalfedgeMesh sphere = make_icosphere(8);
    OffscreenOptions o = small_options();
    o.transparent = true;
    o.samples = 4;
    const Image image = offscreen().render(sphere, o);
    for (auto xy : {glm::ivec2(0, 0), glm::ivec2(o.width - 1, 0), glm::ivec2(0, o.height - 1),
                    glm::ivec2(o.width - 1, o.height - 1)})
        CHECK(pixel(image, xy.x, xy.y).a == 0.0);
    CHECK(pixel(image, o.width / 2, o.height / 2).a == 1.0);
    // Un-premultiplied: the surface keeps its colour where it is opaque.
    o.transparent = false;
    const Image opaque = offscreen().render(sphere, o);
    CHECK(pixel(opaque, 0, 0).a == 1.0);
    CHECK(color_distance(pixel(opaque, o.width / 2, o.height / 2),
                         glm::vec3(pixel(image, o.width / 2, o.height / 2).r,
                                   pixel(image, o.width / 2, o.height / 2).g,
                                   pixel(image, o.width / 2, o.height / 2).b)) < 1.5 / 255.0);
    // Wireframe mode blends: edges have alpha, the rest stays transparent.
    o.transparent = true;
    o.style.mode = RenderMode::Wireframe;
    const Image wires = offscreen().render(sphere, o);
    dump(image, "transparent_gouraud");
    dump(wires, "transparent_wireframe");
    CHECK(pixel(wires, 0, 0).a == 0.0);
    CHECK(pixel_stats(wires, [](const Rgba& p, int, int) { return p.a > 0.5; }).count > 200);
}

TEST_CASE("back faces are drawn in a distinct colour", "[render][offscreen]") {
    const HalfedgeMesh grid = make_grid(8);  // open square in z = 0
    OffscreenOptions o = small_options();
    o.style.specular = false;
    auto mean_from = [&](float azimuth) {
        o.azimuth = azimuth;
        const Image image = offscreen().render(grid, o);
        return foreground(image, o.style.background).mean;
    };
    const Rgba front = mean_from(0), back = mean_from(180);
    INFO("from +z: " << front.r << " " << front.g << " " << front.b << "; from -z: " << back.r
                     << " " << back.g << " " << back.b);
    CHECK(front.b > front.r + 0.1);  // front colour (blue)
    CHECK(back.r > back.b + 0.1);    // back colour (orange)
    o.style.back_face_color = false;
    const Rgba back_plain = mean_from(180);
    CHECK(back_plain.b > back_plain.r + 0.1);
}

TEST_CASE("back faces are culled only where none can be seen, with the same image",
          "[render][offscreen]") {
    offscreen();
    MeshRenderer& renderer = offscreen().mesh_renderer();
    OffscreenOptions o = small_options();
    Framebuffer fb;
    fb.create(o.width, o.height);
    const HalfedgeMesh sphere = make_icosphere(8);
    Camera camera = offscreen_camera(sphere, o);
    auto image = [&](bool cull) {
        RenderStyle style = o.style;
        style.cull_hidden_back_faces = cull;
        Image im = draw(renderer, fb, camera, style);
        Framebuffer::bind_default();
        return im;
    };

    // A closed sphere seen from outside: culled, and not one pixel changes.
    renderer.upload(sphere);
    CHECK(renderer.culls_back_faces(camera.view(), camera.projection()));
    CHECK(mean_difference(image(true), image(false)) == 0.0);

    // The camera inside it (the near plane cuts it open): its inside shows, so no culling.
    Camera inside = camera;
    inside.zoom(200.0f);
    CHECK_FALSE(renderer.culls_back_faces(inside.view(), inside.projection()));

    // Inward oriented (every face reversed): the back faces are what is seen.
    PolygonSoup soup = to_soup(sphere);
    for (std::size_t f = 0; f < soup.n_faces(); ++f)
        std::reverse(soup.corners.begin() + std::ptrdiff_t(soup.face_offsets[f]),
                     soup.corners.begin() + std::ptrdiff_t(soup.face_offsets[f + 1]));
    LoadReport report;
    const HalfedgeMesh inverted = build_mesh(soup, report);
    REQUIRE(volume(inverted) < 0);
    renderer.upload(inverted);
    CHECK_FALSE(renderer.culls_back_faces(camera.view(), camera.projection()));

    // Open (one face removed): back faces show through the hole.
    PolygonSoup open_soup = to_soup(sphere);
    open_soup.corners.resize(open_soup.corners.size() - 3);
    open_soup.face_offsets.pop_back();
    const HalfedgeMesh open = build_mesh(open_soup, report);
    REQUIRE(open.n_faces() + 1 == sphere.n_faces());
    renderer.upload(open);
    CHECK_FALSE(renderer.culls_back_faces(camera.view(), camera.projection()));

    // Positions that turn it inside out are noticed on update.
    renderer.upload(sphere);
    HalfedgeMesh mirrored = sphere;
    for (Vertex v : mirrored.vertices()) mirrored.position(v).x() *= -1;
    renderer.update_positions(mirrored);
    CHECK_FALSE(renderer.culls_back_faces(camera.view(), camera.projection()));
}

TEST_CASE("fog fades the far side towards the background", "[render][offscreen]") {
    const HalfedgeMesh sphere = make_icosphere(16);
    OffscreenOptions o = small_options();
    const Image clear = offscreen().render(sphere, o);
    o.style.fog = true;
    o.style.fog_amount = 1.0f;
    const Image foggy = offscreen().render(sphere, o);
    dump(clear, "fog_off");
    dump(foggy, "fog_on");
    auto distance_to_background = [&](const Image& image) {
        double sum = 0;
        for (int y = 0; y < image.height; ++y)
            for (int x = 0; x < image.width; ++x)
                sum += color_distance(pixel(image, x, y), o.style.background);
        return sum;
    };
    CHECK(distance_to_background(foggy) < 0.95 * distance_to_background(clear));
    // The nearest point (the centre) is not fogged; a point near the silhouette (as deep as
    // the centre of the sphere, half-way into the fog) is.
    auto difference = [&](int x, int y) {
        const Rgba c0 = pixel(clear, x, y), c1 = pixel(foggy, x, y);
        return color_distance(c0, glm::vec3(c1.r, c1.g, c1.b));
    };
    const PixelStats fg = foreground(clear, o.style.background);
    const int rim = int(fg.cx + 0.9 * std::sqrt(double(fg.count) / M_PI));
    CHECK(difference(o.width / 2, o.height / 2) < 0.02);
    CHECK(difference(rim, o.height / 2) > difference(o.width / 2, o.height / 2) + 0.02);
    const Rgba r1 = pixel(foggy, rim, o.height / 2), r0 = pixel(clear, rim, o.height / 2);
    CHECK(color_distance(r1, o.style.background) < color_distance(r0, o.style.background));
}

TEST_CASE("face and vertex normals are drawn as segments", "[render][offscreen]") {
    const HalfedgeMesh sphere = make_icosphere(4);
    OffscreenOptions o = small_options();
    o.azimuth = 10;
    o.elevation = 10;
    auto count = [&](const Image& image, const glm::vec3& c) {
        return pixel_stats(image,
                           [&](const Rgba& p, int, int) { return color_distance(p, c) < 0.05; })
            .count;
    };
    const glm::vec3 magenta(1, 0, 1), green(0, 1, 0);
    o.style.face_normal_color = magenta;
    o.style.vertex_normal_color = green;
    o.style.vector_length = 0.1f;
    const Image none = offscreen().render(sphere, o);
    o.style.face_normals = true;
    const Image faces = offscreen().render(sphere, o);
    o.style.face_normals = false;
    o.style.vertex_normals = true;
    const Image vertices = offscreen().render(sphere, o);
    dump(faces, "vectors_faces");
    dump(vertices, "vectors_vertices");
    CHECK(count(none, magenta) == 0);
    CHECK(count(none, green) == 0);
    CHECK(count(faces, magenta) > 100);  // 320 faces, about half visible
    CHECK(count(vertices, green) > 50);  // 162 vertices
    CHECK(count(vertices, magenta) == 0);
    // Longer vectors cover more pixels.
    o.style.vector_length = 0.2f;
    CHECK(count(offscreen().render(sphere, o), green) > count(vertices, green));
}

TEST_CASE("update_positions and set_vertex_colors upload only what changed",
          "[render][offscreen]") {
    offscreen();
    MeshRenderer& renderer = offscreen().mesh_renderer();
    HalfedgeMesh sphere = make_icosphere(12);
    OffscreenOptions o = small_options();
    const Camera camera = offscreen_camera(sphere, o);
    Framebuffer fb;
    fb.create(o.width, o.height);
    auto frame = [&] {
        fb.bind();
        clear_background(o.style);
        renderer.draw(camera.view(), camera.projection(), o.style);
        Image image = fb.read_rgba();
        Framebuffer::bind_default();
        return image;
    };
    renderer.upload(sphere);
    REQUIRE(renderer.n_vertices() == sphere.vertices_size());
    REQUIRE(renderer.n_triangles() == sphere.n_faces());
    const std::size_t full = foreground(frame(), o.style.background).count;

    // Colours only: a red sphere.
    renderer.set_vertex_colors(std::vector<Color>(sphere.vertices_size(), Color(1, 0, 0)));
    const PixelStats red = foreground(frame(), o.style.background);
    CHECK(red.mean.r > 3 * red.mean.b);

    // Positions only: half the radius, a quarter of the area; the colours stay.
    for (Vertex v : sphere.vertices()) sphere.position(v) *= 0.5;
    renderer.update_positions(sphere);
    const PixelStats small = foreground(frame(), o.style.background);
    CHECK(double(small.count) / double(full) == Approx(0.25).epsilon(0.15));
    CHECK(small.mean.r > 3 * small.mean.b);
    CHECK(renderer.has_vertex_colors());

    // The vertex colours must match the vertex storage; upload() drops them.
    CHECK_THROWS_AS(renderer.set_vertex_colors(std::vector<Color>(3)), InvalidArgument);
    renderer.upload(sphere);
    CHECK_FALSE(renderer.has_vertex_colors());
    CHECK(glGetError() == GL_NO_ERROR);
}

TEST_CASE("show() uploads only what the mesh's revisions say changed", "[render][offscreen]") {
    offscreen();
    MeshRenderer& renderer = offscreen().mesh_renderer();
    using Update = MeshRenderer::Update;
    HalfedgeMesh sphere = make_icosphere(8);
    CHECK(renderer.show(sphere) == Update::Full);
    CHECK(renderer.shows(sphere));
    CHECK(renderer.show(sphere) == Update::None);
    // A copy shares the revisions: nothing to upload.
    const HalfedgeMesh copy = sphere;
    CHECK(renderer.show(copy) == Update::None);
    // Colours set on the GPU stay while nothing is uploaded or only positions are.
    renderer.set_vertex_colors(std::vector<Color>(sphere.vertices_size(), Color(1, 0, 0)));
    for (Vertex v : sphere.vertices()) sphere.position(v) *= 0.5;
    CHECK_FALSE(renderer.shows(sphere));
    CHECK(renderer.shows_topology_of(sphere));
    CHECK(renderer.show(sphere) == Update::Positions);
    CHECK(renderer.has_vertex_colors());
    CHECK(renderer.show(sphere) == Update::None);
    // New texture coordinates (attributes) and a new connectivity need a full upload, which
    // drops the colours.
    project_texcoords(sphere, TexCoordProjection::Planar);
    CHECK(renderer.show(sphere) == Update::Full);
    CHECK(renderer.has_texcoords());
    CHECK_FALSE(renderer.has_vertex_colors());
    const Edge flippable = first_flippable_edge(sphere);
    REQUIRE(flippable.is_valid());
    sphere.flip(flippable);
    CHECK(renderer.show(sphere) == Update::Full);
    // Another mesh with the same counts and positions is still another mesh.
    const HalfedgeMesh twin = make_icosphere(8);
    CHECK(renderer.show(twin) == Update::Full);
    // update_positions() of a mesh whose faces the GPU does not hold uploads it whole.
    renderer.update_positions(copy);
    CHECK(renderer.shows(copy));
    CHECK(renderer.n_triangles() == copy.n_faces());
    // Positions given apart from the mesh: the GPU holds its faces but not its geometry.
    std::vector<Point> moved = copy.positions();
    for (Point& p : moved) p *= 2.0;
    renderer.update_positions(copy, moved);
    CHECK(renderer.shows_topology_of(copy));
    CHECK_FALSE(renderer.shows(copy));
    CHECK(renderer.show(copy) == Update::Positions);
    renderer.clear();
    CHECK_FALSE(renderer.shows_topology_of(copy));
    CHECK(glGetError() == GL_NO_ERROR);
}

TEST_CASE("render_offscreen rejects bad options with clear errors", "[render][offscreen]") {
    const HalfedgeMesh sphere = make_icosphere(2);
    OffscreenOptions o = small_options();
    o.width = 0;
    CHECK_THROWS_AS(offscreen().render(sphere, o), InvalidArgument);
    o = small_options();
    o.vertex_colors.assign(5, Color(1, 1, 1));
    CHECK_THROWS_WITH(offscreen().render(sphere, o), Catch::Contains("vertex colours"));
    CHECK_THROWS_AS(parse_render_mode("shiny"), InvalidArgument);
    CHECK(parse_render_mode("hidden-line") == RenderMode::HiddenLine);
    CHECK(parse_render_mode(render_mode_name(RenderMode::Smooth)) == RenderMode::Smooth);
}
