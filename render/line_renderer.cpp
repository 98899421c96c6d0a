// LineRenderer (render/line_renderer.h): one VBO of endpoints drawn as GL_LINES, which
// lines.geom turns into screen-aligned rectangles: first every outline (the wider rectangle),
// then every core over them.
#include "render/line_renderer.h"

#include <algorithm>

namespace trilab {

LineRenderer::LineRenderer()
    : program_({embedded_shader("lines.vert.glsl"), embedded_shader("lines.geom.glsl"),
                embedded_shader("lines.frag.glsl")}) {
    glGenVertexArrays(1, &vao_);
    glGenBuffers(1, &buffer_);
    glBindVertexArray(vao_);
    glBindBuffer(GL_ARRAY_BUFFER, buffer_);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(glm::vec3), nullptr);
    glBindVertexArray(0);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
}

LineRenderer::~LineRenderer() {
    glDeleteBuffers(1, &buffer_);
    glDeleteVertexArrays(1, &vao_);
}

void LineRenderer::set_segments(const std::vector<glm::vec3>& endpoints) {
    n_points_ = endpoints.size() & ~std::size_t(1);
    glBindBuffer(GL_ARRAY_BUFFER, buffer_);
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(n_points_ * sizeof(glm::vec3)),
                 n_points_ ? endpoints.data() : nullptr, GL_DYNAMIC_DRAW);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
}

void LineRenderer::draw(const glm::mat4& view, const glm::mat4& projection, const LineStyle& style,
                        float scale) const {
    if (n_points_ == 0) return;
    GLint viewport[4] = {0, 0, 1, 1};
    glGetIntegerv(GL_VIEWPORT, viewport);
    const float core_half = 0.5f * std::max(style.width * scale, 1.0f);
    const float outline = std::max(style.outline_width * scale, 0.0f);
    program_.use();
    program_.set("u_model_view", view);
    program_.set("u_projection", projection);
    program_.set("u_pull", std::clamp(style.pull, 0.0f, 0.5f));
    program_.set("u_viewport",
                 glm::vec2(float(std::max(viewport[2], 1)), float(std::max(viewport[3], 1))));
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);
    glDepthMask(GL_FALSE);  // the cores draw over the outlines
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    glBindVertexArray(vao_);
    if (outline > 0.0f) {
        program_.set("u_half_width", core_half + outline);
        program_.set("u_color", style.outline_color);
        glDrawArrays(GL_LINES, 0, GLsizei(n_points_));
    }
    program_.set("u_half_width", core_half);
    program_.set("u_color", style.color);
    glDrawArrays(GL_LINES, 0, GLsizei(n_points_));
    glBindVertexArray(0);
    glDepthMask(GL_TRUE);
    glUseProgram(0);
}

void LineRenderer::draw(const glm::mat4& view, const glm::mat4& projection, const glm::vec3& color,
                        float width) const {
    LineStyle style;
    style.color = color;
    style.width = width;
    draw(view, projection, style);
}

}  // namespace trilab
