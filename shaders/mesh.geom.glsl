#version 330 core
// Mesh geometry stage, used when edges are drawn (overlay, Wireframe, HiddenLine) and for
// categorical vertex colours: passes each triangle through and adds barycentric coordinates,
// which shared vertices cannot carry, so the fragment stage can draw the edges in the same
// pass. With TRILAB_NEAREST_CORNER it also hands every fragment the three corners' colours
// unblended (flat), so that the fragment stage can take its nearest corner's colour. With
// TRILAB_SCALAR the scalar of isolines and bands passes through too, with TRILAB_SELECTION
// the selection's weight.

layout(triangles) in;
layout(triangle_strip, max_vertices = 3) out;

in MeshVertex {
    vec3 position;
    vec3 normal;
    vec3 color;
    vec2 texcoord;
#ifdef TRILAB_SCALAR
    vec2 scalar;
#endif
#ifdef TRILAB_SELECTION
    float selection;
#endif
} gs_in[];

out MeshFragment {
    vec3 position;
    vec3 normal;
    vec3 color;
    vec2 texcoord;
    vec3 barycentric;
#ifdef TRILAB_NEAREST_CORNER
    flat vec3 corner_color0;
    flat vec3 corner_color1;
    flat vec3 corner_color2;
#endif
#ifdef TRILAB_SCALAR
    vec2 scalar;
#endif
#ifdef TRILAB_SELECTION
    float selection;
#endif
} gs_out;

void main() {
    for (int i = 0; i < 3; ++i) {
        gl_Position = gl_in[i].gl_Position;
        gs_out.position = gs_in[i].position;
        gs_out.normal = gs_in[i].normal;
        gs_out.color = gs_in[i].color;
        gs_out.texcoord = gs_in[i].texcoord;
#ifdef TRILAB_SCALAR
        gs_out.scalar = gs_in[i].scalar;
#endif
#ifdef TRILAB_SELECTION
        gs_out.selection = gs_in[i].selection;
#endif
        gs_out.barycentric = vec3(i == 0, i == 1, i == 2);
#ifdef TRILAB_NEAREST_CORNER
        gs_out.corner_color0 = gs_in[0].color;
        gs_out.corner_color1 = gs_in[1].color;
        gs_out.corner_color2 = gs_in[2].color;
#endif
        EmitVertex();
    }
    EndPrimitive();
}
