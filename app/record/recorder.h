#pragma once
// Recording an operation's morph: runs one operation on a mesh and renders the morph from the
// mesh before it to the mesh after it offscreen, as numbered PNG frames (and, when ffmpeg is
// on the PATH and mp4 is asked for, an H.264 MP4). `trilab-cli record` is its command line
// (app/cli/record_command.h); the viewer's Record section names its frames the same way
// (frame_file_name()).
//
// The morph is the snapshot stack's (History::morph of the operation's entry, the loaded
// mesh being the first entry), so the frames show exactly what the viewer's Animate plays.
// The camera is fixed for the whole sequence: the render command's tight fit
// (Camera::fit_points_in_view) of the vertices of every state of the entry together (the
// mesh before and after each step), so no vertex leaves the frame. Vertex colourings are
// computed once per displayed topology, on that topology at the last shape it shows
// (the end state for a geometry-only change), so colours stay attached to the vertices
// while they move; they are recomputed only when the displayed topology changes (a
// decimation's geomorph switches to the coarser mesh at t = 1).
//
// This header needs no GL: trilab-cli includes it whether or not the renderer is built
// (without it, record_morph() throws).
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "core/algorithms/coloring.h"

namespace trilab::record {

constexpr int kMinFrames = 2, kMaxFrames = 100000;  ///< RecordOptions::frames
constexpr int kMaxSide = 16384;                     ///< RecordOptions::width and height
constexpr int kMaxFps = 1000;                       ///< RecordOptions::fps

/// What to record. The strings take the CLI's spellings (`trilab-cli record --help`).
struct RecordOptions {
    std::string input;                  ///< the mesh file to load (any supported format)
    std::string operation;              ///< e.g. "noise --amount 2 --seed 7" (parse_operation())
    std::string out_dir;                ///< created when missing; an existing non-folder is refused
    int frames = 60;                    ///< 2 to 100000; frame i shows t = ease(i / (frames - 1))
    int width = 1280, height = 720;     ///< 1 to 16384 pixels each
    std::string mode = "gouraud";       ///< render_mode_name() spellings
    std::string color = "none";         ///< coloring_name() spellings
    double azimuth = 0, elevation = 0;  ///< view direction in degrees, as `render --view`
    std::string up = "y";               ///< the up axis, "y" or "z" (core/up_axis.h)
    /// "linear", "smoothstep" (or "smooth-step"), "cubic" (or "ease-in-out-cubic").
    std::string easing = "linear";
    std::string name = "frame";  ///< files are out_dir/name_0000.png ...; no '/' allowed
    bool mp4 = false;            ///< also encode out_dir/name.mp4 when ffmpeg is on the PATH
    int fps = 30;                ///< frame rate of the MP4, 1 to 1000
    bool progress = false;       ///< sparse progress lines on stderr
};

/// What record_morph() did.
struct RecordSummary {
    int frames = 0, width = 0, height = 0;
    std::vector<std::string> files;             ///< every frame written, in order
    std::string mp4;                            ///< the MP4 written, or "" when none
    std::string label, parameters;              ///< the operation as the history names it
    std::vector<std::string> operation_report;  ///< the operation's log lines
    std::vector<std::pair<std::string, double>> operation_values;  ///< OperationResult::values
    std::size_t steps = 0;  ///< steps (iterations) of the entry
    std::size_t vertices_before = 0, faces_before = 0;
    std::size_t vertices_after = 0, faces_after = 0;
    std::string mode, color, easing, up;  ///< canonical names
    /// The legend of the last colouring (its colours dropped; has_legend false without one).
    VertexColors legend;
    int colorings = 0;     ///< how many times the colouring was computed (0 without --color)
    std::string renderer;  ///< OffscreenContext::description()
    std::vector<std::string> notes;
    double operation_ms = 0;  ///< running the operation
    double context_ms = 0;    ///< creating the headless GL context and shaders
    double render_ms = 0;     ///< morph evaluation, colouring, drawing and read-back
    double write_ms = 0;      ///< PNG encoding and writing (overlaps rendering)
    double encode_ms = 0;     ///< ffmpeg
    double ms = 0;            ///< operation + context + rendering (no file reading or writing)
};

/// Checks every option that can be checked without reading a file, including that the
/// operation and its parameters parse. Throws InvalidArgument naming the option.
void check_record_options(const RecordOptions& options);

/// Loads the mesh, runs the operation, pushes it into a History whose first entry is the
/// loaded mesh, and renders the entry's morph into options.frames PNG files. Throws
/// InvalidArgument for bad options (nothing is written then, also for an operation whose
/// parameters are refused when it runs), IoError for unreadable input or unwritable output,
/// Error when no headless GL context can be created or the renderer is not built. A failed
/// or impossible MP4 encoding is a note, not an error.
RecordSummary record_morph(const RecordOptions& options);

/// The file name of frame `index`: name_0007.png, the number zero-padded to `digits` (a
/// wider number is written whole).
std::string frame_file_name(const std::string& name, int index, int digits = 4);

/// The executable `program` in a folder of $PATH, or "" when there is none.
std::string find_on_path(const std::string& program);

}  // namespace trilab::record
