// `--region SPEC` and `trilab-cli select` (app/cli/region_option.h). Parsing is two-staged:
// the SPEC's syntax before any file is read (so a typo fails at once), the weights once the
// mesh is loaded.
#include "app/cli/region_option.h"

#include <cctype>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>

#include "app/cli/arg_reader.h"
#include "app/cli/json_writer.h"
#include "app/cli/write_options.h"
#include "core/errors.h"
#include "core/io/mesh_io.h"
#include "core/number_text.h"

namespace trilab::cli {

namespace {

bool parse_number(const std::string& text, double& out) {
    const char* end = text.data() + text.size();
    const auto [ptr, ec] = std::from_chars(text.data(), end, out);
    return !text.empty() && ec == std::errc() && ptr == end && std::isfinite(out);
}

}  // namespace

const char* const kRegionHelp =
    "  --region SPEC (act on a region only: sphere:X,Y,Z,R[,FEATHER], geodesic:V,R[,FEATHER], "
    "component:V, threshold:QUANTITY,LO,HI (vertices whose colouring QUANTITY, e.g. mean, "
    "gaussian, k1, shape-index, is in [LO, HI]), or file:PATH with one weight per vertex per line "
    "or a PLY/OM with a "
    "`selection` vertex property; weight-0 vertices stay as they are; --json adds "
    "\"region_vertices\")\n";

int run_select_command(const std::vector<std::string>& args) {
    constexpr const char* kUsage =
        R"(usage: trilab-cli select IN OUT --region SPEC [--grow K] [--shrink K] [--invert] [--json]

Writes IN to OUT with a selection stored as the per-vertex weight `selection` (PLY property
`selection`, OM custom property `selection`; other formats drop it), for `--region file:OUT`
of any operation, or for the viewer.

options:
)";
    ArgReader reader(args, "select");
    std::vector<std::string> files;
    std::optional<RegionSpec> spec;
    int grow = 0, shrink = 0;
    bool invert = false, json = false;
    WriteOptions write;
    const auto rings = [&](const char* option) {
        const std::string text = reader.value();
        double x = 0;
        if (!parse_number(text, x) || x < 0 || x > 1000 || x != std::floor(x))
            throw InvalidArgument(std::string(option) +
                                  ": expected a whole number from 0 to 1000, got '" + text + "'");
        return int(x);
    };
    while (reader.next()) {
        if (reader.is_help()) {
            std::fputs(kUsage, stdout);
            std::fputs(kRegionHelp, stdout);
            std::fputs(
                "  --grow K, --shrink K (by K rings, in that order), --invert (1 - weight, "
                "last)\n  --json (one JSON object: \"vertices\", \"region_vertices\", "
                "\"ms\")\n",
                stdout);
            return 0;
        } else if (reader.is("--region")) {
            spec = parse_region_spec(reader.value());
        } else if (reader.is("--grow")) {
            grow = rings("--grow");
        } else if (reader.is("--shrink")) {
            shrink = rings("--shrink");
        } else if (reader.is("--invert")) {
            invert = reader.flag();
        } else if (reader.is("--json")) {
            json = reader.flag();
        } else if (take_write_option(reader, write)) {
            continue;
        } else if (reader.is_option()) {
            reader.refuse_unknown();
        } else {
            files.push_back(reader.arg());
        }
    }
    if (!spec) throw InvalidArgument("select: --region SPEC is required");
    if (files.size() != 2)
        throw InvalidArgument("expected IN and OUT files (see `trilab-cli select --help`)");
    LoadedMesh loaded = read_mesh(files[0]);
    const auto t0 = std::chrono::steady_clock::now();
    Selection s = make_region(loaded.mesh, *spec);
    if (grow > 0) grow_selection(loaded.mesh, s, grow);
    if (shrink > 0) shrink_selection(loaded.mesh, s, shrink);
    if (invert) invert_selection(loaded.mesh, s);
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    store_selection(loaded.mesh, s);
    write_mesh(loaded.mesh, files[1], write);
    const std::size_t n = count_selected(s);
    if (json) {
        JsonObject j;
        j.add("input", files[0])
            .add("output", files[1])
            .add("region", spec->text)
            .add("vertices", loaded.mesh.n_vertices())
            .add("region_vertices", n)
            .add("ms", ms);
        std::cout << j.str() << "\n";
    } else {
        std::printf("wrote %s: %zu of %zu vertices selected (%.1f ms)\n", files[1].c_str(), n,
                    loaded.mesh.n_vertices(), ms);
    }
    return 0;
}

}  // namespace trilab::cli
