// Categorical vertex colours (the subdivision level): every pixel of the surface shows one of
// the legend's colours, never a blend of two categories (ColorBlend::NearestCorner).
#include <algorithm>
#include <cmath>

#include "core/algorithms/coloring.h"
#include "core/algorithms/generators.h"
#include "core/algorithms/subdivision.h"
#include "core/progress.h"
#include "render/mesh_renderer.h"
#include "render/offscreen.h"
#include "render_test_util.h"

using namespace trilab;
using namespace trilab::test;

namespace {

/// An icosahedron after two Loop steps: vertices of levels 0, 1 and 2.
HalfedgeMesh subdivided_icosahedron() {
    SubdivisionOptions o;
    o.iterations = 2;
    o.keep_levels = false;
    o.morph = false;
    NullProgress progress;
    return subdivide(make_icosahedron(), o, progress).levels.back().mesh;
}

glm::vec3 to_glm(const Color& c) {
    return glm::vec3(c.x(), c.y(), c.z());
}

/// The colour as the 8-bit vertex colour buffer holds it.
glm::vec3 quantized(const glm::vec3& c) {
    return glm::round(c * 255.0f) / 255.0f;
}

/// Max-channel distance from pixel `p` to the segment from colour `a` to colour `b`.
double distance_to_mix(const Rgba& p, const glm::vec3& a, const glm::vec3& b) {
    const glm::dvec3 q(p.r, p.g, p.b), da(a), d = glm::dvec3(b) - da;
    const double len2 = glm::dot(d, d);
    const double t = len2 > 0 ? std::clamp(glm::dot(q - da, d) / len2, 0.0, 1.0) : 0.0;
    const glm::dvec3 r = glm::abs(q - (da + t * d));
    return std::max({r.x, r.y, r.z});
}

/// Max-channel distance from `p` to the nearest multiple k * c (k >= 0) of colour `c`: zero
/// for `c` under any amount of (white, unspecular) light.
double distance_to_shade(const Rgba& p, const glm::vec3& c) {
    const glm::dvec3 q(p.r, p.g, p.b), dc(c);
    const double k = std::max(glm::dot(q, dc) / glm::dot(dc, dc), 0.0);
    const glm::dvec3 r = glm::abs(q - k * dc);
    return std::max({r.x, r.y, r.z});
}

struct LegendCheck {
    std::size_t surface = 0;  ///< pixels of the mesh
    std::size_t other = 0;    ///< of these, pixels that show no legend colour
    std::vector<std::size_t> per_category;
};

/// Classifies every pixel that is not the background: which legend colour it shows, as
/// `matches(pixel, colour)` says (a distance, accepted up to 2/255).
template <class Match>
LegendCheck check_legend(const Image& image, const RenderStyle& style,
                         const std::vector<glm::vec3>& legend, Match matches) {
    LegendCheck out;
    out.per_category.assign(legend.size(), 0);
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const Rgba p = pixel(image, x, y);
            if (color_distance(p, style.background) <= 0.5 / 255.0) continue;
            ++out.surface;
            std::size_t best = legend.size();
            double best_distance = 2.0 / 255.0;
            for (std::size_t i = 0; i < legend.size(); ++i) {
                const double d = matches(p, legend[i]);
                if (d <= best_distance) {
                    best_distance = d;
                    best = i;
                }
            }
            if (best == legend.size())
                ++out.other;
            else
                ++out.per_category[best];
        }
    return out;
}

}  // namespace

