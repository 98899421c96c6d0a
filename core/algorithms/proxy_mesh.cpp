// Vertex clustering for the proxy (see proxy_mesh.h). One pass per grid size:
//  1. clusters: every live vertex goes to its grid cell (a hash map from the packed cell to
//     a cluster number, numbered in vertex order), summing positions for the means;
//  2. triangles: every live face maps its corners to clusters; a face with two corners in
//     one cluster is dropped, the others are kept once per (rotation-normalized) triangle.
//     Faces are cut into fixed chunks handled on core/parallel.h's pool, each listing its own
//     distinct triangles in face order; the chunks are then merged in order, so the result is
//     the sequential one whatever the thread count.
// The cell is first sized from the mesh's area (a surface of area A meets about 1.5 A / h^2
// cells of size h, and a closed proxy has about two triangles per vertex) and enlarged while
// the proxy has more triangles than asked.
#include "core/algorithms/proxy_mesh.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "core/errors.h"
#include "core/geometry.h"
#include "core/parallel.h"

namespace trilab {
namespace {

constexpr std::uint64_t kEmptyKey = std::numeric_limits<std::uint64_t>::max();
constexpr std::uint64_t kMaxPacked = (std::uint64_t(1) << 21) - 1;  // 21 bits a coordinate
constexpr std::size_t kChunkFaces = std::size_t(1) << 16;

std::uint64_t pack3(std::uint64_t a, std::uint64_t b, std::uint64_t c) {
    return a | (b << 21) | (c << 42);
}

/// Distinct 64-bit keys numbered in insertion order (open addressing, linear probing).
class KeyNumbers {
public:
    explicit KeyNumbers(std::size_t expected) {
        std::size_t cap = 64;
        while (cap < 2 * expected) cap *= 2;
        slot_key_.assign(cap, kEmptyKey);
        slot_number_.resize(cap);
    }
    /// The key's number; a new key gets the next one.
    Index number(std::uint64_t key) {
        std::size_t i = slot(key);
        while (slot_key_[i] != kEmptyKey) {
            if (slot_key_[i] == key) return slot_number_[i];
            i = (i + 1) & (slot_key_.size() - 1);
        }
        const Index n = Index(keys_.size());
        slot_key_[i] = key;
        slot_number_[i] = n;
        keys_.push_back(key);
        if (2 * keys_.size() > slot_key_.size()) grow();
        return n;
    }
    /// The keys in the order they were first given.
    const std::vector<std::uint64_t>& keys() const { return keys_; }

private:
    std::size_t slot(std::uint64_t key) const {
        std::uint64_t h = key * 0x9E3779B97F4A7C15ull;
        h ^= h >> 29;
        return std::size_t(h) & (slot_key_.size() - 1);
    }
    void grow() {
        slot_key_.assign(2 * slot_key_.size(), kEmptyKey);
        slot_number_.resize(slot_key_.size());
        for (Index n = 0; n < keys_.size(); ++n) {
            std::size_t i = slot(keys_[n]);
            while (slot_key_[i] != kEmptyKey) i = (i + 1) & (slot_key_.size() - 1);
            slot_key_[i] = keys_[n];
            slot_number_[i] = n;
        }
    }
    std::vector<std::uint64_t> slot_key_;
    std::vector<Index> slot_number_;
    std::vector<std::uint64_t> keys_;
};

/// The mesh's arrays that the passes read (the soup's: SoupView).
struct MeshView {
    const HalfedgeMesh& mesh;
    const std::vector<Point>& points;
    const std::vector<Halfedge>& face_halfedge;
    const std::vector<Halfedge>& next;
    const std::vector<Vertex>& to;
    bool garbage;

    explicit MeshView(const HalfedgeMesh& m)
        : mesh(m),
          points(m.positions()),
          face_halfedge(m.face_halfedge_array()),
          next(m.halfedge_next_array()),
          to(m.halfedge_to_array()),
          garbage(m.has_garbage()) {}
    bool live(Vertex v) const { return !(garbage && mesh.is_deleted(v)); }
    bool live(Face f) const { return !(garbage && mesh.is_deleted(f)); }
    std::size_t n_faces() const { return face_halfedge.size(); }
    std::array<Index, 3> corners(Index f) const {
        const Halfedge h0 = face_halfedge[f], h1 = next[h0.idx()], h2 = next[h1.idx()];
        return {to[h0.idx()].idx(), to[h1.idx()].idx(), to[h2.idx()].idx()};
    }
};

/// A polygon soup as the passes read it: every vertex and face live, each face a triangle
/// (the soup's own corner list when every face is one, else each polygon's fan from its
/// first corner, faces of fewer than three corners skipped).
struct SoupView {
    const std::vector<Point>& points;
    std::vector<Index> own;  ///< the fans, when the soup is not all triangles
    const Index* tri = nullptr;
    std::size_t n_tri = 0;

