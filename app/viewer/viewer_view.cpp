// The view: the camera's fit and default view, the wireframe decision, the scene and the
// collapsing-edges overlay, the vertex colours and the texture.
#include "app/viewer/viewer.h"

// glad before GLFW: GLFW must not include the system GL header.
#include <glad/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>
#include <imgui_internal.h>  // --print-layout reads the window list

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <tuple>
#include <utility>
#include <vector>

#include "app/ops/operation.h"
#include "app/ops/operation_entries.h"
#include "app/record/recorder.h"
#include "app/viewer/key_bindings.h"
#include "app/viewer/viewer_tuning.h"
#include "core/algorithms/coincident.h"
#include "core/algorithms/decimation.h"
#include "core/algorithms/fairing.h"
#include "core/algorithms/generators.h"
#include "core/algorithms/mesh_stats.h"
#include "core/algorithms/orientation.h"
#include "core/algorithms/texcoords.h"
#include "core/errors.h"
#include "core/geometry.h"
#include "core/io/mesh_io.h"
#include "render/offscreen.h"

namespace trilab::viewer {
using namespace tuning;

namespace {

glm::vec3 to_glm(const Point& p) {
    return glm::vec3(float(p.x()), float(p.y()), float(p.z()));
}

}  // namespace

void Viewer::reset_view() {
    const UpAxis up = view_.settings.up;
    view_.camera.reset_rotation(up);
    fit_view();
    if (preferences_.up != up) {
        preferences_.up = up;
        preferences_.save();
        session_.log().info(std::string("up axis: +") + up_axis_name(up) +
                            " (the default view and the spherical texture projection)");
        // Coordinates the viewer projected around the other axis follow (a history entry).
        if (session_.document().texcoords_projected &&
            view_.settings.projection == TexCoordProjection::Spherical)
            session_.project_texcoords(view_.settings.projection, view_.settings.up);
    }
}

void Viewer::fit_view() {
    const HalfedgeMesh& mesh = session_.mesh();
    BoundingBox box = bounding_box(mesh);
    fit_center_ = glm::vec3(0.0f);
    fit_radius_ = 1.0f;
    if (!box.empty) {
        // The smallest sphere around the box centre that holds every vertex: tighter than the
        // box's own bounding sphere, so round models fill the view.
        Point center = box.center();
        double radius2 = 0.0;
        for (Vertex v : mesh.vertices())
            radius2 = std::max(radius2, (mesh.position(v) - center).squaredNorm());
        fit_center_ = to_glm(center);
        fit_radius_ = float(std::sqrt(radius2));
    }
    view_.camera.set_viewport(std::max(view_rect_.w, 1.0f), std::max(view_rect_.h, 1.0f));
    view_.camera.fit_sphere(fit_center_, fit_radius_);
    camera_fitted_ = true;
}

void Viewer::apply_colors(VertexColors colors) {
    view_.colors = std::move(colors);
    const bool none =
        view_.settings.coloring == VertexColoring::None || view_.colors.colors.empty();
    note_exact_colors(none ? VertexColors{} : view_.colors, session_.mesh());
    // A large state waiting for its upload (viewer_motion.cpp) takes them with it.
    if (proxy_.exact_pending) return;
    if (none)
        renderer_->clear_vertex_colors();
    else
        renderer_->set_vertex_colors(view_.colors);
}

void Viewer::update_coloring() {
    const VertexColoring coloring = view_.settings.coloring;
    const ColoringOptions options = view_.settings.coloring_options;
    if (coloring != VertexColoring::GeodesicDistance) session_.want_pick_distances(false);
    if (coloring == VertexColoring::None) {
        apply_colors(VertexColors{});
        return;
    }
    if (coloring_needs_field(coloring)) {  // from the decomposition: cheap, on this thread
        const bool geodesic = coloring == VertexColoring::GeodesicDistance;
        session_.want_pick_distances(geodesic);
        geodesic_colored_version_ = session_.picks().version;
        VertexColors colors = frequency_colors(session_.mesh());
        if (colors.colors.empty() && geodesic)
            session_.notice() =
                Notice{Notice::Level::Info,
                       session_.picks().picks.empty()
                           ? "geodesic distance: click the model to pick where it is measured from"
                           : "geodesic distance: measuring from the picks...",
                       {},
                       false};
        else if (geodesic && session_.notice().text.rfind("geodesic distance:", 0) == 0)
            session_.notice() = Notice{};  // the distances arrived
        else if (colors.colors.empty())
            session_.notice() =
                Notice{Notice::Level::Info,
                       "the frequency colourings need a decomposition (Algorithms > "
                       "Frequency decomposition)",
                       {},
                       false};
        apply_colors(std::move(colors));
        return;
    }
    auto reference = std::make_shared<const std::vector<Point>>(
        coloring == VertexColoring::SmoothingDistance ? session_.reference_positions()
                                                      : std::vector<Point>{});
    if (session_.mesh().n_faces() < kColoringJobFaces) {
        apply_colors(color_vertices(session_.mesh(), coloring, options, reference.get()));
        return;
    }
    // Large meshes: compute on the worker; the document cannot change while a job runs.
    if (session_.jobs().busy()) {  // e.g. dragging the legend's range: colour again when it is done
        coloring_pending_ = true;
        return;
    }
    const HalfedgeMesh snapshot = session_.mesh();  // copy-on-write: the job's own
    const HalfedgeMesh::Revision state = snapshot.revision();
    const bool started =
        session_.jobs().start(std::string("Colouring by ") + coloring_name(coloring),
                              [this, coloring, options, reference, snapshot, state](Progress&) {
                                  auto colors = std::make_shared<VertexColors>(
                                      color_vertices(snapshot, coloring, options, reference.get()));
                                  return JobRunner::Finish([this, colors, coloring, state] {
                                      // Ignore a result the user has already replaced, or one of
                                      // another state (an entry applied meanwhile): colour that
                                      // state again.
                                      if (view_.settings.coloring != coloring) return;
                                      if (session_.mesh().revision() != state) {
                                          coloring_pending_ = true;
                                          return;
                                      }
                                      apply_colors(std::move(*colors));
                                  });
                              });
    if (!started)
        session_.notify_error("busy: wait for \"" + session_.jobs().name() + "\" or cancel it");
}

void Viewer::show_colors_of(const HalfedgeMesh& mesh, const std::vector<Point>& reference) {
    if (view_.settings.coloring == VertexColoring::None) return;
    const VertexColors colors =
        coloring_needs_field(view_.settings.coloring)
            ? frequency_colors(mesh)
            : color_vertices(mesh, view_.settings.coloring, view_.settings.coloring_options,
                             reference.empty() ? nullptr : &reference);
    note_exact_colors(colors, mesh);
    if (colors.colors.empty())
        renderer_->clear_vertex_colors();
    else
        renderer_->set_vertex_colors(colors);
}

void Viewer::update_texture() {
    const Image& image =
        view_.settings.use_checkerboard || texture_.empty() ? checkerboard_ : texture_;
    try {
        renderer_->set_texture(image);
        if (proxy_.renderer) proxy_.renderer->set_texture(image);  // a textured stand-in
    } catch (const std::exception& e) {
        session_.notify_error(std::string("texture: ") + e.what());
    }
}

void Viewer::view_viewport(int& x, int& y, int& w, int& h) const {
    // The backend reads the window and framebuffer sizes once a frame; no X round trip here.
    const ImGuiIO& io = ImGui::GetIO();
    const float sx = io.DisplayFramebufferScale.x, sy = io.DisplayFramebufferScale.y;
    const int fb_h = int(std::lround(io.DisplaySize.y * sy));
    x = int(std::lround(view_rect_.x * sx));
    w = std::max(1, int(std::lround(view_rect_.w * sx)));
    h = std::max(1, int(std::lround(view_rect_.h * sy)));
    y = fb_h - int(std::lround(view_rect_.y * sy)) - h;  // GL counts rows from the bottom
}

void Viewer::update_wireframe() {
    RenderStyle& style = view_.style;
    // A typical edge of the shown mesh: the side of an equilateral triangle of the mean
    // triangle area (the current state's area over the shown triangles, so previews,
    // morphs and levels of detail count their own density). Two multiplications a frame.
    // (A large state's own count: its proxy or a pending upload may be on the GPU.)
    const std::size_t triangles = proxy_.current && session_.shown().mesh
                                      ? session_.shown().mesh->n_faces()
                                      : renderer_->n_triangles();
    edge_pixels_ = 0;
    if (triangles > 0 && surface_area_ > 0) {
        const double edge = std::sqrt(4.0 * surface_area_ / (std::sqrt(3.0) * double(triangles)));
        edge_pixels_ = edge * double(view_.camera.pixels_per_unit()) *
                       double(ImGui::GetIO().DisplayFramebufferScale.y);
    }
    const double line = std::max(1.0, double(style.wire_width * ui_scale_));
    wire_auto_on_ = edge_pixels_ >= (wire_auto_on_ ? kWireOffLineWidths : kWireOnLineWidths) * line;
    switch (view_.settings.wireframe) {
        case WireframeOverlay::On:
            style.wireframe = true;
            break;
        case WireframeOverlay::Off:
            style.wireframe = false;
            break;
        case WireframeOverlay::Auto:
            style.wireframe = wire_auto_on_;
            break;
    }
}

void Viewer::render_scene() {
    int fb_w = 0, fb_h = 0;
    glfwGetFramebufferSize(window_.get(), &fb_w, &fb_h);
    glViewport(0, 0, fb_w, fb_h);
    clear_background(view_.style);
    if (fb_w <= 0 || fb_h <= 0 || view_rect_.empty()) return;  // minimized
    int x = 0, y = 0, w = 0, h = 0;
    view_viewport(x, y, w, h);
    glViewport(x, y, w, h);

    RenderStyle style = view_.style;
    style.wire_width *= ui_scale_;
    style.isoline_width *= ui_scale_;
    style.point_size *= ui_scale_;
    upload_selection_overlay(style);
    // Large meshes: the proxy while the view moves, the exact surface at rest.
    if (MeshRenderer* shown = choose_renderer())
        shown->draw(view_.camera.view(), view_.camera.projection(), style);
    else
        renderer_->draw(view_.camera.view(), view_.camera.projection(), style);
    if (panels_.decimation.show_collapsing_edges)
        collapse_lines_->draw(view_.camera.view(), view_.camera.projection(), LineStyle{},
                              ui_scale_);
    update_pick_overlay();
    draw_pick_overlay();
    glViewport(0, 0, fb_w, fb_h);  // ImGui draws over the whole window
}

void Viewer::update_collapsing_edges() {
    const DecimationPanelState& d = panels_.decimation;
    if (!d.show_collapsing_edges) return;
    const HalfedgeMesh& mesh = session_.mesh();
    // The mesh state (its topology and geometry revisions) and the options the edges were
    // computed for.
    const std::string key = std::to_string(mesh.topology_revision()) + " " +
                            std::to_string(mesh.geometry_revision()) + " " + d.op.text();
    if (key == collapse_key_) return;
    collapse_key_ = key;
    std::vector<glm::vec3> points;
    // Computed on the render thread: a dry run of the next iteration, a fraction of a second
    // up to a few hundred thousand vertices; bigger meshes skip the overlay.
    constexpr std::size_t kMaxOverlayVertices = 300000;
    if (mesh.n_vertices() > kMaxOverlayVertices) {
        session_.log().warning("Collapsing edges: shown for meshes of up to 300,000 vertices only");
        collapse_lines_->set_segments(points);
        return;
    }
    try {
        const DecimationOptions o = decimation_options(d.op);
        for (const auto& pair : next_collapses(mesh, o)) {
            const Point& a = mesh.position(pair[0]);
            const Point& b = mesh.position(pair[1]);
            points.emplace_back(float(a.x()), float(a.y()), float(a.z()));
            points.emplace_back(float(b.x()), float(b.y()), float(b.z()));
        }
    } catch (const Error& e) {
        session_.notify_error(std::string("Collapsing edges: ") + e.what());
    }
    collapse_lines_->set_segments(points);
}

void Viewer::sync_renderer() {
    const Shown& shown = session_.shown();
    if (shown.version == shown_version_) return;
    shown_version_ = shown.version;
    active_frames_ = std::max(active_frames_, 2);
    proxy_.current = proxy_applies(shown);
    proxy_.exact_pending = false;
    if (proxy_.current) {
        const MeshKey key{shown.mesh->topology_revision(), shown.mesh->geometry_revision()};
        if (key != proxy_.current_key) proxy_.proxy_drawn = false;
        proxy_.current_key = key;
        request_proxy(*shown.mesh);
        // The shown surface changed (a load, an operation, a slider move): the proxy first,
        // the exact surface once the view rests (viewer_motion.cpp). A preview's colours are
        // computed with its upload, so a coloured preview is uploaded at once.
        if (shown.kind == Shown::Kind::Document ||
            view_.settings.coloring == VertexColoring::None) {
            proxy_.exact_pending = true;
            proxy_.motion.note_motion(glfwGetTime());
            shown_kind_ = shown.kind;
            return;
        }
    }
    upload_shown();
}

void Viewer::upload_shown() {
    const Shown& shown = session_.shown();
    const Shown::Kind before = shown_kind_;
    shown_kind_ = shown.kind;
    proxy_.exact_pending = false;
    try {
        switch (shown.kind) {
            case Shown::Kind::Document:
                renderer_->show(*shown.mesh);
                apply_colors(std::move(view_.colors));
                break;
            case Shown::Kind::Preview:
                // Geometry-only previews (fairing, noise) move the vertices already on the GPU:
                // the renderer compares revisions and uploads only what changed.
                if (renderer_->show(*shown.mesh) == MeshRenderer::Update::Full) {
                    const std::vector<Point> reference =
                        session_.mesh().vertices_size() == shown.mesh->vertices_size()
                            ? session_.mesh().positions()
                            : std::vector<Point>{};
                    show_colors_of(*shown.mesh, reference);
                }
                break;
            case Shown::Kind::Morph:
                // The morph's first frame, or a new connectivity: upload it once (unless the GPU
                // holds it already); colours are computed on it at its own (final) shape, so
                // each vertex keeps its colour while it moves.
                if (before != Shown::Kind::Morph || !renderer_->shows_topology_of(*shown.mesh)) {
                    if (!renderer_->shows_topology_of(*shown.mesh)) renderer_->upload(*shown.mesh);
                    show_colors_of(*shown.mesh, session_.reference_positions());
                }
                renderer_->update_positions(*shown.mesh, shown.positions);
                break;
            case Shown::Kind::Level:
                if (before == Shown::Kind::Level)
                    renderer_->update_level(*shown.level);
                else
                    renderer_->upload_level(*shown.level);
                break;
            case Shown::Kind::Band:
                renderer_->show(*shown.mesh);
                renderer_->update_positions(*shown.mesh, shown.positions);
                break;
        }
    } catch (const std::exception& e) {
        session_.notify_error(std::string("view: ") + e.what());
    }
}

}  // namespace trilab::viewer
