#include "core/laplacian.h"

#include <algorithm>
#include <cmath>

#include "core/errors.h"
#include "core/geometry.h"

namespace trilab {

namespace {

using Triplet = Eigen::Triplet<double>;

/// Cotangent of the angle at o between o->a and o->b, with degenerate corners and clamps
/// counted.
double corner_cot(const Point& o, const Point& a, const Point& b, LaplacianDiagnostics& d) {
    const Vector3 u = a - o, w = b - o;
    const double cross = u.cross(w).norm();
    const double dot = u.dot(w);
    const double scale = u.norm() * w.norm();
    if (!(scale > 0) || !std::isfinite(scale) || !(cross > 1e-14 * scale)) {
        ++d.degenerate_corners;
        return 0.0;
    }
    double c = dot / cross;
    if (std::abs(c) > kMaxCotangent) {
        ++d.cotangents_clamped;
        c = std::clamp(c, -kMaxCotangent, kMaxCotangent);
    }
    return c;
}

/// Cotangent of the corner opposite h in its face (0 for a boundary halfedge).
double cot_opposite(const HalfedgeMesh& m, Halfedge h, LaplacianDiagnostics& d) {
    if (m.is_boundary(h)) return 0.0;
    return corner_cot(m.position(m.to_vertex(m.next(h))), m.position(m.from_vertex(h)),
                      m.position(m.to_vertex(h)), d);
}

/// Adds 2 x the lumped (barycentric or mixed Voronoi) area of every mapped vertex to S.
void lumped_mass(const HalfedgeMesh& m, const VertexIndexMap& map, MassMatrix mass,
                 Eigen::VectorXd& S) {
    S.setZero();
    for (Face f : m.faces()) {
        const auto v = m.face_vertices(f);
        const Point* p[3] = {&m.position(v[0]), &m.position(v[1]), &m.position(v[2])};
        const double area = 0.5 * (*p[1] - *p[0]).cross(*p[2] - *p[0]).norm();
        if (!(area > 0) || !std::isfinite(area)) continue;
        double a[3] = {area / 3, area / 3, area / 3};
        if (mass == MassMatrix::Voronoi) {
            // Corner dot products: d[i] = (p[i+1]-p[i])·(p[i+2]-p[i]); d[i] < 0: obtuse at i.
            double d[3];
            for (int i = 0; i < 3; ++i)
                d[i] = (*p[(i + 1) % 3] - *p[i]).dot(*p[(i + 2) % 3] - *p[i]);
            const int obtuse = d[0] < 0 ? 0 : d[1] < 0 ? 1 : d[2] < 0 ? 2 : -1;
            if (obtuse >= 0) {
                for (int i = 0; i < 3; ++i) a[i] = i == obtuse ? area / 2 : area / 4;
            } else {
                // Voronoi area of corner i: (|p_i p_j|² cot k + |p_i p_k|² cot j) / 8, with
                // cot at corner c = d[c] / (2·area).
                for (int i = 0; i < 3; ++i) {
                    const int j = (i + 1) % 3, k = (i + 2) % 3;
                    a[i] = ((*p[j] - *p[i]).squaredNorm() * d[k] +
                            (*p[k] - *p[i]).squaredNorm() * d[j]) /
                           (16.0 * area);
                }
            }
        }
        for (int i = 0; i < 3; ++i) {
            const Index r = map.row_of[v[std::size_t(i)].idx()];
            if (r != kInvalidIndex) S[Eigen::Index(r)] += 2.0 * a[i];
        }
    }
}

}  // namespace

const char* mass_matrix_name(MassMatrix mass) {
    switch (mass) {
        case MassMatrix::Normalizer:
            return "normalizer";
        case MassMatrix::Barycentric:
            return "barycentric";
        case MassMatrix::Voronoi:
            return "voronoi";
    }
    return "?";
}

MassMatrix parse_mass_matrix(const std::string& name) {
    for (auto m : {MassMatrix::Normalizer, MassMatrix::Barycentric, MassMatrix::Voronoi})
        if (name == mass_matrix_name(m)) return m;
    throw InvalidArgument("parse_mass_matrix: unknown mass matrix '" + name +
                          "' (expected normalizer, barycentric, voronoi)");
}

const char* laplacian_operator_name(LaplacianOperator op) {
    switch (op) {
        case LaplacianOperator::Umbrella:
            return "umbrella";
        case LaplacianOperator::ImprovedUmbrella:
            return "improved-umbrella";
        case LaplacianOperator::CurvatureFlow:
            return "curvature-flow";
        case LaplacianOperator::SecondOrder:
            return "second-order";
    }
    return "?";
}

LaplacianOperator parse_laplacian_operator(const std::string& name) {
    for (auto op : {LaplacianOperator::Umbrella, LaplacianOperator::ImprovedUmbrella,
                    LaplacianOperator::CurvatureFlow, LaplacianOperator::SecondOrder})
        if (name == laplacian_operator_name(op)) return op;
    throw InvalidArgument("parse_laplacian_operator: unknown operator '" + name +
                          "' (expected umbrella, improved-umbrella, curvature-flow, "
                          "second-order)");
}

VertexIndexMap make_vertex_index_map(const HalfedgeMesh& mesh) {
    VertexIndexMap map;
    map.row_of.assign(mesh.vertices_size(), kInvalidIndex);
    for (Vertex v : mesh.vertices()) {
        if (mesh.is_isolated(v)) continue;
        map.row_of[v.idx()] = Index(map.vertex_of.size());
        map.vertex_of.push_back(v);
    }
    return map;
}

std::size_t Laplacian::n_free() const {
    return std::size_t(std::count(fixed.begin(), fixed.end(), std::uint8_t(0)));
}

Laplacian build_laplacian(const HalfedgeMesh& mesh, LaplacianOperator op,
                          const LaplacianOptions& options) {
    Laplacian lap;
    lap.op = op;
    lap.map = make_vertex_index_map(mesh);
    const std::size_t n = lap.map.rows();
    auto& diag = lap.diagnostics;
    const auto& row = lap.map.row_of;
    Eigen::VectorXd S = Eigen::VectorXd::Zero(Eigen::Index(n));
    std::vector<Triplet> trip;

    if (op == LaplacianOperator::SecondOrder) {
        // K = Cᵀ C, one hinge per interior edge; see the header for the coefficients.
        trip.reserve(mesh.n_edges() * 16);
        for (Edge e : mesh.edges()) {
            if (mesh.is_boundary(e)) continue;
            const Halfedge h0 = HalfedgeMesh::halfedge(e, 0);  // v1 -> v2, in T1
            const Halfedge h1 = HalfedgeMesh::twin(h0);        // v2 -> v1, in T2
            const Vertex v1 = mesh.from_vertex(h0), v2 = mesh.to_vertex(h0);
            const Vertex v3 = mesh.to_vertex(mesh.next(h0)), v4 = mesh.to_vertex(mesh.next(h1));
            const Point &p1 = mesh.position(v1), &p2 = mesh.position(v2);
            const Point &p3 = mesh.position(v3), &p4 = mesh.position(v4);
            const double t1_1 = corner_cot(p1, p2, p3, diag), t1_2 = corner_cot(p2, p3, p1, diag);
            const double t2_1 = corner_cot(p1, p4, p2, diag), t2_2 = corner_cot(p2, p1, p4, diag);
            const Index r[4] = {row[v1.idx()], row[v2.idx()], row[v3.idx()], row[v4.idx()]};
            const double c[4] = {-(t1_2 + t2_2), -(t1_1 + t2_1), t1_1 + t1_2, t2_1 + t2_2};
            for (int a = 0; a < 4; ++a)
                for (int b = 0; b < 4; ++b) trip.emplace_back(r[a], r[b], c[a] * c[b]);
        }
        lap.K.resize(Eigen::Index(n), Eigen::Index(n));
        lap.K.setFromTriplets(trip.begin(), trip.end());
        S = lap.K.diagonal();
    } else {
        double min_len = 0;
        if (op == LaplacianOperator::ImprovedUmbrella) min_len = 1e-6 * mean_edge_length(mesh);
        if (!(min_len > 0) || !std::isfinite(min_len)) min_len = 1e-300;
        trip.reserve(mesh.n_edges() * 4);
        for (Edge e : mesh.edges()) {
            const Halfedge h = HalfedgeMesh::halfedge(e, 0);
            const Index i = row[mesh.from_vertex(h).idx()], j = row[mesh.to_vertex(h).idx()];
            double w = 1.0;
            if (op == LaplacianOperator::ImprovedUmbrella) {
                double len =
                    (mesh.position(mesh.to_vertex(h)) - mesh.position(mesh.from_vertex(h))).norm();
                if (!(len >= min_len)) {
                    ++diag.short_edges;
                    len = min_len;
                }
                w = 1.0 / len;
                S[i] += 0.5 * len;
                S[j] += 0.5 * len;
            } else if (op == LaplacianOperator::CurvatureFlow) {
                w = cot_opposite(mesh, h, diag) + cot_opposite(mesh, HalfedgeMesh::twin(h), diag);
                if (w < 0 && options.clamp_negative_cotangents) {
                    ++diag.negative_weights_clamped;
                    w = 0;
                }
            }
            if (op != LaplacianOperator::ImprovedUmbrella) {
                S[i] += w;
                S[j] += w;
            }
            trip.emplace_back(i, j, -w);
            trip.emplace_back(j, i, -w);
            trip.emplace_back(i, i, w);
            trip.emplace_back(j, j, w);
        }
        lap.K.resize(Eigen::Index(n), Eigen::Index(n));
        lap.K.setFromTriplets(trip.begin(), trip.end());
    }
    lap.K.makeCompressed();
    if (options.mass != MassMatrix::Normalizer) lumped_mass(mesh, lap.map, options.mass, S);

    // Fixed rows: boundary (by option) and stalled vertices.
    lap.fixed.assign(n, 0);
    double s_max = 0;
    for (Eigen::Index r = 0; r < S.size(); ++r)
        if (std::isfinite(S[r])) s_max = std::max(s_max, std::abs(S[r]));
    for (std::size_t r = 0; r < n; ++r) {
        const Vertex v = lap.map.vertex_of[r];
        if (options.fix_boundary && mesh.is_boundary(v)) {
            lap.fixed[r] = 1;
        } else if (!(S[Eigen::Index(r)] > 1e-12 * s_max)) {
            lap.fixed[r] = 1;
            ++diag.stalled_vertices;
        }
        if (lap.fixed[r]) S[Eigen::Index(r)] = 1.0;
    }
    lap.S = S;

    // L = -S⁻¹ K on free rows.
    std::vector<Triplet> lt;
    lt.reserve(std::size_t(lap.K.nonZeros()));
    for (Eigen::Index c = 0; c < lap.K.outerSize(); ++c)
        for (SparseMatrix::InnerIterator it(lap.K, c); it; ++it)
            if (!lap.fixed[std::size_t(it.row())])
                lt.emplace_back(it.row(), it.col(), -it.value() / S[it.row()]);
    lap.L.resize(Eigen::Index(n), Eigen::Index(n));
    lap.L.setFromTriplets(lt.begin(), lt.end());
    lap.L.makeCompressed();
    return lap;
}

Eigen::MatrixXd gather_positions(const HalfedgeMesh& mesh, const VertexIndexMap& map) {
    Eigen::MatrixXd x(Eigen::Index(map.rows()), 3);
    for (std::size_t r = 0; r < map.rows(); ++r)
        x.row(Eigen::Index(r)) = mesh.position(map.vertex_of[r]).transpose();
    return x;
}

void scatter_positions(HalfedgeMesh& mesh, const VertexIndexMap& map, const Eigen::MatrixXd& x) {
    for (std::size_t r = 0; r < map.rows(); ++r)
        mesh.position(map.vertex_of[r]) = x.row(Eigen::Index(r)).transpose();
}

}  // namespace trilab
