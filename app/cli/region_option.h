#pragma once
// `--region SPEC`: the region an operation of trilab-cli acts on (core/algorithms/selection.h),
// and `trilab-cli select IN OUT --region SPEC`, which stores it in the mesh.
// SPEC: app/ops/region_spec.h.
#include <string>
#include <vector>

#include "app/ops/region_spec.h"

namespace trilab::cli {

// The SPEC parser lives in app/ops/region_spec.h (the viewer's --select shares it).
using trilab::make_region;
using trilab::parse_region_spec;
using trilab::RegionSpec;

/// The --help lines of --region.
extern const char* const kRegionHelp;

/// Runs `trilab-cli select IN OUT --region SPEC [--grow K] [--shrink K] [--invert] [--json]`.
int run_select_command(const std::vector<std::string>& args);

}  // namespace trilab::cli
