#pragma once
// Operations as the viewer and trilab-cli run them: parsed from an "--op" string such as
// "noise --amount 2 --seed 7", run on a copy of the current mesh, and returned as the steps
// the snapshot stack stores (one step per iteration) with their morph correspondences.
// Every operation issue registers its parser here, so `trilab-cli record --op ...`, the
// viewer's panels and the history all speak the same language.
#include <string>
#include <vector>

#include "core/halfedge_mesh.h"
#include "core/morph.h"
#include "core/progress.h"

namespace trilab {

/// One iteration of an operation: the mesh after it, and how it morphs from the one before.
struct OperationStep {
    HalfedgeMesh mesh;
    MorphCorrespondence correspondence;
};

struct OperationResult {
    std::string label;       ///< for the history, e.g. "Add noise"
    std::string parameters;  ///< canonical parameter text, e.g. "--amount 2 --seed 7"
    std::vector<OperationStep> steps;  ///< at least one
    std::vector<std::string> report;   ///< lines for the log
    double ms = 0;                     ///< time of the operation itself
};

/// A parsed operation, ready to run.
struct Operation {
    std::string name;                  ///< e.g. "noise"
    std::vector<std::string> args;     ///< the rest of the --op string, tokenized
};

/// Splits "noise --amount 2" into a name and arguments, and checks the name is known and the
/// arguments parse (without running anything). Throws InvalidArgument naming the bad part.
Operation parse_operation(const std::string& text);
/// Runs `op` on a copy of `mesh`. Throws InvalidArgument for bad parameters, Cancelled when
/// `progress` asks to stop; `mesh` is never changed.
OperationResult run_operation(const Operation& op, const HalfedgeMesh& mesh,
                              Progress& progress);
/// Names of the registered operations.
std::vector<std::string> operation_names();

}  // namespace trilab
