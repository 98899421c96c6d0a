#pragma once
// Offscreen rendering: framebuffer objects that read back into an Image, a headless OpenGL
// context, and one-call rendering of a mesh to an image.
//
// The headless context is EGL without any window system: Mesa's surfaceless platform
// (EGL_MESA_platform_surfaceless) with an OpenGL 3.3 core context made current without a
// surface, drawing into a Framebuffer. It needs no X server and no DISPLAY; on a machine
// without a GPU Mesa renders with llvmpipe (set LIBGL_ALWAYS_SOFTWARE=1 to force that on a
// machine with one). libEGL is opened at run time through glad's EGL loader, so nothing
// links against it. When the surfaceless platform is missing (e.g. a vendor EGL without
// it), the default EGL display is tried before giving up.
//
// Framebuffer needs only a current GL 3.3 context, so the viewer uses it inside its GLFW
// context for screenshots larger than the window.
#include <glad/gl.h>

#include <string>
#include <vector>

#include "core/halfedge_mesh.h"
#include "core/io/image_io.h"
#include "render/camera.h"
#include "render/mesh_renderer.h"

namespace trilab {

/// A framebuffer object with an RGBA8 colour and a 24-bit depth (+ 8-bit stencil) buffer,
/// optionally multisampled (resolved on read-back). Move-only; needs the GL 3.3 context that
/// was current at create() for every call, including destruction.
class Framebuffer {
public:
    Framebuffer() = default;
    ~Framebuffer();
    Framebuffer(Framebuffer&& other) noexcept;
    Framebuffer& operator=(Framebuffer&& other) noexcept;
    Framebuffer(const Framebuffer&) = delete;
    Framebuffer& operator=(const Framebuffer&) = delete;

    /// (Re)creates the buffers: width x height pixels, `samples` samples per pixel (1: no
    /// multisampling; clamped to GL_MAX_SAMPLES). Throws InvalidArgument for a size below 1 or
    /// above the GL limits (renderbuffer size, viewport), GlError if the driver refuses the
    /// combination. Leaves the default framebuffer (0) bound.
    void create(int width, int height, int samples = 1);
    /// Binds it for drawing and reading and sets the viewport to its size.
    void bind() const;
    /// Binds framebuffer 0 (the window's) again.
    static void bind_default();
    /// The pixels, rows top-down (the flip from GL's bottom-up rows is done here). Resolves
    /// multisampling first. Leaves this framebuffer bound. Throws GlError when not created.
    Image read_rgba() const;

    int width() const { return width_; }
    int height() const { return height_; }
    int samples() const { return samples_; }
    bool is_valid() const { return fbo_ != 0; }

private:
    void release();
    GLuint fbo_ = 0, color_ = 0, depth_ = 0;
    GLuint resolve_fbo_ = 0, resolve_color_ = 0;  ///< only when multisampled
    int width_ = 0, height_ = 0, samples_ = 1;
};

/// Converts pixels premultiplied by alpha (what a framebuffer cleared to (0, 0, 0, 0) holds
/// after drawing, see clear_background()) to straight alpha, as PNG files expect. Pixels
/// with alpha 0 or 255 are unchanged. For screenshots with a transparent background.
void unpremultiply_alpha(Image& image);

/// A headless OpenGL 3.3 core context (EGL, see the top of this file), current on the
/// constructing thread from construction on, with glad's GL functions loaded. Throws Error
/// naming what is missing when EGL or a suitable context is unavailable. Move-free; destroy
/// it on the thread that created it, after every GL object made in it.
class OffscreenContext {
public:
    OffscreenContext();
    ~OffscreenContext();
    OffscreenContext(const OffscreenContext&) = delete;
    OffscreenContext& operator=(const OffscreenContext&) = delete;

    /// Makes this context current again (e.g. after another one was).
    void make_current() const;
    /// "EGL platform, GL_RENDERER, GL_VERSION", e.g. "surfaceless, llvmpipe (...), 4.5 ...".
    const std::string& description() const { return description_; }

private:
    void* display_ = nullptr;
    void* context_ = nullptr;
    std::string description_;
};

/// What render_offscreen() draws.
struct OffscreenOptions {
    int width = 1280, height = 800;  ///< pixels
    RenderStyle style;
    /// View direction (Camera::set_view_angles()): degrees around the up axis from the front
    /// (+y up: around +y from +z; +z up: around +z from -y), and above the horizontal plane.
    /// The camera then frames the mesh's vertices tightly and centred
    /// (Camera::fit_points_in_view()).
    float azimuth = 0.0f, elevation = 0.0f;
    UpAxis up = UpAxis::Y;  ///< the model's up axis (core/up_axis.h)
    float margin = 0.07f;   ///< free border, as a fraction of the half-width/half-height
    /// Alpha 0 where no surface is drawn (colours un-premultiplied); otherwise the
    /// background is style.background with alpha 1.
    bool transparent = false;
    int samples = 4;  ///< multisampling (anti-aliased silhouettes); 1 for none
    /// Per-vertex colours by vertex storage index (MeshRenderer::set_vertex_colors()); empty:
    /// none.
    std::vector<Color> vertex_colors;
    /// How vertex_colors fill the triangles: color_blend(colors.kind) for a VertexColors.
    ColorBlend vertex_color_blend = ColorBlend::Interpolate;
    /// Per-vertex scalars for style.scalar_display (MeshRenderer::set_vertex_scalars(): NaN
    /// for none; empty: none) over `scalar_range`, bands coloured by `scalar_map`. For a
    /// VertexColors: its values, range and kind (not for a categorical one).
    std::vector<double> vertex_scalars;
    ValueRange scalar_range;
    ColorMapKind scalar_map = ColorMapKind::Sequential;
    Image texture;  ///< the texture of Textured mode; empty: none
};

/// The camera render_offscreen() uses for `mesh` (viewport = options' size).
Camera offscreen_camera(const HalfedgeMesh& mesh, const OffscreenOptions& options);

/// Renders meshes to images in one headless context kept for its lifetime (creating the
/// context costs tens of milliseconds; reuse an OffscreenRenderer for many images).
class OffscreenRenderer {
public:
    /// Creates the context and compiles the shaders. Throws Error when EGL is unavailable
    /// (see OffscreenContext), GlError when a shader does not build.
    OffscreenRenderer();
    OffscreenRenderer(const OffscreenRenderer&) = delete;
    OffscreenRenderer& operator=(const OffscreenRenderer&) = delete;

    /// Uploads `mesh`, draws one frame as `options` say and reads it back. Throws
    /// InvalidArgument for a bad size or a vertex colour count that does not match
    /// mesh.vertices_size().
    Image render(const HalfedgeMesh& mesh, const OffscreenOptions& options);

    const OffscreenContext& context() const { return context_; }
    MeshRenderer& mesh_renderer() { return renderer_; }

private:
    // Declaration order matters: the GL objects go before the context that owns them.
    OffscreenContext context_;
    MeshRenderer renderer_;
    Framebuffer framebuffer_;
};

/// One image of `mesh` in a fresh headless context (OffscreenRenderer for a single call).
Image render_offscreen(const HalfedgeMesh& mesh, const OffscreenOptions& options);

}  // namespace trilab
