#pragma once
// Picking and measuring: what the user pointed at on the shown surface, how the picks follow
// the document, and the measurement between two picks (straight and geodesic distance, and
// the geodesic path). The ray cast is core/algorithms/ray_pick.h; the distances are the heat
// method of core/algorithms/geodesic.h, run as a job on a snapshot, with the factorization
// kept for later sources on the same state.
#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/algorithms/inspect.h"
#include "core/algorithms/ray_pick.h"
#include "core/halfedge_mesh.h"

namespace trilab {
class GeodesicSolver;
class LevelOfDetail;
}  // namespace trilab

namespace trilab::viewer {

struct Shown;

/// One pick: the face hit by the ray, its corner and edge nearest to the hit point, and where
/// on the face it was hit. Indices are storage indices of the mesh the picks refer to
/// (PickSet::mesh: the document's, a preview's, a morph frame's connectivity; on a level of
/// detail the document's own vertex and face, and the edge when the document has it).
struct Pick {
    Vertex vertex;
    Edge edge;
    Face face;
    std::array<Vertex, 3> corners;
    std::array<double, 3> barycentric{1.0 / 3, 1.0 / 3, 1.0 / 3};
    Point position = Point::Zero();  ///< the hit point
    bool back_face = false;          ///< the ray met the face's back
    bool on_level = false;           ///< picked on a level of detail
    double ms = 0;                   ///< the ray cast's own time
};

/// The pick's line for logs and `--pick`: "vertex V edge E face F position X Y Z ms T".
std::string pick_line(const Pick& pick);

/// Casts `ray` (from depth t_min) at what `shown` shows. Returns nothing on a miss. For a
/// level of detail the hit is mapped to the document's indices (`document`: the mesh the
/// level was built from).
std::optional<Pick> pick_shown(const Shown& shown, const HalfedgeMesh& document, const Ray& ray,
                               double t_min);

/// Between the first and the second pick.
struct Measurement {
    double straight = std::numeric_limits<double>::quiet_NaN();  ///< |b - a| of the vertices
    double geodesic = std::numeric_limits<double>::quiet_NaN();  ///< heat method
    double path_length = std::numeric_limits<double>::quiet_NaN();
    std::vector<Point> path;  ///< the geodesic path from the second pick to the first
    bool computing = false;
    std::string failure;  ///< why there is no geodesic distance
    double ms = 0;        ///< the job's time (a factorization on a new state)
};

/// What the inspector says about the first pick (core/algorithms/inspect.h), computed off the
/// render thread on the picks' state.
struct PickInspection {
    std::optional<VertexInspection> vertex;
    std::optional<EdgeInspection> edge;
    std::optional<FaceInspection> face;
    std::string failure;
    double ms = 0;
};

/// The picks and what was measured with them; part of the session, not of the history.
struct PickSet {
    /// At most two: the second is where a measurement ends.
    std::vector<Pick> picks;
    /// The state the picks refer to (a shared copy, free).
    HalfedgeMesh mesh;
    Measurement measurement;
    /// Geodesic distance from every picked vertex, per vertex of `mesh` (the "geodesic
    /// distance" colouring); empty until computed.
    std::vector<double> distances;
    /// The first pick's inspection; null while it is computed.
    std::shared_ptr<const PickInspection> inspection;
    /// Changes whenever anything above changes (the view redraws its highlight).
    std::uint64_t version = 0;
    /// The heat method's factorization, for `mesh`'s state (kept for later sources).
    std::shared_ptr<const GeodesicSolver> solver;
    HalfedgeMesh::Revision solver_state;
};

}  // namespace trilab::viewer
