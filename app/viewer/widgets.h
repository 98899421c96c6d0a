#pragma once
// The pressable widgets of the panels and menus, reported by their visible labels.
//
// Every button, check box, menu, menu item and sidebar section header is drawn through these
// wrappers, which report the widget (its visible label, the section or menu it is in, its
// ImGui ID and its rectangle) to one hook. Two users read the hook: the headless panel tests,
// which find and press widgets under an ImGui context without a window, and the viewer's
// `--click "SECTION/LABEL"`, which presses what a user would press. Sections give their
// bodies an ID scope of their own (WidgetSection), so that two sections may use the same
// labels ("iterations", "Cancel") without sharing a widget.
#include <functional>
#include <string>

namespace trilab::viewer {

/// One widget drawn in this frame.
struct WidgetNote {
    enum class Kind { Button, Checkbox, Menu, MenuItem, Header, Other };
    Kind kind = Kind::Other;
    std::string id;       ///< the tests' name (a parameter's name, or the label)
    std::string label;    ///< the visible label (the text before "##")
    std::string section;  ///< where it is: "Fairing", "File", "Rendering/Texture"; "" at the top
    unsigned imgui_id = 0;
    float x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    bool enabled = true;  ///< false: drawn disabled (a press does nothing)
    /// Whether it is inside its window's visible part (false: scrolled out of a sidebar), and
    /// that window's rectangle (a scripted click scrolls there with the wheel first).
    bool visible = true;
    float window_x0 = 0, window_y0 = 0, window_x1 = 0, window_y1 = 0;

    /// "SECTION/LABEL" (or "LABEL" at the top): what `--click` names.
    std::string path() const { return section.empty() ? label : section + "/" + label; }
    bool pressable() const { return kind != Kind::Other; }
};

/// Tests and scripted clicks only: called for each widget noted (nullptr: none).
using WidgetHook = std::function<void(const WidgetNote&)>;
void set_widget_hook(WidgetHook hook);
bool has_widget_hook();

/// The visible part of an ImGui label: "Cancel##lod" -> "Cancel".
std::string visible_label(const char* label);

/// Reports the last item to the hook under `id` (nothing without a hook).
void note_widget(const std::string& id, WidgetNote::Kind kind = WidgetNote::Kind::Other,
                 const char* label = nullptr);
/// Reports a rectangle that is not an ImGui item (plots and legends name their parts).
void note_widget_rect(const std::string& id, float x0, float y0, float x1, float y1);

/// The section or menu the widgets drawn now belong to (a stack: menus nest).
class WidgetSection {
public:
    /// `id_scope`: also push an ImGui ID scope named `name` (a sidebar section's body).
    WidgetSection(const char* name, bool id_scope);
    ~WidgetSection();
    WidgetSection(const WidgetSection&) = delete;
    WidgetSection& operator=(const WidgetSection&) = delete;

private:
    bool id_scope_;
};

/// ImGui::Button, reported. `id` defaults to the visible label.
bool button(const char* label, const char* id = nullptr);
/// A button `width` pixels wide (0: fit the label), so that a label that changes (Animate,
/// Stop) moves nothing beside it.
bool button(const char* label, float width, const char* id = nullptr);
/// ImGui::Checkbox, reported.
bool checkbox(const char* label, bool* value, const char* id = nullptr);
/// ImGui::MenuItem (with an optional shortcut text), reported.
bool menu_item(const char* label, const char* shortcut = nullptr, bool selected = false,
               bool enabled = true);
bool menu_item(const char* label, const char* shortcut, bool* selected, bool enabled = true);
/// ImGui::BeginMenu, reported; while it is open the items drawn are in its section. Call
/// end_menu() when it returns true.
bool begin_menu(const char* label, bool enabled = true);
void end_menu();

}  // namespace trilab::viewer
