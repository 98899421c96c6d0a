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
// Typed access (below): options_of<Options>(op) gives an operation's values as its options
// struct, set_options(op, options) writes one back, operation_of(options) makes one, and
// report_of<Report>(result) gives a run's typed report; is_operation<Options>(op) says which
// operation op is. Outside app/ops nothing needs a parameter's or a result's name.
//   operation  options struct                        typed report
//   noise      NoiseOptions (core/algorithms/noise.h)  NoiseReport
//   subdivide  SubdivisionOptions                    SubdivisionResult (levels empty: the steps)
//   smooth     FairingOptions                        SmoothReport (app/ops/smooth_op.h)
//   denoise    DenoiseOptions (core/algorithms/denoise.h)  DenoiseReport
//   spectrum   SpectrumOptions (spectrum_op.h)       SpectrumReport (app/ops/spectrum_op.h)
//   decimate   DecimateOptions (decimate_op.h)       DecimationReport
//   flip       FlipOptions                           FlipReport
//   weld       WeldOptions                           WeldReport
//
// Errors are InvalidArgument messages that name the operation or the option
// ("--amount: expected a number from 0 to 1000 ..., got 'abc'"); an option that does not
// apply to the other values ("--step" with "--operator taubin") is refused, never ignored.
#include <any>
#include <functional>
#include <string>
#include <typeinfo>
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
    /// The run's report as a struct of its own (report_of<Report>()): the core's report
    /// (NoiseReport, DecimationReport, ...) or the operation's (SmoothReport, SpectrumReport).
    std::any typed_report;
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
    /// The region the run acts on (core/algorithms/selection.h: one weight in [0, 1] per vertex
    /// storage index of the input), or nullptr for the whole mesh. Part of the run's input, not
    /// of its parameters: the viewer passes the document's selection, the CLI its --region;
    /// the operation's text and history label do not hold it. Vertices of weight 0 stay bit
    /// for bit; an all-ones region gives exactly the unselected result. run_operation() checks
    /// it against the mesh and refuses it for an operation that does not take one
    /// (OperationDef::takes_region). Not owned; must outlive the run.
    const std::vector<float>* region = nullptr;
    /// The input's connected components as label_components() numbers them, when the caller
    /// has them for this very topology (the viewer keeps its current state's): an operation
    /// that acts on the components a region touches (flip) then need not find them. Not owned.
    const std::vector<Index>* components = nullptr;
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
    /// It honours RunSettings::region (OperationDecl::acts_on_region()); false: a region is
    /// refused with a message naming the operation.
    bool takes_region = false;
    /// How it uses a region, one line for --help (empty when it takes none).
    std::string region_help;
    /// The type of its options struct (FairingOptions for "smooth"); one per operation.
    const std::type_info* options_type = nullptr;

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
    /// The inverse of `options`: the values of an options struct (held in the std::any, of
    /// type *options_type) as the declaration binds them, none marked given. Fields no
    /// parameter binds are not read.
    std::function<ParamValues(const std::any& options)> from_options;
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
/// Throws InvalidArgument "--PARAM: WHY" when parameter `param` of `op` does not apply to
/// op's other values ("--step: does not apply to --operator taubin ..."), as the command line
/// refuses such an option, or naming the operation's options when it has no such parameter.
/// For callers that vary one parameter of an operation (the viewer's --sweep), so that they
/// refuse what the CLI refuses (issue 38, item 2).
void check_parameter_applies(const Operation& op, const std::string& param);
/// "" when a run may be kept as the command line keeps it; otherwise why not, one line: it
/// stopped early ("stopped early: iteration 1: the bounding box grew ...") or changed nothing
/// ("changed nothing"). A sweep's preview that diverged is a failure, as `--op` is.
std::string run_failure(const OperationResult& result);
/// Throws InvalidArgument "LABEL: the region is empty (0 of N vertices selected ...): nothing
/// to do, nothing changed ..." when no weight of `region` is positive (issue 38, item 10): every
/// operation, in the CLI and the viewer, refuses an empty region with this one message.
void check_region_not_empty(const HalfedgeMesh& mesh, const std::vector<float>& region,
                            const std::string& label);
