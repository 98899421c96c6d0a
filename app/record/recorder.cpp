// Recording an operation's morph into numbered PNG frames (and an MP4 through ffmpeg when
// asked for and available). See recorder.h.
#include "app/record/recorder.h"

#include <sys/stat.h>
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
#include <limits>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "app/history/history.h"
#include "app/ops/operation.h"
#include "app/record/mp4_encoder.h"
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

namespace trilab::record {
namespace {

namespace fs = std::filesystem;

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

#ifdef TRILAB_HAS_RENDER
double ms_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

/// Number of digits in the frame numbers: at least 4, enough for the last frame.
int frame_digits(int frames) {
    return std::max(4, int(std::to_string(frames - 1).size()));
}

/// Encodes the frames into out_dir/name.mp4 with ffmpeg (mp4_encoder.h). Returns the MP4's
/// path, or "" with a note saying why there is none.
std::string encode_mp4(const RecordOptions& o, int digits, std::vector<std::string>& notes) {
    if (o.progress) std::fprintf(stderr, "record: encoding the MP4 with ffmpeg\n");
    std::string note;
    const std::string mp4 =
        record::encode_mp4(Mp4Request{o.out_dir, o.name, o.frames, o.fps, digits}, note);
    if (mp4.empty()) notes.push_back("--mp4: " + note);
    return mp4;
}

// ---- the stages of record_morph(), in the order it runs them ---------------------------------

/// The summary's sizes and canonical names, before anything runs.
RecordSummary start_summary(const RecordOptions& o, const RenderStyle& style,
                            VertexColoring coloring, Easing easing, UpAxis up) {
    RecordSummary s;
    s.frames = o.frames;
    s.width = o.width;
    s.height = o.height;
    s.mode = render_mode_name(style.mode);
    s.color = coloring_name(coloring);
    s.easing = easing_name(easing);
    s.up = up_axis_name(up);
    return s;
}

/// Runs the operation on `mesh` (texture coordinates projected first when textured mode needs
/// them) and records what it did in the summary. An operation refusing its parameters is an
/// --op error.
OperationResult run_recorded_operation(const Operation& operation, HalfedgeMesh& mesh,
                                       bool textured, UpAxis up, RecordSummary& s) {
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
    return result;
}

/// The points the camera frames: every vertex of every state (and where a changed
/// connectivity starts or ends on the other surface), so that each vertex's straight path
/// stays in the view.
std::vector<glm::vec3> framing_points(const HalfedgeMesh& mesh, const OperationResult& result) {
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
    return points;
}

/// The snapshot stack: the loaded mesh, then the operation's entry (index 1), its steps moved
/// out of `result`. No budget: both entries must stay. The history's notes go to the summary.
void push_into_history(History& history, const HalfedgeMesh& mesh, OperationResult& result,
                       const std::string& input, RecordSummary& s) {
    history.reset(mesh, "Load", input);
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

/// The headless context. Members are destroyed in reverse order: the GL objects first.
struct RecordGl {
    OffscreenContext context;
    MeshRenderer renderer;
    Framebuffer framebuffer;
};

/// The frame buffer, the checkerboard of textured mode, and the camera that frames `points`
/// from the options' view direction, fixed for every frame.
Camera set_up_gl(RecordGl& gl, const RecordOptions& o, bool textured, UpAxis up,
                 const std::vector<glm::vec3>& points) {
    OffscreenOptions defaults;
    gl.framebuffer.create(o.width, o.height, defaults.samples);
    if (textured) gl.renderer.set_texture(make_checkerboard());
    Camera camera;
    camera.set_viewport(float(o.width), float(o.height));
    camera.set_view_angles(float(o.azimuth), float(o.elevation), up);
    camera.fit_points_in_view(points, defaults.margin);
    return camera;
}

/// The output folder, created only after everything that can refuse the options ran.
void create_output_folder(const std::string& dir) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec || !fs::is_directory(dir))
        throw IoError(dir, 0, "cannot create the output folder" + (ec ? ": " + ec.message() : ""));
}

/// The last shape that topology `topology` shows (it is shown at t): the end state when the
/// morph of entry 1 ends on it, otherwise the limit where it is replaced (bisection over t).
std::vector<Point> last_shape(const History& history, const HalfedgeMesh* topology, double t) {
    MorphFrame end = history.morph(1, 1.0);
    if (end.topology == topology) return std::move(end.positions);
    double lo = t, hi = 1.0;
    for (int k = 0; k < 64; ++k) {
        const double mid = lo + 0.5 * (hi - lo);
        if (!(mid > lo && mid < hi)) break;
        (history.morph(1, mid).topology == topology ? lo : hi) = mid;
    }
    return history.morph(1, lo).positions;
}

/// Uploads a newly shown topology and, with a colouring, colours it on its last shape, so the
/// colours stay on the vertices while they move. The legend goes to the summary.
void show_topology(MeshRenderer& renderer, const History& history, const HalfedgeMesh& shown,
                   double t, VertexColoring coloring, RecordSummary& s) {
    renderer.upload(shown);
    if (coloring == VertexColoring::None) return;
    HalfedgeMesh shape = shown;
    shape.set_positions(last_shape(history, &shown, t));
    if (shape.has_vertex_property("v:normal")) shape.remove_vertex_property("v:normal");
    const VertexColors colors = color_vertices(shape, coloring);
    renderer.set_vertex_colors(colors.colors, color_blend(colors.kind));
    ++s.colorings;
    s.legend = colors;
    s.legend.colors.clear();  // the legend, not the colours
}

/// Writes the frames' PNG files. PNG encoding costs more than drawing: earlier frames are
/// written on other threads meanwhile, a few at once where cores allow (one for huge frames,
/// to bound memory). Adds the writing times to `write_ms`.
class FrameWriter {
public:
    FrameWriter(int width, int height, double& write_ms) : write_ms_(write_ms) {
        const std::size_t frame_bytes = std::size_t(width) * std::size_t(height) * 4;
        max_pending_ =
            frame_bytes > (std::size_t(64) << 20)
                ? 1
                : std::size_t(std::clamp(int(std::thread::hardware_concurrency()), 1, 4));
    }
    /// Queues `image` for `path`, first waiting while too many writes are under way.
    void write(Image image, const std::string& path) {
        while (pending_.size() >= max_pending_) {
            write_ms_ += pending_.front().get();
            pending_.pop_front();
        }
        pending_.push_back(std::async(std::launch::async, [path, picture = std::move(image)] {
            const auto t_write = std::chrono::steady_clock::now();
            write_png(picture, path);
            return ms_since(t_write);
        }));
    }
    /// Waits for every write; rethrows a write's error.
    void finish() {
        for (std::future<double>& w : pending_) write_ms_ += w.get();
        pending_.clear();
    }

private:
    double& write_ms_;
    std::size_t max_pending_ = 1;
    std::deque<std::future<double>> pending_;
};

/// Renders frame i = 0 .. frames - 1 of entry 1's morph at t = ease(i / (frames - 1)) and
/// writes it, with a progress line every 2 seconds or so (and the last frame once any was
/// printed) when asked for.
void render_frames(RecordGl& gl, const History& history, const Camera& camera,
                   const RenderStyle& style, Easing easing, VertexColoring coloring,
                   const RecordOptions& o, RecordSummary& s) {
    const glm::mat4 view = camera.view(), projection = camera.projection();
    const int digits = frame_digits(o.frames);
    const fs::path dir(o.out_dir);
    const HalfedgeMesh* shown = nullptr;
    std::size_t shown_vertices = 0;
    FrameWriter writer(o.width, o.height, s.write_ms);
    auto last_report = std::chrono::steady_clock::now();
    bool reported = false;
    for (int i = 0; i < o.frames; ++i) {
        const auto t_frame = std::chrono::steady_clock::now();
        const double t = ease(easing, double(i) / double(o.frames - 1));
        MorphFrame frame = history.morph(1, t);
        if (frame.topology != shown || frame.topology->vertices_size() != shown_vertices) {
            shown = frame.topology;
            shown_vertices = shown->vertices_size();
            show_topology(gl.renderer, history, *shown, t, coloring, s);
        }
        gl.renderer.update_positions(*shown, frame.positions);
        gl.framebuffer.bind();
        clear_background(style, 1.0f);
        gl.renderer.draw(view, projection, style);
        Image image = gl.framebuffer.read_rgba();
        Framebuffer::bind_default();
        s.render_ms += ms_since(t_frame);

        const std::string path = (dir / frame_file_name(o.name, i, digits)).string();
        s.files.push_back(path);
        writer.write(std::move(image), path);
        if (o.progress && (ms_since(last_report) >= 2000.0 || (reported && i + 1 == o.frames))) {
            std::fprintf(stderr, "record: %d/%d frames\n", i + 1, o.frames);
            last_report = std::chrono::steady_clock::now();
            reported = true;
        }
    }
    writer.finish();
}

/// A note when the folder holds frames of an earlier, longer recording under the same name.
void note_stale_frames(const RecordOptions& o, RecordSummary& s) {
    const int digits = frame_digits(o.frames);
    std::error_code ec;
    if (fs::exists(fs::path(o.out_dir) / frame_file_name(o.name, o.frames, digits), ec))
        s.notes.push_back("the folder also holds frames of an earlier, longer recording (from " +
                          frame_file_name(o.name, o.frames, digits) + " on)" +
                          (o.mp4 ? "; the MP4 leaves them out" : ""));
}

#endif  // TRILAB_HAS_RENDER

}  // namespace

