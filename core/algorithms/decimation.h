#pragma once
// Mesh decimation by edge collapse (section 1.4 of the reference report): the cheapest
// collapse first (an exact priority queue; meshes above 50,000 vertices are first reduced in
// batches, on a copy renumbered into a spatial order, so their result and speed do not depend on
// the input's vertex order), until a target vertex count.
//  - Costs: Quadric (Garland, Heckbert, "Surface simplification using quadric error metrics",
//    SIGGRAPH 1997; boundaries keep their shape) or Roundness (1.4.2: the smallest normalized
//    roundness sqrt(1/3)/R of the changed triangles, R = circumradius / shortest edge).
//  - Binary constraints (1.4.3), each switchable: roundness threshold, normal flipping, an
//    independent set per iteration, a maximum quadric error.
// Guarantees: the link condition (HalfedgeMesh::is_collapse_ok) keeps every output a valid
// manifold mesh with the input's boundary loops, components and genus; a boundary vertex only
// moves along a boundary edge; texture seams ("h:texcoord") and coincident copies (seams
// between patches, split non-manifold vertices) never tear open; uvs are interpolated, other
// attributes ride along with the kept vertex. The input is never modified. Progressive mesh
// (Hoppe, "Progressive meshes", SIGGRAPH 1996): every collapse is recorded with the vertex
// split that undoes it (core/algorithms/progressive_mesh.h; the level of detail over it:
// core/algorithms/level_of_detail.h). Throws InvalidArgument naming a bad option; Cancelled from
// the progress; a run that cannot go on stops and says why (DecimationReport::stop). Complexity:
// O(E) per batch pass, then O(d² + d log E) per collapse for valence d, no allocation per collapse;
// big meshes use a second core for their set-up where there is one.
// Method, placement and the seam rules in detail: decimation.cpp.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/algorithms/morph.h"
#include "core/algorithms/progressive_mesh.h"
#include "core/enum_table.h"
#include "core/features.h"
#include "core/halfedge_mesh.h"
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

/// Which meshes DecimationResult::levels holds.
enum class DecimationLevels {
    All,   ///< one per iteration, each with its geomorph from the one before
    Last,  ///< only the last iteration's mesh, its geomorph from the input (no per-iteration copy)
    None,  ///< none (for a run that only records the progressive mesh)
};

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

    bool normal_flip = true;       ///< the normal-flipping constraint
    double max_normal_angle = 90;  ///< degrees, (0, 180]
    bool roundness = false;        ///< the roundness constraint
    double min_roundness = 0.2;    ///< normalized roundness, (0, 1]
    bool independent_set = false;  ///< the independent-set constraint
    double max_error = 0;          ///< quadric error as a distance; 0: no limit

    // What the result carries besides the algorithm (a caller that wants only the decimated
    // mesh sets levels = Last and record_geomorph = false and pays for the collapses alone,
    // plus one copy of the input and one compaction of the output).
    DecimationLevels levels = DecimationLevels::All;
    bool record_geomorph = true;      ///< fill each level's correspondence (O(V) per level)
    bool record_progressive = false;  ///< fill DecimationResult::progressive (about 10 % more)
    /// The region (core/algorithms/selection.h): one weight per vertex storage index, or
    /// nullptr for the whole mesh. Only edges whose two ends both have a positive weight may
    /// collapse (a kept vertex is then selected too), so vertices of weight 0 keep their
    /// positions bit for bit and the border between stays conforming under the same
    /// constraints; `percent` counts the region's vertices (with faces) instead of the mesh's,
    /// while target_vertices stays a vertex count of the whole mesh. Not owned.
    const std::vector<float>* region = nullptr;
    /// The features kept (core/features.h): the mesh's own (Stored), none, or those detected
    /// at `feature_angle` degrees first (Auto; the result carries them). A vertex on a sharp
    /// edge moves only when it is a crease (two sharp edges) and along one of them, into its
    /// neighbour on the curve, which slides along the input polyline (costed by the larger of
    /// the quadric and the chord error against the input curve: decimation.cpp); corners
    /// (three or more sharp edges, or tagged) and curve ends never move; merged edges keep the
    /// larger sharpness. So every output vertex on a feature lies on an input feature curve.
    /// With None the features are carried but not kept.
    FeatureSource features = FeatureSource::Stored;
    double feature_angle = 60.0;  ///< FeatureSource::Auto: the angle, in (0, 180]
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
    std::size_t iterations_done = 0;   ///< iterations that collapsed anything
    std::size_t refused_topology = 0;  ///< link condition
    std::size_t refused_normal_flip = 0;
    std::size_t refused_roundness = 0;
    std::size_t refused_independent_set = 0;
    std::size_t refused_max_error = 0;
    std::size_t refused_texture_seam = 0;
    /// Vertices of the input with a coincident copy (a seam's two sides, the copies of a split
    /// non-manifold vertex: core/algorithms/coincident.h), which never move alone (see above).
    std::size_t coincident_vertices = 0;
    DecimationStop stop = DecimationStop::Done;
    std::string stop_message;  ///< how far it got and why, for the user
    double ms = 0;
};

