#version 330 core
// Mesh fragment stage: Blinn-Phong with a headlight (light at the eye), smooth or flat
// normals, a distinct colour for back faces and, when compiled with TRILAB_WIREFRAME (after
// mesh.geom), an anti-aliased wireframe overlay of constant width in pixels.

#ifdef TRILAB_WIREFRAME
in MeshFragment {
    vec3 position;
    vec3 normal;
    vec3 barycentric;
} fs_in;
#else
in MeshVertex {
    vec3 position;
    vec3 normal;
} fs_in;
#endif

uniform bool u_flat;
uniform bool u_back_face_color;
uniform vec3 u_front_color;
uniform vec3 u_back_color;
uniform vec3 u_wire_color;
uniform float u_wire_width;  // total line width in framebuffer pixels
uniform float u_ambient;
uniform float u_specular;
uniform float u_shininess;

out vec4 frag_color;

void main() {
    vec3 n;
    if (u_flat) {
        // The triangle's plane from screen-space derivatives; this normal always faces the
        // viewer, so it is not flipped for back faces.
        n = cross(dFdx(fs_in.position), dFdy(fs_in.position));
    } else {
        n = gl_FrontFacing ? fs_in.normal : -fs_in.normal;
    }
    float len = length(n);
    n = len > 0.0 ? n / len : vec3(0.0, 0.0, 1.0);
    vec3 base = (gl_FrontFacing || !u_back_face_color) ? u_front_color : u_back_color;

    // Headlight: light and viewer coincide, so the half vector is the light direction.
    vec3 l = normalize(-fs_in.position);
    float diffuse = max(dot(n, l), 0.0);
    float spec = diffuse > 0.0 ? pow(diffuse, u_shininess) : 0.0;
    vec3 color = base * (u_ambient + (1.0 - u_ambient) * diffuse) + vec3(u_specular * spec);

#ifdef TRILAB_WIREFRAME
    // Distance to the nearest edge in pixels; each side of an edge draws half the width.
    vec3 pixels = fs_in.barycentric / max(fwidth(fs_in.barycentric), vec3(1e-6));
    float d = min(min(pixels.x, pixels.y), pixels.z);
    float half_width = 0.5 * u_wire_width;
    float edge = 1.0 - smoothstep(half_width - 0.5, half_width + 0.5, d);
    color = mix(color, u_wire_color, edge);
#endif
    frag_color = vec4(color, 1.0);
}
