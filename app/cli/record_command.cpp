// `trilab-cli record`: an operation's morph rendered offscreen into numbered PNG frames (and
// an MP4 through ffmpeg when asked for and available). See record_command.h.
#include "app/cli/record_command.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <filesystem>
#include <fstream>
#include <future>
#include <iostream>
#include <limits>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "app/cli/arg_reader.h"
#include "app/cli/json_writer.h"
#include "app/cli/legend_output.h"
#include "app/history/history.h"
#include "app/ops/operation.h"
#include "core/algorithms/coloring.h"
#include "core/algorithms/morph.h"
#include "core/algorithms/texcoords.h"
#include "core/errors.h"
#include "core/io/image_io.h"
#include "core/io/mesh_io.h"
#include "core/progress.h"

#ifdef TRILAB_HAS_RENDER
#include "render/camera.h"
#include "render/mesh_renderer.h"
#include "render/offscreen.h"
#endif

extern char** environ;

namespace trilab::cli {
namespace {

namespace fs = std::filesystem;

constexpr int kMinFrames = 2, kMaxFrames = 100000;
constexpr int kMaxSide = 16384;
constexpr int kMaxFps = 1000;

constexpr const char* kRecordUsage =
    R"(usage: trilab-cli record MESH --op "OPERATION" --out DIR [options]

Loads MESH, runs OPERATION on it (e.g. "noise --amount 2 --seed 7") and renders the morph
from the mesh before it to the mesh after it without a window (EGL surfaceless context;
Mesa's llvmpipe on machines without a GPU) into DIR/frame_0000.png, DIR/frame_0001.png, ...
The camera frames every state of the morph at once and stays fixed, so nothing leaves the
picture. Colourings are computed once on the shape the morph ends in, so colours stay on
their vertices while they move.

options:
  --op "OPERATION"      the operation and its parameters (required)
  --out DIR             the folder for the frames (required; created when missing)
  --frames N            number of frames, 2 to 100000 (default 60); frame i shows the morph
                        at t = ease(i / (N - 1)), from the mesh before (first frame) to the
                        mesh after (last frame)
  --size WxH            frame size in pixels (default 1280x720)
  --mode MODE           gouraud (default), flat, wireframe, hidden-line, points, textured
  --color QUANTITY      colour the vertices: none (default), normal, k1, k2, mean,
                        gaussian, shape-index
  --view AZ,EL          view direction in degrees: azimuth around the up axis from the
                        front, elevation above the horizontal plane (default 0,0)
  --up y|z              the model's up axis (default y): +y up with the front at +z, or
                        +z up with the front at -y; also the pole axis of the spherical
                        projection of textured mode
  --easing EASING       linear (default), smoothstep, cubic (ease in and out)
  --name NAME           file names NAME_0000.png ... (default frame; at least 4 digits)
  --mp4                 also encode DIR/NAME.mp4 (H.264, yuv420p) when ffmpeg is on the
                        PATH; without ffmpeg the frames are still written and a note says so
  --fps N               frame rate of the MP4, 1 to 1000 (default 30)
  --json                print one JSON object ("ms": operation and rendering, file reading
                        and writing excluded) and no progress
)";

/// A whole string as a finite number; false on garbage or trailing characters.
bool to_double(const std::string& s, double& out) {
    if (s.empty()) return false;
    char* end = nullptr;
    out = std::strtod(s.c_str(), &end);
    return end == s.c_str() + s.size() && std::isfinite(out);
}

/// A whole string as an integer in [lo, hi].
bool to_int(const std::string& s, int lo, int hi, int& out) {
    double d = 0;
    if (!to_double(s, d) || d != std::floor(d) || d < lo || d > hi) return false;
    out = int(d);
    return true;
}

/// The record command's easing names, plus core's own spellings.
Easing easing_from_name(const std::string& name) {
    if (name == "smoothstep") return Easing::SmoothStep;
    if (name == "cubic") return Easing::EaseInOutCubic;
    try {
        return parse_easing(name);
    } catch (const InvalidArgument&) {
        throw InvalidArgument("--easing: expected linear, smoothstep or cubic, got '" + name + "'");
    }
}

/// Options parsed from the command line, plus what only the command line has.
struct CommandLine {
    RecordOptions options;
    bool json = false, help = false;
};

CommandLine parse_args(const std::vector<std::string>& args) {
    CommandLine c;
    RecordOptions& o = c.options;
    ArgReader reader(args);
    while (reader.next()) {
        const std::string& a = reader.arg();
        auto value = [&] { return reader.value(); };
        if (a == "--help" || a == "-h") {
            c.help = true;
        } else if (a == "--json") {
            c.json = true;
        } else if (a == "--mp4") {
            o.mp4 = true;
        } else if (a == "--op") {
            o.operation = value();
        } else if (a == "--out") {
            o.out_dir = value();
        } else if (a == "--mode") {
            o.mode = value();
        } else if (a == "--color") {
            o.color = value();
        } else if (a == "--easing") {
            o.easing = value();
        } else if (a == "--up") {
            o.up = value();
        } else if (a == "--name") {
            o.name = value();
        } else if (a == "--frames") {
            const std::string v = value();
            if (!to_int(v, kMinFrames, kMaxFrames, o.frames))
                throw InvalidArgument("--frames: expected a whole number from " +
                                      std::to_string(kMinFrames) + " to " +
                                      std::to_string(kMaxFrames) + ", got '" + v + "'");
        } else if (a == "--fps") {
            const std::string v = value();
            if (!to_int(v, 1, kMaxFps, o.fps))
                throw InvalidArgument("--fps: expected a whole number from 1 to " +
                                      std::to_string(kMaxFps) + ", got '" + v + "'");
        } else if (a == "--size") {
            const std::string v = value();
            const std::size_t x = v.find_first_of("xX");
            if (x == std::string::npos || !to_int(v.substr(0, x), 1, kMaxSide, o.width) ||
                !to_int(v.substr(x + 1), 1, kMaxSide, o.height))
                throw InvalidArgument("--size: expected WxH with whole numbers from 1 to " +
                                      std::to_string(kMaxSide) + ", got '" + v + "'");
        } else if (a == "--view") {
            const std::string v = value();
            const std::size_t comma = v.find(',');
            if (comma == std::string::npos || !to_double(v.substr(0, comma), o.azimuth) ||
                !to_double(v.substr(comma + 1), o.elevation))
                throw InvalidArgument(
                    "--view: expected AZIMUTH,ELEVATION in degrees (e.g. 30,20), got '" + v + "'");
        } else if (a.rfind("--", 0) == 0) {
            throw InvalidArgument("unknown option '" + a + "' (see `trilab-cli record --help`)");
        } else if (o.input.empty()) {
            o.input = a;
        } else {
            throw InvalidArgument("unexpected argument '" + a + "': expected one MESH file");
        }
        if (reader.has_unused_value()) throw InvalidArgument(a + " takes no value");
    }
    return c;
}

#ifdef TRILAB_HAS_RENDER
double ms_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

/// Number of digits in the frame numbers: at least 4, enough for the last frame.
int frame_digits(int frames) {
    return std::max(4, int(std::to_string(frames - 1).size()));
}

std::string frame_file_name(const std::string& name, int index, int digits) {
    std::string number = std::to_string(index);
    if (int(number.size()) < digits) number.insert(0, std::size_t(digits) - number.size(), '0');
    return name + "_" + number + ".png";
}

/// The last non-empty line of a text file (at most 300 characters), or "".
std::string last_line(const std::string& path) {
    std::ifstream in(path);
    std::string line, last;
    while (std::getline(in, line))
        if (line.find_first_not_of(" \t\r") != std::string::npos) last = line;
    if (last.size() > 300) last = last.substr(0, 300) + "...";
    return last;
}

/// Runs `argv` (argv[0] a path) with stdin from /dev/null and stdout and stderr into
/// `log`. Returns the exit status, or -1 with `error` set when it did not run or exit.
int run_program(const std::vector<std::string>& argv, const std::string& log, std::string& error) {
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&actions, 1, 2);
    std::vector<char*> args;
    for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    pid_t pid = 0;
    const int rc = posix_spawn(&pid, args[0], &actions, nullptr, args.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (rc != 0) {
        error = std::string("cannot start ") + argv[0] + ": " + std::strerror(rc);
        return -1;
    }
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0) {
        if (errno != EINTR) {
            error = std::string("waiting for ") + argv[0] + ": " + std::strerror(errno);
            return -1;
        }
    }
    if (WIFEXITED(status)) return WEXITSTATUS(status);
    error = argv[0] + std::string(" was stopped by signal ") +
            std::to_string(WIFSIGNALED(status) ? WTERMSIG(status) : 0);
    return -1;
}

/// Encodes the frames into out_dir/name.mp4 with ffmpeg. Returns the MP4's path, or "" with
/// a note saying why there is none.
std::string encode_mp4(const RecordOptions& o, int digits, std::vector<std::string>& notes) {
    const std::string ffmpeg = find_on_path("ffmpeg");
    if (ffmpeg.empty()) {
        notes.push_back(
            "--mp4: ffmpeg is not on the PATH, so no MP4 was written (the PNG "
            "frames are complete)");
        return "";
    }
    if (o.progress) std::fprintf(stderr, "record: encoding the MP4 with %s\n", ffmpeg.c_str());
    // ffmpeg's image2 pattern: a literal '%' in the name is written "%%".
    std::string escaped;
    for (char ch : o.name) escaped += ch == '%' ? std::string("%%") : std::string(1, ch);
    const fs::path dir(o.out_dir);
    const std::string pattern =
        (dir / (escaped + "_%0" + std::to_string(digits) + "d.png")).string();
    const std::string target = (dir / (o.name + ".mp4")).string();
    const std::string partial = (dir / ("." + o.name + ".mp4.part")).string();
    const std::string log = (fs::temp_directory_path() /
                             ("trilab-record-ffmpeg-" + std::to_string(::getpid()) + ".log"))
                                .string();
    const std::vector<std::string> argv = {ffmpeg,
                                           "-nostdin",
                                           "-hide_banner",
                                           "-loglevel",
                                           "error",
                                           "-y",
                                           "-framerate",
                                           std::to_string(o.fps),
                                           "-start_number",
                                           "0",
                                           "-i",
                                           pattern,
                                           "-frames:v",
                                           std::to_string(o.frames),
                                           "-vf",
                                           "pad=ceil(iw/2)*2:ceil(ih/2)*2",
                                           "-c:v",
                                           "libx264",
                                           "-pix_fmt",
                                           "yuv420p",
                                           "-movflags",
                                           "+faststart",
                                           "-f",
                                           "mp4",
                                           partial};
    std::string error;
    const int status = run_program(argv, log, error);
    std::error_code ec;
    if (status == 0) {
        fs::rename(partial, target, ec);
        if (!ec) {
            fs::remove(log, ec);
            return target;
        }
        error = "cannot rename " + partial + " to " + target + ": " + ec.message();
    } else if (status > 0) {
        error = "ffmpeg failed (exit status " + std::to_string(status) + ")";
        const std::string why = last_line(log);
        if (!why.empty()) error += ": " + why;
    }
    fs::remove(partial, ec);
    fs::remove(log, ec);
    notes.push_back("--mp4: " + error + "; no MP4 was written (the PNG frames are complete)");
    return "";
}

#endif  // TRILAB_HAS_RENDER

}  // namespace

