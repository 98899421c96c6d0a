// Typed access to operations (app/ops/operation.h): options_of<Options>(op), set_options(op, o),
// operation_of(o), is_operation<Options>(op) and report_of<Report>(result). The round trip
// through the declaration's bindings changes nothing; a changed field changes exactly its
// value, marks it given, and gives the text a user typing that option would write.
#include <cmath>
#include <string>
#include <vector>

#include "app/ops/decimate_op.h"
#include "app/ops/operation.h"
#include "app/ops/smooth_op.h"
#include "app/ops/spectrum_op.h"
#include "core/algorithms/fairing.h"
#include "core/algorithms/generators.h"
#include "core/algorithms/noise.h"
#include "core/algorithms/orientation.h"
#include "core/algorithms/subdivision.h"
#include "core/algorithms/weld.h"
#include "core/errors.h"
#include "test_helpers.h"

using namespace trilab;

namespace {

/// Operations with non-default values of every kind (switched off, unset, ranges, flags).
const char* const kEditedOperations[] = {
    "noise --amount 2.5 --seed 9",
    "subdivide --scheme sqrt3 --iterations 3",
    "smooth --operator taubin --lambda 0.6 --mu -0.7 --iterations 4 --boundary slide",
    "smooth --operator curvature-flow --integration implicit --step 0.01 --preserve-volume",
    "spectrum --k 12 --band 2:5 --fix-boundary --threads 1",
    "spectrum --full --which largest",
    "decimate --cost roundness --target-vertices 100 --normal-flip off --roundness 0.3",
    "decimate --percent 20 --iterations 3 --independent-set --max-error 0.5",
    "flip",
    "weld --tolerance 0.001",
    "remove-components --min-faces 50 --min-diameter 0.1",
};

/// The indices whose values differ between `a` and `b` (the same operation).
std::vector<std::string> changed_names(const Operation& a, const Operation& b) {
    std::vector<std::string> names;
    for (std::size_t i = 0; i < a.values.size(); ++i)
        if (a.values[i] != b.values[i]) names.push_back(a.def->params[i].name);
    return names;
}

/// The names of the values marked given.
std::vector<std::string> given_names(const Operation& op) {
    std::vector<std::string> names;
    for (std::size_t i = 0; i < op.values.size(); ++i)
        if (op.values[i].given) names.push_back(op.def->params[i].name);
    return names;
}

/// Writes `options` into `op` and checks the result is what a user would type: exactly
/// `expected` changed and became given (or unset), and its text parses back to it with the same
/// flags.
template <class Options>
Operation edited(const Operation& op, const Options& options,
                 const std::vector<std::string>& expected) {
    Operation after = op;
    set_options(after, options);
    REQUIRE(changed_names(op, after) == expected);
    for (const std::string& name : expected) {  // unset optional values aside: nothing to type
        const ParamValue& v = after.value(name);
        REQUIRE(v.given == !(after.def->params[after.def->index(name)].optional && !v.on));
    }
    for (std::size_t i = 0; i < op.values.size(); ++i)
        if (op.values[i] == after.values[i]) REQUIRE(after.values[i].given == op.values[i].given);
    const Operation typed = parse_operation(after.text());
    REQUIRE(typed == after);
    REQUIRE(typed.text() == after.text());
    check_operation(after);
    return after;
}

}  // namespace

