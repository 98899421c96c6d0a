// LineRenderer, the collapsing-edges overlay: drawn over the surface and its wireframe without
// gaps (no depth fighting), thick, in a colour with an outline that reads on the surface.
#include <algorithm>
#include <cmath>
#include <functional>

#include "core/algorithms/decimation.h"
#include "core/algorithms/generators.h"
#include "core/io/mesh_io.h"
#include "render/line_renderer.h"
#include "render/mesh_renderer.h"
#include "render/offscreen.h"
#include "render_test_util.h"

using namespace trilab;
using namespace trilab::test;

namespace {

glm::vec3 to_glm(const Point& p) {
    return glm::vec3(float(p.x()), float(p.y()), float(p.z()));
}

/// Window pixel (x right, y down, as Image rows) of world point `p`.
glm::vec2 to_pixel(const Camera& camera, const glm::vec3& p, int width, int height) {
    const glm::vec4 c = camera.projection() * camera.view() * glm::vec4(p, 1.0f);
    const glm::vec2 ndc = glm::vec2(c) / c.w;
    return {(ndc.x + 1.0f) * 0.5f * float(width), (1.0f - ndc.y) * 0.5f * float(height)};
}

glm::vec3 face_normal(const HalfedgeMesh& mesh, Face f) {
    std::vector<glm::vec3> p;
    for (Vertex v : mesh.face_vertices(f)) p.push_back(to_glm(mesh.position(v)));
    return glm::normalize(glm::cross(p[1] - p[0], p[2] - p[0]));
}

/// Whether the segment from `eye` to `p` passes through a triangle of `mesh` other than
/// `skip0` and `skip1` (Moeller-Trumbore), short of p.
bool occluded(const HalfedgeMesh& mesh, const glm::vec3& eye, const glm::vec3& p, Face skip0,
              Face skip1) {
    const glm::vec3 dir = p - eye;
    for (Face f : mesh.faces()) {
        if (f == skip0 || f == skip1) continue;
        std::vector<glm::vec3> q;
        for (Vertex v : mesh.face_vertices(f)) q.push_back(to_glm(mesh.position(v)));
        const glm::vec3 e1 = q[1] - q[0], e2 = q[2] - q[0];
        const glm::vec3 h = glm::cross(dir, e2);
        const float det = glm::dot(e1, h);
        if (std::abs(det) < 1e-12f) continue;
        const glm::vec3 s = eye - q[0];
        const float u = glm::dot(s, h) / det;
        if (u < 0.0f || u > 1.0f) continue;
        const glm::vec3 qv = glm::cross(s, e1);
        const float v = glm::dot(dir, qv) / det;
        if (v < 0.0f || u + v > 1.0f) continue;
        const float t = glm::dot(e2, qv) / det;
        if (t > 0.0f && t < 0.98f) return true;
    }
    return false;
}

/// The edges the next decimation iteration collapses that the camera sees (both sides turned
/// towards the eye by at least 15 degrees) and that nothing hides, as endpoint pairs; with
/// `hidden`, those on the far side instead (both sides turned away by that much).
std::vector<std::array<glm::vec3, 2>> visible_collapses(const HalfedgeMesh& mesh,
                                                        const Camera& camera, bool hidden = false) {
    DecimationOptions o;
    o.percent = 30;
    std::vector<std::array<glm::vec3, 2>> out;
    const glm::vec3 eye = camera.eye();
    for (const auto& pair : next_collapses(mesh, o)) {
        const Halfedge h = mesh.find_halfedge(pair[0], pair[1]);
        if (!h.is_valid() || mesh.is_boundary(mesh.edge(h))) continue;
        const Face f0 = mesh.face(h), f1 = mesh.face(HalfedgeMesh::twin(h));
        const glm::vec3 a = to_glm(mesh.position(pair[0])), b = to_glm(mesh.position(pair[1]));
        const glm::vec3 to_eye = glm::normalize(eye - 0.5f * (a + b));
        const float sign = hidden ? -1.0f : 1.0f;
        if (sign * glm::dot(face_normal(mesh, f0), to_eye) < 0.25f ||
            sign * glm::dot(face_normal(mesh, f1), to_eye) < 0.25f)
            continue;
        if (hidden) {
            out.push_back({a, b});
            continue;
        }
        bool covered = false;
        for (float t : {0.2f, 0.5f, 0.8f})
            covered = covered || occluded(mesh, eye, a + t * (b - a), f0, f1);
        if (!covered) out.push_back({a, b});
    }
    return out;
}

/// One column (or row, for a steep segment) crossed by a segment: the pixel that contains
/// the crossing point and the two whose centres straddle the segment there.
struct Sample {
    int x = 0, y = 0;                    ///< the pixel under the segment
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  ///< the straddling pair
};

/// One sample per pixel column (or row) along the middle 60 % of each segment.
std::vector<Sample> along(const Camera& camera, const std::vector<std::array<glm::vec3, 2>>& s,
                          int width, int height) {
    std::vector<Sample> out;
    for (const auto& seg : s) {
        glm::vec2 a = to_pixel(camera, seg[0], width, height);
        glm::vec2 b = to_pixel(camera, seg[1], width, height);
        const bool steep = std::abs(b.y - a.y) > std::abs(b.x - a.x);
        if (steep) {  // work with x as the major axis
            std::swap(a.x, a.y);
            std::swap(b.x, b.y);
        }
        if (b.x < a.x) std::swap(a, b);
        if (b.x - a.x < 5.0f) continue;
        const float from = a.x + 0.2f * (b.x - a.x), to = a.x + 0.8f * (b.x - a.x);
        for (int i = int(std::ceil(from)); i + 0.5f <= to; ++i) {
            const float c = float(i) + 0.5f;
            const float m = a.y + (c - a.x) / (b.x - a.x) * (b.y - a.y);
            const int under = int(std::floor(m)), low = int(std::floor(m - 0.5f));
            Sample p;
            if (steep)
                p = {under, i, low, i, low + 1, i};
            else
                p = {i, under, i, low, i, low + 1};
            out.push_back(p);
        }
    }
    return out;
}

bool has_color(const Image& image, int x, int y, const glm::vec3& color) {
    return color_distance(pixel(image, x, y), color) <= 2.5 / 255.0;
}

/// How many of `samples` have a pixel other than `color` under the segment.
std::size_t count_other(const Image& image, const std::vector<Sample>& samples,
                        const glm::vec3& color) {
    std::size_t n = 0;
    for (const Sample& s : samples) n += has_color(image, s.x, s.y, color) ? 0 : 1;
    return n;
}

/// How many of `samples` have neither pixel of the straddling pair in `color`: gaps in a line
/// of any width (a one-pixel line covers one of the pair).
std::size_t count_gaps(const Image& image, const std::vector<Sample>& samples,
                       const glm::vec3& color) {
    std::size_t n = 0;
    for (const Sample& s : samples)
        n += has_color(image, s.x0, s.y0, color) || has_color(image, s.x1, s.y1, color) ? 0 : 1;
    return n;
}

/// How many of `samples` lack a pixel of `color` within 4 pixels on either side of the
/// segment (along the minor axis): an outline missing on one side.
std::size_t count_unoutlined(const Image& image, const std::vector<Sample>& samples,
                             const glm::vec3& color) {
    std::size_t n = 0;
    for (const Sample& s : samples) {
        const int dx = s.x1 - s.x0, dy = s.y1 - s.y0;  // the minor axis, one pixel
        for (int side : {-1, 1}) {
            bool found = false;
            for (int k = 1; k <= 4 && !found; ++k)
                found = has_color(image, s.x + side * k * dx, s.y + side * k * dy, color);
            if (!found) ++n;
        }
    }
    return n;
}

/// `mesh` with its wireframe, then `draw_lines`, into a `width` x `height` image.
struct OverlayScene {
    const HalfedgeMesh& mesh;
    int width = 640, height = 480;
    Camera camera;
    RenderStyle style;
    Framebuffer fb;

