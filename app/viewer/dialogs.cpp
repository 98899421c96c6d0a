// The floating dialogs: key bindings, about, screenshot, the unsaved-changes question and the
// error popup, kept inside the window; see panels.h.

#include <imgui.h>
#include <imgui_internal.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <optional>
#include <string>
#include <vector>

#include "app/viewer/key_bindings.h"
#include "app/viewer/panel_helpers.h"
#include "app/viewer/panels.h"
#include "app/viewer/plots.h"
#include "app/viewer/widgets.h"
#include "core/algorithms/fairing.h"
#include "core/number_text.h"

namespace trilab::viewer {

using namespace ui;

void place_dialog(float width_em, float height_em) {
    const ImGuiIO& io = ImGui::GetIO();
    const float em = ImGui::GetFontSize(), margin = 0.5f * em;
    const ImVec2 most(std::max(1.0f, io.DisplaySize.x - 2.0f * margin),
                      std::max(1.0f, io.DisplaySize.y - 2.0f * margin));
    ImGui::SetNextWindowPos(ImVec2(0.5f * io.DisplaySize.x, 0.5f * io.DisplaySize.y),
                            ImGuiCond_Appearing, ImVec2(0.5f, 0.5f));
    if (width_em > 0 && height_em > 0)
        ImGui::SetNextWindowSize(
            ImVec2(std::min(width_em * em, most.x), std::min(height_em * em, most.y)),
            ImGuiCond_Appearing);
    ImGui::SetNextWindowSizeConstraints(ImVec2(0, 0), most);
}

void keep_dialog_inside() {
    const ImGuiIO& io = ImGui::GetIO();
    const ImVec2 pos = ImGui::GetWindowPos(), size = ImGui::GetWindowSize();
    const ImVec2 fixed(std::clamp(pos.x, 0.0f, std::max(0.0f, io.DisplaySize.x - size.x)),
                       std::clamp(pos.y, 0.0f, std::max(0.0f, io.DisplaySize.y - size.y)));
    if (fixed.x != pos.x || fixed.y != pos.y) ImGui::SetWindowPos(fixed);
}

bool begin_modal_dialog(const char* title, int flags, float width_em, float height_em) {
    place_dialog(width_em, height_em);
    if (!ImGui::BeginPopupModal(title, nullptr, flags)) return false;
    keep_dialog_inside();
    return true;
}

namespace {

constexpr const char* kErrorPopupTitle = "Error";

void close_on_escape(bool& open) {
    if (ImGui::IsWindowFocused(ImGuiFocusedFlags_RootAndChildWindows) &&
        ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape), false))
        open = false;
}

/// Begins a dialog window (help, about, screenshot): centred when it appears, sized to its
/// content, kept inside the window, closed by Esc while focused. Call ImGui::End() after it
/// whatever it returns.
bool begin_dialog(const char* title, bool& open, ImGuiWindowFlags extra_flags = 0) {
    place_dialog();
    if (!ImGui::Begin(title, &open, ImGuiWindowFlags_AlwaysAutoResize | extra_flags)) return false;
    keep_dialog_inside();
    close_on_escape(open);
    return true;
}

}  // namespace

void help_window(PanelState& panels) {
    if (!panels.help_open) return;
    if (begin_dialog("Key bindings", panels.help_open, ImGuiWindowFlags_NoCollapse)) {
        if (ImGui::BeginTable("bindings", 2,
                              ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersInnerV)) {
            for (const BindingHelpRow& row : binding_help_rows()) {
                ImGui::TableNextRow();
                ImGui::TableNextColumn();
                ImGui::TextUnformatted(row.keys.c_str());
                ImGui::TableNextColumn();
                ImGui::TextUnformatted(row.action.c_str());
            }
            ImGui::EndTable();
        }
    }
    ImGui::End();
}

void screenshot_dialog(ScreenshotState& state, CommandQueue& commands) {
    if (!state.open) return;
    if (begin_dialog("Screenshot", state.open)) {
        ImGui::TextUnformatted("The scene without the panels, framed as the view, as PNG.");
        ImGui::SetNextItemWidth(20.0f * ImGui::GetFontSize());
        ImGui::InputText("file", &state.path);
        int size[2] = {state.width, state.height};
        ImGui::SetNextItemWidth(12.0f * ImGui::GetFontSize());
        if (ImGui::InputInt2("width, height", size)) {
            state.width = std::clamp(size[0], 1, 16384);
            state.height = std::clamp(size[1], 1, 16384);
        }
        checkbox("transparent background", &state.transparent);
        if (button("Save") && !state.path.empty())
            commands.push_back(
                TakeScreenshot{state.path, state.width, state.height, state.transparent});
    }
    ImGui::End();
}

