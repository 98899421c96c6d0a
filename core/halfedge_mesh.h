#pragma once
// HalfedgeMesh: an index-based half-edge data structure for triangle meshes.
//
// Storage is structure-of-arrays: one PropertyContainer per element kind holds the
// connectivity arrays and every named attribute. Halfedges come in pairs: edge e owns
// halfedges 2e and 2e+1, so twin(h) = h ^ 1 and edge(h) = h >> 1 (the OpenMesh/pmp
// numbering, which is also the .om file layout).
//
// Invariants (checked by validate(), core/validate.h):
//  - next/prev are inverse permutations; from_vertex(next(h)) == to_vertex(h).
//  - every face is a loop of exactly three halfedges that all point to that face; face(f)'s
//    halfedge belongs to f. Halfedges without a face form boundary loops.
//  - halfedge(v) is outgoing from v; it is a boundary halfedge when v is on the boundary, and
//    invalid exactly when v is isolated. Every vertex is manifold: rotating around
//    halfedge(v) visits all its outgoing halfedges (one fan).
//  - no edge joins a vertex to itself and no two edges join the same pair of vertices.
//  - live elements never reference deleted ones. Deleted elements stay in storage until
//    garbage_collection(), which compacts and reports the index remapping.
#include <array>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <string>
#include <vector>

#include "core/handles.h"
#include "core/property.h"
#include "core/types.h"

namespace trilab {

template <class H, class T>
using ElementProperty = Property<H, T>;
template <class T>
using VertexProperty = Property<Vertex, T>;
template <class T>
using HalfedgeProperty = Property<Halfedge, T>;
template <class T>
using EdgeProperty = Property<Edge, T>;
template <class T>
using FaceProperty = Property<Face, T>;

/// Iterates over the live (not deleted) elements of one kind. An element i is deleted when
/// deleted[i >> shift] is set (shift 1 for halfedges, whose flags are their edges').
template <class H>
class ElementRange {
public:
    class iterator {
    public:
        using iterator_category = std::input_iterator_tag;  // yields handles by value
        using value_type = H;
        using difference_type = std::ptrdiff_t;
        using pointer = void;
        using reference = H;

        iterator() = default;
        iterator(Index i, Index end, const std::vector<std::uint8_t>* deleted, unsigned shift)
            : i_(i), end_(end), shift_(shift), deleted_(deleted) {
            skip();
        }
        H operator*() const { return H(i_); }
        iterator& operator++() {
            ++i_;
            skip();
            return *this;
        }
        iterator operator++(int) {
            iterator old = *this;
            ++*this;
            return old;
        }
        bool operator!=(const iterator& o) const { return i_ != o.i_; }
        bool operator==(const iterator& o) const { return i_ == o.i_; }

    private:
        void skip() {
            if (!deleted_) return;
            while (i_ < end_ && (*deleted_)[i_ >> shift_]) ++i_;
        }
        Index i_ = 0, end_ = 0;
        unsigned shift_ = 0;
        const std::vector<std::uint8_t>* deleted_ = nullptr;
    };
    ElementRange(Index n, const std::vector<std::uint8_t>* deleted, unsigned shift = 0)
        : n_(n), shift_(shift), deleted_(deleted) {}
    iterator begin() const { return iterator(0, n_, deleted_, shift_); }
    iterator end() const { return iterator(n_, n_, deleted_, shift_); }

private:
    Index n_;
    unsigned shift_;
    const std::vector<std::uint8_t>* deleted_;
};

class HalfedgeMesh;

/// Circulates around a vertex or a face; see HalfedgeMesh::vertices_around() and friends.
template <class Policy>
class Circulator {
public:
    using value_type = typename Policy::value_type;
    class iterator {
    public:
        using iterator_category = std::input_iterator_tag;  // yields handles by value
        using value_type = typename Policy::value_type;
        using difference_type = std::ptrdiff_t;
        using pointer = void;
        using reference = value_type;

