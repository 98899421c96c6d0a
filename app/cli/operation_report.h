#pragma once
// The JSON report of one operation run, as `trilab-cli NAME ... --json` prints it between
// "output" and "ms": the operation, its canonical parameters, every parameter that applies
// (typed), the result's counts, figures and texts, the command's extras (spectrum's
// eigenvalues, subdivide's levels, ...), whether it stopped early, the save notes and the
// report's lines. The CLI (operation_command.cpp) and the Python module (python/, where it is
// Mesh.report) build it here, so both give the same keys and values.
#include <map>
#include <string>
#include <vector>

#include "app/cli/json_writer.h"
#include "app/cli/operation_command.h"
#include "app/ops/operation.h"

namespace trilab::cli {

/// Adds the report of `result` (a run of `op`; its last step is the output) to `json`;
/// `extras` and `own` are the command's extras and their values (command_extras(),
/// `own` empty when none was given), `save_notes` what writing the output left out.
void add_operation_report(JsonObject& json, const Operation& op, const OperationResult& result,
                          const CommandExtras& extras,
                          const std::map<std::string, std::string>& own,
                          const std::vector<std::string>& save_notes);

}  // namespace trilab::cli
