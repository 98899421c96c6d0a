#include "app/viewer/panels.h"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <cmath>

namespace trilab::viewer {
namespace {

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
    {"Right click", "rendering menu"},
    {"W", "toggle the wireframe overlay"},
    {"B", "toggle the back-face colour"},
    {"F", "fog on / off"},
    {"S", "specular highlight on / off"},
    {"T", "cycle texture modes (off, modulate, replace)"},
    {"I", "print model and scene information (and show it)"},
    {"L", "show the log"},
    {"Ctrl+O", "open a mesh file"},
    {"Ctrl+S", "save the mesh as"},
    {"Ctrl+Q", "quit"},
    {"F1", "this window"},
    {"Drop a file", "open a mesh, or load an image as texture"},
};

ImVec4 notice_color(Notice::Level level) {
    return level == Notice::Level::Error ? ImVec4(1.0f, 0.45f, 0.40f, 1.0f)
                                         : ImVec4(0.70f, 0.85f, 0.70f, 1.0f);
}

}  // namespace

void rendering_menu_items(RenderStyle& style, CommandQueue& commands) {
    if (ImGui::MenuItem("Smooth shading", nullptr, style.shading == Shading::Smooth))
        style.shading = Shading::Smooth;
    if (ImGui::MenuItem("Flat shading", nullptr, style.shading == Shading::Flat))
        style.shading = Shading::Flat;
    ImGui::Separator();
    ImGui::MenuItem("Wireframe overlay", "W", &style.wireframe);
    ImGui::MenuItem("Back-face colour", "B", &style.back_face_color);
    ImGui::Separator();
    if (ImGui::MenuItem("Fit view", "Home")) commands.push_back(FitView{});
}

void menu_bar(RenderStyle& style, PanelState& panels, const MenuContext& context,
              CommandQueue& commands) {
    if (!ImGui::BeginMainMenuBar()) return;
    if (ImGui::BeginMenu("File")) {
        if (ImGui::MenuItem("Open...", "Ctrl+O", false, !context.busy))
            panels.file_browser.request(FileBrowserState::Purpose::OpenMesh, context.document_path);
        const bool has_recent = context.recent_files && !context.recent_files->empty();
        if (ImGui::BeginMenu("Open recent", has_recent && !context.busy)) {
            for (const std::string& path : *context.recent_files)
                if (ImGui::MenuItem(path.c_str())) commands.push_back(LoadFile{path});
            ImGui::EndMenu();
        }
        if (ImGui::MenuItem("Revert", nullptr, false, context.has_file && !context.busy))
            commands.push_back(RevertFile{});
        if (ImGui::MenuItem("Save as...", "Ctrl+S", false, !context.busy))
            panels.file_browser.request(FileBrowserState::Purpose::SaveMesh, context.document_path);
        ImGui::Separator();
        if (ImGui::MenuItem("Load texture...", nullptr, false, !context.busy))
            panels.file_browser.request(FileBrowserState::Purpose::LoadTexture, "");
        ImGui::Separator();
        if (ImGui::MenuItem("Quit", "Ctrl+Q")) commands.push_back(Quit{});
        ImGui::EndMenu();
    }
    if (ImGui::BeginMenu("Algorithms")) {
        // The operation panels arrive with their issues; listed so the menu shows the plan.
        ImGui::MenuItem("Fairing", nullptr, false, false);
        ImGui::MenuItem("Frequency decomposition", nullptr, false, false);
        ImGui::MenuItem("Subdivision", nullptr, false, false);
        ImGui::MenuItem("Decimation", nullptr, false, false);
        ImGui::EndMenu();
    }
    if (ImGui::BeginMenu("Rendering")) {
        rendering_menu_items(style, commands);
        ImGui::EndMenu();
    }
    if (ImGui::BeginMenu("Window")) {
        ImGui::MenuItem("Model information", "I", &panels.info_open);
        ImGui::MenuItem("Log", "L", &panels.log_open);
        ImGui::EndMenu();
    }
    if (ImGui::BeginMenu("Help")) {
        ImGui::MenuItem("Key bindings", "F1", &panels.help_open);
        ImGui::MenuItem("About trilab", nullptr, &panels.about_open);
        ImGui::EndMenu();
    }
    ImGui::EndMainMenuBar();
}

