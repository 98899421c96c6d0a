// The level-of-detail upload path (MeshRenderer::upload_level / update_level): after any
// sequence of level changes, each uploading only the index buffers and the changed vertices,
// the picture equals the one of a full upload of that level's mesh.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>

#include "core/algorithms/generators.h"
#include "core/algorithms/level_of_detail.h"
#include "render/camera.h"
#include "render/offscreen.h"
#include "render_test_util.h"
#include "test_helpers.h"

using namespace trilab;
using namespace trilab::test;

TEST_CASE("the level-of-detail path draws every level like a full upload of its mesh",
          "[render][lod]") {
    OffscreenRenderer& r = offscreen();
    MeshRenderer& full = r.mesh_renderer();
    MeshRenderer level_renderer;  // a second renderer in the same context: the LOD path only

    const HalfedgeMesh mesh = make_noisy_sphere(16, 0.15, 7);  // 2562 vertices
    NullProgress progress;
    const ProgressiveBuild pb = build_progressive_mesh(mesh, DecimationOptions(), 1.0, progress);
    LevelOfDetail lod(pb.progressive);
    REQUIRE(lod.max_level() > 2000);

    Framebuffer fb;
    fb.create(200, 150, 1);
    Camera camera;
    camera.set_viewport(200, 150);
    camera.set_view_angles(30.0f, 20.0f);
    camera.fit_sphere(glm::vec3(0.0f), 1.3f);

    RenderStyle smooth;
    RenderStyle flat;
    flat.mode = RenderMode::Flat;
    RenderStyle wire;
    wire.wireframe = true;
    RenderStyle points;
    points.mode = RenderMode::Points;

    level_renderer.upload_level(lod);
    CHECK(level_renderer.n_triangles() == mesh.n_faces());
    CHECK(level_renderer.n_vertices() == mesh.vertices_size());
    const Image fine = draw(level_renderer, fb, camera, smooth);
    full.upload(mesh);
    CHECK(mean_difference(fine, draw(full, fb, camera, smooth)) < 0.01);

    // Percentages as a slider gives them: long jumps (every normal recomputed) and short
    // steps (the changed vertices only), in both directions.
    const double percents[] = {50, 49, 48.5, 10, 100, 99.5, 1, 1.5, 3, 30, 29, 75, 2, 100};
    bool stepwise = false, recomputed = false;
    double coarse_difference = 0;
    for (double percent : percents) {
        lod.set_level(lod.level_for_percent(percent));
        (lod.all_changed() ? recomputed : stepwise) = true;
        level_renderer.update_level(lod);
        CHECK(lod.changed_vertices().empty());
        CHECK_FALSE(lod.all_changed());
        const HalfedgeMesh level_mesh = lod.mesh();
        full.upload(level_mesh);
        INFO(percent << " %: " << lod.vertices() << " vertices");
        CHECK(level_renderer.n_triangles() == level_mesh.n_faces());
        for (const RenderStyle* style : {&smooth, &flat, &wire, &points}) {
            const Image a = draw(level_renderer, fb, camera, *style);
            const Image b = draw(full, fb, camera, *style);
            INFO("mode " << render_mode_name(style->mode) << ", wireframe " << style->wireframe);
            CHECK(mean_difference(a, b) < 0.02);
            const PixelStats sa = foreground(a, style->background);
            const PixelStats sb = foreground(b, style->background);
            CHECK(sa.count == sb.count);
            CHECK(std::abs(sa.mean.r - sb.mean.r) < 1e-3);
            if (style == &smooth && percent <= 2)
                coarse_difference = std::max(coarse_difference, mean_difference(a, fine));
        }
    }
    Framebuffer::bind_default();
    CHECK(stepwise);
    CHECK(recomputed);
    // The comparison can see a level change: the coarsest levels look different.
    CHECK(coarse_difference > 0.5);

    // A mesh upload in between: update_level() starts over with a full level upload.
    level_renderer.upload(mesh);
    lod.set_level(lod.level_for_percent(20));
    level_renderer.update_level(lod);
    full.upload(lod.mesh());
    CHECK(mean_difference(draw(level_renderer, fb, camera, smooth),
                          draw(full, fb, camera, smooth)) < 0.02);
    Framebuffer::bind_default();
}
