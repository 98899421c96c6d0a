// trilab: the interactive viewer. Shows a mesh file, or the built-in noisy sphere when none is
// given. Exit status: 0 on a normal exit, 1 when the window, the GL context or a requested
// screenshot fails, 2 for bad command-line arguments. A mesh file that cannot be read is not
// fatal: the error goes to stderr and to the window, and the default model stays.

#include <cmath>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "app/platform/heap_tuning.h"
#include "app/platform/termination.h"
#include "app/viewer/viewer.h"
#include "core/parallel.h"
#include "trilab/version.h"

#include <GLFW/glfw3.h>  // after glad (viewer.h): glfwPostEmptyEvent

namespace {

constexpr const char* kUsage = R"(usage: trilab [options] [MESH | SESSION.trilab]

Shows MESH (.obj .off .ply .stl .om), or the built-in noisy sphere without one; a session
file (File > Save session) or a crash journal restores its whole history, view and panels.

options:
  --size WxH         window size in screen coordinates (default 1280x800)
  --frames N         render N frames, then exit (for tests and screenshots)
  --screenshot FILE  write the last frame as PNG before exiting (needs --frames); the
                     last frame waits until jobs, previews and the morph animation end
  --morph-t T        show the current entry's morph at time T in [0, 1] in the last frame
  --print-layout     after the last frame print "framebuffer W H", "view X Y W H" and
                     one line 'window "TITLE" X Y W H' per visible window (needs --frames)
  --ui-scale S       scale the panels and fonts by S in [0.5, 4] (default: the monitor's)
  --wireframe W      the wireframe overlay: on, off or auto (default: on while the edges
                     are long enough on the screen)
  --close-after N    press the window's close button after N frames (tests the
                     unsaved-changes question)
  --mode MODE        wireframe, hidden-line, flat, gouraud, points or textured
  --color C          none, normal, k1, k2, mean, gaussian, shape-index, subdivision,
                     smoothing-distance, frequency, frequency-mass, min-angle or quality
  --up y|z           the model's up axis for this run (default: the one chosen in
                     View > Up axis, remembered; +y at first)
  --op "OPERATION"   apply an operation after loading, e.g. --op "noise --amount 2";
                     repeatable: applied in order, each after the one before finished
  --save-session FILE  write the whole session (history, view, panels) to FILE.trilab
                     after the last frame (needs --frames)
  --restore          restore the newest crash journal without asking
  --no-recovery      no crash journal for this run, and no question about old ones
  --click "SECTION/LABEL"  press the widget with that visible label in that sidebar section
                     (or menu path, e.g. "File/Save as"), after --op; repeatable, in order;
                     fails when there is no such widget or more than one
  --pick X,Y         pick the model at window pixel X,Y once it is shown (repeatable: the
                     second pick measures from the first); prints "pick: vertex V edge E
                     face F position X Y Z ms T" and opens the Inspector
  --select SPEC      set the selection (one history entry each, in order, before --op):
                     sphere:X,Y,Z,R[,FEATHER], geodesic:V,R[,FEATHER], component:V or
                     file:PATH (as trilab-cli --region); repeatable
  --brush "X0,Y0:X1,Y1[:R]"  drag the selection brush (adding; radius R pixels, default
                     30) from window pixel X0,Y0 to X1,Y1 once the model is shown, and
                     print "brush: samples=N median_ms=X max_ms=Y"
  --lasso "X0,Y0:X1,Y1:X2,Y2[:...][:through]"  draw the selection lasso (adding) through
                     these window pixels (three or more) once the model is shown, as the
                     mouse does with Ctrl held, over several frames; ":through" also takes
                     the vertices hidden behind the surface; prints "lasso: vertices=N"
  --figure NAME      load a reference figure's mesh kind and settings (e.g. 1.12b; the
                     list is in Help > Reference figures and docs/viewer.md)
  --orbit N          once the model is shown and no job runs, turn the camera once around
                     the model in N frames as if dragged, rest, then print "orbit:
                     frames=N median_ms=X max_ms=Y rest_ms=Z"
  --print-timing     after the last frame print "timing: first_frame_ms=X exact_frame_ms=Y"
  --memory-budget MB the history's memory budget (default: a quarter of the RAM)
  --decompose K[:LO:HI]  decompose the model into K frequencies (the Frequency panel's
                     settings) and apply the band LO..HI, for scripts and tests
  --sweep "OPERATION" --param NAME --range FROM:TO:COUNT
                     open OPERATION's panel, set NAME to COUNT evenly spaced values, wait
                     for each live preview to show, then print
                     "sweep: previews=N median_ms=X max_ms=Y" and exit
  --show PANELS      open panels at start: comma-separated all, tools (every tool), history,
                     morph, subdivision, fairing, frequency, decimation, collapsing-edges,
                     record, log, info, a tool by its operation's name (noise, weld,
                     remove-components), and the dialogs help, about, screenshot
  --threads N        threads of the parallel passes (0: every core, the default; also
                     TRILAB_THREADS); results are the same bits for any N
  --help             this text
  --version          print "trilab VERSION" (the project's version) and exit
)";

