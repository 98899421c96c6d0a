// The session without a window (app/session/session.h): typed commands in, jobs run to their
// end, and the history, the shown value and the notices asserted. Runs under ThreadSanitizer
// in CI (the jobs read snapshots, never the session).
#include <catch2/catch.hpp>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <future>
#include <string>
#include <thread>

#include <unistd.h>

#include "app/ops/operation.h"
#include "app/ops/operation_entries.h"
#include "app/ops/spectrum_op.h"
#include "app/session/session.h"
#include "core/algorithms/coloring.h"
#include "core/algorithms/decimation.h"
#include "core/algorithms/fairing.h"
#include "core/algorithms/generators.h"
#include "core/algorithms/transfer_function.h"
#include "core/features.h"
#include "core/io/mesh_io.h"
#include "core/validate.h"
#include "tests/app/pick_helpers.h"
#include "tests/unit/test_helpers.h"

using namespace trilab;
using namespace trilab::viewer;
using trilab::test::data_file;

namespace {

/// The session's shown mesh is a valid mesh (every operation leaves one).
void require_valid(const Session& s) {
    const ValidationResult v = validate(s.mesh());
    INFO(v.message);
    REQUIRE(v.ok);
}

/// A session whose current state is a closed sphere of about 2,500 vertices.
void load_sphere(Session& s) {
    s.execute(RunOperation{parse_operation("subdivide --scheme loop --iterations 1")});
    s.finish_jobs();
    s.execute(ShowMorphAt{1.0});
}

}  // namespace

TEST_CASE("a session starts on the default model and shows it", "[session]") {
    Session s;
    CHECK(s.history().size() == 1);
    CHECK(s.shown().kind == Shown::Kind::Document);
    CHECK(s.shown().mesh == &s.mesh());
    CHECK(s.mesh().n_vertices() == 1002);
    const SessionEvents e = s.take_events();
    CHECK(e.state_changed);
    CHECK(e.fit);
    CHECK_FALSE(s.document().unsaved);
    require_valid(s);
}

TEST_CASE("morph commands drive the playback on the session's clock", "[session]") {
    Session s;
    load_sphere(s);
    s.execute(RunOperation{parse_operation("smooth --iterations 3")});
    s.finish_jobs();
    s.execute(ShowMorphAt{0.25});
    CHECK(s.morph().t == 0.25);
    CHECK_FALSE(s.morph().playing);
    s.execute(ShowMorphAt{7.0});  // clamped
    CHECK(s.morph().t == 1.0);
    s.execute(SetMorphAnimation{0.5, Easing::Linear, Playback::Once});
    CHECK(s.morph().duration == 0.5);
    CHECK(s.morph().easing == Easing::Linear);
    s.execute(SetMorphAnimation{-1.0, Easing::Linear, Playback::Once});  // refused: kept
    CHECK(s.morph().duration == 0.5);
    const double before = s.now();
    s.execute(PlayMorph{true});
    CHECK(s.morph().playing);
    CHECK(s.morph().play_start >= before);
    CHECK(s.morph().play_start <= s.now());
    s.execute(PlayMorph{false});
    CHECK_FALSE(s.morph().playing);
}

TEST_CASE("a colouring job colours the state it was started on, through the one job runner",
          "[session]") {
    Session s;
    load_sphere(s);
    CHECK(s.coloring().result() == nullptr);
    ColoringOptions options;
    s.execute(ComputeColoring{VertexColoring::Mean, options, nullptr});
    CHECK(s.busy());  // a job of the session's runner
    s.finish_jobs();
    const SessionColoring::Result* r = s.coloring().result();
    REQUIRE(r != nullptr);
    CHECK(r->id == 1);
    CHECK(r->coloring == VertexColoring::Mean);
    CHECK(r->state == s.mesh().revision());
    const VertexColors direct = color_vertices(s.mesh(), VertexColoring::Mean, options);
    REQUIRE(r->colors.colors.size() == direct.colors.size());
    CHECK(r->colors.colors == direct.colors);
    s.execute(ComputeColoring{VertexColoring::Gaussian, options, nullptr});
    s.finish_jobs();
    CHECK(s.coloring().result()->id == 2);
}

