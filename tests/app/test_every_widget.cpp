// Every widget of the sidebar, pressed (issue 23): no ImGui ID is used twice in a frame, in
// any combination of open sections; every button queues the command it names; the sections
// keep their parameters apart; a typed value outside its range is clamped at once; the
// stability warning moves nothing below it.
//
// Duplicate IDs are found where ImGui registers every item: ImGui::ItemAdd. This test binary
// is linked with -Wl,--wrap for that symbol (tests/CMakeLists.txt), so that every call from
// ImGui's widgets (imgui_widgets.cpp calls it across object files) passes through the
// recorder below first.
#include <imgui.h>
#include <imgui_internal.h>
#include <catch2/catch.hpp>

#include <algorithm>
#include <functional>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "app/session/reference_figures.h"
#include "app/viewer/panels.h"
#include "core/algorithms/components.h"
#include "core/algorithms/fairing.h"
#include "core/algorithms/generators.h"
#include "core/errors.h"
#include "tests/app/panel_ui.h"
#include "tests/app/test_tools.h"

using namespace trilab;
using namespace trilab::viewer;
using namespace trilab::viewer::testing;

namespace {

/// One item ImGui registered in the current frame.
struct ItemSeen {
    ImGuiID id;
    std::string window;
    float x0, y0;
};
bool recording_items = false;
std::vector<ItemSeen> items_seen;

}  // namespace

// NOLINTBEGIN(readability-identifier-naming,bugprone-reserved-identifier): the linker's names
extern "C" bool __real__ZN5ImGui7ItemAddERK6ImRectjPS1_i(const ImRect& bb, ImGuiID id,
                                                         const ImRect* nav_bb, int flags);
extern "C" bool __wrap__ZN5ImGui7ItemAddERK6ImRectjPS1_i(const ImRect& bb, ImGuiID id,
                                                         const ImRect* nav_bb, int flags) {
    if (recording_items && id != 0) {
        const ImGuiWindow* window = ImGui::GetCurrentWindow();
        items_seen.push_back({id, window ? window->Name : "", bb.Min.x, bb.Min.y});
    }
    return __real__ZN5ImGui7ItemAddERK6ImRectjPS1_i(bb, id, nav_bb, flags);
}
// NOLINTEND(readability-identifier-naming,bugprone-reserved-identifier)

namespace {

/// Everything the sidebar shows, in one place that does not move (the context points into it).
struct Sidebar {
    TestPanels panels;
    MorphState morph;
    History history;
    FrequencyDocument frequency;
    std::vector<std::string> info{"model: test", "vertices 12"};
    InspectorView inspector;
    SidebarContext context;
    CommandQueue commands;

    Sidebar() {
        const HalfedgeMesh a = make_default_model();
        HalfedgeMesh b = a;
        std::vector<Point> moved = b.positions();
        for (Point& p : moved) p *= 1.1;
        b.set_positions(moved);
        history.reset(a, "Load a.off");
        history.push("Smooth", "--step 0.5", 1.0, {b}, {MorphCorrespondence{}});
        // A decomposition to show the band sliders and plots (the panel reads only these).
        frequency.decomposition = std::make_shared<const SpectralDecomposition>();
        frequency.valid = true;
        frequency.eigenvalues = {0.0f, 0.5f, 1.0f, 2.0f};
        frequency.log_coefficients = {1.0f, 0.0f, -1.0f, -2.0f};
        context.history = &history;
        context.morph = &morph;
        context.closed = true;
        context.can_record = true;
        context.open_seams = true;
        context.frequency = &frequency;
        context.info = &info;
        // Two picks with their rows, a measurement and the provenance plot.
        inspector.has_picks = true;
        inspector.note = "computing the geodesic distance";
        inspector.groups = {{"Vertex 3", {{"position", "0 1 2"}, {"valence", "6"}}},
                            {"Edge 7", {{"length", "0.5"}}},
                            {"Face 2", {{"area", "0.1"}}},
                            {"Measure: vertex 3 to 9", {{"straight", "1"}, {"geodesic", "1.2"}}}};
        inspector.moved_by_entry = {0.0f, 0.25f, 0.5f};
        inspector.current_entry = 2;
        context.inspector = &inspector;
        // A selection, a pick and a colouring with values: every Selection button is enabled.
        context.has_selection = true;
        context.selected = 10;
        context.n_vertices = 1002;
        context.has_pick = true;
        context.has_values = true;
        context.values_max = 1.0;
        // The stability warning and its button show (a step above the limit).
        panels.fairing.max_stable_step = 1.0;
        panels.fairing.lens.lambda_max = 2.0;  // the transfer curve over the analytic range
        panels.fairing.op.value("step").x = 50.0;
    }
    Sidebar(const Sidebar&) = delete;
    Sidebar& operator=(const Sidebar&) = delete;

