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
// (normals, colours, ...) is dropped; "v:subdivision_level" is added (input vertices 0).
// Isolated vertices are kept, unmoved. An input with garbage is collected on a copy first
// (indices then refer to the collected mesh). Two faces with the same three vertices (a closed
// two-triangle "pillow") would give double edges in every scheme: subdivide() refuses them.
//
// Implementation: the 1-to-4 refinement is built directly into the new mesh's arrays (no
// edge splits, no hash maps): old vertex v keeps index v, the odd vertex of edge e is V + e,
// old halfedge h = 2e + s becomes A(h) = 4e + 2s (from_vertex(h) -> midpoint) and
// B(h) = 4e + 3 - 2s (midpoint -> to_vertex(h)), face f becomes corner faces 4f + k and the
// centre face 4f + 3 with interior edges 2E + 3f + k. Sqrt3 is built the same way.
// Complexity: linear in the mesh size per iteration.
#include "core/subdivision.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstring>

#include "core/errors.h"

namespace trilab {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr std::size_t kMaxFaces = 50'000'000;
constexpr std::size_t kCheckMask = 0xFFFF;  // check for cancellation every 64k elements

const char* const kLevelName = "v:subdivision_level";

/// Attributes carried from one level to the next.
struct Carried {
    VertexProperty<TexCoord> vuv;
    HalfedgeProperty<TexCoord> huv;
    VertexProperty<int> level;
};

/// The attributes of `m` to carry into level `level`. The input's own "v:subdivision_level"
/// (from an earlier subdivision) is not carried: the input's vertices are level 0.
Carried carried_of(const HalfedgeMesh& m, int level) {
    Carried c{m.get_vertex_property<TexCoord>("v:texcoord"),
              m.get_halfedge_property<TexCoord>("h:texcoord"),
              {}};
    if (level > 1) c.level = m.get_vertex_property<int>(kLevelName);
    return c;
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

// ---------------------------------------------------------------------------------------
// 1-to-4 refinement (Loop, Butterfly, Modified Butterfly)
// ---------------------------------------------------------------------------------------

/// Sum of the neighbours' positions around the interior vertex whose outgoing halfedge is
/// h0; `n` receives the valence.
inline Point ring_sum(const HalfedgeMesh& m, const std::vector<Point>& x, Halfedge h0,
                      unsigned& n) {
    Point s = Point::Zero();
    n = 0;
    Halfedge h = h0;
    do {
        s += x[m.to_vertex(h).idx()];
        ++n;
        h = m.ccw_rotated(h);
    } while (h != h0);
    return s;
}

inline Index half_a(Index h) {
    return 4 * (h >> 1) + 2 * (h & 1u);
}
inline Index half_b(Index h) {
    return 4 * (h >> 1) + 3 - 2 * (h & 1u);
}

/// Builds the connectivity of the 1-to-4 split of `m` into `out` (positions not set).
void build_1to4(const HalfedgeMesh& m, HalfedgeMesh& out, const Stage& stage) {
    const Index nv = Index(m.vertices_size()), ne = Index(m.edges_size()),
                nf = Index(m.faces_size());
    out.resize_elements(std::size_t(nv) + ne, 2 * std::size_t(ne) + 3 * std::size_t(nf),
                        4 * std::size_t(nf));
    auto mid = [&](Halfedge h) { return Vertex(nv + (h.idx() >> 1)); };
    for (Index fi = 0; fi < nf; ++fi) {
        stage.tick(fi);
        Face f(fi);
        Halfedge h[3];
        h[0] = m.halfedge(f);
        h[1] = m.next(h[0]);
        h[2] = m.next(h[1]);
        for (int k = 0; k < 3; ++k) {
            const int k1 = (k + 1) % 3;
            Face corner(4 * fi + Index(k));
            Halfedge b(half_b(h[k].idx())), a(half_a(h[k1].idx()));
            Halfedge in(2 * (2 * ne + 3 * fi + Index(k)));
            out.set_next(b, a);
            out.set_next(a, in);
            out.set_next(in, b);
            out.set_face(b, corner);
            out.set_face(a, corner);
            out.set_face(in, corner);
            out.set_halfedge(corner, b);
            out.set_to_vertex(b, m.to_vertex(h[k]));
            out.set_to_vertex(a, mid(h[k1]));
            out.set_to_vertex(in, mid(h[k]));
            // The centre face: mid(h_k) -> mid(h_k1).
            Halfedge cin(in.idx() + 1), cnext(2 * (2 * ne + 3 * fi + Index(k1)) + 1);
            Face centre(4 * fi + 3);
            out.set_next(cin, cnext);
            out.set_face(cin, centre);
            out.set_to_vertex(cin, mid(h[k1]));
        }
        out.set_halfedge(Face(4 * fi + 3), Halfedge(2 * (2 * ne + 3 * fi) + 1));
    }
    stage.report(0.3);
    for (Index hi = 0; hi < 2 * ne; ++hi) {
        Halfedge h(hi);
        if (!m.is_boundary(h)) continue;
        Halfedge a(half_a(hi)), b(half_b(hi));
        out.set_next(a, b);
        out.set_next(b, Halfedge(half_a(m.next(h).idx())));
        out.set_to_vertex(a, mid(h));
        out.set_to_vertex(b, m.to_vertex(h));
    }
    for (Index vi = 0; vi < nv; ++vi) {
        Halfedge h = m.halfedge(Vertex(vi));
        if (h.is_valid()) out.set_halfedge(Vertex(vi), Halfedge(half_a(h.idx())));
    }
    for (Index e = 0; e < ne; ++e) {
        Halfedge h(2 * e);
        if (m.is_boundary(Halfedge(2 * e + 1))) h = Halfedge(2 * e + 1);
        out.set_halfedge(Vertex(nv + e), Halfedge(half_b(h.idx())));
    }
}

/// Texture coordinates and levels of the 1-to-4 split.
void carry_1to4(const HalfedgeMesh& m, const Carried& in, HalfedgeMesh& out, int level) {
    const Index nv = Index(m.vertices_size()), ne = Index(m.edges_size()),
                nf = Index(m.faces_size());
    auto& levels = out.add_vertex_property<int>(kLevelName, 0).vector();
    for (Index v = 0; v < nv; ++v) levels[v] = in.level ? in.level[Vertex(v)] : 0;
    for (Index e = 0; e < ne; ++e) levels[nv + e] = level;
    if (in.vuv) {
        auto uv = out.add_vertex_property<TexCoord>("v:texcoord", TexCoord::Zero());
        for (Index v = 0; v < nv; ++v) uv[Vertex(v)] = in.vuv[Vertex(v)];
        for (Index e = 0; e < ne; ++e)
            uv[Vertex(nv + e)] =
                0.5 * (in.vuv[m.vertex(Edge(e), 0)] + in.vuv[m.vertex(Edge(e), 1)]);
    }
    if (in.huv) {
        auto uv = out.add_halfedge_property<TexCoord>("h:texcoord", TexCoord::Zero());
        for (Index fi = 0; fi < nf; ++fi) {
            Halfedge h[3];
            h[0] = m.halfedge(Face(fi));
            h[1] = m.next(h[0]);
            h[2] = m.next(h[1]);
            TexCoord c[3], md[3];
            for (int k = 0; k < 3; ++k) c[k] = in.huv[h[k]];
            // h_k runs from corner k-1 to corner k.
            for (int k = 0; k < 3; ++k) md[k] = 0.5 * (c[k] + c[(k + 2) % 3]);
            for (int k = 0; k < 3; ++k) {
                const int k1 = (k + 1) % 3;
                Halfedge in_h(2 * (2 * ne + 3 * fi + Index(k)));
                uv[Halfedge(half_b(h[k].idx()))] = c[k];
                uv[Halfedge(half_a(h[k1].idx()))] = md[k1];
                uv[in_h] = md[k];
                uv[Halfedge(in_h.idx() + 1)] = md[k1];
            }
        }
    }
}

/// Loop positions of the refined mesh (even vertices first, then odd ones).
void loop_positions(const HalfedgeMesh& m, std::vector<Point>& p, const Stage& stage) {
    const Index nv = Index(m.vertices_size()), ne = Index(m.edges_size());
    const auto& x = m.positions();
    std::vector<double> beta(8, 0.0);
    auto beta_of = [&](unsigned n) {
        if (n >= beta.size()) {
            std::size_t old = beta.size();
            beta.resize(2 * n + 1);
            for (std::size_t i = old; i < beta.size(); ++i) beta[i] = 0;
        }
        if (beta[n] == 0) {
            const double t = 0.375 + 0.25 * std::cos(2 * kPi / n);
            beta[n] = (0.625 - t * t) / n;
        }
        return beta[n];
    };
    for (Index vi = 0; vi < nv; ++vi) {
        stage.tick(vi);
        Vertex v(vi);
        const Halfedge h0 = m.halfedge(v);
        if (!h0.is_valid()) {
            p[vi] = x[vi];
        } else if (m.is_boundary(h0)) {
            p[vi] = 0.75 * x[vi] +
                    0.125 * (x[m.to_vertex(h0).idx()] + x[m.from_vertex(m.prev(h0)).idx()]);
        } else {
            unsigned n = 0;
            const Point s = ring_sum(m, x, h0, n);
            const double b = beta_of(n);
            p[vi] = (1.0 - n * b) * x[vi] + b * s;
        }
    }
    stage.report(0.6);
    for (Index e = 0; e < ne; ++e) {
        stage.tick(e);
        Halfedge h(2 * e), t(2 * e + 1);
        const Point& a = x[m.to_vertex(t).idx()];
        const Point& b = x[m.to_vertex(h).idx()];
        if (m.is_boundary(h) || m.is_boundary(t)) {
            p[nv + e] = 0.5 * (a + b);
        } else {
            const Point& c = x[m.to_vertex(m.next(h)).idx()];
            const Point& d = x[m.to_vertex(m.next(t)).idx()];
            p[nv + e] = 0.375 * (a + b) + 0.125 * (c + d);
        }
    }
}

/// The corner opposite the wing edge `w` (a halfedge of a face), or its reflection across
/// `w` when twin(w) is a boundary halfedge.
inline Point wing(const HalfedgeMesh& m, const std::vector<Point>& x, Halfedge w) {
    Halfedge t = HalfedgeMesh::twin(w);
    if (!m.is_boundary(t)) return x[m.to_vertex(m.next(t)).idx()];
    return x[m.to_vertex(w).idx()] + x[m.from_vertex(w).idx()] - x[m.to_vertex(m.next(w)).idx()];
}

/// The 8-point butterfly stencil (w = 1/16) on interior halfedge h.
inline Point butterfly8(const HalfedgeMesh& m, const std::vector<Point>& x, Halfedge h) {
    Halfedge t = HalfedgeMesh::twin(h);
    const Point& a = x[m.from_vertex(h).idx()];
    const Point& b = x[m.to_vertex(h).idx()];
    const Point& c = x[m.to_vertex(m.next(h)).idx()];
    const Point& d = x[m.to_vertex(m.next(t)).idx()];
    const Point e = wing(m, x, m.next(h)) + wing(m, x, m.prev(h)) + wing(m, x, m.next(t)) +
                    wing(m, x, m.prev(t));
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
void butterfly_positions(const HalfedgeMesh& m, std::vector<Point>& p, bool modified,
                         const Stage& stage) {
    const Index nv = Index(m.vertices_size()), ne = Index(m.edges_size());
    const auto& x = m.positions();
    std::copy_n(x.begin(), nv, p.begin());  // not memcpy: data() is null for an empty mesh
    // Valences and boundary flags, for the extraordinary rules.
    std::vector<unsigned> valence;
    std::vector<std::uint8_t> boundary;
    ExtraordinaryWeights weights;
    if (modified) {
        valence.assign(nv, 0);
        boundary.assign(nv, 0);
        for (Index hi = 0; hi < 2 * ne; ++hi) ++valence[m.to_vertex(Halfedge(hi)).idx()];
        for (Index vi = 0; vi < nv; ++vi) boundary[vi] = m.is_boundary(Vertex(vi)) ? 1 : 0;
    }
    stage.report(0.5);
    auto extraordinary = [&](Halfedge h) {  // stencil at from_vertex(h), h interior
        const Index a = m.from_vertex(h).idx();
        const unsigned n = valence[a];
        const double* s = weights.of(n);
        Point q = 0.75 * x[a];
        Halfedge g = h;
        for (unsigned j = 0; j < n; ++j, g = m.ccw_rotated(g)) q += s[j] * x[m.to_vertex(g).idx()];
        return q;
    };
    for (Index e = 0; e < ne; ++e) {
        stage.tick(e);
        Halfedge h(2 * e), t(2 * e + 1);
        Point q;
        if (m.is_boundary(h) || m.is_boundary(t)) {
            Halfedge bh = m.is_boundary(h) ? h : t;  // boundary halfedge a -> b
            const Point& a = x[m.from_vertex(bh).idx()];
            const Point& b = x[m.to_vertex(bh).idx()];
            const Point& a0 = x[m.from_vertex(m.prev(bh)).idx()];
            const Point& b1 = x[m.to_vertex(m.next(bh)).idx()];
            q = 0.5625 * (a + b) - 0.0625 * (a0 + b1);
        } else if (modified) {
            const Index a = m.from_vertex(h).idx(), b = m.to_vertex(h).idx();
            const bool ea = !boundary[a] && valence[a] != 6;
            const bool eb = !boundary[b] && valence[b] != 6;
            if (ea && eb)
                q = 0.5 * (extraordinary(h) + extraordinary(t));
            else if (ea)
                q = extraordinary(h);
            else if (eb)
                q = extraordinary(t);
            else
                q = butterfly8(m, x, h);
        } else {
            q = butterfly8(m, x, h);
        }
        p[nv + e] = q;
    }
}

SubdivisionLevel refine_1to4(const HalfedgeMesh& m, SubdivisionScheme scheme, int level,
                             const Stage& stage) {
    SubdivisionLevel out;
    const Carried in = carried_of(m, level);
    build_1to4(m, out.mesh, stage);
    stage.progress.check_cancelled();
    auto& p = out.mesh.positions();
    if (scheme == SubdivisionScheme::Loop)
        loop_positions(m, p, stage);
    else
        butterfly_positions(m, p, scheme == SubdivisionScheme::ModifiedButterfly, stage);
    stage.progress.check_cancelled();
    carry_1to4(m, in, out.mesh, level);
    // Morph: even vertices start where they were, odd ones at their edge's midpoint.
    const Index nv = Index(m.vertices_size()), ne = Index(m.edges_size());
    out.correspondence.kind = MorphCorrespondence::Kind::FromEarlier;
    auto& start = out.correspondence.positions;
    start.resize(std::size_t(nv) + ne);
    const auto& x = m.positions();
    for (Index v = 0; v < nv; ++v) start[v] = x[v];
    for (Index e = 0; e < ne; ++e)
        start[nv + e] = 0.5 * (x[m.vertex(Edge(e), 0).idx()] + x[m.vertex(Edge(e), 1).idx()]);
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
SubdivisionLevel refine_sqrt3(const HalfedgeMesh& m, bool even_step, int level,
                              const Stage& stage) {
    const Index nv = Index(m.vertices_size()), ne = Index(m.edges_size()),
                nf = Index(m.faces_size());
    const auto& x = m.positions();
    // Corner ids of interior halfedges and numbers of boundary halfedges.
    std::vector<Index> id(2 * std::size_t(ne));
    Index nb = 0;
    for (Index fi = 0; fi < nf; ++fi) {
        Halfedge h = m.halfedge(Face(fi));
        for (Index k = 0; k < 3; ++k, h = m.next(h)) id[h.idx()] = 3 * fi + k;
    }
    for (Index hi = 0; hi < 2 * ne; ++hi)
        if (m.is_boundary(Halfedge(hi))) id[hi] = nb++;
    if (!even_step) nb = 0;  // boundary edges are not split in odd steps
    stage.report(0.1);

    SubdivisionLevel result;
    HalfedgeMesh& out = result.mesh;
    out.resize_elements(std::size_t(nv) + nf + 2 * std::size_t(nb),
                        std::size_t(ne) + 3 * std::size_t(nf) + 4 * std::size_t(nb),
                        3 * std::size_t(nf) + 2 * std::size_t(nb));
    const Index eb = ne + 3 * nf;  // first edge of the boundary splits
    auto s_out = [&](Halfedge h) { return Halfedge(2 * (ne + id[h.idx()])); };
    auto s_in = [&](Halfedge h) { return Halfedge(2 * (ne + id[h.idx()]) + 1); };
    auto split_edge = [&](Halfedge boundary, Index which) {  // 0: p-q, 1: q-b, 2: p-c, 3: q-c
        return Halfedge(2 * (eb + 4 * id[boundary.idx()] + which));
    };
    // Boundary split vertices of boundary halfedge t (b -> a): P0 near b, P1 near a.
    auto split_vertex = [&](Halfedge t, Index which) {
        return Vertex(nv + nf + 2 * id[t.idx()] + which);
    };
    auto triangle = [&](Face f, Halfedge h0, Vertex v0, Halfedge h1, Vertex v1, Halfedge h2,
                        Vertex v2) {
        out.set_next(h0, h1);
        out.set_next(h1, h2);
        out.set_next(h2, h0);
        out.set_face(h0, f);
        out.set_face(h1, f);
        out.set_face(h2, f);
        out.set_to_vertex(h0, v0);
        out.set_to_vertex(h1, v1);
        out.set_to_vertex(h2, v2);
        out.set_halfedge(f, h0);
    };
    for (Index fi = 0; fi < nf; ++fi) {
        stage.tick(fi);
        const Vertex c(nv + fi);
        Halfedge h = m.halfedge(Face(fi));
        out.set_halfedge(c, s_in(h));
        for (int k = 0; k < 3; ++k, h = m.next(h)) {
            const Halfedge t = HalfedgeMesh::twin(h);
            const Vertex a = m.from_vertex(h), b = m.to_vertex(h);
            const Face own(id[h.idx()]);
            if (!m.is_boundary(t)) {
                // (a, c_g, c_f): the flipped edge is h itself, from c_g to c_f.
                const Vertex cg(nv + m.face(t).idx());
                triangle(own, s_out(m.next(t)), cg, h, c, s_in(h), a);
            } else if (!even_step) {
                triangle(own, h, b, s_out(m.next(h)), c, s_in(h), a);
            } else {
                const Vertex p = split_vertex(t, 1), q = split_vertex(t, 0);
                const Index j = id[t.idx()];
                triangle(own, h, p, split_edge(t, 2), c, s_in(h), a);
                triangle(Face(3 * nf + 2 * j), split_edge(t, 0), q, split_edge(t, 3), c,
                         Halfedge(split_edge(t, 2).idx() + 1), p);
                triangle(Face(3 * nf + 2 * j + 1), split_edge(t, 1), b, s_out(m.next(h)), c,
                         Halfedge(split_edge(t, 3).idx() + 1), q);
            }
        }
    }
    stage.report(0.4);
    // Boundary loops.
    for (Index hi = 0; hi < 2 * ne; ++hi) {
        const Halfedge t(hi);
        if (!m.is_boundary(t)) continue;
        const Halfedge n = m.next(t);
        if (!even_step) {
            out.set_next(t, n);
            out.set_to_vertex(t, m.to_vertex(t));
            continue;
        }
        // b -> q -> p -> a, then on to the first piece of the next boundary halfedge.
        const Halfedge bq(split_edge(t, 1).idx() + 1), qp(split_edge(t, 0).idx() + 1);
        out.set_next(bq, qp);
        out.set_next(qp, t);
        out.set_next(t, Halfedge(split_edge(n, 1).idx() + 1));
        out.set_to_vertex(bq, split_vertex(t, 0));
        out.set_to_vertex(qp, split_vertex(t, 1));
        out.set_to_vertex(t, m.to_vertex(t));
        out.set_halfedge(split_vertex(t, 0), qp);
        out.set_halfedge(split_vertex(t, 1), t);
    }
    for (Index vi = 0; vi < nv; ++vi) {
        const Halfedge h = m.halfedge(Vertex(vi));
        if (!h.is_valid()) continue;
        if (!m.is_boundary(h))
            out.set_halfedge(Vertex(vi), s_out(h));
        else
            out.set_halfedge(Vertex(vi), even_step ? Halfedge(split_edge(h, 1).idx() + 1) : h);
    }
    stage.progress.check_cancelled();
    stage.report(0.5);

    // Positions and morph start positions.
    auto& p = out.positions();
    auto& start = result.correspondence.positions;
    result.correspondence.kind = MorphCorrespondence::Kind::FromEarlier;
    start.resize(p.size());
    std::vector<double> alpha;
    for (Index vi = 0; vi < nv; ++vi) {
        stage.tick(vi);
        const Vertex v(vi);
        const Halfedge h0 = m.halfedge(v);
        start[vi] = x[vi];
        if (!h0.is_valid()) {
            p[vi] = x[vi];
        } else if (m.is_boundary(h0)) {
            p[vi] = even_step ? Point((4.0 * x[m.from_vertex(m.prev(h0)).idx()] + 19.0 * x[vi] +
                                       4.0 * x[m.to_vertex(h0).idx()]) /
                                      27.0)
                              : x[vi];
        } else {
            unsigned n = 0;
            const Point s = ring_sum(m, x, h0, n);
            if (n >= alpha.size()) alpha.resize(n + 1, -1.0);
            if (alpha[n] < 0) alpha[n] = (4.0 - 2.0 * std::cos(2 * kPi / n)) / 9.0;
            p[vi] = (1.0 - alpha[n]) * x[vi] + (alpha[n] / n) * s;
        }
    }
    for (Index fi = 0; fi < nf; ++fi) {
        stage.tick(fi);
        const auto c = m.face_vertices(Face(fi));
        p[nv + fi] = (x[c[0].idx()] + x[c[1].idx()] + x[c[2].idx()]) / 3.0;
        start[nv + fi] = p[nv + fi];
    }
    if (even_step) {
        for (Index hi = 0; hi < 2 * ne; ++hi) {
            const Halfedge t(hi);
            if (!m.is_boundary(t)) continue;
            // Along t: p0 = from(prev t), p1 = from(t), p2 = to(t), p3 = to(next t).
            const Point& p0 = x[m.from_vertex(m.prev(t)).idx()];
            const Point& p1 = x[m.from_vertex(t).idx()];
            const Point& p2 = x[m.to_vertex(t).idx()];
            const Point& p3 = x[m.to_vertex(m.next(t)).idx()];
            const Index i0 = split_vertex(t, 0).idx(), i1 = split_vertex(t, 1).idx();
            p[i0] = (p0 + 16.0 * p1 + 10.0 * p2) / 27.0;
            p[i1] = (10.0 * p1 + 16.0 * p2 + p3) / 27.0;
            start[i0] = (2.0 * p1 + p2) / 3.0;
            start[i1] = (p1 + 2.0 * p2) / 3.0;
        }
    }
    stage.progress.check_cancelled();
    stage.report(0.8);

    // Levels and texture coordinates.
    const Carried in = carried_of(m, level);
    auto& levels = out.add_vertex_property<int>(kLevelName, level).vector();
    for (Index v = 0; v < nv; ++v) levels[v] = in.level ? in.level[Vertex(v)] : 0;
    if (in.vuv) {
        auto uv = out.add_vertex_property<TexCoord>("v:texcoord", TexCoord::Zero());
        for (Index v = 0; v < nv; ++v) uv[Vertex(v)] = in.vuv[Vertex(v)];
        for (Index fi = 0; fi < nf; ++fi) {
            const auto c = m.face_vertices(Face(fi));
            uv[Vertex(nv + fi)] = (in.vuv[c[0]] + in.vuv[c[1]] + in.vuv[c[2]]) / 3.0;
        }
        for (Index hi = 0; even_step && hi < 2 * ne; ++hi) {
            const Halfedge t(hi);
            if (!m.is_boundary(t)) continue;
            const TexCoord &u1 = in.vuv[m.from_vertex(t)], &u2 = in.vuv[m.to_vertex(t)];
            uv[split_vertex(t, 0)] = (2.0 * u1 + u2) / 3.0;
            uv[split_vertex(t, 1)] = (u1 + 2.0 * u2) / 3.0;
        }
    }
    if (in.huv) {
        // Corner uvs come from the old face each new corner lies in; a new triangle that
        // straddles a flipped edge takes its old corner's uv from face(h) and the far
        // centroid's from its own face.
        auto uv = out.add_halfedge_property<TexCoord>("h:texcoord", TexCoord::Zero());
        std::vector<TexCoord> centre(nf);
        for (Index fi = 0; fi < nf; ++fi) {
            const Halfedge h = m.halfedge(Face(fi));
            centre[fi] = (in.huv[h] + in.huv[m.next(h)] + in.huv[m.prev(h)]) / 3.0;
        }
        for (Index fi = 0; fi < nf; ++fi) {
            Halfedge h = m.halfedge(Face(fi));
            for (int k = 0; k < 3; ++k, h = m.next(h)) {
                const Halfedge t = HalfedgeMesh::twin(h);
                const TexCoord& ua = in.huv[m.prev(h)];
                const TexCoord& ub = in.huv[h];
                uv[s_in(h)] = ua;
                if (!m.is_boundary(t)) {
                    uv[h] = centre[fi];
                    uv[s_out(m.next(t))] = centre[m.face(t).idx()];
                } else if (!even_step) {
                    uv[h] = ub;
                    uv[s_out(m.next(h))] = centre[fi];
                } else {
                    const TexCoord up = (2.0 * ua + ub) / 3.0, uq = (ua + 2.0 * ub) / 3.0;
                    uv[h] = up;
                    uv[split_edge(t, 2)] = centre[fi];
                    uv[split_edge(t, 0)] = uq;
                    uv[split_edge(t, 3)] = centre[fi];
                    uv[Halfedge(split_edge(t, 2).idx() + 1)] = up;
                    uv[split_edge(t, 1)] = ub;
                    uv[s_out(m.next(h))] = centre[fi];
                    uv[Halfedge(split_edge(t, 3).idx() + 1)] = uq;
                }
            }
        }
    }
    stage.report(1.0);
    return result;
}

}  // namespace

const char* scheme_name(SubdivisionScheme scheme) {
    switch (scheme) {
        case SubdivisionScheme::Loop:
            return "loop";
        case SubdivisionScheme::Sqrt3:
            return "sqrt3";
        case SubdivisionScheme::Butterfly:
            return "butterfly";
        case SubdivisionScheme::ModifiedButterfly:
            return "modified-butterfly";
    }
    return "loop";
}

SubdivisionScheme parse_scheme(const std::string& name) {
    for (SubdivisionScheme s : {SubdivisionScheme::Loop, SubdivisionScheme::Sqrt3,
                                SubdivisionScheme::Butterfly, SubdivisionScheme::ModifiedButterfly})
        if (name == scheme_name(s)) return s;
    throw InvalidArgument("subdivision scheme '" + name +
                          "' unknown: use loop, sqrt3, butterfly or modified-butterfly");
}

namespace {

/// Refuses a mesh where two faces have the same three vertices (a closed two-triangle
/// "pillow", possibly part of a larger mesh after non-manifold repairs): the 1-to-4 split
/// would join two of its edge midpoints twice and Sqrt3 would join its two centroids three
/// times, i.e. the result would have double edges.
void check_no_pillows(const HalfedgeMesh& m, int iteration) {
    std::vector<std::array<Index, 4>> triples;  // sorted vertices, then the face
    triples.reserve(m.n_faces());
    for (Face f : m.faces()) {
        std::array<Index, 4> t{};
        const Halfedge h = m.halfedge(f);
        t[0] = Index(m.to_vertex(h).idx());
        t[1] = Index(m.to_vertex(m.next(h)).idx());
        t[2] = Index(m.to_vertex(m.next(m.next(h))).idx());
        std::sort(t.begin(), t.begin() + 3);
        t[3] = Index(f.idx());
        triples.push_back(t);
    }
    std::sort(triples.begin(), triples.end());
    for (std::size_t i = 1; i < triples.size(); ++i) {
        const auto& a = triples[i - 1];
        const auto& b = triples[i];
        if (a[0] == b[0] && a[1] == b[1] && a[2] == b[2])
            throw TopologyError(
                "subdivide: faces " + std::to_string(a[3]) + " and " + std::to_string(b[3]) +
                " have the same three vertices (" + std::to_string(a[0]) + ", " +
                std::to_string(a[1]) + ", " + std::to_string(a[2]) +
                "), a closed two-triangle component; subdividing it would create double "
                "edges" +
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
    for (Vertex v : m.vertices())
        if (!m.position(v).allFinite()) refuse("position", v.idx());
    if (const auto p = m.get_vertex_property<TexCoord>("v:texcoord"))
        for (Vertex v : m.vertices())
            if (!p[v].allFinite()) refuse("texture coordinate", v.idx());
    if (const auto p = m.get_halfedge_property<TexCoord>("h:texcoord"))
        for (Halfedge h : m.halfedges())
            if (!p[h].allFinite()) refuse("corner texture coordinate", m.to_vertex(h).idx());
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
    progress.check_cancelled();
    HalfedgeMesh collected;
    const HalfedgeMesh* current = &mesh;
    if (mesh.has_garbage()) {
        collected = mesh;
        collected.garbage_collection();
        current = &collected;
    }
    SubdivisionResult result;
    result.levels.reserve(std::size_t(options.iterations));
    const double span = 1.0 / options.iterations;
    for (int it = 1; it <= options.iterations; ++it) {
        progress.check_cancelled();
        check_no_pillows(*current, it);
        Stage stage{progress, (it - 1) * span, span};
        stage.report(0);
        if (sqrt3)
            result.levels.push_back(refine_sqrt3(*current, it % 2 == 0, it, stage));
        else
            result.levels.push_back(refine_1to4(*current, options.scheme, it, stage));
        current = &result.levels.back().mesh;
        check_finite_level(*current, options.scheme, it);
    }
    progress.check_cancelled();
    progress.report(1.0, "subdividing");
    result.ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    return result;
}

}  // namespace trilab
