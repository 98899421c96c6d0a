// How MeshRenderer (mesh_renderer.h) lays out its GPU data and draws it.
//
// The renderer never owns the mesh. upload() copies what it needs into GPU buffers:
//  - positions and normals (float, interleaved), one entry per GPU vertex;
//  - optional per-vertex colours (RGBA8), set_vertex_colors();
//  - optional per-vertex scalars (2 floats: t w and w, t the value normalized to the legend
//    range, w = 1 where there is a value), set_vertex_scalars(), for bands and isolines;
//  - optional texture coordinates (float), from "v:texcoord", or from per-corner
//    "h:texcoord": then every mesh vertex gets one GPU vertex per distinct texture coordinate
//    of its corners, so seams stay seams (positions, normals and colours are gathered through
//    that mapping);
//  - a uint32 index buffer of triangles and one of points (one GPU vertex per live mesh
//    vertex, isolated ones included).
// Upload only what changed: show() compares the mesh's revisions with `shown_`;
// update_positions() rewrites positions and normals for a pure geometry change,
// set_vertex_colors() rewrites the colours (and scalars) only, upload() (a topology or
// attribute change) rewrites everything and drops the vertex colours and scalars.
//
// Level of detail (LevelOfDetail, core/algorithms/decimation.h, for a slider over a progressive
// mesh): upload_level() puts every vertex of the fine mesh on the GPU once, in the level of
// detail's drawing order (positions and the level's area-weighted normals), with the live
// triangles and vertices; update_level() after LevelOfDetail::set_level() rewrites the index
// buffers (O(live faces): the software rasterizer wants the drawing order, which a list
// patched in place would lose) and only the vertices the move changed (a few ranges of the
// vertex buffer), or all of them when the level of detail reports that all changed. This
// path has no texture coordinates; upload_level() drops vertex colours and scalars
// (set_vertex_colors() and set_vertex_scalars() take them per level-of-detail vertex, and
// update_level() keeps them); the bounding box (fog, vector length) stays the one
// of upload_level().
//
// Normals: the mesh's "v:normal" (Vector3) when it has one, otherwise area-weighted vertex
// normals computed on the fly (the same as core's vertex_normal()). A caller that moves
// vertices of a mesh carrying "v:normal" must refresh that attribute (compute_vertex_normals)
// or remove it before update_positions(), or the shading uses the stale normals.
//
// Shaders (shaders/*.glsl, compiled at construction into program variants):
//  - mesh.vert + mesh.frag: Flat, Smooth and Textured without overlay. Lighting is per
//    fragment: a head light (light at the eye), ambient + Lambert + optional Blinn-Phong
//    specular. Flat normals come from screen-space derivatives.
//  - mesh.vert + mesh.geom + mesh.frag [TRILAB_WIREFRAME]: the geometry stage gives every
//    triangle corner barycentric coordinates, from which the fragment stage draws
//    anti-aliased edges of any width in pixels (glLineWidth > 1 is not available in core
//    profiles). Used for the overlay and for the Wireframe and HiddenLine modes. Without
//    wires no geometry stage runs, which matters on llvmpipe.
//  - mesh.vert + mesh.geom + mesh.frag [TRILAB_NEAREST_CORNER] (and [TRILAB_WIREFRAME]):
//    categorical vertex colours (ColorBlend::NearestCorner): the geometry stage hands every
//    fragment its triangle's three corner colours unblended, and the fragment takes the one of
//    the corner with the largest barycentric coordinate, so no blend of two categories (a
//    colour in no legend) appears. Points need nothing: a point has one vertex's colour.
//  - mesh.vert + mesh.frag [TRILAB_SCALAR] and mesh.vert + mesh.geom + mesh.frag
//    [TRILAB_SCALAR, TRILAB_WIREFRAME]: bands and isolines of the vertex scalars
//    (RenderStyle::scalar_display), used only when that is not Smooth, so the Smooth picture
//    comes from the same programs as without scalars; built by the first set_vertex_scalars().
//  - mesh.vert + mesh.frag [TRILAB_POINTS]: round, lit point sprites; mesh.vert + depth.frag
//    lays down the surface's depth first so that it hides the points behind it.
//  - vectors.vert + vectors.geom + vectors.frag: face normals (one segment per triangle, from
//    its centroid) and vertex normals (one per vertex), built on the GPU from the uploaded
//    positions, so they need no buffers of their own and follow update_positions().
#include "render/mesh_renderer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <glm/gtc/matrix_inverse.hpp>
#include <limits>
#include <utility>

#include "core/algorithms/mesh_stats.h"
#include "core/errors.h"