    void open_all() {
        for (OperationPanelState& tool : panels.tools) tool.open = true;
        panels.fairing.open = true;
        panels.frequency.open = panels.subdivision.open = panels.decimation.open = true;
        panels.morph_open = panels.record.open = panels.info_open = true;
        panels.inspector_open = true;
        panels.selection.open = true;
        panels.decimation.lod_open = true;
        panels.denoise.open = true;
        panels.features.open = true;
        panels.fill_holes.open = true;
        panels.remesh.open = true;
        panels.compare_open = true;
    }
    void draw() {
        in_sidebar(panels.layout, [&] { sidebar_sections(panels.list(), context, commands); });
    }
};

/// The IDs registered more than once in the frame `draw` draws, with where they were.
template <class Draw>
std::vector<std::string> duplicate_ids(Ui& ui, Draw draw) {
    items_seen.clear();
    recording_items = true;
    ui.frame(draw);
    recording_items = false;
    std::map<ImGuiID, std::vector<const ItemSeen*>> by_id;
    for (const ItemSeen& item : items_seen) by_id[item.id].push_back(&item);
    std::vector<std::string> out;
    for (const auto& [id, seen] : by_id) {
        if (seen.size() < 2) continue;
        std::string what = "ID " + std::to_string(id) + " in " + seen[0]->window + " at";
        for (const ItemSeen* s : seen)
            what += " (" + std::to_string(int(s->x0)) + ", " + std::to_string(int(s->y0)) + ")";
        for (const WidgetNote& n : ui.notes())
            if (n.imgui_id == id) what += " '" + n.path() + "'";
        out.push_back(what);
    }
    return out;
}

/// The pressable widget at `path` in the last frame (exactly one).
WidgetNote find_widget(const Ui& ui, const std::string& path, WidgetNote::Kind kind) {
    std::vector<WidgetNote> found;
    for (const WidgetNote& n : ui.notes())
        if (n.kind == kind && n.path() == path) found.push_back(n);
    INFO(path);
    REQUIRE(found.size() == 1);
    return found[0];
}

template <class Draw>
void press(Ui& ui, Draw draw, const WidgetNote& n) {
    ui.click(draw, 0.5f * (n.x0 + n.x1), 0.5f * (n.y0 + n.y1));
}

}  // namespace

TEST_CASE("no widget ID is used twice in a frame, in any combination of open sections",
          "[panels][ids]") {
    Ui ui(1280, 6000);  // tall: every widget is on the screen
    Sidebar s;
    s.open_all();
    const auto draw = [&] { s.draw(); };
    ui.frame(draw);
    // The recorder sees what ImGui registers: with every section open, hundreds of items.
    items_seen.clear();
    recording_items = true;
    ui.frame(draw);
    recording_items = false;
    CHECK(items_seen.size() > 60);

    bool* flags[] = {
        &s.panels.tool("noise")->open, &s.panels.tool("weld")->open, &s.panels.fairing.open,
        &s.panels.frequency.open,      &s.panels.subdivision.open,   &s.panels.decimation.open,
        &s.panels.morph_open,          &s.panels.record.open,        &s.panels.info_open};
    const unsigned n = unsigned(std::size(flags));
    for (unsigned mask = 0; mask < (1u << n); ++mask) {
        for (unsigned i = 0; i < n; ++i) *flags[i] = (mask >> i) & 1u;
        s.panels.decimation.lod_open = (mask & 1u) != 0;
        s.panels.decimation.lod_ready = (mask & 2u) != 0;
        s.panels.record.running = (mask & 4u) != 0;
        s.panels.fairing.previewing = s.panels.subdivision.previewing = (mask & 8u) != 0;
        s.panels.decimation.previewing = s.panels.tool("noise")->previewing = (mask & 8u) != 0;
        s.morph.playing = (mask & 16u) != 0;
        s.panels.inspector_open = (mask & 32u) != 0;
        s.panels.denoise.open = s.panels.fairing.open;  // one more section, no more frames
        s.panels.denoise.previewing = (mask & 8u) != 0;
        s.panels.features.open = s.panels.fairing.open;
        s.panels.features.previewing = (mask & 8u) != 0;
        s.panels.fill_holes.open = s.panels.fairing.open;
        s.panels.fill_holes.previewing = (mask & 8u) != 0;
        s.panels.remesh.open = s.panels.fairing.open;
        s.panels.remesh.previewing = (mask & 8u) != 0;
        s.panels.compare_open = s.panels.fairing.open;
        ui.frame(draw);  // the sections take their new state
        const std::vector<std::string> duplicates = duplicate_ids(ui, draw);
        INFO("open sections mask " << mask);
        for (const std::string& d : duplicates) INFO(d);
        CHECK(duplicates.empty());
        if (!duplicates.empty()) break;
    }
}

TEST_CASE("the menus and dialogs use no widget ID twice", "[panels][ids]") {
    Ui ui;
    RenderStyle style;
    ViewSettings settings;
    TestPanels panels;
    CommandQueue commands;
    MenuContext menu;
    RenderContext render;
    const auto draw = [&] {
        menu_bar(style, settings, panels, panels.list(), menu, render, commands);
        screenshot_dialog(panels.screenshot, commands);
    };
    panels.screenshot.open = true;
    ui.frame(draw);
    ui.frame(draw);
    // Open each menu of the bar in turn and look at the frame that shows it.
    std::vector<WidgetNote> menus;
    for (const WidgetNote& n : ui.notes())
        if (n.kind == WidgetNote::Kind::Menu && n.section.empty()) menus.push_back(n);
    REQUIRE(menus.size() >= 7);
    for (const WidgetNote& m : menus) {
        press(ui, draw, m);
        const std::vector<std::string> duplicates = duplicate_ids(ui, draw);
        INFO("menu " << m.label);
        for (const std::string& d : duplicates) INFO(d);
        CHECK(duplicates.empty());
        ui.click(draw, 1200, 700);  // close it
    }
}

