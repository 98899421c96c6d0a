#pragma once
// Small ImGui helpers the panel files share (menus.cpp, regions.cpp, dialogs.cpp,
// parameter_widgets.cpp, sections.cpp); not an interface of its own.
#include <imgui.h>

#include <algorithm>

#include "app/session/session.h"
#include "app/viewer/panels.h"

namespace trilab::viewer::ui {

/// Pushes one style variable for the lifetime of the guard.
class ScopedStyleVar {
public:
    ScopedStyleVar(ImGuiStyleVar var, float value) { ImGui::PushStyleVar(var, value); }
    ScopedStyleVar(ImGuiStyleVar var, const ImVec2& value) { ImGui::PushStyleVar(var, value); }
    ~ScopedStyleVar() { ImGui::PopStyleVar(); }
    ScopedStyleVar(const ScopedStyleVar&) = delete;
    ScopedStyleVar& operator=(const ScopedStyleVar&) = delete;
};

inline const ImVec4 kErrorColor(1.0f, 0.45f, 0.40f, 1.0f);

inline ImVec4 notice_color(Notice::Level level) {
    return level == Notice::Level::Error ? kErrorColor : ImVec4(0.70f, 0.85f, 0.70f, 1.0f);
}

/// The width of a widget with its label at the right: `wanted_em`, less in a narrow sidebar
/// (the label keeps `label_share` of the line), never under 4 em.
inline float widget_width(float wanted_em = 12.0f, float label_share = 0.4f) {
    const float em = ImGui::GetFontSize();
    const float avail = ImGui::GetContentRegionAvail().x;
    return std::max(4.0f * em, std::min(wanted_em * em, (1.0f - label_share) * avail));
}

/// Greyed text that wraps at the sidebar's edge.
template <class... Args>
void wrapped_disabled(const char* format, Args... args) {
    ImGui::PushTextWrapPos(0.0f);
    ImGui::TextDisabled(format, args...);
    ImGui::PopTextWrapPos();
}

/// `text` on the rest of the current line, as much as fits there ending in "..." (fit_text()),
/// the whole in a tooltip: a message that comes and goes never moves the rows below.
inline void fitted_text(const ImVec4& color, const std::string& text) {
    if (text.empty()) return;
    const float room = ImGui::GetContentRegionAvail().x;
    const std::string shown =
        fit_text(text, room, [](const std::string& t) { return ImGui::CalcTextSize(t.c_str()).x; });
    ImGui::TextColored(color, "%s", shown.c_str());
    if (shown != text && ImGui::IsItemHovered()) {
        ImGui::BeginTooltip();
        ImGui::PushTextWrapPos(30.0f * ImGui::GetFontSize());
        ImGui::TextUnformatted(text.c_str());
        ImGui::PopTextWrapPos();
        ImGui::EndTooltip();
    }
}

/// Coloured text that wraps at the sidebar's edge.
template <class... Args>
void wrapped_colored(const ImVec4& color, const char* format, Args... args) {
    ImGui::PushTextWrapPos(0.0f);
    ImGui::TextColored(color, format, args...);
    ImGui::PopTextWrapPos();
}

}  // namespace trilab::viewer::ui
