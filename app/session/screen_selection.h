#pragma once
// Selecting on the screen (issue 26): the brush and the lasso of the viewer's Selection
// section work on the vertices as the view shows them, with no GL: every vertex is projected
// with the view's matrix, and which ones are visible is decided by a depth buffer rasterized
// here on the CPU (the view does not move while the user brushes or draws, so it is built
// once per stroke). Pixel coordinates are the view's: (0, 0) its top-left corner, y down.
#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "core/algorithms/selection.h"
#include "core/halfedge_mesh.h"

namespace trilab::viewer {

/// How the view projects: clip = view_projection · (x, y, z, 1), then the view's pixels.
struct ScreenView {
    Eigen::Matrix4d view_projection = Eigen::Matrix4d::Identity();
    double width = 1, height = 1;  ///< the view's size in pixels
};

/// Every vertex on the screen (storage index; deleted ones are never eligible).
struct ProjectedVertices {
    std::vector<Eigen::Vector2f> pixel;  ///< where it shows
    /// 1 where the brush or lasso may take it: in front of the camera and, unless the
    /// projection was made `through` the model, not hidden by the surface.
    std::vector<std::uint8_t> eligible;
};

/// Projects the vertices at `positions` (one per vertex storage index of `mesh`). Without
/// `through`, a vertex hidden behind the surface (deeper than the nearest triangle at its
/// pixel by more than 1% of the bounding-box diagonal) is not eligible: the depth buffer is
/// rasterized on the CPU over the triangles in front of the camera. O(V + F + covered pixels).
ProjectedVertices project_vertices(const HalfedgeMesh& mesh, const std::vector<Point>& positions,
                                   const ScreenView& view, bool through);

/// Paints one brush segment from pixel `a` to `b` (a dab when they coincide) with `radius`
/// pixels: every eligible vertex within `radius` of the segment gets weight 1 (`add`) or 0.
/// `weights` has one weight per vertex storage index. Returns how many weights changed.
/// O(V).
std::size_t paint_brush(const ProjectedVertices& projected, const Eigen::Vector2f& a,
                        const Eigen::Vector2f& b, float radius, bool add, Selection& weights);

/// Weight 1 for every eligible vertex inside the closed polygon `lasso` (pixels; even-odd
/// rule), 0 elsewhere. Fewer than three points select nothing. O(V · points).
Selection lasso_selection(const ProjectedVertices& projected,
                          const std::vector<Eigen::Vector2f>& lasso);

}  // namespace trilab::viewer
