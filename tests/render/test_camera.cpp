// Camera math: fitting, orthonormal rotations, view angles, no flips at the poles, and the
// ray through a pixel that picking casts.
#include <cmath>
#include <glm/gtc/matrix_access.hpp>
#include <random>

#include "core/algorithms/generators.h"
#include "core/algorithms/ray_pick.h"
#include "core/mesh_builder.h"
#include "render/camera.h"
#include "test_helpers.h"

using namespace trilab;

namespace {

/// Normalized device coordinates of a world point.
glm::vec3 ndc(const Camera& camera, const glm::vec3& p) {
    const glm::vec4 c = camera.projection() * camera.view() * glm::vec4(p, 1.0f);
    REQUIRE(c.w > 0.0f);  // in front of the camera
    return glm::vec3(c) / c.w;
}

glm::vec3 corner(const glm::vec3& lo, const glm::vec3& hi, int i) {
    return {(i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z};
}

/// The largest |x| or |y| NDC coordinate of the box corners; also checks depth is in range.
float box_extent_ndc(const Camera& camera, const glm::vec3& lo, const glm::vec3& hi) {
    float extent = 0.0f;
    for (int i = 0; i < 8; ++i) {
        const glm::vec3 q = ndc(camera, corner(lo, hi, i));
        CHECK(q.z > -1.0f);  // between the near and far planes
        CHECK(q.z < 1.0f);
        extent = std::max({extent, std::abs(q.x), std::abs(q.y)});
    }
    return extent;
}

/// Angle in degrees between two rotations.
float angle_between(const glm::quat& a, const glm::quat& b) {
    const float d = std::min(1.0f, std::abs(glm::dot(glm::normalize(a), glm::normalize(b))));
    return glm::degrees(2.0f * std::acos(d));
}

void require_orthonormal(const glm::mat4& view) {
    const glm::mat3 r(view);
    const glm::mat3 rrt = r * glm::transpose(r);
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) REQUIRE(std::abs(rrt[i][j] - (i == j ? 1.0f : 0.0f)) < 1e-4f);
    REQUIRE(std::abs(glm::determinant(r) - 1.0f) < 1e-4f);
}

}  // namespace

TEST_CASE("Camera::fit_box keeps the box in view from every direction", "[camera]") {
    const glm::vec3 lo(-2.0f, 0.5f, -1.0f), hi(3.0f, 1.5f, 4.0f);
    for (auto size : {glm::vec2(1280, 800), glm::vec2(400, 900), glm::vec2(500, 500)}) {
        for (float az = 0; az < 360; az += 45)
            for (float el = -90; el <= 90; el += 30) {
                Camera camera;
                camera.set_viewport(size.x, size.y);
                camera.set_view_angles(az, el);
                camera.fit_box(lo, hi);
                INFO("viewport " << size.x << "x" << size.y << " view " << az << "," << el);
                const glm::vec3 center = 0.5f * (lo + hi);
                const glm::vec3 c = ndc(camera, center);
                CHECK(std::abs(c.x) < 1e-4f);  // centred
                CHECK(std::abs(c.y) < 1e-4f);
                CHECK(box_extent_ndc(camera, lo, hi) < 1.0f);
            }
    }
}

TEST_CASE("Camera::fit_box_in_view frames the box tightly", "[camera]") {
    const glm::vec3 lo(-1.0f, -0.2f, -0.5f), hi(1.0f, 0.8f, 0.5f);
    for (auto size : {glm::vec2(1280, 800), glm::vec2(300, 700)})
        for (float az : {0.0f, 30.0f, 135.0f})
            for (float el : {-60.0f, 0.0f, 20.0f, 90.0f}) {
                Camera camera;
                camera.set_viewport(size.x, size.y);
                camera.set_view_angles(az, el);
                camera.fit_box_in_view(lo, hi, 0.04f);
                INFO("viewport " << size.x << "x" << size.y << " view " << az << "," << el);
                // Every corner inside the view, the outermost exactly at the margin.
                const float extent = box_extent_ndc(camera, lo, hi);
                CHECK(extent == Approx(0.96f).epsilon(1e-3));
                // Tighter than (or as tight as) the bounding-sphere fit.
                Camera loose = camera;
                loose.fit_box(lo, hi);
                CHECK(camera.distance() <= loose.distance() * 1.0001f);
            }
}

