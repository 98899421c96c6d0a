// Uniform subdivision of triangle meshes: Loop, Sqrt3, Butterfly and Modified Butterfly.
//
// Notation: an edge a-b with halfedge h = a -> b; c is the third corner of face(h) and d the
// third corner of face(twin(h)); n is a vertex's valence; boundary neighbours of a boundary
// vertex v are v- (previous) and v+ (next) along its boundary loop.
//
// Loop (C. Loop, "Smooth subdivision surfaces based on triangles", MS thesis, Utah 1987),
// 1-to-4 split, approximating:
//   odd, interior edge:   3/8 (a + b) + 1/8 (c + d)
//   odd, boundary edge:   1/2 (a + b)
//   even, interior:       (1 - n beta_n) v + beta_n sum(neighbours),
//                         beta_n = (1/n) (5/8 - (3/8 + 1/4 cos(2 pi / n))^2)
//   even, boundary:       1/8 v- + 3/4 v + 1/8 v+          (cubic B-spline curve rules)
//
// Loop with features (T. DeRose, M. Kass, T. Truong, "Subdivision surfaces in character
// animation", SIGGRAPH 1998; the rules exactly as OpenSubdiv 3.5's Sdc computes them for its
// Loop scheme with the default options: uniform creasing, boundary edges infinitely sharp).
// An edge is sharp when its sharpness s > 0 ("e:sharpness", core/features.h) or it is a
// boundary edge; a vertex's rule comes from its number of sharp edges (0 smooth, 1 dart,
// 2 crease, 3 or more corner) or its corner tag ("v:corner": corner):
//   odd, s > 1:           1/2 (a + b)                                  (crease rule)
//   odd, 0 < s <= 1:      s 1/2 (a + b) + (1 - s) (3/8 (a + b) + 1/8 (c + d))
//   even, smooth, dart:   the smooth rule above
//   even, crease:         3/4 v + 1/8 (e1 + e2), e1, e2 the ends of its two sharp edges
//   even, corner:         v
// The children of an edge get s - 1 (0 once s <= 1; s >= 10 never decays, as OpenSubdiv's
// infinite sharpness). Where a vertex's rule with the children's sharpness differs from its
// rule now (a semi-sharp crease ends at this level), the result is w P + (1 - w) C with P, C
// the two rules' positions and w the mean sharpness of its sharp edges with s <= 1 (at most 1).
// Vertices without a sharp edge, a boundary or a tag take the plain loop's rule, bit for bit.
//
// Sqrt3 (L. Kobbelt, "sqrt(3)-Subdivision", SIGGRAPH 2000), approximating: a new vertex at
// every face centroid (a + b + c) / 3, every old interior edge flipped (the triangle pair at
// edge a-b becomes (a, d', c') and (b, c', d') with c', d' the new centroids), even interior
// vertices relaxed: (1 - alpha_n) v + alpha_n / n sum(neighbours), alpha_n = (4 - 2 cos(2 pi
// / n)) / 9. Boundaries (Kobbelt 2000, section 4): the parity counts the iterations of one
// subdivide() call (iteration 1 is odd).
//   odd step:  boundary edges are neither split nor flipped: the face at boundary edge a-b
//              contributes the triangle (a, b, centroid); boundary vertices stay in place.
//   even step: every boundary edge p_i p_(i+1) is split in three by
//                (p_(i-1) + 16 p_i + 10 p_(i+1)) / 27 and (10 p_i + 16 p_(i+1) + p_(i+2)) / 27
//              and boundary vertices move to (4 p_(i-1) + 19 p_i + 4 p_(i+1)) / 27 (the ternary
//              cubic B-spline rules); the face at the edge gets its centroid c as usual and
//              contributes the fan (a, p, c), (p, q, c), (q, b, c) along the split edge.
//   Two steps therefore split every boundary edge tri-adically, boundary loops keep their
//   number, and the boundary converges to a cubic B-spline.
//
// Butterfly (N. Dyn, D. Levin, J. Gregory, "A butterfly subdivision scheme for surface
// interpolation with tension control", ACM TOG 1990), interpolating, 1-to-4, tension w = 1/16:
//   odd, interior edge:   1/2 (a + b) + 2w (c + d) - w (e1 + e2 + e3 + e4)
//   where e1..e4 are the corners opposite the four "wing" edges b-c, c-a, a-d, d-b.
//
// Modified Butterfly (D. Zorin, P. Schröder, W. Sweldens, "Interpolating subdivision for
// meshes with arbitrary topology", SIGGRAPH 1996), interpolating, 1-to-4:
//   both ends regular (valence 6) or on the boundary: the 10-point stencil with w = 0, which is
//     the 8-point stencil above (1/2, 1/2, 1/8, 1/8, -1/16 x 4);
//   one end a interior and extraordinary (n != 6): 3/4 a + sum_j s_j v_j, v_0 = b, v_j the
//     neighbours of a in order, s_j = (1/n)(1/4 + cos(2 pi j/n) + 1/2 cos(4 pi j/n)) for
//     n >= 5, (3/8, 0, -1/8, 0) for n = 4, (5/12, -1/12, -1/12) for n = 3;
//   both ends interior and extraordinary: the average of the two extraordinary stencils.
// Boundaries (both butterfly schemes): boundary edges use the 4-point rule
//   -1/16 a- + 9/16 a + 9/16 b - 1/16 b+.
// Fallbacks, so that nothing is read outside the mesh: a wing vertex e_i that does not exist
// (its wing edge is a boundary edge) is replaced by its reflection across that wing edge,
// e.g. across c-a: c + a - b. The extraordinary stencil is only used at interior vertices
// (their one-ring is closed); at a boundary vertex of any valence the 8-point stencil with
// reflected wings is used instead (Zorin et al.'s dedicated boundary masks are not).
// Even vertices are never moved (interpolation).
//
// Attributes: "v:texcoord" is interpolated linearly (even vertices keep theirs, odd ones get
// the edge midpoint's / face centroid's / boundary third point's uv); "h:texcoord" (per
// corner) is interpolated within each old face, so 1-to-4 schemes keep seams exactly. Sqrt3's
// flipped edges cross old edges: a new triangle takes its old corner's uv from the old face
// of the halfedge it replaces and each centroid's uv from that centroid's face, so a seam on
// an old interior edge is not kept by Sqrt3 (vertex uvs are exact). Every other attribute
// (normals, colours, ...) is dropped; "v:subdivision_level" is added (input vertices 0), and
// the step's provenance: "v:subdivision_stencil" (the rule that placed each vertex) and
// "v:subdivision_parents" (the coarser vertices it started from; subdivision.h).
// Isolated vertices are kept, unmoved. An input with garbage is collected on a copy first
// (indices then refer to the collected mesh). Two faces with the same three vertices (a closed
// two-triangle "pillow") would give double edges in every scheme: subdivide() sets them aside
// and puts them back unchanged (core/algorithms/pillows.h).
// Coincident vertices (core/algorithms/coincident.h): when the input has any, each level's
// positions are computed on its weld (1-to-4 schemes) and new vertices with the same start position
// are made to coincide (keep_coincident_together()), as follows.
//
// In brief (section 1.3 of the reference):
//  - Loop (Loop 1987; approximating, 1-to-4): beta_n = (1/n)(5/8 - (3/8 + cos(2 pi/n)/4)^2);
//    boundary curves use the cubic B-spline rules (odd 1/2, 1/2; even 1/8, 3/4, 1/8).
//  - Sqrt3 (Kobbelt 2000; approximating): a vertex at every face centroid, every old interior
//    edge flipped, even vertices relaxed with alpha_n = (4 - 2 cos(2 pi/n)) / 9; boundary
//    edges are split in every second step so that two steps make a tri-adic boundary split.
//  - Butterfly (Dyn, Levin, Gregory 1990; interpolating): the 8-point stencil, w = 1/16.
//  - Modified Butterfly (Zorin, Schröder, Sweldens 1996; interpolating): the 10-point regular
//    stencil, extraordinary-vertex rules, the 4-point boundary rule.
// By default every iteration's level is returned and each new vertex records where it starts
// on the coarser surface (for the morph); callers that need neither (the CLI) switch both off
// in SubdivisionOptions. Every vertex records its level (for the "subdivision vertices"
// colouring).
// Texture coordinates ("v:texcoord", "h:texcoord") are interpolated linearly.
// Messy meshes (core/algorithms/coincident.h): vertices at the same position (a seam between
// patches, the copies build_mesh() makes of a non-manifold vertex) stay together on every level.
// The 1-to-4 schemes compute their positions on the mesh welded where that keeps it manifold
// (core/algorithms/weld.h), so a seam edge gets the interior stencil with the partner's faces as
// its other side and the copies of a split vertex the rule of the joined vertex; Sqrt3, whose edge
// flips would dissolve a seam, refines each seam as a boundary curve on both sides. Then new
// vertices whose coarse parents coincide (same start position) and still differ (copies the
// weld cannot join: surfaces touching at a point or three sheets at an edge) get their mean.
// Seams stay seams (boundaries): welding is a separate tool. Pillows (core/algorithms/pillows.h)
// are set aside, the rest is refined, and they come back unchanged on every level with a note.
//
// Implementation: the 1-to-4 refinement is built directly into the new mesh's arrays (no
// edge splits, no hash maps): old vertex v keeps index v, the odd vertex of edge e is V + e,
// old halfedge h = 2e + s becomes A(h) = 4e + 2s (from_vertex(h) -> midpoint) and
// B(h) = 4e + 3 - 2s (midpoint -> to_vertex(h)), face f becomes corner faces 4f + k and the
// centre face 4f + 3 with interior edges 2E + 3f + k. Sqrt3 is built the same way. The inner
// loops index the connectivity arrays directly and write every new halfedge once, in the
// order of its index (the new faces' halfedges face by face, then the old halfedges' pieces
// edge by edge), so that the writes stream; the neighbour sums of the smoothing rules are
// gathered in the same edge pass. The morph correspondence is computed only when asked for,
// and intermediate levels are released at once when the caller keeps only the finest.
// Complexity: linear in the mesh size per iteration.
#include "core/algorithms/subdivision.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>

#include "core/algorithms/coincident.h"
#include "core/algorithms/feature_detection.h"
#include "core/algorithms/pillows.h"
#include "core/algorithms/subdivision_creases.h"
#include "core/algorithms/weld.h"
#include "core/errors.h"
#include "core/features.h"
#include "core/number_text.h"
#include "core/parallel.h"