/// The executable `program` in a folder of $PATH, or "" when there is none.
std::string find_on_path(const std::string& program) {
    const char* path = std::getenv("PATH");
    if (!path) return "";
    const std::string dirs = path;
    std::size_t start = 0;
    while (start <= dirs.size()) {
        std::size_t end = dirs.find(':', start);
        if (end == std::string::npos) end = dirs.size();
        const std::string dir = end > start ? dirs.substr(start, end - start) : ".";
        const std::string candidate = dir + "/" + program;
        struct stat st {};
        if (::stat(candidate.c_str(), &st) == 0 && S_ISREG(st.st_mode) &&
            ::access(candidate.c_str(), X_OK) == 0)
            return candidate;
        start = end + 1;
    }
    return "";
}

void check_record_options(const RecordOptions& o) {
    if (o.input.empty())
        throw InvalidArgument("expected a MESH file (see `trilab-cli record --help`)");
    if (o.operation.empty())
        throw InvalidArgument("--op is required (e.g. --op \"noise --amount 2\")");
    if (o.out_dir.empty()) throw InvalidArgument("--out DIR is required");
    if (o.frames < kMinFrames || o.frames > kMaxFrames)
        throw InvalidArgument("--frames: expected a whole number from " +
                              std::to_string(kMinFrames) + " to " + std::to_string(kMaxFrames) +
                              ", got " + std::to_string(o.frames));
    if (o.width < 1 || o.height < 1 || o.width > kMaxSide || o.height > kMaxSide)
        throw InvalidArgument("--size: expected WxH with whole numbers from 1 to " +
                              std::to_string(kMaxSide) + ", got " + std::to_string(o.width) + "x" +
                              std::to_string(o.height));
    if (o.fps < 1 || o.fps > kMaxFps)
        throw InvalidArgument("--fps: expected a whole number from 1 to " +
                              std::to_string(kMaxFps) + ", got " + std::to_string(o.fps));
    if (!std::isfinite(o.azimuth) || !std::isfinite(o.elevation))
        throw InvalidArgument("--view: the angles must be finite numbers");
    if (o.name.empty() || o.name == "." || o.name == ".." ||
        o.name.find_first_of(std::string("/\\\0", 3)) != std::string::npos)
        throw InvalidArgument("--name: expected a file name without folders, got '" + o.name + "'");
#ifdef TRILAB_HAS_RENDER
    try {
        parse_render_mode(o.mode);
    } catch (const InvalidArgument& e) {
        throw InvalidArgument(std::string("--mode: ") + e.what());
    }
#endif
    try {
        parse_coloring(o.color);
    } catch (const InvalidArgument& e) {
        throw InvalidArgument(std::string("--color: ") + e.what());
    }
    easing_from_name(o.easing);
    parse_up_axis(o.up, "--up");
    try {
        parse_operation(o.operation);
    } catch (const InvalidArgument& e) {
        throw InvalidArgument(std::string("--op: ") + e.what());
    }
    std::error_code ec;
    if (fs::exists(o.out_dir, ec) && !fs::is_directory(o.out_dir, ec))
        throw InvalidArgument("--out: '" + o.out_dir + "' exists and is not a folder");
}

