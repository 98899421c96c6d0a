#pragma once
// MeshRenderer: the GPU mirror of one HalfedgeMesh and the shaders that draw it.
//
// The renderer never owns the mesh; upload() copies positions, normals, optional texture
// coordinates ("v:texcoord", or per-corner "h:texcoord" with seams kept) and the triangles.
// Only what changed is uploaded: show() compares the mesh's revisions (HalfedgeMesh::revision())
// with what the GPU holds and does nothing, update_positions() or upload();
// set_vertex_colors() rewrites colours only. upload_level() / update_level() show a
// LevelOfDetail (core/algorithms/decimation.h) with index-buffer rewrites and only the changed
// vertices. Normals are the mesh's "v:normal" when it has one (the caller keeps it fresh),
// else area-weighted vertex normals. Draw modes and overlays: RenderStyle; the shader
// variants, buffer layouts and the level-of-detail path are described in mesh_renderer.cpp.
//
// Every member function needs the GL 3.3 core context that was current at construction.
// render/ never includes ImGui: the viewer edits a RenderStyle and calls draw().
#include <glad/gl.h>

#include <array>
#include <cstddef>
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "core/algorithms/coloring.h"
#include "core/algorithms/level_of_detail.h"
#include "core/halfedge_mesh.h"
#include "core/io/image_io.h"
#include "render/gl_program.h"

namespace trilab {

/// What draw() draws. Names for menus and the CLI: render_mode_name() / parse_render_mode().
enum class RenderMode {
    Wireframe,   ///< every triangle edge, hidden ones too (no surface)
    HiddenLine,  ///< the edges that a surface in the background colour does not hide
    Flat,        ///< one normal per triangle
    Smooth,      ///< Gouraud-style: vertex normals interpolated, lit per fragment
    Points,      ///< one round point per vertex, lit by its normal
    Textured,    ///< Smooth with the texture applied as texture_mode says
};

/// How Textured mode combines the texture with the shading. Off draws Textured mode exactly
/// like Smooth. Without a texture (MeshRenderer::has_texture()) or texture coordinates
/// (MeshRenderer::has_texcoords()) Textured mode also draws like Smooth: the caller tells
/// the user why.
enum class TextureMode {
    Off,
    Modulate,  ///< texture colour (x the vertex colour when shown), then lit
    Replace,   ///< the texture colour as it is, unlit
};

/// How a scalar colouring (MeshRenderer::set_vertex_scalars()) is shown. N is
/// RenderStyle::scalar_steps: the legend range cut into N equal steps.
enum class ScalarDisplay {
    Smooth,            ///< the vertex colours as they are (a continuous map)
    Bands,             ///< each step one colour: the map's colour at the step's centre
    Isolines,          ///< the vertex colours with a line at each of the N - 1 step boundaries
    BandsAndIsolines,  ///< both: lines between the bands
};
/// "smooth", "bands", "isolines", "bands-isolines".
const char* scalar_display_name(ScalarDisplay display);
/// Parses scalar_display_name() strings; throws InvalidArgument listing them otherwise.
ScalarDisplay parse_scalar_display(const std::string& name);
/// The fewest and most steps of a scalar display (RenderStyle::scalar_steps).
constexpr int kMinScalarSteps = 2, kMaxScalarSteps = 64;

/// Every switch of draw(). A plain struct: copy it, edit it, pass it. Colours are linear RGB
/// in [0, 1]; widths and sizes are in framebuffer pixels (multiply by the HiDPI scale).
struct RenderStyle {
    RenderMode mode = RenderMode::Smooth;
    /// Overlay the triangle edges on the shaded modes (Flat, Smooth, Textured). Wireframe and
    /// HiddenLine always draw edges; Points ignores it.
    bool wireframe = false;
    float wire_width = 1.0f;                    ///< total edge width in pixels (anti-aliased)
    glm::vec3 wire_color{0.10f, 0.12f, 0.16f};  ///< edges of the overlay
    glm::vec3 line_color{0.86f, 0.89f, 0.93f};  ///< edges of Wireframe and HiddenLine modes

