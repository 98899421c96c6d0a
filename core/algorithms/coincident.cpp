#include "core/algorithms/coincident.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <unordered_map>
#include <utility>

#include "core/errors.h"
#include "core/hash.h"
#include "core/number_text.h"
#include "core/parallel.h"

namespace trilab {

namespace {

/// The bits of a coordinate with -0 made +0 (so that the two compare and hash alike).
inline std::uint64_t coordinate_bits(double x) {
    if (x == 0) x = 0;
    std::uint64_t b;
    std::memcpy(&b, &x, sizeof b);
    return b;
}

inline std::uint64_t hash_point(const Point& p) {
    return mix_bits(coordinate_bits(p.x()) ^
                    mix_bits(coordinate_bits(p.y()) ^ mix_bits(coordinate_bits(p.z()))));
}

/// Groups from a representative per point (kInvalidIndex: skipped); the representative of a
/// group is the same for all its members.
CoincidentGroups groups_from_representatives(const std::vector<Index>& rep) {
    const std::size_t n = rep.size();
    std::vector<Index> count(n, 0);
    for (std::size_t i = 0; i < n; ++i)
        if (rep[i] != kInvalidIndex) ++count[rep[i]];
    // Groups in the order of their smallest member; `slot` numbers them.
    std::vector<Index> slot(n, kInvalidIndex);
    CoincidentGroups g;
    std::vector<Index> group_size;
    for (std::size_t i = 0; i < n; ++i) {
        const Index r = rep[i];
        if (r == kInvalidIndex || count[r] < 2 || slot[r] != kInvalidIndex) continue;
        slot[r] = Index(group_size.size());
        group_size.push_back(count[r]);
    }
    g.offsets.resize(group_size.size() + 1, 0);
    for (std::size_t k = 0; k < group_size.size(); ++k)
        g.offsets[k + 1] = g.offsets[k] + group_size[k];
    g.members.resize(g.offsets.back());
    std::vector<std::size_t> fill(g.offsets.begin(), g.offsets.end() - 1);
    for (std::size_t i = 0; i < n; ++i) {
        const Index r = rep[i];
        if (r == kInvalidIndex || count[r] < 2) continue;
        g.members[fill[slot[r]]++] = Index(i);
    }
    return g;
}

/// Exact groups: the points partitioned by their hash's top bits (kParts parts, a fixed number),
/// each part's points listed in index order, then each part hashed into a table of its own
/// (small enough to stay in the cache), the parts on every thread (core/parallel.h). A point's
/// representative is the first point (in index order) at the same position, whatever the
/// number of threads: equal points hash alike, so they fall in the same part.
CoincidentGroups exact_groups(const Point* p, std::size_t n, const std::uint8_t* skip) {
    constexpr unsigned kPartBits = 6;
    constexpr std::size_t kParts = std::size_t(1) << kPartBits;
    constexpr std::uint64_t kSkipped = ~std::uint64_t(0);  // not a point to group
    std::vector<std::uint64_t> hash(n);
    const std::size_t blocks = block_count(0, n);
    std::vector<std::size_t> count(blocks * kParts, 0);  // [block][part]
    parallel_for_blocks(0, n, [&](std::size_t begin, std::size_t end) {
        std::size_t* c = count.data() + (begin / kBlock) * kParts;
        for (std::size_t i = begin; i < end; ++i) {
            if ((skip && skip[i]) || !p[i].allFinite()) {
                hash[i] = kSkipped;
                continue;
            }
            hash[i] = hash_point(p[i]);
            if (hash[i] == kSkipped) hash[i] = 0;
            ++c[hash[i] >> (64 - kPartBits)];
        }
    });
    // Each part's points: the blocks' in block order, so in index order.
    std::vector<std::size_t> part_begin(kParts + 1, 0);
    std::size_t total = 0;
    for (std::size_t q = 0; q < kParts; ++q) {
        part_begin[q] = total;
        for (std::size_t k = 0; k < blocks; ++k) {
            const std::size_t c = count[k * kParts + q];
            count[k * kParts + q] = total;  // now where block k's points of part q start
            total += c;
        }
    }
    part_begin[kParts] = total;
    std::vector<Index> listed(total);
    parallel_for_blocks(0, n, [&](std::size_t begin, std::size_t end) {
        std::size_t* at = count.data() + (begin / kBlock) * kParts;
        for (std::size_t i = begin; i < end; ++i)
            if (hash[i] != kSkipped) listed[at[hash[i] >> (64 - kPartBits)]++] = Index(i);
    });
    std::vector<Index> rep(n, kInvalidIndex);
    parallel_for(
        0, kParts,
        [&](std::size_t q) {
            const std::size_t m = part_begin[q + 1] - part_begin[q];
            std::size_t size = 16;
            while (size < 2 * m) size *= 2;
            const std::uint64_t mask = size - 1;
            std::vector<Index> table(size, kInvalidIndex);
            for (std::size_t k = part_begin[q]; k < part_begin[q + 1]; ++k) {
                const Index i = listed[k];
                for (std::uint64_t h = hash[i] & mask;; h = (h + 1) & mask) {
                    const Index j = table[h];
                    if (j == kInvalidIndex) {
                        table[h] = i;
                        rep[i] = i;
                        break;
                    }
                    if (p[j] == p[i]) {  // -0 == +0 as numbers
                        rep[i] = j;
                        break;
                    }
                }
            }
        },
        1);
    return groups_from_representatives(rep);
}

Index find_root(std::vector<Index>& parent, Index i) {
    Index r = i;
    while (parent[r] != r) r = parent[r];
    while (parent[i] != r) {
        const Index next = parent[i];
        parent[i] = r;
        i = next;
    }
    return r;
}

CoincidentGroups tolerance_groups(const Point* p, std::size_t n, const std::uint8_t* skip,
                                  double d) {
    constexpr double kMaxCell = 1125899906842624.0;  // 2^50
    struct Cell {
        std::int64_t x, y, z;
        bool operator==(const Cell& o) const { return x == o.x && y == o.y && z == o.z; }
    };
    struct CellHash {
        std::size_t operator()(const Cell& c) const {
            return std::size_t(mix_bits(
                std::uint64_t(c.x) ^ mix_bits(std::uint64_t(c.y) ^ mix_bits(std::uint64_t(c.z)))));
        }
    };
    std::unordered_map<Cell, std::vector<Index>, CellHash> cells;
    std::vector<Cell> cell_of(n);
    std::vector<Index> parent(n, kInvalidIndex);
    for (std::size_t i = 0; i < n; ++i) {
        if ((skip && skip[i]) || !p[i].allFinite()) continue;
        double c[3];
        for (int k = 0; k < 3; ++k) {
            c[k] = std::floor(p[i][k] / d);
            if (!(std::abs(c[k]) < kMaxCell))
                throw InvalidArgument("coincident vertices: tolerance " + number_text(d) +
                                      " is too small for coordinates of magnitude " +
                                      number_text(std::abs(p[i][k])) +
                                      " (use a larger tolerance, or 0 for exact positions)");
        }
        cell_of[i] = Cell{std::int64_t(c[0]), std::int64_t(c[1]), std::int64_t(c[2])};
        cells[cell_of[i]].push_back(Index(i));
        parent[i] = Index(i);
    }
    // Refuse a tolerance so large that the comparisons would be quadratic (most vertices
    // within reach of each other): count them first.
    std::uint64_t pairs = 0;
    for (const auto& [cell, points] : cells)
        for (std::int64_t dx = -1; dx <= 1; ++dx)
            for (std::int64_t dy = -1; dy <= 1; ++dy)
                for (std::int64_t dz = -1; dz <= 1; ++dz) {
                    const auto it = cells.find(Cell{cell.x + dx, cell.y + dy, cell.z + dz});
                    if (it != cells.end())
                        pairs += std::uint64_t(points.size()) * it->second.size();
                }
    const std::uint64_t limit = 200 * std::uint64_t(n) + 1000000;
    if (pairs > limit)
        throw InvalidArgument("coincident vertices: tolerance " + number_text(d) +
                              " is too large for this mesh: about " + std::to_string(pairs / 2) +
                              " pairs of vertices lie within two cells of each other (use a "
                              "tolerance well below the edge lengths)");
    const double d2 = d * d;
    for (std::size_t i = 0; i < n; ++i) {
        if (parent[i] == kInvalidIndex) continue;
        const Cell c = cell_of[i];
        for (std::int64_t dx = -1; dx <= 1; ++dx)
            for (std::int64_t dy = -1; dy <= 1; ++dy)
                for (std::int64_t dz = -1; dz <= 1; ++dz) {
                    const auto it = cells.find(Cell{c.x + dx, c.y + dy, c.z + dz});
                    if (it == cells.end()) continue;
                    for (Index j : it->second) {
                        if (j >= i || (p[j] - p[i]).squaredNorm() > d2) continue;
                        const Index a = find_root(parent, Index(i)), b = find_root(parent, j);
                        if (a != b) parent[std::max(a, b)] = std::min(a, b);
                    }
                }
    }
    std::vector<Index> rep(n, kInvalidIndex);
    for (std::size_t i = 0; i < n; ++i)
        if (parent[i] != kInvalidIndex) rep[i] = find_root(parent, Index(i));
    return groups_from_representatives(rep);
}

}  // namespace

std::vector<Index> CoincidentGroups::group_of(std::size_t n) const {
    std::vector<Index> g(n, kInvalidIndex);
    for (std::size_t k = 0; k < size(); ++k)
        for (const Index* m = begin(k); m != end(k); ++m)
            if (*m < n) g[*m] = Index(k);
    return g;
}

CoincidentGroups find_coincident_points(const Point* p, std::size_t n, const std::uint8_t* skip,
                                        double tolerance) {
    if (!std::isfinite(tolerance) || tolerance < 0)
        throw InvalidArgument("coincident vertices: tolerance must be finite and >= 0 (got " +
                              number_text(tolerance) + ")");
    return tolerance == 0 ? exact_groups(p, n, skip) : tolerance_groups(p, n, skip, tolerance);
}

CoincidentGroups find_coincident_vertices(const HalfedgeMesh& mesh, double tolerance) {
    const std::size_t n = mesh.vertices_size();
    std::vector<std::uint8_t> skip(n, 1);
    for (Vertex v : mesh.vertices()) skip[v.idx()] = mesh.is_isolated(v) ? 1 : 0;
    return find_coincident_points(mesh.positions().data(), n, skip.data(), tolerance);
}

std::size_t unify_groups(const CoincidentGroups& groups, Point* values) {
    std::size_t changed = 0;
    std::vector<Point> distinct;
    const auto less = [](const Point& a, const Point& b) {
        return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
    };
    for (std::size_t g = 0; g < groups.size(); ++g) {
        const Index* b = groups.begin(g);
        const Index* e = groups.end(g);
        const Point& first = values[*b];
        bool same = true;
        for (const Index* m = b + 1; m != e && same; ++m) same = values[*m] == first;
        if (same) continue;
        distinct.clear();
        for (const Index* m = b; m != e; ++m) distinct.push_back(values[*m]);
        std::sort(distinct.begin(), distinct.end(), less);
        distinct.erase(std::unique(distinct.begin(), distinct.end()), distinct.end());
        Point sum = Point::Zero();
        for (const Point& p : distinct) sum += p;
        const Point mean = sum / double(distinct.size());
        for (const Index* m = b; m != e; ++m) values[*m] = mean;
        ++changed;
    }
    return changed;
}

BoundaryPairing pair_boundary_edges(const HalfedgeMesh& mesh) {
    // Only boundary vertices matter: every boundary halfedge is the outgoing boundary
    // halfedge (halfedge(v)) of exactly one vertex, so the vertices the boundary halfedges
    // start at are the boundary vertices (found by one sequential pass over the halfedges'
    // faces, where asking each vertex reads a random halfedge). Their positions are grouped
    // on their own (a few thousand points on a 17.8M-face scan, where a table over every
    // vertex would cost more than the rest of the statistics).
    BoundaryPairing r;
    const std::size_t n = mesh.vertices_size();
    std::vector<std::uint8_t> on_boundary(n, 0);
    const std::vector<Face>& face = mesh.halfedge_face_array();
    const std::vector<Vertex>& to = mesh.halfedge_to_array();
    const bool garbage = mesh.has_garbage();
    for (std::size_t h = 0; h < face.size(); ++h)
        if (!face[h].is_valid() && !(garbage && mesh.is_deleted(Edge(Index(h >> 1)))))
            on_boundary[to[h ^ 1].idx()] = 1;
    std::vector<Index> boundary;  // the boundary vertices, in index order
    std::vector<Point> points;    // their positions
    for (std::size_t v = 0; v < n; ++v)
        if (on_boundary[v] && !(garbage && mesh.is_deleted(Vertex(Index(v))))) {
            boundary.push_back(Index(v));
            points.push_back(mesh.position(Vertex(Index(v))));
        }
    const CoincidentGroups groups = find_coincident_points(points.data(), points.size(), nullptr);
    const std::vector<Index> group = groups.group_of(points.size());  // per boundary vertex
    const auto group_of = [&](Vertex v) {  // kInvalidIndex: not a boundary vertex, or alone
        const auto it = std::lower_bound(boundary.begin(), boundary.end(), v.idx());
        return it != boundary.end() && *it == v.idx() ? group[std::size_t(it - boundary.begin())]
                                                      : kInvalidIndex;
    };
    // Ids: a group's id is its number, an ungrouped vertex's is n_groups + its index.
    const auto id = [&](Vertex v, Index g) {
        return g != kInvalidIndex ? std::uint64_t(g) : std::uint64_t(groups.size()) + v.idx();
    };
    std::vector<std::pair<std::uint64_t, std::uint64_t>> keys;
    for (std::size_t i = 0; i < boundary.size(); ++i) {
        ++r.boundary_edges;
        const Vertex a(boundary[i]);
        const Vertex b = mesh.to_vertex(mesh.halfedge(a));
        const Index ga = group[i], gb = group_of(b);
        // A partner needs an end at a grouped vertex (otherwise it would be the same edge).
        if (ga == kInvalidIndex && gb == kInvalidIndex) continue;
        const std::uint64_t ia = id(a, ga), ib = id(b, gb);
        keys.emplace_back(std::min(ia, ib), std::max(ia, ib));
    }
    std::sort(keys.begin(), keys.end());
    for (std::size_t i = 0; i < keys.size();) {
        std::size_t j = i + 1;
        while (j < keys.size() && keys[j] == keys[i]) ++j;
        if (j - i >= 2) r.paired_edges += j - i;
        i = j;
    }
    r.unpaired_edges = r.boundary_edges - r.paired_edges;
    return r;
}

}  // namespace trilab
