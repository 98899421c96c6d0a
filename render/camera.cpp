#include "render/camera.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace trilab {

void Camera::set_viewport(float width, float height) {
    viewport_ = glm::vec2(std::max(width, 1.0f), std::max(height, 1.0f));
}

void Camera::reframe_for_viewport(float width, float height) {
    const float old_aspect = viewport_.x / viewport_.y;
    set_viewport(width, height);
    const float new_aspect = viewport_.x / viewport_.y;
    if (new_aspect < old_aspect) {  // narrower: keep the width, gain room at top and bottom
        const float tan_half = std::tan(0.5f * fov_y_) * old_aspect / new_aspect;
        fov_y_ = 2.0f * std::atan(tan_half);
    }
}

float Camera::pixels_per_unit() const {
    return viewport_.y / (2.0f * distance_ * std::tan(0.5f * fov_y_));
}

void Camera::fit_sphere(const glm::vec3& center, float radius) {
    target_ = center;
    radius_ = radius > 0.0f && std::isfinite(radius) ? radius : 1.0f;
    // The narrower of the two fields of view decides; 8 % margin around the sphere.
    float aspect = viewport_.x / viewport_.y;
    float half_fov = 0.5f * fov_y_;
    if (aspect < 1.0f) half_fov = std::atan(std::tan(half_fov) * aspect);
    distance_ = 1.08f * radius_ / std::sin(half_fov);
}

void Camera::fit_box(const glm::vec3& lo, const glm::vec3& hi) {
    fit_sphere(0.5f * (lo + hi), 0.5f * glm::length(hi - lo));
}

void Camera::fit_points_in_view(const std::vector<glm::vec3>& points, float margin) {
    if (points.empty()) {
        fit_box_in_view(glm::vec3(-1.0f), glm::vec3(1.0f), margin);
        return;
    }
    glm::vec3 lo = points[0], hi = points[0];
    for (const glm::vec3& p : points) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    fit_box(lo, hi);  // radius (zoom limits, clipping planes)

    const float tan_y = std::tan(0.5f * fov_y_) * (1.0f - std::clamp(margin, 0.0f, 0.9f));
    const float tan_x = tan_y * viewport_.x / viewport_.y;
    // In camera axes (z towards the viewer), a point (x, y, z) is in view from the camera
    // position (cx, cy, cz) when |x - cx| <= (cz - z) tan_x, and likewise for y. For x that
    // is cz >= z + x / tan_x - cx / tan_x and cz >= z - x / tan_x + cx / tan_x for every
    // point; with A and B the maxima of z + x / tan_x and z - x / tan_x, the smallest cz is
    // (A + B) / 2, at cx = tan_x (A - B) / 2.
    std::vector<glm::vec3> c(points.size());
    float ax = -INFINITY, bx = -INFINITY, ay = -INFINITY, by = -INFINITY;
    for (std::size_t i = 0; i < points.size(); ++i) {
        c[i] = rotation_ * points[i];
        ax = std::max(ax, c[i].z + c[i].x / tan_x);
        bx = std::max(bx, c[i].z - c[i].x / tan_x);
        ay = std::max(ay, c[i].z + c[i].y / tan_y);
        by = std::max(by, c[i].z - c[i].y / tan_y);
    }
    const float czx = 0.5f * (ax + bx), czy = 0.5f * (ay + by);
    glm::vec3 eye(0.5f * tan_x * (ax - bx), 0.5f * tan_y * (ay - by), std::max(czx, czy));
    // The other axis has room to spare at this distance: centre its projection, i.e. find
    // the offset where the largest tangents on both sides are equal (bisection: the
    // difference decreases as the offset grows).
    const int axis = czx >= czy ? 1 : 0;
    if (eye.z > std::min(czx, czy)) {
        float lo_offset = INFINITY, hi_offset = -INFINITY;
        for (const glm::vec3& q : c) {
            lo_offset = std::min(lo_offset, q[axis]);
            hi_offset = std::max(hi_offset, q[axis]);
        }
        for (int iteration = 0; iteration < 40 && hi_offset - lo_offset > 0.0f; ++iteration) {
            const float offset = 0.5f * (lo_offset + hi_offset);
            float positive = -INFINITY, negative = -INFINITY;
            for (const glm::vec3& q : c) {
                const float depth = std::max(eye.z - q.z, 1e-12f);
                positive = std::max(positive, (q[axis] - offset) / depth);
                negative = std::max(negative, (offset - q[axis]) / depth);
            }
            (positive > negative ? lo_offset : hi_offset) = offset;
        }
        eye[axis] = 0.5f * (lo_offset + hi_offset);
    }
    const float center_depth = (rotation_ * (0.5f * (lo + hi))).z;
    distance_ = std::max(eye.z - center_depth, 1e-3f * radius_);
    target_ = glm::conjugate(rotation_) * glm::vec3(eye.x, eye.y, eye.z - distance_);
}

