#version 330 core
// Mesh vertex stage: transforms positions and normals to view space and passes the optional
// per-vertex colour and texture coordinate on (disabled attribute arrays read as zero; the
// fragment stage's uniforms say whether they are used). With TRILAB_SCALAR also the scalar
// (value normalized to the legend range times validity, validity): see mesh.frag. With
// TRILAB_SELECTION the selection's weight (the overlay of mesh.frag).

layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec4 a_color;
layout(location = 3) in vec2 a_texcoord;
#ifdef TRILAB_SCALAR
layout(location = 4) in vec2 a_scalar;
#endif
#ifdef TRILAB_SELECTION
layout(location = 5) in float a_selection;
#endif

uniform mat4 u_model_view;
uniform mat4 u_projection;
uniform mat3 u_normal_matrix;
uniform float u_point_size;  // Points mode: diameter in framebuffer pixels

out MeshVertex {
    vec3 position;  // view space
    vec3 normal;    // view space, not normalized
    vec3 color;
    vec2 texcoord;
#ifdef TRILAB_SCALAR
    vec2 scalar;
#endif
#ifdef TRILAB_SELECTION
    float selection;
#endif
} vs_out;

void main() {
    vec4 p = u_model_view * vec4(a_position, 1.0);
    vs_out.position = p.xyz;
    vs_out.normal = u_normal_matrix * a_normal;
    vs_out.color = a_color.rgb;
    vs_out.texcoord = a_texcoord;
#ifdef TRILAB_SCALAR
    vs_out.scalar = a_scalar;
#endif
#ifdef TRILAB_SELECTION
    vs_out.selection = a_selection;
#endif
    gl_Position = u_projection * p;
    gl_PointSize = u_point_size;
}
