// Placeholder until the ply reader and writer land.
#include "core/errors.h"
#include "core/io/mesh_io.h"

namespace trilab {
LoadedMesh read_ply(const std::string& path) { throw IoError(path, 0, "ply: not implemented yet"); }
void write_ply(const HalfedgeMesh&, const std::string& path, const WriteOptions&) {
    throw IoError(path, 0, "ply: not implemented yet");
}
}  // namespace trilab
