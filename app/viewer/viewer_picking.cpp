// Picking in the view: the click that picks, the highlight of the picked elements and the
// geodesic path, the Inspector's rows, and the scripted picks (--pick X,Y).
#include "app/viewer/viewer.h"

#include <glad/gl.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "app/ops/operation_entries.h"
#include "app/session/provenance.h"
#include "core/algorithms/inspect.h"
#include "core/errors.h"
#include "core/geometry.h"
#include "core/number_text.h"

namespace trilab::viewer {
namespace {

glm::vec3 to_glm(const Point& p) {
    return glm::vec3(float(p.x()), float(p.y()), float(p.z()));
}

std::string vec_text(const Point& p) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "%.6g %.6g %.6g", p.x(), p.y(), p.z());
    return buf;
}

std::string number(double x) {
    if (std::isnan(x)) return "-";
    char buf[48];
    std::snprintf(buf, sizeof buf, "%.6g", x);
    return buf;
}

}  // namespace

std::optional<Pick> Viewer::pick_at(const glm::vec2& view_pos, bool second) {
    Camera& camera = view_.camera;
    camera.set_viewport(std::max(view_rect_.w, 1.0f), std::max(view_rect_.h, 1.0f));
    glm::dvec3 origin, direction;
    camera.ray_through(view_pos, origin, direction);
    Ray ray;
    ray.origin = Point(origin.x, origin.y, origin.z);
    ray.direction = Vector3(direction.x, direction.y, direction.z);
    const std::optional<Pick> hit = session_.pick(ray, double(camera.near_plane()), second);
    if (hit) panels_.inspector_open = true;
    return hit;
}

void Viewer::update_pick_overlay() {
    const PickSet& set = session_.picks();
    const Shown& shown = session_.shown();
    const std::string key = std::to_string(set.version) + " " + std::to_string(shown.version);
    if (key == pick_overlay_key_) return;
    pick_overlay_key_ = key;
    if (!pick_face_lines_) {
        pick_face_lines_ = std::make_unique<LineRenderer>();
        pick_edge_lines_ = std::make_unique<LineRenderer>();
        pick_vertex_lines_ = std::make_unique<LineRenderer>();
        pick_path_lines_ = std::make_unique<LineRenderer>();
    }
    std::vector<glm::vec3> faces, edges, vertices, path;
    // Positions: those shown when the shown surface has the picks' connectivity (a preview of
    // a geometry-only step, a morph frame, a band), else the picks' own state.
    const HalfedgeMesh& mesh = set.mesh;
    const std::vector<Point>* positions = &mesh.positions();
    if (shown.kind != Shown::Kind::Level && shown.mesh &&
        shown.mesh->topology_revision() == mesh.topology_revision() &&
        shown.mesh->vertices_size() == mesh.vertices_size())
        positions = shown.positions.size() == mesh.vertices_size() ? &shown.positions
                                                                   : &shown.mesh->positions();
    auto at = [&](Vertex v) { return to_glm((*positions)[v.idx()]); };
    for (const Pick& p : set.picks) {
        if (!mesh.is_valid(p.corners[0]) || !mesh.is_valid(p.corners[1]) ||
            !mesh.is_valid(p.corners[2]))
            continue;
        for (int k = 0; k < 3; ++k) {
            faces.push_back(at(p.corners[k]));
            faces.push_back(at(p.corners[(k + 1) % 3]));
        }
        if (p.edge.is_valid() && mesh.is_valid(p.edge)) {
            edges.push_back(at(mesh.vertex(p.edge, 0)));
            edges.push_back(at(mesh.vertex(p.edge, 1)));
        }
        // The vertex: the first third of each of its edges, a star that shows which corner.
        if (mesh.is_valid(p.vertex) && !mesh.is_isolated(p.vertex)) {
            const glm::vec3 c = at(p.vertex);
            for (Vertex n : mesh.vertices_around(p.vertex)) {
                vertices.push_back(c);
                vertices.push_back(c + (at(n) - c) / 3.0f);
            }
        }
    }
    const Measurement& m = set.measurement;
    for (std::size_t i = 1; i < m.path.size(); ++i) {
        path.push_back(to_glm(m.path[i - 1]));
        path.push_back(to_glm(m.path[i]));
    }
    pick_face_lines_->set_segments(faces);
    pick_edge_lines_->set_segments(edges);
    pick_vertex_lines_->set_segments(vertices);
    pick_path_lines_->set_segments(path);
}

