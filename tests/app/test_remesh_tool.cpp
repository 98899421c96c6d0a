// The Remesh tool (app/viewer/remesh_tool.h): before it runs, the face count it will make;
// after a preview, the quality of the document against the preview's (issue 41).
#include <imgui.h>
#include <catch2/catch.hpp>

#include <string>

#include "app/viewer/remesh_tool.h"
#include "core/algorithms/mesh_quality.h"
#include "core/algorithms/remesh.h"
#include "tests/app/panel_ui.h"
#include "tests/app/test_tools.h"

using namespace trilab;
using namespace trilab::viewer;
using namespace trilab::viewer::testing;

TEST_CASE("the Remesh tool predicts the faces and compares the preview's quality",
          "[remesh_tool][panels]") {
    Ui ui;
    TestPanels panels;
    RemeshTool& tool = find_tool<RemeshTool>(panels.all_tools);
    Session& s = panels.context.session;  // the built-in model
    tool.panel().open = true;
    Operation op = tool.panel().op;
    op.value("relative").x = 0.5;  // half the mean edge: about four times the faces
    tool.panel().op = op;
    tool.finish();  // the plan and the quality come from a worker thread
    REQUIRE(tool.plan());
    const RemeshReport direct = remesh_plan(s.mesh(), options_of<RemeshOptions>(op));
    CHECK(tool.plan()->predicted_faces == direct.predicted_faces);
    CHECK(tool.plan()->predicted_faces > 3 * s.mesh().n_faces());
    REQUIRE(tool.before());
    CHECK(tool.before()->quality.faces == s.mesh().n_faces());
    CHECK_FALSE(tool.after());
    // A preview: its quality beside the document's, at the plan's length.
    s.execute(PreviewOperation{op});
    s.finish_jobs();
    s.update();
    tool.panel().previewing = true;
    tool.finish();
    REQUIRE(tool.after());
    const MeshQuality preview =
        mesh_quality(s.previews().result()->steps.back().mesh, tool.plan()->target_length);
    CHECK(tool.after()->quality.faces == preview.faces);
    CHECK(tool.after()->quality.edges_in_band == Approx(preview.edges_in_band));
    CHECK(tool.after()->quality.edges_in_band > tool.before()->quality.edges_in_band);
    // The cotangent Laplacian's spread, before and after (the lens of issue 41).
    const CotangentSpread spread = cotangent_spread(s.previews().result()->steps.back().mesh);
    CHECK(tool.after()->spread.weight_ratio == spread.weight_ratio);
    CHECK(tool.before()->spread.weight_ratio == cotangent_spread(s.mesh()).weight_ratio);
    const auto rows = quality_rows(*tool.before(), &*tool.after());
    REQUIRE(rows.size() == 8);
    CHECK(rows[6][0] == "cotangent weight, largest / median");
    CHECK(rows[0][1] == std::to_string(s.mesh().n_faces()));
    CHECK(rows[0][2] == std::to_string(preview.faces));
    // Parameters that cannot run say why before anything runs.
    op.value("relative").x = 1e-6;
    tool.panel().op = op;
    tool.finish();
    CHECK_FALSE(tool.plan());
    CHECK_FALSE(tool.plan_error().empty());
    // Its Remesh button applies the panel's operation.
    tool.panel().op.value("relative").x = 0.5;
    CommandQueue commands;
    SidebarContext context;
    const auto draw = [&] { in_sidebar(panels.layout, [&] { tool.section(context, commands); }); };
    ui.frame(draw);
    ui.frame(draw);
    CHECK_FALSE(ui.has("section:Tools: remesh"));  // its own panel
    const Box b = ui.rect("Remesh");
    commands.clear();
    ui.click(draw, 0.5f * (b.x0 + b.x1), 0.5f * (b.y0 + b.y1));
    const auto applied = commands_of<ApplyOperation>(commands);
    REQUIRE(applied.size() == 1);
    CHECK(applied[0]->op.name() == "remesh");
}