RecordSummary record_morph(const RecordOptions& o) {
    check_record_options(o);
#ifndef TRILAB_HAS_RENDER
    throw Error("this trilab-cli was built without the renderer (TRILAB_BUILD_VIEWER=OFF)");
#else
    const Operation operation = parse_operation(o.operation);
    const Easing easing = easing_from_name(o.easing);
    const VertexColoring coloring = parse_coloring(o.color);
    const UpAxis up = parse_up_axis(o.up, "--up");
    RenderStyle style;
    style.mode = parse_render_mode(o.mode);
    const bool textured = style.mode == RenderMode::Textured;

    RecordSummary s;
    s.frames = o.frames;
    s.width = o.width;
    s.height = o.height;
    s.mode = render_mode_name(style.mode);
    s.color = coloring_name(coloring);
    s.easing = easing_name(easing);
    s.up = up_axis_name(up);

    // File input (not timed).
    LoadedMesh loaded = read_mesh(o.input);
    HalfedgeMesh& mesh = loaded.mesh;
    s.vertices_before = mesh.n_vertices();
    s.faces_before = mesh.n_faces();

    const auto t_op = std::chrono::steady_clock::now();
    if (textured && !has_texcoords(mesh)) {
        // Projected once, on the loaded shape, so the texture travels with the vertices.
        project_texcoords(mesh, TexCoordProjection::Spherical, up);
        s.notes.push_back(
            "the mesh has no texture coordinates: textured mode uses a spherical projection "
            "of the loaded shape around its centroid (the poles on the up axis, +" +
            std::string(up_axis_name(up)) + ")");
    }
    NullProgress no_progress;
    OperationResult result;
    try {
        result = run_operation(operation, mesh, no_progress);
    } catch (const InvalidArgument& e) {
        throw InvalidArgument(std::string("--op: ") + e.what());
    }
    if (result.steps.empty()) throw Error("--op: the operation returned no result");
    s.label = result.label;
    s.parameters = result.parameters;
    s.operation_report = result.report;
    s.operation_values = result.values;
    s.steps = result.steps.size();
    s.vertices_after = result.steps.back().mesh.n_vertices();
    s.faces_after = result.steps.back().mesh.n_faces();

    // The framing: every vertex of every state (and where a changed connectivity starts or
    // ends on the other surface), so that each vertex's straight path stays in the view.
    std::vector<glm::vec3> points;
    auto add_points = [&](const HalfedgeMesh& m, const std::vector<Point>* positions) {
        for (Vertex v : m.vertices()) {
            const Point& p = positions ? (*positions)[v.idx()] : m.position(v);
            points.emplace_back(float(p.x()), float(p.y()), float(p.z()));
        }
    };
    add_points(mesh, nullptr);
    for (std::size_t k = 0; k < result.steps.size(); ++k) {
        const OperationStep& step = result.steps[k];
        const HalfedgeMesh& before = k == 0 ? mesh : result.steps[k - 1].mesh;
        add_points(step.mesh, nullptr);
        const std::vector<Point>& cp = step.correspondence.positions;
        if (step.correspondence.kind == MorphCorrespondence::Kind::FromEarlier &&
            cp.size() == step.mesh.vertices_size())
            add_points(step.mesh, &cp);
        else if (step.correspondence.kind == MorphCorrespondence::Kind::ToLater &&
                 cp.size() == before.vertices_size())
            add_points(before, &cp);
    }

    // The snapshot stack: the loaded mesh, then the operation's entry (index 1). No budget:
    // both entries must stay.
    History history(std::numeric_limits<std::size_t>::max());
    history.reset(mesh, "Load", o.input);
    {
        std::vector<HalfedgeMesh> meshes;
        std::vector<MorphCorrespondence> correspondences;
        for (OperationStep& step : result.steps) {
            meshes.push_back(std::move(step.mesh));
            correspondences.push_back(std::move(step.correspondence));
        }
        for (std::string& m : history.push(result.label, result.parameters, result.ms,
                                           std::move(meshes), std::move(correspondences)))
            s.notes.push_back(std::move(m));
    }
    s.operation_ms = ms_since(t_op);

    // The headless context. Members are destroyed in reverse order: the GL objects first.
    const auto t_context = std::chrono::steady_clock::now();
    struct Gl {
        OffscreenContext context;
        MeshRenderer renderer;
        Framebuffer framebuffer;
    } gl;
    OffscreenOptions defaults;
    gl.framebuffer.create(o.width, o.height, defaults.samples);
    if (textured) gl.renderer.set_texture(make_checkerboard());
    s.renderer = gl.context.description();
    Camera camera;
    camera.set_viewport(float(o.width), float(o.height));
    camera.set_view_angles(float(o.azimuth), float(o.elevation), up);
    camera.fit_points_in_view(points, defaults.margin);
    const glm::mat4 view = camera.view(), projection = camera.projection();
    s.context_ms = ms_since(t_context);

    // Output folder: only now, after everything that can refuse the options ran.
    std::error_code ec;
    fs::create_directories(o.out_dir, ec);
    if (ec || !fs::is_directory(o.out_dir))
        throw IoError(o.out_dir, 0,
                      "cannot create the output folder" + (ec ? ": " + ec.message() : ""));

    // The last shape that topology `topology` shows (it is shown at t): the end state when
    // the morph ends on it, otherwise the limit where it is replaced (bisection over t).
    auto last_shape = [&](const HalfedgeMesh* topology, double t) {
        MorphFrame end = history.morph(1, 1.0);
        if (end.topology == topology) return std::move(end.positions);
        double lo = t, hi = 1.0;
        for (int k = 0; k < 64; ++k) {
            const double mid = lo + 0.5 * (hi - lo);
            if (!(mid > lo && mid < hi)) break;
            (history.morph(1, mid).topology == topology ? lo : hi) = mid;
        }
        return history.morph(1, lo).positions;
    };

    const int digits = frame_digits(o.frames);
    const fs::path dir(o.out_dir);
    const HalfedgeMesh* shown = nullptr;
    std::size_t shown_vertices = 0;
    // PNG encoding costs more than drawing: earlier frames are written on other threads
    // meanwhile, a few at once where cores allow (one for huge frames, to bound memory).
    std::deque<std::future<double> > pending_writes;
    const std::size_t frame_bytes = std::size_t(o.width) * std::size_t(o.height) * 4;
    const std::size_t max_pending =
        frame_bytes > (std::size_t(64) << 20)
            ? 1
            : std::size_t(std::clamp(int(std::thread::hardware_concurrency()), 1, 4));
    auto last_report = std::chrono::steady_clock::now();
    bool reported = false;
    for (int i = 0; i < o.frames; ++i) {
        const auto t_frame = std::chrono::steady_clock::now();
        const double t = ease(easing, double(i) / double(o.frames - 1));
        MorphFrame frame = history.morph(1, t);
        if (frame.topology != shown || frame.topology->vertices_size() != shown_vertices) {
            shown = frame.topology;
            shown_vertices = shown->vertices_size();
            gl.renderer.upload(*shown);
            if (coloring != VertexColoring::None) {
                HalfedgeMesh shape = *shown;
                shape.set_positions(last_shape(shown, t));
                if (shape.has_vertex_property("v:normal")) shape.remove_vertex_property("v:normal");
                const VertexColors colors = color_vertices(shape, coloring);
                gl.renderer.set_vertex_colors(colors.colors);
                ++s.colorings;
                s.legend = colors;
                s.legend.colors.clear();  // the legend, not the colours
            }
        }
        gl.renderer.update_positions(*shown, frame.positions);
        gl.framebuffer.bind();
        clear_background(style, 1.0f);
        gl.renderer.draw(view, projection, style);
        Image image = gl.framebuffer.read_rgba();
        Framebuffer::bind_default();
        s.render_ms += ms_since(t_frame);

        while (pending_writes.size() >= max_pending) {
            s.write_ms += pending_writes.front().get();
            pending_writes.pop_front();
        }
        const std::string path = (dir / frame_file_name(o.name, i, digits)).string();
        s.files.push_back(path);
        pending_writes.push_back(std::async(std::launch::async, [path, picture = std::move(image)] {
            const auto t_write = std::chrono::steady_clock::now();
            write_png(picture, path);
            return ms_since(t_write);
        }));
        // Progress: a line every 2 seconds or so, and the last frame once any was printed.
        if (o.progress && (ms_since(last_report) >= 2000.0 || (reported && i + 1 == o.frames))) {
            std::fprintf(stderr, "record: %d/%d frames\n", i + 1, o.frames);
            last_report = std::chrono::steady_clock::now();
            reported = true;
        }
    }
    for (std::future<double>& w : pending_writes) s.write_ms += w.get();
    s.ms = s.operation_ms + s.context_ms + s.render_ms;
    if (fs::exists(dir / frame_file_name(o.name, o.frames, digits), ec))
        s.notes.push_back("the folder also holds frames of an earlier, longer recording (from " +
                          frame_file_name(o.name, o.frames, digits) + " on)" +
                          (o.mp4 ? "; the MP4 leaves them out" : ""));

    if (o.mp4) {
        const auto t_encode = std::chrono::steady_clock::now();
        s.mp4 = encode_mp4(o, digits, s.notes);
        s.encode_ms = ms_since(t_encode);
    }
    return s;
#endif
}

