// Welding coincident vertices (core/algorithms/weld.h): the method in full.
//
// Welding coincident vertices: joins pieces of one surface that a file keeps apart (patch
// seams, the copies build_mesh() makes of a non-manifold vertex), as far as the result stays
// a valid manifold mesh.
//
// Method: vertices are grouped by position (core/algorithms/coincident.h: exact, or within
// `tolerance`). A weld glues pairs of boundary edges: two boundary edges whose ends lie in
// the same two groups, with no other edge between those groups, whose faces run in opposite
// directions along them (consistent orientation), become one interior edge, and their ends
// become one vertex. Joining only through glued edges keeps every vertex manifold: each
// vertex is one fan with two open ends (or none), a glue links two ends, so the fans joined
// into one vertex form a chain or a closed ring. Coincident vertices of a group that no glue
// joins stay apart (surfaces touching at a point would make a non-manifold vertex), and so do
// edges where three or more faces would meet or whose faces run the same way; a glue that
// would still break the mesh (a face with two corners in one vertex, two edges between the
// same two vertices) is undone with the glues at its vertices. Isolated vertices in a group
// join it. Everything left apart is counted and explained in the report.
//
// The joined vertex sits at its group's position (with a tolerance: the mean of the vertices
// joined, in index order) and keeps the per-vertex normal, colour and texture coordinate of
// its lowest-index vertex; per-corner texture coordinates stay with their faces. Other
// properties are not carried. Faces keep their order; vertices are renumbered (the map is
// returned). The input is not modified.
// Throws InvalidArgument for a negative or non-finite tolerance, or one too small for the
// coordinates (core/algorithms/coincident.h). Complexity: O(V + E) expected, plus a few rounds of
// checks when glues are undone.
#include "core/algorithms/weld.h"

#include <algorithm>
#include <cstdint>
#include <utility>

#include "core/algorithms/coincident.h"
#include "core/algorithms/selection.h"
#include "core/errors.h"
#include "core/mesh_builder.h"
#include "core/number_text.h"

namespace trilab {

namespace {

/// An edge with an end in a group, keyed by the (sorted) ids of its ends' groups.
struct KeyedEdge {
    std::uint64_t lo, hi;
    Index edge;
    bool operator<(const KeyedEdge& o) const {
        return lo != o.lo ? lo < o.lo : (hi != o.hi ? hi < o.hi : edge < o.edge);
    }
};

/// Two boundary halfedges (a -> b and b' -> a') to glue into one edge.
struct Glue {
    Halfedge h1, h2;
    bool active = true;
};

class UnionFind {
public:
    explicit UnionFind(std::size_t n) : parent_(n) { reset(); }
    void reset() {
        for (std::size_t i = 0; i < parent_.size(); ++i) parent_[i] = Index(i);
    }
    Index find(Index i) {
        Index r = i;
        while (parent_[r] != r) r = parent_[r];
        while (parent_[i] != r) {
            const Index next = parent_[i];
            parent_[i] = r;
            i = next;
        }
        return r;
    }
    /// The root of a set is its smallest member.
    void unite(Index a, Index b) {
        a = find(a);
        b = find(b);
        if (a != b) parent_[std::max(a, b)] = std::min(a, b);
    }

private:
    std::vector<Index> parent_;
};

// weld_coincident_vertices() in four stages, one method each: the glues (pairs of coincident
// boundary edges), the vertex sets joined through them (undoing glues that would break the
// mesh), the welded mesh, the report.
class Welder {
public:
    Welder(const HalfedgeMesh& mesh, const WeldOptions& options)
        : mesh_(mesh),
          options_(options),
          n_(mesh.vertices_size()),
          groups_(coincident_groups(mesh, options)),
          group_(groups_.group_of(n_)),
          sets_(n_) {}

