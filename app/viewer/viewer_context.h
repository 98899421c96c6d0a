#pragma once
// What the viewer's owners share: the session (the document and everything headless), how
// the document is looked at, the command queue the panels and scripts fill, where the view
// is on the window, and the frame requests. The Viewer owns one; SceneView, FrameOutput,
// ScriptDriver and every Tool hold a reference to it.
#include <algorithm>

#include "app/session/commands.h"
#include "app/session/session.h"
#include "app/viewer/layout.h"
#include "app/viewer/panels.h"
#include "core/algorithms/coloring.h"
#include "render/camera.h"
#include "render/mesh_renderer.h"

namespace trilab::viewer {

/// How the document is looked at.
struct ViewState {
    Camera camera;
    RenderStyle style;
    ViewSettings settings;
    VertexColors colors;  ///< the current vertex colouring (empty colors: none uploaded)
    /// The sphere of the last fit, and whether the camera has not moved since (a fitted
    /// model is fitted again when the view changes size).
    glm::vec3 fit_center{0.0f};
    float fit_radius = 1.0f;
    bool fitted = true;
};

struct ViewerContext {
    Session session;  ///< the document, its history, jobs and operations (no GL)
    ViewState view;
    CommandQueue commands;
    /// The window's own panels and dialogs (each tool owns its panel's state: tool.h).
    PanelState panels;
    /// The Record settings, owned by the Morph tool (morph_tool.h); FrameOutput reads them
    /// while it records (nullptr: no such tool).
    RecordState* record = nullptr;
    Rect view_rect;         ///< where the model is drawn (window pixels), from the layout
    float ui_scale = 1.0f;  ///< content scale of the monitor (HiDPI)
    /// A scripted sweep times the previews itself (the panels' latency notes wait).
    bool sweeping = false;
    /// Frames still to draw after the last event or command (the loop sleeps at 0).
    int active_frames = 0;
    /// Keeps the loop drawing for at least `frames` more frames.
    void keep_drawing(int frames = 1) { active_frames = std::max(active_frames, frames); }
    /// Fits the camera to the sphere (center, radius) over the current view rectangle.
    void fit_camera(const glm::vec3& center, float radius) {
        view.fit_center = center;
        view.fit_radius = radius;
        view.camera.set_viewport(std::max(view_rect.w, 1.0f), std::max(view_rect.h, 1.0f));
        view.camera.fit_sphere(center, radius);
    }
};

}  // namespace trilab::viewer
