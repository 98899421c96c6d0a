// Face orientation; see orientation.h. The connectivity part is
// HalfedgeMesh::reverse_orientation() (core/topology.cpp), which needs the mesh's property
// containers to move per-halfedge attributes with their corners.
#include "core/algorithms/orientation.h"

#include <cmath>
#include <cstdio>

#include "core/geometry.h"

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
