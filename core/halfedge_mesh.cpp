#include "core/halfedge_mesh.h"

#include <algorithm>
#include <exception>
#include <iterator>
#include <string>
#include <thread>
#include <utility>

#include "core/errors.h"
#include "core/parallel.h"
#include "core/two_threads.h"

namespace trilab {

namespace {
// From this many halfedges on, apply_order() works on two threads.
constexpr std::size_t kParallelOrderMin = 200000;
// Built-in arrays: part of the connectivity, never removable by users.
const char* const kBuiltinNames[] = {"v:position", "v:halfedge", "v:deleted", "h:to",
                                     "h:next",     "h:prev",     "h:face",    "e:deleted",
                                     "f:halfedge", "f:deleted"};
bool is_builtin(const std::string& name) {
    return std::find(std::begin(kBuiltinNames), std::end(kBuiltinNames), name) !=
           std::end(kBuiltinNames);
}
}  // namespace

HalfedgeMesh::HalfedgeMesh() {
    vprops_.add<Point>("v:position", Point::Zero());
    vprops_.add<Halfedge>("v:halfedge");
    vprops_.add<std::uint8_t>("v:deleted", 0);
    hprops_.add<Vertex>("h:to");
    hprops_.add<Halfedge>("h:next");
    hprops_.add<Halfedge>("h:prev");
    hprops_.add<Face>("h:face");
    eprops_.add<std::uint8_t>("e:deleted", 0);
    fprops_.add<Halfedge>("f:halfedge");
    fprops_.add<std::uint8_t>("f:deleted", 0);
    bind_builtins();
}

HalfedgeMesh::HalfedgeMesh(const HalfedgeMesh& other)
    : vprops_(other.vprops_),
      hprops_(other.hprops_),
      eprops_(other.eprops_),
      fprops_(other.fprops_),
      n_deleted_vertices_(other.n_deleted_vertices_),
      n_deleted_edges_(other.n_deleted_edges_),
      n_deleted_faces_(other.n_deleted_faces_) {
    bind_builtins();
}

HalfedgeMesh& HalfedgeMesh::operator=(const HalfedgeMesh& other) {
    if (this == &other) return *this;
    vprops_ = other.vprops_;
    hprops_ = other.hprops_;
    eprops_ = other.eprops_;
    fprops_ = other.fprops_;
    n_deleted_vertices_ = other.n_deleted_vertices_;
    n_deleted_edges_ = other.n_deleted_edges_;
    n_deleted_faces_ = other.n_deleted_faces_;
    bind_builtins();
    return *this;
}

HalfedgeMesh::HalfedgeMesh(HalfedgeMesh&& other) noexcept
    : vprops_(std::move(other.vprops_)),
      hprops_(std::move(other.hprops_)),
      eprops_(std::move(other.eprops_)),
      fprops_(std::move(other.fprops_)),
      n_deleted_vertices_(other.n_deleted_vertices_),
      n_deleted_edges_(other.n_deleted_edges_),
      n_deleted_faces_(other.n_deleted_faces_) {
    bind_builtins();
    other.clear();
}

HalfedgeMesh& HalfedgeMesh::operator=(HalfedgeMesh&& other) noexcept {
    if (this == &other) return *this;
    vprops_ = std::move(other.vprops_);
    hprops_ = std::move(other.hprops_);
    eprops_ = std::move(other.eprops_);
    fprops_ = std::move(other.fprops_);
    n_deleted_vertices_ = other.n_deleted_vertices_;
    n_deleted_edges_ = other.n_deleted_edges_;
    n_deleted_faces_ = other.n_deleted_faces_;
    bind_builtins();
    other.clear();
    return *this;
}

void HalfedgeMesh::bind_builtins() {
    vpoint_ = VertexProperty<Point>(vprops_.get<Point>("v:position"));
    vhalfedge_ = VertexProperty<Halfedge>(vprops_.get<Halfedge>("v:halfedge"));
    vdeleted_ = VertexProperty<std::uint8_t>(vprops_.get<std::uint8_t>("v:deleted"));
    hto_ = HalfedgeProperty<Vertex>(hprops_.get<Vertex>("h:to"));
    hnext_ = HalfedgeProperty<Halfedge>(hprops_.get<Halfedge>("h:next"));
    hprev_ = HalfedgeProperty<Halfedge>(hprops_.get<Halfedge>("h:prev"));
    hface_ = HalfedgeProperty<Face>(hprops_.get<Face>("h:face"));
    edeleted_ = EdgeProperty<std::uint8_t>(eprops_.get<std::uint8_t>("e:deleted"));
    fhalfedge_ = FaceProperty<Halfedge>(fprops_.get<Halfedge>("f:halfedge"));
    fdeleted_ = FaceProperty<std::uint8_t>(fprops_.get<std::uint8_t>("f:deleted"));
}

void HalfedgeMesh::set_positions(std::vector<Point> positions) {
    if (positions.size() != vertices_size())
        throw InvalidArgument("HalfedgeMesh::set_positions: " + std::to_string(positions.size()) +
                              " positions for a vertex storage size of " +
                              std::to_string(vertices_size()));
    vpoint_.array()->assign(std::move(positions));
}

std::vector<HalfedgeMesh::MemoryBlock> HalfedgeMesh::memory_blocks() const {
    std::vector<MemoryBlock> out;
    for (const PropertyContainer* c : {&vprops_, &hprops_, &eprops_, &fprops_})
        c->for_each_array([&](const std::string&, const void* id, std::size_t bytes) {
            out.push_back({id, bytes});
        });
    return out;
}

std::size_t HalfedgeMesh::share_equal_arrays(const HalfedgeMesh& other) {
    if (vertices_size() != other.vertices_size() || halfedges_size() != other.halfedges_size() ||
        faces_size() != other.faces_size())
        return 0;
    return vprops_.share_equal_arrays(other.vprops_) + hprops_.share_equal_arrays(other.hprops_) +
           eprops_.share_equal_arrays(other.eprops_) + fprops_.share_equal_arrays(other.fprops_);
}

std::uint64_t HalfedgeMesh::topology_revision() const {
    return std::max({vhalfedge_.array()->revision(), vdeleted_.array()->revision(),
                     hto_.array()->revision(), hnext_.array()->revision(),
                     hprev_.array()->revision(), hface_.array()->revision(),
                     edeleted_.array()->revision(), fhalfedge_.array()->revision(),
                     fdeleted_.array()->revision()});
}

std::uint64_t HalfedgeMesh::attribute_revision() const {
    const auto attribute = [](const std::string& name) { return !is_builtin(name); };
    std::uint64_t r = 0;
    for (const PropertyContainer* c : {&vprops_, &hprops_, &eprops_, &fprops_})
        r = std::max({r, c->layout_revision(), c->max_revision(attribute)});
    return r;
}

void HalfedgeMesh::clear() {
    HalfedgeMesh fresh;
    vprops_ = std::move(fresh.vprops_);
    hprops_ = std::move(fresh.hprops_);
    eprops_ = std::move(fresh.eprops_);
    fprops_ = std::move(fresh.fprops_);
    n_deleted_vertices_ = n_deleted_edges_ = n_deleted_faces_ = 0;
    bind_builtins();
}

void HalfedgeMesh::reserve(std::size_t nv, std::size_t ne, std::size_t nf) {
    vprops_.reserve(nv);
    hprops_.reserve(2 * ne);
    eprops_.reserve(ne);
    fprops_.reserve(nf);
}

void HalfedgeMesh::throw_name_taken(const std::string& name) {
    throw InvalidArgument("add property: a property named '" + name + "' exists already");
}

void HalfedgeMesh::checked_remove(PropertyContainer& c, const std::string& name) {
    if (is_builtin(name))
        throw InvalidArgument("remove property: '" + name + "' is part of the connectivity");
    c.remove(name);
}

Halfedge HalfedgeMesh::find_halfedge(Vertex a, Vertex b) const {
    for (Halfedge h : halfedges_around(a))
        if (to_vertex(h) == b) return h;
    return Halfedge();
}

Edge HalfedgeMesh::find_edge(Vertex a, Vertex b) const {
    Halfedge h = find_halfedge(a, b);
    return h.is_valid() ? edge(h) : Edge();
}

bool HalfedgeMesh::is_boundary(Face f) const {
    for (Halfedge h : halfedges_of(f))
        if (is_boundary(twin(h))) return true;
    return false;
}

unsigned HalfedgeMesh::valence(Vertex v) const {
    const auto around = halfedges_around(v);
    return unsigned(std::distance(around.begin(), around.end()));
}

void HalfedgeMesh::resize_elements(std::size_t nv, std::size_t ne, std::size_t nf) {
    if (has_garbage())
        throw TopologyError("resize_elements: collect the garbage first (deleted elements)");
    // Every array of the four containers resized (allocated, filled with its default, its
    // fresh pages faulted in) as one task each, on every thread (core/parallel.h): a 1-to-4
    // subdivision of 1M faces allocates about 300 MB here.
    struct Task {
        PropertyContainer* container;
        std::size_t array, size;
    };
    std::vector<Task> tasks;
    for (auto [container, size] : {std::pair{&hprops_, 2 * ne}, std::pair{&vprops_, nv},
                                   std::pair{&fprops_, nf}, std::pair{&eprops_, ne}})
        for (std::size_t k = 0; k < container->n_properties(); ++k)
            tasks.push_back({container, k, size});
    parallel_for(
        0, tasks.size(),
        [&](std::size_t t) { tasks[t].container->resize_array(tasks[t].array, tasks[t].size); }, 1);
    vprops_.set_size(nv);
    hprops_.set_size(2 * ne);
    eprops_.set_size(ne);
    fprops_.set_size(nf);
}

void HalfedgeMesh::assign_connectivity(std::vector<Point>&& positions,
                                       std::vector<Halfedge>&& vertex_halfedge,
                                       std::vector<Vertex>&& to, std::vector<Halfedge>&& next,
                                       std::vector<Halfedge>&& prev, std::vector<Face>&& face,
                                       std::vector<Halfedge>&& face_halfedge) {
    if (vertices_size() + edges_size() + faces_size() != 0)
        throw InvalidArgument("assign_connectivity: the mesh is not empty");
    const std::size_t nv = positions.size(), nh = to.size(), nf = face_halfedge.size();
    if (vertex_halfedge.size() != nv || nh % 2 != 0 || next.size() != nh || prev.size() != nh ||
        face.size() != nh)
        throw InvalidArgument("assign_connectivity: the array sizes disagree");
    vpoint_.vector().swap(positions);
    vhalfedge_.vector().swap(vertex_halfedge);
    hto_.vector().swap(to);
    hnext_.vector().swap(next);
    hprev_.vector().swap(prev);
    hface_.vector().swap(face);
    fhalfedge_.vector().swap(face_halfedge);
    // The other arrays (deleted flags) grow to the new sizes; the swapped ones have them.
    vprops_.resize(nv);
    hprops_.resize(nh);
    eprops_.resize(nh / 2);
    fprops_.resize(nf);
}

Vertex HalfedgeMesh::add_vertex(const Point& p) {
    vprops_.push_back();
    Vertex v(Index(vprops_.size() - 1));
    vpoint_[v] = p;
    return v;
}

Vertex HalfedgeMesh::add_vertex_copy(Vertex source) {
    vprops_.push_back();
    Vertex v(Index(vprops_.size() - 1));
    vprops_.copy_element(source.idx(), v.idx());
    vhalfedge_[v] = Halfedge();
    vdeleted_[v] = 0;
    return v;
}

Halfedge HalfedgeMesh::new_edge(Vertex a, Vertex b) {
    eprops_.push_back();
    hprops_.push_back();
    hprops_.push_back();
    Halfedge h(Index(hprops_.size() - 2));
    hto_[h] = b;
    hto_[twin(h)] = a;
    return h;
}

Face HalfedgeMesh::new_face() {
    fprops_.push_back();
    return Face(Index(fprops_.size() - 1));
}

void HalfedgeMesh::adjust_outgoing_halfedge(Vertex v) {
    Halfedge start = halfedge(v);
    if (!start.is_valid()) return;
    Halfedge h = start;
    do {
        if (is_boundary(h)) {
            set_halfedge(v, h);
            return;
        }
        h = ccw_rotated(h);
    } while (h != start);
}

void HalfedgeMesh::mark_deleted(Vertex v) {
    if (vdeleted_[v]) return;
    vdeleted_[v] = 1;
    vhalfedge_[v] = Halfedge();
    ++n_deleted_vertices_;
}

void HalfedgeMesh::mark_deleted(Edge e) {
    if (edeleted_[e]) return;
    edeleted_[e] = 1;
    ++n_deleted_edges_;
}

void HalfedgeMesh::mark_deleted(Face f) {
    if (fdeleted_[f]) return;
    fdeleted_[f] = 1;
    ++n_deleted_faces_;
}

IndexRemap HalfedgeMesh::garbage_collection() {
    IndexRemap remap;
    std::vector<Index> v_keep, h_keep, e_keep, f_keep;
    // Old -> new index and the kept elements (new -> old) of one kind, in their order; for the
    // edges also the halfedges' two lists (h_old_to_new, h_new_to_old). One pass writing each
    // array once, front to back, without branches (the deleted elements lie scattered: a branch
    // would mispredict).
    const auto build = [](const std::vector<std::uint8_t>& deleted, std::vector<Index>& old_to_new,
                          std::vector<Index>& new_to_old, std::vector<Index>* h_old_to_new,
                          std::vector<Index>* h_new_to_old) {
        const std::size_t n = deleted.size();
        const std::size_t live = std::size_t(std::count(deleted.begin(), deleted.end(), 0));
        old_to_new.resize(n);
        new_to_old.resize(live + 1);  // the last slot takes the writes of deleted elements
        if (h_old_to_new) {
            h_old_to_new->resize(2 * n);
            h_new_to_old->resize(2 * live + 2);
        }
        Index next = 0;
        for (std::size_t i = 0; i < n; ++i) {
            const bool gone = deleted[i] != 0;
            old_to_new[i] = gone ? kInvalidIndex : next;
            new_to_old[next] = Index(i);
            if (h_old_to_new) {
                (*h_old_to_new)[2 * i] = gone ? kInvalidIndex : 2 * next;
                (*h_old_to_new)[2 * i + 1] = gone ? kInvalidIndex : 2 * next + 1;
                (*h_new_to_old)[2 * next] = Index(2 * i);
                (*h_new_to_old)[2 * next + 1] = Index(2 * i + 1);
            }
            next += gone ? 0 : 1;
        }
        new_to_old.pop_back();
        if (h_new_to_old) h_new_to_old->resize(2 * live);
    };
    // Vertices and faces, edges and halfedges: side by side on big meshes.
    on_two_threads(worth_two_threads(halfedges_size()), [&](int part) {
        if (part == 0) {
            build(std::as_const(vdeleted_).vector(), remap.vertices, v_keep, nullptr, nullptr);
            build(std::as_const(fdeleted_).vector(), remap.faces, f_keep, nullptr, nullptr);
        } else {
            build(std::as_const(edeleted_).vector(), remap.edges, e_keep, &remap.halfedges,
                  &h_keep);
        }
    });
    apply_order(remap, v_keep, h_keep, e_keep, f_keep);
    return remap;
}

IndexRemap HalfedgeMesh::renumber(const std::vector<Index>& vertex_order,
                                  const std::vector<Index>& halfedge_order,
                                  const std::vector<Index>& face_order) {
    // old -> new, checking that each list holds every live element once.
    // deleted[old >> shift]: halfedges read their edge's flag.
    const auto invert = [](const std::vector<Index>& order, std::size_t storage, std::size_t live,
                           const std::vector<std::uint8_t>& deleted, unsigned shift,
                           const char* what, std::vector<Index>& old_to_new) {
        if (order.size() != live)
            throw InvalidArgument(std::string("HalfedgeMesh::renumber: the ") + what +
                                  " order lists " + std::to_string(order.size()) +
                                  " elements, the mesh has " + std::to_string(live));
        old_to_new.assign(storage, kInvalidIndex);
        for (Index i = 0; i < order.size(); ++i) {
            const Index old = order[i];
            if (old >= storage || deleted[old >> shift] || old_to_new[old] != kInvalidIndex)
                throw InvalidArgument(std::string("HalfedgeMesh::renumber: ") + what + " " +
                                      std::to_string(old) + " (entry " + std::to_string(i) +
                                      ") is out of range, deleted or listed twice");
            old_to_new[old] = i;
        }
    };
    IndexRemap remap;
    std::vector<Index> e_keep;
    // The vertex and face lists here, the halfedge list on a second thread for big meshes; a
    // fault in either list leaves the mesh unchanged, and one in the vertex or face list is the
    // one reported when both have one (the order of the checks on one thread).
    on_two_threads(worth_two_threads(halfedges_size()), [&](int part) {
        if (part == 1) {
            invert(vertex_order, vertices_size(), n_vertices(), std::as_const(vdeleted_).vector(),
                   0, "vertex", remap.vertices);
            invert(face_order, faces_size(), n_faces(), std::as_const(fdeleted_).vector(), 0,
                   "face", remap.faces);
            return;
        }
        invert(halfedge_order, halfedges_size(), n_halfedges(), std::as_const(edeleted_).vector(),
               1, "halfedge", remap.halfedges);
        e_keep.resize(halfedge_order.size() / 2);
        remap.edges.assign(edges_size(), kInvalidIndex);
        for (Index k = 0; k < e_keep.size(); ++k) {
            const Index a = halfedge_order[2 * k], b = halfedge_order[2 * k + 1];
            if ((a ^ 1u) != b)
                throw InvalidArgument("HalfedgeMesh::renumber: halfedges " + std::to_string(a) +
                                      " and " + std::to_string(b) + " (entries " +
                                      std::to_string(2 * k) + ", " + std::to_string(2 * k + 1) +
                                      ") are not the two halves of one edge");
            e_keep[k] = a >> 1;
            remap.edges[a >> 1] = k;
        }
    });
    apply_order(remap, vertex_order, halfedge_order, e_keep, face_order);
    return remap;
}

void HalfedgeMesh::apply_order(IndexRemap& remap, const std::vector<Index>& v_keep,
                               const std::vector<Index>& h_keep, const std::vector<Index>& e_keep,
                               const std::vector<Index>& f_keep) {
    const Index* const new_h = remap.halfedges.data();
    const Index* const new_v = remap.vertices.data();
    const Index* const new_f = remap.faces.data();
    const auto map_h = [new_h](Halfedge h) { return h.is_valid() ? Halfedge(new_h[h.idx()]) : h; };
    const auto map_v = [new_v](Vertex v) { return v.is_valid() ? Vertex(new_v[v.idx()]) : v; };
    const auto map_f = [new_f](Face f) { return f.is_valid() ? Face(new_f[f.idx()]) : f; };
    // The built-in arrays (links and positions) are gathered, and the links renumbered, in one
    // pass each into new arrays, every thread writing its half of each new array; every other
    // array (attributes, deleted flags) is gathered as it is, the halfedges' and edges' on one
    // thread, the vertices' and faces' on the other. Side by side for big meshes where there
    // is a second core (a thread costs more than it saves on small ones); the same result
    // either way.
    const std::vector<Vertex>& to = std::as_const(hto_).vector();
    const std::vector<Halfedge>& next = std::as_const(hnext_).vector();
    const std::vector<Halfedge>& prev = std::as_const(hprev_).vector();
    const std::vector<Face>& face = std::as_const(hface_).vector();
    const std::vector<Halfedge>& vh = std::as_const(vhalfedge_).vector();
    const std::vector<Point>& pos = std::as_const(vpoint_).vector();
    const std::vector<Halfedge>& fh = std::as_const(fhalfedge_).vector();
    std::vector<Vertex> new_to;
    std::vector<Halfedge> new_next, new_prev, new_vh, new_fh;
    std::vector<Face> new_face;
    std::vector<Point> new_pos;
    const bool parallel =
        h_keep.size() >= kParallelOrderMin && unsigned(trilab::thread_count()) >= 2;
    on_two_threads(parallel, [&](int part) {  // the new arrays, zeroed and paged in by halves
        if (part == 0) {
            new_to.resize(h_keep.size());
            new_next.resize(h_keep.size());
            new_vh.resize(v_keep.size());
            new_fh.resize(f_keep.size());
        } else {
            new_prev.resize(h_keep.size());
            new_face.resize(h_keep.size());
            new_pos.resize(v_keep.size());
        }
    });
    // Writes out[i] = map(in[keep[i]]) for i in this part's half of keep.
    const auto half = [](int part, const std::vector<Index>& keep, const auto& in, auto& out,
                         const auto& map) {
        const std::size_t n = keep.size(), begin = part == 0 ? 0 : n / 2,
                          end = part == 0 ? n / 2 : n;
        const Index* from = keep.data();
        const auto* src = in.data();
        auto* dst = out.data();
        for (std::size_t i = begin; i < end; ++i) dst[i] = map(src[from[i]]);
    };
    const auto same = [](const Point& p) -> const Point& { return p; };
    on_two_threads(parallel, [&](int part) {
        half(part, h_keep, next, new_next, map_h);
        half(part, h_keep, prev, new_prev, map_h);
        half(part, h_keep, to, new_to, map_v);
        half(part, h_keep, face, new_face, map_f);
        half(part, v_keep, vh, new_vh, map_h);
        half(part, v_keep, pos, new_pos, same);
        half(part, f_keep, fh, new_fh, map_h);
        // The other arrays; none of them is one of the arrays read above.
        if (part == 0) {
            hprops_.gather_except(h_keep, [&](const BasePropertyArray* a) {
                return a == hnext_.array() || a == hprev_.array() || a == hto_.array() ||
                       a == hface_.array();
            });
            eprops_.gather(e_keep);
        } else {
            vprops_.gather_except(v_keep, [&](const BasePropertyArray* a) {
                return a == vhalfedge_.array() || a == vpoint_.array();
            });
            fprops_.gather_except(
                f_keep, [&](const BasePropertyArray* a) { return a == fhalfedge_.array(); });
        }
    });
    hto_.array()->assign(std::move(new_to));
    hnext_.array()->assign(std::move(new_next));
    hprev_.array()->assign(std::move(new_prev));
    hface_.array()->assign(std::move(new_face));
    vhalfedge_.array()->assign(std::move(new_vh));
    vpoint_.array()->assign(std::move(new_pos));
    fhalfedge_.array()->assign(std::move(new_fh));
    bind_builtins();
    n_deleted_vertices_ = n_deleted_edges_ = n_deleted_faces_ = 0;
    vprops_.shrink_to_fit();
    hprops_.shrink_to_fit();
    eprops_.shrink_to_fit();
    fprops_.shrink_to_fit();
}

}  // namespace trilab
