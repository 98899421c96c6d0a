// Scripted runs (script_driver.h): --click.
//
// --click "SECTION/LABEL": every pressable widget reports itself through the widget hook
// (widgets.h) with its visible label and the section or menu it is in. A click finds its
// widget among those of the last frame; where it is not drawn because its section or menu is
// closed, the header of the deepest open part of its path is pressed first (a sidebar section,
// a menu, a submenu), and the search goes on in the next frame. The press itself is the
// mouse's: moved over the widget for a frame, pressed for a frame, released for a frame (the
// frames ImGui needs to see a click), set through ImGuiIO after the backend has read the real
// mouse.
#include "app/viewer/script_driver.h"

#include <imgui.h>

#include <algorithm>
#include <cfloat>
#include <cstdio>
#include <string>
#include <vector>

namespace trilab::viewer {
namespace {

constexpr int kMaxOpenings = 4;  ///< headers pressed on the way to one widget

/// A label as a script names it: "Save as..." is "Save as".
std::string script_label(std::string label) {
    while (!label.empty() && (label.back() == '.' || label.back() == ' ')) label.pop_back();
    return label;
}

std::string script_path(const WidgetNote& n) {
    return n.section.empty() ? script_label(n.label) : n.section + "/" + script_label(n.label);
}

/// The pressable widgets of `notes` at `path`, drawn enabled or not.
std::vector<const WidgetNote*> widgets_at(const std::vector<WidgetNote>& notes,
                                          const std::string& path) {
    std::vector<const WidgetNote*> out;
    for (const WidgetNote& n : notes)
        if (n.pressable() && script_path(n) == script_label(path)) out.push_back(&n);
    return out;
}

/// The header (a closed section or menu) that opens the deepest part of `path` that is drawn.
const WidgetNote* opener_for(const std::vector<WidgetNote>& notes, const std::string& path) {
    const WidgetNote* best = nullptr;
    std::size_t best_length = 0;
    for (const WidgetNote& n : notes) {
        if (n.kind != WidgetNote::Kind::Header && n.kind != WidgetNote::Kind::Menu) continue;
        const std::string p = script_path(n);
        // An open section or menu has widgets drawn in it: pressing it again would close it.
        const bool open = std::any_of(notes.begin(), notes.end(), [&](const WidgetNote& m) {
            return m.section == p || m.section.compare(0, p.size() + 1, p + "/") == 0;
        });
        if (open) continue;
        if (path.size() > p.size() && path.compare(0, p.size(), p) == 0 && path[p.size()] == '/' &&
            p.size() > best_length) {
            best = &n;
            best_length = p.size();
        }
    }
    return best;
}

}  // namespace

void ScriptDriver::fail_click(const std::string& why) {
    const std::string text = "--click \"" + options_.clicks[clicks_.next] + "\": " + why;
    std::fprintf(stderr, "trilab: %s\n", text.c_str());
    session_.notify_error(text);
    exit_status_ = 1;
    quit_ = true;
    clicks_.next = options_.clicks.size();  // no further clicks
}

namespace {
constexpr int kMaxScrolls = 200;  ///< wheel steps a click takes at most to reach its target
}  // namespace

void ScriptDriver::drive_clicks() {
    ScriptedClicks& c = clicks_;
    c.shown.swap(c.drawing);
    c.drawing.clear();
    if (!clicks_pending() || !ready() || session_.busy() || c.shown.empty()) return;
    ImGuiIO& io = ImGui::GetIO();
    const std::string& path = options_.clicks[c.next];
    switch (c.phase) {
        case 0: {
            const std::vector<const WidgetNote*> found = widgets_at(c.shown, path);
            const WidgetNote* target = nullptr;
            if (found.size() > 1) {
                fail_click("more than one widget has that label there (" +
                           std::to_string(found.size()) + ")");
                return;
            }
            if (found.size() == 1) {
                target = found[0];
                c.opening = false;
            } else if (const WidgetNote* opener = opener_for(c.shown, path);
                       opener && c.openings < kMaxOpenings) {
                target = opener;
                c.opening = true;
                ++c.openings;
            } else {
                // Say what is there, so that the script can be corrected.
                const std::size_t slash = path.rfind('/');
                const std::string section = slash == std::string::npos ? "" : path.substr(0, slash);
                std::string there;
                for (const WidgetNote& n : c.shown)
                    if (n.pressable() && n.section == section)
                        there += (there.empty() ? "" : ", ") + script_label(n.label);
                fail_click("no such widget" + (there.empty()
                                                   ? std::string(" (nothing is drawn there)")
                                                   : " (there: " + there + ")"));
                return;
            }
            if (!target->enabled) {
                // The widgets are last frame's: a job that ended since (or the morph it
                // started) may have enabled it by now. Fail only once it stays disabled.
                constexpr int kDisabledFrames = 10;
                if (++c.disabled_frames < kDisabledFrames) {
                    context_.keep_drawing(2);
                    return;
                }
                fail_click("'" + script_path(*target) + "' is disabled now");
                return;
            }
            c.disabled_frames = 0;
            if (!target->visible && c.scrolls < kMaxScrolls) {
                // Scrolled out of its window (a long sidebar): the wheel over that window
                // brings it in, as a user would scroll, then it is looked for again.
                ++c.scrolls;
                io.MousePos = ImVec2(0.5f * (target->window_x0 + target->window_x1),
                                     0.5f * (target->window_y0 + target->window_y1));
                io.MouseWheel += target->y1 > target->window_y1 ? -1.0f : 1.0f;
                context_.keep_drawing(2);
                return;
            }
            c.target = script_path(*target);
            c.x = 0.5f * (target->x0 + target->x1);
            c.y = 0.5f * (target->y0 + target->y1);
            c.queued.clear();
            c.phase = 1;
            io.MousePos = ImVec2(c.x, c.y);  // hover first: ImGui presses what it hovers
            io.MouseDown[0] = false;
            break;
        }
        case 1:
        case 2: {
            // Follow the target: the layout may move between frames (a button's text changes
            // as a playback ends); a target gone or disabled is looked for again.
            const std::vector<const WidgetNote*> now = widgets_at(c.shown, c.target);
            if (now.size() != 1 || !now[0]->enabled) {
                io.MouseDown[0] = false;
                c.phase = 0;
                break;
            }
            c.x = 0.5f * (now[0]->x0 + now[0]->x1);
            c.y = 0.5f * (now[0]->y0 + now[0]->y1);
            io.MousePos = ImVec2(c.x, c.y);
            io.MouseDown[0] = c.phase == 1;
            ++c.phase;
            break;
        }
        default: {
            io.MousePos = ImVec2(-FLT_MAX, -FLT_MAX);  // away, so nothing stays hovered
            io.MouseDown[0] = false;
            c.phase = 0;
            if (c.opening) break;  // look for the widget again, now that more is drawn
            std::string did;
            for (const std::string& q : c.queued) did += (did.empty() ? "" : ", ") + q;
            session_.log().info("click " + path + ": " +
                                (did.empty() ? std::string("pressed (no command; a panel setting)")
                                             : "queued " + did));
            ++c.next;
            c.openings = 0;
            c.scrolls = 0;
            break;
        }
    }
    context_.keep_drawing(2);
}

void ScriptDriver::note_commands() {
    ScriptedClicks& c = clicks_;
    if (!clicks_pending() || (c.phase != 2 && c.phase != 3)) return;
    for (const Command& command : context_.commands) c.queued.push_back(command_name(command));
}

}  // namespace trilab::viewer