namespace trilab {
namespace {

/// One vertex as the vertex shaders read it (locations 0 and 1).
struct GpuVertex {
    float position[3];
    float normal[3];
};
static_assert(sizeof(GpuVertex) == 6 * sizeof(float), "GpuVertex must be tightly packed");

constexpr GLuint kPosition = 0, kNormal = 1, kColor = 2, kTexcoord = 3, kScalar = 4;
constexpr GLuint kSelection = 5;  ///< the selection overlay's weight (one float)

/// What upload() derives from the connectivity: the GPU vertices and the index buffers.
struct Layout {
    std::vector<Index> source;      ///< GPU vertex -> mesh vertex; empty = identity
    std::size_t n_gpu = 0;          ///< GPU vertex count
    std::vector<GLuint> triangles;  ///< 3 GPU vertices per live face
    std::vector<GLuint> points;     ///< one GPU vertex per live mesh vertex
    std::vector<float> texcoords;   ///< 2 per GPU vertex, or empty
};

Layout build_layout(const HalfedgeMesh& mesh) {
    Layout layout;
    const auto corner_uv = mesh.get_halfedge_property<TexCoord>("h:texcoord");
    const auto vertex_uv = mesh.get_vertex_property<TexCoord>("v:texcoord");
    layout.triangles.reserve(3 * mesh.n_faces());
    layout.points.reserve(mesh.n_vertices());

    if (!corner_uv) {
        // Shared vertices: GPU vertex i is mesh vertex i.
        layout.n_gpu = mesh.vertices_size();
        for (Face f : mesh.faces())
            for (Vertex v : mesh.face_vertices(f)) layout.triangles.push_back(v.idx());
        for (Vertex v : mesh.vertices()) layout.points.push_back(v.idx());
        if (vertex_uv) {
            layout.texcoords.resize(2 * layout.n_gpu, 0.0f);
            for (Vertex v : mesh.vertices()) {
                layout.texcoords[2 * v.idx()] = float(vertex_uv[v].x());
                layout.texcoords[2 * v.idx() + 1] = float(vertex_uv[v].y());
            }
        }
        return layout;
    }

    // Per-corner texture coordinates: one GPU vertex per (mesh vertex, distinct coordinate).
    // first[v] starts a chain (through chain[]) of the GPU vertices made for v.
    const Index none = kInvalidIndex;
    std::vector<Index> first(mesh.vertices_size(), none);
    std::vector<Index> chain;
    chain.reserve(mesh.vertices_size() + mesh.vertices_size() / 4);
    layout.source.reserve(chain.capacity());
    layout.texcoords.reserve(2 * chain.capacity());
    auto gpu_vertex = [&](Vertex v, float u, float w) -> Index {
        for (Index g = first[v.idx()]; g != none; g = chain[g])
            if (layout.texcoords[2 * g] == u && layout.texcoords[2 * g + 1] == w) return g;
        const Index g = Index(layout.source.size());
        layout.source.push_back(v.idx());
        layout.texcoords.push_back(u);
        layout.texcoords.push_back(w);
        chain.push_back(first[v.idx()]);
        first[v.idx()] = g;
        return g;
    };
    for (Face f : mesh.faces())
        for (Halfedge h : mesh.halfedges_of(f)) {
            const TexCoord& t = corner_uv[h];
            layout.triangles.push_back(gpu_vertex(mesh.to_vertex(h), float(t.x()), float(t.y())));
        }
    for (Vertex v : mesh.vertices()) {
        if (first[v.idx()] == none) {  // isolated: no corner
            TexCoord t = vertex_uv ? vertex_uv[v] : TexCoord(0, 0);
            gpu_vertex(v, float(t.x()), float(t.y()));
        }
        layout.points.push_back(first[v.idx()]);
    }
    layout.n_gpu = layout.source.size();
    return layout;
}

/// Area-weighted vertex normals by storage index (vertex_normal() for all vertices at once).
std::vector<Vector3> area_weighted_normals(const HalfedgeMesh& mesh, const std::vector<Point>& p) {
    std::vector<Vector3> normals(mesh.vertices_size(), Vector3::Zero());
    for (Face f : mesh.faces()) {
        const auto c = mesh.face_vertices(f);
        const Point& p0 = p[c[0].idx()];
        const Vector3 n = (p[c[1].idx()] - p0).cross(p[c[2].idx()] - p0);
        for (Vertex v : c) normals[v.idx()] += n;
    }
    for (Vector3& n : normals) {
        const double len = n.norm();
        if (len > 0) n /= len;
    }
    return normals;
}

GLsizeiptr bytes(std::size_t n, std::size_t size) {
    return GLsizeiptr(n * size);
}

}  // namespace

const char* render_mode_name(RenderMode mode) {
    switch (mode) {
        case RenderMode::Wireframe:
            return "wireframe";
        case RenderMode::HiddenLine:
            return "hidden-line";
        case RenderMode::Flat:
            return "flat";
        case RenderMode::Smooth:
            return "gouraud";
        case RenderMode::Points:
            return "points";
        case RenderMode::Textured:
            return "textured";
    }
    return "?";
}

RenderMode parse_render_mode(const std::string& name) {
    for (RenderMode m : {RenderMode::Wireframe, RenderMode::HiddenLine, RenderMode::Flat,
                         RenderMode::Smooth, RenderMode::Points, RenderMode::Textured})
        if (name == render_mode_name(m)) return m;
    if (name == "smooth") return RenderMode::Smooth;
    throw InvalidArgument("unknown render mode '" + name +
                          "' (expected gouraud, flat, wireframe, hidden-line, points or textured)");
}

const char* scalar_display_name(ScalarDisplay display) {
    switch (display) {
        case ScalarDisplay::Smooth:
            return "smooth";
        case ScalarDisplay::Bands:
            return "bands";
        case ScalarDisplay::Isolines:
            return "isolines";
        case ScalarDisplay::BandsAndIsolines:
            return "bands-isolines";
    }
    return "?";
}

ScalarDisplay parse_scalar_display(const std::string& name) {
    for (ScalarDisplay d : {ScalarDisplay::Smooth, ScalarDisplay::Bands, ScalarDisplay::Isolines,
                            ScalarDisplay::BandsAndIsolines})
        if (name == scalar_display_name(d)) return d;
    throw InvalidArgument("unknown scalar display '" + name +
                          "' (expected smooth, bands, isolines or bands-isolines)");
}

const char* texture_mode_name(TextureMode mode) {
    switch (mode) {
        case TextureMode::Off:
            return "off";
        case TextureMode::Modulate:
            return "modulate";
        case TextureMode::Replace:
            return "replace";
    }
    return "?";
}

void clear_background(const RenderStyle& style, float alpha) {
    if (alpha <= 0.0f) {
        glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
    } else {
        glClearColor(style.background.r, style.background.g, style.background.b, alpha);
    }
    glDepthMask(GL_TRUE);
    glClearDepth(1.0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
}

namespace {

GlProgram surface_variant(bool vertex_colors, bool texture) {
    std::vector<std::string> defines;
    if (!vertex_colors) defines.push_back("TRILAB_NO_VERTEX_COLOR");
    if (!texture) defines.push_back("TRILAB_NO_TEXTURE");
    return GlProgram({embedded_shader("mesh.vert.glsl"),
                      with_defines(embedded_shader("mesh.frag.glsl"), defines)});
}

/// Bands and isolines: every input, and the geometry stage for edges (`wires`).
GlProgram scalar_variant(bool wires) {
    std::vector<std::string> defines{"TRILAB_SCALAR"};
    if (!wires)
        return GlProgram({with_defines(embedded_shader("mesh.vert.glsl"), defines),
                          with_defines(embedded_shader("mesh.frag.glsl"), defines)});
    defines.push_back("TRILAB_WIREFRAME");
    return GlProgram({with_defines(embedded_shader("mesh.vert.glsl"), defines),
                      with_defines(embedded_shader("mesh.geom.glsl"), defines),
                      with_defines(embedded_shader("mesh.frag.glsl"), defines)});
}

/// The selection overlay: every input, the scalar display (off without scalars) and the
/// selection's weight; the geometry stage for edges (`wires`) or categorical colours.
GlProgram selection_variant(bool wires, bool nearest_corner) {
    std::vector<std::string> defines{"TRILAB_SCALAR", "TRILAB_SELECTION"};
    if (wires) defines.push_back("TRILAB_WIREFRAME");
    if (nearest_corner) defines.push_back("TRILAB_NEAREST_CORNER");
    if (!wires && !nearest_corner)
        return GlProgram({with_defines(embedded_shader("mesh.vert.glsl"), defines),
                          with_defines(embedded_shader("mesh.frag.glsl"), defines)});
    return GlProgram({with_defines(embedded_shader("mesh.vert.glsl"), defines),
                      with_defines(embedded_shader("mesh.geom.glsl"), defines),
                      with_defines(embedded_shader("mesh.frag.glsl"), defines)});
}

/// The programs with the geometry stage: edges (`wires`) and/or nearest-corner colours.
GlProgram geometry_stage_variant(bool wires, bool nearest_corner) {
    std::vector<std::string> defines;
    if (wires) defines.push_back("TRILAB_WIREFRAME");
    if (nearest_corner) defines.push_back("TRILAB_NEAREST_CORNER");
    return GlProgram({embedded_shader("mesh.vert.glsl"),
                      with_defines(embedded_shader("mesh.geom.glsl"), defines),
                      with_defines(embedded_shader("mesh.frag.glsl"), defines)});
}

// Whether every corner of the box [lo, hi] lies strictly in front of the near plane of
// `clip` (projection * view): no part of the mesh is cut open by it.
bool in_front_of_near_plane(const glm::mat4& clip, const glm::vec3& lo, const glm::vec3& hi) {
    for (int i = 0; i < 8; ++i) {
        const glm::vec4 c = clip * glm::vec4((i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y,
                                             (i & 4) ? hi.z : lo.z, 1.0f);
        if (!(c.w > 0.0f && c.z > -c.w)) return false;
    }
    return true;
}

}  // namespace

MeshRenderer::MeshRenderer()
    : surface_programs_{surface_variant(false, false), surface_variant(true, false),
                        surface_variant(false, true), surface_variant(true, true)},
      wire_program_(geometry_stage_variant(true, false)),
      points_program_({embedded_shader("mesh.vert.glsl"),
                       with_defines(embedded_shader("mesh.frag.glsl"), {"TRILAB_POINTS"})}),
      depth_program_({embedded_shader("mesh.vert.glsl"), embedded_shader("depth.frag.glsl")}),
      face_vector_program_(
          {embedded_shader("vectors.vert.glsl"),
           with_defines(embedded_shader("vectors.geom.glsl"), {"TRILAB_FACE_VECTORS"}),
           embedded_shader("vectors.frag.glsl")}),
      vertex_vector_program_({embedded_shader("vectors.vert.glsl"),
                              embedded_shader("vectors.geom.glsl"),
                              embedded_shader("vectors.frag.glsl")}) {
    glGenVertexArrays(1, &triangle_vao_);
    glGenVertexArrays(1, &point_vao_);
    GLuint buffers[6];
    glGenBuffers(6, buffers);
    geometry_buffer_ = buffers[0];
    color_buffer_ = buffers[1];
    texcoord_buffer_ = buffers[2];
    triangle_buffer_ = buffers[3];
    point_buffer_ = buffers[4];
    scalar_buffer_ = buffers[5];
    setup_vertex_array(triangle_vao_, triangle_buffer_);
    setup_vertex_array(point_vao_, point_buffer_);
    glGenBuffers(1, &selection_buffer_);
    for (GLuint vao : {triangle_vao_, point_vao_}) {
        glBindVertexArray(vao);
        glBindBuffer(GL_ARRAY_BUFFER, selection_buffer_);
        glVertexAttribPointer(kSelection, 1, GL_FLOAT, GL_FALSE, sizeof(float), nullptr);
    }
    glBindVertexArray(0);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
}

MeshRenderer::~MeshRenderer() {
    const GLuint buffers[6] = {geometry_buffer_, color_buffer_, texcoord_buffer_,
                               triangle_buffer_, point_buffer_, scalar_buffer_};
    glDeleteBuffers(6, buffers);
    glDeleteBuffers(1, &selection_buffer_);
    glDeleteVertexArrays(1, &point_vao_);
    glDeleteVertexArrays(1, &triangle_vao_);
    if (texture_ != 0) glDeleteTextures(1, &texture_);
}

void MeshRenderer::setup_vertex_array(GLuint vao, GLuint element_buffer) const {
    glBindVertexArray(vao);
    glBindBuffer(GL_ARRAY_BUFFER, geometry_buffer_);
    glEnableVertexAttribArray(kPosition);
    glVertexAttribPointer(kPosition, 3, GL_FLOAT, GL_FALSE, sizeof(GpuVertex),
                          reinterpret_cast<const void*>(offsetof(GpuVertex, position)));
    glEnableVertexAttribArray(kNormal);
    glVertexAttribPointer(kNormal, 3, GL_FLOAT, GL_FALSE, sizeof(GpuVertex),
                          reinterpret_cast<const void*>(offsetof(GpuVertex, normal)));
    glBindBuffer(GL_ARRAY_BUFFER, color_buffer_);
    glVertexAttribPointer(kColor, 4, GL_UNSIGNED_BYTE, GL_TRUE, 4, nullptr);
    glBindBuffer(GL_ARRAY_BUFFER, texcoord_buffer_);
    glVertexAttribPointer(kTexcoord, 2, GL_FLOAT, GL_FALSE, 2 * sizeof(float), nullptr);
    glBindBuffer(GL_ARRAY_BUFFER, scalar_buffer_);
    glVertexAttribPointer(kScalar, 2, GL_FLOAT, GL_FALSE, 2 * sizeof(float), nullptr);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, element_buffer);  // recorded in the VAO
    glBindVertexArray(0);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
}

MeshRenderer::Update MeshRenderer::show(const HalfedgeMesh& mesh) {
    const HalfedgeMesh::Revision r = mesh.revision();
    if (!holds_topology(r)) {
        upload(mesh);
        return Update::Full;
    }
    if (shown_.geometry == r.geometry) return Update::None;
    write_geometry(mesh);
    shown_.geometry = r.geometry;
    return Update::Positions;
}

bool MeshRenderer::shows(const HalfedgeMesh& mesh) const {
    const HalfedgeMesh::Revision r = mesh.revision();
    return holds_topology(r) && shown_.geometry == r.geometry;
}

bool MeshRenderer::shows_topology_of(const HalfedgeMesh& mesh) const {
    return holds_topology({mesh.topology_revision(), 0, mesh.attribute_revision()});
}

bool MeshRenderer::holds_topology(const HalfedgeMesh::Revision& r) const {
    // Revisions are never 0, so nothing uploaded (all 0) never matches.
    return level_vertices_.empty() && shown_.topology == r.topology &&
           shown_.attributes == r.attributes;
}

void MeshRenderer::upload(const HalfedgeMesh& mesh) {
    shown_ = mesh.revision();
    level_vertices_.clear();
    Layout layout = build_layout(mesh);
    gpu_source_ = std::move(layout.source);
    n_vertices_ = mesh.vertices_size();
    n_gpu_vertices_ = layout.n_gpu;
    component_of_vertex_.clear();
    n_components_ = 0;
    bool closed = mesh.n_faces() > 0;
    for (Edge e : mesh.edges())
        if (mesh.is_boundary(e)) {
            closed = false;
            break;
        }
    if (closed) n_components_ = label_components(mesh, component_of_vertex_);
    write_geometry(mesh);

    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, 0);  // no VAO bound: safe to use the binding point
    glBindBuffer(GL_ARRAY_BUFFER, triangle_buffer_);
    glBufferData(GL_ARRAY_BUFFER, bytes(layout.triangles.size(), sizeof(GLuint)),
                 layout.triangles.data(), GL_STATIC_DRAW);
    glBindBuffer(GL_ARRAY_BUFFER, point_buffer_);
    glBufferData(GL_ARRAY_BUFFER, bytes(layout.points.size(), sizeof(GLuint)), layout.points.data(),
                 GL_STATIC_DRAW);
    n_triangle_indices_ = layout.triangles.size();
    n_point_indices_ = layout.points.size();

    has_texcoords_ = !layout.texcoords.empty();
    glBindBuffer(GL_ARRAY_BUFFER, texcoord_buffer_);
    glBufferData(GL_ARRAY_BUFFER, bytes(layout.texcoords.size(), sizeof(float)),
                 layout.texcoords.data(), GL_STATIC_DRAW);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    for (GLuint vao : {triangle_vao_, point_vao_}) {
        glBindVertexArray(vao);
        if (has_texcoords_)
            glEnableVertexAttribArray(kTexcoord);
        else
            glDisableVertexAttribArray(kTexcoord);
    }
    glBindVertexArray(0);
    clear_vertex_colors();
    clear_vertex_selection();
}

void MeshRenderer::update_positions(const HalfedgeMesh& mesh) {
    if (!shows_topology_of(mesh)) {
        upload(mesh);
        return;
    }
    write_geometry(mesh);
    shown_.geometry = mesh.geometry_revision();
}

void MeshRenderer::update_positions(const HalfedgeMesh& topology,
                                    const std::vector<Point>& positions) {
    if (positions.size() != topology.vertices_size())
        throw InvalidArgument(
            "MeshRenderer::update_positions: " + std::to_string(positions.size()) +
            " positions for a mesh with vertex storage size " +
            std::to_string(topology.vertices_size()));
    if (!shows_topology_of(topology)) upload(topology);
    write_geometry(topology, &positions);
    shown_.geometry = 0;  // not the mesh's own positions
}

void MeshRenderer::write_level_vertex(const LevelOfDetail& lod, Index v) {
    const Point& p = lod.positions()[v];
    const Vector3 n = lod.vertex_normal(v);
    float* out = &level_vertices_[6 * std::size_t(v)];
    out[0] = float(p.x());
    out[1] = float(p.y());
    out[2] = float(p.z());
    out[3] = float(n.x());
    out[4] = float(n.y());
    out[5] = float(n.z());
}

namespace {

// Uploads the elements `changed` (indices into `data`, `stride` bytes each) of the bound
// GL_ARRAY_BUFFER in runs: neighbours up to kGap elements apart go in one call; with more
// than kMaxRuns runs the whole of `data` (`n` elements) goes in one call instead.
void upload_runs(std::vector<Index> changed, const void* data, std::size_t stride, std::size_t n) {
    constexpr Index kGap = 32;
    constexpr std::size_t kMaxRuns = 256;
    std::sort(changed.begin(), changed.end());
    std::vector<std::pair<Index, Index>> runs;  // [first, last]
    for (Index i : changed) {
        if (!runs.empty() && i <= runs.back().second + kGap)
            runs.back().second = i;
        else
            runs.emplace_back(i, i);
    }
    const auto* bytes_of = static_cast<const char*>(data);
    if (runs.size() > kMaxRuns) {
        glBufferSubData(GL_ARRAY_BUFFER, 0, bytes(n, stride), bytes_of);
        return;
    }
    for (const auto& [first, last] : runs)
        glBufferSubData(GL_ARRAY_BUFFER, GLintptr(std::size_t(first) * stride),
                        bytes(std::size_t(last - first) + 1, stride),
                        bytes_of + std::size_t(first) * stride);
}

}  // namespace

void MeshRenderer::write_level_indices(const LevelOfDetail& lod) {
    static_assert(sizeof(std::array<Index, 3>) == 3 * sizeof(GLuint) && sizeof(Index) == 4,
                  "triangles must be tightly packed uint32 triples");
    const auto& triangles = lod.triangles();
    const auto& points = lod.live_vertices();
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, 0);  // no VAO bound: safe to use the binding point
    glBindBuffer(GL_ARRAY_BUFFER, triangle_buffer_);
    glBufferData(GL_ARRAY_BUFFER, bytes(triangles.size(), 3 * sizeof(GLuint)), triangles.data(),
                 GL_DYNAMIC_DRAW);
    glBindBuffer(GL_ARRAY_BUFFER, point_buffer_);
    glBufferData(GL_ARRAY_BUFFER, bytes(points.size(), sizeof(GLuint)), points.data(),
                 GL_DYNAMIC_DRAW);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    n_triangle_indices_ = 3 * triangles.size();
    n_point_indices_ = points.size();
}

