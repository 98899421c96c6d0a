// The viewer's side of sessions (issue 27): the settings text reads back bit for bit, a
// session saved and opened through the Session's commands restores every state, and the
// Record section's MP4 encoder gets an argument vector (no shell) that keeps any file name
// as one argument.
#include <unistd.h>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "app/record/mp4_encoder.h"
#include "app/record/recorder.h"
#include "app/session/session.h"
#include "app/viewer/viewer_settings.h"
#include "core/algorithms/generators.h"
#include "core/io/image_io.h"
#include "core/io/mesh_io.h"
#include "tests/app/test_tools.h"

using namespace trilab;
using namespace trilab::viewer;
using namespace trilab::viewer::testing;
namespace fs = std::filesystem;

namespace {

/// A fresh folder under the temporary directory, removed at the end.
struct TempDir {
    fs::path path;
    explicit TempDir(const std::string& name) {
        path = fs::temp_directory_path() / (name + "-" + std::to_string(::getpid()));
        fs::remove_all(path);
        fs::create_directories(path);
    }
    ~TempDir() {
        std::error_code ec;
        fs::remove_all(path, ec);
    }
};

const char* const kHostileNames[] = {"it's", "$(touch PWNED)", "`touch PWNED`", "a b\"c;d"};

}  // namespace

TEST_CASE("the MP4 encoder's arguments keep hostile names as single arguments", "[record]") {
    for (const char* name : kHostileNames) {
        INFO(name);
        const record::Mp4Request request{"out dir/$(x)", name, 12, 25, 4};
        const std::vector<std::string> argv =
            record::mp4_encoder_arguments("/usr/bin/ffmpeg", request, "target.mp4");
        REQUIRE(argv.front() == "/usr/bin/ffmpeg");
        CHECK(argv.back() == "target.mp4");
        // The input pattern is one argument: the folder and the name as they are.
        const auto input = std::find(argv.begin(), argv.end(), "-i");
        REQUIRE(input + 1 < argv.end());
        CHECK(input[1] == "out dir/$(x)/" + std::string(name) + "_%04d.png");
        CHECK(std::find(argv.begin(), argv.end(), "25") != argv.end());
        CHECK(std::find(argv.begin(), argv.end(), "12") != argv.end());
    }
    // ffmpeg's pattern escapes a literal '%'.
    const std::vector<std::string> argv =
        record::mp4_encoder_arguments("ffmpeg", {"d", "100%", 2, 30, 4}, "o.mp4");
    CHECK(std::find(argv.begin(), argv.end(), "d/100%%_%04d.png") != argv.end());
}

