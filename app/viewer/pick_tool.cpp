#include "app/viewer/pick_tool.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "app/session/provenance.h"
#include "core/algorithms/inspect.h"

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

std::optional<Pick> PickTool::pick_at(const glm::vec2& view_pos, bool second) {
    Camera& camera = context_.view.camera;
    camera.set_viewport(std::max(context_.view_rect.w, 1.0f), std::max(context_.view_rect.h, 1.0f));
    glm::dvec3 origin, direction;
    camera.ray_through(view_pos, origin, direction);
    Ray ray;
    ray.origin = Point(origin.x, origin.y, origin.z);
    ray.direction = Vector3(direction.x, direction.y, direction.z);
    Session& session = context_.session;
    const std::uint64_t version = session.picking().picks().version;
    session.execute(PickAt{ray, double(camera.near_plane()), second});
    const PickSet& picks = session.picking().picks();
    if (picks.version == version || picks.picks.empty()) return std::nullopt;  // a miss
    inspector_open_ = true;
    return picks.picks.back();
}

void PickTool::update_overlay() {
    const PickSet& set = context_.session.picking().picks();
    const Shown& shown = context_.session.shown();
    const std::string key = std::to_string(set.version) + " " + std::to_string(shown.version);
    if (key == overlay_key_) return;
    overlay_key_ = key;
    if (!face_lines_) {
        face_lines_ = std::make_unique<LineRenderer>();
        edge_lines_ = std::make_unique<LineRenderer>();
        vertex_lines_ = std::make_unique<LineRenderer>();
        path_lines_ = std::make_unique<LineRenderer>();
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
    face_lines_->set_segments(faces);
    edge_lines_->set_segments(edges);
    vertex_lines_->set_segments(vertices);
    path_lines_->set_segments(path);
}

void PickTool::draw_overlay() {
    update_overlay();
    if (!face_lines_ || context_.session.picking().picks().picks.empty()) return;
    const glm::mat4 view = context_.view.camera.view(),
                    projection = context_.view.camera.projection();
    LineStyle style;
    style.color = glm::vec3(1.0f, 0.85f, 0.1f);  // face: yellow
    style.width = 2.0f;
    face_lines_->draw(view, projection, style, context_.ui_scale);
    style.color = glm::vec3(1.0f, 0.35f, 0.1f);  // path: orange-red
    style.width = 3.0f;
    path_lines_->draw(view, projection, style, context_.ui_scale);
    style.color = glm::vec3(0.1f, 0.9f, 1.0f);  // edge: cyan
    style.width = 3.5f;
    edge_lines_->draw(view, projection, style, context_.ui_scale);
    style.color = glm::vec3(1.0f, 0.2f, 0.9f);  // vertex: magenta
    style.width = 3.0f;
    vertex_lines_->draw(view, projection, style, context_.ui_scale);
}

void PickTool::update() {
    // The geodesic colouring follows the picks' distances as they arrive.
    if (context_.view.settings.coloring == VertexColoring::GeodesicDistance &&
        context_.session.picking().picks().version != geodesic_colored_())
        context_.commands.push_back(UpdateColoring{});
    const PickSet& set = context_.session.picking().picks();
    const FrequencyDocument& frequency = context_.session.document().frequency;
    const std::string key =
        std::to_string(set.version) + " " + std::to_string(context_.session.history().current()) +
        " " + std::to_string(context_.session.shown().version) + " " +
        std::to_string(int(context_.view.settings.coloring)) + " " +
        std::to_string(context_.view.colors.colors.size()) + " " + std::to_string(frequency.valid) +
        " " + std::to_string(band_lo()) + " " + std::to_string(band_hi());
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
            if (v < context_.view.colors.values.size() &&
                !std::isnan(context_.view.colors.values[v]))
                fields.push_back({"coloring",
                                  "Colouring (" + context_.view.colors.label + ")",
                                  number(context_.view.colors.values[v]),
                                  {context_.view.colors.values[v]}});
            const SpectralDecomposition* d = frequency.decomposition.get();
            if (frequency.valid && d && v < d->map.row_of.size() &&
                d->map.row_of[v] != kInvalidIndex && mesh.vertices_size() == d->map.row_of.size()) {
                const Eigen::Index row = Eigen::Index(d->map.row_of[v]);
                const std::size_t lo = std::min(std::size_t(std::max(0, band_lo())), d->size() - 1);
                const std::size_t hi = std::min(std::size_t(std::max(0, band_hi())), d->size() - 1);
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
            const Shown& shown = context_.session.shown();
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
    if (!p.on_level && mesh.topology_revision() == context_.session.mesh().topology_revision()) {
        const std::vector<double> moves = vertex_moves(context_.session.history(), p.vertex);
        bool any = false;
        for (double d : moves) {
            view.moved_by_entry.push_back(std::isnan(d) ? 0.0f : float(d));
            any = any || (!std::isnan(d) && d > 0);
        }
        if (!any) view.moved_by_entry.clear();
        view.current_entry = context_.session.history().current();
    }
}

bool PickTool::mouse(const ViewMouse& mouse) {
    if (mouse.clicked && !mouse.shift) pick_at(mouse.pos, mouse.ctrl);
    if (mouse.double_clicked && pick_at(mouse.pos, false))
        context_.commands.push_back(CentreOnPick{});
    return false;  // the view still turns on a drag
}

void PickTool::section(const SidebarContext& context, CommandQueue& commands) {
    // The rows describe() handed the sidebar (the tests hand their own).
    inspector_section(inspector_open_, context.inspector ? *context.inspector : inspector_,
                      commands);
}

PanelEntries PickTool::panels() {
    PanelEntry entry;
    entry.name = "inspector";
    entry.title = "Inspector";
    entry.open = &inspector_open_;
    entry.in_all = false;
    return {entry};
}

}  // namespace trilab::viewer