TEST_CASE("every registered operation has an options struct of its own", "[ops][typed]") {
    const std::vector<const OperationDef*>& defs = operation_defs();
    for (std::size_t i = 0; i < defs.size(); ++i) {
        REQUIRE(defs[i]->options_type != nullptr);
        REQUIRE(&operation_def_of(*defs[i]->options_type) == defs[i]);
        for (std::size_t j = 0; j < i; ++j)
            REQUIRE(*defs[i]->options_type != *defs[j]->options_type);
    }
    REQUIRE(definition_of<FairingOptions>().name == "smooth");
    REQUIRE(definition_of<NoiseOptions>().name == "noise");
    REQUIRE(definition_of<SubdivisionOptions>().name == "subdivide");
    REQUIRE(definition_of<SpectrumOptions>().name == "spectrum");
    REQUIRE(definition_of<DecimateOptions>().name == "decimate");
    REQUIRE(definition_of<FlipOptions>().name == "flip");
    REQUIRE(definition_of<WeldOptions>().name == "weld");
    REQUIRE(is_operation<FlipOptions>(make_operation("flip")));
    REQUIRE_FALSE(is_operation<FlipOptions>(make_operation("weld")));
    REQUIRE_FALSE(is_operation<FlipOptions>(Operation{}));
    // A type no operation takes is refused, naming the known operations.
    REQUIRE_THROWS_WITH(definition_of<DecimationOptions>(), Catch::Contains("known: noise"));
}

TEST_CASE("options and back through the bindings changes no operation", "[ops][typed]") {
    std::vector<Operation> ops;
    for (const std::string& name : operation_names()) ops.push_back(make_operation(name));
    for (const char* text : kEditedOperations) ops.push_back(parse_operation(text));
    for (const Operation& op : ops) {
        CAPTURE(op.text());
        // Every registered operation, through its type-erased bindings.
        const ParamValues values = op.def->from_options(op.def->options(op.values));
        REQUIRE(values == op.values);
        Operation copy = op;
        store_changed_values(copy, values);
        REQUIRE(given_names(copy) == given_names(op));
        // The text parses back, where the values make a valid run (remove-components needs a
        // threshold: its defaults alone are refused, naming the options).
        bool valid = true;
        try {
            check_operation(op);
        } catch (const InvalidArgument&) {
            valid = false;
        }
        if (valid) REQUIRE(parse_operation(op.text()) == op);
    }
    // And through the typed functions, per options struct.
    for (Operation op : ops) {
        const Operation before = op;
        if (is_operation<NoiseOptions>(op)) set_options(op, options_of<NoiseOptions>(op));
        if (is_operation<SubdivisionOptions>(op))
            set_options(op, options_of<SubdivisionOptions>(op));
        if (is_operation<FairingOptions>(op)) set_options(op, options_of<FairingOptions>(op));
        if (is_operation<SpectrumOptions>(op)) set_options(op, options_of<SpectrumOptions>(op));
        if (is_operation<DecimateOptions>(op)) set_options(op, options_of<DecimateOptions>(op));
        if (is_operation<FlipOptions>(op)) set_options(op, options_of<FlipOptions>(op));
        if (is_operation<WeldOptions>(op)) set_options(op, options_of<WeldOptions>(op));
        REQUIRE(op == before);
        REQUIRE(given_names(op) == given_names(before));
        REQUIRE(op.text() == before.text());
    }
}

TEST_CASE("options_of reads typed fields of the operation's values", "[ops][typed]") {
    const FairingOptions f = options_of<FairingOptions>(parse_operation(
        "smooth --operator taubin --lambda 0.6 --mu -0.7 --preserve-volume --boundary slide"));
    REQUIRE(f.op == FairingOperator::Taubin);
    REQUIRE(f.taubin_lambda == 0.6);
    REQUIRE(f.taubin_mu == -0.7);
    REQUIRE(f.preserve_volume);
    REQUIRE(f.boundary == BoundaryMode::Slide);
    REQUIRE(f.step == FairingOptions{}.step);
    const SpectrumOptions s = options_of<SpectrumOptions>(parse_operation("spectrum --band 2:5"));
    REQUIRE(s.band.has_value());
    REQUIRE(s.band->first == 2);
    REQUIRE(s.band->second == 5);
    REQUIRE_FALSE(s.k.has_value());
    const DecimateOptions d = options_of<DecimateOptions>(
        parse_operation("decimate --target-vertices 100 --normal-flip off"));
    REQUIRE(d.target_vertices == std::optional<std::size_t>(100));
    REQUIRE_FALSE(d.core.normal_flip);
    REQUIRE(decimation_options(d).target_vertices == 100);
    REQUIRE(
        spectral_options(options_of<SpectrumOptions>(parse_operation("spectrum --full"))).method ==
        SpectralMethod::Full);
}

