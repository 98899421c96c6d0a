// The Python module `trilab` (docs/python.md): trilab.load(), trilab.Mesh and its methods, one
// per registered operation. Built by CMake with pybind11 (python/CMakeLists.txt).
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstdlib>
#include <string>
#include <utility>

#include "app/ops/operation.h"
#include "app/platform/heap_tuning.h"
#include "core/errors.h"
#include "core/io/mesh_io.h"
#include "core/progress.h"
#include "python/mesh_handle.h"
#include "trilab/version.h"

namespace py = pybind11;
using trilab::python::MeshHandle;

namespace {

std::shared_ptr<MeshHandle> load(const std::string& path) {
    trilab::LoadedMesh loaded;
    {
        py::gil_scoped_release release;
        loaded = trilab::read_mesh(path);
    }
    std::shared_ptr<MeshHandle> h = trilab::python::make_handle(std::move(loaded.mesh));
    h->load_report = loaded.report.lines();
    return h;
}

void save(const MeshHandle& h, const std::string& path, bool ascii, bool big_endian) {
    trilab::WriteOptions o;
    o.ascii = ascii;
    o.big_endian = big_endian;
    py::gil_scoped_release release;
    trilab::write_mesh(h.mesh, path, o);
}

std::string repr(const MeshHandle& h) {
    return "<trilab.Mesh: " + std::to_string(h.mesh.n_vertices()) + " vertices, " +
           std::to_string(h.mesh.n_faces()) + " faces>";
}

void register_exceptions(py::module_& m) {
    static py::exception<trilab::RunStopped> stopped(m, "StoppedEarly", PyExc_RuntimeError);
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const trilab::RunStopped& e) {
            stopped(e.what());
        } catch (const trilab::InvalidArgument& e) {
            PyErr_SetString(PyExc_ValueError, e.what());
        } catch (const trilab::Cancelled& e) {
            PyErr_SetString(PyExc_KeyboardInterrupt, e.what());
        } catch (const trilab::IoError& e) {
            PyErr_SetString(PyExc_OSError, e.what());
        } catch (const trilab::Error& e) {
            PyErr_SetString(PyExc_ValueError, e.what());
        }
    });
}

}  // namespace

PYBIND11_MODULE(trilab, m) {
    m.doc() = "trilab: triangle meshes, their operations and analyses (docs/python.md)";
    m.attr("__version__") = TRILAB_VERSION;
    register_exceptions(m);
    py::class_<MeshHandle, std::shared_ptr<MeshHandle>> cls(m, "Mesh",
                                                            "A triangle mesh; never changed: "
                                                            "every operation returns a new one.");
    trilab::python::bind_mesh_constructor(cls);
    cls.def("save", &save, py::arg("path"), py::arg("ascii") = false, py::arg("big_endian") = false,
            "Writes the mesh (format by extension: .obj .off .ply .stl .om), as trilab-cli does.");
    cls.def_property_readonly("n_vertices",
                              [](const MeshHandle& h) { return h.mesh.n_vertices(); });
    cls.def_property_readonly("n_faces", [](const MeshHandle& h) { return h.mesh.n_faces(); });
    cls.def_readonly("report", &MeshHandle::report,
                     "The dict `trilab-cli OP --json` prints (less \"ms\") for an operation's "
                     "result; None for a loaded or built mesh.");
    cls.def_property_readonly(
        "ms",
        [](const MeshHandle& h) -> py::object {
            return h.ms < 0 ? py::object(py::none()) : py::object(py::float_(h.ms));
        },
        "For an operation's result: the operation's own time in ms (the CLI's --json \"ms\", "
        "which .report leaves out); None otherwise.");
    cls.def_property_readonly(
        "run_ms",
        [](const MeshHandle& h) -> py::object {
            return h.run_ms < 0 ? py::object(py::none()) : py::object(py::float_(h.run_ms));
        },
        "For an operation's result: the whole run in ms (ms plus the operation layer's report "
        "figures, which trilab-cli also computes outside its \"ms\"); None otherwise.");
    cls.def_readonly("load_report", &MeshHandle::load_report,
                     "What loading or building repaired, one line each.");
    cls.def("__repr__", &repr);
    trilab::python::bind_mesh_arrays(cls);
    trilab::python::bind_operations(cls);
    trilab::python::bind_session(m);
    trilab::python::bind_show(cls);
    m.def("load", &load, py::arg("path"),
          "Reads a mesh file (.obj .off .ply .stl .om) as trilab-cli does.");
    m.def("operations", &trilab::operation_names, "The names of the registered operations.");
    m.def("tune_heap_for_large_meshes", &trilab::tune_heap_for_large_meshes,
          "Keeps large freed buffers in the process's heap (glibc mallopt), as trilab-cli and "
          "the viewer do at start: a large mesh's next buffers then cost no page faults. "
          "Called on import unless the environment has TRILAB_HEAP_TUNING=0.");
    const char* tuning = std::getenv("TRILAB_HEAP_TUNING");
    if (!tuning || std::string(tuning) != "0") trilab::tune_heap_for_large_meshes();
}
