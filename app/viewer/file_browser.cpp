#include "app/viewer/file_browser.h"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <system_error>

#include "app/viewer/panels.h"
#include "app/viewer/widgets.h"
#include "core/io/image_io.h"
#include "core/io/mesh_io.h"

namespace trilab::viewer {
namespace {

constexpr const char* kTitle = "Choose a file###file_browser";

bool has_extension(const std::filesystem::path& p, const std::vector<std::string>& exts) {
    const std::string ext = file_extension(p.string());
    return std::find(exts.begin(), exts.end(), ext) != exts.end();
}

std::vector<std::string> extensions_for(FileBrowserState::Purpose purpose) {
    switch (purpose) {
        case FileBrowserState::Purpose::LoadTexture:
            return supported_image_extensions();
        case FileBrowserState::Purpose::OpenSession:
            return {"trilab", "journal"};
        case FileBrowserState::Purpose::SaveSession:
            return {"trilab"};
        case FileBrowserState::Purpose::OpenMesh:
        case FileBrowserState::Purpose::SaveMesh:
            break;
    }
    return supported_mesh_extensions();
}

/// Whether the dialog writes a file (an extension is required, an existing file confirmed).
bool writes(FileBrowserState::Purpose purpose) {
    return purpose == FileBrowserState::Purpose::SaveMesh ||
           purpose == FileBrowserState::Purpose::SaveSession;
}

const char* verb(FileBrowserState::Purpose purpose) {
    switch (purpose) {
        case FileBrowserState::Purpose::OpenMesh:
            return "Open";
        case FileBrowserState::Purpose::SaveMesh:
            return "Save";
        case FileBrowserState::Purpose::LoadTexture:
            return "Load texture";
        case FileBrowserState::Purpose::OpenSession:
            return "Open session";
        case FileBrowserState::Purpose::SaveSession:
            return "Save session";
    }
    return "Open";
}

struct Entry {
    std::string name;
    bool is_folder;
};

std::vector<Entry> list_folder(const std::filesystem::path& folder, bool all,
                               const std::vector<std::string>& exts, std::string& error) {
    std::vector<Entry> out;
    std::error_code ec;
    std::filesystem::directory_iterator it(folder, ec), end;
    if (ec) {
        error = "cannot list " + folder.string() + ": " + ec.message();
        return out;
    }
    for (; it != end; it.increment(ec)) {
        if (ec) break;
        const std::string name = it->path().filename().string();
        if (name.empty() || name[0] == '.') continue;
        std::error_code type_ec;
        const bool folder_entry = it->is_directory(type_ec);
        if (!folder_entry && !all && !has_extension(it->path(), exts)) continue;
        out.push_back({name, folder_entry});
    }
    std::sort(out.begin(), out.end(), [](const Entry& a, const Entry& b) {
        return a.is_folder != b.is_folder ? a.is_folder : a.name < b.name;
    });
    return out;
}

}  // namespace

void FileBrowserState::request(Purpose p, const std::string& near) {
    purpose = p;
    open_requested = true;
    error.clear();
    confirm_overwrite = false;
    then_continue = false;
    std::error_code ec;
    std::filesystem::path start =
        near.empty() ? std::filesystem::current_path(ec) : std::filesystem::absolute(near, ec);
    if (!near.empty() && !std::filesystem::is_directory(start, ec)) {
        name = p == Purpose::SaveMesh      ? start.filename().string()
               : p == Purpose::SaveSession ? start.stem().string() + ".trilab"
                                           : std::string();
        start = start.parent_path();
    } else {
        name = p == Purpose::SaveSession ? "session.trilab" : "";
    }
    folder = start.empty() ? std::filesystem::path("/") : start;
}

void file_browser(FileBrowserState& state, CommandQueue& commands) {
    if (state.open_requested) {
        ImGui::OpenPopup(kTitle);
        state.open_requested = false;
    }
    if (!begin_modal_dialog(kTitle, 0, 40.0f, 28.0f)) return;

    const std::vector<std::string> exts = extensions_for(state.purpose);
    ImGui::TextUnformatted(state.folder.string().c_str());
    if (button("Up")) state.folder = state.folder.parent_path();
    ImGui::SameLine();
    ImGui::Checkbox("Show all files", &state.show_all_files);

    std::string list_error;
    const std::vector<Entry> entries =
        list_folder(state.folder, state.show_all_files, exts, list_error);
    const float footer = 3.2f * ImGui::GetFrameHeightWithSpacing();
    bool accept = false;
    if (ImGui::BeginChild("##entries", ImVec2(0, -footer), true)) {
        if (!list_error.empty())
            ImGui::TextColored(ImVec4(1, 0.45f, 0.4f, 1), "%s", list_error.c_str());
        for (const Entry& e : entries) {
            const std::string label = e.is_folder ? e.name + "/" : e.name;
            const bool selected = !e.is_folder && e.name == state.name;
            if (ImGui::Selectable(label.c_str(), selected, ImGuiSelectableFlags_AllowDoubleClick)) {
                if (e.is_folder) {
                    if (ImGui::IsMouseDoubleClicked(0)) state.folder /= e.name;
                } else {
                    state.name = e.name;
                    state.confirm_overwrite = false;
                    accept = ImGui::IsMouseDoubleClicked(0);
                }
            }
        }
    }
    ImGui::EndChild();

    ImGui::SetNextItemWidth(-1);
    if (ImGui::InputTextWithHint("##name", "file name or path", &state.name,
                                 ImGuiInputTextFlags_EnterReturnsTrue))
        accept = true;
    std::string ext_list;
    for (const std::string& e : exts) ext_list += (ext_list.empty() ? "." : " .") + e;
    ImGui::TextDisabled("%s", ext_list.c_str());

    if (button(verb(state.purpose))) accept = true;
    ImGui::SameLine();
    const bool cancel =
        button("Cancel") || ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape));
    if (!state.error.empty()) {
        ImGui::SameLine();
        ImGui::TextColored(ImVec4(1, 0.45f, 0.4f, 1), "%s", state.error.c_str());
    }

    if (accept && !state.name.empty()) {
        std::filesystem::path chosen(state.name);
        if (chosen.is_relative()) chosen = state.folder / chosen;
        std::error_code ec;
        if (std::filesystem::is_directory(chosen, ec)) {
            state.folder = chosen;
            state.name.clear();
        } else if (writes(state.purpose) && !has_extension(chosen, exts)) {
            state.error = "choose an extension: " + ext_list;
        } else if (writes(state.purpose) && std::filesystem::exists(chosen, ec) &&
                   !state.confirm_overwrite) {
            state.error = "exists: press Save again to replace it";
            state.confirm_overwrite = true;
        } else {
            const std::string path = chosen.string();
            switch (state.purpose) {
                case FileBrowserState::Purpose::OpenMesh:
                    commands.push_back(LoadFile{path});
                    break;
                case FileBrowserState::Purpose::SaveMesh:
                    commands.push_back(SaveFile{path, state.then_continue});
                    break;
                case FileBrowserState::Purpose::LoadTexture:
                    commands.push_back(LoadTexture{path});
                    break;
                case FileBrowserState::Purpose::OpenSession:
                    commands.push_back(OpenSession{path});
                    break;
                case FileBrowserState::Purpose::SaveSession:
                    commands.push_back(SaveSession{path});
                    break;
            }
            state.error.clear();
            ImGui::CloseCurrentPopup();
        }
    } else if (cancel) {
        state.error.clear();
        ImGui::CloseCurrentPopup();
    }
    ImGui::EndPopup();
}

