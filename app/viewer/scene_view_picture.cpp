// SceneView's loading picture and the automatic wireframe decision (scene_view.h; the rest of
// the class is in scene_view.cpp).
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "app/viewer/scene_view.h"
#include "app/viewer/viewer_tuning.h"

namespace trilab::viewer {
using namespace tuning;

MeshRenderer* SceneView::choose_loading_picture() {
    loading_.drawn = false;
    std::shared_ptr<const LoadingPicture> picture = session_.files().loading_picture();
    if (!picture) {
        if (loading_.picture && loading_.restore_camera) view_.camera = loading_.camera_before;
        loading_.picture.reset();
        loading_.restore_camera = false;
        return nullptr;
    }
    MeshRenderer& r = *proxy_.renderer;
    if (picture != loading_.picture) {
        try {
            r.upload_triangles(picture->proxy->positions, picture->proxy->triangles);
            r.clear_vertex_colors();
        } catch (const std::exception& e) {
            session_.log().warning(std::string("no picture while loading: ") + e.what());
            return nullptr;
        }
        proxy_.uploaded_key = {0, 0};  // the proxy's renderer holds the picture now
        if (!loading_.picture) {
            loading_.camera_before = view_.camera;
            loading_.restore_camera = true;
        }
        loading_.picture = picture;
        // The view the loaded model gets (fit_view over the same vertices).
        view_.camera.reset_rotation(view_.settings.up);
        context_.fit_camera(glm::vec3(float(picture->center.x()), float(picture->center.y()),
                                      float(picture->center.z())),
                            picture->bounds.empty ? 1.0f : float(picture->radius));
        char line[160];
        std::snprintf(line, sizeof(line),
                      "simplified picture while loading: %zu triangles for %zu faces",
                      picture->proxy->triangles.size(), picture->faces);
        session_.log().info(line);
    }
    loading_.drawn = true;
    loading_.error_pixels = proxy_error_pixels(picture->proxy->error_bound, view_.camera,
                                               ImGui::GetIO().DisplayFramebufferScale.y);
    context_.keep_drawing();
    return &r;
}

void SceneView::update_wireframe() {
    RenderStyle& style = view_.style;
    // A typical edge of the shown mesh: the side of an equilateral triangle of the mean
    // triangle area (the current state's area over the shown triangles, so previews,
    // morphs and levels of detail count their own density). Two multiplications a frame.
    // (A large state's own count: its proxy or a pending upload may be on the GPU.)
    // A file's picture while it loads: the file's own faces over the picture's area (its
    // coarse triangles' edges are not the surface's), not the model still open.
    std::size_t triangles = proxy_.current && session_.shown().mesh
                                ? session_.shown().mesh->n_faces()
                                : renderer_->n_triangles();
    double area = surface_area_;
    if (const std::shared_ptr<const LoadingPicture> picture = session_.files().loading_picture()) {
        if (picture != loading_.area_of) {
            loading_.area_of = picture;
            loading_.area = 0;
            const std::vector<Point>& x = picture->proxy->positions;
            for (const auto& t : picture->proxy->triangles)
                loading_.area += 0.5 * (x[t[1]] - x[t[0]]).cross(x[t[2]] - x[t[0]]).norm();
        }
        triangles = picture->faces;
        area = loading_.area;
        const bool first = picture != loading_.wire_logged;
        loading_.wire_logged = picture;
        if (first) {
            const double edge = triangles > 0 && area > 0
                                    ? std::sqrt(4.0 * area / (std::sqrt(3.0) * double(triangles)))
                                    : 0.0;
            const double px = edge * double(view_.camera.pixels_per_unit());
            char line[128];
            std::snprintf(line, sizeof(line),
                          "loading picture: automatic wireframe %s (the file's edges %.2f px)",
                          px >= kWireOnLineWidths * std::max(1.0f, style.wire_width) ? "on" : "off",
                          px);
            session_.log().info(line);
        }
    }
    edge_pixels_ = 0;
    if (triangles > 0 && area > 0) {
        const double edge = std::sqrt(4.0 * area / (std::sqrt(3.0) * double(triangles)));
        edge_pixels_ = edge * double(view_.camera.pixels_per_unit()) *
                       double(ImGui::GetIO().DisplayFramebufferScale.y);
    }
    const double line = std::max(1.0, double(style.wire_width * context_.ui_scale));
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

}  // namespace trilab::viewer
