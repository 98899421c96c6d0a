#pragma once
// MeshRenderer: the GPU mirror of one HalfedgeMesh and the shader that draws it.
//
// The renderer never owns the mesh: upload() copies what it needs (float positions and
// normals per vertex, a uint32 index buffer of triangles) into one vertex array object.
// A geometry-only change goes through update_positions(), which rewrites the vertex buffer
// and keeps the index buffer; a topology change goes through upload().
//
// Normals: the mesh's "v:normal" (Vector3) when it has one, otherwise area-weighted vertex
// normals computed on the fly (the same as core's vertex_normal()). A caller that moves
// vertices of a mesh carrying "v:normal" must refresh that attribute (compute_vertex_normals)
// or remove it before update_positions(), or the shading uses the stale normals.
//
// Drawing is one pass. Flat normals come from screen-space derivatives in the fragment stage.
// With the wireframe overlay on, a second variant of the program (mesh.vert, mesh.geom,
// mesh.frag with TRILAB_WIREFRAME) adds a geometry stage that gives each triangle corner
// barycentric coordinates, from which the fragment stage draws the edges; vertices stay
// shared. Without the overlay no geometry stage runs, which matters on llvmpipe.
//
// Every member function needs the GL 3.3 core context that was current at construction.
#include <glad/gl.h>

#include <cstddef>
#include <glm/glm.hpp>

#include "core/halfedge_mesh.h"
#include "render/gl_program.h"

namespace trilab {

enum class Shading {
    Smooth,  ///< Gouraud-style: per-vertex normals interpolated (lit per fragment)
    Flat,    ///< one normal per triangle
};

/// How draw() shades the mesh. Colours are linear RGB in [0, 1].
struct RenderStyle {
    Shading shading = Shading::Smooth;
    bool wireframe = false;       ///< overlay the triangle edges
    bool back_face_color = true;  ///< back faces in back_color instead of front_color
    glm::vec3 front_color{0.50f, 0.62f, 0.80f};
    glm::vec3 back_color{0.85f, 0.42f, 0.30f};
    glm::vec3 wire_color{0.10f, 0.12f, 0.16f};
    float wire_width = 1.0f;  ///< line width in framebuffer pixels
    float ambient = 0.15f;    ///< fraction of the base colour lit regardless of the normal
    float specular = 0.25f;   ///< strength of the white highlight
    float shininess = 64.0f;  ///< Blinn-Phong exponent
};

class MeshRenderer {
public:
    /// Compiles both program variants. Throws GlError (with the driver's log) if one fails.
    MeshRenderer();
    ~MeshRenderer();
    MeshRenderer(const MeshRenderer&) = delete;
    MeshRenderer& operator=(const MeshRenderer&) = delete;

    /// Copies positions, normals and triangles of `mesh` to the GPU, replacing what was
    /// there. Vertices are addressed by storage index, so a mesh with deleted elements
    /// (garbage) draws correctly. O(vertices + faces).
    void upload(const HalfedgeMesh& mesh);
    /// Rewrites positions and normals only, for a mesh whose faces are unchanged since the
    /// last upload(). Falls back to upload() when the vertex storage size differs.
    void update_positions(const HalfedgeMesh& mesh);
    /// Forgets the uploaded mesh; draw() then draws nothing.
    void clear();

    /// Draws the uploaded mesh (model matrix = identity) into the current framebuffer with
    /// depth testing. Leaves the depth test enabled and the program and VAO unbound.
    void draw(const glm::mat4& view, const glm::mat4& projection, const RenderStyle& style) const;

    std::size_t n_vertices() const { return n_vertices_; }
    std::size_t n_triangles() const { return n_indices_ / 3; }

private:
    void write_vertices(const HalfedgeMesh& mesh);

    GlProgram surface_program_;    ///< mesh.vert + mesh.frag
    GlProgram wireframe_program_;  ///< mesh.vert + mesh.geom + mesh.frag [TRILAB_WIREFRAME]
    GLuint vao_ = 0, vertex_buffer_ = 0, index_buffer_ = 0;
    std::size_t n_vertices_ = 0, n_indices_ = 0;
};

}  // namespace trilab