void about_window(PanelState& panels) {
    if (!panels.about_open) return;
    if (begin_dialog("About trilab", panels.about_open)) {
        ImGui::TextUnformatted("trilab: a laboratory for triangle meshes");
        ImGui::Separator();
        ImGui::TextUnformatted("Half-edge core, OpenGL 3.3 renderer, Dear ImGui " IMGUI_VERSION);
        ImGui::TextUnformatted("Formats: .obj .off .ply .stl .om");
    }
    ImGui::End();
}

void unsaved_changes_popup(UnsavedPrompt& prompt, CommandQueue& commands) {
    constexpr const char* kTitle = "Unsaved changes";
    if (prompt.open_requested) {
        ImGui::OpenPopup(kTitle);
        prompt.open_requested = false;
    }
    if (!begin_modal_dialog(kTitle, ImGuiWindowFlags_AlwaysAutoResize)) return;
    ImGui::PushTextWrapPos(
        std::min(36.0f * ImGui::GetFontSize(), 0.8f * ImGui::GetIO().DisplaySize.x));
    ImGui::TextUnformatted(
        prompt.quitting  ? "The mesh has changes that are not saved to a file. Quit anyway?"
        : prompt.recover ? "The mesh has changes that are not saved to a file. Restoring the "
                           "recovered work replaces the whole history: save first to keep them."
                         : "The mesh has changes that are not saved to a file. Open the other "
                           "file anyway? (The changes stay in the history: Edit -> Undo brings "
                           "them back.)");
    ImGui::PopTextWrapPos();
    if (!prompt.document_path.empty()) {
        if (button("Save (overwrite)")) {
            commands.push_back(SaveAndContinue{});
            ImGui::CloseCurrentPopup();
        }
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("replace %s with the current mesh", prompt.document_path.c_str());
        ImGui::SameLine();
    }
    if (button("Save as...")) {
        commands.push_back(SaveAsAndContinue{});
        ImGui::CloseCurrentPopup();
    }
    ImGui::SameLine();
    if (button(prompt.quitting  ? "Discard and quit"
               : prompt.recover ? "Discard and restore"
                                : "Discard and open")) {
        if (prompt.quitting)
            commands.push_back(Quit{true});
        else if (prompt.recover)
            commands.push_back(RecoverJournal{prompt.path, true, true});
        else
            commands.push_back(LoadFile{prompt.path, true});
        ImGui::CloseCurrentPopup();
    }
    ImGui::SameLine();
    if (button("Cancel") || ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape)))
        ImGui::CloseCurrentPopup();
    ImGui::EndPopup();
}

void recovery_popup(RecoveryPrompt& prompt, CommandQueue& commands) {
    constexpr const char* kTitle = "Recover the last session?";
    if (prompt.open_requested) {
        ImGui::OpenPopup(kTitle);
        prompt.open_requested = false;
    }
    if (!begin_modal_dialog(kTitle, ImGuiWindowFlags_AlwaysAutoResize)) return;
    ImGui::PushTextWrapPos(
        std::min(36.0f * ImGui::GetFontSize(), 0.8f * ImGui::GetIO().DisplaySize.x));
    constexpr const char* kRestore =
        "Its journal holds every change that was complete; restoring it replaces the current "
        "model with that history (asking first when the model has unsaved changes).";
    if (prompt.ended.empty())
        ImGui::Text("A trilab session did not end cleanly. %s", kRestore);
    else
        ImGui::Text("A trilab session was ended by %s before its work was saved. %s",
                    prompt.ended.c_str(), kRestore);
    ImGui::TextDisabled("%s", prompt.description.c_str());
    ImGui::PopTextWrapPos();
    if (button("Restore")) {
        commands.push_back(RecoverJournal{prompt.path, true});
        ImGui::CloseCurrentPopup();
    }
    ImGui::SameLine();
    if (button("Discard")) {
        commands.push_back(RecoverJournal{prompt.path, false});
        ImGui::CloseCurrentPopup();
    }
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("delete %s", prompt.path.c_str());
    ImGui::SameLine();
    if (button("Later") || ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape)))
        ImGui::CloseCurrentPopup();
    ImGui::EndPopup();
}

void error_popup(const Notice& notice, CommandQueue& commands) {
    if (notice.popup_pending) {
        ImGui::OpenPopup(kErrorPopupTitle);
        commands.push_back(NoticeShown{});
    }
    if (!begin_modal_dialog(kErrorPopupTitle, ImGuiWindowFlags_AlwaysAutoResize)) return;
    ImGui::PushTextWrapPos(
        std::min(40.0f * ImGui::GetFontSize(), 0.8f * ImGui::GetIO().DisplaySize.x));
    ImGui::TextColored(notice_color(Notice::Level::Error), "%s", notice.text.c_str());
    ImGui::PopTextWrapPos();
    if (button("OK") || ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Enter)) ||
        ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape)))
        ImGui::CloseCurrentPopup();
    ImGui::EndPopup();
}

}  // namespace trilab::viewer
