// `trilab-cli generate`: see generate_command.h.
#include "app/cli/generate_command.h"

#include <chrono>
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include "app/cli/arg_reader.h"
#include "app/cli/json_writer.h"
#include "app/cli/stopwatch.h"
#include "app/cli/write_options.h"
#include "core/algorithms/generators.h"
#include "core/errors.h"
#include "core/io/mesh_io.h"

namespace trilab::cli {
namespace {

constexpr const char* kGenerateUsage =
    R"(usage: trilab-cli generate NAME OUT [--ascii] [--big-endian] [--json]
       trilab-cli generate --list

Writes the built-in model NAME to OUT (format by extension).

options:
  --list                print the names of the models, one per line
{write-options}  --json                one JSON object: "model", "output", "vertices", "faces", "ms" (the
                        model's construction, file writing excluded)
)";

}  // namespace

int run_generate_command(const std::vector<std::string>& args) {
    std::vector<std::string> positional;
    WriteOptions write;
    bool json = false, help = false, list = false;
    ArgReader reader(args, "generate");
    while (reader.next()) {
        if (reader.is_help())
            help = true;
        else if (reader.is("--json"))
            json = reader.flag();
        else if (reader.is("--list"))
            list = reader.flag();
        else if (take_write_option(reader, write))
            continue;
        else if (reader.is_option())
            reader.refuse_unknown();
        else
            positional.push_back(reader.arg());
    }
    if (help) {
        std::string usage = kGenerateUsage;
        const std::string placeholder = "{write-options}";
        usage.replace(usage.find(placeholder), placeholder.size(), kWriteOptionsHelp);
        std::fputs(usage.c_str(), stdout);
        return 0;
    }
    if (list) {
        for (const auto& n : generator_names()) std::cout << n << "\n";
        return 0;
    }
    if (positional.size() != 2)
        throw InvalidArgument("expected NAME and OUT (see `trilab-cli generate --help`)");
    const auto t0 = std::chrono::steady_clock::now();
    const HalfedgeMesh mesh = generate(positional[0]);
    const double ms = ms_since(t0);
    write_mesh(mesh, positional[1], write);
    if (json) {
        JsonObject j;
        j.add("model", positional[0])
            .add("output", positional[1])
            .add("vertices", mesh.n_vertices())
            .add("faces", mesh.n_faces())
            .add("ms", ms);
        std::cout << j.str() << "\n";
    }
    return 0;
}

}  // namespace trilab::cli