namespace trilab {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr std::size_t kMaxFaces = 50'000'000;
constexpr std::size_t kCheckMask = 0xFFFF;  // check for cancellation every 64k elements

const char* const kLevelName = "v:subdivision_level";
const char* const kStencilName = "v:subdivision_stencil";
const char* const kParentsName = "v:subdivision_parents";

/// Plain pointers into a mesh's connectivity and position arrays (its built-in properties),
/// fetched once so that the inner loops index arrays instead of going through the property
/// views (subdivision_creases.h's MeshArrays, which the crease rules read too). `Out` is taken
/// after resize_elements() and stays valid while no element is added.
using In = subdivision_detail::MeshArrays;

struct Out {
    Vertex* to;
    Halfedge* next;
    Halfedge* prev;
    Face* face;
    Halfedge* vh;
    Halfedge* fh;
    Point* p;
    explicit Out(HalfedgeMesh& m)
        : to(m.halfedge_to_array().data()),
          next(m.halfedge_next_array().data()),
          prev(m.halfedge_prev_array().data()),
          face(m.halfedge_face_array().data()),
          vh(m.vertex_halfedge_array().data()),
          fh(m.face_halfedge_array().data()),
          p(m.positions().data()) {}
    void link(Index h, Index n) {
        next[h] = Halfedge(n);
        prev[n] = Halfedge(h);
    }
    /// Halfedge h of face f, between halfedges hp and hn, ending at v.
    void halfedge(Index h, Halfedge hn, Halfedge hp, Face f, Vertex v) {
        next[h] = hn;
        prev[h] = hp;
        face[h] = f;
        to[h] = v;
    }
    /// Boundary halfedge h (its face stays invalid), between halfedges hp and hn, ending at v.
    void boundary_halfedge(Index h, Halfedge hn, Halfedge hp, Vertex v) {
        next[h] = hn;
        prev[h] = hp;
        to[h] = v;
    }
    /// Face f is the loop h0 -> h1 -> h2, the halfedges ending at v0, v1, v2.
    void triangle(Index f, Index h0, Index v0, Index h1, Index v1, Index h2, Index v2) {
        link(h0, h1);
        link(h1, h2);
        link(h2, h0);
        face[h0] = face[h1] = face[h2] = Face(f);
        to[h0] = Vertex(v0);
        to[h1] = Vertex(v1);
        to[h2] = Vertex(v2);
        fh[f] = Halfedge(h0);
    }
};

/// The three halfedges of face f: h[0] = halfedge(f), h[1] = next(h[0]), h[2] = next(h[1]).
inline void face_halfedges(const In& m, Index f, Index h[3]) {
    h[0] = m.fh[f].idx();
    h[1] = m.next_i(h[0]);
    h[2] = m.next_i(h[1]);
}

/// The outgoing halfedges of vertex v (valid halfedge), in rotation order.
template <typename F>
void for_each_outgoing_edge(const In& m, Index v, F&& f) {
    const Index h0 = m.vh[v].idx();
    Index g = h0;
    do {
        f(g);
        g = m.prev_i(g) ^ 1u;
    } while (g != h0);
}

/// The feature arrays of a level (core/features.h), indexed by edge and vertex storage index;
/// null where the mesh has none. Boundary edges act as infinitely sharp (OpenSubdiv's default
/// boundary interpolation, VTX_BOUNDARY_EDGE_ONLY).
struct Creases {
    const float* sharp = nullptr;
    const std::uint8_t* corner = nullptr;
    bool any() const { return sharp || corner; }
};

/// The features of `mesh` as crease arrays (null where it has no such property).
Creases creases_of(const HalfedgeMesh& mesh) {
    Creases creases;
    if (const auto s = mesh.get_edge_property<float>(kSharpnessProperty))
        creases.sharp = s.vector().data();
    if (const auto c = mesh.get_vertex_property<std::uint8_t>(kCornerProperty))
        creases.corner = c.vector().data();
    return creases;
}

/// The vertex-vertex rule of OpenSubdiv (Sdc::Crease::DetermineVertexVertexRule) from a count
/// of sharp edges: 0 smooth, 1 dart, 2 crease, 3 or more corner.
enum class CreaseRule { Smooth, Dart, Crease, Corner };
inline CreaseRule rule_of(unsigned sharp_edges, bool tagged) {
    if (tagged || sharp_edges > 2) return CreaseRule::Corner;
    return sharp_edges == 2 ? CreaseRule::Crease
                            : (sharp_edges == 1 ? CreaseRule::Dart : CreaseRule::Smooth);
}

/// The outgoing halfedge of every old vertex with one: map(its old outgoing halfedge).
template <typename Map>
void set_old_vertex_halfedges(const In& m, Out& out, const Map& map) {
    parallel_for(0, m.nv, [&](std::size_t vi) {
        const Halfedge h = m.vh[vi];
        if (h.is_valid()) out.vh[vi] = Halfedge(map(h.idx()));
    });
}

/// Progress within one iteration, mapped onto the whole run.
struct Stage {
    Progress& progress;
    double base, span;
    void report(double f) const { progress.report(base + span * f, "subdividing"); }
    void tick(std::size_t i) const {
        if ((i & kCheckMask) == 0) progress.check_cancelled();
    }
};

/// The levels of the vertices kept from `m` (the input's own "v:subdivision_level", from an
/// earlier subdivision, is not carried: the input's vertices are level 0) and `level` for
/// the new ones, as `out`'s "v:subdivision_level".
void add_levels(const HalfedgeMesh& m, HalfedgeMesh& out, int level) {
    auto& levels = out.vertex_property<int>(kLevelName, level).vector();
    const std::size_t nv = m.vertices_size();
    if (level > 1) {
        if (auto in = m.get_vertex_property<int>(kLevelName)) {
            std::copy_n(in.vector().begin(), nv, levels.begin());
            return;
        }
    }
    std::fill_n(levels.begin(), nv, 0);
}

/// Adds the vertex properties of a level (add_levels(), Provenance) to the empty mesh `out`
/// with their defaults, before its arrays are sized: resize_elements() then fills them with the
/// connectivity's, one array per task on every thread, instead of one after the other here.
void add_level_properties(HalfedgeMesh& out, int level) {
    out.add_vertex_property<int>(kLevelName, level);
    out.add_vertex_property<int>(kStencilName, 0);
    out.add_vertex_property<SubdivisionParents>(kParentsName,
                                                SubdivisionParents::Constant(kInvalidIndex));
}

/// Provenance arrays of a new level ("v:subdivision_stencil", "v:subdivision_parents"), all
/// entries Unknown and without parents.
struct Provenance {
    int* stencil;
    SubdivisionParents* parents;
    explicit Provenance(HalfedgeMesh& out)
        : stencil(out.vertex_property<int>(kStencilName, 0).vector().data()),
          parents(out.vertex_property<SubdivisionParents>(
                         kParentsName, SubdivisionParents::Constant(kInvalidIndex))
                      .vector()
                      .data()) {}
    void set(Index v, SubdivisionStencil st, Index a, Index b = kInvalidIndex,
             Index c = kInvalidIndex) {
        stencil[v] = int(st);
        parents[v] = SubdivisionParents(a, b, c);
    }
};

// ---------------------------------------------------------------------------------------
// 1-to-4 refinement (Loop, Butterfly, Modified Butterfly)
// ---------------------------------------------------------------------------------------

/// The stencils and parents of a 1-to-4 level (old vertex v keeps index v, edge e's vertex is
/// nv + e), classified on `m` itself (coincident copies are marked later, mark_creases()).
/// `known_valence`: the valences when the caller has them (loop_positions()).
void provenance_1to4(const In& m, SubdivisionScheme scheme, HalfedgeMesh& out, const Creases& cr,
                     const std::vector<unsigned>* known_valence = nullptr) {
    const Index nv = m.nv, ne = m.ne;
    Provenance pr(out);
    // The valences by an owner scan of the halfedges (unless known), the stencils in fixed
    // blocks, on every thread (core/parallel.h).
    std::vector<unsigned> counted;
    if (!known_valence) {
        counted.assign(nv, 0);
        parallel_ranges(0, nv, [&](std::size_t lo, std::size_t hi) {
            for (Index h = 0; h < 2 * ne; ++h)
                if (m.to_i(h) - lo < hi - lo) ++counted[m.to_i(h)];
        });
    }
    const std::vector<unsigned>& valence = known_valence ? *known_valence : counted;
    const bool loop = scheme == SubdivisionScheme::Loop;
    const auto interior = [&](Index v) {
        const Halfedge h = m.vh[v];
        return h.is_valid() && !m.boundary(h.idx());
    };
    parallel_for(0, nv, [&](std::size_t vs) {
        const Index v = Index(vs);
        SubdivisionStencil st = SubdivisionStencil::EvenKept;
        if (loop && m.vh[v].is_valid())
            st = !interior(v)      ? SubdivisionStencil::EvenBoundary
                 : valence[v] == 6 ? SubdivisionStencil::EvenRegular
                                   : SubdivisionStencil::EvenExtraordinary;
        pr.set(v, st, v);
    });
    const bool modified = scheme == SubdivisionScheme::ModifiedButterfly;
    parallel_for(0, ne, [&](std::size_t es) {
        const Index e = Index(es);
        const Index a = m.to_i(2 * e + 1), b = m.to_i(2 * e);
        SubdivisionStencil st = SubdivisionStencil::OddRegular;
        if (m.boundary(2 * e) || m.boundary(2 * e + 1))
            st = SubdivisionStencil::OddBoundary;
        else if (modified && ((interior(a) && valence[a] != 6) || (interior(b) && valence[b] != 6)))
            st = SubdivisionStencil::OddExtraordinary;
        pr.set(nv + e, st, a, b);
    });
    if (!loop && cr.sharp) {  // the butterflies' crease rules (subdivision_creases.h)
        for (Index e = 0; e < ne; ++e) {
            const float sh = cr.sharp[e];
            if (!(sh > 0.0f) || m.boundary(2 * e) || m.boundary(2 * e + 1)) continue;
            pr.stencil[nv + e] = int(sh > 1.0f ? SubdivisionStencil::OddFourPoint
                                               : SubdivisionStencil::OddSemiSharp);
        }
    }
    if (!loop || !cr.any()) return;
    // Loop with features: the rules of loop_positions_creased().
    // Only the ends of sharp interior edges and tagged vertices differ from the rules above.
    std::vector<std::uint8_t> touched(nv, 0);
    if (cr.corner) std::copy_n(cr.corner, nv, touched.begin());
    for (Index e = 0; cr.sharp && e < ne; ++e) {
        const float sh = cr.sharp[e];
        if (!(sh > 0.0f) || m.boundary(2 * e) || m.boundary(2 * e + 1)) continue;
        pr.stencil[nv + e] =
            int(sh > 1.0f ? SubdivisionStencil::OddSharp : SubdivisionStencil::OddSemiSharp);
        touched[m.to_i(2 * e)] = touched[m.to_i(2 * e + 1)] = 1;
    }
    for (Index v = 0; v < nv; ++v) {
        if (!touched[v] || !m.vh[v].is_valid()) continue;
        unsigned sharp_p = 0, sharp_c = 0, sharp_only = 0;
        for_each_outgoing_edge(m, v, [&](Index h) {
            const bool border = m.boundary(h) || m.boundary(h ^ 1u);
            const float sh = border ? kInfiniteSharpness : (cr.sharp ? cr.sharp[h >> 1] : 0.0f);
            sharp_p += sh > 0.0f ? 1 : 0;
            sharp_c += child_sharpness(sh) > 0.0f ? 1 : 0;
            sharp_only += sh > 0.0f && !border ? 1 : 0;
        });
        const bool tagged = cr.corner && cr.corner[v] != 0;
        if (sharp_only == 0 && !tagged) continue;  // smooth or boundary: as without features
        const CreaseRule parent = rule_of(sharp_p, tagged), child = rule_of(sharp_c, tagged);
        SubdivisionStencil st = SubdivisionStencil::EvenDart;
        if (parent == CreaseRule::Smooth || parent == CreaseRule::Dart)
            st = SubdivisionStencil::EvenDart;
        else if (parent != child)
            st = SubdivisionStencil::EvenSemiSharp;
        else if (parent == CreaseRule::Crease)
            st = SubdivisionStencil::EvenSharpCrease;
        else
            st = tagged ? SubdivisionStencil::EvenTaggedCorner : SubdivisionStencil::EvenCorner;
        pr.stencil[v] = int(st);
    }
}

/// Marks the vertices of a new level that have coincident copies (a seam's two sides, the
/// copies of a split vertex; `groups` by start position) as creases: their rule was the
/// welded surface's (1-to-4) or the boundary rule on both sides, averaged (Sqrt3).
void mark_creases(const CoincidentGroups& groups, HalfedgeMesh& level) {
    auto stencil = level.get_vertex_property<int>(kStencilName);
    if (!stencil) return;
    for (Index v : groups.members) {
        const auto st = SubdivisionStencil(stencil[Vertex(v)]);
        stencil[Vertex(v)] = int(is_even_stencil(st) ? SubdivisionStencil::EvenCrease
                                                     : SubdivisionStencil::OddCrease);
    }
}

inline Index half_a(Index h) {
    return 4 * (h >> 1) + 2 * (h & 1u);
}
inline Index half_b(Index h) {
    return 4 * (h >> 1) + 3 - 2 * (h & 1u);
}

/// Position of face halfedge h in its face (h_0 = halfedge(f), h_1, h_2), from the
/// face's halfedge and h's neighbours.
inline Index corner_of(const In& m, Index h) {
    const Index f0 = m.fh[m.face[h].idx()].idx();
    return f0 == h ? 0 : (f0 == m.prev_i(h) ? 1 : 2);
}

/// Builds the connectivity of the 1-to-4 split of `m` into `mesh` (positions not set). Each
/// new halfedge is written once, in the order of its index: the interior edges face by face,
/// then the halves of the old edges edge by edge.
void build_1to4(const In& m, HalfedgeMesh& mesh, const Stage& stage) {
    const Index nv = m.nv, ne = m.ne, nf = m.nf;
    mesh.resize_elements(std::size_t(nv) + ne, 2 * std::size_t(ne) + 3 * std::size_t(nf),
                         4 * std::size_t(nf));
    Out out(mesh);
    // Face f: corner faces 4f + k (at to_vertex(h_k)), centre face 4f + 3; interior edge k
    // joins mid(h_k) and mid(h_k1): halfedge `in` (mid(h_k1) -> mid(h_k)) in corner face k,
    // its twin in the centre face.
    // Every face, edge and vertex writes only its own new elements: fixed blocks on every
    // thread (core/parallel.h), the same arrays for any number of threads.
    parallel_for(0, nf, [&](std::size_t fs) {
        const Index fi = Index(fs);
        stage.tick(fi);
        Index h[3];
        face_halfedges(m, fi, h);
        const Index first = 2 * (2 * ne + 3 * fi);  // halfedge `in` of interior edge k: +2k
        for (Index k = 0; k < 3; ++k) {
            const Index k1 = k == 2 ? 0 : k + 1, k2 = k == 0 ? 2 : k - 1;
            const Index in = first + 2 * k, cin = in + 1;
            out.halfedge(in, Halfedge(half_b(h[k])), Halfedge(half_a(h[k1])), Face(4 * fi + k),
                         Vertex(nv + (h[k] >> 1)));
            out.halfedge(cin, Halfedge(first + 2 * k1 + 1), Halfedge(first + 2 * k2 + 1),
                         Face(4 * fi + 3), Vertex(nv + (h[k1] >> 1)));
            out.fh[4 * fi + k] = Halfedge(half_b(h[k]));
        }
        out.fh[4 * fi + 3] = Halfedge(first + 1);
    });
    stage.report(0.3);
    // Old halfedge h (from a to b, in corner k of face f) becomes A = half_a(h) (a -> mid, in
    // corner face k - 1) and B = half_b(h) (mid -> b, in corner face k); on the boundary A
    // and B follow each other.
    parallel_for(0, ne, [&](std::size_t es) {
        const Index e = Index(es);
        stage.tick(e);
        const Index mid = nv + e;
        for (Index hi = 2 * e; hi <= 2 * e + 1; ++hi) {
            const Index a = half_a(hi), b = half_b(hi);
            const Halfedge a_prev(half_b(m.prev_i(hi))), b_next(half_a(m.next_i(hi)));
            const Face f = m.face[hi];
            Index a_next = b, b_prev = a;  // on the boundary A and B follow each other
            Face a_face, b_face;
            if (f.is_valid()) {
                const Index k = corner_of(m, hi), k2 = k == 0 ? 2 : k - 1;
                const Index first = 2 * (2 * ne + 3 * f.idx());
                a_next = first + 2 * k2;
                a_face = Face(4 * f.idx() + k2);
                b_prev = first + 2 * k;
                b_face = Face(4 * f.idx() + k);
            }
            out.halfedge(a, Halfedge(a_next), a_prev, a_face, Vertex(mid));
            out.halfedge(b, b_next, Halfedge(b_prev), b_face, m.to[hi]);
        }
        // The odd vertex's outgoing halfedge: the boundary one if the edge has one.
        out.vh[mid] = Halfedge(half_b(m.boundary(2 * e + 1) ? 2 * e + 1 : 2 * e));
    });
    set_old_vertex_halfedges(m, out, half_a);
}

/// Texture coordinates of the 1-to-4 split.
void carry_uv_1to4(const HalfedgeMesh& mesh, HalfedgeMesh& out) {
    const In m(mesh);
    const Index nv = m.nv, ne = m.ne, nf = m.nf;
    if (auto vuv = mesh.get_vertex_property<TexCoord>("v:texcoord")) {
        const TexCoord* in = vuv.vector().data();
        TexCoord* uv =
            out.add_vertex_property<TexCoord>("v:texcoord", TexCoord::Zero()).vector().data();
        std::copy_n(in, nv, uv);
        for (Index e = 0; e < ne; ++e)
            uv[nv + e] = 0.5 * (in[m.to_i(2 * e)] + in[m.to_i(2 * e + 1)]);
    }
    if (auto huv = mesh.get_halfedge_property<TexCoord>("h:texcoord")) {
        const TexCoord* in = huv.vector().data();
        TexCoord* uv =
            out.add_halfedge_property<TexCoord>("h:texcoord", TexCoord::Zero()).vector().data();
        for (Index fi = 0; fi < nf; ++fi) {
            Index h[3];
            face_halfedges(m, fi, h);
            TexCoord c[3], md[3];
            for (int k = 0; k < 3; ++k) c[k] = in[h[k]];
            // h_k runs from corner k-1 to corner k.
            for (int k = 0; k < 3; ++k) md[k] = 0.5 * (c[k] + c[(k + 2) % 3]);
            for (int k = 0; k < 3; ++k) {
                const int k1 = (k + 1) % 3;
                const Index in_h = 2 * (2 * ne + 3 * fi + Index(k));
                uv[half_b(h[k])] = c[k];
                uv[half_a(h[k1])] = md[k1];
                uv[in_h] = md[k];
                uv[in_h + 1] = md[k1];
            }
        }
    }
}

/// Loop's smooth even rule: (1 - n beta_n) v + beta_n sum(neighbours).
inline Point loop_smooth_even(const Point& v, unsigned n, const Point& ring_sum) {
    const double t = 0.375 + 0.25 * std::cos(2 * kPi / n);
    const double b = (0.625 - t * t) / n;
    return (1.0 - n * b) * v + b * ring_sum;
}

/// Loop's even rule at a vertex with features (DeRose, Kass, Truong 1998, as OpenSubdiv 3.5's
/// Sdc::Scheme::ComputeVertexVertexMask computes it with its default uniform creasing): the
/// parent's rule from its sharp edges (sharpness > 0; boundary edges count) and corner tag,
/// the child's from the decremented sharpness; smooth and dart vertices use the smooth mask,
/// creases 3/4 v + 1/8 (ends), corners stay. Where the parent's and the child's rules differ,
/// the masks blend with the mean parent sharpness of the edges that become smooth (at most 1).
Point loop_feature_even(const In& m, const Creases& cr, Index v, unsigned valence,
                        const Point& ring_sum) {
    const bool tagged = cr.corner && cr.corner[v] != 0;
    unsigned sharp_p = 0, sharp_c = 0, transitions = 0;
    float transition_sum = 0.0f;
    Point ends_p = Point::Zero(), ends_c = Point::Zero();
    for_each_outgoing_edge(m, v, [&](Index h) {
        const bool border = m.boundary(h) || m.boundary(h ^ 1u);
        const float sh = border ? kInfiniteSharpness : (cr.sharp ? cr.sharp[h >> 1] : 0.0f);
        if (!(sh > 0.0f)) return;
        const Point& w = m.x[m.to_i(h)];
        ++sharp_p;
        ends_p += w;
        if (sh <= 1.0f) {
            transition_sum += sh;
            ++transitions;
        }
        if (child_sharpness(sh) > 0.0f) {
            ++sharp_c;
            ends_c += w;
        }
    });
    const Point& x = m.x[v];
    const CreaseRule parent = rule_of(sharp_p, tagged), child = rule_of(sharp_c, tagged);
    auto mask = [&](CreaseRule r, const Point& ends) -> Point {
        switch (r) {
            case CreaseRule::Smooth:
            case CreaseRule::Dart:
                return loop_smooth_even(x, valence, ring_sum);
            case CreaseRule::Crease:
                return 0.75 * x + 0.125 * ends;
            case CreaseRule::Corner:
                break;
        }
        return x;
    };
    if (parent == CreaseRule::Smooth || parent == CreaseRule::Dart)
        return loop_smooth_even(x, valence, ring_sum);
    const Point pm = mask(parent, ends_p);
    if (child == parent) return pm;
    float fraction = transitions ? transition_sum / float(transitions) : 0.0f;
    if (fraction > 1.0f) fraction = 1.0f;
    const double pw = fraction;
    return pw * pm + (1.0 - pw) * mask(child, ends_c);
}

/// Loop positions with features (loop_positions() with the rules of loop_feature_even() and,
/// for an edge of sharpness s > 0, the crease rule (the midpoint) when s > 1 and the blend
/// s midpoint + (1 - s) smooth when s <= 1, as OpenSubdiv's ComputeEdgeVertexMask). Vertices
/// without a sharp edge, a boundary or a tag take exactly loop_positions()' smooth rule.
void loop_positions_creased(const In& m, const Creases& cr, Point* p, const Stage& stage) {
    const Index nv = m.nv, ne = m.ne;
    const Point* x = m.x;
    std::vector<unsigned> valence(nv, 0);
    std::vector<std::uint8_t> special(nv, 0);  // touches a sharp or boundary edge
    std::fill_n(p, nv, Point::Zero());
    for (Index e = 0; e < ne; ++e) {
        stage.tick(e);
        const Index h = 2 * e, t = 2 * e + 1;
        const Index ia = m.to_i(t), ib = m.to_i(h);
        const Point& a = x[ia];
        const Point& b = x[ib];
        p[ia] += b;
        p[ib] += a;
        ++valence[ia];
        ++valence[ib];
        const float sh = cr.sharp ? cr.sharp[e] : 0.0f;
        if (m.boundary(h) || m.boundary(t) || sh > 1.0f) {
            special[ia] = special[ib] = 1;
            p[nv + e] = 0.5 * (a + b);
            continue;
        }
        const Point& c = x[m.to_i(m.next_i(h))];
        const Point& d = x[m.to_i(m.next_i(t))];
        if (sh > 0.0f) {
            special[ia] = special[ib] = 1;
            const double pw = sh, cw = 1.0 - pw;
            p[nv + e] = (pw * 0.5 + cw * 0.375) * (a + b) + (cw * 0.125) * (c + d);
        } else {
            p[nv + e] = 0.375 * (a + b) + 0.125 * (c + d);
        }
    }
    stage.report(0.6);
    std::vector<double> beta(8, -1.0);
    for (Index vi = 0; vi < nv; ++vi) {
        stage.tick(vi);
        const Halfedge h0 = m.vh[vi];
        if (!h0.is_valid()) {
            p[vi] = x[vi];
        } else if (special[vi] || (cr.corner && cr.corner[vi])) {
            p[vi] = loop_feature_even(m, cr, vi, valence[vi], p[vi]);
        } else {
            const unsigned n = valence[vi];
            if (n >= beta.size()) beta.resize(2 * std::size_t(n) + 1, -1.0);
            if (beta[n] < 0) {
                const double t = 0.375 + 0.25 * std::cos(2 * kPi / n);
                beta[n] = (0.625 - t * t) / n;
            }
            const double b = beta[n];
            p[vi] = (1.0 - n * b) * x[vi] + b * p[vi];
        }
    }
}

/// Loop positions of the refined mesh: the odd vertices over the edges in fixed blocks, then
/// the even vertices by an owner scan (core/parallel.h, parallel_ranges()): each thread owns a
/// range of vertices, reads every edge in order and sums the neighbours of its own vertices
/// only, so that each sum runs in edge order (the bits of a one-thread scatter, and of
/// uniform_step_1to4()'s loop_even_at()) for any number of threads; the even rules then run on
/// the same range. The valences stay in `valence` (provenance_1to4() reads them).
void loop_positions(const In& m, Point* p, const Stage& stage, std::vector<unsigned>& valence) {
    const Index nv = m.nv, ne = m.ne;
    const Point* x = m.x;
    parallel_for_blocks(0, ne, [&](std::size_t b, std::size_t end) {
        stage.tick(b);
        for (Index e = Index(b); e < Index(end); ++e) {
            const Index h = 2 * e, t = 2 * e + 1;
            const Point& pa = x[m.to_i(t)];
            const Point& pb = x[m.to_i(h)];
            if (m.boundary(h) || m.boundary(t)) {
                p[nv + e] = 0.5 * (pa + pb);
            } else {
                const Point& c = x[m.to_i(m.next_i(h))];
                const Point& d = x[m.to_i(m.next_i(t))];
                p[nv + e] = 0.375 * (pa + pb) + 0.125 * (c + d);
            }
        }
    });
    stage.report(0.6);
    valence.resize(nv);
    parallel_ranges(0, nv, [&](std::size_t lo, std::size_t hi) {
        const Index first = Index(lo), count = Index(hi - lo);
        std::fill(p + lo, p + hi, Point::Zero());
        std::fill(valence.begin() + std::ptrdiff_t(lo), valence.begin() + std::ptrdiff_t(hi), 0u);
        for (Index e = 0; e < ne; ++e) {
            stage.tick(e);
            const Index ia = m.to_i(2 * e + 1), ib = m.to_i(2 * e);
            if (ia - first < count) {
                p[ia] += x[ib];
                ++valence[ia];
            }
            if (ib - first < count) {
                p[ib] += x[ia];
                ++valence[ib];
            }
        }
        std::vector<double> beta(8, -1.0);
        for (Index vi = first; vi < Index(hi); ++vi) {
            const Halfedge h0 = m.vh[vi];
            if (!h0.is_valid()) {
                p[vi] = x[vi];
            } else if (m.boundary(h0.idx())) {
                p[vi] =
                    0.75 * x[vi] + 0.125 * (x[m.to_i(h0.idx())] + x[m.from_i(m.prev_i(h0.idx()))]);
            } else {
                const unsigned n = valence[vi];
                if (n >= beta.size()) beta.resize(2 * std::size_t(n) + 1, -1.0);
                if (beta[n] < 0) {
                    const double t = 0.375 + 0.25 * std::cos(2 * kPi / n);
                    beta[n] = (0.625 - t * t) / n;
                }
                const double b = beta[n];
                p[vi] = (1.0 - n * b) * x[vi] + b * p[vi];
            }
        }
    });
}

/// The corner opposite the wing edge `w` (a halfedge of a face), or its reflection across
/// `w` when twin(w) is a boundary halfedge. opp[h] is the corner opposite face halfedge h
/// (to_vertex(next(h))), invalid on boundary halfedges.
template <typename Opp>
inline Point wing(const In& m, const Opp& opp, Index w) {
    const Index o = opp[w ^ 1u];
    if (o != kInvalidIndex) return m.x[o];
    return m.x[m.to_i(w)] + m.x[m.from_i(w)] - m.x[opp[w]];
}

/// The 8-point butterfly stencil (w = 1/16) on interior halfedge h.
template <typename Opp>
inline Point butterfly8(const In& m, const Opp& opp, Index h) {
    const Index t = h ^ 1u;
    const Point& a = m.x[m.from_i(h)];
    const Point& b = m.x[m.to_i(h)];
    const Point& c = m.x[opp[h]];
    const Point& d = m.x[opp[t]];
    const Point e = wing(m, opp, m.next_i(h)) + wing(m, opp, m.prev_i(h)) +
                    wing(m, opp, m.next_i(t)) + wing(m, opp, m.prev_i(t));
    return 0.5 * (a + b) + 0.125 * (c + d) - 0.0625 * e;
}

/// Weights s_j of the Modified Butterfly extraordinary stencil, flattened per valence.
class ExtraordinaryWeights {
public:
    const double* of(unsigned n) {
        if (n >= offset_.size()) offset_.resize(n + 1, kNone);
        if (offset_[n] == kNone) {
            offset_[n] = weights_.size();
            for (unsigned j = 0; j < n; ++j) weights_.push_back(weight(n, j));
        }
        return weights_.data() + offset_[n];
    }

private:
    static double weight(unsigned n, unsigned j) {
        if (n == 3) return j == 0 ? 5.0 / 12 : -1.0 / 12;
        if (n == 4) return j == 0 ? 0.375 : (j == 2 ? -0.125 : 0.0);
        const double a = 2 * kPi * j / n;
        return (0.25 + std::cos(a) + 0.5 * std::cos(2 * a)) / n;
    }
    static constexpr std::size_t kNone = ~std::size_t(0);
    std::vector<std::size_t> offset_;
    std::vector<double> weights_;
};

/// Odd positions of the butterfly schemes; even vertices keep their position.
void butterfly_positions(const In& m, Point* p, bool modified, const Stage& stage) {
    const Index nv = m.nv, ne = m.ne;
    const Point* x = m.x;
    std::copy_n(x, nv, p);
    // Valences and "extraordinary interior" flags, for the extraordinary rules.
    std::vector<unsigned> valence;
    std::vector<std::uint8_t> extraordinary_vertex;
    ExtraordinaryWeights weights;
    if (modified) {
        valence.assign(nv, 0);
        extraordinary_vertex.assign(nv, 0);
        for (Index hi = 0; hi < 2 * ne; ++hi) ++valence[m.to_i(hi)];
        for (Index vi = 0; vi < nv; ++vi) {
            const Halfedge h = m.vh[vi];
            const bool boundary = !h.is_valid() || m.boundary(h.idx());
            extraordinary_vertex[vi] = !boundary && valence[vi] != 6 ? 1 : 0;
        }
    }
    std::unique_ptr<Index[]> opp_storage(new Index[2 * std::size_t(ne)]);
    Index* opp = opp_storage.get();
    for (Index hi = 0; hi < 2 * ne; ++hi)
        opp[hi] = m.boundary(hi) ? kInvalidIndex : m.to_i(m.next_i(hi));
    stage.report(0.5);
    auto extraordinary = [&](Index h) {  // stencil at from_vertex(h), h interior
        const Index a = m.from_i(h);
        const unsigned n = valence[a];
        const double* s = weights.of(n);
        Point q = 0.75 * x[a];
        Index g = h;
        for (unsigned j = 0; j < n; ++j, g = m.prev_i(g) ^ 1u) q += s[j] * x[m.to_i(g)];
        return q;
    };
    for (Index e = 0; e < ne; ++e) {
        stage.tick(e);
        const Index h = 2 * e, t = 2 * e + 1;
        Point q;
        if (m.boundary(h) || m.boundary(t)) {
            const Index bh = m.boundary(h) ? h : t;  // boundary halfedge a -> b
            const Point& a = x[m.from_i(bh)];
            const Point& b = x[m.to_i(bh)];
            const Point& a0 = x[m.from_i(m.prev_i(bh))];
            const Point& b1 = x[m.to_i(m.next_i(bh))];
            q = 0.5625 * (a + b) - 0.0625 * (a0 + b1);
        } else if (modified) {
            const bool ea = extraordinary_vertex[m.from_i(h)] != 0;
            const bool eb = extraordinary_vertex[m.to_i(h)] != 0;
            if (ea && eb)
                q = 0.5 * (extraordinary(h) + extraordinary(t));
            else if (ea)
                q = extraordinary(h);
            else if (eb)
                q = extraordinary(t);
            else
                q = butterfly8(m, opp, h);
        } else {
            q = butterfly8(m, opp, h);
        }
        p[nv + e] = q;
    }
}

/// The positions of the 1-to-4 split of `m` by `scheme`: odd vertex of edge e at p[nv + e].
/// Plain Loop leaves the valences in `valence` when given.
void positions_1to4(const In& m, SubdivisionScheme scheme, Point* p, const Stage& stage,
                    const Creases& creases = {}, std::vector<unsigned>* valence = nullptr) {
    std::vector<unsigned> scratch;
    if (scheme == SubdivisionScheme::Loop && creases.any())
        loop_positions_creased(m, creases, p, stage);
    else if (scheme == SubdivisionScheme::Loop)
        loop_positions(m, p, stage, valence ? *valence : scratch);
    else if (creases.any())
        butterfly_positions_creased(m, creases.sharp, creases.corner,
                                    scheme == SubdivisionScheme::ModifiedButterfly, p);
    else
        butterfly_positions(m, p, scheme == SubdivisionScheme::ModifiedButterfly, stage);
}

/// The features of the 1-to-4 split (core/features.h): both halves of old edge e (edges 2e and
/// 2e + 1) get child_sharpness() of e's, the edges inside old faces are smooth; old vertices
/// keep their corner tags, new ones have none.
void carry_features_1to4(const In& m, const Creases& cr, HalfedgeMesh& out) {
    if (cr.sharp) {
        std::vector<float>& s = out.add_edge_property<float>(kSharpnessProperty, 0.0f).vector();
        for (Index e = 0; e < m.ne; ++e) s[2 * e] = s[2 * e + 1] = child_sharpness(cr.sharp[e]);
    }
    if (cr.corner) {
        std::vector<std::uint8_t>& c =
            out.add_vertex_property<std::uint8_t>(kCornerProperty, 0).vector();
        std::copy_n(cr.corner, m.nv, c.begin());
    }
}

/// The positions of the 1-to-4 split of `mesh` (compact) computed on its weld
/// (core/algorithms/weld.h): a seam's two sides and the copies of a split vertex get the stencils
/// of the welded surface (the partner's faces are the other side of a seam edge), one value for all
/// copies. The weld keeps the faces in order, so face f's halfedges match the welded face f's.
void welded_positions_1to4(const HalfedgeMesh& mesh, SubdivisionScheme scheme, Point* p,
                           const Stage& stage, const Creases& creases) {
    const WeldResult weld = weld_coincident_vertices(mesh);
    const In w(weld.mesh);
    const In m(mesh);
    std::vector<Point> pw(std::size_t(w.nv) + w.ne);
    // The features on the weld: an edge takes the largest sharpness of the edges it joins, a
    // vertex the tags of its copies.
    std::vector<float> wsharp;
    std::vector<std::uint8_t> wcorner;
    Creases wcreases;
    if (creases.sharp) {
        wsharp.assign(w.ne, 0.0f);
        for (Index f = 0; f < m.nf; ++f) {
            Index h = m.fh[f].idx(), g = w.fh[f].idx();
            for (int k = 0; k < 3; ++k, h = m.next_i(h), g = w.next_i(g))
                wsharp[g >> 1] = std::max(wsharp[g >> 1], creases.sharp[h >> 1]);
        }
        wcreases.sharp = wsharp.data();
    }
    if (creases.corner) {
        wcorner.assign(w.nv, 0);
        for (Index v = 0; v < m.nv; ++v)
            if (creases.corner[v]) wcorner[weld.vertex_map[v]] = 1;
        wcreases.corner = wcorner.data();
    }
    positions_1to4(w, scheme, pw.data(), stage, wcreases);
    for (Index v = 0; v < m.nv; ++v)  // isolated vertices stay (the weld may join them)
        p[v] = m.vh[v].is_valid() ? pw[weld.vertex_map[v]] : m.x[v];
    for (Index f = 0; f < m.nf; ++f) {
        Index h = m.fh[f].idx(), g = w.fh[f].idx();
        for (int k = 0; k < 3; ++k, h = m.next_i(h), g = w.next_i(g))
            p[m.nv + (h >> 1)] = pw[w.nv + (g >> 1)];
    }
}

SubdivisionLevel refine_1to4(const HalfedgeMesh& mesh, SubdivisionScheme scheme, int level,
                             bool morph, bool welded, bool features, const Stage& stage) {
    SubdivisionLevel out;
    out.correspondence.kind = MorphCorrespondence::Kind::FromEarlier;
    const In m(mesh);
    add_level_properties(out.mesh, level);
    build_1to4(m, out.mesh, stage);
    stage.progress.check_cancelled();
    const Creases creases = features ? creases_of(mesh) : Creases{};
    Point* p = out.mesh.positions().data();
    std::vector<unsigned> valence;  // plain Loop on `m` itself: its valences, for the stencils
    if (welded)
        welded_positions_1to4(mesh, scheme, p, stage, creases);
    else
        positions_1to4(m, scheme, p, stage, creases, &valence);
    stage.progress.check_cancelled();
    add_levels(mesh, out.mesh, level);
    provenance_1to4(m, scheme, out.mesh, creases, valence.empty() ? nullptr : &valence);
    if (features) carry_features_1to4(m, creases, out.mesh);
    carry_uv_1to4(mesh, out.mesh);
    if (morph) {
        // Even vertices start where they were, odd ones at their edge's midpoint.
        auto& start = out.correspondence.positions;
        start.resize(std::size_t(m.nv) + m.ne);
        std::copy_n(m.x, m.nv, start.begin());
        for (Index e = 0; e < m.ne; ++e)
            start[m.nv + e] = 0.5 * (m.x[m.to_i(2 * e)] + m.x[m.to_i(2 * e + 1)]);
    }
    return out;
}

// ---------------------------------------------------------------------------------------
// Sqrt3
// ---------------------------------------------------------------------------------------

/// Sqrt3 refinement. Old edge e keeps index e (flipped when interior; in even steps a
/// boundary edge keeps its first segment), the spoke from from_vertex(h) to the centroid of
/// face(h) is edge E + id(h) with id(h) = 3f + k, and in even steps boundary halfedge number j
/// adds the edges E + 3F + 4j + {0: p-q, 1: q-b, 2: p-c, 3: q-c} and the faces 3F + 2j + {0,
/// 1}. Face id(h) is the triangle that interior halfedge h keeps.
///
/// Corner ids of face halfedges (with the id of the next halfedge beside them, so that
/// s_out(next(h)) is read where h is) and numbers of boundary halfedges: every halfedge is
/// one or the other, so every id is written.
struct Sqrt3Ids {
    Index id, next_id;  // next_id: for face halfedges only
};

/// The numbering over arrays filled by number_sqrt3(). Passed by value: the sizes are then
/// locals of each pass, which the stores to the new mesh's arrays cannot alias.
struct Sqrt3Numbering {
    Index nv, ne, nf;
    Index nb;  ///< boundary halfedges split (even steps only)
    Index eb;  ///< first edge of the boundary splits
    const Sqrt3Ids* ids;
    /// corner[3f + k] is halfedge k of face f, so that the spoke pass reads them in order.
    const Index* corner;

