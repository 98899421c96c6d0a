// The Compare tool (app/viewer/compare_tool.h): the current state's distance to a state of
// the history or to a file, as figures and as the surface-distance colouring (issue 40).
#include <imgui.h>
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "app/viewer/compare_tool.h"
#include "core/algorithms/mesh_distance.h"
#include "core/io/mesh_io.h"
#include "tests/app/panel_ui.h"
#include "tests/app/test_tools.h"

using namespace trilab;
using namespace trilab::viewer;
using namespace trilab::viewer::testing;

TEST_CASE("summarize_distances skips missing values", "[compare_tool]") {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const DistanceSummary s = summarize_distances({1.0, nan, 3.0});
    CHECK(s.vertices == 2);
    CHECK(s.mean == 2.0);
    CHECK(s.max == 3.0);
    CHECK(s.rms == Approx(std::sqrt(5.0)));
    CHECK(summarize_distances({}).vertices == 0);
}

TEST_CASE("the Compare tool measures the current state against a state and a file",
          "[compare_tool][panels]") {
    TestPanels panels;
    CompareTool& tool = find_tool<CompareTool>(panels.all_tools);
    Session& s = panels.context.session;  // the built-in model
    const HalfedgeMesh original = s.mesh();
    Operation noise = parse_operation("noise --amount 2 --seed 5");
    s.execute(RunOperation{noise});
    s.finish_jobs();
    REQUIRE(s.history().size() == 2);
    const std::vector<double> expected = vertex_surface_distances(s.mesh(), original);

    // Against state 0 (the load).
    tool.open() = true;
    tool.target().entry = 0;
    tool.update();
    tool.finish();
    REQUIRE(tool.error().empty());
    REQUIRE(tool.distances().size() == expected.size());
    for (std::size_t i = 0; i < expected.size(); ++i) CHECK(tool.distances()[i] == expected[i]);
    CHECK(tool.summary().max > 0);
    // The colouring shows them, and only as the surface-distance colouring.
    CHECK(tool.field_colors(s.mesh()).colors.empty());
    panels.context.view.settings.coloring = VertexColoring::SurfaceDistance;
    const VertexColors colors = tool.field_colors(s.mesh());
    REQUIRE(colors.values.size() == expected.size());
    CHECK(colors.values[7] == expected[7]);
    CHECK(colors.range.min == 0.0);
    // Against state 1 (itself): zero everywhere.
    tool.target().entry = 1;
    tool.update();
    tool.finish();
    CHECK(tool.summary().max < 1e-12);

    // Against a file: the original written out; then a file that does not load.
    const std::string path =
        (std::filesystem::temp_directory_path() / "trilab_compare_tool.off").string();
    write_mesh(original, path);
    tool.target().source = CompareTool::Source::File;
    tool.target().file = path;
    tool.update();
    tool.finish();
    std::filesystem::remove(path);
    REQUIRE(tool.error().empty());
    REQUIRE(tool.distances().size() == expected.size());
    CHECK(tool.summary().max == Approx(summarize_distances(expected).max).epsilon(1e-6));
    tool.target().file = path + ".missing.off";
    tool.update();
    tool.finish();
    CHECK(tool.distances().empty());
    CHECK(tool.error().find(".missing.off") != std::string::npos);
}

TEST_CASE("the Compare panel's button colours by the distance", "[compare_tool][panels]") {
    Ui ui;
    TestPanels panels;
    CompareTool& tool = find_tool<CompareTool>(panels.all_tools);
    tool.open() = true;
    CommandQueue commands;
    SidebarContext context;
    context.history = &panels.context.session.history();
    const auto draw = [&] { in_sidebar(panels.layout, [&] { tool.section(context, commands); }); };
    ui.frame(draw);
    ui.frame(draw);
    REQUIRE(ui.has("section:Compare"));
    // The source's radio buttons: a mesh file (its path field shows), then a state again.
    const auto press = [&](const std::string& id) {
        const Box r = ui.rect(id);
        ui.click(draw, 0.5f * (r.x0 + r.x1), 0.5f * (r.y0 + r.y1));
    };
    press("compare: file");
    CHECK(tool.target().source == CompareTool::Source::File);
    ui.frame(draw);
    CHECK(ui.has("compare: path"));
    press("compare: state");
    CHECK(tool.target().source == CompareTool::Source::State);
    ui.frame(draw);
    CHECK(ui.has("compare: entry"));
    const Box b = ui.rect("Colour by the distance");
    commands.clear();
    ui.click(draw, 0.5f * (b.x0 + b.x1), 0.5f * (b.y0 + b.y1));
    CHECK(panels.context.view.settings.coloring == VertexColoring::SurfaceDistance);
    CHECK(commands_of<UpdateColoring>(commands).size() == 1);
    const PanelEntries entries = panels.entries();
    const PanelEntry* entry = find_panel(entries, "compare");
    REQUIRE(entry);
    CHECK(entry->open == &tool.open());
}