void MeshRenderer::upload_level(LevelOfDetail& lod) {
    const std::size_t n = lod.positions().size();
    shown_ = {};
    gpu_source_.clear();
    component_of_vertex_.clear();
    n_components_ = 0;
    outward_ = false;
    n_vertices_ = n_gpu_vertices_ = n;
    level_vertices_.assign(6 * n, 0.0f);
    for (Index v = 0; v < n; ++v) write_level_vertex(lod, v);
    glBindBuffer(GL_ARRAY_BUFFER, geometry_buffer_);
    glBufferData(GL_ARRAY_BUFFER, bytes(level_vertices_.size(), sizeof(float)),
                 level_vertices_.data(), GL_DYNAMIC_DRAW);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    write_level_indices(lod);

    glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    for (Index v : lod.live_vertices()) {
        const float* x = &level_vertices_[6 * std::size_t(v)];
        lo = glm::min(lo, glm::vec3(x[0], x[1], x[2]));
        hi = glm::max(hi, glm::vec3(x[0], x[1], x[2]));
    }
    if (lod.live_vertices().empty()) lo = hi = glm::vec3(0.0f);
    bbox_min_ = lo;
    bbox_max_ = hi;

    drop_texcoords();
    clear_vertex_colors();
    clear_vertex_selection();
    lod.clear_changes();
}