    /// The spokes of halfedge h: a -> c (s_out) and c -> a (s_in).
    Index s_out(Index h) const { return 2 * (ne + ids[h].id); }
    Index s_in(Index h) const { return 2 * (ne + ids[h].id) + 1; }
    Index s_out_next(Index h) const { return 2 * (ne + ids[h].next_id); }  // s_out(next(h))
    /// The new edges at boundary halfedge b: 0: p-q, 1: q-b, 2: p-c, 3: q-c.
    Index split_edge(Index b, Index which) const { return 2 * (eb + 4 * ids[b].id + which); }
    /// Boundary split vertices of boundary halfedge t (b -> a): P0 near b, P1 near a.
    Index split_vertex(Index t, Index which) const { return nv + nf + 2 * ids[t].id + which; }
};

/// Fills `ids` (2E entries) and `corner` (3F entries) and returns the numbering over them.
Sqrt3Numbering number_sqrt3(const In& m, bool even_step, Sqrt3Ids* ids, Index* corner) {
    const Index ne = m.ne, nf = m.nf;
    for (Index fi = 0; fi < nf; ++fi) {
        Index h[3];
        face_halfedges(m, fi, h);
        ids[h[0]] = {3 * fi, 3 * fi + 1};
        ids[h[1]] = {3 * fi + 1, 3 * fi + 2};
        ids[h[2]] = {3 * fi + 2, 3 * fi};
        std::copy_n(h, 3, corner + 3 * std::size_t(fi));
    }
    Index nb = 0;
    for (Index hi = 0; hi < 2 * ne; ++hi)
        if (m.boundary(hi)) ids[hi].id = nb++;
    if (!even_step) nb = 0;  // boundary edges are not split in odd steps
    return {m.nv, ne, nf, nb, ne + 3 * nf, ids, corner};
}

/// The new triangles' halfedges of each old face: the spokes. Corner k of face f is halfedge
/// h (a -> b) with twin t; c is f's centroid (set here too). Triangle id(h) is (a, c_g, c)
/// when t is interior (face g), (a, b, c) on the boundary in odd steps, (a, p, c) in even
/// steps. The spoke s_in(h) (c -> a) closes triangle id(h); s_out(h) (a -> c) lies in the
/// triangle of g = twin(prev(h)), or on the boundary next to prev(h).
void build_sqrt3_spokes(const In& m, const Sqrt3Numbering n, bool even_step, Out& out,
                        const Stage& stage) {
    const Index nv = m.nv, ne = m.ne, nf = m.nf;
    for (Index fi = 0; fi < nf; ++fi) {
        stage.tick(fi);
        const Index* h = n.corner + 3 * std::size_t(fi);
        const Vertex v[3] = {m.to[h[0]], m.to[h[1]], m.to[h[2]]};
        out.p[nv + fi] = (m.x[v[0].idx()] + m.x[v[1].idx()] + m.x[v[2].idx()]) / 3.0;
        out.vh[nv + fi] = Halfedge(n.s_in(h[0]));
        for (Index k = 0; k < 3; ++k) {
            const Index k1 = k == 2 ? 0 : k + 1, k2 = k == 0 ? 2 : k - 1;
            const Index hk = h[k], hp = h[k2], t = hk ^ 1u, g = hp ^ 1u;
            const Index own = 3 * fi + k;  // id[hk]
            const Index si = 2 * (ne + own) + 1, so = si - 1;
            // s_in(hk): closes triangle `own`.
            Index si_next = hk, si_prev;
            if (!m.boundary(t)) {
                si_next = n.s_out_next(t);
                si_prev = hk;
            } else {
                si_prev = even_step ? n.split_edge(t, 2) : 2 * (ne + 3 * fi + k1);
            }
            out.halfedge(si, Halfedge(si_next), Halfedge(si_prev), Face(own), v[k2]);
            out.fh[own] = Halfedge(si_next);
            // s_out(hk): in the triangle of g, or on the boundary next to hp.
            Index so_next, so_prev, so_face;
            if (!m.boundary(g)) {
                so_next = g;
                so_prev = n.s_in(g);
                so_face = n.ids[g].id;
            } else if (!even_step) {
                so_next = 2 * (ne + 3 * fi + k2) + 1;  // s_in(hp)
                so_prev = hp;
                so_face = 3 * fi + k2;
            } else {
                so_next = n.split_edge(g, 3) + 1;
                so_prev = n.split_edge(g, 1);
                so_face = 3 * nf + 2 * n.ids[g].id + 1;
            }
            out.halfedge(so, Halfedge(so_next), Halfedge(so_prev), Face(so_face), Vertex(nv + fi));
        }
    }
}

/// The old halfedges keep their indices: an interior edge flipped (h from c_g to c), a
/// boundary one in place (in even steps shortened to its last third). Alongside, each old
/// vertex's neighbour sum (into its slot of out.p) and valence.
void build_sqrt3_old_halfedges(const In& m, const Sqrt3Numbering n, bool even_step, Out& out,
                               std::vector<unsigned>& valence, const Stage& stage) {
    const Index nv = m.nv, ne = m.ne;
    const Point* x = m.x;
    Point* p = out.p;
    valence.assign(nv, 0);
    std::fill_n(p, nv, Point::Zero());
    for (Index hi = 0; hi < 2 * ne; ++hi) {
        stage.tick(hi);
        const Index t = hi ^ 1u;
        if (!(hi & 1u)) {
            const Index a = m.to_i(t), b = m.to_i(hi);
            p[a] += x[b];
            p[b] += x[a];
            ++valence[a];
            ++valence[b];
        }
        const Face f = m.face[hi];
        if (f.is_valid()) {
            const Index own = n.ids[hi].id;
            const Index closing = 2 * (ne + own) + 1;  // s_in of the triangle's old corner
            Index h_next = closing, h_prev = closing;
            Vertex h_to;
            if (!m.boundary(t)) {
                h_prev = n.s_out_next(t);
                h_to = Vertex(nv + f.idx());
            } else if (!even_step) {
                h_next = n.s_out_next(hi);
                h_to = m.to[hi];
            } else {
                h_next = n.split_edge(t, 2);
                h_to = Vertex(n.split_vertex(t, 1));
            }
            out.halfedge(hi, Halfedge(h_next), Halfedge(h_prev), Face(own), h_to);
        } else if (!even_step) {
            out.boundary_halfedge(hi, m.next[hi], m.prev[hi], m.to[hi]);
        } else {  // b -> q -> p -> a, then on to the next boundary halfedge's b -> q
            out.boundary_halfedge(hi, Halfedge(n.split_edge(m.next_i(hi), 1) + 1),
                                  Halfedge(n.split_edge(hi, 0) + 1), m.to[hi]);
        }
    }
}

/// Even steps: the pieces of each boundary edge b -> q -> p -> a and the two new triangles
/// (p, q, c) and (q, b, c) at it.
void build_sqrt3_boundary_splits(const In& m, const Sqrt3Numbering n, Out& out) {
    const Index ne = m.ne, nf = m.nf;
    for (Index t = 0; t < 2 * ne; ++t) {
        if (!m.boundary(t)) continue;
        const Index h = t ^ 1u, own = n.ids[h].id, j = n.ids[t].id;
        const Index c = m.nv + m.face[h].idx(), vp = n.split_vertex(t, 1),
                    vq = n.split_vertex(t, 0);
        const Index pq = n.split_edge(t, 0), qb = n.split_edge(t, 1), pc = n.split_edge(t, 2),
                    qc = n.split_edge(t, 3);
        const Index bq = qb + 1, qp = pq + 1, cp = pc + 1, cq = qc + 1;
        const Index f2 = 3 * nf + 2 * j, f3 = f2 + 1;
        const Index so_next = n.s_out_next(h);
        // In triangle id(h) = (a, p, c): p -> c.
        out.halfedge(pc, Halfedge(2 * (ne + own) + 1), Halfedge(h), Face(own), Vertex(c));
        // Triangle f2 = (p, q, c): p -> q -> c -> p.
        out.triangle(f2, pq, vq, qc, c, cp, vp);
        // Triangle f3 = (q, b, c): q -> b, b -> c (s_out(next(h))), c -> q.
        out.halfedge(qb, Halfedge(so_next), Halfedge(cq), Face(f3), Vertex(m.from_i(t)));
        out.halfedge(cq, Halfedge(qb), Halfedge(so_next), Face(f3), Vertex(vq));
        out.fh[f3] = Halfedge(qb);
        // The boundary pieces b -> q and q -> p.
        out.boundary_halfedge(bq, Halfedge(qp), m.prev[t], Vertex(vq));
        out.boundary_halfedge(qp, Halfedge(t), Halfedge(bq), Vertex(vp));
        out.vh[vq] = Halfedge(qp);
        out.vh[vp] = Halfedge(t);
    }
}

/// The positions of the old vertices (relaxed; in even steps boundary vertices by the
/// ternary rule) and of the boundary split vertices; the centroids are set. `start`, when
/// given, gets the morph start positions of the new vertices (the old ones' are set).
void sqrt3_positions(const In& m, const Sqrt3Numbering n, bool even_step,
                     const std::vector<unsigned>& valence, Point* p, Point* start,
                     const Stage& stage) {
    const Index nv = m.nv, ne = m.ne, nf = m.nf;
    const Point* x = m.x;
    std::vector<double> alpha;
    for (Index vi = 0; vi < nv; ++vi) {
        stage.tick(vi);
        const Halfedge h0 = m.vh[vi];
        if (!h0.is_valid()) {
            p[vi] = x[vi];
        } else if (m.boundary(h0.idx())) {
            p[vi] = even_step ? Point((4.0 * x[m.from_i(m.prev_i(h0.idx()))] + 19.0 * x[vi] +
                                       4.0 * x[m.to_i(h0.idx())]) /
                                      27.0)
                              : x[vi];
        } else {
            const unsigned k = valence[vi];
            if (k >= alpha.size()) alpha.resize(k + 1, -1.0);
            if (alpha[k] < 0) alpha[k] = (4.0 - 2.0 * std::cos(2 * kPi / k)) / 9.0;
            p[vi] = (1.0 - alpha[k]) * x[vi] + (alpha[k] / k) * p[vi];
        }
    }
    if (start) std::copy_n(p + nv, nf, start + nv);
    for (Index t = 0; even_step && t < 2 * ne; ++t) {
        if (!m.boundary(t)) continue;
        // Along t: p0 = from(prev t), p1 = from(t), p2 = to(t), p3 = to(next t).
        const Point& p0 = x[m.from_i(m.prev_i(t))];
        const Point& p1 = x[m.from_i(t)];
        const Point& p2 = x[m.to_i(t)];
        const Point& p3 = x[m.to_i(m.next_i(t))];
        const Index i0 = n.split_vertex(t, 0), i1 = n.split_vertex(t, 1);
        p[i0] = (p0 + 16.0 * p1 + 10.0 * p2) / 27.0;
        p[i1] = (10.0 * p1 + 16.0 * p2 + p3) / 27.0;
        if (start) {
            start[i0] = (2.0 * p1 + p2) / 3.0;
            start[i1] = (p1 + 2.0 * p2) / 3.0;
        }
    }
}

/// "v:texcoord" of the Sqrt3 level: kept at the old vertices, the face centroid's at the
/// new ones, the boundary third points' at the split vertices.
void carry_vertex_uv_sqrt3(const HalfedgeMesh& mesh, const In& m, const Sqrt3Numbering n,
                           bool even_step, HalfedgeMesh& mesh_out) {
    auto vuv = mesh.get_vertex_property<TexCoord>("v:texcoord");
    if (!vuv) return;
    const Index nv = m.nv, ne = m.ne, nf = m.nf;
    const TexCoord* in = vuv.vector().data();
    TexCoord* uv =
        mesh_out.add_vertex_property<TexCoord>("v:texcoord", TexCoord::Zero()).vector().data();
    std::copy_n(in, nv, uv);
    for (Index fi = 0; fi < nf; ++fi) {
        const Index h = m.fh[fi].idx(), hn = m.next_i(h);
        uv[nv + fi] = (in[m.to_i(h)] + in[m.to_i(hn)] + in[m.to_i(m.next_i(hn))]) / 3.0;
    }
    for (Index t = 0; even_step && t < 2 * ne; ++t) {
        if (!m.boundary(t)) continue;
        const TexCoord &u1 = in[m.from_i(t)], &u2 = in[m.to_i(t)];
        uv[n.split_vertex(t, 0)] = (2.0 * u1 + u2) / 3.0;
        uv[n.split_vertex(t, 1)] = (u1 + 2.0 * u2) / 3.0;
    }
}

/// "h:texcoord" of the Sqrt3 level. Corner uvs come from the old face each new corner lies
/// in; a new triangle that straddles a flipped edge takes its old corner's uv from face(h)
/// and the far centroid's from its own face.
void carry_corner_uv_sqrt3(const HalfedgeMesh& mesh, const In& m, const Sqrt3Numbering n,
                           bool even_step, HalfedgeMesh& mesh_out) {
    auto huv = mesh.get_halfedge_property<TexCoord>("h:texcoord");
    if (!huv) return;
    const Index nf = m.nf;
    const TexCoord* in = huv.vector().data();
    TexCoord* uv =
        mesh_out.add_halfedge_property<TexCoord>("h:texcoord", TexCoord::Zero()).vector().data();
    std::vector<TexCoord> centre(nf);
    for (Index fi = 0; fi < nf; ++fi) {
        const Index h = m.fh[fi].idx();
        centre[fi] = (in[h] + in[m.next_i(h)] + in[m.prev_i(h)]) / 3.0;
    }
    for (Index fi = 0; fi < nf; ++fi) {
        Index h = m.fh[fi].idx();
        for (int k = 0; k < 3; ++k, h = m.next_i(h)) {
            const Index t = h ^ 1u;
            const TexCoord& ua = in[m.prev_i(h)];
            const TexCoord& ub = in[h];
            uv[n.s_in(h)] = ua;
            if (!m.boundary(t)) {
                uv[h] = centre[fi];
                uv[n.s_out_next(t)] = centre[m.face[t].idx()];
            } else if (!even_step) {
                uv[h] = ub;
                uv[n.s_out_next(h)] = centre[fi];
            } else {
                const TexCoord up = (2.0 * ua + ub) / 3.0, uq = (ua + 2.0 * ub) / 3.0;
                uv[h] = up;
                uv[n.split_edge(t, 2)] = centre[fi];
                uv[n.split_edge(t, 0)] = uq;
                uv[n.split_edge(t, 3)] = centre[fi];
                uv[n.split_edge(t, 2) + 1] = up;
                uv[n.split_edge(t, 1)] = ub;
                uv[n.s_out_next(h)] = centre[fi];
                uv[n.split_edge(t, 3) + 1] = uq;
            }
        }
    }
}

/// The stencils and parents of a Sqrt3 level: old vertices keep their index, face f's
/// centroid is nv + f, the boundary split vertices follow (even steps).
void provenance_sqrt3(const In& m, const Sqrt3Numbering n, bool even_step, HalfedgeMesh& out) {
    const Index nv = m.nv, ne = m.ne, nf = m.nf;
    Provenance pr(out);
    for (Index v = 0; v < nv; ++v) {
        const Halfedge h = m.vh[v];
        SubdivisionStencil st = SubdivisionStencil::EvenRelaxed;
        if (!h.is_valid())
            st = SubdivisionStencil::EvenKept;
        else if (m.boundary(h.idx()))
            st = even_step ? SubdivisionStencil::EvenBoundary : SubdivisionStencil::EvenKept;
        pr.set(v, st, v);
    }
    for (Index f = 0; f < nf; ++f) {
        const Index h = m.fh[f].idx(), hn = m.next_i(h);
        pr.set(nv + f, SubdivisionStencil::OddFace, m.to_i(h), m.to_i(hn), m.to_i(m.next_i(hn)));
    }
    for (Index t = 0; even_step && t < 2 * ne; ++t) {
        if (!m.boundary(t)) continue;
        for (Index which = 0; which < 2; ++which)
            pr.set(n.split_vertex(t, which), SubdivisionStencil::OddBoundarySplit, m.from_i(t),
                   m.to_i(t));
    }
}

/// One Sqrt3 iteration with creases (core/algorithms/subdivision_creases.h): the level, its
/// provenance, levels and vertex texture coordinates (old vertices keep theirs, centroids and
/// split points interpolate); corner texture coordinates are not carried.
SubdivisionLevel refine_sqrt3_creased(const HalfedgeMesh& mesh, bool even_step, int level,
                                      bool morph, const Stage& stage) {
    subdivision_detail::Sqrt3CreaseStep step =
        subdivision_detail::sqrt3_creased_step(mesh, even_step, stage.progress);
    SubdivisionLevel result;
    result.mesh = std::move(step.mesh);
    result.correspondence.kind = MorphCorrespondence::Kind::FromEarlier;
    add_levels(mesh, result.mesh, level);
    Provenance pr(result.mesh);
    std::copy(step.stencil.begin(), step.stencil.end(), pr.stencil);
    std::copy(step.parents.begin(), step.parents.end(), pr.parents);
    if (auto vuv = mesh.get_vertex_property<TexCoord>("v:texcoord")) {
        auto uv = result.mesh.add_vertex_property<TexCoord>("v:texcoord", TexCoord::Zero());
        for (std::size_t v = 0; v < step.parents.size(); ++v) {
            const SubdivisionParents& q = step.parents[v];
            if (q[1] == kInvalidIndex) {
                uv.vector()[v] = vuv.vector()[q[0]];
            } else if (q[2] != kInvalidIndex) {
                uv.vector()[v] =
                    (vuv.vector()[q[0]] + vuv.vector()[q[1]] + vuv.vector()[q[2]]) / 3.0;
            } else {  // a split point, a third of the way from its first parent (the nearer)
                uv.vector()[v] = (2.0 * vuv.vector()[q[0]] + vuv.vector()[q[1]]) / 3.0;
            }
        }
    }
    if (morph) result.correspondence.positions = std::move(step.start);
    stage.report(1.0);
    return result;
}

/// One Sqrt3 iteration (see Sqrt3Numbering): the connectivity, written once per halfedge,
/// then the positions (and morph start positions), the levels and the texture coordinates.
SubdivisionLevel refine_sqrt3(const HalfedgeMesh& mesh, bool even_step, int level, bool morph,
                              const Stage& stage, bool features = false) {
    if (features) return refine_sqrt3_creased(mesh, even_step, level, morph, stage);
    const In m(mesh);
    const Index nv = m.nv, ne = m.ne, nf = m.nf;
    std::unique_ptr<Sqrt3Ids[]> ids(new Sqrt3Ids[2 * std::size_t(ne)]);
    std::unique_ptr<Index[]> corner(new Index[3 * std::size_t(nf)]);
    const Sqrt3Numbering n = number_sqrt3(m, even_step, ids.get(), corner.get());
    const Index nb = n.nb;
    stage.report(0.1);

    SubdivisionLevel result;
    HalfedgeMesh& mesh_out = result.mesh;
    add_level_properties(mesh_out, level);
    mesh_out.resize_elements(std::size_t(nv) + nf + 2 * std::size_t(nb),
                             std::size_t(ne) + 3 * std::size_t(nf) + 4 * std::size_t(nb),
                             3 * std::size_t(nf) + 2 * std::size_t(nb));
    Out out(mesh_out);
    build_sqrt3_spokes(m, n, even_step, out, stage);
    stage.report(0.3);
    std::vector<unsigned> valence;
    build_sqrt3_old_halfedges(m, n, even_step, out, valence, stage);
    if (even_step) build_sqrt3_boundary_splits(m, n, out);
    set_old_vertex_halfedges(m, out, [&](Index h) {
        return m.boundary(h) ? (even_step ? n.split_edge(h, 1) + 1 : h) : n.s_out(h);
    });
    stage.progress.check_cancelled();
    stage.report(0.5);

    // Positions (the centroids are set) and morph start positions.
    Point* start = nullptr;
    result.correspondence.kind = MorphCorrespondence::Kind::FromEarlier;
    if (morph) {
        result.correspondence.positions.resize(mesh_out.vertices_size());
        start = result.correspondence.positions.data();
        std::copy_n(m.x, nv, start);
    }
    sqrt3_positions(m, n, even_step, valence, out.p, start, stage);
    stage.progress.check_cancelled();
    stage.report(0.8);

    add_levels(mesh, mesh_out, level);
    provenance_sqrt3(m, n, even_step, mesh_out);
    carry_vertex_uv_sqrt3(mesh, m, n, even_step, mesh_out);
    carry_corner_uv_sqrt3(mesh, m, n, even_step, mesh_out);
    stage.report(1.0);
    return result;
}

/// The corner opposite face halfedge h, computed where it is needed (invalid on boundary
/// halfedges): the local counterpart of butterfly_positions()' table.
struct OppOnTheFly {
    const In& m;
    Index operator[](Index h) const { return m.boundary(h) ? kInvalidIndex : m.to_i(m.next_i(h)); }
};

/// The outgoing halfedges of vertex v (valid halfedge), in rotation order.
template <typename F>
void for_each_outgoing(const In& m, Index v, F&& f) {
    const Index h0 = m.vh[v].idx();
    Index g = h0;
    do {
        f(g);
        g = m.prev_i(g) ^ 1u;
    } while (g != h0);
}

unsigned local_valence(const In& m, Index v) {
    if (!m.vh[v].is_valid()) return 0;
    unsigned n = 0;
    for_each_outgoing(m, v, [&](Index) { ++n; });
    return n;
}

bool local_interior(const In& m, Index v) {
    const Halfedge h = m.vh[v];
    return h.is_valid() && !m.boundary(h.idx());
}

/// Loop's even rule at vertex v from its one ring, summing the neighbours in the order of
/// their edges' indices as loop_positions() does (so the result is the same bit for bit).
Point loop_even_at(const In& m, Index v, std::vector<std::pair<Index, Index>>& ring,
                   std::vector<double>& beta) {
    const Point* x = m.x;
    const Halfedge h0 = m.vh[v];
    if (!h0.is_valid()) return x[v];
    if (m.boundary(h0.idx()))
        return 0.75 * x[v] + 0.125 * (x[m.to_i(h0.idx())] + x[m.from_i(m.prev_i(h0.idx()))]);
    ring.clear();
    for_each_outgoing(m, v, [&](Index g) { ring.emplace_back(g >> 1, m.to_i(g)); });
    std::sort(ring.begin(), ring.end());
    Point sum = Point::Zero();
    for (const auto& edge_and_neighbour : ring) sum += x[edge_and_neighbour.second];
    const unsigned n = unsigned(ring.size());
    if (n >= beta.size()) beta.resize(2 * std::size_t(n) + 1, -1.0);
    if (beta[n] < 0) {  // as loop_positions() computes it
        const double t = 0.375 + 0.25 * std::cos(2 * kPi / n);
        beta[n] = (0.625 - t * t) / n;
    }
    const double b = beta[n];
    return (1.0 - n * b) * x[v] + b * sum;
}

/// Loop's odd rule on edge e.
Point loop_odd_at(const In& m, Index e) {
    const Index h = 2 * e, t = 2 * e + 1;
    const Point& a = m.x[m.to_i(t)];
    const Point& b = m.x[m.to_i(h)];
    if (m.boundary(h) || m.boundary(t)) return 0.5 * (a + b);
    const Point& c = m.x[m.to_i(m.next_i(h))];
    const Point& d = m.x[m.to_i(m.next_i(t))];
    return 0.375 * (a + b) + 0.125 * (c + d);
}

/// The butterflies' odd rule on edge e, as butterfly_positions() computes it.
Point butterfly_odd_at(const In& m, Index e, bool modified, ExtraordinaryWeights& weights) {
    const Point* x = m.x;
    const OppOnTheFly opp{m};
    const Index h = 2 * e, t = 2 * e + 1;
    if (m.boundary(h) || m.boundary(t)) {
        const Index bh = m.boundary(h) ? h : t;
        const Point& a = x[m.from_i(bh)];
        const Point& b = x[m.to_i(bh)];
        const Point& a0 = x[m.from_i(m.prev_i(bh))];
        const Point& b1 = x[m.to_i(m.next_i(bh))];
        return 0.5625 * (a + b) - 0.0625 * (a0 + b1);
    }
    if (!modified) return butterfly8(m, opp, h);
    const auto extraordinary_vertex = [&](Index v) {
        return local_interior(m, v) && local_valence(m, v) != 6;
    };
    auto extraordinary = [&](Index g0) {
        const Index a = m.from_i(g0);
        const unsigned n = local_valence(m, a);
        const double* s = weights.of(n);
        Point q = 0.75 * x[a];
        Index g = g0;
        for (unsigned j = 0; j < n; ++j, g = m.prev_i(g) ^ 1u) q += s[j] * x[m.to_i(g)];
        return q;
    };
    const bool ea = extraordinary_vertex(m.from_i(h));
    const bool eb = extraordinary_vertex(m.to_i(h));
    if (ea && eb) return 0.5 * (extraordinary(h) + extraordinary(t));
    if (ea) return extraordinary(h);
    if (eb) return extraordinary(t);
    return butterfly8(m, opp, h);
}

/// The stencil provenance_1to4() gives old vertex v.
SubdivisionStencil even_stencil_at(const In& m, Index v, SubdivisionScheme scheme) {
    if (scheme != SubdivisionScheme::Loop || !m.vh[v].is_valid())
        return SubdivisionStencil::EvenKept;
    if (!local_interior(m, v)) return SubdivisionStencil::EvenBoundary;
    return local_valence(m, v) == 6 ? SubdivisionStencil::EvenRegular
                                    : SubdivisionStencil::EvenExtraordinary;
}

/// The stencil provenance_1to4() gives the new vertex of edge e.
SubdivisionStencil odd_stencil_at(const In& m, Index e, SubdivisionScheme scheme) {
    if (m.boundary(2 * e) || m.boundary(2 * e + 1)) return SubdivisionStencil::OddBoundary;
    const Index a = m.to_i(2 * e + 1), b = m.to_i(2 * e);
    const auto extraordinary = [&](Index v) {
        return local_interior(m, v) && local_valence(m, v) != 6;
    };
    if (scheme == SubdivisionScheme::ModifiedButterfly && (extraordinary(a) || extraordinary(b)))
        return SubdivisionStencil::OddExtraordinary;
    return SubdivisionStencil::OddRegular;
}

}  // namespace