TEST_CASE("every button of every section queues what it says", "[panels][buttons]") {
    // What pressing each button does, by its path: a command queued or a state changed.
    using Check = std::function<void(const Sidebar&)>;
    const auto applies = [](const char* name) {
        return Check([name](const Sidebar& s) {
            const auto applied = commands_of<ApplyOperation>(s.commands);
            REQUIRE(applied.size() == 1);
            CHECK(applied[0]->op.name() == name);
        });
    };
    const auto queues_one = [](auto tag) {
        using T = decltype(tag);
        return Check([](const Sidebar& s) {
            CHECK(commands_of<T>(s.commands).size() == 1);
            CHECK(commands_of<ApplyOperation>(s.commands).empty());
        });
    };
    const auto queues_selection_at_pick = [](bool component) {
        return Check([component](const Sidebar& s) {
            const auto at = commands_of<SelectAtPick>(s.commands);
            REQUIRE(at.size() == 1);
            CHECK(at[0]->component == component);
            if (!component) CHECK(at[0]->radius == Approx(s.panels.selection.geodesic_radius));
        });
    };
    const auto edits_selection = [](EditSelection::Kind kind) {
        return Check([kind](const Sidebar& s) {
            const auto edits = commands_of<EditSelection>(s.commands);
            REQUIRE(edits.size() == 1);
            CHECK(edits[0]->kind == kind);
        });
    };
    std::map<std::string, Check> expected = {
        {"Fairing/Smooth", applies("smooth")},
        {"Fairing/Cancel", queues_one(CancelPreview{})},
        {"Fairing/Use implicit",
         [](const Sidebar& s) {
             const auto previews = commands_of<PreviewOperation>(s.commands);
             REQUIRE_FALSE(previews.empty());
             CHECK(int(previews.back()->op.value("integration").x) == int(Integration::Implicit));
         }},
        {"Frequency decomposition/Decompose", queues_one(Decompose{})},
        {"Frequency decomposition/Restore", queues_one(RestoreDecomposed{})},
        {"Subdivision/Subdivide", applies("subdivide")},
        {"Denoise/Denoise", applies("denoise")},
        {"Denoise/Cancel", queues_one(CancelPreview{})},
        {"Features/Detect", applies("features")},
        {"Features/Cancel", queues_one(CancelPreview{})},
        {"Features/Sharpen the selection's edges",
         [](const Sidebar& s) {
             const auto runs = commands_of<RunOperation>(s.commands);
             REQUIRE(runs.size() == 1);
             CHECK(runs[0]->op.name() == "sharpen");
             CHECK(runs[0]->op.text().find("--clear") == std::string::npos);
         }},
        {"Features/Clear them",
         [](const Sidebar& s) {
             const auto runs = commands_of<RunOperation>(s.commands);
             REQUIRE(runs.size() == 1);
             CHECK(runs[0]->op.text().find("--clear") != std::string::npos);
         }},
        {"Fill holes/Fill", applies("fill-holes")},
        {"Fill holes/Cancel", queues_one(CancelPreview{})},
        {"Remesh/Remesh", applies("remesh")},
        {"Remesh/Cancel", queues_one(CancelPreview{})},
        {"Compare/Colour by the distance",
         [](const Sidebar& s) {
             CHECK(commands_of<UpdateColoring>(s.commands).size() == 1);
             CHECK(s.panels.context.view.settings.coloring == VertexColoring::SurfaceDistance);
         }},
        {"Subdivision/Cancel", queues_one(CancelPreview{})},
        {"Subdivision/Weld coincident vertices", applies("weld")},
        {"Decimation/Decimate", applies("decimate")},
        {"Decimation/Cancel", queues_one(CancelPreview{})},
        {"Decimation/Level of detail/Build levels", queues_one(BuildLevelOfDetail{})},
        {"Decimation/Level of detail/Apply level", queues_one(ApplyLevelOfDetail{})},
        {"Decimation/Level of detail/Cancel", queues_one(CancelPreview{})},
        {"Morph/Animate",
         [](const Sidebar& s) {
             const auto play = commands_of<PlayMorph>(s.commands);
             REQUIRE(play.size() == 1);
             CHECK(play[0]->play);
         }},
        {"Morph/Stop",
         [](const Sidebar& s) {
             const auto play = commands_of<PlayMorph>(s.commands);
             REQUIRE(play.size() == 1);
             CHECK_FALSE(play[0]->play);
         }},
        {"Morph/Before",
         [](const Sidebar& s) {
             const auto at = commands_of<ShowMorphAt>(s.commands);
             REQUIRE(at.size() == 1);
             CHECK(at[0]->t == 0.0);
         }},
        {"Morph/After",
         [](const Sidebar& s) {
             const auto at = commands_of<ShowMorphAt>(s.commands);
             REQUIRE(at.size() == 1);
             CHECK(at[0]->t == 1.0);
         }},
        {"Record/Record", queues_one(StartRecording{})},
        {"Inspector/Clear picks", queues_one(ClearPicks{})},
        {"Fairing/Decompose for this operator", queues_one(Decompose{})},
        {"Fairing/Show the diverging run", queues_one(ShowDivergingRun{})},
        {"Inspector/Centre view here", queues_one(CentreOnPick{})},
        {"Record/Cancel", queues_one(CancelRecording{})},
        {"Selection/Brush",
         [](const Sidebar& s) {
             CHECK(s.panels.selection.tool == SelectionPanelState::Tool::Brush);
             CHECK(s.commands.empty());
         }},
        {"Selection/Lasso",
         [](const Sidebar& s) {
             CHECK(s.panels.selection.tool == SelectionPanelState::Tool::Lasso);
             CHECK(s.commands.empty());
         }},
        {"Selection/Geodesic ball at pick", queues_selection_at_pick(false)},
        {"Selection/Component at pick", queues_selection_at_pick(true)},
        {"Selection/Threshold", queues_one(SelectThreshold{})},
        {"Selection/Grow", edits_selection(EditSelection::Kind::Grow)},
        {"Selection/Shrink", edits_selection(EditSelection::Kind::Shrink)},
        {"Selection/Invert", edits_selection(EditSelection::Kind::Invert)},
        {"Selection/Clear", edits_selection(EditSelection::Kind::Clear)},
        {"Selection/Feather", edits_selection(EditSelection::Kind::Feather)},
    };
    // Every tool from the registry: Apply (where its defaults make a valid run; otherwise it
    // is drawn disabled with the reason) and the preview's Cancel.
    const TestPanels registry;
    for (const OperationPanelState& tool : registry.tools) {
        if (tool.op.def->params.empty()) continue;  // a menu action
        const std::string title = tool_section_title(*tool.op.def);
        bool valid = true;
        try {
            check_operation(tool.op);
        } catch (const InvalidArgument&) {
            valid = false;
        }
        if (valid) expected.emplace(title + "/Apply", applies(tool.op.def->name.c_str()));
        expected.emplace(title + "/Cancel", queues_one(CancelPreview{}));
    }
    // The states that show every button: idle; previews up, levels built, recording, playing.
    const std::vector<std::function<void(Sidebar&)>> scenes = {
        [](Sidebar& s) { s.morph.t = 0.5; },
        [](Sidebar& s) {
            s.panels.fairing.previewing = s.panels.subdivision.previewing = true;
            s.panels.decimation.previewing = s.panels.denoise.previewing = true;
            s.panels.features.previewing = true;
            s.panels.fill_holes.previewing = true;
            s.panels.remesh.previewing = true;
            for (OperationPanelState& tool : s.panels.tools) tool.previewing = true;
            s.panels.decimation.lod_ready = true;
            s.panels.record.running = true;
            s.morph.playing = true;
        },
    };
    std::set<std::string> pressed;
    for (const auto& scene : scenes) {
        std::vector<WidgetNote> buttons;
        {
            Ui ui(1280, 6000);
            Sidebar s;
            s.open_all();
            scene(s);
            const auto draw = [&] { s.draw(); };
            ui.frame(draw);
            ui.frame(draw);
            for (const WidgetNote& n : ui.notes())
                if (n.kind == WidgetNote::Kind::Button && n.enabled) buttons.push_back(n);
        }
        REQUIRE_FALSE(buttons.empty());
        for (const WidgetNote& b : buttons) {
            INFO("button " << b.path());
            const auto it = expected.find(b.path());
            REQUIRE(it != expected.end());  // a new button needs its expectation here
            Ui ui(1280, 6000);
            Sidebar s;
            s.open_all();
            scene(s);
            const auto draw = [&] { s.draw(); };
            ui.frame(draw);
            ui.frame(draw);
            s.commands.clear();
            // The press: hover, down, up; the actions of the frame of the release count.
            const float x = 0.5f * (b.x0 + b.x1), y = 0.5f * (b.y0 + b.y1);
            ui.frame(draw, x, y, false);
            ui.frame(draw, x, y, true);
            s.commands.clear();
            ui.frame(draw, x, y, false);
            it->second(s);
            pressed.insert(b.path());
        }
    }
    for (const auto& [path, check] : expected) {
        INFO("never shown: " << path);
        CHECK(pressed.count(path) == 1);
    }
}

