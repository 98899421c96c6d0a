// Session files (app/history/session_file.h) and recipes (app/history/recipe.h): every state
// of a history comes back bit for bit (connectivity, positions, every attribute, the morph
// correspondences, labels and typed operations, the current entry, the viewer's settings);
// arrays shared between states are stored and restored once; a file cut at any byte or with
// any byte damaged is refused with a message naming the file and the chunk, never half
// restored; the committed file of this format version reads and replays its recipe exactly.
#include <sys/stat.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <cstring>
#include <fstream>
#include <optional>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "app/history/chunk_io.h"
#include "app/history/recipe.h"
#include "app/history/session_file.h"
#include "app/history/session_types.h"
#include "app/ops/region_spec.h"
#include "core/algorithms/generators.h"
#include "core/algorithms/selection.h"
#include "core/errors.h"
#include "core/io/file_util.h"
#include "core/io/mesh_io.h"
#include "core/progress.h"
#include "core/validate.h"
#include "session_test_util.h"
#include "test_helpers.h"

using namespace trilab;

TEST_CASE("crc32_update gives the standard CRC-32 check value", "[session]") {
    const char* text = "123456789";
    CHECK(crc32_update(0, text, 9) == 0xCBF43926u);
    // In pieces: the same.
    CHECK(crc32_update(crc32_update(0, text, 4), text + 4, 5) == 0xCBF43926u);
    CHECK(crc32_update(0, "", 0) == 0u);
}

TEST_CASE("a session restores every state bit for bit", "[session]") {
    const History history = test::sample_history();
    SessionExtras extras;
    extras.viewer_settings = "camera.distance=3.5\ncolor=curvature\nlegend=-0.25:1.5\n";
    extras.texture_path = "textures/checker.png";
    extras.texture_bytes = std::string("\x89PNG\r\n\x1a\n\0\x01", 10);
    const std::string path = test::temp_path("roundtrip.trilab");
    const SessionWriteReport report = write_session(path, history.snapshot(), extras);
    CHECK(report.entries == history.size());
    CHECK(report.skipped.empty());

    const SessionContents s = read_session(path);
    CHECK_FALSE(s.journal);
    CHECK(s.complete);
    CHECK(s.extras.viewer_settings == extras.viewer_settings);
    CHECK(s.extras.texture_path == extras.texture_path);
    CHECK(s.extras.texture_bytes == extras.texture_bytes);
    test::require_same_history(history, s.history);
    REQUIRE(s.entries.size() == history.size());
    std::size_t sum = 0;
    for (const SessionEntrySummary& e : s.entries) sum += e.bytes;
    CHECK(sum + 16 + 24 + 28 < s.file_bytes + 1);  // header, CURR, END outside entries
    unlink(path.c_str());
}

TEST_CASE("a session stores shared arrays once and restores them shared", "[session]") {
    // Ten geometry-only steps: each adds its positions alone (and a few hundred bytes of
    // records, small against 4002 positions).
    HalfedgeMesh mesh = make_icosphere(20);
    History history(std::size_t(-1));
    history.reset(mesh, "Load");
    Operation smooth = parse_operation("smooth --iterations 1");
    for (int k = 0; k < 10; ++k) {
        NullProgress progress;
        OperationResult r = run_operation(smooth, history.current_mesh(), progress);
        history.push(r.label, r.parameters, r.ms, {r.steps.back().mesh},
                     {r.steps.back().correspondence}, smooth);
    }
    const std::string path = test::temp_path("shared.trilab");
    const SessionWriteReport report = write_session(path, history.snapshot());
    std::size_t mesh_bytes = 0;
    for (const auto& b : mesh.memory_blocks()) mesh_bytes += b.bytes;
    const std::size_t positions = mesh.vertices_size() * sizeof(Point);
    INFO("file " << report.bytes << " bytes, mesh " << mesh_bytes << ", positions " << positions);
    CHECK(double(report.bytes) <= 1.2 * double(mesh_bytes + 10 * positions));
    const SessionContents s = read_session(path);
    test::require_same_history(history, s.history);
    // The restored history holds about what the original holds (arrays shared again).
    CHECK(double(s.history.bytes()) <= 1.05 * double(history.bytes()));
    unlink(path.c_str());
}

