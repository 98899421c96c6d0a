// What the viewer writes: screenshots (F12, --screenshot) and recorded morph frames.
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
#include "app/record/mp4_encoder.h"
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

void Viewer::take_screenshot(const TakeScreenshot& request) {
    try {
        Framebuffer framebuffer;
        framebuffer.create(request.width, request.height, 4);
        framebuffer.bind();
        RenderStyle style = view_.style;
        // Framed as the view; line widths and point sizes keep their look relative to it.
        int x = 0, y = 0, view_w = 0, view_h = 0;
        view_viewport(x, y, view_w, view_h);
        const float scale =
            std::min(float(request.width) / float(view_w), float(request.height) / float(view_h));
        style.wire_width *= ui_scale_ * scale;
        style.point_size *= ui_scale_ * scale;
        clear_background(style, request.transparent ? 0.0f : 1.0f);
        Camera camera = view_.camera;
        camera.reframe_for_viewport(float(request.width), float(request.height));
        renderer_->draw(camera.view(), camera.projection(), style);
        Image image = framebuffer.read_rgba();
        Framebuffer::bind_default();
        if (request.transparent) unpremultiply_alpha(image);
        write_png(image, request.path);
        session_.log().info("screenshot " + request.path + " (" + std::to_string(request.width) +
                            " x " + std::to_string(request.height) + ")");
        session_.notice() = Notice{Notice::Level::Info, "Saved " + request.path, {}, false};
    } catch (const std::exception& e) {
        Framebuffer::bind_default();
        session_.notify_error(std::string("screenshot: ") + e.what());
    }
}

std::string Viewer::write_screenshot(const std::string& path) const {
    int w = 0, h = 0;
    glfwGetFramebufferSize(window_.get(), &w, &h);
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

void Viewer::start_recording() {
    RecordState& r = panels_.record;
    const History& h = session_.history();
    if (h.current() == 0 || r.running) return;
    std::error_code ec;
    std::filesystem::create_directories(r.folder, ec);
    if (ec || !std::filesystem::is_directory(r.folder)) {
        session_.notify_error("record: cannot create the folder " + r.folder);
        return;
    }
    // Framed as the view, fixed for all frames.
    record_camera_ = view_.camera;
    record_camera_.reframe_for_viewport(float(r.width), float(r.height));
    int x = 0, y = 0, view_w = 0, view_h = 0;
    view_viewport(x, y, view_w, view_h);
    record_line_scale_ =
        ui_scale_ * std::min(float(r.width) / float(view_w), float(r.height) / float(view_h));
    session_.morph().playing = false;
    r.running = true;
    r.next = 0;
    session_.log().info("recording " + std::to_string(r.frames) + " frames to " + r.folder);
}

void Viewer::record_next_frame() {
    RecordState& r = panels_.record;
    if (!r.running) return;
    active_frames_ = std::max(active_frames_, 1);
    try {
        // Show frame `next` of the morph (this also updates the window).
        session_.morph().t = r.frames > 1 ? double(r.next) / double(r.frames - 1) : 1.0;
        session_.update();
        sync_renderer();
        Framebuffer framebuffer;
        framebuffer.create(r.width, r.height, 4);
        framebuffer.bind();
        RenderStyle style = view_.style;
        style.wire_width *= record_line_scale_;
        style.point_size *= record_line_scale_;
        clear_background(style);
        renderer_->draw(record_camera_.view(), record_camera_.projection(), style);
        Image image = framebuffer.read_rgba();
        Framebuffer::bind_default();
        write_png(
            image,
            (std::filesystem::path(r.folder) / record::frame_file_name(r.name, r.next)).string());
    } catch (const std::exception& e) {
        Framebuffer::bind_default();
        session_.notify_error(std::string("record: ") + e.what());
        finish_recording(true);
        return;
    }
    if (++r.next >= r.frames) finish_recording(false);
}

void Viewer::finish_recording(bool cancelled) {
    RecordState& r = panels_.record;
    r.running = false;
    if (cancelled) {
        session_.log().warning("recording stopped after " + std::to_string(r.next) + " frames");
        return;
    }
    session_.log().info("recorded " + std::to_string(r.frames) + " frames in " + r.folder);
    if (!r.mp4) return;
    // ffmpeg through posix_spawn with an argument vector (no shell): any folder or name is
    // passed as it is.
    std::string note;
    const std::string mp4 =
        record::encode_mp4(record::Mp4Request{r.folder, r.name, r.frames, r.fps, 4}, note);
    if (!mp4.empty())
        session_.log().info("wrote " + mp4);
    else
        session_.log().warning("record: " + note);
}

}  // namespace trilab::viewer
