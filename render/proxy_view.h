#pragma once
// What a view needs to draw a proxy (core/algorithms/proxy_mesh.h) in place of a large mesh
// while it moves: when it moves (MotionClock), the proxy's colours (sample_proxy_colors) and
// how far the proxy may be from the surface on the screen (proxy_error_pixels). Pure logic:
// no GL, usable in tests.
#include <glm/glm.hpp>
#include <vector>

#include "core/algorithms/coloring.h"
#include "core/halfedge_mesh.h"
#include "render/camera.h"
#include "render/mesh_renderer.h"

namespace trilab {

/// Tells motion from rest from one frame to the next: the view moves while its camera
/// matrices change between frames (a rotate, pan or zoom, whatever input did it) or the
/// shown surface changes (note_motion(): a slider drag), and rests once nothing changed for
/// `rest_seconds`.
class MotionClock {
public:
    explicit MotionClock(double rest_seconds = 0.1) : rest_seconds_(rest_seconds) {}
    /// Compares this frame's camera with the last frame's; a change is motion at `now`
    /// (seconds, any monotonic clock). The first frame is no motion. Returns whether the
    /// camera changed.
    bool frame(const glm::mat4& view, const glm::mat4& projection, double now);
    /// Something else on the screen moved at `now` (the shown surface changed).
    void note_motion(double now) { last_motion_ = now; }
    /// Whether the view moved within rest_seconds before `now`.
    bool moving(double now) const {
        return last_motion_ >= 0 && now - last_motion_ < rest_seconds_;
    }
    /// When the view last moved (-1: never).
    double last_motion() const { return last_motion_; }
    double rest_seconds() const { return rest_seconds_; }

private:
    double rest_seconds_;
    double last_motion_ = -1;
    bool has_camera_ = false;
    glm::mat4 view_{1.0f}, projection_{1.0f};
};

/// The colouring of a proxy: per proxy vertex the colour (and value, for bands and
/// isolines) of its representative mesh vertex (ProxyMesh::representative, storage indices of
/// the mesh `colors` was made for); legend, range, kind and categories are kept. Empty
/// colours give empty colours. Throws InvalidArgument when a representative is outside
/// `colors` (colours of another mesh).
VertexColors sample_proxy_colors(const VertexColors& colors,
                                 const std::vector<Index>& representative);

/// The selection overlay of a proxy: per proxy vertex the weight of its representative mesh
/// vertex (as sample_proxy_colors samples colours), for MeshRenderer::set_vertex_selection().
/// Throws InvalidArgument when a representative is outside `weights` (another mesh's).
std::vector<float> sample_proxy_selection(const std::vector<float>& weights,
                                          const std::vector<Index>& representative);

/// The texture coordinates of a proxy of `mesh`, one per proxy vertex: its representative's
/// "v:texcoord", or with per-corner "h:texcoord" those of one corner at the representative
/// (a proxy triangle across a texture seam then stretches the texture between the two
/// sides, while the view moves); empty when the mesh has neither. Throws InvalidArgument
/// when a representative is not a vertex of `mesh`.
std::vector<TexCoord> sample_proxy_texcoords(const HalfedgeMesh& mesh,
                                             const std::vector<Index>& representative);

/// The style a stand-in is drawn with in place of the surface's `style`: normals turned
/// towards the viewer and no back colour (RenderStyle::facing_normals), so that its folded
/// clustered triangles leave no dark specks; the rest as the surface is drawn.
RenderStyle stand_in_style(RenderStyle style);

/// How many framebuffer pixels `error_bound` (world units, ProxyMesh::error_bound) spans at
/// the camera's target depth: error_bound x Camera::pixels_per_unit() x `framebuffer_scale`
/// (framebuffer pixels per window pixel).
double proxy_error_pixels(double error_bound, const Camera& camera, float framebuffer_scale = 1.0f);

}  // namespace trilab
