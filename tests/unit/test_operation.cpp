// The operation registry: parsing "--op" strings, running them on a copy of the mesh,
// canonical parameters that parse back to the same operation, and errors naming the option.
#include <algorithm>
#include <cstring>

#include "app/ops/operation.h"
#include "core/algorithms/generators.h"
#include "core/algorithms/noise.h"
#include "core/algorithms/subdivision.h"
#include "core/errors.h"
#include "core/geometry.h"
#include "test_helpers.h"

using namespace trilab;

namespace {

bool bit_identical(const std::vector<Point>& a, const std::vector<Point>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(Point)) == 0;
}

Operation with_value(Operation op, const char* name, double x) {
    op.value(name).x = x;
    return op;
}

/// The InvalidArgument message of parse_operation(text), "" when it parses.
std::string parse_error(const std::string& text) {
    return test::error_text<InvalidArgument>([&] { parse_operation(text); });
}

}  // namespace

TEST_CASE("noise is registered", "[ops]") {
    const auto names = operation_names();
    REQUIRE(std::find(names.begin(), names.end(), "noise") != names.end());
    REQUIRE_THAT(operation_usage("noise"),
                 Catch::Contains("--amount") && Catch::Contains("--seed"));
    REQUIRE_THROWS_AS(operation_usage("nope"), InvalidArgument);
}

TEST_CASE("parse_operation gives typed values, marking what was named", "[ops]") {
    const Operation op = parse_operation("  noise\t--amount 2   --seed 7 ");
    REQUIRE(op.name() == "noise");
    REQUIRE(op.value("amount").x == 2);
    REQUIRE(op.value("amount").given);
    REQUIRE(op.value("seed").x == 7);
    const Operation defaults = parse_operation("noise");
    REQUIRE(defaults == make_operation("noise"));
    REQUIRE_FALSE(defaults.value("seed").given);
    REQUIRE(parse_operation("noise --amount=2.5").value("amount").x == 2.5);
    REQUIRE(op.text() == "noise --amount 2 --seed 7");
}

TEST_CASE("running noise gives one geometry-only step and leaves the input alone", "[ops]") {
    const HalfedgeMesh input = make_default_model();
    const HalfedgeMesh copy = input;
    NullProgress progress;
    const OperationResult r =
        run_operation(parse_operation("noise --amount 2 --seed 7"), input, progress);
    REQUIRE(bit_identical(input.positions(), copy.positions()));
    REQUIRE(r.label == "Add noise");
    REQUIRE(r.parameters == "--amount 2 --seed 7");
    REQUIRE(r.steps.size() == 1);
    const OperationStep& step = r.steps.front();
    REQUIRE(step.correspondence.kind == MorphCorrespondence::Kind::SameVertices);
    REQUIRE_NOTHROW(check_correspondence(input, step.mesh, step.correspondence));
    REQUIRE_VALID(step.mesh);
    REQUIRE(step.mesh.n_faces() == input.n_faces());
    REQUIRE_FALSE(bit_identical(step.mesh.positions(), input.positions()));
    REQUIRE(r.report.size() >= 2);
    REQUIRE_THAT(r.report[0], Catch::Contains("mean edge length"));
    REQUIRE_THAT(r.report[1], Catch::Contains("largest displacement"));
    REQUIRE(r.ms >= 0);

    // The same as calling the core directly.
    HalfedgeMesh direct = input;
    const NoiseReport nr = add_noise(direct, NoiseOptions{2.0, 7});
    REQUIRE(bit_identical(direct.positions(), step.mesh.positions()));
    bool found = false;
    for (const auto& [key, value] : r.values)
        if (key == "max_displacement") {
            REQUIRE(value == nr.max_displacement);
            found = true;
        }
    REQUIRE(found);
}

TEST_CASE("canonical parameters parse back to the same operation", "[ops]") {
    const std::string text = GENERATE(std::string("noise"), std::string("noise --seed 3"),
                                      std::string("noise --seed=12 --amount=0.1"),
                                      std::string("noise --amount 2.50 --seed 0"),
                                      std::string("noise --amount 1e-3 --seed 4294967295"));
    INFO(text);
    const HalfedgeMesh input = make_icosphere(3);
    NullProgress progress;
    const OperationResult first = run_operation(parse_operation(text), input, progress);
    const OperationResult again =
        run_operation(parse_operation("noise " + first.parameters), input, progress);
    REQUIRE(again.parameters == first.parameters);
    REQUIRE(
        bit_identical(first.steps.back().mesh.positions(), again.steps.back().mesh.positions()));
}

