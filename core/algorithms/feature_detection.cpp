#include "core/algorithms/feature_detection.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "core/errors.h"
#include "core/number_text.h"
#include "core/two_threads.h"

namespace trilab {

namespace {

constexpr double kRadToDeg = 57.295779513082320876798154814105;
constexpr int kPlateauMinAngle = 5;    // thresholds below this are not plateau candidates
constexpr int kPlateauMinWidth = 15;   // degrees
constexpr double kPlateauDrop = 0.05;  // at most this fraction of the edges lost across it

/// Unit face normals (zero for a degenerate face), one per face storage index.
std::vector<Vector3> unit_face_normals(const HalfedgeMesh& mesh) {
    const std::size_t nf = mesh.faces_size();
    std::vector<Vector3> n(nf, Vector3::Zero());
    const bool garbage = mesh.has_garbage();
    on_two_threads(worth_two_threads(nf), [&](int part) {
        const HalfRange r = half_of(nf, part);
        for (std::size_t i = r.begin; i < r.end; ++i) {
            const Face f(static_cast<Index>(i));
            if (garbage && mesh.is_deleted(f)) continue;
            const std::array<Vertex, 3> v = mesh.face_vertices(f);
            const Point& a = mesh.position(v[0]);
            const Vector3 c = (mesh.position(v[1]) - a).cross(mesh.position(v[2]) - a);
            const double len = c.norm();
            if (len > 0 && std::isfinite(len)) n[i] = c / len;
        }
    });
    return n;
}

/// The histogram of the interior edges' dihedral angles; with `flags`, also each edge's flag:
/// 1 for an interior edge of angle >= angle_deg, or a boundary edge when `boundary`.
void edge_angles(const HalfedgeMesh& mesh, AngleHistogram& h, double angle_deg, bool boundary,
                 std::vector<std::uint8_t>* flags) {
    const std::vector<Vector3> normals = unit_face_normals(mesh);
    const std::size_t ne = mesh.edges_size();
    if (flags) flags->assign(ne, 0);
    const bool garbage = mesh.has_garbage();
    std::array<AngleHistogram, 2> part_h;
    on_two_threads(worth_two_threads(ne), [&](int part) {
        AngleHistogram& ph = part_h[std::size_t(part)];
        const HalfRange r = half_of(ne, part);
        for (std::size_t i = r.begin; i < r.end; ++i) {
            const Edge e(static_cast<Index>(i));
            if (garbage && mesh.is_deleted(e)) continue;
            const Face f0 = mesh.face(mesh.halfedge(e, 0)), f1 = mesh.face(mesh.halfedge(e, 1));
            if (!f0.is_valid() || !f1.is_valid()) {
                if (flags && boundary) (*flags)[i] = 1;
                continue;
            }
            const Vector3& n0 = normals[f0.idx()];
            const Vector3& n1 = normals[f1.idx()];
            if (n0.isZero(0) || n1.isZero(0)) {
                ++ph.degenerate_edges;
                continue;
            }
            const double a = std::acos(std::clamp(n0.dot(n1), -1.0, 1.0)) * kRadToDeg;
            if (flags && a >= angle_deg) (*flags)[i] = 1;
            ++ph.counts[std::min<std::size_t>(kAngleBins - 1, std::size_t(a))];
            ++ph.interior_edges;
        }
    });
    for (const AngleHistogram& ph : part_h) {
        for (std::size_t k = 0; k < kAngleBins; ++k) h.counts[k] += ph.counts[k];
        h.interior_edges += ph.interior_edges;
        h.degenerate_edges += ph.degenerate_edges;
    }
    find_plateau(h);
}

/// The chains of the flagged edges: maximal paths between vertices where the flagged degree
/// is not 2, then the closed loops left. Calls chain(edges) for each.
template <class Chain>
void for_each_chain(const HalfedgeMesh& mesh, const std::vector<std::uint8_t>& flagged,
                    const Chain& chain) {
    std::vector<std::uint32_t> degree(mesh.vertices_size(), 0);
    for (Edge e : mesh.edges())
        if (flagged[e.idx()])
            for (int k = 0; k < 2; ++k) ++degree[mesh.to_vertex(mesh.halfedge(e, k)).idx()];
    std::vector<std::uint8_t> visited(mesh.edges_size(), 0);
    std::vector<Edge> edges;
    // Walks from vertex v along the flagged, unvisited halfedge h until a vertex whose degree
    // is not 2 or an edge already visited (a loop closing).
    auto walk = [&](Halfedge h) {
        edges.clear();
        while (true) {
            const Edge e = HalfedgeMesh::edge(h);
            visited[e.idx()] = 1;
            edges.push_back(e);
            const Vertex w = mesh.to_vertex(h);
            if (degree[w.idx()] != 2) break;
            Halfedge next;
            for (Halfedge g : mesh.halfedges_around(w)) {
                const Edge ge = HalfedgeMesh::edge(g);
                if (flagged[ge.idx()] && !visited[ge.idx()]) {
                    next = g;
                    break;
                }
            }
            if (!next.is_valid()) break;
            h = next;
        }
        chain(edges);
    };
    for (Vertex v : mesh.vertices()) {
        if (degree[v.idx()] == 0 || degree[v.idx()] == 2) continue;
        for (Halfedge h : mesh.halfedges_around(v))
            if (flagged[HalfedgeMesh::edge(h).idx()] && !visited[HalfedgeMesh::edge(h).idx()])
                walk(h);
    }
    for (Edge e : mesh.edges())
        if (flagged[e.idx()] && !visited[e.idx()]) walk(mesh.halfedge(e, 0));
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
    edge_angles(mesh, r.histogram, o.angle_deg, o.boundary, &flagged);
    for_each_chain(mesh, flagged, [&](const std::vector<Edge>& edges) {
        if (o.min_chain > 1 && edges.size() < o.min_chain) {
            ++r.dropped_chains;
            r.dropped_edges += edges.size();
            for (Edge e : edges) flagged[e.idx()] = 0;
        } else {
            ++r.chains;
        }
    });
    // Replace the features: only now is the mesh changed.
    clear_features(mesh);
    auto sharp = sharpness_property(mesh);
    for (Edge e : mesh.edges()) {
        if (!flagged[e.idx()]) continue;
        sharp[e] = o.sharpness;
        ++r.feature_edges;
        if (mesh.is_boundary(e)) ++r.boundary_edges;
    }
    const VertexClassification c = classify_vertices(mesh, o.boundary);
    r.corners = c.corners;
    r.creases = c.creases;
    r.darts = c.darts;
    r.verdict = verdict_of(r.histogram, o.angle_deg);
    r.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    return r;
}

}  // namespace trilab
