// trilab.Session (a session file or crash journal: its entries, their states as Meshes, the
// recipe) and trilab.replay (a recipe run on a mesh), through app/history (session_file.h,
// recipe.h): the same readers as `trilab-cli session` and `trilab-cli replay`.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <memory>
#include <string>
#include <utility>

#include "app/history/recipe.h"
#include "app/history/session_file.h"
#include "core/errors.h"
#include "core/io/file_util.h"
#include "python/mesh_handle.h"

namespace py = pybind11;

namespace trilab::python {
namespace {

struct SessionHandle {
    std::shared_ptr<SessionContents> contents;
    History::Snapshot snapshot;
};

SessionHandle open_session(const std::string& path) {
    SessionHandle s;
    {
        py::gil_scoped_release release;
        s.contents = std::make_shared<SessionContents>(read_session_or_journal(path));
    }
    s.snapshot = s.contents->history.snapshot();
    return s;
}

py::list entries(const SessionHandle& s) {
    py::list out;
    for (const SessionEntrySummary& e : s.contents->entries) {
        py::dict d;
        d["label"] = e.label;
        d["parameters"] = e.parameters;
        d["operation"] = e.operation.def ? py::object(py::str(e.operation.name())) : py::none();
        d["ms"] = e.ms;
        d["steps"] = e.steps;
        out.append(d);
    }
    return out;
}

/// Entry `i`'s state (its last step, or step `step`) as a Mesh.
std::shared_ptr<MeshHandle> state(const SessionHandle& s, long long i, long long step) {
    const auto n = static_cast<long long>(s.snapshot.entries.size());
    if (i < 0) i += n;
    if (i < 0 || i >= n)
        throw py::index_error("Session.state: entry " + std::to_string(i) + " of " +
                              std::to_string(n));
    const History::EntryRecord& e = *s.snapshot.entries[std::size_t(i)];
    const auto steps = static_cast<long long>(e.steps.size());
    if (step < 0) step += steps;
    if (step < 0 || step >= steps)
        throw py::index_error("Session.state: step " + std::to_string(step) + " of " +
                              std::to_string(steps) + " in entry " + std::to_string(i));
    const std::shared_ptr<const HalfedgeMesh>& mesh = e.steps[std::size_t(step)].mesh;
    if (!mesh)
        throw InvalidArgument("Session.state: entry " + std::to_string(i) +
                              " keeps no state (dropped for the memory budget)");
    return make_handle(*mesh);  // shares the arrays (copy-on-write)
}

std::string recipe_text(const SessionHandle& s) {
    return recipe_json(recipe_of(s.contents->history));
}

/// replay(recipe, mesh): `recipe` a dict, a JSON text or the path of a recipe file.
std::shared_ptr<MeshHandle> replay_recipe(const py::object& recipe, const MeshHandle& mesh) {
    std::string json, name = "recipe";
    if (py::isinstance<py::dict>(recipe)) {
        json = py::module_::import("json").attr("dumps")(recipe).cast<std::string>();
    } else {
        json = recipe.cast<std::string>();
        if (json.find('{') == std::string::npos) {  // a path
            name = json;
            json = read_file_bytes(name);
        }
    }
    const Recipe parsed = parse_recipe(json, name);
    HalfedgeMesh out;
    {
        py::gil_scoped_release release;
        out = replay(parsed, mesh.mesh);
    }
    return make_handle(std::move(out));
}

}  // namespace

void bind_session(py::module_& m) {
    py::class_<SessionHandle>(m, "Session",
                              "A session file (.trilab) or crash journal, as the viewer saved it.")
        .def(py::init(&open_session), py::arg("path"))
        .def_property_readonly("entries", &entries,
                               "Every entry, oldest first: label, parameters, operation (None "
                               "for loads and viewer-made states), ms, steps (vertices, faces).")
        .def_property_readonly(
            "current", [](const SessionHandle& s) { return s.snapshot.current; },
            "The current entry's index (an undo leaves it before the last).")
        .def_property_readonly(
            "journal", [](const SessionHandle& s) { return s.contents->journal; },
            "Whether the file is a crash journal.")
        .def("state", &state, py::arg("entry"), py::arg("step") = -1,
             "Entry ENTRY's state as a Mesh (its last step, or step STEP; negative counts from "
             "the end).")
        .def("recipe", &recipe_text,
             "The recipe (JSON text, as `trilab-cli session recipe` writes it) from the loaded "
             "file to the current entry; ValueError for a state the viewer made otherwise.")
        .def("__len__", [](const SessionHandle& s) { return s.snapshot.entries.size(); });
    m.def("replay", &replay_recipe, py::arg("recipe"), py::arg("mesh"),
          "Runs a recipe (a dict, its JSON text or a recipe file's path) on MESH as "
          "`trilab-cli replay` does; returns the last state.");
}

}  // namespace trilab::python