TEST_CASE("a load is a job: the document changes when it succeeds, and not when it fails",
          "[session]") {
    Session s;
    s.take_events();
    s.execute(LoadFile{data_file("good/header_variants.off"), true});
    CHECK(s.busy());
    s.finish_jobs();
    CHECK(s.history().size() == 1);  // it replaced the untouched default model
    CHECK(s.history().info(0).label == "Load header_variants.off");
    CHECK(s.document().name == "header_variants.off");
    SessionEvents e = s.take_events();
    CHECK(e.state_changed);
    CHECK(e.fit);
    REQUIRE(e.recent.size() == 1);
    require_valid(s);

    const std::size_t vertices = s.mesh().n_vertices();
    s.execute(LoadFile{data_file("bad/off_nan.off"), true});
    s.finish_jobs();
    CHECK(s.notice().level == Notice::Level::Error);
    CHECK(s.notice().text.find("off_nan.off:4") != std::string::npos);
    CHECK(s.history().size() == 1);
    CHECK(s.mesh().n_vertices() == vertices);
    CHECK_FALSE(s.take_events().state_changed);
}

TEST_CASE("an operation becomes one history entry and plays its morph", "[session]") {
    Session s;
    s.execute(RunOperation{parse_operation("noise --amount 30 --seed 4")});
    CHECK(s.busy());
    s.finish_jobs();
    REQUIRE(s.history().size() == 2);
    CHECK(s.history().current() == 1);
    CHECK(s.history().info(1).label == "Add noise");
    CHECK(s.document().unsaved);
    require_valid(s);
    // The morph plays from before to after: the view shows a morph frame until it ends.
    CHECK(s.morph().playing);
    s.update();
    CHECK(s.shown().kind == Shown::Kind::Morph);
    CHECK(s.shown().positions.size() == s.mesh().vertices_size());
    s.execute(ShowMorphAt{1.0});
    s.update();
    CHECK(s.shown().kind == Shown::Kind::Document);
    // Undo, redo, jump: the history moves, the view shows the state.
    s.execute(Undo{});
    CHECK(s.history().current() == 0);
    CHECK(s.shown().kind == Shown::Kind::Document);
    s.execute(Redo{});
    CHECK(s.history().current() == 1);
    s.execute(JumpTo{0});
    CHECK(s.history().current() == 0);
    require_valid(s);
}

TEST_CASE("a preview shows without an entry, Apply commits what is shown, Cancel drops it",
          "[session]") {
    Session s;
    const Operation loop = parse_operation("subdivide --scheme loop --iterations 2");
    s.execute(PreviewOperation{loop});
    s.finish_jobs();
    s.update();
    CHECK(s.history().size() == 1);
    REQUIRE(s.shown().kind == Shown::Kind::Preview);
    CHECK(s.shown().mesh->n_faces() == 16 * s.mesh().n_faces());
    CHECK(s.previews().previewing(loop));
    CHECK(s.previews().shown(loop));
    // One iteration fewer is shown at once from what was computed.
    const Operation one = parse_operation("subdivide --scheme loop --iterations 1");
    s.execute(PreviewOperation{one});
    CHECK_FALSE(s.busy());
    CHECK(s.shown().mesh->n_faces() == 4 * s.mesh().n_faces());
    s.execute(ApplyOperation{one});
    s.finish_jobs();
    REQUIRE(s.history().size() == 2);
    CHECK(s.mesh().n_faces() == 4 * s.history().mesh(0, 0).n_faces());
    require_valid(s);

    s.execute(PreviewOperation{parse_operation("noise --amount 10")});
    s.finish_jobs();
    s.update();
    CHECK(s.shown().kind == Shown::Kind::Preview);
    s.execute(CancelPreview{});
    CHECK(s.shown().kind == Shown::Kind::Document);
    CHECK(s.history().size() == 2);
}

TEST_CASE("an operation that changes nothing adds no entry and says so", "[session]") {
    Session s;
    s.execute(RunOperation{parse_operation("smooth --step 0 --iterations 1")});
    s.finish_jobs();
    CHECK(s.history().size() == 1);
    CHECK(s.notice().text.find("changed nothing: no history entry") != std::string::npos);
}

TEST_CASE("a refused operation is said, and the document stays", "[session]") {
    Session s;
    s.execute(RunOperation{parse_operation("subdivide --scheme loop --iterations 8")});
    s.finish_jobs();
    CHECK(s.history().size() == 1);
    CHECK(s.notice().level == Notice::Level::Error);
    CHECK(s.notice().text.find("at most 50 million") != std::string::npos);
    // A refused preview is kept as the preview's failure (a sweep ends on it).
    s.execute(PreviewOperation{parse_operation("subdivide --scheme loop --iterations 8")});
    s.finish_jobs();
    CHECK_FALSE(s.previews().failure().empty());
    CHECK(s.shown().kind == Shown::Kind::Document);
}

