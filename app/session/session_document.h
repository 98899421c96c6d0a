#pragma once
// SessionDocument: the session's document and history owner. It loads a mesh into the
// history, runs an operation on a job and commits its result as one entry, walks the history
// (undo, redo, jump), computes texture coordinates, and describes the current state (the
// model information, its components and area). Every change goes through SessionCore's
// push_entry or state_changed, so the other owners follow it.
#include <memory>
#include <string>
#include <vector>

#include "app/ops/operation.h"
#include "app/session/commands.h"
#include "app/session/session_core.h"
#include "core/algorithms/texcoords.h"
#include "core/up_axis.h"

namespace trilab::viewer {

/// The document's selection ("v:selection", core/algorithms/selection.h) as the region of
/// `op`: null when `mesh` has none, it selects everything, or `op` takes no region.
std::shared_ptr<const std::vector<float>> region_of(const Operation& op, const HalfedgeMesh& mesh);

class SessionDocument {
public:
    explicit SessionDocument(SessionCore& core) : core_(core) {}

    /// Makes `mesh` the document (a history entry, or the history's start while the built-in
    /// model is untouched) named `name` from `path`.
    void push_loaded(HalfedgeMesh mesh, std::string label, std::string name, std::string path,
                     LoadReport report);
    /// Runs `op` on the current state as a job; its result becomes one entry (commit()).
    void run(const Operation& op);
    /// Commits `result` of `op` (computed on the current state) as one history entry, or says
    /// why nothing changed; plays the change's morph once.
    void commit(const Operation& op, OperationResult result);
    /// Undo, Redo or JumpTo (other commands: nothing); refused while a job runs.
    void step_history(const Command& command);
    /// Computes texture coordinates by `projection` on the current shape (a history entry).
    void project_texcoords(TexCoordProjection projection, UpAxis up);
    /// The current state's description: its information lines, components, area, closedness
    /// and seams (after every state change).
    void describe_state();

    /// The state before the current entry, on the current connectivity (the morph's start;
    /// the smoothing distance's reference); empty when there is none.
    std::vector<Point> reference_positions() const;
    /// Whether the current history entry moves any vertex (for the morph controls).
    bool entry_moves() const;

private:
    SessionCore& core_;
};

}  // namespace trilab::viewer
