#pragma once
// Operations as the viewer and trilab-cli run them: parsed from an "--op" string such as
// "noise --amount 2 --seed 7", run on a copy of the current mesh, and returned as the steps
// the snapshot stack stores (one step per iteration) with their morph correspondences.
// Every operation issue registers its parser here, so `trilab-cli record --op ...`, the
// viewer's panels and the history all speak the same language.
//
// Syntax: the name, then "--option value" pairs (or "--option=value"), split on whitespace;
// no quoting. Errors are InvalidArgument messages that name the operation or the option
// ("--amount: expected a number from 0 to 1000 ..., got 'abc'").
//
// Adding an operation (decimate, spectrum, ...) is a file app/ops/<name>_op.cpp holding its
// two functions and an entry function declared in app/ops/operation_entries.h, plus one line
// in registry() in app/ops/operation.cpp:
//   XOptions parse_x(OptionReader& r);   // loop `while (r.next())`, `r.is("--iterations")`,
//                                        // r.number() / r.whole_number() / r.choice(...), and
//                                        // r.unknown() for anything else; own checks
//                                        // throw r.bad_value("...", text) naming the option
//   OperationResult run_x(const XOptions& o, const HalfedgeMesh& mesh, Progress& progress);
//                                        // copies `mesh`, fills one OperationStep per
//                                        // iteration with its MorphCorrespondence, sets label,
//                                        // canonical parameters, report lines, values and ms
//   OperationEntry x_operation() {      // the entry
//       return make_entry<XOptions>("x", "--iterations N ...", parse_x, run_x); }
// parse_operation() then checks the arguments without running, and run_operation() parses
// again (cheap) and runs; nothing else changes (CLI record --op, viewer, history).
#include <string>
#include <utility>
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
    std::string label;                 ///< for the history, e.g. "Add noise"
    std::string parameters;            ///< canonical parameter text, e.g. "--amount 2 --seed 7"
    std::vector<OperationStep> steps;  ///< at least one
    std::vector<std::string> report;   ///< lines for the log
    double ms = 0;                     ///< time of the operation itself
    /// Named numbers for machine-readable output (the CLI's --json), parameters included,
    /// in a fixed order, e.g. {"amount", 2}, {"seed", 7}, {"max_displacement", 0.013}.
    std::vector<std::pair<std::string, double>> values;
    /// Named texts for --json (e.g. the solver that ran).
    std::vector<std::pair<std::string, std::string>> texts;
    /// Named lists of numbers (e.g. the eigenvalues of "spectrum").
    std::vector<std::pair<std::string, std::vector<double>>> series;
};

/// A parsed operation, ready to run.
struct Operation {
    std::string name;               ///< e.g. "noise"
    std::vector<std::string> args;  ///< the rest of the --op string, tokenized
};

/// Splits "noise --amount 2" into a name and arguments, and checks the name is known and the
/// arguments parse (without running anything). Throws InvalidArgument naming the bad part.
Operation parse_operation(const std::string& text);
/// Runs `op` on a copy of `mesh`. Throws InvalidArgument for bad parameters, Cancelled when
/// `progress` asks to stop; `mesh` is never changed.
OperationResult run_operation(const Operation& op, const HalfedgeMesh& mesh, Progress& progress);
/// Names of the registered operations.
std::vector<std::string> operation_names();
/// The options of operation `name` for help texts, e.g. "--amount PCT (default 1) ...".
/// Throws InvalidArgument for an unknown name.
std::string operation_usage(const std::string& name);

}  // namespace trilab