TEST_CASE("a job works on its own snapshot while the session goes on", "[session]") {
    Session s;
    load_sphere(s);
    const std::size_t entries = s.history().size();
    const HalfedgeMesh before = s.mesh();
    s.execute(RunOperation{parse_operation("decimate --percent 50")});
    REQUIRE(s.busy());
    // While it runs: the document is read on this thread, undo is refused (one job at a time).
    CHECK(s.mesh().n_vertices() == before.n_vertices());
    s.execute(Undo{});
    CHECK(s.history().size() == entries);
    s.finish_jobs();
    CHECK(s.history().size() == entries + 1);
    CHECK(s.mesh().n_vertices() < before.n_vertices());
    require_valid(s);
}

TEST_CASE("the level-of-detail slider shows levels and commits one as an entry", "[session]") {
    Session s;
    load_sphere(s);
    const std::size_t entries = s.history().size();
    s.execute(BuildLevelOfDetail{parse_operation("decimate")});
    s.finish_jobs();
    REQUIRE(s.levels().ready());
    CHECK_FALSE(s.levels().note().empty());
    s.execute(ShowLevelOfDetail{25.0});
    REQUIRE(s.shown().kind == Shown::Kind::Level);
    const std::size_t kept = s.shown().level->vertices();
    CHECK(kept < s.mesh().n_vertices() / 2);
    s.execute(ApplyLevelOfDetail{});
    REQUIRE(s.history().size() == entries + 1);
    CHECK(s.mesh().n_vertices() == kept);
    CHECK_FALSE(s.levels().ready());  // it belonged to the state before
    require_valid(s);
}

TEST_CASE("a frequency band shows live and is committed as a geometry-only entry", "[session]") {
    Session s;
    SpectrumOptions options;
    options.k = 20;
    s.take_events();
    s.execute(Decompose{operation_of(options)});
    s.finish_jobs();
    REQUIRE(s.document().frequency.valid);
    CHECK(s.take_events().decomposed_hi == std::optional<std::size_t>(19));
    s.execute(PreviewBand{0, 5});
    REQUIRE(s.shown().kind == Shown::Kind::Band);
    CHECK(s.shown().positions.size() == s.mesh().vertices_size());
    CHECK(s.history().size() == 1);
    s.execute(CommitBand{0, 5});
    REQUIRE(s.history().size() == 2);
    CHECK(s.document().frequency.applied);
    CHECK(s.document().frequency.applied_hi == 5);
    CHECK(s.mesh().topology_revision() == s.history().mesh(0, 0).topology_revision());
    require_valid(s);
}

TEST_CASE("saving writes the current state and marks the document saved", "[session]") {
    Session s;
    s.execute(RunOperation{parse_operation("noise --amount 5")});
    s.finish_jobs();
    REQUIRE(s.document().unsaved);
    const std::string path =
        (std::filesystem::temp_directory_path() / "trilab_session_test_save.off").string();
    s.take_events();
    s.execute(SaveFile{path});
    s.finish_jobs();
    CHECK_FALSE(s.document().unsaved);
    const SessionEvents e = s.take_events();
    CHECK(e.saved);
    const LoadedMesh back = read_mesh(path);
    CHECK(back.mesh.n_vertices() == s.mesh().n_vertices());
    std::filesystem::remove(path);
}

TEST_CASE("right after Decompose the full band is the mesh: no jump at the first touch",
          "[session]") {
    Session s;
    SpectrumOptions options;
    options.k = 12;  // far fewer than the 1,002 vertices: most of the shape is in the rest
    s.execute(Decompose{operation_of(options)});
    s.finish_jobs();
    REQUIRE(s.document().frequency.valid);
    // The sliders read 0 .. 11: that band, with the rest, is the mesh as it is.
    s.execute(PreviewBand{0, 11});
    REQUIRE(s.shown().kind == Shown::Kind::Band);
    double worst = 0;
    for (Vertex v : s.mesh().vertices())
        worst = std::max(worst, (s.shown().positions[v.idx()] - s.mesh().position(v)).norm());
    CHECK(worst < 1e-9);
    // One frequency fewer drops the rest with it: a real change, the user's.
    s.execute(PreviewBand{0, 10});
    double moved = 0;
    for (Vertex v : s.mesh().vertices())
        moved = std::max(moved, (s.shown().positions[v.idx()] - s.mesh().position(v)).norm());
    CHECK(moved > 1e-3);
    // The entry records the rest, so that replaying it gives the same positions.
    s.execute(CommitBand{0, 11});
    REQUIRE(s.history().size() == 2);
    const History::EntryInfo info = s.history().info(1);
    CHECK(info.operation.text().find("--with-rest") != std::string::npos);
}

