// The reported widgets; see widgets.h.
#include "app/viewer/widgets.h"

#include <imgui.h>
#include <imgui_internal.h>

#include <cstring>
#include <utility>
#include <vector>

namespace trilab::viewer {
namespace {

WidgetHook widget_hook;                  // tests and scripted clicks only
std::vector<std::string> section_stack;  // the sections and menus open around the widget

std::string current_section() {
    std::string path;
    for (const std::string& s : section_stack) path += (path.empty() ? "" : "/") + s;
    return path;
}

bool last_item_enabled() {
    return (ImGui::GetCurrentContext()->LastItemData.InFlags & ImGuiItemFlags_Disabled) == 0;
}

}  // namespace

void set_widget_hook(WidgetHook hook) {
    widget_hook = std::move(hook);
    section_stack.clear();
}

bool has_widget_hook() {
    return bool(widget_hook);
}

std::string visible_label(const char* label) {
    const char* end = std::strstr(label, "##");
    return end ? std::string(label, end) : std::string(label);
}

void note_widget(const std::string& id, WidgetNote::Kind kind, const char* label) {
    if (!widget_hook) return;
    WidgetNote note;
    note.kind = kind;
    note.id = id;
    note.label = label ? visible_label(label) : id;
    note.section = current_section();
    note.imgui_id = ImGui::GetItemID();
    const ImVec2 a = ImGui::GetItemRectMin(), b = ImGui::GetItemRectMax();
    note.x0 = a.x;
    note.y0 = a.y;
    note.x1 = b.x;
    note.y1 = b.y;
    note.enabled = last_item_enabled();
    // Whole inside the part of its window that shows content (a press on a half-hidden widget
    // may land on the window's padding).
    const ImRect inner = ImGui::GetCurrentWindow()->ClipRect;
    note.visible =
        a.y >= inner.Min.y && b.y <= inner.Max.y && a.x >= inner.Min.x - 1 && a.x < inner.Max.x;
    note.window_x0 = inner.Min.x;
    note.window_y0 = inner.Min.y;
    note.window_x1 = inner.Max.x;
    note.window_y1 = inner.Max.y;
    widget_hook(note);
}

void note_widget_rect(const std::string& id, float x0, float y0, float x1, float y1) {
    if (!widget_hook) return;
    WidgetNote note;
    note.id = note.label = id;
    note.section = current_section();
    note.x0 = x0;
    note.y0 = y0;
    note.x1 = x1;
    note.y1 = y1;
    widget_hook(note);
}

WidgetSection::WidgetSection(const char* name, bool id_scope) : id_scope_(id_scope) {
    section_stack.push_back(visible_label(name));
    if (id_scope_) ImGui::PushID(name);
}

WidgetSection::~WidgetSection() {
    if (id_scope_) ImGui::PopID();
    section_stack.pop_back();
}

bool button(const char* label, const char* id) {
    const bool pressed = ImGui::Button(label);
    note_widget(id ? id : visible_label(label), WidgetNote::Kind::Button, label);
    return pressed;
}

bool button(const char* label, float width, const char* id) {
    const bool pressed = ImGui::Button(label, ImVec2(width, 0.0f));
    note_widget(id ? id : visible_label(label), WidgetNote::Kind::Button, label);
    return pressed;
}

bool checkbox(const char* label, bool* value, const char* id) {
    const bool pressed = ImGui::Checkbox(label, value);
    note_widget(id ? id : visible_label(label), WidgetNote::Kind::Checkbox, label);
    return pressed;
}

bool menu_item(const char* label, const char* shortcut, bool selected, bool enabled) {
    const bool pressed = ImGui::MenuItem(label, shortcut, selected, enabled);
    note_widget(visible_label(label), WidgetNote::Kind::MenuItem, label);
    return pressed;
}

bool menu_item(const char* label, const char* shortcut, bool* selected, bool enabled) {
    const bool pressed = ImGui::MenuItem(label, shortcut, selected, enabled);
    note_widget(visible_label(label), WidgetNote::Kind::MenuItem, label);
    return pressed;
}

bool begin_menu(const char* label, bool enabled) {
    const bool open = ImGui::BeginMenu(label, enabled);
    // A closed menu's header keeps the tests' old name "menu:LABEL".
    note_widget((open ? "" : "menu:") + visible_label(label), WidgetNote::Kind::Menu, label);
    if (open) section_stack.push_back(visible_label(label));
    return open;
}

void end_menu() {
    section_stack.pop_back();
    ImGui::EndMenu();
}

}  // namespace trilab::viewer