TEST_CASE("Record's button records: it does not share the section header's ID",
          "[panels][buttons]") {
    Ui ui;
    Sidebar s;
    s.panels.record.open = true;
    const auto draw = [&] { s.draw(); };
    ui.frame(draw);
    ui.frame(draw);
    const WidgetNote record = find_widget(ui, "Record/Record", WidgetNote::Kind::Button);
    const WidgetNote header = find_widget(ui, "Record", WidgetNote::Kind::Header);
    CHECK(record.imgui_id != header.imgui_id);
    s.commands.clear();
    press(ui, draw, record);
    CHECK(commands_of<StartRecording>(s.commands).size() == 1);
    CHECK(s.panels.record.open);  // the section stayed open
}

TEST_CASE("sections keep their parameters apart: a slider moves only its own", "[panels][ids]") {
    Ui ui(1280, 6000);
    Sidebar s;
    s.panels.fairing.open = s.panels.subdivision.open = s.panels.decimation.open = true;
    s.panels.fairing.op.value("step").x = 0.5;  // no warning
    const auto draw = [&] { s.draw(); };
    ui.frame(draw);
    ui.frame(draw);
    const double fairing_before = s.panels.fairing.op.value("iterations").x;
    const double decimation_before = s.panels.decimation.op.value("iterations").x;
    std::vector<WidgetNote> iterations;
    for (const WidgetNote& n : ui.notes())
        if (n.id == "iterations" && n.section == "Subdivision") iterations.push_back(n);
    REQUIRE(iterations.size() == 1);
    const WidgetNote& slider = iterations[0];
    const float y = 0.5f * (slider.y0 + slider.y1);
    s.commands.clear();
    // The item's rectangle includes its label on the right: press inside the frame, well
    // right of its left end (the smallest value, 1).
    ui.frame(draw, slider.x0 + 40, y, false);
    ui.frame(draw, slider.x0 + 40, y, true);
    ui.frame(draw, slider.x0 + 40, y, false);
    CHECK(s.panels.subdivision.op.value("iterations").x > 1);
    CHECK(s.panels.fairing.op.value("iterations").x == fairing_before);
    CHECK(s.panels.decimation.op.value("iterations").x == decimation_before);
    const auto previews = commands_of<PreviewOperation>(s.commands);
    REQUIRE(previews.size() == 1);
    CHECK(previews[0]->op.name() == "subdivide");
}

TEST_CASE("the morph controls are drawn once, in the Morph section, and respond there",
          "[panels]") {
    Ui ui(1280, 6000);
    Sidebar s;
    s.open_all();
    s.morph.t = 0.5;
    const auto draw = [&] { s.draw(); };
    ui.frame(draw);
    ui.frame(draw);
    int animate = 0;
    for (const WidgetNote& n : ui.notes())
        if (n.kind == WidgetNote::Kind::Button && n.label == "Animate") ++animate;
    CHECK(animate == 1);
    press(ui, draw, find_widget(ui, "Morph/Animate", WidgetNote::Kind::Button));
    const auto play = commands_of<PlayMorph>(s.commands);
    REQUIRE(play.size() == 1);
    CHECK(play[0]->play);
}

