// trilab-cli: the viewer's operations, headless. Every command exits 0 on success and
// non-zero with one line on stderr otherwise ("trilab-cli COMMAND: what went wrong"); with
// --json it prints one JSON object on stdout either way: the command's result (with "ms",
// the time spent in the operation itself, file reading and writing excluded) or
// {"command": ..., "error": ..., "exit": ...}. Each command lives in its own file
// (app/cli/*_command.cpp); this file only dispatches and reports failures.
#include <algorithm>
#include <cstdio>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "app/cli/compare_command.h"
#include "app/cli/convert_command.h"
#include "app/cli/figures_command.h"
#include "app/cli/generate_command.h"
#include "app/cli/geodesic_command.h"
#include "app/cli/info_command.h"
#include "app/cli/inspect_command.h"
#include "app/cli/json_writer.h"
#include "app/cli/operation_command.h"
#include "app/cli/record_command.h"
#include "app/cli/region_option.h"
#include "app/cli/render_command.h"
#include "app/cli/session_command.h"
#include "app/cli/spectrum_filter_command.h"
#include "app/ops/operation.h"
#include "app/platform/heap_tuning.h"
#include "core/errors.h"
#include "core/parallel.h"
#include "trilab/version.h"

namespace trilab::cli {
namespace {

constexpr const char* kUsage = R"(usage: trilab-cli COMMAND [options]

commands:
  info MESH [--json]              counts, topology, seams, bounding box, area, volume, load report
  convert IN OUT [--ascii] [--big-endian] [--json]
                                  convert between .obj .off .ply .stl .om (by extension);
                                  .stl and .ply are written binary unless --ascii
  generate NAME OUT [--json]      write a built-in model (see `trilab-cli generate --list`)
  figures [--json]                the reference's figures the viewer loads (--figure NAME)
  render MESH --out FILE.png [options]
                                  render offscreen to a PNG (`trilab-cli render --help`)
  record MESH --op "OP" --out DIR [options]
                                  render an operation's morph to PNG frames (`record --help`)
  compare A B [--samples N] [--json]
                                  sampled Hausdorff and RMS distance between two meshes
  geodesic IN OUT --from N[,N...] [--to M] [--json]
                                  heat-method geodesic distances as the PLY vertex `distance`
  inspect IN (--vertex N | --edge N | --face N | --point X,Y,Z) [--json]
                                  what the viewer's inspector shows for one element
  select IN OUT --region SPEC [--grow K] [--shrink K] [--invert] [--json]
                                  store a selection as the vertex weight `selection`
  session info|export|recipe|make ...
                                  session files and crash journals (`session --help`)
  replay RECIPE.json IN OUT [--check SESSION] [--json]
                                  run a session's recipe headless; --check compares bit for bit
  help                            this text
  --version                       print "trilab-cli VERSION" (the project's version)

every command: --threads N        the threads of the parallel passes (0 or left out: every
                                  core; TRILAB_THREADS=N does the same); results are the same
                                  bits for any N (`spectrum --threads 1|2` is its own option)

operations (options: `trilab-cli NAME --help`):
)";

/// kUsage, then one line per registered operation, from its declaration.
std::string usage_text() {
    std::string s = kUsage;
    for (const trilab::OperationDef* def : trilab::operation_defs()) {
        std::string head = "  " + def->name + " [options] IN OUT [--json]";
        head.resize(std::max<std::size_t>(head.size() + 1, 34), ' ');
        s += head + def->label + "\n";
    }
    return s;
}

/// Runs command `cmd` on `args`; returns its exit code, or nothing for an unknown command.
std::optional<int> run_command(const std::string& cmd, const std::vector<std::string>& args) {
    if (cmd == "help" || cmd == "--help" || cmd == "-h") {
        std::fputs(usage_text().c_str(), stdout);
        return 0;
    }
    if (cmd == "--version" || cmd == "version") {
        std::printf("trilab-cli %s\n", TRILAB_VERSION);
        return 0;
    }
    if (cmd == "info") return run_info_command(args);
    if (cmd == "convert") return run_convert_command(args);
    if (cmd == "generate") return run_generate_command(args);
    if (cmd == "figures") return run_figures_command(args);
    if (cmd == "render") return run_render_command(args);
    if (cmd == "record") return run_record_command(args);
    if (cmd == "compare") return run_compare_command(args);
    if (cmd == "geodesic") return run_geodesic_command(args);
    if (cmd == "spectrum" && wants_spectrum_filter(args)) return run_spectrum_filter_command(args);
    if (cmd == "inspect") return run_inspect_command(args);
    if (cmd == "select") return run_select_command(args);
    if (cmd == "session") return run_session_command(args);
    if (cmd == "replay") return run_replay_command(args);
    for (const std::string& name : trilab::operation_names())
        if (cmd == name) return run_operation_command(name, args);
    return std::nullopt;
}

/// Takes the global `--threads N` (or `--threads=N`) out of `args` and applies it
/// (core/parallel.h), after TRILAB_THREADS; the operation `cmd` keeps the option when it
/// declares its own "threads" (spectrum's slicing threads). Throws InvalidArgument for a value
/// that does not parse or an option given twice.
void take_threads_option(const std::string& cmd, std::vector<std::string>& args) {
    trilab::apply_thread_environment();
    for (const trilab::OperationDef* def : trilab::operation_defs())
        if (def->name == cmd)
            for (const trilab::ParamSpec& param : def->params)
                if (param.name == "threads") return;
    bool seen = false;
    for (std::size_t i = 0; i < args.size();) {
        std::string value;
        std::size_t taken = 0;
        if (args[i] == "--threads") {
            if (i + 1 >= args.size()) throw trilab::InvalidArgument("--threads: missing value");
            value = args[i + 1];
            taken = 2;
        } else if (args[i].rfind("--threads=", 0) == 0) {
            value = args[i].substr(10);
            taken = 1;
        } else {
            ++i;
            continue;
        }
        if (seen) throw trilab::InvalidArgument("--threads: given more than once");
        seen = true;
        trilab::set_thread_count(trilab::parse_thread_count(value, "--threads"));
        args.erase(args.begin() + std::ptrdiff_t(i), args.begin() + std::ptrdiff_t(i + taken));
    }
}

/// Reports a failure: one line on stderr, "trilab-cli CMD: MESSAGE" (MESSAGE's own "CMD: "
/// prefix, which the core's messages carry, is not repeated; "trilab-cli: MESSAGE" for an
/// unknown command), and with --json one object on stdout. Returns `exit_code`.
int fail(const std::string& cmd, bool known, std::string message, int exit_code, bool json) {
    if (message.rfind(cmd + ": ", 0) == 0) message.erase(0, cmd.size() + 2);
    std::fflush(stdout);
    const std::string prefix = known ? "trilab-cli " + cmd : std::string("trilab-cli");
    std::fprintf(stderr, "%s: %s\n", prefix.c_str(), message.c_str());
    if (json) {
        JsonObject j;
        j.add("command", cmd).add("error", message).add("exit", exit_code);
        std::cout << j.str() << std::endl;
    }
    return exit_code;
}

}  // namespace
}  // namespace trilab::cli

