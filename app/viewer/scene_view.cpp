// What the view draws of the document (scene_view.h).
//
// Large meshes: simplified while moving, exact at rest. After a state is shown whose mesh has
// at least proxy_min_faces() faces (a Document or a Preview), its stand-in
// (core/algorithms/proxy_mesh.h: vertex clustering to about kProxyTriangles triangles) is made
// on a worker thread from a copy of the mesh (the document is never touched there); a job for
// a state no longer shown is left to end and ignored. While the view moves (its camera
// matrices change between frames: rotate, pan, zoom, the scripted orbit) or the shown surface
// changes (a slider drag, a load), the second renderer draws the stand-in, with the current
// colouring sampled through ProxyMesh::representative, in whatever mode; kRestSeconds after
// the last motion the exact surface is drawn again. A new large state is uploaded to the
// exact renderer only once its stand-in has been on the screen and the view rests, so a
// slider drag or the first picture of a large file costs the stand-in's frame, not the exact
// upload. While the stand-in is on the screen a note says so, with its error bound in
// framebuffer pixels at the target's depth.
#include "app/viewer/scene_view.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>

#include "app/viewer/viewer_tuning.h"
#include "core/algorithms/selection.h"
#include "core/geometry.h"

namespace trilab::viewer {
using namespace tuning;
namespace {

/// Meshes of at least this many faces are drawn through a stand-in while moving: llvmpipe
/// sets up about 130 ns a triangle here, so 200k faces are about 26 ms of a frame, the most
/// that leaves room for the UI in the 40 ms budget; smaller meshes are always drawn exactly.
constexpr std::size_t kProxyMinFaces = 200000;
/// The stand-in's triangles (at most a quarter of the mesh's): about 8 ms of llvmpipe's
/// setup a frame; the error bound is about 9 px for the bunny filling a 1280x800 view.
constexpr std::size_t kProxyTriangles = 60000;
/// Stand-ins kept (the levels a slider visits).
constexpr std::size_t kProxyCache = 6;

template <typename T>
bool ready(const std::future<T>& f) {
    return f.valid() && f.wait_for(std::chrono::seconds(0)) == std::future_status::ready;
}

}  // namespace

void framebuffer_viewport(const Rect& view_rect, int& x, int& y, int& w, int& h) {
    // The backend reads the window and framebuffer sizes once a frame; no X round trip here.
    const ImGuiIO& io = ImGui::GetIO();
    const float sx = io.DisplayFramebufferScale.x, sy = io.DisplayFramebufferScale.y;
    const int fb_h = int(std::lround(io.DisplaySize.y * sy));
    x = int(std::lround(view_rect.x * sx));
    w = std::max(1, int(std::lround(view_rect.w * sx)));
    h = std::max(1, int(std::lround(view_rect.h * sy)));
    y = fb_h - int(std::lround(view_rect.y * sy)) - h;  // GL counts rows from the bottom
}

SceneView::SceneView(ViewerContext& context)
    : context_(context), session_(context.session), view_(context.view) {
    renderer_ = std::make_unique<MeshRenderer>();
    proxy_.renderer = std::make_unique<MeshRenderer>();
    checkerboard_ = make_checkerboard();
    update_texture();
}

void SceneView::state_changed(double area) {
    surface_area_ = area;
    shown_version_ = 0;  // upload what is shown again, with the new colours
    view_.colors = VertexColors{};
    // A large state is uploaded once its stand-in was shown (sync()).
    if (session_.mesh().n_faces() < proxy_min_faces()) renderer_->show(session_.mesh());
    renderer_->clear_vertex_colors();
    if (view_.settings.coloring != VertexColoring::None) update_coloring();
}

void SceneView::adopt_loaded_proxy(std::shared_ptr<const ProxyMesh> proxy) {
    // The loading picture is the loaded document's stand-in (a clean triangle soup): no
    // second clustering.
    const HalfedgeMesh& mesh = session_.mesh();
    const MeshKey key{mesh.topology_revision(), mesh.geometry_revision()};
    if (proxy_.cache.count(key)) return;
    proxy_.cache[key] = std::move(proxy);
    proxy_.cache_order.push_back(key);
}

void SceneView::set_texture_image(Image image, std::string path) {
    texture_ = std::move(image);
    texture_path_ = std::move(path);
    view_.settings.use_checkerboard = false;
    update_texture();
}

void SceneView::ensure_exact() {
    if (proxy_.exact_pending) upload_shown();
}

bool SceneView::poll_coloring() {
    // The session's colouring job ended: its colours, unless the user has already replaced
    // the colouring; of another state (an entry applied meanwhile), that state is coloured
    // again.
    if (const SessionColoring::Result* r = session_.coloring().result();
        r && r->id != coloring_result_id_) {
        coloring_result_id_ = r->id;
        if (view_.settings.coloring == r->coloring) {
            if (session_.mesh().revision() != r->state)
                coloring_pending_ = true;
            else
                apply_colors(r->colors);
        }
    }
    const bool pending = coloring_pending_;
    coloring_pending_ = false;
    return pending;
}

bool SceneView::new_loading_picture() const {
    const auto picture = session_.files().loading_picture();
    return picture && picture != loading_.picture;
}

std::pair<std::size_t, std::size_t> SceneView::shown_counts() const {
    const Shown& shown = session_.shown();
    if (shown.kind == Shown::Kind::Level)
        return {shown.level->vertices(), renderer_->n_triangles()};
    return {shown.mesh->n_vertices(), shown.mesh->n_faces()};
}

bool SceneView::at_rest(double now) const {
    const bool proxy_ready = !proxy_.current || proxy_.cache.count(proxy_.current_key) ||
                             std::find(proxy_.failed.begin(), proxy_.failed.end(),
                                       proxy_.current_key) != proxy_.failed.end();
    return session_.shown().version == shown_version_ && !proxy_.exact_pending &&
           !proxy_.drew_proxy && proxy_ready && !proxy_.motion.moving(now);
}

bool SceneView::settled(double now) const {
    if (proxy_.exact_pending || proxy_.drew_proxy) return false;
    return !(proxy_.current && proxy_.motion.moving(now));
}

void SceneView::draw(const RenderStyle& style) {
    MeshRenderer* shown = choose_renderer();
    if (shown)
        shown->draw(view_.camera.view(), view_.camera.projection(),
                    shown == proxy_.renderer.get() ? stand_in_style(style) : style);
    else
        renderer_->draw(view_.camera.view(), view_.camera.projection(), style);
    // The note is drawn with the UI, before the scene: when it told otherwise than what this
    // frame drew (the view came to rest), one more frame corrects it, even where the loop
    // would sleep now.
    if (note_shown_ != (proxy_.drew_proxy || loading_.drawn)) context_.keep_drawing();
    // Tests only: an exact frame of a large mesh as slow as a 17.8M-face one in a software
    // renderer (input that happens during it is tested with a small mesh).
    static const int exact_delay_ms = [] {
        const char* env = std::getenv("TRILAB_EXACT_FRAME_DELAY_MS");
        return env && *env ? std::atoi(env) : 0;
    }();
    if (exact_delay_ms > 0 && proxy_.current && shown != proxy_.renderer.get())
        std::this_thread::sleep_for(std::chrono::milliseconds(exact_delay_ms));
}

void SceneView::note_input() {
    if (!proxy_.current) return;
    proxy_.motion.note_motion(glfwGetTime());
    context_.keep_drawing();
}

void SceneView::draw_note() {
    // While the stand-in or a loading picture is on the screen (over the view's corner). It is
    // drawn before the frame decides: the last frame's stand-in counts only while the view
    // still moves or the exact surface still waits.
    note_shown_ = loading_.drawn || (proxy_.drew_proxy &&
                                     (proxy_.motion.moving(glfwGetTime()) || proxy_.exact_pending));
    if (!note_shown_) return;
    char text[96];
    if (loading_.drawn)
        std::snprintf(text, sizeof(text), "loading... simplified (within %.1f px)",
                      loading_.error_pixels);
    else
        std::snprintf(text, sizeof(text), "simplified while moving (within %.1f px)",
                      proxy_.error_pixels);
    ImDrawList* list = ImGui::GetForegroundDrawList();
    const float pad = 6.0f * context_.ui_scale;
    const Rect& r = context_.view_rect;
    const ImVec2 at(r.x + 2 * pad, r.y + 2 * pad);
    const ImVec2 size = ImGui::CalcTextSize(text);
    list->AddRectFilled(ImVec2(at.x - pad, at.y - pad / 2),
                        ImVec2(at.x + size.x + pad, at.y + size.y + pad / 2),
                        IM_COL32(20, 22, 26, 200), 3.0f * context_.ui_scale);
    list->AddText(at, IM_COL32(235, 220, 150, 255), text);
}

std::size_t SceneView::proxy_min_faces() {
    // For tests only: a smaller threshold gives small test meshes a proxy.
    if (const char* env = std::getenv("TRILAB_PROXY_MIN_FACES"); env && *env) {
        char* end = nullptr;
        const unsigned long long n = std::strtoull(env, &end, 10);
        if (end && *end == '\0' && n >= 16) return std::size_t(n);
    }
    return kProxyMinFaces;
}

bool SceneView::proxy_applies(const Shown& shown) const {
    return (shown.kind == Shown::Kind::Document || shown.kind == Shown::Kind::Preview) &&
           shown.mesh && shown.mesh->n_faces() >= proxy_min_faces();
}

ProxyMeshOptions SceneView::proxy_options(std::size_t n_faces) {
    ProxyMeshOptions options;
    std::size_t target = kProxyTriangles;
    if (const char* env = std::getenv("TRILAB_PROXY_TRIANGLES"); env && *env)
        target = std::size_t(std::strtoull(env, nullptr, 10));  // measurements only
    options.target_triangles = std::clamp<std::size_t>(std::min(target, n_faces / 4), 16, 2000000);
    options.keep_clusters = true;  // for the states that only move the vertices
    return options;
}

void SceneView::request_proxy(const HalfedgeMesh& mesh) {
    const MeshKey key{mesh.topology_revision(), mesh.geometry_revision()};
    if (proxy_.cache.count(key) ||
        std::find(proxy_.failed.begin(), proxy_.failed.end(), key) != proxy_.failed.end())
        return;
    if (proxy_.job.valid() && proxy_.job_key == key) return;
    if (proxy_.job.valid()) proxy_.abandoned.push_back(std::move(proxy_.job));
    proxy_.job_key = key;
    // A state with the connectivity of a proxy already made (a preview, a spectral
    // prediction, a smoothing step) moves that proxy's clusters: O(V) instead of a new grid.
    std::shared_ptr<const ProxyMesh> same_connectivity;
    for (const auto& [k, made] : proxy_.cache)
        if (k.first == key.first && made->cluster_of.size() == mesh.vertices_size())
            same_connectivity = made;
    // The worker's own copy (copy-on-write): the document may change meanwhile.
    if (same_connectivity) {
        proxy_.job = std::async(std::launch::async,
                                [copy = HalfedgeMesh(mesh), base = std::move(same_connectivity)] {
                                    return std::shared_ptr<const ProxyMesh>(
                                        std::make_shared<ProxyMesh>(moved_proxy_mesh(*base, copy)));
                                });
        return;
    }
    const ProxyMeshOptions options = proxy_options(mesh.n_faces());
    proxy_.job = std::async(std::launch::async, [copy = HalfedgeMesh(mesh), options] {
        return std::shared_ptr<const ProxyMesh>(
            std::make_shared<ProxyMesh>(make_proxy_mesh(copy, options)));
    });
}

void SceneView::poll_proxy_job() {
    for (auto it = proxy_.abandoned.begin(); it != proxy_.abandoned.end();) {
        if (!ready(*it)) {
            ++it;
            continue;
        }
        try {
            it->get();
        } catch (const std::exception&) {  // a state no longer shown: nothing to say
        }
        it = proxy_.abandoned.erase(it);
    }
    if (!ready(proxy_.job)) return;
    try {
        std::shared_ptr<const ProxyMesh> made = proxy_.job.get();
        proxy_.cache[proxy_.job_key] = std::move(made);
        proxy_.cache_order.push_back(proxy_.job_key);
        while (proxy_.cache_order.size() > kProxyCache) {
            auto oldest = std::find_if(proxy_.cache_order.begin(), proxy_.cache_order.end(),
                                       [&](const MeshKey& k) { return k != proxy_.current_key; });
            if (oldest == proxy_.cache_order.end()) break;
            proxy_.cache.erase(*oldest);
            proxy_.cache_order.erase(oldest);
        }
    } catch (const std::exception& e) {
        proxy_.failed.push_back(proxy_.job_key);
        session_.log().warning(std::string("no simplified view while moving: ") + e.what());
    }
    context_.keep_drawing();
}

void SceneView::note_exact_colors(const VertexColors& colors, const HalfedgeMesh& mesh) {
    proxy_.colors = colors;
    proxy_.colors_key = {mesh.topology_revision(), mesh.geometry_revision()};
    ++proxy_.colors_stamp;
}

void SceneView::colour_proxy(MeshRenderer& r, const MeshKey& stands_for,
                             const std::vector<Index>& representative) {
    if (proxy_.colors_key == stands_for && !proxy_.colors.colors.empty())
        r.set_vertex_colors(sample_proxy_colors(proxy_.colors, representative));
    else
        r.clear_vertex_colors();
}

void SceneView::dress_proxy(MeshRenderer& r, const HalfedgeMesh& mesh,
                            const std::vector<Index>& representative) {
    proxy_.attributes_revision = mesh.attribute_revision();
    const std::optional<Selection> weights = stored_selection(mesh);
    if (weights && weights->size() == mesh.vertices_size())
        r.set_vertex_selection(sample_proxy_selection(*weights, representative));
    else
        r.clear_vertex_selection();
    const std::vector<TexCoord> uv = sample_proxy_texcoords(mesh, representative);
    if (!uv.empty()) r.set_vertex_texcoords(uv);
}

MeshRenderer* SceneView::choose_clustered_prediction() {
    proxy_.drew_predicted = false;
    if (ready(proxy_.basis_job)) {
        try {
            proxy_.basis = proxy_.basis_job.get();
        } catch (const std::exception& e) {
            proxy_.basis.reset();
            session_.log().warning(std::string("no simplified spectral preview: ") + e.what());
        }
    }
    const HalfedgeMesh& doc = session_.document().mesh();
    if (doc.n_faces() < proxy_min_faces()) return nullptr;
    const MeshKey doc_key{doc.topology_revision(), doc.geometry_revision()};
    const auto found = proxy_.cache.find(doc_key);
    if (found == proxy_.cache.end() || found->second->cluster_of.size() != doc.vertices_size())
        return nullptr;
    const FrequencyDocument& frequency = session_.document().frequency;
    if (frequency.valid && frequency.decomposition && !frequency.decomposition->empty() &&
        (proxy_.basis_of != frequency.decomposition || proxy_.basis_key != doc_key) &&
        !proxy_.basis_job.valid()) {
        // Once per decomposition and document state, before any slider moves: two passes over
        // the eigenvectors on a worker thread.
        proxy_.basis.reset();
        proxy_.basis_of = frequency.decomposition;
        proxy_.basis_key = doc_key;
        proxy_.basis_job = std::async(
            std::launch::async,
            [d = frequency.decomposition, stand_in = found->second, positions = doc.positions()] {
                // Only the decomposed shape's prediction comes from the stored coefficients.
                if (positions != d->base_positions) return std::shared_ptr<const ClusteredBasis>();
                return std::shared_ptr<const ClusteredBasis>(std::make_shared<ClusteredBasis>(
                    cluster_basis(*d, stand_in->cluster_of, stand_in->positions.size())));
            });
    }
    const std::optional<Operation>& request = session_.previews().requested();
    const std::optional<SessionPreviews::Predictable> p =
        request ? session_.previews().predictable(*request) : std::nullopt;
    if (!p) return nullptr;
    if (!proxy_.basis || proxy_.basis_of != p->decomposition || proxy_.basis_key != doc_key ||
        session_.previews().shown(*request) || !session_.previews().prediction_computing())
        return nullptr;
    MeshRenderer& r = *proxy_.renderer;
    const ProxyMesh& stand_in = *found->second;
    if (proxy_.predicted_for != *request) {
        try {
            const ClusteredPrediction predicted =
                predict_clustered(*proxy_.basis, *p->decomposition, p->options);
            for (const Point& x : predicted.positions)
                if (!x.allFinite()) return nullptr;  // diverging: the exact run says why
            r.upload_triangles(predicted.positions, stand_in.triangles);
            colour_proxy(r, doc_key, stand_in.representative);
            dress_proxy(r, doc, stand_in.representative);
            proxy_.error_pixels = proxy_error_pixels(predicted.bound, view_.camera,
                                                     ImGui::GetIO().DisplayFramebufferScale.y);
        } catch (const std::exception& e) {
            session_.log().warning(std::string("no simplified spectral preview: ") + e.what());
            return nullptr;
        }
        if (!proxy_.predicted_for) {
            char line[200];
            std::snprintf(line, sizeof(line),
                          "spectral prediction drawn simplified while it is computed: %zu "
                          "triangles (within %.1f px)",
                          stand_in.triangles.size(), proxy_.error_pixels);
            session_.log().info(line);
        }
        proxy_.predicted_for = *request;
        proxy_.uploaded_key = {0, 0};  // the proxy's renderer holds the prediction now
    }
    proxy_.drew_predicted = true;
    proxy_.motion.note_motion(glfwGetTime());
    context_.keep_drawing();
    return &r;
}

MeshRenderer* SceneView::choose_renderer() {
    const double now = glfwGetTime();
    proxy_.motion.frame(view_.camera.view(), view_.camera.projection(), now);
    poll_proxy_job();
    if (MeshRenderer* picture = choose_loading_picture()) {
        proxy_.drew_proxy = false;
        proxy_.shows_current = false;
        return picture;
    }
    const bool drew_proxy_before = proxy_.drew_proxy;
    if (MeshRenderer* predicted = choose_clustered_prediction()) {
        proxy_.drew_proxy = true;  // the note: simplified while moving
        proxy_.shows_current = false;
        return predicted;
    }
    proxy_.drew_proxy = false;
    proxy_.shows_current = true;
    if (!proxy_.current) {
        return renderer_.get();
    }
    const bool moving = proxy_.motion.moving(now);
    const auto found = proxy_.cache.find(proxy_.current_key);
    const ProxyMesh* proxy = found == proxy_.cache.end() ? nullptr : found->second.get();
    const bool making = proxy_.job.valid() && proxy_.job_key == proxy_.current_key;
    // At rest: upload the state once its proxy was seen (or none is coming).
    if (proxy_.exact_pending && !moving && (proxy_.proxy_drawn || (!proxy && !making)))
        upload_shown();
    if (moving || proxy_.exact_pending) context_.keep_drawing();

    if (proxy && (moving || proxy_.exact_pending)) {
        MeshRenderer& r = *proxy_.renderer;
        try {
            if (proxy_.uploaded_key != proxy_.current_key) {
                r.upload_triangles(proxy->positions, proxy->triangles);
                proxy_.uploaded_key = proxy_.current_key;
                proxy_.uploaded_colors = 0;
                proxy_.attributes_revision = 0;
            }
            if (proxy_.uploaded_colors != proxy_.colors_stamp) {
                proxy_.uploaded_colors = proxy_.colors_stamp;
                colour_proxy(r, proxy_.current_key, proxy->representative);
            }
            const HalfedgeMesh& shown = *session_.shown().mesh;
            if (proxy_.attributes_revision != shown.attribute_revision())
                dress_proxy(r, shown, proxy->representative);
        } catch (const std::exception& e) {
            session_.notify_error(std::string("simplified view: ") + e.what());
            proxy_.failed.push_back(proxy_.current_key);
            proxy_.cache.erase(proxy_.current_key);
            proxy_.uploaded_key = {0, 0};
            return renderer_.get();
        }
        proxy_.drew_proxy = true;
        proxy_.proxy_drawn = true;
        proxy_.error_pixels = proxy_error_pixels(proxy->error_bound, view_.camera,
                                                 ImGui::GetIO().DisplayFramebufferScale.y);
        ++proxy_.proxy_frames;
        if (proxy_.proxy_frames == 1) {
            char line[160];
            std::snprintf(
                line, sizeof(line),
                "simplified while moving: %zu triangles for %zu faces (within %.1f px)%s%s",
                proxy->triangles.size(), session_.shown().mesh->n_faces(), proxy_.error_pixels,
                view_.style.mode == RenderMode::Textured && r.has_texcoords() ? ", textured" : "",
                r.has_vertex_selection() ? ", with the selection" : "");
            session_.log().info(line);
        }
        return &r;
    }
    if (proxy_.exact_pending) {
        // The new state's proxy is still being made: what was on the screen stays.
        proxy_.shows_current = false;
        return drew_proxy_before && proxy_.uploaded_key.first != 0 ? proxy_.renderer.get()
                                                                   : renderer_.get();
    }
    return renderer_.get();
}

void SceneView::apply_colors(VertexColors colors) {
    view_.colors = std::move(colors);
    const bool none =
        view_.settings.coloring == VertexColoring::None || view_.colors.colors.empty();
    note_exact_colors(none ? VertexColors{} : view_.colors, session_.mesh());
    // A large state waiting for its upload (sync()) takes them with it.
    if (proxy_.exact_pending) return;
    if (none)
        renderer_->clear_vertex_colors();
    else
        renderer_->set_vertex_colors(view_.colors);
}

void SceneView::update_coloring() {
    const VertexColoring coloring = view_.settings.coloring;
    const ColoringOptions options = view_.settings.coloring_options;
    if (coloring != VertexColoring::GeodesicDistance) session_.execute(WantPickDistances{false});
    if (coloring == VertexColoring::None) {
        apply_colors(VertexColors{});
        return;
    }
    if (coloring_needs_field(coloring)) {  // from the decomposition: cheap, on this thread
        const bool geodesic = coloring == VertexColoring::GeodesicDistance;
        session_.execute(WantPickDistances{geodesic});
        geodesic_colored_version_ = session_.picking().picks().version;
        VertexColors colors = (field_colors_ ? field_colors_(session_.mesh()) : VertexColors{});
        if (colors.colors.empty() && geodesic)
            session_.notify(
                Notice{Notice::Level::Info,
                       session_.picking().picks().picks.empty()
                           ? "geodesic distance: click the model to pick where it is measured from"
                           : "geodesic distance: measuring from the picks...",
                       {},
                       false});
        else if (!colors.colors.empty() &&
                 (session_.notice().text.rfind("geodesic distance:", 0) == 0 ||
                  session_.notice().text.rfind("distance:", 0) == 0))
            session_.notify(Notice{});  // the distances arrived
        else if (colors.colors.empty() && coloring == VertexColoring::SurfaceDistance)
            session_.notify(Notice{Notice::Level::Info,
                                   "distance: measuring against the surface chosen in the Compare "
                                   "section (Tools > Compare)...",
                                   {},
                                   false});
        else if (colors.colors.empty())
            session_.notify(Notice{Notice::Level::Info,
                                   "the frequency colourings need a decomposition (Algorithms > "
                                   "Frequency decomposition)",
                                   {},
                                   false});
        apply_colors(std::move(colors));
        return;
    }
    auto reference = std::make_shared<const std::vector<Point>>(
        coloring == VertexColoring::SmoothingDistance ? session_.editing().reference_positions()
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
    session_.execute(ComputeColoring{coloring, options, reference});
}

void SceneView::show_colors_of(const HalfedgeMesh& mesh, const std::vector<Point>& reference) {
    if (view_.settings.coloring == VertexColoring::None) return;
    const VertexColors colors =
        coloring_needs_field(view_.settings.coloring)
            ? (field_colors_ ? field_colors_(mesh) : VertexColors{})
            : color_vertices(mesh, view_.settings.coloring, view_.settings.coloring_options,
                             reference.empty() ? nullptr : &reference);
    note_exact_colors(colors, mesh);
    if (colors.colors.empty())
        renderer_->clear_vertex_colors();
    else
        renderer_->set_vertex_colors(colors);
}

void SceneView::update_texture() {
    const Image& image =
        view_.settings.use_checkerboard || texture_.empty() ? checkerboard_ : texture_;
    try {
        renderer_->set_texture(image);
        if (proxy_.renderer) proxy_.renderer->set_texture(image);  // a textured stand-in
    } catch (const std::exception& e) {
        session_.notify_error(std::string("texture: ") + e.what());
    }
}

void SceneView::sync() {
    const Shown& shown = session_.shown();
    if (shown.version == shown_version_) return;
    shown_version_ = shown.version;
    context_.keep_drawing(2);
    proxy_.current = proxy_applies(shown);
    proxy_.exact_pending = false;
    if (proxy_.current) {
        const MeshKey key{shown.mesh->topology_revision(), shown.mesh->geometry_revision()};
        if (key != proxy_.current_key) proxy_.proxy_drawn = false;
        proxy_.current_key = key;
        request_proxy(*shown.mesh);
        // The shown surface changed (a load, an operation, a slider move): the proxy first,
        // the exact surface once the view rests (choose_renderer()). A preview's colours are
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

void SceneView::upload_shown() {
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
                    show_colors_of(*shown.mesh, session_.editing().reference_positions());
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
