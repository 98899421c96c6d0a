#pragma once
// `trilab-cli spectrum IN OUT --filter "smooth ..." [spectrum options] [--json]`: the spectral
// lens headless (core/algorithms/transfer_function.h). See spectrum_filter_command.cpp.
#include <string>
#include <vector>

namespace trilab::cli {

/// Whether `spectrum`'s arguments ask for the lens (--filter, --gains or --removed).
bool wants_spectrum_filter(const std::vector<std::string>& args);

/// Runs the lens; returns the exit code (4 when the fairing stopped early). Throws
/// trilab::Error for bad arguments or files.
int run_spectrum_filter_command(const std::vector<std::string>& args);

/// The lines spectrum's --help adds for the lens's options.
extern const char* const kSpectrumFilterHelp;

}  // namespace trilab::cli
