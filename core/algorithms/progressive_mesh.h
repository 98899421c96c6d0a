#pragma once
// A progressive mesh (Hoppe, "Progressive meshes", SIGGRAPH 1996): the fine mesh as a face list
// plus its edge collapses in order, each with the vertex split that undoes it. decimate()
// records one (DecimationOptions::record_progressive, core/algorithms/decimation.h);
// LevelOfDetail (core/algorithms/level_of_detail.h) replays it.
#include <array>
#include <cstdint>
#include <vector>

#include "core/handles.h"
#include "core/types.h"

namespace trilab {

/// The vertex split that undoes one collapse (indices of the input mesh's storage): `removed`
/// came back at `removed_position`, `kept` returns from `kept_after` to `kept_before`, the
/// faces [moved_begin, moved_end) of ProgressiveMesh::ring_faces get `removed` back as the
/// corner that is `kept`, and `faces` (one, or two for an interior edge) reappear. The faces
/// [moved_begin, ring_end) are all faces at `kept` after the collapse (the moved ones, then
/// kept's own): the faces whose shape the collapse changes.
struct VertexSplit {
    Vertex removed, kept;
    Point removed_position, kept_before, kept_after;
    std::array<Face, 2> faces;
    std::uint32_t moved_begin = 0, moved_end = 0, ring_end = 0;
};

/// A progressive mesh: the fine mesh as a face list plus its collapses in order.
struct ProgressiveMesh {
    std::vector<Point> positions;              ///< fine positions, per input vertex index
    std::vector<std::array<Vertex, 3>> faces;  ///< fine corners, per input face index
    std::vector<std::uint8_t> face_alive;      ///< 0 for faces deleted in the input
    std::vector<std::uint8_t> vertex_alive;    ///< 0 for vertices deleted in the input
    std::vector<VertexSplit> collapses;
    std::vector<Face> ring_faces;  ///< see VertexSplit
};

}  // namespace trilab