        iterator() = default;
        iterator(const HalfedgeMesh* m, Halfedge h, bool at_end)
            : mesh_(m), start_(h), h_(h), at_end_(at_end || !h.is_valid()) {
            if (!at_end_ && Policy::skip(*mesh_, h_)) advance();
        }
        value_type operator*() const { return Policy::deref(*mesh_, h_); }
        iterator& operator++() {
            advance();
            return *this;
        }
        iterator operator++(int) {
            iterator old = *this;
            advance();
            return old;
        }
        bool operator!=(const iterator& o) const { return at_end_ != o.at_end_ || h_ != o.h_; }
        bool operator==(const iterator& o) const { return !(*this != o); }

    private:
        void advance() {
            do {
                h_ = Policy::step(*mesh_, h_);
                if (h_ == start_) {
                    at_end_ = true;
                    h_ = Halfedge();
                    return;
                }
            } while (Policy::skip(*mesh_, h_));
        }
        const HalfedgeMesh* mesh_ = nullptr;
        Halfedge start_, h_;
        bool at_end_ = true;
    };
    Circulator(const HalfedgeMesh* m, Halfedge start) : mesh_(m), start_(start) {}
    iterator begin() const { return iterator(mesh_, start_, false); }
    iterator end() const { return iterator(mesh_, Halfedge(), true); }

private:
    const HalfedgeMesh* mesh_;
    Halfedge start_;
};

/// Index remapping produced by garbage_collection(): old index -> new index, or
/// kInvalidIndex for removed elements.
struct IndexRemap {
    std::vector<Index> vertices, halfedges, edges, faces;
};

class HalfedgeMesh {
public:
    HalfedgeMesh();
    HalfedgeMesh(const HalfedgeMesh& other);
    HalfedgeMesh& operator=(const HalfedgeMesh& other);
    HalfedgeMesh(HalfedgeMesh&& other) noexcept;
    HalfedgeMesh& operator=(HalfedgeMesh&& other) noexcept;
    ~HalfedgeMesh() = default;

    // ---- sizes ---------------------------------------------------------------------------
    /// Live element counts (deleted elements excluded).
    std::size_t n_vertices() const { return vprops_.size() - n_deleted_vertices_; }
    std::size_t n_halfedges() const { return 2 * n_edges(); }
    std::size_t n_edges() const { return eprops_.size() - n_deleted_edges_; }
    std::size_t n_faces() const { return fprops_.size() - n_deleted_faces_; }
    /// Storage sizes (deleted elements included): valid indices are below these.
    std::size_t vertices_size() const { return vprops_.size(); }
    std::size_t halfedges_size() const { return hprops_.size(); }
    std::size_t edges_size() const { return eprops_.size(); }
    std::size_t faces_size() const { return fprops_.size(); }
    bool is_empty() const { return n_vertices() == 0; }
    bool has_garbage() const {
        return n_deleted_vertices_ + n_deleted_edges_ + n_deleted_faces_ > 0;
    }
    void clear();
    void reserve(std::size_t n_vertices, std::size_t n_edges, std::size_t n_faces);

    // ---- element ranges ------------------------------------------------------------------
    ElementRange<Vertex> vertices() const {
        return {Index(vertices_size()), n_deleted_vertices_ ? &vdeleted_.vector() : nullptr};
    }
    ElementRange<Edge> edges() const {
        return {Index(edges_size()), n_deleted_edges_ ? &edeleted_.vector() : nullptr};
    }
    ElementRange<Face> faces() const {
        return {Index(faces_size()), n_deleted_faces_ ? &fdeleted_.vector() : nullptr};
    }
    /// All live halfedges (both halves of each live edge).
    ElementRange<Halfedge> halfedges() const {
        return {Index(halfedges_size()), n_deleted_edges_ ? &edeleted_.vector() : nullptr, 1};
    }

