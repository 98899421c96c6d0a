#version 330 core
// Mesh vertex stage: transforms positions and normals to view space.

layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;

uniform mat4 u_model_view;
uniform mat4 u_projection;
uniform mat3 u_normal_matrix;

out MeshVertex {
    vec3 position;  // view space
    vec3 normal;    // view space, not normalized
} vs_out;

void main() {
    vec4 p = u_model_view * vec4(a_position, 1.0);
    vs_out.position = p.xyz;
    vs_out.normal = u_normal_matrix * a_normal;
    gl_Position = u_projection * p;
}