TEST_CASE("a session of the bunny with ten smoothing steps stays within 1.2 x mesh + positions",
          "[session][slow]") {
    const std::string bunny = test::shared_mesh("stanford-bunny.obj");
    if (!test::present_or_skip(bunny)) return;
    LoadedMesh loaded = read_mesh(bunny);
    History history(std::size_t(-1));
    history.reset(loaded.mesh, "Load stanford-bunny.obj");
    const Operation smooth = parse_operation("smooth --iterations 1");
    for (int k = 0; k < 10; ++k) {
        NullProgress progress;
        OperationResult r = run_operation(smooth, history.current_mesh(), progress);
        std::vector<HalfedgeMesh> meshes;
        std::vector<MorphCorrespondence> corr;
        for (OperationStep& s : r.steps) {
            meshes.push_back(std::move(s.mesh));
            corr.push_back(std::move(s.correspondence));
        }
        history.push(r.label, r.parameters, r.ms, std::move(meshes), std::move(corr), smooth);
    }
    const std::string path = test::temp_path("bunny.trilab");
    const SessionWriteReport report = write_session(path, history.snapshot());
    std::size_t mesh_bytes = 0;
    for (const auto& b : loaded.mesh.memory_blocks()) mesh_bytes += b.bytes;
    const std::size_t positions = loaded.mesh.vertices_size() * sizeof(Point);
    const double limit = 1.2 * double(mesh_bytes + 10 * positions);
    INFO("file " << report.bytes << " bytes; mesh " << mesh_bytes << " + 10 x " << positions
                 << " positions; limit " << limit);
    CHECK(double(report.bytes) <= limit);
    const SessionContents s = read_session(path);
    test::require_same_history(history, s.history);
    unlink(path.c_str());
}

TEST_CASE("a session cut at any byte is refused, naming the file and the chunk", "[session]") {
    const History history = test::small_history();
    const std::string path = test::temp_path("small.trilab");
    write_session(path, history.snapshot(), SessionExtras{"a=1\n", "", ""});
    const std::string bytes = read_file_bytes(path);
    unlink(path.c_str());
    REQUIRE_NOTHROW(read_session_bytes(bytes, "small.trilab"));
    for (std::size_t n = 0; n < bytes.size(); ++n) {
        INFO("cut at " << n << " of " << bytes.size());
        try {
            read_session_bytes(std::string_view(bytes).substr(0, n), "small.trilab");
            FAIL("a cut session was read");
        } catch (const IoError& e) {
            REQUIRE(std::string(e.what()).rfind("small.trilab: ", 0) == 0);
            if (n >= 16) REQUIRE(std::string(e.what()).find("chunk ") != std::string::npos);
        }
    }
}

TEST_CASE("a session with any damaged byte is refused", "[session]") {
    const History history = test::small_history();
    const std::string path = test::temp_path("damaged.trilab");
    write_session(path, history.snapshot());
    const std::string bytes = read_file_bytes(path);
    unlink(path.c_str());
    std::mt19937 rng(5);
    for (std::size_t i = 0; i < bytes.size(); ++i) {
        std::string damaged = bytes;
        damaged[i] = char(damaged[i] ^ char(1 + rng() % 255));
        INFO("byte " << i << " of " << bytes.size());
        REQUIRE_THROWS_AS(read_session_bytes(damaged, "damaged.trilab"), IoError);
    }
    // Bytes appended after the end chunk are refused too.
    REQUIRE_THROWS_AS(read_session_bytes(bytes + "x", "damaged.trilab"), IoError);
}