TEST_CASE("a typed value outside its range is clamped at once, and every widget shows it",
          "[panels][input]") {
    Ui ui;
    Sidebar s;
    s.panels.fairing.open = true;
    s.panels.fairing.max_stable_step = 1e9;  // no warning: the rows stay where they are
    const auto draw = [&] { s.draw(); };
    ui.frame(draw);
    ui.frame(draw);
    const auto type_into_step = [&](const char* text) {
        Box field = ui.rect("step:value");
        const float x = 0.5f * (field.x0 + field.x1), y = 0.5f * (field.y0 + field.y1);
        ui.click(draw, x, y);
        ImGuiIO& io = ImGui::GetIO();
        // Select what is there and replace it (Ctrl+A: the key map has no backend here).
        io.KeyMap[ImGuiKey_A] = 'A';
        io.KeyCtrl = true;
        io.KeysDown[io.KeyMap[ImGuiKey_A]] = true;
        ui.frame(draw, x, y);
        io.KeysDown[io.KeyMap[ImGuiKey_A]] = false;
        io.KeyCtrl = false;
        ui.frame(draw, x, y);
        for (const char* c = text; *c; ++c) {
            io.AddInputCharacter(unsigned(*c));
            ui.frame(draw, x, y);
        }
    };
    SECTION("above the largest value") {
        type_into_step("1e9");
        const double step = s.panels.fairing.op.value("step").x;
        CHECK(step == 1e6);                // the declared maximum, at once
        CHECK(ImGui::GetActiveID() == 0);  // the field let go: it shows 1e+06 now
        CHECK(s.panels.fairing.input_note.find("1e+09") != std::string::npos);
        CHECK(s.panels.fairing.input_note.find("using 1e+06") != std::string::npos);
        const auto previews = commands_of<PreviewOperation>(s.commands);
        REQUIRE_FALSE(previews.empty());
        CHECK(previews.back()->op.value("step").x == 1e6);
    }
    SECTION("below the smallest value") {
        type_into_step("-5");
        CHECK(s.panels.fairing.op.value("step").x == 0.0);
        CHECK(ImGui::GetActiveID() == 0);
    }
    SECTION("a value in range stays as typed, the field keeps the focus") {
        type_into_step("0.25");
        CHECK(s.panels.fairing.op.value("step").x == 0.25);
        CHECK(ImGui::GetActiveID() != 0);
        CHECK(s.panels.fairing.input_note.empty());
    }
}

TEST_CASE("the stability warning and its button move nothing below them", "[panels]") {
    Ui ui;
    Sidebar s;
    s.panels.fairing.open = s.panels.subdivision.open = true;
    const auto draw = [&] { s.draw(); };
    s.panels.fairing.op.value("step").x = 0.5;  // below the limit 1.0: no warning
    ui.frame(draw);
    ui.frame(draw);
    CHECK_FALSE(ui.has("unstable"));
    const Box smooth_stable = ui.rect("Smooth");
    const Box subdivide_stable = ui.rect("Subdivide");
    s.panels.fairing.op.value("step").x = 50;  // above: the warning and its button show
    ui.frame(draw);
    ui.frame(draw);
    REQUIRE(ui.has("unstable"));
    REQUIRE(ui.has("Use implicit integration"));
    CHECK(ui.rect("Smooth").y0 == smooth_stable.y0);
    CHECK(ui.rect("Subdivide").y0 == subdivide_stable.y0);
    // And implicit integration, which needs no warning, keeps the rows too.
    s.panels.fairing.op.value("integration").x = int(Integration::Implicit);
    ui.frame(draw);
    CHECK_FALSE(ui.has("unstable"));
    CHECK(ui.rect("Smooth").y0 == smooth_stable.y0);
    // Issue 38, item 13: a clamped value's note, Cancel and the preview's note come on the
    // Apply row; the transfer curve and its button below do not move.
    REQUIRE(ui.has("Show the diverging run"));
    const Box diverging = ui.rect("Show the diverging run");
    s.panels.fairing.input_note = "step 1e+09 is above the largest allowed; using 1e+06";
    s.panels.fairing.preview_note = "preview 2 ms";
    s.panels.fairing.previewing = true;
    ui.frame(draw);
    ui.frame(draw);
    CHECK(ui.has("Cancel"));
    CHECK(ui.rect("Smooth").y0 == smooth_stable.y0);
    CHECK(ui.rect("Show the diverging run").y0 == diverging.y0);
    s.panels.fairing.input_note.clear();
    ui.frame(draw);
    CHECK(ui.rect("Show the diverging run").y0 == diverging.y0);
}

TEST_CASE("an optional number's check box carries the parameter's label", "[panels]") {
    Ui ui;
    Sidebar s;
    s.panels.frequency.open = true;
    const auto draw = [&] { s.draw(); };
    ui.frame(draw);
    ui.frame(draw);
    const WidgetNote k = find_widget(ui, "Frequency decomposition/k", WidgetNote::Kind::Checkbox);
    CHECK(k.id == "k:on");
}

TEST_CASE("slider grabs leave the value text legible", "[panels]") {
    ImGuiStyle style;
    apply_panel_style(style);
    CHECK(style.GrabMinSize <= 6.0f);  // a thin bar, not a block over the digits
    CHECK(style.Colors[ImGuiCol_SliderGrab].w <= 0.5f);
    CHECK(style.Colors[ImGuiCol_SliderGrabActive].w <= 0.7f);
}

TEST_CASE("sidebar notes are the GUI's words: no command-line options in labels", "[panels]") {
    Ui ui(1280, 6000);
    Sidebar s;
    s.open_all();
    s.panels.decimation.op.value("target-vertices").on = false;
    const auto draw = [&] { s.draw(); };
    ui.frame(draw);
    ui.frame(draw);
    const WidgetNote target =
        find_widget(ui, "Decimation/target vertices", WidgetNote::Kind::Checkbox);
    CHECK(target.id == "target-vertices:on");
    CHECK(default_note_text(s.panels.decimation.op.def
                                ->params[s.panels.decimation.op.def->index("target-vertices")])
              .find("--") == std::string::npos);
}