TEST_CASE("defaults are amount 1 and seed 1", "[ops]") {
    NullProgress progress;
    const OperationResult r = run_operation(parse_operation("noise"), make_icosahedron(), progress);
    REQUIRE(r.parameters == "--amount 1 --seed 1");
}

TEST_CASE("bad operation strings are refused, naming the bad part", "[ops]") {
    REQUIRE_THAT(parse_error(""), Catch::Contains("empty operation"));
    REQUIRE_THAT(parse_error("   "), Catch::Contains("empty operation"));
    REQUIRE_THAT(parse_error("frobnicate --x 1"),
                 Catch::Contains("frobnicate") && Catch::Contains("noise"));
    REQUIRE_THAT(parse_error("noise --bogus 1"), Catch::Contains("--bogus"));
    REQUIRE_THAT(parse_error("noise --amount"),
                 Catch::Contains("--amount") && Catch::Contains("missing value"));
    REQUIRE_THAT(parse_error("noise --amount abc"),
                 Catch::Contains("--amount") && Catch::Contains("'abc'"));
    REQUIRE_THAT(parse_error("noise --amount 2x"), Catch::Contains("--amount"));
    REQUIRE_THAT(parse_error("noise --amount nan"), Catch::Contains("--amount"));
    REQUIRE_THAT(parse_error("noise --amount -1"), Catch::Contains("--amount"));
    REQUIRE_THAT(parse_error("noise --amount 2000"),
                 Catch::Contains("--amount") && Catch::Contains("1000"));
    REQUIRE_THAT(parse_error("noise --seed -1"), Catch::Contains("--seed"));
    REQUIRE_THAT(parse_error("noise --seed 1.5"), Catch::Contains("--seed"));
    REQUIRE_THAT(parse_error("noise --seed 4294967296"), Catch::Contains("--seed"));
    REQUIRE_THAT(parse_error("noise --seed 1 --seed 2"),
                 Catch::Contains("--seed") && Catch::Contains("more than once"));
    REQUIRE_THAT(parse_error("noise 2"), Catch::Contains("unexpected argument '2'"));
    // And run_operation refuses the same when given an Operation built by hand.
    NullProgress progress;
    const HalfedgeMesh mesh = make_icosahedron();
    Operation bad = make_operation("noise");
    bad.value("amount").x = -3;
    REQUIRE_THROWS_WITH(run_operation(bad, mesh, progress), Catch::Contains("--amount"));
    REQUIRE_THROWS_WITH(run_operation(Operation{}, mesh, progress),
                        Catch::Contains("empty operation"));
    REQUIRE_THROWS_WITH(make_operation("frobnicate"),
                        Catch::Contains("unknown operation 'frobnicate'"));
}

TEST_CASE("a cancelled operation throws Cancelled and leaves the input alone", "[ops]") {
    const HalfedgeMesh input = make_icosphere(2);
    const HalfedgeMesh copy = input;
    auto cancel = test::CancellingProgress::at_once();
    REQUIRE_THROWS_AS(run_operation(parse_operation("noise --amount 3"), input, cancel), Cancelled);
    REQUIRE(bit_identical(input.positions(), copy.positions()));
}

// ---- subdivide ----------------------------------------------------------------------------

namespace {

double value_of(const OperationResult& r, const std::string& key) {
    for (const auto& [k, v] : r.values)
        if (k == key) return v;
    FAIL("no value '" << key << "'");
    return 0;
}

}  // namespace

TEST_CASE("subdivide is registered with its options", "[ops]") {
    const auto names = operation_names();
    REQUIRE(std::find(names.begin(), names.end(), "subdivide") != names.end());
    REQUIRE_THAT(operation_usage("subdivide"), Catch::Contains("--scheme") &&
                                                   Catch::Contains("--iterations") &&
                                                   Catch::Contains("modified-butterfly"));
    const Operation op = parse_operation("subdivide --scheme sqrt3 --iterations=2");
    REQUIRE(op.name() == "subdivide");
    REQUIRE(op.text() == "subdivide --scheme sqrt3 --iterations 2");
}