TEST_CASE("an unreadable session says why: not a session, another version", "[session]") {
    CHECK_THROWS_WITH(read_session_bytes("hello", "a.trilab"),
                      Catch::Contains("a.trilab") && Catch::Contains("shorter than the 16-byte"));
    CHECK_THROWS_WITH(read_session_bytes(std::string(40, 'x'), "b.trilab"),
                      Catch::Contains("not a trilab session"));
    std::string v2 = std::string("TRILABSN") + std::string("\x02\0\0\0\0\0\0\0", 8);
    CHECK_THROWS_WITH(read_session_bytes(v2, "c.trilab"), Catch::Contains("format version 2"));
    // A journal is not a session (and the other way round).
    std::string journal = std::string("TRILABJN") + std::string("\x01\0\0\0\0\0\0\0", 8);
    CHECK_THROWS_WITH(read_session_bytes(journal, "d.trilab"), Catch::Contains("not a trilab"));
}

TEST_CASE("writing a session goes through a temporary file: a failure keeps the old one",
          "[session]") {
    const History history = test::small_history();
    const std::string path = test::temp_path("keep.trilab");
    write_session(path, history.snapshot());
    const std::string before = read_file_bytes(path);
    CHECK_THROWS_AS(write_session(path, History::Snapshot{}), InvalidArgument);
    CHECK(read_file_bytes(path) == before);
    CHECK_THROWS_AS(write_session("/nonexistent-folder/x.trilab", history.snapshot()), IoError);
    unlink(path.c_str());
}

TEST_CASE("the committed session of this format version reads and replays bit for bit",
          "[session]") {
    const std::string path = test::data_file("session/icosahedron-history.trilab");
    const SessionContents s = read_session(path);
    REQUIRE(s.history.size() == 5);
    CHECK(s.history.current() == 3);
    CHECK(s.entries[1].operation.text() == "subdivide --scheme loop --iterations 1");
    CHECK(s.entries[4].steps.back().first == 30);
    CHECK(s.extras.viewer_settings.find("legend=-1:1") != std::string::npos);
    for (std::size_t i = 0; i < s.history.size(); ++i)
        for (std::size_t k = 0; k < s.history.info(i).steps.size(); ++k)
            REQUIRE(validate(s.history.mesh(i, k)));
    // Its recipe (loaded file to current entry) replays to the current state exactly.
    const Recipe recipe = recipe_of(s.history);
    REQUIRE(recipe.operations() == 3);
    const HalfedgeMesh replayed = replay(recipe, s.history.mesh(0, 0));
    CHECK(first_difference(replayed, s.history.current_mesh()) == "");
    // Regenerated today, every state is the same bit for bit (the operations did not change).
    History again(std::size_t(-1));
    again.reset(make_icosahedron(), "Load ico.off");
    for (std::size_t i = 1; i < s.history.size(); ++i) {
        const Operation op = s.history.info(i).operation;
        ReplayStep step = run_recipe_step(op, again.current_mesh());
        std::vector<HalfedgeMesh> meshes;
        std::vector<MorphCorrespondence> corr;
        for (OperationStep& st : step.result.steps) {
            meshes.push_back(std::move(st.mesh));
            corr.push_back(std::move(st.correspondence));
        }
        again.push(step.result.label, step.result.parameters, 0, std::move(meshes), std::move(corr),
                   op);
        INFO("entry " << i);
        CHECK(first_difference(again.current_mesh(),
                               s.history.mesh(i, s.history.info(i).steps.size() - 1)) == "");
    }
}

TEST_CASE("recipes round-trip through JSON and replay bit for bit", "[session]") {
    const History history = test::sample_history();
    const Recipe recipe = recipe_of(history);
    const std::string json = recipe_json(recipe);
    const Recipe back = parse_recipe(json, "r.json");
    REQUIRE(back.steps.size() == recipe.steps.size());
    for (std::size_t i = 0; i < back.steps.size(); ++i) CHECK(back.steps[i] == recipe.steps[i]);
    const HalfedgeMesh replayed = replay(back, history.mesh(0, 0));
    CHECK(first_difference(replayed, history.current_mesh()) == "");
    // A changed state is told apart.
    HalfedgeMesh moved = replayed;
    moved.position(Vertex(3)).x() = std::nextafter(moved.position(Vertex(3)).x(), 1e9);
    CHECK(first_difference(moved, history.current_mesh()) == "positions differ at index 3");
}

