#pragma once
// `trilab-cli figures`: lists the reference's figures (app/session/reference_figures.h) that
// the viewer loads with Help > Reference figures or `trilab --figure NAME`.
#include <string>
#include <vector>

namespace trilab::cli {

/// Runs `trilab-cli figures [--json]`. Returns the exit code; throws trilab::Error for bad
/// arguments.
int run_figures_command(const std::vector<std::string>& args);

}  // namespace trilab::cli