TEST_CASE("options_of and set_options refuse another operation, naming both", "[ops][typed]") {
    REQUIRE_THROWS_AS(options_of<DecimateOptions>(make_operation("smooth")), InvalidArgument);
    REQUIRE_THROWS_WITH(options_of<DecimateOptions>(make_operation("smooth")),
                        "options_of: expected 'decimate', got 'smooth'");
    Operation weld = make_operation("weld");
    REQUIRE_THROWS_WITH(set_options(weld, FairingOptions{}),
                        "set_options: expected 'smooth', got 'weld'");
    REQUIRE(weld == make_operation("weld"));
    REQUIRE_THROWS_WITH(options_of<NoiseOptions>(Operation{}),
                        "options_of: expected 'noise', got an empty operation");
}

TEST_CASE("set_options changes exactly the fields that changed and marks them given",
          "[ops][typed]") {
    const Operation smooth = make_operation("smooth");
    FairingOptions f = options_of<FairingOptions>(smooth);
    f.step = 2;
    REQUIRE(edited(smooth, f, {"step"}).text() == parse_operation("smooth --step 2").text());
    f = options_of<FairingOptions>(smooth);
    f.integration = Integration::Implicit;
    edited(smooth, f, {"integration"});
    f = options_of<FairingOptions>(smooth);
    f.preserve_volume = true;
    const Operation volume = edited(smooth, f, {"preserve-volume"});
    REQUIRE(volume == parse_operation("smooth --preserve-volume"));
    f = options_of<FairingOptions>(smooth);
    f.boundary = BoundaryMode::Slide;
    edited(smooth, f, {"boundary"});
    f = options_of<FairingOptions>(smooth);
    f.op = FairingOperator::Taubin;
    f.taubin_lambda = 0.6;
    f.taubin_mu = -0.65;
    const Operation taubin = edited(smooth, f, {"operator", "lambda", "mu"});
    REQUIRE(taubin == parse_operation("smooth --operator taubin --lambda 0.6 --mu -0.65"));
    // Back to a value equal to the default: still changed, still given.
    f = options_of<FairingOptions>(volume);
    f.preserve_volume = false;
    REQUIRE(edited(volume, f, {"preserve-volume"}).value("preserve-volume").given);

    const Operation decimate = make_operation("decimate");
    DecimateOptions d = options_of<DecimateOptions>(decimate);
    d.target_vertices = 1234;
    const Operation target = edited(decimate, d, {"target-vertices"});
    REQUIRE(target.text() == parse_operation("decimate --target-vertices 1234").text());
    d = options_of<DecimateOptions>(decimate);
    d.core.percent = 25;
    edited(decimate, d, {"percent"});
    d = options_of<DecimateOptions>(decimate);
    d.core.normal_flip = false;  // switched off: the angle is not read
    d.core.max_normal_angle = 45;
    REQUIRE(edited(decimate, d, {"normal-flip"}) == parse_operation("decimate --normal-flip off"));

    const Operation spectrum = make_operation("spectrum");
    SpectrumOptions s = options_of<SpectrumOptions>(spectrum);
    s.k = 20;
    edited(spectrum, s, {"k"});
    s.band = std::pair<std::size_t, std::size_t>(3, 7);
    const Operation band = edited(spectrum, s, {"k", "band"});
    REQUIRE(band == parse_operation("spectrum --k 20 --band 3:7"));
    // Unsetting an optional value: unset and not given (a user cannot type "unset").
    s = options_of<SpectrumOptions>(band);
    s.band.reset();
    const Operation unset = edited(band, s, {"band"});
    REQUIRE_FALSE(unset.value("band").on);
    REQUIRE_FALSE(unset.value("band").given);
    REQUIRE(unset.text() == parse_operation("spectrum --k 20").text());
}