TEST_CASE("Camera::fit_points_in_view centres the points' projection with the margin", "[camera]") {
    std::mt19937 rng(3);
    std::normal_distribution<float> g(0.0f, 1.0f);
    std::vector<glm::vec3> points;
    for (int i = 0; i < 500; ++i) points.emplace_back(3 * g(rng) + 5, g(rng) - 2, 0.5f * g(rng));
    for (auto size : {glm::vec2(1280, 800), glm::vec2(300, 700)})
        for (float az : {0.0f, 50.0f, 200.0f})
            for (float el : {-30.0f, 10.0f, 90.0f}) {
                Camera camera;
                camera.set_viewport(size.x, size.y);
                camera.set_view_angles(az, el);
                camera.fit_points_in_view(points, 0.1f);
                INFO("viewport " << size.x << "x" << size.y << " view " << az << "," << el);
                glm::vec2 lo(1e9f), hi(-1e9f);
                for (const glm::vec3& p : points) {
                    const glm::vec3 q = ndc(camera, p);
                    REQUIRE(q.z > -1.0f);
                    REQUIRE(q.z < 1.0f);
                    lo = glm::min(lo, glm::vec2(q));
                    hi = glm::max(hi, glm::vec2(q));
                }
                CHECK(hi.x <= 0.9001f);
                CHECK(hi.y <= 0.9001f);
                CHECK(lo.x >= -0.9001f);
                CHECK(lo.y >= -0.9001f);
                // One axis is the limiting one: its extremes touch the margin on both sides.
                const bool x_limits = hi.x > 0.8999f && lo.x < -0.8999f;
                const bool y_limits = hi.y > 0.8999f && lo.y < -0.8999f;
                CHECK((x_limits || y_limits));
                // The other axis is centred.
                if (x_limits) CHECK(hi.y + lo.y == Approx(0.0f).margin(1e-3));
                if (y_limits) CHECK(hi.x + lo.x == Approx(0.0f).margin(1e-3));
                require_orthonormal(camera.view());
            }
}

TEST_CASE("Camera rotations stay orthonormal after many trackball drags", "[camera]") {
    Camera camera;
    camera.set_viewport(1280, 800);
    camera.fit_sphere(glm::vec3(1, 2, 3), 2.0f);
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> x(0, 1280), y(0, 800);
    for (int i = 0; i < 2000; ++i) camera.rotate({x(rng), y(rng)}, {x(rng), y(rng)});
    require_orthonormal(camera.view());
    REQUIRE(std::abs(glm::length(camera.rotation()) - 1.0f) < 1e-5f);
    // The target stays in the middle of the view.
    const glm::vec3 c = ndc(camera, camera.target());
    REQUIRE(std::abs(c.x) < 1e-4f);
    REQUIRE(std::abs(c.y) < 1e-4f);
}

TEST_CASE("Camera::set_view_angles looks from the stated direction", "[camera]") {
    struct Case {
        float az, el;
        glm::vec3 eye_dir, screen_up;
    };
    const Case cases[] = {
        {0, 0, {0, 0, 1}, {0, 1, 0}},    {90, 0, {1, 0, 0}, {0, 1, 0}},
        {180, 0, {0, 0, -1}, {0, 1, 0}}, {-90, 0, {-1, 0, 0}, {0, 1, 0}},
        {0, 90, {0, 1, 0}, {0, 0, -1}},  {0, -90, {0, -1, 0}, {0, 0, 1}},
    };
    for (const Case& c : cases) {
        Camera camera;
        camera.set_view_angles(c.az, c.el);
        INFO("view " << c.az << "," << c.el);
        const glm::vec3 eye = glm::normalize(camera.eye() - camera.target());
        CHECK(glm::length(eye - c.eye_dir) < 1e-5f);
        // The camera's up axis (second row of the view rotation) in world coordinates.
        const glm::vec3 up = glm::vec3(glm::row(camera.view(), 1));
        CHECK(glm::length(up - c.screen_up) < 1e-5f);
        require_orthonormal(camera.view());
    }
    // Elsewhere world +y projects upwards on the screen (positive second view-row component).
    Camera camera;
    camera.set_view_angles(37, 41);
    CHECK(glm::row(camera.view(), 1).y > 0.5f);
}

