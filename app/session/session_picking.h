#pragma once
// SessionPicking: the picks on the shown surface and what they measure (app/session/
// picking.h): the ray cast, how the picks follow the document (a geometry-only step moves
// them, a step that renumbers drops them), the geodesic job (distances and the path between
// two picks, on the one job runner), and the Inspector's explanation of the first pick,
// computed off the render thread.
#include <cstdint>
#include <future>
#include <memory>

#include "app/session/picking.h"
#include "app/session/session_core.h"
#include "app/session/session_document.h"
#include "core/algorithms/decimation.h"

namespace trilab::viewer {

class SessionPicking {
public:
    SessionPicking(SessionCore& core, const SessionDocument& document)
        : core_(core), document_(document) {}

    const PickSet& picks() const { return picks_; }
    /// The picks' inspection or measurement is still being computed.
    bool pending() const { return inspection_future_.valid() || picks_.measurement.computing; }

    /// Casts `ray` (from depth t_min) at the shown surface. A hit replaces the picks, or with
    /// `second` sets the second pick (a measurement from the first; without a first pick it
    /// is the first). A miss clears the picks. Two picks start the geodesic measurement as a
    /// job (the factorization is kept for the state).
    void pick(const Ray& ray, double t_min, bool second);
    void clear();
    /// Keep the geodesic distance from the picked vertices up to date (the colouring).
    void want_distances(bool want);
    /// The decimation options the Inspector explains an edge's collapse with (the Decimation
    /// panel's); a change inspects the picks again.
    void set_inspection_options(const DecimationOptions& options);
    /// After the document is shown again: the picks follow a geometry-only step or are dropped.
    void follow();
    /// Each frame: starts the pending geodesic job when the runner is free, and takes a
    /// finished inspection.
    void update();
    /// Waits for the inspection of the picks (tests and scripted runs).
    void finish_inspection();

private:
    void start_job();
    void start_inspection();
    void launch_inspection();
    void take_inspection();
    /// Forgets what was measured; with `measure` a new measurement and distance job follow.
    void restart(bool measure);

    SessionCore& core_;
    const SessionDocument& document_;
    PickSet picks_;
    bool job_pending_ = false;
    bool want_distances_ = false;
    std::uint64_t request_ = 0;  ///< changes with every request (stale job results)
    DecimationOptions inspection_options_;
    std::future<std::shared_ptr<const PickInspection>> inspection_future_;
    std::uint64_t inspection_request_ = 0;  ///< the pick request the future inspects
    bool inspection_pending_ = false;       ///< an inspection waits for the running one
};

}  // namespace trilab::viewer
