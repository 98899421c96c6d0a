// Geodesic distances by the heat method and the path down the distance field
// (core/algorithms/geodesic.h).
//
// Scaling: laplacian.h's K holds the full cotangent weights (2 x the FEM stiffness) and its
// lumped S is 2 x the vertex area, so L_c = -K/2 and M = S/2:
//  - heat (M - t·L_c)·u = δ  <=>  (S + t·K)·u = 2δ (the factor is irrelevant: X is normalized);
//  - Poisson L_c·φ = div X   <=>  K·φ = -2·div X, with
//    div X at vertex i = ½ Σ_faces (cot θ_k (p_j - p_i)·X + cot θ_j (p_k - p_i)·X)
//    = -∫ ∇φ_i·X (the weak divergence), θ the angle opposite each edge. The cotangents are the
//    operator's own per-halfedge cotangents (Laplacian::halfedge_cotangents), so the two
//    operators agree exactly and Σ_i div_i = 0 over every component.
// K is singular (constants per component): one row and column per component are replaced by
// the identity (φ = 0 there), which leaves the other equations those of the full system.
#include "core/algorithms/geodesic.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>
#include <queue>
#include <string>

#include <Eigen/SparseCholesky>

#include "core/errors.h"
#include "core/geometry.h"
#include "core/number_text.h"

namespace trilab {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

void check_sources(const HalfedgeMesh& mesh, const std::vector<Vertex>& sources, const char* who) {
    const std::string what = std::string(who) + ": ";
    if (sources.empty()) throw InvalidArgument(what + "no source vertex given");
    for (Vertex s : sources) {
        if (!s.is_valid() || !mesh.is_valid(s))
            throw InvalidArgument(what + "source vertex " +
                                  (s.is_valid() ? std::to_string(s.idx()) : std::string("-1")) +
                                  " is out of range (the mesh has " +
                                  std::to_string(mesh.vertices_size()) + " vertices)");
        if (mesh.is_deleted(s))
            throw InvalidArgument(what + "source vertex " + std::to_string(s.idx()) +
                                  " is deleted");
    }
}

/// Per row: its connected component (over the edges), and the number of components.
std::vector<Index> row_components(const HalfedgeMesh& mesh, const VertexIndexMap& map,
                                  Index& count) {
    std::vector<Index> parent(map.rows());
    std::iota(parent.begin(), parent.end(), Index(0));
    std::function<Index(Index)> find = [&](Index x) {
        while (parent[x] != x) x = parent[x] = parent[parent[x]];
        return x;
    };
    for (Edge e : mesh.edges()) {
        const Index a = map.row_of[mesh.vertex(e, 0).idx()],
                    b = map.row_of[mesh.vertex(e, 1).idx()];
        const Index ra = find(a), rb = find(b);
        if (ra != rb) parent[std::max(ra, rb)] = std::min(ra, rb);
    }
    std::vector<Index> comp(map.rows(), kInvalidIndex), id_of_root(map.rows(), kInvalidIndex);
    count = 0;
    for (std::size_t r = 0; r < map.rows(); ++r) {
        const Index root = find(Index(r));
        if (id_of_root[root] == kInvalidIndex) id_of_root[root] = count++;
        comp[r] = id_of_root[root];
    }
    return comp;
}

}  // namespace

struct GeodesicSolver::State {
    HalfedgeMesh mesh;
    Laplacian lap;
    double t = 0;
    std::vector<Index> component;  ///< per row
    Index n_components = 0;
    std::vector<std::uint8_t> pinned;  ///< per row
    Eigen::SimplicialLDLT<SparseMatrix> heat, poisson;
};

