// `trilab-cli record`: the command line of the recorder (app/record/recorder.h). See
// record_command.h.
#include "app/cli/record_command.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

#include "app/cli/arg_reader.h"
#include "app/cli/json_writer.h"
#include "app/cli/legend_output.h"
#include "app/record/recorder.h"
#include "core/algorithms/coloring.h"
#include "core/errors.h"

namespace trilab::cli {
namespace {

using record::kMaxFps;
using record::kMaxFrames;
using record::kMaxSide;
using record::kMinFrames;
using record::record_morph;
using record::RecordOptions;
using record::RecordSummary;

/// The --help text; record_usage() puts the colourings from the table in place of {colorings}.
constexpr const char* kRecordUsage =
    R"(usage: trilab-cli record MESH --op "OPERATION" --out DIR [options]

Loads MESH, runs OPERATION on it (e.g. "noise --amount 2 --seed 7") and renders the morph
from the mesh before it to the mesh after it without a window (EGL surfaceless context;
Mesa's llvmpipe on machines without a GPU) into DIR/frame_0000.png, DIR/frame_0001.png, ...
The camera frames every state of the morph at once and stays fixed, so nothing leaves the
picture. Colourings are computed once on the shape the morph ends in, so colours stay on
their vertices while they move.

options:
  --op "OPERATION"      the operation and its parameters (required; one operation: a
                        second --op is refused)
  --out DIR             the folder for the frames (required; created when missing)
  --frames N            number of frames, 2 to 100000 (default 60); frame i shows the morph
                        at t = ease(i / (N - 1)), from the mesh before (first frame) to the
                        mesh after (last frame)
  --size WxH            frame size in pixels (default 1280x720)
  --mode MODE           gouraud (default), flat, wireframe, hidden-line, points, textured
  --color QUANTITY      colour the vertices: {colorings}
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

/// The colourings record accepts (those that need no spectral decomposition), from the
/// colouring table, "none (default)" first, wrapped under the option's help column.
std::string coloring_list() {
    constexpr std::size_t kIndent = 24, kWidth = 92;
    std::string text, line;
    std::size_t column = kIndent + std::string("colour the vertices: ").size();
    for (const VertexColoring c : vertex_colorings()) {
        if (coloring_needs_field(c)) continue;
        std::string item = coloring_name(c);
        if (c == VertexColoring::None) item += " (default)";
        const bool first = text.empty() && line.empty();
        if (!first && column + item.size() + 2 > kWidth) {
            text += line + ",\n" + std::string(kIndent, ' ');
            line.clear();
            column = kIndent;
        } else if (!first) {
            line += ", ";
            column += 2;
        }
        line += item;
        column += item.size();
    }
    return text + line;
}

/// The --help text.
std::string record_usage() {
    std::string s = kRecordUsage;
    const std::string placeholder = "{colorings}";
    return s.replace(s.find(placeholder), placeholder.size(), coloring_list());
}

/// Refuses a colouring that is unknown or needs a spectral decomposition, before any file
/// is read.
void check_coloring(const std::string& name) {
    VertexColoring coloring = VertexColoring::None;
    try {
        coloring = parse_coloring(name);
    } catch (const InvalidArgument& e) {
        throw InvalidArgument(std::string("--color: ") + e.what());
    }
    if (coloring == VertexColoring::GeodesicDistance)
        throw InvalidArgument(
            "--color: 'geodesic-distance' needs distances from sources (trilab-cli render "
            "--color geodesic-distance colours the output of trilab-cli geodesic)");
    if (coloring_needs_field(coloring))
        throw InvalidArgument("--color: '" + name +
                              "' needs a spectral decomposition (the viewer's Frequency panel)");
}

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

/// Options parsed from the command line, plus what only the command line has.
struct CommandLine {
    RecordOptions options;
    bool json = false, help = false;
};

CommandLine parse_args(const std::vector<std::string>& args) {
    CommandLine c;
    RecordOptions& o = c.options;
    ArgReader reader(args, "record");
    while (reader.next()) {
        if (reader.is_help()) {
            c.help = true;
        } else if (reader.is("--json")) {
            c.json = reader.flag();
        } else if (reader.is("--mp4")) {
            o.mp4 = reader.flag();
        } else if (reader.is("--op")) {
            o.operation = reader.value();
        } else if (reader.is("--out")) {
            o.out_dir = reader.value();
        } else if (reader.is("--mode")) {
            o.mode = reader.value();
        } else if (reader.is("--color")) {
            o.color = reader.value();
        } else if (reader.is("--easing")) {
            o.easing = reader.value();
        } else if (reader.is("--up")) {
            o.up = reader.value();
        } else if (reader.is("--name")) {
            o.name = reader.value();
        } else if (reader.is("--frames")) {
            const std::string v = reader.value();
            if (!to_int(v, kMinFrames, kMaxFrames, o.frames))
                throw InvalidArgument("--frames: expected a whole number from " +
                                      std::to_string(kMinFrames) + " to " +
                                      std::to_string(kMaxFrames) + ", got '" + v + "'");
        } else if (reader.is("--fps")) {
            const std::string v = reader.value();
            if (!to_int(v, 1, kMaxFps, o.fps))
                throw InvalidArgument("--fps: expected a whole number from 1 to " +
                                      std::to_string(kMaxFps) + ", got '" + v + "'");
        } else if (reader.is("--size")) {
            const std::string v = reader.value();
            const std::size_t x = v.find_first_of("xX");
            if (x == std::string::npos || !to_int(v.substr(0, x), 1, kMaxSide, o.width) ||
                !to_int(v.substr(x + 1), 1, kMaxSide, o.height))
                throw InvalidArgument("--size: expected WxH with whole numbers from 1 to " +
                                      std::to_string(kMaxSide) + ", got '" + v + "'");
        } else if (reader.is("--view")) {
            const std::string v = reader.value();
            const std::size_t comma = v.find(',');
            if (comma == std::string::npos || !to_double(v.substr(0, comma), o.azimuth) ||
                !to_double(v.substr(comma + 1), o.elevation))
                throw InvalidArgument(
                    "--view: expected AZIMUTH,ELEVATION in degrees (e.g. 30,20), got '" + v + "'");
        } else if (reader.is_option()) {
            reader.refuse_unknown();
        } else if (o.input.empty()) {
            o.input = reader.arg();
        } else {
            throw InvalidArgument("unexpected argument '" + reader.arg() +
                                  "': expected one MESH file");
        }
    }
    return c;
}

}  // namespace

int run_record_command(const std::vector<std::string>& args) {
    CommandLine c = parse_args(args);
    if (c.help) {
        std::fputs(record_usage().c_str(), stdout);
        return 0;
    }
    check_coloring(c.options.color);
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