    // ---- handle arithmetic ---------------------------------------------------------------
    static Halfedge twin(Halfedge h) { return Halfedge(h.idx() ^ 1u); }
    static Edge edge(Halfedge h) { return Edge(h.idx() >> 1); }
    static Halfedge halfedge(Edge e, unsigned i) { return Halfedge((e.idx() << 1) | (i & 1u)); }

    // ---- navigation ----------------------------------------------------------------------
    Vertex to_vertex(Halfedge h) const { return hto_[h]; }
    Vertex from_vertex(Halfedge h) const { return hto_[twin(h)]; }
    Halfedge next(Halfedge h) const { return hnext_[h]; }
    Halfedge prev(Halfedge h) const { return hprev_[h]; }
    Face face(Halfedge h) const { return hface_[h]; }
    Halfedge halfedge(Vertex v) const { return vhalfedge_[v]; }
    Halfedge halfedge(Face f) const { return fhalfedge_[f]; }
    Vertex vertex(Edge e, unsigned i) const { return to_vertex(halfedge(e, i)); }
    /// Next outgoing halfedge counter-clockwise around from_vertex(h).
    Halfedge ccw_rotated(Halfedge h) const { return twin(prev(h)); }
    /// Next outgoing halfedge clockwise around from_vertex(h).
    Halfedge cw_rotated(Halfedge h) const { return next(twin(h)); }
    /// The halfedge from a to b, or an invalid handle.
    Halfedge find_halfedge(Vertex a, Vertex b) const;
    Edge find_edge(Vertex a, Vertex b) const;

    // ---- queries -------------------------------------------------------------------------
    bool is_boundary(Halfedge h) const { return !face(h).is_valid(); }
    bool is_boundary(Edge e) const {
        return is_boundary(halfedge(e, 0)) || is_boundary(halfedge(e, 1));
    }
    /// A vertex is on the boundary when it is isolated or has a boundary outgoing halfedge.
    bool is_boundary(Vertex v) const {
        Halfedge h = halfedge(v);
        return !h.is_valid() || is_boundary(h);
    }
    /// A face is on the boundary when one of its edges is.
    bool is_boundary(Face f) const;
    bool is_isolated(Vertex v) const { return !halfedge(v).is_valid(); }
    bool is_deleted(Vertex v) const { return vdeleted_[v] != 0; }
    bool is_deleted(Edge e) const { return edeleted_[e] != 0; }
    bool is_deleted(Halfedge h) const { return edeleted_[edge(h)] != 0; }
    bool is_deleted(Face f) const { return fdeleted_[f] != 0; }
    bool is_valid(Vertex v) const { return v.idx() < vertices_size(); }
    bool is_valid(Halfedge h) const { return h.idx() < halfedges_size(); }
    bool is_valid(Edge e) const { return e.idx() < edges_size(); }
    bool is_valid(Face f) const { return f.idx() < faces_size(); }
    /// Number of edges at v.
    unsigned valence(Vertex v) const;

    // ---- circulators ---------------------------------------------------------------------
    struct VertexVertexPolicy;
    struct VertexHalfedgePolicy;
    struct VertexFacePolicy;
    struct FaceVertexPolicy;
    struct FaceHalfedgePolicy;
    /// Neighbours of v, counter-clockwise.
    Circulator<VertexVertexPolicy> vertices_around(Vertex v) const;
    /// Outgoing halfedges of v, counter-clockwise.
    Circulator<VertexHalfedgePolicy> halfedges_around(Vertex v) const;
    /// Faces incident to v, counter-clockwise.
    Circulator<VertexFacePolicy> faces_around(Vertex v) const;
    /// The three corners of f in order.
    Circulator<FaceVertexPolicy> vertices_of(Face f) const;
    /// The three halfedges of f in order.
    Circulator<FaceHalfedgePolicy> halfedges_of(Face f) const;
    /// The three corners of f, starting at to_vertex(halfedge(f)).
    std::array<Vertex, 3> face_vertices(Face f) const;

