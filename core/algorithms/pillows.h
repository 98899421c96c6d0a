#pragma once
// Pillows: closed components of two triangles on the same three vertices (a file that lists a
// triangle twice, once each way round, gives one). Every edge of a pillow joins the same two
// faces, so a pillow is always a whole component. Subdivision cannot refine one (every scheme
// would join two new vertices twice); it sets the pillows aside, refines the rest and puts
// them back unchanged, with a note (core/algorithms/subdivision.h).
#include <cstddef>
#include <string>
#include <vector>

#include "core/halfedge_mesh.h"

namespace trilab {

/// The faces of the pillows of `mesh`, two per pillow (in face order). O(F).
std::vector<Face> pillow_faces(const HalfedgeMesh& mesh);

struct PillowSplit {
    HalfedgeMesh rest;     ///< the mesh without its pillows (compacted, renumbered)
    HalfedgeMesh pillows;  ///< the pillows alone, with their positions and texture coordinates
    std::size_t count = 0;
};
/// Splits `mesh` into its pillows and the rest. Per-vertex normals, colours and texture
/// coordinates and per-corner texture coordinates are kept; other properties are not. O(V + F).
PillowSplit split_off_pillows(const HalfedgeMesh& mesh);

/// Appends a copy of `part` (without garbage) to `mesh` as new elements: positions, and
/// "v:texcoord" and "h:texcoord" where both meshes have them (other properties of the new
/// elements get their defaults). Returns the index of the first new vertex.
Index append_mesh(HalfedgeMesh& mesh, const HalfedgeMesh& part);

/// "1 component left as it is: two triangles on the same three vertices" (n components).
std::string pillow_note(std::size_t n);

}  // namespace trilab