    explicit SoupView(const PolygonSoup& soup) : points(soup.positions) {
        const std::size_t nf = soup.n_faces();
        if (soup.corners.size() == 3 * nf && soup.face_offsets.back() == 3 * nf &&
            std::adjacent_find(soup.face_offsets.begin(), soup.face_offsets.end(),
                               [](std::size_t a, std::size_t b) { return b != a + 3; }) ==
                soup.face_offsets.end()) {
            tri = soup.corners.data();
            n_tri = nf;
            return;
        }
        for (std::size_t f = 0; f < nf; ++f) {
            const std::size_t b = soup.face_offsets[f], e = soup.face_offsets[f + 1];
            for (std::size_t k = b + 1; k + 1 < e; ++k)
                own.insert(own.end(), {soup.corners[b], soup.corners[k], soup.corners[k + 1]});
        }
        tri = own.data();
        n_tri = own.size() / 3;
    }
    bool live(Vertex) const { return true; }
    bool live(Face) const { return true; }
    std::size_t n_faces() const { return n_tri; }
    std::array<Index, 3> corners(Index f) const {
        const Index* c = tri + 3 * std::size_t(f);
        return {c[0], c[1], c[2]};
    }
};

/// The area of the live faces, from about 2^18 of them evenly spread (an estimate that is
/// exact for smaller meshes).
template <typename View>
double sampled_area(const View& m) {
    const std::size_t nf = m.n_faces();
    const std::size_t stride = std::max<std::size_t>(1, nf >> 18);
    double sum = 0;
    for (std::size_t f = 0; f < nf; f += stride) {
        if (!m.live(Face(Index(f)))) continue;
        const std::array<Index, 3> c = m.corners(Index(f));
        const Point &a = m.points[c[0]], &b = m.points[c[1]], &d = m.points[c[2]];
        sum += 0.5 * (b - a).cross(d - a).norm();
    }
    return sum * double(stride);
}

template <typename View>
BoundingBox live_bounds(const View& m) {
    BoundingBox box;
    for (std::size_t v = 0; v < m.points.size(); ++v)
        if (m.live(Vertex(Index(v)))) box.extend(m.points[v]);
    return box;
}

/// One grid's clusters.
struct Clusters {
    std::vector<Index> of_vertex;  ///< per vertex: its cluster (invalid for deleted ones)
    std::vector<Point> mean;
    std::size_t count() const { return mean.size(); }
};

/// Cluster numbers per grid cell, in the order cells are first met: a dense array where the
/// grid has at most kDenseCells cells, else a hash map of the packed cell.
class CellNumbers {
public:
    static constexpr std::uint64_t kDenseCells = std::uint64_t(1) << 23;  // 32 MB
    CellNumbers(const std::array<std::uint64_t, 3>& dims, std::size_t n_vertices)
        : dims_(dims), hashed_(std::min<std::size_t>(n_vertices, 1u << 16)) {
        if (dims[0] * dims[1] * dims[2] <= kDenseCells)
            dense_.assign(dims[0] * dims[1] * dims[2], kInvalidIndex);
    }
    Index number(std::uint64_t x, std::uint64_t y, std::uint64_t z) {
        if (dense_.empty()) return hashed_.number(pack3(x, y, z));
        Index& n = dense_[(z * dims_[1] + y) * dims_[0] + x];
        if (n == kInvalidIndex) n = count_++;
        return n;
    }

private:
    std::array<std::uint64_t, 3> dims_;
    std::vector<Index> dense_;
    Index count_ = 0;
    KeyNumbers hashed_;
};

/// Pass 1. False when the grid or the cluster count exceed the 21-bit packing.
template <typename View>
bool make_clusters(const View& m, const BoundingBox& box, double cell, Clusters& out) {
    const Vector3 extent = box.max - box.min;
    std::array<std::uint64_t, 3> dims;
    for (int k = 0; k < 3; ++k) {
        if (extent[k] / cell >= double(kMaxPacked)) return false;
        dims[k] = std::uint64_t(extent[k] / cell) + 1;
    }
    const double inv = 1.0 / cell;
    const std::size_t nv = m.points.size();
    CellNumbers numbers(dims, nv);
    out.of_vertex.assign(nv, kInvalidIndex);
    out.mean.clear();
    std::vector<std::uint32_t> members;
    for (std::size_t v = 0; v < nv; ++v) {
        if (!m.live(Vertex(Index(v)))) continue;
        const Vector3 q = (m.points[v] - box.min) * inv;
        std::array<std::uint64_t, 3> i;
        for (int k = 0; k < 3; ++k) i[k] = std::min(std::uint64_t(q[k]), dims[k] - 1);
        const Index c = numbers.number(i[0], i[1], i[2]);
        if (c == out.mean.size()) {
            if (c > kMaxPacked) return false;
            out.mean.push_back(Point::Zero());
            members.push_back(0);
        }
        out.mean[c] += m.points[v];
        ++members[c];
        out.of_vertex[v] = c;
    }
    for (std::size_t c = 0; c < out.mean.size(); ++c) out.mean[c] /= double(members[c]);
    return true;
}

/// The distinct proxy triangles of faces [begin, end), as packed keys in face order.
template <typename View>
std::vector<std::uint64_t> chunk_triangles(const View& m, const Clusters& clusters,
                                           std::size_t begin, std::size_t end) {
    KeyNumbers seen(1024);
    for (std::size_t f = begin; f < end; ++f) {
        if (!m.live(Face(Index(f)))) continue;
        const std::array<Index, 3> v = m.corners(Index(f));
        std::array<Index, 3> c = {clusters.of_vertex[v[0]], clusters.of_vertex[v[1]],
                                  clusters.of_vertex[v[2]]};
        if (c[0] == c[1] || c[1] == c[2] || c[0] == c[2]) continue;
        // The rotation that starts at the smallest cluster: the same triangle, one key.
        const std::size_t r = c[0] < c[1] ? (c[0] < c[2] ? 0 : 2) : (c[1] < c[2] ? 1 : 2);
        std::rotate(c.begin(), c.begin() + r, c.end());
        seen.number(pack3(c[0], c[1], c[2]));
    }
    return seen.keys();
}

/// Pass 2: the proxy triangles, chunks on the pool's threads (core/parallel.h), merged in
/// chunk order.
template <typename View>
std::vector<std::array<Index, 3>> make_triangles(const View& m, const Clusters& clusters) {
    const std::size_t nf = m.n_faces();
    const std::size_t n_chunks = (nf + kChunkFaces - 1) / kChunkFaces;
    std::vector<std::vector<std::uint64_t>> per_chunk(n_chunks);
    parallel_for_blocks(
        0, n_chunks,
        [&](std::size_t begin, std::size_t end) {
            for (std::size_t k = begin; k < end; ++k)
                per_chunk[k] = chunk_triangles(m, clusters, k * kChunkFaces,
                                               std::min(nf, (k + 1) * kChunkFaces));
        },
        1);
    KeyNumbers all(1u << 16);
    for (const std::vector<std::uint64_t>& keys : per_chunk)
        for (std::uint64_t key : keys) all.number(key);
    std::vector<std::array<Index, 3>> out;
    out.reserve(all.keys().size());
    for (std::uint64_t key : all.keys())
        out.push_back({Index(key & kMaxPacked), Index((key >> 21) & kMaxPacked),
                       Index((key >> 42) & kMaxPacked)});
    return out;
}

/// Per cluster: its vertex nearest to the mean (the lowest index among equally near ones).
template <typename View>
std::vector<Index> nearest_members(const View& m, const Clusters& clusters) {
    std::vector<Index> rep(clusters.count(), kInvalidIndex);
    std::vector<double> best(clusters.count(), std::numeric_limits<double>::infinity());
    for (std::size_t v = 0; v < m.points.size(); ++v) {
        const Index c = clusters.of_vertex[v];
        if (c == kInvalidIndex) continue;
        const double d = (m.points[v] - clusters.mean[c]).squaredNorm();
        if (d < best[c]) {
            best[c] = d;
            rep[c] = Index(v);
        }
    }
    return rep;
}

/// The first cell size: from the area for the target, or a 64th of the box for a mesh
/// without area, or 1 for a single point.
template <typename View>
double first_cell_size(const View& m, const BoundingBox& box, std::size_t target) {
    const double area = sampled_area(m);
    const double longest = (box.max - box.min).maxCoeff();
    double cell = area > 0 ? std::sqrt(3.0 * area / double(target)) : longest / 64;
    // Never finer than the packing allows.
    cell = std::max(cell, longest / double(kMaxPacked - 1));
    return cell > 0 && std::isfinite(cell) ? cell : 1.0;
}

/// make_proxy_mesh over either view.
template <typename View>
ProxyMesh make_proxy(const View& m, const ProxyMeshOptions& options, const char* name) {
    const std::size_t target = options.target_triangles;
    if (target < 16 || target > 2000000)
        throw InvalidArgument(std::string(name) + ": target_triangles " + std::to_string(target) +
                              " is outside [16, 2000000]");
    ProxyMesh out;
    const BoundingBox box = live_bounds(m);
    if (box.empty) return out;
    double cell = first_cell_size(m, box, target);
    Clusters clusters;
    bool shrunk = false;
    for (;;) {
        ++out.passes;
        if (!make_clusters(m, box, cell, clusters)) {
            cell *= 2;  // too fine for the packing
            continue;
        }
        out.triangles = make_triangles(m, clusters);
        const double ratio = double(out.triangles.size()) / double(target);
        if (ratio > 1) {
            cell *= std::sqrt(ratio) * 1.02;  // triangles go as 1 / cell^2
        } else if (ratio < 0.5 && ratio > 0 && !shrunk && out.passes == 1) {
            // (No triangles at all, e.g. isolated points: no finer cell makes any.)
            shrunk = true;  // far below the target: one finer try
            cell *= std::sqrt(ratio) * 1.02;
        } else {
            break;
        }
    }
    out.positions = clusters.mean;
    out.representative = nearest_members(m, clusters);
    out.cell_size = cell;
    out.error_bound = cell * std::sqrt(3.0);
    if (options.keep_clusters) out.cluster_of = std::move(clusters.of_vertex);
    return out;
}

}  // namespace

ProxyMesh make_proxy_mesh(const HalfedgeMesh& mesh, const ProxyMeshOptions& options) {
    return make_proxy(MeshView(mesh), options, "make_proxy_mesh");
}

ProxyMesh moved_proxy_mesh(const ProxyMesh& proxy, const HalfedgeMesh& mesh) {
    const std::vector<Point>& x = mesh.positions();
    if (proxy.cluster_of.size() != x.size())
        throw InvalidArgument("moved_proxy_mesh: the proxy's clusters are for " +
                              std::to_string(proxy.cluster_of.size()) + " vertices, the mesh has " +
                              std::to_string(x.size()) +
                              (proxy.cluster_of.empty() ? " (make it with keep_clusters)" : ""));
    ProxyMesh out;
    const std::size_t nc = proxy.positions.size();
    out.positions.assign(nc, Point::Zero());
    std::vector<std::uint32_t> members(nc, 0);
    for (std::size_t v = 0; v < x.size(); ++v) {
        const Index c = proxy.cluster_of[v];
        if (c == kInvalidIndex) continue;
        if (c >= nc)
            throw InvalidArgument("moved_proxy_mesh: vertex " + std::to_string(v) +
                                  " has cluster " + std::to_string(c) + ", the proxy has " +
                                  std::to_string(nc));
        out.positions[c] += x[v];
        ++members[c];
    }
    for (std::size_t c = 0; c < nc; ++c)
        if (members[c]) out.positions[c] /= double(members[c]);
    double largest = 0;
    for (std::size_t v = 0; v < x.size(); ++v) {
        const Index c = proxy.cluster_of[v];
        if (c != kInvalidIndex)
            largest = std::max(largest, (x[v] - out.positions[c]).squaredNorm());
    }
    out.triangles = proxy.triangles;
    out.representative = proxy.representative;
    out.cell_size = proxy.cell_size;
    out.error_bound = std::sqrt(largest);
    out.passes = 0;
    out.cluster_of = proxy.cluster_of;
    return out;
}

ProxyMesh make_soup_proxy_mesh(const PolygonSoup& soup, const ProxyMeshOptions& options) {
    for (Index c : soup.corners)
        if (c >= soup.positions.size())
            throw InvalidArgument("make_soup_proxy_mesh: corner index " + std::to_string(c) +
                                  " is out of range (" + std::to_string(soup.positions.size()) +
                                  " vertices)");
    return make_proxy(SoupView(soup), options, "make_soup_proxy_mesh");
}

}  // namespace trilab
