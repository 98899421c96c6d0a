// Face orientation; see orientation.h. The connectivity part is
// HalfedgeMesh::reverse_orientation() (core/topology.cpp, in place), which needs the mesh's
// property containers to move per-halfedge attributes with their corners.
#include "core/algorithms/orientation.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>

#include "core/algorithms/mesh_stats.h"
#include "core/algorithms/selection.h"
#include "core/errors.h"
#include "core/geometry.h"

namespace trilab {

FlipReport flip_orientation(HalfedgeMesh& mesh, const FlipOptions& options) {
    FlipReport report;
    const std::vector<float>* region = options.region;
    if (region) check_selection(mesh, *region, "flip: region");
    const bool closed = is_closed(std::as_const(mesh));
    if (closed) report.volume_before = volume(std::as_const(mesh));
    if (!region) {
        report.faces = mesh.n_faces();
        mesh.reverse_orientation();
        if (auto normals = mesh.get_vertex_property<Vector3>("v:normal")) {
            for (Vertex v : mesh.vertices()) normals[v] = -normals[v];
            report.normals_negated = true;
        }
    } else {
        // The components the region touches, flipped whole: each vertex has its component's
        // label (union-find over the edges, label_components(), or the caller's); the faces
        // and edges follow their vertices. When the region touches every component this is
        // the whole mesh's flip.
        std::vector<Index> own_label;
        const std::vector<Index>& label = options.components ? *options.components : own_label;
        std::vector<std::uint8_t> flip, present;  // per component
        if (!options.components) {
            const std::size_t n_labels = label_components(std::as_const(mesh), own_label);
            flip.assign(n_labels, 0);
            present.assign(n_labels, 0);
        } else if (label.size() != mesh.vertices_size()) {
            throw InvalidArgument("flip: " + std::to_string(label.size()) +
                                  " component labels for " + std::to_string(mesh.vertices_size()) +
                                  " vertices");
        }
        for (Vertex v : mesh.vertices()) {
            if (mesh.is_isolated(v)) continue;
            const Index c = label[v.idx()];
            if (c >= flip.size()) {  // the caller's labels: as many as they use
                flip.resize(std::size_t(c) + 1, 0);
                present.resize(std::size_t(c) + 1, 0);
            }
            present[c] = 1;
            if ((*region)[v.idx()] > 0.0f) flip[c] = 1;
        }
        const std::size_t n_labels = flip.size();
        std::size_t n_present = 0;
        for (std::size_t c = 0; c < n_labels; ++c) {
            n_present += present[c];
            report.components += flip[c];
        }
        const auto flipped = [&](Vertex v) { return flip[label[v.idx()]] != 0; };
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
        if (auto normals = mesh.get_vertex_property<Vector3>("v:normal")) {
            // An isolated vertex has no component: its normal follows its own weight.
            for (Vertex v : mesh.vertices()) {
                const bool isolated = mesh.is_isolated(v);
                if ((!isolated && flipped(v)) || (isolated && (*region)[v.idx()] > 0.0f)) {
                    normals[v] = -normals[v];
                    report.normals_negated = true;
                }
            }
        }
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