UniformStep1to4 uniform_step_1to4_at(const HalfedgeMesh& mesh, SubdivisionScheme scheme,
                                     const std::vector<std::uint8_t>& vertices,
                                     const std::vector<std::uint8_t>& edges, Progress& progress) {
    if (mesh.has_garbage() || scheme == SubdivisionScheme::Sqrt3 ||
        vertices.size() != mesh.vertices_size() || edges.size() != mesh.edges_size())
        throw InvalidArgument(
            "uniform_step_1to4_at: expected a compact mesh, a 1-to-4 scheme (loop, butterfly, "
            "modified-butterfly) and one flag per vertex and per edge");
    const In m(mesh);
    UniformStep1to4 step;
    step.positions.assign(std::size_t(m.nv) + m.ne, Point::Zero());
    step.stencils.assign(std::size_t(m.nv) + m.ne, int(SubdivisionStencil::EvenKept));
    std::vector<std::pair<Index, Index>> ring;
    std::vector<double> beta;  // Loop's even weight by valence (loop_even_at())
    const bool loop = scheme == SubdivisionScheme::Loop;
    for (Index v = 0; v < m.nv; ++v) {
        if (!vertices[v]) continue;
        if ((v & kCheckMask) == 0) progress.check_cancelled();
        step.positions[v] = loop ? loop_even_at(m, v, ring, beta) : m.x[v];
        step.stencils[v] = int(even_stencil_at(m, v, scheme));
    }
    ExtraordinaryWeights weights;
    const bool modified = scheme == SubdivisionScheme::ModifiedButterfly;
    for (Index e = 0; e < m.ne; ++e) {
        if (!edges[e]) continue;
        if ((e & kCheckMask) == 0) progress.check_cancelled();
        step.positions[m.nv + e] =
            loop ? loop_odd_at(m, e) : butterfly_odd_at(m, e, modified, weights);
        step.stencils[m.nv + e] = int(odd_stencil_at(m, e, scheme));
    }
    return step;
}