/// Parses "WxH" with both numbers in [1, 16384].
bool parse_size(const std::string& text, int& width, int& height) {
    int w = 0, h = 0;
    char x = 0, rest = 0;
    if (std::sscanf(text.c_str(), "%d%c%d%c", &w, &x, &h, &rest) != 3 || (x != 'x' && x != 'X'))
        return false;
    if (w < 1 || h < 1 || w > 16384 || h > 16384) return false;
    width = w;
    height = h;
    return true;
}

bool parse_count(const std::string& text, int& value) {
    int n = 0;
    char rest = 0;
    if (std::sscanf(text.c_str(), "%d%c", &n, &rest) != 1 || n < 1) return false;
    value = n;
    return true;
}

/// The options that need or exclude each other; returns an error message, or "".
std::string check_combinations(const trilab::viewer::ViewerOptions& options) {
    if (!options.screenshot.empty() && options.frames == 0) return "--screenshot needs --frames N";
    if (options.print_layout && options.frames == 0) return "--print-layout needs --frames N";
    if (options.morph_t >= 0 && options.frames == 0) return "--morph-t needs --frames N";
    if (!options.save_session.empty() && options.frames == 0)
        return "--save-session needs --frames N";
    if (options.restore && options.no_recovery)
        return "--restore and --no-recovery exclude each other";
    if (options.restore && !options.mesh_path.empty())
        return "--restore restores a crash journal: give no MESH with it";
    if (options.sweep_op.empty() != options.sweep_param.empty() ||
        options.sweep_op.empty() != (options.sweep_count == 0))
        return "--sweep, --param and --range go together";
    if (!options.lasso.empty()) {
        std::vector<glm::vec2> points;
        bool through = false;
        const std::string error =
            trilab::viewer::parse_lasso_script(options.lasso, points, through);
        if (!error.empty()) return "--lasso \"" + options.lasso + "\": " + error;
    }
    return "";
}

/// --threads N: the parallel passes' threads (core/parallel.h; the same bits for any count).
/// Returns false with `error` set when N does not parse.
bool apply_threads(const std::string& text, std::string& error) {
    try {
        trilab::set_thread_count(trilab::parse_thread_count(text, "--threads"));
        return true;
    } catch (const std::exception& e) {
        error = e.what();
        return false;
    }
}

