// Large meshes: simplified while moving, exact at rest.
//
// After a state is shown whose mesh has at least proxy_min_faces() faces (a Document or a
// Preview), its proxy (core/algorithms/proxy_mesh.h: vertex clustering to about
// kProxyTriangles triangles) is made on a worker thread from a copy of the mesh (the document
// is never touched there); a job for a state no longer shown is left to end and ignored.
// While the view moves (its camera matrices change between frames: rotate, pan, zoom, the
// scripted orbit) or the shown surface changes (a slider drag, a load), the second renderer
// draws the proxy, with the current colouring sampled through ProxyMesh::representative, in
// whatever mode; kRestSeconds after the last motion the exact surface is drawn again. A new
// large state is uploaded to the exact renderer only once its proxy has been on the screen
// and the view rests, so a slider drag or the first picture of a large file costs the proxy's
// frame, not the exact upload. While the proxy is on the screen a note says so, with its
// error bound in framebuffer pixels at the target's depth.
//
// --orbit N turns the camera once around the up axis through the target in N frames (each
// frame's rotation computed from the start, the last one the start itself, so the rested view
// is the unturned view pixel for pixel), then rests, and prints the frame times and the time
// from the last motion to the first exact frame. --print-timing prints when the model and its
// exact surface first reached the screen, from process start.
#include <glad/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "app/viewer/viewer.h"
#include "app/viewer/viewer_tuning.h"
#include "core/algorithms/selection.h"
#include "core/up_axis.h"
#include "render/proxy_view.h"

namespace trilab::viewer {
namespace {

/// Meshes of at least this many faces are drawn through a proxy while moving: llvmpipe sets
/// up about 130 ns a triangle here, so 200k faces are about 26 ms of a frame, the most that
/// leaves room for the UI in the 40 ms budget; smaller meshes are always drawn exactly.
constexpr std::size_t kProxyMinFaces = 200000;
/// The proxy's triangles (at most a quarter of the mesh's): about 8 ms of llvmpipe's setup
/// a frame; the error bound is about 9 px for the bunny filling a 1280x800 view.
constexpr std::size_t kProxyTriangles = 60000;
/// Proxies kept (the levels a slider visits).
constexpr std::size_t kProxyCache = 6;

/// When the process started (static initialisation, before main).
const auto kProcessStart = std::chrono::steady_clock::now();

double ms_since_start() {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() -
                                                     kProcessStart)
        .count();
}

template <typename T>
bool ready(const std::future<T>& f) {
    return f.valid() && f.wait_for(std::chrono::seconds(0)) == std::future_status::ready;
}

}  // namespace

std::size_t Viewer::proxy_min_faces() {
    // For tests only: a smaller threshold gives small test meshes a proxy.
    if (const char* env = std::getenv("TRILAB_PROXY_MIN_FACES"); env && *env) {
        char* end = nullptr;
        const unsigned long long n = std::strtoull(env, &end, 10);
        if (end && *end == '\0' && n >= 16) return std::size_t(n);
    }
    return kProxyMinFaces;
}

bool Viewer::proxy_applies(const Shown& shown) const {
    return (shown.kind == Shown::Kind::Document || shown.kind == Shown::Kind::Preview) &&
           shown.mesh && shown.mesh->n_faces() >= proxy_min_faces();
}

ProxyMeshOptions Viewer::proxy_options(std::size_t n_faces) {
    ProxyMeshOptions options;
    std::size_t target = kProxyTriangles;
    if (const char* env = std::getenv("TRILAB_PROXY_TRIANGLES"); env && *env)
        target = std::size_t(std::strtoull(env, nullptr, 10));  // measurements only
    options.target_triangles = std::clamp<std::size_t>(std::min(target, n_faces / 4), 16, 2000000);
    options.keep_clusters = true;  // for the states that only move the vertices
    return options;
}

