#pragma once
// Triangulation of one polygon (a face of a polygon soup) in its best-fit plane (the Newell
// normal; Tampieri, Graphics Gems III, 1992); every triangle keeps the corner order's
// orientation. Up to kEarClippingCorners corners: ear clipping (Meisters 1975); more: a
// monotone partition by a plane sweep (Garey, Johnson, Preparata, Tarjan, IPL 7(4), 1978),
// O(n log n) time, O(n) space, its result checked (n - 2 triangles, none inverted, areas
// summing to the polygon's). A polygon that fails the check (it crosses or folds over itself,
// or is degenerate) is ear clipped when small enough, else becomes a fan from corner 0, which
// is reported. Never throws on any finite input. The method in detail: triangulate.cpp.
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/handles.h"
#include "core/types.h"

namespace trilab {

/// A triangle as three local corner indices (0 .. n-1) of the polygon.
using PolygonTriangle = std::array<Index, 3>;

enum class TriangulationMethod {
    kEarClipping,  ///< small polygon, or the fallback for a larger one that is not simple
    kMonotone,     ///< monotone partition and chain triangulation, checked
    kFan,          ///< no valid triangulation found (crossing, folded or zero-area polygon)
};

inline constexpr std::size_t kEarClippingCorners = 16;
inline constexpr std::size_t kFallbackEarClippingCorners = 256;

/// Reusable scratch space for triangulating many polygons (build_mesh keeps one).
class PolygonTriangulator {
public:
    /// Appends n - 2 triangles (local corner indices) of the polygon with these corners to
    /// `out`; n >= 3. Returns the method that produced them.
    TriangulationMethod triangulate(const std::vector<Point>& corners,
                                    std::vector<PolygonTriangle>& out);

private:
    // monotone() in four stages (triangulate.cpp): the sweep order, the diagonals of the
    // monotone partition, the pieces the diagonals cut (each triangulated), the check.
    bool monotone(std::vector<PolygonTriangle>& out);
    void sort_corners_for_sweep();
    bool find_monotone_diagonals();
    bool link_pieces();
    bool triangulate_pieces(std::vector<PolygonTriangle>& out);
    bool is_valid_triangulation(const std::vector<PolygonTriangle>& out, std::size_t before) const;
    bool triangulate_piece(std::vector<PolygonTriangle>& out);
    bool ear_clip(const std::vector<Point>& p, const Vector3& normal,
                  std::vector<PolygonTriangle>& out);
    double orient(Index a, Index b, Index c) const {
        const double* p = xy_.data();
        return (p[2 * b] - p[2 * a]) * (p[2 * c + 1] - p[2 * a + 1]) -
               (p[2 * b + 1] - p[2 * a + 1]) * (p[2 * c] - p[2 * a]);
    }

    // Corners projected into the plane, scaled to about [-1, 1]: x, y of corner i at 2i, 2i+1.
    std::vector<double> xy_;
    // Sweep: corners from top to bottom, each corner's place in that order, the helper of
    // each edge (edge i runs from corner i to corner i + 1), merge corners, diagonals.
    // The sweep order's keys: top first, then left first, then by index.
    struct SweepKey {
        std::uint64_t high, low;  ///< order images of -y and x
        Index corner;
    };
    void sort_sweep();
    std::vector<SweepKey> sweep_, sweep_scratch_;
    std::vector<Index> digit_count_;
    std::vector<Index> order_, rank_, helper_;
    std::vector<std::uint8_t> is_merge_;
    std::vector<std::array<Index, 2>> diagonals_;
    // Pieces: next halfedge around each piece (corner edges, then two per diagonal), the
    // diagonal halfedges leaving each corner, one piece's corners, its chains.
    std::vector<Index> half_next_, out_begin_, out_list_, piece_, sorted_, stack_;
    std::vector<std::uint8_t> visited_, on_left_;
    // Ear clipping.
    std::vector<Index> ring_;
};

/// Convenience: the triangles of one polygon, and optionally the method used.
std::vector<PolygonTriangle> triangulate_polygon(const std::vector<Point>& corners,
                                                 TriangulationMethod* method = nullptr);

}  // namespace trilab
