#pragma once
// The panel tests' ImGui context without a window or GL (the idea of Polyscope's mock
// backend): the mouse is moved and pressed through ImGuiIO, the widgets are found through the
// widget hook (app/viewer/widgets.h), and the tests assert the typed commands the panels queue.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <catch2/catch.hpp>

#include <map>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "app/viewer/panels.h"

namespace trilab::viewer::testing {

struct Box {
    float x0, y0, x1, y1;
};

/// An ImGui context of its own (1280 x 800 unless told), fonts built (no texture upload).
class Ui {
public:
    explicit Ui(float width = 1280, float height = 800) {
        ctx_ = ImGui::CreateContext();
        ImGuiIO& io = ImGui::GetIO();
        io.DisplaySize = ImVec2(width, height);
        io.IniFilename = nullptr;
        io.BackendFlags |= ImGuiBackendFlags_HasMouseCursors;  // resizing from window edges
        unsigned char* pixels = nullptr;
        int w = 0, h = 0;
        io.Fonts->GetTexDataAsRGBA32(&pixels, &w, &h);
        set_widget_hook([this](const WidgetNote& note) {
            rects_[note.id] = Box{note.x0, note.y0, note.x1, note.y1};
            notes_.push_back(note);
        });
    }
    ~Ui() {
        set_widget_hook(nullptr);
        ImGui::DestroyContext(ctx_);
    }
    Ui(const Ui&) = delete;
    Ui& operator=(const Ui&) = delete;

    /// One frame: the mouse at (x, y), the left button down or not; `draw` draws the panels.
    template <class Draw>
    void frame(Draw draw, float x = -1, float y = -1, bool down = false) {
        ImGuiIO& io = ImGui::GetIO();
        io.DeltaTime = 1.0f / 60.0f;
        io.MousePos = ImVec2(x, y);
        io.MouseDown[0] = down;
        rects_.clear();
        notes_.clear();
        ImGui::NewFrame();
        draw();
        ImGui::Render();
    }
    /// Presses and releases the left button at (x, y) over three frames.
    template <class Draw>
    void click(Draw draw, float x, float y) {
        frame(draw, x, y, false);
        frame(draw, x, y, true);
        frame(draw, x, y, false);
    }
    bool has(const std::string& id) const { return rects_.count(id) > 0; }
    /// Every rectangle whose id starts with `prefix`, with its id.
    std::vector<std::pair<std::string, Box>> with_prefix(const std::string& prefix) const {
        std::vector<std::pair<std::string, Box>> out;
        for (const auto& [id, r] : rects_)
            if (id.rfind(prefix, 0) == 0) out.emplace_back(id, r);
        return out;
    }
    Box rect(const std::string& id) const {
        const auto it = rects_.find(id);
        REQUIRE(it != rects_.end());
        return it->second;
    }

    /// Every widget noted in the last frame, in drawing order.
    const std::vector<WidgetNote>& notes() const { return notes_; }

private:
    ImGuiContext* ctx_ = nullptr;
    std::map<std::string, Box> rects_;
    std::vector<WidgetNote> notes_;
};

inline bool overlap(const Box& a, const Box& b) {
    return a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1;
}

/// Asserts that no two of the rectangles overlap.
inline void require_disjoint(const std::vector<std::pair<std::string, Box>>& rects) {
    for (std::size_t i = 0; i < rects.size(); ++i)
        for (std::size_t j = i + 1; j < rects.size(); ++j) {
            INFO(rects[i].first << " and " << rects[j].first);
            REQUIRE_FALSE(overlap(rects[i].second, rects[j].second));
        }
}

/// The legend window as the viewer draws it, for `colors`.
inline void draw_legend(const VertexColors& colors, ColoringOptions& options,
                        RenderStyle* style_out = nullptr) {
    RenderStyle local;
    RenderStyle& style = style_out ? *style_out : local;
    LegendSlot slot;
    slot.right = 1280;
    slot.bottom = 800;
    slot.max_width = 600;
    slot.max_height = 400;
    color_legend(colors, options, style, slot);
}

/// Draws `body` in the sidebar of the display's layout, as the viewer does.
template <class Body>
void in_sidebar(LayoutState& sizes, Body body) {
    LayoutInput in;
    in.width = ImGui::GetIO().DisplaySize.x;
    in.height = ImGui::GetIO().DisplaySize.y;
    in.em = ImGui::GetFontSize();
    in.frame_height = ImGui::GetFrameHeight();
    const Layout layout = compute_layout(in, sizes);
    if (begin_sidebar(layout.sidebar, sizes)) body();
    end_region();
}

/// The sidebar's context for a closed mesh (volume preservation applies).
inline SidebarContext closed_mesh() {
    SidebarContext context;
    context.closed = true;
    return context;
}

template <class T>
std::vector<const T*> commands_of(const CommandQueue& q) {
    std::vector<const T*> out;
    for (const Command& c : q)
        if (const T* t = std::get_if<T>(&c)) out.push_back(t);
    return out;
}

}  // namespace trilab::viewer::testing
