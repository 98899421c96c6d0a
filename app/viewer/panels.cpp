#include "app/viewer/panels.h"

#include <imgui.h>
#include <imgui_stdlib.h>

namespace trilab::viewer {
namespace {

constexpr const char* kOpenDialogTitle = "Open mesh";
constexpr const char* kErrorPopupTitle = "Error";

/// Pushes one style variable for the lifetime of the guard.
class ScopedStyleVar {
public:
    ScopedStyleVar(ImGuiStyleVar var, float value) { ImGui::PushStyleVar(var, value); }
    ScopedStyleVar(ImGuiStyleVar var, const ImVec2& value) { ImGui::PushStyleVar(var, value); }
    ~ScopedStyleVar() { ImGui::PopStyleVar(); }
    ScopedStyleVar(const ScopedStyleVar&) = delete;
    ScopedStyleVar& operator=(const ScopedStyleVar&) = delete;
};

struct Binding {
    const char* keys;
    const char* action;
};
constexpr Binding kBindings[] = {
    {"Left drag", "rotate (trackball)"},
    {"Middle drag, Shift + left drag", "pan"},
    {"Mouse wheel", "zoom"},
    {"Home, double-click", "fit the model into the view"},
    {"W", "toggle the wireframe overlay"},
    {"F", "toggle flat / smooth shading"},
    {"B", "toggle the back-face colour"},
    {"Ctrl+O", "open a mesh file"},
    {"Ctrl+Q", "quit"},
    {"F1", "this window"},
};

ImVec4 notice_color(Notice::Level level) {
    return level == Notice::Level::Error ? ImVec4(1.0f, 0.45f, 0.40f, 1.0f)
                                         : ImVec4(0.70f, 0.85f, 0.70f, 1.0f);
}

}  // namespace

void menu_bar(RenderStyle& style, OpenDialogState& open_dialog, HelpState& help,
              CommandQueue& commands) {
    if (!ImGui::BeginMainMenuBar()) return;
    if (ImGui::BeginMenu("File")) {
        if (ImGui::MenuItem("Open...", "Ctrl+O")) open_dialog.open_requested = true;
        ImGui::Separator();
        if (ImGui::MenuItem("Quit", "Ctrl+Q")) commands.push_back(Quit{});
        ImGui::EndMenu();
    }
    if (ImGui::BeginMenu("Rendering")) {
        if (ImGui::MenuItem("Smooth", "F", style.shading == Shading::Smooth))
            style.shading = Shading::Smooth;
        if (ImGui::MenuItem("Flat", "F", style.shading == Shading::Flat))
            style.shading = Shading::Flat;
        ImGui::Separator();
        ImGui::MenuItem("Wireframe overlay", "W", &style.wireframe);
        ImGui::MenuItem("Back-face colour", "B", &style.back_face_color);
        ImGui::Separator();
        if (ImGui::MenuItem("Fit view", "Home")) commands.push_back(FitView{});
        ImGui::EndMenu();
    }
    if (ImGui::BeginMenu("Help")) {
        ImGui::MenuItem("Key bindings", "F1", &help.open);
        ImGui::EndMenu();
    }
    ImGui::EndMainMenuBar();
}

void status_bar(const StatusInfo& info, const Notice& notice) {
    const ImGuiIO& io = ImGui::GetIO();
    const ImGuiStyle& style = ImGui::GetStyle();
    const float height = ImGui::GetFrameHeight();
    ImGui::SetNextWindowPos(ImVec2(0.0f, io.DisplaySize.y - height));
    ImGui::SetNextWindowSize(ImVec2(io.DisplaySize.x, height));
    const ImGuiWindowFlags flags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove |
                                   ImGuiWindowFlags_NoSavedSettings |
                                   ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoNav |
                                   ImGuiWindowFlags_NoBringToFrontOnFocus;
    ScopedStyleVar padding(ImGuiStyleVar_WindowPadding,
                           ImVec2(style.FramePadding.x * 2.0f, style.FramePadding.y));
    ScopedStyleVar rounding(ImGuiStyleVar_WindowRounding, 0.0f);
    ScopedStyleVar border(ImGuiStyleVar_WindowBorderSize, 0.0f);
    if (ImGui::Begin("##status_bar", nullptr, flags)) {
        ImGui::Text("%zu vertices   %zu faces   %s   %.1f ms", info.n_vertices, info.n_faces,
                    info.file_name.c_str(), info.frame_ms);
        if (notice.level != Notice::Level::None) {
            ImGui::SameLine(0.0f, 3.0f * style.ItemSpacing.x);
            ImGui::TextColored(notice_color(notice.level), "%s", notice.text.c_str());
            if (ImGui::IsItemHovered()) {  // the whole text (the bar may clip it) and details
                ImGui::BeginTooltip();
                ImGui::TextUnformatted(notice.text.c_str());
                for (const std::string& line : notice.details) ImGui::TextUnformatted(line.c_str());
                ImGui::EndTooltip();
            }
        }
    }
    ImGui::End();
}

void open_dialog(OpenDialogState& state, CommandQueue& commands) {
    if (state.open_requested) {
        ImGui::OpenPopup(kOpenDialogTitle);
        state.open_requested = false;
    }
    const ImGuiIO& io = ImGui::GetIO();
    ImGui::SetNextWindowPos(ImVec2(0.5f * io.DisplaySize.x, 0.4f * io.DisplaySize.y),
                            ImGuiCond_Appearing, ImVec2(0.5f, 0.5f));
    if (!ImGui::BeginPopupModal(kOpenDialogTitle, nullptr, ImGuiWindowFlags_AlwaysAutoResize))
        return;
    ImGui::TextUnformatted("Path of a mesh file (.obj .off .ply .stl .om):");
    if (ImGui::IsWindowAppearing()) ImGui::SetKeyboardFocusHere();
    ImGui::SetNextItemWidth(36.0f * ImGui::GetFontSize());
    bool open = ImGui::InputText("##path", &state.path, ImGuiInputTextFlags_EnterReturnsTrue);
    open = ImGui::Button("Open") || open;
    ImGui::SameLine();
    bool cancel =
        ImGui::Button("Cancel") || ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape));
    if (open && !state.path.empty()) {
        commands.push_back(LoadFile{state.path});
        ImGui::CloseCurrentPopup();
    } else if (cancel) {
        ImGui::CloseCurrentPopup();
    }
    ImGui::EndPopup();
}

