// The Denoise tool (app/viewer/denoise_tool.h): its panel's widgets queue the denoise
// operation's preview and apply, and its band energies match an independent computation.
#include <imgui.h>
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <cmath>
#include <string>
#include <vector>

#include "app/ops/operation_entries.h"
#include "app/viewer/denoise_tool.h"
#include "core/algorithms/generators.h"
#include "core/algorithms/spectral.h"
#include "core/errors.h"
#include "tests/app/panel_ui.h"
#include "tests/app/test_tools.h"

using namespace trilab;
using namespace trilab::viewer;
using namespace trilab::viewer::testing;

namespace {

/// The rows of `p` through the decomposition's map (rows x 3).
Eigen::MatrixXd rows_of(const SpectralDecomposition& d, const std::vector<Point>& p) {
    Eigen::MatrixXd x(Eigen::Index(d.rows()), 3);
    for (std::size_t r = 0; r < d.rows(); ++r)
        x.row(Eigen::Index(r)) = p[d.map.vertex_of[r].idx()].transpose();
    return x;
}

/// ||Y||²_S = trace(Yᵀ S Y).
double s_norm2(const SpectralDecomposition& d, const Eigen::MatrixXd& y) {
    return (y.transpose() * d.S.asDiagonal() * y).trace();
}

/// The energy of X in the computed frequencies [lo, hi], as the S-norm of its projection
/// P = E_b E_bᵀ S X (not as a sum of coefficients), and of the rest X - E Eᵀ S X.
double projected_energy(const SpectralDecomposition& d, const Eigen::MatrixXd& x, std::size_t lo,
                        std::size_t hi) {
    const Eigen::MatrixXd e =
        d.eigenvectors.middleCols(Eigen::Index(lo), Eigen::Index(hi - lo + 1));
    return s_norm2(d, e * (e.transpose() * d.S.asDiagonal() * x));
}
double rest_energy(const SpectralDecomposition& d, const Eigen::MatrixXd& x) {
    const Eigen::MatrixXd& e = d.eigenvectors;
    return s_norm2(d, x - e * (e.transpose() * d.S.asDiagonal() * x));
}

void check_energies(const SpectralDecomposition& d, const std::vector<Point>& before,
                    const std::vector<Point>& after, const BandEnergies& e) {
    REQUIRE(e.size() == e.lo.size());
    REQUIRE(e.after.size() == e.size());
    const std::size_t computed = e.rest ? e.size() - 1 : e.size();
    for (const auto* side : {&before, &after}) {
        const Eigen::MatrixXd x = rows_of(d, *side);
        const std::vector<double>& got = side == &before ? e.before : e.after;
        double sum = 0;
        for (std::size_t b = 0; b < computed; ++b) {
            INFO("band " << b << ": " << e.lo[b] << ".." << e.hi[b]);
            CHECK(got[b] ==
                  Approx(projected_energy(d, x, e.lo[b], e.hi[b])).epsilon(1e-8).margin(1e-14));
            sum += got[b];
        }
        if (e.rest) {
            CHECK(got.back() == Approx(rest_energy(d, x)).epsilon(1e-6).margin(1e-12));
            sum += got.back();
        }
        CHECK(sum == Approx(s_norm2(d, x)).epsilon(1e-9));  // the bands cover everything
    }
}

}  // namespace

TEST_CASE("band energies: the S-norm of each band's projection, and the rest", "[denoise_tool]") {
    const HalfedgeMesh mesh = make_default_model();
    SpectralOptions options;
    options.k = 20;
    const SpectralDecomposition d = decompose(mesh, options);
    REQUIRE(d.size() == 20);
    std::vector<Point> after = mesh.positions();
    for (std::size_t i = 0; i < after.size(); ++i)  // a deterministic wiggle
        after[i] *= 1.0 + 0.01 * std::sin(double(i) * 1.7);
    const BandEnergies e = band_energies(d, mesh.positions(), after, 8);
    CHECK(e.size() == 9);  // 8 bands of the 20 computed, and the rest
    CHECK(e.rest);
    CHECK(e.lo.front() == 0);
    CHECK(e.hi[7] == 19);
    for (std::size_t b = 1; b < 8; ++b) CHECK(e.lo[b] == e.hi[b - 1] + 1);
    check_energies(d, mesh.positions(), after, e);
    // Fewer frequencies than bands: one band each.
    CHECK(band_energies(d, mesh.positions(), after, 50).size() == 21);
    CHECK_THROWS_AS(band_energies(d, mesh.positions(), after, 0), InvalidArgument);
    after.pop_back();
    CHECK_THROWS_AS(band_energies(d, mesh.positions(), after, 8), InvalidArgument);
}

