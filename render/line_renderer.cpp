// LineRenderer (render/line_renderer.h): one VBO of endpoints drawn as GL_LINES.
#include "render/line_renderer.h"

namespace trilab {

LineRenderer::LineRenderer()
    : program_({embedded_shader("lines.vert.glsl"), embedded_shader("lines.frag.glsl")}) {
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

void LineRenderer::draw(const glm::mat4& view, const glm::mat4& projection, const glm::vec3& color,
                        float width) const {
    if (n_points_ == 0) return;
    program_.use();
    program_.set("u_model_view", view);
    program_.set("u_projection", projection);
    program_.set("u_color", color);
    program_.set("u_depth_offset", 1e-4f);
    GLfloat range[2] = {1.0f, 1.0f};
    glGetFloatv(GL_ALIASED_LINE_WIDTH_RANGE, range);
    glLineWidth(width < range[0] ? range[0] : width > range[1] ? range[1] : width);
    glEnable(GL_DEPTH_TEST);
    glBindVertexArray(vao_);
    glDrawArrays(GL_LINES, 0, GLsizei(n_points_));
    glBindVertexArray(0);
    glLineWidth(1.0f);
    glUseProgram(0);
}

}  // namespace trilab