void MeshRenderer::update_level(LevelOfDetail& lod) {
    const std::size_t n = lod.positions().size();
    if (level_vertices_.size() != 6 * n || n != n_vertices_) {
        upload_level(lod);
        return;
    }
    glBindBuffer(GL_ARRAY_BUFFER, geometry_buffer_);
    if (lod.all_changed()) {
        // Dead vertices keep stale entries: they are rewritten when they come back.
        for (Index v : lod.live_vertices()) write_level_vertex(lod, v);
        glBufferSubData(GL_ARRAY_BUFFER, 0, bytes(level_vertices_.size(), sizeof(float)),
                        level_vertices_.data());
    } else {
        for (Index v : lod.changed_vertices()) write_level_vertex(lod, v);
        upload_runs(lod.changed_vertices(), level_vertices_.data(), 6 * sizeof(float), n);
    }
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    write_level_indices(lod);
    lod.clear_changes();
}

void MeshRenderer::write_geometry(const HalfedgeMesh& mesh,
                                  const std::vector<Point>* moved_positions) {
    const std::vector<Point>& positions = moved_positions ? *moved_positions : mesh.positions();
    std::vector<Vector3> computed;
    const std::vector<Vector3>* normals = &computed;
    auto stored = mesh.get_vertex_property<Vector3>("v:normal");
    if (stored && !moved_positions) {
        normals = &stored.vector();
    } else {
        computed = area_weighted_normals(mesh, positions);
    }

    // Bounding box of the live vertices (for fog and vector lengths).
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    for (Vertex v : mesh.vertices()) {
        const Point& p = positions[v.idx()];
        const glm::vec3 q(float(p.x()), float(p.y()), float(p.z()));
        lo = glm::min(lo, q);
        hi = glm::max(hi, q);
    }
    if (mesh.n_vertices() == 0) lo = hi = glm::vec3(0.0f);
    bbox_min_ = lo;
    bbox_max_ = hi;

    // Signed volume of each closed component (formula (1.15), about the box's corner).
    outward_ = false;
    if (n_components_ > 0) {
        std::vector<double> volume(n_components_, 0.0);
        const Point origin(lo.x, lo.y, lo.z);
        for (Face f : mesh.faces()) {
            const auto [a, b, c] = mesh.face_vertices(f);
            volume[component_of_vertex_[a.idx()]] +=
                (positions[a.idx()] - origin)
                    .dot((positions[b.idx()] - origin).cross(positions[c.idx()] - origin));
        }
        outward_ = std::all_of(volume.begin(), volume.end(), [](double v) { return v > 0.0; });
    }

    // Deleted vertices keep whatever they had (zeros in practice); nothing indexes them.
    std::vector<GpuVertex> data(n_gpu_vertices_);
    for (std::size_t i = 0; i < n_gpu_vertices_; ++i) {
        const std::size_t v = gpu_source_.empty() ? i : gpu_source_[i];
        const Point& p = positions[v];
        const Vector3& n = (*normals)[v];
        data[i] = GpuVertex{{float(p.x()), float(p.y()), float(p.z())},
                            {float(n.x()), float(n.y()), float(n.z())}};
    }
    // glBufferData also for same-size rewrites: the driver can orphan the old storage
    // instead of waiting for draws that still read it.
    glBindBuffer(GL_ARRAY_BUFFER, geometry_buffer_);
    glBufferData(GL_ARRAY_BUFFER, bytes(data.size(), sizeof(GpuVertex)), data.data(),
                 GL_DYNAMIC_DRAW);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
}