TEST_CASE("the Denoise tool compares the preview's bands with the document's, once per preview",
          "[denoise_tool]") {
    TestPanels panels;
    DenoiseTool& tool = find_tool<DenoiseTool>(panels.all_tools);
    panels.denoise.open = true;  // computed while the section shows them
    Session& s = panels.context.session;
    const Operation denoise = make_operation("denoise");
    // No decomposition: no bands, even with a preview.
    s.execute(PreviewOperation{denoise});
    s.finish_jobs();
    s.update();
    tool.update();
    CHECK(tool.bands().size() == 0);
    s.execute(CancelPreview{});
    s.execute(Decompose{parse_operation("spectrum --k 20")});
    s.finish_jobs();
    s.update();
    REQUIRE(s.document().frequency.valid);
    tool.update();
    CHECK(tool.bands().size() == 0);  // no preview
    Operation stronger = denoise;
    stronger.value("normal-iterations").x = 4;
    s.execute(PreviewOperation{stronger});
    s.finish_jobs();
    s.update();
    REQUIRE(s.previews().result());
    panels.denoise.open = false;  // a closed section computes nothing
    tool.update();
    CHECK(tool.bands().size() == 0);
    CHECK(tool.computations() == 0);
    panels.denoise.open = true;
    tool.update();
    tool.finish();  // computed on a worker thread
    CHECK(tool.computations() == 1);
    const BandEnergies& e = tool.bands();
    REQUIRE(e.size() > 0);
    const HalfedgeMesh& after = s.previews().result()->steps.back().mesh;
    const SpectralDecomposition& d = *s.document().frequency.decomposition;
    check_energies(d, s.mesh().positions(), after.positions(), e);
    const std::size_t computed = tool.computations();
    tool.update();
    tool.update();
    tool.finish();
    CHECK(tool.computations() == computed);  // cached until the preview changes
    s.execute(CancelPreview{});
    tool.update();
    CHECK(tool.bands().size() == 0);
}

TEST_CASE("the Denoise panel's widgets queue the denoise operation's preview and apply",
          "[denoise_tool][panels]") {
    Ui ui;
    TestPanels panels;
    DenoiseTool& tool = find_tool<DenoiseTool>(panels.all_tools);
    panels.denoise.open = true;
    CommandQueue commands;
    SidebarContext context;
    const auto draw = [&] { in_sidebar(panels.layout, [&] { tool.section(context, commands); }); };
    ui.frame(draw);
    ui.frame(draw);
    CHECK_FALSE(ui.has("section:Tools: denoise"));  // its own panel, not the generic one
    REQUIRE(ui.has("section:Denoise"));
    const Box apply = ui.rect("Denoise");
    commands.clear();
    ui.click(draw, 0.5f * (apply.x0 + apply.x1), 0.5f * (apply.y0 + apply.y1));
    const auto applied = commands_of<ApplyOperation>(commands);
    REQUIRE(applied.size() == 1);
    CHECK(applied[0]->op == make_operation("denoise"));
    // A changed value previews it, live.
    panels.denoise.op.value("normal-iterations").x = 3;
    panels.denoise.dirty = true;
    commands.clear();
    ui.frame(draw);
    const auto previews = commands_of<PreviewOperation>(commands);
    REQUIRE(previews.size() == 1);
    CHECK(previews[0]->op.def == make_operation("denoise").def);
    CHECK(previews[0]->op.value("normal-iterations").x == 3);
    // The menus and --panels find it by its name.
    const PanelEntries entries = panels.entries();
    const PanelEntry* entry = find_panel(entries, "denoise");
    REQUIRE(entry);
    CHECK(entry->open == &panels.denoise.open);
    CHECK(entry->menu == PanelMenu::Tools);
}
