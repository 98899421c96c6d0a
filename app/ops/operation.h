#pragma once
// Operations as the viewer, trilab-cli and the history run them. Each operation declares its
// typed parameters once (app/ops/operation_decl.h); an Operation is that declaration plus
// one value per parameter. The CLI parses its options into an Operation, the viewer's panels
// edit one directly, the history stores one with each entry, and run_operation() applies it
// to a copy of a mesh, returning the steps the snapshot stack stores (one per iteration)
// with their morph correspondences.
//
// Text form (the CLI's options, `--op` strings, the history's label): the name, then
// "--option value" pairs (or "--option=value"), split on whitespace; flags take no value.
// Errors are InvalidArgument messages that name the operation or the option
// ("--amount: expected a number from 0 to 1000 ..., got 'abc'"); an option that does not
// apply to the other values ("--step" with "--operator taubin") is refused, never ignored.
#include <any>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "app/ops/parameter.h"
#include "core/algorithms/morph.h"
#include "core/halfedge_mesh.h"
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
    /// Named numbers for machine-readable output (the CLI's --json), in a fixed order, e.g.
    /// {"max_displacement", 0.013}. NaN: not defined for this mesh (the volume of an open
    /// mesh); --json writes null.
    std::vector<std::pair<std::string, double>> values;
    /// Named texts for --json (e.g. the solver that ran).
    std::vector<std::pair<std::string, std::string>> texts;
    /// Named lists of numbers (e.g. the eigenvalues of "spectrum").
    std::vector<std::pair<std::string, std::vector<double>>> series;
    /// The run stopped before its last iteration (the steps hold the good ones) and says why
    /// in `stop_reason`; callers report it as a failure unless asked to keep partial results.
    bool stopped_early = false;
    std::string stop_reason;
    /// false: the run changed nothing (it stopped at its first iteration; the one step is
    /// the input), so there is nothing to keep.
    bool changed = true;
};

/// What the caller needs from a run beyond the final mesh. The CLI asks for neither (it
/// writes the last state), the viewer for both (history steps and morphs).
struct RunSettings {
    bool keep_steps = true;  ///< one step per iteration; false: only the last
    bool morph = true;       ///< morph correspondences; false: SameVertices/none where allowed
    /// The caller gives up the input: when this points at the `mesh` passed to run_operation(),
    /// an operation may move it into its result instead of copying it (the CLI, whose input
    /// is not needed after the run). It is left valid but unspecified.
    HalfedgeMesh* consumable = nullptr;
};

class OperationDef;

/// An operation with a value for every parameter.
struct Operation {
    const OperationDef* def = nullptr;
    ParamValues values;

    const std::string& name() const;
    /// The parameter `name`'s value; throws InvalidArgument for an unknown name.
    const ParamValue& value(const std::string& name) const;
    ParamValue& value(const std::string& name);
    /// The canonical parameter text: every parameter that applies, in declaration order
    /// ("--scheme loop --iterations 1"); parses back to the same values.
    std::string parameters() const;
    /// The name and the parameters: "subdivide --scheme loop --iterations 1".
    std::string text() const;
    bool operator==(const Operation& o) const { return def == o.def && values == o.values; }
    bool operator!=(const Operation& o) const { return !(*this == o); }
};

/// The declaration of one operation, made by OperationDecl (app/ops/operation_decl.h).
class OperationDef {
public:
    std::string name;     ///< "smooth": the CLI command and the `--op` name
    std::string label;    ///< "Smooth": the history's and the panel's title
    std::string summary;  ///< a paragraph for --help
    std::vector<ParamSpec> params;
    ParamValues defaults;  ///< from the options struct's own defaults
    /// Its run may stop before the last iteration and say why (OperationResult::stopped_early).
    bool may_stop_early = false;

    /// Index of the parameter `name` (without dashes); throws InvalidArgument naming the
    /// operation and its options when there is none.
    std::size_t index(const std::string& param) const;
    /// nullptr when parameter `i` applies to `values`, else why not ("applies to --operator
    /// taubin only").
    std::function<const char*(const ParamValues& values, std::size_t i)> why_not;
    /// Checks the values together (ranges, combinations); throws InvalidArgument naming the
    /// option.
    std::function<void(const ParamValues& values)> check;
    /// The operation's options struct for `values`, as its declaration binds them (for
    /// callers that call the core themselves, e.g. the collapsing-edges overlay).
    std::function<std::any(const ParamValues& values)> options;
    /// Runs on a copy of `mesh` (never modified). Throws InvalidArgument, Cancelled.
    std::function<OperationResult(const ParamValues& values, const HalfedgeMesh& mesh,
                                  Progress& progress, const RunSettings& settings)>
        run;
    /// One line listing the options: "--amount PCT (...), --seed S (...)".
    std::string usage() const;
    /// Lines for --help: one per option, with its range, default and help.
    std::string help() const;
};

/// Every registered operation, in menu order.
const std::vector<const OperationDef*>& operation_defs();
/// The operation `name`; throws InvalidArgument listing the known names.
const OperationDef& operation_def(const std::string& name);
/// Names of the registered operations.
std::vector<std::string> operation_names();
/// The options of operation `name` for help texts (OperationDef::usage()).
std::string operation_usage(const std::string& name);

/// The operation `name` with its default values.
Operation make_operation(const std::string& name);
/// Parses "--option value" tokens for operation `name`; checks everything (without
/// running). Throws InvalidArgument naming the bad part.
Operation parse_operation(const std::string& name, const std::vector<std::string>& args);
/// Parses "noise --amount 2": the name, then the options.
Operation parse_operation(const std::string& text);
/// Checks values set programmatically (a panel, a sweep): ranges and combinations (values of
/// parameters that do not apply are not used). Throws InvalidArgument naming the option.
void check_operation(const Operation& op);
/// Runs `op` on a copy of `mesh`. Throws InvalidArgument for bad parameters, Cancelled when
/// `progress` asks to stop; `mesh` is never changed.
OperationResult run_operation(const Operation& op, const HalfedgeMesh& mesh, Progress& progress,
                              const RunSettings& settings = {});

}  // namespace trilab
