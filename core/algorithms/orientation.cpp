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

// The components that hold a seed, found while they are reversed
// (HalfedgeMesh::reverse_orientation_from(): a flood over their edges only), and their
// vertices' stored normals negated, with those of the given isolated vertices.
void flip_from_seeds(HalfedgeMesh& mesh, const std::vector<Vertex>& seeds,
                     const std::vector<Vertex>& isolated, VertexProperty<Vector3> normals,
                     FlipReport& report) {
    const HalfedgeMesh::ReversedPart part = mesh.reverse_orientation_from(seeds, bool(normals));
    report.components = part.components;
    report.faces = part.faces;
    if (!normals) return;
    for (Vertex v : part.vertices) normals[v] = -normals[v];
    for (Vertex v : isolated) normals[v] = -normals[v];
    report.normals_negated = !part.vertices.empty() || !isolated.empty();
}

// Without labels: every vertex of positive weight seeds the flood (those in a component
// already reached cost a look each).
void flip_region_flood(HalfedgeMesh& mesh, const std::vector<float>& region,
                       VertexProperty<Vector3> normals, FlipReport& report) {
    std::vector<Vertex> seeds, isolated;
    for (Vertex v : mesh.vertices()) {
        if (!(region[v.idx()] > 0.0f)) continue;
        (mesh.is_isolated(v) ? isolated : seeds).push_back(v);
    }
    flip_from_seeds(mesh, seeds, isolated, normals, report);
}

// With the caller's component labels (FlipOptions::components): the components the region
// touches are marked from their labels. When that is every component, this is the whole
// mesh's reversal (no flood); otherwise one vertex of each seeds the flood.
void flip_region_labelled(HalfedgeMesh& mesh, const std::vector<float>& region,
                          const std::vector<Index>& label, VertexProperty<Vector3> normals,
                          FlipReport& report) {
    if (label.size() != mesh.vertices_size())
        throw InvalidArgument("flip: " + std::to_string(label.size()) + " component labels for " +
                              std::to_string(mesh.vertices_size()) + " vertices");
    std::vector<Vertex> seed_of;  // per component: its first vertex of positive weight
    std::vector<std::uint8_t> present;
    std::vector<Vertex> isolated;  // of positive weight
    for (Vertex v : mesh.vertices()) {
        const bool selected = region[v.idx()] > 0.0f;
        if (mesh.is_isolated(v)) {
            if (selected) isolated.push_back(v);
            continue;
        }
        const Index c = label[v.idx()];
        if (c >= present.size()) {  // the caller's labels: as many as they use
            seed_of.resize(std::size_t(c) + 1);
            present.resize(std::size_t(c) + 1, 0);
        }
        present[c] = 1;
        if (selected && !seed_of[c].is_valid()) seed_of[c] = v;
    }
    std::vector<Vertex> seeds;
    std::size_t n_present = 0;
    for (std::size_t c = 0; c < present.size(); ++c) {
        n_present += present[c];
        if (seed_of[c].is_valid()) seeds.push_back(seed_of[c]);
    }
    if (seeds.size() != n_present) {
        flip_from_seeds(mesh, seeds, isolated, normals, report);
        return;
    }
    report.components = n_present;
    report.faces = mesh.n_faces();
    mesh.reverse_orientation();
    if (!normals) return;
    // Every vertex but the isolated ones of weight 0, which belong to no component.
    for (Vertex v : mesh.vertices())
        if (!mesh.is_isolated(v) || region[v.idx()] > 0.0f) normals[v] = -normals[v];
    report.normals_negated = true;
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
