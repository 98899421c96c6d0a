#pragma once
// SessionFigures: the reference's figures in the session (app/session/reference_figures.h):
// loading one as a job (its built-in model, setup operations and operation as history
// entries, exactly as the panels would run them), and the diverging run shown for teaching:
// an explicit fairing run without its health checks, up to its last finite iteration, as a
// marked shown state that is never a result.
#include <string>

#include "app/ops/operation.h"
#include "app/session/session_core.h"
#include "app/session/session_document.h"
#include "app/session/session_levels.h"
#include "app/session/session_preview.h"

namespace trilab::viewer {

class SessionFigures {
public:
    SessionFigures(SessionCore& core, SessionDocument& document, SessionPreviews& previews,
                   SessionLevels& levels)
        : core_(core), document_(document), previews_(previews), levels_(levels) {}

    /// The figure the document is ("" when none: nothing loaded, or another model since).
    std::string figure() const;
    /// The diverging run is on the screen.
    bool diverging_run_shown() const;
    /// What the diverging run shows (one line, starting "DIVERGED").
    const std::string& diverging_run_note() const { return diverging_note_; }

    /// Loads the reference figure `name` ("1.12b") as one job; logs what the figure used and
    /// the step's translation; an unknown name is an error listing them.
    void load_figure(const std::string& name);
    /// Shows the explicit fairing `op` run from the current state without its health checks
    /// (no history entry; Apply runs `op` itself, which is refused again; Cancel or Esc
    /// returns). Refused with a notice for implicit runs.
    void show_diverging_run(const Operation& op);

private:
    SessionCore& core_;
    SessionDocument& document_;
    SessionPreviews& previews_;
    SessionLevels& levels_;
    std::string figure_;           ///< the figure loaded last
    HalfedgeMesh diverging_mesh_;  ///< the diverging run shown (shown.mesh points here)
    std::string diverging_note_;   ///< what it shows
};

}  // namespace trilab::viewer
