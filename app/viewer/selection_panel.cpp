// The Selection section of the sidebar (issue 26): see panels.h selection_section(). The brush
// and the lasso draw in the view (selection_tool.cpp); this section holds their settings and
// queues the one-shot selections and the edits, each one history entry.
#include <imgui.h>

#include <algorithm>
#include <cstdio>

#include "app/viewer/panel_helpers.h"
#include "app/viewer/panels.h"
#include "app/viewer/widgets.h"

namespace trilab::viewer {

using namespace ui;

namespace {

/// A radio button for `value`, reported as a button (the tests and --click press it).
void tool_choice(const char* label, SelectionPanelState::Tool value,
                 SelectionPanelState::Tool& tool) {
    if (ImGui::RadioButton(label, tool == value)) tool = value;
    note_widget(visible_label(label), WidgetNote::Kind::Button);
}

}  // namespace

void selection_section(SelectionPanelState& s, const SidebarContext& context,
                       CommandQueue& commands) {
    SidebarSection section("Selection", s.open);
    if (!section) return;
    if (context.has_selection)
        ImGui::Text("%zu of %zu vertices selected", context.selected, context.n_vertices);
    else
        wrapped_disabled("no selection: operations act on the whole mesh");
    note_widget("selected-count");

    // The brush and the lasso draw in the view.
    using Stroke = SelectionPanelState::Tool;
    tool_choice("Brush", Stroke::Brush, s.tool);
    ImGui::SameLine();
    tool_choice("Lasso", Stroke::Lasso, s.tool);
    const float w = widget_width(10.0f);
    if (s.tool == Stroke::Brush) {
        ImGui::SetNextItemWidth(w);
        ImGui::SliderFloat("radius (pixels)", &s.brush_radius, 2.0f, 200.0f, "%.0f");
        note_widget("brush-radius");
    } else {
        checkbox("through the model", &s.lasso_through);
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("off: only the surface you see; on: hidden vertices too");
    }
    wrapped_disabled("in the view: Ctrl+drag adds, Alt+drag removes; plain drags turn it");

    ImGui::Separator();
    const char* modes[] = {"replace", "add", "remove"};
    int mode = int(s.mode);
    ImGui::SetNextItemWidth(w);
    if (ImGui::Combo("combine", &mode, modes, IM_ARRAYSIZE(modes)))
        s.mode = SelectionMode(std::clamp(mode, 0, 2));
    note_widget("combine");
    if (context.busy) ImGui::BeginDisabled();
    // At the pick: the geodesic ball, the connected component.
    ImGui::SetNextItemWidth(w);
    if (ImGui::InputFloat("geodesic radius", &s.geodesic_radius, 0.0f, 0.0f, "%.4g"))
        s.geodesic_radius = std::max(s.geodesic_radius, 0.0f);
    note_widget("geodesic-radius");
    if (!context.has_pick) ImGui::BeginDisabled();
    if (button("Geodesic ball at pick"))
        commands.push_back(SelectAtPick{false, double(s.geodesic_radius), s.mode});
    ImGui::SameLine();
    if (button("Component at pick")) commands.push_back(SelectAtPick{true, 0.0, s.mode});
    if (!context.has_pick) {
        ImGui::EndDisabled();
        wrapped_disabled("click the model to pick a vertex");
    }
    // The threshold on the colouring's values.
    ImGui::SetNextItemWidth(w);
    ImGui::InputFloat("value", &s.threshold, 0.0f, 0.0f, "%.4g");
    note_widget("threshold");
    checkbox("above", &s.threshold_above);
    if (!context.has_values) ImGui::BeginDisabled();
    ImGui::SameLine();
    if (button("Threshold"))
        commands.push_back(SelectThreshold{double(s.threshold), s.threshold_above, s.mode});
    if (!context.has_values) {
        ImGui::EndDisabled();
        wrapped_disabled("colour the model by a value (curvature, distance...) first");
    } else {
        wrapped_disabled("the colouring's values: %.4g to %.4g", context.values_min,
                         context.values_max);
    }

    ImGui::Separator();
    using Kind = EditSelection::Kind;
    ImGui::SetNextItemWidth(w);
    if (ImGui::InputInt("rings", &s.rings)) s.rings = std::clamp(s.rings, 1, 100);
    note_widget("rings");
    if (!context.has_selection) ImGui::BeginDisabled();
    if (button("Grow")) commands.push_back(EditSelection{Kind::Grow, s.rings, 0.0});
    ImGui::SameLine();
    if (button("Shrink")) commands.push_back(EditSelection{Kind::Shrink, s.rings, 0.0});
    if (!context.has_selection) ImGui::EndDisabled();
    ImGui::SameLine();
    if (button("Invert")) commands.push_back(EditSelection{Kind::Invert, 1, 0.0});
    if (!context.has_selection) ImGui::BeginDisabled();
    ImGui::SameLine();
    if (button("Clear")) commands.push_back(EditSelection{Kind::Clear, 1, 0.0});
    ImGui::SetNextItemWidth(w);
    if (ImGui::InputFloat("feather width", &s.feather, 0.0f, 0.0f, "%.4g"))
        s.feather = std::max(s.feather, 0.0f);
    note_widget("feather");
    if (button("Feather")) commands.push_back(EditSelection{Kind::Feather, 1, double(s.feather)});
    if (!context.has_selection) ImGui::EndDisabled();
    if (context.busy) ImGui::EndDisabled();
    wrapped_disabled("every change is one history entry (Ctrl+Z undoes it); Save keeps it");
}

}  // namespace trilab::viewer
