// The Features tool (app/viewer/features_tool.h): its panel previews the detection with the
// histogram and the counts, its lines are the shown surface's sharp edges, and its widgets
// queue the features operation (issue 39, item 5).
#include <imgui.h>
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "app/viewer/features_tool.h"
#include "core/algorithms/feature_detection.h"
#include "core/algorithms/generators.h"
#include "core/algorithms/selection.h"
#include "core/features.h"
#include "core/io/mesh_io.h"
#include "core/validate.h"
#include "tests/app/panel_ui.h"
#include "tests/app/test_tools.h"

using namespace trilab;
using namespace trilab::viewer;
using namespace trilab::viewer::testing;

TEST_CASE("feature lines are the sharp edges at the shown positions", "[features_tool]") {
    HalfedgeMesh cube = generate("cube");
    CHECK(feature_segments(cube, {}).empty());  // no sharpness stored: no lines
    FeatureDetectionOptions o;
    o.angle_deg = 60;
    const FeatureDetectionReport r = detect_features(cube, o);
    REQUIRE(r.feature_edges > 0);
    const auto lines = feature_segments(cube, {});
    CHECK(lines.size() == r.feature_edges);
    const auto sharpness = cube.get_edge_property<float>(kSharpnessProperty);
    std::size_t k = 0;
    for (Edge e : cube.edges()) {
        if (!(sharpness[e] > 0)) continue;
        const Halfedge h = HalfedgeMesh::halfedge(e, 0);
        CHECK(lines[k][0] == cube.position(cube.from_vertex(h)));
        CHECK(lines[k][1] == cube.position(cube.to_vertex(h)));
        ++k;
    }
    // Other positions (a morph frame): the same edges there.
    std::vector<Point> moved = cube.positions();
    for (Point& p : moved) p *= 2.0;
    const auto frame = feature_segments(cube, moved);
    REQUIRE(frame.size() == lines.size());
    CHECK(frame.front()[0] == 2.0 * lines.front()[0]);
}

TEST_CASE("the Features tool previews the detection with its histogram and lines",
          "[features_tool]") {
    TestPanels panels;
    FeaturesTool& tool = find_tool<FeaturesTool>(panels.all_tools);
    Session& s = panels.context.session;
    HalfedgeMesh cube = generate("cube");
    const std::string path =
        (std::filesystem::temp_directory_path() / "trilab_features_tool_cube.off").string();
    write_mesh(cube, path);
    s.execute(LoadFile{path});
    s.finish_jobs();
    std::filesystem::remove(path);
    REQUIRE(s.mesh().n_faces() == cube.n_faces());
    Operation op = tool.panel().op;
    op.value("angle").x = 60;
    s.execute(PreviewOperation{op});
    s.finish_jobs();
    s.update();
    tool.update();
    const FeatureDetectionReport* r = tool.report();
    REQUIRE(r);
    FeatureDetectionOptions o;
    o.angle_deg = 60;
    const FeatureDetectionReport direct = detect_features(cube, o);
    CHECK(r->feature_edges == direct.feature_edges);
    CHECK(r->histogram.counts == direct.histogram.counts);
    CHECK(tool.lines().size() == direct.feature_edges);
}

TEST_CASE("the Features panel's widgets queue the features operation", "[features_tool][panels]") {
    Ui ui;
    TestPanels panels;
    FeaturesTool& tool = find_tool<FeaturesTool>(panels.all_tools);
    tool.panel().open = true;
    CommandQueue commands;
    SidebarContext context;
    const auto draw = [&] { in_sidebar(panels.layout, [&] { tool.section(context, commands); }); };
    ui.frame(draw);
    ui.frame(draw);
    CHECK_FALSE(ui.has("section:Tools: detect features"));  // its own panel
    REQUIRE(ui.has("section:Features"));
    const Box detect = ui.rect("Detect");
    commands.clear();
    ui.click(draw, 0.5f * (detect.x0 + detect.x1), 0.5f * (detect.y0 + detect.y1));
    const auto applied = commands_of<ApplyOperation>(commands);
    REQUIRE(applied.size() == 1);
    CHECK(applied[0]->op == tool.panel().op);
    // The angle previews live.
    tool.panel().op.value("angle").x = 30;
    tool.panel().dirty = true;
    commands.clear();
    ui.frame(draw);
    const auto previews = commands_of<PreviewOperation>(commands);
    REQUIRE(previews.size() == 1);
    CHECK(previews[0]->op.value("angle").x == 30);
    // The check box turns the feature lines off, queueing nothing.
    REQUIRE(tool.show_lines());
    const Box lines = ui.rect("show feature lines");
    commands.clear();
    ui.click(draw, 0.5f * (lines.x0 + lines.x1), 0.5f * (lines.y0 + lines.y1));
    CHECK_FALSE(tool.show_lines());
    CHECK(commands.empty());
    // Tagging's check boxes: clicking tags, and a semi-sharp value (its slider shows).
    REQUIRE_FALSE(tool.tag_by_click());
    const Box tag = ui.rect("tag edges by clicking");
    ui.click(draw, 0.5f * (tag.x0 + tag.x1), 0.5f * (tag.y0 + tag.y1));
    CHECK(tool.tag_by_click());
    REQUIRE(tool.infinite());
    CHECK_FALSE(ui.has("features: sharpness"));
    const Box infinite = ui.rect("infinitely sharp");
    ui.click(draw, 0.5f * (infinite.x0 + infinite.x1), 0.5f * (infinite.y0 + infinite.y1));
    CHECK_FALSE(tool.infinite());
    ui.frame(draw);
    CHECK(ui.has("features: sharpness"));
    CHECK(tool.sharpen_selection(false).text().find("--sharpness") != std::string::npos);
    const PanelEntries entries = panels.entries();
    const PanelEntry* entry = find_panel(entries, "features");
    REQUIRE(entry);
    CHECK(entry->open == &tool.panel().open);
    CHECK(entry->menu == PanelMenu::Tools);
}

