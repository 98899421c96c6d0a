#pragma once
// The shape every mesh-operation command of trilab-cli shares (noise, subdivide, and the
// operations later issues add): `trilab-cli NAME [operation options] IN OUT [--json]
// [--ascii] [--big-endian]`. The command's own flags are taken out and every other "--option"
// goes, with its value, into the operation text, so the CLI accepts exactly what the viewer
// and `record --op` accept. The options are checked before any file is read; the output is
// written (atomically) only when everything succeeded; "ms" is the operation alone.
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "app/cli/json_writer.h"
#include "app/ops/operation.h"

namespace trilab::cli {

/// Adds a command's own keys to the JSON object (after input, output, operation,
/// parameters, vertices and faces; before report and ms).
using AddJson = std::function<void(JsonObject&, const OperationResult&)>;

/// Adds every entry of result.values except vertices and faces (whole numbers as integers).
void add_operation_values(JsonObject& json, const OperationResult& result);

/// What a command adds to the shared shape: options of its own that take a value (kept out
/// of the operation text, e.g. spectrum's "--eigenvalues FILE"), and `finish`, called once
/// OUT is written with their values (by option name): it writes the command's own outputs,
/// and adds its keys to `json` (after the result's texts) or, without --json (null), prints
/// its lines after the report.
struct CommandExtras {
    std::vector<std::string> value_options;
    std::function<void(const OperationResult&, const std::map<std::string, std::string>& values,
                       JsonObject* json)>
        finish;
};

/// Runs `trilab-cli NAME ARGS...` for the registered operation `name`; `usage` is printed
/// for --help. Returns the exit code; throws trilab::Error for bad arguments or files.
/// `flags` names the operation's options that take no value (e.g. "--preserve-volume").
int run_operation_command(const std::string& name, const char* usage,
                          const std::vector<std::string>& args,
                          const AddJson& add_json = add_operation_values,
                          const std::vector<std::string>& flags = {},
                          const CommandExtras& extras = {});

}  // namespace trilab::cli
