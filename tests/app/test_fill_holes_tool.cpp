// The Fill holes tool (app/viewer/fill_holes_tool.h): the document's holes listed with check
// boxes, and "Fill the checked loops" selecting their rims and filling only them (issue 41).
#include <imgui.h>
#include <catch2/catch.hpp>

#include <filesystem>
#include <string>
#include <vector>

#include "app/viewer/fill_holes_tool.h"
#include "core/algorithms/generators.h"
#include "core/algorithms/hole_filling.h"
#include "core/io/mesh_io.h"
#include "core/validate.h"
#include "tests/app/panel_ui.h"
#include "tests/app/test_tools.h"

using namespace trilab;
using namespace trilab::viewer;
using namespace trilab::viewer::testing;

TEST_CASE("rim_weights marks the checked loops' rims only", "[fill_holes_tool]") {
    const HalfedgeMesh cylinder = generate("cylinder");  // open: two rims
    const std::vector<BoundaryLoop> loops = boundary_loops(cylinder);
    REQUIRE(loops.size() == 2);
    const std::vector<float> w = rim_weights(loops, {0, 1}, cylinder.vertices_size());
    std::size_t marked = 0;
    for (float x : w) marked += x == 1.0f ? 1 : 0;
    CHECK(marked == loops[1].vertices.size());
    for (Vertex v : loops[0].vertices) CHECK(w[v.idx()] == 0.0f);
    for (Vertex v : loops[1].vertices) CHECK(w[v.idx()] == 1.0f);
}

TEST_CASE("the Fill holes tool lists the holes and fills the checked one",
          "[fill_holes_tool][panels]") {
    Ui ui;
    TestPanels panels;
    FillHolesTool& tool = find_tool<FillHolesTool>(panels.all_tools);
    Session& s = panels.context.session;
    const HalfedgeMesh cylinder = generate("cylinder");
    const std::string path =
        (std::filesystem::temp_directory_path() / "trilab_fill_holes_tool.off").string();
    write_mesh(cylinder, path);
    s.execute(LoadFile{path});
    s.finish_jobs();
    std::filesystem::remove(path);
    REQUIRE(s.mesh().n_faces() == cylinder.n_faces());
    tool.panel().open = true;
    tool.update();
    REQUIRE(tool.loops().size() == 2);

    CommandQueue commands;
    SidebarContext context;
    const auto draw = [&] { in_sidebar(panels.layout, [&] { tool.section(context, commands); }); };
    ui.frame(draw);
    ui.frame(draw);
    CHECK_FALSE(ui.has("section:Tools: fill holes"));  // its own panel
    REQUIRE(ui.has("section:Fill holes"));
    const auto press = [&](const std::string& id) {
        const Box b = ui.rect(id);
        ui.click(draw, 0.5f * (b.x0 + b.x1), 0.5f * (b.y0 + b.y1));
    };
    const auto enabled = [&](const std::string& label) {
        for (const WidgetNote& n : ui.notes())
            if (n.label == label) return n.enabled;
        FAIL("no widget " << label);
        return false;
    };
    // Nothing checked: the fill of the checked loops is disabled.
    CHECK_FALSE(enabled("Fill the checked loops"));
    commands.clear();
    press("loop 1");
    CHECK(tool.checked() == std::vector<std::uint8_t>{0, 1});
    CHECK(commands.empty());
    REQUIRE(enabled("Fill the checked loops"));
    press("Fill the checked loops");
    const auto selections = commands_of<SetSelection>(commands);
    const auto applied = commands_of<ApplyOperation>(commands);
    REQUIRE(selections.size() == 1);
    REQUIRE(applied.size() == 1);
    CHECK(selections[0]->parameters == "loops 1");
    CHECK(applied[0]->op.name() == "fill-holes");
    // Run them: only loop 1 is closed, the mesh is valid, the other rim stays open.
    for (const Command& c : commands) s.execute(c);
    s.finish_jobs();
    CHECK(validate(s.mesh()).ok);
    const std::vector<BoundaryLoop> left = boundary_loops(s.mesh());
    REQUIRE(left.size() == 1);
    CHECK(left[0].vertices == tool.loops()[0].vertices);
    tool.update();  // the new connectivity: one loop listed
    CHECK(tool.loops().size() == 1);
    // Check all / Check none.
    ui.frame(draw);
    press("Check all");
    CHECK(tool.checked() == std::vector<std::uint8_t>{1});
    press("Check none");
    CHECK(tool.checked() == std::vector<std::uint8_t>{0});
    const PanelEntries entries = panels.entries();
    const PanelEntry* entry = find_panel(entries, "fill-holes");
    REQUIRE(entry);
    CHECK(entry->open == &tool.panel().open);
}