int main(int argc, char** argv) {
    using namespace trilab::cli;
    trilab::tune_heap_for_large_meshes();
    if (argc < 2) {
        std::fputs(usage_text().c_str(), stderr);
        return 2;
    }
    // `--threads N` may also come before the command (`trilab-cli --threads 2 smooth ...`).
    int first = 1;
    std::vector<std::string> leading;
    while (first < argc && std::string(argv[first]).rfind("--threads", 0) == 0) {
        leading.push_back(argv[first]);
        if (std::string(argv[first]) == "--threads" && first + 1 < argc)
            leading.push_back(argv[++first]);
        ++first;
    }
    if (first >= argc) {
        std::fputs(usage_text().c_str(), stderr);
        return 2;
    }
    const std::string cmd = argv[first];
    std::vector<std::string> args(argv + first + 1, argv + argc);
    args.insert(args.end(), leading.begin(), leading.end());
    // --json anywhere among the arguments asks for a JSON answer, a failure's included.
    const bool json = std::find(args.begin(), args.end(), "--json") != args.end();
    try {
        take_threads_option(cmd, args);
        if (const std::optional<int> exit_code = run_command(cmd, args)) return *exit_code;
        return fail(cmd, false, "unknown command '" + cmd + "' (try `trilab-cli help`)", 2, json);
    } catch (const trilab::RunStopped& e) {
        return fail(cmd, true, std::string("stopped early: ") + e.what(), 4, json);
    } catch (const trilab::Error& e) {
        return fail(cmd, true, e.what(), 1, json);
    } catch (const std::exception& e) {
        return fail(cmd, true, std::string("internal error: ") + e.what(), 3, json);
    }
}
