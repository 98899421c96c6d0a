// The operation panels drawn under an ImGui context with no window and no GL (the idea of
// Polyscope's mock backend): the mouse is moved and pressed through ImGuiIO, the widgets are
// found through the panels' test hook (set_widget_rect_hook), and the tests assert the typed
// commands the panels queue. The sections are drawn in the real sidebar (layout.h), whose
// regions are checked here too.
#include <imgui.h>
#include <catch2/catch.hpp>

#include <cmath>
#include <map>
#include <string>
#include <variant>

#include "app/viewer/panels.h"
#include "core/fairing.h"
#include "core/generators.h"

using namespace trilab;
using namespace trilab::viewer;

namespace {

struct Box {
    float x0, y0, x1, y1;
};

/// An ImGui context of its own, 1280 x 800, fonts built (no texture upload is needed).
class Ui {
public:
    Ui() {
        ctx_ = ImGui::CreateContext();
        ImGuiIO& io = ImGui::GetIO();
        io.DisplaySize = ImVec2(1280, 800);
        io.IniFilename = nullptr;
        io.BackendFlags |= ImGuiBackendFlags_HasMouseCursors;  // resizing from window edges
        unsigned char* pixels = nullptr;
        int w = 0, h = 0;
        io.Fonts->GetTexDataAsRGBA32(&pixels, &w, &h);
        set_widget_rect_hook([this](const std::string& id, float x0, float y0, float x1, float y1) {
            rects_[id] = Box{x0, y0, x1, y1};
        });
    }
    ~Ui() {
        set_widget_rect_hook(nullptr);
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
    Box rect(const std::string& id) const {
        const auto it = rects_.find(id);
        REQUIRE(it != rects_.end());
        return it->second;
    }

private:
    ImGuiContext* ctx_ = nullptr;
    std::map<std::string, Box> rects_;
};

/// Draws `body` in the sidebar of the 1280 x 800 layout, as the viewer does.
template <class Body>
void in_sidebar(LayoutState& sizes, Body body) {
    LayoutInput in;
    in.width = 1280;
    in.height = 800;
    in.em = ImGui::GetFontSize();
    in.frame_height = ImGui::GetFrameHeight();
    const Layout layout = compute_layout(in, sizes);
    if (begin_sidebar(layout.sidebar, sizes)) body();
    end_region();
}

template <class T>
std::vector<const T*> commands_of(const CommandQueue& q) {
    std::vector<const T*> out;
    for (const Command& c : q)
        if (const T* t = std::get_if<T>(&c)) out.push_back(t);
    return out;
}

}  // namespace

TEST_CASE("the Subdivision panel's Subdivide queues the typed operation it shows", "[panels]") {
    Ui ui;
    PanelState panels;
    MorphState morph;
    History history;
    panels.subdivision.open = true;
    CommandQueue commands;
    const auto draw = [&] {
        in_sidebar(panels.layout,
                   [&] { subdivision_section(panels, morph, history, false, 0.0, commands); });
    };
    ui.frame(draw);
    ui.frame(draw);  // auto-resized windows take their size on the second frame
    REQUIRE(ui.has("scheme"));
    REQUIRE(ui.has("iterations"));
    const Box apply = ui.rect("Subdivide");
    commands.clear();
    ui.click(draw, (apply.x0 + apply.x1) / 2, (apply.y0 + apply.y1) / 2);
    const auto applied = commands_of<ApplyOperation>(commands);
    REQUIRE(applied.size() == 1);
    CHECK(applied[0]->op == make_operation("subdivide"));
    CHECK(commands_of<PreviewOperation>(commands).empty());  // nothing changed
}

TEST_CASE("dragging a slider previews live with the new typed value", "[panels]") {
    Ui ui;
    PanelState panels;
    MorphState morph;
    History history;
    panels.decimation.open = true;
    CommandQueue commands;
    const auto draw = [&] {
        in_sidebar(panels.layout,
                   [&] { decimation_section(panels, morph, history, false, 0.0, 0, commands); });
    };
    ui.frame(draw);
    ui.frame(draw);
    const Box percent = ui.rect("percent");
    commands.clear();
    // Press at the slider's left end: the value jumps to the slider's minimum while held.
    ui.frame(draw, percent.x0 + 1, (percent.y0 + percent.y1) / 2, false);
    ui.frame(draw, percent.x0 + 1, (percent.y0 + percent.y1) / 2, true);
    const auto previews = commands_of<PreviewOperation>(commands);
    REQUIRE(previews.size() == 1);
    CHECK(previews[0]->op.value("percent").x == Approx(1.0));
    CHECK(previews[0]->op.value("percent").given);
    CHECK(previews[0]->op.value("cost").x == make_operation("decimate").value("cost").x);
    CHECK(commands_of<ApplyOperation>(commands).empty());
}

TEST_CASE("slow panels preview once, when the drag is released", "[panels]") {
    Ui ui;
    PanelState panels;
    MorphState morph;
    History history;
    panels.decimation.open = true;
    panels.decimation.live = false;  // the viewer found the last preview over the budget
    CommandQueue commands;
    const auto draw = [&] {
        in_sidebar(panels.layout,
                   [&] { decimation_section(panels, morph, history, false, 0.0, 0, commands); });
    };
    ui.frame(draw);
    ui.frame(draw);
    const Box percent = ui.rect("percent");
    const float y = (percent.y0 + percent.y1) / 2;
    commands.clear();
    ui.frame(draw, percent.x0 + 1, y, false);
    ui.frame(draw, percent.x0 + 1, y, true);
    ui.frame(draw, percent.x0 + 20, y, true);  // dragging
    CHECK(commands_of<PreviewOperation>(commands).empty());
    ui.frame(draw, percent.x0 + 20, y, false);  // released
    ui.frame(draw, percent.x0 + 20, y, false);
    const auto previews = commands_of<PreviewOperation>(commands);
    REQUIRE(previews.size() == 1);
    CHECK(previews[0]->op.value("percent").x > 1.0);
}

TEST_CASE("the Fairing panel shows only the parameters that apply", "[panels]") {
    Ui ui;
    PanelState panels;
    MorphState morph;
    History history;
    panels.fairing.open = true;
    CommandQueue commands;
    const auto draw = [&] {
        in_sidebar(panels.layout,
                   [&] { fairing_section(panels, morph, history, true, false, 0.0, commands); });
    };
    ui.frame(draw);
    ui.frame(draw);
    CHECK(ui.has("step"));
    CHECK(ui.has("integration"));
    CHECK_FALSE(ui.has("lambda"));
    CHECK_FALSE(ui.has("mu"));
    panels.fairing.op.value("operator").x = int(FairingOperator::Taubin);
    ui.frame(draw);
    CHECK_FALSE(ui.has("step"));
    CHECK_FALSE(ui.has("integration"));
    CHECK(ui.has("lambda"));
    CHECK(ui.has("mu"));
    // A click on "preserve volume" (a closed mesh) previews with the flag set.
    const Box volume = ui.rect("preserve-volume");
    commands.clear();
    ui.click(draw, volume.x0 + 5, (volume.y0 + volume.y1) / 2);
    const auto previews = commands_of<PreviewOperation>(commands);
    REQUIRE(previews.size() == 1);
    CHECK(previews[0]->op.value("preserve-volume").x == 1);
    CHECK(previews[0]->op.text().find("--preserve-volume") != std::string::npos);
}

TEST_CASE("Cancel shows while a preview is up and queues CancelPreview", "[panels]") {
    Ui ui;
    PanelState panels;
    panels.tools.open = true;
    CommandQueue commands;
    const auto draw = [&] {
        in_sidebar(panels.layout, [&] { tools_section(panels, false, commands); });
    };
    ui.frame(draw);
    ui.frame(draw);
    CHECK_FALSE(ui.has("Cancel"));
    panels.tools.previewing = true;
    ui.frame(draw);
    const Box cancel = ui.rect("Cancel");
    commands.clear();
    ui.click(draw, (cancel.x0 + cancel.x1) / 2, (cancel.y0 + cancel.y1) / 2);
    CHECK(commands_of<CancelPreview>(commands).size() == 1);
    CHECK(commands_of<ApplyOperation>(commands).empty());
}

TEST_CASE("the Fairing panel marks a step above the stable limit and offers implicit", "[panels]") {
    Ui ui;
    PanelState panels;
    MorphState morph;
    History history;
    panels.fairing.open = true;
    panels.fairing.max_stable_step = 1.35;
    CommandQueue commands;
    const auto draw = [&] {
        in_sidebar(panels.layout,
                   [&] { fairing_section(panels, morph, history, true, false, 0.0, commands); });
    };
    ui.frame(draw);
    ui.frame(draw);
    CHECK(ui.has("stable-step"));
    CHECK_FALSE(ui.has("unstable"));  // the default step is below the limit
    panels.fairing.op.value("step").x = 20;
    ui.frame(draw);
    ui.frame(draw);
    REQUIRE(ui.has("unstable"));
    const Box use_implicit = ui.rect("Use implicit integration");
    commands.clear();
    ui.click(draw, (use_implicit.x0 + use_implicit.x1) / 2,
             (use_implicit.y0 + use_implicit.y1) / 2);
    const auto previews = commands_of<PreviewOperation>(commands);
    REQUIRE_FALSE(previews.empty());
    CHECK(int(previews.back()->op.value("integration").x) == int(Integration::Implicit));
    CHECK(previews.back()->op.value("step").x == 20);
    ui.frame(draw);
    CHECK_FALSE(ui.has("unstable"));  // implicit: any step is stable
}

namespace {

/// The layout rule on compute_layout's regions: inside the display, whole pixels, no two
/// overlapping; the view keeps a third of the width and half of the height between the bars.
void check_regions(const LayoutInput& in, const Layout& l) {
    const std::vector<std::pair<const char*, Rect>> regions = {
        {"menu", l.menu},     {"sidebar", l.sidebar}, {"status", l.status}, {"log", l.log},
        {"legend", l.legend}, {"history", l.history}, {"view", l.view}};
    for (const auto& [name, r] : regions) {
        if (r.empty()) continue;
        INFO(name << " " << r.x << " " << r.y << " " << r.w << " " << r.h);
        CHECK(r.x >= 0);
        CHECK(r.y >= 0);
        CHECK(r.right() <= in.width);
        CHECK(r.bottom() <= in.height);
        CHECK(r.x == std::floor(r.x));
        CHECK(r.w == std::floor(r.w));
        CHECK(r.h == std::floor(r.h));
    }
    for (std::size_t i = 0; i < regions.size(); ++i)
        for (std::size_t j = i + 1; j < regions.size(); ++j) {
            const Rect &a = regions[i].second, &b = regions[j].second;
            if (a.empty() || b.empty()) continue;
            INFO(regions[i].first << " and " << regions[j].first);
            const bool apart =
                a.right() <= b.x || b.right() <= a.x || a.bottom() <= b.y || b.bottom() <= a.y;
            CHECK(apart);
        }
    CHECK(l.view.w >= in.width / 3);
    CHECK(l.view.h >= 0.5f * (in.height - l.menu.h - l.status.h) - 1);
    CHECK(l.legend.w <= l.legend_max_width);
}

}  // namespace

TEST_CASE("the layout's regions tile the window at every size, scale and panel set", "[layout]") {
    const float sizes[][2] = {{1280, 720}, {1920, 1080}, {2560, 1440}, {1400, 900}, {800, 600}};
    const float scales[] = {1.0f, 2.0f};
    // The user's sizes: the defaults, dragged to nothing, dragged past the window.
    const float user[] = {0.0f, 1.0f, 1e6f};
    for (const auto& size : sizes)
        for (float scale : scales)
            for (int panels = 0; panels < 16; ++panels)
                for (float u : user) {
                    LayoutInput in;
                    in.width = size[0];
                    in.height = size[1];
                    in.em = 13.0f * scale;
                    in.frame_height = 19.0f * scale;
                    in.history = panels & 1;
                    in.log = panels & 2;
                    in.legend = panels & 4;
                    in.sidebar = !(panels & 8);
                    LayoutState state;
                    state.sidebar_width = state.history_width = state.log_height = u;
                    state.legend_width = state.legend_height = u;
                    INFO(size[0] << " x " << size[1] << " scale " << scale << " panels " << panels
                                 << " user size " << u);
                    const Layout l = compute_layout(in, state);
                    check_regions(in, l);
                    CHECK(l.history.empty() == !in.history);
                    CHECK(l.log.empty() == !in.log);
                    CHECK(l.legend.empty() == !in.legend);
                    CHECK(l.sidebar.empty() == !in.sidebar);
                    // The clamped sizes are kept: a second pass gives the same regions.
                    const Layout again = compute_layout(in, state);
                    CHECK(again.view.x == l.view.x);
                    CHECK(again.view.w == l.view.w);
                    CHECK(again.view.h == l.view.h);
                }
}

TEST_CASE("dragging the sidebar's edge resizes it and the view follows", "[layout]") {
    Ui ui;
    PanelState panels;
    CommandQueue commands;
    panels.tools.open = true;
    const auto draw = [&] {
        in_sidebar(panels.layout, [&] { tools_section(panels, false, commands); });
    };
    ui.frame(draw);
    ui.frame(draw);
    const float before = panels.layout.sidebar_width;
    REQUIRE(before > 0);
    const float y = 400;
    ui.frame(draw, before - 1, y, false);  // hover the right edge
    ui.frame(draw, before - 1, y, true);
    ui.frame(draw, before + 60, y, true);
    ui.frame(draw, before + 120, y, true);
    ui.frame(draw, before + 120, y, false);
    ui.frame(draw);
    CHECK(panels.layout.sidebar_width == Approx(before + 121).margin(2));
    LayoutInput in;
    in.width = 1280;
    in.height = 800;
    in.em = ImGui::GetFontSize();
    const Layout l = compute_layout(in, panels.layout);
    CHECK(l.view.x == panels.layout.sidebar_width);
}

TEST_CASE("a section opened elsewhere shows its body; its header closes it", "[layout]") {
    Ui ui;
    PanelState panels;
    CommandQueue commands;
    const auto draw = [&] {
        in_sidebar(panels.layout, [&] { tools_section(panels, false, commands); });
    };
    ui.frame(draw);
    CHECK_FALSE(ui.has("Apply"));  // collapsed: only the header
    REQUIRE(ui.has("section:Tools: add noise"));
    panels.tools.open = true;  // the menu item, or --show tools
    ui.frame(draw);
    CHECK(ui.has("Apply"));
    const Box header = ui.rect("section:Tools: add noise");
    ui.click(draw, (header.x0 + header.x1) / 2, (header.y0 + header.y1) / 2);
    CHECK_FALSE(panels.tools.open);
    ui.frame(draw);
    CHECK_FALSE(ui.has("Apply"));
}

TEST_CASE("the morph controls offer no animation for a state that moves nothing", "[panels]") {
    Ui ui;
    PanelState panels;
    MorphState morph;
    History history;
    HalfedgeMesh a = make_default_model();
    history.reset(a, "Load a.off");
    history.push("Load b.off", "", 0.0, {a},
                 {MorphCorrespondence{MorphCorrespondence::Kind::FromEarlier, a.positions()}});
    panels.morph_open = true;
    CommandQueue commands;
    const auto draw = [&] {
        in_sidebar(panels.layout, [&] { morph_section(panels, morph, history, 0.0); });
    };
    ui.frame(draw);
    CHECK(ui.has("Animate"));
    morph.moves = false;  // the viewer's finding for a load
    ui.frame(draw);
    CHECK_FALSE(ui.has("Animate"));
}

TEST_CASE("the unsaved-changes question offers Save as", "[panels]") {
    Ui ui;
    UnsavedPrompt prompt;
    prompt.open_requested = true;
    prompt.quitting = true;
    prompt.document_path = "/tmp/original.off";
    CommandQueue commands;
    const auto draw = [&] { unsaved_changes_popup(prompt, commands); };
    ui.frame(draw);
    ui.frame(draw);
    const Box save_as = ui.rect("Save as...");
    commands.clear();
    ui.click(draw, (save_as.x0 + save_as.x1) / 2, (save_as.y0 + save_as.y1) / 2);
    CHECK(commands_of<SaveAsAndContinue>(commands).size() == 1);
    CHECK(commands_of<SaveAndContinue>(commands).empty());
}

TEST_CASE("Esc closes the key bindings", "[panels]") {
    Ui ui;
    PanelState panels;
    panels.help_open = true;
    ImGuiIO& io = ImGui::GetIO();
    io.KeyMap[ImGuiKey_Escape] = 256;  // any free slot of KeysDown
    const auto draw = [&] { help_window(panels); };
    ui.frame(draw);
    ui.frame(draw);
    REQUIRE(panels.help_open);
    io.KeysDown[256] = true;
    ui.frame(draw);
    io.KeysDown[256] = false;
    ui.frame(draw);
    CHECK_FALSE(panels.help_open);
}