UniformStep1to4 uniform_step_1to4_listed(const HalfedgeMesh& mesh, SubdivisionScheme scheme,
                                         const std::vector<Index>& vertices,
                                         const std::vector<Index>& edges, Progress& progress,
                                         bool rings_listed) {
    const In m(mesh);
    const bool in_range =
        std::all_of(vertices.begin(), vertices.end(), [&](Index v) { return v < m.nv; }) &&
        std::all_of(edges.begin(), edges.end(), [&](Index e) { return e < m.ne; });
    if (mesh.has_garbage() || scheme == SubdivisionScheme::Sqrt3 || !in_range)
        throw InvalidArgument(
            "uniform_step_1to4_listed: expected a compact mesh, a 1-to-4 scheme (loop, "
            "butterfly, modified-butterfly) and vertex and edge indices within the mesh");
    const std::size_t n = vertices.size() + edges.size();
    UniformStep1to4 step;
    step.positions.resize(n);
    step.stencils.resize(n);
    std::vector<std::pair<Index, Index>> ring;
    std::vector<double> beta;  // Loop's even weight by valence (loop_even_at())
    const bool loop = scheme == SubdivisionScheme::Loop;
    // Loop's even rule from the listed rings: each listed vertex's neighbours summed over the
    // listed edges in ascending order, as loop_positions() sums them, then the rule.
    const bool sum_over_edges = loop && rings_listed;
    std::vector<Index> slot;        // per vertex: its entry, or invalid
    std::vector<unsigned> valence;  // per listed vertex
    if (sum_over_edges) {
        slot.assign(m.nv, kInvalidIndex);
        for (std::size_t k = 0; k < vertices.size(); ++k) slot[vertices[k]] = Index(k);
        valence.assign(vertices.size(), 0);
        std::fill_n(step.positions.begin(), vertices.size(), Point::Zero());
    }
    std::size_t i = vertices.size();
    ExtraordinaryWeights weights;
    const bool modified = scheme == SubdivisionScheme::ModifiedButterfly;
    for (const Index e : edges) {
        if ((i & kCheckMask) == 0) progress.check_cancelled();
        if (sum_over_edges) {
            const Index a = m.to_i(2 * e + 1), b = m.to_i(2 * e);
            if (slot[a] != kInvalidIndex) step.positions[slot[a]] += m.x[b], ++valence[slot[a]];
            if (slot[b] != kInvalidIndex) step.positions[slot[b]] += m.x[a], ++valence[slot[b]];
        }
        step.positions[i] = loop ? loop_odd_at(m, e) : butterfly_odd_at(m, e, modified, weights);
        step.stencils[i++] = int(odd_stencil_at(m, e, scheme));
    }
    i = 0;
    for (const Index v : vertices) {
        if ((i & kCheckMask) == 0) progress.check_cancelled();
        if (!sum_over_edges) {
            step.positions[i] = loop ? loop_even_at(m, v, ring, beta) : m.x[v];
            step.stencils[i++] = int(even_stencil_at(m, v, scheme));
            continue;
        }
        const Halfedge h0 = m.vh[v];
        if (!h0.is_valid()) {  // as loop_even_at() and even_stencil_at()
            step.positions[i] = m.x[v];
            step.stencils[i++] = int(SubdivisionStencil::EvenKept);
        } else if (m.boundary(h0.idx())) {
            step.positions[i] =
                0.75 * m.x[v] + 0.125 * (m.x[m.to_i(h0.idx())] + m.x[m.from_i(m.prev_i(h0.idx()))]);
            step.stencils[i++] = int(SubdivisionStencil::EvenBoundary);
        } else {
            const unsigned k = valence[i];
            if (k >= beta.size()) beta.resize(2 * std::size_t(k) + 1, -1.0);
            if (beta[k] < 0) {  // as loop_positions() computes it
                const double t = 0.375 + 0.25 * std::cos(2 * kPi / k);
                beta[k] = (0.625 - t * t) / k;
            }
            const double b = beta[k];
            step.positions[i] = (1.0 - k * b) * m.x[v] + b * step.positions[i];
            step.stencils[i++] = int(k == 6 ? SubdivisionStencil::EvenRegular
                                            : SubdivisionStencil::EvenExtraordinary);
        }
    }
    return step;
}

