#include "app/viewer/compare_tool.h"

#include <imgui.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <exception>
#include <filesystem>

#include "app/viewer/panel_helpers.h"
#include "app/viewer/widgets.h"
#include "core/algorithms/mesh_distance.h"
#include "core/geometry.h"
#include "core/io/mesh_io.h"

namespace trilab::viewer {

using namespace ui;

DistanceSummary summarize_distances(const std::vector<double>& distances) {
    DistanceSummary s;
    double sum = 0, squares = 0;
    for (double d : distances) {
        if (!std::isfinite(d)) continue;
        ++s.vertices;
        sum += d;
        squares += d * d;
        s.max = std::max(s.max, d);
    }
    if (s.vertices) {
        s.mean = sum / double(s.vertices);
        s.rms = std::sqrt(squares / double(s.vertices));
    }
    return s;
}

CompareTool::CompareTool(ViewerContext& context) : Tool(context) {}

std::string CompareTool::key_now() const {
    const Session& session = context_.session;
    const HalfedgeMesh& mesh = session.mesh();
    std::string key = std::to_string(mesh.topology_revision()) + "/" +
                      std::to_string(mesh.geometry_revision()) + " to ";
    if (target_.source == Source::File) {
        std::error_code ec;
        const auto time = std::filesystem::last_write_time(target_.file, ec);
        return key + "file " + target_.file + " @" +
               (ec ? std::string("?") : std::to_string(time.time_since_epoch().count()));
    }
    const History& history = session.history();
    if (target_.entry < 0 || std::size_t(target_.entry) >= history.size()) return key + "none";
    const std::size_t steps = history.info(std::size_t(target_.entry)).steps.size();
    const HalfedgeMesh target = history.mesh(std::size_t(target_.entry), steps - 1);
    return key + "state " + std::to_string(target.topology_revision()) + "/" +
           std::to_string(target.geometry_revision());
}

void CompareTool::start(const std::string& key) {
    const Session& session = context_.session;
    HalfedgeMesh from = session.mesh();  // copies: the document may change meanwhile
    HalfedgeMesh to;
    std::string file;
    if (target_.source == Source::File) {
        file = target_.file;
    } else {
        const History& history = session.history();
        if (target_.entry < 0 || std::size_t(target_.entry) >= history.size()) {
            result_ = Result{key, {}, {}, 0, "no such state in the history", {}};
            return;
        }
        const std::size_t steps = history.info(std::size_t(target_.entry)).steps.size();
        to = history.mesh(std::size_t(target_.entry), steps - 1);
    }
    job_ = std::async(std::launch::async,
                      [key, from = std::move(from), to = std::move(to), file]() mutable {
                          Result r;
                          r.key = key;
                          r.of = {from.topology_revision(), from.geometry_revision()};
                          try {
                              if (!file.empty()) to = read_mesh(file).mesh;
                              r.distances = vertex_surface_distances(from, to);
                              r.summary = summarize_distances(r.distances);
                              const BoundingBox box = bounding_box(from);
                              r.diagonal = box.empty ? 0.0 : (box.max - box.min).norm();
                          } catch (const std::exception& e) {
                              r.distances.clear();
                              r.error = e.what();
                          }
                          return r;
                      });
}

void CompareTool::update() {
    ViewSettings& settings = context_.view.settings;
    const bool coloring = settings.coloring == VertexColoring::SurfaceDistance;
    if (coloring) open_ = true;  // the colouring's settings are here
    if (job_.valid() && job_.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
        result_ = job_.get();
        if (coloring) context_.commands.push_back(UpdateColoring{});
    }
    if (!open_ || job_.valid()) return;  // one computation at a time
    if (target_.source == Source::File && target_.file.empty()) return;
    const std::string key = key_now();
    if (key != result_.key) start(key);
}

void CompareTool::finish() {
    if (job_.valid()) job_.wait();
    update();
}

VertexColors CompareTool::field_colors(const HalfedgeMesh& mesh) const {
    if (context_.view.settings.coloring != VertexColoring::SurfaceDistance) return {};
    if (result_.distances.size() != mesh.vertices_size() ||
        result_.of[0] != mesh.topology_revision() || result_.of[1] != mesh.geometry_revision())
        return {};
    return color_field(mesh, result_.distances, VertexColoring::SurfaceDistance,
                       context_.view.settings.coloring_options);
}

void CompareTool::section(const SidebarContext& context, CommandQueue& commands) {
    SidebarSection section("Compare", open_);
    if (!section) return;
    wrapped_disabled(
        "How far each vertex of the current state is from another surface (one-sided, to "
        "the closest point of its triangles).");
    int source = int(target_.source);
    if (ImGui::RadioButton("a state of the history", &source, 0)) target_.source = Source::State;
    note_widget("compare: state");
    if (ImGui::RadioButton("a mesh file", &source, 1)) target_.source = Source::File;
    note_widget("compare: file");
    if (target_.source == Source::State) {
        const int last = context.history ? int(context.history->size()) - 1 : 0;
        target_.entry = std::clamp(target_.entry, 0, std::max(0, last));
        ImGui::SetNextItemWidth(widget_width());
        ImGui::SliderInt("state", &target_.entry, 0, std::max(0, last), "%d",
                         ImGuiSliderFlags_AlwaysClamp);
        note_widget("compare: entry");
        if (context.history && std::size_t(target_.entry) < context.history->size()) {
            const auto info = context.history->info(std::size_t(target_.entry));
            wrapped_disabled("%s %s", info.label.c_str(), info.parameters.c_str());
        }
    } else {
        if (target_.file != file_text_.data()) {
            std::strncpy(file_text_.data(), target_.file.c_str(), file_text_.size() - 1);
            file_text_.back() = '\0';
        }
        ImGui::SetNextItemWidth(widget_width(16.0f));
        if (ImGui::InputText("file", file_text_.data(), file_text_.size(),
                             ImGuiInputTextFlags_EnterReturnsTrue))
            target_.file = file_text_.data();
        note_widget("compare: path");
        wrapped_disabled("a path, then Enter");
    }
    if (button("Colour by the distance")) {
        context_.view.settings.coloring = VertexColoring::SurfaceDistance;
        commands.push_back(UpdateColoring{});
    }
    if (computing()) {
        wrapped_disabled("measuring...");
    } else if (!result_.error.empty()) {
        wrapped_colored(kErrorColor, "%s", result_.error.c_str());
    } else if (!result_.distances.empty()) {
        const DistanceSummary& s = result_.summary;
        const double d = result_.diagonal > 0 ? result_.diagonal : 1.0;
        wrapped_disabled(
            "mean %.4g, largest %.4g (%.3f %% of the diagonal), RMS %.4g over %zu "
            "vertices",
            s.mean, s.max, 100.0 * s.max / d, s.rms, s.vertices);
    }
}

PanelEntries CompareTool::panels() {
    PanelEntry entry;
    entry.name = "compare";
    entry.title = "Compare...";
    entry.open = &open_;
    entry.menu = PanelMenu::Tools;
    entry.in_tools = true;
    return {entry};
}

void CompareTool::settings(SettingsVisitor& v) {
    v.flag("compare.open", open_);
    int source = int(target_.source);
    v.number("compare.source", source);
    target_.source = source == 1 ? Source::File : Source::State;
    v.number("compare.entry", target_.entry);
    v.text("compare.file", target_.file);
}

}  // namespace trilab::viewer