/// Fills `options`; returns an error message, or "" on success.
std::string parse_args(int argc, char** argv, trilab::viewer::ViewerOptions& options, bool& help) {
    std::string error = "--threads needs a count (0: every core)";
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        auto value = [&](std::string& out) {
            if (i + 1 >= argc) return false;
            out = argv[++i];
            return true;
        };
        std::string v;
        if (arg == "--help" || arg == "-h") {
            help = true;
        } else if (arg == "--threads") {
            if (!value(v) || !apply_threads(v, error)) return error;
        } else if (arg == "--size") {
            if (!value(v) || !parse_size(v, options.width, options.height))
                return "--size needs WxH, e.g. 1280x800";
        } else if (arg == "--frames") {
            if (!value(v) || !parse_count(v, options.frames))
                return "--frames needs a positive number";
        } else if (arg == "--close-after") {
            if (!value(v) || !parse_count(v, options.close_after))
                return "--close-after needs a positive number";
        } else if (arg == "--screenshot") {
            if (!value(options.screenshot) || options.screenshot.empty())
                return "--screenshot needs a file name";
        } else if (arg == "--print-layout") {
            options.print_layout = true;
        } else if (arg == "--ui-scale") {
            char rest = 0;
            if (!value(v) || std::sscanf(v.c_str(), "%f%c", &options.ui_scale, &rest) != 1 ||
                !(options.ui_scale >= 0.5f && options.ui_scale <= 4.0f))
                return "--ui-scale needs a number in [0.5, 4]";
        } else if (arg == "--wireframe") {
            if (!value(options.wireframe) ||
                (options.wireframe != "on" && options.wireframe != "off" &&
                 options.wireframe != "auto"))
                return "--wireframe needs on, off or auto";
        } else if (arg == "--morph-t") {
            char rest = 0;
            if (!value(v) || std::sscanf(v.c_str(), "%lf%c", &options.morph_t, &rest) != 1 ||
                !(options.morph_t >= 0.0 && options.morph_t <= 1.0))
                return "--morph-t needs a time in [0, 1]";
        } else if (arg == "--mode") {
            if (!value(options.mode)) return "--mode needs a name";
        } else if (arg == "--memory-budget") {
            if (!value(v) || !parse_count(v, options.memory_budget_mb))
                return "--memory-budget needs a positive number of megabytes";
        } else if (arg == "--show") {
            if (!value(options.show)) return "--show needs panel names, e.g. history,morph";
        } else if (arg == "--click") {
            if (!value(v) || v.empty())
                return "--click needs a widget, e.g. \"Record/Record\" or \"File/Save as\"";
            options.clicks.push_back(v);
        } else if (arg == "--pick") {
            if (!value(v) || v.empty()) return "--pick needs window pixels X,Y, e.g. 640,400";
            options.picks.push_back(v);
        } else if (arg == "--select") {
            if (!value(v) || v.empty()) return "--select needs a region, e.g. sphere:0,0,0,0.5";
            options.selections.push_back(v);
        } else if (arg == "--brush") {
            if (!value(options.brush) || options.brush.empty())
                return "--brush needs \"X0,Y0:X1,Y1[:R]\", e.g. \"600,400:700,420:30\"";
        } else if (arg == "--lasso") {
            if (!value(options.lasso) || options.lasso.empty())
                return "--lasso needs \"X0,Y0:X1,Y1:X2,Y2[:...]\", e.g. "
                       "\"600,300:760,300:700,460\"";
        } else if (arg == "--figure") {
            if (!value(options.figure) || options.figure.empty())
                return "--figure needs a reference figure, e.g. 1.12b";
        } else if (arg == "--orbit") {
            if (!value(v) || !parse_count(v, options.orbit_frames))
                return "--orbit needs a positive number of frames";
        } else if (arg == "--print-timing") {
            options.print_timing = true;
        } else if (arg == "--op") {
            if (!value(v) || v.empty()) return "--op needs an operation, e.g. \"noise --amount 2\"";
            options.operations.push_back(v);
        } else if (arg == "--save-session") {
            if (!value(options.save_session) || options.save_session.empty())
                return "--save-session needs a file name, e.g. session.trilab";
        } else if (arg == "--restore") {
            options.restore = true;
        } else if (arg == "--no-recovery") {
            options.no_recovery = true;
        } else if (arg == "--sweep") {
            if (!value(options.sweep_op) || options.sweep_op.empty())
                return "--sweep needs an operation, e.g. \"smooth --iterations 10\"";
        } else if (arg == "--param") {
            if (!value(options.sweep_param) || options.sweep_param.empty())
                return "--param needs a parameter name";
        } else if (arg == "--range") {
            char colon1 = 0, colon2 = 0, rest = 0;
            if (!value(v) ||
                std::sscanf(v.c_str(), "%lf%c%lf%c%d%c", &options.sweep_from, &colon1,
                            &options.sweep_to, &colon2, &options.sweep_count, &rest) != 5 ||
                colon1 != ':' || colon2 != ':' || options.sweep_count < 1 ||
                !std::isfinite(options.sweep_from) || !std::isfinite(options.sweep_to))
                return "--range needs FROM:TO:COUNT, e.g. 0.1:1:20";
        } else if (arg == "--decompose") {
            if (!value(options.decompose)) return "--decompose needs K or K:LO:HI";
        } else if (arg == "--color") {
            if (!value(options.color)) return "--color needs a name";
        } else if (arg == "--up") {
            if (!value(options.up) || (options.up != "y" && options.up != "z"))
                return "--up needs y or z";
        } else if (arg.size() > 1 && arg[0] == '-') {
            return "unknown option '" + arg + "'";
        } else if (options.mesh_path.empty()) {
            options.mesh_path = arg;
        } else {
            return "more than one mesh file given ('" + arg + "')";
        }
    }
    return check_combinations(options);
}

}  // namespace

int main(int argc, char** argv) {
    // llvmpipe page-faults on every frame when glibc keeps trimming and unmapping its large
    // buffers (docs/toolchain.md, section 5): keep big blocks mapped.
    trilab::tune_heap_for_large_meshes();
    // SIGTERM and SIGHUP end the viewer like a quit that keeps its journal (termination.h);
    // first, so that every thread inherits the blocked signals.
    trilab::watch_termination([] { glfwPostEmptyEvent(); });

    for (int i = 1; i < argc; ++i)
        if (std::string(argv[i]) == "--version") {
            std::printf("trilab %s\n", TRILAB_VERSION);
            return 0;
        }
    trilab::viewer::ViewerOptions options;
    bool help = false;
    std::string error;
    try {
        trilab::apply_thread_environment();  // TRILAB_THREADS, before --threads overrides it
    } catch (const std::exception& e) {
        error = e.what();
    }
    if (error.empty()) error = parse_args(argc, argv, options, help);
    if (help) {
        std::fputs(kUsage, stdout);
        return 0;
    }
    if (!error.empty()) {
        std::fprintf(stderr, "trilab: %s\n%s", error.c_str(), kUsage);
        return 2;
    }
    try {
        trilab::viewer::Viewer viewer(options);
        return viewer.run();
    } catch (const std::exception& e) {
        std::fprintf(stderr, "trilab: %s\n", e.what());
        return 1;
    }
}