TEST_CASE("the document may change while a job reads its snapshot, and the stale result is dropped",
          "[session]") {
    Session s;
    load_sphere(s);
    s.execute(BuildLevelOfDetail{parse_operation("decimate")});
    s.finish_jobs();
    REQUIRE(s.levels().ready());
    s.execute(ShowLevelOfDetail{50.0});
    // A job reads its snapshot on the worker while this thread pushes an entry (ThreadSanitizer
    // watches this in CI): the arrays they share are copy-on-write.
    s.execute(RunOperation{parse_operation("smooth --iterations 20")});
    REQUIRE(s.busy());
    const std::size_t entries = s.history().size();
    s.execute(ApplyLevelOfDetail{});
    REQUIRE(s.history().size() == entries + 1);
    const std::size_t vertices = s.mesh().n_vertices();
    s.finish_jobs();
    // The smoothing was computed on the state before: it is not stacked on the new one.
    CHECK(s.history().size() == entries + 1);
    CHECK(s.mesh().n_vertices() == vertices);
    CHECK(s.notice().text.find("changed while it ran") != std::string::npos);
    require_valid(s);
}

namespace {

/// A ray from far out on +z straight down at (x, y).
Ray ray_down(double x, double y) {
    Ray r;
    r.origin = Point(x, y, 10);
    r.direction = Vector3(0, 0, -1);
    return r;
}

/// The pick's elements belong together: the vertex and the edge are the face's.
void require_consistent(const Pick& p, const HalfedgeMesh& mesh) {
    REQUIRE(mesh.is_valid(p.face));
    const std::array<Vertex, 3> c = mesh.face_vertices(p.face);
    CHECK(std::find(c.begin(), c.end(), p.vertex) != c.end());
    REQUIRE(p.edge.is_valid());
    const Vertex a = mesh.vertex(p.edge, 0), b = mesh.vertex(p.edge, 1);
    CHECK(std::find(c.begin(), c.end(), a) != c.end());
    CHECK(std::find(c.begin(), c.end(), b) != c.end());
    // The vertex is the corner nearest to the hit point.
    for (Vertex v : c)
        CHECK((mesh.position(p.vertex) - p.position).norm() <=
              (mesh.position(v) - p.position).norm() + 1e-12);
}

}  // namespace

TEST_CASE("a pick names the front face under the ray, its nearest corner and edge",
          "[session][pick]") {
    Session s;
    const std::optional<Pick> hit = pick(s, ray_down(0.1, 0.05), false);
    REQUIRE(hit);
    CHECK(hit->position.z() > 0.5);  // the front of the sphere, not its back
    CHECK_FALSE(hit->back_face);
    require_consistent(*hit, s.mesh());
    REQUIRE(s.picking().picks().picks.size() == 1);
    // The background: the picks are cleared.
    CHECK_FALSE(pick(s, ray_down(5, 5), false).has_value());
    CHECK(s.picking().picks().picks.empty());
}