ColorBlend color_blend(ColorMapKind kind) {
    return kind == ColorMapKind::Categorical ? ColorBlend::NearestCorner : ColorBlend::Interpolate;
}

void MeshRenderer::set_vertex_colors(const std::vector<Color>& colors, ColorBlend blend) {
    if (colors.size() != n_vertices_)
        throw InvalidArgument("MeshRenderer::set_vertex_colors: " + std::to_string(colors.size()) +
                              " colours for a mesh with vertex storage size " +
                              std::to_string(n_vertices_));
    // Before anything changes, so that a shader that does not build leaves all as it was.
    if (blend == ColorBlend::NearestCorner && !corner_programs_[0].is_valid())
        corner_programs_ = {geometry_stage_variant(false, true),
                            geometry_stage_variant(true, true)};
    auto byte = [](float c) {
        return std::uint8_t(
            std::lround(255.0f * std::clamp(std::isfinite(c) ? c : 0.0f, 0.0f, 1.0f)));
    };
    std::vector<std::uint8_t> rgba(4 * n_gpu_vertices_);
    for (std::size_t i = 0; i < n_gpu_vertices_; ++i) {
        const Color& c = colors[gpu_source_.empty() ? i : gpu_source_[i]];
        rgba[4 * i] = byte(c.x());
        rgba[4 * i + 1] = byte(c.y());
        rgba[4 * i + 2] = byte(c.z());
        rgba[4 * i + 3] = 255;
    }
    glBindBuffer(GL_ARRAY_BUFFER, color_buffer_);
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(rgba.size()), rgba.data(), GL_DYNAMIC_DRAW);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    for (GLuint vao : {triangle_vao_, point_vao_}) {
        glBindVertexArray(vao);
        glEnableVertexAttribArray(kColor);
    }
    glBindVertexArray(0);
    has_colors_ = true;
    color_blend_ = blend;
    clear_vertex_scalars();
}

void MeshRenderer::set_vertex_colors(const VertexColors& colors) {
    const bool scalars = colors.kind != ColorMapKind::Categorical && !colors.values.empty();
    if (scalars && colors.values.size() != colors.colors.size())
        throw InvalidArgument(
            "MeshRenderer::set_vertex_colors: " + std::to_string(colors.values.size()) +
            " values for " + std::to_string(colors.colors.size()) + " colours");
    set_vertex_colors(colors.colors, color_blend(colors.kind));
    if (scalars) set_vertex_scalars(colors.values, colors.range, colors.kind);
}

void MeshRenderer::set_vertex_scalars(const std::vector<double>& values, const ValueRange& range,
                                      ColorMapKind map) {
    if (values.size() != n_vertices_)
        throw InvalidArgument("MeshRenderer::set_vertex_scalars: " + std::to_string(values.size()) +
                              " values for a mesh with vertex storage size " +
                              std::to_string(n_vertices_));
    if (map == ColorMapKind::Categorical)
        throw InvalidArgument(
            "MeshRenderer::set_vertex_scalars: a categorical map has no bands or isolines");
    const double width = range.max - range.min;
    if (!(std::isfinite(range.min) && std::isfinite(range.max) && width > 0 &&
          std::isfinite(width)))
        throw InvalidArgument("MeshRenderer::set_vertex_scalars: the range [" +
                              std::to_string(range.min) + ", " + std::to_string(range.max) +
                              "] must be finite with min < max");
    // Before anything changes, so that a shader that does not build leaves all as it was.
    if (!scalar_programs_[0].is_valid())
        scalar_programs_ = {scalar_variant(false), scalar_variant(true)};
    std::vector<float> data(2 * n_gpu_vertices_, 0.0f);
    for (std::size_t i = 0; i < n_gpu_vertices_; ++i) {
        const double value = values[gpu_source_.empty() ? i : gpu_source_[i]];
        if (!std::isfinite(value)) continue;  // (0, 0): no value
        // Far outside the range the value is only ever beyond the last isoline: keep the float
        // finite and its precision where the lines are.
        data[2 * i] = float(std::clamp((value - range.min) / width, -1e4, 1e4));
        data[2 * i + 1] = 1.0f;
    }
    glBindBuffer(GL_ARRAY_BUFFER, scalar_buffer_);
    glBufferData(GL_ARRAY_BUFFER, bytes(data.size(), sizeof(float)), data.data(), GL_DYNAMIC_DRAW);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    for (GLuint vao : {triangle_vao_, point_vao_}) {
        glBindVertexArray(vao);
        glEnableVertexAttribArray(kScalar);
    }
    glBindVertexArray(0);
    has_scalars_ = true;
    scalar_map_ = map;
}