    // ---- positions -----------------------------------------------------------------------
    const Point& position(Vertex v) const { return vpoint_[v]; }
    Point& position(Vertex v) { return vpoint_[v]; }
    std::vector<Point>& positions() { return vpoint_.vector(); }
    const std::vector<Point>& positions() const { return vpoint_.vector(); }
    /// Replaces every position (one per vertex storage slot) without copying the old ones.
    /// Throws InvalidArgument for another count.
    void set_positions(std::vector<Point> positions);

    // ---- connectivity arrays -------------------------------------------------------------
    // The built-in arrays behind navigation, indexed by element index, for passes over every
    // element (to_vertex(h) is halfedge_to_array()[h.idx()], and so on). The const overloads
    // read; the mutable ones are write accesses (a shared array is copied first, see
    // core/property.h) for bulk construction, whose callers keep the invariants.
    const std::vector<Vertex>& halfedge_to_array() const { return hto_.vector(); }
    const std::vector<Halfedge>& halfedge_next_array() const { return hnext_.vector(); }
    const std::vector<Halfedge>& halfedge_prev_array() const { return hprev_.vector(); }
    const std::vector<Face>& halfedge_face_array() const { return hface_.vector(); }
    const std::vector<Halfedge>& vertex_halfedge_array() const { return vhalfedge_.vector(); }
    const std::vector<Halfedge>& face_halfedge_array() const { return fhalfedge_.vector(); }
    std::vector<Vertex>& halfedge_to_array() { return hto_.vector(); }
    std::vector<Halfedge>& halfedge_next_array() { return hnext_.vector(); }
    std::vector<Halfedge>& halfedge_prev_array() { return hprev_.vector(); }
    std::vector<Face>& halfedge_face_array() { return hface_.vector(); }
    std::vector<Halfedge>& vertex_halfedge_array() { return vhalfedge_.vector(); }
    std::vector<Halfedge>& face_halfedge_array() { return fhalfedge_.vector(); }

    // ---- revisions (see core/property.h) --------------------------------------------------
    /// What a cache or a GPU copy of the mesh was made from. Each number changes whenever its
    /// part may have changed (any write access), and copies share it while they share that
    /// part, so equal numbers mean equal contents within this process; 0 is never a revision.
    struct Revision {
        std::uint64_t topology = 0;    ///< connectivity, including which elements are deleted
        std::uint64_t geometry = 0;    ///< vertex positions
        std::uint64_t attributes = 0;  ///< every other property, and which properties exist
        bool operator==(const Revision& o) const {
            return topology == o.topology && geometry == o.geometry && attributes == o.attributes;
        }
        bool operator!=(const Revision& o) const { return !(*this == o); }
    };
    Revision revision() const {
        return {topology_revision(), geometry_revision(), attribute_revision()};
    }
    std::uint64_t topology_revision() const;
    std::uint64_t geometry_revision() const { return vpoint_.array()->revision(); }
    std::uint64_t attribute_revision() const;

    // ---- sharing (copy-on-write, see core/property.h) -------------------------------------
    /// One block of stored values: its identity (equal for meshes sharing it) and bytes.
    struct MemoryBlock {
        const void* id;
        std::size_t bytes;
    };
    /// Every array's values (connectivity, positions, attributes).
    std::vector<MemoryBlock> memory_blocks() const;
    /// Shares `other`'s arrays wherever an array of the same name holds equal values bit for
    /// bit; returns how many arrays are shared with it now. Nothing visible changes.
    std::size_t share_equal_arrays(const HalfedgeMesh& other);

