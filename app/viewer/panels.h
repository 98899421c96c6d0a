#pragma once
// The viewer's ImGui panels. Each panel is a function over one plain state struct: it edits
// what it owns directly and asks the viewer for everything else by queueing a Command, so
// panels never touch the document, the window or the GPU.
#include <cstddef>
#include <string>
#include <variant>
#include <vector>

#include "render/mesh_renderer.h"

namespace trilab::viewer {

// ---- commands ----------------------------------------------------------------------------
struct LoadFile {
    std::string path;
};
struct FitView {};
struct Quit {};
using Command = std::variant<LoadFile, FitView, Quit>;
using CommandQueue = std::vector<Command>;

// ---- panel state -------------------------------------------------------------------------
/// The last thing the viewer has to tell the user. Errors also open a modal popup once.
struct Notice {
    enum class Level { None, Info, Error };
    Level level = Level::None;
    std::string text;                  ///< one line, shown in the status bar
    std::vector<std::string> details;  ///< extra lines for the tooltip (e.g. a load report)
    bool popup_pending = false;        ///< an error the popup has not shown yet
};

struct OpenDialogState {
    bool open_requested = false;  ///< open the dialog on the next frame
    std::string path;             ///< the text field's contents
};

struct HelpState {
    bool open = false;
};

/// What the status bar shows.
struct StatusInfo {
    std::size_t n_vertices = 0;
    std::size_t n_faces = 0;
    std::string file_name;
    double frame_ms = 0.0;
};

// ---- panels ------------------------------------------------------------------------------
/// File (Open..., Quit), Rendering (shading, overlays, fit) and Help menus.
void menu_bar(RenderStyle& style, OpenDialogState& open_dialog, HelpState& help,
              CommandQueue& commands);
/// A one-line bar along the bottom edge of the window.
void status_bar(const StatusInfo& info, const Notice& notice);
/// Modal dialog with a path text field; queues LoadFile on Open or Enter.
void open_dialog(OpenDialogState& state, CommandQueue& commands);
/// The key and mouse bindings.
void help_window(HelpState& state);
/// Modal popup showing an error notice once.
void error_popup(Notice& notice);

}  // namespace trilab::viewer
