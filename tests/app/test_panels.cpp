// The operation panels drawn under an ImGui context with no window and no GL (the idea of
// Polyscope's mock backend): the mouse is moved and pressed through ImGuiIO, the widgets are
// found through the widget hook (app/viewer/widgets.h), and the tests assert the typed
// commands the panels queue. The sections are drawn in the real sidebar (layout.h), whose
// regions are checked here too.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <catch2/catch.hpp>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <string>
#include <variant>

#include "app/viewer/key_bindings.h"
#include "app/viewer/panels.h"
#include "app/viewer/plots.h"
#include "core/algorithms/fairing.h"
#include "core/algorithms/generators.h"
#include "tests/app/panel_ui.h"
#include "tests/app/test_tools.h"

using namespace trilab;
using namespace trilab::viewer;

using namespace trilab::viewer::testing;

TEST_CASE("the Subdivision panel's Subdivide queues the typed operation it shows", "[panels]") {
    Ui ui;
    TestPanels panels;
    MorphState morph;
    History history;
    panels.subdivision.open = true;
    CommandQueue commands;
    const auto draw = [&] {
        in_sidebar(panels.layout,
                   [&] { subdivision_section(panels.subdivision, SidebarContext{}, commands); });
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
    TestPanels panels;
    MorphState morph;
    History history;
    panels.decimation.open = true;
    CommandQueue commands;
    const auto draw = [&] {
        in_sidebar(panels.layout,
                   [&] { decimation_section(panels.decimation, SidebarContext{}, commands); });
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
    TestPanels panels;
    MorphState morph;
    History history;
    panels.decimation.open = true;
    panels.decimation.live = false;  // the viewer found the last preview over the budget
    CommandQueue commands;
    const auto draw = [&] {
        in_sidebar(panels.layout,
                   [&] { decimation_section(panels.decimation, SidebarContext{}, commands); });
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
    TestPanels panels;
    MorphState morph;
    History history;
    panels.fairing.open = true;
    CommandQueue commands;
    const auto draw = [&] {
        in_sidebar(panels.layout,
                   [&] { fairing_section(panels.fairing, closed_mesh(), commands); });
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
    TestPanels panels;
    panels.tool("noise")->open = true;
    CommandQueue commands;
    const auto draw = [&] {
        in_sidebar(panels.layout, [&] { tools_section(panels.tools, false, commands); });
    };
    ui.frame(draw);
    ui.frame(draw);
    CHECK_FALSE(ui.has("Cancel"));
    panels.tool("noise")->previewing = true;
    ui.frame(draw);
    const Box cancel = ui.rect("Cancel");
    commands.clear();
    ui.click(draw, (cancel.x0 + cancel.x1) / 2, (cancel.y0 + cancel.y1) / 2);
    CHECK(commands_of<CancelPreview>(commands).size() == 1);
    CHECK(commands_of<ApplyOperation>(commands).empty());
}

TEST_CASE("the Fairing panel marks a step above the stable limit and offers implicit", "[panels]") {
    Ui ui;
    TestPanels panels;
    MorphState morph;
    History history;
    panels.fairing.open = true;
    panels.fairing.max_stable_step = 1.35;
    CommandQueue commands;
    const auto draw = [&] {
        in_sidebar(panels.layout,
                   [&] { fairing_section(panels.fairing, closed_mesh(), commands); });
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

TEST_CASE("the Fairing panel's transfer curve marks instability, the pass band and measurements",
          "[panels][lens]") {
    Ui ui(1280, 2000);
    TestPanels panels;
    panels.fairing.open = true;
    panels.fairing.max_stable_step = 0.5;  // lambda_max = 4 from the stability estimate
    panels.fairing.lens.lambda_max = 4.0;
    CommandQueue commands;
    const auto draw = [&] {
        in_sidebar(panels.layout,
                   [&] { fairing_section(panels.fairing, closed_mesh(), commands); });
    };
    FairingOptions o = options_of<FairingOptions>(panels.fairing.op);
    o.op = FairingOperator::Umbrella;
    o.integration = Integration::Explicit;
    o.step = 0.4;  // unstable above 2 / 0.4 = 5: beyond this spectrum's 4
    set_options(panels.fairing.op, o);
    ui.frame(draw);
    ui.frame(draw);
    REQUIRE(ui.has("lens: area"));
    CHECK_FALSE(ui.has("lens: grows"));
    const Box area = ui.rect("lens: area");
    // A larger step: unstable above lambda = 2 / 0.8 = 2.5, inside the range: marked there.
    o.step = 0.8;
    set_options(panels.fairing.op, o);
    ui.frame(draw);
    REQUIRE(ui.has("lens: unstable"));
    CHECK(ui.has("lens: grows"));
    const Box mark = ui.rect("lens: unstable");
    const double lo = std::log10(4.0 * 1e-4), hi = std::log10(4.0);
    const double expected_x = area.x0 + (std::log10(2.5) - lo) / (hi - lo) * (area.x1 - area.x0);
    CHECK(std::abs(0.5 * (mark.x0 + mark.x1) - expected_x) < 2.0);
    // The curve follows the options within the frame: implicit is stable everywhere.
    o.integration = Integration::Implicit;
    set_options(panels.fairing.op, o);
    ui.frame(draw);
    CHECK_FALSE(ui.has("lens: unstable"));
    CHECK_FALSE(ui.has("lens: grows"));
    // Taubin: the pass band is marked.
    o.op = FairingOperator::Taubin;
    o.integration = Integration::Explicit;
    set_options(panels.fairing.op, o);
    ui.frame(draw);
    CHECK(ui.has("lens: pass band"));
    // Measured gains over a spectrum: dots.
    o.op = FairingOperator::Umbrella;
    o.step = 0.3;
    set_options(panels.fairing.op, o);
    panels.fairing.lens.eigenvalues = {0.0, 0.5, 1.0, 2.0, 4.0};
    panels.fairing.lens.measured = {std::nan(""), 0.85, 0.7, 0.4, -0.2};
    ui.frame(draw);
    CHECK(ui.has("lens: measured"));
    CHECK_FALSE(ui.has("Decompose for this operator"));
    // Without a decomposition of this operator: the button that computes one.
    panels.fairing.lens.eigenvalues.clear();
    panels.fairing.lens.measured.clear();
    ui.frame(draw);
    const Box decompose = ui.rect("Decompose for this operator");
    commands.clear();
    ui.click(draw, (decompose.x0 + decompose.x1) / 2, (decompose.y0 + decompose.y1) / 2);
    const auto asked = commands_of<Decompose>(commands);
    REQUIRE(asked.size() == 1);
    CHECK(asked[0]->op.name() == "spectrum");
}

TEST_CASE(
    "the transfer curve offers the diverging run only where the settings diverge, and "
    "marks it when shown",
    "[panels][lens][figures]") {
    Ui ui(1280, 2000);
    TestPanels panels;
    panels.fairing.open = true;
    panels.fairing.max_stable_step = 1.34;
    panels.fairing.lens.lambda_max = 2.0 / 1.34;
    CommandQueue commands;
    const auto draw = [&] {
        in_sidebar(panels.layout,
                   [&] { fairing_section(panels.fairing, closed_mesh(), commands); });
    };
    // Figure 1.12(b)'s settings: explicit umbrella at step 20, unstable above 0.1.
    panels.fairing.op = parse_operation("smooth --operator umbrella --step 20");
    panels.fairing.lens.figure_note = "Figure 1.12b: its step means the same here";
    ui.frame(draw);
    ui.frame(draw);
    CHECK(ui.has("lens: figure"));
    REQUIRE(ui.has("Show the diverging run"));
    const Box show = ui.rect("Show the diverging run");
    ui.click(draw, (show.x0 + show.x1) / 2, (show.y0 + show.y1) / 2);
    REQUIRE(commands_of<ShowDivergingRun>(commands).size() == 1);
    CHECK(commands_of<ShowDivergingRun>(commands)[0]->op == panels.fairing.op);
    CHECK(commands_of<ApplyOperation>(commands).empty());
    commands.clear();
    // Shown: the red mark replaces the button.
    panels.fairing.lens.diverging_note = "DIVERGED: shown for teaching, not a result";
    ui.frame(draw);
    CHECK(ui.has("lens: diverged"));
    CHECK_FALSE(ui.has("Show the diverging run"));
    // Stable settings (a step of 1, implicit step 20) offer nothing: the button is drawn
    // disabled, so that nothing moves while the step is dragged across the limit.
    panels.fairing.lens.diverging_note.clear();
    const auto enabled = [&] {
        for (const WidgetNote& n : ui.notes())
            if (n.id == "Show the diverging run") return n.enabled;
        FAIL("no button");
        return false;
    };
    ui.frame(draw);
    CHECK(enabled());
    for (const char* text : {"smooth --operator umbrella --step 1",
                             "smooth --operator umbrella --integration implicit --step 20"}) {
        INFO(text);
        panels.fairing.op = parse_operation(text);
        ui.frame(draw);
        CHECK_FALSE(enabled());
        ui.click(draw, (show.x0 + show.x1) / 2, (show.y0 + show.y1) / 2);
        CHECK(commands_of<ShowDivergingRun>(commands).empty());
    }
}

TEST_CASE("the legend's display combo chooses bands or isolines, and its count follows",
          "[panels][legend]") {
    Ui ui;
    VertexColors colors;
    colors.has_legend = true;
    colors.label = "mean curvature";
    colors.range = {-1.0, 1.0};
    colors.kind = ColorMapKind::Diverging;
    colors.values = {-1.0, 0.0, 1.0};
    ColoringOptions options;
    RenderStyle style;
    const auto draw = [&] { draw_legend(colors, options, &style); };
    ui.frame(draw);
    ui.frame(draw);
    REQUIRE(ui.has("legend: display"));
    CHECK_FALSE(ui.has("legend: bands"));  // smooth: no count
    const auto press = [&](const std::string& id) {
        const Box b = ui.rect(id);
        ui.click(draw, 0.5f * (b.x0 + b.x1), 0.5f * (b.y0 + b.y1));
    };
    press("legend: display");
    ui.frame(draw);
    press("legend: display isolines");
    CHECK(style.scalar_display == ScalarDisplay::Isolines);
    ui.frame(draw);
    CHECK(ui.has("legend: lines"));
    press("legend: display");
    ui.frame(draw);
    press("legend: display bands");
    CHECK(style.scalar_display == ScalarDisplay::Bands);
    ui.frame(draw);
    CHECK(ui.has("legend: bands"));
    // A categorical colouring has no display choice.
    colors.kind = ColorMapKind::Categorical;
    ui.frame(draw);
    CHECK_FALSE(ui.has("legend: display"));
}

// ---- legends and plots (issue 16) ------------------------------------------------------------

TEST_CASE("legend labels never overlap, both ends always show, the centre where it fits",
          "[panels][legend]") {
    Ui ui;
    ColoringOptions options;
    // The issue's Gaussian curvature range, and ranges with long and short labels.
    const ValueRange ranges[] = {{-3.568e+05, 3.568e+05},
                                 {-1.234567e-300, 1.234567e-300},
                                 {-0.5, 0.5},
                                 {2.5e-7, 9.875e+12},
                                 {0.0, 1.0},
                                 {-123456.7, 9.0}};
    for (const ValueRange& r : ranges) {
        for (const ColorMapKind kind : {ColorMapKind::Diverging, ColorMapKind::Sequential}) {
            INFO("range " << r.min << " .. " << r.max << ", " << color_map_name(kind));
            VertexColors colors;
            colors.has_legend = true;
            colors.kind = kind;
            colors.label = "Gaussian curvature K";
            colors.range = r;
            const auto draw = [&] { draw_legend(colors, options); };
            ui.frame(draw);
            ui.frame(draw);
            const auto labels = ui.with_prefix("legend: label ");
            require_disjoint(labels);
            const Box bar = ui.rect("legend: bar");
            char min_text[32], max_text[32];
            std::snprintf(min_text, sizeof min_text, "%.4g", r.min);
            std::snprintf(max_text, sizeof max_text, "%.4g", r.max);
            const Box lo = ui.rect(std::string("legend: label ") + min_text);
            const Box hi = ui.rect(std::string("legend: label ") + max_text);
            CHECK(lo.x0 == Approx(bar.x0));  // the ends sit under the ends of the bar
            CHECK(hi.x1 == Approx(bar.x1));
            for (const auto& [id, rect] : labels) {
                CHECK(rect.x0 >= bar.x0 - 0.01f);
                CHECK(rect.x1 <= bar.x1 + 0.01f);
                CHECK(rect.y0 >= bar.y1);  // under the bar, not on it
            }
            // The centre of a symmetric range is 0; it shows on these (room enough).
            if (r.min == -r.max) CHECK(ui.has("legend: label 0"));
            CHECK(ui.has("legend: percentiles"));  // a continuous map has the range control
        }
    }
}

TEST_CASE("place_labels drops what would overlap, keeping the most important labels",
          "[panels][legend]") {
    // Ends (priority 2) at 0 and 100, a centre (1) at 50: wide labels push the centre out.
    std::vector<LabelSpec> specs = {{0, 45, 0.0f, 2}, {50, 20, 0.5f, 1}, {100, 45, 1.0f, 2}};
    auto at = place_labels(specs, 0, 100, 4);
    REQUIRE(at[0]);
    REQUIRE(at[2]);
    CHECK_FALSE(at[1]);
    CHECK(*at[0] == 0);
    CHECK(*at[2] == 55);
    // Narrow labels all fit, each at its anchor.
    specs = {{0, 10, 0.0f, 2}, {50, 10, 0.5f, 1}, {100, 10, 1.0f, 2}};
    at = place_labels(specs, 0, 100, 4);
    REQUIRE(at[1]);
    CHECK(*at[1] == 45);
    // A label that would stick out is moved inside.
    at = place_labels({{98, 10, 0.5f, 0}}, 0, 100, 4);
    REQUIRE(at[0]);
    CHECK(*at[0] == 90);
}

TEST_CASE("nice_ticks: 1-2-5 steps inside the range, at most the count asked", "[panels][plots]") {
    const auto ticks = nice_ticks(0, 49, 6, 1);
    REQUIRE(ticks.size() >= 2);
    REQUIRE(ticks.size() <= 6);
    CHECK(ticks.front() == 0);
    const double step = ticks[1] - ticks[0];
    CHECK((step == 10 || step == 20 || step == 50));
    for (std::size_t i = 1; i < ticks.size(); ++i) CHECK(ticks[i] - ticks[i - 1] == Approx(step));
    for (const double t : ticks) CHECK((t >= 0 && t <= 49));
    const auto small = nice_ticks(-0.031, 0.047, 5);
    REQUIRE(small.size() >= 2);
    for (const double t : small) CHECK((t >= -0.031 && t <= 0.047));
    CHECK(nice_ticks(0, 3, 10, 1) == std::vector<double>{0, 1, 2, 3});  // whole steps only
    CHECK(nice_ticks(2, 2, 5) == std::vector<double>{2});
    CHECK(nice_ticks(0, NAN, 5).empty());
    CHECK(tick_text(-0.0) == "0");
}

TEST_CASE("a categorical legend shows one swatch per value and no range control",
          "[panels][legend]") {
    Ui ui;
    ColoringOptions options;
    VertexColors colors;
    colors.has_legend = true;
    colors.kind = ColorMapKind::Categorical;
    colors.label = "subdivision level of each vertex";
    for (int level = 0; level < 4; ++level) {
        ColorCategory c;
        c.value = level;
        c.color = categorical_color(std::size_t(level));
        c.label = "level " + std::to_string(level);
        c.count = std::size_t(12) << (2 * level);
        colors.categories.push_back(c);
    }
    colors.range = {0, 3};
    const auto draw = [&] { draw_legend(colors, options); };
    ui.frame(draw);
    ui.frame(draw);
    const auto swatches = ui.with_prefix("legend: swatch ");
    REQUIRE(swatches.size() == 4);
    require_disjoint(swatches);
    float last_y = -1;
    for (int level = 0; level < 4; ++level) {  // one row per level, in order
        const Box r = ui.rect("legend: swatch level " + std::to_string(level));
        CHECK(r.y0 > last_y);
        last_y = r.y0;
    }
    CHECK_FALSE(ui.has("legend: percentiles"));
    CHECK_FALSE(ui.has("legend: bar"));
}

namespace {

/// A decomposition's display data: k eigenvalues and coefficients, the band of a state.
FrequencyDocument frequency_document(std::size_t k) {
    FrequencyDocument doc;
    doc.decomposition = std::make_shared<const SpectralDecomposition>();
    doc.valid = true;
    for (std::size_t i = 0; i < k; ++i) {
        doc.eigenvalues.push_back(float(0.01 * double(i) * double(i)));
        doc.log_coefficients.push_back(float(-0.1 * double(i)));
    }
    doc.log_coefficients[3] = -INFINITY;  // |alpha| = 0: no point, no crash
    doc.applied = true;
    doc.applied_lo = 0;
    doc.applied_hi = 9;
    return doc;
}

}  // namespace

TEST_CASE("the frequency plots shade exactly the band's share and mark the visualized frequency",
          "[panels][plots]") {
    Ui ui;
    FrequencyPanelState state;
    state.open = true;
    const std::size_t k = 50;
    const FrequencyDocument doc = frequency_document(k);
    state.lo = 0;
    state.hi = 24;
    state.visualize = 7;
    CommandQueue commands;
    const auto draw = [&] { frequency_window(state, doc, false, commands); };
    ui.frame(draw);
    ui.frame(draw);
    for (const char* plot : {"spectrum", "coefficients", "frequency bar"}) {
        INFO(plot);
        const std::string p = plot;
        const Box area = ui.rect(p == "frequency bar" ? p : p + ": area");
        const Box band = ui.rect(p + ": band");
        const Box marker = ui.rect(p + ": marker");
        const float w = area.x1 - area.x0;
        REQUIRE(w > 100);
        // Band 0..24 of 50: exactly half the plot area, from its left edge (the issue saw
        // 58 %: the band was scaled to the plot plus its label).
        CHECK(band.x0 == Approx(area.x0).margin(0.01));
        CHECK((band.x1 - band.x0) / w == Approx(25.0 / 50.0).margin(1e-4));
        // The marker sits at the centre of slot 7.
        CHECK((marker.x0 + marker.x1) / 2 == Approx(area.x0 + 7.5f / 50.0f * w).margin(0.01));
        // The bar and the plots share their x range.
        const Box spectrum = ui.rect("spectrum: area");
        CHECK(area.x0 == Approx(spectrum.x0));
        CHECK(area.x1 == Approx(spectrum.x1));
    }
    // The applied band (0..9) on the bar: 10 of 50 slots.
    const Box bar = ui.rect("frequency bar");
    const Box applied = ui.rect("frequency bar: applied");
    CHECK((applied.x1 - applied.x0) / (bar.x1 - bar.x0) == Approx(0.2).margin(1e-4));
    // Axes with tick labels that do not overlap: index ticks starting at 0, value ticks.
    for (const char* plot : {"spectrum", "coefficients"}) {
        INFO(plot);
        const auto x_ticks = ui.with_prefix(std::string(plot) + ": x tick ");
        const auto y_ticks = ui.with_prefix(std::string(plot) + ": y tick ");
        CHECK(x_ticks.size() >= 3);
        CHECK(y_ticks.size() >= 2);
        CHECK(ui.has(std::string(plot) + ": x tick 0"));
        auto all = x_ticks;
        all.insert(all.end(), y_ticks.begin(), y_ticks.end());
        require_disjoint(all);
        const Box area = ui.rect(std::string(plot) + ": area");
        for (const auto& [id, r] : x_ticks) CHECK(r.y0 >= area.y1);  // below the area
        for (const auto& [id, r] : y_ticks) CHECK(r.x1 <= area.x0);  // left of it
    }
    // The spectrum's y ticks span its values (0 .. 24.01).
    CHECK(ui.has("spectrum: y tick 0"));
    // A single-frequency band is one slot wide; the marker follows the slider's value.
    state.lo = state.hi = 49;
    state.visualize = 0;
    ui.frame(draw);
    const Box area = ui.rect("spectrum: area");
    const Box band = ui.rect("spectrum: band");
    CHECK(band.x1 == Approx(area.x1).margin(0.01));
    CHECK((band.x1 - band.x0) == Approx((area.x1 - area.x0) / 50).margin(0.01));
    const Box marker = ui.rect("spectrum: marker");
    CHECK((marker.x0 + marker.x1) / 2 == Approx(area.x0 + 0.5f / 50 * (area.x1 - area.x0)));
}

TEST_CASE(
    "the Frequency panel flags a band that splits equal eigenvalues, with the nearest "
    "bands that do not",
    "[panels][frequency]") {
    Ui ui;
    FrequencyPanelState state;
    state.open = true;
    // A sphere's spectrum: 0, the three-fold lambda_1, the five-fold lambda_2.
    FrequencyDocument doc;
    doc.decomposition = std::make_shared<const SpectralDecomposition>();
    doc.valid = true;
    for (const float v :
         {0.0f, 0.05f, 0.0501f, 0.0502f, 0.15f, 0.1501f, 0.1502f, 0.1503f, 0.1504f, 0.3f}) {
        doc.eigenvalues.push_back(v);
        doc.log_coefficients.push_back(-1.0f);
    }
    state.lo = 0;
    state.hi = 2;  // the noisy sphere's band 0:2 keeps two of the three lambda_1
    CommandQueue commands;
    const auto draw = [&] { frequency_window(state, doc, false, commands); };
    ui.frame(draw);
    ui.frame(draw);
    const auto note = std::find_if(ui.notes().begin(), ui.notes().end(),
                                   [](const WidgetNote& n) { return n.id == "band-split"; });
    REQUIRE(note != ui.notes().end());
    CHECK(note->label.find("band 0:2 splits the multiplet 1:3") != std::string::npos);
    CHECK(note->label.find("0:0") != std::string::npos);
    CHECK(note->label.find("0:3") != std::string::npos);
    // The nearest whole band, pressed: the sliders follow and the band is pushed.
    REQUIRE(ui.has("use 0:0"));
    const Box wider = ui.rect("use 0:3");
    commands.clear();
    ui.click(draw, (wider.x0 + wider.x1) / 2, (wider.y0 + wider.y1) / 2);
    CHECK(state.lo == 0);
    CHECK(state.hi == 3);
    REQUIRE(commands.size() == 2);
    REQUIRE(std::holds_alternative<PreviewBand>(commands[0]));
    CHECK(std::get<PreviewBand>(commands[0]).hi == 3);
    REQUIRE(std::holds_alternative<CommitBand>(commands[1]));
    CHECK(std::get<CommitBand>(commands[1]).hi == 3);
    // A band of whole multiplets is not flagged.
    ui.frame(draw);
    CHECK_FALSE(ui.has("band-split"));
    CHECK_FALSE(ui.has("use 0:3"));
    // Its upper edge inside lambda_2 is flagged again.
    state.hi = 6;
    ui.frame(draw);
    CHECK(ui.has("band-split"));
    CHECK(ui.has("use 0:3"));
    CHECK(ui.has("use 0:8"));
}

TEST_CASE("the up axis is remembered in the settings file, other keys kept", "[panels][prefs]") {
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / ("trilab-prefs-" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir);
    const std::filesystem::path file = dir / "trilab" / "settings";
    Preferences p;
    p.load(file);  // missing: the defaults
    CHECK(p.up == UpAxis::Y);
    p.up = UpAxis::Z;
    p.save();  // creates the folder
    Preferences q;
    q.load(file);
    CHECK(q.up == UpAxis::Z);
    // Keys of other versions survive a save; a bad value falls back to the default.
    {
        std::ofstream out(file);
        out << "up-axis sideways\nfuture-key 42\n";
    }
    q.load(file);
    CHECK(q.up == UpAxis::Y);
    q.save();
    std::ifstream in(file);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    CHECK(text.find("future-key 42") != std::string::npos);
    CHECK(text.find("up-axis y") != std::string::npos);
    std::filesystem::remove_all(dir);
    // Without a file (scripted runs) nothing is written.
    Preferences none;
    none.up = UpAxis::Z;
    none.save();
    CHECK_FALSE(std::filesystem::exists(dir));
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
    TestPanels panels;
    CommandQueue commands;
    panels.tool("noise")->open = true;
    const auto draw = [&] {
        in_sidebar(panels.layout, [&] { tools_section(panels.tools, false, commands); });
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

TEST_CASE("a section opened elsewhere shows its body, its header closes it", "[layout]") {
    Ui ui;
    TestPanels panels;
    CommandQueue commands;
    const auto draw = [&] {
        in_sidebar(panels.layout, [&] { tools_section(panels.tools, false, commands); });
    };
    ui.frame(draw);
    CHECK_FALSE(ui.has("Apply"));  // collapsed: only the header
    REQUIRE(ui.has("section:Tools: add noise"));
    panels.tool("noise")->open = true;  // the menu item, or --show tools
    ui.frame(draw);
    CHECK(ui.has("Apply"));
    const Box header = ui.rect("section:Tools: add noise");
    ui.click(draw, (header.x0 + header.x1) / 2, (header.y0 + header.y1) / 2);
    CHECK_FALSE(panels.tool("noise")->open);
    ui.frame(draw);
    CHECK_FALSE(ui.has("Apply"));
}

TEST_CASE("the morph controls offer no animation for a state that moves nothing", "[panels]") {
    Ui ui;
    TestPanels panels;
    MorphState morph;
    History history;
    HalfedgeMesh a = make_default_model();
    history.reset(a, "Load a.off");
    history.push("Load b.off", "", 0.0, {a},
                 {MorphCorrespondence{MorphCorrespondence::Kind::FromEarlier, a.positions()}});
    panels.morph_open = true;
    CommandQueue commands;
    const auto draw = [&] {
        in_sidebar(panels.layout,
                   [&] { morph_section(panels.morph_open, morph, history, commands); });
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
    TestPanels panels;
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

namespace {

/// The viewer's state the key actions work on, fresh: a morph that moves, an operation
/// preview up, no dialog open, no job running, no texture coordinates.
struct KeyFixture {
    TestPanels panels;
    RenderStyle style;
    ViewSettings settings;
    MorphState morph;
    CommandQueue commands;
    Log log{false};
    KeyActionTargets targets{
        panels, style, settings, morph, commands,        log, "/data/model.obj",
        false,  true,  false,    true,  panels.entries()};
};

/// A click that opens the menu (or submenu) whose closed header is "menu:LABEL", then a frame
/// over it; returns every "shortcut:" item drawn meanwhile.
template <class Draw>
void open_menu(Ui& ui, Draw draw, const std::string& label,
               std::map<std::string, std::string>& shortcuts) {
    const Box header = ui.rect("menu:" + label);
    const float x = (header.x0 + header.x1) / 2, y = (header.y0 + header.y1) / 2;
    const auto collect = [&] {
        for (const auto& [id, box] : ui.with_prefix("shortcut:")) {
            const std::size_t eq = id.find('=');
            shortcuts[id.substr(9, eq - 9)] = id.substr(eq + 1);
        }
    };
    ui.frame(draw, x, y, false);
    ui.frame(draw, x, y, true);
    collect();
    for (int i = 0; i < 3; ++i) {
        ui.frame(draw, x, y, false);
        collect();
    }
}

}  // namespace

TEST_CASE("every key binding reaches its action", "[panels][keys]") {
    for (const KeyBinding& b : kKeyBindings) {
        const std::string keys = chord_text(b.key, b.mods);
        INFO(keys);
        REQUIRE(find_key_binding(b.key, b.mods) == &b);  // no binding shadows another
        KeyFixture f;
        const PanelState before = f.panels;
        const bool morph_before = f.panels.morph_open, record_before = f.panels.record.open;
        const RenderStyle style = f.style;
        REQUIRE(dispatch_key(b.key, b.mods, f.targets));
        const auto queued = [&](auto command) {
            return f.commands.size() == 1 &&
                   std::holds_alternative<decltype(command)>(f.commands.front());
        };
        switch (b.action) {
            case KeyAction::FitView:
                CHECK(queued(FitView{}));
                break;
            case KeyAction::ToggleWireframe:
                CHECK(f.settings.wireframe ==
                      (style.wireframe ? WireframeOverlay::Off : WireframeOverlay::On));
                break;
            case KeyAction::ToggleBackFaceColor:
                CHECK(f.style.back_face_color != style.back_face_color);
                break;
            case KeyAction::ToggleFog:
                CHECK(f.style.fog != style.fog);
                break;
            case KeyAction::ToggleSpecular:
                CHECK(f.style.specular != style.specular);
                break;
            case KeyAction::CycleTexture:
                CHECK(f.style.mode == RenderMode::Textured);
                CHECK(f.style.texture_mode == TextureMode::Modulate);
                REQUIRE(f.log.size() == 1);  // no texture coordinates: a warning says so
                CHECK(f.log.entries()[0].level == LogEntry::Level::Warning);
                break;
            case KeyAction::Screenshot:
                CHECK(f.panels.screenshot.open);
                break;
            case KeyAction::PrintInfo:
                CHECK(queued(PrintInfo{}));
                break;
            case KeyAction::ToggleLog:
                CHECK(f.panels.log_open != before.log_open);
                break;
            case KeyAction::Undo:
                CHECK(queued(Undo{}));
                break;
            case KeyAction::Redo:
                CHECK(queued(Redo{}));
                break;
            case KeyAction::ToggleHistory:
                CHECK(f.panels.history_open != before.history_open);
                break;
            case KeyAction::ToggleMorph:
                CHECK(f.panels.morph_open != morph_before);
                break;
            case KeyAction::ToggleRecord:
                CHECK(f.panels.record.open != record_before);
                break;
            case KeyAction::PlayMorph:
                REQUIRE(queued(PlayMorph{}));
                CHECK(commands_of<PlayMorph>(f.commands).back()->play);
                break;
            case KeyAction::OpenFile:
                CHECK(f.panels.file_browser.open_requested);
                CHECK(f.panels.file_browser.purpose == FileBrowserState::Purpose::OpenMesh);
                break;
            case KeyAction::SaveFile:
                CHECK(f.panels.file_browser.open_requested);
                CHECK(f.panels.file_browser.purpose == FileBrowserState::Purpose::SaveMesh);
                break;
            case KeyAction::Quit:
                CHECK(queued(Quit{}));
                break;
            case KeyAction::ToggleHelp:
                CHECK(f.panels.help_open);
                break;
            case KeyAction::Escape:  // no dialog open: back from the preview
                CHECK(queued(CancelPreview{}));
                break;
        }
    }
    // Modifiers must match exactly; unbound keys do nothing.
    KeyFixture f;
    CHECK_FALSE(dispatch_key(GLFW_KEY_W, GLFW_MOD_ALT, f.targets));
    CHECK_FALSE(dispatch_key(GLFW_KEY_Z, GLFW_MOD_CONTROL | GLFW_MOD_ALT, f.targets));
    CHECK_FALSE(dispatch_key(GLFW_KEY_Q, 0, f.targets));
    CHECK(f.commands.empty());
}

TEST_CASE("keys typed into a widget stay there, quit is never lost", "[panels][keys]") {
    KeyFixture f;
    const RenderStyle before = f.style;
    // A text field has the keyboard: F, I, W and Ctrl+Z are the field's, not the bindings'.
    CHECK_FALSE(dispatch_key(GLFW_KEY_F, 0, f.targets, KeyboardFocus::Widget));
    CHECK_FALSE(dispatch_key(GLFW_KEY_I, 0, f.targets, KeyboardFocus::Widget));
    CHECK_FALSE(dispatch_key(GLFW_KEY_W, 0, f.targets, KeyboardFocus::Widget));
    CHECK_FALSE(dispatch_key(GLFW_KEY_Z, GLFW_MOD_CONTROL, f.targets, KeyboardFocus::Widget));
    CHECK(f.style.fog == before.fog);
    CHECK(f.commands.empty());
    // Ctrl+Q is an application shortcut: it quits whatever holds the keyboard.
    CHECK(dispatch_key(GLFW_KEY_Q, GLFW_MOD_CONTROL, f.targets, KeyboardFocus::Widget));
    REQUIRE(f.commands.size() == 1);
    CHECK(std::holds_alternative<Quit>(f.commands[0]));
}

TEST_CASE("key actions keep their conditions: busy, no morph, Esc's order, T's cycle",
          "[panels][keys]") {
    KeyFixture f;
    f.targets.busy = true;  // no file dialog while a job runs
    dispatch_key(GLFW_KEY_O, GLFW_MOD_CONTROL, f.targets);
    dispatch_key(GLFW_KEY_S, GLFW_MOD_CONTROL, f.targets);
    CHECK_FALSE(f.panels.file_browser.open_requested);
    f.morph.moves = false;  // nothing to animate
    dispatch_key(GLFW_KEY_SPACE, 0, f.targets);
    CHECK(commands_of<PlayMorph>(f.commands).empty());
    f.morph.moves = true;
    f.targets.has_entry = false;  // the loaded state: no morph
    dispatch_key(GLFW_KEY_SPACE, 0, f.targets);
    CHECK(commands_of<PlayMorph>(f.commands).empty());
    f.targets.has_entry = true;
    f.morph.playing = true;  // Space while playing stops it
    dispatch_key(GLFW_KEY_SPACE, 0, f.targets);
    REQUIRE(commands_of<PlayMorph>(f.commands).size() == 1);
    CHECK_FALSE(commands_of<PlayMorph>(f.commands)[0]->play);
    f.commands.clear();

    // Esc closes the key bindings, then about, then the screenshot dialog, then the preview.
    f.panels.help_open = f.panels.about_open = f.panels.screenshot.open = true;
    dispatch_key(GLFW_KEY_ESCAPE, 0, f.targets);
    CHECK((!f.panels.help_open && f.panels.about_open && f.panels.screenshot.open));
    dispatch_key(GLFW_KEY_ESCAPE, 0, f.targets);
    CHECK((!f.panels.about_open && f.panels.screenshot.open));
    dispatch_key(GLFW_KEY_ESCAPE, 0, f.targets);
    CHECK(!f.panels.screenshot.open);
    CHECK(f.commands.empty());
    dispatch_key(GLFW_KEY_ESCAPE, 0, f.targets);
    CHECK(commands_of<CancelPreview>(f.commands).size() == 1);

    // T: off -> modulate -> replace -> off; with texture coordinates no warning.
    f.targets.has_texcoords = true;
    const std::pair<RenderMode, TextureMode> cycle[] = {
        {RenderMode::Textured, TextureMode::Modulate},
        {RenderMode::Textured, TextureMode::Replace},
        {RenderMode::Smooth, TextureMode::Off},
        {RenderMode::Textured, TextureMode::Modulate}};
    for (const auto& [mode, texture] : cycle) {
        dispatch_key(GLFW_KEY_T, 0, f.targets);
        CHECK(f.style.mode == mode);
        CHECK(f.style.texture_mode == texture);
    }
    CHECK(f.log.size() == 0);
}

TEST_CASE("the menus show the key bindings' shortcut texts, F1 lists every binding",
          "[panels][keys]") {
    // The menu items with a key, as the menus spelled their shortcuts by hand before the
    // table, with the action the item does.
    struct Expected {
        const char* label;
        KeyAction action;
        const char* keys;
    };
    const Expected expected[] = {
        {"Open...", KeyAction::OpenFile, "Ctrl+O"},
        {"Save as...", KeyAction::SaveFile, "Ctrl+S"},
        {"Quit", KeyAction::Quit, "Ctrl+Q"},
        {"Undo", KeyAction::Undo, "Ctrl+Z"},
        {"Redo", KeyAction::Redo, "Ctrl+Shift+Z"},
        {"History", KeyAction::ToggleHistory, "H"},
        {"Morph", KeyAction::ToggleMorph, "M"},
        {"Record", KeyAction::ToggleRecord, "R"},
        {"On", KeyAction::ToggleWireframe, "W"},  // Rendering > Wireframe overlay
        {"Off", KeyAction::ToggleWireframe, "W"},
        {"Back-face colour", KeyAction::ToggleBackFaceColor, "B"},
        {"off", KeyAction::CycleTexture, "T"},  // Rendering > Texture
        {"Specular highlight", KeyAction::ToggleSpecular, "S"},
        {"Fog", KeyAction::ToggleFog, "F"},
        {"Fit view", KeyAction::FitView, "Home"},
        {"Screenshot...", KeyAction::Screenshot, "F12"},
        {"Model information", KeyAction::PrintInfo, "I"},
        {"Log", KeyAction::ToggleLog, "L"},
        {"Key bindings", KeyAction::ToggleHelp, "F1"},
    };

    // Open every menu and submenu with a key item; collect the shortcut texts drawn.
    std::map<std::string, std::string> shortcuts;
    const std::string top_menus[] = {"File", "Edit", "Rendering", "Window", "Help"};
    for (const std::string& menu : top_menus) {
        Ui ui;
        RenderStyle style;
        ViewSettings settings;
        TestPanels panels;
        MenuContext context;
        RenderContext render;
        CommandQueue commands;
        const auto draw = [&] {
            menu_bar(style, settings, panels, panels.list(), context, render, commands);
        };
        ui.frame(draw);
        open_menu(ui, draw, menu, shortcuts);
        if (menu == "Rendering")
            for (const char* sub : {"Wireframe overlay", "Texture", "Lighting and colours"})
                open_menu(ui, draw, sub, shortcuts);
    }
    for (const Expected& e : expected) {
        INFO(e.label);
        REQUIRE(shortcuts.count(e.label) == 1);
        CHECK(shortcuts[e.label] == e.keys);
        CHECK(shortcut_text(e.action) == e.keys);
        // The key shown triggers the item's action.
        const auto bound =
            std::find_if(kKeyBindings.begin(), kKeyBindings.end(),
                         [&](const KeyBinding& b) { return chord_text(b.key, b.mods) == e.keys; });
        REQUIRE(bound != kKeyBindings.end());
        CHECK(bound->action == e.action);
    }
    CHECK(shortcuts.size() == std::size(expected));  // no other item shows a key

    // The key bindings window: every binding's keys in the row of its action's help text.
    const std::vector<BindingHelpRow> rows = binding_help_rows();
    for (const KeyBinding& b : kKeyBindings) {
        const std::string keys = chord_text(b.key, b.mods);
        INFO(keys);
        const auto lists = [&](const BindingHelpRow& r) {
            const std::string all = ", " + r.keys + ", ";
            return r.action == b.help && all.find(", " + keys + ", ") != std::string::npos;
        };
        CHECK(std::count_if(rows.begin(), rows.end(), lists) == 1);
    }
    CHECK(chord_text(GLFW_KEY_Z, GLFW_MOD_CONTROL | GLFW_MOD_SHIFT) == "Ctrl+Shift+Z");
    CHECK(chord_text(GLFW_KEY_ESCAPE, 0) == "Esc");
}

TEST_CASE("the legend shows the histogram of the values over its bar", "[panels][legend]") {
    // Issue 40: the distance colouring's legend has the histogram of the distances.
    const std::vector<double> values = {0.0, 0.1, 0.1,  0.2,
                                        0.9, 5.0, -1.0, std::numeric_limits<double>::quiet_NaN()};
    const std::vector<std::size_t> counts = value_histogram(values, {0.0, 1.0}, 10);
    REQUIRE(counts.size() == 10);
    CHECK(counts[0] == 2);  // 0 and -1 (below the range: the first bin)
    CHECK(counts[1] == 2);
    CHECK(counts[2] == 1);
    CHECK(counts[9] == 2);  // 0.9 and 5 (above: the last bin)
    std::size_t total = 0;
    for (std::size_t c : counts) total += c;
    CHECK(total == 7);  // NaN nowhere
    CHECK(value_histogram(values, {1.0, 1.0}, 4) == std::vector<std::size_t>(4, 0));

    Ui ui;
    ColoringOptions options;
    VertexColors colors;
    colors.has_legend = true;
    colors.kind = ColorMapKind::Sequential;
    colors.label = "distance to the compared surface";
    colors.range = {0.0, 1.0};
    const auto draw = [&] { draw_legend(colors, options); };
    ui.frame(draw);
    ui.frame(draw);
    CHECK_FALSE(ui.has("legend: histogram"));  // no values: no histogram
    colors.values = values;
    ui.frame(draw);
    ui.frame(draw);
    REQUIRE(ui.has("legend: histogram"));
    const Box histogram = ui.rect("legend: histogram");
    const Box bar = ui.rect("legend: bar");
    CHECK(histogram.x0 == Approx(bar.x0));
    CHECK(histogram.x1 == Approx(bar.x1));
    CHECK(histogram.y1 <= bar.y0 + 0.01f);  // above the bar
}