TEST_CASE("a bad recipe is refused naming the file and the operation", "[session]") {
    CHECK_THROWS_WITH(parse_recipe("{", "r.json"), Catch::Contains("r.json:1"));
    CHECK_THROWS_WITH(parse_recipe("{\"format\": \"x\"}", "r.json"),
                      Catch::Contains("not a trilab recipe"));
    const std::string head = "{\"format\": \"trilab-recipe\", \"version\": 1, \"operations\": [";
    CHECK_THROWS_WITH(
        parse_recipe(head + "{\"operation\": \"nope\", \"parameters\": {}}]}", "r.json"),
        Catch::Contains("operation 0") && Catch::Contains("unknown operation"));
    CHECK_THROWS_WITH(
        parse_recipe(head + "{\"operation\": \"smooth\", \"parameters\": {\"iterations\": -2}}]}",
                     "r.json"),
        Catch::Contains("--iterations"));
    CHECK_THROWS_WITH(
        parse_recipe(
            head + "{\"operation\": \"smooth\", \"parameters\": {\"iterations\": \"x\"}}]}",
            "r.json"),
        Catch::Contains("expected a number"));
}

TEST_CASE("operations give the same bits on every run (recipes rely on it)", "[session]") {
    const HalfedgeMesh mesh = make_icosphere(3);
    for (const char* text :
         {"smooth --iterations 3", "smooth --operator curvature-flow --integration implicit",
          "subdivide --scheme loop --iterations 2", "subdivide --scheme sqrt3",
          "decimate --target-vertices 200", "noise --amount 2 --seed 9",
          "spectrum --k 20 --band 0:5 --threads 1"}) {
        INFO(text);
        const Operation op = parse_operation(text);
        const HalfedgeMesh a = replay(Recipe{"", {op}}, mesh);
        const HalfedgeMesh b = replay(Recipe{"", {op}}, mesh);
        CHECK(first_difference(a, b) == "");
    }
    // The spectrum's slices on one or two threads agree.
    const HalfedgeMesh one =
        replay(Recipe{"", {parse_operation("spectrum --k 20 --band 0:5 --threads 1")}}, mesh);
    const HalfedgeMesh two =
        replay(Recipe{"", {parse_operation("spectrum --k 20 --band 0:5 --threads 2")}}, mesh);
    CHECK(first_difference(one, two) == "");
}

// ---- issue 38, item 1: recipes keep selections --------------------------------------------

namespace {

/// A selection entry as the viewer pushes one (app/session/session_selection.cpp): the current
/// state with "v:selection" set, one step, no motion.
void push_selection(History& h, const Selection& weights, const std::string& label,
                    const std::string& parameters) {
    HalfedgeMesh m = h.current_mesh();
    store_selection(m, weights);
    h.push(label, parameters, 0.0, {std::move(m)}, {MorphCorrespondence{}});
}

/// Runs `text` on the current state's selection, as the viewer does (Session::region_for: none
/// without a selection or when it selects everything), and pushes every step.
void push_on_selection(History& h, const std::string& text) {
    const Operation op = parse_operation(text);
    std::optional<Selection> region = stored_selection(h.current_mesh());
    if (region && selects_everything(h.current_mesh(), *region)) region.reset();
    ReplayStep r = run_recipe_step(op, h.current_mesh(), region ? &*region : nullptr);
    REQUIRE(r.changed);
    std::vector<HalfedgeMesh> meshes;
    std::vector<MorphCorrespondence> corr;
    for (OperationStep& s : r.result.steps) {
        meshes.push_back(std::move(s.mesh));
        corr.push_back(std::move(s.correspondence));
    }
    h.push(r.result.label, r.result.parameters, r.result.ms, std::move(meshes), std::move(corr),
           op);
}

/// The session: noise on everything, a sphere selected, implicit curvature flow on it,
/// then a brush stroke (fractional weights), grown, and noise on that.
History selection_history() {
    History h(std::size_t(-1));
    h.reset(make_icosphere(3), "Load ico.off");
    push_on_selection(h, "noise --amount 20 --seed 3");
    const std::string spec = "sphere:0,0,1,0.8";
    push_selection(h, make_region(h.current_mesh(), parse_region_spec(spec)), "Select", spec);
    push_on_selection(h, "smooth --operator curvature-flow --integration implicit --step 3");
    Selection brush(h.current_mesh().vertices_size(), 0.0f);
    for (std::size_t i = 0; i < brush.size(); i += 7) brush[i] = 0.25f + 0.5f * float(i % 3) / 2;
    push_selection(h, brush, "Brush", "radius 20 px");
    Selection grown = brush;
    grow_selection(h.current_mesh(), grown, 1);
    push_selection(h, grown, "Grow selection", "1 rings");
    push_on_selection(h, "noise --amount 5 --seed 8");
    return h;
}

}  // namespace

