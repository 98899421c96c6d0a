// Crease rules of Sqrt3 and the butterflies: see subdivision_creases.h.
#include "core/algorithms/subdivision_creases.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include "core/errors.h"
#include "core/features.h"
#include "core/mesh_builder.h"

namespace trilab {
namespace subdivision_detail {

namespace {

constexpr double kPi = 3.14159265358979323846;

using Arrays = MeshArrays;

/// The sharpness an edge acts with: +inf on the boundary, its own (0 without the property).
inline float edge_sharpness(const Arrays& m, const float* sharp, Index e) {
    if (m.boundary_edge(e)) return kInfiniteSharpness;
    return sharp ? sharp[e] : 0.0f;
}

/// The crease edges at each vertex (sharpness > 0 or boundary) with the parent's and the
/// child's view (child_sharpness() > 0): counts, the first two neighbours along them, the
/// semi-sharp transition weight, the valence and the neighbour sum.
struct VertexCreases {
    unsigned valence = 0;
    Point ring_sum = Point::Zero();
    unsigned parent = 0, child = 0;
    Index parent_nb[2] = {kInvalidIndex, kInvalidIndex};
    Index child_nb[2] = {kInvalidIndex, kInvalidIndex};
    float transition_sum = 0.0f;
    unsigned transitions = 0;
};

enum class Rule { Smooth, Dart, Crease, Corner };
inline Rule rule_of(unsigned creases, bool tagged) {
    if (tagged || creases > 2) return Rule::Corner;
    return creases == 2 ? Rule::Crease : (creases == 1 ? Rule::Dart : Rule::Smooth);
}

std::vector<VertexCreases> gather_creases(const Arrays& m, const float* sharp) {
    std::vector<VertexCreases> vc(m.nv);
    for (Index e = 0; e < m.ne; ++e) {
        const Index a = m.from_i(2 * e), b = m.to_i(2 * e);
        VertexCreases& A = vc[a];
        VertexCreases& B = vc[b];
        ++A.valence;
        ++B.valence;
        A.ring_sum += m.x[b];
        B.ring_sum += m.x[a];
        const float s = edge_sharpness(m, sharp, e);
        if (!(s > 0.0f)) continue;
        auto add = [&](VertexCreases& v, Index other) {
            if (v.parent < 2) v.parent_nb[v.parent] = other;
            ++v.parent;
            if (s <= 1.0f) {
                v.transition_sum += s;
                ++v.transitions;
            }
            if (child_sharpness(s) > 0.0f) {
                if (v.child < 2) v.child_nb[v.child] = other;
                ++v.child;
            }
        };
        add(A, b);
        add(B, a);
    }
    return vc;
}

/// The crease neighbour of vertex v beyond `other` along v's two crease edges, or the
/// reflection 2v - other where v is not a crease vertex (a curve end: corner, dart).
inline Point beyond(const Arrays& m, const std::vector<VertexCreases>& vc,
                    const std::uint8_t* corner, Index v, Index other) {
    const VertexCreases& c = vc[v];
    const bool tagged = corner && corner[v] != 0;
    if (rule_of(c.parent, tagged) == Rule::Crease) {
        const Index w = c.parent_nb[0] == other ? c.parent_nb[1] : c.parent_nb[0];
        return m.x[w];
    }
    return 2.0 * m.x[v] - m.x[other];
}

// ---------------------------------------------------------------------------------------
// Sqrt3
// ---------------------------------------------------------------------------------------

/// The Sqrt3 position of old vertex v under `rule` with crease neighbours `nb`.
Point sqrt3_rule(const Arrays& m, const VertexCreases& c, Index v, Rule r, const Index nb[2],
                 bool even_step) {
    const Point& x = m.x[v];
    switch (r) {
        case Rule::Smooth:
        case Rule::Dart: {
            const unsigned k = c.valence;
            const double alpha = (4.0 - 2.0 * std::cos(2 * kPi / k)) / 9.0;
            return (1.0 - alpha) * x + (alpha / k) * c.ring_sum;
        }
        case Rule::Crease:
            return even_step ? Point((4.0 * m.x[nb[0]] + 19.0 * x + 4.0 * m.x[nb[1]]) / 27.0) : x;
        case Rule::Corner:
            break;
    }
    return x;
}

/// The position and stencil of old vertex v of a Sqrt3 step with creases.
Point sqrt3_even(const Arrays& m, const std::vector<VertexCreases>& vc, const std::uint8_t* corner,
                 Index v, bool even_step, int& stencil) {
    const VertexCreases& c = vc[v];
    const bool tagged = corner && corner[v] != 0;
    const Rule parent = rule_of(c.parent, tagged), child = rule_of(c.child, tagged);
    const Point pp = sqrt3_rule(m, c, v, parent, c.parent_nb, even_step);
    if (parent == child || parent == Rule::Smooth || parent == Rule::Dart) {
        bool border = false;  // a crease made of boundary edges only: the boundary rule
        if (parent == Rule::Crease) border = m.boundary(m.vh[v].idx()) && c.parent == 2 && !tagged;
        switch (parent) {
            case Rule::Smooth:
                stencil = int(SubdivisionStencil::EvenRelaxed);
                break;
            case Rule::Dart:
                stencil = int(SubdivisionStencil::EvenDart);
                break;
            case Rule::Crease:
                stencil = int(border ? (even_step ? SubdivisionStencil::EvenBoundary
                                                  : SubdivisionStencil::EvenKept)
                                     : SubdivisionStencil::EvenCreaseCurve);
                break;
            case Rule::Corner:
                stencil = int(tagged ? SubdivisionStencil::EvenTaggedCorner
                                     : SubdivisionStencil::EvenCorner);
                break;
        }
        return pp;
    }
    stencil = int(SubdivisionStencil::EvenSemiSharp);
    double w = c.transitions ? double(c.transition_sum) / c.transitions : 0.0;
    w = std::min(w, 1.0);
    return w * pp + (1.0 - w) * sqrt3_rule(m, c, v, child, c.child_nb, even_step);
}

/// The faces of a Sqrt3 step with creases, into `soup`: per face halfedge h = a -> b of face
/// f (centroid c): across a smooth edge the flipped edge's triangle (a, c_g, c); along a
/// crease (a, b, c) in odd steps, the fan (a, p, c), (p, q, c), (q, b, c) over its pieces in
/// even steps.
void sqrt3_crease_faces(const Arrays& m, const std::vector<std::uint8_t>& crease,
                        const std::vector<Index>& split, bool even_step, PolygonSoup& soup) {
    const Index nv = m.nv, nf = m.nf;
    soup.corners.reserve(9 * std::size_t(nf));
    auto tri = [&](Index i, Index j, Index k) {
        soup.corners.push_back(i);
        soup.corners.push_back(j);
        soup.corners.push_back(k);
    };
    for (Index f = 0; f < nf; ++f) {
        Index h = m.fh[f].idx();
        const Index c = nv + f;
        for (int k = 0; k < 3; ++k, h = m.next_i(h)) {
            const Index e = h >> 1, a = m.from_i(h), b = m.to_i(h);
            if (!crease[e]) {
                tri(a, nv + m.face[h ^ 1u].idx(), c);
            } else if (!even_step) {
                tri(a, b, c);
            } else {
                const bool forward = (h & 1u) == 0;  // h = 2e: a is split[e]'s end
                const Index s0 = forward ? split[e] : split[e] + 1;
                const Index s1 = forward ? split[e] + 1 : split[e];
                tri(a, s0, c);
                tri(s0, s1, c);
                tri(s1, b, c);
            }
        }
    }
    soup.face_offsets.resize(soup.corners.size() / 3 + 1);
    for (std::size_t i = 0; i < soup.face_offsets.size(); ++i) soup.face_offsets[i] = 3 * i;
}

/// The children's features of a Sqrt3 step with creases, into `soup`: the interior crease
/// edges (or their pieces) with child_sharpness(), the old vertices' corner tags.
void sqrt3_crease_features(const Arrays& m, const float* sharp, const std::uint8_t* corner,
                           const std::vector<std::uint8_t>& crease, const std::vector<Index>& split,
                           bool even_step, std::size_t n_out, PolygonSoup& soup) {
    const Index nv = m.nv, ne = m.ne;
    for (Index e = 0; sharp && e < ne; ++e) {
        if (!crease[e] || m.boundary_edge(e)) continue;
        const float s = child_sharpness(sharp[e]);
        if (!(s > 0.0f)) continue;
        const Index a = m.from_i(2 * e), b = m.to_i(2 * e);
        if (!even_step) {
            soup.sharp_edges.push_back({a, b, s});
        } else {
            soup.sharp_edges.push_back({a, split[e], s});
            soup.sharp_edges.push_back({split[e], split[e] + 1, s});
            soup.sharp_edges.push_back({split[e] + 1, b, s});
        }
    }
    if (corner) {
        soup.corner_tags.assign(n_out, 0);
        std::copy_n(corner, nv, soup.corner_tags.begin());
    }
}

}  // namespace

Sqrt3CreaseStep sqrt3_creased_step(const HalfedgeMesh& mesh, bool even_step, Progress& progress) {
    const Arrays m(mesh);
    const Index nv = m.nv, ne = m.ne, nf = m.nf;
    const auto sharp_prop = mesh.get_edge_property<float>(kSharpnessProperty);
    const auto corner_prop = mesh.get_vertex_property<std::uint8_t>(kCornerProperty);
    const float* sharp = sharp_prop ? sharp_prop.vector().data() : nullptr;
    const std::uint8_t* corner = corner_prop ? corner_prop.vector().data() : nullptr;
    const std::vector<VertexCreases> vc = gather_creases(m, sharp);
    progress.check_cancelled();

    // Crease edges and their split points (even steps): split[e] = first of the two, the one
    // near from_vertex(2e); kInvalidIndex where e is no crease.
    std::vector<Index> split(ne, kInvalidIndex);
    std::vector<std::uint8_t> crease(ne, 0);
    Index n_split = 0;
    for (Index e = 0; e < ne; ++e) {
        if (!(edge_sharpness(m, sharp, e) > 0.0f)) continue;
        crease[e] = 1;
        if (even_step) split[e] = nv + nf + 2 * n_split++;
    }
    const std::size_t n_out = std::size_t(nv) + nf + 2 * std::size_t(n_split);

    Sqrt3CreaseStep out;
    PolygonSoup soup;
    soup.positions.resize(n_out);
    out.start.resize(n_out);
    out.stencil.assign(n_out, 0);
    out.parents.assign(n_out, SubdivisionParents::Constant(kInvalidIndex));
    Point* p = soup.positions.data();
    for (Index v = 0; v < nv; ++v) {
        out.start[v] = m.x[v];
        out.parents[v] = SubdivisionParents(v, kInvalidIndex, kInvalidIndex);
        if (!m.vh[v].is_valid()) {
            p[v] = m.x[v];
            out.stencil[v] = int(SubdivisionStencil::EvenKept);
        } else {
            p[v] = sqrt3_even(m, vc, corner, v, even_step, out.stencil[v]);
        }
    }
    for (Index f = 0; f < nf; ++f) {
        const Index h0 = m.fh[f].idx(), h1 = m.next_i(h0), h2 = m.next_i(h1);
        const Index a = m.to_i(h0), b = m.to_i(h1), c = m.to_i(h2);
        p[nv + f] = out.start[nv + f] = (m.x[a] + m.x[b] + m.x[c]) / 3.0;
        out.stencil[nv + f] = int(SubdivisionStencil::OddFace);
        out.parents[nv + f] = SubdivisionParents(a, b, c);
    }
    for (Index e = 0; e < ne; ++e) {
        if (split[e] == kInvalidIndex) continue;
        const Index a = m.from_i(2 * e), b = m.to_i(2 * e), i0 = split[e], i1 = i0 + 1;
        const Point a0 = beyond(m, vc, corner, a, b), b1 = beyond(m, vc, corner, b, a);
        p[i0] = (a0 + 16.0 * m.x[a] + 10.0 * m.x[b]) / 27.0;
        p[i1] = (10.0 * m.x[a] + 16.0 * m.x[b] + b1) / 27.0;
        out.start[i0] = (2.0 * m.x[a] + m.x[b]) / 3.0;
        out.start[i1] = (m.x[a] + 2.0 * m.x[b]) / 3.0;
        const auto st = m.boundary_edge(e) ? SubdivisionStencil::OddBoundarySplit
                                           : SubdivisionStencil::OddCreaseSplit;
        out.stencil[i0] = out.stencil[i1] = int(st);
        out.parents[i0] = SubdivisionParents(a, b, kInvalidIndex);  // the nearer end first
        out.parents[i1] = SubdivisionParents(b, a, kInvalidIndex);
    }
    progress.check_cancelled();

    sqrt3_crease_faces(m, crease, split, even_step, soup);
    sqrt3_crease_features(m, sharp, corner, crease, split, even_step, n_out, soup);
    LoadReport report;
    out.mesh = build_mesh(std::move(soup), report);
    if (out.mesh.vertices_size() != n_out || report.vertex_copies_added != 0 ||
        report.degenerate_faces_dropped != 0 || report.detached_faces != 0)
        throw InvalidArgument(
            "subdivide: the Sqrt3 step along the creases did not give a manifold mesh (a crease "
            "on a non-manifold junction?)");
    if (!out.mesh.get_edge_property<float>(kSharpnessProperty))
        sharpness_property(out.mesh);  // all 0: the features end here, the property stays
    return out;
}

// ---------------------------------------------------------------------------------------
// Butterflies
// ---------------------------------------------------------------------------------------

namespace {

/// The corner opposite wing halfedge w (a face halfedge), or its reflection across w where
/// w's edge is a boundary or a crease (sharpness > 0).
inline Point wing_across(const Arrays& m, const float* sharp, Index w) {
    const Index t = w ^ 1u;
    const bool crease = m.boundary(t) || (sharp && sharp[w >> 1] > 0.0f);
    if (!crease) return m.x[m.to_i(m.next_i(t))];
    return m.x[m.to_i(w)] + m.x[m.from_i(w)] - m.x[m.to_i(m.next_i(w))];
}

/// The 8-point stencil on interior halfedge h with wings reflected across creases.
inline Point butterfly8_creased(const Arrays& m, const float* sharp, Index h) {
    const Index t = h ^ 1u;
    const Point& a = m.x[m.from_i(h)];
    const Point& b = m.x[m.to_i(h)];
    const Point& c = m.x[m.to_i(m.next_i(h))];
    const Point& d = m.x[m.to_i(m.next_i(t))];
    const Point e = wing_across(m, sharp, m.next_i(h)) + wing_across(m, sharp, m.prev_i(h)) +
                    wing_across(m, sharp, m.next_i(t)) + wing_across(m, sharp, m.prev_i(t));
    return 0.5 * (a + b) + 0.125 * (c + d) - 0.0625 * e;
}

/// Weight s_j of the Modified Butterfly's extraordinary stencil (as subdivision.cpp).
double extraordinary_weight(unsigned n, unsigned j) {
    if (n == 3) return j == 0 ? 5.0 / 12 : -1.0 / 12;
    if (n == 4) return j == 0 ? 0.375 : (j == 2 ? -0.125 : 0.0);
    const double a = 2 * kPi * j / n;
    return (0.25 + std::cos(a) + 0.5 * std::cos(2 * a)) / n;
}

/// The extraordinary stencil at from_vertex(h) (an interior vertex with a closed ring).
Point extraordinary_at(const Arrays& m, Index h, unsigned n) {
    const Index a = m.from_i(h);
    Point q = 0.75 * m.x[a];
    Index g = h;
    for (unsigned j = 0; j < n; ++j, g = m.prev_i(g) ^ 1u)
        q += extraordinary_weight(n, j) * m.x[m.to_i(g)];
    return q;
}

}  // namespace

void butterfly_positions_creased(const MeshArrays& m, const float* sharp,
                                 const std::uint8_t* corner, bool modified, Point* p) {
    const Index nv = m.nv, ne = m.ne;
    std::copy_n(m.x, nv, p);
    const std::vector<VertexCreases> vc = gather_creases(m, sharp);
    // Vertices where the extraordinary stencil applies: interior, no crease edge, no tag,
    // valence other than 6.
    auto extraordinary = [&](Index v) {
        const Halfedge h = m.vh[v];
        const bool tagged = corner && corner[v] != 0;
        return modified && h.is_valid() && !m.boundary(h.idx()) && vc[v].parent == 0 && !tagged &&
               vc[v].valence != 6;
    };
    auto smooth = [&](Index e) -> Point {
        const Index h = 2 * e, t = h + 1;
        const Index a = m.from_i(h), b = m.to_i(h);
        const bool ea = extraordinary(a), eb = extraordinary(b);
        if (ea && eb)
            return 0.5 *
                   (extraordinary_at(m, h, vc[a].valence) + extraordinary_at(m, t, vc[b].valence));
        if (ea) return extraordinary_at(m, h, vc[a].valence);
        if (eb) return extraordinary_at(m, t, vc[b].valence);
        return butterfly8_creased(m, sharp, h);
    };
    for (Index e = 0; e < ne; ++e) {
        const float s = edge_sharpness(m, sharp, e);
        if (!(s > 0.0f)) {
            p[nv + e] = smooth(e);
            continue;
        }
        const Index a = m.from_i(2 * e), b = m.to_i(2 * e);
        const Point a0 = beyond(m, vc, corner, a, b), b1 = beyond(m, vc, corner, b, a);
        const Point four = 0.5625 * (m.x[a] + m.x[b]) - 0.0625 * (a0 + b1);
        if (s > 1.0f) {
            p[nv + e] = four;
        } else {
            const double w = s;
            p[nv + e] = w * four + (1.0 - w) * smooth(e);
        }
    }
}

}  // namespace subdivision_detail
}  // namespace trilab