std::filesystem::path RecentFiles::default_file() {
    if (const char* xdg = std::getenv("XDG_CONFIG_HOME"); xdg && *xdg)
        return std::filesystem::path(xdg) / "trilab" / "recent-files";
    if (const char* home = std::getenv("HOME"); home && *home)
        return std::filesystem::path(home) / ".config" / "trilab" / "recent-files";
    return {};
}

void RecentFiles::load(const std::filesystem::path& file) {
    file_ = file;
    paths_.clear();
    std::ifstream in(file);
    std::string line;
    while (paths_.size() < kMax && std::getline(in, line))
        if (!line.empty()) paths_.push_back(line);
}

void RecentFiles::add(const std::string& path) {
    std::error_code ec;
    const std::string absolute = std::filesystem::absolute(path, ec).lexically_normal().string();
    const std::string& entry = ec ? path : absolute;
    paths_.erase(std::remove(paths_.begin(), paths_.end(), entry), paths_.end());
    paths_.insert(paths_.begin(), entry);
    if (paths_.size() > kMax) paths_.resize(kMax);
    if (file_.empty()) return;
    std::filesystem::create_directories(file_.parent_path(), ec);
    std::ofstream out(file_);
    for (const std::string& p : paths_) out << p << "\n";
}

std::filesystem::path Preferences::default_file() {
    const std::filesystem::path recent = RecentFiles::default_file();
    return recent.empty() ? recent : recent.parent_path() / "settings";
}

void Preferences::load(const std::filesystem::path& file) {
    file_ = file;
    up = UpAxis::Y;
    others_.clear();
    std::ifstream in(file);
    std::string line;
    while (std::getline(in, line)) {
        const std::size_t space = line.find(' ');
        if (line.empty() || space == std::string::npos) continue;
        const std::string key = line.substr(0, space), value = line.substr(space + 1);
        if (key == "up-axis") {
            try {
                up = parse_up_axis(value);
            } catch (const std::exception&) {
                up = UpAxis::Y;
            }
        } else {
            others_.emplace_back(key, value);
        }
    }
}

void Preferences::save() const {
    if (file_.empty()) return;
    std::error_code ec;
    std::filesystem::create_directories(file_.parent_path(), ec);
    std::ofstream out(file_);
    out << "up-axis " << up_axis_name(up) << "\n";
    for (const auto& [key, value] : others_) out << key << " " << value << "\n";
}

}  // namespace trilab::viewer