TEST_CASE("tagging by hand: a click toggles an edge, the selection's edges are sharpened",
          "[features_tool]") {
    // Issue 39, item 2: click an edge to toggle it, sharpen or clear the edges of a selection,
    // set a sharpness value; each one "sharpen" history entry.
    TestPanels panels;
    FeaturesTool& tool = find_tool<FeaturesTool>(panels.all_tools);
    Session& s = panels.context.session;  // the built-in model, no features
    const Edge e(Index(10));
    Operation op = tool.toggle_edge(e);
    CHECK(op.name() == "sharpen");
    CHECK(op.value("edge").x == 10.0);
    s.execute(RunOperation{op});
    s.finish_jobs();
    CHECK(std::isinf(sharpness(s.mesh(), e)));
    CHECK(s.history().info(s.history().current()).label == "Sharpen edges");
    // The same edge again: smooth again.
    s.execute(RunOperation{tool.toggle_edge(e)});
    s.finish_jobs();
    CHECK(sharpness(s.mesh(), e) == 0.0f);
    // A semi-sharp value for the selection's edges.
    tool.infinite() = false;
    tool.sharpness() = 2.5f;
    s.execute(SelectSpec{"sphere:0,0,1,0.3"});
    s.finish_jobs();
    s.execute(RunOperation{tool.sharpen_selection(false)});
    s.finish_jobs();
    const std::optional<Selection> w = stored_selection(s.mesh());
    REQUIRE(w);
    std::size_t inside = 0;
    for (Edge x : s.mesh().edges()) {
        const Halfedge h = HalfedgeMesh::halfedge(x, 0);
        const bool both =
            (*w)[s.mesh().from_vertex(h).idx()] > 0 && (*w)[s.mesh().to_vertex(h).idx()] > 0;
        CHECK(sharpness(s.mesh(), x) == (both ? 2.5f : 0.0f));
        inside += both ? 1 : 0;
    }
    CHECK(inside > 10);
    CHECK(validate(s.mesh()).ok);
    // Undo takes the tags back.
    s.execute(Undo{});
    CHECK_FALSE(has_features(s.mesh()));
}

TEST_CASE("with tagging on, a click on the model tags the edge under it instead of picking",
          "[features_tool]") {
    TestPanels panels;
    FeaturesTool& tool = find_tool<FeaturesTool>(panels.all_tools);
    ViewerContext& c = panels.context;
    c.view_rect = Rect{0, 0, 800, 600};
    c.fit_camera(glm::vec3(0.0f), 1.0f);  // the built-in model: a sphere of radius 1
    ViewMouse click;
    click.pos = glm::vec2(400, 300);  // the middle of the view: on the sphere
    click.in_view = click.drag_in_view = click.clicked = true;
    // Off (the default), or with the section closed: the click is left to the pick.
    CHECK_FALSE(tool.mouse(click));
    tool.tag_by_click() = true;
    CHECK_FALSE(tool.mouse(click));
    tool.panel().open = true;
    c.commands.clear();
    CHECK(tool.mouse(click));  // taken: no pick
    const auto runs = commands_of<RunOperation>(c.commands);
    REQUIRE(runs.size() == 1);
    CHECK(runs[0]->op.name() == "sharpen");
    const double edge = runs[0]->op.value("edge").x;
    CHECK(edge >= 0);
    CHECK(edge < double(c.session.mesh().edges_size()));
    // A click beside the model tags nothing, and is still not a pick.
    click.pos = glm::vec2(5, 5);
    c.commands.clear();
    CHECK(tool.mouse(click));
    CHECK(c.commands.empty());
}