    explicit OverlayScene(const HalfedgeMesh& m) : mesh(m) {
        // As the viewer frames a mesh (Viewer::fit_view()): its bounding sphere about the box
        // centre fills the view, so the near plane is not close to the eye and the depth
        // buffer's resolution at the mesh is fine.
        glm::vec3 lo(1e30f), hi(-1e30f);
        for (Vertex v : mesh.vertices()) {
            lo = glm::min(lo, to_glm(mesh.position(v)));
            hi = glm::max(hi, to_glm(mesh.position(v)));
        }
        const glm::vec3 center = 0.5f * (lo + hi);
        float radius = 0.0f;
        for (Vertex v : mesh.vertices())
            radius = std::max(radius, glm::length(to_glm(mesh.position(v)) - center));
        camera.set_viewport(float(width), float(height));
        camera.fit_sphere(center, radius);
        style.wireframe = true;
        style.specular = false;
        fb.create(width, height, 1);
        offscreen().mesh_renderer().upload(mesh);
    }
    Image frame(const std::function<void()>& draw_lines) {
        fb.bind();
        clear_background(style);
        offscreen().mesh_renderer().draw(camera.view(), camera.projection(), style);
        draw_lines();
        Image image = fb.read_rgba();
        Framebuffer::bind_default();
        return image;
    }
};

}  // namespace

