#version 330 core
// Overlay segments, stage 3: one flat colour (LineRenderer draws the wider outline rectangles
// first, then the narrower coloured ones over them).

uniform vec3 u_color;

out vec4 frag_color;

void main() {
    frag_color = vec4(u_color, 1.0);
}