TEST_CASE("the Frequency section says whether the mesh shows a band", "[panels][frequency]") {
    Ui ui;
    Sidebar s;
    s.panels.frequency.open = true;
    s.panels.frequency.hi = 3;  // the sliders read 0..3 right after Decompose
    const auto draw = [&] { s.draw(); };
    ui.frame(draw);
    ui.frame(draw);
    const auto state = [&] {
        for (const WidgetNote& n : ui.notes())
            if (n.id == "band-state") return n.label;
        return std::string();
    };
    CHECK(state().find("its own shape") != std::string::npos);
    s.frequency.applied = true;
    s.frequency.applied_lo = 0;
    s.frequency.applied_hi = 2;
    ui.frame(draw);
    CHECK(state().rfind("the mesh shows the band 0 .. 2", 0) == 0);
}

TEST_CASE("every registered operation has a panel: its own, or a tool's from the registry",
          "[panels][tools]") {
    TestPanels panels;
    // Exactly one tool holds each operation (the Frequency tool the decomposition's).
    for (const OperationDef* def : operation_defs()) {
        INFO(def->name);
        int holders = def == panels.frequency.op.def ? 1 : 0;
        for (Tool* tool : panels.list())
            for (OperationPanelState* panel : tool->operation_panels())
                if (panel->op.def == def) ++holders;
        CHECK(holders == 1);
    }
    // The operations with tools of their own have no generic panel.
    for (const char* own : {"smooth", "subdivide", "decimate", "spectrum", "denoise", "features"}) {
        INFO(own);
        CHECK(panels.tool(own) == nullptr);
    }
    CHECK(panels.tool("noise") != nullptr);
    // A tool with parameters is a sidebar section named after its label; Apply applies it.
    Ui ui(1280, 6000);
    CommandQueue commands;
    for (OperationPanelState& tool : panels.tools) tool.open = true;
    const auto draw = [&] {
        in_sidebar(panels.layout, [&] { tools_section(panels.tools, false, commands); });
    };
    ui.frame(draw);
    ui.frame(draw);
    for (OperationPanelState& tool : panels.tools) {
        const std::string title = tool_section_title(*tool.op.def);
        INFO(title);
        if (tool.op.def->params.empty()) {
            CHECK_FALSE(ui.has("section:" + title));  // a menu action instead
            continue;
        }
        const WidgetNote apply = find_widget(ui, title + "/Apply", WidgetNote::Kind::Button);
        bool valid = true;
        try {
            check_operation(tool.op);
        } catch (const InvalidArgument&) {
            valid = false;
        }
        CHECK(apply.enabled == valid);  // refused defaults: disabled, the reason beside it
        if (!valid) continue;
        commands.clear();
        press(ui, draw, apply);
        const auto applied = commands_of<ApplyOperation>(commands);
        REQUIRE(applied.size() == 1);
        CHECK(applied[0]->op.def == tool.op.def);
    }
}

TEST_CASE("open_panels (--show) opens panels by name, tools by their operation name",
          "[panels][tools]") {
    TestPanels panels;
    open_panels(panels, panels.entries(), "history,weld,collapsing-edges");
    CHECK(panels.history_open);
    CHECK(panels.tool("weld")->open);
    CHECK_FALSE(panels.tool("noise")->open);
    CHECK(panels.decimation.show_collapsing_edges);
    open_panels(panels, panels.entries(), "tools");
    CHECK(panels.tool("noise")->open);
    CHECK_THROWS_WITH(open_panels(panels, panels.entries(), "history,nope"),
                      Catch::Contains("unknown panel 'nope'") && Catch::Contains("weld"));
}

TEST_CASE("long messages end with an ellipsis, numbers never wrap (issue 38, item 12)",
          "[panels][status]") {
    const auto chars = [](const std::string& t) { return float(t.size()); };
    const std::string notice =
        "the explicit step is above the largest stable one: use a smaller step or implicit";
    CHECK(fit_text(notice, 200.0f, chars) == notice);  // fits: whole
    for (float width : {0.0f, 3.0f, 10.0f, 30.0f, 60.0f, 79.0f}) {
        const std::string shown = fit_text(notice, width, chars);
        INFO(width << ": '" << shown << "'");
        CHECK(chars(shown) <= width);
        if (!shown.empty()) {
            REQUIRE(shown.size() >= 3);
            CHECK(shown.substr(shown.size() - 3) == "...");
            const std::string start = shown.substr(0, shown.size() - 3);
            CHECK(notice.compare(0, start.size(), start) == 0);
            CHECK(start.back() != ' ');
        }
    }
    // Cut at a word's end when one is near: never "... use a sma...".
    CHECK(fit_text(notice, 64.0f, chars) ==
          "the explicit step is above the largest stable one: use a...");
    // UTF-8 is cut between characters only.
    const std::string degrees = "angle 27.0\u00b0 \u00b0\u00b0\u00b0\u00b0\u00b0\u00b0";
    for (float width = 4; width < 20; ++width) {
        const std::string shown = fit_text(degrees, width, chars);
        for (std::size_t i = 0; i + 3 < shown.size(); ++i)
            if ((static_cast<unsigned char>(shown[i]) & 0xC0) == 0xC0) {  // a lead byte
                INFO(width);
                CHECK((static_cast<unsigned char>(shown[i + 1]) & 0xC0) == 0x80);
            }
    }
    // The Inspector's values break at spaces only.
    const std::string position = "-0.053496 0.108443 0.038977";
    for (float width : {10.0f, 12.0f, 19.0f, 20.0f, 27.0f, 100.0f}) {
        INFO(width);
        std::string joined;
        for (const std::string& line : wrap_at_spaces(position, width, chars)) {
            CHECK((chars(line) <= width || line.find(' ') == std::string::npos));
            joined += (joined.empty() ? "" : " ") + line;
        }
        CHECK(joined == position);  // nothing split or lost
    }
    CHECK(wrap_at_spaces(position, 19.0f, chars) ==
          std::vector<std::string>{"-0.053496 0.108443", "0.038977"});
    CHECK(wrap_at_spaces(position, 5.0f, chars).size() == 3);  // a number wider: its own line
}

