#version 330 core
// Overlay segments (e.g. the edges the next decimation collapses): positions to clip space,
// pulled slightly towards the camera so segments on the surface win the depth test.

layout(location = 0) in vec3 a_position;

uniform mat4 u_model_view;
uniform mat4 u_projection;
uniform float u_depth_offset;

void main() {
    vec4 view = u_model_view * vec4(a_position, 1.0);
    gl_Position = u_projection * view;
    gl_Position.z -= u_depth_offset * gl_Position.w;
}
