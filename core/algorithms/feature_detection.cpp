#include "core/algorithms/feature_detection.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <utility>

#include "core/errors.h"
#include "core/number_text.h"
#include "core/two_threads.h"

namespace trilab {

namespace {

constexpr double kRadToDeg = 57.295779513082320876798154814105;
constexpr int kPlateauMinAngle = 5;    // thresholds below this are not plateau candidates
constexpr int kPlateauMinWidth = 15;   // degrees
constexpr double kPlateauDrop = 0.05;  // at most this fraction of the edges lost across it

/// cos(k degrees) for k = 0 .. kAngleBins: an angle a between unit normals with dot product d
/// is >= k degrees exactly when d <= cos_deg[k], so the histogram bin is found by comparisons
/// (no acos per edge; almost every edge of a smooth mesh is in the first bins).
struct CosineBins {
    double cos_deg[kAngleBins + 1];
    CosineBins() {
        for (std::size_t k = 0; k <= kAngleBins; ++k) cos_deg[k] = std::cos(double(k) / kRadToDeg);
    }
    std::size_t bin(double d) const {
        std::size_t k = 0;
        while (k + 1 < kAngleBins && d <= cos_deg[k + 1]) ++k;
        return k;
    }
};

/// Unit face normals in single precision (zero for a degenerate or deleted face), one per face
/// storage index: half the memory traffic of doubles, and a float dot product still tells
/// angles apart to about 0.03 degrees near 0 and far better elsewhere (the bins are whole
/// degrees). The array is not zero-filled first: every entry is written once.
std::unique_ptr<Eigen::Vector3f[]> unit_face_normals(const HalfedgeMesh& mesh) {
    const std::size_t nf = mesh.faces_size();
    std::unique_ptr<Eigen::Vector3f[]> n(new Eigen::Vector3f[nf]);
    const bool garbage = mesh.has_garbage();
    const Vertex* to = mesh.halfedge_to_array().data();
    const Halfedge* next = mesh.halfedge_next_array().data();
    const Halfedge* fh = mesh.face_halfedge_array().data();
    const Point* x = mesh.positions().data();
    on_two_threads(worth_two_threads(nf), [&](int part) {
        const HalfRange r = half_of(nf, part);
        for (std::size_t i = r.begin; i < r.end; ++i) {
            n[i] = Eigen::Vector3f::Zero();
            if (garbage && mesh.is_deleted(Face(static_cast<Index>(i)))) continue;
            const Index h0 = fh[i].idx(), h1 = next[h0].idx(), h2 = next[h1].idx();
            const Point& a = x[to[h0].idx()];
            const Vector3 c = (x[to[h1].idx()] - a).cross(x[to[h2].idx()] - a);
            const double len = c.norm();
            if (len > 0 && std::isfinite(len)) n[i] = (c / len).cast<float>();
        }
    });
    return n;
}

/// The histogram of the interior edges' dihedral angles; with `flags`, also each edge's flag
/// (1 for an interior edge of angle >= angle_deg, or a boundary edge when `boundary`) and the
/// list of the flagged edges, ascending.
void edge_angles(const HalfedgeMesh& mesh, AngleHistogram& h, double angle_deg, bool boundary,
                 std::vector<std::uint8_t>* flags, std::vector<Index>* flagged_list = nullptr) {
    const std::unique_ptr<Eigen::Vector3f[]> normals = unit_face_normals(mesh);
    const std::size_t ne = mesh.edges_size();
    if (flags) flags->assign(ne, 0);
    const bool garbage = mesh.has_garbage();
    const Face* face = mesh.halfedge_face_array().data();
    static const CosineBins bins;
    // The threshold as a dot product (the angle is >= angle_deg exactly when the dot is <= it).
    const double flag_dot = std::cos(angle_deg / kRadToDeg);
    std::array<AngleHistogram, 2> part_h;
    std::array<std::vector<Index>, 2> part_list;
    on_two_threads(worth_two_threads(ne), [&](int part) {
        AngleHistogram& ph = part_h[std::size_t(part)];
        std::vector<Index>& list = part_list[std::size_t(part)];
        const HalfRange r = half_of(ne, part);
        for (std::size_t i = r.begin; i < r.end; ++i) {
            if (garbage && mesh.is_deleted(Edge(static_cast<Index>(i)))) continue;
            const Face f0 = face[2 * i], f1 = face[2 * i + 1];
            if (!f0.is_valid() || !f1.is_valid()) {
                if (flags && boundary) {
                    (*flags)[i] = 1;
                    list.push_back(Index(i));
                }
                continue;
            }
            const Eigen::Vector3f& n0 = normals[f0.idx()];
            const Eigen::Vector3f& n1 = normals[f1.idx()];
            if (n0.isZero(0) || n1.isZero(0)) {
                ++ph.degenerate_edges;
                continue;
            }
            const double d = std::clamp(double(n0.dot(n1)), -1.0, 1.0);
            if (flags && d <= flag_dot) {
                (*flags)[i] = 1;
                list.push_back(Index(i));
            }
            ++ph.counts[bins.bin(d)];
            ++ph.interior_edges;
        }
    });
    for (const AngleHistogram& ph : part_h) {
        for (std::size_t k = 0; k < kAngleBins; ++k) h.counts[k] += ph.counts[k];
        h.interior_edges += ph.interior_edges;
        h.degenerate_edges += ph.degenerate_edges;
    }
    if (flagged_list) {
        flagged_list->clear();
        flagged_list->reserve(part_list[0].size() + part_list[1].size());
        for (const std::vector<Index>& l : part_list)
            flagged_list->insert(flagged_list->end(), l.begin(), l.end());
    }
    find_plateau(h);
}

/// The number of flagged edges at each vertex, saturating at 255.
std::vector<std::uint8_t> flagged_degrees(const HalfedgeMesh& mesh,
                                          const std::vector<Index>& list) {
    std::vector<std::uint8_t> degree(mesh.vertices_size(), 0);
    const Vertex* to = mesh.halfedge_to_array().data();
    for (Index e : list)
        for (Index k = 0; k < 2; ++k) {
            std::uint8_t& d = degree[to[2 * e + k].idx()];
            if (d < 255) ++d;
        }
    return degree;
}

/// The chains of the flagged edges (`flagged`: 1 for a flagged edge, `list` the flagged edges):
/// maximal paths between vertices where the flagged degree is not 2, then the closed loops
/// left. Calls chain(edges) for each; marks the visited edges 2 in `flagged` (a chain callback
/// may set its edges to 0). O(flagged edges + their ends' valences).
template <class Chain>
void for_each_chain(const HalfedgeMesh& mesh, std::vector<std::uint8_t>& flagged,
                    const std::vector<Index>& list, const Chain& chain) {
    const std::vector<std::uint8_t> degree = flagged_degrees(mesh, list);
    std::vector<Edge> edges;
    // Walks from vertex v along the flagged, unvisited halfedge h until a vertex whose degree
    // is not 2 or an edge already visited (a loop closing).
    auto walk = [&](Halfedge h) {
        edges.clear();
        while (true) {
            const Edge e = HalfedgeMesh::edge(h);
            flagged[e.idx()] = 2;
            edges.push_back(e);
            const Vertex w = mesh.to_vertex(h);
            if (degree[w.idx()] != 2) break;
            Halfedge next;
            for (Halfedge g : mesh.halfedges_around(w)) {
                if (flagged[HalfedgeMesh::edge(g).idx()] == 1) {
                    next = g;
                    break;
                }
            }
            if (!next.is_valid()) break;
            h = next;
        }
        chain(edges);
    };
    for (Index e : list)
        for (Index k = 0; k < 2; ++k) {
            const Vertex v = mesh.to_vertex(Halfedge(2 * e + k));
            if (degree[v.idx()] == 2) continue;
            for (Halfedge h : mesh.halfedges_around(v))
                if (flagged[HalfedgeMesh::edge(h).idx()] == 1) walk(h);
        }
    for (Index e : list)
        if (flagged[e] == 1) walk(mesh.halfedge(Edge(e), 0));
}

std::string verdict_of(const AngleHistogram& h, double angle_deg) {
    char line[240];
    if (h.at_or_above(kPlateauMinAngle) == 0) {
        std::snprintf(line, sizeof(line),
                      "no sharp edges: every dihedral angle is below %d degrees", kPlateauMinAngle);
    } else if (!h.plateau) {
        std::snprintf(line, sizeof(line),
                      "no plateau: the number of edges keeps changing with the angle (a noisy "
                      "mesh?); a threshold alone finds noise, denoise first (%zu edges at %g deg)",
                      h.at_or_above(int(angle_deg)), angle_deg);
    } else {
        std::snprintf(line, sizeof(line),
                      "plateau from %d to %d degrees (%zu to %zu edges): a threshold of about %d "
                      "degrees finds the sharp edges",
                      h.plateau_lo, h.plateau_hi, h.at_or_above(h.plateau_lo), h.plateau_edges,
                      (h.plateau_lo + h.plateau_hi) / 2);
    }
    return line;
}

}  // namespace

std::size_t AngleHistogram::at_or_above(int angle) const {
    std::size_t n = 0;
    for (std::size_t k = std::size_t(std::clamp(angle, 0, int(kAngleBins))); k < kAngleBins; ++k)
        n += counts[k];
    return n;
}

void find_plateau(AngleHistogram& h) {
    // above[k]: edges at or above k degrees.
    std::array<std::size_t, kAngleBins + 1> above{};
    for (std::size_t k = kAngleBins; k-- > 0;) above[k] = above[k + 1] + h.counts[k];
    int best_lo = 0, best_hi = -1;
    for (int lo = kPlateauMinAngle; lo < int(kAngleBins); ++lo) {
        if (above[std::size_t(lo)] == 0) break;
        const double allowed =
            std::max(1.0, kPlateauDrop * double(above[std::size_t(lo)]));  // edges lost
        int hi = lo;
        while (hi + 1 < int(kAngleBins) && above[std::size_t(hi + 1)] > 0 &&
               double(above[std::size_t(lo)] - above[std::size_t(hi + 1)]) <= allowed)
            ++hi;
        if (hi - lo > best_hi - best_lo) {
            best_lo = lo;
            best_hi = hi;
        }
    }
    h.plateau = best_hi - best_lo >= kPlateauMinWidth;
    h.plateau_lo = h.plateau ? best_lo : 0;
    h.plateau_hi = h.plateau ? best_hi : 0;
    h.plateau_edges = h.plateau ? above[std::size_t(best_hi)] : 0;
}

AngleHistogram angle_histogram(const HalfedgeMesh& mesh) {
    AngleHistogram h;
    edge_angles(mesh, h, 0, false, nullptr);
    return h;
}

std::vector<float> feature_neighbourhood(const HalfedgeMesh& mesh, unsigned rings) {
    if (!has_features(mesh))
        throw InvalidArgument(
            "the mesh has no features (no sharp edge, no corner tag): run `features` first");
    std::vector<float> w(mesh.vertices_size(), 0.0f);
    std::vector<Vertex> front;
    const auto sharp = mesh.get_edge_property<float>(kSharpnessProperty);
    if (sharp)
        for (Edge e : mesh.edges())
            if (sharp[e] > 0.0f)
                for (int k = 0; k < 2; ++k) {
                    const Vertex v = mesh.to_vertex(mesh.halfedge(e, k));
                    if (w[v.idx()] == 0.0f) front.push_back(v);
                    w[v.idx()] = 1.0f;
                }
    for (Vertex v : mesh.vertices())
        if (is_corner_tagged(mesh, v) && w[v.idx()] == 0.0f) {
            w[v.idx()] = 1.0f;
            front.push_back(v);
        }
    for (unsigned r = 0; r < rings && !front.empty(); ++r) {
        std::vector<Vertex> next;
        for (Vertex v : front)
            for (Vertex u : mesh.vertices_around(v))
                if (w[u.idx()] == 0.0f) {
                    w[u.idx()] = 1.0f;
                    next.push_back(u);
                }
        front.swap(next);
    }
    return w;
}

FeatureDetectionReport detect_features(HalfedgeMesh& mesh, const FeatureDetectionOptions& o) {
    const auto t0 = std::chrono::steady_clock::now();
    if (!(o.angle_deg > 0 && o.angle_deg <= 180))
        throw InvalidArgument("features: angle must be in (0, 180] degrees (got " +
                              number_text(o.angle_deg) + ")");
    if (!(o.sharpness > 0.0f))
        throw InvalidArgument("features: sharpness must be > 0 or inf (got " +
                              number_text(o.sharpness) + ")");
    FeatureDetectionReport r;
    std::vector<std::uint8_t> flagged;
    std::vector<Index> list;
    edge_angles(mesh, r.histogram, o.angle_deg, o.boundary, &flagged, &list);
    bool dropped = false;
    for_each_chain(mesh, flagged, list, [&](const std::vector<Edge>& edges) {
        if (o.min_chain > 1 && edges.size() < o.min_chain) {
            ++r.dropped_chains;
            r.dropped_edges += edges.size();
            for (Edge e : edges) flagged[e.idx()] = 0;
            dropped = true;
        } else {
            ++r.chains;
        }
    });
    if (dropped)
        list.erase(std::remove_if(list.begin(), list.end(), [&](Index e) { return !flagged[e]; }),
                   list.end());
    // Replace the features: only now is the mesh changed.
    clear_features(mesh);
    auto sharp = sharpness_property(mesh);
    const Face* face = std::as_const(mesh).halfedge_face_array().data();
    for (Index e : list) {
        sharp[Edge(e)] = o.sharpness;
        if (!face[2 * e].is_valid() || !face[2 * e + 1].is_valid()) ++r.boundary_edges;
    }
    r.feature_edges = list.size();
    // The vertex classes (classify_vertices() with o.boundary: the flagged edges are exactly
    // the sharp ones and no vertex is tagged), from the flagged degrees of the list's ends.
    std::vector<std::uint8_t> degree = flagged_degrees(mesh, list);
    const Vertex* to = std::as_const(mesh).halfedge_to_array().data();
    for (Index e : list)
        for (Index k = 0; k < 2; ++k) {
            std::uint8_t& d = degree[to[2 * e + k].idx()];
            if (d == 1)
                ++r.darts;
            else if (d == 2)
                ++r.creases;
            else if (d >= 3) {
                ++r.corners;
                ++r.junctions;
            }
            d = 0;  // counted once
        }
    r.verdict = verdict_of(r.histogram, o.angle_deg);
    r.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    return r;
}

}  // namespace trilab
