#include "app/viewer/features_tool.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>

#include "app/viewer/panel_helpers.h"
#include "app/viewer/widgets.h"
#include "core/algorithms/ray_pick.h"
#include "core/features.h"

namespace trilab::viewer {

using namespace ui;

namespace {

/// The ends of `mesh`'s edges of positive sharpness, in edge order.
std::vector<std::array<Vertex, 2>> sharp_edges(const HalfedgeMesh& mesh) {
    std::vector<std::array<Vertex, 2>> out;
    const auto sharpness = mesh.get_edge_property<float>(kSharpnessProperty);
    if (!sharpness) return out;
    for (Edge e : mesh.edges()) {
        if (!(sharpness[e] > 0)) continue;
        const Halfedge h = HalfedgeMesh::halfedge(e, 0);
        out.push_back({mesh.from_vertex(h), mesh.to_vertex(h)});
    }
    return out;
}

/// The segments of `edges` at `positions`, or at the mesh's own positions when its size
/// differs.
std::vector<std::array<Point, 2>> segments_of(const std::vector<std::array<Vertex, 2>>& edges,
                                              const HalfedgeMesh& mesh,
                                              const std::vector<Point>& positions) {
    const bool own = positions.size() != mesh.vertices_size();
    std::vector<std::array<Point, 2>> out;
    out.reserve(edges.size());
    for (const auto& [a, b] : edges)
        out.push_back(own ? std::array<Point, 2>{mesh.position(a), mesh.position(b)}
                          : std::array<Point, 2>{positions[a.idx()], positions[b.idx()]});
    return out;
}

}  // namespace

std::vector<std::array<Point, 2>> feature_segments(const HalfedgeMesh& mesh,
                                                   const std::vector<Point>& positions) {
    return segments_of(sharp_edges(mesh), mesh, positions);
}

FeaturesTool::FeaturesTool(ViewerContext& context) : OperationTool(context, {}) {
    set_panels({&panel_});
}

const FeatureDetectionReport* FeaturesTool::report() const {
    const Session& session = context_.session;
    const OperationResult* result = session.previews().result();
    if (!result || !panel_.previewing) return nullptr;
    return report_of<FeatureDetectionReport>(*result);
}

void FeaturesTool::update() {
    OperationTool::update();
    // The feature lines of what is shown (a preview of the detection, the document, a morph
    // frame); none on a level of detail, whose edges are not the document's.
    // A morph frame changes the version every frame: the sharp edges are found once per
    // connectivity and properties, and only their ends' positions are gathered per frame.
    const Shown& shown = context_.session.shown();
    if (shown.version == lines_version_) return;
    lines_version_ = shown.version;
    lines_.clear();
    upload_ = true;
    if (!shown.mesh || shown.kind == Shown::Kind::Level) return;
    const HalfedgeMesh& mesh = *shown.mesh;
    const std::array<std::uint64_t, 2> key{mesh.topology_revision(), mesh.attribute_revision()};
    if (key != edges_key_) {
        edges_key_ = key;
        edges_ = sharp_edges(mesh);
    }
    lines_ = segments_of(edges_, mesh, shown.positions);
}

namespace {

/// "sharpen" with the panel's sharpness (or --clear), for `edge` (empty: the region's).
Operation sharpen_text(bool clear, bool infinite, float sharpness, const std::string& edge) {
    char text[128];
    if (clear)
        std::snprintf(text, sizeof(text), "sharpen --clear");
    else if (infinite)
        std::snprintf(text, sizeof(text), "sharpen");
    else
        std::snprintf(text, sizeof(text), "sharpen --sharpness %g", double(sharpness));
    return parse_operation(std::string(text) + (edge.empty() ? "" : " --edge " + edge));
}

}  // namespace

Operation FeaturesTool::sharpen_selection(bool clear) const {
    return sharpen_text(clear, infinite_, sharpness_, "");
}

Operation FeaturesTool::toggle_edge(Edge e) const {
    const bool sharp = trilab::sharpness(context_.session.mesh(), e) > 0.0f;
    return sharpen_text(sharp, infinite_, sharpness_, std::to_string(e.idx()));
}

bool FeaturesTool::mouse(const ViewMouse& mouse) {
    // With tagging on (and the section open), a click tags instead of picking.
    if (!tag_by_click_ || !panel_.open || !mouse.clicked || !mouse.in_view) return false;
    const Session& session = context_.session;
    if (session.shown().kind != Shown::Kind::Document || session.jobs().busy()) return true;
    Camera& camera = context_.view.camera;
    glm::dvec3 origin, direction;
    camera.ray_through(mouse.pos, origin, direction);
    Ray ray;
    ray.origin = Point(origin.x, origin.y, origin.z);
    ray.direction = Vector3(direction.x, direction.y, direction.z);
    const HalfedgeMesh& mesh = session.mesh();
    const std::optional<RayHit> hit =
        pick_face(mesh, mesh.positions(), ray, double(camera.near_plane()));
    if (!hit) return true;  // a miss tags nothing (and picks nothing)
    const Edge e = HalfedgeMesh::edge(face_side(mesh, Face(hit->triangle), hit->nearest_edge));
    context_.commands.push_back(RunOperation{toggle_edge(e)});
    return true;
}

void FeaturesTool::draw_overlay() {
    if (!show_lines_ || lines_.empty()) return;
    if (!renderer_) renderer_ = std::make_unique<LineRenderer>();  // the GL context is current
    if (upload_) {
        std::vector<glm::vec3> points;
        points.reserve(2 * lines_.size());
        for (const std::array<Point, 2>& s : lines_)
            for (const Point& p : s) points.emplace_back(float(p.x()), float(p.y()), float(p.z()));
        renderer_->set_segments(points);
        upload_ = false;
    }
    LineStyle style;
    style.color = glm::vec3(0.95f, 0.2f, 0.6f);  // magenta: apart from the other overlays
    style.width = 2.0f;
    const Camera& camera = context_.view.camera;
    renderer_->draw(camera.view(), camera.projection(), style, context_.ui_scale);
}

namespace {

/// The dihedral angles' histogram (log count per degree), the plateau shaded, the angle
/// marked. Test hook id: "features: histogram".
void histogram_plot(const AngleHistogram& h, double angle) {
    const float width = widget_width(16.0f, 0.0f), height = 4.0f * ImGui::GetFrameHeight();
    const ImVec2 p0 = ImGui::GetCursorScreenPos();
    ImGui::Dummy(ImVec2(width, height));
    note_widget("features: histogram");
    ImDrawList* draw = ImGui::GetWindowDrawList();
    draw->AddRect(p0, ImVec2(p0.x + width, p0.y + height), IM_COL32(110, 110, 110, 255));
    const auto x_of = [&](double degrees) { return p0.x + float(degrees / 180.0) * width; };
    if (h.plateau)
        draw->AddRectFilled(ImVec2(x_of(h.plateau_lo), p0.y),
                            ImVec2(x_of(h.plateau_hi + 1), p0.y + height),
                            IM_COL32(60, 140, 80, 110));
    std::size_t most = 1;
    for (std::size_t c : h.counts) most = std::max(most, c);
    const double top = std::log10(double(most) + 1.0);
    for (std::size_t k = 0; k < h.counts.size(); ++k) {
        if (h.counts[k] == 0) continue;
        const float t = float(std::log10(double(h.counts[k]) + 1.0) / top);
        draw->AddRectFilled(
            ImVec2(x_of(double(k)), p0.y + height * (1.0f - t)),
            ImVec2(std::max(x_of(double(k + 1)), x_of(double(k)) + 1.0f), p0.y + height),
            IM_COL32(170, 170, 190, 255));
    }
    draw->AddLine(ImVec2(x_of(angle), p0.y), ImVec2(x_of(angle), p0.y + height),
                  IM_COL32(240, 50, 150, 255), 2.0f);
}

}  // namespace

void FeaturesTool::tagging(const SidebarContext& context, CommandQueue& commands) {
    ImGui::Separator();
    ImGui::TextUnformatted("Tagging by hand");
    checkbox("tag edges by clicking", &tag_by_click_);
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("a click on the model makes the nearest edge sharp, or smooth again");
    checkbox("infinitely sharp", &infinite_);
    if (!infinite_) {
        ImGui::SetNextItemWidth(widget_width());
        ImGui::SliderFloat("sharpness", &sharpness_, 0.1f, 10.0f, "%.2f",
                           ImGuiSliderFlags_AlwaysClamp);
        note_widget("features: sharpness");
    }
    const bool can = context.has_selection && context.selected > 1 && !context.busy;
    if (!can) ImGui::BeginDisabled();
    if (button("Sharpen the selection's edges"))
        commands.push_back(RunOperation{sharpen_selection(false)});
    ImGui::SameLine();
    if (button("Clear them")) commands.push_back(RunOperation{sharpen_selection(true)});
    if (!can) ImGui::EndDisabled();
    if (!context.has_selection) wrapped_disabled("select vertices to tag the edges between them");
}

void FeaturesTool::section(const SidebarContext& context, CommandQueue& commands) {
    SidebarSection section("Features", panel_.open);
    if (!section) return;
    ImGui::TextWrapped("%s", panel_words(panel_.op.def->summary).c_str());
    operation_panel_body(panel_, "Detect", context.busy, commands);
    checkbox("show feature lines", &show_lines_);
    ImGui::SameLine();
    ImGui::TextDisabled("(%zu shown)", lines_.size());
    tagging(context, commands);
    ImGui::Separator();
    ImGui::TextUnformatted("Dihedral angles (log count per degree)");
    const FeatureDetectionReport* r = report();
    if (!r) {
        wrapped_disabled("change the angle to preview the detection and its histogram");
    } else {
        histogram_plot(r->histogram, options_of<FeatureDetectionOptions>(panel_.op).angle_deg);
        ImGui::TextDisabled("%zu feature edges, %zu chains, %zu corners, %zu darts",
                            r->feature_edges, r->chains, r->corners, r->darts);
        wrapped_disabled("%s", r->verdict.c_str());
        if (!r->histogram.plateau)
            wrapped_disabled(
                "no plateau: on a noisy scan a threshold alone finds false edges; "
                "denoise first (Tools > Denoise)");
    }
    ImGui::Separator();
    morph_hint();
}

PanelEntries FeaturesTool::panels() {
    PanelEntry entry;
    entry.name = "features";
    entry.title = "Features...";
    entry.open = &panel_.open;
    entry.menu = PanelMenu::Tools;
    entry.in_tools = true;
    return {entry};
}

void FeaturesTool::settings(SettingsVisitor& v) {
    // The key the generic panel saved it under before the tool had its own panel.
    operation_setting(v, "panel.tool.features", panel_);
    v.flag("features.show_lines", show_lines_);
    v.flag("features.tag_by_click", tag_by_click_);
    v.flag("features.infinite", infinite_);
    v.number("features.sharpness", sharpness_);
}

}  // namespace trilab::viewer
