#pragma once
// The registered operations, one function per file app/ops/<name>_op.cpp. Adding an
// operation: write its file (parser, runner, entry function), declare the function here and
// add one line to registry() in app/ops/operation.cpp.
#include "app/ops/operation_entry.h"

namespace trilab {

OperationEntry noise_operation();      ///< app/ops/noise_op.cpp
OperationEntry subdivide_operation();  ///< app/ops/subdivide_op.cpp
OperationEntry smooth_operation();     ///< app/ops/smooth_op.cpp
OperationEntry spectrum_operation();   ///< app/ops/spectrum_op.cpp
OperationEntry decimate_operation();   ///< app/ops/decimate_op.cpp

}  // namespace trilab
