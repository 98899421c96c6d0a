// Connected components and removing the small ones (core/algorithms/components.h).
//
// Labelling reuses label_components() (union-find over the edges): since every vertex is one
// fan, the faces around it are joined through edges, so vertex components through edges and
// face components through edges are the same sets. Removing whole components never cuts an
// edge or a fan, so the kept elements are copied with their connectivity as it is, only
// renumbered: no rebuild from a polygon soup, no new splits or detachments.
#include "core/algorithms/components.h"

#include <cmath>
#include <string>
#include <utility>

#include "core/algorithms/mesh_stats.h"
#include "core/errors.h"
#include "core/number_text.h"

namespace trilab {

ComponentLabels label_face_components(const HalfedgeMesh& mesh) {
    ComponentLabels out;
    std::vector<Index> label;
    const std::size_t n_labels = label_components(mesh, label);
    // Keep the labels of non-isolated vertices, in the order first met (their smallest
    // vertex), as consecutive component numbers.
    std::vector<Index> component_of_label(n_labels, kInvalidIndex);
    out.of_vertex.assign(mesh.vertices_size(), kInvalidIndex);
    for (Vertex v : mesh.vertices()) {
        if (mesh.is_isolated(v)) {
            ++out.isolated_vertices;
            continue;
        }
        Index& c = component_of_label[label[v.idx()]];
        if (c == kInvalidIndex) {
            c = Index(out.components.size());
            out.components.emplace_back();
        }
        out.of_vertex[v.idx()] = c;
        ComponentStats& s = out.components[c];
        ++s.vertices;
        s.bbox.extend(mesh.position(v));
    }
    out.of_face.assign(mesh.faces_size(), kInvalidIndex);
    for (Face f : mesh.faces()) {
        const Index c = out.of_vertex[mesh.to_vertex(mesh.halfedge(f)).idx()];
        out.of_face[f.idx()] = c;
        ++out.components[c].faces;
    }
    return out;
}

namespace {

void check_options(const RemoveComponentsOptions& options) {
    if (!options.min_faces && !options.min_diameter)
        throw InvalidArgument(
            "remove_small_components: give min_faces and/or min_diameter (neither is set, so "
            "nothing would be removed)");
    // NaN is tested first: an ordered comparison with NaN raises FE_INVALID (the tests run
    // with floating-point traps).
    if (options.min_diameter && (std::isnan(*options.min_diameter) || *options.min_diameter < 0 ||
                                 *options.min_diameter > 1))
        throw InvalidArgument(
            "remove_small_components: min_diameter: expected a fraction of the bounding-box "
            "diagonal in [0, 1], got " +
            number_text(*options.min_diameter));
}

/// The component with the most faces; on a tie the first.
Index largest_component(const std::vector<ComponentStats>& components) {
    Index best = 0;
    for (Index c = 1; c < components.size(); ++c)
        if (components[c].faces > components[best].faces) best = c;
    return best;
}

/// Per component: whether it goes. Fills the report's thresholds and counts of faces and
/// components.
std::vector<std::uint8_t> choose_removed(const HalfedgeMesh& mesh, const ComponentLabels& labels,
                                         const RemoveComponentsOptions& options,
                                         RemoveComponentsReport& report) {
    const std::vector<ComponentStats>& components = labels.components;
    report.components_before = components.size();
    report.mesh_diagonal = bounding_box(mesh).diagonal();
    if (options.min_diameter) report.min_diagonal = *options.min_diameter * report.mesh_diagonal;
    std::vector<std::uint8_t> removed(components.size(), 0);
    for (std::size_t c = 0; c < components.size(); ++c) {
        const bool few_faces = options.min_faces && components[c].faces < *options.min_faces;
        const bool too_small =
            options.min_diameter && components[c].bbox.diagonal() < report.min_diagonal;
        removed[c] = few_faces || too_small;
    }
    if (!components.empty()) {
        const Index largest = largest_component(components);
        report.largest_faces = components[largest].faces;
        report.largest_kept_anyway = removed[largest] != 0;
        removed[largest] = 0;
    }
    for (std::size_t c = 0; c < components.size(); ++c) {
        if (removed[c]) report.faces_removed += components[c].faces;
        if (!removed[c]) ++report.components_after;
    }
    return removed;
}

/// New index of each element kept (kInvalidIndex for the others) and old index of each new
/// one.
struct Renumbering {
    std::vector<Index> new_of_old;
    std::vector<Index> old_of_new;
    void keep(Index old) {
        new_of_old[old] = Index(old_of_new.size());
        old_of_new.push_back(old);
    }
};

/// Which vertices, edges and faces stay, in storage order.
struct Kept {
    Renumbering vertices, edges, faces;
    Halfedge halfedge(Halfedge h) const {
        if (!h.is_valid()) return h;
        return Halfedge(2 * edges.new_of_old[h.idx() >> 1] + (h.idx() & 1));
    }
};

Kept choose_kept(const HalfedgeMesh& mesh, const ComponentLabels& labels,
                 const std::vector<std::uint8_t>& removed) {
    Kept kept;
    kept.vertices.new_of_old.assign(mesh.vertices_size(), kInvalidIndex);
    kept.edges.new_of_old.assign(mesh.edges_size(), kInvalidIndex);
    kept.faces.new_of_old.assign(mesh.faces_size(), kInvalidIndex);
    const auto stays = [&](Vertex v) {
        const Index c = labels.of_vertex[v.idx()];
        return c != kInvalidIndex && !removed[c];
    };
    for (Vertex v : mesh.vertices())
        if (stays(v)) kept.vertices.keep(v.idx());
    for (Edge e : mesh.edges())
        if (stays(mesh.vertex(e, 0))) kept.edges.keep(e.idx());
    for (Face f : mesh.faces())
        if (!removed[labels.of_face[f.idx()]]) kept.faces.keep(f.idx());
    return kept;
}

/// The kept elements with their connectivity, renumbered.
HalfedgeMesh copy_connectivity(const HalfedgeMesh& mesh, const Kept& kept) {
    const std::size_t nv = kept.vertices.old_of_new.size();
    const std::size_t nh = 2 * kept.edges.old_of_new.size();
    const std::size_t nf = kept.faces.old_of_new.size();
    std::vector<Point> positions(nv);
    std::vector<Halfedge> vertex_halfedge(nv), next(nh), prev(nh), face_halfedge(nf);
    std::vector<Vertex> to(nh);
    std::vector<Face> face(nh);
    for (Index i = 0; i < nv; ++i) {
        const Vertex v(kept.vertices.old_of_new[i]);
        positions[i] = mesh.position(v);
        vertex_halfedge[i] = kept.halfedge(mesh.halfedge(v));
    }
    for (Index i = 0; i < nh; ++i) {
        const Halfedge h(2 * kept.edges.old_of_new[i >> 1] + (i & 1));
        to[i] = Vertex(kept.vertices.new_of_old[mesh.to_vertex(h).idx()]);
        next[i] = kept.halfedge(mesh.next(h));
        prev[i] = kept.halfedge(mesh.prev(h));
        const Face f = mesh.face(h);
        face[i] = f.is_valid() ? Face(kept.faces.new_of_old[f.idx()]) : f;
    }
    for (Index i = 0; i < nf; ++i)
        face_halfedge[i] = kept.halfedge(mesh.halfedge(Face(kept.faces.old_of_new[i])));
    HalfedgeMesh out;
    out.assign_connectivity(std::move(positions), std::move(vertex_halfedge), std::move(to),
                            std::move(next), std::move(prev), std::move(face),
                            std::move(face_halfedge));
    return out;
}

template <class T>
void carry_vertex_attribute(const HalfedgeMesh& mesh, const Kept& kept, const char* name,
                            HalfedgeMesh& out) {
    const auto from = mesh.get_vertex_property<T>(name);
    if (!from) return;
    auto to = out.add_vertex_property<T>(name);
    for (Index i = 0; i < kept.vertices.old_of_new.size(); ++i)
        to[Vertex(i)] = from[Vertex(kept.vertices.old_of_new[i])];
}

template <class T>
void carry_halfedge_attribute(const HalfedgeMesh& mesh, const Kept& kept, const char* name,
                              HalfedgeMesh& out) {
    const auto from = mesh.get_halfedge_property<T>(name);
    if (!from) return;
    auto to = out.add_halfedge_property<T>(name);
    for (Index i = 0; i < 2 * kept.edges.old_of_new.size(); ++i)
        to[Halfedge(i)] = from[Halfedge(2 * kept.edges.old_of_new[i >> 1] + (i & 1))];
}

}  // namespace

RemoveComponentsResult remove_small_components(const HalfedgeMesh& mesh,
                                               const RemoveComponentsOptions& options) {
    check_options(options);
    RemoveComponentsResult result;
    result.labels = label_face_components(mesh);
    result.removed = choose_removed(mesh, result.labels, options, result.report);
    RemoveComponentsReport& report = result.report;
    if (mesh.n_faces() == 0) {  // only isolated vertices, if any: removing them empties it
        result.mesh = mesh;
        return result;
    }
    report.isolated_vertices_removed = result.labels.isolated_vertices;
    if (report.faces_removed == 0 && report.isolated_vertices_removed == 0) {
        result.mesh = mesh;  // nothing to remove: the input as it is
        return result;
    }
    const Kept kept = choose_kept(mesh, result.labels, result.removed);
    result.mesh = copy_connectivity(mesh, kept);
    carry_vertex_attribute<Vector3>(mesh, kept, "v:normal", result.mesh);
    carry_vertex_attribute<Color>(mesh, kept, "v:color", result.mesh);
    carry_vertex_attribute<TexCoord>(mesh, kept, "v:texcoord", result.mesh);
    carry_vertex_attribute<int>(mesh, kept, "v:subdivision_level", result.mesh);
    carry_halfedge_attribute<TexCoord>(mesh, kept, "h:texcoord", result.mesh);
    report.vertices_removed = mesh.n_vertices() - result.mesh.n_vertices();
    return result;
}

}  // namespace trilab
