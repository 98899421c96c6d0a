// Placeholder until the stl reader and writer land.
#include "core/errors.h"
#include "core/io/mesh_io.h"

namespace trilab {
LoadedMesh read_stl(const std::string& path) { throw IoError(path, 0, "stl: not implemented yet"); }
void write_stl(const HalfedgeMesh&, const std::string& path, const WriteOptions&) {
    throw IoError(path, 0, "stl: not implemented yet");
}
}  // namespace trilab