/// One iteration: the decimated mesh (compact) and its geomorph from the previous mesh
/// (MorphCorrespondence::Kind::ToLater: every vertex of the previous mesh ends where the
/// vertex it collapsed into ends; kept vertices end at their new position). With
/// DecimationLevels::Last the previous mesh is the input; without record_geomorph the
/// correspondence is empty.
/// "v:decimation_source" (Index), on every DecimationLevel's mesh: each vertex's index in the
/// mesh given to decimate(), so a vertex can be followed back through the decimation.
inline constexpr const char* kDecimationSourceName = "v:decimation_source";

struct DecimationLevel {
    HalfedgeMesh mesh;
    MorphCorrespondence correspondence;
    std::size_t target_vertices = 0;  ///< what the iteration aimed at
};

struct DecimationResult {
    std::vector<DecimationLevel> levels;  ///< see DecimationLevels (may be fewer, see stop)
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

/// Why the decimator refuses a collapse, in the order it checks (CollapseExplanation).
enum class CollapseRefusal {
    None,            ///< it would collapse
    NoDirection,     ///< neither end may move (boundary, texture seam or coincident rules)
    MaxError,        ///< the quadric error exceeds max_error
    IndependentSet,  ///< an end is locked by an earlier collapse of the iteration
    Topology,        ///< the link condition (also on the welded surface of a seam)
    TextureSeam,     ///< the removed vertex is on a texture seam
    NormalFlip,      ///< a changed face turns by more than max_normal_angle or degenerates
    Roundness,       ///< a changed face is less round than min_roundness
};
/// "none", "no-direction", "max-error", "independent-set", "topology", "texture-seam",
/// "normal-flip", "roundness".
const char* collapse_refusal_name(CollapseRefusal refusal);

/// What the decimator would decide about collapsing one edge now, as the first collapse of a
/// run with the given options, and the numbers that decide it. Every answer comes from the
/// decimator's own checks (decimation.cpp), each constraint evaluated on its own (a run stops
/// at the first refusal, `refusal`).
struct CollapseExplanation {
    bool possible = false;  ///< some direction is allowed; the rest is unset when false
    Vertex removed, kept;   ///< the direction the decimator chooses (removed moves into kept)
    Point target = Point::Zero();  ///< where the kept vertex goes
    /// The priority: the quadric error (squared distance) for Quadric, minus the smallest
    /// normalized roundness of the changed faces for Roundness (smaller goes first).
    double cost = 0;
    CollapseRefusal refusal = CollapseRefusal::NoDirection;  ///< the first refusal, or None
    bool topology_ok = false;   ///< the link condition (with a seam's other side)
    bool texture_seam = false;  ///< refused: the removed vertex is on a texture seam
    // Each binary constraint: whether it is switched on, whether it refuses, and its numbers.
    bool normal_flip_on = false, normal_flip_refuses = false;
    double largest_normal_change = 0;  ///< degrees, over the changed faces
    bool degenerate_face = false;      ///< a changed face would have no area (refused)
    double max_normal_angle = 0;       ///< the limit, degrees
    bool roundness_on = false, roundness_refuses = false;
    double roundness = 0;      ///< smallest normalized roundness of the changed faces
    double min_roundness = 0;  ///< the limit
    bool independent_set_on = false, independent_set_refuses = false;  ///< never at a start
    bool max_error_on = false, max_error_refuses = false;
    double error = 0;      ///< the quadric error as a distance (sqrt of the quadric cost)
    double max_error = 0;  ///< the limit
};

/// Explains the collapse of live edge `e` of `mesh` under `options` (see CollapseExplanation).
/// Sets up the decimator on `mesh` without copying it (quadrics, boundary flags, coincident
/// vertices: O(V + F)); throws InvalidArgument for bad options or a bad edge.
CollapseExplanation explain_collapse(const HalfedgeMesh& mesh, Edge e,
                                     const DecimationOptions& options);

/// Normalized roundness of the triangle (a, b, c): sqrt(1/3) * shortest edge / circumradius,
/// in [0, 1], 1 for an equilateral triangle, 0 for a degenerate one.
double normalized_roundness(const Point& a, const Point& b, const Point& c);

}  // namespace trilab
