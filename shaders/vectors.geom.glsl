#version 330 core
// Vector stage 2: one segment of length u_length (view units = world units, the view is
// rigid) per input primitive. With TRILAB_FACE_VECTORS the input is a triangle and the
// segment starts at its centroid along its geometric normal; otherwise the input is a point
// and the segment follows the vertex normal. Zero normals give no segment.

#ifdef TRILAB_FACE_VECTORS
layout(triangles) in;
#else
layout(points) in;
#endif
layout(line_strip, max_vertices = 2) out;

in VectorVertex {
    vec3 position;
    vec3 normal;
} gs_in[];

uniform mat4 u_projection;
uniform float u_length;

out float gs_depth;  // view depth, for fog

void emit(vec3 p) {
    gl_Position = u_projection * vec4(p, 1.0);
    gs_depth = -p.z;
    EmitVertex();
}

void main() {
#ifdef TRILAB_FACE_VECTORS
    vec3 p0 = gs_in[0].position, p1 = gs_in[1].position, p2 = gs_in[2].position;
    vec3 start = (p0 + p1 + p2) / 3.0;
    vec3 n = cross(p1 - p0, p2 - p0);
#else
    vec3 start = gs_in[0].position;
    vec3 n = gs_in[0].normal;
#endif
    float len = length(n);
    if (len <= 0.0) return;
    emit(start);
    emit(start + (u_length / len) * n);
    EndPrimitive();
}