    /// Back faces (the side facing away from the normal's orientation) in back_color, in
    /// every mode: shaded modes use it as base colour, HiddenLine tints its surface with it,
    /// Wireframe draws the edges of back-facing triangles faded towards the background, and
    /// Points colours points whose normal faces away. Off: both sides look alike.
    bool back_face_color = true;
    /// Let draw() skip back faces where none can be seen (see culls_back_faces()).
    bool cull_hidden_back_faces = true;
    /// Shade each fragment of the shaded modes with its interpolated normal turned towards
    /// the viewer, and no back colour: for a clustered stand-in, whose folded triangles (a
    /// cluster mean that inverts a triangle) would otherwise show as dark back-face specks
    /// inside a surface that faces the viewer.
    bool facing_normals = false;
    glm::vec3 front_color{0.50f, 0.62f, 0.80f};  ///< base colour without vertex colours
    glm::vec3 back_color{0.85f, 0.42f, 0.30f};

    /// Vertex colours (MeshRenderer::set_vertex_colors()) replace front_color when set. This
    /// switch hides them without discarding the uploaded buffer.
    bool vertex_colors = true;

    /// Scalar colourings (uploaded with set_vertex_scalars()) as bands and/or isolines, in
    /// the shaded modes (Flat, Smooth, Textured); Points, Wireframe and HiddenLine ignore it.
    /// Bands replace the vertex colours, so they show only while vertex_colors is on;
    /// isolines also draw over the plain shading. Smooth draws exactly as without scalars.
    ScalarDisplay scalar_display = ScalarDisplay::Smooth;
    int scalar_steps = 10;        ///< N, clamped to [kMinScalarSteps, kMaxScalarSteps]
    float isoline_width = 1.25f;  ///< total isoline width in pixels (anti-aliased)

    float point_size = 4.0f;  ///< diameter of a point in Points mode, pixels
    /// Points mode: an invisible surface (depth only) hides the points behind it, as
    /// HiddenLine does for edges. Off: every point shows (meshes without faces always).
    bool occlude_points = true;

    // Lighting: one head light (light and eye coincide).
    float ambient = 0.15f;            ///< fraction of the base colour lit regardless of the normal
    bool specular = true;             ///< Blinn-Phong highlight on/off (viewer key S)
    float specular_strength = 0.25f;  ///< strength of the white highlight
    float shininess = 64.0f;          ///< Blinn-Phong exponent

    /// Fog by depth (viewer key F): blends towards `background`, linearly from nothing at the
    /// depth of the mesh's nearest bounding-box corner to fog_amount at the farthest one.
    bool fog = false;
    float fog_amount = 0.85f;  ///< in [0, 1]
    /// The background colour: clear_background() clears to it, fog fades to it, HiddenLine
    /// paints its surface in it.
    glm::vec3 background{0.16f, 0.17f, 0.19f};

    TextureMode texture_mode = TextureMode::Modulate;  ///< used by Textured mode only

    // Vectors: segments of vector_length x (bounding-box diagonal of the mesh), 1 pixel wide.
    bool face_normals = false;    ///< one per triangle, from its centroid
    bool vertex_normals = false;  ///< one per vertex
    float vector_length = 0.02f;
    glm::vec3 face_normal_color{0.95f, 0.80f, 0.20f};
    glm::vec3 vertex_normal_color{0.30f, 0.85f, 0.45f};