void Camera::fit_box_in_view(const glm::vec3& lo, const glm::vec3& hi, float margin) {
    std::vector<glm::vec3> corners;
    for (int i = 0; i < 8; ++i)
        corners.emplace_back((i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z);
    fit_points_in_view(corners, margin);
}

void Camera::set_view_angles(float azimuth_deg, float elevation_deg, UpAxis up) {
    // World -> camera: for z-up first turn the world into the y-up frame (-90 degrees about
    // x: z -> y, -y -> z), then undo the azimuth (about y), then tilt down by the elevation
    // (about x).
    const glm::quat frame = up == UpAxis::Z
                                ? glm::angleAxis(glm::radians(-90.0f), glm::vec3(1, 0, 0))
                                : glm::quat(1, 0, 0, 0);
    const glm::quat tilt = glm::angleAxis(glm::radians(elevation_deg), glm::vec3(1, 0, 0));
    const glm::quat turn = glm::angleAxis(glm::radians(-azimuth_deg), glm::vec3(0, 1, 0));
    rotation_ = glm::normalize(tilt * turn * frame);
}

glm::vec3 Camera::ball_point(const glm::vec2& window) const {
    float scale = 0.5f * std::min(viewport_.x, viewport_.y);
    float x = (window.x - 0.5f * viewport_.x) / scale;
    float y = (0.5f * viewport_.y - window.y) / scale;
    float d2 = x * x + y * y;
    // Sphere of radius 1 near the centre, hyperbola z = 1 / (2 d) beyond d = 1 / sqrt(2).
    float z = d2 <= 0.5f ? std::sqrt(1.0f - d2) : 0.5f / std::sqrt(d2);
    return glm::normalize(glm::vec3(x, y, z));
}

void Camera::rotate(const glm::vec2& from, const glm::vec2& to) {
    glm::vec3 a = ball_point(from), b = ball_point(to);
    float c = glm::dot(a, b);
    if (c > 0.999999f) return;  // no movement
    // Quaternion of the rotation taking a to b: (1 + a.b, a x b), normalized (half angle).
    glm::quat delta = glm::normalize(glm::quat(1.0f + c, glm::cross(a, b)));
    rotation_ = glm::normalize(delta * rotation_);  // delta acts in camera coordinates
}

void Camera::pan(const glm::vec2& delta) {
    float world_per_pixel = 2.0f * distance_ * std::tan(0.5f * fov_y_) / viewport_.y;
    glm::quat to_world = glm::conjugate(rotation_);
    glm::vec3 right = to_world * glm::vec3(1, 0, 0);
    glm::vec3 up = to_world * glm::vec3(0, 1, 0);
    target_ += world_per_pixel * (-delta.x * right + delta.y * up);
}

void Camera::zoom(float steps) {
    // 0.9^±300 spans more than the 1e6 between the limits: more steps change nothing, and the
    // power cannot overflow.
    steps = std::clamp(steps, -300.0f, 300.0f);
    distance_ = std::clamp(distance_ * std::pow(0.9f, steps), radius_ * 1e-3f, radius_ * 1e3f);
}

glm::mat4 Camera::view() const {
    glm::mat4 m = glm::translate(glm::mat4(1.0f), glm::vec3(0, 0, -distance_));
    m = m * glm::mat4_cast(rotation_);
    return glm::translate(m, -target_);
}

float Camera::far_plane() const {
    return distance_ + 2.0f * radius_;
}

float Camera::near_plane() const {
    const float near = std::max(distance_ - 2.0f * radius_, 0.01f * radius_);
    return std::min(near, 0.5f * far_plane());
}

glm::mat4 Camera::projection() const {
    return glm::perspective(fov_y_, viewport_.x / viewport_.y, near_plane(), far_plane());
}

void Camera::ray_through(const glm::vec2& window, glm::dvec3& origin, glm::dvec3& direction) const {
    const double ndc_x = 2.0 * double(window.x) / double(viewport_.x) - 1.0;
    const double ndc_y = 1.0 - 2.0 * double(window.y) / double(viewport_.y);
    const double tan_half = std::tan(0.5 * double(fov_y_));
    const double aspect = double(viewport_.x) / double(viewport_.y);
    const glm::dvec3 camera_dir(ndc_x * tan_half * aspect, ndc_y * tan_half, -1.0);
    const glm::dquat to_world = glm::conjugate(glm::dquat(rotation_));
    direction = to_world * camera_dir;
    origin = glm::dvec3(target_) + to_world * glm::dvec3(0.0, 0.0, double(distance_));
}

void Camera::set_target(const glm::vec3& point) {
    target_ = point;
}

glm::vec3 Camera::eye() const {
    return target_ + glm::conjugate(rotation_) * glm::vec3(0, 0, distance_);
}

bool Camera::set_state(const glm::quat& rotation, const glm::vec3& target, float distance,
                       float radius, float fov_y) {
    const auto finite = [](float x) { return std::isfinite(x); };
    if (!finite(rotation.w) || !finite(rotation.x) || !finite(rotation.y) || !finite(rotation.z) ||
        !finite(target.x) || !finite(target.y) || !finite(target.z) || !(distance > 0.0f) ||
        !finite(distance) || !(radius > 0.0f) || !finite(radius) ||
        !(fov_y > 0.0f && fov_y < 3.14f))
        return false;
    rotation_ = rotation;
    target_ = target;
    distance_ = distance;
    radius_ = radius;
    fov_y_ = fov_y;
    return true;
}

}  // namespace trilab