TEST_CASE("the job's progress text drops whole parts instead of being cut", "[panels][status]") {
    JobInfo job;
    job.name = "Loading stanford-bunny-loop4.ply";
    job.stage = "reading and building the half-edge mesh";
    job.seconds = 3.25;
    const auto chars = [](const std::string& t) { return float(t.size()); };
    const std::string full = job_label(job, 1000.0f, chars);
    CHECK(full ==
          "Loading stanford-bunny-loop4.ply: reading and building the half-edge mesh (3.2 s)");
    CHECK(job_label(job, 45.0f, chars) == "Loading stanford-bunny-loop4.ply (3.2 s)");
    CHECK(job_label(job, 33.0f, chars) == "Loading stanford-bunny-loop4.ply");
    CHECK(job_label(job, 20.0f, chars) == "Loading...");
    for (float width : {0.0f, 5.0f, 12.0f, 40.0f, 60.0f, 90.0f}) {
        const std::string label = job_label(job, width, chars);
        INFO(width << ": '" << label << "'");
        CHECK(chars(label) <= width);
    }
    // In the status bar at 1280 px: the text the bar shows fits the bar.
    Ui ui;
    StatusInfo info;
    Notice notice;
    CommandQueue commands;
    const Rect region{0, 770, 1280, 30};
    const auto draw = [&] { status_bar(info, notice, &job, region, commands); };
    ui.frame(draw);
    ui.frame(draw);
    for (const WidgetNote& n : ui.notes()) {
        if (n.id != "job-progress") continue;
        CHECK(ImGui::CalcTextSize(n.label.c_str()).x <= n.x1 - n.x0);
        CHECK_FALSE(n.label.empty());
    }
}

TEST_CASE("panels name options by their labels, not the command line's", "[panels]") {
    CHECK(panel_words("give --min-faces N and/or --min-diameter F") ==
          "give min faces N and/or min diameter F");
    CHECK(panel_words("none (--percent and --iterations)") == "none (percent and iterations)");
    CHECK(panel_words("a - b -- c") == "a - b -- c");  // dashes that name no option stay
    CHECK(panel_words("x--y") == "x--y");
}

TEST_CASE("an optional number has a check box that sets it", "[panels]") {
    Ui ui(1280, 6000);
    Sidebar s;
    OperationPanelState& tool = *s.panels.tool("remove-components");
    tool.open = true;
    const auto draw = [&] { s.draw(); };
    ui.frame(draw);
    ui.frame(draw);
    const std::string title = tool_section_title(*tool.op.def);
    const WidgetNote diameter =
        find_widget(ui, title + "/min diameter", WidgetNote::Kind::Checkbox);
    CHECK_FALSE(find_widget(ui, title + "/Apply", WidgetNote::Kind::Button).enabled);
    press(ui, draw, diameter);
    ui.frame(draw);
    CHECK(options_of<RemoveComponentsOptions>(tool.op).min_diameter.has_value());
    CHECK(find_widget(ui, title + "/Apply", WidgetNote::Kind::Button).enabled);
}

TEST_CASE("File > Open session and Save session ask for a session file, which is queued",
          "[panels][session]") {
    RenderStyle style;
    ViewSettings settings;
    TestPanels panels;
    MenuContext context;
    context.document_path = "/tmp/model.obj";
    RenderContext render;
    CommandQueue commands;
    const auto draw = [&] {
        menu_bar(style, settings, panels, panels.list(), context, render, commands);
    };
    const std::pair<const char*, FileBrowserState::Purpose> items[] = {
        {"File/Open session...", FileBrowserState::Purpose::OpenSession},
        {"File/Save session...", FileBrowserState::Purpose::SaveSession}};
    for (const auto& [path, purpose] : items) {
        INFO(path);
        Ui ui;
        panels.file_browser = FileBrowserState{};
        ui.frame(draw);
        const auto file = std::find_if(ui.notes().begin(), ui.notes().end(), [](const auto& n) {
            return n.kind == WidgetNote::Kind::Menu && n.label == "File";
        });
        REQUIRE(file != ui.notes().end());
        press(ui, draw, *file);
        const WidgetNote item = find_widget(ui, path, WidgetNote::Kind::MenuItem);
        press(ui, draw, item);
        CHECK(panels.file_browser.open_requested);
        CHECK(panels.file_browser.purpose == purpose);
    }
    CHECK(panels.file_browser.name == "model.trilab");  // Save session: beside the model
    // The dialog queues the command of its purpose.
    for (const auto& [path, purpose] : items) {
        Ui ui;
        CommandQueue queued;
        FileBrowserState browser;
        browser.request(purpose, "");
        browser.name = "/tmp/trilab-no-such-folder/x.trilab";
        const auto dialog = [&] { file_browser(browser, queued); };
        ui.frame(dialog);
        ui.frame(dialog);
        press(ui, dialog,
              find_widget(ui,
                          purpose == FileBrowserState::Purpose::OpenSession ? "Open session"
                                                                            : "Save session",
                          WidgetNote::Kind::Button));
        if (purpose == FileBrowserState::Purpose::OpenSession) {
            REQUIRE(commands_of<OpenSession>(queued).size() == 1);
            CHECK(commands_of<OpenSession>(queued)[0]->path == browser.name);
        } else {
            REQUIRE(commands_of<SaveSession>(queued).size() == 1);
            CHECK(commands_of<SaveSession>(queued)[0]->path == browser.name);
        }
    }
}

