// Renderer benchmark (not a test): in an offscreen EGL context (llvmpipe where there is no
// GPU), the median frame time of each render mode at 1280x800 for the shared bunny and a
// 1,000,000-face torus, and the time to upload changed positions (MeshRenderer::
// update_positions) and colours for the torus's 500,000 vertices, with glFinish.
//
//   trilab_render_bench [--frames N]
#include <glad/gl.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <vector>

#include "app/platform/heap_tuning.h"
#include "core/algorithms/coloring.h"
#include "core/algorithms/generators.h"
#include "core/geometry.h"
#include "core/io/mesh_io.h"
#include "render/camera.h"
#include "render/mesh_renderer.h"
#include "render/offscreen.h"

using namespace trilab;

namespace {

double median_ms(int runs, const std::function<void()>& work) {
    std::vector<double> t;
    for (int i = 0; i < runs; ++i) {
        const auto t0 = std::chrono::steady_clock::now();
        work();
        glFinish();
        t.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
                        .count());
    }
    std::sort(t.begin(), t.end());
    return t[t.size() / 2];
}

void frames(const char* label, const HalfedgeMesh& mesh, int n, MeshRenderer& renderer,
            Framebuffer& fb) {
    renderer.upload(mesh);
    Camera camera;
    camera.set_viewport(float(fb.width()), float(fb.height()));
    const BoundingBox box = bounding_box(mesh);
    camera.fit_sphere(
        glm::vec3(float(box.center().x()), float(box.center().y()), float(box.center().z())),
        float(0.5 * box.diagonal()));
    const RenderMode modes[] = {RenderMode::Smooth,     RenderMode::Flat,   RenderMode::Wireframe,
                                RenderMode::HiddenLine, RenderMode::Points, RenderMode::Textured};
    std::printf("%-6s %8zu faces:", label, mesh.n_faces());
    for (RenderMode mode : modes) {
        RenderStyle style;
        style.mode = mode;
        const double ms = median_ms(n, [&] {
            fb.bind();
            clear_background(style);
            renderer.draw(camera.view(), camera.projection(), style);
        });
        std::printf("  %s %.1f ms", render_mode_name(mode), ms);
        std::fflush(stdout);
    }
    RenderStyle overlay;
    overlay.wireframe = true;
    const double ms = median_ms(n, [&] {
        fb.bind();
        clear_background(overlay);
        renderer.draw(camera.view(), camera.projection(), overlay);
    });
    std::printf("  gouraud+overlay %.1f ms\n", ms);
}

}  // namespace

int main(int argc, char** argv) {
    tune_heap_for_large_meshes();
    int n = 20;
    for (int i = 1; i < argc; ++i) {
        if (!std::strcmp(argv[i], "--frames") && i + 1 < argc)
            n = std::max(3, std::atoi(argv[++i]));
        else {
            std::fprintf(stderr, "usage: trilab_render_bench [--frames N]\n");
            return 2;
        }
    }
    OffscreenContext context;
    std::printf("renderer benchmark: %s\nmedian of %d frames at 1280x800, glFinish included\n\n",
                context.description().c_str(), n);
    Framebuffer fb;
    fb.create(1280, 800, 1);
    MeshRenderer renderer;

    const std::string bunny = std::string(TRILAB_SHARED_DIR) + "/meshes/stanford-bunny.obj";
    if (std::filesystem::exists(bunny))
        frames("bunny", read_mesh(bunny).mesh, n, renderer, fb);
    else
        std::printf("bunny: skipped, %s is absent\n", bunny.c_str());
    HalfedgeMesh torus = make_torus(1000, 500, 1.0, 0.3);
    frames("torus", torus, n, renderer, fb);

    // Geometry-only change: positions (and recomputed normals) only.
    renderer.upload(torus);
    const double positions_ms = median_ms(n, [&] {
        for (Vertex v : torus.vertices()) torus.position(v) *= 1.0001;
        renderer.update_positions(torus);
    });
    compute_vertex_normals(torus);  // with "v:normal" present the renderer skips the normals
    const double positions_with_normals_ms = median_ms(n, [&] {
        for (Vertex v : torus.vertices()) torus.position(v) *= 1.0001;
        renderer.update_positions(torus);
    });
    const VertexColors colors = color_vertices(torus, VertexColoring::Normal);
    const double colors_ms = median_ms(n, [&] { renderer.set_vertex_colors(colors.colors); });
    const double upload_ms = median_ms(std::max(3, n / 4), [&] { renderer.upload(torus); });
    std::printf("\ntorus, %zu vertices:\n", torus.n_vertices());
    std::printf(
        "  update_positions (normals recomputed)      %6.1f ms (incl. moving the vertices)\n",
        positions_ms);
    std::printf(
        "  update_positions (mesh carries v:normal)   %6.1f ms (incl. moving the vertices)\n",
        positions_with_normals_ms);
    std::printf("  set_vertex_colors                          %6.1f ms\n", colors_ms);
    std::printf("  full upload                                %6.1f ms\n", upload_ms);
    return 0;
}
