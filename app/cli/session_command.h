#pragma once
// `trilab-cli session info|export|recipe|make` and `trilab-cli replay`: session files and
// crash journals headless (docs/cli.md#session-and-replay).
#include <string>
#include <vector>

namespace trilab::cli {

/// `trilab-cli session SUBCOMMAND ...`. Returns the exit code; throws trilab::Error for bad
/// arguments or files.
int run_session_command(const std::vector<std::string>& args);

/// `trilab-cli replay RECIPE.json IN OUT [--check SESSION] [--json]`: exit 0 when the result
/// equals the session's current state (or without --check), 5 when it differs.
int run_replay_command(const std::vector<std::string>& args);

}  // namespace trilab::cli
