#include "app/viewer/key_bindings.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

namespace trilab::viewer {
namespace {

constexpr int kCtrl = GLFW_MOD_CONTROL;
constexpr int kShift = GLFW_MOD_SHIFT;

/// The mouse bindings (handle_input spells them out; they have no menu item).
struct PointerBinding {
    const char* gesture;
    const char* help;
};
constexpr PointerBinding kPointerBindings[] = {
    {"Left drag", "rotate (trackball)"},
    {"Middle drag, Shift + left drag", "pan"},
    {"Mouse wheel", "zoom"},
    {"Double-click", "fit the model into the view"},
    {"Right click", "rendering menu"},
    {"Ctrl + left drag", "Selection section open: brush or lasso, adding to the selection"},
    {"Alt + left drag", "Selection section open: brush or lasso, removing from it"},
};
constexpr PointerBinding kDropBinding = {"Drop a file", "open a mesh, or load an image as texture"};

/// T: off -> modulate -> replace -> off.
void cycle_texture(KeyActionTargets& t) {
    RenderStyle& style = t.style;
    if (style.mode != RenderMode::Textured || style.texture_mode == TextureMode::Off) {
        style.mode = RenderMode::Textured;
        style.texture_mode = TextureMode::Modulate;
    } else if (style.texture_mode == TextureMode::Modulate) {
        style.texture_mode = TextureMode::Replace;
    } else {
        style.mode = RenderMode::Smooth;
        style.texture_mode = TextureMode::Off;
    }
    if (style.mode == RenderMode::Textured && !t.has_texcoords)
        t.log.warning(
            "textured mode: the model has no texture coordinates "
            "(Rendering > Texture > planar or spherical projection)");
}

/// Esc: close a dialog, or go back to the state before the preview.
void escape(KeyActionTargets& t) {
    PanelState& panels = t.panels;
    if (panels.help_open)
        panels.help_open = false;
    else if (panels.about_open)
        panels.about_open = false;
    else if (panels.screenshot.open)
        panels.screenshot.open = false;
    else if (t.preview_requested)
        t.commands.push_back(CancelPreview{});
}

}  // namespace

const std::vector<KeyBinding> kKeyBindings = {
    {GLFW_KEY_HOME, 0, KeyAction::FitView, "fit the model into the view"},
    {GLFW_KEY_W, 0, KeyAction::ToggleWireframe,
     "wireframe overlay on / off (Rendering menu: automatic)"},
    {GLFW_KEY_B, 0, KeyAction::ToggleBackFaceColor, "toggle the back-face colour"},
    {GLFW_KEY_F, 0, KeyAction::ToggleFog, "fog on / off"},
    {GLFW_KEY_S, 0, KeyAction::ToggleSpecular, "specular highlight on / off"},
    {GLFW_KEY_T, 0, KeyAction::CycleTexture, "cycle texture modes (off, modulate, replace)"},
    {GLFW_KEY_F12, 0, KeyAction::Screenshot, "screenshot (any resolution, without panels)"},
    {GLFW_KEY_I, 0, KeyAction::PrintInfo, "print model and scene information (and show it)"},
    {GLFW_KEY_L, 0, KeyAction::ToggleLog, "show the log (along the bottom)"},
    {GLFW_KEY_Z, kCtrl, KeyAction::Undo, "undo"},
    {GLFW_KEY_Z, kCtrl | kShift, KeyAction::Redo, "redo"},
    {GLFW_KEY_Y, kCtrl, KeyAction::Redo, "redo"},
    {GLFW_KEY_H, 0, KeyAction::ToggleHistory, "the History column"},
    {GLFW_KEY_M, 0, KeyAction::ToggleMorph, "the Morph section of the sidebar"},
    {GLFW_KEY_R, 0, KeyAction::ToggleRecord, "the Record section of the sidebar"},
    {GLFW_KEY_SPACE, 0, KeyAction::PlayMorph, "play or stop the morph animation"},
    {GLFW_KEY_O, kCtrl, KeyAction::OpenFile, "open a mesh file"},
    {GLFW_KEY_S, kCtrl, KeyAction::SaveFile, "save the mesh as"},
    {GLFW_KEY_Q, kCtrl, KeyAction::Quit, "quit", true},
    {GLFW_KEY_F1, 0, KeyAction::ToggleHelp, "this window (Esc closes it)"},
    {GLFW_KEY_ESCAPE, 0, KeyAction::Escape, "cancel a preview; close a dialog"},
};

std::string chord_text(int key, int mods) {
    std::string text;
    if (mods & kCtrl) text += "Ctrl+";
    if (mods & kShift) text += "Shift+";
    if (key >= GLFW_KEY_A && key <= GLFW_KEY_Z) return text + char('A' + (key - GLFW_KEY_A));
    if (key >= GLFW_KEY_F1 && key <= GLFW_KEY_F25)
        return text + "F" + std::to_string(key - GLFW_KEY_F1 + 1);
    switch (key) {
        case GLFW_KEY_HOME:
            return text + "Home";
        case GLFW_KEY_SPACE:
            return text + "Space";
        case GLFW_KEY_ESCAPE:
            return text + "Esc";
        default:
            return text + "key " + std::to_string(key);
    }
}

std::string shortcut_text(KeyAction action) {
    for (const KeyBinding& b : kKeyBindings)
        if (b.action == action) return chord_text(b.key, b.mods);
    return "";
}

const KeyBinding* find_key_binding(int key, int mods) {
    for (const KeyBinding& b : kKeyBindings)
        if (b.key == key && b.mods == mods) return &b;
    return nullptr;
}

std::vector<BindingHelpRow> binding_help_rows() {
    std::vector<BindingHelpRow> rows;
    for (const PointerBinding& p : kPointerBindings) rows.push_back({p.gesture, p.help});
    // One row per action: a second key of an action joins its row.
    std::vector<KeyAction> row_actions;
    const std::size_t first_key_row = rows.size();
    for (const KeyBinding& b : kKeyBindings) {
        std::size_t i = 0;
        while (i < row_actions.size() && row_actions[i] != b.action) ++i;
        if (i < row_actions.size()) {
            rows[first_key_row + i].keys += ", " + chord_text(b.key, b.mods);
        } else {
            rows.push_back({chord_text(b.key, b.mods), b.help});
            row_actions.push_back(b.action);
        }
    }
    rows.push_back({kDropBinding.gesture, kDropBinding.help});
    return rows;
}

void run_key_action(KeyAction action, KeyActionTargets& t) {
    RenderStyle& style = t.style;
    PanelState& panels = t.panels;
    switch (action) {
        case KeyAction::FitView:
            t.commands.push_back(FitView{});
            break;
        case KeyAction::ToggleWireframe:  // from whatever shows now to the other, explicitly
            t.settings.wireframe = style.wireframe ? WireframeOverlay::Off : WireframeOverlay::On;
            break;
        case KeyAction::ToggleBackFaceColor:
            style.back_face_color = !style.back_face_color;
            break;
        case KeyAction::ToggleFog:
            style.fog = !style.fog;
            break;
        case KeyAction::ToggleSpecular:
            style.specular = !style.specular;
            break;
        case KeyAction::CycleTexture:
            cycle_texture(t);
            break;
        case KeyAction::Screenshot:
            panels.screenshot.open = true;
            break;
        case KeyAction::PrintInfo:
            t.commands.push_back(PrintInfo{});
            break;
        case KeyAction::ToggleLog:
            panels.log_open = !panels.log_open;
            break;
        case KeyAction::Undo:
            t.commands.push_back(Undo{});
            break;
        case KeyAction::Redo:
            t.commands.push_back(Redo{});
            break;
        case KeyAction::ToggleHistory:
            panels.history_open = !panels.history_open;
            break;
        case KeyAction::ToggleMorph:
        case KeyAction::ToggleRecord:
            for (const PanelEntry& entry : t.entries)
                if (entry.open && entry.shortcut == int(action)) *entry.open = !*entry.open;
            break;
        case KeyAction::PlayMorph:
            if (t.has_entry && t.morph.moves) t.commands.push_back(PlayMorph{!t.morph.playing});
            break;
        case KeyAction::OpenFile:
            if (!t.busy)
                panels.file_browser.request(FileBrowserState::Purpose::OpenMesh, t.document_path);
            break;
        case KeyAction::SaveFile:
            if (!t.busy)
                panels.file_browser.request(FileBrowserState::Purpose::SaveMesh, t.document_path);
            break;
        case KeyAction::Quit:
            t.commands.push_back(Quit{});
            break;
        case KeyAction::ToggleHelp:
            panels.help_open = !panels.help_open;
            break;
        case KeyAction::Escape:
            escape(t);
            break;
    }
}

bool dispatch_key(int key, int mods, KeyActionTargets& targets, KeyboardFocus focus) {
    const KeyBinding* binding = find_key_binding(key, mods);
    if (!binding) return false;
    if (!binding->always && focus != KeyboardFocus::Bindings) return false;
    run_key_action(binding->action, targets);
    return true;
}

}  // namespace trilab::viewer