    /// The selection overlay (MeshRenderer::set_vertex_selection(), issue 26) in the shaded
    /// modes (Flat, Smooth, Textured): the colour is blended towards selection_tint by
    /// selection_tint_strength × weight, so the colouring under it still reads, and the
    /// weight-0.5 contour is drawn as an outline selection_outline_width pixels wide. Points,
    /// Wireframe and HiddenLine do not show it. Off, or without weights: the image is exactly
    /// the one without a selection.
    bool selection_overlay = true;
    glm::vec3 selection_tint{1.00f, 0.62f, 0.10f};
    float selection_tint_strength = 0.40f;  ///< in [0, 1]: the blend at weight 1
    glm::vec3 selection_outline{1.00f, 0.86f, 0.30f};
    float selection_outline_width = 2.0f;  ///< pixels; 0: no outline
};

/// How vertex colours fill a triangle between its corners.
enum class ColorBlend {
    Interpolate,  ///< blended across the triangle (values: curvature, distance, ...)
    /// Every point takes the colour of its nearest corner (largest barycentric coordinate):
    /// for categories (the subdivision level), whose blends would show colours that are in
    /// no legend.
    NearestCorner,
};
/// The blend that shows colours of map `kind` truthfully: NearestCorner for Categorical,
/// Interpolate otherwise.
ColorBlend color_blend(ColorMapKind kind);

/// "wireframe", "hidden-line", "flat", "gouraud", "points", "textured".
const char* render_mode_name(RenderMode mode);
/// Parses render_mode_name() strings ("smooth" is accepted for "gouraud"). Throws
/// InvalidArgument listing the names otherwise.
RenderMode parse_render_mode(const std::string& name);
/// "off", "modulate", "replace".
const char* texture_mode_name(TextureMode mode);

/// Clears colour and depth of the bound framebuffer (all of it, unless a scissor box is
/// set) to style.background with the given alpha. Use alpha 0 for a transparent background: then
/// clear_background() clears to (0, 0, 0, 0) so that the drawn pixels are premultiplied by alpha.
void clear_background(const RenderStyle& style, float alpha = 1.0f);

class MeshRenderer {
public:
    /// Compiles every program variant. Throws GlError (with the driver's log) if one fails.
    MeshRenderer();
    ~MeshRenderer();
    MeshRenderer(const MeshRenderer&) = delete;
    MeshRenderer& operator=(const MeshRenderer&) = delete;

    /// What show() had to do.
    enum class Update { None, Positions, Full };
    /// Makes the GPU show `mesh`, doing only what its revisions (HalfedgeMesh::revision())
    /// say changed since the last upload: nothing, positions and normals (update_positions()),
    /// or everything (upload(), which drops the vertex colours). The one upload decision the
    /// viewer uses.
    Update show(const HalfedgeMesh& mesh);
    /// Whether the GPU shows exactly `mesh` (same revisions, no level of detail).
    bool shows(const HalfedgeMesh& mesh) const;
    /// Whether the GPU holds the faces and attributes of `mesh` (positions may differ).
    bool shows_topology_of(const HalfedgeMesh& mesh) const;

