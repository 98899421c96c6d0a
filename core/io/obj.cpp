// Placeholder until the obj reader and writer land.
#include "core/errors.h"
#include "core/io/mesh_io.h"

namespace trilab {
LoadedMesh read_obj(const std::string& path) { throw IoError(path, 0, "obj: not implemented yet"); }
void write_obj(const HalfedgeMesh&, const std::string& path, const WriteOptions&) {
    throw IoError(path, 0, "obj: not implemented yet");
}
}  // namespace trilab
