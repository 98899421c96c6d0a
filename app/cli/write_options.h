#pragma once
// --ascii and --big-endian, how the commands that write a mesh (convert, generate and every
// operation) write .ply and .stl files.
#include "app/cli/arg_reader.h"
#include "core/io/mesh_io.h"

namespace trilab::cli {

/// The help lines of the two options.
inline constexpr const char* kWriteOptionsHelp =
    "  --ascii               write .ply and .stl as text (default binary)\n"
    "  --big-endian          write binary .ply big-endian (default little-endian)\n";

/// When the reader's current option is --ascii or --big-endian, sets it in `o` and returns
/// true.
inline bool take_write_option(ArgReader& reader, WriteOptions& o) {
    if (reader.is("--ascii"))
        o.ascii = reader.flag();
    else if (reader.is("--big-endian"))
        o.big_endian = reader.flag();
    else
        return false;
    return true;
}

}  // namespace trilab::cli