void MeshRenderer::clear_vertex_scalars() {
    for (GLuint vao : {triangle_vao_, point_vao_}) {
        glBindVertexArray(vao);
        glDisableVertexAttribArray(kScalar);
    }
    glBindVertexArray(0);
    glBindBuffer(GL_ARRAY_BUFFER, scalar_buffer_);
    glBufferData(GL_ARRAY_BUFFER, 0, nullptr, GL_DYNAMIC_DRAW);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    has_scalars_ = false;
}

void MeshRenderer::clear_vertex_colors() {
    for (GLuint vao : {triangle_vao_, point_vao_}) {
        glBindVertexArray(vao);
        glDisableVertexAttribArray(kColor);
    }
    glBindVertexArray(0);
    glBindBuffer(GL_ARRAY_BUFFER, color_buffer_);
    glBufferData(GL_ARRAY_BUFFER, 0, nullptr, GL_DYNAMIC_DRAW);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    has_colors_ = false;
    color_blend_ = ColorBlend::Interpolate;
    clear_vertex_scalars();
}

void MeshRenderer::set_texture(const Image& image) {
    if (image.empty() || image.rgba.size() != std::size_t(image.width) * image.height * 4)
        throw InvalidArgument("MeshRenderer::set_texture: empty or inconsistent image");
    GLint max_size = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
    if (image.width > max_size || image.height > max_size)
        throw InvalidArgument("MeshRenderer::set_texture: " + std::to_string(image.width) + "x" +
                              std::to_string(image.height) + " exceeds the GL texture size limit " +
                              std::to_string(max_size));
    // GL's first row is the bottom one (t = 0); the image's first row is the top one.
    const std::size_t row = std::size_t(image.width) * 4;
    std::vector<std::uint8_t> flipped(image.rgba.size());
    for (int y = 0; y < image.height; ++y)
        std::copy_n(image.rgba.begin() + std::ptrdiff_t(row * (image.height - 1 - y)), row,
                    flipped.begin() + std::ptrdiff_t(row * y));

    if (texture_ == 0) glGenTextures(1, &texture_);
    glBindTexture(GL_TEXTURE_2D, texture_);
    GLint alignment = 4;
    glGetIntegerv(GL_UNPACK_ALIGNMENT, &alignment);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, image.width, image.height, 0, GL_RGBA,
                 GL_UNSIGNED_BYTE, flipped.data());
    glPixelStorei(GL_UNPACK_ALIGNMENT, alignment);
    glGenerateMipmap(GL_TEXTURE_2D);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
    glBindTexture(GL_TEXTURE_2D, 0);
    has_texture_ = true;
}

void MeshRenderer::clear_texture() {
    if (texture_ != 0) glDeleteTextures(1, &texture_);
    texture_ = 0;
    has_texture_ = false;
}

void MeshRenderer::set_vertex_selection(const std::vector<float>& weights) {
    if (weights.size() != n_vertices_)
        throw InvalidArgument(
            "MeshRenderer::set_vertex_selection: " + std::to_string(weights.size()) +
            " weights for a mesh with vertex storage size " + std::to_string(n_vertices_));
    // Before anything changes, so that a shader that does not build leaves all as it was.
    if (!selection_programs_[0].is_valid())
        selection_programs_ = {selection_variant(false, false), selection_variant(true, false),
                               selection_variant(false, true), selection_variant(true, true)};
    std::vector<float> data(n_gpu_vertices_, 0.0f);
    for (std::size_t i = 0; i < n_gpu_vertices_; ++i) {
        const float w = weights[gpu_source_.empty() ? i : gpu_source_[i]];
        data[i] = std::isfinite(w) ? std::clamp(w, 0.0f, 1.0f) : 0.0f;
    }
    glBindBuffer(GL_ARRAY_BUFFER, selection_buffer_);
    glBufferData(GL_ARRAY_BUFFER, bytes(data.size(), sizeof(float)), data.data(), GL_DYNAMIC_DRAW);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    for (GLuint vao : {triangle_vao_, point_vao_}) {
        glBindVertexArray(vao);
        glEnableVertexAttribArray(kSelection);
    }
    glBindVertexArray(0);
    has_selection_ = true;
}

void MeshRenderer::clear_vertex_selection() {
    if (!has_selection_) return;
    for (GLuint vao : {triangle_vao_, point_vao_}) {
        glBindVertexArray(vao);
        glDisableVertexAttribArray(kSelection);
    }
    glBindVertexArray(0);
    glBindBuffer(GL_ARRAY_BUFFER, selection_buffer_);
    glBufferData(GL_ARRAY_BUFFER, 0, nullptr, GL_DYNAMIC_DRAW);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    has_selection_ = false;
}

void MeshRenderer::set_display_uniforms(const GlProgram& program, const RenderStyle& style,
                                        bool selection, bool scalars) const {
    if (selection)
        set_selection_uniforms(program, style, scalars);
    else if (scalars)
        set_scalar_uniforms(program, style);
}

const GlProgram& MeshRenderer::selection_program(bool wires, bool nearest_corner) const {
    return selection_programs_[(wires ? 1 : 0) + (nearest_corner ? 2 : 0)];
}

void MeshRenderer::set_selection_uniforms(const GlProgram& program, const RenderStyle& style,
                                          bool scalars) const {
    if (scalars)
        set_scalar_uniforms(program, style);
    else
        program.set("u_scalar_display", 0);
    program.set("u_selection_tint", style.selection_tint);
    program.set("u_selection_strength", std::clamp(style.selection_tint_strength, 0.0f, 1.0f));
    program.set("u_selection_outline", style.selection_outline);
    program.set("u_selection_outline_width", std::max(style.selection_outline_width, 0.0f));
}

void MeshRenderer::clear() {
    for (GLuint buffer : {geometry_buffer_, texcoord_buffer_, triangle_buffer_, point_buffer_}) {
        glBindBuffer(GL_ARRAY_BUFFER, buffer);
        glBufferData(GL_ARRAY_BUFFER, 0, nullptr, GL_STATIC_DRAW);
    }
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    clear_vertex_colors();
    clear_vertex_selection();
    gpu_source_.clear();
    level_vertices_.clear();
    shown_ = {};
    n_vertices_ = n_gpu_vertices_ = n_triangle_indices_ = n_point_indices_ = 0;
    has_texcoords_ = false;
    bbox_min_ = bbox_max_ = glm::vec3(0.0f);
}

namespace {

/// The lighting and colour uniforms of the programs that shade points and surfaces: the
/// front and back colours, vertex colours (`colored`), ambient and specular terms.
void set_shading_uniforms(const GlProgram& program, const RenderStyle& style, bool colored) {
    program.set("u_back_face_color", style.back_face_color && !style.facing_normals ? 1 : 0);
    program.set("u_facing_normals", style.facing_normals ? 1 : 0);
    program.set("u_use_vertex_color", colored ? 1 : 0);
    program.set("u_front_color", style.front_color);
    program.set("u_back_color", style.back_color);
    program.set("u_ambient", style.ambient);
    program.set("u_specular", style.specular ? style.specular_strength : 0.0f);
    program.set("u_shininess", style.shininess);
}

}  // namespace

