#pragma once
// The report of the "smooth" operation (app/ops/smooth_op.cpp), read as typed fields:
// report_of<SmoothReport>(result) (app/ops/operation.h). Its options are the core's
// FairingOptions (core/algorithms/fairing.h): options_of<FairingOptions>(op).
#include <cstddef>
#include <limits>
#include <string>

#include "core/algorithms/fairing.h"

namespace trilab {

/// What a smoothing run did, as its --json writes it.
struct SmoothReport {
    int iterations_done = 0;  ///< good iterations
    /// Largest stable explicit step of the operator at the input (Taubin: the limit for
    /// lambda); NaN when not estimated (above 2,000,000 vertices), +inf when nothing moves.
    double max_stable_step = std::numeric_limits<double>::quiet_NaN();
    bool max_stable_step_estimated = true;  ///< false: left out for the mesh's size
    double max_residual = 0;                ///< of the accepted implicit solves
    double initial_volume = std::numeric_limits<double>::quiet_NaN();  ///< NaN: open mesh
    double final_volume = std::numeric_limits<double>::quiet_NaN();    ///< NaN: open mesh
    std::size_t factorizations = 0;
    std::size_t cg_iterations = 0;
    double max_smoothing_distance = 0;   ///< along the normal, result against input
    double mean_smoothing_distance = 0;  ///< over all the input's vertices (moved or not)
    /// Over the vertices that moved only (on a region: its moving vertices), so that a small
    /// region's figure is not diluted by the whole mesh (issue 38, item 3); 0 when none moved.
    double mean_smoothing_distance_moved = 0;
    std::size_t moved_vertices = 0;  ///< vertices whose position changed
    /// Rows of the implicit system solved per iteration (the free vertices of the operator
    /// built: on a region with the outside fixed, the region's vertices); 0 when explicit.
    std::size_t solved_rows = 0;
    std::string solver;  ///< "none", "SimplicialLDLT", ...
};

}  // namespace trilab
