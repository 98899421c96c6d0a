#version 330 core
// Mesh geometry stage, used only when edges are drawn (overlay, Wireframe, HiddenLine):
// passes each triangle through and adds barycentric coordinates, which shared vertices cannot
// carry, so the fragment stage can draw the edges in the same pass.

layout(triangles) in;
layout(triangle_strip, max_vertices = 3) out;

in MeshVertex {
    vec3 position;
    vec3 normal;
    vec3 color;
    vec2 texcoord;
} gs_in[];

out MeshFragment {
    vec3 position;
    vec3 normal;
    vec3 color;
    vec2 texcoord;
    vec3 barycentric;
} gs_out;

void main() {
    for (int i = 0; i < 3; ++i) {
        gl_Position = gl_in[i].gl_Position;
        gs_out.position = gs_in[i].position;
        gs_out.normal = gs_in[i].normal;
        gs_out.color = gs_in[i].color;
        gs_out.texcoord = gs_in[i].texcoord;
        gs_out.barycentric = vec3(i == 0, i == 1, i == 2);
        EmitVertex();
    }
    EndPrimitive();
}