    void find_glues();
    void join_vertices();
    void build_mesh_into(WeldResult& result);
    void fill_report(WeldResult& result);

private:
    static CoincidentGroups coincident_groups(const HalfedgeMesh& mesh,
                                              const WeldOptions& options) {
        const std::size_t n = mesh.vertices_size();
        std::vector<std::uint8_t> deleted(n, 1);
        for (Vertex v : mesh.vertices())  // outside the region: left out like a deleted one
            if (!options.region || (*options.region)[v.idx()] > 0.0f) deleted[v.idx()] = 0;
        return find_coincident_points(mesh.positions().data(), n, deleted.data(),
                                      options.tolerance);
    }
    /// The id of v's group, or a unique id above the groups' for a vertex in none.
    std::uint64_t key(Vertex v) const {
        const Index g = group_[v.idx()];
        return g != kInvalidIndex ? std::uint64_t(g) : std::uint64_t(groups_.size()) + v.idx();
    }
    Halfedge boundary_half(Edge e) const {
        const Halfedge h = HalfedgeMesh::halfedge(e, 0);
        return mesh_.is_boundary(h) ? h : HalfedgeMesh::twin(h);
    }
    void unite_through_glues(const std::vector<Index>& target);
    bool mark_broken_vertices(std::vector<std::uint8_t>& bad,
                              const std::vector<Index>& glue_of_edge);