void MeshRenderer::set_scalar_uniforms(const GlProgram& program, const RenderStyle& style) const {
    const int steps = std::clamp(style.scalar_steps, kMinScalarSteps, kMaxScalarSteps);
    const ScalarDisplay d = style.scalar_display;
    const bool bands = d == ScalarDisplay::Bands || d == ScalarDisplay::BandsAndIsolines;
    const bool lines = d == ScalarDisplay::Isolines || d == ScalarDisplay::BandsAndIsolines;
    program.set("u_scalar_display", (bands ? 1 : 0) | (lines ? 2 : 0));
    program.set("u_scalar_steps", steps);
    program.set("u_isoline_width", std::max(style.isoline_width, 0.0f));
    // Step k shows the map's colour at its centre, (k + 1/2) / N of the range.
    std::vector<glm::vec3> colors(static_cast<std::size_t>(steps));
    for (int k = 0; k < steps; ++k) {
        const Color c = map_color((k + 0.5) / steps, ValueRange{0.0, 1.0}, scalar_map_);
        colors[std::size_t(k)] = glm::vec3(c.x(), c.y(), c.z());
    }
    program.set("u_band_colors", colors);
}

void MeshRenderer::set_common_uniforms(const GlProgram& program, const glm::mat4& view,
                                       const glm::mat4& projection,
                                       const RenderStyle& style) const {
    program.use();
    program.set("u_model_view", view);
    program.set("u_projection", projection);
    program.set("u_normal_matrix", glm::inverseTranspose(glm::mat3(view)));
    program.set("u_background", style.background);
    program.set("u_fog", style.fog ? 1 : 0);
    if (style.fog) {
        // Fog over the depth range of the bounding box's corners, as seen from this view.
        float near_depth = std::numeric_limits<float>::max(), far_depth = -near_depth;
        for (int i = 0; i < 8; ++i) {
            const glm::vec3 corner((i & 1) ? bbox_max_.x : bbox_min_.x,
                                   (i & 2) ? bbox_max_.y : bbox_min_.y,
                                   (i & 4) ? bbox_max_.z : bbox_min_.z);
            const float depth = -(view * glm::vec4(corner, 1.0f)).z;
            near_depth = std::min(near_depth, depth);
            far_depth = std::max(far_depth, depth);
        }
        program.set("u_fog_near", near_depth);
        program.set("u_fog_far", far_depth);
        program.set("u_fog_amount", std::clamp(style.fog_amount, 0.0f, 1.0f));
    }
}

bool MeshRenderer::culls_back_faces(const glm::mat4& view, const glm::mat4& projection) const {
    return outward_ && in_front_of_near_plane(projection * view, bbox_min_, bbox_max_);
}

void MeshRenderer::draw(const glm::mat4& view, const glm::mat4& projection,
                        const RenderStyle& style) const {
    if (n_point_indices_ == 0) return;
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);
    glDepthMask(GL_TRUE);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);

    const RenderMode mode = style.mode;
    if (mode == RenderMode::Points) {
        if (style.occlude_points && n_triangle_indices_ > 0) {
            // Depth of the surface, pushed back by about a point radius of depth slope so
            // that a point is not cut by the triangles around its own vertex.
            set_common_uniforms(depth_program_, view, projection, style);
            glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
            glEnable(GL_POLYGON_OFFSET_FILL);
            glPolygonOffset(0.5f * std::max(style.point_size, 1.0f) + 1.0f, 4.0f);
            glBindVertexArray(triangle_vao_);
            glDrawElements(GL_TRIANGLES, GLsizei(n_triangle_indices_), GL_UNSIGNED_INT, nullptr);
            glDisable(GL_POLYGON_OFFSET_FILL);
            glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        }
        set_common_uniforms(points_program_, view, projection, style);
        points_program_.set("u_point_size", std::max(style.point_size, 1.0f));
        set_shading_uniforms(points_program_, style, has_colors_ && style.vertex_colors);
        glEnable(GL_PROGRAM_POINT_SIZE);
        glBindVertexArray(point_vao_);
        glDrawElements(GL_POINTS, GLsizei(n_point_indices_), GL_UNSIGNED_INT, nullptr);
        glDisable(GL_PROGRAM_POINT_SIZE);
    } else if (n_triangle_indices_ > 0) {
        const bool edges_only = mode == RenderMode::Wireframe;
        const bool hidden_line = mode == RenderMode::HiddenLine;
        const bool wires = edges_only || hidden_line || style.wireframe;
        const bool textured = mode == RenderMode::Textured &&
                              style.texture_mode != TextureMode::Off && has_texture_ &&
                              has_texcoords_;
        const bool colored = has_colors_ && style.vertex_colors;
        // Categorical colours on a shaded surface: the nearest corner's colour, never a blend.
        const bool nearest_corner =
            colored && !edges_only && !hidden_line && color_blend_ == ColorBlend::NearestCorner;
        // Bands and isolines on a shaded surface; Smooth keeps the programs without scalars.
        const bool scalars = has_scalars_ && !edges_only && !hidden_line && !nearest_corner &&
                             style.scalar_display != ScalarDisplay::Smooth;
        // The selection overlay on a shaded surface (its programs do all of the above too).
        const bool selection =
            has_selection_ && style.selection_overlay && !edges_only && !hidden_line;
        const GlProgram& program = selection        ? selection_program(wires, nearest_corner)
                                   : nearest_corner ? corner_programs_[wires ? 1 : 0]
                                   : scalars        ? scalar_programs_[wires ? 1 : 0]
                                   : wires
                                       ? wire_program_
                                       : surface_programs_[(colored ? 1 : 0) + (textured ? 2 : 0)];
        set_common_uniforms(program, view, projection, style);
        set_display_uniforms(program, style, selection, scalars);
        program.set("u_surface", edges_only ? 2 : hidden_line ? 1 : 0);
        program.set("u_flat", mode == RenderMode::Flat ? 1 : 0);
        set_shading_uniforms(program, style, colored);
        program.set("u_wire_color",
                    edges_only || hidden_line ? style.line_color : style.wire_color);
        program.set("u_wire_width", std::max(style.wire_width, 0.0f));
        program.set("u_texture_mode", textured ? int(style.texture_mode) : 0);
        program.set("u_texture", 0);
        if (textured) {
            glActiveTexture(GL_TEXTURE0);
            glBindTexture(GL_TEXTURE_2D, texture_);
        }
        if (edges_only) {
            // Every edge, hidden ones too: no depth test, blended by coverage. The alpha
            // channel accumulates too, so a transparent background stays correct.
            glDisable(GL_DEPTH_TEST);
            glEnable(GL_BLEND);
            glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE,
                                GL_ONE_MINUS_SRC_ALPHA);
        }
        glBindVertexArray(triangle_vao_);
        if (edges_only) {
            // Back-facing triangles first, so that the edges of the front ones end on top.
            glEnable(GL_CULL_FACE);
            glCullFace(GL_FRONT);
            glDrawElements(GL_TRIANGLES, GLsizei(n_triangle_indices_), GL_UNSIGNED_INT, nullptr);
            glCullFace(GL_BACK);
            glDrawElements(GL_TRIANGLES, GLsizei(n_triangle_indices_), GL_UNSIGNED_INT, nullptr);
            glDisable(GL_CULL_FACE);
            glDisable(GL_BLEND);
            glEnable(GL_DEPTH_TEST);
        } else {
            // No back face can be seen (see outward_): the rasterizer skips about half the
            // triangles, which on a software renderer is about half the frame.
            const bool cull = style.cull_hidden_back_faces && culls_back_faces(view, projection);
            if (cull) glEnable(GL_CULL_FACE);
            glDrawElements(GL_TRIANGLES, GLsizei(n_triangle_indices_), GL_UNSIGNED_INT, nullptr);
            if (cull) glDisable(GL_CULL_FACE);
        }
        if (textured) glBindTexture(GL_TEXTURE_2D, 0);
    }

    // Normals as 1-pixel segments, depth-tested against the surface.
    const float length = style.vector_length * glm::length(bbox_max_ - bbox_min_);
    if ((style.face_normals && n_triangle_indices_ > 0) || style.vertex_normals) {
        if (style.face_normals && n_triangle_indices_ > 0) {
            set_common_uniforms(face_vector_program_, view, projection, style);
            face_vector_program_.set("u_length", length);
            face_vector_program_.set("u_color", style.face_normal_color);
            glBindVertexArray(triangle_vao_);
            glDrawElements(GL_TRIANGLES, GLsizei(n_triangle_indices_), GL_UNSIGNED_INT, nullptr);
        }
        if (style.vertex_normals) {
            set_common_uniforms(vertex_vector_program_, view, projection, style);
            vertex_vector_program_.set("u_length", length);
            vertex_vector_program_.set("u_color", style.vertex_normal_color);
            glBindVertexArray(point_vao_);
            glDrawElements(GL_POINTS, GLsizei(n_point_indices_), GL_UNSIGNED_INT, nullptr);
        }
    }
    glBindVertexArray(0);
    glUseProgram(0);
}

