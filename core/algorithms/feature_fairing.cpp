// Sliding features in fairing (core/algorithms/feature_fairing.h).
#include "core/algorithms/feature_fairing.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include "core/features.h"

namespace trilab {

const char* feature_mode_name(FeatureMode mode) {
    return enum_id<FeatureMode>(kFeatureModes, mode);
}

FeatureMode parse_feature_mode(const std::string& name) {
    return parse_enum<FeatureMode>(kFeatureModes, name, "feature mode");
}

FeatureCurveFairing::FeatureCurveFairing(const HalfedgeMesh& mesh,
                                         const std::vector<float>* region) {
    const auto sharp = mesh.get_edge_property<float>(kSharpnessProperty);
    if (!sharp) return;
    const auto corner = mesh.get_vertex_property<std::uint8_t>(kCornerProperty);
    for (Vertex v : mesh.vertices()) {
        if (mesh.is_isolated(v) || mesh.is_boundary(v) || (corner && corner[v])) continue;
        if (region && !((*region)[v.idx()] > 0.0f)) continue;
        Index ends[2] = {kInvalidIndex, kInvalidIndex};
        unsigned n = 0;
        for (Halfedge h : mesh.halfedges_around(v)) {
            if (!(sharp[HalfedgeMesh::edge(h)] > 0.0f)) continue;
            if (n < 2) ends[n] = mesh.to_vertex(h).idx();
            if (++n > 2) break;
        }
        if (n == 2) rows_.push_back(Row{v.idx(), ends[0], ends[1]});
    }
    moving_.reserve(rows_.size());
    for (const Row& r : rows_) moving_.push_back(r.v);
}

void FeatureCurveFairing::remap(const std::vector<Index>& map) {
    std::vector<Row> kept;
    std::vector<Index> taken;
    for (const Row& r : rows_) {
        const Row m{map[r.v], map[r.a], map[r.b]};
        if (m.v == kInvalidIndex || m.a == kInvalidIndex || m.b == kInvalidIndex || m.v == m.a ||
            m.v == m.b || m.a == m.b)
            continue;
        kept.push_back(m);
        taken.push_back(m.v);
    }
    // A vertex that two rows claim (a seam's two copies of one curve) keeps the first row.
    std::vector<std::size_t> order(kept.size());
    for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t x, std::size_t y) { return kept[x].v < kept[y].v; });
    rows_.clear();
    moving_.clear();
    for (std::size_t k = 0; k < order.size(); ++k) {
        if (k > 0 && kept[order[k]].v == kept[order[k - 1]].v) continue;
        rows_.push_back(kept[order[k]]);
        moving_.push_back(kept[order[k]].v);
    }
}

namespace {

/// The weight of the curve edge (p, q): 1 (uniform) or 1/length (1-D cotangent), the mean
/// length's where the edge has none.
double edge_weight(const Point& p, const Point& q, bool length_weighted, double fallback) {
    if (!length_weighted) return 1.0;
    const double l = (p - q).norm();
    return l > 0 && std::isfinite(l) ? 1.0 / l : fallback;
}

bool all_finite(const std::vector<Point>& x) {
    return std::all_of(x.begin(), x.end(), [](const Point& p) { return p.allFinite(); });
}

}  // namespace

bool FeatureCurveFairing::step(const CurveStep& s, const std::vector<Point>& P,
                               std::vector<Point>& out) const {
    if (rows_.empty()) return true;
    const std::size_t n = rows_.size();
    double fallback = 1.0;
    if (s.length_weighted) {
        double sum = 0;
        std::size_t count = 0;
        for (const Row& r : rows_)
            for (Index w : {r.a, r.b})
                if (const double l = (P[r.v] - P[w]).norm(); l > 0 && std::isfinite(l)) {
                    sum += l;
                    ++count;
                }
        fallback = count && sum > 0 ? double(count) / sum : 1.0;
    }
    std::vector<Point> x(n);
    // One explicit step of size t from positions Q (where the row's vertices are).
    const auto explicit_step = [&](double t, const std::vector<Point>& Q,
                                   const std::vector<Point>* own) {
        for (std::size_t k = 0; k < n; ++k) {
            const Row& r = rows_[k];
            const Point& xv = own ? (*own)[k] : Q[r.v];
            const Point& xa = Q[r.a];
            const Point& xb = Q[r.b];
            const double ca = edge_weight(xv, xa, s.length_weighted, fallback);
            const double cb = edge_weight(xv, xb, s.length_weighted, fallback);
            x[k] = xv + t * ((ca * xa + cb * xb) / (ca + cb) - xv);
        }
    };
    if (!s.implicit || s.mu != 0) {
        explicit_step(s.t, P, nullptr);
        if (s.mu != 0) {
            // Taubin's second step, from the first step's positions.
            std::vector<Point> Q = P;
            for (std::size_t k = 0; k < n; ++k) Q[rows_[k].v] = x[k];
            const std::vector<Point> own = x;
            explicit_step(s.mu, Q, &own);
        }
    } else {
        // (D + t K) x' = D x: diagonal (1 + t)(c_a + c_b), -t c_e off the diagonal between two
        // moving vertices, + t c_e x_e on the right for a fixed neighbour.
        std::vector<Index> row_of;  // vertex -> row, for the neighbours
        row_of.assign(P.size(), kInvalidIndex);
        for (std::size_t k = 0; k < n; ++k) row_of[rows_[k].v] = Index(k);
        std::vector<Eigen::Triplet<double>> trip;
        trip.reserve(3 * n);
        Eigen::MatrixXd rhs(static_cast<Eigen::Index>(n), 3);
        for (std::size_t k = 0; k < n; ++k) {
            const Row& r = rows_[k];
            const auto i = Eigen::Index(k);
            const double ca = edge_weight(P[r.v], P[r.a], s.length_weighted, fallback);
            const double cb = edge_weight(P[r.v], P[r.b], s.length_weighted, fallback);
            trip.emplace_back(i, i, (1.0 + s.t) * (ca + cb));
            Eigen::RowVector3d b = (ca + cb) * P[r.v].transpose();
            for (const auto& [w, c] : {std::pair<Index, double>{r.a, ca}, {r.b, cb}}) {
                if (row_of[w] != kInvalidIndex)
                    trip.emplace_back(i, Eigen::Index(row_of[w]), -s.t * c);
                else
                    b += s.t * c * P[w].transpose();
            }
            rhs.row(i) = b;
        }
        const auto rows = static_cast<Eigen::Index>(n);
        Eigen::SparseMatrix<double> a(rows, rows);
        a.setFromTriplets(trip.begin(), trip.end());
        const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(a);
        if (ldlt.info() != Eigen::Success) return false;
        const Eigen::MatrixXd y = ldlt.solve(rhs);
        if (ldlt.info() != Eigen::Success || !y.allFinite()) return false;
        for (std::size_t k = 0; k < n; ++k) x[k] = y.row(Eigen::Index(k)).transpose();
    }
    if (!all_finite(x)) return false;
    for (std::size_t k = 0; k < n; ++k) out[rows_[k].v] = x[k];
    return true;
}

}  // namespace trilab
