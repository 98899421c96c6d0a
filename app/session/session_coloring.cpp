// The colouring's side in the session; see session_coloring.h.
#include "app/session/session_coloring.h"

#include <string>
#include <utility>

namespace trilab::viewer {

void SessionColoring::compute(const ComputeColoring& command) {
    if (core_.jobs.busy()) return core_.busy_error();
    const HalfedgeMesh snapshot = core_.mesh();  // copy-on-write: the job's own
    core_.jobs.start(std::string("Colouring by ") + coloring_name(command.coloring),
                     [this, c = command, snapshot](Progress&) {
                         auto result = std::make_shared<Result>();
                         result->coloring = c.coloring;
                         result->state = snapshot.revision();
                         result->colors =
                             color_vertices(snapshot, c.coloring, c.options, c.reference.get());
                         return JobRunner::Finish([this, result] {
                             result->id = (result_ ? result_->id : 0) + 1;
                             result_ = result;
                         });
                     });
}

}  // namespace trilab::viewer
