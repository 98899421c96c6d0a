#pragma once
// FrameOutput: pictures of the scene. Screenshots (the dialog, F12) render the scene without
// the panels into an offscreen framebuffer at any size; recording writes the current entry's
// morph as PNG frames (and an MP4 when ffmpeg is on the PATH), one frame per UI frame so the
// window stays responsive; --screenshot reads the window's back buffer.
#include <string>

#include "app/viewer/viewer_context.h"

namespace trilab::viewer {

class SceneView;

class FrameOutput {
public:
    FrameOutput(ViewerContext& context, SceneView& scene) : context_(context), scene_(scene) {}
    /// Renders the scene without the panels into an offscreen framebuffer and writes a PNG.
    void take_screenshot(const TakeScreenshot& request);
    /// Reads the back buffer (`width` x `height` framebuffer pixels) and writes it as PNG;
    /// returns an error message or "".
    static std::string write_window(const std::string& path, int width, int height);
    /// Recording: starts, writes the next frame (once per UI frame), finishes.
    void start_recording();
    void record_next_frame();
    void finish_recording(bool cancelled);
    bool recording() const { return context_.record && context_.record->running; }

private:
    ViewerContext& context_;
    SceneView& scene_;
    Camera record_camera_;         ///< the recording's framing, fixed for the whole sequence
    float record_line_scale_ = 1;  ///< line widths of recorded frames relative to the view
};

}  // namespace trilab::viewer