void Viewer::draw_pick_overlay() const {
    if (!pick_face_lines_ || session_.picks().picks.empty()) return;
    const glm::mat4 view = view_.camera.view(), projection = view_.camera.projection();
    LineStyle style;
    style.color = glm::vec3(1.0f, 0.85f, 0.1f);  // face: yellow
    style.width = 2.0f;
    pick_face_lines_->draw(view, projection, style, ui_scale_);
    style.color = glm::vec3(1.0f, 0.35f, 0.1f);  // path: orange-red
    style.width = 3.0f;
    pick_path_lines_->draw(view, projection, style, ui_scale_);
    style.color = glm::vec3(0.1f, 0.9f, 1.0f);  // edge: cyan
    style.width = 3.5f;
    pick_edge_lines_->draw(view, projection, style, ui_scale_);
    style.color = glm::vec3(1.0f, 0.2f, 0.9f);  // vertex: magenta
    style.width = 3.0f;
    pick_vertex_lines_->draw(view, projection, style, ui_scale_);
}

void Viewer::update_inspector() {
    // The geodesic colouring follows the picks' distances as they arrive.
    if (view_.settings.coloring == VertexColoring::GeodesicDistance &&
        session_.picks().version != geodesic_colored_version_)
        commands_.push_back(UpdateColoring{});
    try {
        session_.set_inspection_options(decimation_options(panels_.decimation.op));
    } catch (const std::exception&) {
        // The panel shows its own error; the inspector keeps the last valid options.
    }
    const PickSet& set = session_.picks();
    const FrequencyDocument& frequency = session_.document().frequency;
    const std::string key =
        std::to_string(set.version) + " " + std::to_string(session_.history().current()) + " " +
        std::to_string(session_.shown().version) + " " +
        std::to_string(int(view_.settings.coloring)) + " " +
        std::to_string(view_.colors.colors.size()) + " " + std::to_string(frequency.valid) + " " +
        std::to_string(panels_.frequency.lo) + " " + std::to_string(panels_.frequency.hi);
    if (key == inspector_key_) return;
    inspector_key_ = key;
    InspectorView& view = inspector_;
    view = InspectorView{};
    view.has_picks = !set.picks.empty();
    if (!view.has_picks) return;
    const HalfedgeMesh& mesh = set.mesh;
    const Pick& p = set.picks.front();
    if (p.on_level) view.note = "picked on the level of detail: the document's elements are shown";
    const auto add_fields = [&](std::string title, const std::vector<InspectionField>& fields) {
        InspectorView::Group g{std::move(title), {}};
        for (const InspectionField& f : fields) g.rows.push_back({f.label, f.text});
        view.groups.push_back(std::move(g));
    };
    const PickInspection* inspection = set.inspection.get();
    if (!inspection) {
        view.note += (view.note.empty() ? "" : "; ") + std::string("inspecting...");
    } else {
        if (inspection->vertex) {
            std::vector<InspectionField> fields = inspection_fields(*inspection->vertex);
            const Index v = p.vertex.idx();
            // What the view shows at this vertex: the colouring's value, the eigenvectors of
            // the band, the band's displacement.
            if (v < view_.colors.values.size() && !std::isnan(view_.colors.values[v]))
                fields.push_back({"coloring",
                                  "Colouring (" + view_.colors.label + ")",
                                  number(view_.colors.values[v]),
                                  {view_.colors.values[v]}});
            const SpectralDecomposition* d = frequency.decomposition.get();
            if (frequency.valid && d && v < d->map.row_of.size() &&
                d->map.row_of[v] != kInvalidIndex && mesh.vertices_size() == d->map.row_of.size()) {
                const Eigen::Index row = Eigen::Index(d->map.row_of[v]);
                const std::size_t lo =
                    std::min(std::size_t(std::max(0, panels_.frequency.lo)), d->size() - 1);
                const std::size_t hi =
                    std::min(std::size_t(std::max(0, panels_.frequency.hi)), d->size() - 1);
                constexpr std::size_t kMaxShown = 8;
                for (std::size_t k = lo; k <= hi && k < lo + kMaxShown; ++k) {
                    const double e = d->eigenvectors(row, Eigen::Index(k));
                    fields.push_back(
                        {"eigenvector", "Frequency " + std::to_string(k), number(e), {e}});
                }
                if (hi >= lo + kMaxShown)
                    fields.push_back({"eigenvector",
                                      "Frequencies",
                                      "the first 8 of the band " + std::to_string(lo) + ".." +
                                          std::to_string(hi) + " are listed",
                                      {}});
            }
            const Shown& shown = session_.shown();
            if (shown.kind == Shown::Kind::Band && v < shown.positions.size() &&
                v < mesh.vertices_size()) {
                const Vector3 moved = shown.positions[v] - mesh.position(p.vertex);
                fields.push_back({"band_displacement",
                                  "Band displacement",
                                  vec_text(moved) + " (|d| " + number(moved.norm()) + ")",
                                  {moved.x(), moved.y(), moved.z()}});
            }
            add_fields("Vertex " + std::to_string(v), fields);
        }
        if (inspection->edge)
            add_fields("Edge " + std::to_string(p.edge.idx()),
                       inspection_fields(*inspection->edge));
        if (inspection->face)
            add_fields("Face " + std::to_string(p.face.idx()),
                       inspection_fields(*inspection->face));
        if (!inspection->failure.empty()) view.note = inspection->failure;
    }
    if (set.picks.size() == 2) {
        const Measurement& m = set.measurement;
        InspectorView::Group g{"Measure: vertex " + std::to_string(p.vertex.idx()) + " to " +
                                   std::to_string(set.picks[1].vertex.idx()),
                               {}};
        g.rows.push_back({"Straight distance", number(m.straight)});
        g.rows.push_back(
            {"Geodesic distance (heat method)", m.computing ? "computing..." : number(m.geodesic)});
        if (!m.path.empty()) {
            g.rows.push_back({"Path length on the surface", number(m.path_length)});
            g.rows.push_back({"Path points", std::to_string(m.path.size())});
        }
        if (!m.failure.empty()) g.rows.push_back({"Note", m.failure});
        view.groups.push_back(std::move(g));
    }
    // Provenance: how far each entry moved the picked vertex (when it is the document's).
    if (!p.on_level && mesh.topology_revision() == session_.mesh().topology_revision()) {
        const std::vector<double> moves = vertex_moves(session_.history(), p.vertex);
        bool any = false;
        for (double d : moves) {
            view.moved_by_entry.push_back(std::isnan(d) ? 0.0f : float(d));
            any = any || (!std::isnan(d) && d > 0);
        }
        if (!any) view.moved_by_entry.clear();
        view.current_entry = session_.history().current();
    }
}