TEST_CASE("run_program runs no shell: quotes, $(...) and backticks are plain text", "[record]") {
    TempDir dir("trilab-spawn");
    const fs::path log = dir.path / "log.txt";
    const std::string printf_path = record::find_on_path("printf");
    if (printf_path.empty()) {
        WARN("skipped: no printf on the PATH");
        return;
    }
    for (const char* name : kHostileNames) {
        INFO(name);
        std::string error;
        const std::string cwd = fs::current_path().string();
        fs::current_path(dir.path);
        const int status = record::run_program({printf_path, "%s", name}, log.string(), error);
        fs::current_path(cwd);
        REQUIRE(status == 0);
        std::ifstream in(log);
        std::string out((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        CHECK(out == name);
        CHECK_FALSE(fs::exists(dir.path / "PWNED"));
    }
}

TEST_CASE("the Record section's MP4 is encoded whatever its name, when ffmpeg exists",
          "[record][ffmpeg]") {
    if (record::find_on_path("ffmpeg").empty()) {
        WARN("skipped: ffmpeg is not on the PATH (the argument vector is tested above)");
        return;
    }
    TempDir dir("trilab-mp4");
    for (const char* name : kHostileNames) {
        INFO(name);
        // Two tiny frames: a 1x1 PNG written by hand is not worth it; use the recorder's
        // own frame names with a minimal valid PNG from the image writer.
        for (int i = 0; i < 2; ++i) {
            Image image;
            image.width = image.height = 2;
            image.rgba.assign(16, 200);
            write_png(image, (dir.path / record::frame_file_name(name, i)).string());
        }
        std::string note;
        const std::string mp4 = record::encode_mp4({dir.path.string(), name, 2, 10, 4}, note);
        CHECK(note.empty());
        CHECK(mp4 == (dir.path / (std::string(name) + ".mp4")).string());
        CHECK(fs::exists(mp4));
        CHECK_FALSE(fs::exists(dir.path / "PWNED"));
        CHECK_FALSE(fs::exists("PWNED"));
    }
}

TEST_CASE("the viewer settings text reads back bit for bit", "[session]") {
    Camera camera;
    camera.set_viewport(800, 600);
    camera.fit_sphere(glm::vec3(0.1f, 0.2f, 0.3f), 1.7f);
    camera.rotate(glm::vec2(100, 100), glm::vec2(173.3f, 141.9f));
    camera.zoom(1.37f);
    RenderStyle style;
    style.mode = RenderMode::Flat;
    style.wire_width = 1.0f / 3.0f;
    style.front_color = glm::vec3(0.1f, 0.7f / 3.0f, 0.9f);
    style.scalar_steps = 17;
    ViewSettings settings;
    settings.coloring = parse_coloring("mean");
    settings.coloring_options.low_percentile = 1.0 / 3.0;
    settings.coloring_options.high_percentile = 97.123456789012345;
    settings.up = UpAxis::Z;
    TestPanels panels;
    panels.fairing.op = parse_operation("smooth --iterations 7 --step 0.123");
    panels.record.folder = "odd\\name\nwith newline";
    panels.frequency.lo = 3;
    MorphState morph;
    morph.duration = 2.0 / 3.0;
    morph.easing = Easing::EaseInOutCubic;

    const std::string text =
        viewer_settings_text({camera, style, settings, panels, morph, panels.list()});
    Camera camera2;
    RenderStyle style2;
    ViewSettings settings2;
    TestPanels panels2;
    MorphState morph2;
    const std::vector<std::string> notes =
        apply_viewer_settings(text, {camera2, style2, settings2, panels2, morph2, panels2.list()});
    CHECK(notes.empty());
    CHECK(camera2.rotation() == camera.rotation());
    CHECK(camera2.target() == camera.target());
    CHECK(camera2.distance() == camera.distance());
    CHECK(camera2.radius() == camera.radius());
    CHECK(camera2.view() == camera.view());
    CHECK(style2.mode == RenderMode::Flat);
    CHECK(style2.wire_width == style.wire_width);
    CHECK(style2.front_color == style.front_color);
    CHECK(style2.scalar_steps == 17);
    CHECK(settings2.coloring == parse_coloring("mean"));
    CHECK(settings2.coloring_options.low_percentile == settings.coloring_options.low_percentile);
    CHECK(settings2.coloring_options.high_percentile == settings.coloring_options.high_percentile);
    CHECK(settings2.up == UpAxis::Z);
    CHECK(panels2.fairing.op == panels.fairing.op);
    CHECK(panels2.record.folder == panels.record.folder);
    CHECK(panels2.frequency.lo == 3);
    CHECK(morph2.duration == morph.duration);
    CHECK(morph2.easing == Easing::EaseInOutCubic);
    CHECK(viewer_settings_text({camera2, style2, settings2, panels2, morph2, panels2.list()}) ==
          text);
}

TEST_CASE("the tools keep the saved settings' keys the panels had", "[viewer_settings]") {
    // Session files and journals written before the tools owned their panels load: every key
    // is where it was (docs/file-formats.md#session-files).
    Camera camera;
    RenderStyle style;
    ViewSettings settings;
    TestPanels panels;
    MorphState morph;
    panels.denoise.op = parse_operation("denoise --normal-iterations 5");
    panels.tool("noise")->op = parse_operation("noise --amount 12");
    const std::string text =
        "\n" + viewer_settings_text({camera, style, settings, panels, morph, panels.list()});
    for (const char* key : {"panel.subdivision=",
                            "panel.fairing=",
                            "panel.decimation=",
                            "panel.frequency=",
                            "panel.tool.noise=",
                            "panel.tool.weld=",
                            "panel.tool.denoise=",
                            "frequency.lo=",
                            "frequency.hi=",
                            "frequency.visualize=",
                            "decimation.lod_percent=",
                            "decimation.show_collapsing_edges=",
                            "record.frames=",
                            "record.fps=",
                            "record.width=",
                            "record.height=",
                            "record.folder=",
                            "record.name=",
                            "record.mp4=",
                            "screenshot.path=",
                            "morph.duration="}) {
        INFO(key);
        CHECK(text.find(std::string("\n") + key) != std::string::npos);
    }
    // The lines the generic Denoise panel wrote reach the Denoise tool.
    TestPanels panels2;
    CHECK(apply_viewer_settings("panel.tool.denoise=" + panels.denoise.op.text() +
                                    "\npanel.tool.noise=" + panels.tool("noise")->op.text() + "\n",
                                {camera, style, settings, panels2, morph, panels2.list()})
              .empty());
    CHECK(panels2.denoise.op == panels.denoise.op);
    CHECK(panels2.tool("noise")->op == panels.tool("noise")->op);
}

TEST_CASE("bad viewer settings lines are notes naming the line, never a throw", "[session]") {
    Camera camera;
    RenderStyle style;
    ViewSettings settings;
    TestPanels panels;
    MorphState morph;
    const std::vector<std::string> notes = apply_viewer_settings(
        "style.wire_width=nan\nstyle.mode=sideways\nnonsense\nno.such=1\n"
        "panel.fairing=subdivide --iterations 1\ncamera.rotation=1 0 0\nstyle.fog=1\n",
        {camera, style, settings, panels, morph, panels.list()});
    REQUIRE(notes.size() == 7);       // the short camera line: its own note and the camera's
    CHECK(style.fog);                 // the good line applies
    CHECK(style.wire_width == 1.0f);  // the bad ones leave their setting
    CHECK(panels.fairing.op.name() == "smooth");
    std::string all;
    for (const std::string& n : notes) all += n + "\n";
    CHECK(all.find("line 1: style.wire_width") != std::string::npos);
    CHECK(all.find("line 3: expected key=value") != std::string::npos);
    CHECK(all.find("unknown setting 'no.such'") != std::string::npos);
    CHECK(all.find("camera") != std::string::npos);
}

TEST_CASE("a session saved and opened through the commands restores every state", "[session]") {
    TempDir dir("trilab-viewer-session");
    const std::string path = (dir.path / "s.trilab").string();
    Session a;
    a.execute(RunOperation{parse_operation("noise --amount 2 --seed 9")});
    a.finish_jobs();
    a.execute(RunOperation{parse_operation("smooth --iterations 2")});
    a.finish_jobs();
    a.execute(Undo{});
    REQUIRE(a.history().size() == 3);
    SessionExtras extras;
    extras.viewer_settings = "style.fog=1\n";
    a.set_extras_provider([extras] { return extras; });
    a.execute(SaveSession{path});
    a.finish_jobs();
    REQUIRE(fs::exists(path));

    Session b;
    b.execute(OpenSession{path});
    b.finish_jobs();
    const SessionEvents events = b.take_events();
    REQUIRE(events.session_extras);
    CHECK(events.session_extras->viewer_settings == "style.fog=1\n");
    REQUIRE(b.history().size() == 3);
    CHECK(b.history().current() == 1);
    CHECK(b.document().path == path);
    for (std::size_t i = 0; i < 3; ++i) {
        CHECK(b.history().info(i).label == a.history().info(i).label);
        const HalfedgeMesh ma = a.history().mesh(i, a.history().info(i).steps.size() - 1);
        const HalfedgeMesh mb = b.history().mesh(i, b.history().info(i).steps.size() - 1);
        CHECK(ma.positions() == mb.positions());
        CHECK(ma.faces_size() == mb.faces_size());
    }
    // A file that is no session: an error in the window, the document unchanged.
    const std::string bad = (dir.path / "bad.trilab").string();
    std::ofstream(bad) << "not a session";
    b.execute(OpenSession{bad});
    b.finish_jobs();
    CHECK(b.notice().level == Notice::Level::Error);
    CHECK(b.notice().text.find("bad.trilab") != std::string::npos);
    CHECK(b.history().size() == 3);
}

TEST_CASE("the session's journal records every history change and a close removes it",
          "[session]") {
    TempDir dir("trilab-viewer-journal");
    Session s;
    JournalOptions options;
    options.directory = dir.path.string();
    options.sync = false;
    s.start_journal(options);
    s.execute(RunOperation{parse_operation("noise --amount 2 --seed 1")});
    s.finish_jobs();
    s.execute(Undo{});
    s.flush_journal();
    const std::string path = s.files().journal()->path();
    REQUIRE_FALSE(path.empty());
    const SessionContents read = read_journal(path);
    CHECK(read.history.size() == 2);
    CHECK(read.history.current() == 0);
    s.close_journal();
    CHECK_FALSE(fs::exists(path));
    CHECK(s.files().journal() == nullptr);
}

TEST_CASE("restoring a journal asks before replacing unsaved work and names the model",
          "[session][journal]") {
    TempDir dir("trilab-viewer-recover");
    const std::string model = (dir.path / "ball.off").string();
    write_mesh(make_default_model(), model);
    // The work of a viewer that ended: a load and an operation, journaled.
    Session a;
    JournalOptions options;
    options.directory = dir.path.string();
    options.sync = false;
    a.start_journal(options);
    a.execute(LoadFile{model});
    a.finish_jobs();
    a.execute(RunOperation{parse_operation("noise --amount 2 --seed 1")});
    a.finish_jobs();
    a.flush_journal();
    const std::string journal = (dir.path / "copy.journal").string();
    fs::copy_file(a.files().journal()->path(), journal);
    std::ofstream(journal + ".ended") << "SIGTERM";
    a.close_journal();

    // Unsaved work open here: the restore waits for the window's question.
    Session b;
    b.set_ask_before_discarding(true);
    b.execute(RunOperation{parse_operation("smooth --iterations 2")});
    b.finish_jobs();
    REQUIRE(b.document().unsaved);
    b.take_events();
    b.execute(RecoverJournal{journal, true});
    b.finish_jobs();
    SessionEvents e = b.take_events();
    REQUIRE(e.confirm_discard == std::optional<std::string>(journal));
    CHECK(e.confirm_recovery);
    CHECK(b.history().info(1).label == "Smooth");  // nothing replaced
    CHECK(fs::exists(journal));
    // The answer "discard": restored, named after its model, and removed with its note.
    b.execute(RecoverJournal{journal, true, true});
    b.finish_jobs();
    REQUIRE(b.history().size() == 2);  // the load and the noise
    CHECK(b.history().info(1).label == "Add noise");
    CHECK(b.document().name == "ball.off (recovered)");
    CHECK(b.document().path.empty());
    CHECK(b.document().unsaved);
    CHECK_FALSE(fs::exists(journal));
    CHECK_FALSE(fs::exists(journal + ".ended"));
}
