// Face orientation; see orientation.h. The connectivity part is
// HalfedgeMesh::reverse_orientation() (core/topology.cpp), which needs the mesh's property
// containers to move per-halfedge attributes with their corners.
#include "core/algorithms/orientation.h"

#include <cmath>
#include <cstdio>
#include <future>
#include <utility>

#include "core/algorithms/mesh_stats.h"
#include "core/algorithms/selection.h"
#include "core/geometry.h"

namespace trilab {

FlipReport flip_orientation(HalfedgeMesh& mesh, const FlipOptions& options) {
    FlipReport report;
    const std::vector<float>* region = options.region;
    if (region) check_selection(mesh, *region, "flip: region");
    // A region flips the components it touches. A second thread labels the components
    // (union-find over the edges, label_components()) and marks those with a vertex of
    // positive weight, while this one measures the volume and computes the reversed
    // connectivity of every edge, which the flip then applies to those components. Both
    // threads only read the mesh; so a region costs what the whole mesh costs.
    struct Touched {
        std::vector<Index> label;        ///< per vertex: its component
        std::vector<std::uint8_t> flip;  ///< per component: it has a vertex of positive weight
        std::size_t present = 0, flipped = 0;  ///< components with a face; of those, flipped
    };
    Touched touched;
    std::future<void> labelling;
    if (region)
        labelling = std::async(std::launch::async, [&] {
            const HalfedgeMesh& m = mesh;
            const std::size_t n_labels = label_components(m, touched.label);
            touched.flip.assign(n_labels, 0);
            std::vector<std::uint8_t> present(n_labels, 0);
            for (Vertex v : m.vertices()) {
                if (m.is_isolated(v)) continue;
                const Index c = touched.label[v.idx()];
                present[c] = 1;
                if ((*region)[v.idx()] > 0.0f) touched.flip[c] = 1;
            }
            for (std::size_t c = 0; c < n_labels; ++c) {
                touched.present += present[c];
                touched.flipped += touched.flip[c];
            }
        });
    const bool closed = is_closed(std::as_const(mesh));
    if (closed) report.volume_before = volume(std::as_const(mesh));
    HalfedgeMesh::ReversedConnectivity reversed = std::as_const(mesh).reversed_connectivity();
    if (!region) {
        report.faces = mesh.n_faces();
        mesh.apply_reversed(std::move(reversed));
        if (auto normals = mesh.get_vertex_property<Vector3>("v:normal")) {
            for (Vertex v : mesh.vertices()) normals[v] = -normals[v];
            report.normals_negated = true;
        }
    } else {
        // The components the region touches, flipped whole: each vertex has its component's
        // label; the faces and edges follow their vertices. When the region touches every
        // component this is the whole mesh's flip.
        labelling.get();
        const std::vector<Index>& label = touched.label;
        const std::vector<std::uint8_t>& flip = touched.flip;
        report.components = touched.flipped;
        const std::size_t n_present = touched.present;
        const auto flipped = [&](Vertex v) { return flip[label[v.idx()]] != 0; };
        if (report.components == n_present) {
            report.faces = mesh.n_faces();
            mesh.apply_reversed(std::move(reversed));
        } else {
            for (Face f : mesh.faces()) report.faces += flipped(mesh.to_vertex(mesh.halfedge(f)));
            std::vector<std::uint8_t> edge_mask(mesh.edges_size(), 0);
            for (Edge e : mesh.edges())
                edge_mask[e.idx()] = flipped(mesh.to_vertex(HalfedgeMesh::halfedge(e, 0))) ? 1 : 0;
            mesh.apply_reversed(std::move(reversed), &edge_mask);
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