void MeshRenderer::upload_triangles(const std::vector<Point>& positions,
                                    const std::vector<std::array<Index, 3>>& triangles) {
    const std::size_t n = positions.size();
    for (const auto& t : triangles)
        for (Index v : t)
            if (v >= n)
                throw InvalidArgument("MeshRenderer::upload_triangles: corner " +
                                      std::to_string(v) + " of a list of " + std::to_string(n) +
                                      " positions");
    std::vector<Vector3> normals(n, Vector3::Zero());
    for (const auto& t : triangles) {
        const Point& p0 = positions[t[0]];
        const Vector3 nt = (positions[t[1]] - p0).cross(positions[t[2]] - p0);
        for (Index v : t) normals[v] += nt;
    }
    std::vector<GpuVertex> data(n);
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    for (std::size_t i = 0; i < n; ++i) {
        const double len = normals[i].norm();
        const Vector3 nv = len > 0 ? Vector3(normals[i] / len) : Vector3::Zero();
        const Point& p = positions[i];
        data[i] = GpuVertex{{float(p.x()), float(p.y()), float(p.z())},
                            {float(nv.x()), float(nv.y()), float(nv.z())}};
        lo = glm::min(lo, glm::vec3(data[i].position[0], data[i].position[1], data[i].position[2]));
        hi = glm::max(hi, glm::vec3(data[i].position[0], data[i].position[1], data[i].position[2]));
    }
    if (n == 0) lo = hi = glm::vec3(0.0f);
    std::vector<GLuint> points(n);
    for (std::size_t i = 0; i < n; ++i) points[i] = GLuint(i);

    shown_ = {};
    level_vertices_.clear();
    gpu_source_.clear();
    component_of_vertex_.clear();
    n_components_ = 0;
    outward_ = false;
    n_vertices_ = n_gpu_vertices_ = n;
    bbox_min_ = lo;
    bbox_max_ = hi;
    static_assert(sizeof(std::array<Index, 3>) == 3 * sizeof(GLuint) && sizeof(Index) == 4,
                  "triangles must be tightly packed uint32 triples");
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, 0);  // no VAO bound: safe to use the binding point
    glBindBuffer(GL_ARRAY_BUFFER, geometry_buffer_);
    glBufferData(GL_ARRAY_BUFFER, bytes(data.size(), sizeof(GpuVertex)), data.data(),
                 GL_DYNAMIC_DRAW);
    glBindBuffer(GL_ARRAY_BUFFER, triangle_buffer_);
    glBufferData(GL_ARRAY_BUFFER, bytes(triangles.size(), 3 * sizeof(GLuint)), triangles.data(),
                 GL_STATIC_DRAW);
    glBindBuffer(GL_ARRAY_BUFFER, point_buffer_);
    glBufferData(GL_ARRAY_BUFFER, bytes(points.size(), sizeof(GLuint)), points.data(),
                 GL_STATIC_DRAW);
    n_triangle_indices_ = 3 * triangles.size();
    n_point_indices_ = points.size();
    drop_texcoords();
    clear_vertex_colors();
    clear_vertex_selection();
}

void MeshRenderer::set_vertex_texcoords(const std::vector<TexCoord>& texcoords) {
    if (!gpu_source_.empty() || texcoords.size() != n_gpu_vertices_)
        throw InvalidArgument(
            "MeshRenderer::set_vertex_texcoords: " + std::to_string(texcoords.size()) +
            " texture coordinates for " + std::to_string(n_gpu_vertices_) + " vertices" +
            (gpu_source_.empty() ? "" : " with per-corner texture coordinates"));
    std::vector<float> data(2 * texcoords.size());
    for (std::size_t i = 0; i < texcoords.size(); ++i) {
        data[2 * i] = float(texcoords[i].x());
        data[2 * i + 1] = float(texcoords[i].y());
    }
    glBindBuffer(GL_ARRAY_BUFFER, texcoord_buffer_);
    glBufferData(GL_ARRAY_BUFFER, bytes(data.size(), sizeof(float)), data.data(), GL_STATIC_DRAW);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    for (GLuint vao : {triangle_vao_, point_vao_}) {
        glBindVertexArray(vao);
        glEnableVertexAttribArray(kTexcoord);
    }
    glBindVertexArray(0);
    has_texcoords_ = !texcoords.empty();
}

void MeshRenderer::drop_texcoords() {
    has_texcoords_ = false;
    glBindBuffer(GL_ARRAY_BUFFER, texcoord_buffer_);
    glBufferData(GL_ARRAY_BUFFER, 0, nullptr, GL_STATIC_DRAW);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    for (GLuint vao : {triangle_vao_, point_vao_}) {
        glBindVertexArray(vao);
        glDisableVertexAttribArray(kTexcoord);
    }
    glBindVertexArray(0);
}

}  // namespace trilab