void check_subdivision_features(const HalfedgeMesh& mesh, const SubdivisionOptions& options) {
    if (options.features == SubdivisionFeatures::Auto &&
        !(std::isfinite(options.feature_angle) && options.feature_angle > 0 &&
          options.feature_angle <= 180))
        throw InvalidArgument("subdivide: the feature angle must be in (0, 180] degrees (got " +
                              number_text(options.feature_angle) + ")");
    if (const std::string bad = check_features(mesh); !bad.empty())
        throw InvalidArgument("subdivide: invalid features: " + bad);
}

std::string detect_subdivision_features(HalfedgeMesh& mesh, const SubdivisionOptions& options) {
    FeatureDetectionOptions d;
    d.angle_deg = options.feature_angle;
    const FeatureDetectionReport r = detect_features(mesh, d);
    return "features detected at " + number_text(options.feature_angle) +
           " deg: " + count_text(r.feature_edges, "sharp edge", "sharp edges") + ", " +
           count_text(r.corners, "corner", "corners");
}

UniformStep1to4 uniform_step_1to4(const HalfedgeMesh& mesh, SubdivisionScheme scheme,
                                  Progress& progress, bool features) {
    if (mesh.has_garbage() || scheme == SubdivisionScheme::Sqrt3)
        throw InvalidArgument(
            "uniform_step_1to4: expected a compact mesh and a 1-to-4 scheme (loop, butterfly, "
            "modified-butterfly)");
    const In m(mesh);
    const Stage stage{progress, 0.0, 0.5};
    UniformStep1to4 step;
    step.positions.resize(std::size_t(m.nv) + m.ne);
    const Creases creases = features ? creases_of(mesh) : Creases{};
    if (!find_coincident_vertices(mesh).empty())
        welded_positions_1to4(mesh, scheme, step.positions.data(), stage, creases);
    else
        positions_1to4(m, scheme, step.positions.data(), stage, creases);
    HalfedgeMesh scratch;  // provenance_1to4() writes vertex properties: a vertex-only mesh
    scratch.resize_elements(std::size_t(m.nv) + m.ne, 0, 0);
    provenance_1to4(m, scheme, scratch, creases);
    step.stencils = std::move(scratch.get_vertex_property<int>(kStencilName).vector());
    return step;
}

