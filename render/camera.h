#pragma once
// Camera: an orbiting perspective camera for inspecting one object.
//
// The camera looks at `target` from `distance` along the view direction given by a unit
// quaternion (world -> camera rotation). Input is in window coordinates (pixels, origin at
// the top left, y down) over a viewport set with set_viewport(); on HiDPI screens pass the
// window size, not the framebuffer size. Pure math: no GL, usable in tests.
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <vector>

#include "core/up_axis.h"

namespace trilab {

class Camera {
public:
    /// The window size in pixels that mouse input and the aspect ratio refer to.
    void set_viewport(float width, float height);
    glm::vec2 viewport() const { return viewport_; }

    /// Centres the sphere (center, radius) and moves the camera so that it fills the view
    /// with a small margin. Keeps the rotation. A radius <= 0 counts as 1.
    void fit_sphere(const glm::vec3& center, float radius);
    /// fit_sphere() for the bounding sphere of the box [lo, hi]: the model stays in view
    /// whichever way it is turned afterwards.
    void fit_box(const glm::vec3& lo, const glm::vec3& hi);
    /// Frames the points tightly for the current rotation and viewport: the camera moves in
    /// its view plane and along its axis to the nearest position from which every point lies
    /// inside the view with `margin` (a fraction of the half-width and half-height) to spare,
    /// with the points' projection centred horizontally and vertically. The target (the centre
    /// of rotation) is then placed at the depth of the points' bounding-box centre. Zoom
    /// limits and clipping planes enclose the bounding box's sphere. Tighter than fit_box()
    /// for still images. An empty list frames the unit cube. O(n): at most 42 passes over
    /// the points.
    void fit_points_in_view(const std::vector<glm::vec3>& points, float margin = 0.04f);
    /// fit_points_in_view() for the eight corners of the box [lo, hi].
    void fit_box_in_view(const glm::vec3& lo, const glm::vec3& hi, float margin = 0.04f);
    /// Looks at the target from azimuth `azimuth_deg` around the world y axis (0: from +z,
    /// 90: from +x) and elevation `elevation_deg` above the xz plane (90: from +y, looking
    /// down with -z up on the screen), keeping world +y up on the screen elsewhere. The
    /// rotation is the product of two axis rotations (a quaternion), so it passes the poles
    /// without a flip. With `up` = UpAxis::Z (core/up_axis.h) the same in the z-up frame:
    /// azimuth around z from the front (-y; 90: from +x), elevation above the xy plane, +z up
    /// on the screen.
    void set_view_angles(float azimuth_deg, float elevation_deg, UpAxis up = UpAxis::Y);
    /// The default view for the up axis: looks at the model's front (+z for y-up, -y for
    /// z-up) with the up axis up on the screen; set_view_angles(0, 0, up).
    void reset_rotation(UpAxis up = UpAxis::Y) { set_view_angles(0.0f, 0.0f, up); }
    /// For a picture of width x height pixels of what the camera shows: sets that viewport and
    /// widens the vertical field of view where the picture's aspect ratio is narrower than the
    /// current viewport's, so that everything visible now stays visible, centred, and fills
    /// the picture in one direction (the other gets the extra room). Screenshots and recorded
    /// frames use it so that they are framed like the view.
    void reframe_for_viewport(float width, float height);
    /// Viewport pixels per world unit at the target's depth (how long a unit segment facing
    /// the camera appears there).
    float pixels_per_unit() const;

    /// Virtual trackball (Shoemake's arcball with Bell's hyperbolic sheet outside the ball):
    /// rotates about the target as if the ball under the cursor were dragged from `from` to
    /// `to` (window pixels).
    void rotate(const glm::vec2& from, const glm::vec2& to);
    /// Moves the target in the view plane so the surface at the target's depth follows a
    /// cursor movement of `delta` window pixels.
    void pan(const glm::vec2& delta);
    /// Moves towards the target by `steps` wheel notches (negative: away), 10 % per notch,
    /// clamped to [radius / 1000, radius * 1000] of the fitted sphere.
    void zoom(float steps);

    /// The ray from the eye through the window point `window` (pixels over the viewport,
    /// origin at the top left; pass a pixel's centre, x + 0.5): `origin` the eye, `direction`
    /// scaled to depth 1 along the view axis, so that a ray parameter t is the depth (compare
    /// it with near_plane()). In double precision, for picking.
    void ray_through(const glm::vec2& window, glm::dvec3& origin, glm::dvec3& direction) const;
    /// The projection's near and far planes (depths in front of the eye).
    float near_plane() const;
    float far_plane() const;
    /// Makes `point` the centre of rotation, keeping the rotation and the distance: the view
    /// moves so that the point is at its centre.
    void set_target(const glm::vec3& point);
    glm::mat4 view() const;
    /// Perspective projection for the viewport's aspect ratio; near and far planes enclose
    /// the fitted sphere.
    glm::mat4 projection() const;

    const glm::quat& rotation() const { return rotation_; }
    const glm::vec3& target() const { return target_; }
    float distance() const { return distance_; }
    float fov_y() const { return fov_y_; }
    /// The radius of the last fitted sphere (zoom limits and clipping planes follow it).
    float radius() const { return radius_; }
    /// Sets everything but the viewport exactly (a saved session's camera); non-finite or
    /// non-positive sizes are refused with false and leave the camera unchanged.
    bool set_state(const glm::quat& rotation, const glm::vec3& target, float distance, float radius,
                   float fov_y);
    /// The camera position in world coordinates.
    glm::vec3 eye() const;

private:
    glm::vec3 ball_point(const glm::vec2& window) const;

    glm::quat rotation_{1, 0, 0, 0};  ///< world -> camera
    glm::vec3 target_{0.0f};
    float distance_ = 3.0f;
    float radius_ = 1.0f;                ///< of the fitted sphere
    float fov_y_ = glm::radians(40.0f);  ///< vertical field of view
    glm::vec2 viewport_{1.0f, 1.0f};
};

}  // namespace trilab