TEST_CASE("Camera view angles and the default view follow the up axis", "[camera]") {
    struct Case {
        float az, el;
        glm::vec3 eye_dir, screen_up;
    };
    // z-up: azimuth around +z from the front (-y), elevation above the xy plane.
    const Case cases[] = {
        {0, 0, {0, -1, 0}, {0, 0, 1}},
        {90, 0, {1, 0, 0}, {0, 0, 1}},
        {180, 0, {0, 1, 0}, {0, 0, 1}},
        {0, 90, {0, 0, 1}, {0, 1, 0}},
    };
    for (const Case& c : cases) {
        Camera camera;
        camera.set_view_angles(c.az, c.el, UpAxis::Z);
        INFO("z-up view " << c.az << "," << c.el);
        const glm::vec3 eye = glm::normalize(camera.eye() - camera.target());
        CHECK(glm::length(eye - c.eye_dir) < 1e-5f);
        const glm::vec3 up = glm::vec3(glm::row(camera.view(), 1));
        CHECK(glm::length(up - c.screen_up) < 1e-5f);
        require_orthonormal(camera.view());
    }
    // The default view: the up axis is the screen's up vector, the front faces the camera.
    for (const UpAxis axis : {UpAxis::Y, UpAxis::Z}) {
        INFO("up " << up_axis_name(axis));
        Camera camera;
        camera.set_view_angles(30, 20);
        camera.reset_rotation(axis);
        const Vector3 u = up_vector(axis), f = front_vector(axis);
        const glm::vec3 up = glm::vec3(glm::row(camera.view(), 1));
        CHECK(glm::length(up - glm::vec3(float(u.x()), float(u.y()), float(u.z()))) < 1e-5f);
        const glm::vec3 eye = glm::normalize(camera.eye() - camera.target());
        CHECK(glm::length(eye - glm::vec3(float(f.x()), float(f.y()), float(f.z()))) < 1e-5f);
    }
    // y-up is the identity rotation, as before.
    Camera camera;
    camera.reset_rotation();
    CHECK(angle_between(camera.rotation(), glm::quat(1, 0, 0, 0)) < 1e-3f);
}

TEST_CASE("Camera has no gimbal flip at the poles", "[camera]") {
    SECTION("view angles through the pole change the rotation continuously") {
        Camera camera;
        camera.set_view_angles(30, 80);
        glm::quat previous = camera.rotation();
        for (float el = 80.5f; el <= 100.0f; el += 0.5f) {
            camera.set_view_angles(30, el);
            INFO("elevation " << el);
            REQUIRE(angle_between(previous, camera.rotation()) < 0.51f);
            previous = camera.rotation();
        }
    }
    SECTION("dragging the trackball over the top turns smoothly by a full circle") {
        Camera camera;
        camera.set_viewport(800, 800);
        camera.fit_sphere(glm::vec3(0), 1.0f);
        glm::quat previous = camera.rotation();
        glm::vec3 previous_up = glm::vec3(glm::row(camera.view(), 1));
        float total = 0;
        // Small vertical drags through the centre: each one a rotation about the x axis.
        for (int i = 0; i < 400; ++i) {
            camera.rotate({400, 405}, {400, 395});
            const float step = angle_between(previous, camera.rotation());
            const glm::vec3 up = glm::vec3(glm::row(camera.view(), 1));
            INFO("step " << i);
            REQUIRE(step < 2.0f);
            REQUIRE(glm::dot(up, previous_up) > 0.99f);  // no sudden flip of the screen's up
            total += step;
            previous = camera.rotation();
            previous_up = up;
        }
        CHECK(total > 360.0f);  // went over the pole (and round) without trouble
        require_orthonormal(camera.view());
    }
}

TEST_CASE("Camera zoom is clamped and pan keeps the distance", "[camera]") {
    Camera camera;
    camera.set_viewport(640, 480);
    camera.fit_sphere(glm::vec3(0), 2.0f);
    const float d = camera.distance();
    camera.zoom(1000.0f);
    CHECK(camera.distance() >= 2.0f * 1e-3f * 0.999f);
    camera.zoom(-2000.0f);
    CHECK(camera.distance() <= 2.0f * 1e3f * 1.001f);
    Camera panned;
    panned.set_viewport(640, 480);
    panned.fit_sphere(glm::vec3(0), 2.0f);
    panned.pan({100, 0});
    CHECK(panned.distance() == Approx(d));
    // Dragging right moves the scene right: the old target moves to positive NDC x.
    CHECK(ndc(panned, glm::vec3(0)).x > 0.1f);
}