    /// Copies positions, normals, texture coordinates and triangles of `mesh` to the GPU,
    /// replacing what was there, and drops the vertex colours. Vertices are addressed by
    /// storage index, so a mesh with deleted elements (garbage) draws correctly.
    /// O(vertices + faces).
    void upload(const HalfedgeMesh& mesh);
    /// Rewrites positions and normals only. Falls back to upload() unless the GPU holds the
    /// faces and attributes of `mesh` (shows_topology_of()). O(vertices + faces).
    void update_positions(const HalfedgeMesh& mesh);
    /// The same with positions given apart from the mesh (one per vertex storage index of
    /// `topology`), for morph frames: normals are computed from these positions (a stored
    /// "v:normal" is ignored). Uploads `topology` first unless the GPU holds its faces and
    /// attributes. Throws InvalidArgument on a size mismatch.
    void update_positions(const HalfedgeMesh& topology, const std::vector<Point>& positions);
    /// Shows the current level of `lod`: uploads positions and normals of every vertex, the
    /// live triangles and vertices, drops texture coordinates and vertex colours, and clears
    /// the level of detail's changes (this renderer consumes them). O(fine vertices + faces).
    void upload_level(LevelOfDetail& lod);
    /// Shows the current level of `lod` after set_level(): the index buffers and the vertices
    /// that changed since the last upload_level()/update_level() (see the top of this file);
    /// clears the changes. Falls back to upload_level() when the last upload was not of a
    /// level of detail of this size. O(fine faces + changed vertices), O(fine vertices +
    /// faces) when all changed.
    void update_level(LevelOfDetail& lod);
    /// Forgets the uploaded mesh and colours; draw() then draws nothing. Keeps the texture.
    void clear();
    /// Shows a bare triangle list (a proxy, core/algorithms/proxy_mesh.h): `positions` one per
    /// vertex, `triangles` over them (non-manifold lists are fine), area-weighted vertex
    /// normals, every vertex a point. Replaces what was uploaded and drops texture
    /// coordinates, vertex colours, scalars and the selection; set_vertex_colors(),
    /// set_vertex_texcoords() and set_vertex_selection() then take one value per position.
    /// Back faces are never culled (a proxy need not be closed). Throws InvalidArgument for a
    /// corner outside `positions`. O(vertices + triangles).
    void upload_triangles(const std::vector<Point>& positions,
                          const std::vector<std::array<Index, 3>>& triangles);
    /// Texture coordinates, one per vertex, for what was uploaded without per-corner ones (the
    /// triangle list of upload_triangles(): a proxy of a textured mesh): Textured mode then
    /// draws it with the texture. Throws InvalidArgument on a size mismatch or when the GPU
    /// holds per-corner vertices (a mesh uploaded with "h:texcoord" seams).
    void set_vertex_texcoords(const std::vector<TexCoord>& texcoords);

    /// Per-vertex colours indexed by vertex storage index (size == n_vertices(), the storage
    /// size at the last upload()); they replace front_color while style.vertex_colors is on,
    /// filling triangles as `blend` says (pass color_blend(colors.kind) for a VertexColors).
    /// Uploads the colours only (the first NearestCorner call also builds its shaders) and
    /// drops the vertex scalars (colours given alone have none). Throws InvalidArgument on a
    /// size mismatch, GlError when a shader does not build.
    void set_vertex_colors(const std::vector<Color>& colors,
                           ColorBlend blend = ColorBlend::Interpolate);
    /// A colouring as a whole: its colours (blend color_blend(colors.kind)) and, for a
    /// sequential or diverging one with values, its values as vertex scalars over its
    /// legend range (set_vertex_scalars()), so that style.scalar_display can show bands and
    /// isolines; categorical and value-less colourings (Normal) get no scalars.
    void set_vertex_colors(const VertexColors& colors);
    /// Drops the vertex colours and the vertex scalars.
    void clear_vertex_colors();
    bool has_vertex_colors() const { return has_colors_; }
    ColorBlend vertex_color_blend() const { return color_blend_; }

    /// Per-vertex scalars (storage index, size == n_vertices(); NaN: no value) for
    /// style.scalar_display: each is uploaded as t = (value - range.min) / (range.max -
    /// range.min), so that step k of N is t in [k/N, (k+1)/N); `map` colours the bands
    /// (Sequential or Diverging). Without vertex colours isolines still draw over the plain
    /// shading. Kept by update_positions() and update_level(); upload(), upload_level() and
    /// the colour calls drop them (call this after set_vertex_colors(vector)). The first
    /// call builds the scalar shaders. Throws InvalidArgument on a size mismatch, a
    /// categorical map or a range that is not finite with min < max; GlError when a shader
    /// does not build.
    void set_vertex_scalars(const std::vector<double>& values, const ValueRange& range,
                            ColorMapKind map);
    void clear_vertex_scalars();
    bool has_vertex_scalars() const { return has_scalars_; }