void Viewer::scripted_picks() {
    if (next_scripted_pick_ >= options_.picks.size() || !ready_for_script() || session_.busy())
        return;
    const std::string& spec = options_.picks[next_scripted_pick_];
    const bool second = next_scripted_pick_ > 0;
    ++next_scripted_pick_;
    float x = 0, y = 0;
    char extra = 0;
    if (std::sscanf(spec.c_str(), "%f,%f%c", &x, &y, &extra) != 2 || !std::isfinite(x) ||
        !std::isfinite(y)) {
        session_.notify_error("--pick: expected X,Y in window pixels, got \"" + spec + "\"");
        exit_status_ = 1;
        return;
    }
    const glm::vec2 view_pos(x - view_rect_.x, y - view_rect_.y);
    const std::optional<Pick> hit = pick_at(view_pos, second);
    if (hit)
        std::printf("pick: %s\n", pick_line(*hit).c_str());
    else
        std::printf("pick: nothing at %g,%g (the background)\n", double(x), double(y));
    std::fflush(stdout);
}

bool Viewer::scripted_picks_pending() const {
    // The last frame of a scripted run shows the Inspector filled in.
    return next_scripted_pick_ < options_.picks.size() ||
           (!options_.picks.empty() && session_.picks_pending());
}

}  // namespace trilab::viewer