int run_record_command(const std::vector<std::string>& args) {
    CommandLine c = parse_args(args);
    if (c.help) {
        std::fputs(kRecordUsage, stdout);
        return 0;
    }
    c.options.progress = !c.json;
    const RecordSummary s = record_morph(c.options);
    if (c.json) {
        JsonObject values;
        for (const auto& [key, number] : s.operation_values) values.add(key, number);
        JsonObject op;
        op.add("text", c.options.operation)
            .add("label", s.label)
            .add("parameters", s.parameters)
            .add("steps", s.steps)
            .add("values", values)
            .add("report", s.operation_report)
            .add("ms", s.operation_ms);
        JsonObject j;
        j.add("input", c.options.input)
            .add("output", c.options.out_dir)
            .add("operation", op)
            .add("frames", s.frames)
            .add("files", std::vector<std::string>{s.files.front(), s.files.back()});
        if (s.mp4.empty())
            j.add_null("mp4");
        else
            j.add("mp4", s.mp4);
        j.add("width", s.width).add("height", s.height).add("mode", s.mode).add("color", s.color);
        add_legend(j, s.legend);
        j.add("easing", s.easing)
            .add("view", std::vector<double>{c.options.azimuth, c.options.elevation})
            .add("up", s.up)
            .add("vertices_before", s.vertices_before)
            .add("faces_before", s.faces_before)
            .add("vertices_after", s.vertices_after)
            .add("faces_after", s.faces_after)
            .add("renderer", s.renderer)
            .add("notes", s.notes)
            .add("operation_ms", s.operation_ms)
            .add("context_ms", s.context_ms)
            .add("render_ms", s.render_ms)
            .add("write_ms", s.write_ms)
            .add("encode_ms", s.encode_ms)
            .add("ms", s.ms);
        std::cout << j.str() << "\n";
    } else {
        std::printf("wrote %d frames %s ... %s: %dx%d, %s", s.frames, s.files.front().c_str(),
                    s.files.back().c_str(), s.width, s.height, s.mode.c_str());
        if (s.legend.has_legend)
            std::printf(", %s", legend_text(s.legend).c_str());
        else if (s.color != "none")
            std::printf(", %s colouring", s.color.c_str());
        std::printf("; %s %s (%.1f ms operation + rendering; %s)\n", s.label.c_str(),
                    s.parameters.c_str(), s.ms, s.renderer.c_str());
        if (!s.mp4.empty()) std::printf("wrote %s\n", s.mp4.c_str());
        for (const std::string& n : s.notes) std::printf("note: %s\n", n.c_str());
    }
    return 0;
}

}  // namespace trilab::cli