    const HalfedgeMesh& mesh_;
    const WeldOptions& options_;
    const std::size_t n_;
    const CoincidentGroups groups_;
    const std::vector<Index> group_;
    std::vector<KeyedEdge> keyed_;
    std::vector<Glue> glues_;
    std::size_t open_many_faces_ = 0, open_orientation_ = 0, undone_ = 0;
    UnionFind sets_;
    std::vector<std::pair<std::pair<Index, Index>, Index>> pairs_;  // root pair, edge
};

// Edges with an end in a group, sorted by their ends' ids: a run of equal ids is a set of
// edges that a weld would make one; a run of two boundary edges running in opposite
// directions is a glue.
void Welder::find_glues() {
    const HalfedgeMesh& mesh = mesh_;
    for (Edge e : mesh.edges()) {
        const Vertex a = mesh.vertex(e, 0), b = mesh.vertex(e, 1);
        if (group_[a.idx()] == kInvalidIndex && group_[b.idx()] == kInvalidIndex) continue;
        const std::uint64_t ka = key(a), kb = key(b);
        keyed_.push_back({std::min(ka, kb), std::max(ka, kb), e.idx()});
    }
    std::sort(keyed_.begin(), keyed_.end());
    const std::vector<KeyedEdge>& keyed = keyed_;
    for (std::size_t i = 0; i < keyed.size();) {
        std::size_t j = i + 1;
        while (j < keyed.size() && keyed[j].lo == keyed[i].lo && keyed[j].hi == keyed[i].hi) ++j;
        const std::size_t run = j - i;
        std::size_t boundary = 0;
        for (std::size_t k = i; k < j; ++k) boundary += mesh.is_boundary(Edge(keyed[k].edge));
        if (keyed[i].lo == keyed[i].hi) {
            // Edges of length zero inside one group: never glued (they would become loops).
        } else if (run == 2 && boundary == 2) {
            const Halfedge h1 = boundary_half(Edge(keyed[i].edge));
            const Halfedge h2 = boundary_half(Edge(keyed[i + 1].edge));
            const bool opposite = key(mesh.from_vertex(h1)) == key(mesh.to_vertex(h2)) &&
                                  key(mesh.to_vertex(h1)) == key(mesh.from_vertex(h2));
            if (opposite && mesh.face(HalfedgeMesh::twin(h1)) != mesh.face(HalfedgeMesh::twin(h2)))
                glues_.push_back({h1, h2, true});
            else
                open_orientation_ += 2;
        } else if (run >= 2) {
            open_many_faces_ += boundary;
        }
        i = j;
    }
}

// The sets of the active glues' ends, with each isolated member of a group joined to
// `target` of its group.
void Welder::unite_through_glues(const std::vector<Index>& target) {
    sets_.reset();
    for (const Glue& gl : glues_) {
        if (!gl.active) continue;
        sets_.unite(mesh_.from_vertex(gl.h1).idx(), mesh_.to_vertex(gl.h2).idx());
        sets_.unite(mesh_.to_vertex(gl.h1).idx(), mesh_.from_vertex(gl.h2).idx());
    }
    for (std::size_t g = 0; g < groups_.size(); ++g)
        for (const Index* m = groups_.begin(g); m != groups_.end(g); ++m)
            if (mesh_.is_isolated(Vertex(*m))) sets_.unite(*m, target[g]);
}

// Marks (in `bad`, by set root) the vertices where the joined mesh would break: a face with
// two corners in one vertex, two edges joining the same two vertices that are not one glued
// pair. True when there is one.
bool Welder::mark_broken_vertices(std::vector<std::uint8_t>& bad,
                                  const std::vector<Index>& glue_of_edge) {
    const HalfedgeMesh& mesh = mesh_;
    std::fill(bad.begin(), bad.end(), 0);
    bool any_bad = false;
    for (Face f : mesh.faces()) {
        const auto c = mesh.face_vertices(f);
        const Index r0 = sets_.find(c[0].idx()), r1 = sets_.find(c[1].idx()),
                    r2 = sets_.find(c[2].idx());
        if (r0 == r1 || r1 == r2 || r0 == r2) {
            bad[r0] = bad[r1] = bad[r2] = 1;
            any_bad = true;
        }
    }
    auto& pairs = pairs_;
    pairs.clear();
    for (const KeyedEdge& k : keyed_) {
        const Edge e(k.edge);
        const Index a = sets_.find(mesh.vertex(e, 0).idx()),
                    b = sets_.find(mesh.vertex(e, 1).idx());
        pairs.push_back({{std::min(a, b), std::max(a, b)}, k.edge});
    }
    std::sort(pairs.begin(), pairs.end());
    for (std::size_t i = 0; i < pairs.size();) {
        std::size_t j = i + 1;
        while (j < pairs.size() && pairs[j].first == pairs[i].first) ++j;
        if (j - i > 1) {
            // Allowed only as one glued pair.
            const Index x = glue_of_edge[pairs[i].second];
            const bool glued = j - i == 2 && x != kInvalidIndex && glues_[x].active &&
                               x == glue_of_edge[pairs[i + 1].second];
            if (!glued) {
                bad[pairs[i].first.first] = bad[pairs[i].first.second] = 1;
                any_bad = true;
            }
        }
        i = j;
    }
    return any_bad;
}

// Join through the glues; undo the glues at vertices where the result would break (a
// face with two corners in one vertex, two edges joining the same two vertices).
void Welder::join_vertices() {
    std::vector<Index> target(groups_.size(), kInvalidIndex);  // where isolated members go
    for (std::size_t g = 0; g < groups_.size(); ++g) {
        target[g] = *groups_.begin(g);
        for (const Index* m = groups_.begin(g); m != groups_.end(g); ++m)
            if (!mesh_.is_isolated(Vertex(*m))) {
                target[g] = *m;
                break;
            }
    }
    std::vector<Index> glue_of_edge(mesh_.edges_size(), kInvalidIndex);
    for (std::size_t g = 0; g < glues_.size(); ++g) {
        glue_of_edge[HalfedgeMesh::edge(glues_[g].h1).idx()] = Index(g);
        glue_of_edge[HalfedgeMesh::edge(glues_[g].h2).idx()] = Index(g);
    }
    std::vector<std::uint8_t> bad(n_, 0);
    for (;;) {
        unite_through_glues(target);
        if (!mark_broken_vertices(bad, glue_of_edge)) break;
        std::size_t undone_now = 0;
        for (Glue& gl : glues_) {
            if (!gl.active) continue;
            const Index r = sets_.find(mesh_.from_vertex(gl.h1).idx());
            const Index s = sets_.find(mesh_.to_vertex(gl.h1).idx());
            if (bad[r] || bad[s]) {
                gl.active = false;
                ++undone_now;
            }
        }
        if (undone_now == 0)  // only isolated vertices were joined: cannot break anything
            throw Error("weld_coincident_vertices: internal error: a check failed without glues");
        undone_ += undone_now;
    }
}

// The welded mesh: one vertex per set, in the order of the sets' smallest members.
void Welder::build_mesh_into(WeldResult& result) {
    const HalfedgeMesh& mesh = mesh_;
    std::vector<Index> new_index(n_, kInvalidIndex);
    PolygonSoup soup;
    const auto normals = mesh.get_vertex_property<Vector3>("v:normal");
    const auto colors = mesh.get_vertex_property<Color>("v:color");
    const auto vuv = mesh.get_vertex_property<TexCoord>("v:texcoord");
    const auto huv = mesh.get_halfedge_property<TexCoord>("h:texcoord");
    std::vector<std::size_t> joined;  // per new vertex: how many vertices it joins
    for (Vertex v : mesh.vertices()) {
        const Index r = sets_.find(v.idx());
        if (r != v.idx()) continue;
        new_index[r] = Index(soup.positions.size());
        soup.positions.push_back(mesh.position(v));
        joined.push_back(0);
        if (normals) soup.normals.push_back(normals[v]);
        if (colors) soup.colors.push_back(colors[v]);
        if (vuv) soup.texcoords.push_back(vuv[v]);
    }
    result.vertex_map.assign(n_, kInvalidIndex);
    if (options_.tolerance > 0)
        std::fill(soup.positions.begin(), soup.positions.end(), Point::Zero());
    for (Vertex v : mesh.vertices()) {
        const Index w = new_index[sets_.find(v.idx())];
        result.vertex_map[v.idx()] = w;
        ++joined[w];
        if (options_.tolerance > 0) soup.positions[w] += mesh.position(v);
    }
    if (options_.tolerance > 0)
        for (std::size_t w = 0; w < soup.positions.size(); ++w)
            soup.positions[w] /= double(joined[w]);
    soup.corners.reserve(3 * mesh.n_faces());
    for (Face f : mesh.faces()) {
        Halfedge h = mesh.halfedge(f);
        for (int k = 0; k < 3; ++k, h = mesh.next(h)) {
            soup.corners.push_back(result.vertex_map[mesh.to_vertex(h).idx()]);
            if (huv) soup.corner_texcoords.push_back(huv[h]);
        }
        soup.face_offsets.push_back(soup.corners.size());
    }
    LoadReport built;
    result.mesh = build_mesh(soup, built);
    if (built.detached_faces || built.nonmanifold_vertices_split || built.degenerate_faces_dropped)
        throw Error("weld_coincident_vertices: internal error: the welded faces are not manifold");
}

// The report: counts, and a note for each reason something was left apart.
void Welder::fill_report(WeldResult& result) {
    WeldReport& report = result.report;
    report.groups = groups_.size();
    report.coincident_vertices = groups_.members.size();
    std::size_t glued = 0;
    for (const Glue& gl : glues_) glued += gl.active;
    report.edges_glued = glued;
    report.vertices_joined = mesh_.n_vertices() - result.mesh.n_vertices();
    for (std::size_t g = 0; g < groups_.size(); ++g) {
        std::vector<Index> roots;
        for (const Index* m = groups_.begin(g); m != groups_.end(g); ++m)
            roots.push_back(sets_.find(*m));
        std::sort(roots.begin(), roots.end());
        report.vertices_left_apart +=
            std::size_t(std::unique(roots.begin(), roots.end()) - roots.begin()) - 1;
    }
    report.edges_left_open = open_many_faces_ + open_orientation_ + 2 * undone_;
    if (open_many_faces_)
        report.notes.push_back(
            count_text(open_many_faces_, "coincident boundary edge", "coincident boundary edges") +
            " left open: three or more faces would meet at the edge");
    if (open_orientation_)
        report.notes.push_back(
            count_text(open_orientation_, "coincident boundary edge", "coincident boundary edges") +
            " left open: the faces on the two sides run the same way along the edge (inconsistent "
            "orientation)");
    if (undone_)
        report.notes.push_back(
            count_text(2 * undone_, "coincident boundary edge", "coincident boundary edges") +
            " left open: gluing would give a face two corners at one vertex or two edges "
            "between the same vertices");
    if (report.vertices_left_apart)
        report.notes.push_back(
            count_text(report.vertices_left_apart, "coincident vertex", "coincident vertices") +
            " left apart: joining would make a non-manifold vertex (surfaces touching at a "
            "point, or along edges that cannot be glued)");
}

}  // namespace

WeldResult weld_coincident_vertices(const HalfedgeMesh& mesh, const WeldOptions& options) {
    if (options.region) check_selection(mesh, *options.region, "weld: region");
    Welder welder(mesh, options);
    welder.find_glues();
    welder.join_vertices();
    WeldResult result;
    welder.build_mesh_into(result);
    welder.fill_report(result);
    return result;
}

}  // namespace trilab
