#version 330 core
// Overlay segments, stage 2: every segment becomes a screen-aligned rectangle u_half_width
// pixels to each side of it and as far beyond its ends (glLineWidth > 1 is not available in
// core profiles). Segments are clipped at the near plane first, so that a segment with an end
// behind the eye keeps its visible part.

layout(lines) in;
layout(triangle_strip, max_vertices = 4) out;

uniform vec2 u_viewport;  // size in pixels
uniform float u_half_width;

void main() {
    vec4 p0 = gl_in[0].gl_Position;
    vec4 p1 = gl_in[1].gl_Position;
    // Near plane: z >= -w inside.
    float d0 = p0.z + p0.w, d1 = p1.z + p1.w;
    if (d0 < 0.0 && d1 < 0.0) return;
    if (d0 < 0.0) p0 = mix(p0, p1, d0 / (d0 - d1));
    if (d1 < 0.0) p1 = mix(p1, p0, d1 / (d1 - d0));
    if (p0.w <= 0.0 || p1.w <= 0.0) return;

    vec2 s0 = 0.5 * u_viewport * (p0.xy / p0.w);  // pixels from the viewport centre
    vec2 s1 = 0.5 * u_viewport * (p1.xy / p1.w);
    vec2 d = s1 - s0;
    float len = length(d);
    vec2 along = len > 1e-4 ? d / len : vec2(1.0, 0.0);
    vec2 across = vec2(-along.y, along.x);
    float h = u_half_width;

    for (int i = 0; i < 4; ++i) {
        bool end = i >= 2;
        float side = (i % 2 == 0) ? -1.0 : 1.0;
        vec4 p = end ? p1 : p0;
        vec2 s = (end ? s1 : s0) + (end ? h : -h) * along + side * h * across;
        gl_Position = vec4(s / (0.5 * u_viewport) * p.w, p.z, p.w);
        EmitVertex();
    }
    EndPrimitive();
}
