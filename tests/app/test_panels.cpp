// The operation panels drawn under an ImGui context with no window and no GL (the idea of
// Polyscope's mock backend): the mouse is moved and pressed through ImGuiIO, the widgets are
// found through the panels' test hook (set_widget_rect_hook), and the tests assert the typed
// commands the panels queue.
#include <imgui.h>
#include <catch2/catch.hpp>

#include <map>
#include <string>
#include <variant>

#include "app/viewer/panels.h"
#include "core/fairing.h"

using namespace trilab;
using namespace trilab::viewer;

namespace {

struct Rect {
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
        unsigned char* pixels = nullptr;
        int w = 0, h = 0;
        io.Fonts->GetTexDataAsRGBA32(&pixels, &w, &h);
        set_widget_rect_hook([this](const std::string& id, float x0, float y0, float x1, float y1) {
            rects_[id] = Rect{x0, y0, x1, y1};
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
    Rect rect(const std::string& id) const {
        const auto it = rects_.find(id);
        REQUIRE(it != rects_.end());
        return it->second;
    }

private:
    ImGuiContext* ctx_ = nullptr;
    std::map<std::string, Rect> rects_;
};

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
    const auto draw = [&] { subdivision_window(panels, morph, history, false, 0.0, commands); };
    ui.frame(draw);
    ui.frame(draw);  // auto-resized windows take their size on the second frame
    REQUIRE(ui.has("scheme"));
    REQUIRE(ui.has("iterations"));
    const Rect apply = ui.rect("Subdivide");
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
    const auto draw = [&] { decimation_window(panels, morph, history, false, 0.0, 0, commands); };
    ui.frame(draw);
    ui.frame(draw);
    const Rect percent = ui.rect("percent");
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
    const auto draw = [&] { decimation_window(panels, morph, history, false, 0.0, 0, commands); };
    ui.frame(draw);
    ui.frame(draw);
    const Rect percent = ui.rect("percent");
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
    const auto draw = [&] { fairing_window(panels, morph, history, true, false, 0.0, commands); };
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
    const Rect volume = ui.rect("preserve-volume");
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
    const auto draw = [&] { tools_window(panels, false, commands); };
    ui.frame(draw);
    ui.frame(draw);
    CHECK_FALSE(ui.has("Cancel"));
    panels.tools.previewing = true;
    ui.frame(draw);
    const Rect cancel = ui.rect("Cancel");
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
    const auto draw = [&] { fairing_window(panels, morph, history, true, false, 0.0, commands); };
    ui.frame(draw);
    ui.frame(draw);
    CHECK(ui.has("stable-step"));
    CHECK_FALSE(ui.has("unstable"));  // the default step is below the limit
    panels.fairing.op.value("step").x = 20;
    ui.frame(draw);
    ui.frame(draw);
    REQUIRE(ui.has("unstable"));
    const Rect use_implicit = ui.rect("Use implicit integration");
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
