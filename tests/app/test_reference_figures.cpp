// The reference's figures (app/session/reference_figures.h) loaded into a session: each runs to
// the kind of result the reference shows with the reference's own settings, translated, and
// Figure 1.12(b)'s explosion is refused and shown only as a marked, diverged state.
#include <catch2/catch.hpp>

#include <cmath>
#include <set>
#include <string>

#include "app/ops/operation.h"
#include "app/session/reference_figures.h"
#include "app/session/session.h"
#include "core/algorithms/generators.h"
#include "core/algorithms/laplacian.h"
#include "core/algorithms/mesh_stats.h"
#include "core/validate.h"

using namespace trilab;
using namespace trilab::viewer;

namespace {

/// The umbrella's roughness: |L·X|² over the vertices, relative to the squared size (so a
/// uniform shrink does not count as smoothing).
double roughness(const HalfedgeMesh& mesh) {
    const Laplacian lap = build_laplacian(mesh, LaplacianOperator::Umbrella);
    const Eigen::MatrixXd x = gather_positions(mesh, lap.map);
    const double size = (x.colwise().maxCoeff() - x.colwise().minCoeff()).norm();
    return (lap.L * x).squaredNorm() / (size * size);
}

double box_diagonal(const HalfedgeMesh& mesh) {
    const MeshStats s = compute_stats(mesh);
    return (s.bbox.max - s.bbox.min).norm();
}

void settle(Session& s) {
    s.finish_jobs();
    s.execute(ShowMorphAt{1.0});
    s.update();
}

void require_valid(const HalfedgeMesh& mesh) {
    const ValidationResult v = validate(mesh);
    INFO(v.message);
    REQUIRE(v.ok);
}

}  // namespace

TEST_CASE("the reference figures are the issue's, by name, with their sub-figures", "[figures]") {
    std::set<std::string> figures;
    for (const ReferenceFigure& f : reference_figures()) {
        INFO(f.name);
        figures.insert(f.name.substr(0, f.name.find_first_of("abcd")));
        CHECK_FALSE(f.title.empty());
        CHECK_FALSE(f.reference.empty());
        CHECK_FALSE(f.translation.empty());
        CHECK_NOTHROW(generate(f.model));
        for (const std::string& s : f.setup) CHECK_NOTHROW(check_operation(parse_operation(s)));
        const Operation op = parse_operation(f.operation);
        CHECK_NOTHROW(check_operation(op));
        // The step in the table is the operation's step.
        if (f.step > 0) {
            REQUIRE(op.name() == "smooth");
            CHECK(op.text().find("--step " + std::to_string(int(f.step))) != std::string::npos);
        }
    }
    CHECK(figures == std::set<std::string>{"1.2", "1.4", "1.7", "1.10", "1.12", "1.13", "1.15",
                                           "1.16", "1.20", "1.22", "1.26", "1.29", "1.31"});
    REQUIRE(find_reference_figure("1.12b"));
    CHECK(find_reference_figure("1.12b")->result == FigureResult::Diverges);
    REQUIRE(find_reference_figure("1.12"));
    CHECK(find_reference_figure("1.12")->name == "1.12b");  // the first sub-figure
    CHECK(find_reference_figure("1.1") == nullptr);
    CHECK(find_reference_figure("1.12x") == nullptr);
    CHECK(reference_figure_names().find("1.12b, 1.12c") != std::string::npos);
}

TEST_CASE("the improved umbrella's step is translated by the model's squared mean edge",
          "[figures]") {
    // The reference's improved umbrella is in 1/length²; trilab's is h² times it. Its unit
    // sphere of about 1,000 vertices is the default model: step 1.0 there is 1/h² here.
    const double h = mean_edge_length(make_default_model());
    const ReferenceFigure* f = find_reference_figure("1.4b");
    REQUIRE(f);
    CHECK(f->reference_step == 1.0);
    CHECK(f->step == Approx(1.0 / (h * h)).epsilon(0.01));
    CHECK(f->translation.find("1/length") != std::string::npos);
    // The head's 0.0002 is not taken as it is.
    const ReferenceFigure* head = find_reference_figure("1.4d");
    REQUIRE(head);
    CHECK(head->reference_step == 0.0002);
    CHECK(head->step == Approx(2.0));
    // Scale-free operators keep their step.
    CHECK(find_reference_figure("1.7b")->step == 1.0);
}

