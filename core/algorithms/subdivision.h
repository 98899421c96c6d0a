#pragma once
// Uniform subdivision of triangle meshes, with boundaries (section 1.3 of the reference):
//  - Loop (Loop 1987; approximating, 1-to-4): beta_n = (1/n)(5/8 - (3/8 + cos(2 pi/n)/4)^2);
//    boundary curves use the cubic B-spline rules (odd 1/2, 1/2; even 1/8, 3/4, 1/8).
//  - Sqrt3 (Kobbelt 2000; approximating): a vertex at every face centroid, every old interior
//    edge flipped, even vertices relaxed with alpha_n = (4 - 2 cos(2 pi/n)) / 9; boundary
//    edges are split in every second step so that two steps make a tri-adic boundary split.
//  - Butterfly (Dyn, Levin, Gregory 1990; interpolating): the 8-point stencil, w = 1/16.
//  - Modified Butterfly (Zorin, Schröder, Sweldens 1996; interpolating): the 10-point regular
//    stencil, extraordinary-vertex rules, the 4-point boundary rule.
// By default every iteration's level is returned and each new vertex records where it starts
// on the coarser surface (for the morph); callers that need neither (the CLI) switch both off
// in SubdivisionOptions. Every vertex records its level (for the "subdivision vertices"
// colouring).
// Texture coordinates ("v:texcoord", "h:texcoord") are interpolated linearly.
// Messy meshes (core/algorithms/coincident.h): vertices at the same position (a seam between
// patches, the copies build_mesh() makes of a non-manifold vertex) stay together on every level.
// The 1-to-4 schemes compute their positions on the mesh welded where that keeps it manifold
// (core/algorithms/weld.h), so a seam edge gets the interior stencil with the partner's faces as
// its other side and the copies of a split vertex the rule of the joined vertex; Sqrt3, whose edge
// flips would dissolve a seam, refines each seam as a boundary curve on both sides. Then new
// vertices whose coarse parents coincide (same start position) and still differ (copies the
// weld cannot join: surfaces touching at a point or three sheets at an edge) get their mean.
// Seams stay seams (boundaries): welding is a separate tool. Pillows (core/algorithms/pillows.h)
// are set aside, the rest is refined, and they come back unchanged on every level with a note.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/algorithms/morph.h"
#include "core/enum_table.h"
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

struct SubdivisionOptions {
    SubdivisionScheme scheme = SubdivisionScheme::Loop;
    int iterations = 1;  ///< 1 to 10 (refused above, or when the result would be absurdly big)
    /// Return every level (coarse to fine). When false only the finest level is returned and
    /// each intermediate level is released as soon as the next one is built.
    bool keep_levels = true;
    /// Compute each returned level's MorphCorrespondence (the start positions). When false its
    /// `positions` stay empty (check_correspondence() refuses it) and no time is spent on it.
    bool morph = true;
};

/// One subdivision level: the refined mesh and how it morphs from the previous level
/// (MorphCorrespondence::Kind::FromEarlier: every vertex's start position on the coarser
/// surface; even vertices start at their old position, odd ones at their parent edge's
/// midpoint or parent face's centroid). The mesh carries "v:subdivision_level" (int: the
/// iteration that created the vertex, 0 for the original vertices).
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

}  // namespace trilab
