#pragma once
// The GLSL sources in shaders/*.glsl, embedded into the binary at build time by
// third_party/cmake/embed_shaders.cmake, so the programs run from any folder.

namespace trilab {

/// The source text of the embedded shader with that file name (e.g. "mesh.vert.glsl"), or
/// nullptr when there is none. The text lives for the whole program.
const char* shader_source(const char* name);

}  // namespace trilab
