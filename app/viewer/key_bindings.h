#pragma once
// The viewer's key bindings in one table (kKeyBindings): Viewer::handle_input dispatches the
// key presses through it (dispatch_key), the menus show its shortcut texts
// (shortcut_text), and the key bindings window (F1) lists it with the mouse bindings
// (binding_help_rows). Key codes and modifiers are GLFW's; a binding matches a press whose
// modifiers are exactly its own.
#include <cstddef>
#include <string>
#include <vector>

#include "app/session/commands.h"
#include "app/session/log.h"
#include "app/viewer/panels.h"
#include "render/mesh_renderer.h"

namespace trilab::viewer {

/// What a key does.
enum class KeyAction {
    FitView,
    ToggleWireframe,
    ToggleBackFaceColor,
    ToggleFog,
    ToggleSpecular,
    CycleTexture,
    Screenshot,
    PrintInfo,
    ToggleLog,
    Undo,
    Redo,
    ToggleHistory,
    ToggleMorph,
    ToggleRecord,
    PlayMorph,
    OpenFile,
    SaveFile,
    Quit,
    ToggleHelp,
    Escape,
};

/// One key binding: a GLFW key with exactly these GLFW modifier bits triggers `action`.
struct KeyBinding {
    int key;
    int mods;
    KeyAction action;
    const char* help;  ///< what it does, in the key bindings window
    /// An application shortcut (quit): it works whatever has the keyboard, so that it is never
    /// lost while a text field or a slider holds it.
    bool always = false;
};

/// Who has the keyboard: the bindings, or a widget (a text field being typed into, a slider
/// held, a popup): then only the `always` bindings act.
enum class KeyboardFocus { Bindings, Widget };

/// Every key binding, in the order the key bindings window lists them. An action may have
/// several keys (redo: Ctrl+Shift+Z and Ctrl+Y); the first is the one the menus show.
extern const std::vector<KeyBinding> kKeyBindings;

/// The text of a key with modifiers, as menus show it: "Ctrl+Shift+Z", "F12", "Home".
std::string chord_text(int key, int mods);
/// The shortcut text of `action`'s first binding, for its menu item ("" when it has none).
std::string shortcut_text(KeyAction action);
/// The binding `key` with exactly `mods` triggers, or nullptr.
const KeyBinding* find_key_binding(int key, int mods);

/// One row of the key bindings window: the keys (or mouse gesture) and what they do.
struct BindingHelpRow {
    std::string keys, action;
};
/// The key bindings window's rows: the mouse's, then one per key action (its keys joined),
/// then dropping a file.
std::vector<BindingHelpRow> binding_help_rows();

/// What the key actions act on (the viewer's state) and what they depend on.
struct KeyActionTargets {
    PanelState& panels;
    RenderStyle& style;
    ViewSettings& settings;
    const MorphState& morph;  ///< the session's (Space queues PlayMorph)
    CommandQueue& commands;
    Log& log;
    std::string document_path;       ///< where Open and Save as start
    bool busy = false;               ///< a job runs: no file dialogs
    bool has_entry = false;          ///< the history is past its first state (a morph to play)
    bool has_texcoords = false;      ///< the shown mesh has texture coordinates
    bool preview_requested = false;  ///< an operation preview is up (Esc cancels it)
    /// The tools' panels: a key that toggles a panel toggles the entry with its shortcut
    /// (M the Morph section, R the Record section).
    PanelEntries entries = {};
};

/// Carries out `action` on the targets (a command queued, a panel or style setting changed).
void run_key_action(KeyAction action, KeyActionTargets& targets);
/// Runs the action `key` with `mods` is bound to; false when it is bound to none, or when a
/// widget has the keyboard and the binding is not an `always` one (the key is the widget's).
bool dispatch_key(int key, int mods, KeyActionTargets& targets,
                  KeyboardFocus focus = KeyboardFocus::Bindings);

}  // namespace trilab::viewer
