#pragma once
// Coincident vertices: distinct vertices at the same position.
//
// Messy files hold one surface in several pieces: patches whose boundary curves lie on top of
// each other (the teapot's patch seams), and the copies build_mesh() makes of a file vertex
// with several fans (core/mesh_builder.h). Their vertices sit at bit-identical positions. The
// operations keep such vertices together (subdivision, fairing and decimation: see their
// headers) and weld_coincident_vertices() (core/algorithms/weld.h) joins them where the user wants
// one surface.
//
// Exact coincidence compares coordinates as numbers (-0 equals +0; a non-finite coordinate
// never coincides). With a tolerance d > 0, two points closer than d (Euclidean) are linked
// and a group is a connected set of links (single linkage: a chain of links may span more
// than d). Complexity: O(n) expected (a hash of the positions; with d > 0 a hash of grid
// cells of size d, each point compared with the points of its 27 neighbouring cells).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/halfedge_mesh.h"

namespace trilab {

/// Groups of at least two points (vertex storage indices), each group's members ascending,
/// groups ordered by their first member.
struct CoincidentGroups {
    std::vector<Index> members;
    std::vector<std::size_t> offsets{0};  ///< group g: members[offsets[g], offsets[g + 1])

    std::size_t size() const { return offsets.size() - 1; }
    bool empty() const { return size() == 0; }
    const Index* begin(std::size_t g) const { return members.data() + offsets[g]; }
    const Index* end(std::size_t g) const { return members.data() + offsets[g + 1]; }
    /// Per point (up to n): its group, or kInvalidIndex for a point in no group.
    std::vector<Index> group_of(std::size_t n) const;
};

/// Groups the points p[0..n) that are not skipped (skip[i] != 0; `skip` may be null). Throws
/// InvalidArgument when `tolerance` is negative or not finite, so small against the
/// coordinates that grid cells cannot be numbered (|x| / tolerance above 2^50), or so large
/// that the comparisons would be quadratic (more than 200 n + 10^6 candidate pairs: most
/// points within reach of each other).
CoincidentGroups find_coincident_points(const Point* p, std::size_t n,
                                        const std::uint8_t* skip = nullptr, double tolerance = 0);

/// Groups of live vertices with faces (isolated vertices never move and are left out) at the
/// same position (tolerance as above).
CoincidentGroups find_coincident_vertices(const HalfedgeMesh& mesh, double tolerance = 0);

/// Makes the values of each group exactly equal: a group whose members differ gets the mean
/// of its distinct values (members that already agree, e.g. copies computed as one, count
/// once), summed in sorted order (every member gets the same bits). Returns the number of
/// groups changed.
std::size_t unify_groups(const CoincidentGroups& groups, Point* values);

/// Boundary edges and how they pair up: an edge has a partner when another boundary edge
/// joins vertices at the same two positions (exact coincidence, either direction).
struct BoundaryPairing {
    std::size_t boundary_edges = 0;
    std::size_t paired_edges = 0;    ///< boundary edges with at least one partner
    std::size_t unpaired_edges = 0;  ///< boundary edges with none: open boundary or a crack
};
/// O(V) expected (a pass over the vertices, a hash of the boundary ones).
BoundaryPairing pair_boundary_edges(const HalfedgeMesh& mesh);

}  // namespace trilab
