// The reference's figures and the diverging run; see session_figures.h.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <utility>
#include <vector>

#include "app/ops/operation_entries.h"
#include "app/session/reference_figures.h"
#include "app/session/session_figures.h"
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

void SessionFigures::load_figure(const std::string& name) {
    const ReferenceFigure* found = find_reference_figure(name);
    if (!found) {
        core_.notify_error("no reference figure '" + name + "'; the figures are " +
                           reference_figure_names());
        return;
    }
    if (core_.jobs.busy()) return core_.busy_error();
    previews_.clear();
    const ReferenceFigure figure = *found;
    struct Loaded {
        HalfedgeMesh model;
        std::vector<std::pair<Operation, OperationResult>> setup;
        Operation op;
        OperationResult result;
    };
    const bool started =
        core_.jobs.start("Figure " + figure.name, [this, figure](Progress& progress) {
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
                core_.log.info("Figure " + figure.name + ": " + figure.title);
                core_.log.info("  the reference: " + figure.reference);
                core_.log.info("  here: " + figure.model_note);
                core_.log.info("  step: " + figure.translation);
                document_.push_loaded(
                    std::move(loaded->model), "Figure " + figure.name + ": " + figure.model,
                    "figure " + figure.name + " (" + figure.model + ")", "", LoadReport{});
                for (auto& [op, result] : loaded->setup) document_.commit(op, std::move(result));
                figure_ = figure.name;
                document_.commit(loaded->op, std::move(loaded->result));
                // A refused run keeps its error in the status bar; otherwise the figure says what
                // it is and how its step was translated.
                if (core_.notice.level != Notice::Level::Error)
                    core_.notice =
                        Notice{Notice::Level::Info,
                               "Figure " + figure.name + ": " + figure.title,
                               {"the reference: " + figure.reference, "here: " + figure.model_note,
                                "step: " + figure.translation},
                               false};
            });
        });
    if (!started) core_.busy_error();
}

std::string SessionFigures::figure() const {
    // push_loaded() names the document after the figure; any other load renames it.
    const std::string prefix = "figure " + figure_ + " (";
    return !figure_.empty() && core_.document.name.rfind(prefix, 0) == 0 ? figure_ : std::string();
}

bool SessionFigures::diverging_run_shown() const {
    return !diverging_note_.empty() && core_.shown.kind == Shown::Kind::Preview &&
           core_.shown.mesh == &diverging_mesh_;
}

void SessionFigures::show_diverging_run(const Operation& op) {
    if (!is_operation<FairingOptions>(op)) return;
    FairingOptions o;
    try {
        check_operation(op);
        o = options_of<FairingOptions>(op);
    } catch (const std::exception& e) {
        core_.notify_error(e.what());
        return;
    }
    if (o.integration == Integration::Implicit) {
        core_.inform("an implicit run does not diverge: nothing to show");
        return;
    }
    previews_.clear();
    levels_.clear(false);
    HalfedgeMesh mesh = core_.mesh();
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
    core_.log.warning(diverging_note_);
    core_.notice = Notice{Notice::Level::Error, diverging_note_, {}, false};
    core_.show(Shown::Kind::Preview, &diverging_mesh_);
}

}  // namespace trilab::viewer
