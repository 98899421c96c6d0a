#pragma once
// Level of detail over a progressive mesh (Hoppe, "Progressive meshes", SIGGRAPH 1996): the
// progressive mesh of a level-of-detail slider (build_progressive_mesh(), a decimation that
// records every collapse) and LevelOfDetail, which moves between its levels by replaying
// collapses and vertex splits. The constructor's checks and the drawing order in detail:
// level_of_detail.cpp.
#include <array>
#include <cstdint>
#include <vector>

#include "core/algorithms/decimation.h"
#include "core/algorithms/progressive_mesh.h"
#include "core/halfedge_mesh.h"
#include "core/progress.h"

namespace trilab {

/// The progressive mesh of a level-of-detail slider: decimates a copy of `mesh` with the cost
/// and constraints of `options` (its amount, levels, geomorph and progressive fields are
/// ignored, and so is the independent-set constraint, which only shapes iterations) down to
/// ceil(min_percent / 100 * V) of its V vertices with faces, or as far as the constraints
/// allow (the report says), recording every collapse and nothing else. Throws InvalidArgument
/// for bad options or a min_percent outside (0, 100], Cancelled when `progress` asks to stop.
struct ProgressiveBuild {
    ProgressiveMesh progressive;
    DecimationReport report;
};
ProgressiveBuild build_progressive_mesh(const HalfedgeMesh& mesh, const DecimationOptions& options,
                                        double min_percent, Progress& progress);

/// Level of detail over a progressive mesh (Hoppe, "Progressive meshes", SIGGRAPH 1996).
///
/// set_level() replays collapses (coarser) and vertex splits (finer) from the current level:
/// a collapse moves one vertex, re-points the corners of the faces around it and drops one
/// or two faces, so a move costs O(the faces around the collapses between the two levels),
/// never a rebuild of a mesh. Vertices and faces are numbered in a drawing order of their
/// own, made once: faces along a Hilbert curve through their centroids, vertices in the order
/// the faces first use them, so that consecutive triangles share vertices (a software
/// rasterizer's vertex cache depends on that). Area-weighted vertex normals of the current
/// level are kept as sums of face normals in fixed point (exact integer sums: a level's
/// normals do not depend on the path taken to it). For a renderer that keeps a copy of
/// positions and normals, the level of detail lists the vertices whose position or normal
/// changed since clear_changes(); a move so long that updating the normals step by step
/// would cost more than recomputing them for the new level recomputes them (O(live faces))
/// and reports every vertex as changed. A move towards the fine mesh that is more than twice
/// as long as the way from the fine mesh starts over from a copy of the fine state (O(V + F)
/// memory copies) and collapses from there.
///
/// It copies what it needs from the progressive mesh (which may be dropped afterwards). Use it
/// from one thread at a time (triangles() and live_vertices() fill caches).
class LevelOfDetail {
public:
    /// Starts at level 0 (the fine mesh). Throws InvalidArgument when `pm` is inconsistent
    /// (sizes, indices, a collapse that does not match the faces it names, non-finite
    /// positions). O(V + F log F + the progressive record).
    explicit LevelOfDetail(const ProgressiveMesh& pm);
    /// Number of collapses applied, 0 (fine) to max_level() (coarsest).
    std::size_t level() const { return level_; }
    std::size_t max_level() const { return steps_.size(); }
    /// Moves to `level` (clamped to max_level()).
    void set_level(std::size_t level);

    /// Vertices with faces at level 0 (isolated vertices are kept at every level and not
    /// counted), and at the current level: fine_vertices() - level().
    std::size_t fine_vertices() const { return fine_vertices_; }
    std::size_t vertices() const { return fine_vertices_ - level_; }
    /// The level that keeps ceil(percent / 100 * fine_vertices()) vertices, clamped to
    /// [0, max_level()]: 100 gives 0, 0 the coarsest level. Throws InvalidArgument unless
    /// 0 <= percent <= 100.
    std::size_t level_for_percent(double percent) const;
    /// 100 * vertices at `level` / fine_vertices() (100 for a mesh without faces).
    double percent_at_level(std::size_t level) const;

    /// The mesh at the current level: live vertices in the fine mesh's order (compacted),
    /// faces in the fine mesh's order. O(V + F): for saving or applying a level, not for
    /// drawing it.
    HalfedgeMesh mesh() const;

