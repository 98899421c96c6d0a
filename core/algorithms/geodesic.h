#pragma once
// Geodesic distances on the surface by the heat method (Crane, Weischedel, Wardetzky 2013,
// "Geodesics in heat"), and a geodesic path traced back down the distance field.
//
// Method, on the cotangent Laplacian of core/algorithms/laplacian.h (LaplacianOperator::
// CurvatureFlow, negative weights kept, boundary rows free) with a lumped (barycentric or
// Voronoi) mass M and the time step t = (mean edge length)²:
//  1. heat: solve (M - t·L_c)·u = δ_sources (one implicit Euler step);
//  2. X = -∇u/|∇u| on every face (0 where ∇u vanishes or the face is degenerate);
//  3. solve L_c·φ = ∇·X (the integrated divergence), the cotangent operator with one vertex
//     pinned per connected component (exact: ∇·X sums to 0 over every component);
//  4. shift φ per component so that the sources' mean is 0, set the sources to exactly 0 and
//     clamp rounding below 0 to 0.
// Both systems are factorized once (Eigen SimplicialLDLT) by GeodesicSolver; every later
// distances() call costs two back-substitutions plus two passes over the faces.
// Boundaries: the heat method's Neumann condition (the boundary rows are left free), which is
// accurate away from the boundary and bends the distance's level sets to meet the boundary at
// right angles close to it (Crane et al. section 3.3).
// Unreached vertices: vertices in a connected component that holds no source, and isolated
// vertices that are not sources, get +infinity (there is no path to them); deleted vertices
// get +infinity too.
// Accuracy: on a unit icosphere of 16k vertices within 0.03 of the great-circle distance
// (tests/unit/test_geodesic.cpp); the error is of the order of the mean edge length.
#include <limits>
#include <memory>
#include <vector>

#include "core/algorithms/laplacian.h"
#include "core/halfedge_mesh.h"

namespace trilab {

struct GeodesicOptions {
    /// The lumped mass of the heat step: Barycentric or Voronoi (Normalizer is refused).
    MassMatrix mass = MassMatrix::Barycentric;
    /// Heat step t = time_factor x (mean edge length)²; Crane et al. suggest 1.
    double time_factor = 1.0;
};

/// A point on the surface: at vertex `a` (b invalid), or on the edge a-b at
/// position = (1 - t)·a + t·b with 0 < t < 1.
struct SurfacePoint {
    Vertex a;
    Vertex b;  ///< invalid: the point is the vertex a
    double t = 0;
    Point position = Point::Zero();
    bool on_vertex() const { return !b.is_valid(); }
};

/// Heat-method geodesic distances with both factorizations kept: built once per mesh state
/// (positions and connectivity), then distances() for any number of source sets.
/// Throws InvalidArgument naming `time_factor` or `mass` for bad options. The mesh is copied
/// where needed (only positions and connectivity are used) and never modified.
/// Complexity: construction one sparse Cholesky factorization of each of two V x V
/// systems; distances() O(V + F) plus two back-substitutions.
class GeodesicSolver {
public:
    explicit GeodesicSolver(const HalfedgeMesh& mesh, const GeodesicOptions& options = {});
    ~GeodesicSolver();
    GeodesicSolver(GeodesicSolver&&) noexcept;
    GeodesicSolver& operator=(GeodesicSolver&&) noexcept;

    /// Per vertex storage index: the geodesic distance from the nearest of `sources` (0 at
    /// the sources, +infinity where unreachable; see the file comment). Throws
    /// InvalidArgument when `sources` is empty or names an out-of-range or deleted vertex
    /// (the message names the index).
    std::vector<double> distances(const std::vector<Vertex>& sources) const;

    /// The heat step t used.
    double time_step() const;

private:
    struct State;
    std::unique_ptr<State> state_;
};

/// One-off: GeodesicSolver(mesh, options).distances(sources).
std::vector<double> geodesic_distances(const HalfedgeMesh& mesh, const std::vector<Vertex>& sources,
                                       const GeodesicOptions& options = {});

/// Shortest distances along the edges (Dijkstra) from the nearest of `sources`, per vertex
/// storage index; +infinity where unreachable. An upper bound of the geodesic distance.
/// Throws InvalidArgument as GeodesicSolver::distances. O((V + E) log V).
std::vector<double> edge_graph_distances(const HalfedgeMesh& mesh,
                                         const std::vector<Vertex>& sources);

/// The geodesic path from `target` down to a source of `distances` (as returned above):
/// steepest descent of the piecewise-linear distance field across the faces. From a vertex
/// it leaves through the incident face whose gradient descends steepest into the face; on an
/// edge it crosses into the next face along that face's -∇distance; where the descent
/// direction does not enter the face (or at a boundary edge) it walks along the edge to its
/// lower end, and at a vertex no face descends from it moves to its lowest lower neighbour.
/// Every point is on a vertex or an edge, the distance strictly decreases along the path, and
/// it ends at a vertex of distance 0 (a source), or at a vertex with no lower neighbour.
/// The first point is `target`. Throws InvalidArgument when `distances` does not have one
/// entry per vertex, or `target` is out of range, deleted or unreachable (not finite).
/// Complexity: O(faces crossed x valence).
std::vector<SurfacePoint> geodesic_path(const HalfedgeMesh& mesh,
                                        const std::vector<double>& distances, Vertex target);

/// Length of a path (sum of its segments).
double path_length(const std::vector<SurfacePoint>& path);

}  // namespace trilab
