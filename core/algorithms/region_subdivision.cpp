// Subdivision of a region (core/algorithms/region_subdivision.h).
//
// Implementation: each iteration builds the next level straight into a copy of the coarse
// level's arrays, allocated once at their final size (bare_copy). 1-to-4 schemes: the stencils
// are computed only at the region's vertices and edges (uniform_step_1to4_listed(), bit for bit
// the whole-mesh values), the red-green closure grows until no closure triangle is flatter than
// the input's flattest face (close_red_green), build_red_green writes the red faces' 1-to-4
// pattern and the green faces' bisections into the connectivity arrays, and improve_closure
// flips closure edges that raise the smaller angle of their pair. Sqrt3: the selected faces
// are split at their centroids, the old edges between two split faces flipped, with Kobbelt's
// adaptive rule at the region's edge. Old vertices keep their indices; the new ones follow in
// the order of their edge (face) index. Positions are blended by the weights.
#include "core/algorithms/region_subdivision.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>

#include "core/algorithms/coincident.h"
#include "core/algorithms/pillows.h"
#include "core/errors.h"
#include "core/features.h"
#include "core/geometry.h"

#if defined(__linux__)
#include <sys/mman.h>
#include <unistd.h>
#endif

namespace trilab {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr std::size_t kMaxFaces = 50'000'000;  // as subdivide()
// A bisection of a face with a vertex that moves (weight > 0) must keep this many degrees
// above the target: the scheme moves that vertex again at every later level, while the face's
// outside vertices stay, so its descendants' angles drift (on the generated sphere's cap by
// 0.6 degrees over four levels); a face that misses it is split 1-to-4 instead.
constexpr double kMovingGreenMargin = 3.0;

// A closure edge is flipped only between faces this close to coplanar (before and after), so
// that the flips move the surface by at most about sin(7.5 deg) / 4 of an edge's length.
constexpr double kMaxClosureFlipDihedral = 15.0;

const char* const kLevelName = "v:subdivision_level";
const char* const kStencilName = "v:subdivision_stencil";
const char* const kParentsName = "v:subdivision_parents";

/// Has the kernel map the pages of `v`'s reserved storage in one call (MADV_POPULATE_WRITE,
/// Linux 5.14 and later) before they are first written: on the region's copy of the mesh
/// (fresh pages, written once) that costs about a fifth less than a page fault per page.
/// Only a hint: where the kernel lacks it nothing changes.
template <typename T>
void prefault_capacity(const std::vector<T>& v) {
#if defined(__linux__) && defined(MADV_POPULATE_WRITE)
    static const std::uintptr_t page = std::uintptr_t(::sysconf(_SC_PAGESIZE));
    const std::uintptr_t begin = reinterpret_cast<std::uintptr_t>(v.data());
    const std::uintptr_t from = (begin + page - 1) & ~(page - 1);
    const std::uintptr_t to = (begin + v.capacity() * sizeof(T)) & ~(page - 1);
    if (to > from) ::madvise(reinterpret_cast<void*>(from), to - from, MADV_POPULATE_WRITE);
#else
    (void)v;
#endif
}

/// `in` copied into an array of n elements (n >= in.size()), allocated once; the elements
/// past in's are value-initialized (an invalid handle). The handles' tail is written by
/// resize(n), whose default-construction loop the compiler vectorizes: resize(n, Handle())
/// stores one element at a time, and on fresh pages (every page of the new level is one)
/// that took three times as long (the region's copy of the untouched part, measured).
template <typename H>
std::vector<H> grown_handles(const std::vector<H>& in, std::size_t n) {
    std::vector<H> out;
    out.reserve(n);
    prefault_capacity(out);
    out.insert(out.end(), in.begin(), in.end());
    out.resize(n);
    return out;
}

/// A copy of `m`'s connectivity and positions only (`m` compact), with room for `nv` vertices,
/// `ne` edges and `nf` faces (at least m's: the elements past m's are invalid, their position
/// zero), so that the refinement writes into arrays allocated once.
HalfedgeMesh bare_copy(const HalfedgeMesh& m, std::size_t nv, std::size_t ne, std::size_t nf) {
    std::vector<Point> positions;
    positions.reserve(nv);
    prefault_capacity(positions);
    positions.insert(positions.end(), m.positions().begin(), m.positions().end());
    positions.resize(nv, Point::Zero());
    HalfedgeMesh out;
    out.assign_connectivity(std::move(positions), grown_handles(m.vertex_halfedge_array(), nv),
                            grown_handles(m.halfedge_to_array(), 2 * ne),
                            grown_handles(m.halfedge_next_array(), 2 * ne),
                            grown_handles(m.halfedge_prev_array(), 2 * ne),
                            grown_handles(m.halfedge_face_array(), 2 * ne),
                            grown_handles(m.face_halfedge_array(), nf));
    return out;
}

/// One refined level with its carried selection.
/// A Sqrt3 closure triangle (a, b, centroid of the split face) left unflipped beside an unsplit
/// face: its halfedge a -> b and its apex (the centroid).
struct OddTriangle {
    Index halfedge;
    Index apex;
};

struct RegionStep {
    SubdivisionLevel level;
    Selection selection;
    RegionClosureCounts counts;
    std::vector<double> flatness;  ///< face_flatness() of every face (unless it is the last level)
    /// Per face of the new level: 1 for the closure's faces and their descendants (green halves,
    /// the children of refined faces outside the selection), which a later level never bisects
    /// again but splits 1-to-4 (red) when one of their edges is split: red-green refinement's
    /// removal of the previous closure, so that repeated levels do not keep halving angles.
    std::vector<std::uint8_t> closure_faces;
    /// Sqrt3: the closure's triangles left unflipped (Kobbelt's odd generation): a later level
    /// completes them (complete_sqrt3()).
    std::vector<OddTriangle> odd_triangles;
    Index flattest = kInvalidIndex;  ///< the level's flattest face (the first of equal ones)
};

/// The cosine of the smallest corner angle of triangle p0 p1 p2 (the corner opposite the
/// shortest edge; 1 for a degenerate triangle): larger is flatter. No sort, no trigonometry.
__attribute__((always_inline)) inline double triangle_flatness(const Point& p0, const Point& p1,
                                                               const Point& p2) {
    const double l0 = (p1 - p2).squaredNorm(), l1 = (p2 - p0).squaredNorm(),
                 l2 = (p0 - p1).squaredNorm();
    double s, a, b;  // the shortest edge, the two others (squared)
    if (l0 <= l1 && l0 <= l2) {
        s = l0, a = l1, b = l2;
    } else if (l1 <= l2) {
        s = l1, a = l0, b = l2;
    } else {
        s = l2, a = l0, b = l1;
    }
    const double denominator = 2.0 * std::sqrt(a * b);
    return denominator > 0 ? (a + b - s) / denominator : 1.0;
}

/// The three corners of each face, read from the connectivity arrays directly (the loops over
/// every face of a level go through here).
struct FaceCorners {
    const Vertex* to;
    const Halfedge* next;
    const Halfedge* fh;
    explicit FaceCorners(const HalfedgeMesh& m)
        : to(m.halfedge_to_array().data()),
          next(m.halfedge_next_array().data()),
          fh(m.face_halfedge_array().data()) {}
    std::array<Index, 3> operator()(std::size_t f) const {
        const Halfedge h0 = fh[f], h1 = next[h0.idx()], h2 = next[h1.idx()];
        return {to[h0.idx()].idx(), to[h1.idx()].idx(), to[h2.idx()].idx()};
    }
};

/// face_flatness of every face of `m` (compact), and its flattest face (the first of equal
/// ones; invalid without faces) in the same pass.
std::vector<double> flatness_of(const HalfedgeMesh& m, Index& flattest) {
    const FaceCorners corners(m);
    const Point* x = m.positions().data();
    std::vector<double> flat(m.faces_size());
    flattest = kInvalidIndex;
    double largest = 0;
    for (std::size_t f = 0; f < flat.size(); ++f) {
        const auto v = corners(f);
        flat[f] = triangle_flatness(x[v[0]], x[v[1]], x[v[2]]);
        if (flattest == kInvalidIndex || flat[f] > largest) largest = flat[f], flattest = Index(f);
    }
    return flat;
}

/// The new level's flatness into step.flatness (only when `keep`: a later level reads it) and
/// its flattest face into step.flattest: a face of `out` that is a coarse face left as it was
/// (`changed(f)` false) keeps the coarse value, every other one is computed.
template <typename Changed>
void level_flatness(const HalfedgeMesh& out, const std::vector<double>& coarse,
                    const Changed& changed, bool keep, RegionStep& step) {
    const FaceCorners corners(out);
    const Point* x = out.positions().data();
    const std::size_t nf = out.faces_size();
    if (keep) step.flatness.resize(nf);
    double flattest = 0;
    for (std::size_t f = 0; f < nf; ++f) {
        double flat;
        if (f < coarse.size() && !changed(Index(f))) {
            flat = coarse[f];
        } else {
            const auto v = corners(f);
            flat = triangle_flatness(x[v[0]], x[v[1]], x[v[2]]);
        }
        if (keep) step.flatness[f] = flat;
        if (step.flattest == kInvalidIndex || flat > flattest) {
            flattest = flat;
            step.flattest = Index(f);
        }
    }
}

/// Per-vertex bookkeeping of a new level `out` (built, its vertices counted), written in vertex
/// order by the refinement: the provenance straight into out's properties (added here, in
/// the order finish() expects), the selection and the morph start positions (only when
/// `morph`) into vectors that finish() hands on.
struct NewVertices {
    int* stencil;
    SubdivisionParents* parents;
    bool morph;
    std::vector<Point> start;  // morph start positions
    Selection selection;
    std::size_t n = 0;
    NewVertices(HalfedgeMesh& out, bool with_morph) : morph(with_morph) {
        out.add_vertex_property<int>(kLevelName, 0);  // filled by finish()
        stencil = out.add_vertex_property<int>(kStencilName, 0).vector().data();
        parents = out.add_vertex_property<SubdivisionParents>(
                         kParentsName, SubdivisionParents::Constant(kInvalidIndex))
                      .vector()
                      .data();
        const std::size_t count = out.vertices_size();
        if (morph) start.reserve(count);
        selection.reserve(count);
    }
    void add(SubdivisionStencil st, const Point& from, float weight, Index a,
             Index b = kInvalidIndex, Index c = kInvalidIndex) {
        stencil[n] = int(st);
        parents[n] = SubdivisionParents(a, b, c);
        ++n;
        if (morph) start.push_back(from);
        selection.push_back(weight);
    }
};

/// Writes levels, provenance, selection, vertex uvs (interpolated from the parents) and the
/// morph start positions onto the new level; step.selection gets the weights when `more_levels`.
void finish(const HalfedgeMesh& coarse, int level, bool morph, bool more_levels, NewVertices&& nv,
            RegionStep& step) {
    HalfedgeMesh& m = step.level.mesh;
    const std::size_t n_old = coarse.vertices_size(), n = m.vertices_size();
    auto& levels = m.get_vertex_property<int>(kLevelName).vector();  // added by NewVertices
    const auto in_levels = coarse.get_vertex_property<int>(kLevelName);
    for (std::size_t v = 0; v < n_old; ++v)
        levels[v] = level > 1 && in_levels ? in_levels.vector()[v] : 0;
    std::fill(levels.begin() + std::ptrdiff_t(n_old), levels.end(), level);
    if (const auto uv_in = coarse.get_vertex_property<TexCoord>("v:texcoord")) {
        auto& uv = m.add_vertex_property<TexCoord>("v:texcoord", TexCoord::Zero()).vector();
        const auto& parents = m.get_vertex_property<SubdivisionParents>(kParentsName).vector();
        for (std::size_t v = 0; v < n; ++v) {
            TexCoord sum = TexCoord::Zero();
            int k = 0;
            for (; k < 3 && parents[v][k] != kInvalidIndex; ++k)
                sum += uv_in.vector()[parents[v][k]];
            uv[v] = k == 1 ? uv_in.vector()[parents[v][0]] : sum / double(k);
        }
    }
    if (more_levels) step.selection = nv.selection;  // the next level's weights
    m.add_vertex_property<float>(kSelectionProperty, 0.0f).vector().swap(nv.selection);
    step.level.correspondence.kind = MorphCorrespondence::Kind::FromEarlier;
    if (morph) step.level.correspondence.positions = std::move(nv.start);
}

/// Refuses to refine a face of a closed two-triangle pillow (the split would create a double
/// edge): `refined(f)` says whether face f is refined.
template <typename Refined>
void check_no_refined_pillow(const HalfedgeMesh& m, const Refined& refined) {
    for (Face f : pillow_faces(m))
        if (refined(f))
            throw TopologyError("subdivide --region: face " + std::to_string(f.idx()) +
                                " is half of a closed two-triangle pillow (two faces with the "
                                "same three vertices) and lies in the region; refining it would "
                                "create double edges (leave it out of the region)");
}

void check_face_limit(std::size_t faces) {
    if (faces > kMaxFaces)
        throw InvalidArgument("subdivide --region: the refinement would give " +
                              std::to_string(faces) +
                              " faces (at most 50 million): use fewer iterations");
}

/// The smallest corner angle of triangle p0 p1 p2 in degrees (atan2 of each corner: exact near
/// 0 and 180).
double corner_min_angle(const Point& p0, const Point& p1, const Point& p2) {
    const Point* p[3] = {&p0, &p1, &p2};
    double smallest = 180.0;
    for (int k = 0; k < 3; ++k) {
        const Vector3 a = *p[(k + 1) % 3] - *p[k], b = *p[(k + 2) % 3] - *p[k];
        smallest = std::min(smallest, std::atan2(a.cross(b).norm(), a.dot(b)) * 180.0 / kPi);
    }
    return smallest;
}

double face_min_angle(const HalfedgeMesh& m, Face f) {
    const auto v = m.face_vertices(f);
    return corner_min_angle(m.position(v[0]), m.position(v[1]), m.position(v[2]));
}

/// The angle between two vectors in degrees (180 when one is zero: never "close").
double angle_between(const Vector3& a, const Vector3& b) {
    const double n = a.norm() * b.norm();
    return n > 0 ? std::atan2(a.cross(b).norm(), a.dot(b)) * 180.0 / kPi : 180.0;
}

// The angle tests below decide as the atan2 expressions above do, without trigonometry where
// the answer is clear by a wide margin (the cosine of an angle, or the sign of the sine of
// its difference to the limit, farther than this from the limit: the rounding of either side
// is a few 1e-16), and with the atan2 expression itself otherwise, so every decision is the
// same bit for bit.
constexpr double kClearMargin = 1e-7;

/// angle_between(a, b) > kMaxClosureFlipDihedral: the sign of |a||b| sin(angle - limit) =
/// |a x b| cos(limit) - (a . b) sin(limit), which is that of angle - limit for angles in
/// [0, 180].
bool bends_more_than_flip_limit(const Vector3& a, const Vector3& b) {
    static const double cos_limit = std::cos(kMaxClosureFlipDihedral * kPi / 180.0);
    static const double sin_limit = std::sin(kMaxClosureFlipDihedral * kPi / 180.0);
    if (a.norm() * b.norm() > 0) {
        const double y = a.cross(b).norm(), x = a.dot(b);
        const double r = y * cos_limit - x * sin_limit, margin = kClearMargin * (y + std::abs(x));
        if (r > margin) return true;
        if (r < -margin) return false;
    }
    return angle_between(a, b) > kMaxClosureFlipDihedral;
}

/// corner_min_angle(p0, p1, p2) >= angle (degrees; `cos_angle` its cosine): the triangle's
/// flatness is the cosine of its smallest angle, which falls as the angle rises.
bool min_angle_at_least(const Point& p0, const Point& p1, const Point& p2, double angle,
                        double cos_angle) {
    const double flat = triangle_flatness(p0, p1, p2);
    if (flat < cos_angle - kClearMargin) return true;
    if (flat > cos_angle + kClearMargin) return false;
    return corner_min_angle(p0, p1, p2) >= angle;
}

/// Whether flipping interior edge e raises the smaller of its two faces' minimum angles, keeps
/// the surface where it was (the two faces and the two flipped ones each within
/// kMaxClosureFlipDihedral degrees of each other) and keeps a valid mesh. The validity test
/// comes last (it searches the ring for the flipped edge), the angles first.
bool flip_improves(const HalfedgeMesh& m, Edge e) {
    const Halfedge h = HalfedgeMesh::halfedge(e, 0), t = HalfedgeMesh::twin(h);
    const Point& u = m.position(m.to_vertex(t));
    const Point& v = m.position(m.to_vertex(h));
    const Point& c = m.position(m.to_vertex(m.next(h)));
    const Point& d = m.position(m.to_vertex(m.next(t)));
    const Vector3 n1 = (v - u).cross(c - u), n2 = (u - v).cross(d - v);
    const Vector3 n3 = (d - u).cross(c - u), n4 = (c - v).cross(d - v);
    if (bends_more_than_flip_limit(n1, n2) || bends_more_than_flip_limit(n3, n4) ||
        bends_more_than_flip_limit(n1 + n2, n3) || bends_more_than_flip_limit(n1 + n2, n4))
        return false;
    // after > before + 1e-9 degrees. The flatness (cosine) of the smaller angle on each side:
    // a difference beyond kClearMargin is a difference of at least that many radians.
    const double flat_before = std::max(triangle_flatness(u, v, c), triangle_flatness(v, u, d));
    const double flat_after = std::max(triangle_flatness(u, d, c), triangle_flatness(v, c, d));
    bool raises;
    if (flat_after < flat_before - kClearMargin) {
        raises = true;
    } else if (flat_after > flat_before + kClearMargin) {
        raises = false;
    } else {
        const double before = std::min(corner_min_angle(u, v, c), corner_min_angle(v, u, d));
        const double after = std::min(corner_min_angle(u, d, c), corner_min_angle(v, c, d));
        raises = after > before + 1e-9;
    }
    return raises && m.is_flip_ok(e);
}

/// Lawson's max-min-angle flips restricted to the closure: an edge is flipped when it is not a
/// feature (sharpness 0) and both of its faces are closure faces (`closure`, per face index; a flip
/// keeps both faces' indices, so the flags stay right) and flip_improves(). Each flip raises the
/// smaller minimum angle of the pair, so the closure's minimum angle never goes down, and the
/// sorted list of angles rises with each flip, so it ends. Returns the number of flips.
std::size_t improve_closure(HalfedgeMesh& m, const std::vector<std::uint8_t>& closure) {
    const auto sharpness = m.get_edge_property<float>(kSharpnessProperty);
    const float* sharp = sharpness ? sharpness.vector().data() : nullptr;
    const auto candidate = [&](Edge e) {
        if (sharp && sharp[e.idx()] > 0.0f) return false;  // a feature edge is never flipped
        const Face f0 = m.face(HalfedgeMesh::halfedge(e, 0));
        const Face f1 = m.face(HalfedgeMesh::halfedge(e, 1));
        return f0.is_valid() && f1.is_valid() && closure[f0.idx()] && closure[f1.idx()];
    };
    // The candidates in ascending edge order (as a scan over every edge would list them), found
    // from the closure's faces.
    std::vector<Edge> queue;
    for (std::size_t f = 0; f < closure.size(); ++f)
        if (closure[f])
            for (Halfedge h : m.halfedges_of(Face(Index(f)))) {
                const Edge e = HalfedgeMesh::edge(h);
                if (candidate(e)) queue.push_back(e);
            }
    std::sort(queue.begin(), queue.end(), [](Edge a, Edge b) { return a.idx() < b.idx(); });
    queue.erase(std::unique(queue.begin(), queue.end()), queue.end());
    std::size_t flips = 0;
    const std::size_t cap = 10 * queue.size() + 10;
    while (!queue.empty() && flips < cap) {
        const Edge e = queue.back();
        queue.pop_back();
        if (!candidate(e) || !flip_improves(m, e)) continue;
        m.flip(e);
        ++flips;
        const Halfedge h = HalfedgeMesh::halfedge(e, 0), t = HalfedgeMesh::twin(h);
        for (Halfedge g : {m.next(h), m.prev(h), m.next(t), m.prev(t)}) {
            const Edge ge = HalfedgeMesh::edge(g);
            if (candidate(ge)) queue.push_back(ge);
        }
    }
    return flips;
}

/// The smallest minimum angle over the flagged faces (180 when none is): the minimum of
/// face_min_angle() over the faces whose flatness is within kClearMargin of the largest (no
/// other face can hold it).
double min_angle_of(const HalfedgeMesh& m, const std::vector<std::uint8_t>& flagged) {
    const FaceCorners corners(m);
    const Point* x = m.positions().data();
    std::vector<std::pair<Index, double>> flat;
    double flattest = -1.0;
    for (std::size_t f = 0; f < flagged.size(); ++f) {
        if (!flagged[f]) continue;
        const auto v = corners(f);
        flat.emplace_back(Index(f), triangle_flatness(x[v[0]], x[v[1]], x[v[2]]));
        flattest = std::max(flattest, flat.back().second);
    }
    double smallest = 180.0;
    for (const auto& [f, flatness] : flat)
        if (!(flatness < flattest - kClearMargin))
            smallest = std::min(smallest, face_min_angle(m, Face(f)));
    return smallest;
}

/// The uniform step's positions and stencils where region subdivision uses them: old vertices
/// that move (weight > 0) and the edges with such an end, packed (uniform_step_1to4_listed():
/// a small region allocates little), or the whole mesh's pass, across seams, where the mesh
/// has coincident vertices, and by the crease rules where it has features in use.
struct RegionStencils {
    bool dense = false;  ///< the whole mesh's step: entry v, then nv + e
    Index nv = 0;
    std::vector<Index> vertices;  ///< listed (ascending): the moving vertices
    std::vector<Index> edges;     ///< listed (ascending): the edges with a moving end
    UniformStep1to4 step;
    /// The entry of a moving vertex, or of an edge with a moving end (binary search: for the
    /// closure's few look-ups; the passes in order count the entries instead).
    Index vertex_slot(Index v) const {
        return dense ? v
                     : Index(std::lower_bound(vertices.begin(), vertices.end(), v) -
                             vertices.begin());
    }
    Index edge_slot(Index e) const {
        return dense ? nv + e
                     : Index(vertices.size()) +
                           Index(std::lower_bound(edges.begin(), edges.end(), e) - edges.begin());
    }
};

RegionStencils region_stencils(const HalfedgeMesh& m, const Selection& w, SubdivisionScheme scheme,
                               bool features, Progress& progress) {
    const Index nv = Index(m.vertices_size()), ne = Index(m.edges_size());
    RegionStencils r;
    r.nv = nv;
    if (features || !find_coincident_vertices(m).empty()) {
        r.dense = true;
        r.step = uniform_step_1to4(m, scheme, progress, features);
        return r;
    }
    for (Index v = 0; v < nv; ++v)
        if (w[v] > 0.0f) r.vertices.push_back(v);
    const Vertex* to = m.halfedge_to_array().data();
    for (Index e = 0; e < ne; ++e)
        if (w[to[2 * e].idx()] > 0.0f || w[to[2 * e + 1].idx()] > 0.0f) r.edges.push_back(e);
    r.step = uniform_step_1to4_listed(m, scheme, r.vertices, r.edges, progress, true);
    return r;
}

/// The red-green closure of the split edges `split` (those of the selected faces on entry):
/// a face with two split edges gets its third (red), and (unless local_closure) a face outside
/// the selection with one split edge whose bisection would be flatter than target_angle gets
/// its other two (red), until nothing changes. `near`: the faces with a vertex of weight > 0.
/// Returns the number of faces grown into.
std::size_t close_red_green(const HalfedgeMesh& m, const Selection& w,
                            const std::vector<std::uint8_t>& selected,
                            const std::vector<std::uint8_t>& near, const RegionStencils& uniform,
                            bool local_closure, double target_angle,
                            const std::vector<std::uint8_t>& earlier_closure,
                            const std::vector<std::uint8_t>& region_edge,
                            std::vector<std::uint8_t>& split, std::size_t& closure_reds) {
    const auto was_closure = [&](Face f) {
        return !earlier_closure.empty() && earlier_closure[f.idx()] != 0;
    };
    const Index nf = Index(m.faces_size());
    const Point* x = m.positions().data();
    const Halfedge* next_of = m.halfedge_next_array().data();
    const Halfedge* face_halfedge = m.face_halfedge_array().data();
    const auto n_split = [&](Face f) {
        const Index h0 = face_halfedge[f.idx()].idx(), h1 = next_of[h0].idx(),
                    h2 = next_of[h1].idx();
        return int(split[h0 >> 1]) + int(split[h1 >> 1]) + int(split[h2 >> 1]);
    };
    // Where each vertex of the new level will be (the same expressions as below).
    const auto old_position = [&](Index v) {
        return w[v] > 0.0f
                   ? blend_by_weight(x[v], uniform.step.positions[uniform.vertex_slot(v)], w[v])
                   : x[v];
    };
    const auto edge_position = [&](Index e) {
        const Index a = m.vertex(Edge(e), 1).idx(), b = m.vertex(Edge(e), 0).idx();
        if (!region_edge[e]) return Point(0.5 * (old_position(a) + old_position(b)));
        const Point mid = 0.5 * (x[a] + x[b]);
        const float wmax = std::max(w[a], w[b]);
        return wmax > 0.0f
                   ? blend_by_weight(mid, uniform.step.positions[uniform.edge_slot(e)], wmax)
                   : mid;
    };
    // Whether the bisection of face f (one split edge) keeps every angle >= the target: the
    // input's smallest angle growing the closure (global), half of it keeping it local (a
    // bisection that would cut deeper is split 1-to-4 instead: no closure triangle is ever
    // flatter than half the input's smallest angle, at any number of levels).
    const double green_target = local_closure ? 0.5 * target_angle : target_angle;
    const double cos_target = std::cos(green_target * kPi / 180.0);
    const double moving_target = std::min(green_target + kMovingGreenMargin, 60.0);
    const double cos_moving = std::cos(moving_target * kPi / 180.0);
    const auto green_ok = [&](Face f) {
        const bool moves = near[f.idx()] != 0;
        const double t = moves ? moving_target : green_target;
        const double ct = moves ? cos_moving : cos_target;
        for (Halfedge h : m.halfedges_of(f)) {
            const Index e = HalfedgeMesh::edge(h).idx();
            if (!split[e]) continue;
            const Point a = old_position(m.from_vertex(h).idx());
            const Point b = old_position(m.to_vertex(h).idx());
            const Point c = old_position(m.to_vertex(m.next(h)).idx());
            const Point mid = edge_position(e);
            return min_angle_at_least(a, mid, c, t, ct) && min_angle_at_least(mid, b, c, t, ct);
        }
        return true;
    };
    // On entry only the selected faces' edges are split: a face with a split edge has two
    // vertices that move, so it is `near`.
    std::vector<Face> queue;
    for (Index f = 0; f < nf; ++f) {
        if (!near[f] && !was_closure(Face(f))) continue;
        const int c = n_split(Face(f));
        if (c == 2 || c == 1) queue.push_back(Face(f));
    }
    std::size_t grown = 0;
    closure_reds = 0;
    while (!queue.empty()) {
        const Face f = queue.back();
        queue.pop_back();
        const int c = n_split(f);
        if (c == 1) {
            if (was_closure(f)) {
                ++closure_reds;  // an earlier closure face is never bisected again: red
            } else {
                if (selected[f.idx()] || green_ok(f)) continue;
                ++grown;
            }
        } else if (c != 2) {
            continue;
        }
        for (Halfedge h : m.halfedges_of(f)) {
            const Index e = HalfedgeMesh::edge(h).idx();
            if (split[e]) continue;
            split[e] = 1;
            const Face g = m.face(HalfedgeMesh::twin(h));
            if (g.is_valid()) queue.push_back(g);
        }
    }
    return grown;
}

/// Writes the red-green refinement of `m` (split edges `split`, split counts per face `splits`:
/// 0, 1 or 3) into `out`: a bare copy of m grown to the new sizes, connectivity only (the new
/// vertices' positions are left to the caller: the vertex of split edge number k, in edge
/// order, is nv + k). Returns the flags of the closure's faces in `out`: the faces of refined
/// coarse faces that `touched` flags (per coarse face).
std::vector<std::uint8_t> build_red_green(const HalfedgeMesh& m,
                                          const std::vector<std::uint8_t>& split,
                                          const std::vector<std::uint8_t>& splits,
                                          const std::vector<std::uint8_t>& touched,
                                          HalfedgeMesh& out) {
    const Index nv = Index(m.vertices_size()), ne = Index(m.edges_size()),
                nf = Index(m.faces_size());
    // The new elements, numbered in order: the vertex of split edge number k (ascending edge
    // index) is nv + k and its second half edge ne + k; then, face by face, a red face's three
    // inner edges and three corner faces, a green face's cut and second half.
    std::vector<Index> split_number(ne, kInvalidIndex);
    Index n_split_edges = 0;
    for (Index e = 0; e < ne; ++e)
        if (split[e]) split_number[e] = n_split_edges++;
    Index n_new = 0;  // inner edges and corner faces of red faces, cuts and halves of green ones
    for (Index f = 0; f < nf; ++f) n_new += splits[f];
    const Index next_edge = ne + n_split_edges + n_new, next_face = nf + n_new;
    out = bare_copy(m, std::size_t(nv) + n_split_edges, next_edge, next_face);
    Vertex* to = out.halfedge_to_array().data();
    Halfedge* nx = out.halfedge_next_array().data();
    Halfedge* pv = out.halfedge_prev_array().data();
    Face* fc = out.halfedge_face_array().data();
    Halfedge* vh = out.vertex_halfedge_array().data();
    Halfedge* fh = out.face_halfedge_array().data();
    const Vertex* to_in = m.halfedge_to_array().data();
    const Halfedge* next_in = m.halfedge_next_array().data();
    const Halfedge* prev_in = m.halfedge_prev_array().data();
    const Face* face_in = m.halfedge_face_array().data();
    // The halves of a split halfedge h: first(h) from its start to the new vertex, second(h)
    // from the new vertex to its end. Halfedge 2e keeps the half at its start, 2e + 1 the half
    // at its end; the new edge ne + k carries the other two.
    const auto mid_of = [&](Index h) { return nv + split_number[h >> 1]; };
    const auto first = [&](Index h) { return (h & 1u) ? 2 * (ne + split_number[h >> 1]) + 1 : h; };
    const auto second = [&](Index h) { return (h & 1u) ? h : 2 * (ne + split_number[h >> 1]); };
    const auto link = [&](Index a, Index b) {
        nx[a] = Halfedge(b);
        pv[b] = Halfedge(a);
    };
    const auto triangle = [&](Index f, Index a, Index b, Index c) {
        link(a, b), link(b, c), link(c, a);
        fc[a] = fc[b] = fc[c] = Face(f);
        fh[f] = Halfedge(a);
    };
    for (Index e = 0; e < ne; ++e) {
        if (!split[e]) continue;
        const Index h = 2 * e, t = h + 1, mv = mid_of(h);
        to[first(h)] = to[first(t)] = Vertex(mv);
        to[second(h)] = to_in[h];
        to[second(t)] = to_in[t];
        vh[mv] = Halfedge(face_in[t].is_valid() ? second(h) : second(t));
        if (!face_in[h].is_valid()) vh[mv] = Halfedge(second(h));
        for (Index g : {h, t}) {
            if (face_in[g].is_valid()) continue;  // boundary halfedge: first, then second
            const Index before = prev_in[g].idx(), after = next_in[g].idx();
            fc[first(g)] = fc[second(g)] = Face();
            link(split[before >> 1] ? second(before) : before, first(g));
            link(first(g), second(g));
            link(second(g), split[after >> 1] ? first(after) : after);
        }
    }
    for (Index v = 0; v < nv; ++v) {
        const Halfedge g = vh[v];
        if (g.is_valid() && split[g.idx() >> 1]) vh[v] = Halfedge(first(g.idx()));
    }
    // The faces, in order (the first new edge and face of each refined face follow from the
    // counts of the ones before it).
    std::vector<std::uint8_t> closure(next_face, 0);
    for (Index f = 0, e0 = ne + n_split_edges, f0 = nf; f < nf;
         e0 += splits[f], f0 += splits[f], ++f) {
        if (splits[f] == 0) continue;
        if (touched[f])
            std::fill_n(closure.begin() + std::ptrdiff_t(f0), splits[f], 1), closure[f] = 1;
        Index h[3];
        h[0] = m.halfedge(Face(f)).idx();
        h[1] = next_in[h[0]].idx();
        h[2] = next_in[h[1]].idx();
        if (splits[f] == 3) {
            // Corner k (at the end of h[k]): second(h[k]), first(h[k+1]), and the inner edge
            // e0 + k between the two midpoints; the middle keeps f.
            Index inner[3];
            for (int k = 0; k < 3; ++k) {
                const Index hk = h[k], hn = h[(k + 1) % 3];
                const Index in = 2 * (e0 + Index(k));  // mid(hn) -> mid(hk), in the corner
                to[in] = Vertex(mid_of(hk));
                to[in + 1] = Vertex(mid_of(hn));
                triangle(f0 + Index(k), second(hk), first(hn), in);
                inner[k] = in + 1;  // mid(hk) -> mid(hn), in the middle
            }
            triangle(f, inner[0], inner[1], inner[2]);
        } else {
            int k = 0;
            while (!split[h[k] >> 1]) ++k;
            const Index hs = h[k], h1 = h[(k + 1) % 3], h2 = h[(k + 2) % 3];
            const Index cut = 2 * e0;  // mid -> the opposite corner
            to[cut] = to_in[h1];
            to[cut + 1] = Vertex(mid_of(hs));
            triangle(f, first(hs), cut, h2);
            triangle(f0, second(hs), h1, cut + 1);
        }
    }
    return closure;
}

/// The split edges per face of `m` (0 to 3), counting the selected, red and green faces.
std::vector<std::uint8_t> split_counts(const HalfedgeMesh& m,
                                       const std::vector<std::uint8_t>& split,
                                       const std::vector<std::uint8_t>& selected,
                                       RegionClosureCounts& counts) {
    const Index nf = Index(m.faces_size());
    std::vector<std::uint8_t> splits(nf, 0);
    for (Index f = 0; f < nf; ++f) {
        const Halfedge h0 = m.halfedge(Face(f)), h1 = m.next(h0), h2 = m.next(h1);
        const int c = split[h0.idx() >> 1] + split[h1.idx() >> 1] + split[h2.idx() >> 1];
        splits[f] = std::uint8_t(c);
        counts.selected_faces += selected[f];
        counts.red_faces += c == 3 ? 1 : 0;
        counts.green_faces += c == 1 ? 1 : 0;
    }
    return splits;
}

/// This level's closure (per face of the new level) and every face that descends from an
/// earlier level's closure (`earlier`, per coarse face; a refined face keeps its index for one
/// child and numbers the others after the coarse faces, in face order: build_red_green()). The
/// next level reads them, and the closure's flips run over all of them.
std::vector<std::uint8_t> with_earlier_closure(const std::vector<std::uint8_t>& closure,
                                               const std::vector<std::uint8_t>& earlier,
                                               const std::vector<std::uint8_t>& splits) {
    std::vector<std::uint8_t> all = closure;
    const Index nf = Index(splits.size());
    if (!earlier.empty())
        for (Index f = 0, f0 = nf; f < nf; f0 += splits[f], ++f) {
            if (!earlier[f]) continue;
            all[f] = 1;
            std::fill_n(all.begin() + std::ptrdiff_t(f0), splits[f], 1);
        }
    return all;
}

/// Butterfly and Modified Butterfly keep every old vertex, so a triangle of a level is never
/// moved again, only split, and a 1-to-4 split at its edges' midpoints gives four triangles
/// similar to it. An edge vertex whose stencil makes a new triangle flatter than `bound`
/// degrees is moved toward its edge's midpoint, its offset halved until no triangle at it is
/// flatter (at most four times, then the midpoint itself): level by level, no triangle the
/// step makes is flatter than the bound unless its coarse face was. (At the region's border
/// the extraordinary-vertex stencils read the closure's flat, irregular ring and put the
/// vertex up to a tenth of the edge off the chord: Modified Butterfly on the default model fell
/// to 16.4 degrees at level 3 for a bound of 23.8.) `placed`: the new vertices at a stencil
/// (ascending), `midpoint`: their edges' midpoints; `stencil`: the level's provenance, where
/// each vertex moved is marked SubdivisionStencil::OddDamped. Returns the number moved.
/// O(placed and their faces).
std::size_t damp_flat_edge_vertices(HalfedgeMesh& out, const std::vector<Index>& placed,
                                    const std::vector<Point>& midpoint, double bound,
                                    int* stencil_of) {
    if (placed.empty()) return 0;
    const double cos_bound = std::cos(bound * kPi / 180.0);
    Point* p = out.positions().data();
    const Index first = placed.front();
    std::vector<Index> slot_of(std::size_t(placed.back() - first) + 1, kInvalidIndex);
    for (std::size_t i = 0; i < placed.size(); ++i) slot_of[placed[i] - first] = Index(i);
    const auto slot = [&](Index v) {
        return v < first || v - first >= slot_of.size() ? kInvalidIndex : slot_of[v - first];
    };
    std::vector<Point> scheme_position(placed.size());
    std::vector<int> halvings(placed.size(), 0);  // 5: at the midpoint
    std::vector<Index> pending, next;
    // The placed vertices of the triangles at `v` flatter than the bound, still movable.
    const auto flat_triangles_at = [&](Index v, std::vector<Index>& into) {
        for (Face f : out.faces_around(Vertex(v))) {
            Index c[3];
            int k = 0;
            for (Vertex u : out.vertices_of(f)) c[k++] = u.idx();
            if (min_angle_at_least(p[c[0]], p[c[1]], p[c[2]], bound, cos_bound)) continue;
            for (Index u : c)
                if (slot(u) != kInvalidIndex && halvings[slot(u)] < 5) into.push_back(slot(u));
        }
    };
    for (Index v : placed) flat_triangles_at(v, pending);
    std::size_t moved = 0;
    while (!pending.empty()) {
        std::sort(pending.begin(), pending.end());
        pending.erase(std::unique(pending.begin(), pending.end()), pending.end());
        next.clear();
        for (Index i : pending) {
            const Index v = placed[i];
            if (halvings[i] == 0) {
                scheme_position[i] = p[v], ++moved;
                stencil_of[v] = int(SubdivisionStencil::OddDamped);
            }
            ++halvings[i];
            p[v] = halvings[i] == 5 ? midpoint[i]
                                    : Point(midpoint[i] + std::ldexp(1.0, -halvings[i]) *
                                                              (scheme_position[i] - midpoint[i]));
        }
        for (Index i : pending) flat_triangles_at(placed[i], next);
        pending.swap(next);
    }
    return moved;
}

/// The features of `m` (core/features.h) carried onto a refinement `out` in which old edges
/// and old vertices keep their indices: carry_edge(sharpness of out, e, s) writes what old
/// edge e (sharpness s) leaves (new edges are smooth unless it writes them); old vertices keep
/// their corner tags, new ones have none. O(V + E).
template <typename CarryEdge>
void carry_features(const HalfedgeMesh& m, HalfedgeMesh& out, CarryEdge&& carry_edge) {
    if (const auto in = m.get_edge_property<float>(kSharpnessProperty)) {
        std::vector<float>& sharp = out.add_edge_property<float>(kSharpnessProperty, 0.0f).vector();
        for (Index e = 0; e < Index(m.edges_size()); ++e) carry_edge(sharp, e, in.vector()[e]);
    }
    if (const auto in = m.get_vertex_property<std::uint8_t>(kCornerProperty)) {
        std::vector<std::uint8_t>& corner =
            out.add_vertex_property<std::uint8_t>(kCornerProperty, 0).vector();
        std::copy_n(in.vector().begin(), m.vertices_size(), corner.begin());
    }
}

/// The features of `m` carried onto its red-green refinement `out` (build_red_green()'s
/// numbering: the second half of split edge number k is edge ne + k): both halves of a split
/// edge take child_sharpness() of its sharpness (one level finer, as subdivide() carries them),
/// an edge not split keeps its own, the red faces' inner edges and the green cuts are smooth.
void carry_region_features(const HalfedgeMesh& m, const std::vector<std::uint8_t>& split,
                           HalfedgeMesh& out) {
    const Index ne = Index(m.edges_size());
    Index k = 0;  // split edges so far
    carry_features(m, out, [&](std::vector<float>& sharp, Index e, float s) {
        if (!split[e])
            sharp[e] = s;
        else
            sharp[e] = sharp[ne + k++] = child_sharpness(s);
    });
}

/// One red-green step of a 1-to-4 scheme on `m` (compact) with weights `w`.
/// `coarse_flat`: the flatness of m's faces, or empty on the input (then computed here, in the
/// first pass over the faces, and `target_angle`, the input's minimum angle, set from it).
RegionStep refine_region_1to4(const HalfedgeMesh& m, const Selection& w, SubdivisionScheme scheme,
                              bool features, int level, bool morph, bool local_closure,
                              double& target_angle, std::vector<double>& coarse_flat,
                              const std::vector<std::uint8_t>& earlier_closure, bool keep_flatness,
                              Progress& progress) {
    const Index nv = Index(m.vertices_size()), ne = Index(m.edges_size()),
                nf = Index(m.faces_size());
    // In one pass: the selected faces (region_faces()), their edges (split), and the faces
    // with a vertex that moves (`near`: changed even when they are not refined).
    // On the input, the same pass computes the faces' flatness (flatness_of()).
    std::vector<std::uint8_t> selected(nf, 0), near(nf, 0), split(ne, 0);
    const Point* x = m.positions().data();
    const bool measure = coarse_flat.empty();
    if (measure) coarse_flat.resize(nf);
    Index flattest = kInvalidIndex;
    double largest = 0;
    const Vertex* to = m.halfedge_to_array().data();
    const Halfedge* next_of = m.halfedge_next_array().data();
    const Halfedge* face_halfedge = m.face_halfedge_array().data();
    for (Index f = 0; f < nf; ++f) {
        const Index h0 = face_halfedge[f].idx(), h1 = next_of[h0].idx(), h2 = next_of[h1].idx();
        const Index v0 = to[h0].idx(), v1 = to[h1].idx(), v2 = to[h2].idx();
        if (measure) {
            const double flat = triangle_flatness(x[v0], x[v1], x[v2]);
            coarse_flat[f] = flat;
            if (flattest == kInvalidIndex || flat > largest) largest = flat, flattest = f;
        }
        const bool in0 = w[v0] > 0.0f, in1 = w[v1] > 0.0f, in2 = w[v2] > 0.0f;
        near[f] = in0 || in1 || in2;
        if (!(in0 && in1 && in2)) continue;
        selected[f] = 1;
        split[h0 >> 1] = split[h1 >> 1] = split[h2 >> 1] = 1;
    }
    if (measure)
        target_angle = flattest == kInvalidIndex ? 180.0 : min_face_angle(m, Face(flattest));
    const RegionStencils uniform = region_stencils(m, w, scheme, features, progress);
    progress.check_cancelled();
    RegionStep step;
    // The edges of the selected faces (refined by the scheme); the closure's other split edges
    // get the midpoint of their ends' new positions, so that the faces cut from refined faces
    // outside are similar to them (and never move again: their weight is 0).
    const std::vector<std::uint8_t> region_edge = split;
    step.counts.grown_faces =
        close_red_green(m, w, selected, near, uniform, local_closure, target_angle, earlier_closure,
                        region_edge, split, step.counts.closure_reds);
    const std::vector<std::uint8_t> splits = split_counts(m, split, selected, step.counts);
    check_face_limit(std::size_t(nf) + 3 * step.counts.red_faces + step.counts.green_faces);
    check_no_refined_pillow(m, [&](Face f) { return splits[f.idx()] > 0; });
    progress.check_cancelled();
    HalfedgeMesh& out = step.level.mesh;
    // The closure: the faces cut from refined faces outside the selection (green halves, the
    // children of faces that turned red), improved below by max-min-angle flips among
    // themselves.
    std::vector<std::uint8_t> touched(nf, 0);
    for (Index f = 0; f < nf; ++f) touched[f] = !selected[f] && splits[f] > 0;
    const std::vector<std::uint8_t> closure = build_red_green(m, split, splits, touched, out);
    if (features) carry_region_features(m, split, out);
    std::vector<std::uint8_t> all_closure = with_earlier_closure(closure, earlier_closure, splits);
    const Vertex* to_in = m.halfedge_to_array().data();
    NewVertices nvx(out, morph);
    Point* p = out.positions().data();
    // The uniform step's entries in order: the moving vertices counted, the edges with a
    // moving end walked alongside the split ones (both ascending).
    const Point* uniform_p = uniform.step.positions.data();
    const int* uniform_st = uniform.step.stencils.data();
    Index slot = 0;
    for (Index v = 0; v < nv; ++v) {
        const bool moves = w[v] > 0.0f;
        if (!moves) {
            nvx.add(SubdivisionStencil::EvenKept, x[v], w[v], v);
            continue;
        }
        const Index i = uniform.dense ? v : slot++;
        nvx.add(SubdivisionStencil(uniform_st[i]), x[v], w[v], v);
        p[v] = blend_by_weight(x[v], uniform_p[i], w[v]);
    }
    std::size_t listed = 0;  // in uniform.edges
    const bool interpolating = scheme != SubdivisionScheme::Loop;
    std::vector<Index> placed;  // the new vertices at a stencil, and their edges' midpoints
    std::vector<Point> placed_midpoint;
    for (Index e = 0, k = 0; e < ne; ++e) {
        if (!split[e]) continue;
        const Index a = to_in[2 * e + 1].idx(), b = to_in[2 * e].idx();
        const Point mid = 0.5 * (x[a] + x[b]);
        const float wmax = std::max(w[a], w[b]);
        if (wmax > 0.0f && !region_edge[e]) {
            // A closure edge with an end that moves: the midpoint of the ends' new positions.
            p[nv + k++] = 0.5 * (p[a] + p[b]);
            nvx.add(SubdivisionStencil::OddClosureMidpoint, mid, std::min(w[a], w[b]), a, b);
        } else if (wmax > 0.0f) {
            Index i = nv + e;
            if (!uniform.dense) {
                while (uniform.edges[listed] < e) ++listed;  // e is listed: it has a moving end
                i = Index(uniform.vertices.size() + listed);
            }
            if (interpolating) placed.push_back(nv + k), placed_midpoint.push_back(mid);
            p[nv + k++] = blend_by_weight(mid, uniform_p[i], wmax);
            nvx.add(SubdivisionStencil(uniform_st[i]), mid, std::min(w[a], w[b]), a, b);
        } else {
            p[nv + k++] = mid;
            nvx.add(SubdivisionStencil::OddClosureMidpoint, mid, std::min(w[a], w[b]), a, b);
        }
    }
    step.counts.damped_vertices =
        damp_flat_edge_vertices(out, placed, placed_midpoint, 0.5 * target_angle, nvx.stencil);
    step.counts.closure_flips = improve_closure(out, all_closure);
    if (keep_flatness) step.closure_faces = std::move(all_closure);
    step.counts.min_angle_touched = min_angle_of(m, touched);
    step.counts.min_angle_closure = min_angle_of(out, closure);
    // Faces of the coarse level left as they were: not refined, no vertex moved.
    const auto changed = [&](Index f) { return splits[f] > 0 || near[f]; };
    level_flatness(out, coarse_flat, changed, keep_flatness, step);
    finish(m, level, morph, keep_flatness, std::move(nvx), step);
    return step;
}

/// Sqrt3's relaxed positions of the interior vertices that move (weight > 0), from the coarse
/// ring: the neighbours summed in the order of their edges' indices and the rule written as
/// subdivide() writes it, so that a vertex of weight 1 lands where the uniform step puts it,
/// bit for bit. Only the vertices that move are visited and written; the others' entries are
/// left unset (Eigen's default constructor: no store, so no page of a small region's array is
/// touched but its own) and are never read.
std::vector<Point> sqrt3_relaxed(const HalfedgeMesh& m, const Selection& w) {
    const Index nv = Index(m.vertices_size());
    const Point* x = m.positions().data();
    std::vector<Point> relaxed(nv);
    std::vector<double> alpha_of;  // by valence, as computed below (the same bits)
    std::vector<std::pair<Index, Index>> ring;
    for (Index v = 0; v < nv; ++v) {
        if (!(w[v] > 0.0f) || m.is_isolated(Vertex(v)) || m.is_boundary(Vertex(v))) continue;
        ring.clear();
        for (Halfedge h : m.halfedges_around(Vertex(v)))
            ring.emplace_back(HalfedgeMesh::edge(h).idx(), m.to_vertex(h).idx());
        std::sort(ring.begin(), ring.end());
        Point sum = Point::Zero();
        for (const auto& edge_and_neighbour : ring) sum += x[edge_and_neighbour.second];
        const unsigned k = unsigned(ring.size());
        if (k >= alpha_of.size()) alpha_of.resize(2 * std::size_t(k) + 1, -1.0);
        if (alpha_of[k] < 0) alpha_of[k] = (4.0 - 2.0 * std::cos(2 * kPi / k)) / 9.0;
        const double alpha = alpha_of[k];
        relaxed[v] = (1.0 - alpha) * x[v] + (alpha / k) * sum;
    }
    return relaxed;
}

/// The faces of `split_face` (the selected ones on entry) grown until no old edge between a
/// split and an unsplit face leaves the split side a triangle (a, b, centroid) flatter than
/// target_angle (`position`: where each old vertex will be). Returns the number grown into.
template <typename Position>
std::size_t grow_sqrt3(const HalfedgeMesh& m, const Position& old_position, double target_angle,
                       std::vector<std::uint8_t>& split_face) {
    const Index nf = Index(m.faces_size());
    const Point* x = m.positions().data();
    const double cos_target = std::cos(target_angle * kPi / 180.0);
    std::size_t grown = 0;
    const auto centroid_of = [&](Face f) {
        const Halfedge h = m.halfedge(f), hn = m.next(h);
        return Point((x[m.to_vertex(h).idx()] + x[m.to_vertex(hn).idx()] +
                      x[m.to_vertex(m.next(hn)).idx()]) /
                     3.0);
    };
    {
        std::vector<Face> queue;
        for (Index f = 0; f < nf; ++f)
            if (split_face[f]) queue.push_back(Face(f));
        while (!queue.empty()) {
            const Face f = queue.back();
            queue.pop_back();
            const Point c = centroid_of(f);
            for (Halfedge h : m.halfedges_of(f)) {
                const Face g = m.face(HalfedgeMesh::twin(h));
                if (!g.is_valid() || split_face[g.idx()]) continue;
                const Point a = old_position(m.from_vertex(h).idx());
                const Point b = old_position(m.to_vertex(h).idx());
                if (min_angle_at_least(a, b, c, target_angle, cos_target)) continue;
                split_face[g.idx()] = 1;
                ++grown;
                queue.push_back(g);
            }
        }
    }
    return grown;
}

/// The Sqrt3 closure on `out`: each old edge (of `m`) between a split and an unsplit face
/// keeps the split side's triangle (a, b, centroid); it is flipped (towards the pattern of
/// the paper's next generation) when that raises the pair's minimum angle and it is not a
/// feature edge (`sharp`: sharpness per edge, or null). Fills the flip
/// counts and closure angles of `counts`; returns the closure's faces (flags per face of
/// `out`).
std::vector<std::uint8_t> sqrt3_closure(const HalfedgeMesh& m, HalfedgeMesh& out,
                                        const std::vector<std::uint8_t>& split_face,
                                        const float* sharp, RegionClosureCounts& counts,
                                        std::vector<OddTriangle>& odd_triangles) {
    const Index nf = Index(m.faces_size());
    // The old edges of the split faces, the only ones the rule or the closure changes: flipped
    // by the rule when the face across is split too (counted at their even halfedge, so once),
    // a closure edge when it is not (met once, from the split side; handled in ascending edge
    // order below, as a scan over every edge would).
    std::vector<Index> closure_edges;
    for (Index f = 0; f < nf; ++f) {
        if (!split_face[f]) continue;
        for (Halfedge h : m.halfedges_of(Face(f))) {
            const Face g = m.face(HalfedgeMesh::twin(h));
            if (!g.is_valid()) continue;
            if (split_face[g.idx()])
                counts.flipped_edges += (h.idx() & 1u) == 0 && !(sharp && sharp[h.idx() >> 1] > 0);
            else
                closure_edges.push_back(h.idx() >> 1);
        }
    }
    std::sort(closure_edges.begin(), closure_edges.end());
    std::vector<std::uint8_t> touched(nf, 0), closure(out.faces_size(), 0);
    for (const Index e : closure_edges) {
        const Face f0 = m.face(HalfedgeMesh::halfedge(Edge(e), 0));
        const Face f1 = m.face(HalfedgeMesh::halfedge(Edge(e), 1));
        touched[f0.idx()] = touched[f1.idx()] = 1;
        if (sharp && sharp[e] > 0) {
            // A feature edge stays (Kobbelt's boundary rule): neither flipped nor completed.
        } else if (flip_improves(out, Edge(e))) {
            out.flip(Edge(e));
            ++counts.closure_flips;
        } else {
            // The split side keeps its halfedge (the triangle a, b, centroid).
            const Halfedge h = HalfedgeMesh::halfedge(Edge(e), split_face[f0.idx()] ? 0 : 1);
            odd_triangles.push_back({h.idx(), out.to_vertex(out.next(h)).idx()});
        }
        closure[out.face(HalfedgeMesh::halfedge(Edge(e), 0)).idx()] = 1;
        closure[out.face(HalfedgeMesh::halfedge(Edge(e), 1)).idx()] = 1;
    }
    counts.min_angle_touched = min_angle_of(m, touched);
    counts.min_angle_closure = min_angle_of(out, closure);
    return closure;
}

/// The provenance of `m`'s vertices on the new level: relaxed or kept, and from `n_level` on
/// the centroids complete_sqrt3() added (new face points of this level).
template <typename Moves>
void add_sqrt3_old_vertices(const HalfedgeMesh& m, const Selection& w, Index n_level,
                            const Moves& moves, NewVertices& nvx) {
    const Index nv = Index(m.vertices_size());
    const Point* x = m.positions().data();
    for (Index v = 0; v < std::min(nv, n_level); ++v)
        nvx.add(moves(v) ? SubdivisionStencil::EvenRelaxed : SubdivisionStencil::EvenKept, x[v],
                w[v], v);
    if (n_level >= nv) return;
    const auto completion = m.get_vertex_property<SubdivisionParents>(kParentsName);
    for (Index v = n_level; v < nv; ++v) {
        const SubdivisionParents& q = completion[Vertex(v)];
        nvx.add(SubdivisionStencil::OddFace, x[v], w[v], q[0], q[1], q[2]);
    }
}

/// The features of `m` carried onto its adaptive Sqrt3 step `out` (the spokes follow the old
/// edges): an old edge at a split face takes child_sharpness() of its sharpness (one step finer,
/// as subdivide() carries them), one between unsplit faces keeps its own, the spokes are
/// smooth.
void carry_sqrt3_features(const HalfedgeMesh& m, const std::vector<std::uint8_t>& split_face,
                          HalfedgeMesh& out) {
    const auto split_at = [&](Halfedge h) {
        const Face f = m.face(h);
        return f.is_valid() && split_face[f.idx()] != 0;
    };
    carry_features(m, out, [&](std::vector<float>& sharp, Index e, float s) {
        const bool refined = split_at(HalfedgeMesh::halfedge(Edge(e), 0)) ||
                             split_at(HalfedgeMesh::halfedge(Edge(e), 1));
        sharp[e] = refined ? child_sharpness(s) : s;
    });
}

/// The features a Sqrt3 region step keeps (Kobbelt 2000, section 4: creases as boundaries):
/// sharp edges are never flipped (nor, in this odd-step rule, split), crease and corner
/// vertices stay. Without features (or none stored) nothing is kept.
struct Sqrt3Features {
    const float* sharp = nullptr;      ///< sharpness per edge, or null
    std::vector<VertexClass> classes;  ///< per vertex, or empty
    Sqrt3Features(const HalfedgeMesh& m, bool features) {
        if (!features) return;
        if (const auto sharpness = m.get_edge_property<float>(kSharpnessProperty))
            sharp = sharpness.vector().data();
        classes = classify_vertices(m, false).classes;
    }
    bool on_feature(Index v) const { return !classes.empty() && classes[v] >= VertexClass::Crease; }
    /// The provenance of the first `n` old vertices that weigh > 0 and stay on a feature.
    void label_kept(const Selection& w, Index n, int* stencil) const {
        for (Index v = 0; v < n; ++v)
            if (w[v] > 0.0f && on_feature(v))
                stencil[v] =
                    int(classes[v] == VertexClass::Corner ? SubdivisionStencil::EvenCorner
                                                          : SubdivisionStencil::EvenCreaseCurve);
    }
};

/// One adaptive Sqrt3 step on `m` (compact) with weights `w`. The vertices from `n_level` on
/// are the centroids complete_sqrt3() added to the previous level: new vertices of this one.
/// Built straight into the arrays. Split face number i (in face order) gets the centroid
/// nv + i, the spokes ne + 3i + k (from the start of its halfedge k to the centroid) and keeps
/// one triangle per halfedge ("slot"): slot 0 is face f, slots 1 and 2 the faces nf + 2i and
/// nf + 2i + 1. Slot x (u -> v, in face F) is the triangle (u, v, c_F) when the face across x
/// is not split; when it is (G), x becomes c_F -> c_G, the old edge flipped, and the slot is
/// (c_F, c_G, v).
RegionStep refine_region_sqrt3(const HalfedgeMesh& m, const Selection& w, bool features,
                               Index n_level, int level, bool morph, bool local_closure,
                               double target_angle, const std::vector<double>& coarse_flat,
                               bool keep_flatness, Progress& progress) {
    const Index nv = Index(m.vertices_size()), ne = Index(m.edges_size()),
                nf = Index(m.faces_size());
    const std::vector<std::uint8_t> selected = region_faces(m, w);
    RegionStep step;
    for (Index f = 0; f < nf; ++f) step.counts.selected_faces += selected[f];
    const Point* x = m.positions().data();
    const std::vector<Point> relaxed = sqrt3_relaxed(m, w);
    const Sqrt3Features kept(m, features);
    const auto moves = [&](Index v) {
        return w[v] > 0.0f && !m.is_isolated(Vertex(v)) && !m.is_boundary(Vertex(v)) &&
               !kept.on_feature(v);
    };
    const auto old_position = [&](Index v) {
        return moves(v) ? blend_by_weight(x[v], relaxed[v], w[v]) : x[v];
    };
    std::vector<std::uint8_t> split_face = selected;  // and those grown into (grow_sqrt3())
    if (!local_closure)
        step.counts.grown_faces = grow_sqrt3(m, old_position, target_angle, split_face);
    for (Index f = 0; f < nf; ++f) step.counts.red_faces += split_face[f];
    check_face_limit(std::size_t(nf) + 2 * step.counts.red_faces);
    check_no_refined_pillow(m, [&](Face f) { return split_face[f.idx()] != 0; });
    progress.check_cancelled();
    const Index n_split_faces = Index(step.counts.red_faces);
    std::vector<Index> split_number(nf, kInvalidIndex);
    for (Index f = 0, i = 0; f < nf; ++f)
        if (split_face[f]) split_number[f] = i++;
    HalfedgeMesh& out = step.level.mesh;
    out = bare_copy(m, std::size_t(nv) + n_split_faces, std::size_t(ne) + 3 * n_split_faces,
                    std::size_t(nf) + 2 * n_split_faces);
    Vertex* to = out.halfedge_to_array().data();
    Halfedge* nx = out.halfedge_next_array().data();
    Halfedge* pv = out.halfedge_prev_array().data();
    Face* fc = out.halfedge_face_array().data();
    Halfedge* vh = out.vertex_halfedge_array().data();
    Halfedge* fh = out.face_halfedge_array().data();
    const Vertex* to_in = m.halfedge_to_array().data();
    const Halfedge* next_in = m.halfedge_next_array().data();
    const Face* face_in = m.halfedge_face_array().data();
    const auto corner = [&](Index hx) {  // 0, 1, 2: hx's place in its face
        const Index h0 = m.halfedge(face_in[hx]).idx();
        return h0 == hx ? 0 : (next_in[h0].idx() == hx ? 1 : 2);
    };
    // The spoke of face halfedge x: from x's start to its face's centroid (in) and back (out).
    const auto spoke_in = [&](Index hx) {
        return 2 * (ne + 3 * split_number[face_in[hx].idx()] + Index(corner(hx)));
    };
    const auto spoke_out = [&](Index hx) { return spoke_in(hx) + 1; };
    const auto flipped = [&](Index hx) {
        const Face g = face_in[hx ^ 1u];
        return g.is_valid() && split_face[g.idx()] != 0 &&
               !(kept.sharp && kept.sharp[hx >> 1] > 0.0f);
    };
    NewVertices nvx(out, morph);
    add_sqrt3_old_vertices(m, w, n_level, moves, nvx);
    kept.label_kept(w, std::min(nv, n_level), nvx.stencil);
    Point* p = out.positions().data();
    for (Index f = 0; f < nf; ++f) {
        if (!split_face[f]) continue;
        const Index i = split_number[f], c = nv + i;
        Index h[3];
        h[0] = m.halfedge(Face(f)).idx();
        h[1] = next_in[h[0]].idx();
        h[2] = next_in[h[1]].idx();
        const Index a = to_in[h[0]].idx(), b = to_in[h[1]].idx(), d = to_in[h[2]].idx();
        const Point centroid = (x[a] + x[b] + x[d]) / 3.0;
        p[c] = centroid;
        nvx.add(SubdivisionStencil::OddFace, centroid, std::min({w[a], w[b], w[d]}), a, b, d);
        vh[c] = Halfedge(spoke_out(h[0]));
        for (int k = 0; k < 3; ++k) {
            const Index xk = h[k], xn = h[(k + 1) % 3];
            const Index from = to_in[h[(k + 2) % 3]].idx();  // start of xk
            const Index in = spoke_in(xk);
            to[in] = Vertex(c);
            to[in + 1] = Vertex(from);
            const Index slot = k == 0 ? f : nf + 2 * i + Index(k - 1);
            Index second, third;
            if (flipped(xk)) {
                const Index g = face_in[xk ^ 1u].idx();
                to[xk] = Vertex(nv + split_number[g]);
                second = spoke_out(xk ^ 1u);  // c_G -> end of xk
                third = spoke_in(xn);         // end of xk -> c_F
            } else {
                second = spoke_in(xn);  // end of xk -> c_F
                third = spoke_out(xk);  // c_F -> start of xk
            }
            nx[xk] = Halfedge(second), pv[second] = Halfedge(xk);
            nx[second] = Halfedge(third), pv[third] = Halfedge(second);
            nx[third] = Halfedge(xk), pv[xk] = Halfedge(third);
            fc[xk] = fc[second] = fc[third] = Face(slot);
            fh[slot] = Halfedge(xk);
            // The start's outgoing halfedge, when it was xk and xk now leaves elsewhere.
            if (vh[from].idx() == xk && flipped(xk)) vh[from] = Halfedge(in);
        }
    }
    for (Index v = 0; v < nv; ++v)
        if (nvx.stencil[v] == int(SubdivisionStencil::EvenRelaxed))
            p[v] = blend_by_weight(x[v], relaxed[v], w[v]);
    const std::vector<std::uint8_t> closure =
        sqrt3_closure(m, out, split_face, kept.sharp, step.counts, step.odd_triangles);
    if (features) carry_sqrt3_features(m, split_face, out);
    // Faces of the coarse level left as they were: not split, not flipped, no vertex of weight
    // > 0 (a face counted as changed that is not, one with a boundary vertex, gets the same
    // value computed anew).
    const FaceCorners corners(m);
    const auto changed = [&](Index f) {
        if (split_face[f] || closure[f]) return true;
        const auto v = corners(f);
        return w[v[0]] > 0.0f || w[v[1]] > 0.0f || w[v[2]] > 0.0f;
    };
    level_flatness(out, coarse_flat, changed, keep_flatness, step);
    finish(m, level, morph, keep_flatness, std::move(nvx), step);
    return step;
}

/// Kobbelt's completion of earlier levels' odd triangles ("√3-Subdivision", SIGGRAPH 2000,
/// adaptive refinement): a closure triangle T = (a, b, centroid of F) left unflipped beside an
/// unsplit face M is, when T is to be refined now (its three vertices weigh > 0), first
/// completed as the uniform step would have made it: M is split at its centroid and the edge
/// a-b flipped, giving the regular pair (c_F, c_M, b), (c_M, c_F, a) instead of refining the
/// flat T again (which halved its angles at every level: 29 to 12 degrees over five levels on
/// the generated sphere's cap). A face M beside two such triangles is split once, and its
/// other two old edges are then flipped where that raises the smaller angle of their pair
/// (max-min-angle, within 15 degrees of coplanar). A completion whose pair would be flatter
/// than `min_angle` degrees (M itself flat, an earlier odd triangle) is not done: T is
/// refined as an ordinary face. The new centroids weigh the least of M's weights (0: M was
/// not selected) and carry the level `level`, the one being built (its step reports them as
/// new face points of M: refine_region_sqrt3()'s `n_level`). `w` and `flatness` grow with
/// the mesh; every face changed has a new centroid as a corner and is measured anew. An odd
/// triangle not refined now is kept in `odd` for a later level; one that a flip has changed
/// since is dropped. Returns the number of edges flipped. O(odd triangles).
std::size_t complete_sqrt3(HalfedgeMesh& m, Selection& w, std::vector<double>& flatness,
                           std::vector<OddTriangle>& odd, int level, double min_angle) {
    std::vector<std::uint8_t> completed(m.faces_size(), 0);  // children of a split M
    auto levels = m.get_vertex_property<int>(kLevelName);
    auto stencils = m.get_vertex_property<int>(kStencilName);
    auto parents = m.get_vertex_property<SubdivisionParents>(kParentsName);
    auto uv = m.get_vertex_property<TexCoord>("v:texcoord");
    const double cos_min = std::cos(min_angle * kPi / 180.0);
    const auto fair = [&](const Point& p0, const Point& p1, const Point& p2) {
        return min_angle_at_least(p0, p1, p2, min_angle, cos_min);
    };
    std::vector<OddTriangle> kept;
    std::vector<Edge> outer;  // M's old edges but a-b: max-min-angle flips after
    const Index first_new = Index(m.vertices_size());
    std::size_t flips = 0;
    for (const OddTriangle& o : odd) {
        const Halfedge h(o.halfedge);
        if (o.halfedge >= m.halfedges_size() || m.is_boundary(h) ||
            m.to_vertex(m.next(h)).idx() != o.apex)
            continue;  // flipped or refined since
        const Halfedge t = HalfedgeMesh::twin(h);
        if (m.is_boundary(t)) continue;
        const Vertex a = m.from_vertex(h), b = m.to_vertex(h), apex(o.apex);
        if (!(w[a.idx()] > 0.0f && w[b.idx()] > 0.0f && w[o.apex] > 0.0f)) {
            kept.push_back(o);  // not refined at this level: perhaps at a later one
            continue;
        }
        const Face mate = m.face(t);
        const Vertex d = m.to_vertex(m.next(t));
        const Point &pa = m.position(a), &pb = m.position(b), &pc = m.position(apex);
        const bool split_now = !completed[mate.idx()];
        const Point cm = split_now ? Point((pa + pb + m.position(d)) / 3.0) : m.position(d);
        if (!fair(pc, cm, pb) || !fair(cm, pc, pa)) continue;
        if (split_now) {
            const float weight = std::min({w[a.idx()], w[b.idx()], w[d.idx()]});
            const Vertex c = m.split(mate, cm);
            w.resize(m.vertices_size(), 0.0f);
            w[c.idx()] = weight;
            if (levels) levels[c] = level;
            if (stencils) stencils[c] = int(SubdivisionStencil::OddFace);
            if (parents) parents[c] = SubdivisionParents(a.idx(), b.idx(), d.idx());
            if (uv) uv[c] = (uv[a] + uv[b] + uv[d]) / 3.0;
            outer.push_back(m.find_edge(b, d));
            outer.push_back(m.find_edge(d, a));
            completed.resize(m.faces_size(), 0);
            for (Halfedge g : m.halfedges_around(c)) completed[m.face(g).idx()] = 1;
        }
        const Edge e = HalfedgeMesh::edge(h);
        if (!m.is_flip_ok(e)) continue;
        m.flip(e);
        ++flips;
    }
    const auto sharpness = m.get_edge_property<float>(kSharpnessProperty);
    for (const Edge e : outer)
        if (e.is_valid() && !m.is_boundary(e) &&
            !(sharpness && sharpness.vector()[e.idx()] > 0.0f) && flip_improves(m, e))
            m.flip(e);
    // Every face the completion changed has a new centroid as a corner: measured anew.
    flatness.resize(m.faces_size(), 0.0);
    for (Index v = first_new; v < Index(m.vertices_size()); ++v)
        for (Halfedge g : m.halfedges_around(Vertex(v))) {
            const Face f = m.face(g);
            if (!f.is_valid()) continue;
            const auto c = m.face_vertices(f);
            flatness[f.idx()] =
                triangle_flatness(m.position(c[0]), m.position(c[1]), m.position(c[2]));
        }
    odd = std::move(kept);
    return flips;
}

/// The uniform run, for an all-ones selection: subdivide() itself, with the selection (all
/// ones) carried onto every level.
SubdivisionResult subdivide_everything(const HalfedgeMesh& mesh, const SubdivisionOptions& options,
                                       Progress& progress, RegionSubdivisionReport& report) {
    SubdivisionResult result = subdivide(mesh, options, progress);
    std::size_t faces = mesh.n_faces();
    for (const auto& counts : result.level_counts) {
        RegionClosureCounts c;
        c.selected_faces = c.red_faces = faces;
        report.closure.push_back(c);
        faces = counts[1];
    }
    for (SubdivisionLevel& level : result.levels)
        level.mesh.add_vertex_property<float>(kSelectionProperty, 1.0f);
    return result;
}

}  // namespace