TEST_CASE("Camera::reframe_for_viewport keeps what the view shows in the picture", "[camera]") {
    Camera view;
    view.set_viewport(900, 600);  // a view 1.5 : 1
    view.set_view_angles(30, 20);
    view.fit_sphere(glm::vec3(0.2f, -0.1f, 0.3f), 1.0f);
    view.pan(glm::vec2(40, -25));
    // Points on the view's edges: the middle of the left and right edges, of the top and
    // bottom edges, at the target's depth.
    const glm::mat4 inverse = glm::inverse(view.projection() * view.view());
    const glm::vec3 target_ndc = ndc(view, view.target());
    auto unproject = [&](float x, float y) {
        const glm::vec4 p = inverse * glm::vec4(x, y, target_ndc.z, 1.0f);
        return glm::vec3(p) / p.w;
    };
    const glm::vec3 left = unproject(-1, 0), right = unproject(1, 0);
    const glm::vec3 top = unproject(0, 1), bottom = unproject(0, -1);
    SECTION("a wider picture: the same height, room at the sides") {
        Camera picture = view;
        picture.reframe_for_viewport(1920, 1080);
        CHECK(ndc(picture, top).y == Approx(1.0f).margin(1e-4));
        CHECK(ndc(picture, bottom).y == Approx(-1.0f).margin(1e-4));
        CHECK(ndc(picture, right).x == Approx(1.5f / (1920.0f / 1080.0f)).margin(1e-4));
        CHECK(ndc(picture, left).x == Approx(-1.5f / (1920.0f / 1080.0f)).margin(1e-4));
        CHECK(picture.pixels_per_unit() == Approx(view.pixels_per_unit() * 1080.0f / 600.0f));
    }
    SECTION("a narrower picture: the same width, room at the top and bottom") {
        Camera picture = view;
        picture.reframe_for_viewport(800, 800);
        CHECK(ndc(picture, right).x == Approx(1.0f).margin(1e-4));
        CHECK(ndc(picture, left).x == Approx(-1.0f).margin(1e-4));
        CHECK(ndc(picture, top).y == Approx(1.0f / 1.5f).margin(1e-4));
        CHECK(ndc(picture, bottom).y == Approx(-1.0f / 1.5f).margin(1e-4));
        CHECK(picture.pixels_per_unit() == Approx(view.pixels_per_unit() * 800.0f / 900.0f));
    }
}

TEST_CASE("Camera::pixels_per_unit is a unit segment's length on the screen", "[camera]") {
    Camera camera;
    camera.set_viewport(1280, 800);
    camera.fit_sphere(glm::vec3(0.0f), 2.0f);
    camera.zoom(3.0f);
    // A unit segment at the target, across the view direction.
    const glm::vec3 right = glm::conjugate(camera.rotation()) * glm::vec3(1, 0, 0);
    const float a = ndc(camera, camera.target()).x, b = ndc(camera, camera.target() + right).x;
    CHECK(0.5f * (b - a) * 1280.0f == Approx(camera.pixels_per_unit()).epsilon(1e-4));
}

TEST_CASE("Camera::ray_through meets the world point drawn at that pixel", "[camera][pick]") {
    Camera camera;
    camera.set_viewport(800, 500);
    camera.fit_box(glm::vec3(-1), glm::vec3(1));
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> angle(-180.0f, 180.0f), unit(-1.0f, 1.0f);
    for (int trial = 0; trial < 20; ++trial) {
        camera.set_view_angles(angle(rng), angle(rng) / 2.0f);
        const glm::vec3 p(unit(rng), unit(rng), unit(rng));
        const glm::vec3 q = ndc(camera, p);
        const glm::vec2 window((q.x + 1.0f) * 0.5f * 800.0f, (1.0f - q.y) * 0.5f * 500.0f);
        glm::dvec3 origin, direction;
        camera.ray_through(window, origin, direction);
        // The ray passes through p: p - origin is parallel to the direction.
        const glm::dvec3 to_p = glm::dvec3(p) - origin;
        const double along = glm::dot(to_p, glm::normalize(direction));
        CHECK(glm::length(to_p - along * glm::normalize(direction)) < 1e-4);
        CHECK(along > 0.0);
        // t is the depth along the view axis: between the near and far planes.
        const double t = along / glm::length(direction);
        CHECK(t > camera.near_plane());
        CHECK(t < camera.far_plane());
    }
}

