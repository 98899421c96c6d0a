#version 330 core
// Mesh fragment stage. One file, variants by defines:
//  - default: shaded surface (Flat, Smooth, Textured);
//  - TRILAB_WIREFRAME (after mesh.geom): the same plus anti-aliased edges of constant width
//    in pixels from barycentric coordinates; u_surface also selects the HiddenLine surface
//    (background colour) and the Wireframe mode (edges only, blended);
//  - TRILAB_NEAREST_CORNER (after mesh.geom, alone or with TRILAB_WIREFRAME): vertex colours
//    are categories, not values: every fragment takes the colour of its triangle's corner
//    with the largest barycentric coordinate instead of a blend, so only the legend's
//    colours appear;
//  - TRILAB_POINTS: round point sprites lit by the vertex normal;
//  - TRILAB_SCALAR (default or TRILAB_WIREFRAME variant): a per-vertex scalar, the value
//    normalized to the legend range, t = (value - min) / (max - min), carried as (t w, w)
//    with w = 1 where the vertex has a value and 0 where not, so the interpolated t is the
//    weighted mean of the corners that have one and the part without (w < 1/2) shows none.
//    u_scalar_display bit 1: bands: t cut into N = u_scalar_steps equal steps, step k
//    (t in [k/N, (k+1)/N)) painted u_band_colors[k] (the map's colour at the step's centre)
//    instead of the vertex colour; bit 2: isolines at the N - 1 inner step boundaries t = k/N,
//    k = 1..N-1, anti-aliased with fwidth, u_isoline_width pixels wide, over the lit colour:
//    dark over light colours and light over dark ones, so they read on every part of a map;
//    they fade out where they would be under 2 pixels apart.
//  - TRILAB_SELECTION (with TRILAB_SCALAR, any of the variants above but points): the
//    selection's weight w per vertex, interpolated: the lit colour is blended towards
//    u_selection_tint by u_selection_strength · w (a tint: the colouring under it still
//    reads), and the contour w = 1/2 is drawn as an anti-aliased outline
//    u_selection_outline_width pixels wide (from fwidth(w); none where w is constant).
// The default variant also compiles with TRILAB_NO_VERTEX_COLOR and/or TRILAB_NO_TEXTURE:
// inputs a variant does not read are dropped by the linker, and on a software rasterizer
// every interpolated input costs per-triangle setup work.
// Lighting: a head light (light at the eye, so the half vector is the light direction),
// ambient + Lambert + optional Blinn-Phong specular. Fog blends towards the background by
// view depth.

#if defined(TRILAB_WIREFRAME) || defined(TRILAB_NEAREST_CORNER)
in MeshFragment {
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
} fs_in;
#else
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
} fs_in;
#endif

uniform int u_surface;  // 0 shaded, 1 background colour (HiddenLine), 2 none (Wireframe)
uniform bool u_flat;
uniform bool u_back_face_color;
uniform bool u_facing_normals;  // the normal turned towards the viewer (a stand-in's folds)
uniform bool u_use_vertex_color;
uniform vec3 u_front_color;
uniform vec3 u_back_color;
uniform int u_texture_mode;  // 0 off, 1 modulate, 2 replace
uniform sampler2D u_texture;
uniform float u_ambient;
uniform float u_specular;  // 0 when the highlight is off
uniform float u_shininess;
uniform bool u_fog;
uniform float u_fog_near;  // view depth where the fog starts
uniform float u_fog_far;   // view depth where it reaches u_fog_amount
uniform float u_fog_amount;
uniform vec3 u_background;
uniform vec3 u_wire_color;
uniform float u_wire_width;  // total line width in framebuffer pixels
#ifdef TRILAB_SCALAR
uniform int u_scalar_display;  // bit 1: bands, bit 2: isolines
uniform int u_scalar_steps;    // N, 2 to 64
uniform vec3 u_band_colors[64];
uniform float u_isoline_width;  // total line width in framebuffer pixels
#endif
#ifdef TRILAB_SELECTION
uniform vec3 u_selection_tint;
uniform float u_selection_strength;  // the tint's blend at weight 1
uniform vec3 u_selection_outline;
uniform float u_selection_outline_width;  // total line width in framebuffer pixels
#endif

out vec4 frag_color;

vec3 apply_fog(vec3 color) {
    if (!u_fog) return color;
    float depth = -fs_in.position.z;
    float t = clamp((depth - u_fog_near) / max(u_fog_far - u_fog_near, 1e-6), 0.0, 1.0);
    return mix(color, u_background, t * u_fog_amount);
}

vec3 lit(vec3 base, vec3 n) {
    vec3 l = normalize(-fs_in.position);
    float diffuse = max(dot(n, l), 0.0);
    float spec = diffuse > 0.0 ? pow(diffuse, u_shininess) : 0.0;
    return base * (u_ambient + (1.0 - u_ambient) * diffuse) + vec3(u_specular * spec);
}

// The vertex colour here: interpolated, or with TRILAB_NEAREST_CORNER the nearest corner's,
// or with bands the colour of the step the scalar falls in.
vec3 vertex_color() {
#ifdef TRILAB_NEAREST_CORNER
    vec3 b = fs_in.barycentric;
    if (b.x >= b.y && b.x >= b.z) return fs_in.corner_color0;
    return b.y >= b.z ? fs_in.corner_color1 : fs_in.corner_color2;
#else
#ifdef TRILAB_SCALAR
    if ((u_scalar_display & 1) != 0 && fs_in.scalar.y >= 0.5) {
        float t = fs_in.scalar.x / fs_in.scalar.y;
        int k = clamp(int(floor(t * float(u_scalar_steps))), 0, u_scalar_steps - 1);
        return u_band_colors[k];
    }
#endif
    return fs_in.color;
#endif
}