/// Runs `op` on a copy of `mesh` (on settings.region of it, where given). Throws
/// InvalidArgument for bad parameters or a region that does not fit `mesh` or the operation,
/// or is empty (check_region_not_empty()),
/// Cancelled when `progress` asks to stop; `mesh` is never changed.
OperationResult run_operation(const Operation& op, const HalfedgeMesh& mesh, Progress& progress,
                              const RunSettings& settings = {});

// ---- typed access ---------------------------------------------------------------------------

/// The registered operation whose options struct is `options` (typeid(FairingOptions):
/// "smooth"); throws InvalidArgument when none is.
const OperationDef& operation_def_of(const std::type_info& options);
/// Throws InvalidArgument naming `caller` and both operations unless `op` is the operation of
/// `options` (used by the templates below).
void require_options_type(const Operation& op, const std::type_info& options, const char* caller);
/// Writes `values` (OperationDef::from_options) into `op`: exactly the values whose meaning
/// changed are replaced and marked given (unset optional values aside, which a user cannot
/// type), so op.text() is what a user typing those options would write.
void store_changed_values(Operation& op, const ParamValues& values);

/// The registered operation whose options struct is `Options`.
template <class Options>
const OperationDef& definition_of() {
    return operation_def_of(typeid(Options));
}

/// Whether `op` is the operation whose options struct is `Options`:
/// is_operation<FlipOptions>(op) instead of op.name() == "flip".
template <class Options>
bool is_operation(const Operation& op) {
    return op.def && op.def->options_type && *op.def->options_type == typeid(Options);
}

/// The options struct of `op`'s current values, through its declaration's bindings (fields no
/// parameter binds keep their defaults). Throws InvalidArgument when `op` is another
/// operation (or none).
template <class Options>
Options options_of(const Operation& op) {
    require_options_type(op, typeid(Options), "options_of");
    return std::any_cast<Options>(op.def->options(op.values));
}

/// Writes every bound field of `options` into `op`'s values; the values that changed are
/// marked given (see store_changed_values), the others left as they were, so
/// set_options(op, options_of<Options>(op)) changes nothing. Nothing is checked here
/// (check_operation() does). Throws InvalidArgument when `op` is another operation.
template <class Options>
void set_options(Operation& op, const Options& options) {
    require_options_type(op, typeid(Options), "set_options");
    store_changed_values(op, op.def->from_options(std::any(options)));
}

/// The options struct of `op` where its values were given (named on the command line or
/// changed in a panel) and of `fallback` where they were not: a caller that wants its own
/// value unless the user chose one asks given_or(op, mine) and compares, never a parameter by
/// its name. Throws InvalidArgument when `op` is another operation.
template <class Options>
Options given_or(const Operation& op, const Options& fallback) {
    require_options_type(op, typeid(Options), "given_or");
    ParamValues values = op.def->from_options(std::any(fallback));
    for (std::size_t i = 0; i < values.size() && i < op.values.size(); ++i)
        if (op.values[i].given) values[i] = op.values[i];
    return std::any_cast<Options>(op.def->options(values));
}

/// The operation of `options`: its defaults, with the values `options` changes marked given.
template <class Options>
Operation operation_of(const Options& options) {
    const OperationDef& def = definition_of<Options>();
    Operation op{&def, def.defaults};
    set_options(op, options);
    return op;
}

/// The typed report of a run (OperationResult::typed_report); nullptr when the run holds
/// another type (or none). E.g. report_of<SmoothReport>(result)->max_stable_step.
template <class Report>
const Report* report_of(const OperationResult& result) {
    return std::any_cast<Report>(&result.typed_report);
}

}  // namespace trilab
