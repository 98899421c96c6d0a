#pragma once
// The file browser panel: a modal dialog that lists a folder (sub-folders first, then the
// files whose extension fits the purpose), lets the user walk the tree, type a name or a
// whole path, and queues a command when a file is chosen. Also the recent-files list, kept
// in $XDG_CONFIG_HOME/trilab/recent-files (or ~/.config/...), and the other remembered
// settings (Preferences) in $XDG_CONFIG_HOME/trilab/settings.
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "app/session/commands.h"
#include "core/up_axis.h"

namespace trilab::viewer {

struct FileBrowserState {
    /// Sessions: .trilab files (app/history/session_file.h); opening also takes crash journals.
    enum class Purpose { OpenMesh, SaveMesh, LoadTexture, OpenSession, SaveSession };
    Purpose purpose = Purpose::OpenMesh;
    bool open_requested = false;  ///< open the dialog on the next frame
    std::filesystem::path folder;
    std::string name;  ///< the text field: a file name or a whole path
    bool show_all_files = false;
    std::string error;  ///< why the folder cannot be listed, or the name is bad
    bool confirm_overwrite = false;
    /// The save was asked for by the unsaved-changes question: once written, carry out the
    /// question's pending action (quit or open).
    bool then_continue = false;

    /// Opens the dialog for `purpose`, starting in the folder of `near` (or the current
    /// folder when empty).
    void request(Purpose p, const std::string& near);
};

/// Draws the dialog when open; queues LoadFile, SaveFile, LoadTexture, OpenSession or
/// SaveSession.
void file_browser(FileBrowserState& state, CommandQueue& commands);

/// Most recently used files, newest first, at most kMax.
class RecentFiles {
public:
    static constexpr std::size_t kMax = 10;
    /// Reads the list from `file` (missing or unreadable: empty list).
    void load(const std::filesystem::path& file);
    /// Moves `path` to the front and writes the list back (errors are ignored: the list is
    /// a convenience).
    void add(const std::string& path);
    const std::vector<std::string>& paths() const { return paths_; }
    /// The default location of the list, or empty when no home folder is known.
    static std::filesystem::path default_file();

private:
    std::filesystem::path file_;
    std::vector<std::string> paths_;
};

/// Settings the viewer remembers between sessions, one "key value" line each (unknown keys
/// are kept as they are when the file is written back).
class Preferences {
public:
    UpAxis up = UpAxis::Y;  ///< "up-axis y" or "up-axis z" (View > Up axis)

    /// Reads `file` (missing or unreadable: the defaults; a bad value: that setting's default).
    void load(const std::filesystem::path& file);
    /// Writes the settings to the file given to load() (nothing without one; errors are
    /// ignored: remembering is a convenience).
    void save() const;
    /// The default location, or empty when no home folder is known.
    static std::filesystem::path default_file();

private:
    std::filesystem::path file_;
    std::vector<std::pair<std::string, std::string>> others_;  ///< keys this version ignores
};

}  // namespace trilab::viewer
