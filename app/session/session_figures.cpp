// The reference's figures in the session (Session::load_figure) and the diverging run shown
// for teaching (Session::show_diverging_run); the table is app/session/reference_figures.h.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <utility>
#include <vector>

#include "app/ops/operation_entries.h"
#include "app/session/reference_figures.h"
#include "app/session/session.h"
#include "core/algorithms/fairing.h"
#include "core/algorithms/generators.h"
#include "core/algorithms/laplacian.h"
#include "core/algorithms/transfer_function.h"

namespace trilab::viewer {
namespace {

/// The diagonal of the bounding box of the rows of `x` (0 for none).
double box_diagonal(const Eigen::MatrixXd& x) {
    if (x.rows() == 0) return 0;
    return (x.colwise().maxCoeff() - x.colwise().minCoeff()).norm();
}

/// The most iterations the diverging run computes (it is for the eye, and it explodes fast).
constexpr int kMaxDivergingIterations = 100;

}  // namespace

void Session::load_figure(const std::string& name) {
    const ReferenceFigure* found = find_reference_figure(name);
    if (!found) {
        notify_error("no reference figure '" + name + "'; the figures are " +
                     reference_figure_names());
        return;
    }
    if (jobs_.busy()) return busy_error();
    clear_preview();
    const ReferenceFigure figure = *found;
    struct Loaded {
        HalfedgeMesh model;
        std::vector<std::pair<Operation, OperationResult>> setup;
        Operation op;
        OperationResult result;
    };
    const bool started = jobs_.start("Figure " + figure.name, [this, figure](Progress& progress) {
        auto loaded = std::make_shared<Loaded>();
        loaded->model = generate(figure.model);
        HalfedgeMesh input = loaded->model;
        for (const std::string& text : figure.setup) {
            Operation op = parse_operation(text);
            OperationResult result = run_operation(op, input, progress);
            input = result.steps.back().mesh;
            loaded->setup.emplace_back(std::move(op), std::move(result));
        }
        loaded->op = parse_operation(figure.operation);
        loaded->result = run_operation(loaded->op, input, progress);
        return JobRunner::Finish([this, figure, loaded] {
            log_.info("Figure " + figure.name + ": " + figure.title);
            log_.info("  the reference: " + figure.reference);
            log_.info("  here: " + figure.model_note);
            log_.info("  step: " + figure.translation);
            push_loaded(std::move(loaded->model), "Figure " + figure.name + ": " + figure.model,
                        "figure " + figure.name + " (" + figure.model + ")", "", LoadReport{});
            for (auto& [op, result] : loaded->setup) commit_result(op, std::move(result));
            figure_ = figure.name;
            commit_result(loaded->op, std::move(loaded->result));
            // A refused run keeps its error in the status bar; otherwise the figure says what
            // it is and how its step was translated.
            if (notice_.level != Notice::Level::Error)
                notice_ = Notice{Notice::Level::Info,
                                 "Figure " + figure.name + ": " + figure.title,
                                 {"the reference: " + figure.reference,
                                  "here: " + figure.model_note, "step: " + figure.translation},
                                 false};
        });
    });
    if (!started) busy_error();
}

std::string Session::figure() const {
    // push_loaded() names the document after the figure; any other load renames it.
    const std::string prefix = "figure " + figure_ + " (";
    return !figure_.empty() && document_.name.rfind(prefix, 0) == 0 ? figure_ : std::string();
}

bool Session::diverging_run_shown() const {
    return !diverging_note_.empty() && shown_.kind == Shown::Kind::Preview &&
           shown_.mesh == &diverging_mesh_;
}

void Session::show_diverging_run(const Operation& op) {
    if (!is_operation<FairingOptions>(op)) return;
    FairingOptions o;
    try {
        check_operation(op);
        o = options_of<FairingOptions>(op);
    } catch (const std::exception& e) {
        notify_error(e.what());
        return;
    }
    if (o.integration == Integration::Implicit) {
        notice_ = Notice{
            Notice::Level::Info, "an implicit run does not diverge: nothing to show", {}, false};
        return;
    }
    clear_preview();
    clear_level_of_detail(false);
    HalfedgeMesh mesh = document_.mesh();
    Laplacian lap = build_laplacian(mesh, laplacian_of(o.op));
    Eigen::MatrixXd x = gather_positions(mesh, lap.map);
    const double size0 = box_diagonal(x);
    Eigen::MatrixXd last = x;
    int done = 0;
    const int n = std::min(o.iterations, kMaxDivergingIterations);
    const double mu = o.op == FairingOperator::Taubin ? taubin_mu_of(o) : 0.0;
    for (int it = 1; it <= n; ++it) {
        if (it > 1 && !fairing_is_linear(o.op)) {
            scatter_positions(mesh, lap.map, x);
            refresh_laplacian(mesh, lap);
        }
        if (o.op == FairingOperator::Taubin) {
            x += o.taubin_lambda * (lap.L * x);
            x += mu * (lap.L * x);
        } else {
            x += o.step * (lap.L * x);
        }
        if (!x.allFinite()) break;
        last = x;
        done = it;
        if (box_diagonal(x) > 1e12 * size0) break;  // far beyond anything a view shows
    }
    scatter_positions(mesh, lap.map, last);
    diverging_mesh_ = std::move(mesh);
    char buf[400];
    std::snprintf(buf, sizeof buf,
                  "DIVERGED: %s without its checks, iteration %d of %d: the bounding box grew "
                  "%.3g-fold. Shown for teaching, not a result: nothing was applied (Esc "
                  "returns)",
                  op.text().c_str(), done, o.iterations,
                  size0 > 0 ? box_diagonal(last) / size0 : 0.0);
    diverging_note_ = buf;
    log_.warning(diverging_note_);
    notice_ = Notice{Notice::Level::Error, diverging_note_, {}, false};
    shown_.kind = Shown::Kind::Preview;
    shown_.mesh = &diverging_mesh_;
    shown_.positions.clear();
    shown_.level = nullptr;
    bump();
}

}  // namespace trilab::viewer
