// Placeholder until the off reader and writer land.
#include "core/errors.h"
#include "core/io/mesh_io.h"

namespace trilab {
LoadedMesh read_off(const std::string& path) { throw IoError(path, 0, "off: not implemented yet"); }
void write_off(const HalfedgeMesh&, const std::string& path, const WriteOptions&) {
    throw IoError(path, 0, "off: not implemented yet");
}
}  // namespace trilab
