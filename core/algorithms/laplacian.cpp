// Discrete Laplacians (core/algorithms/laplacian.h): conventions, weights and derivations.
//
// Discrete Laplacians of a triangle mesh as Eigen sparse matrices (sections 1.2.4-1.2.7 of the
// reference report), shared by explicit and implicit fairing.
//
// Sign convention (one for every operator): L·x approximates the Laplacian of x, so that
// x + dt·L·x smooths (explicit Euler, 1.4/1.6) and L·(constant) = 0. Every operator is
// written as L = -S⁻¹·K with
//  - K symmetric positive semi-definite ("stiffness"), K·1 = 0;
//  - S diagonal and positive on free rows (the row normalizer).
// Implicit Euler (1.13-1.14), (I - dt·L)·X' = X, is solved in the symmetric form
// (S + dt·K)·X' = S·X, which is SPD whenever K is PSD and S > 0.
//
// Operators (w_ij: symmetric edge weight; K = D - W with D_ii = sum_j w_ij). Every operator is
// scale-free: L·x scales like x, so a mesh and the same mesh scaled by any factor smooth alike.
//  - Umbrella (1.5): w_ij = 1, S_i = valence. L_i = 1/m sum (x_j - x_i).
//  - ImprovedUmbrella (1.7) with every length measured in units of the mean edge length h
//    (of the positions it is built on): w_ij = h/|e_ij|, S_i = E_i/(2h) with E_i = sum_j
//    |e_ij|, so L_i = 2h²/E sum (x_j - x_i)/|e_ij|, i.e. h² x (1.7). On a mesh of equal edges
//    it is twice the umbrella. Lengths are frozen for one build (one step).
//  - CurvatureFlow (1.9, Desbrun-Meyer-Schröder-Barr 1999): w_ij = cot a_ij + cot b_ij,
//    S_i = sum_j w_ij (normalized cotangent weights). Negative weights (obtuse pairs) are
//    clamped to 0 by default and counted; then K stays PSD. Linear precision holds where
//    nothing was clamped (e.g. a flat grid).
//  - SecondOrder (1.10-1.12, Guskov-Sweldens-Schröder 1999): K = Cᵀ·C, where C has one row
//    per interior edge e holding the hinge coefficients c_{e,·}. (K·x)_i / K_ii is the
//    relaxation update (1.12): x_i <- -(sum_e c_{e,i} a_e) / sum_e c_{e,i}² with a_e =
//    sum_{j != i} c_{e,j} x_j. Applied to every vertex at once (Jacobi) that update is not
//    stable: K is a discrete bi-Laplacian, whose highest frequency has K's Rayleigh quotient
//    above 2 K_ii (16/6 K_ii for the 1-D stencil 1 -4 6 -4 1; about 2.3 K_ii on a noisy
//    sphere), so x <- x - D⁻¹K·x amplifies it (a regular pattern of spikes). So S_i = ½ sum_j
//    |K_ij| (half K's absolute row sum): by Gershgorin every eigenvalue of S⁻¹K lies in
//    [0, 2], as for the umbrella, every explicit step <= 1 is stable, and step 1 is the
//    relaxation (1.12) damped per vertex by 2 K_ii / sum_j |K_ij| <= 1 (about 2/3; exactly
//    1 where the row's off-diagonal entries are all <= 0).
// Fixed-weight operators (Umbrella) do not depend on the positions; the others are rebuilt
// from the current positions for every step.
//
// Derivation of the hinge coefficients. Edge e = (v1, v2), length l, unit direction t,
// triangles T1 = (v1, v2, v3) and T2 = (v2, v1, v4) unfolded into the plane, n the in-plane
// unit normal of e pointing into T1. D(e) is the jump, across e, of the derivative along n
// of the piecewise-linear function f with values f_i at the corners (the tangential
// derivative is continuous). Place v1 at (0,0), v2 at (l,0), v3 at (a,h3), v4 at (b,-h4).
// The hat functions' y-derivatives are, in T1: φ3: 1/h3, φ1: -(l-a)/(l·h3), φ2: -a/(l·h3);
// in T2: φ4: -1/h4, φ1: (l-b)/(l·h4), φ2: b/(l·h4). Hence D = sum c_i f_i with
//   c3 = 1/h3, c4 = 1/h4, c1 = -(l-a)/(l·h3) - (l-b)/(l·h4), c2 = -a/(l·h3) - b/(l·h4).
// With h3 = 2·A1/l, l - a = (v2 - v3)·t, a = (v3 - v1)·t (signed areas and the edge length,
// invariant under the unfolding) and cot θ = dot/|cross| at each corner, multiplying by l
// (to make D dimensionless, like a dihedral angle) gives
//   c3 = cot θ1(T1) + cot θ2(T1),  c4 = cot θ1(T2) + cot θ2(T2),
//   c1 = -(cot θ2(T1) + cot θ2(T2)),  c2 = -(cot θ1(T1) + cot θ1(T2)),
// θk(T) the angle of T at vk. They sum to 0 (constants) and annihilate f = x and f = y in the
// unfolded plane (linear functions): c2·l + c3·a - c4·b = -a/h3 - b/h4 + a/h3 + b/h4 = 0 (times
// l) and c3·h3 - c4·h4 = 0.
//
// Vertex index map: rows/columns are the live, non-isolated vertices in storage order.
// Isolated and deleted vertices have no row and never move. Boundary vertices are fixed by
// default (a fixed row of L is zero). A free vertex whose normalizer S_i vanishes (all its
// weights clamped, degenerate fan) is fixed too and counted as stalled.
//
// Mass matrix option (used by the spectral decomposition, core/algorithms/spectral.h): by default S
// is the row normalizer above. MassMatrix::Barycentric and MassMatrix::Voronoi replace it by a
// lumped mass S_i = 2·A_i with A_i the barycentric (a third of the incident triangle areas)
// or the mixed Voronoi area (Meyer, Desbrun, Schröder, Barr 2003: Voronoi region of non-obtuse
// triangles, half / a quarter of an obtuse triangle's area). The factor 2 matches K's full
// cotangent weights (cot a + cot b = 2 x the FEM stiffness), so for CurvatureFlow K·x = λ·S·x
// approximates the Laplace-Beltrami eigenproblem (on a sphere of radius r: l(l+1)/r²).
//
// Degenerate geometry never produces NaN: corners of zero-area triangles get cotangent 0,
// cotangents are clamped to ±kMaxCotangent, edge lengths below 1e-6 x the mean edge length are
// raised to it; every such event is counted in LaplacianDiagnostics.
// Complexity: O(vertices + faces) to build (the pattern once, then values in place).
#include "core/algorithms/laplacian.h"

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
    const double cross2 = u.cross(w).squaredNorm();
    const double scale2 = u.squaredNorm() * w.squaredNorm();
    // Degenerate: a zero-length side, overflow, or sin(angle) below 1e-14 (one square root).
    if (!(scale2 > 0) || !std::isfinite(scale2) || !(cross2 > 1e-28 * scale2)) {
        ++d.degenerate_corners;
        return 0.0;
    }
    double c = u.dot(w) / std::sqrt(cross2);
    if (std::abs(c) > kMaxCotangent) {
        ++d.cotangents_clamped;
        c = std::clamp(c, -kMaxCotangent, kMaxCotangent);
    }
    return c;
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
    return enum_id<MassMatrix>(kMassMatrices, mass);
}

