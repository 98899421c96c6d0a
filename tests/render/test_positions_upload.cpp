// MeshRenderer::update_positions with positions given apart from the mesh (morph frames):
// the picture equals the one of a mesh that carries those positions.
#include <catch2/catch.hpp>

#include <cmath>

#include "core/algorithms/generators.h"
#include "render/camera.h"
#include "render/offscreen.h"
#include "render_test_util.h"
#include "test_helpers.h"

using namespace trilab;
using namespace trilab::test;

TEST_CASE("update_positions with separate positions draws like a moved mesh", "[render]") {
    OffscreenRenderer& r = offscreen();
    MeshRenderer& renderer = r.mesh_renderer();
    const HalfedgeMesh sphere = make_icosphere(8);
    std::vector<Point> positions = sphere.positions();
    for (Point& p : positions)
        p = Point(1.6 * p.x(), 0.7 * p.y(), p.z() + 0.2 * std::sin(4 * p.x()));
    HalfedgeMesh moved = sphere;
    moved.positions() = positions;

    Framebuffer fb;
    fb.create(160, 120, 1);
    Camera camera;
    camera.set_viewport(160, 120);
    camera.fit_sphere(glm::vec3(0.0f), 1.8f);

    renderer.upload(moved);
    const Image expected = draw(renderer, fb, camera);
    renderer.upload(sphere);
    const Image unmoved = draw(renderer, fb, camera);
    renderer.update_positions(sphere, positions);
    const Image morphed = draw(renderer, fb, camera);
    Framebuffer::bind_default();

    REQUIRE(mean_difference(unmoved, expected) > 2.0);  // the shapes differ on screen
    REQUIRE(mean_difference(morphed, expected) < 0.01);
    REQUIRE_THROWS_AS(renderer.update_positions(sphere, std::vector<Point>(3)), InvalidArgument);
}