TEST_CASE("Help > Reference figures: each item sets its panel and queues the figure",
          "[panels][figures]") {
    RenderStyle style;
    ViewSettings settings;
    MenuContext context;
    RenderContext render;
    const std::pair<const char*, const char*> items[] = {
        {"1.12b", "smooth"}, {"1.15c", "spectrum"}, {"1.20", "subdivide"}, {"1.29", "decimate"}};
    for (const auto& [name, operation] : items) {
        INFO(name);
        Ui ui;
        TestPanels panels;
        CommandQueue commands;
        const auto draw = [&] {
            menu_bar(style, settings, panels, panels.list(), context, render, commands);
        };
        ui.frame(draw);
        const auto help = std::find_if(ui.notes().begin(), ui.notes().end(), [](const auto& n) {
            return n.kind == WidgetNote::Kind::Menu && n.label == "Help";
        });
        REQUIRE(help != ui.notes().end());
        press(ui, draw, *help);
        press(ui, draw, find_widget(ui, "Help/Reference figures", WidgetNote::Kind::Menu));
        const ReferenceFigure* figure = find_reference_figure(name);
        REQUIRE(figure);
        press(ui, draw,
              find_widget(ui, "Help/Reference figures/" + figure->name + "  " + figure->title,
                          WidgetNote::Kind::MenuItem));
        const auto queued = commands_of<LoadFigure>(commands);
        REQUIRE(queued.size() == 1);
        CHECK(queued[0]->name == name);
        const std::string op = operation;
        if (op == "smooth") {
            CHECK(panels.fairing.open);
            CHECK(panels.fairing.op.text() == parse_operation(figure->operation).text());
        } else if (op == "spectrum") {
            CHECK(panels.frequency.open);
            CHECK(panels.frequency.lo == 0);
            CHECK(panels.frequency.hi == 2);
            CHECK(panels.frequency.op.text().find("--k 50") != std::string::npos);
        } else if (op == "subdivide") {
            CHECK(panels.subdivision.open);
            CHECK(panels.subdivision.op.text() == parse_operation(figure->operation).text());
        } else {
            CHECK(panels.decimation.open);
            CHECK(panels.decimation.op.text() == parse_operation(figure->operation).text());
        }
    }
    // While a job runs the items are disabled.
    Ui ui;
    TestPanels panels;
    CommandQueue commands;
    context.busy = true;
    const auto draw = [&] {
        menu_bar(style, settings, panels, panels.list(), context, render, commands);
    };
    ui.frame(draw);
    const auto help = std::find_if(ui.notes().begin(), ui.notes().end(), [](const auto& n) {
        return n.kind == WidgetNote::Kind::Menu && n.label == "Help";
    });
    REQUIRE(help != ui.notes().end());
    press(ui, draw, *help);
    press(ui, draw, find_widget(ui, "Help/Reference figures", WidgetNote::Kind::Menu));
    const ReferenceFigure& first = reference_figures().front();
    const WidgetNote item =
        find_widget(ui, "Help/Reference figures/" + first.name + "  " + first.title,
                    WidgetNote::Kind::MenuItem);
    CHECK_FALSE(item.enabled);
    press(ui, draw, item);
    CHECK(commands_of<LoadFigure>(commands).empty());
}

TEST_CASE("the recovery question's buttons: Restore, Discard, Later", "[panels][session]") {
    const std::pair<const char*, int> buttons[] = {{"Restore", 1}, {"Discard", 0}, {"Later", -1}};
    for (const auto& [label, restore] : buttons) {
        INFO(label);
        Ui ui;
        RecoveryPrompt prompt;
        prompt.open_requested = true;
        prompt.path = "/tmp/state/trilab/recovery/trilab-42.journal";
        prompt.description = prompt.path;
        CommandQueue commands;
        const auto draw = [&] { recovery_popup(prompt, commands); };
        ui.frame(draw);
        ui.frame(draw);
        press(ui, draw, find_widget(ui, label, WidgetNote::Kind::Button));
        const auto queued = commands_of<RecoverJournal>(commands);
        if (restore < 0) {
            CHECK(queued.empty());
        } else {
            REQUIRE(queued.size() == 1);
            CHECK(queued[0]->path == prompt.path);
            CHECK(queued[0]->restore == (restore == 1));
        }
        ui.frame(draw);  // every answer closes the question
        CHECK(std::none_of(ui.notes().begin(), ui.notes().end(),
                           [](const WidgetNote& n) { return n.label == "Restore"; }));
    }
}

TEST_CASE("The status bar names the file being loaded and what is drawn", "[panels][status]") {
    // Issue 38 item 8: while a file loads, the bar showed the open model's counts under the
    // file's picture; while a large mesh turns, nothing said the surface was simplified.
    StatusInfo info;
    info.n_vertices = 1002;
    info.n_faces = 2000;
    info.file_name = "default model";
    info.frame_ms = 12.5;
    CHECK(status_text(info) == "1002 vertices   2000 faces   default model   12.5 ms");
    StatusInfo loading = info;
    loading.loading = "bunny17.ply";
    loading.n_faces = 17829952;
    const std::string text = status_text(loading);
    CHECK(text == "loading bunny17.ply   17829952 faces   12.5 ms");
    CHECK(text.find("default model") == std::string::npos);
    StatusInfo turning = info;
    turning.simplified = "simplified while moving";
    turning.frame_ms = 38.0;
    CHECK(status_text(turning) ==
          "1002 vertices   2000 faces   default model   38.0 ms   simplified while moving");
}
