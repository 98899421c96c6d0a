#pragma once
// SceneView: what the view draws of the document. It keeps the shown state (Session::shown())
// on the GPU, colours it by the current colouring (a job for large meshes), gives it the
// texture, decides the automatic wireframe overlay, and draws a large mesh through a
// simplified stand-in while the view moves and exactly at rest (scene_view.cpp has the
// rules). It reads the session and changes nothing in the document; its warnings go to the
// session's log.
#include <cstdint>
#include <functional>
#include <future>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "app/viewer/viewer_context.h"
#include "core/algorithms/proxy_mesh.h"
#include "core/algorithms/spectral.h"
#include "core/algorithms/transfer_function.h"
#include "core/io/image_io.h"
#include "render/mesh_renderer.h"
#include "render/proxy_view.h"

namespace trilab::viewer {

/// The view region `view_rect` (window pixels, from the layout) in framebuffer pixels, GL's
/// origin (bottom left); reads the display's size and scale from ImGui's IO.
void framebuffer_viewport(const Rect& view_rect, int& x, int& y, int& w, int& h);

class SceneView {
public:
    /// Needs the GL context current (creates the renderers and uploads the texture).
    explicit SceneView(ViewerContext& context);
    SceneView(const SceneView&) = delete;
    SceneView& operator=(const SceneView&) = delete;

    /// The smallest face count drawn through a stand-in while moving (TRILAB_PROXY_MIN_FACES
    /// overrides it, for tests), and the stand-in's options for a state of `n_faces` faces (the
    /// document's and the loading picture's: the same options make the same stand-in).
    static std::size_t proxy_min_faces();
    static ProxyMeshOptions proxy_options(std::size_t n_faces);

    /// Follows SessionEvents: a new current state (its area, for the wireframe rule), a
    /// loaded document's stand-in, a new model (its view stays), a loaded texture image.
    void state_changed(double area);
    void adopt_loaded_proxy(std::shared_ptr<const ProxyMesh> proxy);
    void model_fitted() { loading_.restore_camera = false; }
    void set_texture_image(Image image, std::string path);
    void clear_texture_image() { texture_ = Image{}; }
    const Image& texture_image() const { return texture_; }
    const std::string& texture_path() const { return texture_path_; }

    /// Makes the GPU show session.shown(), uploading only what changed; a large new state
    /// waits for its stand-in (exact_pending()). `force` uploads again (new colours).
    void sync();
    void invalidate() { shown_version_ = 0; }
    /// Uploads a pending large state now (pictures of the scene show the exact surface).
    void ensure_exact();
    /// Computes the colouring of view.settings (as a job for large meshes) and uploads it;
    /// `field_colors` gives the colourings computed from a field (frequency, geodesic).
    void update_coloring();
    /// After a job ended: applies the session's colouring result when it is of the current
    /// colouring and state; returns true when a colouring is still to be computed (one asked
    /// for while a job ran, or the result was of another state).
    bool poll_coloring();
    void set_field_colors(std::function<VertexColors(const HalfedgeMesh&)> field_colors) {
        field_colors_ = std::move(field_colors);
    }
    /// Uploads the texture chosen in view.settings (checkerboard or the loaded image).
    void update_texture();
    /// The user drags in the view this frame: a large mesh's stand-in is drawn (an exact
    /// frame would delay the drag's next events by seconds).
    void note_input();
    /// Decides the wireframe overlay for this frame (view.style.wireframe).
    void update_wireframe();
    /// Draws the shown state with `style` over the current viewport: the stand-in while the
    /// view moves, the exact surface at rest; then the note over the view's corner.
    void draw(const RenderStyle& style);
    /// Draws "simplified while moving" over the view's corner (ImGui foreground list), in the
    /// UI pass before draw(): while the stand-in is expected on the screen this frame.
    void draw_note();

    MeshRenderer& exact() { return *renderer_; }
    const MeshRenderer& exact() const { return *renderer_; }
    /// The picks version the geodesic colours show.
    std::uint64_t geodesic_colored_version() const { return geodesic_colored_version_; }
    double edge_pixels() const { return edge_pixels_; }
    /// The vertex and face counts of what is on the screen (a preview, a level of detail).
    std::pair<std::size_t, std::size_t> shown_counts() const;