    // ---- attributes ----------------------------------------------------------------------
    // Names follow "v:name", "h:name", "e:name", "f:name". Built-in connectivity names cannot
    // be removed. add_* throws InvalidArgument if the name is taken; get_* returns an empty
    // view if no property of that name and type exists; *_or_add returns existing or new.
    template <class T>
    VertexProperty<T> add_vertex_property(const std::string& name, T def = zero_value<T>()) {
        return VertexProperty<T>(checked_add(vprops_, name, std::move(def)));
    }
    template <class T>
    VertexProperty<T> get_vertex_property(const std::string& name) {
        return VertexProperty<T>(vprops_.get<T>(name));
    }
    template <class T>
    VertexProperty<const T> get_vertex_property(const std::string& name) const {
        return VertexProperty<const T>(vprops_.get<T>(name));
    }
    template <class T>
    VertexProperty<T> vertex_property(const std::string& name, T def = zero_value<T>()) {
        auto* a = vprops_.get<T>(name);
        return VertexProperty<T>(a ? a : checked_add(vprops_, name, std::move(def)));
    }
    template <class T>
    HalfedgeProperty<T> add_halfedge_property(const std::string& name, T def = zero_value<T>()) {
        return HalfedgeProperty<T>(checked_add(hprops_, name, std::move(def)));
    }
    template <class T>
    HalfedgeProperty<T> get_halfedge_property(const std::string& name) {
        return HalfedgeProperty<T>(hprops_.get<T>(name));
    }
    template <class T>
    HalfedgeProperty<const T> get_halfedge_property(const std::string& name) const {
        return HalfedgeProperty<const T>(hprops_.get<T>(name));
    }
    template <class T>
    HalfedgeProperty<T> halfedge_property(const std::string& name, T def = zero_value<T>()) {
        auto* a = hprops_.get<T>(name);
        return HalfedgeProperty<T>(a ? a : checked_add(hprops_, name, std::move(def)));
    }
    template <class T>
    EdgeProperty<T> add_edge_property(const std::string& name, T def = zero_value<T>()) {
        return EdgeProperty<T>(checked_add(eprops_, name, std::move(def)));
    }
    template <class T>
    EdgeProperty<T> get_edge_property(const std::string& name) {
        return EdgeProperty<T>(eprops_.get<T>(name));
    }
    template <class T>
    EdgeProperty<const T> get_edge_property(const std::string& name) const {
        return EdgeProperty<const T>(eprops_.get<T>(name));
    }
    template <class T>
    EdgeProperty<T> edge_property(const std::string& name, T def = zero_value<T>()) {
        auto* a = eprops_.get<T>(name);
        return EdgeProperty<T>(a ? a : checked_add(eprops_, name, std::move(def)));
    }
    template <class T>
    FaceProperty<T> add_face_property(const std::string& name, T def = zero_value<T>()) {
        return FaceProperty<T>(checked_add(fprops_, name, std::move(def)));
    }
    template <class T>
    FaceProperty<T> get_face_property(const std::string& name) {
        return FaceProperty<T>(fprops_.get<T>(name));
    }
    template <class T>
    FaceProperty<const T> get_face_property(const std::string& name) const {
        return FaceProperty<const T>(fprops_.get<T>(name));
    }
    template <class T>
    FaceProperty<T> face_property(const std::string& name, T def = zero_value<T>()) {
        auto* a = fprops_.get<T>(name);
        return FaceProperty<T>(a ? a : checked_add(fprops_, name, std::move(def)));
    }
    bool has_vertex_property(const std::string& name) const { return vprops_.exists(name); }
    bool has_halfedge_property(const std::string& name) const { return hprops_.exists(name); }
    bool has_edge_property(const std::string& name) const { return eprops_.exists(name); }
    bool has_face_property(const std::string& name) const { return fprops_.exists(name); }
    void remove_vertex_property(const std::string& name) { checked_remove(vprops_, name); }
    void remove_halfedge_property(const std::string& name) { checked_remove(hprops_, name); }
    void remove_edge_property(const std::string& name) { checked_remove(eprops_, name); }
    void remove_face_property(const std::string& name) { checked_remove(fprops_, name); }
    std::vector<std::string> vertex_property_names() const { return vprops_.names(); }
    std::vector<std::string> halfedge_property_names() const { return hprops_.names(); }
    std::vector<std::string> edge_property_names() const { return eprops_.names(); }
    std::vector<std::string> face_property_names() const { return fprops_.names(); }

