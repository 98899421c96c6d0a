#pragma once
// Crease rules of Sqrt3 and of the two butterflies (issue 39), used by subdivide()
// (core/algorithms/subdivision.h) when the mesh has features (core/features.h). Loop's rules
// (OpenSubdiv's) live in subdivision.cpp.
//
// An edge is a crease at a step when it is a boundary edge or its sharpness s > 0; a vertex's
// class comes from its crease edges as in core/features.h (0 smooth, 1 dart, 2 crease, 3 or
// more or a corner tag: corner). Children inherit child_sharpness(s) (s - 1 per step).
//
// Sqrt3 (L. Kobbelt, "sqrt(3)-Subdivision", SIGGRAPH 2000, section 4: creases as boundaries):
//   a crease edge is not flipped; in odd steps the face beside it keeps it (triangle a, b,
//   centroid), in even steps it is split in three by (a0 + 16 a + 10 b) / 27 and
//   (10 a + 16 b + b1) / 27 (a0, b1 the crease neighbours beyond a and b; at a curve end, a
//   corner or a dart, the reflection 2a - b) and each side fans its centroid over the three
//   pieces. Crease vertices stay in odd steps and move to (4 a0 + 19 v + 4 b1) / 27 in even
//   steps; corners stay; smooth and dart vertices relax with alpha_n = (4 - 2 cos(2 pi/n))/9.
//   Two steps split a crease tri-adically and it converges to a cubic B-spline, as a boundary.
// Butterfly (Dyn, Levin, Gregory 1990) and Modified Butterfly (D. Zorin, P. Schröder,
// W. Sweldens, "Interpolating subdivision for meshes with arbitrary topology", SIGGRAPH 1996):
//   an edge point on a crease takes the four-point rule along the curve,
//   -1/16 a0 + 9/16 a + 9/16 b - 1/16 b1, with a0, b1 as above (the reflection at a corner or
//   a dart gives 7/16, 10/16, -1/16: the curve end is interpolated); an edge point off the
//   creases takes the smooth stencil with every wing that lies across a crease reflected
//   across it (the boundary fallback of subdivision.cpp), and the Modified Butterfly's
//   extraordinary stencil only at vertices with no crease edge and no tag (the ZSS 1996 cases
//   for a vertex on a crease or a corner use the butterfly with reflected wings). Old vertices
//   never move, so corners stay.
// Semi-sharp edges (0 < s <= 1 at a step) blend as Loop's: an edge point s crease + (1 - s)
// smooth (butterflies); a Sqrt3 vertex whose rule changes at this step w parent + (1 - w)
// child, w the mean sharpness of its crease edges with s <= 1. Sqrt3's connectivity treats
// every edge with s > 0 as a crease.
#include <cstdint>
#include <vector>

#include "core/algorithms/subdivision.h"
#include "core/halfedge_mesh.h"
#include "core/progress.h"

namespace trilab {
namespace subdivision_detail {

/// One Sqrt3 step with creases: the refined mesh (positions, "e:sharpness" of the children,
/// "v:corner" of the old vertices kept), and per vertex of it the morph start position, the
/// stencil (a SubdivisionStencil) and the parents. Old vertex v keeps index v, face f's
/// centroid is nv + f, the split points of crease edge number j (in edge order) follow at
/// nv + nf + 2j + {0, 1} (their parents: the edge's ends, the nearer first). `mesh` must be
/// compact, a triangle mesh without pillows; its features are read as they are (valid).
/// `even_step`: the boundary-splitting step of Kobbelt's rule (iterations 2, 4, ...). Throws
/// Cancelled from the progress. O(V + E + F) plus building the mesh (core/mesh_builder.h).
struct Sqrt3CreaseStep {
    HalfedgeMesh mesh;
    std::vector<Point> start;
    std::vector<int> stencil;
    std::vector<SubdivisionParents> parents;
};
Sqrt3CreaseStep sqrt3_creased_step(const HalfedgeMesh& mesh, bool even_step, Progress& progress);

/// Connectivity and positions of a compact mesh as plain arrays (halfedge h = 2e + s), the
/// way subdivision.cpp reads them (a welded copy's arrays included).
struct MeshArrays {
    Index nv, ne, nf;
    const Vertex* to;
    const Halfedge* next;
    const Halfedge* prev;
    const Face* face;
    const Halfedge* vh;
    const Halfedge* fh;
    const Point* x;
    explicit MeshArrays(const HalfedgeMesh& m)
        : nv(Index(m.vertices_size())),
          ne(Index(m.edges_size())),
          nf(Index(m.faces_size())),
          to(m.halfedge_to_array().data()),
          next(m.halfedge_next_array().data()),
          prev(m.halfedge_prev_array().data()),
          face(m.halfedge_face_array().data()),
          vh(m.vertex_halfedge_array().data()),
          fh(m.face_halfedge_array().data()),
          x(m.positions().data()) {}
    Index to_i(Index h) const { return to[h].idx(); }
    Index from_i(Index h) const { return to[h ^ 1u].idx(); }
    Index next_i(Index h) const { return next[h].idx(); }
    Index prev_i(Index h) const { return prev[h].idx(); }
    bool boundary(Index h) const { return !face[h].is_valid(); }
    bool boundary_edge(Index e) const { return boundary(2 * e) || boundary(2 * e + 1); }
};

/// The butterflies' positions of the 1-to-4 split of `m` with features: old vertex v at p[v]
/// (unmoved), the point of edge e at p[nv + e]. `sharp` (one per edge, or null) and `corner`
/// (one per vertex, or null) are the features to use. O(V + E).
void butterfly_positions_creased(const MeshArrays& m, const float* sharp,
                                 const std::uint8_t* corner, bool modified, Point* p);

}  // namespace subdivision_detail
}  // namespace trilab
