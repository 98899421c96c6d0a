#include "render/offscreen.h"

// glad's EGL loader (generated with EGL 1.5, EXT_platform_base, MESA_platform_surfaceless,
// KHR_surfaceless_context, KHR_create_context) dlopens libEGL.so.1 at run time.
#include <glad/egl.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

#include "core/errors.h"

namespace trilab {
namespace {

std::string egl_error() {
    char buf[32];
    std::snprintf(buf, sizeof(buf), "EGL error 0x%04X", unsigned(eglGetError()));
    return buf;
}

GLADapiproc egl_load(const char* name) {
    return reinterpret_cast<GLADapiproc>(eglGetProcAddress(name));
}

/// Displays initialised by live OffscreenContexts (EGL hands out one display per platform,
/// so the last context to go terminates it).
int g_live_contexts = 0;

void check_size(const char* who, int width, int height) {
    if (width < 1 || height < 1)
        throw InvalidArgument(std::string(who) + ": size " + std::to_string(width) + "x" +
                              std::to_string(height) + " is not positive");
}

}  // namespace

// ---- Framebuffer -------------------------------------------------------------------------

Framebuffer::~Framebuffer() {
    release();
}

Framebuffer::Framebuffer(Framebuffer&& other) noexcept
    : fbo_(std::exchange(other.fbo_, 0)),
      color_(std::exchange(other.color_, 0)),
      depth_(std::exchange(other.depth_, 0)),
      resolve_fbo_(std::exchange(other.resolve_fbo_, 0)),
      resolve_color_(std::exchange(other.resolve_color_, 0)),
      width_(std::exchange(other.width_, 0)),
      height_(std::exchange(other.height_, 0)),
      samples_(std::exchange(other.samples_, 1)) {}

Framebuffer& Framebuffer::operator=(Framebuffer&& other) noexcept {
    if (this != &other) {
        release();
        fbo_ = std::exchange(other.fbo_, 0);
        color_ = std::exchange(other.color_, 0);
        depth_ = std::exchange(other.depth_, 0);
        resolve_fbo_ = std::exchange(other.resolve_fbo_, 0);
        resolve_color_ = std::exchange(other.resolve_color_, 0);
        width_ = std::exchange(other.width_, 0);
        height_ = std::exchange(other.height_, 0);
        samples_ = std::exchange(other.samples_, 1);
    }
    return *this;
}

void Framebuffer::release() {
    if (fbo_ != 0) glDeleteFramebuffers(1, &fbo_);
    if (resolve_fbo_ != 0) glDeleteFramebuffers(1, &resolve_fbo_);
    const GLuint renderbuffers[3] = {color_, depth_, resolve_color_};
    for (GLuint rb : renderbuffers)
        if (rb != 0) glDeleteRenderbuffers(1, &rb);
    fbo_ = color_ = depth_ = resolve_fbo_ = resolve_color_ = 0;
    width_ = height_ = 0;
    samples_ = 1;
}

void Framebuffer::create(int width, int height, int samples) {
    check_size("Framebuffer::create", width, height);
    GLint max_renderbuffer = 0, max_viewport[2] = {0, 0}, max_samples = 1;
    glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max_renderbuffer);
    glGetIntegerv(GL_MAX_VIEWPORT_DIMS, max_viewport);
    glGetIntegerv(GL_MAX_SAMPLES, &max_samples);
    const int max_w = std::min(max_renderbuffer, max_viewport[0]);
    const int max_h = std::min(max_renderbuffer, max_viewport[1]);
    if (width > max_w || height > max_h)
        throw InvalidArgument("Framebuffer::create: size " + std::to_string(width) + "x" +
                              std::to_string(height) + " exceeds this GL's limit of " +
                              std::to_string(max_w) + "x" + std::to_string(max_h));
    samples = std::clamp(samples, 1, std::max(max_samples, 1));
    release();

    auto make_target = [&](GLuint& fbo, GLuint& color, GLuint* depth, int n_samples) {
        glGenFramebuffers(1, &fbo);
        glBindFramebuffer(GL_FRAMEBUFFER, fbo);
        glGenRenderbuffers(1, &color);
        glBindRenderbuffer(GL_RENDERBUFFER, color);
        if (n_samples > 1)
            glRenderbufferStorageMultisample(GL_RENDERBUFFER, n_samples, GL_RGBA8, width, height);
        else
            glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, color);
        if (depth) {
            glGenRenderbuffers(1, depth);
            glBindRenderbuffer(GL_RENDERBUFFER, *depth);
            if (n_samples > 1)
                glRenderbufferStorageMultisample(GL_RENDERBUFFER, n_samples, GL_DEPTH24_STENCIL8,
                                                 width, height);
            else
                glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH24_STENCIL8, width, height);
            glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER,
                                      *depth);
        }
        const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
        glBindRenderbuffer(GL_RENDERBUFFER, 0);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        if (status != GL_FRAMEBUFFER_COMPLETE) {
            release();
            char buf[128];
            std::snprintf(buf, sizeof(buf),
                          "Framebuffer::create: %dx%d with %d samples is incomplete "
                          "(status 0x%04X)",
                          width, height, n_samples, unsigned(status));
            throw GlError(buf);
        }
    };
    make_target(fbo_, color_, &depth_, samples);
    if (samples > 1) make_target(resolve_fbo_, resolve_color_, nullptr, 1);
    width_ = width;
    height_ = height;
    samples_ = samples;
}