TEST_CASE("every reference figure loads and runs to the kind of result the reference shows",
          "[figures][slow]") {
    for (const ReferenceFigure& f : reference_figures()) {
        if (f.result == FigureResult::Diverges) continue;  // the next test
        INFO("figure " << f.name << ": " << f.operation);
        Session s;
        s.execute(LoadFigure{f.name});
        settle(s);
        CHECK(s.figures().figure() == f.name);
        INFO(s.notice().text);
        REQUIRE(s.notice().level == Notice::Level::Info);
        CHECK(s.notice().text.find("Figure " + f.name) != std::string::npos);
        // The load, one entry per setup operation, the figure's operation.
        REQUIRE(s.history().size() == 2 + f.setup.size());
        CHECK(s.history().info(0).label.find("Figure " + f.name) == 0);
        CHECK(s.history().info(s.history().current()).operation.text() ==
              parse_operation(f.operation).text());
        const std::size_t input_entry = s.history().size() - 2;  // the figure's input
        const HalfedgeMesh before =
            s.history().mesh(input_entry, s.history().info(input_entry).steps.size() - 1);
        const HalfedgeMesh& after = s.mesh();
        require_valid(after);
        switch (f.result) {
            case FigureResult::Smoothed: {
                CHECK(after.n_vertices() == before.n_vertices());
                CHECK(roughness(after) < 0.8 * roughness(before));
                const double v0 = *compute_stats(before).volume;
                const double v1 = *compute_stats(after).volume;
                if (f.name == "1.13c") CHECK(v1 == Approx(v0).epsilon(1e-6));  // anti-shrinking
                if (f.name == "1.13b") CHECK(v1 < 0.9 * v0);  // the shrinkage it shows
                break;
            }
            case FigureResult::Filtered:
                CHECK(after.n_vertices() == before.n_vertices());
                CHECK(after.positions() != before.positions());
                break;
            case FigureResult::Subdivided: {
                const std::size_t factor =
                    f.operation.find("sqrt3") != std::string::npos ? 243 : 1024;  // 3^5, 4^5
                CHECK(after.n_faces() == factor * before.n_faces());
                break;
            }
            case FigureResult::Decimated: {
                // 60 % (quadric) or 30 % (roundness) of the vertices per iteration, 5 times.
                const double kept = f.operation.find("quadric") != std::string::npos ? 0.4 : 0.7;
                const double expected = std::pow(kept, 5) * double(before.n_vertices());
                CHECK(double(after.n_vertices()) < 1.3 * expected);
                CHECK(double(after.n_vertices()) > 0.7 * expected);
                break;
            }
            case FigureResult::Diverges:
                break;
        }
    }
}

TEST_CASE("Figure 1.12(b) diverges and is refused, and its run is shown marked, never as a result",
          "[figures]") {
    Session s;
    s.execute(LoadFigure{"1.12b"});
    settle(s);
    // The run is stopped as any explicit run above its limit: nothing is kept.
    CHECK(s.figures().figure() == "1.12b");
    REQUIRE(s.history().size() == 1);  // the load alone
    CHECK(s.notice().level == Notice::Level::Error);
    CHECK(s.notice().text.find("stopped early") != std::string::npos);
    const HalfedgeMesh input = s.mesh();
    const Operation op = parse_operation(find_reference_figure("1.12b")->operation);

    // Show the diverging run: a marked state, far larger than the model, no history entry.
    s.execute(ShowDivergingRun{op});
    REQUIRE(s.figures().diverging_run_shown());
    CHECK(s.figures().diverging_run_note().rfind("DIVERGED", 0) == 0);
    CHECK(s.notice().text.rfind("DIVERGED", 0) == 0);
    REQUIRE(s.shown().kind == Shown::Kind::Preview);
    REQUIRE(s.shown().mesh);
    CHECK(box_diagonal(*s.shown().mesh) > 1.3 * box_diagonal(input));
    CHECK(s.history().size() == 1);
    CHECK(s.mesh().positions() == input.positions());
    CHECK_FALSE(s.previews().shown(op));  // not a preview that Apply would commit
    CHECK_FALSE(s.previews().previewing(op));

    // Apply runs the operation itself, which is refused again; the diverged state is gone.
    s.execute(ApplyOperation{op});
    settle(s);
    CHECK_FALSE(s.figures().diverging_run_shown());
    CHECK(s.history().size() == 1);
    CHECK(s.mesh().positions() == input.positions());
    CHECK(s.notice().level == Notice::Level::Error);

    // Esc (Cancel) returns to the document.
    s.execute(ShowDivergingRun{op});
    REQUIRE(s.figures().diverging_run_shown());
    s.execute(CancelPreview{});
    CHECK_FALSE(s.figures().diverging_run_shown());
    CHECK(s.shown().kind == Shown::Kind::Document);

    // Another model: the document is no longer the figure.
    s.execute(LoadFile{"../shared/meshes/no-such-file.obj", true});
    settle(s);
    CHECK(s.figures().figure() == "1.12b");  // the load failed: still the figure
    s.execute(LoadFigure{"1.12c"});
    settle(s);
    CHECK(s.figures().figure() == "1.12c");

    // An implicit run does not diverge: nothing is shown.
    s.execute(ShowDivergingRun{parse_operation(find_reference_figure("1.12c")->operation)});
    CHECK_FALSE(s.figures().diverging_run_shown());
    CHECK(s.shown().kind == Shown::Kind::Document);
}

TEST_CASE("an unknown figure is an error naming the figures", "[figures]") {
    Session s;
    s.execute(LoadFigure{"1.99"});
    CHECK_FALSE(s.busy());
    CHECK(s.notice().level == Notice::Level::Error);
    CHECK(s.notice().text.find("1.99") != std::string::npos);
    CHECK(s.notice().text.find("1.12b") != std::string::npos);
    CHECK(s.history().size() == 1);
}
