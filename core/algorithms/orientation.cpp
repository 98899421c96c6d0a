// Face orientation; see orientation.h. The connectivity part is
// HalfedgeMesh::reverse_orientation() (core/topology.cpp), which needs the mesh's property
// containers to move per-halfedge attributes with their corners.
#include "core/algorithms/orientation.h"

#include <cmath>
#include <cstdio>
#include <vector>

#include "core/geometry.h"
#include "core/prefetch.h"

namespace trilab {

FlipReport flip_orientation(HalfedgeMesh& mesh) {
    FlipReport report;
    report.faces = mesh.n_faces();
    const bool closed = is_closed(mesh);
    if (closed) report.volume_before = volume(mesh);
    mesh.reverse_orientation();
    if (auto normals = mesh.get_vertex_property<Vector3>("v:normal")) {
        for (Vertex v : mesh.vertices()) normals[v] = -normals[v];
        report.normals_negated = true;
    }
    if (closed) report.volume_after = volume(mesh);
    return report;
}

std::string inward_orientation_note(const HalfedgeMesh& mesh) {
    // One pass over the connectivity arrays (every load runs this): closed, then the volume
    // (summed in face order like volume()) and the bounding box.
    if (mesh.n_faces() == 0) return "";
    const std::vector<Face>& face = mesh.get_halfedge_property<Face>("h:face").vector();
    for (Edge e : mesh.edges())
        if (!face[2 * e.idx()].is_valid() || !face[2 * e.idx() + 1].is_valid()) return "";
    const std::vector<Vertex>& to = mesh.get_halfedge_property<Vertex>("h:to").vector();
    const std::vector<Halfedge>& next = mesh.get_halfedge_property<Halfedge>("h:next").vector();
    const std::vector<Halfedge>& fh = mesh.get_face_property<Halfedge>("f:halfedge").vector();
    const std::vector<Point>& x = mesh.positions();
    double volume6 = 0;
    constexpr std::size_t kAhead = 8;
    for (Face f : mesh.faces()) {
        if (f.idx() + kAhead < fh.size()) {  // the halfedges a few faces ahead
            const Index a = fh[f.idx() + kAhead].idx();
            if (a < next.size()) {
                prefetch(&next[a]);
                prefetch(&to[a]);
            }
        }
        const Halfedge h0 = fh[f.idx()], h1 = next[h0.idx()], h2 = next[h1.idx()];
        const Point& x0 = x[to[h0.idx()].idx()];
        const Point& x1 = x[to[h1.idx()].idx()];
        const Point& x2 = x[to[h2.idx()].idx()];
        volume6 += ((x0 + x1 + x2) / 3.0).dot((x1 - x0).cross(x2 - x0));
    }
    const double v = volume6 / 6.0;
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
