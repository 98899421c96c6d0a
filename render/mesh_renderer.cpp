#include "render/mesh_renderer.h"

#include <glm/gtc/matrix_inverse.hpp>
#include <vector>

#include "core/geometry.h"

namespace trilab {
namespace {

/// One vertex as the vertex shader reads it (locations 0 and 1).
struct GpuVertex {
    float position[3];
    float normal[3];
};
static_assert(sizeof(GpuVertex) == 6 * sizeof(float), "GpuVertex must be tightly packed");

/// Positions and normals by vertex storage index; deleted vertices get zeros.
std::vector<GpuVertex> vertex_data(const HalfedgeMesh& mesh) {
    std::vector<Vector3> computed;
    const std::vector<Vector3>* normals = &computed;
    if (auto stored = mesh.get_vertex_property<Vector3>("v:normal")) {
        normals = &stored.vector();
    } else {
        // Area-weighted normals (vertex_normal()), accumulated face by face: O(faces).
        computed.assign(mesh.vertices_size(), Vector3::Zero());
        for (Face f : mesh.faces()) {
            Vector3 n = face_area_vector(mesh, f);
            for (Vertex v : mesh.face_vertices(f)) computed[v.idx()] += n;
        }
        for (Vector3& n : computed) {
            double len = n.norm();
            if (len > 0) n /= len;
        }
    }
    std::vector<GpuVertex> data(mesh.vertices_size(), GpuVertex{{0, 0, 0}, {0, 0, 0}});
    for (Vertex v : mesh.vertices()) {
        const Point& p = mesh.position(v);
        const Vector3& n = (*normals)[v.idx()];
        data[v.idx()] = GpuVertex{{float(p.x()), float(p.y()), float(p.z())},
                                  {float(n.x()), float(n.y()), float(n.z())}};
    }
    return data;
}

}  // namespace

MeshRenderer::MeshRenderer()
    : surface_program_({embedded_shader("mesh.vert.glsl"), embedded_shader("mesh.frag.glsl")}),
      wireframe_program_({embedded_shader("mesh.vert.glsl"), embedded_shader("mesh.geom.glsl"),
                          with_defines(embedded_shader("mesh.frag.glsl"), {"TRILAB_WIREFRAME"})}) {
    glGenVertexArrays(1, &vao_);
    glGenBuffers(1, &vertex_buffer_);
    glGenBuffers(1, &index_buffer_);

    glBindVertexArray(vao_);
    glBindBuffer(GL_ARRAY_BUFFER, vertex_buffer_);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(GpuVertex),
                          reinterpret_cast<const void*>(offsetof(GpuVertex, position)));
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, sizeof(GpuVertex),
                          reinterpret_cast<const void*>(offsetof(GpuVertex, normal)));
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, index_buffer_);  // recorded in the VAO
    glBindVertexArray(0);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
}

MeshRenderer::~MeshRenderer() {
    glDeleteBuffers(1, &index_buffer_);
    glDeleteBuffers(1, &vertex_buffer_);
    glDeleteVertexArrays(1, &vao_);
}

void MeshRenderer::upload(const HalfedgeMesh& mesh) {
    std::vector<GLuint> indices;
    indices.reserve(3 * mesh.n_faces());
    for (Face f : mesh.faces())
        for (Vertex v : mesh.face_vertices(f)) indices.push_back(v.idx());

    write_vertices(mesh);
    glBindVertexArray(vao_);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(indices.size() * sizeof(GLuint)),
                 indices.data(), GL_STATIC_DRAW);
    glBindVertexArray(0);
    n_indices_ = indices.size();
}

void MeshRenderer::update_positions(const HalfedgeMesh& mesh) {
    if (mesh.vertices_size() != n_vertices_) {
        upload(mesh);
        return;
    }
    write_vertices(mesh);
}

void MeshRenderer::write_vertices(const HalfedgeMesh& mesh) {
    std::vector<GpuVertex> data = vertex_data(mesh);
    glBindBuffer(GL_ARRAY_BUFFER, vertex_buffer_);
    // Same size: overwrite in place; otherwise reallocate.
    if (data.size() == n_vertices_ && !data.empty()) {
        glBufferSubData(GL_ARRAY_BUFFER, 0, GLsizeiptr(data.size() * sizeof(GpuVertex)),
                        data.data());
    } else {
        glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(data.size() * sizeof(GpuVertex)), data.data(),
                     GL_DYNAMIC_DRAW);
    }
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    n_vertices_ = data.size();
}

void MeshRenderer::clear() {
    glBindBuffer(GL_ARRAY_BUFFER, vertex_buffer_);
    glBufferData(GL_ARRAY_BUFFER, 0, nullptr, GL_DYNAMIC_DRAW);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    glBindVertexArray(vao_);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, 0, nullptr, GL_STATIC_DRAW);
    glBindVertexArray(0);
    n_vertices_ = n_indices_ = 0;
}

void MeshRenderer::draw(const glm::mat4& view, const glm::mat4& projection,
                        const RenderStyle& style) const {
    if (n_indices_ == 0) return;
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);

    const GlProgram& program = style.wireframe ? wireframe_program_ : surface_program_;
    program.use();
    program.set("u_model_view", view);
    program.set("u_projection", projection);
    program.set("u_normal_matrix", glm::inverseTranspose(glm::mat3(view)));
    program.set("u_flat", style.shading == Shading::Flat ? 1 : 0);
    program.set("u_back_face_color", style.back_face_color ? 1 : 0);
    program.set("u_front_color", style.front_color);
    program.set("u_back_color", style.back_color);
    program.set("u_wire_color", style.wire_color);
    program.set("u_wire_width", style.wire_width);
    program.set("u_ambient", style.ambient);
    program.set("u_specular", style.specular);
    program.set("u_shininess", style.shininess);

    glBindVertexArray(vao_);
    glDrawElements(GL_TRIANGLES, GLsizei(n_indices_), GL_UNSIGNED_INT, nullptr);
    glBindVertexArray(0);
    glUseProgram(0);
}

}  // namespace trilab