GeodesicSolver::GeodesicSolver(const HalfedgeMesh& mesh, const GeodesicOptions& options)
    : state_(std::make_unique<State>()) {
    if (!std::isfinite(options.time_factor) || !(options.time_factor > 0))
        throw InvalidArgument("geodesic: time_factor must be finite and > 0 (got " +
                              number_text(options.time_factor) + ")");
    if (options.mass == MassMatrix::Normalizer)
        throw InvalidArgument("geodesic: mass must be barycentric or voronoi (got normalizer)");
    State& s = *state_;
    s.mesh = mesh;
    LaplacianOptions lo;
    lo.fix_boundary = false;  // Neumann
    lo.clamp_negative_cotangents = false;
    lo.mass = options.mass;
    s.lap = build_laplacian(s.mesh, LaplacianOperator::CurvatureFlow, lo);
    const double h = mean_edge_length(s.mesh);
    s.t = options.time_factor * h * h;
    const auto n = Eigen::Index(s.lap.map.rows());
    if (n == 0) return;

    // Stalled rows (zero area) have S = 1 from the builder; use a tiny mass there instead.
    Eigen::VectorXd mass = s.lap.S;
    for (Eigen::Index r = 0; r < n; ++r)
        if (s.lap.fixed[std::size_t(r)]) mass[r] = 1e-12 * s.t;
    SparseMatrix A = s.t * s.lap.K;
    for (Eigen::Index r = 0; r < n; ++r) A.coeffRef(r, r) += mass[r];
    s.heat.compute(A);
    if (s.heat.info() != Eigen::Success)
        throw RunStopped("geodesic: the heat system could not be factorized");

    s.component = row_components(s.mesh, s.lap.map, s.n_components);
    s.pinned.assign(std::size_t(n), 0);
    std::vector<std::uint8_t> seen(std::size_t(s.n_components), 0);
    for (std::size_t r = 0; r < std::size_t(n); ++r)
        if (!seen[s.component[r]]) {
            seen[s.component[r]] = 1;
            s.pinned[r] = 1;
        }
    SparseMatrix P = s.lap.K;
    P.prune([&](Eigen::Index r, Eigen::Index c, double) {
        return !s.pinned[std::size_t(r)] && !s.pinned[std::size_t(c)];
    });
    for (Eigen::Index r = 0; r < n; ++r)
        if (s.pinned[std::size_t(r)]) P.coeffRef(r, r) = 1.0;
    P.makeCompressed();
    s.poisson.compute(P);
    if (s.poisson.info() != Eigen::Success)
        throw RunStopped("geodesic: the Poisson system could not be factorized");
}

GeodesicSolver::~GeodesicSolver() = default;
GeodesicSolver::GeodesicSolver(GeodesicSolver&&) noexcept = default;
GeodesicSolver& GeodesicSolver::operator=(GeodesicSolver&&) noexcept = default;

double GeodesicSolver::time_step() const {
    return state_->t;
}

