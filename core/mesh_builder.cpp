#include "core/mesh_builder.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "core/errors.h"

namespace trilab {

void PolygonSoup::add_face(const std::vector<Index>& face, const std::vector<TexCoord>& uv) {
    corners.insert(corners.end(), face.begin(), face.end());
    corner_texcoords.insert(corner_texcoords.end(), uv.begin(), uv.end());
    face_offsets.push_back(corners.size());
}

std::vector<std::string> LoadReport::lines() const {
    std::vector<std::string> out;
    auto add = [&](std::size_t n, const char* what) {
        if (n) out.push_back(std::to_string(n) + " " + what);
    };
    add(polygons_triangulated, "polygons triangulated");
    add(triangles_from_polygons, "triangles made from polygons");
    add(degenerate_faces_dropped, "degenerate faces dropped (repeated vertex or < 3 corners)");
    add(detached_faces, "faces detached (non-manifold edge, flipped or duplicated face)");
    add(nonmanifold_vertices_split, "non-manifold vertices split");
    add(vertex_copies_added, "vertex copies added");
    add(isolated_vertices, "isolated vertices kept");
    add(merged_vertices, "duplicate vertices merged");
    for (const std::string& n : notes) out.push_back(n);
    return out;
}

namespace {

using Tri = std::array<Index, 3>;

/// Ear-clipping triangulation of a simple polygon in its best-fit (Newell) plane. Returns
/// triangles as local corner indices; falls back to a fan when no ear can be found.
std::vector<Tri> triangulate_polygon(const std::vector<Point>& p) {
    const std::size_t n = p.size();
    std::vector<Tri> out;
    if (n == 3) return {{0, 1, 2}};
    Vector3 normal = Vector3::Zero();
    for (std::size_t i = 0; i < n; ++i) {
        const Point& a = p[i];
        const Point& b = p[(i + 1) % n];
        normal += Vector3((a.y() - b.y()) * (a.z() + b.z()), (a.z() - b.z()) * (a.x() + b.x()),
                          (a.x() - b.x()) * (a.y() + b.y()));
    }
    auto fan = [&] {
        std::vector<Tri> f;
        for (Index i = 1; i + 1 < n; ++i) f.push_back({0, i, i + 1});
        return f;
    };
    if (!(normal.norm() > 0)) return fan();
    normal.normalize();
    std::vector<Index> ring(n);
    for (Index i = 0; i < n; ++i) ring[i] = i;
    auto cross_n = [&](Index a, Index b, Index c) {
        return (p[b] - p[a]).cross(p[c] - p[a]).dot(normal);
    };
    while (ring.size() > 3) {
        const std::size_t m = ring.size();
        bool clipped = false;
        for (std::size_t i = 0; i < m && !clipped; ++i) {
            const Index a = ring[(i + m - 1) % m], b = ring[i], c = ring[(i + 1) % m];
            if (!(cross_n(a, b, c) > 0)) continue;  // reflex or degenerate corner
            bool inside = false;
            for (std::size_t j = 0; j < m && !inside; ++j) {
                const Index q = ring[j];
                if (q == a || q == b || q == c) continue;
                inside = cross_n(a, b, q) >= 0 && cross_n(b, c, q) >= 0 && cross_n(c, a, q) >= 0;
            }
            if (inside) continue;
            out.push_back({a, b, c});
            ring.erase(ring.begin() + static_cast<std::ptrdiff_t>(i));
            clipped = true;
        }
        if (!clipped) return fan();
    }
    out.push_back({ring[0], ring[1], ring[2]});
    return out;
}

/// Open-addressing hash table from an undirected vertex pair to an edge index.
class EdgeTable {
public:
    explicit EdgeTable(std::size_t expected) {
        std::size_t cap = 16;
        while (cap < 2 * expected) cap <<= 1;
        keys_.assign(cap, kEmpty);
        values_.resize(cap);
        mask_ = cap - 1;
    }
    static std::uint64_t key(Index a, Index b) {
        if (a > b) std::swap(a, b);
        return (std::uint64_t(a) << 32) | b;
    }
    Index find(std::uint64_t k) const {
        for (std::size_t i = slot(k);; i = (i + 1) & mask_) {
            if (keys_[i] == k) return values_[i];
            if (keys_[i] == kEmpty) return kInvalidIndex;
        }
    }
    void insert(std::uint64_t k, Index value) {
        if (2 * (count_ + 1) > keys_.size()) grow();
        std::size_t i = slot(k);
        while (keys_[i] != kEmpty) i = (i + 1) & mask_;
        keys_[i] = k;
        values_[i] = value;
        ++count_;
    }

private:
    static constexpr std::uint64_t kEmpty = ~std::uint64_t(0);
    std::size_t slot(std::uint64_t k) const {
        k ^= k >> 33;
        k *= 0xff51afd7ed558ccdULL;
        k ^= k >> 33;
        return std::size_t(k) & mask_;
    }
    void grow() {
        std::vector<std::uint64_t> old_keys = std::move(keys_);
        std::vector<Index> old_values = std::move(values_);
        keys_.assign(old_keys.size() * 2, kEmpty);
        values_.assign(old_keys.size() * 2, 0);
        mask_ = keys_.size() - 1;
        count_ = 0;
        for (std::size_t i = 0; i < old_keys.size(); ++i)
            if (old_keys[i] != kEmpty) insert(old_keys[i], old_values[i]);
    }
    std::vector<std::uint64_t> keys_;
    std::vector<Index> values_;
    std::size_t mask_ = 0, count_ = 0;
};

void check_soup(const PolygonSoup& soup) {
    const std::size_t nv = soup.positions.size();
    if (soup.face_offsets.empty() || soup.face_offsets.front() != 0 ||
        soup.face_offsets.back() != soup.corners.size())
        throw InvalidArgument("build_mesh: face_offsets do not match the corner list");
    for (std::size_t f = 0; f + 1 < soup.face_offsets.size(); ++f) {
        if (soup.face_offsets[f + 1] < soup.face_offsets[f])
            throw InvalidArgument("build_mesh: face_offsets decrease at face " + std::to_string(f));
        for (std::size_t c = soup.face_offsets[f]; c < soup.face_offsets[f + 1]; ++c)
            if (soup.corners[c] >= nv)
                throw InvalidArgument("build_mesh: face " + std::to_string(f) + " uses vertex " +
                                      std::to_string(soup.corners[c]) + " but there are only " +
                                      std::to_string(nv) + " vertices");
    }
    for (std::size_t v = 0; v < nv; ++v)
        if (!soup.positions[v].allFinite())
            throw InvalidArgument("build_mesh: vertex " + std::to_string(v) +
                                  " has a non-finite coordinate");
    auto check_size = [&](std::size_t n, std::size_t want, const char* what) {
        if (n != 0 && n != want)
            throw InvalidArgument(std::string("build_mesh: ") + what + " has " + std::to_string(n) +
                                  " entries, expected " + std::to_string(want));
    };
    check_size(soup.normals.size(), nv, "normals");
    check_size(soup.colors.size(), nv, "colors");
    check_size(soup.texcoords.size(), nv, "texcoords");
    check_size(soup.corner_texcoords.size(), soup.corners.size(), "corner_texcoords");
}

}  // namespace

HalfedgeMesh build_mesh(const PolygonSoup& soup, LoadReport& report) {
    check_soup(soup);
    const std::size_t n_input_vertices = soup.positions.size();

    // 1. Triangles (with the soup corner each triangle corner came from).
    std::vector<Tri> tris, tri_corners;
    tris.reserve(soup.corners.size() / 3 + 1);
    // Which soup corner each triangle corner came from: only needed for corner texcoords.
    const bool keep_corners = !soup.corner_texcoords.empty();
    if (keep_corners) tri_corners.reserve(tris.capacity());
    std::vector<Point> poly;
    for (std::size_t f = 0; f < soup.n_faces(); ++f) {
        const std::size_t begin = soup.face_offsets[f], n = soup.face_offsets[f + 1] - begin;
        bool repeated = n < 3;
        for (std::size_t i = 0; i < n && !repeated; ++i)
            for (std::size_t j = i + 1; j < n && !repeated; ++j)
                repeated = soup.corners[begin + i] == soup.corners[begin + j];
        if (repeated) {
            ++report.degenerate_faces_dropped;
            continue;
        }
        if (n == 3) {
            tris.push_back({soup.corners[begin], soup.corners[begin + 1], soup.corners[begin + 2]});
            if (keep_corners)
                tri_corners.push_back({Index(begin), Index(begin + 1), Index(begin + 2)});
            continue;
        }
        poly.clear();
        for (std::size_t i = 0; i < n; ++i) poly.push_back(soup.positions[soup.corners[begin + i]]);
        ++report.polygons_triangulated;
        for (const Tri& t : triangulate_polygon(poly)) {
            tris.push_back({soup.corners[begin + t[0]], soup.corners[begin + t[1]],
                            soup.corners[begin + t[2]]});
            if (keep_corners)
                tri_corners.push_back(
                    {Index(begin + t[0]), Index(begin + t[1]), Index(begin + t[2])});
            ++report.triangles_from_polygons;
        }
    }

    // 2. Edges. Group the 3T directed corner edges by their unordered vertex pair (a
    //    counting sort on the smaller vertex, then the larger one within each bucket), then
    //    accept triangles in file order when each of their three directed halfedges is still
    //    free. Halfedge 2e runs from the smaller to the larger vertex of edge e.
    const std::size_t n_tris = tris.size();
    auto corner_lo = [&](std::size_t c) {
        const Tri& t = tris[c / 3];
        return std::min(t[c % 3], t[(c % 3 + 1) % 3]);
    };
    auto corner_hi = [&](std::size_t c) {
        const Tri& t = tris[c / 3];
        return std::max(t[c % 3], t[(c % 3 + 1) % 3]);
    };
    std::vector<Index> group_of(3 * n_tris);
    Index n_groups = 0;
    {
        std::vector<Index> bucket(n_input_vertices + 1, 0);
        for (std::size_t c = 0; c < 3 * n_tris; ++c) ++bucket[corner_lo(c) + 1];
        for (std::size_t v = 0; v < n_input_vertices; ++v) bucket[v + 1] += bucket[v];
        // (larger vertex, corner) per bucket entry, so the scans below read memory in order.
        std::vector<std::pair<Index, Index>> entry(3 * n_tris);
        {
            std::vector<Index> fill(bucket.begin(), bucket.end() - 1);
            for (std::size_t c = 0; c < 3 * n_tris; ++c)
                entry[fill[corner_lo(c)]++] = {corner_hi(c), Index(c)};
        }
        for (std::size_t v = 0; v < n_input_vertices; ++v) {
            const Index begin = bucket[v], end = bucket[v + 1];
            // A high-valence vertex is sorted (equal partners become neighbours) instead of
            // scanned quadratically.
            const bool sorted = end - begin > 16;
            if (sorted) std::sort(entry.begin() + begin, entry.begin() + end);
            for (Index i = begin; i < end; ++i) {
                const Index hi = entry[i].first;
                Index j = i;
                if (sorted) {
                    if (i > begin && entry[i - 1].first == hi) j = i - 1;
                } else {
                    j = begin;
                    while (j < i && entry[j].first != hi) ++j;
                }
                group_of[entry[i].second] = j < i ? group_of[entry[j].second] : n_groups++;
            }
        }
    }
    std::vector<std::uint8_t> slot_used(2 * std::size_t(n_groups), 0);
    std::vector<Index> edge_of_group(n_groups, kInvalidIndex);
    std::vector<Index> hto;  // per halfedge: the vertex it points to
    hto.reserve(2 * std::size_t(n_groups));
    std::vector<Index> face_tri;       // accepted face -> triangle index
    std::vector<Index> face_halfedge;  // accepted face -> its halfedge ending at corner 0
    std::vector<Tri> face_he;          // accepted face -> its three halfedges
    std::vector<Index> detached;       // triangle indices added detached
    face_tri.reserve(n_tris);
    face_halfedge.reserve(n_tris);
    face_he.reserve(n_tris);
    for (Index t = 0; t < n_tris; ++t) {
        const Tri& tri = tris[t];
        std::array<std::size_t, 3> slot{};
        bool free = true;
        for (int k = 0; k < 3; ++k) {
            slot[k] = 2 * std::size_t(group_of[3 * t + k]) + (tri[k] < tri[(k + 1) % 3] ? 0 : 1);
            free = free && !slot_used[slot[k]];
        }
        if (!free) {
            detached.push_back(t);
            continue;
        }
        Tri he{};
        for (int k = 0; k < 3; ++k) {
            slot_used[slot[k]] = 1;
            const Index g = Index(slot[k] / 2);
            if (edge_of_group[g] == kInvalidIndex) {
                edge_of_group[g] = Index(hto.size() / 2);
                hto.push_back(std::max(tri[k], tri[(k + 1) % 3]));
                hto.push_back(std::min(tri[k], tri[(k + 1) % 3]));
            }
            he[k] = 2 * edge_of_group[g] + Index(slot[k] & 1);
        }
        face_tri.push_back(t);
        face_halfedge.push_back(he[2]);  // ends at corner 0, as OpenMesh's add_face does
        face_he.push_back(he);
    }
    const std::size_t n_h = hto.size();
    std::vector<Index> hface(n_h, kInvalidIndex), hnext(n_h, kInvalidIndex),
        hprev(n_h, kInvalidIndex);
    for (Index f = 0; f < face_he.size(); ++f) {
        const Tri& he = face_he[f];
        for (int k = 0; k < 3; ++k) {
            hface[he[k]] = f;
            hnext[he[k]] = he[(k + 1) % 3];
            hprev[he[(k + 1) % 3]] = he[k];
        }
    }

    // 3. Fans: group the outgoing halfedges of each vertex into fans; keep the first fan on
    //    the vertex and give every further fan a copy of it.
    std::vector<Index> source_vertex(n_input_vertices);  // vertex -> soup vertex it copies
    for (Index v = 0; v < n_input_vertices; ++v) source_vertex[v] = v;
    std::vector<Index> vhalfedge(n_input_vertices, kInvalidIndex);
    std::vector<std::size_t> out_begin(n_input_vertices + 1, 0);
    for (Index h = 0; h < n_h; ++h) ++out_begin[hto[h ^ 1] + 1];
    for (std::size_t v = 0; v < n_input_vertices; ++v) out_begin[v + 1] += out_begin[v];
    std::vector<Index> outgoing(n_h);
    {
        std::vector<std::size_t> fill(out_begin.begin(), out_begin.end() - 1);
        for (Index h = 0; h < n_h; ++h) outgoing[fill[hto[h ^ 1]]++] = h;
    }
    std::vector<std::uint8_t> visited(n_h, 0);
    std::vector<Index> fan;
    for (Index v = 0; v < n_input_vertices; ++v) {
        unsigned n_fans = 0;
        for (std::size_t i = out_begin[v]; i < out_begin[v + 1]; ++i) {
            const Index h = outgoing[i];
            if (visited[h] || hface[h] == kInvalidIndex) continue;
            // Walk clockwise (x -> next(twin(x))) to the start of the fan.
            Index start = h;
            for (;;) {
                const Index t = start ^ 1;
                if (hface[t] == kInvalidIndex) break;
                const Index y = hnext[t];
                if (y == h) break;
                start = y;
            }
            // Walk counter-clockwise (x -> twin(prev(x))) collecting the fan.
            fan.clear();
            Index boundary_out = kInvalidIndex;
            for (Index cur = start;;) {
                fan.push_back(cur);
                visited[cur] = 1;
                const Index nxt = hprev[cur] ^ 1;
                if (hface[nxt] == kInvalidIndex) {
                    boundary_out = nxt;
                    fan.push_back(nxt);
                    visited[nxt] = 1;
                    break;
                }
                if (nxt == start) break;
                cur = nxt;
            }
            Index vv = v;
            if (n_fans++ > 0) {
                vv = Index(source_vertex.size());
                source_vertex.push_back(v);
                vhalfedge.push_back(kInvalidIndex);
                ++report.vertex_copies_added;
                for (Index x : fan) hto[x ^ 1] = vv;
            }
            if (boundary_out != kInvalidIndex) {
                const Index boundary_in = start ^ 1;
                hnext[boundary_in] = boundary_out;
                hprev[boundary_out] = boundary_in;
                vhalfedge[vv] = boundary_out;
            } else {
                vhalfedge[vv] = start;
            }
        }
        if (n_fans > 1) ++report.nonmanifold_vertices_split;
    }

    // 4. Detached triangles: fresh edges; corners reuse a vertex only if nothing uses it yet.
    for (Index t : detached) {
        const Tri& tri = tris[t];
        std::array<Index, 3> vs{};
        for (int k = 0; k < 3; ++k) {
            const Index v = tri[k];
            if (vhalfedge[v] == kInvalidIndex) {
                vs[k] = v;
            } else {
                vs[k] = Index(source_vertex.size());
                source_vertex.push_back(v);
                vhalfedge.push_back(kInvalidIndex);
                ++report.vertex_copies_added;
            }
        }
        const Index f = Index(face_tri.size());
        const Index h0 = Index(hface.size());
        for (int k = 0; k < 3; ++k) {
            hto.push_back(vs[(k + 1) % 3]);
            hto.push_back(vs[k]);
            hface.push_back(f);
            hface.push_back(kInvalidIndex);
        }
        hnext.resize(hface.size());
        hprev.resize(hface.size());
        for (int k = 0; k < 3; ++k) {
            const Index inner = h0 + 2 * k, inner_next = h0 + 2 * ((k + 1) % 3);
            hnext[inner] = inner_next;
            hprev[inner_next] = inner;
            // Boundary loop runs the other way round.
            const Index outer = inner + 1, outer_next = h0 + 2 * ((k + 2) % 3) + 1;
            hnext[outer] = outer_next;
            hprev[outer_next] = outer;
            vhalfedge[vs[k]] = h0 + 2 * ((k + 2) % 3) + 1;  // outgoing boundary from vs[k]
        }
        face_tri.push_back(t);
        face_halfedge.push_back(h0 + 4);  // vs[2] -> vs[0]: ends at corner 0
        ++report.detached_faces;
    }

    // 5. Assemble the mesh (bulk: no per-element property calls).
    const std::size_t n_v = source_vertex.size(), n_e = hto.size() / 2, n_f = face_tri.size();
    HalfedgeMesh mesh;
    mesh.resize_elements(n_v, n_e, n_f);
    std::vector<Point>& positions = mesh.positions();
    for (Index v = 0; v < n_v; ++v) {
        positions[v] = soup.positions[source_vertex[v]];
        if (vhalfedge[v] != kInvalidIndex)
            mesh.set_halfedge(Vertex(v), Halfedge(vhalfedge[v]));
        else
            ++report.isolated_vertices;
    }
    for (Index h = 0; h < hto.size(); ++h) {
        mesh.set_to_vertex(Halfedge(h), Vertex(hto[h]));
        mesh.set_next(Halfedge(h), Halfedge(hnext[h]));
        if (hface[h] != kInvalidIndex) mesh.set_face(Halfedge(h), Face(hface[h]));
    }
    for (Index f = 0; f < n_f; ++f) mesh.set_halfedge(Face(f), Halfedge(face_halfedge[f]));

    if (!soup.normals.empty()) {
        auto p = mesh.vertex_property<Vector3>("v:normal");
        for (Index v = 0; v < n_v; ++v) p[Vertex(v)] = soup.normals[source_vertex[v]];
    }
    if (!soup.colors.empty()) {
        auto p = mesh.vertex_property<Color>("v:color");
        for (Index v = 0; v < n_v; ++v) p[Vertex(v)] = soup.colors[source_vertex[v]];
    }
    if (!soup.texcoords.empty()) {
        auto p = mesh.vertex_property<TexCoord>("v:texcoord");
        for (Index v = 0; v < n_v; ++v) p[Vertex(v)] = soup.texcoords[source_vertex[v]];
    }
    if (!soup.corner_texcoords.empty()) {
        auto p = mesh.halfedge_property<TexCoord>("h:texcoord", TexCoord::Zero());
        for (Index f = 0; f < n_f; ++f) {
            // The face's halfedge ends at corner 0; its next ends at corner 1, and so on.
            Halfedge h(face_halfedge[f]);
            const Tri& c = tri_corners[face_tri[f]];
            for (int k = 0; k < 3; ++k, h = mesh.next(h)) p[h] = soup.corner_texcoords[c[k]];
        }
    }
    return mesh;
}

PolygonSoup to_soup(const HalfedgeMesh& mesh) {
    PolygonSoup soup;
    std::vector<Index> index(mesh.vertices_size(), kInvalidIndex);
    for (Vertex v : mesh.vertices()) {
        index[v.idx()] = Index(soup.positions.size());
        soup.positions.push_back(mesh.position(v));
    }
    auto normals = mesh.get_vertex_property<Vector3>("v:normal");
    auto colors = mesh.get_vertex_property<Color>("v:color");
    auto texcoords = mesh.get_vertex_property<TexCoord>("v:texcoord");
    auto corner_uv = mesh.get_halfedge_property<TexCoord>("h:texcoord");
    for (Vertex v : mesh.vertices()) {
        if (normals) soup.normals.push_back(normals[v]);
        if (colors) soup.colors.push_back(colors[v]);
        if (texcoords) soup.texcoords.push_back(texcoords[v]);
    }
    soup.corners.reserve(3 * mesh.n_faces());
    soup.face_offsets.reserve(mesh.n_faces() + 1);
    for (Face f : mesh.faces()) {
        // Corner k is to_vertex(h_k); its texture coordinate is stored on h_k.
        for (Halfedge h : mesh.halfedges_of(f)) {
            soup.corners.push_back(index[mesh.to_vertex(h).idx()]);
            if (corner_uv) soup.corner_texcoords.push_back(corner_uv[h]);
        }
        soup.face_offsets.push_back(soup.corners.size());
    }
    return soup;
}

}  // namespace trilab
