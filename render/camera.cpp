#include "render/camera.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace trilab {

void Camera::set_viewport(float width, float height) {
    viewport_ = glm::vec2(std::max(width, 1.0f), std::max(height, 1.0f));
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
    distance_ = std::clamp(distance_ * std::pow(0.9f, steps), radius_ * 1e-3f, radius_ * 1e3f);
}

glm::mat4 Camera::view() const {
    glm::mat4 m = glm::translate(glm::mat4(1.0f), glm::vec3(0, 0, -distance_));
    m = m * glm::mat4_cast(rotation_);
    return glm::translate(m, -target_);
}

glm::mat4 Camera::projection() const {
    float far_plane = distance_ + 2.0f * radius_;
    float near_plane = std::max(distance_ - 2.0f * radius_, 0.01f * radius_);
    near_plane = std::min(near_plane, 0.5f * far_plane);
    return glm::perspective(fov_y_, viewport_.x / viewport_.y, near_plane, far_plane);
}

glm::vec3 Camera::eye() const {
    return target_ + glm::conjugate(rotation_) * glm::vec3(0, 0, distance_);
}

}  // namespace trilab
