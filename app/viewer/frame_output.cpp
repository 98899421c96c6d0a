// Pictures of the scene (frame_output.h): screenshots and recorded morph frames.
#include "app/viewer/frame_output.h"

#include <glad/gl.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <system_error>
#include <utility>

#include "app/record/mp4_encoder.h"
#include "app/record/recorder.h"
#include "app/viewer/scene_view.h"
#include "core/io/image_io.h"
#include "render/offscreen.h"

namespace trilab::viewer {

void FrameOutput::take_screenshot(const TakeScreenshot& request) {
    try {
        Framebuffer framebuffer;
        framebuffer.create(request.width, request.height, 4);
        framebuffer.bind();
        RenderStyle style = context_.view.style;
        // Framed as the view; line widths and point sizes keep their look relative to it.
        int x = 0, y = 0, view_w = 0, view_h = 0;
        framebuffer_viewport(context_.view_rect, x, y, view_w, view_h);
        const float scale =
            std::min(float(request.width) / float(view_w), float(request.height) / float(view_h));
        style.wire_width *= context_.ui_scale * scale;
        style.point_size *= context_.ui_scale * scale;
        clear_background(style, request.transparent ? 0.0f : 1.0f);
        Camera camera = context_.view.camera;
        camera.reframe_for_viewport(float(request.width), float(request.height));
        scene_.exact().draw(camera.view(), camera.projection(), style);
        Image image = framebuffer.read_rgba();
        Framebuffer::bind_default();
        if (request.transparent) unpremultiply_alpha(image);
        write_png(image, request.path);
        context_.session.log().info("screenshot " + request.path + " (" +
                                    std::to_string(request.width) + " x " +
                                    std::to_string(request.height) + ")");
        context_.session.notify(Notice{Notice::Level::Info, "Saved " + request.path, {}, false});
    } catch (const std::exception& e) {
        Framebuffer::bind_default();
        context_.session.notify_error(std::string("screenshot: ") + e.what());
    }
}

std::string FrameOutput::write_window(const std::string& path, int w, int h) {
    if (w <= 0 || h <= 0) return "the window has no pixels";
    Image image;
    image.width = w;
    image.height = h;
    image.rgba.resize(std::size_t(w) * std::size_t(h) * 4);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, image.rgba.data());
    // GL rows go bottom-up; images top-down.
    const std::size_t row = std::size_t(w) * 4;
    for (int y = 0; y < h / 2; ++y)
        std::swap_ranges(image.rgba.begin() + std::ptrdiff_t(y * row),
                         image.rgba.begin() + std::ptrdiff_t((y + 1) * row),
                         image.rgba.begin() + std::ptrdiff_t((h - 1 - y) * row));
    for (std::size_t i = 3; i < image.rgba.size(); i += 4) image.rgba[i] = 255;
    try {
        write_png(image, path);
    } catch (const std::exception& e) {
        return e.what();
    }
    return "";
}

void FrameOutput::start_recording() {
    if (!context_.record) return;
    RecordState& r = *context_.record;
    const History& h = context_.session.history();
    if (h.current() == 0 || r.running) return;
    std::error_code ec;
    std::filesystem::create_directories(r.folder, ec);
    if (ec || !std::filesystem::is_directory(r.folder)) {
        context_.session.notify_error("record: cannot create the folder " + r.folder);
        return;
    }
    // Framed as the view, fixed for all frames.
    record_camera_ = context_.view.camera;
    record_camera_.reframe_for_viewport(float(r.width), float(r.height));
    int x = 0, y = 0, view_w = 0, view_h = 0;
    framebuffer_viewport(context_.view_rect, x, y, view_w, view_h);
    record_line_scale_ = context_.ui_scale *
                         std::min(float(r.width) / float(view_w), float(r.height) / float(view_h));
    context_.session.execute(PlayMorph{false});
    r.running = true;
    r.next = 0;
    context_.session.log().info("recording " + std::to_string(r.frames) + " frames to " + r.folder);
}

void FrameOutput::record_next_frame() {
    if (!context_.record) return;
    RecordState& r = *context_.record;
    if (!r.running) return;
    context_.keep_drawing();
    try {
        // Show frame `next` of the morph (this also updates the window).
        context_.session.execute(
            ShowMorphAt{r.frames > 1 ? double(r.next) / double(r.frames - 1) : 1.0});
        context_.session.update();
        scene_.sync();
        Framebuffer framebuffer;
        framebuffer.create(r.width, r.height, 4);
        framebuffer.bind();
        RenderStyle style = context_.view.style;
        style.wire_width *= record_line_scale_;
        style.point_size *= record_line_scale_;
        clear_background(style);
        scene_.exact().draw(record_camera_.view(), record_camera_.projection(), style);
        Image image = framebuffer.read_rgba();
        Framebuffer::bind_default();
        write_png(
            image,
            (std::filesystem::path(r.folder) / record::frame_file_name(r.name, r.next)).string());
    } catch (const std::exception& e) {
        Framebuffer::bind_default();
        context_.session.notify_error(std::string("record: ") + e.what());
        finish_recording(true);
        return;
    }
    if (++r.next >= r.frames) finish_recording(false);
}

void FrameOutput::finish_recording(bool cancelled) {
    if (!context_.record) return;
    RecordState& r = *context_.record;
    r.running = false;
    if (cancelled) {
        context_.session.log().warning("recording stopped after " + std::to_string(r.next) +
                                       " frames");
        return;
    }
    context_.session.log().info("recorded " + std::to_string(r.frames) + " frames in " + r.folder);
    if (!r.mp4) return;
    // ffmpeg through posix_spawn with an argument vector (no shell): any folder or name is
    // passed as it is.
    std::string note;
    const std::string mp4 =
        record::encode_mp4(record::Mp4Request{r.folder, r.name, r.frames, r.fps, 4}, note);
    if (!mp4.empty())
        context_.session.log().info("wrote " + mp4);
    else
        context_.session.log().warning("record: " + note);
}

}  // namespace trilab::viewer