TEST_CASE("operation_of gives the operation a user typing those options would get",
          "[ops][typed]") {
    SpectrumOptions s;
    s.band = std::pair<std::size_t, std::size_t>(2, 9);
    const Operation band = operation_of(s);
    const Operation typed = parse_operation("spectrum --band 2:9");
    REQUIRE(band == typed);
    REQUIRE(given_names(band) == given_names(typed));
    REQUIRE(band.text() == typed.text());
    NoiseOptions n;
    n.seed = 7;
    REQUIRE(operation_of(n).text() == "noise --amount 1 --seed 7");
    REQUIRE(given_names(operation_of(n)) == std::vector<std::string>{"seed"});
    REQUIRE(operation_of(FlipOptions{}) == make_operation("flip"));
}

TEST_CASE("given_or takes the user's given values over the caller's own", "[ops][typed]") {
    SpectrumOptions mine;
    mine.spectral.op = LaplacianOperator::CurvatureFlow;
    mine.spectral.mass = MassMatrix::Normalizer;
    // Not given: the caller's values, even where they differ from the defaults; given (k):
    // the user's.
    const Operation plain = parse_operation("spectrum --k 12");
    SpectrumOptions got = given_or(plain, mine);
    CHECK(got.spectral.op == LaplacianOperator::CurvatureFlow);
    CHECK(got.spectral.mass == MassMatrix::Normalizer);
    REQUIRE(got.k.has_value());
    CHECK(*got.k == 12);
    mine.k = 30;
    CHECK(*given_or(parse_operation("spectrum"), mine).k == 30);
    // Given: the user's, even where it equals the declaration's default.
    const std::string default_operator = laplacian_operator_name(SpectrumOptions{}.spectral.op);
    const Operation named = parse_operation("spectrum --k 12 --operator " + default_operator);
    got = given_or(named, mine);
    CHECK(got.spectral.op == SpectrumOptions{}.spectral.op);
    REQUIRE(got.k.has_value());
    CHECK(*got.k == 12);
    CHECK_THROWS_AS(given_or(parse_operation("noise"), mine), InvalidArgument);
}

TEST_CASE("a switched-off or unset value means the same whatever number it holds", "[ops][typed]") {
    // "--roundness off" parses to 0, the default holds the core's 0.2 while off.
    REQUIRE(parse_operation("decimate --roundness off") == make_operation("decimate"));
    ParamValue a, b;
    a.on = b.on = false;
    a.x = 1;
    b.x = 2;
    REQUIRE(a == b);
    a.on = b.on = true;
    REQUIRE(a != b);
}

TEST_CASE("the parameter that counts the steps is declared, not named", "[ops][typed]") {
    for (const OperationDef* def : operation_defs()) {
        std::size_t counting = 0;
        for (const ParamSpec& p : def->params) {
            if (!p.counts_steps) continue;
            ++counting;
            REQUIRE(p.name == "iterations");
            REQUIRE(p.kind == ParamKind::Integer);
        }
        const bool iterates =
            def->name == "smooth" || def->name == "subdivide" || def->name == "decimate";
        REQUIRE(counting == (iterates ? 1u : 0u));
    }
}