TEST_CASE("subdivide gives one step per level with FromEarlier correspondences", "[ops]") {
    const HalfedgeMesh input = make_default_model();  // 1002 vertices, 3000 edges, 2000 faces
    const HalfedgeMesh copy = input;
    NullProgress progress;
    const OperationResult r =
        run_operation(parse_operation("subdivide --scheme loop --iterations 2"), input, progress);
    REQUIRE(bit_identical(input.positions(), copy.positions()));
    REQUIRE(r.label == "Subdivide");
    REQUIRE(r.parameters == "--scheme loop --iterations 2");
    REQUIRE(r.steps.size() == 2);
    REQUIRE(r.steps[0].mesh.n_vertices() == 1002 + 3000);
    REQUIRE(r.steps[0].mesh.n_faces() == 4 * 2000);
    REQUIRE(r.steps[1].mesh.n_faces() == 16 * 2000);
    const HalfedgeMesh* before = &input;
    for (const OperationStep& step : r.steps) {
        REQUIRE(step.correspondence.kind == MorphCorrespondence::Kind::FromEarlier);
        REQUIRE(step.correspondence.positions.size() == step.mesh.vertices_size());
        REQUIRE_NOTHROW(check_correspondence(*before, step.mesh, step.correspondence));
        REQUIRE_VALID(step.mesh);
        before = &step.mesh;
    }
    REQUIRE(r.ms >= 0);
    // Report: one line per level with its counts, then a summary with the time.
    REQUIRE(r.report.size() == 3);
    REQUIRE_THAT(r.report[0], Catch::Contains("4002 vertices") && Catch::Contains("8000 faces"));
    REQUIRE_THAT(r.report[1], Catch::Contains("32000 faces"));
    REQUIRE_THAT(r.report[2], Catch::Contains("ms"));
    // Values, in their fixed order (the parameters are the operation's, not values).
    REQUIRE(r.values.size() == 2);
    REQUIRE(r.values[0].first == "vertices");
    REQUIRE(r.values[1].first == "faces");
    REQUIRE(r.parameters == "--scheme loop --iterations 2");
    REQUIRE(value_of(r, "vertices") == double(r.steps[1].mesh.n_vertices()));
    REQUIRE(value_of(r, "faces") == 32000);

    // The same as calling the core directly.
    const SubdivisionResult direct =
        subdivide(input, SubdivisionOptions{SubdivisionScheme::Loop, 2}, progress);
    REQUIRE(direct.levels.size() == 2);
    for (std::size_t i = 0; i < 2; ++i) {
        REQUIRE(bit_identical(direct.levels[i].mesh.positions(), r.steps[i].mesh.positions()));
        REQUIRE(bit_identical(direct.levels[i].correspondence.positions,
                              r.steps[i].correspondence.positions));
    }
}

TEST_CASE("subdivide runs every scheme with the expected counts", "[ops]") {
    const std::string scheme =
        GENERATE(std::string("loop"), std::string("sqrt3"), std::string("butterfly"),
                 std::string("modified-butterfly"));
    INFO(scheme);
    const HalfedgeMesh input = make_icosahedron();  // V 12, E 30, F 20
    NullProgress progress;
    const OperationResult r =
        run_operation(parse_operation("subdivide --scheme " + scheme), input, progress);
    REQUIRE(r.parameters == "--scheme " + scheme + " --iterations 1");
    REQUIRE(r.steps.size() == 1);
    const HalfedgeMesh& m = r.steps[0].mesh;
    REQUIRE_VALID(m);
    if (scheme == "sqrt3") {
        REQUIRE(m.n_vertices() == 12 + 20);
        REQUIRE(m.n_faces() == 3 * 20);
    } else {
        REQUIRE(m.n_vertices() == 12 + 30);
        REQUIRE(m.n_faces() == 4 * 20);
    }
    REQUIRE(value_of(r, "vertices") == double(m.n_vertices()));
    REQUIRE_NOTHROW(check_correspondence(input, m, r.steps[0].correspondence));
}

