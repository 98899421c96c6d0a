#include "core/mesh_builder.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <exception>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <thread>
#include <utility>

#include "core/errors.h"
#include "core/features.h"
#include "core/number_text.h"
#include "core/prefault.h"
#include "core/prefetch.h"
#include "core/triangulate.h"
#include "core/two_threads.h"

namespace trilab {

void PolygonSoup::add_face(const std::vector<Index>& face, const std::vector<TexCoord>& uv) {
    corners.insert(corners.end(), face.begin(), face.end());
    corner_texcoords.insert(corner_texcoords.end(), uv.begin(), uv.end());
    face_offsets.push_back(corners.size());
}

std::vector<std::string> LoadReport::lines() const {
    std::vector<std::string> out;
    auto add = [&](std::size_t n, const char* one, const char* many, const char* what) {
        if (n) out.push_back(count_text(n, one, many) + " " + what);
    };
    add(polygons_triangulated, "polygon", "polygons", "triangulated");
    add(triangles_from_polygons, "triangle", "triangles", "made from polygons");
    add(degenerate_faces_dropped, "degenerate face", "degenerate faces",
        "dropped (repeated vertex or < 3 corners)");
    add(detached_faces, "face", "faces",
        "detached (non-manifold edge, flipped or duplicated face)");
    add(nonmanifold_vertices_split, "non-manifold vertex", "non-manifold vertices", "split");
    add(vertex_copies_added, "vertex copy", "vertex copies", "added");
    add(isolated_vertices, "isolated vertex", "isolated vertices", "kept");
    add(merged_vertices, "duplicate vertex", "duplicate vertices", "merged");
    for (const std::string& n : notes) out.push_back(n);
    return out;
}

void check_polygon_soup(const PolygonSoup& soup) {
    const std::size_t nv = soup.positions.size();
    if (nv >= std::size_t(kInvalidIndex) / 2)
        throw InvalidArgument("build_mesh: " + std::to_string(nv) +
                              " vertices are more than 32-bit indices can number");
    if (soup.face_offsets.empty() || soup.face_offsets.front() != 0 ||
        soup.face_offsets.back() != soup.corners.size())
        throw InvalidArgument("build_mesh: face_offsets do not match the corner list");
    // The faces, then the positions; a large soup's in two halves on two threads, the lower
    // half's first problem reported before the upper half's (as one pass finds them).
    const std::size_t nf = soup.n_faces();
    std::string problem[2][2];  // [faces, positions][half]
    on_two_threads(worth_two_threads(nf) && worth_two_threads(nv), [&](int half) {
        const HalfRange faces = half_of(nf, half);
        for (std::size_t f = faces.begin; f < faces.end; ++f) {
            if (soup.face_offsets[f + 1] < soup.face_offsets[f]) {
                problem[0][half] = "build_mesh: face_offsets decrease at face " + std::to_string(f);
                break;
            }
            bool bad = false;
            for (std::size_t c = soup.face_offsets[f]; c < soup.face_offsets[f + 1] && !bad; ++c)
                if (soup.corners[c] >= nv) {
                    problem[0][half] = "build_mesh: face " + std::to_string(f) + " uses vertex " +
                                       std::to_string(soup.corners[c]) + " but there are only " +
                                       std::to_string(nv) + " vertices";
                    bad = true;
                }
            if (bad) break;
        }
        const HalfRange vertices = half_of(nv, half);
        for (std::size_t v = vertices.begin; v < vertices.end; ++v) {
            // std::isfinite, not allFinite(): that subtracts, and inf - inf traps under the
            // sanitizer build's floating-point exceptions.
            const Point& x = soup.positions[v];
            if (!(std::isfinite(x.x()) && std::isfinite(x.y()) && std::isfinite(x.z()))) {
                problem[1][half] =
                    "build_mesh: vertex " + std::to_string(v) + " has a non-finite coordinate";
                break;
            }
        }
    });
    for (const auto& kind : problem)
        for (const std::string& p : kind)
            if (!p.empty()) throw InvalidArgument(p);
    auto check_size = [&](std::size_t n, std::size_t want, const char* what) {
        if (n != 0 && n != want)
            throw InvalidArgument(std::string("build_mesh: ") + what + " has " + std::to_string(n) +
                                  " entries, expected " + std::to_string(want));
    };
    check_size(soup.normals.size(), nv, "normals");
    check_size(soup.colors.size(), nv, "colors");
    check_size(soup.texcoords.size(), nv, "texcoords");
    check_size(soup.distances.size(), nv, "distances");
    check_size(soup.selections.size(), nv, "selections");
    check_size(soup.corner_texcoords.size(), soup.corners.size(), "corner_texcoords");
    check_size(soup.corner_tags.size(), nv, "corner_tags");
    for (std::size_t i = 0; i < soup.corner_tags.size(); ++i)
        if (soup.corner_tags[i] > 1)
            throw InvalidArgument("build_mesh: vertex " + std::to_string(i) + ": corner tag " +
                                  std::to_string(soup.corner_tags[i]) + " is not 0 or 1");
    for (std::size_t i = 0; i < soup.sharp_edges.size(); ++i) {
        const PolygonSoup::SharpEdge& s = soup.sharp_edges[i];
        if (s.a >= nv || s.b >= nv || s.a == s.b)
            throw InvalidArgument(
                "build_mesh: sharp edge " + std::to_string(i) + " joins vertices " +
                std::to_string(s.a) + " and " + std::to_string(s.b) +
                (s.a == s.b ? " (the same vertex)"
                            : " (the soup has " + std::to_string(nv) + " vertices)"));
        if (!valid_sharpness(s.sharpness))
            throw InvalidArgument("build_mesh: sharp edge " + std::to_string(i) + ": sharpness " +
                                  number_text(s.sharpness) + " is not >= 0 (or inf)");
    }
}

namespace {

// build_mesh() runs in five stages, each a function below:
//  1. triangles: the soup's faces as a flat corner list, three per triangle;
//  2. edges: the corner edges grouped by unordered vertex pair, then the triangles accepted
//     in file order where their three halfedges are free;
//  3. fans: each vertex's faces split into fans, a copy per fan after the first;
//  4. detached triangles, with fresh edges and vertex copies where needed;
//  5. the mesh takes the arrays; attributes follow each vertex's source.
// Memory: the triangle soup's own corner list is used when every face is a triangle; edges are
// found by a counting sort of the corner edges (no hash map), and the mesh takes the
// connectivity arrays without a copy. The prev array is made only once the grouping is freed,
// and a consumed soup (build_mesh(PolygonSoup&&)) gives up its face offsets after stage 1 and
// its positions to the mesh; the fast path releases its triangles once read for the last time:
// 17.8M triangles peak at about 1.3 GB (file reading included).

/// Stage 1's output: the triangles as three corners each. `tri` points into the soup's own
/// corner list when every face is a triangle without a repeated corner (no copy), else into
/// `own_tris`, with the polygons triangulated and the degenerate faces dropped.
/// `own_tri_corner` gives the soup corner of each triangle corner (identity, and empty, when
/// the soup's list is used; filled only when corner texture coordinates are kept).
struct Triangles {
    bool clean = false;
    std::vector<Index> own_tris, own_tri_corner;
    const Index* tri = nullptr;
    std::size_t n_corners = 0;
    std::size_t n_tris() const { return n_corners / 3; }
};

/// The corner that follows corner c in its triangle.
inline std::size_t next_corner(std::size_t c) {
    return c % 3 == 2 ? c - 2 : c + 1;
}

/// True when every face of the soup is a triangle without a repeated corner.
bool is_clean_triangle_soup(const PolygonSoup& soup) {
    const std::size_t nf = soup.n_faces();
    if (soup.corners.size() != 3 * nf) return false;
    bool clean[2] = {true, true};  // per half of the faces (two threads for a large soup)
    on_two_threads(worth_two_threads(nf), [&](int half) {
        bool ok = true;
        const HalfRange faces = half_of(nf, half);
        for (std::size_t f = faces.begin; f < faces.end && ok; ++f) {
            const std::size_t b = soup.face_offsets[f];
            ok = soup.face_offsets[f + 1] == b + 3 && soup.corners[b] != soup.corners[b + 1] &&
                 soup.corners[b + 1] != soup.corners[b + 2] &&
                 soup.corners[b] != soup.corners[b + 2];
        }
        clean[half] = ok;
    });
    return clean[0] && clean[1];
}

/// True when the n corners at c have fewer than three entries or repeat a vertex (pairwise
/// up to 16 corners, sorted in `sorted` above).
bool is_degenerate_face(const Index* c, std::size_t n, std::vector<Index>& sorted) {
    bool repeated = n < 3;
    if (!repeated && n <= 16) {
        for (std::size_t i = 0; i < n && !repeated; ++i)
            for (std::size_t j = i + 1; j < n && !repeated; ++j) repeated = c[i] == c[j];
    } else if (!repeated) {
        sorted.assign(c, c + n);
        std::sort(sorted.begin(), sorted.end());
        repeated = std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end();
    }
    return repeated;
}

/// Stage 1 for a soup that is not clean: triangles into out.own_tris (and their soup
/// corners into out.own_tri_corner when `keep_corners`), polygons triangulated, degenerate
/// faces dropped and counted.
void triangulate_faces(const PolygonSoup& soup, bool keep_corners, LoadReport& report,
                       Triangles& out) {
    out.own_tris.reserve(soup.corners.size());
    if (keep_corners) out.own_tri_corner.reserve(soup.corners.size());
    PolygonTriangulator triangulator;
    std::vector<Point> poly;
    std::vector<PolygonTriangle> local;
    std::vector<Index> sorted;
    std::size_t fanned = 0;
    for (std::size_t f = 0; f < soup.n_faces(); ++f) {
        const std::size_t begin = soup.face_offsets[f], n = soup.face_offsets[f + 1] - begin;
        const Index* c = soup.corners.data() + begin;
        if (is_degenerate_face(c, n, sorted)) {
            ++report.degenerate_faces_dropped;
            continue;
        }
        if (n == 3) {
            out.own_tris.insert(out.own_tris.end(), c, c + 3);
            if (keep_corners)
                for (std::size_t k = 0; k < 3; ++k) out.own_tri_corner.push_back(Index(begin + k));
            continue;
        }
        poly.clear();
        for (std::size_t i = 0; i < n; ++i) poly.push_back(soup.positions[c[i]]);
        ++report.polygons_triangulated;
        local.clear();
        if (triangulator.triangulate(poly, local) == TriangulationMethod::kFan) ++fanned;
        for (const PolygonTriangle& t : local) {
            for (int k = 0; k < 3; ++k) {
                out.own_tris.push_back(c[t[k]]);
                if (keep_corners) out.own_tri_corner.push_back(Index(begin + t[k]));
            }
            ++report.triangles_from_polygons;
        }
    }
    if (fanned)
        report.notes.push_back(count_text(fanned, "polygon is", "polygons are") +
                               " not simple in the best-fit plane (crossing or folding over "
                               "itself, or without area): triangulated as a fan, which may "
                               "overlap");
}

/// Stage 1: the soup's triangles (see Triangles); throws when there are more than 32-bit
/// indices can number.
void make_triangles(const PolygonSoup& soup, bool keep_corners, LoadReport& report,
                    Triangles& out) {
    out.clean = is_clean_triangle_soup(soup);
    if (!out.clean) triangulate_faces(soup, keep_corners, report, out);
    out.tri = out.clean ? soup.corners.data() : out.own_tris.data();
    out.n_corners = out.clean ? soup.corners.size() : out.own_tris.size();
    if (out.n_corners >= std::size_t(kInvalidIndex))
        throw InvalidArgument("build_mesh: " + std::to_string(out.n_tris()) +
                              " triangles are more than the " + std::to_string(kInvalidIndex / 3) +
                              " that 32-bit indices hold");
}

// Stage 2. The 3T corner edges are grouped by their unordered vertex pair: a counting sort on
// the smaller vertex, then the larger one within each bucket (a short bucket is scanned, a
// long one sorted). The first entry of a group holds its state (the edge, once made, and which
// of its two halfedges are taken), the others point to it. Triangles are then accepted in file
// order when each of their three directed halfedges is still free; halfedge 2e runs from the
// smaller to the larger vertex of edge e, and edges are numbered in the order they are first
// used. Both passes visit the corners in the same order, so a running position per bucket
// finds each corner's entry again without storing it.
constexpr std::uint64_t kHead = std::uint64_t(1) << 32;   // the group's first entry
constexpr std::uint64_t kTaken = std::uint64_t(1) << 33;  // << 0: lo -> hi, << 1: hi -> lo

/// The corner edges' grouping (stage 2).
struct EdgeGroups {
    std::vector<Index> position;  ///< per vertex: its bucket's start (then running position)
    std::unique_ptr<std::uint64_t[]> entry;  ///< per corner edge, in bucket order
    std::size_t n_groups = 0;
};

/// The connectivity arrays being built (stages 2 to 4).
struct Connectivity {
    std::vector<Vertex> hto;  ///< per halfedge: the vertex it points to
    std::vector<Halfedge> hnext, hprev;
    std::vector<Face> hface;
    std::vector<Halfedge> face_halfedge;  ///< per face: its halfedge ending at corner 0
    std::vector<Index> face_tri;          ///< per face: its triangle (for corner texcoords)
    std::vector<Index> detached;          ///< triangles added detached
    std::vector<Halfedge> vhalfedge;      ///< per vertex: its outgoing halfedge
    std::vector<Index> copy_source;       ///< vertex n_input_vertices + i copies copy_source[i]
    std::size_t n_h = 0;
};

/// Stage 2a: the counting sort of the corner edges into one bucket per smaller vertex; each
/// entry holds the larger vertex of its corner edge.
void bucket_corner_edges(const Index* tri, std::size_t n_corners, std::size_t n_vertices,
                         EdgeGroups& g) {
    std::vector<Index>& position = g.position;
    position.assign(n_vertices + 1, 0);
    for (std::size_t c = 0; c < n_corners; ++c)
        ++position[std::min(tri[c], tri[next_corner(c)]) + 1];
    for (std::size_t v = 0; v < n_vertices; ++v) position[v + 1] += position[v];
    // Every entry is written by the sort below: no zero fill first.
    g.entry.reset(new std::uint64_t[n_corners]);
    std::vector<Index> fill(position.begin(), position.end() - 1);
    for (std::size_t c = 0; c < n_corners; ++c) {
        const Index a = tri[c], b = tri[next_corner(c)];
        g.entry[fill[std::min(a, b)]++] = std::max(a, b);
    }
}

/// Stage 2b: within each bucket, the entries with the same larger vertex form a group; the
/// first becomes its head (no edge yet), the others point to it. Counts the groups.
void link_groups(std::size_t n_vertices, EdgeGroups& g) {
    constexpr Index kScan = 16;
    Index partner[kScan];
    std::vector<std::pair<Index, Index>> sorted;  // (larger vertex, position)
    std::uint64_t* entry = g.entry.get();
    for (std::size_t v = 0; v < n_vertices; ++v) {
        const Index begin = g.position[v], end = g.position[v + 1], m = end - begin;
        if (m <= kScan) {
            for (Index i = 0; i < m; ++i) partner[i] = Index(entry[begin + i]);
            for (Index i = 0; i < m; ++i) {
                Index j = 0;
                while (j < i && partner[j] != partner[i]) ++j;
                if (j < i) {
                    entry[begin + i] = begin + j;
                } else {
                    entry[begin + i] = kHead | kInvalidIndex;
                    ++g.n_groups;
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
                    ++g.n_groups;
                } else {
                    entry[sorted[i].second] = head;
                }
            }
        }
    }
}

/// The entry positions of triangle t's three corner edges (advancing the running
/// positions), prefetching the entries.
inline void look_up_entries(const Index* tri, std::size_t t, EdgeGroups& g,
                            std::array<Index, 3>& pos3) {
    for (std::size_t k = 0; k < 3; ++k) {
        const std::size_t c = 3 * t + k;
        const Index pos = g.position[std::min(tri[c], tri[next_corner(c)])]++;
        pos3[k] = pos;
        prefetch(&g.entry[pos]);
    }
}

/// Makes triangle t face f: takes its three halfedges (making an edge where its group has
/// none yet) and links them in a loop. `head` and `dir` are each corner edge's group state
/// and direction.
inline void add_triangle(const Index* tri, std::size_t t, const std::array<std::uint64_t*, 3>& head,
                         const std::array<Index, 3>& dir, bool keep_corners, Connectivity& c) {
    std::array<Halfedge, 3> he;
    for (std::size_t k = 0; k < 3; ++k) {
        std::uint64_t& state = *head[k];
        state |= kTaken << dir[k];
        if (Index(state) == kInvalidIndex) {
            const std::size_t corner = 3 * t + k;
            const Index a = tri[corner], b = tri[next_corner(corner)];
            state = (state & ~std::uint64_t(kInvalidIndex)) | Index(c.n_h / 2);
            c.hto[c.n_h++] = Vertex(std::max(a, b));
            c.hto[c.n_h++] = Vertex(std::min(a, b));
        }
        he[k] = Halfedge(2 * Index(state) + dir[k]);
    }
    const Face f(Index(c.face_halfedge.size()));
    for (std::size_t k = 0; k < 3; ++k) {
        const Halfedge h = he[k], n = he[(k + 1) % 3];
        c.hface[h.idx()] = f;
        c.hnext[h.idx()] = n;
    }
    c.face_halfedge.push_back(he[2]);  // ends at corner 0, as OpenMesh's add_face does
    if (keep_corners) c.face_tri.push_back(Index(t));
}

/// Stage 2c: the triangles accepted in file order where their three halfedges are free, the
/// others listed in c.detached. Releases the grouping at the end, then sets prev.
void accept_triangles(const Triangles& tris, bool keep_corners, EdgeGroups& g, Connectivity& c) {
    const Index* tri = tris.tri;
    const std::size_t n_tris = tris.n_tris();
    // Sized for every group becoming an edge (the usual case); trimmed after.
    c.hto.resize(2 * g.n_groups);
    c.hnext.resize(2 * g.n_groups);
    c.hface.resize(2 * g.n_groups);  // prev is derived after the grouping is released
    c.face_halfedge.reserve(n_tris);
    if (keep_corners) c.face_tri.reserve(n_tris);
    // The entries are looked up kAhead triangles early and prefetched (the loop waits on
    // memory, not on arithmetic); the running positions still advance in corner order.
    constexpr std::size_t kAhead = 16;
    std::array<std::array<Index, 3>, kAhead> ahead{};
    for (std::size_t t = 0; t < std::min(kAhead, n_tris); ++t)
        look_up_entries(tri, t, g, ahead[t % kAhead]);
    for (std::size_t t = 0; t < n_tris; ++t) {
        const std::array<Index, 3> pos3 = ahead[t % kAhead];
        if (t + kAhead < n_tris) look_up_entries(tri, t + kAhead, g, ahead[(t + kAhead) % kAhead]);
        if (t + 2 * kAhead < n_tris)
            for (std::size_t k = 0; k < 3; ++k) {
                const std::size_t corner = 3 * (t + 2 * kAhead) + k;
                prefetch(&g.position[std::min(tri[corner], tri[next_corner(corner)])]);
            }
        std::array<std::uint64_t*, 3> head;
        std::array<Index, 3> dir;
        bool free = true;
        for (std::size_t k = 0; k < 3; ++k) {
            const std::size_t corner = 3 * t + k;
            const Index a = tri[corner], b = tri[next_corner(corner)];
            const Index pos = pos3[k];
            const std::uint64_t x = g.entry[pos];
            head[k] = &g.entry[(x & kHead) ? pos : Index(x)];
            dir[k] = a < b ? 0 : 1;
            free = free && !(*head[k] & (kTaken << dir[k]));
        }
        if (free)
            add_triangle(tri, t, head, dir, keep_corners, c);
        else
            c.detached.push_back(Index(t));
    }
    // Release the grouping before the vertices are built.
    g.entry.reset();
    std::vector<Index>().swap(g.position);
    c.hto.resize(c.n_h);
    c.hnext.resize(c.n_h);
    c.hface.resize(c.n_h);
    // prev inverts next on the face halfedges (the boundary ones are linked by find_fans);
    // made only now, so that it never coexists with the grouping (peak memory).
    c.hprev.assign(c.n_h, Halfedge());
    for (Index h = 0; h < c.n_h; ++h)
        if (c.hface[h].is_valid()) c.hprev[c.hnext[h].idx()] = Halfedge(h);
}

// Stage 2, the fast path (two threads). When every unordered vertex pair is the corner edge
// of at most two triangles, and of two only in opposite directions, every triangle is
// accepted in stage 2c, so its result is known without the ordered pass: edge e is the e-th
// pair in the order of its first corner, and a corner's partner takes the other halfedge.
// The corner edges are bucketed by their smaller vertex as in stage 2a (each thread
// counting and placing half of them), the pairs found within the buckets (each thread half
// of the entries), the edges numbered by a prefix count of the first corners, and the
// connectivity arrays scattered per triangle. Each step writes disjoint elements only. The
// result equals stage 2's element for element; when some pair breaks the condition,
// nothing is kept and stage 2 runs (a file with flipped, duplicated or non-manifold faces).

// An entry of the fast path's buckets: the corner (bits 0-31), the larger vertex (32-62;
// check_soup keeps vertex indices below 2^31) and the direction (bit 63: larger to smaller).
constexpr std::uint64_t kDownward = std::uint64_t(1) << 63;
// The fast path's per-corner links (step 2), then halfedges (step 3, marked with kNumbered
// until every corner has one; the fast path needs fewer than 2^30 corners).
constexpr Index kFirstCorner = kInvalidIndex;
constexpr Index kNumbered = Index(1) << 31;

/// Fast path step 1: the corner edges bucketed by their smaller vertex, in corner order
/// within each bucket; `start` gets each bucket's first entry (size n_vertices + 1).
std::unique_ptr<std::uint64_t[]> bucket_corners_by_pair(const Index* tri, std::size_t n_corners,
                                                        std::size_t n_vertices, bool parallel,
                                                        std::vector<Index>& start) {
    const std::size_t half = (n_corners / 3 / 2) * 3;
    const std::size_t lo[2] = {0, half}, hi[2] = {half, n_corners};
    std::vector<Index> fill[2];
    on_two_threads(parallel, [&](int part) {
        std::vector<Index>& count = fill[part];
        count.assign(n_vertices, 0);
        for (std::size_t c = lo[part]; c < hi[part]; ++c)
            ++count[std::min(tri[c], tri[next_corner(c)])];
    });
    // The buckets' starts (a prefix sum; each half of the vertices on its own thread, the
    // upper half offset by the lower half's total), and where each thread's entries go in
    // each bucket: the first half's corners before the second's.
    reserve_prefaulted(n_vertices + 1, parallel, start);
    start.resize(n_vertices + 1);
    const std::size_t v_mid = n_vertices / 2;
    Index lower_total[2] = {0, 0};  // the lower half's entries, by its two quarters
    on_two_threads(parallel, [&](int part) {
        Index sum = 0;
        const HalfRange quarter = half_of(v_mid, part);
        for (std::size_t v = quarter.begin; v < quarter.end; ++v) sum += fill[0][v] + fill[1][v];
        lower_total[part] = sum;
    });
    on_two_threads(parallel, [&](int part) {
        Index running = part == 0 ? 0 : lower_total[0] + lower_total[1];
        const HalfRange vertices = half_of(n_vertices, part);  // split at v_mid
        for (std::size_t v = vertices.begin; v < vertices.end; ++v) {
            start[v] = running;
            const Index n0 = fill[0][v];
            running += n0 + fill[1][v];
            fill[0][v] = start[v];
            fill[1][v] = start[v] + n0;
        }
    });
    start[n_vertices] = Index(n_corners);
    std::unique_ptr<std::uint64_t[]> entry(new std::uint64_t[n_corners]);  // all written below
    on_two_threads(parallel, [&](int part) {
        Index* at = fill[part].data();
        for (std::size_t c = lo[part]; c < hi[part]; ++c) {
            const Index a = tri[c], b = tri[next_corner(c)];
            entry[at[std::min(a, b)]++] =
                (a < b ? 0 : kDownward) | (std::uint64_t(std::max(a, b)) << 32) | std::uint64_t(c);
        }
    });
    return entry;
}

/// One bucket of fast path step 2 (its m entries at b): false when some pair has a third
/// corner edge or two in the same direction.
bool pair_bucket(std::uint64_t* b, std::size_t m, Index* link) {
    constexpr std::uint64_t kPair = ~kDownward;  // the larger vertex and the corner
    if (m > 16)                                  // by larger vertex, then corner
        std::sort(b, b + m,
                  [](std::uint64_t x, std::uint64_t y) { return (x & kPair) < (y & kPair); });
    for (std::size_t i = 0; i < m; ++i) {
        const std::uint64_t x = b[i];
        if (x == 0) continue;  // a partner already paired (no entry is 0: max > 0)
        const Index vx = Index((x & kPair) >> 32);
        std::size_t matches = 0, at = 0;
        for (std::size_t j = i + 1; j < m; ++j)
            if (Index((b[j] & kPair) >> 32) == vx) {
                ++matches;
                at = j;
            } else if (m > 16) {
                break;  // sorted: the group has ended
            }
        const Index cx = Index(x);
        link[cx] = kFirstCorner;
        if (matches == 0) continue;
        const std::uint64_t y = b[at];
        if (matches > 1 || (x & kDownward) == (y & kDownward)) return false;
        link[Index(y)] = cx;
        b[at] = 0;  // paired: skipped when the loop reaches it
    }
    return true;
}

/// Fast path step 2: link[c] is kFirstCorner for the first corner edge of each pair (or for
/// one alone: a boundary edge) and the first corner edge for the second. False when some
/// pair has a third corner edge or two in the same direction. The buckets go in 32 pieces of
/// about as many entries each, which the two threads take in turn (so that neither waits
/// long for the other at the end).
bool pair_corners(std::uint64_t* entry, const std::vector<Index>& start, bool parallel,
                  Index* link) {
    const std::size_t n_vertices = start.size() - 1;
    constexpr std::size_t kPieces = 32;
    const std::size_t pieces = parallel ? kPieces : 1;
    std::array<std::size_t, kPieces + 1> piece_start{};
    for (std::size_t k = 1; k < pieces; ++k)
        piece_start[k] = std::size_t(
            std::lower_bound(start.begin(), start.end(), Index(start.back() * k / pieces)) -
            start.begin());
    piece_start[pieces] = n_vertices;
    std::atomic<bool> conflict{false};
    in_pieces(parallel, pieces, [&](std::size_t k) {
        if (conflict.load(std::memory_order_relaxed)) return;  // a piece failed: stage 2 runs
        const std::size_t to = std::min(piece_start[k + 1], n_vertices);
        for (std::size_t v = std::min(piece_start[k], to); v < to; ++v)
            if (!pair_bucket(entry + start[v], start[v + 1] - start[v], link)) {
                conflict.store(true, std::memory_order_relaxed);
                return;
            }
    });
    return !conflict.load();
}

/// Fast path step 3: the halfedge of every corner edge, in `link` (edges numbered in the
/// order of their first corner; halfedge 2e runs from the smaller to the larger vertex), then
/// the connectivity arrays as stage 2c leaves them: every triangle a face, in order. For
/// peak memory, `release_triangles` is called once the triangles are read for the last time
/// (the caller may free them before the next arrays are made), and the link array is
/// released before prev is made.
void connect_paired_corners(const Index* tri, std::size_t n_corners, std::unique_ptr<Index[]>& link,
                            bool keep_corners, bool parallel,
                            const std::function<void()>& release_triangles, Connectivity& c) {
    const std::size_t half = (n_corners / 3 / 2) * 3;
    const std::size_t lo[2] = {0, half}, hi[2] = {half, n_corners};
    std::size_t n_first[2] = {0, 0};
    on_two_threads(parallel, [&](int part) {
        std::size_t n = 0;
        for (std::size_t k = lo[part]; k < hi[part]; ++k) n += link[k] == kFirstCorner;
        n_first[part] = n;
    });
    on_two_threads(parallel, [&](int part) {
        Index e = Index(part == 0 ? 0 : n_first[0]);
        for (std::size_t k = lo[part]; k < hi[part]; ++k)
            if (link[k] == kFirstCorner)
                link[k] = kNumbered | (2 * e++ + (tri[k] < tri[next_corner(k)] ? 0 : 1));
    });
    // A second corner edge takes the other halfedge of its first (numbered above).
    on_two_threads(parallel, [&](int part) {
        for (std::size_t k = lo[part]; k < hi[part]; ++k)
            if (!(link[k] & kNumbered)) link[k] = link[link[k]] ^ 1;
    });
    const std::size_t n_h = 2 * (n_first[0] + n_first[1]), n_tris = n_corners / 3;
    c.n_h = n_h;
    // Where each halfedge points first: the only pass that reads the triangles, which the
    // caller may then release before the other arrays are made (peak memory).
    reserve_prefaulted(n_h, parallel, c.hto);
    c.hto.resize(n_h);
    on_two_threads(parallel, [&](int part) {
        for (std::size_t t = lo[part] / 3; t < hi[part] / 3; ++t) {
            const Index* he = link.get() + 3 * t;
            for (std::size_t k = 0; k < 3; ++k)
                c.hto[he[k] & ~kNumbered] = Vertex(tri[3 * t + (k + 1) % 3]);
        }
    });
    if (release_triangles) release_triangles();
    reserve_prefaulted(n_h, parallel, c.hnext, c.hface);
    reserve_prefaulted(n_tris, parallel, c.face_halfedge);
    on_two_threads(parallel, [&](int part) {  // each thread sizes its own arrays
        if (part == 0) {
            c.hnext.resize(n_h);
            c.face_halfedge.resize(n_tris);
        } else {
            c.hface.resize(n_h);
        }
    });
    if (keep_corners) c.face_tri.resize(n_tris);
    on_two_threads(parallel, [&](int part) {
        for (std::size_t t = lo[part] / 3; t < hi[part] / 3; ++t) {
            const Index* he = link.get() + 3 * t;
            for (std::size_t k = 0; k < 3; ++k) {
                const Index h = he[k] & ~kNumbered;
                c.hface[h] = Face(Index(t));
                c.hnext[h] = Halfedge(he[(k + 1) % 3] & ~kNumbered);
            }
            c.face_halfedge[t] = Halfedge(he[2] & ~kNumbered);  // ends at corner 0
            if (keep_corners) c.face_tri[t] = Index(t);
        }
    });
    link.reset();
    // The boundary halfedges (of the edges with one corner edge) have no face; each points
    // to where its twin starts, which is where its twin's next-but-one points. prev
    // inverts next on the face halfedges (find_fans links the boundary ones).
    reserve_prefaulted(n_h, parallel, c.hprev);
    c.hprev.resize(n_h);
    const std::size_t mid_h = (n_h / 4) * 2;
    on_two_threads(parallel, [&](int part) {
        const std::size_t h0 = part == 0 ? 0 : mid_h, h1 = part == 0 ? mid_h : n_h;
        for (std::size_t h = h0; h < h1; ++h) {
            if (c.hface[h].is_valid()) {
                c.hprev[c.hnext[h].idx()] = Halfedge(Index(h));
            } else {
                const Index inner = Index(h ^ 1);
                c.hto[h] = c.hto[c.hnext[c.hnext[inner].idx()].idx()];
            }
        }
    });
}

/// The fast path of stage 2 (see above): true when it applied, c then holding what stage 2
/// would have made; false, with c untouched, when stage 2 must run.
bool connect_manifold_triangles(const Triangles& tris, std::size_t n_vertices, bool keep_corners,
                                const std::function<void()>& release_triangles, Connectivity& c) {
    const std::size_t n_corners = tris.n_corners;
    if (n_corners >= (std::size_t(1) << 30)) return false;
    const bool parallel = worth_two_threads(n_corners) && detail::build_threads() >= 2;
    // Every entry is written by pair_corners (no zero fill first). One entry a corner, with
    // room for a sixteenth more: the halfedges are the corners plus the boundary edges, so
    // when this block is freed (before prev is made) prev fits where it was, and a large
    // load's peak memory is one array lower (about 200 MB on 17.8M faces).
    std::unique_ptr<Index[]> link(new Index[n_corners + n_corners / 16 + 1024]);
    {
        std::vector<Index> start;
        std::unique_ptr<std::uint64_t[]> entry =
            bucket_corners_by_pair(tris.tri, n_corners, n_vertices, parallel, start);
        if (!pair_corners(entry.get(), start, parallel, link.get())) return false;
    }
    connect_paired_corners(tris.tri, n_corners, link, keep_corners, parallel, release_triangles, c);
    return true;
}

/// A fan of a vertex after its first: it gets a copy of the vertex (stage 3).
struct ExtraFan {
    Index vertex, start;
    Halfedge first;
};

/// Stage 3a: the fans around each vertex (walked from each face halfedge in index order, so
/// a vertex's first fan is the one holding its lowest halfedge). The first fan sets the
/// vertex's halfedge (c.vhalfedge, sized here to n_v input vertices); the further ones are
/// returned. Boundary halfedges are linked where a fan ends.
///
/// A large mesh's halfedges split in two halves on two threads (as validate() walks its
/// fans): each half walks the fans whose lowest face halfedge it holds, and a fan reaching
/// below the half belongs to the half below, walked here only to be passed over. A fan's
/// walk writes only its own boundary links. The lower half sets the vertices' halfedges;
/// the upper half notes its first fan of each vertex apart, and the merge after gives a
/// vertex that fan only when the lower half found none (otherwise it is a further fan, as
/// the one-thread pass finds it). The further fans are ordered by vertex in copy_extra_fans().
std::vector<ExtraFan> find_fans(Connectivity& c, std::size_t n_v, bool parallel) {
    const Index n_h = Index(c.n_h), mid = parallel ? (n_h / 2) & ~Index(1) : n_h;
    std::vector<Halfedge> upper_first;  // per vertex: the upper half's first fan
    std::vector<ExtraFan> extra_fans[2];
    on_two_threads(parallel, [&](int part) {
        if (part == 1 && !parallel) return;
        const Index lo = part == 0 ? 0 : mid, hi = part == 0 ? mid : n_h;
        // Each thread sizes the array it sets.
        if (part == 0) c.vhalfedge.assign(n_v, Halfedge());
        if (part == 1) upper_first.assign(n_v, Halfedge());
        std::vector<Halfedge>& first_fan = part == 0 ? c.vhalfedge : upper_first;
        std::vector<std::uint64_t> seen((std::size_t(hi - lo) + 63) / 64, 0);  // one bit a halfedge
        const auto mark = [&](Index x) {
            if (x >= lo && x < hi) seen[(x - lo) >> 6] |= std::uint64_t(1) << ((x - lo) & 63);
        };
        for (Index h = lo; h < hi; ++h) {
            if (((seen[(h - lo) >> 6] >> ((h - lo) & 63)) & 1) || !c.hface[h].is_valid()) continue;
            // Walk counter-clockwise (x -> twin(prev(x))) from h. A closed fan comes back to h
            // and starts at ccw(h) (so that clockwise from there comes back first to h); an
            // open one ends at a boundary halfedge, and its start is then found walking
            // clockwise (x -> next(twin(x))) from h.
            bool own = true;
            Halfedge boundary_out;
            Index start = c.hprev[h].idx() ^ 1;
            for (Index cur = h;;) {
                mark(cur);
                own = own && cur >= lo;
                const Index nxt = c.hprev[cur].idx() ^ 1;
                if (!c.hface[nxt].is_valid()) {
                    boundary_out = Halfedge(nxt);
                    break;
                }
                if (nxt == h) break;
                cur = nxt;
            }
            if (boundary_out.is_valid()) {
                start = h;
                for (;;) {
                    const Index t = start ^ 1;
                    if (!c.hface[t].is_valid()) break;
                    start = c.hnext[t].idx();
                    mark(start);
                    own = own && start >= lo;
                }
            }
            if (!own) continue;  // the lower half's fan
            if (boundary_out.is_valid()) {
                const Halfedge boundary_in(start ^ 1);
                c.hnext[boundary_in.idx()] = boundary_out;
                c.hprev[boundary_out.idx()] = boundary_in;
            }
            const Halfedge first = boundary_out.is_valid() ? boundary_out : Halfedge(start);
            const Index v = c.hto[h ^ 1].idx();
            if (!first_fan[v].is_valid())
                first_fan[v] = first;
            else
                extra_fans[part].push_back({v, start, first});
        }
    });
    std::vector<ExtraFan>& result = extra_fans[0];
    if (parallel) {
        // The merge, each half of the vertices on its own thread; the upper half's first
        // fans that come after a lower half's fan of the same vertex are further fans.
        std::vector<ExtraFan> demoted[2];
        on_two_threads(true, [&](int part) {
            const HalfRange vertices = half_of(n_v, part);
            for (std::size_t v = vertices.begin; v < vertices.end; ++v) {
                const Halfedge first = upper_first[v];
                if (!first.is_valid()) continue;
                if (!c.vhalfedge[v].is_valid()) {
                    c.vhalfedge[v] = first;
                    continue;
                }
                // An open fan starts where its boundary link comes from.
                const Index start =
                    c.hface[first.idx()].is_valid() ? first.idx() : c.hprev[first.idx()].idx() ^ 1;
                demoted[part].push_back({Index(v), start, first});
            }
        });
        for (const std::vector<ExtraFan>& d : demoted)
            result.insert(result.end(), d.begin(), d.end());
        result.insert(result.end(), extra_fans[1].begin(), extra_fans[1].end());
    }
    return std::move(result);
}

/// Stage 3b: a vertex copy for every further fan, in vertex order, each vertex's fans in the
/// order found; the fan's halfedges are pointed at the copy.
void copy_extra_fans(std::vector<ExtraFan>& extra_fans, std::size_t n_input_vertices,
                     Connectivity& c, LoadReport& report) {
    std::stable_sort(extra_fans.begin(), extra_fans.end(),
                     [](const ExtraFan& a, const ExtraFan& b) { return a.vertex < b.vertex; });
    for (std::size_t i = 0; i < extra_fans.size(); ++i) {
        const ExtraFan& fan = extra_fans[i];
        if (i == 0 || extra_fans[i - 1].vertex != fan.vertex) ++report.nonmanifold_vertices_split;
        const Vertex copy(Index(n_input_vertices + c.copy_source.size()));
        c.copy_source.push_back(fan.vertex);
        c.vhalfedge.push_back(fan.first);
        ++report.vertex_copies_added;
        for (Index cur = fan.start;;) {
            c.hto[cur ^ 1] = copy;
            const Index nxt = c.hprev[cur].idx() ^ 1;
            if (!c.hface[nxt].is_valid()) {
                c.hto[nxt ^ 1] = copy;
                break;
            }
            if (nxt == fan.start) break;
            cur = nxt;
        }
    }
}

/// Stage 4: the detached triangles get fresh edges; a corner reuses its vertex only if
/// nothing uses it yet, else a copy.
void add_detached_triangles(const Index* tri, std::size_t n_input_vertices, bool keep_corners,
                            Connectivity& c, LoadReport& report) {
    const std::size_t n_h = c.hto.size();
    c.hto.reserve(n_h + 6 * c.detached.size());
    c.hnext.reserve(n_h + 6 * c.detached.size());
    c.hprev.reserve(n_h + 6 * c.detached.size());
    c.hface.reserve(n_h + 6 * c.detached.size());
    for (Index t : c.detached) {
        std::array<Vertex, 3> vs;
        for (std::size_t k = 0; k < 3; ++k) {
            const Index v = tri[3 * std::size_t(t) + k];
            if (!c.vhalfedge[v].is_valid()) {
                vs[k] = Vertex(v);
            } else {
                vs[k] = Vertex(Index(n_input_vertices + c.copy_source.size()));
                c.copy_source.push_back(v);
                c.vhalfedge.push_back(Halfedge());
                ++report.vertex_copies_added;
            }
        }
        const Face f(Index(c.face_halfedge.size()));
        const Index h0 = Index(c.hto.size());
        for (std::size_t k = 0; k < 3; ++k) {
            c.hto.push_back(vs[(k + 1) % 3]);
            c.hto.push_back(vs[k]);
            c.hface.push_back(f);
            c.hface.push_back(Face());
        }
        c.hnext.resize(c.hto.size());
        c.hprev.resize(c.hto.size());
        for (Index k = 0; k < 3; ++k) {
            const Index inner = h0 + 2 * k, inner_next = h0 + 2 * ((k + 1) % 3);
            c.hnext[inner] = Halfedge(inner_next);
            c.hprev[inner_next] = Halfedge(inner);
            // The boundary loop runs the other way round.
            const Index outer = inner + 1, outer_next = h0 + 2 * ((k + 2) % 3) + 1;
            c.hnext[outer] = Halfedge(outer_next);
            c.hprev[outer_next] = Halfedge(outer);
            c.vhalfedge[vs[k].idx()] = Halfedge(h0 + 2 * ((k + 2) % 3) + 1);  // boundary, out
        }
        c.face_halfedge.push_back(Halfedge(h0 + 4));  // vs[2] -> vs[0]: ends at corner 0
        if (keep_corners) c.face_tri.push_back(t);
        ++report.detached_faces;
    }
}

/// Stage 5a: the mesh takes the connectivity arrays (no copy; c keeps copy_source and
/// face_tri); positions follow each vertex's source. Counts the isolated vertices.
HalfedgeMesh assemble_mesh(const PolygonSoup& soup, PolygonSoup* owned, Connectivity& c,
                           LoadReport& report) {
    std::vector<Point> positions;
    if (owned) {
        positions = std::move(owned->positions);  // the soup's own array: no copy
        positions.reserve(c.vhalfedge.size());
    } else {
        positions.reserve(c.vhalfedge.size());
        positions.assign(soup.positions.begin(), soup.positions.end());
    }
    for (Index s : c.copy_source) positions.push_back(positions[s]);
    for (const Halfedge& h : c.vhalfedge)
        if (!h.is_valid()) ++report.isolated_vertices;
    HalfedgeMesh mesh;
    mesh.assign_connectivity(std::move(positions), std::move(c.vhalfedge), std::move(c.hto),
                             std::move(c.hnext), std::move(c.hprev), std::move(c.hface),
                             std::move(c.face_halfedge));
    return mesh;
}

/// The soup's corner tags and sharp edges onto the mesh (`source` maps a mesh vertex to its
/// soup vertex): each mesh edge takes the sharpness listed for its ends' soup vertices.
template <class Source>
void copy_features(const PolygonSoup& soup, const Source& source, HalfedgeMesh& mesh,
                   LoadReport& report) {
    const std::size_t n_v = mesh.vertices_size();
    if (!soup.corner_tags.empty()) {
        auto p = corner_property(mesh);
        for (std::size_t v = 0; v < n_v; ++v) p[Vertex(Index(v))] = soup.corner_tags[source(v)];
    }
    if (soup.sharp_edges.empty()) return;
    auto key = [](std::size_t a, std::size_t b) {
        return a < b ? (std::uint64_t(a) << 32) | b : (std::uint64_t(b) << 32) | a;
    };
    // Sorted (key, entry) pairs; the last entry of equal keys wins.
    std::vector<std::pair<std::uint64_t, Index>> listed;
    listed.reserve(soup.sharp_edges.size());
    for (std::size_t i = 0; i < soup.sharp_edges.size(); ++i)
        listed.emplace_back(key(soup.sharp_edges[i].a, soup.sharp_edges[i].b), Index(i));
    std::sort(listed.begin(), listed.end());
    std::vector<std::uint8_t> used(listed.size(), 0);
    auto sharp = sharpness_property(mesh);
    for (Edge e : mesh.edges()) {
        const std::uint64_t k = key(source(mesh.to_vertex(mesh.halfedge(e, 0)).idx()),
                                    source(mesh.to_vertex(mesh.halfedge(e, 1)).idx()));
        auto it = std::upper_bound(listed.begin(), listed.end(),
                                   std::make_pair(k, std::numeric_limits<Index>::max()));
        if (it == listed.begin() || (it - 1)->first != k) continue;
        --it;
        sharp[e] = soup.sharp_edges[it->second].sharpness;
        used[std::size_t(it - listed.begin())] = 1;
    }
    std::size_t unmatched = 0;
    for (std::size_t i = 0; i < listed.size(); ++i)
        if (!used[i] && (i + 1 == listed.size() || listed[i + 1].first != listed[i].first))
            ++unmatched;
    if (unmatched > 0)
        report.notes.push_back(count_text(unmatched, "sharp edge joins", "sharp edges join") +
                               " two vertices that no edge of the mesh joins (dropped)");
}

/// Stage 5b: the soup's attributes onto the mesh: per vertex from each vertex's source
/// (copy_source for the copies), per corner from each face's triangle.
void copy_attributes(const PolygonSoup& soup, std::size_t n_input_vertices, const Triangles& tris,
                     const std::vector<Index>& copy_source, const std::vector<Index>& face_tri,
                     HalfedgeMesh& mesh, LoadReport& report) {
    const std::size_t n_v = mesh.vertices_size();
    auto source = [&](std::size_t v) {
        return v < n_input_vertices ? v : std::size_t(copy_source[v - n_input_vertices]);
    };
    if (!soup.normals.empty()) {
        auto p = mesh.vertex_property<Vector3>("v:normal");
        for (std::size_t v = 0; v < n_v; ++v) p[Vertex(Index(v))] = soup.normals[source(v)];
    }
    if (!soup.colors.empty()) {
        auto p = mesh.vertex_property<Color>("v:color");
        for (std::size_t v = 0; v < n_v; ++v) p[Vertex(Index(v))] = soup.colors[source(v)];
    }
    if (!soup.distances.empty()) {
        auto p = mesh.vertex_property<double>("v:distance");
        for (std::size_t v = 0; v < n_v; ++v) p[Vertex(Index(v))] = soup.distances[source(v)];
    }
    if (!soup.selections.empty()) {
        auto p = mesh.vertex_property<float>("v:selection");
        for (std::size_t v = 0; v < n_v; ++v) p[Vertex(Index(v))] = soup.selections[source(v)];
    }
    if (!soup.texcoords.empty()) {
        auto p = mesh.vertex_property<TexCoord>("v:texcoord");
        for (std::size_t v = 0; v < n_v; ++v) p[Vertex(Index(v))] = soup.texcoords[source(v)];
    }
    copy_features(soup, source, mesh, report);
    if (!soup.corner_texcoords.empty()) {
        const Index* tri_corner = tris.clean ? nullptr : tris.own_tri_corner.data();
        auto p = mesh.halfedge_property<TexCoord>("h:texcoord", TexCoord::Zero());
        const Index n_f = Index(mesh.faces_size());
        for (Index f = 0; f < n_f; ++f) {
            // The face's halfedge ends at corner 0; its next ends at corner 1, and so on.
            Halfedge h = mesh.halfedge(Face(f));
            const std::size_t c0 = 3 * std::size_t(face_tri[f]);
            for (std::size_t k = 0; k < 3; ++k, h = mesh.next(h))
                p[h] = soup.corner_texcoords[tri_corner ? tri_corner[c0 + k] : c0 + k];
        }
    }
}

/// build_mesh for a soup read through `soup`; when `owned` (the same soup) is given, its
/// arrays are released or moved as soon as they are no longer needed.
HalfedgeMesh build_from_soup(const PolygonSoup& soup, PolygonSoup* owned, LoadReport& report) {
    check_polygon_soup(soup);

    const std::size_t n_input_vertices = soup.positions.size();
    const bool keep_corners = !soup.corner_texcoords.empty();
    Triangles tris;
    make_triangles(soup, keep_corners, report, tris);
    if (owned) std::vector<std::size_t>().swap(owned->face_offsets);  // no longer read

    Connectivity c;
    // Once the fast path has read the triangles for the last time, a consumed soup's own
    // corner list (the triangles, when clean) is released: nothing after reads it.
    const std::function<void()> release_triangles = [&] {
        if (owned && tris.clean) std::vector<Index>().swap(owned->corners);
    };
    if (!connect_manifold_triangles(tris, n_input_vertices, keep_corners, release_triangles, c)) {
        EdgeGroups groups;
        bucket_corner_edges(tris.tri, tris.n_corners, n_input_vertices, groups);
        link_groups(n_input_vertices, groups);
        accept_triangles(tris, keep_corners, groups, c);
    }

    const bool parallel = worth_two_threads(c.n_h) && detail::build_threads() >= 2;
    std::vector<ExtraFan> extra_fans = find_fans(c, n_input_vertices, parallel);

    copy_extra_fans(extra_fans, n_input_vertices, c, report);
    add_detached_triangles(tris.tri, n_input_vertices, keep_corners, c, report);

    HalfedgeMesh mesh = assemble_mesh(soup, owned, c, report);
    copy_attributes(soup, n_input_vertices, tris, c.copy_source, c.face_tri, mesh, report);

    if (owned) {
        owned->face_offsets.assign(1, 0);  // an empty soup's offsets
        owned->corners.clear();
    }
    return mesh;
}

}  // namespace

HalfedgeMesh build_mesh(const PolygonSoup& soup, LoadReport& report) {
    return build_from_soup(soup, nullptr, report);
}

HalfedgeMesh build_mesh(PolygonSoup&& soup, LoadReport& report) {
    return build_from_soup(soup, &soup, report);
}

namespace detail {
namespace {
std::atomic<int> g_build_threads{2};
}  // namespace
void set_build_threads(int n) {
    g_build_threads.store(n < 2 ? 1 : 2);
}
int build_threads() {
    return g_build_threads.load();
}
}  // namespace detail

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
    auto distances = mesh.get_vertex_property<double>("v:distance");
    auto selections = mesh.get_vertex_property<float>("v:selection");
    auto corner_uv = mesh.get_halfedge_property<TexCoord>("h:texcoord");
    const auto corner_tags = mesh.get_vertex_property<std::uint8_t>(kCornerProperty);
    const auto sharpness = mesh.get_edge_property<float>(kSharpnessProperty);
    if (sharpness)
        for (Edge e : mesh.edges())
            if (sharpness[e] > 0.0f)
                soup.sharp_edges.push_back({index[mesh.to_vertex(mesh.halfedge(e, 1)).idx()],
                                            index[mesh.to_vertex(mesh.halfedge(e, 0)).idx()],
                                            sharpness[e]});
    if (corner_tags)
        for (Vertex v : mesh.vertices()) soup.corner_tags.push_back(corner_tags[v]);
    for (Vertex v : mesh.vertices()) {
        if (normals) soup.normals.push_back(normals[v]);
        if (colors) soup.colors.push_back(colors[v]);
        if (texcoords) soup.texcoords.push_back(texcoords[v]);
        if (distances) soup.distances.push_back(distances[v]);
        if (selections) soup.selections.push_back(selections[v]);
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
