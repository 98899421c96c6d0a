#pragma once
// Uniform subdivision of triangle meshes, with boundaries (section 1.3 of the reference):
//  - Loop (Loop 1987; approximating, 1-to-4);
//  - Sqrt3 (Kobbelt 2000; approximating; two steps split a boundary edge in three);
//  - Butterfly (Dyn, Levin, Gregory 1990; interpolating, w = 1/16);
//  - Modified Butterfly (Zorin, Schröder, Sweldens 1996; interpolating).
// Every iteration's level is returned by default, each new vertex with where it starts on the
// coarser surface (for the morph) and every vertex with its level; SubdivisionOptions switches
// the levels and the morph off. Texture coordinates are interpolated linearly; features
// (core/features.h: sharp edges, corner tags) drive Loop's crease rules (DeRose, Kass, Truong
// 1998, exactly as OpenSubdiv 3.5), Sqrt3's (Kobbelt 2000's boundary rule along creases) and
// the butterflies' (the four-point rule along creases; core/algorithms/subdivision_creases.h)
// and are carried to every level; other attributes are dropped.
// Coincident vertices (seams, copies of split vertices) stay together on every level; pillows
// (core/algorithms/pillows.h) come back unchanged with a note. Throws InvalidArgument for
// iterations outside 1 to 10, above 50 million faces, invalid features (a negative or NaN
// sharpness), or a level that overflows to non-finite values; Cancelled from the progress. The
// input is not modified. Complexity: linear in the mesh size per iteration. The rules (stencils,
// boundaries, fallbacks) and the handling of seams: subdivision.cpp.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/algorithms/morph.h"
#include "core/enum_table.h"
#include "core/features.h"
#include "core/halfedge_mesh.h"
#include "core/progress.h"