MassMatrix parse_mass_matrix(const std::string& name) {
    return parse_enum<MassMatrix>(kMassMatrices, name, "mass matrix");
}

const char* laplacian_operator_name(LaplacianOperator op) {
    return enum_id<LaplacianOperator>(kLaplacianOperators, op);
}

LaplacianOperator parse_laplacian_operator(const std::string& name) {
    return parse_enum<LaplacianOperator>(kLaplacianOperators, name, "operator");
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

namespace {

/// The position of entry (row, col) in the compressed column-major K (it must exist).
Index slot_of(const SparseMatrix& K, Eigen::Index row, Eigen::Index col) {
    const int* begin = K.innerIndexPtr() + K.outerIndexPtr()[col];
    const int* end = K.innerIndexPtr() + K.outerIndexPtr()[col + 1];
    const int* it = std::lower_bound(begin, end, int(row));
    return Index(it - K.innerIndexPtr());
}

/// The operator's hinge (SecondOrder) or edge (other operators) entries of one edge, in the
/// order of the slots recorded for it.
struct Hinge {
    Index r[4];
};

}  // namespace

Laplacian build_laplacian(const HalfedgeMesh& mesh, LaplacianOperator op,
                          const LaplacianOptions& options) {
    Laplacian lap;
    lap.op = op;
    lap.options = options;
    lap.map = make_vertex_index_map(mesh);
    const auto n = Eigen::Index(lap.map.rows());
    const auto& row = lap.map.row_of;
    // The sparsity pattern, once: the diagonal, and each edge's pairs (each hinge's 4 x 4
    // block for SecondOrder). refresh_laplacian() then writes values into fixed slots.
    if (op == LaplacianOperator::SecondOrder) {
        std::vector<Triplet> trip;
        for (Eigen::Index r = 0; r < n; ++r) trip.emplace_back(r, r, 0.0);
        for (Edge e : mesh.edges()) {
            if (mesh.is_boundary(e)) continue;
            const Halfedge h0 = HalfedgeMesh::halfedge(e, 0);
            const Index r[4] = {row[mesh.from_vertex(h0).idx()], row[mesh.to_vertex(h0).idx()],
                                row[mesh.to_vertex(mesh.next(h0)).idx()],
                                row[mesh.to_vertex(mesh.next(HalfedgeMesh::twin(h0))).idx()]};
            for (int a = 0; a < 4; ++a)
                for (int b = 0; b < 4; ++b) trip.emplace_back(r[a], r[b], 0.0);
        }
        lap.K.resize(n, n);
        lap.K.setFromTriplets(trip.begin(), trip.end());
    } else {
        // Column r (= row r, K is symmetric): r itself and its one-ring, sorted, built
        // directly in compressed form from the half-edge fans.
        std::vector<int> outer(std::size_t(n) + 1, 0), inner;
        inner.reserve(std::size_t(n) + 2 * mesh.n_edges());
        std::vector<int> column;
        for (Eigen::Index r = 0; r < n; ++r) {
            column.clear();
            column.push_back(int(r));
            const Vertex v = lap.map.vertex_of[std::size_t(r)];
            const Halfedge first = mesh.halfedge(v);
            Halfedge h = first;
            std::size_t guard = 0;
            do {
                column.push_back(int(row[mesh.to_vertex(h).idx()]));
                h = mesh.cw_rotated(h);
            } while (h != first && ++guard < mesh.halfedges_size());
            std::sort(column.begin(), column.end());
            column.erase(std::unique(column.begin(), column.end()), column.end());
            inner.insert(inner.end(), column.begin(), column.end());
            outer[std::size_t(r) + 1] = int(inner.size());
        }
        const std::vector<double> zeros(inner.size(), 0.0);
        lap.K = Eigen::Map<const SparseMatrix>(n, n, Eigen::Index(inner.size()), outer.data(),
                                               inner.data(), zeros.data());
    }
    lap.K.makeCompressed();
    lap.diag_slots.resize(std::size_t(n));
    for (Eigen::Index r = 0; r < n; ++r) lap.diag_slots[std::size_t(r)] = slot_of(lap.K, r, r);
    for (Edge e : mesh.edges()) {
        const Halfedge h0 = HalfedgeMesh::halfedge(e, 0);
        const Index i = row[mesh.from_vertex(h0).idx()], j = row[mesh.to_vertex(h0).idx()];
        if (op == LaplacianOperator::SecondOrder) {
            if (mesh.is_boundary(e)) continue;
            const Index r[4] = {i, j, row[mesh.to_vertex(mesh.next(h0)).idx()],
                                row[mesh.to_vertex(mesh.next(HalfedgeMesh::twin(h0))).idx()]};
            for (int a = 0; a < 4; ++a)
                for (int b = 0; b < 4; ++b) lap.edge_slots.push_back(slot_of(lap.K, r[a], r[b]));
        } else {
            lap.edge_slots.push_back(slot_of(lap.K, i, j));
            lap.edge_slots.push_back(slot_of(lap.K, j, i));
        }
    }
    lap.L = lap.K;  // same pattern; fixed rows hold explicit zeros
    lap.S.resize(n);
    lap.fixed.assign(std::size_t(n), 0);
    refresh_laplacian(mesh, lap);
    return lap;
}

void refresh_laplacian(const HalfedgeMesh& mesh, Laplacian& lap) {
    const LaplacianOperator op = lap.op;
    const std::size_t n = lap.map.rows();
    LaplacianDiagnostics diag;
    const auto& row = lap.map.row_of;
    double* k = lap.K.valuePtr();
    std::fill(k, k + lap.K.nonZeros(), 0.0);
    Eigen::VectorXd& S = lap.S;
    S.setZero();
    std::size_t slot = 0;

    if (op == LaplacianOperator::SecondOrder) {
        // K = Cᵀ C, one hinge per interior edge; see the header for the coefficients.
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
            const double c[4] = {-(t1_2 + t2_2), -(t1_1 + t2_1), t1_1 + t1_2, t2_1 + t2_2};
            for (int a = 0; a < 4; ++a)
                for (int b = 0; b < 4; ++b) k[lap.edge_slots[slot++]] += c[a] * c[b];
        }
        // S_i = ½ sum_j |K_ij| (column i of the symmetric K): eigenvalues of S⁻¹K in [0, 2].
        const int* outer = lap.K.outerIndexPtr();
        for (std::size_t r = 0; r < n; ++r) {
            double sum = 0;
            for (int p = outer[r]; p < outer[r + 1]; ++p) sum += std::abs(k[p]);
            S[Eigen::Index(r)] = 0.5 * sum;
        }
    } else {
        // CurvatureFlow: the cotangent of the corner opposite each halfedge, one face at a
        // time (its three corners from three position loads), 0 on boundary halfedges.
        std::vector<double>& cot = lap.halfedge_cotangents;
        if (op == LaplacianOperator::CurvatureFlow) {
            cot.assign(mesh.halfedges_size(), 0.0);
            for (Face f : mesh.faces()) {
                const Halfedge h0 = mesh.halfedge(f), h1 = mesh.next(h0), h2 = mesh.next(h1);
                const Point& a = mesh.position(mesh.from_vertex(h0));
                const Point& b = mesh.position(mesh.to_vertex(h0));
                const Point& c = mesh.position(mesh.to_vertex(h1));
                cot[h0.idx()] = corner_cot(c, a, b, diag);
                cot[h1.idx()] = corner_cot(a, b, c, diag);
                cot[h2.idx()] = corner_cot(b, c, a, diag);
            }
        }
        // ImprovedUmbrella: lengths in units of the mean edge length (scale-free weights).
        double unit = 1, min_len = 1e-300;
        if (op == LaplacianOperator::ImprovedUmbrella) {
            const double mean = mean_edge_length(mesh);
            if (mean > 0 && std::isfinite(mean)) {
                unit = mean;
                min_len = 1e-6 * mean;
            }
        }
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
                w = unit / len;
                S[i] += 0.5 * len / unit;
                S[j] += 0.5 * len / unit;
            } else if (op == LaplacianOperator::CurvatureFlow) {
                w = cot[h.idx()] + cot[HalfedgeMesh::twin(h).idx()];
                if (w < 0 && lap.options.clamp_negative_cotangents) {
                    ++diag.negative_weights_clamped;
                    w = 0;
                }
            }
            if (op != LaplacianOperator::ImprovedUmbrella) {
                S[i] += w;
                S[j] += w;
            }
            k[lap.edge_slots[slot++]] -= w;
            k[lap.edge_slots[slot++]] -= w;
            k[lap.diag_slots[i]] += w;
            k[lap.diag_slots[j]] += w;
        }
    }
    if (lap.options.mass != MassMatrix::Normalizer) lumped_mass(mesh, lap.map, lap.options.mass, S);

    // Fixed rows: boundary (by option) and stalled vertices.
    double s_max = 0;
    for (Eigen::Index r = 0; r < S.size(); ++r)
        if (std::isfinite(S[r])) s_max = std::max(s_max, std::abs(S[r]));
    for (std::size_t r = 0; r < n; ++r) {
        const Vertex v = lap.map.vertex_of[r];
        lap.fixed[r] = 0;
        if ((lap.options.fix_boundary && mesh.is_boundary(v)) ||
            (!lap.options.fixed_vertices.empty() && lap.options.fixed_vertices[v.idx()])) {
            lap.fixed[r] = 1;
        } else if (!(S[Eigen::Index(r)] > 1e-12 * s_max)) {
            lap.fixed[r] = 1;
            ++diag.stalled_vertices;
        }
        if (lap.fixed[r]) S[Eigen::Index(r)] = 1.0;
    }

    // L = -S⁻¹ K on free rows (same pattern as K, zeros on fixed rows).
    const int* inner = lap.K.innerIndexPtr();
    double* l = lap.L.valuePtr();
    for (Eigen::Index p = 0; p < lap.K.nonZeros(); ++p) {
        const int r = inner[p];
        l[p] = lap.fixed[std::size_t(r)] ? 0.0 : -k[p] / S[r];
    }
    lap.diagnostics = diag;
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