std::vector<double> GeodesicSolver::distances(const std::vector<Vertex>& sources) const {
    const State& s = *state_;
    const HalfedgeMesh& m = s.mesh;
    check_sources(m, sources, "geodesic");
    const auto& row = s.lap.map.row_of;
    const auto n = Eigen::Index(s.lap.map.rows());
    std::vector<double> out(m.vertices_size(), kInfinity);
    for (Vertex v : sources) out[v.idx()] = 0.0;
    if (n == 0) return out;

    // 1. Heat.
    Eigen::VectorXd delta = Eigen::VectorXd::Zero(n);
    std::vector<std::uint8_t> reached(std::size_t(s.n_components), 0);
    for (Vertex v : sources) {
        const Index r = row[v.idx()];
        if (r == kInvalidIndex) continue;  // isolated source
        delta[Eigen::Index(r)] = 2.0;
        reached[s.component[r]] = 1;
    }
    const Eigen::VectorXd u = s.heat.solve(delta);

    // 2-3. Normalized gradient per face, its divergence per vertex.
    Eigen::VectorXd div = Eigen::VectorXd::Zero(n);
    const std::vector<double>& cot = s.lap.halfedge_cotangents;
    for (Face f : m.faces()) {
        const Halfedge h[3] = {m.halfedge(f), m.next(m.halfedge(f)), m.next(m.next(m.halfedge(f)))};
        Index r[3];
        Point p[3];
        for (int i = 0; i < 3; ++i) {
            const Vertex v = m.from_vertex(h[i]);
            r[i] = row[v.idx()];
            p[i] = m.position(v);
        }
        const Vector3 normal = (p[1] - p[0]).cross(p[2] - p[0]);
        // Σ u_i (N x e_i), e_i the edge opposite corner i, counter-clockwise.
        Vector3 sum = Vector3::Zero();
        for (int i = 0; i < 3; ++i)
            sum += u[Eigen::Index(r[i])] * normal.cross(p[(i + 2) % 3] - p[(i + 1) % 3]);
        const double len = sum.norm();
        if (!(len > 0) || !std::isfinite(len)) continue;
        const Vector3 X = -sum / len;
        for (int i = 0; i < 3; ++i) {  // halfedge h[i]: p[i] -> p[i+1]
            const double w = 0.5 * cot[h[i].idx()] * (p[(i + 1) % 3] - p[i]).dot(X);
            div[Eigen::Index(r[i])] += w;
            div[Eigen::Index(r[(i + 1) % 3])] -= w;
        }
    }
    Eigen::VectorXd rhs = -2.0 * div;
    for (Eigen::Index i = 0; i < n; ++i)
        if (s.pinned[std::size_t(i)]) rhs[i] = 0.0;
    const Eigen::VectorXd phi = s.poisson.solve(rhs);

    // 4. Shift per component: the sources' mean to 0.
    std::vector<double> shift(std::size_t(s.n_components), 0.0);
    std::vector<std::size_t> count(std::size_t(s.n_components), 0);
    for (Vertex v : sources) {
        const Index r = row[v.idx()];
        if (r == kInvalidIndex) continue;
        shift[s.component[r]] += phi[Eigen::Index(r)];
        ++count[s.component[r]];
    }
    for (std::size_t c = 0; c < shift.size(); ++c)
        if (count[c]) shift[c] /= double(count[c]);
    for (Eigen::Index i = 0; i < n; ++i) {
        const Index c = s.component[std::size_t(i)];
        if (!reached[c]) continue;
        const double d = phi[i] - shift[c];
        out[s.lap.map.vertex_of[std::size_t(i)].idx()] = std::isfinite(d) ? std::max(d, 0.0) : d;
    }
    for (Vertex v : sources) out[v.idx()] = 0.0;
    return out;
}

std::vector<double> geodesic_distances(const HalfedgeMesh& mesh, const std::vector<Vertex>& sources,
                                       const GeodesicOptions& options) {
    check_sources(mesh, sources, "geodesic");
    return GeodesicSolver(mesh, options).distances(sources);
}

std::vector<double> edge_graph_distances(const HalfedgeMesh& mesh,
                                         const std::vector<Vertex>& sources) {
    check_sources(mesh, sources, "edge_graph_distances");
    std::vector<double> dist(mesh.vertices_size(), kInfinity);
    using Item = std::pair<double, Index>;
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
    for (Vertex v : sources) {
        dist[v.idx()] = 0.0;
        queue.emplace(0.0, v.idx());
    }
    while (!queue.empty()) {
        const auto [d, i] = queue.top();
        queue.pop();
        if (d > dist[i]) continue;
        const Vertex v(i);
        if (mesh.is_isolated(v)) continue;
        const Halfedge first = mesh.halfedge(v);
        Halfedge h = first;
        do {
            const Vertex w = mesh.to_vertex(h);
            const double nd = d + (mesh.position(w) - mesh.position(v)).norm();
            if (nd < dist[w.idx()]) {
                dist[w.idx()] = nd;
                queue.emplace(nd, w.idx());
            }
            h = mesh.cw_rotated(h);
        } while (h != first);
    }
    return dist;
}

