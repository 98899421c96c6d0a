#pragma once
// LineRenderer: draws a set of 3D segments in one flat colour over the scene (depth tested,
// pulled slightly towards the camera), e.g. the edges the next decimation iteration collapses.
// It owns its GPU buffer; set_segments() replaces the segments. Needs a current GL 3.3 core
// context for every call, including construction and destruction.
#include <glad/gl.h>

#include <glm/glm.hpp>
#include <vector>

#include "render/gl_program.h"

namespace trilab {

class LineRenderer {
public:
    LineRenderer();
    ~LineRenderer();
    LineRenderer(const LineRenderer&) = delete;
    LineRenderer& operator=(const LineRenderer&) = delete;

    /// Two endpoints per segment (an odd last point is ignored).
    void set_segments(const std::vector<glm::vec3>& endpoints);
    std::size_t n_segments() const { return n_points_ / 2; }
    /// Draws the segments with `width` pixels (clamped to what the driver supports).
    void draw(const glm::mat4& view, const glm::mat4& projection, const glm::vec3& color,
              float width = 2.0f) const;

private:
    GlProgram program_;
    GLuint vao_ = 0, buffer_ = 0;
    std::size_t n_points_ = 0;
};

}  // namespace trilab