namespace trilab {

enum class SubdivisionScheme { Loop, Sqrt3, Butterfly, ModifiedButterfly };
/// The one table of SubdivisionScheme (core/enum_table.h): identifier and label of each value.
inline constexpr EnumEntry<SubdivisionScheme> kSubdivisionSchemes[] = {
    {SubdivisionScheme::Loop, "loop", "Loop"},
    {SubdivisionScheme::Sqrt3, "sqrt3", "Sqrt3"},
    {SubdivisionScheme::Butterfly, "butterfly", "Butterfly"},
    {SubdivisionScheme::ModifiedButterfly, "modified-butterfly", "Modified Butterfly"},
};

/// "loop", "sqrt3", "butterfly", "modified-butterfly".
const char* scheme_name(SubdivisionScheme scheme);
/// Parses scheme_name() strings; throws InvalidArgument listing them otherwise.
SubdivisionScheme parse_scheme(const std::string& name);

/// Which features subdivision uses (core/features.h).
using SubdivisionFeatures = FeatureSource;

struct SubdivisionOptions {
    SubdivisionScheme scheme = SubdivisionScheme::Loop;
    int iterations = 1;  ///< 1 to 10 (refused above, or when the result would be absurdly big)
    /// Return every level (coarse to fine). When false only the finest level is returned and
    /// each intermediate level is released as soon as the next one is built.
    bool keep_levels = true;
    /// Compute each returned level's MorphCorrespondence (the start positions). When false its
    /// `positions` stay empty (check_correspondence() refuses it) and no time is spent on it.
    bool morph = true;
    /// Region subdivision only (core/algorithms/region_subdivision.h): grow the closure until
    /// none of its triangles is flatter than the input (on an almost regular mesh: over the whole
    /// connected surface) instead of keeping it next to the selection (the default since issue
    /// 38: green bisections, unflipped Sqrt3 triangles, the earlier levels' closure split 1-to-4
    /// rather than bisected again).
    bool global_closure = false;
    /// The closure next to the selection: the default now; kept so that recipes and sessions
    /// written before issue 38 (`--local-closure`) still read. Not with global_closure.
    bool local_closure = false;
    /// Which features (core/features.h: sharp and semi-sharp edges, corner tags) to use: the
    /// mesh's own, none, or those detected at `feature_angle` degrees first (infinitely sharp;
    /// core/algorithms/feature_detection.h). Loop applies the crease, corner and dart rules
    /// exactly as OpenSubdiv 3.5 does (DeRose, Kass, Truong 1998; uniform creasing, boundary
    /// edges infinitely sharp); Sqrt3 treats sharp edges as boundaries (Kobbelt 2000), the
    /// butterflies use the four-point rule along them (core/algorithms/subdivision_creases.h);
    /// every level carries them (sharpness - 1 per level, per step for Sqrt3). With None the
    /// result has no features.
    SubdivisionFeatures features = SubdivisionFeatures::Stored;
    double feature_angle = 60.0;  ///< SubdivisionFeatures::Auto: the angle, in (0, 180]
};

/// The rule that placed a vertex in one subdivision step ("v:subdivision_stencil").
/// Even vertices are the coarser mesh's vertices, odd ones are new.
enum class SubdivisionStencil : int {
    Unknown = 0,
    EvenRegular,        ///< Loop: interior vertex of valence 6
    EvenExtraordinary,  ///< Loop: interior vertex of another valence
    EvenBoundary,       ///< Loop, Sqrt3: boundary rule (1/8, 3/4, 1/8 or its Sqrt3 analogue)
    EvenCrease,         ///< on a seam of coincident copies: the boundary rule, welded
    EvenKept,           ///< interpolating schemes: the old vertex stays where it is
    EvenRelaxed,        ///< Sqrt3: interior vertex relaxed with its ring
    OddRegular,         ///< edge vertex, both ends regular (Loop 3/8-1/8, the 8/10-point butterfly)
    OddExtraordinary,   ///< Butterfly family: an end is extraordinary (Zorin's or a fallback)
    OddBoundary,        ///< edge vertex on a boundary edge
    OddCrease,          ///< edge vertex on a seam of coincident copies
    OddFace,            ///< Sqrt3: the centroid of a face
    OddBoundarySplit,   ///< Sqrt3: one of the two vertices splitting a boundary edge in three
    OddClosureMidpoint,  ///< region subdivision: closure edge outside the selection, its midpoint
    EvenDart,            ///< Loop with features: one sharp edge (the smooth rule)
    EvenSharpCrease,     ///< Loop with features: two sharp edges (3/4, 1/8, 1/8 along them)
    EvenCorner,          ///< Loop with features: three or more sharp edges (stays)
    EvenTaggedCorner,    ///< Loop with features: tagged as a corner (stays)
    EvenSemiSharp,       ///< Loop with features: rules blended (sharp edges turn smooth)
    OddSharp,            ///< Loop with features: on an edge of sharpness > 1 (midpoint)
    OddSemiSharp,        ///< with features: sharpness <= 1 (sharp and smooth rules blended)
    EvenCreaseCurve,     ///< Sqrt3 with features: two sharp edges (kept, or 4/19/4 along them)
    OddCreaseSplit,      ///< Sqrt3 with features: one of the two points splitting a sharp edge
    OddFourPoint,        ///< butterflies with features: the four-point rule along a sharp edge
    OddDamped,           ///< region subdivision: moved from its stencil toward its edge's midpoint
};
/// Words for a stencil ("even, regular (valence 6)", "odd, face centroid").
const char* subdivision_stencil_label(SubdivisionStencil stencil);
/// Whether the stencil places an old (even) vertex.
bool is_even_stencil(SubdivisionStencil stencil);
/// Parents of a vertex in the previous level ("v:subdivision_parents").
using SubdivisionParents = Eigen::Matrix<Index, 3, 1>;

/// One subdivision level: the refined mesh and how it morphs from the previous level
/// (MorphCorrespondence::Kind::FromEarlier: every vertex's start position on the coarser
/// surface; even vertices start at their old position, odd ones at their parent edge's
/// midpoint or parent face's centroid). The mesh carries, per vertex:
///  - "v:subdivision_level" (int): the iteration that created the vertex, 0 for the original
///    vertices;
///  - "v:subdivision_stencil" (int, a SubdivisionStencil): the rule of this level's step that
///    placed the vertex;
///  - "v:subdivision_parents" (SubdivisionParents): the vertices of the previous level (indices
///    into the previous level's mesh) the rule started from: an even vertex's old self, an
///    edge vertex's two ends, a Sqrt3 face vertex's three corners; unused entries
///    kInvalidIndex.
struct SubdivisionLevel {
    HalfedgeMesh mesh;
    MorphCorrespondence correspondence;
};

struct SubdivisionResult {
    /// One per iteration, coarse to fine; only the finest (the last iteration's) when
    /// options.keep_levels is false.
    std::vector<SubdivisionLevel> levels;
    /// Vertices and faces of every level, coarse to fine, whether kept or not.
    std::vector<std::array<std::size_t, 2>> level_counts;
    /// Lines for the user about what was left as it is (pillows).
    std::vector<std::string> notes;
    double ms = 0;
};

/// Subdivides a copy of `mesh` `options.iterations` times. The input must be a triangle mesh;
/// one with garbage is compacted in a copy first, pillows are set aside (see above). It is not
/// modified. Throws
/// InvalidArgument for bad options (naming them) and for a level whose positions or texture
/// coordinates overflow to infinity (coordinates near the largest double), Cancelled when
/// `progress` asks to stop.
SubdivisionResult subdivide(const HalfedgeMesh& mesh, const SubdivisionOptions& options,
                            Progress& progress);

/// Throws InvalidArgument for a feature angle outside (0, 180] with SubdivisionFeatures::Auto,
/// or features that check_features() refuses (core/features.h). O(V + E).
void check_subdivision_features(const HalfedgeMesh& mesh, const SubdivisionOptions& options);
/// Detects the features of `mesh` at options.feature_angle degrees (infinitely sharp; stored
/// on it, core/algorithms/feature_detection.h) and returns the note subdivide() reports ("features
/// detected at A deg: N sharp edges, M corners"). O(V + E).
std::string detect_subdivision_features(HalfedgeMesh& mesh, const SubdivisionOptions& options);

/// What one uniform step of a 1-to-4 scheme (Loop, Butterfly, Modified Butterfly) gives each
/// vertex, without building the refined mesh (region subdivision,
/// core/algorithms/region_subdivision.h, refines only part of the mesh with these stencils):
/// old vertex v at index v, the new vertex of edge e at n_vertices + e; positions computed on
/// the weld where the mesh has coincident vertices, exactly as subdivide() computes them.
struct UniformStep1to4 {
    std::vector<Point> positions;
    std::vector<int> stencils;  ///< SubdivisionStencil values
};
/// The uniform step's positions and stencils on `mesh`, which must be compact (no garbage)
/// and free of pillows; with `features`, by the crease rules of the mesh's features (as
/// subdivide() with SubdivisionFeatures::Stored). Throws InvalidArgument for garbage or Sqrt3.
/// O(V + E) (plus the coincidence search, O(V log V)).
UniformStep1to4 uniform_step_1to4(const HalfedgeMesh& mesh, SubdivisionScheme scheme,
                                  Progress& progress, bool features = false);

/// The same values as uniform_step_1to4(), bit for bit, computed only for the flagged old
/// vertices (`vertices`, one flag per vertex) and edges (`edges`, one per edge) from their
/// one rings: what a region needs. The other entries are zero (positions) and EvenKept
/// (stencils). The mesh must be compact and must have no coincident vertices (on a weld the
/// stencils reach across seams: use uniform_step_1to4()); throws InvalidArgument for garbage,
/// Sqrt3 or flags that do not fit. O(V + E) to scan the flags, plus O(valence) per flagged
/// element.
UniformStep1to4 uniform_step_1to4_at(const HalfedgeMesh& mesh, SubdivisionScheme scheme,
                                     const std::vector<std::uint8_t>& vertices,
                                     const std::vector<std::uint8_t>& edges, Progress& progress);

/// The same values again, packed: entry i of the result is old vertex `vertices[i]`, entry
/// vertices.size() + j the new vertex of edge `edges[j]` (indices must be in range), so that
/// a small region allocates a small result. Same preconditions and errors as
/// uniform_step_1to4_at(). O(valence) per listed element. `rings_listed` promises that
/// `edges` is ascending and holds every edge with an end in `vertices` (region subdivision's
/// lists): Loop's even rule then sums the neighbours in one pass over those edges (the order
/// of subdivide()'s own pass, the same bits) instead of sorting each vertex's ring.
UniformStep1to4 uniform_step_1to4_listed(const HalfedgeMesh& mesh, SubdivisionScheme scheme,
                                         const std::vector<Index>& vertices,
                                         const std::vector<Index>& edges, Progress& progress,
                                         bool rings_listed = false);

}  // namespace trilab