TEST_CASE("subdivide defaults to one Loop step and its parameters parse back", "[ops]") {
    NullProgress progress;
    const HalfedgeMesh input = make_icosahedron();
    const OperationResult r = run_operation(parse_operation("subdivide"), input, progress);
    REQUIRE(r.parameters == "--scheme loop --iterations 1");
    REQUIRE(r.steps.size() == 1);
    const std::string text = GENERATE(std::string("subdivide --iterations=3 --scheme sqrt3"),
                                      std::string("subdivide --scheme modified-butterfly"),
                                      std::string("subdivide --iterations 02"));
    INFO(text);
    const OperationResult first = run_operation(parse_operation(text), input, progress);
    const OperationResult again =
        run_operation(parse_operation("subdivide " + first.parameters), input, progress);
    REQUIRE(again.parameters == first.parameters);
    REQUIRE(first.steps.size() == again.steps.size());
    REQUIRE(
        bit_identical(first.steps.back().mesh.positions(), again.steps.back().mesh.positions()));
}

TEST_CASE("bad subdivide strings are refused, naming the option", "[ops]") {
    REQUIRE_THAT(parse_error("subdivide --scheme nope"),
                 Catch::Contains("--scheme") && Catch::Contains("'nope'") &&
                     Catch::Contains("loop") && Catch::Contains("modified-butterfly"));
    REQUIRE_THAT(parse_error("subdivide --scheme"),
                 Catch::Contains("--scheme") && Catch::Contains("missing value"));
    REQUIRE_THAT(parse_error("subdivide --iterations 0"),
                 Catch::Contains("--iterations") && Catch::Contains("1 to 10"));
    REQUIRE_THAT(parse_error("subdivide --iterations 11"), Catch::Contains("--iterations"));
    REQUIRE_THAT(parse_error("subdivide --iterations 1.5"), Catch::Contains("--iterations"));
    REQUIRE_THAT(parse_error("subdivide --iterations -1"), Catch::Contains("--iterations"));
    REQUIRE_THAT(parse_error("subdivide --amount 2"),
                 Catch::Contains("--amount") && Catch::Contains("subdivide"));
    REQUIRE_THAT(parse_error("subdivide --scheme loop --scheme sqrt3"),
                 Catch::Contains("more than once"));
    NullProgress progress;
    REQUIRE_THROWS_WITH(run_operation(with_value(make_operation("subdivide"), "iterations", 0),
                                      make_icosahedron(), progress),
                        Catch::Contains("--iterations"));
}

TEST_CASE("a cancelled subdivision throws Cancelled and leaves the input alone", "[ops]") {
    const HalfedgeMesh input = make_icosphere(2);
    const HalfedgeMesh copy = input;
    auto cancel = test::CancellingProgress::at_once();
    REQUIRE_THROWS_AS(run_operation(parse_operation("subdivide --iterations 2"), input, cancel),
                      Cancelled);
    REQUIRE(bit_identical(input.positions(), copy.positions()));
}

TEST_CASE("smooth runs fairing as geometry-only steps the history accepts", "[ops]") {
    const HalfedgeMesh m = make_noisy_sphere(6, 0.05, 3);
    const Operation op = parse_operation(
        "smooth --operator curvature-flow --integration implicit --step 0.01 --iterations 3 "
        "--preserve-volume");
    NullProgress progress;
    const OperationResult r = run_operation(op, m, progress);
    REQUIRE(r.label == "Smooth");
    REQUIRE(r.steps.size() == 3);
    REQUIRE(r.parameters ==
            "--operator curvature-flow --integration implicit --step 0.01 --iterations 3 "
            "--preserve-volume");
    for (const OperationStep& s : r.steps) {
        REQUIRE_VALID(s.mesh);
        REQUIRE(s.correspondence.kind == MorphCorrespondence::Kind::SameVertices);
    }
    REQUIRE(volume(r.steps.back().mesh) == Approx(volume(m)).epsilon(1e-6));
    REQUIRE(r.texts.size() == 1);
    // A well-conditioned single step on a small mesh: conjugate gradients (see fairing.cpp).
    REQUIRE(r.texts[0].second == "ConjugateGradient(Jacobi)");
    REQUIRE_THROWS_WITH(parse_operation("smooth --boundary free"),
                        Catch::Matchers::Contains("--boundary"));
    // Volume preservation on an open mesh and bad values are refused, naming the option.
    REQUIRE_THROWS_AS(
        run_operation(parse_operation("smooth --preserve-volume"), make_grid(4), progress),
        InvalidArgument);
    REQUIRE_THROWS_WITH(parse_operation("smooth --operator nope"),
                        Catch::Matchers::Contains("--operator"));
    REQUIRE_THROWS_WITH(parse_operation("smooth --step -1"), Catch::Matchers::Contains("--step"));
}

