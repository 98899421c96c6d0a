#pragma once
// SessionColoring: the vertex colouring's side in the session: the colouring job the window
// asks for on a large mesh (ComputeColoring, on the one job runner; its result is read back
// here), and the current colouring's values per vertex, which the threshold selection uses.
#include <cstdint>
#include <memory>
#include <vector>

#include "app/session/commands.h"
#include "app/session/session_core.h"
#include "core/algorithms/coloring.h"

namespace trilab::viewer {

class SessionColoring {
public:
    explicit SessionColoring(SessionCore& core) : core_(core) {}

    /// The colours of the last ComputeColoring job that ended (null: none yet), with the
    /// colouring and the document state they are of; `id` grows with each result.
    struct Result {
        std::uint64_t id = 0;
        VertexColoring coloring = VertexColoring::None;
        HalfedgeMesh::Revision state;
        VertexColors colors;
    };
    const Result* result() const { return result_.get(); }
    /// The current colouring's value per vertex storage index (NaN: none), for SelectThreshold
    /// (empty: the colouring has none).
    const std::vector<double>& values() const { return values_; }

    /// Starts the colouring job of `command`.
    void compute(const ComputeColoring& command);
    void set_values(std::vector<double> values) { values_ = std::move(values); }

private:
    SessionCore& core_;
    std::shared_ptr<const Result> result_;
    std::vector<double> values_;
};

}  // namespace trilab::viewer