    /// The selection's weight per vertex storage index (size == n_vertices(), each in [0, 1];
    /// a value outside is clamped) for style.selection_overlay. Kept by update_positions(),
    /// update_level() and the colour calls; upload(), upload_level() and clear() drop it. The
    /// first call builds the overlay's shaders. Throws InvalidArgument on a size mismatch,
    /// GlError when a shader does not build. O(vertices).
    void set_vertex_selection(const std::vector<float>& weights);
    void clear_vertex_selection();
    bool has_vertex_selection() const { return has_selection_; }

    /// Uploads `image` (RGBA8, rows top-down) as the texture of Textured mode, with mipmaps
    /// and repeat wrapping; texture coordinate (0, 0) is the image's bottom-left corner (the
    /// OBJ convention). Throws InvalidArgument for an empty image or one above the GL limit.
    void set_texture(const Image& image);
    void clear_texture();
    bool has_texture() const { return has_texture_; }
    /// Whether the uploaded mesh had texture coordinates ("v:texcoord" or "h:texcoord").
    bool has_texcoords() const { return has_texcoords_; }

    /// Draws the uploaded mesh (model matrix = identity) into the current framebuffer and
    /// viewport with depth testing; does not clear (see clear_background()). Leaves depth
    /// test enabled, blending disabled, and no program, VAO or texture bound.
    void draw(const glm::mat4& view, const glm::mat4& projection, const RenderStyle& style) const;

    /// Whether draw() may skip back-facing triangles because none can be seen: every
    /// component of the uploaded mesh is closed with positive volume (a ray from outside
    /// first meets a front face) and the whole mesh lies in front of the near plane (none of
    /// it is cut open). The image is the same; on a software renderer the frame is about
    /// half as long.
    bool culls_back_faces(const glm::mat4& view, const glm::mat4& projection) const;

    /// Vertex storage size of the uploaded mesh (what set_vertex_colors() expects).
    std::size_t n_vertices() const { return n_vertices_; }
    std::size_t n_triangles() const { return n_triangle_indices_ / 3; }
    /// Vertices on the GPU: n_vertices(), or more where per-corner texture coordinates split
    /// vertices at seams.
    std::size_t n_gpu_vertices() const { return n_gpu_vertices_; }
    /// Bounding box of the uploaded positions (live vertices), updated by update_positions().
    glm::vec3 bbox_min() const { return bbox_min_; }
    glm::vec3 bbox_max() const { return bbox_max_; }

private:
    /// No texture coordinates on the GPU (a level of detail or a triangle list has none).
    void drop_texcoords();
    /// The GPU holds faces and attributes of these revisions (positions may differ).
    bool holds_topology(const HalfedgeMesh::Revision& r) const;
    void write_geometry(const HalfedgeMesh& mesh,
                        const std::vector<Point>* moved_positions = nullptr);
    void write_level_vertex(const LevelOfDetail& lod, Index v);
    void write_level_indices(const LevelOfDetail& lod);
    void setup_vertex_array(GLuint vao, GLuint element_buffer) const;
    void set_common_uniforms(const GlProgram& program, const glm::mat4& view,
                             const glm::mat4& projection, const RenderStyle& style) const;
    /// The bands' and isolines' uniforms (the program in use has TRILAB_SCALAR).
    void set_scalar_uniforms(const GlProgram& program, const RenderStyle& style) const;

    /// The selection overlay's program for this draw (wires: with the geometry stage's edges;
    /// nearest_corner: categorical colours), its uniforms set by draw().
    const GlProgram& selection_program(bool wires, bool nearest_corner) const;
    void set_selection_uniforms(const GlProgram& program, const RenderStyle& style,
                                bool scalars) const;
    /// The overlay's (`selection`) or the bands' and isolines' (`scalars`) uniforms, if any.
    void set_display_uniforms(const GlProgram& program, const RenderStyle& style, bool selection,
                              bool scalars) const;

