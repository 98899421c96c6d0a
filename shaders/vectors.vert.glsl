#version 330 core
// Vector stage 1 (face and vertex normals): positions and normals to view space. The
// geometry stage (vectors.geom) turns triangles or points into segments.

layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;

uniform mat4 u_model_view;
uniform mat3 u_normal_matrix;

out VectorVertex {
    vec3 position;  // view space
    vec3 normal;    // view space, not normalized
} vs_out;

void main() {
    vs_out.position = (u_model_view * vec4(a_position, 1.0)).xyz;
    vs_out.normal = u_normal_matrix * a_normal;
    gl_Position = vec4(vs_out.position, 1.0);
}