void Framebuffer::bind() const {
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
    glViewport(0, 0, width_, height_);
}

void Framebuffer::bind_default() {
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

Image Framebuffer::read_rgba() const {
    if (fbo_ == 0) throw GlError("Framebuffer::read_rgba: the framebuffer was not created");
    GLuint source = fbo_;
    if (samples_ > 1) {
        glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo_);
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, resolve_fbo_);
        glBlitFramebuffer(0, 0, width_, height_, 0, 0, width_, height_, GL_COLOR_BUFFER_BIT,
                          GL_NEAREST);
        source = resolve_fbo_;
    }
    glBindFramebuffer(GL_READ_FRAMEBUFFER, source);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    GLint alignment = 4;
    glGetIntegerv(GL_PACK_ALIGNMENT, &alignment);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    const std::size_t row = std::size_t(width_) * 4;
    std::vector<std::uint8_t> bottom_up(row * std::size_t(height_));
    glReadPixels(0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, bottom_up.data());
    glPixelStorei(GL_PACK_ALIGNMENT, alignment);
    bind();

    Image image;
    image.width = width_;
    image.height = height_;
    image.rgba.resize(bottom_up.size());
    for (int y = 0; y < height_; ++y)
        std::copy_n(bottom_up.begin() + std::ptrdiff_t(row * std::size_t(height_ - 1 - y)), row,
                    image.rgba.begin() + std::ptrdiff_t(row * std::size_t(y)));
    return image;
}

void unpremultiply_alpha(Image& image) {
    for (std::size_t i = 0; i + 3 < image.rgba.size(); i += 4) {
        const unsigned a = image.rgba[i + 3];
        if (a == 0 || a == 255) continue;
        for (std::size_t c = 0; c < 3; ++c)
            image.rgba[i + c] =
                std::uint8_t(std::min(255u, (unsigned(image.rgba[i + c]) * 255u + a / 2) / a));
    }
}

// ---- OffscreenContext --------------------------------------------------------------------

OffscreenContext::OffscreenContext() {
    const std::string what = "offscreen rendering needs EGL (a headless OpenGL context)";
    if (gladLoaderLoadEGL(EGL_NO_DISPLAY) == 0)
        throw Error(what +
                    ", but libEGL.so.1 could not be loaded: install libegl1 and a "
                    "Mesa driver (libgl1-mesa-dri)");

    // 1. Mesa's surfaceless platform: no window system at all. 2. The default display (works
    // with drivers that are headless by default, or with a DISPLAY).
    EGLDisplay display = EGL_NO_DISPLAY;
    std::string platform, failures;
    EGLint major = 0, minor = 0;
    if (eglGetPlatformDisplayEXT) {
        display = eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, nullptr, nullptr);
        if (display != EGL_NO_DISPLAY && eglInitialize(display, &major, &minor)) {
            platform = "EGL surfaceless";
        } else {
            failures +=
                "the surfaceless platform (EGL_MESA_platform_surfaceless) failed: " + egl_error() +
                "; ";
            display = EGL_NO_DISPLAY;
        }
    } else {
        failures += "eglGetPlatformDisplayEXT is missing (no EGL_EXT_platform_base); ";
    }
    if (display == EGL_NO_DISPLAY) {
        display = eglGetDisplay(EGL_DEFAULT_DISPLAY);
        if (display != EGL_NO_DISPLAY && eglInitialize(display, &major, &minor)) {
            platform = "EGL default display";
        } else {
            failures += "the default display failed: " + egl_error();
            throw Error(what + ", but no EGL display could be initialised: " + failures +
                        " (on Debian: libegl1 and libgl1-mesa-dri)");
        }
    }
    // Now that a display is initialised, glad can load the EGL 1.5 entry points.
    gladLoaderLoadEGL(display);
    ++g_live_contexts;
    display_ = display;

    auto fail = [&](const std::string& why) {
        if (--g_live_contexts == 0) eglTerminate(display);
        throw Error(what + ": " + why + " (" + platform + ")");
    };
    if (!GLAD_EGL_KHR_surfaceless_context) fail("the display lacks EGL_KHR_surfaceless_context");
    if (!eglBindAPI(EGL_OPENGL_API)) fail("eglBindAPI(EGL_OPENGL_API) failed: " + egl_error());

    const EGLint config_attributes[] = {EGL_RENDERABLE_TYPE,
                                        EGL_OPENGL_BIT,
                                        EGL_SURFACE_TYPE,
                                        0,  // any: nothing is drawn to a surface
                                        EGL_RED_SIZE,
                                        8,
                                        EGL_GREEN_SIZE,
                                        8,
                                        EGL_BLUE_SIZE,
                                        8,
                                        EGL_ALPHA_SIZE,
                                        8,
                                        EGL_NONE};
    EGLConfig config = nullptr;
    EGLint n_configs = 0;
    if (!eglChooseConfig(display, config_attributes, &config, 1, &n_configs) || n_configs < 1)
        fail("no RGBA8 OpenGL config: " + egl_error());

    const EGLint context_attributes[] = {EGL_CONTEXT_MAJOR_VERSION,
                                         3,
                                         EGL_CONTEXT_MINOR_VERSION,
                                         3,
                                         EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                         EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                         EGL_NONE};
    EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, context_attributes);
    if (context == EGL_NO_CONTEXT)
        fail("no OpenGL 3.3 core context: eglCreateContext failed: " + egl_error());
    context_ = context;
    if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
        const std::string error = egl_error();
        eglDestroyContext(display, context);
        fail("eglMakeCurrent without a surface failed: " + error);
    }
    if (gladLoadGL(egl_load) == 0) {
        eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        eglDestroyContext(display, context);
        fail("the OpenGL functions could not be loaded");
    }
    auto text = [](GLenum name) {
        const GLubyte* s = glGetString(name);
        return s ? std::string(reinterpret_cast<const char*>(s)) : std::string("?");
    };
    description_ = platform + ", " + text(GL_RENDERER) + ", OpenGL " + text(GL_VERSION);
}

