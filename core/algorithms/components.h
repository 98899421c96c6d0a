#pragma once
// Connected components of a mesh's surface, and removing the small ones (the pieces a scan
// leaves floating around the object: MeshLab's "Remove Isolated pieces (wrt Face Num / wrt
// Diameter)").
//
// A component is a set of faces joined through shared edges. Faces that only touch at a
// point are never in one component: every vertex of a HalfedgeMesh is manifold (one fan), so
// a file's surfaces touching at a vertex arrive as separate copies of it (build_mesh() splits
// such a vertex), and coincident vertices are not joined either (weld them first,
// core/algorithms/weld.h). Isolated vertices belong to no component.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "core/geometry.h"
#include "core/halfedge_mesh.h"

namespace trilab {

/// One component: its size and extent.
struct ComponentStats {
    std::size_t faces = 0;
    std::size_t vertices = 0;
    BoundingBox bbox;  ///< of its vertices
};

/// Which component each element is in, and the components, numbered in the order of their
/// smallest vertex storage index (deterministic).
struct ComponentLabels {
    /// Per face storage index: its component; kInvalidIndex for deleted faces.
    std::vector<Index> of_face;
    /// Per vertex storage index: its component; kInvalidIndex for isolated and deleted ones.
    std::vector<Index> of_vertex;
    std::vector<ComponentStats> components;
    std::size_t isolated_vertices = 0;
};

/// Labels the faces and vertices of `mesh` by connected component (see the file comment) and
/// measures each component: faces, vertices and bounding box. Builds on label_components()
/// (core/algorithms/mesh_stats.h: union-find over the edges), so the count equals
/// MeshStats::components. Any mesh, deleted elements skipped; throws nothing.
/// O(V + E + F) (union-find with path compression, practically linear).
ComponentLabels label_face_components(const HalfedgeMesh& mesh);

struct RemoveComponentsOptions {
    /// Components with fewer faces than this are removed; unset: no face-count rule.
    std::optional<std::size_t> min_faces;
    /// Components whose bounding-box diagonal is below this fraction (in [0, 1]) of the whole
    /// mesh's bounding-box diagonal are removed; unset: no size rule.
    std::optional<double> min_diameter;
};

struct RemoveComponentsReport {
    std::size_t components_before = 0;
    std::size_t components_after = 0;
    std::size_t faces_removed = 0;
    /// Vertices removed, the isolated ones included.
    std::size_t vertices_removed = 0;
    std::size_t isolated_vertices_removed = 0;
    std::size_t largest_faces = 0;  ///< faces of the largest component (always kept)
    /// The thresholds would have removed the largest component too: it is kept anyway.
    bool largest_kept_anyway = false;
    double mesh_diagonal = 0;  ///< the input's bounding-box diagonal (every live vertex)
    /// min_diameter times mesh_diagonal: the size below which a component goes (0 unset).
    double min_diagonal = 0;
};

struct RemoveComponentsResult {
    HalfedgeMesh mesh;
    RemoveComponentsReport report;
    /// The input's components (label_face_components()), and which of them were removed.
    ComponentLabels labels;
    std::vector<std::uint8_t> removed;
};

/// Removes the connected components of `mesh` below a face count or a size, and its isolated
/// vertices, into a new mesh; the input is not modified.
///
/// Method (after MeshLab's "Remove Isolated pieces"): label_face_components(), then a
/// component is removed when it has fewer than `min_faces` faces or when its bounding-box
/// diagonal is below `min_diameter` times the whole mesh's (a component failing either rule
/// goes; one exactly at a threshold stays). The largest component (most faces; on a tie the
/// first in label order) is always kept, so the result is never empty; the report says when
/// the rules would have removed it. A mesh with no faces is returned unchanged (removing its
/// vertices would remove everything). When nothing is removed the result is a copy of the
/// input, bit for bit.
///
/// The kept part keeps its connectivity exactly: vertices, edges and faces keep their order
/// (compacted), every halfedge its next/prev/face, so boundaries, orientation and genus of
/// each kept component are unchanged. Carried attributes: "v:normal", "v:color",
/// "v:texcoord", "v:subdivision_level" and the per-corner "h:texcoord"; others are dropped.
/// The result passes validate().
///
/// Throws InvalidArgument, before anything is built, when neither option is set, or when
/// min_diameter is not a number in [0, 1]. Complexity: O(V + E + F).
RemoveComponentsResult remove_small_components(const HalfedgeMesh& mesh,
                                               const RemoveComponentsOptions& options);

}  // namespace trilab