void Viewer::request_proxy(const HalfedgeMesh& mesh) {
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

void Viewer::poll_proxy_job() {
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
    active_frames_ = std::max(active_frames_, 1);
}

void Viewer::note_exact_colors(const VertexColors& colors, const HalfedgeMesh& mesh) {
    proxy_.colors = colors;
    proxy_.colors_key = {mesh.topology_revision(), mesh.geometry_revision()};
    ++proxy_.colors_stamp;
}

MeshRenderer* Viewer::choose_loading_picture() {
    loading_.drawn = false;
    std::shared_ptr<const LoadingPicture> picture = session_.loading_picture();
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
        fit_center_ = glm::vec3(float(picture->center.x()), float(picture->center.y()),
                                float(picture->center.z()));
        fit_radius_ = picture->bounds.empty ? 1.0f : float(picture->radius);
        view_.camera.reset_rotation(view_.settings.up);
        view_.camera.set_viewport(std::max(view_rect_.w, 1.0f), std::max(view_rect_.h, 1.0f));
        view_.camera.fit_sphere(fit_center_, fit_radius_);
        char line[160];
        std::snprintf(line, sizeof(line),
                      "simplified picture while loading: %zu triangles for %zu faces",
                      picture->proxy->triangles.size(), picture->faces);
        session_.log().info(line);
    }
    loading_.drawn = true;
    loading_.error_pixels = proxy_error_pixels(picture->proxy->error_bound, view_.camera,
                                               ImGui::GetIO().DisplayFramebufferScale.y);
    active_frames_ = std::max(active_frames_, 1);
    return &r;
}

void Viewer::colour_proxy(MeshRenderer& r, const MeshKey& stands_for,
                          const std::vector<Index>& representative) {
    if (proxy_.colors_key == stands_for && !proxy_.colors.colors.empty())
        r.set_vertex_colors(sample_proxy_colors(proxy_.colors, representative));
    else
        r.clear_vertex_colors();
}

void Viewer::dress_proxy(MeshRenderer& r, const HalfedgeMesh& mesh,
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

MeshRenderer* Viewer::choose_clustered_prediction() {
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
    const std::optional<Operation>& request = session_.preview_requested();
    const std::optional<Session::Predictable> p =
        request ? session_.predictable(*request) : std::nullopt;
    if (!p) return nullptr;
    if (!proxy_.basis || proxy_.basis_of != p->decomposition || proxy_.basis_key != doc_key ||
        session_.preview_shown(*request) || !session_.prediction_computing())
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
    active_frames_ = std::max(active_frames_, 1);
    return &r;
}

MeshRenderer* Viewer::choose_renderer() {
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
        ++proxy_.exact_frames;
        return renderer_.get();
    }
    const bool moving = proxy_.motion.moving(now);
    const auto found = proxy_.cache.find(proxy_.current_key);
    const ProxyMesh* proxy = found == proxy_.cache.end() ? nullptr : found->second.get();
    const bool making = proxy_.job.valid() && proxy_.job_key == proxy_.current_key;
    // At rest: upload the state once its proxy was seen (or none is coming).
    if (proxy_.exact_pending && !moving && (proxy_.proxy_drawn || (!proxy && !making)))
        upload_shown();
    if (moving || proxy_.exact_pending) active_frames_ = std::max(active_frames_, 1);

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
    ++proxy_.exact_frames;
    return renderer_.get();
}

