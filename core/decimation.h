#pragma once
// Mesh decimation by edge collapse (section 1.4 of the reference report).
//
// Method: every edge gets a cost and the cheapest collapse goes first, from a binary heap of
// (cost, edge) entries with lazy invalidation (an entry whose cost is no longer its edge's is
// skipped), so the queue stays exact while costs change; after a collapse only the edges at
// the kept vertex are re-priced. Meshes of more than 50,000 vertices are first reduced in
// batches down to max(50,000, 4 x target): each pass selects the cheapest edges, up to half
// the vertex count (nth_element), and collapses them in memory order (for the cache),
// skipping edges re-priced during the pass; the exact heap then does the last collapses, the
// ones that shape the result. Costs:
//  - Quadric (Garland, Heckbert, "Surface simplification using quadric error metrics",
//    SIGGRAPH 1997): per-vertex quadrics of the incident face planes, summed on collapse; the
//    kept vertex moves to the minimizer of Q0 + Q1 (the 3x3 system), or, where that is
//    ill-conditioned or lands far from the edge, to the best of the two ends and the
//    midpoint. Each boundary edge adds a heavily weighted plane through it, perpendicular to
//    its face, to both its ends, so boundaries keep their shape.
//  - Roundness (1.4.2): R = circumradius / shortest edge, normalized as sqrt(1/3) / R (1 for
//    an equilateral triangle, towards 0 for a sliver); a halfedge collapse (the kept vertex
//    stays) is weighted by the smallest normalized roundness among the triangles it changes,
//    and the collapse with the largest such minimum goes first.
// Binary constraints (1.4.3), each switchable: a roundness threshold, normal flipping (no
// changed face normal turns by more than an angle; degenerate results are refused too),
// an independent set (after a collapse the one-ring of the kept vertex is locked until the
// next iteration), and a maximum quadric error (a distance: the collapse is refused when the
// quadric error exceeds its square).
//
// Guarantees: the topology is always protected by the link condition
// (HalfedgeMesh::is_collapse_ok), so every output is a valid manifold mesh with the input's
// boundary loops, components and genus; a boundary vertex only moves along a boundary edge.
// With "v:texcoord" the kept vertex's uv is interpolated along the edge; with per-corner
// "h:texcoord", vertices on a texture seam are never removed and the corners that move keep
// the seam's side (no seam is torn open). Other attributes ride along with the kept vertex.
// The input is never modified. Progressive mesh (Hoppe, "Progressive meshes", SIGGRAPH 1996):
// every collapse is recorded with the vertex split that undoes it.
//
// Complexity: O(E) per batch pass (a few dozen passes: the mesh shrinks geometrically), O(E)
// to fill the heap (make_heap), then O(d^2 + d log E) per collapse for valence d; no
// allocation per collapse (amortized); garbage collection once per iteration.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/enum_table.h"
#include "core/halfedge_mesh.h"
#include "core/morph.h"
#include "core/progress.h"

namespace trilab {

enum class DecimationCost { Quadric, Roundness };
/// The one table of DecimationCost (core/enum_table.h): identifier and label of each value.
inline constexpr EnumEntry<DecimationCost> kDecimationCosts[] = {
    {DecimationCost::Quadric, "quadric", "Quadrics"},
    {DecimationCost::Roundness, "roundness", "Roundness"},
};
/// "quadric", "roundness".
const char* decimation_cost_name(DecimationCost cost);
/// Parses decimation_cost_name() strings; throws InvalidArgument listing them otherwise.
DecimationCost parse_decimation_cost(const std::string& name);

struct DecimationOptions {
    DecimationCost cost = DecimationCost::Quadric;
    /// Amount: when target_vertices > 0, one iteration down to that many vertices; otherwise
    /// `iterations` iterations that each remove floor(percent / 100 * V) of the V vertices at
    /// the start of the iteration (the reference's "collapse P percent per iteration").
    /// Vertex counts are of the vertices with faces: isolated vertices are kept as they are
    /// and not counted.
    double percent = 60;              ///< (0, 100]
    int iterations = 1;               ///< 1 to 1000
    std::size_t target_vertices = 0;  ///< 0: use percent and iterations

