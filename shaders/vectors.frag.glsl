#version 330 core
// Vector stage 3: a flat colour, faded by the same depth fog as the surface.

in float gs_depth;

uniform vec3 u_color;
uniform bool u_fog;
uniform float u_fog_near;
uniform float u_fog_far;
uniform float u_fog_amount;
uniform vec3 u_background;

out vec4 frag_color;

void main() {
    vec3 color = u_color;
    if (u_fog) {
        float t = clamp((gs_depth - u_fog_near) / max(u_fog_far - u_fog_near, 1e-6), 0.0, 1.0);
        color = mix(color, u_background, t * u_fog_amount);
    }
    frag_color = vec4(color, 1.0);
}