TEST_CASE("recipes replay selections: the spec or the weights, and each step's region",
          "[session][recipe][selection]") {
    const History h = selection_history();
    const Recipe recipe = recipe_of(h);
    CHECK(recipe.source == "Load ico.off");
    REQUIRE(recipe.steps.size() == 6);
    CHECK(recipe.operations() == 3);
    CHECK(recipe.selections() == 3);
    using Kind = RecipeStep::Kind;
    using From = RecipeStep::From;
    CHECK(recipe.steps[0].kind == Kind::RunOperation);  // the noise before the selection
    CHECK(recipe.steps[1].kind == Kind::SetSelection);
    CHECK(recipe.steps[1].from == From::Spec);  // replays as its SPEC: the same weights
    CHECK(recipe.steps[1].region == "sphere:0,0,1,0.8");
    CHECK(recipe.steps[3].from == From::Weights);  // a brush stroke: its weights
    CHECK(recipe.steps[4].from == From::Weights);  // grown: its weights
    CHECK(recipe.steps[4].text == "Grow selection 1 rings");
    // Through JSON and back: the same steps, the weights bit for bit.
    const std::string json = recipe_json(recipe);
    const Recipe back = parse_recipe(json, "r.json");
    REQUIRE(back.steps.size() == recipe.steps.size());
    for (std::size_t i = 0; i < back.steps.size(); ++i) CHECK(back.steps[i] == recipe.steps[i]);
    // The replay gives the session's state bit for bit; the smoothing moved only the region.
    const HalfedgeMesh replayed = replay(back, h.mesh(0, 0));
    CHECK(first_difference(replayed, h.current_mesh()) == "");
    const HalfedgeMesh noisy = h.mesh(1, 0), smoothed = h.mesh(3, 0);
    const Selection region = *stored_selection(h.mesh(2, 0));
    std::size_t moved = 0;
    for (Vertex v : noisy.vertices()) {
        if (region[v.idx()] == 0.0f)
            REQUIRE(noisy.position(v) == smoothed.position(v));
        else
            moved += noisy.position(v) != smoothed.position(v) ? 1 : 0;
    }
    CHECK(moved > 10);
    // Without the selections (what recipes did before): not the session's state.
    Recipe operations_only;
    for (const RecipeStep& s : recipe.steps)
        if (s.kind == Kind::RunOperation) operations_only.steps.push_back(s);
    CHECK(first_difference(replay(operations_only, h.mesh(0, 0)), h.current_mesh()) != "");
}