    /// The revisions of the mesh on the GPU (all 0: none, a level of detail, or positions
    /// given apart from the mesh).
    HalfedgeMesh::Revision shown_;
    /// mesh.vert + mesh.frag, indexed by (vertex colours read) + 2 (texture read): the
    /// variants without an input leave it out (TRILAB_NO_VERTEX_COLOR, TRILAB_NO_TEXTURE).
    std::array<GlProgram, 4> surface_programs_;
    /// Bands and isolines (RenderStyle::scalar_display other than Smooth, with scalars):
    /// mesh.vert + mesh.frag [TRILAB_SCALAR] with every input, and mesh.vert + mesh.geom +
    /// mesh.frag [TRILAB_SCALAR, TRILAB_WIREFRAME] for the edge overlay; built by the first
    /// set_vertex_scalars().
    std::array<GlProgram, 2> scalar_programs_;
    GlProgram wire_program_;  ///< mesh.vert + mesh.geom + mesh.frag [TRILAB_WIREFRAME]
    /// ColorBlend::NearestCorner: mesh.vert + mesh.geom + mesh.frag [TRILAB_NEAREST_CORNER],
    /// without and with TRILAB_WIREFRAME; built by the first set_vertex_colors() that needs
    /// them (few sessions do; each program costs about 20 ms to build on llvmpipe).
    std::array<GlProgram, 2> corner_programs_;
    /// The selection overlay: mesh.vert + mesh.frag [TRILAB_SCALAR, TRILAB_SELECTION] with every
    /// input, indexed by (edges: + mesh.geom, TRILAB_WIREFRAME) + 2 (TRILAB_NEAREST_CORNER);
    /// built by the first set_vertex_selection().
    std::array<GlProgram, 4> selection_programs_;
    GLuint selection_buffer_ = 0;  ///< one float per GPU vertex
    bool has_selection_ = false;
    GlProgram points_program_;         ///< mesh.vert + mesh.frag [TRILAB_POINTS]
    GlProgram depth_program_;          ///< mesh.vert + depth.frag
    GlProgram face_vector_program_;    ///< vectors.* [TRILAB_FACE_VECTORS]: triangles in
    GlProgram vertex_vector_program_;  ///< vectors.*: points in

    GLuint triangle_vao_ = 0, point_vao_ = 0;
    GLuint geometry_buffer_ = 0, color_buffer_ = 0, texcoord_buffer_ = 0, scalar_buffer_ = 0;
    GLuint triangle_buffer_ = 0, point_buffer_ = 0;
    GLuint texture_ = 0;

    /// GPU vertex -> mesh vertex storage index; empty when that is the identity.
    std::vector<Index> gpu_source_;
    std::size_t n_vertices_ = 0, n_gpu_vertices_ = 0;
    std::size_t n_triangle_indices_ = 0, n_point_indices_ = 0;
    bool has_colors_ = false, has_texcoords_ = false, has_texture_ = false;
    bool has_scalars_ = false;
    ColorMapKind scalar_map_ = ColorMapKind::Sequential;  ///< the bands' map
    ColorBlend color_blend_ = ColorBlend::Interpolate;
    /// The level-of-detail path: a copy of the vertex buffer (6 floats a vertex, position
    /// and normal) to patch changed vertices in; empty when the last upload was a mesh.
    std::vector<float> level_vertices_;
    glm::vec3 bbox_min_{0.0f}, bbox_max_{0.0f};
    /// Back faces can be culled exactly when every component is closed with positive volume
    /// (a ray from outside first hits a front face) and the whole box lies in front of the
    /// near plane (checked per draw): `component_of_vertex_` is filled (upload) only for a
    /// closed mesh, `outward_` is recomputed with every geometry write.
    std::vector<Index> component_of_vertex_;
    std::size_t n_components_ = 0;
    bool outward_ = false;
};

}  // namespace trilab
