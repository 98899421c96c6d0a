#pragma once
// SessionSelection: the document's selection (issue 26). Every way to select from the viewer
// (the brush, the lasso, a region spec, the geodesic ball or component at the pick, a
// threshold on the colouring's values, grow, shrink, invert, feather, clear) ends here as ONE
// history entry whose mesh is the current one with "v:selection" set (or removed), so undo,
// redo, the morph, session files and saving the mesh keep it as they keep any vertex
// property. A preview shown or computing follows: it is computed again on the new selection.
#include <cstddef>
#include <optional>
#include <string>

#include "app/session/commands.h"
#include "app/session/session_coloring.h"
#include "app/session/session_core.h"
#include "app/session/session_picking.h"
#include "app/session/session_preview.h"
#include "core/algorithms/selection.h"

namespace trilab::viewer {

class SessionSelection {
public:
    SessionSelection(SessionCore& core, SessionPreviews& previews, const SessionPicking& picking,
                     const SessionColoring& coloring)
        : core_(core), previews_(previews), picking_(picking), coloring_(coloring) {}

    /// The document's selection ("v:selection"), or nullopt when it has none (operations then
    /// act on the whole mesh).
    std::optional<Selection> get() const;
    /// Vertices of positive weight in the document's selection (0 without one).
    std::size_t count() const;

    /// Carries out a selection command (SetSelection, SelectSpec, SelectAtPick,
    /// SelectThreshold, EditSelection); false: not one. A bad one is an error notice and
    /// changes nothing; so is any while a job other than a preview runs.
    bool execute(const Command& command);

private:
    /// Makes `weights` the document's selection as one entry named `label`.
    bool set(const Selection& weights, const std::string& label,
             const std::string& parameters = "");
    /// Removes the selection (one history entry); nothing when there is none.
    bool clear();
    /// `fresh` combined with the document's selection as `mode` says.
    Selection combine(Selection fresh, SelectionMode mode) const;
    /// The selection edit of `edit` (grow, shrink, invert, feather, clear).
    void edit(const EditSelection& edit);
    /// Pushes `mesh` (the current state with its selection changed) as one entry; the preview
    /// follows.
    void push(HalfedgeMesh mesh, const std::string& label, const std::string& parameters);

    SessionCore& core_;
    SessionPreviews& previews_;
    const SessionPicking& picking_;
    const SessionColoring& coloring_;
};

}  // namespace trilab::viewer
