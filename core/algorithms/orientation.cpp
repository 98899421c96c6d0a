// Face orientation; see orientation.h. The connectivity part is
// HalfedgeMesh::reverse_orientation() and reverse_orientation_from() (core/topology.cpp, in
// place), which need the mesh's property containers to move per-halfedge attributes with
// their corners.
#include "core/algorithms/orientation.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "core/algorithms/selection.h"
#include "core/errors.h"
#include "core/geometry.h"

namespace trilab {

namespace {

// The components with a vertex of positive weight, found while they are reversed
// (HalfedgeMesh::reverse_orientation_from(): a flood over their edges only), and their
// vertices' stored normals negated, with those of isolated vertices of positive weight.
void flip_region_flood(HalfedgeMesh& mesh, const std::vector<float>& region,
                       VertexProperty<Vector3> normals, FlipReport& report) {
    std::vector<Vertex> seeds, isolated;
    for (Vertex v : mesh.vertices()) {
        if (!(region[v.idx()] > 0.0f)) continue;
        (mesh.is_isolated(v) ? isolated : seeds).push_back(v);
    }
    const HalfedgeMesh::ReversedPart part = mesh.reverse_orientation_from(seeds);
    report.components = part.components;
    report.faces = part.faces;
    if (!normals) return;
    for (Vertex v : part.vertices) normals[v] = -normals[v];
    for (Vertex v : isolated) normals[v] = -normals[v];
    report.normals_negated = !part.vertices.empty() || !isolated.empty();
}

// The same with the caller's component labels (FlipOptions::components): the components the
// region touches are marked from their labels; when that is every component, this is the
// whole mesh's reversal, otherwise the reversal of their edges.
void flip_region_labelled(HalfedgeMesh& mesh, const std::vector<float>& region,
                          const std::vector<Index>& label, VertexProperty<Vector3> normals,
                          FlipReport& report) {
    if (label.size() != mesh.vertices_size())
        throw InvalidArgument("flip: " + std::to_string(label.size()) + " component labels for " +
                              std::to_string(mesh.vertices_size()) + " vertices");
    std::vector<std::uint8_t> flip, present;  // per component
    for (Vertex v : mesh.vertices()) {
        if (mesh.is_isolated(v)) continue;
        const Index c = label[v.idx()];
        if (c >= flip.size()) {  // the caller's labels: as many as they use
            flip.resize(std::size_t(c) + 1, 0);
            present.resize(std::size_t(c) + 1, 0);
        }
        present[c] = 1;
        if (region[v.idx()] > 0.0f) flip[c] = 1;
    }
    std::size_t n_present = 0;
    for (std::size_t c = 0; c < flip.size(); ++c) {
        n_present += present[c];
        report.components += flip[c];
    }
    // An isolated vertex has no component: it follows its own weight (for its normal).
    const auto flipped = [&](Vertex v) {
        return mesh.is_isolated(v) ? region[v.idx()] > 0.0f : flip[label[v.idx()]] != 0;
    };
    if (report.components == n_present) {
        report.faces = mesh.n_faces();
        mesh.reverse_orientation();
    } else {
        for (Face f : mesh.faces()) report.faces += flipped(mesh.to_vertex(mesh.halfedge(f)));
        std::vector<std::uint8_t> edge_mask(mesh.edges_size(), 0);
        for (Edge e : mesh.edges())
            edge_mask[e.idx()] = flipped(mesh.to_vertex(HalfedgeMesh::halfedge(e, 0))) ? 1 : 0;
        mesh.reverse_orientation(edge_mask);
    }
    if (!normals) return;
    for (Vertex v : mesh.vertices()) {
        if (!flipped(v)) continue;
        normals[v] = -normals[v];
        report.normals_negated = true;
    }
}

}  // namespace

FlipReport flip_orientation(HalfedgeMesh& mesh, const FlipOptions& options) {
    FlipReport report;
    const std::vector<float>* region = options.region;
    if (region) check_selection(mesh, *region, "flip: region");
    const bool closed = is_closed(std::as_const(mesh));
    if (closed) report.volume_before = volume(std::as_const(mesh));
    auto normals = mesh.get_vertex_property<Vector3>("v:normal");
    if (!region) {
        report.faces = mesh.n_faces();
        mesh.reverse_orientation();
        if (normals) {
            for (Vertex v : mesh.vertices()) normals[v] = -normals[v];
            report.normals_negated = true;
        }
    } else {
        // The components the region touches, flipped whole.
        if (options.components)
            flip_region_labelled(mesh, *region, *options.components, normals, report);
        else
            flip_region_flood(mesh, *region, normals, report);
    }
    if (closed) report.volume_after = volume(mesh);
    return report;
}

std::string inward_orientation_note(const HalfedgeMesh& mesh) {
    // Every load runs this: closed (an early exit at the first boundary edge), then the volume
    // and the bounding box.
    if (!is_closed(mesh)) return "";
    const double v = volume(mesh);
    if (!(v < 0)) return "";
    const double d = bounding_box(mesh).diagonal();
    if (!(v < -1e-9 * d * d * d)) return "";
    char buf[320];
    std::snprintf(buf, sizeof(buf),
                  "the mesh is closed but its volume is negative (%.6g): its faces are oriented "
                  "inwards, so the viewer shows their back faces and normals point in; "
                  "Tools > Flip orientation (or `trilab-cli flip IN OUT`) turns them outwards",
                  v);
    return buf;
}

}  // namespace trilab
