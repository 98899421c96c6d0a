#pragma once
// Renumbering a mesh into a spatial order, so that elements close on the surface are close in
// memory: vertices along a Morton (Z-order) curve of their positions, edges and faces by their
// smallest vertex. Algorithms that walk vertex rings over a big mesh (decimation) then miss the
// cache far less, whatever order the file gave, and the numbering depends only on the positions
// and the connectivity: the same mesh with its vertices or faces in another order gets the same
// numbering (up to vertices at exactly the same position, ordered as they were).
#include "core/halfedge_mesh.h"

namespace trilab {

/// Renumbers `mesh` (compacting it: deleted elements are dropped) into the spatial order:
/// vertices by the Morton code of their position quantized to 2^21 steps per axis of the
/// bounding box (ties, such as coincident or non-finite positions, by their old index),
/// edges by (smaller, larger) new vertex index with halfedge 2e going from the smaller to the
/// larger, faces by their sorted new vertex indices; halfedge(f) leaves the face's smallest
/// vertex and halfedge(v) of an interior vertex goes to its smallest neighbour (a boundary
/// vertex keeps its boundary halfedge). Attributes move with their elements; the mesh stays
/// valid. Returns the remapping (old index -> new index). O(V log V + H).
IndexRemap renumber_spatially(HalfedgeMesh& mesh);

}  // namespace trilab