std::string frame_file_name(const std::string& name, int index, int digits) {
    std::string number = std::to_string(index);
    if (int(number.size()) < digits) number.insert(0, std::size_t(digits) - number.size(), '0');
    return name + "_" + number + ".png";
}

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
    RecordSummary s = start_summary(o, style, coloring, easing, up);

    // File input (not timed).
    LoadedMesh loaded = read_mesh(o.input);
    s.vertices_before = loaded.mesh.n_vertices();
    s.faces_before = loaded.mesh.n_faces();

    const auto t_op = std::chrono::steady_clock::now();
    OperationResult result = run_recorded_operation(operation, loaded.mesh, textured, up, s);
    const std::vector<glm::vec3> points = framing_points(loaded.mesh, result);
    History history(std::numeric_limits<std::size_t>::max());
    push_into_history(history, loaded.mesh, result, o.input, s);
    s.operation_ms = ms_since(t_op);

    const auto t_context = std::chrono::steady_clock::now();
    RecordGl gl;
    const Camera camera = set_up_gl(gl, o, textured, up, points);
    s.renderer = gl.context.description();
    s.context_ms = ms_since(t_context);

    create_output_folder(o.out_dir);
    render_frames(gl, history, camera, style, easing, coloring, o, s);
    s.ms = s.operation_ms + s.context_ms + s.render_ms;
    note_stale_frames(o, s);

    if (o.mp4) {
        const auto t_encode = std::chrono::steady_clock::now();
        s.mp4 = encode_mp4(o, frame_digits(o.frames), s.notes);
        s.encode_ms = ms_since(t_encode);
    }
    return s;
#endif
}

}  // namespace trilab::record