TEST_CASE("two picks measure: straight, geodesic and a path on the surface", "[session][pick]") {
    Session s;
    REQUIRE(pick(s, ray_down(0.3, 0.0), false));
    REQUIRE(pick(s, ray_down(-0.3, 0.2), true));
    REQUIRE(s.picking().picks().picks.size() == 2);
    CHECK(s.picking().picks().measurement.computing);
    s.finish_jobs();
    const Measurement& m = s.picking().picks().measurement;
    CHECK_FALSE(m.computing);
    CHECK(m.failure.empty());
    const Pick& a = s.picking().picks().picks[0];
    const Pick& b = s.picking().picks().picks[1];
    CHECK(m.straight == Approx((s.mesh().position(a.vertex) - s.mesh().position(b.vertex)).norm()));
    REQUIRE(std::isfinite(m.geodesic));
    // On a sphere of radius about 1 the surface distance is a little more than the chord;
    // the heat method is within a few edge lengths of the traced path.
    CHECK(m.geodesic > 0.9 * m.straight);
    CHECK(m.path_length >= m.straight - 1e-12);
    CHECK(std::abs(m.path_length - m.geodesic) < 0.1 * m.geodesic);
    REQUIRE(m.path.size() >= 2);
    CHECK((m.path.front() - s.mesh().position(b.vertex)).norm() < 1e-12);
    CHECK((m.path.back() - s.mesh().position(a.vertex)).norm() < 1e-12);
    // The factorization is kept for the state: a new second pick reuses it.
    const auto solver = s.picking().picks().solver;
    REQUIRE(solver);
    REQUIRE(pick(s, ray_down(-0.2, -0.3), true));
    s.finish_jobs();
    CHECK(s.picking().picks().solver == solver);
    // The colouring's distances from both picked vertices.
    s.execute(WantPickDistances{true});
    s.finish_jobs();
    REQUIRE(s.picking().picks().distances.size() == s.mesh().vertices_size());
    CHECK(s.picking().picks().distances[s.picking().picks().picks[0].vertex.idx()] == 0.0);
    CHECK(s.picking().picks().distances[s.picking().picks().picks[1].vertex.idx()] == 0.0);
}

TEST_CASE("picks follow geometry-only steps and are dropped by steps that renumber",
          "[session][pick]") {
    Session s;
    const std::optional<Pick> hit = pick(s, ray_down(0.1, 0.1), false);
    REQUIRE(hit);
    s.execute(RunOperation{parse_operation("noise --amount 20 --seed 2")});
    s.finish_jobs();
    REQUIRE(s.picking().picks().picks.size() == 1);
    const Pick& kept = s.picking().picks().picks[0];
    CHECK(kept.vertex == hit->vertex);
    CHECK(kept.face == hit->face);
    // The hit point moved with its face.
    Point expected = Point::Zero();
    for (int k = 0; k < 3; ++k)
        expected += hit->barycentric[k] * s.mesh().position(hit->corners[k]);
    CHECK((kept.position - expected).norm() < 1e-12);
    CHECK((kept.position - hit->position).norm() > 0);
    // Undo: the same connectivity, the picks stay.
    s.execute(Undo{});
    CHECK(s.picking().picks().picks.size() == 1);
    s.execute(RunOperation{parse_operation("subdivide --scheme loop --iterations 1")});
    s.finish_jobs();
    CHECK(s.picking().picks().picks.empty());
    CHECK(s.notice().text.find("picks dropped") != std::string::npos);
}

TEST_CASE("a pick on a morph frame or a level of detail hits what is shown", "[session][pick]") {
    Session s;
    load_sphere(s);
    s.execute(RunOperation{parse_operation("smooth --iterations 10 --step 0.9")});
    s.finish_jobs();
    s.execute(ShowMorphAt{0.0});  // the frame shows the state before the smoothing
    s.update();
    REQUIRE(s.shown().kind == Shown::Kind::Morph);
    const Ray ray = ray_down(0.37, 0.21);
    std::optional<Pick> on_frame = pick(s, ray, false);
    REQUIRE(on_frame);
    const auto direct = pick_face(*s.shown().mesh, s.shown().positions, ray);
    REQUIRE(direct);
    CHECK(on_frame->face.idx() == direct->triangle);
    CHECK((on_frame->position - direct->position).norm() < 1e-12);

    s.execute(ShowMorphAt{1.0});
    s.update();
    s.execute(BuildLevelOfDetail{parse_operation("decimate")});
    s.finish_jobs();
    REQUIRE(s.levels().ready());
    s.execute(ShowLevelOfDetail{20.0});
    REQUIRE(s.shown().kind == Shown::Kind::Level);
    const LevelOfDetail& lod = *s.shown().level;
    const std::optional<Pick> on_level = pick(s, ray, false);
    REQUIRE(on_level);
    CHECK(on_level->on_level);
    const auto lod_hit = pick_triangle(lod.faces(), lod.face_alive(), lod.positions(), ray);
    REQUIRE(lod_hit);
    CHECK((on_level->position - lod_hit->position).norm() < 1e-12);
    // Indices are the document's: the picked vertex is live on the level.
    REQUIRE(s.mesh().is_valid(on_level->vertex));
    CHECK(lod.vertex_alive()[lod.vertex_of(on_level->vertex.idx())] != 0);
    REQUIRE(on_level->face.is_valid());
    CHECK(lod.face_of(on_level->face.idx()) == lod_hit->triangle);
}

