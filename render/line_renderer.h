#pragma once
// LineRenderer: draws a set of 3D segments over the scene as thick lines in one colour with a
// dark outline, e.g. the edges the next decimation iteration collapses. Depth tested, but
// pulled towards the eye (by LineStyle::pull of their distance) so that segments lying on the
// surface always win over it and over the wireframe drawn on it: no dashes from depth
// fighting. Draw it after the mesh. It owns its GPU buffer; set_segments() replaces the
// segments. Needs a current GL 3.3 core context for every call, including construction and
// destruction.
#include <glad/gl.h>

#include <glm/glm.hpp>
#include <vector>

#include "render/gl_program.h"

namespace trilab {

/// How LineRenderer::draw() draws. Widths are in framebuffer pixels at UI scale 1 (draw()
/// multiplies them by its `scale`). The defaults read on the default background, the default
/// surface colour, the (dark) wireframe and the subdivision-level colours.
struct LineStyle {
    glm::vec3 color{1.00f, 0.55f, 0.00f};          ///< bright orange
    glm::vec3 outline_color{0.04f, 0.04f, 0.05f};  ///< near black, around the colour
    float width = 2.5f;                            ///< of the coloured core
    float outline_width = 1.0f;                    ///< on each side of the core (0: none)
    /// Depth bias: segments are drawn as if this fraction of their distance closer to the eye
    /// (where they appear does not change). Surfaces in front of a segment by more than that
    /// still hide it.
    float pull = 0.01f;
};

class LineRenderer {
public:
    LineRenderer();
    ~LineRenderer();
    LineRenderer(const LineRenderer&) = delete;
    LineRenderer& operator=(const LineRenderer&) = delete;

    /// Two endpoints per segment (an odd last point is ignored).
    void set_segments(const std::vector<glm::vec3>& endpoints);
    std::size_t n_segments() const { return n_points_ / 2; }
    /// Draws the segments into the current framebuffer and viewport, widths times `scale`
    /// (the HiDPI scale). Writes no depth; leaves depth test enabled (GL_LEQUAL), blending
    /// disabled and no program or VAO bound.
    void draw(const glm::mat4& view, const glm::mat4& projection, const LineStyle& style = {},
              float scale = 1.0f) const;
    /// The same with `color` for the core and a core `width` in pixels (the default outline
    /// and depth bias).
    void draw(const glm::mat4& view, const glm::mat4& projection, const glm::vec3& color,
              float width) const;

private:
    GlProgram program_;
    GLuint vao_ = 0, buffer_ = 0;
    std::size_t n_points_ = 0;
};

}  // namespace trilab
