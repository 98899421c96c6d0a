// Every registered operation (app/ops/operation.h operation_defs()) as a method of trilab.Mesh:
// its name with '_' for '-' (fill-holes: Mesh.fill_holes), its options as keyword arguments
// (max-edges: max_edges=10; a name an analysis has already gets "_op": spectrum_op), turned into
// the very option list `trilab-cli NAME` parses, so the values are checked by the same code and
// refused with the same message (ValueError). A new operation appears here with no binding code.
// The run releases the GIL; it returns a new Mesh whose .report is the dict `trilab-cli NAME
// --json` prints (less "ms"), built by the CLI's own app/cli/operation_report.h.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <algorithm>
#include <chrono>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "app/cli/operation_report.h"
#include "app/ops/operation.h"
#include "app/ops/region_spec.h"
#include "core/algorithms/selection.h"
#include "core/errors.h"
#include "python/mesh_handle.h"
#include "python/python_progress.h"

namespace py = pybind11;

namespace trilab::python {
namespace {

/// What a call passes besides the operation's own options.
struct CallExtras {
    std::optional<Selection> region;
    py::object progress = py::none();
    bool keep_partial = false;
};

/// The CLI text of a keyword argument's value: whole numbers as such, floats as Python's
/// shortest round-trip text, (lo, hi) as "LO:HI", anything else as str(); the operation's
/// parser then checks it as it checks the command line.
std::string value_text(const py::handle& v) {
    if (py::isinstance<py::bool_>(v)) return py::str(v).cast<std::string>();
    if (py::isinstance<py::float_>(v))
        return py::repr(py::float_(py::reinterpret_borrow<py::object>(v))).cast<std::string>();
    if (PyIndex_Check(v.ptr()))
        return py::str(py::int_(py::reinterpret_borrow<py::object>(v))).cast<std::string>();
    if ((py::isinstance<py::tuple>(v) || py::isinstance<py::list>(v)) && py::len(v) == 2) {
        const py::sequence s = py::reinterpret_borrow<py::sequence>(v);
        return value_text(s[0]) + ":" + value_text(s[1]);
    }
    return py::str(v).cast<std::string>();
}

const ParamSpec* find_param(const OperationDef& def, const std::string& name) {
    for (const ParamSpec& p : def.params)
        if (p.name == name) return &p;
    return nullptr;
}

/// region=: a SPEC string as trilab-cli's --region takes it, or one weight in [0, 1] per vertex.
Selection region_of(const HalfedgeMesh& mesh, const py::handle& v) {
    if (py::isinstance<py::str>(v))
        return make_region(mesh, parse_region_spec(v.cast<std::string>()));
    const auto w = py::array_t<float, py::array::forcecast>::ensure(v);
    if (!w) {
        PyErr_Clear();
        throw InvalidArgument("--region: expected a SPEC string or an array of weights");
    }
    if (w.ndim() != 1 || std::size_t(w.shape(0)) != mesh.vertices_size())
        throw InvalidArgument("--region: expected one weight per vertex (" +
                              std::to_string(mesh.vertices_size()) + "), got an array of " +
                              std::to_string(w.size()) + " values in " + std::to_string(w.ndim()) +
                              " dimension(s)");
    Selection region(std::size_t(w.shape(0)));
    const auto a = w.unchecked<1>();
    for (py::ssize_t i = 0; i < w.shape(0); ++i) {
        const float x = a(i);
        if (!(x >= 0.0f && x <= 1.0f))
            throw InvalidArgument("--region: weight " + std::to_string(i) + " is " +
                                  std::to_string(x) + ", not in [0, 1]");
        region[std::size_t(i)] = x;
    }
    return region;
}

/// The command-line option list of `kwargs` for `def` (and the call's own arguments).
std::vector<std::string> option_args(const OperationDef& def, const HalfedgeMesh& mesh,
                                     const py::kwargs& kwargs, CallExtras& extras) {
    std::vector<std::string> args;
    for (const auto& [k, v] : kwargs) {
        const std::string key = py::str(k).cast<std::string>();
        if (key == "region") {
            if (!v.is_none()) extras.region = region_of(mesh, v);
            continue;
        }
        if (key == "progress") {
            extras.progress = py::reinterpret_borrow<py::object>(v);
            continue;
        }
        if (key == "keep_partial" && def.may_stop_early) {
            extras.keep_partial = py::bool_(py::reinterpret_borrow<py::object>(v));
            continue;
        }
        std::string name = key;
        std::replace(name.begin(), name.end(), '_', '-');
        const ParamSpec* p = find_param(def, name);
        if (p && p->kind == ParamKind::Flag) {
            if (!py::isinstance<py::bool_>(v))
                throw InvalidArgument("--" + name + ": a flag: expected True or False, got " +
                                      py::repr(v).cast<std::string>());
            if (v.cast<bool>()) args.push_back("--" + name);
            continue;
        }
        if (v.is_none() && p && p->optional) continue;  // unset: the run picks its default
        args.push_back("--" + name);
        args.push_back(value_text(v));
    }
    return args;
}

/// Runs operation `name` on `self` as `trilab-cli NAME` would, with the GIL released.
std::shared_ptr<MeshHandle> run(const MeshHandle& self, const std::string& name,
                                const py::kwargs& kwargs) {
    const OperationDef& def = operation_def(name);
    CallExtras extras;
    const Operation op = parse_operation(name, option_args(def, self.mesh, kwargs, extras));
    if (extras.region && !def.takes_region)
        throw InvalidArgument("--region: " + name +
                              " does not work on a region yet (it acts on the whole mesh)");
    RunSettings settings;
    settings.keep_steps = false;  // only the last state is kept, as by the CLI
    settings.morph = false;
    if (extras.region) settings.region = &*extras.region;
    PythonProgress progress(extras.progress);
    std::optional<OperationResult> result;
    const auto t0 = std::chrono::steady_clock::now();
    try {
        py::gil_scoped_release release;
        result = run_operation(op, self.mesh, progress, settings);
    } catch (const Cancelled&) {
        progress.rethrow_if_stopped();
        throw;
    }
    const double run_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    if (result->stopped_early && !extras.keep_partial)
        throw RunStopped(result->stop_reason +
                         " (nothing returned; keep_partial=True returns the last good state)");
    cli::JsonObject json;
    cli::add_operation_report(json, op, *result, cli::command_extras(name), {}, {});
    std::shared_ptr<MeshHandle> out = make_handle(std::move(result->steps.back().mesh));
    out->report = py::module_::import("json").attr("loads")(json.str());
    out->ms = result->ms;
    out->run_ms = run_ms;
    return out;
}

/// The method's docstring: the summary and the options as `trilab-cli NAME --help` lists them.
std::string doc_of(const OperationDef& def) {
    std::string s = def.label + ": " + def.summary +
                    "\n\nKeyword arguments (the options of `trilab-cli " + def.name +
                    "`, '-' written '_'):\n" + def.help();
    if (def.takes_region)
        s += "  region: a SPEC string as --region takes it, or one weight in [0, 1] per vertex\n";
    if (def.may_stop_early)
        s += "  keep_partial: return the last good state of a run that stops early\n";
    s += "  progress: a callable(fraction, stage), called now and then; raising in it stops "
         "the run\n\nReturns a new Mesh; .report holds the run's figures.";
    return s;
}

}  // namespace

void bind_operations(py::class_<MeshHandle, std::shared_ptr<MeshHandle>>& cls) {
    for (const OperationDef* def : operation_defs()) {
        std::string method = def->name;
        std::replace(method.begin(), method.end(), '-', '_');
        // A name an analysis already has (spectrum: the eigenpairs) gets "_op" (spectrum_op).
        if (py::hasattr(cls, method.c_str())) method += "_op";
        const std::string name = def->name;
        cls.def(
            method.c_str(),
            [name](const MeshHandle& self, const py::kwargs& kwargs) {
                return run(self, name, kwargs);
            },
            doc_of(*def).c_str());
    }
    cls.def(
        "run",
        [](const MeshHandle& self, const std::string& name, const py::kwargs& kwargs) {
            return run(self, name, kwargs);
        },
        py::arg("name"),
        "Runs the operation NAME (as `trilab-cli NAME`) with keyword options; the same as the "
        "method of that name.");
}

}  // namespace trilab::python