    // What the last draw showed (scripted runs, timing).
    bool exact_pending() const { return proxy_.exact_pending; }
    bool drew_proxy() const { return proxy_.drew_proxy; }
    bool shows_current() const { return proxy_.shows_current; }
    bool drew_prediction_of(const Operation& op) const {
        return proxy_.drew_predicted && proxy_.predicted_for == op;
    }
    double error_pixels() const { return proxy_.error_pixels; }
    bool loading_picture_drawn() const { return loading_.drawn; }
    /// The loading picture not on the screen yet (a scripted run's wait draws it first).
    bool new_loading_picture() const;
    const std::string* loading_picture_path() const {
        return loading_.picture ? &loading_.picture->path : nullptr;
    }
    std::size_t loading_picture_faces() const {
        return loading_.picture ? loading_.picture->faces : 0;
    }
    /// The view's stand-in is ready (made or failed) or none applies, and nothing moves:
    /// scripted actions that time the view may start.
    bool at_rest(double now) const;
    /// Nothing pending: no upload waits and no stand-in is on the screen.
    bool settled(double now) const;

private:
    /// A shown mesh state: its topology and geometry revisions.
    using MeshKey = std::pair<std::uint64_t, std::uint64_t>;
    /// The stand-ins and the motion that decides between them and the exact surface.
    struct ProxyView {
        std::unique_ptr<MeshRenderer> renderer;  ///< the stand-in's GPU mirror
        MotionClock motion;
        /// Stand-ins made, by the state they stand for (a few: the levels a slider visits).
        std::map<MeshKey, std::shared_ptr<const ProxyMesh>> cache;
        std::vector<MeshKey> cache_order;  ///< oldest first
        std::vector<MeshKey> failed;       ///< states whose stand-in could not be made
        /// The stand-in being made (on a worker thread, from a copy of the mesh).
        MeshKey job_key{0, 0};
        std::future<std::shared_ptr<const ProxyMesh>> job;
        /// Jobs for states no longer shown: kept until they end (a future's destructor waits).
        std::vector<std::future<std::shared_ptr<const ProxyMesh>>> abandoned;
        bool current = false;  ///< the shown state is large enough for a stand-in
        MeshKey current_key{0, 0};
        bool exact_pending = false;         ///< the shown state is not uploaded yet (sync())
        bool proxy_drawn = false;           ///< the current state's stand-in was on the screen
        MeshKey uploaded_key{0, 0};         ///< on `renderer`
        std::uint64_t uploaded_colors = 0;  ///< colors_stamp of the stand-in's colours
        /// The attribute revision of the state whose selection and texture coordinates the
        /// stand-in's renderer has (0: none given since the last upload).
        std::uint64_t attributes_revision = 0;
        /// The colours on (or waiting for) the exact renderer, and the state they are for.
        VertexColors colors;
        MeshKey colors_key{0, 0};
        std::uint64_t colors_stamp = 1;
        bool drew_proxy = false;       ///< this frame drew the stand-in
        bool shows_current = false;    ///< this frame showed the shown state (stand-in or exact)
        double error_pixels = 0;       ///< of the stand-in on the screen
        std::size_t proxy_frames = 0;  ///< frames of the current run drawn simplified
        /// A large mesh's spectral prediction drawn before it is computed: the decomposition
        /// averaged over the document's stand-in (cluster_basis, made on a worker thread), for
        /// that decomposition and document state.
        std::shared_ptr<const ClusteredBasis> basis;
        std::shared_ptr<const SpectralDecomposition> basis_of;
        MeshKey basis_key{0, 0};
        std::future<std::shared_ptr<const ClusteredBasis>> basis_job;
        std::optional<Operation> predicted_for;  ///< the request whose prediction is uploaded
        bool drew_predicted = false;             ///< this frame drew it
    };
    /// The picture of a file still loading (Session::loading_picture), drawn by the
    /// stand-in's renderer until the load ends.
    struct LoadingView {
        std::shared_ptr<const LoadingPicture> picture;  ///< on the stand-in's renderer
        bool drawn = false;                             ///< this frame drew it
        Camera camera_before;                           ///< the view before the picture was fitted
        bool restore_camera = false;                    ///< the load has not brought a model yet
        double error_pixels = 0;
        /// The surface area of a picture's triangles (the automatic wireframe's rule).
        std::shared_ptr<const LoadingPicture> area_of;
        double area = 0;
        std::shared_ptr<const LoadingPicture> wire_logged;  ///< its wireframe decision logged
    };

    void upload_shown();
    void apply_colors(VertexColors colors);
    /// Colours `mesh` by the current colouring (`reference`: the smoothing distance's).
    void show_colors_of(const HalfedgeMesh& mesh, const std::vector<Point>& reference);
    bool proxy_applies(const Shown& shown) const;
    void request_proxy(const HalfedgeMesh& mesh);
    void poll_proxy_job();
    void note_exact_colors(const VertexColors& colors, const HalfedgeMesh& mesh);
    void colour_proxy(MeshRenderer& r, const MeshKey& stands_for,
                      const std::vector<Index>& representative);
    void dress_proxy(MeshRenderer& r, const HalfedgeMesh& mesh,
                     const std::vector<Index>& representative);
    /// The renderer to draw this frame (nullptr: nothing new; the old content stays).
    MeshRenderer* choose_renderer();
    MeshRenderer* choose_loading_picture();
    MeshRenderer* choose_clustered_prediction();

    ViewerContext& context_;
    Session& session_;
    ViewState& view_;
    std::unique_ptr<MeshRenderer> renderer_;  ///< the exact surface's GPU mirror
    ProxyView proxy_;
    LoadingView loading_;
    Image texture_;       ///< the loaded texture image (empty: none)
    Image checkerboard_;  ///< the built-in texture
    std::string texture_path_;
    std::function<VertexColors(const HalfedgeMesh&)> field_colors_;
    std::uint64_t shown_version_ = 0;  ///< of session.shown() on the GPU
    Shown::Kind shown_kind_ = Shown::Kind::Document;
    double surface_area_ = 0;               ///< of the current state (the wireframe decision)
    bool wire_auto_on_ = false;             ///< the automatic overlay's last decision (hysteresis)
    double edge_pixels_ = 0;                ///< a typical edge on the screen (framebuffer pixels)
    bool coloring_pending_ = false;         ///< a colouring was asked for while a job ran
    std::uint64_t coloring_result_id_ = 0;  ///< the session's colouring result applied last
    std::uint64_t geodesic_colored_version_ = 0;
    bool note_shown_ = false;  ///< this frame's UI showed "simplified" (draw_note())
};

}  // namespace trilab::viewer
