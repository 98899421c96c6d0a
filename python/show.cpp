// Mesh.show(): the trilab viewer on this mesh, and the mesh shown when its window closes, with
// the viewer's whole history (a trilab.Session) as the result's .session. The viewer runs as
// its own process (`trilab IN.trilab --save-session OUT.trilab --no-recovery`, the program the
// module was installed or built beside, or TRILAB_VIEWER), on a temporary session holding the
// mesh bit for bit; its session file comes back when it ends. No binding of this field hands an
// interactive edit back to the script; the viewer's windows, GL and event loop stay out of the
// module.
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <pybind11/pybind11.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "app/history/history.h"
#include "app/history/session_file.h"
#include "python/mesh_handle.h"

extern char** environ;

namespace py = pybind11;
namespace fs = std::filesystem;

namespace trilab::python {
namespace {

/// The viewer program: TRILAB_VIEWER, else `trilab` beside the module (the build's
/// build/python/trilab*.so and build/trilab; an install's .../lib/python3/dist-packages and
/// .../bin/trilab), else `trilab` on the PATH.
std::string viewer_program() {
    if (const char* env = std::getenv("TRILAB_VIEWER"); env && *env) return env;
    const fs::path module = py::module_::import("trilab").attr("__file__").cast<std::string>();
    for (const fs::path& candidate :
         {module.parent_path().parent_path() / "trilab",
          module.parent_path().parent_path().parent_path().parent_path() / "bin" / "trilab"}) {
        std::error_code ec;
        if (fs::is_regular_file(candidate, ec) && access(candidate.c_str(), X_OK) == 0)
            return candidate.string();
    }
    return "trilab";
}

/// What the viewer said: its lines naming an error (or, without one, its last `n` lines).
std::string said(const fs::path& path, std::size_t n) {
    std::ifstream in(path);
    std::vector<std::string> lines, errors;
    for (std::string line; std::getline(in, line);) {
        if (line.find("error") != std::string::npos ||
            (line.rfind("trilab: ", 0) == 0 && line.find("unknown") != std::string::npos))
            errors.push_back(line);
        lines.push_back(line);
    }
    if (errors.empty())
        errors.assign(lines.end() - std::ptrdiff_t(std::min(n, lines.size())), lines.end());
    std::string out;
    for (const std::string& line : errors) out += "\n  " + line;
    return out;
}

/// Runs `args` with stdout and stderr into `log`; waits (the GIL released, Ctrl+C ends the
/// viewer and raises KeyboardInterrupt); returns the exit status.
int run_viewer(const std::vector<std::string>& args, const fs::path& log) {
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    posix_spawn_file_actions_adddup2(&actions, 1, 2);
    std::vector<char*> argv;
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    pid_t pid = 0;
    const int error = posix_spawnp(&pid, argv[0], &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (error != 0)
        throw std::runtime_error("Mesh.show: cannot start the viewer '" + args[0] +
                                 "': " + std::strerror(error) +
                                 " (build it, install trilab, or set TRILAB_VIEWER)");
    int status = 0;
    for (;;) {
        pid_t done = 0;
        {
            py::gil_scoped_release release;
            for (int i = 0; i < 10 && (done = waitpid(pid, &status, WNOHANG)) == 0; ++i)
                std::this_thread::sleep_for(std::chrono::milliseconds(20));
        }
        if (done == pid) break;
        if (done < 0 && errno != EINTR) throw std::runtime_error("Mesh.show: waitpid failed");
        if (PyErr_CheckSignals() != 0) {  // Ctrl+C: the viewer ends as on a logout
            kill(pid, SIGTERM);
            waitpid(pid, &status, 0);
            throw py::error_already_set();
        }
    }
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

/// Removes a folder when the call ends, whatever the outcome.
struct TempDir {
    fs::path path;
    ~TempDir() {
        std::error_code ec;
        fs::remove_all(path, ec);
    }
};

std::shared_ptr<MeshHandle> show(const MeshHandle& h, int frames) {
    const char* display = std::getenv("DISPLAY");
    const char* wayland = std::getenv("WAYLAND_DISPLAY");
    if ((!display || !*display) && (!wayland || !*wayland))
        throw std::runtime_error(
            "Mesh.show: no display (DISPLAY and WAYLAND_DISPLAY are unset): the viewer needs a "
            "window; run it in a desktop session, under xvfb-run, or save the mesh and open it "
            "with trilab elsewhere");
    if (frames < 0) throw py::value_error("Mesh.show: frames must be >= 0 (0: until closed)");
    char pattern[] = "/tmp/trilab-show-XXXXXX";
    if (!mkdtemp(pattern)) throw std::runtime_error("Mesh.show: cannot make a temporary folder");
    const TempDir dir{pattern};
    // The mesh goes as a session of one entry: stored bit for bit (a mesh file might round
    // its positions), so an untouched mesh comes back equal.
    const fs::path mesh = dir.path / "mesh.trilab", session = dir.path / "shown.trilab",
                   log = dir.path / "viewer.log";
    {
        py::gil_scoped_release release;
        History history(std::size_t(-1));
        history.reset(HalfedgeMesh(h.mesh), "From Python", "");
        write_session(mesh.string(), history.snapshot(), SessionExtras{});
    }
    std::vector<std::string> args = {viewer_program(), mesh.string(), "--save-session",
                                     session.string(), "--no-recovery"};
    if (frames > 0) args.insert(args.end(), {"--frames", std::to_string(frames)});
    const int status = run_viewer(args, log);
    std::error_code ec;
    if (status != 0 || !fs::exists(session, ec))
        throw std::runtime_error("Mesh.show: the viewer ended with status " +
                                 std::to_string(status) + " and no session:" + said(log, 8));
    // The whole history, read into memory before the folder goes.
    py::object history = py::module_::import("trilab").attr("Session")(session.string());
    py::object current = history.attr("state")(history.attr("current"));
    auto shown = current.cast<std::shared_ptr<MeshHandle>>();
    shown->session = history;
    return shown;
}

}  // namespace

void bind_show(pybind11::class_<MeshHandle, std::shared_ptr<MeshHandle>>& cls) {
    cls.def("show", &show, py::arg("frames") = 0,
            "Opens the trilab viewer on this mesh and returns the mesh shown when its window "
            "closes (the current state), with the viewer's whole history as its .session (a "
            "trilab.Session). RuntimeError without a display. frames > 0: the viewer ends "
            "after that many frames (scripts, tests).");
    cls.def_readonly("session", &MeshHandle::session,
                     "For the mesh Mesh.show() returned: the viewer's history (a "
                     "trilab.Session); None otherwise.");
}

}  // namespace trilab::python
