#pragma once
// The registered operations, one function per file app/ops/<name>_op.cpp, each returning
// its declaration (app/ops/operation_decl.h). Adding an operation: write its file, declare
// its function here and add one line to operation_defs() in app/ops/operation.cpp. An
// operation whose options or report are its own structs declares them in app/ops/<name>_op.h
// (decimate_op.h, smooth_op.h, spectrum_op.h) for the callers that read them.
#include <memory>

#include "app/ops/operation.h"

namespace trilab {

std::unique_ptr<OperationDef> noise_operation();      ///< app/ops/noise_op.cpp
std::unique_ptr<OperationDef> subdivide_operation();  ///< app/ops/subdivide_op.cpp
std::unique_ptr<OperationDef> smooth_operation();     ///< app/ops/smooth_op.cpp
std::unique_ptr<OperationDef> spectrum_operation();   ///< app/ops/spectrum_op.cpp
std::unique_ptr<OperationDef> decimate_operation();   ///< app/ops/decimate_op.cpp
std::unique_ptr<OperationDef> flip_operation();       ///< app/ops/flip_op.cpp
std::unique_ptr<OperationDef> weld_operation();       ///< app/ops/weld_op.cpp
std::unique_ptr<OperationDef> remove_components_operation();
std::unique_ptr<OperationDef> features_operation();
std::unique_ptr<OperationDef> sharpen_operation();
std::unique_ptr<OperationDef> fill_holes_operation();

std::unique_ptr<OperationDef> denoise_operation();

std::unique_ptr<OperationDef> remesh_operation();

/// The core options of a "spectrum" operation (the Frequency panel's Decompose).
struct SpectralOptions;
SpectralOptions spectral_options(const Operation& op);
/// The core options of a "decimate" operation (for the collapsing-edges overlay).
struct DecimationOptions;
DecimationOptions decimation_options(const Operation& op);

}  // namespace trilab