    // ---- low-level construction (callers keep the invariants; validate() checks) ---------
    /// Resizes storage to exactly these element counts; new elements have invalid
    /// connectivity and zero/default attributes (bulk construction, e.g. by build_mesh).
    void resize_elements(std::size_t n_vertices, std::size_t n_edges, std::size_t n_faces);
    /// Bulk construction without copies (build_mesh): an empty mesh takes these arrays by
    /// move and becomes exactly their elements (n_v = positions.size(), n_e = to.size() / 2,
    /// n_f = face_halfedge.size()); nothing is deleted. Throws InvalidArgument when the mesh
    /// is not empty or the sizes disagree.
    void assign_connectivity(std::vector<Point>&& positions,
                             std::vector<Halfedge>&& vertex_halfedge, std::vector<Vertex>&& to,
                             std::vector<Halfedge>&& next, std::vector<Halfedge>&& prev,
                             std::vector<Face>&& face, std::vector<Halfedge>&& face_halfedge);
    Vertex add_vertex(const Point& p);
    /// A new vertex with all attributes of `source` (used to split non-manifold vertices).
    Vertex add_vertex_copy(Vertex source);
    /// A new edge from a to b; returns the halfedge a -> b (its twin is b -> a). Faces,
    /// next/prev and vertex halfedges are left for the caller to set.
    Halfedge new_edge(Vertex a, Vertex b);
    Face new_face();
    void set_next(Halfedge h, Halfedge n) {
        hnext_[h] = n;
        hprev_[n] = h;
    }
    void set_to_vertex(Halfedge h, Vertex v) { hto_[h] = v; }
    void set_face(Halfedge h, Face f) { hface_[h] = f; }
    void set_halfedge(Vertex v, Halfedge h) { vhalfedge_[v] = h; }
    void set_halfedge(Face f, Halfedge h) { fhalfedge_[f] = h; }
    /// Makes halfedge(v) a boundary halfedge if v has one (restores the invariant).
    void adjust_outgoing_halfedge(Vertex v);

