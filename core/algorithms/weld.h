#pragma once
// Welding coincident vertices: joins pieces of one surface that a file keeps apart (patch
// seams, the copies build_mesh() makes of a non-manifold vertex), as far as the result stays
// a valid manifold mesh: only pairs of oppositely oriented boundary edges between the same two
// position groups (core/algorithms/coincident.h: exact, or within `tolerance`) are glued.
// Whatever is left apart (surfaces touching at a point, three faces at an edge, ...) is
// counted and explained in the report.
// The joined vertex sits at its group's position (with a tolerance: the mean of the vertices
// joined, in index order) and keeps the per-vertex normal, colour and texture coordinate of
// its lowest-index vertex; per-corner texture coordinates stay with their faces. Other
// properties are not carried. Faces keep their order; vertices are renumbered (the map is
// returned). The input is not modified.
// Throws InvalidArgument for a negative or non-finite tolerance, or one too small for the
// coordinates (core/algorithms/coincident.h). Complexity: O(V + E) expected, plus a few rounds of
// checks when glues are undone. Why gluing keeps every vertex manifold: weld.cpp.
#include <cstddef>
#include <string>
#include <vector>

#include "core/halfedge_mesh.h"

namespace trilab {

struct WeldOptions {
    /// Distance below which vertices count as coincident; 0 (the default): exactly the same
    /// position, which is what files with seams hold (the teapot's patches share their
    /// boundary coordinates exactly).
    double tolerance = 0;
    /// The region (core/algorithms/selection.h): one weight per vertex storage index, or
    /// nullptr for the whole mesh. Only vertices of positive weight are welded; the others are
    /// never joined and keep their positions bit for bit (they are renumbered like every vertex).
    /// Not owned.
    const std::vector<float>* region = nullptr;
};

struct WeldReport {
    std::size_t groups = 0;               ///< groups of coincident vertices found
    std::size_t coincident_vertices = 0;  ///< vertices in those groups
    std::size_t vertices_joined = 0;      ///< vertices that disappeared into another
    std::size_t edges_glued = 0;          ///< boundary edge pairs that became one edge
    /// Coincident vertices left as separate vertices (one per group counts as kept: a group
    /// of 3 joined into 2 vertices leaves 1 apart).
    std::size_t vertices_left_apart = 0;
    std::size_t edges_left_open = 0;  ///< coincident boundary edges not glued
    /// One line per reason something was left apart, with its count.
    std::vector<std::string> notes;
};

struct WeldResult {
    HalfedgeMesh mesh;
    WeldReport report;
    /// Per input vertex storage index: its vertex in `mesh`, kInvalidIndex for deleted ones.
    std::vector<Index> vertex_map;
};

/// Welds a copy of `mesh`; see the file comment. The result passes validate(). Throws
/// InvalidArgument naming the region when it does not fit the mesh (check_selection()).
WeldResult weld_coincident_vertices(const HalfedgeMesh& mesh, const WeldOptions& options = {});

}  // namespace trilab