TEST_CASE("every run reports a typed report that agrees with its JSON values", "[ops][typed]") {
    const HalfedgeMesh sphere = make_noisy_sphere(6, 0.05, 3);
    NullProgress progress;
    const auto value = [](const OperationResult& r, const std::string& key) {
        for (const auto& [k, v] : r.values)
            if (k == key) return v;
        FAIL("no value " << key);
        return 0.0;
    };

    const OperationResult smooth =
        run_operation(parse_operation("smooth --step 0.5 --iterations 2"), sphere, progress);
    const SmoothReport* sr = report_of<SmoothReport>(smooth);
    REQUIRE(sr != nullptr);
    REQUIRE(report_of<DecimationReport>(smooth) == nullptr);
    REQUIRE(std::isfinite(sr->max_stable_step));
    REQUIRE(sr->max_stable_step > 0);
    REQUIRE(sr->max_stable_step == value(smooth, "max_stable_step"));
    REQUIRE(sr->iterations_done == 2);
    REQUIRE(sr->max_smoothing_distance == value(smooth, "max_smoothing_distance"));
    REQUIRE(sr->solver == smooth.texts[0].second);
    REQUIRE(std::isnan(
        report_of<SmoothReport>(run_operation(make_operation("smooth"), make_grid(4), progress))
            ->final_volume));

    const OperationResult spectrum =
        run_operation(parse_operation("spectrum --k 8 --band 1:4"), sphere, progress);
    const SpectrumReport* spr = report_of<SpectrumReport>(spectrum);
    REQUIRE(spr != nullptr);
    REQUIRE(spr->k == 8);
    REQUIRE(spr->lo == 1);
    REQUIRE(spr->hi == 4);
    REQUIRE(spr->rows == sphere.n_vertices());
    REQUIRE(spr->eigenvalues.size() == 8);
    REQUIRE(spr->eigenvalues == spectrum.series[0].second);
    REQUIRE(spr->decomposition.max_residual == value(spectrum, "max_residual"));

    const OperationResult decimate =
        run_operation(parse_operation("decimate --percent 30"), sphere, progress);
    const DecimationReport* dr = report_of<DecimationReport>(decimate);
    REQUIRE(dr != nullptr);
    REQUIRE(double(dr->collapses) == value(decimate, "collapses"));
    REQUIRE(dr->output_vertices == decimate.steps.back().mesh.n_vertices());

    const OperationResult noise =
        run_operation(parse_operation("noise --amount 2"), sphere, progress);
    REQUIRE(report_of<NoiseReport>(noise)->max_displacement == value(noise, "max_displacement"));
    const OperationResult flip = run_operation(make_operation("flip"), sphere, progress);
    REQUIRE(report_of<FlipReport>(flip)->faces == sphere.n_faces());
    const OperationResult weld = run_operation(make_operation("weld"), sphere, progress);
    REQUIRE(double(report_of<WeldReport>(weld)->vertices_joined) == value(weld, "vertices_joined"));
    const OperationResult subdivide =
        run_operation(parse_operation("subdivide --iterations 2"), sphere, progress);
    const SubdivisionResult* sub = report_of<SubdivisionResult>(subdivide);
    REQUIRE(sub != nullptr);
    REQUIRE(sub->levels.empty());
    REQUIRE(sub->level_counts.size() == 2);
    REQUIRE(sub->level_counts.back()[1] == subdivide.steps.back().mesh.n_faces());
}

TEST_CASE("smooth leaves out the stable-step estimate where a Gershgorin bound decides it",
          "[ops][fairing]") {
    // From 65,536 vertices an explicit umbrella step up to 1 is not estimated (stable on any
    // mesh: the umbrella's eigenvalues lie in [0, 2]); a larger step, another operator and a
    // smaller mesh still are.
    const HalfedgeMesh large = make_icosphere(81);  // 65,612 vertices
    REQUIRE(large.n_vertices() >= 65536);
    const HalfedgeMesh small = make_icosphere(8);
    NullProgress progress;
    const auto run = [&](const HalfedgeMesh& m, const std::string& op) {
        const OperationResult r = run_operation(parse_operation(op), m, progress);
        const SmoothReport* sr = report_of<SmoothReport>(r);
        REQUIRE(sr != nullptr);
        CHECK(sr->iterations_done == 1);
        bool note = false;
        for (const auto& [key, text] : r.texts) note = note || key == "max_stable_step_note";
        CHECK(note == !std::isfinite(sr->max_stable_step));
        return sr->max_stable_step;
    };
    CHECK(std::isnan(run(large, "smooth --step 1 --iterations 1")));
    const double limit = run(large, "smooth --step 1.2 --iterations 1");
    CHECK(limit > 1.0);  // the icosphere's umbrella: about 1.33
    CHECK(
        std::isfinite(run(large, "smooth --operator improved-umbrella --step 0.5 --iterations 1")));
    CHECK(std::isfinite(run(small, "smooth --step 0.5 --iterations 1")));
}