    // ---- topological operators (core/topology.cpp) ---------------------------------------
    /// Whether collapsing h (from_vertex(h) moves into to_vertex(h)) keeps a valid manifold
    /// mesh: the link condition of Dey et al. 1999 / Hoppe et al. 1993. Geometry (fold-overs)
    /// is the caller's concern.
    bool is_collapse_ok(Halfedge h) const;
    /// Collapses h: from_vertex(h) is removed, to_vertex(h) is kept at its position. The one
    /// or two faces at the edge disappear. Throws TopologyError if !is_collapse_ok(h).
    void collapse(Halfedge h);
    /// collapse() without the check, for callers that have just called is_collapse_ok(h)
    /// (decimation); on a halfedge that fails it the mesh is left invalid.
    void collapse_unchecked(Halfedge h);
    /// Whether flipping e keeps a valid mesh: interior edge, and the two opposite corners are
    /// distinct and not already joined by an edge.
    bool is_flip_ok(Edge e) const;
    /// Replaces e by the other diagonal of its two triangles. Throws TopologyError if
    /// !is_flip_ok(e).
    void flip(Edge e);
    /// Splits e at p: a new vertex on the edge, each adjacent face split in two. Always
    /// legal on a live edge. Returns the new vertex; halfedge(e, 0) still ends at it.
    Vertex split(Edge e, const Point& p);
    /// Splits f 1-to-3 at p (a new vertex joined to its three corners). Returns the vertex.
    Vertex split(Face f, const Point& p);
    /// Reverses the orientation of every face (core/algorithms/orientation.h flip_orientation()
    /// adds the attribute semantics): each halfedge moves to the other side of its edge, so face f
    /// keeps its three vertices in the opposite order; vertex, edge and face indices and all
    /// their attributes are kept. Halfedge attributes follow their corner: the value of the
    /// corner at (vertex v, face f) stays at that corner (per-corner "h:texcoord"). Boundary
    /// loops are reversed too; halfedge(v) stays a boundary halfedge at boundary vertices.
    /// In place, edge by edge (no copy of the connectivity; a copy of a halfedge attribute
    /// only when there is one). O(vertices + halfedges); keeps every invariant.
    void reverse_orientation();
    /// The same for the edges with edge_mask[e] != 0 only (one per edge storage index), which
    /// must be whole connected components (every edge of a face or boundary loop that one of
    /// them borders): the rest of the mesh is untouched. Throws InvalidArgument for a mask of
    /// the wrong size.
    void reverse_orientation(const std::vector<std::uint8_t>& edge_mask);
    /// What reverse_orientation_from() reversed.
    struct ReversedPart {
        std::size_t components = 0;    ///< connected components reversed
        std::size_t faces = 0;         ///< their faces
        std::vector<Vertex> vertices;  ///< their vertices (with list_vertices), each once
    };
    /// The same for the connected components that hold one of the seed vertices, found while
    /// they are reversed: one breadth-first flood over their edges, each edge reached from the
    /// faces and boundary loops it borders and rewritten as it is taken; the rest of the mesh
    /// is untouched. Isolated and deleted seeds are skipped. Lists the components' vertices
    /// when list_vertices (for a caller with per-vertex data to follow, e.g. normals). The
    /// result is bit for bit what reverse_orientation(edge_mask) gives with those components'
    /// edges masked. Throws InvalidArgument for a seed out of range (the mesh is then
    /// unchanged). O(their halfedges) for the flood, plus one pass over the vertex and face
    /// halfedges (O(halfedges) with halfedge attributes): a small component costs less than
    /// the whole mesh's reversal.
    ReversedPart reverse_orientation_from(const std::vector<Vertex>& seeds,
                                          bool list_vertices = true);
    /// Compacts storage, removing deleted elements. Returns the index remapping.
    IndexRemap garbage_collection();
    /// Compacts storage into a given order: new vertex i is old vertex vertex_order[i], new face
    /// i old face face_order[i], new halfedges 2k and 2k + 1 old halfedges halfedge_order[2k]
    /// and halfedge_order[2k + 1], which must be the two halves of one edge (in either order:
    /// an edge may turn around). Each list holds every live element exactly once; deleted ones
    /// are dropped, as by garbage_collection(). halfedge(v) and halfedge(f) stay the same
    /// halfedges (renumbered); every attribute moves with its element. Throws InvalidArgument
    /// naming the list and the element when a list is not such a permutation (the mesh is then
    /// unchanged). Returns the remapping (old index -> new index). O(V + H + F).
    IndexRemap renumber(const std::vector<Index>& vertex_order,
                        const std::vector<Index>& halfedge_order,
                        const std::vector<Index>& face_order);

private:
    template <class T>
    PropertyArray<T>* checked_add(PropertyContainer& c, const std::string& name, T def) {
        PropertyArray<T>* a = c.add<T>(name, std::move(def));
        if (!a) throw_name_taken(name);
        return a;
    }
    [[noreturn]] static void throw_name_taken(const std::string& name);
    void checked_remove(PropertyContainer& c, const std::string& name);
    void bind_builtins();
    /// Gathers every element kind into the given orders (renumber() without its checks).
    void apply_order(IndexRemap& remap, const std::vector<Index>& v_keep,
                     const std::vector<Index>& h_keep, const std::vector<Index>& e_keep,
                     const std::vector<Index>& f_keep);
    /// reverse_orientation() of every live edge, or of those with (*edge_mask)[e] != 0.
    void reverse_edges(const std::vector<std::uint8_t>* edge_mask);
    /// After the edges e with reversed(e) (live edges only) were rewritten reversed: sets their
    /// vertices' and faces' halfedges and moves the halfedge attributes with their corners.
    /// Appends those vertices to *listed when given; returns the number of faces reversed.
    /// Defined in topology.cpp, its only user.
    template <class Reversed>
    std::size_t finish_reversal(Reversed reversed, std::vector<Vertex>* listed);
    void mark_deleted(Vertex v);
    void mark_deleted(Edge e);
    void mark_deleted(Face f);
    void remove_loop(Halfedge h);