void Viewer::update_motion_ui() {
    const int n = options_.orbit_frames;
    if (n > 0 && !orbit_.done) {
        if (orbit_.frame < 0) {
            const bool proxy_ready = !proxy_.current || proxy_.cache.count(proxy_.current_key) ||
                                     std::find(proxy_.failed.begin(), proxy_.failed.end(),
                                               proxy_.current_key) != proxy_.failed.end();
            if (ready_for_script() && session_.shown().version == shown_version_ &&
                !session_.preview_pending() && !session_.morph().playing && !proxy_.exact_pending &&
                !proxy_.drew_proxy && proxy_ready && !proxy_.motion.moving(glfwGetTime())) {
                orbit_.frame = 0;
                orbit_.start = view_.camera;
                orbit_.ms.clear();
            }
        }
        if (orbit_.frame >= 0 && orbit_.frame < n) {
            ++orbit_.frame;
            if (orbit_.frame == n) {
                view_.camera = orbit_.start;  // exactly where it started
            } else {
                const Vector3 up = up_vector(view_.settings.up);
                const float angle = float(2.0 * M_PI * double(orbit_.frame) / double(n));
                const glm::quat turn =
                    glm::angleAxis(angle, glm::vec3(float(up.x()), float(up.y()), float(up.z())));
                const Camera& s = orbit_.start;
                view_.camera.set_state(s.rotation() * turn, s.target(), s.distance(), s.radius(),
                                       s.fov_y());
            }
        }
        active_frames_ = std::max(active_frames_, 1);
    }
    // The note, while the last frame showed the proxy or a loading picture (it is drawn over
    // the view's corner).
    if (proxy_.drew_proxy || loading_.drawn) {
        char text[96];
        if (loading_.drawn)
            std::snprintf(text, sizeof(text), "loading... simplified (within %.1f px)",
                          loading_.error_pixels);
        else
            std::snprintf(text, sizeof(text), "simplified while moving (within %.1f px)",
                          proxy_.error_pixels);
        ImDrawList* list = ImGui::GetForegroundDrawList();
        const float pad = 6.0f * ui_scale_;
        const ImVec2 at(view_rect_.x + 2 * pad, view_rect_.y + 2 * pad);
        const ImVec2 size = ImGui::CalcTextSize(text);
        list->AddRectFilled(ImVec2(at.x - pad, at.y - pad / 2),
                            ImVec2(at.x + size.x + pad, at.y + size.y + pad / 2),
                            IM_COL32(20, 22, 26, 200), 3.0f * ui_scale_);
        list->AddText(at, IM_COL32(235, 220, 150, 255), text);
    }
}

void Viewer::note_frame_end(double frame_ms) {
    const bool model_shown =
        initial_load_ended_ &&
        (options_.mesh_path.empty() || session_.document().path == options_.mesh_path);
    // The loading picture of the file asked for shows the model (simplified).
    const bool picture_shown = loading_.drawn && !options_.mesh_path.empty() && loading_.picture &&
                               loading_.picture->path == options_.mesh_path;
    if (picture_shown && first_frame_ms_ < 0) first_frame_ms_ = ms_since_start();
    if (model_shown && proxy_.shows_current) {
        if (first_frame_ms_ < 0) first_frame_ms_ = ms_since_start();
        if (exact_frame_ms_ < 0 && !proxy_.drew_proxy && !proxy_.exact_pending)
            exact_frame_ms_ = ms_since_start();
    }
    const int n = options_.orbit_frames;
    if (n <= 0 || orbit_.done || orbit_.frame <= 0) return;
    if (orbit_.frame <= n && int(orbit_.ms.size()) < orbit_.frame) {  // a turning frame
        orbit_.ms.push_back(frame_ms);
        if (proxy_.drew_proxy) ++orbit_.proxy_frames;
        if (orbit_.frame == n) orbit_.motion_end = glfwGetTime();
        return;
    }
    if (orbit_.frame < n || proxy_.drew_proxy || !proxy_.shows_current || proxy_.exact_pending)
        return;
    // The first exact frame after the turn is on the screen.
    const double rest_ms = 1000.0 * (glfwGetTime() - orbit_.motion_end);
    std::vector<double> sorted = orbit_.ms;
    std::sort(sorted.begin(), sorted.end());
    std::printf("orbit: frames=%d median_ms=%.1f max_ms=%.1f rest_ms=%.1f\n", n,
                sorted[sorted.size() / 2], sorted.back(), rest_ms);
    std::printf("orbit: proxy_frames=%zu exact_frames=%zu error_px=%.2f\n", orbit_.proxy_frames,
                orbit_.ms.size() - orbit_.proxy_frames,
                orbit_.proxy_frames ? proxy_.error_pixels : 0.0);
    std::fflush(stdout);
    orbit_.done = true;
}

bool Viewer::motion_settled() const {
    if (options_.orbit_frames > 0 && !orbit_.done) return false;
    if (proxy_.exact_pending || proxy_.drew_proxy) return false;
    return !(proxy_.current && proxy_.motion.moving(glfwGetTime()));
}

void Viewer::print_timing() const {
    std::printf("timing: first_frame_ms=%.0f exact_frame_ms=%.0f\n", first_frame_ms_,
                exact_frame_ms_);
    std::fflush(stdout);
}

}  // namespace trilab::viewer
