// The recorder behind `trilab-cli record` (app/record/recorder.h): the frames of an operation's
// morph, checked against independent offscreen renders of the two states, plus option errors.
#include "app/record/recorder.h"

#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "app/cli/record_command.h"
#include "app/ops/operation.h"
#include "core/algorithms/coloring.h"
#include "core/algorithms/generators.h"
#include "core/errors.h"
#include "core/io/image_io.h"
#include "core/io/mesh_io.h"
#include "core/progress.h"
#include "render/offscreen.h"
#include "render_test_util.h"
#include "tests/support/skip.h"

using namespace trilab;
using namespace trilab::test;
using trilab::record::record_morph;
using trilab::record::RecordOptions;
using trilab::record::RecordSummary;

namespace {

constexpr const char* kNoise = "noise --amount 20";

/// Mean absolute difference of the RGB channels, in [0, 1].
double mean_abs_difference(const Image& a, const Image& b) {
    REQUIRE(a.width == b.width);
    REQUIRE(a.height == b.height);
    double sum = 0;
    std::size_t n = 0;
    for (std::size_t i = 0; i < a.rgba.size(); i += 4)
        for (std::size_t c = 0; c < 3; ++c, ++n)
            sum += std::abs(int(a.rgba[i + c]) - int(b.rgba[i + c]));
    return sum / (255.0 * double(n));
}

/// The default model, written where record_morph can load it.
std::string default_model(const TempDir& tmp) {
    const std::string path = tmp.path("default.obj");
    write_mesh(generate("default"), path);
    return path;
}

RecordOptions small_recording(const std::string& input, const std::string& out_dir) {
    RecordOptions o;
    o.input = input;
    o.operation = kNoise;
    o.out_dir = out_dir;
    o.frames = 5;
    o.width = 320;
    o.height = 240;
    return o;
}

/// `mesh` with the live vertices of `other` added as isolated vertices: render_offscreen
/// frames every vertex but draws only faces, so this renders `mesh` with the framing of
/// both states together, as record does.
HalfedgeMesh with_framing_of(HalfedgeMesh mesh, const HalfedgeMesh& other) {
    for (Vertex v : other.vertices()) mesh.add_vertex(other.position(v));
    return mesh;
}

OffscreenOptions reference_options(const RecordOptions& o) {
    OffscreenOptions r;
    r.width = o.width;
    r.height = o.height;
    r.style.mode = parse_render_mode(o.mode);
    r.azimuth = float(o.azimuth);
    r.elevation = float(o.elevation);
    r.up = parse_up_axis(o.up);
    return r;
}

/// The two states: the loaded mesh and the operation's result (deterministic: fixed seed).
struct States {
    HalfedgeMesh before, after;
};

States states_of(const std::string& input, const std::string& operation) {
    States s;
    s.before = read_mesh(input).mesh;
    NullProgress progress;
    s.after = run_operation(parse_operation(operation), s.before, progress).steps.back().mesh;
    return s;
}

std::vector<std::string> files_in(const std::string& dir) {
    std::vector<std::string> names;
    for (const auto& e : std::filesystem::directory_iterator(dir))
        names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

}  // namespace

TEST_CASE("record writes N frames from the loaded mesh to the operation's result", "[record]") {
    offscreen();  // software rendering, as everywhere in these tests
    TempDir tmp;
    const RecordOptions o = small_recording(default_model(tmp), tmp.path("frames/sub"));
    const RecordSummary s = record_morph(o);

    // Exactly N files, numbered from 0 with four digits, in a folder created for them.
    REQUIRE(s.files.size() == 5);
    CHECK(files_in(o.out_dir) == std::vector<std::string>{"frame_0000.png", "frame_0001.png",
                                                          "frame_0002.png", "frame_0003.png",
                                                          "frame_0004.png"});
    CHECK(s.files.front() == tmp.path("frames/sub/frame_0000.png"));
    CHECK(s.frames == 5);
    CHECK(s.label == "Add noise");
    CHECK(s.steps == 1);
    CHECK(s.mp4.empty());
    CHECK(s.colorings == 0);
    CHECK(s.ms > 0);

    const Image first = read_image(s.files.front());
    const Image middle = read_image(s.files[2]);
    const Image last = read_image(s.files.back());
    REQUIRE(first.width == 320);
    REQUIRE(first.height == 240);
    dump(first, "record_first");
    dump(last, "record_last");

    // The first and last frames differ visibly (20 % noise roughens the silhouette and the
    // shading), and the middle one lies between them.
    const double first_last = mean_abs_difference(first, last);
    INFO("first vs last: " << first_last);
    CHECK(first_last > 0.004);
    CHECK(mean_abs_difference(first, middle) < first_last);
    CHECK(mean_abs_difference(middle, last) < first_last);
    // Both show the mesh, centred and about equally large (a fixed framing).
    const auto bg = RenderStyle().background;
    const PixelStats f = foreground(first, bg), l = foreground(last, bg);
    CHECK(f.fraction > 0.2);
    CHECK(std::abs(f.fraction - l.fraction) < 0.05);
    CHECK(std::abs(f.cx - l.cx) < 4);
    CHECK(std::abs(f.cy - l.cy) < 4);

    // They match independent offscreen renders of the two states, framed as record frames
    // them (both states' vertices).
    const States states = states_of(o.input, o.operation);
    const OffscreenOptions ro = reference_options(o);
    const Image before = render_offscreen(with_framing_of(states.before, states.after), ro);
    const Image after = render_offscreen(with_framing_of(states.after, states.before), ro);
    offscreen();  // the shared context current again
    dump(before, "record_reference_first");
    dump(after, "record_reference_last");
    const double d_first = mean_abs_difference(first, before);
    const double d_last = mean_abs_difference(last, after);
    INFO("first vs its reference: " << d_first << ", last vs its reference: " << d_last);
    CHECK(d_first < 0.001);
    CHECK(d_last < 0.001);
    CHECK(d_first < first_last / 10);
    CHECK(d_last < first_last / 10);
}

TEST_CASE("record keeps colourings attached to the vertices during the morph", "[record][color]") {
    offscreen();
    TempDir tmp;
    RecordOptions o = small_recording(default_model(tmp), tmp.path("frames"));
    o.frames = 3;
    o.color = "mean";
    o.name = "curv";
    o.easing = "smoothstep";
    const RecordSummary s = record_morph(o);
    REQUIRE(s.files.size() == 3);
    CHECK(files_in(o.out_dir) ==
          std::vector<std::string>{"curv_0000.png", "curv_0001.png", "curv_0002.png"});
    CHECK(s.colorings == 1);  // a geometry-only change: computed once
    CHECK(s.easing == "smooth-step");

    // Colours computed on the end state, in every frame: the first frame is the loaded
    // shape wearing the noisy mesh's curvature colours, the last is the noisy mesh in its own.
    const States states = states_of(o.input, o.operation);
    const VertexColors colors = color_vertices(states.after, VertexColoring::Mean);
    CHECK(s.legend.has_legend);
    CHECK(s.legend.label == colors.label);
    CHECK(s.legend.range.min == colors.range.min);
    CHECK(s.legend.range.max == colors.range.max);
    CHECK(s.legend.kind == ColorMapKind::Diverging);
    CHECK(s.legend.colors.empty());
    OffscreenOptions ro = reference_options(o);
    HalfedgeMesh before = with_framing_of(states.before, states.after);
    HalfedgeMesh after = with_framing_of(states.after, states.before);
    ro.vertex_colors = colors.colors;
    ro.vertex_colors.resize(before.vertices_size(), Color(0, 0, 0));  // isolated: not drawn
    const Image ref_first = render_offscreen(before, ro);
    const Image ref_last = render_offscreen(after, ro);
    // Colours of the loaded shape itself would look quite different.
    OffscreenOptions own = ro;
    own.vertex_colors = color_vertices(before, VertexColoring::Mean).colors;
    const Image loaded_own_colors = render_offscreen(before, own);
    offscreen();

    const Image first = read_image(s.files.front()), last = read_image(s.files.back());
    const double d_first = mean_abs_difference(first, ref_first);
    const double d_last = mean_abs_difference(last, ref_last);
    const double d_own = mean_abs_difference(first, loaded_own_colors);
    INFO("first: " << d_first << ", last: " << d_last << ", loaded colours: " << d_own);
    CHECK(d_first < 0.001);
    CHECK(d_last < 0.001);
    CHECK(d_own > 10 * d_first);
}

TEST_CASE("record refuses bad options, naming them, and writes nothing", "[record]") {
    TempDir tmp;
    const std::string input = default_model(tmp);
    const std::string out = tmp.path("never");
    const RecordOptions good = small_recording(input, out);
    auto refuses = [&](RecordOptions o, const std::string& option) {
        INFO("expected a refusal naming " << option);
        try {
            record_morph(o);
            FAIL("no exception");
        } catch (const InvalidArgument& e) {
            CHECK(std::string(e.what()).find(option) != std::string::npos);
        }
        CHECK_FALSE(std::filesystem::exists(out));
    };
    RecordOptions o = good;
    o.frames = 1;
    refuses(o, "--frames");
    o.frames = 100001;
    refuses(o, "--frames");
    o = good;
    o.width = 0;
    refuses(o, "--size");
    o = good;
    o.operation = "frobnicate --amount 2";
    refuses(o, "--op");
    o.operation = "noise --amount -5";  // parses as an option value, refused by its range
    refuses(o, "--op");
    o.operation = "noise --bogus 1";
    refuses(o, "--op");
    o = good;
    o.mode = "sketchy";
    refuses(o, "--mode");
    o = good;
    o.color = "plaid";
    refuses(o, "--color");
    o = good;
    o.easing = "bouncy";
    refuses(o, "--easing");
    o = good;
    o.name = "a/b";
    refuses(o, "--name");
    o = good;
    o.fps = 0;
    refuses(o, "--fps");
    o = good;
    o.out_dir = input;  // an existing file
    refuses(o, "--out");

    // The command line: the same errors from the parser, naming the option.
    auto cli_refuses = [&](std::vector<std::string> args, const std::string& option) {
        INFO("expected a refusal naming " << option);
        try {
            trilab::cli::run_record_command(args);
            FAIL("no exception");
        } catch (const InvalidArgument& e) {
            CHECK(std::string(e.what()).find(option) != std::string::npos);
        }
        CHECK_FALSE(std::filesystem::exists(out));
    };
    cli_refuses({input, "--op", kNoise, "--out", out, "--frames", "1"}, "--frames");
    cli_refuses({input, "--op", kNoise, "--out", out, "--frames", "2.5"}, "--frames");
    cli_refuses({input, "--op", kNoise, "--out", out, "--size", "12x"}, "--size");
    cli_refuses({input, "--op", "nothing", "--out", out}, "--op");
    cli_refuses({input, "--out", out}, "--op");
    cli_refuses({input, "--op", kNoise}, "--out");
    cli_refuses({input, "--op", kNoise, "--out", out, "--wobble"}, "--wobble");
}

TEST_CASE("record --mp4 never fails for want of ffmpeg", "[record]") {
    offscreen();
    TempDir tmp;
    RecordOptions o = small_recording(default_model(tmp), tmp.path("frames"));
    o.frames = 2;
    o.width = 63;  // odd: the encoder pads to even sizes
    o.height = 47;
    o.mp4 = true;

    SECTION("without ffmpeg on the PATH: a note, the frames, no MP4") {
        const char* old = std::getenv("PATH");
        const std::string saved = old ? old : "";
        ::setenv("PATH", tmp.path("empty-path").c_str(), 1);
        RecordSummary s;
        try {
            s = record_morph(o);
        } catch (...) {
            ::setenv("PATH", saved.c_str(), 1);
            throw;
        }
        ::setenv("PATH", saved.c_str(), 1);
        CHECK(s.files.size() == 2);
        CHECK(s.mp4.empty());
        REQUIRE(s.notes.size() == 1);
        CHECK(s.notes[0].find("ffmpeg is not on the PATH") != std::string::npos);
        CHECK(files_in(o.out_dir).size() == 2);
    }
    SECTION("with ffmpeg, when there is one: an MP4 beside the frames") {
        if (trilab::record::find_on_path("ffmpeg").empty()) {
            SKIP_TEST("ffmpeg is not on the PATH: the MP4 encoding is not tested");
        }
        const RecordSummary s = record_morph(o);
        INFO((s.notes.empty() ? std::string() : s.notes[0]));
        REQUIRE(s.mp4 == tmp.path("frames/frame.mp4"));
        CHECK(std::filesystem::file_size(s.mp4) > 100);
        CHECK(files_in(o.out_dir).size() == 3);  // 2 frames + the MP4, no leftovers
    }
}