const char* subdivision_stencil_label(SubdivisionStencil stencil) {
    switch (stencil) {
        case SubdivisionStencil::Unknown:
            return "not made by this step";
        case SubdivisionStencil::EvenRegular:
            return "even, regular (valence 6)";
        case SubdivisionStencil::EvenExtraordinary:
            return "even, extraordinary (valence other than 6)";
        case SubdivisionStencil::EvenBoundary:
            return "even, boundary rule";
        case SubdivisionStencil::EvenCrease:
            return "even, crease of a seam (kept with its coincident copies)";
        case SubdivisionStencil::EvenKept:
            return "even, kept in place";
        case SubdivisionStencil::EvenRelaxed:
            return "even, relaxed with its ring (Sqrt3)";
        case SubdivisionStencil::OddRegular:
            return "odd, edge point, regular stencil";
        case SubdivisionStencil::OddExtraordinary:
            return "odd, edge point, extraordinary stencil";
        case SubdivisionStencil::OddBoundary:
            return "odd, edge point, boundary rule";
        case SubdivisionStencil::OddCrease:
            return "odd, crease of a seam (kept with its coincident copies)";
        case SubdivisionStencil::OddFace:
            return "odd, face centroid (Sqrt3)";
        case SubdivisionStencil::OddBoundarySplit:
            return "odd, boundary edge split in three (Sqrt3)";
        case SubdivisionStencil::OddClosureMidpoint:
            return "odd, edge midpoint (region closure outside the selection)";
        case SubdivisionStencil::EvenDart:
            return "even, dart (one sharp edge: the smooth rule)";
        case SubdivisionStencil::EvenSharpCrease:
            return "even, crease (two sharp edges: 3/4 v + 1/8 of each crease neighbour)";
        case SubdivisionStencil::EvenCorner:
            return "even, corner (three or more sharp edges meet: stays)";
        case SubdivisionStencil::EvenTaggedCorner:
            return "even, corner (tagged as a corner: stays)";
        case SubdivisionStencil::EvenSemiSharp:
            return "even, semi-sharp (its sharp edges turn smooth at this level: rules blended)";
        case SubdivisionStencil::OddSharp:
            return "odd, edge point on a sharp edge (midpoint)";
        case SubdivisionStencil::OddSemiSharp:
            return "odd, edge point on a semi-sharp edge (sharp and smooth rules blended)";
        case SubdivisionStencil::EvenCreaseCurve:
            return "even, crease (two sharp edges: kept in odd Sqrt3 steps, 4/27, 19/27, 4/27 "
                   "along them in even ones)";
        case SubdivisionStencil::OddCreaseSplit:
            return "odd, sharp edge split in three (Sqrt3)";
        case SubdivisionStencil::OddFourPoint:
            return "odd, edge point on a sharp edge (four-point rule along the crease)";
        case SubdivisionStencil::OddDamped:
            return "odd, edge point moved from its stencil toward the edge's midpoint (region "
                   "subdivision: no triangle flatter than half the input's smallest angle)";
    }
    return "unknown";
}