void context_menu(RenderStyle& style, PanelState& panels, CommandQueue& commands) {
    if (panels.context_menu_requested) {
        ImGui::OpenPopup("##rendering_context");
        panels.context_menu_requested = false;
    }
    if (ImGui::BeginPopup("##rendering_context")) {
        rendering_menu_items(style, commands);
        ImGui::EndPopup();
    }
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

void help_window(PanelState& panels) {
    if (!panels.help_open) return;
    ImGui::SetNextWindowPos(
        ImVec2(0.5f * ImGui::GetIO().DisplaySize.x, 0.4f * ImGui::GetIO().DisplaySize.y),
        ImGuiCond_Appearing, ImVec2(0.5f, 0.5f));
    if (ImGui::Begin("Key bindings", &panels.help_open,
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

void about_window(PanelState& panels) {
    if (!panels.about_open) return;
    if (ImGui::Begin("About trilab", &panels.about_open, ImGuiWindowFlags_AlwaysAutoResize)) {
        ImGui::TextUnformatted("trilab: a laboratory for triangle meshes");
        ImGui::Separator();
        ImGui::TextUnformatted("Half-edge core, OpenGL 3.3 renderer, Dear ImGui " IMGUI_VERSION);
        ImGui::TextUnformatted("Formats: .obj .off .ply .stl .om");
    }
    ImGui::End();
}

void job_progress(const JobInfo& job, CommandQueue& commands) {
    const ImGuiIO& io = ImGui::GetIO();
    ImGui::SetNextWindowPos(
        ImVec2(0.5f * io.DisplaySize.x, io.DisplaySize.y - 3.0f * ImGui::GetFrameHeight()),
        ImGuiCond_Always, ImVec2(0.5f, 1.0f));
    ImGui::SetNextWindowSize(ImVec2(26.0f * ImGui::GetFontSize(), 0.0f));
    const ImGuiWindowFlags flags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove |
                                   ImGuiWindowFlags_NoSavedSettings |
                                   ImGuiWindowFlags_NoFocusOnAppearing;
    if (ImGui::Begin("##job", nullptr, flags)) {
        ImGui::Text("%s  (%.1f s)", job.name.c_str(), job.seconds);
        if (!job.stage.empty()) ImGui::TextDisabled("%s", job.stage.c_str());
        // Unknown progress: a bar that sweeps, so the user sees the program is alive.
        const float f = job.fraction >= 0.0 ? float(job.fraction)
                                            : float(0.5 + 0.5 * std::sin(3.0 * job.seconds));
        ImGui::ProgressBar(f, ImVec2(-1.0f - 6.0f * ImGui::GetFontSize(), 0.0f),
                           job.fraction >= 0.0 ? nullptr : "");
        ImGui::SameLine();
        if (job.cancel_requested)
            ImGui::TextDisabled("cancelling");
        else if (ImGui::Button("Cancel"))
            commands.push_back(CancelJob{});
    }
    ImGui::End();
}

void log_window(PanelState& panels, const Log& log) {
    if (!panels.log_open) return;
    ImGui::SetNextWindowSize(ImVec2(40.0f * ImGui::GetFontSize(), 14.0f * ImGui::GetFontSize()),
                             ImGuiCond_FirstUseEver);
    if (ImGui::Begin("Log", &panels.log_open)) {
        const std::vector<LogEntry> entries = log.entries();
        for (const LogEntry& e : entries) {
            if (e.level == LogEntry::Level::Error)
                ImGui::TextColored(ImVec4(1.0f, 0.45f, 0.40f, 1.0f), "%s", e.text.c_str());
            else if (e.level == LogEntry::Level::Warning)
                ImGui::TextColored(ImVec4(1.0f, 0.80f, 0.35f, 1.0f), "%s", e.text.c_str());
            else
                ImGui::TextUnformatted(e.text.c_str());
        }
        if (ImGui::GetScrollY() >= ImGui::GetScrollMaxY()) ImGui::SetScrollHereY(1.0f);
    }
    ImGui::End();
}

void info_window(PanelState& panels, const std::vector<std::string>& lines) {
    if (!panels.info_open) return;
    if (ImGui::Begin("Model information", &panels.info_open, ImGuiWindowFlags_AlwaysAutoResize)) {
        for (const std::string& line : lines) ImGui::TextUnformatted(line.c_str());
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