TEST_CASE("every operation refuses an empty region with one message and changes nothing",
          "[ops][selection]") {
    // Issue 38, item 10: with 0 selected vertices subdivision added a no-op entry and the
    // other operations ran on nothing. The shared run path refuses it, for the CLI and the
    // viewer alike.
    const HalfedgeMesh mesh = make_icosphere(2);
    const HalfedgeMesh before = mesh;
    const std::vector<float> empty(mesh.vertices_size(), 0.0f);
    NullProgress progress;
    RunSettings settings;
    settings.region = &empty;
    std::size_t refused = 0;
    for (const OperationDef* def : operation_defs()) {
        if (!def->takes_region) continue;
        INFO(def->name);
        const Operation op = make_operation(def->name);
        try {
            run_operation(op, mesh, progress, settings);
            FAIL("an empty region was not refused");
        } catch (const InvalidArgument& e) {
            CHECK_THAT(e.what(),
                       Catch::StartsWith(def->label + ": the region is empty (0 of " +
                                         std::to_string(mesh.n_vertices()) + " vertices selected"));
            ++refused;
        }
        CHECK(mesh.positions() == before.positions());
    }
    CHECK(refused >= 6);  // noise, subdivide, smooth, spectrum, decimate, flip, weld
    // One vertex of positive weight is a region: it runs.
    std::vector<float> one = empty;
    one[3] = 0.5f;
    settings.region = &one;
    CHECK_NOTHROW(run_operation(parse_operation("smooth"), mesh, progress, settings));
}

TEST_CASE(
    "a sweep refuses what the command line refuses: a parameter that does not apply, a "
    "run that diverged",
    "[ops]") {
    // Issue 38, item 2: --sweep "smooth --operator taubin" --param step ran although Taubin
    // takes no step, and a diverging preview counted as a success.
    const Operation taubin = parse_operation("smooth --operator taubin");
    CHECK_THROWS_WITH(check_parameter_applies(taubin, "step"),
                      Catch::StartsWith("--step: does not apply to --operator taubin"));
    CHECK_NOTHROW(check_parameter_applies(taubin, "lambda"));
    const Operation umbrella = parse_operation("smooth --iterations 3");
    CHECK_NOTHROW(check_parameter_applies(umbrella, "step"));
    CHECK_THROWS_WITH(check_parameter_applies(umbrella, "lambda"),
                      Catch::StartsWith("--lambda: applies to --operator taubin only"));
    CHECK_THROWS_WITH(check_parameter_applies(umbrella, "bogus"), Catch::Contains("bogus"));
    // The same refusal as the command line's.
    CHECK_THROWS_WITH(parse_operation("smooth --operator taubin --step 0.5"),
                      Catch::StartsWith("--step: does not apply to --operator taubin"));

    NullProgress progress;
    const HalfedgeMesh mesh = make_icosphere(2);
    const OperationResult diverged =
        run_operation(parse_operation("smooth --iterations 3 --step 30"), mesh, progress);
    REQUIRE(diverged.stopped_early);
    CHECK_THAT(run_failure(diverged), Catch::StartsWith("stopped early: iteration 1: "));
    const OperationResult nothing =
        run_operation(parse_operation("smooth --step 0"), mesh, progress);
    CHECK(run_failure(nothing) == (nothing.changed ? "" : "changed nothing"));
    CHECK(run_failure(run_operation(umbrella, mesh, progress)) == "");
}