#ifdef TRILAB_SCALAR
// How much of this fragment an isoline covers (0 to 1). Derivatives first, in uniform flow.
float isoline_coverage() {
    float level = fs_in.scalar.x / max(fs_in.scalar.y, 1e-6) * float(u_scalar_steps);
    float slope = fwidth(level);  // levels per pixel
    if ((u_scalar_display & 2) == 0 || fs_in.scalar.y < 0.5) return 0.0;
    float k = floor(level + 0.5);
    if (k < 1.0 || k > float(u_scalar_steps - 1)) return 0.0;
    float pixels = abs(level - k) / max(slope, 1e-6);
    float half_width = 0.5 * u_isoline_width;
    float line = 1.0 - smoothstep(half_width - 0.5, half_width + 0.5, pixels);
    return line * (1.0 - smoothstep(0.25, 0.5, slope));
}

// The isoline's colour over `under`: dark over light colours, light over dark ones.
vec3 isoline_color(vec3 under) {
    float luminance = dot(under, vec3(0.2126, 0.7152, 0.0722));
    return luminance > 0.3 ? under * 0.15 : mix(under, vec3(1.0), 0.75);
}
#endif

#ifdef TRILAB_SELECTION
// How much of this fragment the selection's outline (the contour w = 1/2) covers, 0 to 1.
// Derivatives first, in uniform flow.
float selection_outline_coverage() {
    float w = fs_in.selection;
    float slope = fwidth(w);  // weight per pixel
    if (slope <= 0.0) return 0.0;
    float pixels = abs(w - 0.5) / slope;
    float half_width = 0.5 * u_selection_outline_width;
    return 1.0 - smoothstep(half_width - 0.5, half_width + 0.5, pixels);
}
#endif

vec3 front_base() {
#ifdef TRILAB_NO_VERTEX_COLOR
    return u_front_color;
#else
    return u_use_vertex_color ? vertex_color() : u_front_color;
#endif
}

#ifdef TRILAB_POINTS
void main() {
    vec2 d = 2.0 * gl_PointCoord - 1.0;
    float r2 = dot(d, d);
    if (r2 > 1.0) discard;
    vec3 n = fs_in.normal;
    float len = length(n);
    n = len > 0.0 ? n / len : normalize(-fs_in.position);
    bool back = dot(n, -fs_in.position) < 0.0;
    vec3 base = (back && u_back_face_color) ? u_back_color : front_base();
    if (back) n = -n;
    // Darken towards the rim so that a point reads as a small ball.
    vec3 color = lit(base, n) * (0.65 + 0.35 * sqrt(1.0 - r2));
    frag_color = vec4(apply_fog(color), 1.0);
}
#else
void main() {
#ifdef TRILAB_SELECTION
    float outline = selection_outline_coverage();
#endif
    bool back = !gl_FrontFacing && u_back_face_color;
    vec3 color = vec3(0.0);
    if (u_surface == 0) {
        vec3 n;
        if (u_flat) {
            // The triangle's plane from screen-space derivatives; this normal always faces
            // the viewer, so it is not flipped for back faces.
            n = cross(dFdx(fs_in.position), dFdy(fs_in.position));
        } else if (u_facing_normals) {
            n = dot(fs_in.normal, fs_in.position) > 0.0 ? -fs_in.normal : fs_in.normal;
        } else {
            n = gl_FrontFacing ? fs_in.normal : -fs_in.normal;
        }
        float len = length(n);
        n = len > 0.0 ? n / len : vec3(0.0, 0.0, 1.0);
        if (back) {
            color = lit(u_back_color, n);
#ifndef TRILAB_NO_TEXTURE
        } else if (u_texture_mode == 2) {
            color = texture(u_texture, fs_in.texcoord).rgb;
        } else if (u_texture_mode == 1) {
#ifdef TRILAB_NO_VERTEX_COLOR
            vec3 tint = vec3(1.0);
#else
            vec3 tint = u_use_vertex_color ? vertex_color() : vec3(1.0);
#endif
            color = lit(texture(u_texture, fs_in.texcoord).rgb * tint, n);
#endif
        } else {
            color = lit(front_base(), n);
        }
#ifdef TRILAB_SCALAR
        float iso = isoline_coverage();
        color = mix(color, isoline_color(color), iso);
#endif
#ifdef TRILAB_SELECTION
        float weight = clamp(fs_in.selection, 0.0, 1.0);
        color = mix(color, u_selection_tint, u_selection_strength * weight);
        color = mix(color, u_selection_outline, outline);
#endif
        color = apply_fog(color);
    } else if (u_surface == 1) {
        color = back ? mix(u_background, u_back_color, 0.3) : u_background;
    }

#ifdef TRILAB_WIREFRAME
    // Distance to the nearest edge in pixels; each side of an edge draws half the width.
    vec3 pixels = fs_in.barycentric / max(fwidth(fs_in.barycentric), vec3(1e-6));
    float d = min(min(pixels.x, pixels.y), pixels.z);
    float half_width = 0.5 * u_wire_width;
    float edge = 1.0 - smoothstep(half_width - 0.5, half_width + 0.5, d);
    vec3 wire = u_wire_color;
    if (u_surface == 2) {
        // Edges only, blended over what is there; back-facing triangles' edges fade.
        if (edge <= 0.0) discard;
        if (back) wire = mix(wire, u_background, 0.6);
        frag_color = vec4(apply_fog(wire), edge);
        return;
    }
    color = mix(color, apply_fog(wire), edge);
#endif
    frag_color = vec4(color, 1.0);
}
#endif