TEST_CASE(
    "a large decomposition's prediction is computed on a worker, the newest request's shown "
    "when it ends, and the exact job follows once it is drawn",
    "[session][lens]") {
    Session s;
    s.execute(Decompose{parse_operation("spectrum --full")});
    s.finish_jobs();
    REQUIRE(s.document().frequency.valid);
    // Every decomposition counts as large here.
    REQUIRE(setenv("TRILAB_ASYNC_PREDICTION_WORK", "1", 1) == 0);
    const Operation first = parse_operation("smooth --integration implicit --step 2");
    const Operation second = parse_operation("smooth --integration implicit --step 4");
    const std::optional<SessionPreviews::Predictable> p = s.previews().predictable(second);
    REQUIRE(p);
    CHECK(p->decomposition == s.document().frequency.decomposition);
    CHECK(p->options.step == 4);
    CHECK_FALSE(s.previews().predictable(parse_operation("smooth --operator curvature-flow")));
    s.execute(PreviewOperation{first});
    // Not in this frame: the worker computes it.
    CHECK(s.previews().prediction_computing());
    CHECK_FALSE(s.previews().prediction_shown());
    s.execute(PreviewOperation{second});  // waits for the first to end
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
    while (!s.previews().shown(second) && std::chrono::steady_clock::now() < deadline) {
        s.update();
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    REQUIRE(s.previews().shown(second));
    REQUIRE(s.previews().prediction_shown());
    CHECK_FALSE(s.previews().prediction_computing());
    const std::vector<Point> expected =
        predict_fairing(*p->decomposition, p->options, s.mesh().positions());
    CHECK(s.shown().mesh->positions() == expected);
    s.execute(PredictionDrawn{});
    s.wait_for_preview(0.0);
    CHECK((s.busy() || !s.previews().prediction_shown()));
    s.finish_jobs();
    s.update();
    CHECK_FALSE(s.previews().prediction_shown());
    CHECK(s.previews().shown(second));
    REQUIRE(unsetenv("TRILAB_ASYNC_PREDICTION_WORK") == 0);
    require_valid(s);
}

TEST_CASE("a fairing run that uses features gets no spectral prediction", "[session][lens]") {
    Session s;
    s.execute(RunOperation{parse_operation("features --angle 5")});
    s.finish_jobs();
    REQUIRE(has_features(s.mesh()));
    s.execute(Decompose{parse_operation("spectrum --full")});
    s.finish_jobs();
    REQUIRE(s.document().frequency.valid);
    // The feature vertices stay (or slide along their curves): the spectrum does not know.
    CHECK_FALSE(s.previews().predictable(parse_operation("smooth --integration implicit")));
    CHECK_FALSE(s.previews().predictable(
        parse_operation("smooth --integration implicit --feature-mode slide")));
    CHECK_FALSE(s.previews().predictable(
        parse_operation("smooth --integration implicit --features auto --feature-angle 30")));
    // Told to ignore them, the run is the spectrum's filter again.
    CHECK(
        s.previews().predictable(parse_operation("smooth --integration implicit --features none")));
    const Operation op = parse_operation("smooth --integration implicit --step 2");
    s.execute(PreviewOperation{op});
    CHECK_FALSE(s.previews().prediction_shown());
    s.finish_jobs();
    require_valid(s);
}

TEST_CASE(
    "with a decomposition of its operator a fairing preview shows the spectral prediction "
    "at once, then the exact result",
    "[session][lens]") {
    Session s;
    s.execute(Decompose{parse_operation("spectrum --full")});
    s.finish_jobs();
    REQUIRE(s.document().frequency.valid);
    const Operation op = parse_operation("smooth --integration implicit --step 2 --iterations 2");
    s.execute(PreviewOperation{op});
    // In the same frame: the prediction, marked as one.
    REQUIRE(s.previews().prediction_shown());
    CHECK(s.previews().shown(op));
    REQUIRE(s.shown().kind == Shown::Kind::Preview);
    const std::vector<Point> predicted = s.shown().mesh->positions();
    CHECK(predicted != s.mesh().positions());
    // The exact job waits until the view has drawn the prediction (prediction_drawn()), then
    // starts with the next frame (the viewer calls wait_for_preview once per frame).
    CHECK_FALSE(s.busy());
    s.update();
    CHECK_FALSE(s.busy());
    s.wait_for_preview(0.1);  // the prediction's frame
    CHECK_FALSE(s.busy());
    s.wait_for_preview(0.0);  // a frame that did not draw it yet (a large mesh's proxy)
    CHECK_FALSE(s.busy());
    CHECK(s.previews().prediction_shown());
    s.execute(PredictionDrawn{});
    CHECK_FALSE(s.busy());    // not within the frame that drew it
    s.wait_for_preview(0.0);  // the next frame: the exact job starts
    CHECK((s.busy() || !s.previews().prediction_shown()));
    s.finish_jobs();
    s.update();
    CHECK_FALSE(s.previews().prediction_shown());
    REQUIRE(s.previews().shown(op));
    const std::vector<Point>& exact = s.shown().mesh->positions();
    // A closed mesh, a linear operator, every frequency: the prediction is the result.
    double worst = 0;
    for (std::size_t i = 0; i < exact.size(); ++i)
        worst = std::max(worst, (exact[i] - predicted[i]).norm());
    CHECK(worst < 1e-6);
    // Another operator than the decomposition's: no prediction, the exact preview only.
    const Operation flow = parse_operation("smooth --operator curvature-flow --step 0.5");
    s.execute(PreviewOperation{flow});
    CHECK_FALSE(s.previews().prediction_shown());
    s.finish_jobs();
    s.update();
    CHECK(s.previews().shown(flow));
    require_valid(s);
}

namespace {

/// Waits (polling nothing, so that the job's end is not collected) until the session shows
/// a loading picture; false after 20 s.
bool wait_for_loading_picture(const Session& s) {
    for (int i = 0; i < 20000 && !s.files().loading_picture(); ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    return s.files().loading_picture() != nullptr;
}

}  // namespace

TEST_CASE("a load shows a picture from the file's arrays until the mesh is built",
          "[session][loading_picture]") {
    // A folder of this test's own (test::TempDir lives in the unit tests' helpers).
    const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                      ("trilab-loading-picture-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    struct Remove {
        std::filesystem::path dir;
        ~Remove() { std::filesystem::remove_all(dir); }
    } remove{dir};
    const std::string path = (dir / "sphere.ply").string();
    write_mesh(make_icosphere(10), path);
    ProxyMeshOptions options;
    options.target_triangles = 200;
    auto maker = [&](const PolygonSoup& soup) {
        return std::make_shared<ProxyMesh>(make_soup_proxy_mesh(soup, options));
    };

    SECTION("a load that succeeds: the picture goes, the mesh comes with it as its proxy") {
        Session s;
        s.set_loading_picture_maker(maker);
        s.take_events();
        s.execute(LoadFile{path, true});
        REQUIRE(wait_for_loading_picture(s));  // shown before the job's end is collected
        const auto picture = s.files().loading_picture();
        CHECK(picture->path == path);
        CHECK(picture->faces == 2000);
        CHECK(picture->proxy->triangles.size() <= 200);
        s.finish_jobs();
        CHECK_FALSE(s.files().loading_picture());
        CHECK(s.document().name == "sphere.ply");
        const SessionEvents e = s.take_events();
        REQUIRE(e.loaded_proxy);
        CHECK(e.loaded_proxy == picture->proxy);
        // The mesh's own proxy is the picture's (what lets the window skip a second one).
        const ProxyMesh own = make_proxy_mesh(s.mesh(), options);
        CHECK(own.positions == e.loaded_proxy->positions);
        CHECK(own.triangles == e.loaded_proxy->triangles);
        require_valid(s);
    }
    SECTION("a load that ends without a mesh: the picture goes, the document stays") {
        Session s;
        s.take_events();
        std::promise<void> go;
        std::shared_future<void> released = go.get_future().share();
        s.set_loading_picture_maker([&, released](const PolygonSoup& soup) {
            released.wait();  // the test cancels meanwhile
            return maker(soup);
        });
        s.execute(LoadFile{path, true});
        s.execute(CancelJob{});
        go.set_value();
        REQUIRE(wait_for_loading_picture(s));
        s.finish_jobs();
        CHECK_FALSE(s.files().loading_picture());
        CHECK(s.document().name != "sphere. py");
        CHECK(s.mesh().n_vertices() == 1002);  // still the default model
        CHECK_FALSE(s.take_events().state_changed);
    }
    SECTION("a file with an index out of range shows no picture") {
        const std::string bad = (dir / "bad.ply").string();
        std::ofstream(bad)
            << "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
               "property float y\nproperty float z\nelement face 1\nproperty list "
               "uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n";
        Session s;
        bool made = false;
        s.set_loading_picture_maker([&](const PolygonSoup& soup) {
            made = true;
            return maker(soup);
        });
        s.execute(LoadFile{bad, true});
        s.finish_jobs();
        CHECK_FALSE(made);
        CHECK_FALSE(s.files().loading_picture());
        CHECK(s.notice().level == Notice::Level::Error);
    }
}

TEST_CASE("the panels' guidance is computed off the render thread for the state asked about",
          "[session][guidance]") {
    Session s;
    s.execute(EstimateStableStep{FairingOperator::CurvatureFlow});
    s.execute(FindCollapsingEdges{parse_operation("decimate --percent 5")});
    s.finish_jobs();
    const SessionGuidance::StableStep* step = s.guidance().stable_step();
    REQUIRE(step);
    CHECK(step->state == s.mesh().revision());
    CHECK(step->op == FairingOperator::CurvatureFlow);
    CHECK(step->step == max_stable_explicit_step(s.mesh(), FairingOperator::CurvatureFlow));
    const SessionGuidance::CollapsingEdges* edges = s.guidance().collapsing_edges();
    REQUIRE(edges);
    CHECK(edges->failure.empty());
    const auto pairs =
        next_collapses(s.mesh(), decimation_options(parse_operation("decimate --percent 5")));
    REQUIRE(edges->segments.size() == pairs.size());
    REQUIRE_FALSE(pairs.empty());
    CHECK(edges->segments.front()[0] == s.mesh().position(pairs.front()[0]));
    CHECK(edges->segments.back()[1] == s.mesh().position(pairs.back()[1]));
    // Another state: what was computed stays marked with its own state until asked again.
    s.execute(RunOperation{parse_operation("noise --amount 5")});
    s.finish_jobs();
    CHECK(s.guidance().stable_step()->state != s.mesh().revision());
    s.execute(EstimateStableStep{FairingOperator::Umbrella});
    // Asked twice while it computes: one estimate, of the newest request.
    s.execute(EstimateStableStep{FairingOperator::Umbrella});
    s.finish_jobs();
    step = s.guidance().stable_step();
    CHECK(step->state == s.mesh().revision());
    CHECK(step->op == FairingOperator::Umbrella);
    CHECK(step->step == max_stable_explicit_step(s.mesh(), FairingOperator::Umbrella));
}

TEST_CASE("an operation that only writes properties is a history entry", "[session]") {
    // Detecting features moves no vertex but stores the feature edges: a change to keep (it
    // was once taken for "changed nothing").
    Session s;
    const std::string path =
        (std::filesystem::temp_directory_path() / "trilab_session_props_cube.off").string();
    write_mesh(generate("cube"), path);
    s.execute(LoadFile{path});
    s.finish_jobs();
    std::filesystem::remove(path);
    const std::size_t entries = s.history().size();
    s.execute(RunOperation{parse_operation("features --angle 60")});
    s.finish_jobs();
    REQUIRE(s.history().size() == entries + 1);
    CHECK(s.mesh().has_edge_property("e:sharpness"));
    require_valid(s);
}

TEST_CASE("picking again while the Inspector computes never waits, and shows the last pick",
          "[session][pick]") {
    Session s;
    std::optional<Pick> last;
    for (double x : {0.3, -0.2, 0.1, -0.35}) last = pick(s, ray_down(x, 0.1), false);
    REQUIRE(last);
    // Every pick returned at once; the inspection that arrives is of the last one.
    for (int i = 0; i < 5000 && s.picking().pending(); ++i) {
        s.poll();
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    REQUIRE_FALSE(s.picking().pending());
    const auto& inspection = s.picking().picks().inspection;
    REQUIRE(inspection);
    REQUIRE(inspection->vertex);
    CHECK(inspection->vertex->vertex == last->vertex);
}