    PropertyContainer vprops_, hprops_, eprops_, fprops_;
    VertexProperty<Point> vpoint_;
    VertexProperty<Halfedge> vhalfedge_;
    HalfedgeProperty<Vertex> hto_;
    HalfedgeProperty<Halfedge> hnext_, hprev_;
    HalfedgeProperty<Face> hface_;
    FaceProperty<Halfedge> fhalfedge_;
    VertexProperty<std::uint8_t> vdeleted_;
    EdgeProperty<std::uint8_t> edeleted_;
    FaceProperty<std::uint8_t> fdeleted_;
    Index n_deleted_vertices_ = 0, n_deleted_edges_ = 0, n_deleted_faces_ = 0;
};

// ---- circulator policies ----------------------------------------------------------------
struct HalfedgeMesh::VertexHalfedgePolicy {
    using value_type = Halfedge;
    static Halfedge step(const HalfedgeMesh& m, Halfedge h) { return m.ccw_rotated(h); }
    static bool skip(const HalfedgeMesh&, Halfedge) { return false; }
    static Halfedge deref(const HalfedgeMesh&, Halfedge h) { return h; }
};
struct HalfedgeMesh::VertexVertexPolicy : VertexHalfedgePolicy {
    using value_type = Vertex;
    static Vertex deref(const HalfedgeMesh& m, Halfedge h) { return m.to_vertex(h); }
};
struct HalfedgeMesh::VertexFacePolicy : VertexHalfedgePolicy {
    using value_type = Face;
    static bool skip(const HalfedgeMesh& m, Halfedge h) { return m.is_boundary(h); }
    static Face deref(const HalfedgeMesh& m, Halfedge h) { return m.face(h); }
};
struct HalfedgeMesh::FaceHalfedgePolicy {
    using value_type = Halfedge;
    static Halfedge step(const HalfedgeMesh& m, Halfedge h) { return m.next(h); }
    static bool skip(const HalfedgeMesh&, Halfedge) { return false; }
    static Halfedge deref(const HalfedgeMesh&, Halfedge h) { return h; }
};
struct HalfedgeMesh::FaceVertexPolicy : FaceHalfedgePolicy {
    using value_type = Vertex;
    static Vertex deref(const HalfedgeMesh& m, Halfedge h) { return m.to_vertex(h); }
};

inline Circulator<HalfedgeMesh::VertexVertexPolicy> HalfedgeMesh::vertices_around(Vertex v) const {
    return {this, halfedge(v)};
}
inline Circulator<HalfedgeMesh::VertexHalfedgePolicy> HalfedgeMesh::halfedges_around(
    Vertex v) const {
    return {this, halfedge(v)};
}
inline Circulator<HalfedgeMesh::VertexFacePolicy> HalfedgeMesh::faces_around(Vertex v) const {
    return {this, halfedge(v)};
}
inline Circulator<HalfedgeMesh::FaceVertexPolicy> HalfedgeMesh::vertices_of(Face f) const {
    return {this, halfedge(f)};
}
inline Circulator<HalfedgeMesh::FaceHalfedgePolicy> HalfedgeMesh::halfedges_of(Face f) const {
    return {this, halfedge(f)};
}
inline std::array<Vertex, 3> HalfedgeMesh::face_vertices(Face f) const {
    Halfedge h = halfedge(f);
    Halfedge n = next(h);
    return {to_vertex(h), to_vertex(n), to_vertex(next(n))};
}

}  // namespace trilab