std::vector<std::uint8_t> region_faces(const HalfedgeMesh& mesh, const Selection& selection) {
    std::vector<std::uint8_t> selected(mesh.faces_size(), 0);
    const FaceCorners corners(mesh);
    for (Face f : mesh.faces()) {
        const auto v = corners(f.idx());
        selected[f.idx()] =
            selection[v[0]] > 0.0f && selection[v[1]] > 0.0f && selection[v[2]] > 0.0f;
    }
    return selected;
}

SubdivisionResult subdivide_region(const HalfedgeMesh& mesh, const SubdivisionOptions& options,
                                   const Selection& selection, Progress& progress,
                                   RegionSubdivisionReport& report) {
    const auto t0 = std::chrono::steady_clock::now();
    check_selection(mesh, selection, "subdivide --region");
    if (options.iterations < 1 || options.iterations > 10)
        throw InvalidArgument("subdivide: iterations must be between 1 and 10 (got " +
                              std::to_string(options.iterations) + ")");
    check_subdivision_features(mesh, options);
    report = RegionSubdivisionReport{};
    report.region_vertices = count_selected(selection);
    SubdivisionResult result;
    if (selects_everything(mesh, selection)) {
        report.min_angle_in = min_triangle_angle(mesh);
        result = subdivide_everything(mesh, options, progress, report);
        report.min_angle_out = min_triangle_angle(result.levels.back().mesh);
    } else {
        // A compact copy, its selection following the vertices, when the input has garbage.
        HalfedgeMesh collected;
        const HalfedgeMesh* current = &mesh;
        Selection weights = selection;
        if (mesh.has_garbage()) {
            collected = mesh;
            const IndexRemap remap = collected.garbage_collection();
            weights.assign(collected.vertices_size(), 0.0f);
            for (std::size_t v = 0; v < remap.vertices.size(); ++v)
                if (remap.vertices[v] != kInvalidIndex) weights[remap.vertices[v]] = selection[v];
            current = &collected;
        }
        const bool sqrt3 = options.scheme == SubdivisionScheme::Sqrt3;
        // Features: the 1-to-4 schemes refine by their crease rules, Sqrt3 keeps sharp edges as
        // boundaries; both carry them.
        if (options.features == SubdivisionFeatures::Auto) {
            if (current != &collected) collected = mesh;
            current = &collected;
            result.notes.push_back(detect_subdivision_features(collected, options));
        }
        const bool features =
            options.features != SubdivisionFeatures::None && has_features(*current);
        Index flattest = kInvalidIndex;  // of the last level built
        // The input's flatness and minimum angle (the 1-to-4 step computes them in its first
        // pass over the faces).
        std::vector<double> flatness;
        if (sqrt3) {
            flatness = flatness_of(*current, flattest);
            report.min_angle_in =
                flattest == kInvalidIndex ? 180.0 : min_face_angle(*current, Face(flattest));
        }
        RegionStep latest;
        std::vector<std::uint8_t> closure_faces;  // of the last level built (1-to-4 schemes)
        std::vector<OddTriangle> odd_triangles;   // of the levels built (Sqrt3)
        HalfedgeMesh completed;                   // Sqrt3: the last level, completed
        if (options.keep_levels) result.levels.reserve(std::size_t(options.iterations));
        for (int it = 1; it <= options.iterations; ++it) {
            progress.check_cancelled();
            progress.report(double(it - 1) / options.iterations, "subdividing the region");
            const bool morph = options.morph && (options.keep_levels || it == options.iterations);
            const bool keep_flatness = it < options.iterations;  // the next level reads it
            std::size_t completions = 0;
            const Index n_level = Index(current->vertices_size());
            if (sqrt3 && !odd_triangles.empty()) {
                completed = *current;
                completions = complete_sqrt3(completed, weights, flatness, odd_triangles, it,
                                             0.5 * report.min_angle_in);
                current = &completed;
            }
            RegionStep step =
                sqrt3 ? refine_region_sqrt3(*current, weights, features, n_level, it, morph,
                                            !options.global_closure, report.min_angle_in, flatness,
                                            keep_flatness, progress)
                      : refine_region_1to4(*current, weights, options.scheme, features, it, morph,
                                           !options.global_closure, report.min_angle_in, flatness,
                                           closure_faces, keep_flatness, progress);
            step.counts.completed_edges = completions;
            report.closure.push_back(step.counts);
            result.level_counts.push_back(
                {step.level.mesh.n_vertices(), step.level.mesh.n_faces()});
            weights = std::move(step.selection);
            flatness = std::move(step.flatness);
            closure_faces = std::move(step.closure_faces);
            odd_triangles.insert(odd_triangles.end(), step.odd_triangles.begin(),
                                 step.odd_triangles.end());
            flattest = step.flattest;
            if (options.keep_levels) {
                result.levels.push_back(std::move(step.level));
                current = &result.levels.back().mesh;
            } else {
                latest = std::move(step);
                current = &latest.level.mesh;
            }
        }
        if (!options.keep_levels) result.levels.push_back(std::move(latest.level));
        if (mesh.get_halfedge_property<TexCoord>("h:texcoord"))
            result.notes.push_back(
                "corner texture coordinates (h:texcoord) are not carried by region subdivision");
        report.min_angle_out = flattest == kInvalidIndex
                                   ? 180.0
                                   : min_face_angle(result.levels.back().mesh, Face(flattest));
    }
    progress.report(1.0, "subdividing the region");
    result.ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    return result;
}

}  // namespace trilab
