// `trilab-cli convert`: see convert_command.h.
#include "app/cli/convert_command.h"

#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include "app/cli/arg_reader.h"
#include "app/cli/json_writer.h"
#include "app/cli/write_options.h"
#include "core/errors.h"
#include "core/io/mesh_io.h"

namespace trilab::cli {
namespace {

constexpr const char* kConvertUsage =
    R"(usage: trilab-cli convert IN OUT [--ascii] [--big-endian] [--json]

Reads IN and writes it to OUT, each in the format of its extension (.obj .off .ply .stl .om).
OUT is replaced atomically: a failed write leaves an existing OUT as it was.

options:
{write-options}  --json                one JSON object: "input", "output", "vertices", "faces", "ms"
)";

}  // namespace

int run_convert_command(const std::vector<std::string>& args) {
    std::vector<std::string> files;
    WriteOptions write;
    bool json = false, help = false;
    ArgReader reader(args, "convert");
    while (reader.next()) {
        if (reader.is_help())
            help = true;
        else if (reader.is("--json"))
            json = reader.flag();
        else if (take_write_option(reader, write))
            continue;
        else if (reader.is_option())
            reader.refuse_unknown();
        else
            files.push_back(reader.arg());
    }
    if (help) {
        std::string usage = kConvertUsage;
        const std::string placeholder = "{write-options}";
        usage.replace(usage.find(placeholder), placeholder.size(), kWriteOptionsHelp);
        std::fputs(usage.c_str(), stdout);
        return 0;
    }
    if (files.size() != 2)
        throw InvalidArgument("expected IN and OUT files (see `trilab-cli convert --help`)");
    const LoadedMesh loaded = read_mesh(files[0]);
    write_mesh(loaded.mesh, files[1], write);
    const std::vector<std::string> notes = write_notes(loaded.mesh, files[1]);
    if (json) {
        JsonObject j;
        j.add("input", files[0])
            .add("output", files[1])
            .add("vertices", loaded.mesh.n_vertices())
            .add("faces", loaded.mesh.n_faces());
        if (!notes.empty()) j.add("save_notes", notes);
        j.add("ms", 0.0);
        std::cout << j.str() << "\n";
    } else {
        for (const std::string& line : notes) std::fprintf(stderr, "note: %s\n", line.c_str());
    }
    return 0;
}

}  // namespace trilab::cli
