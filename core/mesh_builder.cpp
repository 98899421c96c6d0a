#include "core/mesh_builder.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <string>

#include "core/errors.h"
#include "core/prefetch.h"
#include "core/triangulate.h"

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

void check_soup(const PolygonSoup& soup) {
    const std::size_t nv = soup.positions.size();
    if (nv >= std::size_t(kInvalidIndex) / 2)
        throw InvalidArgument("build_mesh: " + std::to_string(nv) +
                              " vertices are more than 32-bit indices can number");
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
    const bool keep_corners = !soup.corner_texcoords.empty();

    // 1. Triangles as a flat corner list, three per triangle: the soup's own list when every
    //    face is a triangle without a repeated corner (no copy), else a new one with the
    //    polygons triangulated and the degenerate faces dropped. `tri_corner` gives the
    //    soup corner of each triangle corner (identity when the soup's list is used).
    bool clean_triangles = soup.corners.size() == 3 * soup.n_faces();
    for (std::size_t f = 0; f < soup.n_faces() && clean_triangles; ++f) {
        const std::size_t b = soup.face_offsets[f];
        clean_triangles =
            soup.face_offsets[f + 1] == b + 3 && soup.corners[b] != soup.corners[b + 1] &&
            soup.corners[b + 1] != soup.corners[b + 2] && soup.corners[b] != soup.corners[b + 2];
    }
    std::vector<Index> own_tris, own_tri_corner;
    if (!clean_triangles) {
        own_tris.reserve(soup.corners.size());
        if (keep_corners) own_tri_corner.reserve(soup.corners.size());
        PolygonTriangulator triangulator;
        std::vector<Point> poly;
        std::vector<PolygonTriangle> local;
        std::vector<Index> sorted;
        std::size_t fanned = 0;
        for (std::size_t f = 0; f < soup.n_faces(); ++f) {
            const std::size_t begin = soup.face_offsets[f], n = soup.face_offsets[f + 1] - begin;
            const Index* c = soup.corners.data() + begin;
            bool repeated = n < 3;
            if (!repeated && n <= 16) {
                for (std::size_t i = 0; i < n && !repeated; ++i)
                    for (std::size_t j = i + 1; j < n && !repeated; ++j) repeated = c[i] == c[j];
            } else if (!repeated) {
                sorted.assign(c, c + n);
                std::sort(sorted.begin(), sorted.end());
                repeated = std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end();
            }
            if (repeated) {
                ++report.degenerate_faces_dropped;
                continue;
            }
            if (n == 3) {
                own_tris.insert(own_tris.end(), c, c + 3);
                if (keep_corners)
                    for (std::size_t k = 0; k < 3; ++k) own_tri_corner.push_back(Index(begin + k));
                continue;
            }
            poly.clear();
            for (std::size_t i = 0; i < n; ++i) poly.push_back(soup.positions[c[i]]);
            ++report.polygons_triangulated;
            local.clear();
            if (triangulator.triangulate(poly, local) == TriangulationMethod::kFan) ++fanned;
            for (const PolygonTriangle& t : local) {
                for (int k = 0; k < 3; ++k) {
                    own_tris.push_back(c[t[k]]);
                    if (keep_corners) own_tri_corner.push_back(Index(begin + t[k]));
                }
                ++report.triangles_from_polygons;
            }
        }
        if (fanned)
            report.notes.push_back(std::to_string(fanned) +
                                   " polygons are not simple in their best-fit plane (they cross "
                                   "or fold over themselves, or have no area): triangulated as "
                                   "fans, which may overlap");
    }
    const Index* tri = clean_triangles ? soup.corners.data() : own_tris.data();
    const std::size_t n_corners = clean_triangles ? soup.corners.size() : own_tris.size();
    const std::size_t n_tris = n_corners / 3;
    if (n_corners >= std::size_t(kInvalidIndex))
        throw InvalidArgument("build_mesh: " + std::to_string(n_tris) +
                              " triangles are more than the " + std::to_string(kInvalidIndex / 3) +
                              " that 32-bit indices hold");
    // The corner that follows corner c in its triangle.
    auto next_corner = [](std::size_t c) { return c % 3 == 2 ? c - 2 : c + 1; };

    // 2. Edges. The 3T corner edges are grouped by their unordered vertex pair: a counting
    //    sort on the smaller vertex, then the larger one within each bucket (a short bucket
    //    is scanned, a long one sorted). The first entry of a group holds its state (the
    //    edge, once made, and which of its two halfedges are taken), the others point to it.
    //    Triangles are then accepted in file order when each of their three directed
    //    halfedges is still free; halfedge 2e runs from the smaller to the larger vertex of
    //    edge e, and edges are numbered in the order they are first used. Both passes visit
    //    the corners in the same order, so a running position per bucket finds each corner's
    //    entry again without storing it.
    constexpr std::uint64_t kHead = std::uint64_t(1) << 32;   // the group's first entry
    constexpr std::uint64_t kTaken = std::uint64_t(1) << 33;  // << 0: lo -> hi, << 1: hi -> lo
    std::vector<Index> position(n_input_vertices + 1, 0);
    for (std::size_t c = 0; c < n_corners; ++c)
        ++position[std::min(tri[c], tri[next_corner(c)]) + 1];
    for (std::size_t v = 0; v < n_input_vertices; ++v) position[v + 1] += position[v];
    // First the larger vertex of each corner edge in bucket order, then the group links.
    // Every entry is written by the sort below: no zero fill first.
    std::unique_ptr<std::uint64_t[]> entry(new std::uint64_t[n_corners]);
    {
        std::vector<Index> fill(position.begin(), position.end() - 1);
        for (std::size_t c = 0; c < n_corners; ++c) {
            const Index a = tri[c], b = tri[next_corner(c)];
            entry[fill[std::min(a, b)]++] = std::max(a, b);
        }
    }
    std::size_t n_groups = 0;
    {
        constexpr Index kScan = 16;
        Index partner[kScan];
        std::vector<std::pair<Index, Index>> sorted;  // (larger vertex, position)
        for (std::size_t v = 0; v < n_input_vertices; ++v) {
            const Index begin = position[v], end = position[v + 1], m = end - begin;
            if (m <= kScan) {
                for (Index i = 0; i < m; ++i) partner[i] = Index(entry[begin + i]);
                for (Index i = 0; i < m; ++i) {
                    Index j = 0;
                    while (j < i && partner[j] != partner[i]) ++j;
                    if (j < i) {
                        entry[begin + i] = begin + j;
                    } else {
                        entry[begin + i] = kHead | kInvalidIndex;
                        ++n_groups;
                    }
                }
            } else {
                sorted.clear();
                for (Index i = begin; i < end; ++i) sorted.push_back({Index(entry[i]), i});
                std::sort(sorted.begin(), sorted.end());
                Index head = 0;
                for (std::size_t i = 0; i < sorted.size(); ++i) {
                    if (i == 0 || sorted[i].first != sorted[i - 1].first) {
                        head = sorted[i].second;
                        entry[head] = kHead | kInvalidIndex;
                        ++n_groups;
                    } else {
                        entry[sorted[i].second] = head;
                    }
                }
            }
        }
    }
    std::vector<Vertex> hto;  // per halfedge: the vertex it points to
    std::vector<Halfedge> hnext, hprev;
    std::vector<Face> hface;
    std::vector<Halfedge> face_halfedge;  // per face: its halfedge ending at corner 0
    std::vector<Index> face_tri;          // per face: its triangle (for corner texcoords)
    std::vector<Index> detached;          // triangles added detached
    // Sized for every group becoming an edge (the usual case); trimmed after.
    hto.resize(2 * n_groups);
    hnext.resize(2 * n_groups);
    hprev.resize(2 * n_groups);
    hface.resize(2 * n_groups);
    std::size_t n_h = 0;
    face_halfedge.reserve(n_tris);
    if (keep_corners) face_tri.reserve(n_tris);
    // The entries are looked up kAhead triangles early and prefetched (the loop waits on
    // memory, not on arithmetic); the running positions still advance in corner order.
    constexpr std::size_t kAhead = 16;
    std::array<std::array<Index, 3>, kAhead> ahead{};
    auto look_up = [&](std::size_t t) {
        for (std::size_t k = 0; k < 3; ++k) {
            const std::size_t c = 3 * t + k;
            const Index pos = position[std::min(tri[c], tri[next_corner(c)])]++;
            ahead[t % kAhead][k] = pos;
            prefetch(&entry[pos]);
        }
    };
    for (std::size_t t = 0; t < std::min(kAhead, n_tris); ++t) look_up(t);
    for (std::size_t t = 0; t < n_tris; ++t) {
        const std::array<Index, 3> pos3 = ahead[t % kAhead];
        if (t + kAhead < n_tris) look_up(t + kAhead);
        if (t + 2 * kAhead < n_tris)
            for (std::size_t k = 0; k < 3; ++k) {
                const std::size_t c = 3 * (t + 2 * kAhead) + k;
                prefetch(&position[std::min(tri[c], tri[next_corner(c)])]);
            }
        std::array<std::uint64_t*, 3> head;
        std::array<Index, 3> dir;
        bool free = true;
        for (std::size_t k = 0; k < 3; ++k) {
            const std::size_t c = 3 * t + k;
            const Index a = tri[c], b = tri[next_corner(c)];
            const Index pos = pos3[k];
            const std::uint64_t x = entry[pos];
            head[k] = &entry[(x & kHead) ? pos : Index(x)];
            dir[k] = a < b ? 0 : 1;
            free = free && !(*head[k] & (kTaken << dir[k]));
        }
        if (!free) {
            detached.push_back(Index(t));
            continue;
        }
        std::array<Halfedge, 3> he;
        for (std::size_t k = 0; k < 3; ++k) {
            std::uint64_t& state = *head[k];
            state |= kTaken << dir[k];
            if (Index(state) == kInvalidIndex) {
                const std::size_t c = 3 * t + k;
                const Index a = tri[c], b = tri[next_corner(c)];
                state = (state & ~std::uint64_t(kInvalidIndex)) | Index(n_h / 2);
                hto[n_h++] = Vertex(std::max(a, b));
                hto[n_h++] = Vertex(std::min(a, b));
            }
            he[k] = Halfedge(2 * Index(state) + dir[k]);
        }
        const Face f(Index(face_halfedge.size()));
        for (std::size_t k = 0; k < 3; ++k) {
            const Halfedge h = he[k], n = he[(k + 1) % 3];
            hface[h.idx()] = f;
            hnext[h.idx()] = n;
            hprev[n.idx()] = h;
        }
        face_halfedge.push_back(he[2]);  // ends at corner 0, as OpenMesh's add_face does
        if (keep_corners) face_tri.push_back(Index(t));
    }
    // Release the grouping before the vertices are built.
    entry.reset();
    std::vector<Index>().swap(position);
    hto.resize(n_h);
    hnext.resize(n_h);
    hprev.resize(n_h);
    hface.resize(n_h);

    // 3. Fans: the faces around each vertex split into fans (walked from each face halfedge
    //    in index order, so a vertex's first fan is the one holding its lowest halfedge);
    //    the first fan keeps the vertex, every further one gets a copy. Boundary halfedges
    //    are linked where a fan ends.
    std::vector<Halfedge> vhalfedge(n_input_vertices);
    std::vector<Index> copy_source;  // vertex n_input_vertices + i copies copy_source[i]
    struct ExtraFan {
        Index vertex, start;
        Halfedge first;
    };
    std::vector<ExtraFan> extra_fans;
    {
        std::vector<std::uint8_t> visited(n_h, 0);
        for (Index h = 0; h < n_h; ++h) {
            if (visited[h] || !hface[h].is_valid()) continue;
            // Walk counter-clockwise (x -> twin(prev(x))) from h. A closed fan comes back
            // to h and starts at ccw(h) (so that clockwise from there comes back first to
            // h); an open one ends at a boundary halfedge, and its start is then found
            // walking clockwise (x -> next(twin(x))) from h.
            Halfedge boundary_out;
            Index start = hprev[h].idx() ^ 1;
            for (Index cur = h;;) {
                visited[cur] = 1;
                const Index nxt = hprev[cur].idx() ^ 1;
                if (!hface[nxt].is_valid()) {
                    boundary_out = Halfedge(nxt);
                    visited[nxt] = 1;
                    break;
                }
                if (nxt == h) break;
                cur = nxt;
            }
            if (boundary_out.is_valid()) {
                start = h;
                for (;;) {
                    const Index t = start ^ 1;
                    if (!hface[t].is_valid()) break;
                    start = hnext[t].idx();
                    visited[start] = 1;
                }
                const Halfedge boundary_in(start ^ 1);
                hnext[boundary_in.idx()] = boundary_out;
                hprev[boundary_out.idx()] = boundary_in;
            }
            const Halfedge first = boundary_out.is_valid() ? boundary_out : Halfedge(start);
            const Index v = hto[h ^ 1].idx();
            if (!vhalfedge[v].is_valid())
                vhalfedge[v] = first;
            else
                extra_fans.push_back({v, start, first});
        }
    }
    // Copies in vertex order, each vertex's fans in the order found.
    std::stable_sort(extra_fans.begin(), extra_fans.end(),
                     [](const ExtraFan& a, const ExtraFan& b) { return a.vertex < b.vertex; });
    for (std::size_t i = 0; i < extra_fans.size(); ++i) {
        const ExtraFan& fan = extra_fans[i];
        if (i == 0 || extra_fans[i - 1].vertex != fan.vertex) ++report.nonmanifold_vertices_split;
        const Vertex copy(Index(n_input_vertices + copy_source.size()));
        copy_source.push_back(fan.vertex);
        vhalfedge.push_back(fan.first);
        ++report.vertex_copies_added;
        for (Index cur = fan.start;;) {
            hto[cur ^ 1] = copy;
            const Index nxt = hprev[cur].idx() ^ 1;
            if (!hface[nxt].is_valid()) {
                hto[nxt ^ 1] = copy;
                break;
            }
            if (nxt == fan.start) break;
            cur = nxt;
        }
    }

    // 4. Detached triangles: fresh edges; corners reuse a vertex only if nothing uses it yet.
    hto.reserve(n_h + 6 * detached.size());
    hnext.reserve(n_h + 6 * detached.size());
    hprev.reserve(n_h + 6 * detached.size());
    hface.reserve(n_h + 6 * detached.size());
    for (Index t : detached) {
        std::array<Vertex, 3> vs;
        for (std::size_t k = 0; k < 3; ++k) {
            const Index v = tri[3 * std::size_t(t) + k];
            if (!vhalfedge[v].is_valid()) {
                vs[k] = Vertex(v);
            } else {
                vs[k] = Vertex(Index(n_input_vertices + copy_source.size()));
                copy_source.push_back(v);
                vhalfedge.push_back(Halfedge());
                ++report.vertex_copies_added;
            }
        }
        const Face f(Index(face_halfedge.size()));
        const Index h0 = Index(hto.size());
        for (std::size_t k = 0; k < 3; ++k) {
            hto.push_back(vs[(k + 1) % 3]);
            hto.push_back(vs[k]);
            hface.push_back(f);
            hface.push_back(Face());
        }
        hnext.resize(hto.size());
        hprev.resize(hto.size());
        for (Index k = 0; k < 3; ++k) {
            const Index inner = h0 + 2 * k, inner_next = h0 + 2 * ((k + 1) % 3);
            hnext[inner] = Halfedge(inner_next);
            hprev[inner_next] = Halfedge(inner);
            // The boundary loop runs the other way round.
            const Index outer = inner + 1, outer_next = h0 + 2 * ((k + 2) % 3) + 1;
            hnext[outer] = Halfedge(outer_next);
            hprev[outer_next] = Halfedge(outer);
            vhalfedge[vs[k].idx()] = Halfedge(h0 + 2 * ((k + 2) % 3) + 1);  // boundary, out
        }
        face_halfedge.push_back(Halfedge(h0 + 4));  // vs[2] -> vs[0]: ends at corner 0
        if (keep_corners) face_tri.push_back(t);
        ++report.detached_faces;
    }

    // 5. The mesh takes the arrays (no copy); attributes follow each vertex's source.
    const std::size_t n_v = vhalfedge.size();
    auto source = [&](std::size_t v) {
        return v < n_input_vertices ? v : std::size_t(copy_source[v - n_input_vertices]);
    };
    std::vector<Point> positions;
    positions.reserve(n_v);
    positions.assign(soup.positions.begin(), soup.positions.end());
    for (Index s : copy_source) positions.push_back(soup.positions[s]);
    for (const Halfedge& h : vhalfedge)
        if (!h.is_valid()) ++report.isolated_vertices;
    const std::size_t n_f = face_halfedge.size();
    HalfedgeMesh mesh;
    mesh.assign_connectivity(std::move(positions), std::move(vhalfedge), std::move(hto),
                             std::move(hnext), std::move(hprev), std::move(hface),
                             std::move(face_halfedge));

    if (!soup.normals.empty()) {
        auto p = mesh.vertex_property<Vector3>("v:normal");
        for (std::size_t v = 0; v < n_v; ++v) p[Vertex(Index(v))] = soup.normals[source(v)];
    }
    if (!soup.colors.empty()) {
        auto p = mesh.vertex_property<Color>("v:color");
        for (std::size_t v = 0; v < n_v; ++v) p[Vertex(Index(v))] = soup.colors[source(v)];
    }
    if (!soup.texcoords.empty()) {
        auto p = mesh.vertex_property<TexCoord>("v:texcoord");
        for (std::size_t v = 0; v < n_v; ++v) p[Vertex(Index(v))] = soup.texcoords[source(v)];
    }
    if (keep_corners) {
        const Index* tri_corner = clean_triangles ? nullptr : own_tri_corner.data();
        auto p = mesh.halfedge_property<TexCoord>("h:texcoord", TexCoord::Zero());
        for (Index f = 0; f < n_f; ++f) {
            // The face's halfedge ends at corner 0; its next ends at corner 1, and so on.
            Halfedge h = mesh.halfedge(Face(f));
            const std::size_t c0 = 3 * std::size_t(face_tri[f]);
            for (std::size_t k = 0; k < 3; ++k, h = mesh.next(h))
                p[h] = soup.corner_texcoords[tri_corner ? tri_corner[c0 + k] : c0 + k];
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