void help_window(HelpState& state) {
    if (!state.open) return;
    ImGui::SetNextWindowPos(
        ImVec2(0.5f * ImGui::GetIO().DisplaySize.x, 0.4f * ImGui::GetIO().DisplaySize.y),
        ImGuiCond_Appearing, ImVec2(0.5f, 0.5f));
    if (ImGui::Begin("Key bindings", &state.open,
                     ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoCollapse)) {
        if (ImGui::BeginTable("bindings", 2,
                              ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersInnerV)) {
            for (const Binding& b : kBindings) {
                ImGui::TableNextRow();
                ImGui::TableNextColumn();
                ImGui::TextUnformatted(b.keys);
                ImGui::TableNextColumn();
                ImGui::TextUnformatted(b.action);
            }
            ImGui::EndTable();
        }
    }
    ImGui::End();
}

void error_popup(Notice& notice) {
    if (notice.popup_pending) {
        ImGui::OpenPopup(kErrorPopupTitle);
        notice.popup_pending = false;
    }
    const ImGuiIO& io = ImGui::GetIO();
    ImGui::SetNextWindowPos(ImVec2(0.5f * io.DisplaySize.x, 0.4f * io.DisplaySize.y),
                            ImGuiCond_Appearing, ImVec2(0.5f, 0.5f));
    if (!ImGui::BeginPopupModal(kErrorPopupTitle, nullptr, ImGuiWindowFlags_AlwaysAutoResize))
        return;
    ImGui::PushTextWrapPos(40.0f * ImGui::GetFontSize());
    ImGui::TextColored(notice_color(Notice::Level::Error), "%s", notice.text.c_str());
    ImGui::PopTextWrapPos();
    if (ImGui::Button("OK") || ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Enter)) ||
        ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape)))
        ImGui::CloseCurrentPopup();
    ImGui::EndPopup();
}

}  // namespace trilab::viewer
