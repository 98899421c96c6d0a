// Placeholder until the om reader and writer land.
#include "core/errors.h"
#include "core/io/mesh_io.h"

namespace trilab {
LoadedMesh read_om(const std::string& path) { throw IoError(path, 0, "om: not implemented yet"); }
void write_om(const HalfedgeMesh&, const std::string& path, const WriteOptions&) {
    throw IoError(path, 0, "om: not implemented yet");
}
}  // namespace trilab
