#pragma once
// The options of the "decimate" operation (app/ops/decimate_op.cpp), for callers that read or
// write its values as typed fields: options_of<DecimateOptions>(op), set_options(op, o)
// (app/ops/operation.h). Its runs report a DecimationReport (report_of<DecimationReport>()).
#include <cstddef>
#include <optional>

#include "core/algorithms/decimation.h"

namespace trilab {

/// The operation's options: the core's, with the vertex target optional (--target-vertices).
struct DecimateOptions {
    DecimationOptions core;
    std::optional<std::size_t> target_vertices;  ///< unset: --percent and --iterations
};

/// The core's options of `o` (its target_vertices is o.target_vertices, or 0 when unset).
DecimationOptions decimation_options(const DecimateOptions& o);

}  // namespace trilab