TEST_CASE("Camera::set_target brings the point to the centre and keeps the rotation", "[camera]") {
    Camera camera;
    camera.set_viewport(640, 480);
    camera.fit_box(glm::vec3(-1), glm::vec3(1));
    camera.set_view_angles(30.0f, 20.0f);
    const glm::quat rotation = camera.rotation();
    const float distance = camera.distance();
    const glm::vec3 point(0.5f, -0.25f, 0.75f);
    camera.set_target(point);
    const glm::vec3 q = ndc(camera, point);
    CHECK(std::abs(q.x) < 1e-5f);
    CHECK(std::abs(q.y) < 1e-5f);
    CHECK(camera.distance() == distance);
    CHECK(camera.rotation() == rotation);
}

TEST_CASE(
    "picking through the camera: the face under a pixel, back faces, the silhouette, the "
    "background",
    "[camera][pick]") {
    // A unit sphere filling the view from +z, and a single triangle facing away.
    const HalfedgeMesh sphere = make_icosphere(20);
    Camera camera;
    camera.set_viewport(400, 400);
    camera.fit_box(glm::vec3(-1), glm::vec3(1));
    const auto ray_at = [&](float x, float y) {
        glm::dvec3 o, d;
        camera.ray_through(glm::vec2(x, y), o, d);
        Ray ray;
        ray.origin = Point(o.x, o.y, o.z);
        ray.direction = Vector3(d.x, d.y, d.z);
        return ray;
    };
    // The centre pixel: the front of the sphere, facing the camera.
    auto hit = pick_face(sphere, sphere.positions(), ray_at(200.5f, 200.5f), camera.near_plane());
    REQUIRE(hit);
    CHECK(hit->position.z() > 0.99);
    CHECK_FALSE(hit->back_face);
    // The hit point projects back onto that pixel.
    const glm::vec3 q = ndc(camera, glm::vec3(float(hit->position.x()), float(hit->position.y()),
                                              float(hit->position.z())));
    CHECK(std::abs((q.x + 1.0f) * 200.0f - 200.5f) < 0.01f);
    CHECK(std::abs((1.0f - q.y) * 200.0f - 200.5f) < 0.01f);
    // The silhouette along the row through the centre: the last pixel that hits and the first
    // that misses straddle the sphere's outline (its projected radius, from the hit points).
    int last_hit = -1;
    for (int x = 200; x < 400; ++x)
        if (pick_face(sphere, sphere.positions(), ray_at(x + 0.5f, 200.5f)))
            last_hit = x;
        else
            break;
    REQUIRE(last_hit > 200);
    REQUIRE(last_hit < 399);  // the background is reached before the edge of the view
    const auto edge_hit = pick_face(sphere, sphere.positions(), ray_at(last_hit + 0.5f, 200.5f));
    REQUIRE(edge_hit);
    CHECK(std::abs(edge_hit->position.z()) < 0.35);  // grazing: near the outline
    for (int x = last_hit + 1; x < 400; x += 7)
        CHECK_FALSE(pick_face(sphere, sphere.positions(), ray_at(x + 0.5f, 200.5f)));
    // The corner of the view: the background.
    CHECK_FALSE(pick_face(sphere, sphere.positions(), ray_at(2.5f, 2.5f)));
    // A triangle whose front faces away from the camera: hit, and said to be a back face.
    PolygonSoup soup;
    soup.positions = {Point(-1, -1, 0), Point(0, 1, 0), Point(1, -1, 0)};  // clockwise from +z
    soup.add_face({0, 1, 2});
    LoadReport report;
    const HalfedgeMesh away = build_mesh(soup, report);
    hit = pick_face(away, away.positions(), ray_at(200.5f, 200.5f), camera.near_plane());
    REQUIRE(hit);
    CHECK(hit->back_face);
    CHECK(std::abs(hit->position.z()) < 1e-9);
}