TEST_CASE("categorical colours show only the legend's colours", "[render][offscreen][coloring]") {
    const HalfedgeMesh mesh = subdivided_icosahedron();
    const VertexColors colors = color_vertices(mesh, VertexColoring::SubdivisionLevel);
    REQUIRE(colors.kind == ColorMapKind::Categorical);
    REQUIRE(colors.categories.size() == 3);
    std::vector<glm::vec3> legend;
    for (const ColorCategory& c : colors.categories) legend.push_back(quantized(to_glm(c.color)));
    CHECK(color_blend(colors.kind) == ColorBlend::NearestCorner);
    CHECK(color_blend(ColorMapKind::Sequential) == ColorBlend::Interpolate);
    CHECK(color_blend(ColorMapKind::Diverging) == ColorBlend::Interpolate);

    OffscreenOptions o;
    o.width = 320;
    o.height = 240;
    o.samples = 1;  // multisampling would blend neighbours at every boundary, of any kind
    o.azimuth = 20.0f;
    o.elevation = 15.0f;
    o.vertex_colors = colors.colors;
    o.vertex_color_blend = color_blend(colors.kind);
    o.style.specular = false;
    o.style.fog = false;
    o.style.back_face_color = false;
    o.style.background = glm::vec3(1.0f, 1.0f, 1.0f);  // in no legend: white
    // Unlit: a fragment's colour is its base colour exactly.
    RenderStyle unlit = o.style;
    unlit.ambient = 1.0f;

    const auto exact = [](const Rgba& p, const glm::vec3& c) { return color_distance(p, c); };
    const auto shade = [](const Rgba& p, const glm::vec3& c) { return distance_to_shade(p, c); };
    const glm::vec3 wire = quantized(o.style.wire_color);
    const auto with_wire = [&](const Rgba& p, const glm::vec3& c) {
        return distance_to_mix(p, c, wire);
    };

    struct Case {
        const char* name;
        RenderMode mode;
        bool lit, wireframe;
    };
    for (const Case& c :
         {Case{"smooth unlit", RenderMode::Smooth, false, false},
          Case{"flat unlit", RenderMode::Flat, false, false},
          Case{"textured mode without a texture", RenderMode::Textured, false, false},
          Case{"smooth lit", RenderMode::Smooth, true, false},
          Case{"flat lit", RenderMode::Flat, true, false},
          Case{"smooth unlit with the wireframe", RenderMode::Smooth, false, true}}) {
        INFO(c.name);
        OffscreenOptions run = o;
        run.style = c.lit ? o.style : unlit;
        run.style.mode = c.mode;
        run.style.wireframe = c.wireframe;
        const Image image = offscreen().render(mesh, run);
        dump(image, std::string("categorical_") + c.name);
        const LegendCheck r = c.wireframe ? check_legend(image, run.style, legend, with_wire)
                              : c.lit     ? check_legend(image, run.style, legend, shade)
                                          : check_legend(image, run.style, legend, exact);
        REQUIRE(r.surface > 10000);
        CHECK(r.other == 0);
        for (std::size_t i = 0; i < legend.size(); ++i) {
            INFO("level " << i);
            CHECK(r.per_category[i] > r.surface / 50);
        }

        // The same colours blended across the triangles (what the viewer showed): many pixels
        // in between, in no legend.
        run.vertex_color_blend = ColorBlend::Interpolate;
        const Image blended = offscreen().render(mesh, run);
        const LegendCheck b = c.wireframe ? check_legend(blended, run.style, legend, with_wire)
                              : c.lit     ? check_legend(blended, run.style, legend, shade)
                                          : check_legend(blended, run.style, legend, exact);
        CHECK(b.other > b.surface / 4);
    }
    CHECK(glGetError() == GL_NO_ERROR);
}

TEST_CASE("set_vertex_colors keeps its blend until the colours change or go",
          "[render][offscreen][coloring]") {
    offscreen();
    MeshRenderer& renderer = offscreen().mesh_renderer();
    const HalfedgeMesh mesh = subdivided_icosahedron();
    renderer.upload(mesh);
    CHECK(renderer.vertex_color_blend() == ColorBlend::Interpolate);
    const std::vector<Color> colors(mesh.vertices_size(), Color(1, 0, 0));
    renderer.set_vertex_colors(colors, ColorBlend::NearestCorner);
    CHECK(renderer.vertex_color_blend() == ColorBlend::NearestCorner);
    renderer.set_vertex_colors(colors);  // the default: values, interpolated
    CHECK(renderer.vertex_color_blend() == ColorBlend::Interpolate);
    renderer.set_vertex_colors(colors, ColorBlend::NearestCorner);
    renderer.clear_vertex_colors();
    CHECK(renderer.vertex_color_blend() == ColorBlend::Interpolate);
    renderer.set_vertex_colors(colors, ColorBlend::NearestCorner);
    renderer.upload(mesh);  // drops the colours
    CHECK_FALSE(renderer.has_vertex_colors());
    CHECK(renderer.vertex_color_blend() == ColorBlend::Interpolate);
}