TEST_CASE("a recipe step may carry its own region, and a clear selection replays",
          "[session][recipe][selection]") {
    const HalfedgeMesh mesh = make_icosphere(3);
    const std::string head = "{\"format\": \"trilab-recipe\", \"version\": 2, \"operations\": [";
    const Recipe r =
        parse_recipe(head +
                         "{\"operation\": \"smooth\", \"parameters\": {\"iterations\": 3}, "
                         "\"region\": \"sphere:0,0,1,0.5\"},"
                         "{\"selection\": \"spec\", \"spec\": \"sphere:0,0,-1,0.5\"},"
                         "{\"selection\": \"clear\"},"
                         "{\"operation\": \"noise\", \"parameters\": {\"amount\": 1}}]}",
                     "r.json");
    REQUIRE(r.steps.size() == 4);
    CHECK(r.steps[0].region == "sphere:0,0,1,0.5");
    const HalfedgeMesh out = replay(r, mesh);
    // The same as running the two operations by hand: smooth on the sphere, noise on all.
    NullProgress progress;
    const Selection region = make_region(mesh, parse_region_spec("sphere:0,0,1,0.5"));
    RunSettings settings;
    settings.region = &region;
    const HalfedgeMesh a =
        run_operation(parse_operation("smooth --iterations 3"), mesh, progress, settings)
            .steps.back()
            .mesh;
    const HalfedgeMesh b =
        run_operation(parse_operation("noise --amount 1"), a, progress).steps.back().mesh;
    CHECK(first_difference(out, b) == "");
    CHECK_FALSE(out.has_vertex_property(kSelectionProperty));
}

TEST_CASE("an entry a recipe cannot replay is refused by name, never skipped",
          "[session][recipe][selection]") {
    History h(std::size_t(-1));
    h.reset(make_icosphere(2), "Load ico.off");
    push_on_selection(h, "noise --amount 5 --seed 1");
    // Texture coordinates: the same shape, a state the viewer made (not a selection).
    HalfedgeMesh textured = h.current_mesh();
    textured.add_vertex_property<TexCoord>("v:texcoord", TexCoord(0.5, 0.5));
    h.push("Texture coordinates", "planar", 0.0, {std::move(textured)}, {MorphCorrespondence{}});
    push_on_selection(h, "smooth --iterations 2");
    CHECK_THROWS_WITH(recipe_of(h), Catch::Contains("entry 2 \"Texture coordinates planar\"") &&
                                        Catch::Contains("cannot replay"));
    // A later load starts the recipe afresh: what came before it is not needed.
    HalfedgeMesh other = make_icosphere(1);
    MorphCorrespondence none{MorphCorrespondence::Kind::FromEarlier, other.positions()};
    h.push("Load other.off", "", 0.0, {std::move(other)}, {std::move(none)});
    push_on_selection(h, "smooth --iterations 1");
    const Recipe r = recipe_of(h);
    CHECK(r.source == "Load other.off");
    CHECK(r.steps.size() == 1);
    // Weights of another vertex count are refused naming the step.
    Recipe wrong;
    RecipeStep s;
    s.kind = RecipeStep::Kind::SetSelection;
    s.from = RecipeStep::From::Weights;
    s.weights = Selection(5, 1.0f);
    s.text = "Brush";
    wrong.steps.push_back(s);
    CHECK_THROWS_WITH(replay(wrong, make_icosphere(1)),
                      Catch::Contains("step 0 (Brush)") && Catch::Contains("5 vertex weights"));
    // Bad selection steps in a file are refused naming the step.
    const std::string head = "{\"format\": \"trilab-recipe\", \"version\": 2, \"operations\": [";
    CHECK_THROWS_WITH(parse_recipe(head + "{\"selection\": \"lasso\"}]}", "r.json"),
                      Catch::Contains("r.json: operation 0: unknown selection \"lasso\""));
    CHECK_THROWS_WITH(
        parse_recipe(head + "{\"selection\": \"weights\", \"vertices\": 3, \"indices\": [5], "
                            "\"weights\": [1]}]}",
                     "r.json"),
        Catch::Contains("operation 0: weight 0: index"));
    CHECK_THROWS_WITH(
        parse_recipe(head + "{\"selection\": \"spec\", \"spec\": \"cube:1\"}]}", "r.json"),
        Catch::Contains("unknown kind 'cube'"));
    CHECK_THROWS_WITH(
        parse_recipe("{\"format\": \"trilab-recipe\", \"version\": 1, \"operations\": "
                     "[{\"selection\": \"clear\"}]}",
                     "r.json"),
        Catch::Contains("needs recipe version 2"));
}