bool is_even_stencil(SubdivisionStencil stencil) {
    switch (stencil) {
        case SubdivisionStencil::EvenRegular:
        case SubdivisionStencil::EvenExtraordinary:
        case SubdivisionStencil::EvenBoundary:
        case SubdivisionStencil::EvenCrease:
        case SubdivisionStencil::EvenKept:
        case SubdivisionStencil::EvenRelaxed:
        case SubdivisionStencil::EvenDart:
        case SubdivisionStencil::EvenSharpCrease:
        case SubdivisionStencil::EvenCorner:
        case SubdivisionStencil::EvenTaggedCorner:
        case SubdivisionStencil::EvenSemiSharp:
        case SubdivisionStencil::EvenCreaseCurve:
            return true;
        default:
            return false;
    }
}

const char* scheme_name(SubdivisionScheme scheme) {
    return enum_id<SubdivisionScheme>(kSubdivisionSchemes, scheme);
}

SubdivisionScheme parse_scheme(const std::string& name) {
    return parse_enum<SubdivisionScheme>(kSubdivisionSchemes, name, "subdivision scheme");
}

namespace {

/// The lowest face of a pillow (both faces' three halfedges are twins of each other's), or
/// kInvalidIndex: in fixed blocks on every thread, the blocks' first finds combined by minimum.
Index first_pillow_face(const In& m) {
    return parallel_reduce(
        0, m.nf, kInvalidIndex,
        [&](std::size_t begin, std::size_t end) {
            for (Index fi = Index(begin); fi < Index(end); ++fi) {
                const Index h0 = m.fh[fi].idx(), h1 = m.next_i(h0), h2 = m.next_i(h1);
                const Face g = m.face[h0 ^ 1u];
                if (g.is_valid() && m.face[h1 ^ 1u] == g && m.face[h2 ^ 1u] == g) return fi;
            }
            return kInvalidIndex;
        },
        [](Index a, Index b) { return std::min(a, b); });
}

/// Refuses a mesh where two faces have the same three vertices (a closed two-triangle
/// "pillow"; subdivide() sets the input's aside, so this only guards the levels): the 1-to-4 split
/// would join two of its edge midpoints twice and Sqrt3 would join its two centroids three
/// times, i.e. the result would have double edges. No two edges join the same two vertices
/// (a mesh invariant), so two faces share their three vertices exactly when they share their
/// three edges: face f is half of a pillow when the twins of its three halfedges lie in one
/// face. Reports the pillow of the lowest face index.
void check_no_pillows(const HalfedgeMesh& mesh, int iteration) {
    const In m(mesh);
    const Index fi = first_pillow_face(m);
    if (fi != kInvalidIndex) {
        const Index h0 = m.fh[fi].idx(), h1 = m.next_i(h0), h2 = m.next_i(h1);
        const Face g = m.face[h0 ^ 1u];
        Index v[3] = {m.to_i(h0), m.to_i(h1), m.to_i(h2)};
        std::sort(v, v + 3);
        throw TopologyError(
            "subdivide: faces " + std::to_string(fi) + " and " + std::to_string(g.idx()) +
            " have the same three vertices (" + std::to_string(v[0]) + ", " + std::to_string(v[1]) +
            ", " + std::to_string(v[2]) +
            "), a closed two-triangle component; subdividing it would create double edges" +
            (iteration > 1 ? " (iteration " + std::to_string(iteration) + ")" : ""));
    }
}

/// Refuses a level whose positions or carried attributes overflowed (coordinates near the
/// largest double: the schemes' affine combinations of finite points can reach infinity).
void check_finite_level(const HalfedgeMesh& m, SubdivisionScheme scheme, int iteration) {
    auto refuse = [&](const std::string& what, Index i) {
        throw InvalidArgument(std::string("subdivide: ") + scheme_name(scheme) + " iteration " +
                              std::to_string(iteration) + " produced a non-finite " + what +
                              " at vertex " + std::to_string(i) +
                              " (the input's values are too large for the scheme's weights; "
                              "scale the mesh down)");
    };
    // The first vertex with a non-finite position, found in fixed blocks on every thread.
    const Point* x = m.positions().data();
    const Index bad = parallel_reduce(
        0, m.vertices_size(), kInvalidIndex,
        [&](std::size_t begin, std::size_t end) {
            for (std::size_t v = begin; v < end; ++v)
                if (!x[v].allFinite() && !m.is_deleted(Vertex(Index(v)))) return Index(v);
            return kInvalidIndex;
        },
        [](Index a, Index b) { return std::min(a, b); });
    if (bad != kInvalidIndex) refuse("position", bad);
    if (const auto p = m.get_vertex_property<TexCoord>("v:texcoord"))
        for (Vertex v : m.vertices())
            if (!p[v].allFinite()) refuse("texture coordinate", v.idx());
    if (const auto p = m.get_halfedge_property<TexCoord>("h:texcoord"))
        for (Halfedge h : m.halfedges())
            if (!p[h].allFinite()) refuse("corner texture coordinate", m.to_vertex(h).idx());
}

/// Makes the vertices of a new level that start at the same place (their coarse parents
/// coincide: the two sides of a seam, the copies of a split vertex) end at the same place:
/// where the level's rule gave them different positions (copies that the weld could not
/// join, a non-manifold point or edge; Sqrt3, whose flips would dissolve a seam, treats one
/// as a boundary curve on both sides) they get their mean, bit for bit the same.
/// Their stencils are marked as creases (mark_creases()).
void keep_coincident_together(SubdivisionLevel& level) {
    const std::vector<Point>& start = level.correspondence.positions;
    HalfedgeMesh& m = level.mesh;
    std::vector<std::uint8_t> skip(m.vertices_size(), 0);
    for (Vertex v : m.vertices()) skip[v.idx()] = m.is_isolated(v) ? 1 : 0;
    const CoincidentGroups groups = find_coincident_points(start.data(), start.size(), skip.data());
    unify_groups(groups, m.positions().data());
    mark_creases(groups, m);
}

/// Appends the pillows set aside to a level (subdivision level 0, starting where they are).
void put_back(const HalfedgeMesh& pillows, SubdivisionLevel& level) {
    const Index first = append_mesh(level.mesh, pillows);
    if (auto levels = level.mesh.get_vertex_property<int>(kLevelName))
        for (std::size_t v = first; v < level.mesh.vertices_size(); ++v)
            levels[Vertex(Index(v))] = 0;
    // Not made by the step: no stencil, no parents.
    if (auto stencil = level.mesh.get_vertex_property<int>(kStencilName))
        for (std::size_t v = first; v < level.mesh.vertices_size(); ++v)
            stencil[Vertex(Index(v))] = int(SubdivisionStencil::Unknown);
    if (auto parents = level.mesh.get_vertex_property<SubdivisionParents>(kParentsName))
        for (std::size_t v = first; v < level.mesh.vertices_size(); ++v)
            parents[Vertex(Index(v))] = SubdivisionParents::Constant(kInvalidIndex);
    auto& start = level.correspondence.positions;
    if (!start.empty())
        for (Vertex v : pillows.vertices()) start.push_back(pillows.position(v));
}

}  // namespace

SubdivisionResult subdivide(const HalfedgeMesh& mesh, const SubdivisionOptions& options,
                            Progress& progress) {
    const auto t0 = std::chrono::steady_clock::now();
    if (options.iterations < 1 || options.iterations > 10)
        throw InvalidArgument("subdivide: iterations must be between 1 and 10 (got " +
                              std::to_string(options.iterations) + ")");
    const bool sqrt3 = options.scheme == SubdivisionScheme::Sqrt3;
    double faces = double(mesh.n_faces());
    for (int i = 0; i < options.iterations; ++i) faces *= sqrt3 ? 3.0 : 4.0;
    if (faces > double(kMaxFaces))
        throw InvalidArgument("subdivide: " + std::to_string(options.iterations) +
                              " iterations would give about " +
                              std::to_string(static_cast<long long>(faces)) +
                              " faces (at most 50 million): use fewer iterations");
    const bool auto_features = options.features == SubdivisionFeatures::Auto;
    check_subdivision_features(mesh, options);
    progress.check_cancelled();
    HalfedgeMesh collected;
    const HalfedgeMesh* current = &mesh;
    if (mesh.has_garbage() || auto_features) {
        collected = mesh;
        if (mesh.has_garbage()) collected.garbage_collection();
        current = &collected;
    }
    const std::string detected =
        auto_features ? detect_subdivision_features(collected, options) : std::string();
    SubdivisionResult result;
    // Pillows cannot be refined: they are set aside and put back unchanged on every level.
    PillowSplit pillows;
    // The parallel scan finds the pillows pillow_faces() lists (the same test); without any,
    // the first iteration's check_no_pillows() is that scan again and is skipped.
    const bool had_pillows = first_pillow_face(In(*current)) != kInvalidIndex;
    if (had_pillows) {
        pillows = split_off_pillows(*current);
        current = &pillows.rest;
        result.notes.push_back(pillow_note(pillows.count));
    }
    // Features (core/features.h): the crease rules of every scheme (Loop here, Sqrt3 and the
    // butterflies in subdivision_creases.cpp).
    if (!detected.empty()) result.notes.push_back(detected);
    const bool features = options.features != SubdivisionFeatures::None && has_features(*current);
    // Coincident vertices (seams, copies of a split vertex) are kept together on every level.
    const bool coincident = !find_coincident_vertices(*current).empty();
    result.levels.reserve(options.keep_levels ? std::size_t(options.iterations) : 1);
    SubdivisionLevel latest;  // the last level built, when only the finest is kept
    const double span = 1.0 / options.iterations;
    for (int it = 1; it <= options.iterations; ++it) {
        progress.check_cancelled();
        if (it > 1 || had_pillows) check_no_pillows(*current, it);
        Stage stage{progress, (it - 1) * span, span};
        stage.report(0);
        // Morph start positions for the levels returned, and to find the coincident ones.
        const bool morph = options.morph && (options.keep_levels || it == options.iterations);
        SubdivisionLevel level =
            sqrt3 ? refine_sqrt3(*current, it % 2 == 0, it, morph || coincident, stage, features)
                  : refine_1to4(*current, options.scheme, it, morph || coincident, coincident,
                                features, stage);
        if (coincident) {
            keep_coincident_together(level);
            if (!morph) std::vector<Point>().swap(level.correspondence.positions);
        }
        if (options.keep_levels) {
            result.levels.push_back(std::move(level));  // reserved: `current` stays valid
            current = &result.levels.back().mesh;
        } else {
            latest = std::move(level);  // releases the level before
            current = &latest.mesh;
        }
        check_finite_level(*current, options.scheme, it);
        result.level_counts.push_back(
            {current->n_vertices() + 3 * pillows.count, current->n_faces() + 2 * pillows.count});
        if (it == 1) {  // the input's copies are no longer read
            collected.clear();
            pillows.rest.clear();
        }
    }
    if (!options.keep_levels) result.levels.push_back(std::move(latest));
    if (pillows.count > 0)
        for (SubdivisionLevel& level : result.levels) put_back(pillows.pillows, level);
    progress.check_cancelled();
    progress.report(1.0, "subdividing");
    result.ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    return result;
}

}  // namespace trilab