namespace {

constexpr double kSnap = 1e-9;  ///< edge parameters this close to 0 or 1 snap to the vertex

/// Steepest descent of the piecewise-linear distance field d. The state: at vertex v, or on
/// halfedge h at (1 - t)·from + t·to about to enter face(h); `value` is d there.
struct Tracer {
    const HalfedgeMesh& m;
    const std::vector<double>& d;
    std::vector<SurfacePoint> path;
    Vertex v;
    Halfedge h;
    double t = 0, value = 0;
    bool at_vertex = true;

    void go_to_vertex(Vertex w) {
        v = w;
        value = d[w.idx()];
        at_vertex = true;
        path.push_back({w, Vertex(), 0.0, m.position(w)});
    }
    /// Onto edge `exit` at parameter s (from its start), then into the face across it.
    void go_to_edge(Halfedge exit, double s, double new_value) {
        if (s < kSnap || s > 1 - kSnap) {
            go_to_vertex(s < kSnap ? m.from_vertex(exit) : m.to_vertex(exit));
            return;
        }
        h = HalfedgeMesh::twin(exit);
        t = 1 - s;
        value = new_value;
        at_vertex = false;
        const Vertex a = m.from_vertex(h), b = m.to_vertex(h);
        path.push_back({a, b, t, (1 - t) * m.position(a) + t * m.position(b)});
    }
    double edge_value(Halfedge e, double s) const {
        return (1 - s) * d[m.from_vertex(e).idx()] + s * d[m.to_vertex(e).idx()];
    }
    /// The 3D gradient of the distance over face(f), f's corners a = from, b = to, c.
    bool gradient(Halfedge f, Vector3& g) const {
        const Vertex va = m.from_vertex(f), vb = m.to_vertex(f), vc = m.to_vertex(m.next(f));
        const Point &a = m.position(va), &b = m.position(vb), &c = m.position(vc);
        const Vector3 n = (b - a).cross(c - a);
        const double n2 = n.squaredNorm();
        if (!(n2 > 0)) return false;
        g = (d[va.idx()] * n.cross(c - b) + d[vb.idx()] * n.cross(a - c) +
             d[vc.idx()] * n.cross(b - a)) /
            n2;
        return std::isfinite(g.squaredNorm()) && g.squaredNorm() > 0;
    }
    /// -∇d over face(f) = alpha·(b - a) + beta·(c - a) (least squares in the face's plane).
    bool descent(Halfedge f, double& alpha, double& beta, double& rate) const {
        Vector3 g;
        if (m.is_boundary(f) || !gradient(f, g)) return false;
        const Point& a = m.position(m.from_vertex(f));
        const Vector3 e1 = m.position(m.to_vertex(f)) - a;
        const Vector3 e2 = m.position(m.to_vertex(m.next(f))) - a;
        const double a11 = e1.dot(e1), a12 = e1.dot(e2), a22 = e2.dot(e2);
        const double det = a11 * a22 - a12 * a12;
        if (!(det > 0)) return false;
        const double r1 = -e1.dot(g), r2 = -e2.dot(g);
        alpha = (a22 * r1 - a12 * r2) / det;
        beta = (a11 * r2 - a12 * r1) / det;
        rate = g.norm();
        return std::isfinite(alpha) && std::isfinite(beta);
    }

    /// One step from vertex v; false when the path ends.
    bool vertex_step() {
        if (d[v.idx()] <= 0 || m.is_isolated(v)) return false;
        // The steepest incident face whose descent enters its interior.
        double best_rate = 0, best_s = 0;
        Halfedge best;
        const Halfedge first = m.halfedge(v);
        Halfedge o = first;
        do {
            double alpha, beta, rate;
            if (descent(o, alpha, beta, rate) && alpha >= 0 && beta >= 0 && alpha + beta > 0 &&
                rate > best_rate) {
                best_rate = rate;
                best = o;
                best_s = beta / (alpha + beta);  // where the ray meets the opposite edge
            }
            o = m.cw_rotated(o);
        } while (o != first);
        if (best.is_valid()) {
            const Halfedge bc = m.next(best);
            const double s = std::clamp(best_s, 0.0, 1.0);
            const double nv = edge_value(bc, s);
            if (nv < value) {
                go_to_edge(bc, s, nv);
                return true;
            }
        }
        // No face descends: the lowest lower neighbour, if any.
        Vertex lowest;
        double low = value;
        o = first;
        do {
            const Vertex w = m.to_vertex(o);
            if (d[w.idx()] < low) {
                low = d[w.idx()];
                lowest = w;
            }
            o = m.cw_rotated(o);
        } while (o != first);
        if (!lowest.is_valid()) return false;
        go_to_vertex(lowest);
        return true;
    }