OffscreenContext::~OffscreenContext() {
    EGLDisplay display = static_cast<EGLDisplay>(display_);
    eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(display, static_cast<EGLContext>(context_));
    if (--g_live_contexts == 0) eglTerminate(display);
}

void OffscreenContext::make_current() const {
    if (!eglMakeCurrent(static_cast<EGLDisplay>(display_), EGL_NO_SURFACE, EGL_NO_SURFACE,
                        static_cast<EGLContext>(context_)))
        throw Error("OffscreenContext::make_current: eglMakeCurrent failed: " + egl_error());
}

// ---- rendering ---------------------------------------------------------------------------

Camera offscreen_camera(const HalfedgeMesh& mesh, const OffscreenOptions& options) {
    Camera camera;
    camera.set_viewport(float(options.width), float(options.height));
    camera.set_view_angles(options.azimuth, options.elevation, options.up);
    std::vector<glm::vec3> points;
    points.reserve(mesh.n_vertices());
    for (Vertex v : mesh.vertices()) {
        const Point& p = mesh.position(v);
        points.emplace_back(float(p.x()), float(p.y()), float(p.z()));
    }
    camera.fit_points_in_view(points, options.margin);
    return camera;
}

OffscreenRenderer::OffscreenRenderer() = default;

Image OffscreenRenderer::render(const HalfedgeMesh& mesh, const OffscreenOptions& options) {
    check_size("render_offscreen", options.width, options.height);
    if (!options.vertex_colors.empty() && options.vertex_colors.size() != mesh.vertices_size())
        throw InvalidArgument("render_offscreen: " + std::to_string(options.vertex_colors.size()) +
                              " vertex colours for a mesh with vertex storage size " +
                              std::to_string(mesh.vertices_size()));
    if (!options.vertex_scalars.empty() && options.vertex_scalars.size() != mesh.vertices_size())
        throw InvalidArgument("render_offscreen: " + std::to_string(options.vertex_scalars.size()) +
                              " vertex scalars for a mesh with vertex storage size " +
                              std::to_string(mesh.vertices_size()));
    context_.make_current();
    if (!framebuffer_.is_valid() || framebuffer_.width() != options.width ||
        framebuffer_.height() != options.height || framebuffer_.samples() != options.samples)
        framebuffer_.create(options.width, options.height, options.samples);

    renderer_.upload(mesh);
    if (!options.vertex_colors.empty())
        renderer_.set_vertex_colors(options.vertex_colors, options.vertex_color_blend);
    if (!options.vertex_scalars.empty())
        renderer_.set_vertex_scalars(options.vertex_scalars, options.scalar_range,
                                     options.scalar_map);
    if (options.texture.empty())
        renderer_.clear_texture();
    else
        renderer_.set_texture(options.texture);

    const Camera camera = offscreen_camera(mesh, options);
    framebuffer_.bind();
    clear_background(options.style, options.transparent ? 0.0f : 1.0f);
    renderer_.draw(camera.view(), camera.projection(), options.style);
    Image image = framebuffer_.read_rgba();
    Framebuffer::bind_default();

    if (options.transparent) unpremultiply_alpha(image);
    return image;
}

Image render_offscreen(const HalfedgeMesh& mesh, const OffscreenOptions& options) {
    OffscreenRenderer renderer;
    return renderer.render(mesh, options);
}

}  // namespace trilab
