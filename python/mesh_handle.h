#pragma once
// The C++ side of trilab.Mesh (python/module.cpp): one HalfedgeMesh that Python never changes
// (every operation returns a new Mesh), compacted once when it is made (no deleted elements),
// so vertex i of V, F and every property is the mesh's storage index i, and Mesh.V can view
// the positions array itself.
#include <pybind11/pybind11.h>

#include <memory>
#include <string>
#include <vector>

#include "core/halfedge_mesh.h"

namespace trilab::python {

struct MeshHandle {
    HalfedgeMesh mesh;
    /// Mesh.report: the dict of `trilab-cli OP --json` (less "ms") for an operation's result,
    /// None otherwise.
    pybind11::object report = pybind11::none();
    /// Mesh.ms: for an operation's result, the operation's own time (the CLI's --json "ms",
    /// OperationResult::ms); negative otherwise (Mesh.ms is then None).
    double ms = -1;
    /// Mesh.run_ms: the whole run_operation() call (the operation layer's report figures
    /// included, which the CLI also computes outside its "ms"); negative when not a result.
    double run_ms = -1;
    /// What loading or building did (LoadReport::lines()), for Mesh.load_report.
    std::vector<std::string> load_report;
    /// Mesh.session: for the mesh Mesh.show() returned, the viewer's history (a
    /// trilab.Session); None otherwise.
    pybind11::object session = pybind11::none();
};

/// A handle owning `mesh`, compacted when it holds deleted elements.
std::shared_ptr<MeshHandle> make_handle(HalfedgeMesh mesh);

/// Binds Mesh's arrays (V, F, properties) and analyses (spectrum, laplacian, geodesic) on `cls`.
void bind_mesh_arrays(pybind11::class_<MeshHandle, std::shared_ptr<MeshHandle>>& cls);
/// Binds trilab.Mesh(V, F) (the constructor from arrays).
void bind_mesh_constructor(pybind11::class_<MeshHandle, std::shared_ptr<MeshHandle>>& cls);
/// Binds trilab.Session and trilab.replay on module `m`.
void bind_session(pybind11::module_& m);
/// Binds Mesh.show() and Mesh.session (python/show.cpp).
void bind_show(pybind11::class_<MeshHandle, std::shared_ptr<MeshHandle>>& cls);
/// Binds one method per registered operation (app/ops/operation.h) on `cls`.
void bind_operations(pybind11::class_<MeshHandle, std::shared_ptr<MeshHandle>>& cls);

}  // namespace trilab::python