    /// One step from edge h at t into face(h).
    void edge_step() {
        const Vertex a = m.from_vertex(h), b = m.to_vertex(h);
        const Vertex lower_end = d[a.idx()] <= d[b.idx()] ? a : b;
        double alpha, beta, rate;
        if (!descent(h, alpha, beta, rate) || !(beta > 0)) {
            go_to_vertex(lower_end);  // the descent does not enter the face: along the edge
            return;
        }
        // Barycentric (1 - t, t, 0) moves by (-alpha - beta, alpha, beta) per unit.
        double lambda_a = kInfinity, lambda_b = kInfinity;
        if (alpha + beta > 0) lambda_a = (1 - t) / (alpha + beta);
        if (alpha < 0) lambda_b = t / -alpha;
        Halfedge exit;
        double s;  // parameter on `exit` (from its start)
        if (lambda_a <= lambda_b) {
            exit = m.next(h);  // b -> c; a's coordinate reaches 0: s is c's coordinate
            s = std::clamp(beta * lambda_a, 0.0, 1.0);
        } else {
            exit = m.next(m.next(h));  // c -> a; b's coordinate reaches 0: s is a's coordinate
            s = std::clamp(1 - t - (alpha + beta) * lambda_b, 0.0, 1.0);
        }
        const double nv = edge_value(exit, s);
        if (!(nv < value))
            go_to_vertex(lower_end);
        else
            go_to_edge(exit, s, nv);
    }
};

}  // namespace

std::vector<SurfacePoint> geodesic_path(const HalfedgeMesh& mesh,
                                        const std::vector<double>& distances, Vertex target) {
    if (distances.size() != mesh.vertices_size())
        throw InvalidArgument("geodesic_path: distances has " + std::to_string(distances.size()) +
                              " entries, the mesh " + std::to_string(mesh.vertices_size()) +
                              " vertices");
    if (!target.is_valid() || !mesh.is_valid(target) || mesh.is_deleted(target))
        throw InvalidArgument(
            "geodesic_path: target vertex " +
            (target.is_valid() ? std::to_string(target.idx()) : "-1") +
            (target.is_valid() && mesh.is_valid(target) ? " is deleted" : " is out of range"));
    if (!std::isfinite(distances[target.idx()]))
        throw InvalidArgument("geodesic_path: target vertex " + std::to_string(target.idx()) +
                              " is not reached by the sources (distance not finite)");
    Tracer tracer{mesh, distances, {}, Vertex(), Halfedge(), 0.0, 0.0, true};
    tracer.go_to_vertex(target);
    // The value strictly decreases at every step that does not end the path; the bound only
    // guards against a cycle of rounding.
    const std::size_t max_steps = 4 * (mesh.n_faces() + mesh.n_vertices()) + 16;
    for (std::size_t step = 0; step < max_steps; ++step) {
        if (tracer.at_vertex) {
            if (!tracer.vertex_step()) break;
        } else {
            tracer.edge_step();
        }
    }
    return std::move(tracer.path);
}

double path_length(const std::vector<SurfacePoint>& path) {
    double length = 0;
    for (std::size_t i = 1; i < path.size(); ++i)
        length += (path[i].position - path[i - 1].position).norm();
    return length;
}

}  // namespace trilab
