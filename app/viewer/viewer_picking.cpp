// Picking in the view: the click that picks, the highlight of the picked elements and the
// geodesic path, the Inspector's rows, and the scripted picks (--pick X,Y).
#include "app/viewer/viewer.h"

#include <glad/gl.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

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
    const PickSet& set = session_.picks();
    const std::string key = std::to_string(set.version) + " " +
                            std::to_string(session_.history().current()) + " " +
                            std::to_string(int(view_.settings.coloring)) + " " +
                            std::to_string(view_.colors.colors.size());
    if (key == inspector_key_) return;
    inspector_key_ = key;
    InspectorView& view = inspector_;
    view = InspectorView{};
    view.has_picks = !set.picks.empty();
    if (!view.has_picks) return;
    const HalfedgeMesh& mesh = set.mesh;
    const Pick& p = set.picks.front();
    if (p.on_level) view.note = "picked on the level of detail: the document's elements are shown";
    if (mesh.is_valid(p.vertex)) {
        InspectorView::Group g{"Vertex " + std::to_string(p.vertex.idx()), {}};
        g.rows.push_back({"position", vec_text(mesh.position(p.vertex))});
        if (!mesh.is_isolated(p.vertex)) {
            g.rows.push_back({"normal", vec_text(vertex_normal(mesh, p.vertex))});
            std::size_t valence = 0;
            for (Vertex n : mesh.vertices_around(p.vertex)) {
                (void)n;
                ++valence;
            }
            g.rows.push_back({"valence", std::to_string(valence)});
            g.rows.push_back({"boundary", mesh.is_boundary(p.vertex) ? "yes" : "no"});
        }
        view.groups.push_back(std::move(g));
    }
    if (p.edge.is_valid() && mesh.is_valid(p.edge)) {
        InspectorView::Group g{"Edge " + std::to_string(p.edge.idx()), {}};
        g.rows.push_back({"ends", std::to_string(mesh.vertex(p.edge, 0).idx()) + " - " +
                                      std::to_string(mesh.vertex(p.edge, 1).idx())});
        g.rows.push_back({"length", number(edge_length(mesh, p.edge))});
        view.groups.push_back(std::move(g));
    }
    if (p.face.is_valid() && mesh.is_valid(p.face)) {
        InspectorView::Group g{"Face " + std::to_string(p.face.idx()), {}};
        g.rows.push_back({"area", number(face_area(mesh, p.face))});
        g.rows.push_back({"normal", vec_text(face_normal(mesh, p.face))});
        g.rows.push_back({"hit", vec_text(p.position) + (p.back_face ? " (back face)" : "")});
        view.groups.push_back(std::move(g));
    }
    if (set.picks.size() == 2) {
        const Measurement& m = set.measurement;
        InspectorView::Group g{"Measure: vertex " + std::to_string(p.vertex.idx()) + " to " +
                                   std::to_string(set.picks[1].vertex.idx()),
                               {}};
        g.rows.push_back({"straight", number(m.straight)});
        g.rows.push_back({"geodesic", m.computing ? "computing..." : number(m.geodesic)});
        if (!m.path.empty()) {
            g.rows.push_back({"path length", number(m.path_length)});
            g.rows.push_back({"path points", std::to_string(m.path.size())});
        }
        if (!m.failure.empty()) g.rows.push_back({"note", m.failure});
        view.groups.push_back(std::move(g));
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
    return next_scripted_pick_ < options_.picks.size();
}

}  // namespace trilab::viewer