TEST_CASE("collapsing edges draw over the surface and its wireframe without gaps",
          "[render][offscreen][overlay]") {
    offscreen();
    std::vector<std::pair<std::string, HalfedgeMesh>> meshes;
    // Bumps: valley edges, where the surface beside the edge is nearer to the eye than the
    // edge itself, are where a small depth offset loses to the surface.
    meshes.emplace_back("noisy sphere", make_noisy_sphere(6, 0.04, 7));
    const std::string spot = shared_mesh("spot.obj");
    if (present_or_skip(spot)) meshes.emplace_back("spot", read_mesh(spot).mesh);

    for (const auto& [name, mesh] : meshes) {
        INFO(name);
        OverlayScene scene(mesh);
        const auto segments = visible_collapses(mesh, scene.camera);
        REQUIRE(segments.size() >= 5);
        std::vector<glm::vec3> endpoints;
        for (const auto& s : segments) endpoints.insert(endpoints.end(), s.begin(), s.end());
        LineRenderer lines;
        lines.set_segments(endpoints);
        REQUIRE(lines.n_segments() == segments.size());
        const std::vector<Sample> middle = along(scene.camera, segments, scene.width, scene.height);
        REQUIRE(middle.size() > 50);

        // The viewer's call: a given colour and width.
        const glm::vec3 red(0.95f, 0.25f, 0.20f);
        const Image given = scene.frame(
            [&] { lines.draw(scene.camera.view(), scene.camera.projection(), red, 2.0f); });
        dump(given, "collapsing_edges_given_color_" + name);
        INFO(middle.size() << " pixels sampled along " << segments.size() << " edges");
        CHECK(count_gaps(given, middle, red) == 0);

        // The default style: every pixel under each edge has the line's colour, and the
        // outline borders it on both sides.
        const LineStyle style;
        const Image image =
            scene.frame([&] { lines.draw(scene.camera.view(), scene.camera.projection()); });
        dump(image, "collapsing_edges_" + name);
        CHECK(count_other(image, middle, style.color) == 0);
        // (Where two edges lie side by side, one's core may cover the other's outline.)
        CHECK(count_unoutlined(image, middle, style.outline_color) <= middle.size() / 50);

        // Depth tested all the same: the edges on the far side do not show through.
        const auto behind = visible_collapses(mesh, scene.camera, true);
        REQUIRE(behind.size() >= 5);
        std::vector<glm::vec3> behind_endpoints;
        for (const auto& s : behind)
            behind_endpoints.insert(behind_endpoints.end(), s.begin(), s.end());
        lines.set_segments(behind_endpoints);
        const Image back =
            scene.frame([&] { lines.draw(scene.camera.view(), scene.camera.projection()); });
        const std::vector<Sample> hidden = along(scene.camera, behind, scene.width, scene.height);
        REQUIRE(hidden.size() > 50);
        CHECK(count_other(back, hidden, style.color) == hidden.size());
        CHECK(count_other(back, hidden, style.outline_color) == hidden.size());
    }
    CHECK(glGetError() == GL_NO_ERROR);
}

TEST_CASE("the overlay's default colour stands apart from the scene's default colours",
          "[render][overlay]") {
    const LineStyle line;
    const RenderStyle scene;
    auto distance = [](const glm::vec3& a, const glm::vec3& b) {
        const glm::vec3 d = glm::abs(a - b);
        return std::max({d.x, d.y, d.z});
    };
    // The background, the wireframe (near black) and the surface (light blue), and the
    // outline against the colour: at least 0.45 apart in some channel.
    for (const glm::vec3& c : {scene.background, scene.wire_color, scene.line_color,
                               scene.front_color, line.outline_color})
        CHECK(distance(line.color, c) >= 0.45f);
    CHECK(line.width > 1.0f);  // thicker than the default wireframe (1 pixel)
    CHECK(line.width >= 2.0f * std::max(scene.wire_width, 1.0f));
}
