// The operation registry: parsing "--op" strings, running them on a copy of the mesh,
// canonical parameters that parse back to the same operation, and errors naming the option.
#include <algorithm>
#include <cstring>

#include "app/ops/operation.h"
#include "core/errors.h"
#include "core/generators.h"
#include "core/noise.h"
#include "test_helpers.h"

using namespace trilab;

namespace {

bool bit_identical(const std::vector<Point>& a, const std::vector<Point>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(Point)) == 0;
}

/// A Progress that asks to stop at once.
class CancelAtOnce final : public Progress {
public:
    void report(double, const char*) override {}
    bool cancel_requested() const override { return true; }
};

std::string parse_error(const std::string& text) {
    try {
        parse_operation(text);
    } catch (const InvalidArgument& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST_CASE("noise is registered", "[ops]") {
    const auto names = operation_names();
    REQUIRE(std::find(names.begin(), names.end(), "noise") != names.end());
    REQUIRE_THAT(operation_usage("noise"),
                 Catch::Contains("--amount") && Catch::Contains("--seed"));
    REQUIRE_THROWS_AS(operation_usage("nope"), InvalidArgument);
}

TEST_CASE("parse_operation splits the name and the arguments", "[ops]") {
    const Operation op = parse_operation("  noise\t--amount 2   --seed 7 ");
    REQUIRE(op.name == "noise");
    REQUIRE(op.args == std::vector<std::string>{"--amount", "2", "--seed", "7"});
    REQUIRE(parse_operation("noise").args.empty());
    REQUIRE(parse_operation("noise --amount=2.5").args.size() == 1);
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
    REQUIRE_THROWS_WITH(run_operation(Operation{"noise", {"--amount", "-3"}}, mesh, progress),
                        Catch::Contains("--amount"));
    REQUIRE_THROWS_WITH(run_operation(Operation{"smooth", {}}, mesh, progress),
                        Catch::Contains("unknown operation 'smooth'"));
}

TEST_CASE("a cancelled operation throws Cancelled and leaves the input alone", "[ops]") {
    const HalfedgeMesh input = make_icosphere(2);
    const HalfedgeMesh copy = input;
    CancelAtOnce cancel;
    REQUIRE_THROWS_AS(run_operation(parse_operation("noise --amount 3"), input, cancel), Cancelled);
    REQUIRE(bit_identical(input.positions(), copy.positions()));
}
