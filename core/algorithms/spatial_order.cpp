// Spatial renumbering (core/algorithms/spatial_order.h): Morton codes for the vertices, then
// counting sorts by the smallest new vertex for the edges and the faces.
#include "core/algorithms/spatial_order.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <exception>
#include <limits>
#include <thread>
#include <vector>

#include "core/parallel.h"

namespace trilab {
namespace {

constexpr unsigned kMortonBits = 21;  // per axis: 63 bits in all
// Below this many vertices the edge and face orders are made one after the other.
constexpr std::size_t kParallelMin = 100000;

// The bits of x (below 2^21) spread to every third bit.
std::uint64_t spread_bits(std::uint64_t x) {
    x &= 0x1fffff;
    x = (x | x << 32) & 0x1f00000000ffffULL;
    x = (x | x << 16) & 0x1f0000ff0000ffULL;
    x = (x | x << 8) & 0x100f00f00f00f00fULL;
    x = (x | x << 4) & 0x10c30c30c30c30c3ULL;
    x = (x | x << 2) & 0x1249249249249249ULL;
    return x;
}

// New vertex order (new index -> old index): by Morton code, ties by old index.
std::vector<Index> morton_order(const HalfedgeMesh& mesh) {
    Point lo = Point::Constant(std::numeric_limits<double>::infinity());
    Point hi = -lo;
    for (Vertex v : mesh.vertices()) {
        const Point& p = mesh.position(v);
        if (!p.allFinite()) continue;
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
    }
    const double steps = double((std::uint64_t(1) << kMortonBits) - 1);
    std::array<double, 3> scale{};
    for (int a = 0; a < 3; ++a) scale[a] = hi[a] > lo[a] ? steps / (hi[a] - lo[a]) : 0.0;
    struct Keyed {
        std::uint64_t key;
        Index vertex;
    };
    std::vector<Keyed> keyed;
    keyed.reserve(mesh.n_vertices());
    for (Vertex v : mesh.vertices()) {
        const Point& p = mesh.position(v);
        std::uint64_t key = 0;
        if (p.allFinite()) {
            for (int a = 0; a < 3; ++a) {
                const double q = std::min(steps, std::max(0.0, (p[a] - lo[a]) * scale[a]));
                key |= spread_bits(std::uint64_t(q)) << a;
            }
        }
        keyed.push_back({key, v.idx()});
    }
    // A stable radix sort on the key, 11 bits a pass (the list starts in old-index order, so
    // equal keys stay in it).
    constexpr unsigned kDigit = 11;
    std::vector<Keyed> other(keyed.size());
    std::vector<std::size_t> count(std::size_t(1) << kDigit);
    for (unsigned shift = 0; shift < 3 * kMortonBits; shift += kDigit) {
        std::fill(count.begin(), count.end(), 0);
        const std::uint64_t mask = (std::uint64_t(1) << kDigit) - 1;
        for (const Keyed& k : keyed) ++count[(k.key >> shift) & mask];
        std::size_t sum = 0;
        for (std::size_t& c : count) {
            const std::size_t here = c;
            c = sum;
            sum += here;
        }
        for (const Keyed& k : keyed) other[count[(k.key >> shift) & mask]++] = k;
        keyed.swap(other);
    }
    std::vector<Index> order(keyed.size());
    for (std::size_t i = 0; i < keyed.size(); ++i) order[i] = keyed[i].vertex;
    return order;
}

// Groups `items` by their bucket (a new vertex index below n_buckets), each group sorted by the
// item's order key: a counting sort, then a sort of each small group.
template <class Item, class Bucket, class Less>
std::vector<Item> bucket_sort(const std::vector<Item>& items, std::size_t n_buckets,
                              const Bucket& bucket_of, const Less& less) {
    std::vector<Index> start(n_buckets + 1, 0);
    for (const Item& it : items) ++start[bucket_of(it) + 1];
    for (std::size_t b = 0; b < n_buckets; ++b) start[b + 1] += start[b];
    std::vector<Item> out(items.size());
    std::vector<Index> fill(start.begin(), start.end() - 1);
    for (const Item& it : items) out[fill[bucket_of(it)]++] = it;
    for (std::size_t b = 0; b < n_buckets; ++b)
        std::sort(out.begin() + start[b], out.begin() + start[b + 1], less);
    return out;
}

}  // namespace

IndexRemap renumber_spatially(HalfedgeMesh& mesh) {
    const std::vector<Index> vertex_order = morton_order(mesh);
    std::vector<Index> new_vertex(mesh.vertices_size(), kInvalidIndex);
    for (Index i = 0; i < vertex_order.size(); ++i) new_vertex[vertex_order[i]] = i;
    const std::size_t n = vertex_order.size();

    // The edge order and the face order read the mesh only: side by side where there is a
    // second core.
    const HalfedgeMesh& read = mesh;
    std::vector<Index> halfedge_order, face_order;
    const auto order_edges = [&] {
        // Edges: the halfedge from the smaller new vertex to the larger, by (smaller, larger).
        struct EdgeItem {
            Index lo, hi, halfedge;
        };
        std::vector<EdgeItem> edges;
        edges.reserve(read.n_edges());
        for (Edge e : read.edges()) {
            const Halfedge h = HalfedgeMesh::halfedge(e, 0);
            const Index a = new_vertex[read.from_vertex(h).idx()],
                        b = new_vertex[read.to_vertex(h).idx()];
            edges.push_back(a < b ? EdgeItem{a, b, h.idx()} : EdgeItem{b, a, h.idx() ^ 1u});
        }
        edges = bucket_sort(
            edges, n, [](const EdgeItem& x) { return x.lo; },
            [](const EdgeItem& x, const EdgeItem& y) { return x.hi < y.hi; });
        halfedge_order.reserve(2 * edges.size());
        for (const EdgeItem& x : edges) {
            halfedge_order.push_back(x.halfedge);
            halfedge_order.push_back(x.halfedge ^ 1u);
        }
    };
    const auto order_faces = [&] {
        // Faces: by their sorted new vertex indices.
        struct FaceItem {
            std::array<Index, 3> v;
            Index face;
        };
        std::vector<FaceItem> faces;
        faces.reserve(read.n_faces());
        for (Face f : read.faces()) {
            const auto c = read.face_vertices(f);
            std::array<Index, 3> v{new_vertex[c[0].idx()], new_vertex[c[1].idx()],
                                   new_vertex[c[2].idx()]};
            std::sort(v.begin(), v.end());
            faces.push_back({v, f.idx()});
        }
        faces = bucket_sort(
            faces, n, [](const FaceItem& x) { return x.v[0]; },
            [](const FaceItem& x, const FaceItem& y) { return x.v < y.v; });
        face_order.resize(faces.size());
        for (std::size_t i = 0; i < faces.size(); ++i) face_order[i] = faces[i].face;
    };
    if (n >= kParallelMin && unsigned(trilab::thread_count()) >= 2) {
        std::exception_ptr faces_error;
        std::thread faces_thread([&] {
            try {
                order_faces();
            } catch (...) {
                faces_error = std::current_exception();
            }
        });
        try {
            order_edges();
        } catch (...) {
            faces_thread.join();
            throw;
        }
        faces_thread.join();
        if (faces_error) std::rethrow_exception(faces_error);
    } else {
        order_edges();
        order_faces();
    }

    IndexRemap remap = mesh.renumber(vertex_order, halfedge_order, face_order);

    // The halfedges the old numbering happened to pick: canonical ones.
    for (Face f : mesh.faces()) {
        Halfedge best = mesh.halfedge(f);
        for (Halfedge h = mesh.next(best); h != mesh.halfedge(f); h = mesh.next(h))
            if (mesh.from_vertex(h) < mesh.from_vertex(best)) best = h;
        mesh.set_halfedge(f, best);
    }
    for (Vertex v : mesh.vertices()) {
        const Halfedge start = mesh.halfedge(v);
        if (!start.is_valid() || mesh.is_boundary(start)) continue;
        Halfedge best = start;
        for (Halfedge h = mesh.ccw_rotated(start); h != start; h = mesh.ccw_rotated(h))
            if (mesh.to_vertex(h) < mesh.to_vertex(best)) best = h;
        mesh.set_halfedge(v, best);
    }
    return remap;
}

}  // namespace trilab
