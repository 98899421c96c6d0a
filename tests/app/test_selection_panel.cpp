// The Selection section (issue 26) under an ImGui context without a window: what it offers
// depends on the document (a selection, a pick, a colouring with values), and its buttons queue
// the selection commands with the section's settings.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <catch2/catch.hpp>

#include <string>

#include "app/viewer/panels.h"
#include "tests/app/panel_ui.h"
#include "tests/app/test_tools.h"

using namespace trilab;
using namespace trilab::viewer;
using namespace trilab::viewer::testing;

namespace {

/// Whether the button `label` was drawn enabled in the last frame.
bool enabled(const Ui& ui, const std::string& label) {
    for (const WidgetNote& n : ui.notes())
        if (n.label == label) return n.enabled;
    FAIL("no widget " << label);
    return false;
}

}  // namespace

TEST_CASE("the Selection section offers what the document allows and queues its settings",
          "[panels][selection]") {
    Ui ui;
    TestPanels panels;
    panels.selection.open = true;
    SidebarContext context;
    context.n_vertices = 1002;
    CommandQueue commands;
    const auto draw = [&] {
        in_sidebar(panels.layout, [&] { selection_section(panels.selection, context, commands); });
    };
    ui.frame(draw);
    ui.frame(draw);
    // No selection, no pick, no values: only Invert (of nothing: everything) is pressable.
    CHECK_FALSE(enabled(ui, "Grow"));
    CHECK_FALSE(enabled(ui, "Clear"));
    CHECK_FALSE(enabled(ui, "Feather"));
    CHECK_FALSE(enabled(ui, "Geodesic ball at pick"));
    CHECK_FALSE(enabled(ui, "Threshold"));
    CHECK(enabled(ui, "Invert"));
    CHECK(ui.has("brush-radius"));
    CHECK_FALSE(ui.has("through the model"));  // the lasso's option shows with the lasso

    // With a selection, a pick and values, the settings travel with the commands.
    context.has_selection = true;
    context.selected = 40;
    context.has_pick = true;
    context.has_values = true;
    panels.selection.rings = 3;
    panels.selection.feather = 0.5f;
    panels.selection.geodesic_radius = 0.75f;
    panels.selection.threshold = 0.25f;
    panels.selection.threshold_above = false;
    panels.selection.mode = SelectionMode::Add;
    ui.frame(draw);
    ui.frame(draw);
    const auto press = [&](const std::string& label) {
        const Box b = ui.rect(label);
        commands.clear();
        ui.click(draw, 0.5f * (b.x0 + b.x1), 0.5f * (b.y0 + b.y1));
    };
    press("Grow");
    REQUIRE(commands_of<EditSelection>(commands).size() == 1);
    CHECK(commands_of<EditSelection>(commands)[0]->kind == EditSelection::Kind::Grow);
    CHECK(commands_of<EditSelection>(commands)[0]->rings == 3);
    press("Feather");
    REQUIRE(commands_of<EditSelection>(commands).size() == 1);
    CHECK(commands_of<EditSelection>(commands)[0]->width == Approx(0.5));
    press("Geodesic ball at pick");
    REQUIRE(commands_of<SelectAtPick>(commands).size() == 1);
    CHECK(commands_of<SelectAtPick>(commands)[0]->radius == Approx(0.75));
    CHECK(commands_of<SelectAtPick>(commands)[0]->mode == SelectionMode::Add);
    press("Threshold");
    REQUIRE(commands_of<SelectThreshold>(commands).size() == 1);
    CHECK(commands_of<SelectThreshold>(commands)[0]->value == Approx(0.25));
    CHECK_FALSE(commands_of<SelectThreshold>(commands)[0]->above);
    // The lasso: its option shows instead of the brush's radius; no command.
    press("Lasso");
    CHECK(commands.empty());
    CHECK(panels.selection.tool == SelectionPanelState::Tool::Lasso);
    ui.frame(draw);
    CHECK(ui.has("through the model"));
    CHECK_FALSE(ui.has("brush-radius"));
}

TEST_CASE("the Selection section's lengths follow the model's size unless the user set them",
          "[panels][selection]") {
    // Issue 38, item 14: a ball of 0.25 model units selected nearly all of a head scan 0.1
    // tall. The radius is 10 % and the feather 4 % of the fitted sphere's radius.
    TestPanels panels;
    SelectionTool& tool = find_tool<SelectionTool>(panels.all_tools);
    panels.context.view.fit_radius = 0.075f;  // the bunny: about 0.15 across
    tool.update();
    CHECK(panels.selection.geodesic_radius == Approx(0.0075f));
    CHECK(panels.selection.feather == Approx(0.003f));
    // The user's radius stays when another model comes; the untouched feather follows it.
    panels.selection.geodesic_radius = 0.02f;
    panels.context.view.fit_radius = 10.0f;
    tool.update();
    CHECK(panels.selection.geodesic_radius == 0.02f);
    CHECK(panels.selection.feather == Approx(0.4f));
}
