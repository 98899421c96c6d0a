#pragma once
// SessionLevels: Decimation's level-of-detail slider. Builds the progressive mesh of the
// current state on a job (core/algorithms/level_of_detail.h), shows any level of it at once,
// and applies the shown level as one Decimate entry. A level belongs to the state it was
// built on: any other state forgets it.
#include <memory>
#include <string>

#include "app/ops/operation.h"
#include "app/session/session_core.h"
#include "app/session/session_document.h"
#include "core/algorithms/decimation.h"

namespace trilab::viewer {

class SessionLevels {
public:
    SessionLevels(SessionCore& core, SessionDocument& document)
        : core_(core), document_(document) {}

    /// A level of detail is ready for the current state.
    bool ready() const;
    /// What the progressive mesh reaches (or why it stopped), and whether it is being built.
    const std::string& note() const { return state_.note; }
    bool building() const { return state_.building; }

    /// Builds the progressive mesh of the current state with decimation `op` (a job).
    void build(const Operation& op);
    /// Shows the level keeping `percent` of the vertices.
    void show(double percent);
    /// Commits the shown level as one Decimate entry.
    void apply();
    /// Shows the document again instead of a level; with `forget`, drops the levels too.
    void clear(bool forget);

private:
    struct State {
        std::shared_ptr<const ProgressiveMesh> progressive;
        std::shared_ptr<LevelOfDetail> lod;
        HalfedgeMesh::Revision base;  ///< the document state it was built on
        Operation op;                 ///< the decimation it was built with
        bool building = false;
        std::string note;
    };
    SessionCore& core_;
    SessionDocument& document_;
    State state_;
};

}  // namespace trilab::viewer
