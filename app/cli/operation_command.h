#pragma once
// The one shape of every mesh-operation command of trilab-cli (noise, subdivide, smooth,
// spectrum, decimate, and any operation registered later):
//   trilab-cli NAME [operation options] IN OUT [--json] [--ascii] [--big-endian]
//                   [--keep-partial]  (only where the declaration says it may stop early)
// The operation's options, their --help lines, their errors and their JSON echo all come
// from the operation's declaration (app/ops/operation_decl.h): nothing here knows an
// operation's parameters. The options are checked before any file is read; the output is
// written (atomically) only when everything succeeded; "ms" is the operation alone. A run
// that stopped early (e.g. a diverging fairing) exits 4 with one line naming the iteration
// and the reason, and writes nothing, or with --keep-partial the last good state and
// "stopped_early": true.
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "app/cli/json_writer.h"
#include "app/ops/operation.h"
#include "core/algorithms/selection.h"

namespace trilab::cli {

/// What a command adds to the shared shape: options of its own that take a value (kept out
/// of the operation's options, e.g. spectrum's "--eigenvalues FILE", with their help lines),
/// and `finish`, called once OUT is written with their values (by option name): it writes
/// the command's own outputs, and adds its keys to `json` (after the result's texts) or,
/// without --json (null), prints its lines after the report.
struct CommandExtras {
    std::vector<std::string> value_options;
    std::string help;  ///< lines for --help, one per own option
    std::function<void(const OperationResult&, const std::map<std::string, std::string>& values,
                       JsonObject* json)>
        finish;
    /// Turns the command's own options into the run's region (fill-holes' --loops I,J: the
    /// rims of those loops), or returns false when they name none. Called twice: before any
    /// file is read with `mesh` null (to check the text), then with the loaded mesh (to make
    /// the region, checked against it). Throws InvalidArgument naming the option.
    std::function<bool(const HalfedgeMesh* mesh, const std::map<std::string, std::string>& values,
                       Selection& region)>
        region;
};

/// The extras of command `name` (spectrum's eigenvalues, subdivide's levels; none for others).
CommandExtras command_extras(const std::string& name);

/// Runs `trilab-cli NAME ARGS...` for the registered operation `name`. Returns the exit
/// code; throws trilab::Error for bad arguments or files.
int run_operation_command(const std::string& name, const std::vector<std::string>& args);

/// The --help text of command `name`, from its declaration.
std::string operation_command_help(const std::string& name);

}  // namespace trilab::cli
