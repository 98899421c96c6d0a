#include "app/viewer/remesh_tool.h"

#include <imgui.h>

#include <chrono>
#include <cstdio>
#include <exception>

#include "app/viewer/panel_helpers.h"
#include "app/viewer/widgets.h"

namespace trilab::viewer {

using namespace ui;

namespace {

std::string fixed(double value, const char* format) {
    char text[64];
    std::snprintf(text, sizeof(text), format, value);
    return text;
}

}  // namespace

RemeshQuality remesh_quality(const HalfedgeMesh& mesh, std::optional<double> length) {
    return {mesh_quality(mesh, length), cotangent_spread(mesh)};
}

std::vector<std::array<std::string, 3>> quality_rows(const RemeshQuality& before_all,
                                                     const RemeshQuality* after_all) {
    std::vector<std::array<std::string, 3>> rows;
    const MeshQuality& before = before_all.quality;
    const MeshQuality* after = after_all ? &after_all->quality : nullptr;
    const auto row = [&](const char* label, double b, double a, const char* format) {
        rows.push_back({label, fixed(b, format), after ? fixed(a, format) : "-"});
    };
    const MeshQuality none;
    const MeshQuality& x = after ? *after : none;
    row("faces", double(before.faces), double(x.faces), "%.0f");
    row("smallest angle (deg)", before.min_angle, x.min_angle, "%.1f");
    row("mean smallest angle (deg)", before.mean_min_angle, x.mean_min_angle, "%.1f");
    row("angles under 30 deg (%)", 100.0 * before.angles_under_30, 100.0 * x.angles_under_30,
        "%.1f");
    row("edges in [0.8 L, 4/3 L] (%)", 100.0 * before.edges_in_band, 100.0 * x.edges_in_band,
        "%.1f");
    row("valence 6 (%)", 100.0 * before.valence6, 100.0 * x.valence6, "%.1f");
    const CotangentSpread no_spread;
    const CotangentSpread& s = after_all ? after_all->spread : no_spread;
    row("cotangent weight, largest / median", before_all.spread.weight_ratio, s.weight_ratio,
        "%.3g");
    row("negative cotangent weights (%)", 100.0 * before_all.spread.negative_share,
        100.0 * s.negative_share, "%.1f");
    return rows;
}

RemeshTool::RemeshTool(ViewerContext& context) : OperationTool(context, {}) {
    set_panels({&panel_});
}

void RemeshTool::take_results() {
    const auto ready = [](const auto& job) {
        return job.valid() && job.wait_for(std::chrono::seconds(0)) == std::future_status::ready;
    };
    if (ready(plan_job_)) {
        Planned p = plan_job_.get();
        if (p.key == plan_key_) {  // not overtaken by newer parameters
            plan_ = std::move(p.plan);
            plan_error_ = std::move(p.error);
            before_ = std::move(p.before);
        }
    }
    if (ready(after_job_)) after_ = after_job_.get();
}

void RemeshTool::update() {
    OperationTool::update();
    take_results();
    if (!panel_.open) return;
    const Session& session = context_.session;
    const HalfedgeMesh& mesh = session.mesh();
    const std::string state =
        std::to_string(mesh.topology_revision()) + "/" + std::to_string(mesh.geometry_revision());
    const std::string key = panel_.op.text() + "@" + state;
    if (key != plan_key_ && !plan_job_.valid()) {  // one computation at a time
        plan_key_ = key;
        after_of_ = nullptr;  // at a new length, the preview's quality too
        RemeshOptions options;
        bool valid = true;
        std::string error;
        try {
            options = options_of<RemeshOptions>(panel_.op);
        } catch (const std::exception& e) {
            valid = false;
            error = e.what();
        }
        plan_job_ = std::async(std::launch::async, [key, copy = mesh, options, valid, error] {
            Planned p{key, std::nullopt, error, {}};
            if (valid) {
                try {
                    p.plan = remesh_plan(copy, options);
                } catch (const std::exception& e) {
                    p.error = e.what();
                }
            }
            const std::optional<double> length =
                p.plan ? std::optional<double>(p.plan->target_length) : std::nullopt;
            p.before = remesh_quality(copy, length);
            return p;
        });
    }
    const OperationResult* result = session.previews().result();
    if (!result || !panel_.previewing || result->steps.empty()) {
        after_.reset();
        after_of_ = nullptr;
    } else if (result != after_of_ && plan_ && !plan_job_.valid() && !after_job_.valid()) {
        after_of_ = result;
        after_job_ = std::async(std::launch::async,
                                [copy = result->steps.back().mesh, length = plan_->target_length] {
                                    return remesh_quality(copy, length);
                                });
    }
}

void RemeshTool::finish() {
    for (int i = 0; i < 3; ++i) {  // the plan, then the preview's quality it enables
        if (plan_job_.valid()) plan_job_.wait();
        if (after_job_.valid()) after_job_.wait();
        update();
    }
}

void RemeshTool::section(const SidebarContext& context, CommandQueue& commands) {
    SidebarSection section("Remesh", panel_.open);
    if (!section) return;
    ImGui::TextWrapped("%s", panel_words(panel_.op.def->summary).c_str());
    operation_panel_body(panel_, "Remesh", context.busy, commands);
    ImGui::Separator();
    if (plan_) {
        wrapped_disabled("before it runs: L = %.4g (mean edge %.4g), about %zu faces from %zu",
                         plan_->target_length, plan_->input_mean_edge, plan_->predicted_faces,
                         plan_->input_faces);
    } else if (!plan_error_.empty()) {
        wrapped_colored(kErrorColor, "%s", plan_error_.c_str());
    }
    if (computing()) wrapped_disabled("%s", "measuring the quality...");
    if (before_ && ImGui::BeginTable("remesh quality", 3, ImGuiTableFlags_SizingFixedFit)) {
        ImGui::TableSetupColumn("quality");
        ImGui::TableSetupColumn("now");
        ImGui::TableSetupColumn("preview");
        ImGui::TableHeadersRow();
        for (const auto& row : quality_rows(*before_, after_ ? &*after_ : nullptr)) {
            ImGui::TableNextRow();
            for (int c = 0; c < 3; ++c) {
                ImGui::TableSetColumnIndex(c);
                ImGui::TextUnformatted(row[std::size_t(c)].c_str());
            }
        }
        ImGui::EndTable();
    }
    ImGui::Separator();
    morph_hint();
}

PanelEntries RemeshTool::panels() {
    PanelEntry entry;
    entry.name = "remesh";
    entry.title = "Remesh...";
    entry.open = &panel_.open;
    entry.menu = PanelMenu::Tools;
    entry.in_tools = true;
    return {entry};
}

void RemeshTool::settings(SettingsVisitor& v) {
    // The key the generic panel saved it under before the tool had its own panel.
    operation_setting(v, "panel.tool.remesh", panel_);
}

}  // namespace trilab::viewer