    bool normal_flip = true;         ///< the normal-flipping constraint
    double max_normal_angle = 90;    ///< degrees, (0, 180]
    bool roundness = false;          ///< the roundness constraint
    double min_roundness = 0.2;      ///< normalized roundness, (0, 1]
    bool independent_set = false;    ///< the independent-set constraint
    double max_error = 0;            ///< quadric error as a distance; 0: no limit
    bool record_progressive = true;  ///< fill DecimationResult::progressive
};

/// Why a decimation ended.
enum class DecimationStop {
    Done,         ///< every iteration reached its vertex count
    MaxError,     ///< the next collapse would exceed max_error
    Constraints,  ///< every remaining collapse was refused by a binary constraint
    Topology,     ///< no collapse keeps a manifold mesh (e.g. a tetrahedron)
};
/// The one table of DecimationStop (core/enum_table.h): identifier and label of each value.
inline constexpr EnumEntry<DecimationStop> kDecimationStops[] = {
    {DecimationStop::Done, "done", "done"},
    {DecimationStop::MaxError, "max-error", "maximum error"},
    {DecimationStop::Constraints, "constraints", "constraints"},
    {DecimationStop::Topology, "topology", "topology"},
};
/// "done", "max-error", "constraints", "topology".
const char* decimation_stop_name(DecimationStop stop);

/// What a run did; refusals count every time a collapse candidate was refused.
struct DecimationReport {
    std::size_t input_vertices = 0, output_vertices = 0;  ///< vertices with faces
    std::size_t isolated_vertices = 0;                    ///< kept, in addition
    std::size_t collapses = 0;
    std::size_t refused_topology = 0;  ///< link condition
    std::size_t refused_normal_flip = 0;
    std::size_t refused_roundness = 0;
    std::size_t refused_independent_set = 0;
    std::size_t refused_max_error = 0;
    std::size_t refused_texture_seam = 0;
    DecimationStop stop = DecimationStop::Done;
    std::string stop_message;  ///< how far it got and why, for the user
    double ms = 0;
};

/// One iteration: the decimated mesh (compact) and its geomorph from the previous mesh
/// (MorphCorrespondence::Kind::ToLater: every vertex of the previous mesh ends where the
/// vertex it collapsed into ends; kept vertices end at their new position).
struct DecimationLevel {
    HalfedgeMesh mesh;
    MorphCorrespondence correspondence;
    std::size_t target_vertices = 0;  ///< what the iteration aimed at
};

/// The vertex split that undoes one collapse (indices of the input mesh's storage): `removed`
/// came back at `removed_position`, `kept` returns from `kept_after` to `kept_before`, the
/// faces [moved_begin, moved_end) of ProgressiveMesh::moved_faces get `removed` back as the
/// corner that is `kept`, and `faces` (one, or two for an interior edge) reappear.
struct VertexSplit {
    Vertex removed, kept;
    Point removed_position, kept_before, kept_after;
    std::array<Face, 2> faces;
    std::uint32_t moved_begin = 0, moved_end = 0;
};

/// A progressive mesh: the fine mesh as a face list plus its collapses in order.
struct ProgressiveMesh {
    std::vector<Point> positions;              ///< fine positions, per input vertex index
    std::vector<std::array<Vertex, 3>> faces;  ///< fine corners, per input face index
    std::vector<std::uint8_t> face_alive;      ///< 0 for faces deleted in the input
    std::vector<std::uint8_t> vertex_alive;    ///< 0 for vertices deleted in the input
    std::vector<VertexSplit> collapses;
    std::vector<Face> moved_faces;
};

struct DecimationResult {
    std::vector<DecimationLevel> levels;  ///< one per iteration done (may be fewer, see stop)
    DecimationReport report;
    ProgressiveMesh progressive;  ///< empty unless options.record_progressive
};

/// Decimates a copy of `mesh` (which may have garbage and isolated vertices; isolated
/// vertices are kept and not counted). Throws InvalidArgument for bad options (naming
/// them), Cancelled when `progress` asks to stop. When no collapse is possible the result
/// holds the iterations done (possibly none) and the report says why it stopped.
DecimationResult decimate(const HalfedgeMesh& mesh, const DecimationOptions& options,
                          Progress& progress);
DecimationResult decimate(const HalfedgeMesh& mesh, const DecimationOptions& options);

/// The edges the next iteration would collapse (the first floor(percent / 100 * V) collapses,
/// or down to target_vertices), in order, as (removed vertex, kept vertex) pairs of `mesh`'s
/// indices, for drawing. Runs the decimation on a copy.
std::vector<std::array<Vertex, 2>> next_collapses(const HalfedgeMesh& mesh,
                                                  const DecimationOptions& options);

/// Normalized roundness of the triangle (a, b, c): sqrt(1/3) * shortest edge / circumradius,
/// in [0, 1], 1 for an equilateral triangle, 0 for a degenerate one.
double normalized_roundness(const Point& a, const Point& b, const Point& c);

/// Level of detail over a progressive mesh: moves between any two numbers of collapses by
/// replaying collapses (forward) and vertex splits (backward); each step is O(faces moved).
class LevelOfDetail {
public:
    explicit LevelOfDetail(const ProgressiveMesh& pm);
    /// Number of collapses applied, 0 (fine) to pm.collapses.size() (coarse).
    std::size_t level() const { return level_; }
    void set_level(std::size_t level);
    /// The mesh at the current level: live vertices and faces, compacted (vertex order kept).
    HalfedgeMesh mesh() const;
    /// Current corners of every face of the fine mesh (dead faces have invalid corners).
    const std::vector<std::array<Vertex, 3>>& faces() const { return faces_; }
    const std::vector<std::uint8_t>& face_alive() const { return face_alive_; }
    const std::vector<Point>& positions() const { return positions_; }

private:
    const ProgressiveMesh* pm_;
    std::size_t level_ = 0;
    std::vector<std::array<Vertex, 3>> faces_;
    std::vector<std::uint8_t> face_alive_, vertex_alive_;
    std::vector<Point> positions_;
};

}  // namespace trilab
