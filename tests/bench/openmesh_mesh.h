#pragma once
// The benchmarks' OpenMesh peer mesh: double-precision points (like trilab's), built from a
// HalfedgeMesh with the same vertex and face order. Include only where TRILAB_HAS_OPENMESH.
#include <vector>

// OpenMesh's VectorT default constructor leaves its elements uninitialized on purpose; GCC 12
// flags that where its property containers get inlined (not our code).
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

#include "core/halfedge_mesh.h"

namespace trilab::bench {

struct DoubleTraits : OpenMesh::DefaultTraits {
    typedef OpenMesh::Vec3d Point;
    typedef OpenMesh::Vec3d Normal;
};
using OpenMeshDouble = OpenMesh::TriMesh_ArrayKernelT<DoubleTraits>;

/// `m` as an OpenMesh mesh (deleted elements left out, the order kept).
inline OpenMeshDouble to_openmesh(const HalfedgeMesh& m) {
    OpenMeshDouble om;
    std::vector<OpenMeshDouble::VertexHandle> handles(m.vertices_size());
    for (Vertex v : m.vertices()) {
        const Point& p = m.position(v);
        handles[v.idx()] = om.add_vertex(OpenMeshDouble::Point(p.x(), p.y(), p.z()));
    }
    for (Face f : m.faces()) {
        const auto vs = m.face_vertices(f);
        om.add_face(handles[vs[0].idx()], handles[vs[1].idx()], handles[vs[2].idx()]);
    }
    return om;
}

}  // namespace trilab::bench
