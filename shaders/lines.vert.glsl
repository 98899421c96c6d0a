#version 330 core
// Overlay segments (e.g. the edges the next decimation collapses), stage 1: positions to clip
// space, pulled towards the eye by the fraction u_pull of their distance. Scaling a point
// about the eye moves it along its own line of sight, so the picture keeps its place and only
// the depth changes: a segment lying on the surface then wins the depth test against that
// surface (and the edges drawn on it) by a margin that does not depend on the depth range,
// while surfaces in front of it by more than that still hide it.

layout(location = 0) in vec3 a_position;

uniform mat4 u_model_view;
uniform mat4 u_projection;
uniform float u_pull;

void main() {
    vec4 view = u_model_view * vec4(a_position, 1.0);
    view.xyz *= 1.0 - u_pull;
    gl_Position = u_projection * view;
}