    // Drawing data, in the level of detail's own order (see above).
    /// Current positions of all vertices (dead ones keep their last position).
    const std::vector<Point>& positions() const { return positions_; }
    /// Unit area-weighted normal of vertex v at the current level (zero without faces).
    Vector3 vertex_normal(Index v) const;
    /// The live faces of the current level as vertex triples, in drawing order. Rebuilt on
    /// the first call after a move: O(fine faces).
    const std::vector<std::array<Index, 3>>& triangles() const;
    /// The live vertices (isolated ones included), in order. Rebuilt on the first call after
    /// a move: O(fine vertices).
    const std::vector<Index>& live_vertices() const;
    std::size_t n_triangles() const { return fine_faces_ - removed_prefix_[level_]; }
    std::size_t n_live_vertices() const { return live_at_fine_ - level_; }

    /// Every face of the fine mesh with its current corners (dead faces keep their last
    /// ones), and whether it is live; vertex liveness.
    const std::vector<std::array<Index, 3>>& faces() const { return faces_; }
    const std::vector<std::uint8_t>& face_alive() const { return face_alive_; }
    const std::vector<std::uint8_t>& vertex_alive() const { return vertex_alive_; }
    /// The fine mesh's (ProgressiveMesh's) vertex index of vertex v and back (vertices
    /// deleted in the input are numbered last and never live); the face (index into faces())
    /// of a fine face, kInvalidIndex for a face deleted in the input.
    Index fine_vertex(Index v) const { return fine_vertex_[v]; }
    Index vertex_of(Index fine_vertex) const { return vertex_of_[fine_vertex]; }
    Index face_of(Index fine_face) const { return face_of_[fine_face]; }

    /// What changed since clear_changes(), for a renderer's copy of positions and normals:
    /// all_changed() says that any vertex may have (then changed_vertices() is empty);
    /// otherwise changed_vertices() lists, once each, the vertices whose position or normal
    /// changed (or that died or came back).
    bool all_changed() const { return all_changed_; }
    const std::vector<Index>& changed_vertices() const { return changed_vertices_; }
    void clear_changes();

private:
    using NormalSum = std::array<std::int64_t, 3>;
    /// One collapse in the level of detail's numbering.
    struct Step {
        Index kept, removed;
        std::array<Index, 2> dead;  ///< the faces it removes (kInvalidIndex: none)
        std::uint32_t ring_begin, moved_end, ring_end;  ///< into ring_
        Point kept_before, kept_after;
    };
    /// The constructor's last stage: positions, faces and steps in the drawing order.
    void take_in_drawing_order(const ProgressiveMesh& pm,
                               const std::vector<std::uint8_t>& ring_corner);
    void collapse_step(const Step& s, bool normals, bool track);
    void split_step(const Step& s, bool normals, bool track);
    void face_normal(Index f, int sign);
    void recompute_normals();
    void mark_vertices(Index f) {
        for (Index v : faces_[f])
            if (!vertex_changed_[v]) {
                vertex_changed_[v] = 1;
                changed_vertices_.push_back(v);
            }
    }

    std::size_t level_ = 0, fine_vertices_ = 0, live_at_fine_ = 0, fine_faces_ = 0;
    std::vector<Step> steps_;
    /// Per step: face << 2 | corner for the moved faces, face << 2 for kept's own.
    std::vector<std::uint32_t> ring_;
    std::vector<Point> positions_;
    std::vector<std::array<Index, 3>> faces_;
    std::vector<std::uint8_t> face_alive_, vertex_alive_;
    std::vector<Index> fine_vertex_, vertex_of_, face_of_, fine_face_;
    std::vector<NormalSum> normal_sum_;
    double normal_scale_ = 1;  ///< fixed-point units per unit of face normal
    /// Prefix sums over the steps: ring faces, and faces removed, before step k.
    std::vector<std::uint64_t> ring_prefix_, removed_prefix_;
    std::vector<std::uint8_t> vertex_changed_;
    std::vector<Index> changed_vertices_;
    bool all_changed_ = true;
    /// The fine state (level 0), for long moves towards it.
    std::vector<std::array<Index, 3>> fine_faces_state_;
    std::vector<Point> fine_positions_state_;
    std::vector<NormalSum> fine_normals_state_;
    std::vector<std::uint8_t> fine_vertex_alive_state_;
    mutable std::vector<std::array<Index, 3>> triangles_;
    mutable std::vector<Index> live_vertices_;
    mutable bool triangles_stale_ = true, live_vertices_stale_ = true;
};

}  // namespace trilab
