// The document's selection in the session (issue 26): every selection edit is one history
// entry that undo and redo restore, operations and their morphs keep, saving writes; the brush
// and lasso select what a known view shows.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

#include "app/history/recipe.h"
#include "app/ops/operation.h"
#include "app/session/screen_selection.h"
#include "app/session/session.h"
#include "core/algorithms/generators.h"
#include "core/algorithms/mesh_stats.h"
#include "core/algorithms/orientation.h"
#include "core/algorithms/selection.h"
#include "core/io/mesh_io.h"
#include "core/mesh_builder.h"
#include "core/validate.h"
#include "tests/app/pick_helpers.h"

using namespace trilab;
using namespace trilab::viewer;

namespace {

/// The document's weights (empty without a selection).
Selection weights_of(const Session& s) {
    return s.selections().get().value_or(Selection{});
}

/// The vertices as a camera far away on +z (distance 50, looking at the origin) shows them in
/// a 500 x 500 view: world (x, y) at about pixel (250 + 200 x, 250 − 200 y) (within 2% at
/// |z| <= 1), depth w = 50 − z.
ProjectedVertices project_front(const HalfedgeMesh& mesh, bool through) {
    const double d = 50.0;
    ScreenView view;
    view.width = view.height = 500;
    view.view_projection.setZero();
    view.view_projection(0, 0) = 0.8 * d;
    view.view_projection(1, 1) = 0.8 * d;
    view.view_projection(2, 2) = -1.0;
    view.view_projection(3, 2) = -1.0;
    view.view_projection(3, 3) = d;
    return project_vertices(mesh, mesh.positions(), view, through);
}

}  // namespace

TEST_CASE("a selection edit is one history entry that undo and redo restore",
          "[session][selection]") {
    Session s;
    const std::size_t before = s.history().size();
    REQUIRE_FALSE(s.selections().get());
    s.execute(SelectSpec{"sphere:0,0,1,0.6"});
    REQUIRE(s.history().size() == before + 1);
    const Selection first = weights_of(s);
    REQUIRE(count_selected(first) > 0);
    REQUIRE(count_selected(first) < s.mesh().n_vertices());
    CHECK(s.selections().count() == count_selected(first));
    CHECK(s.history().info(s.history().current()).label == "Select");

    s.execute(EditSelection{EditSelection::Kind::Grow, 2, 0});
    REQUIRE(s.history().size() == before + 2);
    const Selection grown = weights_of(s);
    CHECK(count_selected(grown) > count_selected(first));

    s.execute(Undo{});
    CHECK(weights_of(s) == first);
    s.execute(Undo{});
    CHECK_FALSE(s.selections().get());
    s.execute(Redo{});
    CHECK(weights_of(s) == first);
    s.execute(Redo{});
    CHECK(weights_of(s) == grown);

    // Invert, feather, shrink, clear: one entry each.
    s.execute(EditSelection{EditSelection::Kind::Invert, 1, 0});
    CHECK(count_selected(weights_of(s)) == s.mesh().n_vertices() - count_selected(grown));
    s.execute(EditSelection{EditSelection::Kind::Shrink, 1, 0});
    s.execute(EditSelection{EditSelection::Kind::Feather, 1, 0.3});
    const Selection feathered = weights_of(s);
    CHECK(std::any_of(feathered.begin(), feathered.end(), [](float w) { return w > 0 && w < 1; }));
    s.execute(EditSelection{EditSelection::Kind::Clear, 1, 0});
    CHECK_FALSE(s.selections().get());
    CHECK(s.history().size() == before + 6);
    // The shape never moved.
    CHECK(s.mesh().positions() == s.history().mesh(0, 0).positions());
    CHECK(validate(s.mesh()).ok);
}

TEST_CASE("a bad selection is refused with a notice and no entry", "[session][selection]") {
    Session s;
    const std::size_t before = s.history().size();
    s.execute(SetSelection{Selection(3, 1.0f), "Brush", ""});
    CHECK(s.history().size() == before);
    CHECK(s.notice().level == Notice::Level::Error);
    s.execute(SelectSpec{"sphere:0,0"});
    CHECK(s.history().size() == before);
    CHECK(s.notice().text.find("--region") != std::string::npos);
    // No pick yet: the geodesic ball asks for one.
    s.execute(SelectAtPick{false, 0.5, SelectionMode::Replace});
    CHECK(s.history().size() == before);
    CHECK(s.notice().text.find("pick") != std::string::npos);
    // No values in the colouring: the threshold says so.
    s.execute(SelectThreshold{0.0, true, SelectionMode::Replace});
    CHECK(s.history().size() == before);
    // Nothing to grow.
    s.execute(EditSelection{EditSelection::Kind::Grow, 1, 0});
    CHECK(s.history().size() == before);
}

TEST_CASE("selections combine: add takes the larger weight, remove takes it away",
          "[session][selection]") {
    Session s;
    s.execute(SelectSpec{"sphere:0,0,1,0.5"});
    const Selection a = weights_of(s);
    s.execute(SelectSpec{"sphere:0,0,-1,0.5", SelectionMode::Add});
    const Selection both = weights_of(s);
    CHECK(count_selected(both) > count_selected(a));
    s.execute(SelectSpec{"sphere:0,0,-1,0.5", SelectionMode::Remove});
    CHECK(weights_of(s) == a);
    // The threshold on the colouring's values (here: z).
    std::vector<double> z(s.mesh().vertices_size());
    for (Vertex v : s.mesh().vertices()) z[v.idx()] = s.mesh().position(v).z();
    s.execute(SetColoringValues{z});
    s.execute(SelectThreshold{0.5, true, SelectionMode::Replace});
    for (Vertex v : s.mesh().vertices())
        CHECK((weights_of(s)[v.idx()] == 1.0f) == (s.mesh().position(v).z() > 0.5));
}

TEST_CASE("the geodesic ball and the component come from the pick", "[session][selection]") {
    Session s;
    Ray ray;
    ray.origin = Point(0.05, 0.02, 5);
    ray.direction = Vector3(0, 0, -1);
    const std::optional<Pick> hit = pick(s, ray, false);
    REQUIRE(hit);
    s.execute(SelectAtPick{false, 0.4, SelectionMode::Replace});
    const Selection ball = weights_of(s);
    REQUIRE(ball.size() == s.mesh().vertices_size());
    CHECK(ball[hit->vertex.idx()] == 1.0f);
    CHECK(count_selected(ball) > 1);
    CHECK(count_selected(ball) < s.mesh().n_vertices() / 2);
    s.execute(SelectAtPick{true, 0, SelectionMode::Replace});
    CHECK(count_selected(weights_of(s)) == s.mesh().n_vertices());  // one component
}

TEST_CASE("operations and their morphs keep the selection, and the region is what they act on",
          "[session][selection]") {
    Session s;
    s.execute(SelectSpec{"sphere:0,0,1,0.7,0.2"});
    const Selection w = weights_of(s);
    const std::vector<Point> before = s.mesh().positions();
    s.execute(RunOperation{parse_operation("smooth --iterations 3")});
    s.finish_jobs();
    REQUIRE(s.history().info(s.history().current()).label.find("mooth") != std::string::npos);
    CHECK(weights_of(s) == w);  // kept by the operation
    // The morph frame shows a state whose selection is the same.
    const MorphFrame frame = s.history().morph(s.history().current(), 0.5);
    REQUIRE(frame.topology);
    CHECK(stored_selection(*frame.topology) == w);
    // Weight-0 vertices did not move; some selected ones did.
    bool moved = false;
    for (Vertex v : s.mesh().vertices()) {
        if (w[v.idx()] == 0.0f) CHECK(s.mesh().position(v) == before[v.idx()]);
        moved = moved || s.mesh().position(v) != before[v.idx()];
    }
    CHECK(moved);
    // Undo goes back to the state with the selection and the old shape.
    s.execute(Undo{});
    CHECK(weights_of(s) == w);
    CHECK(s.mesh().positions() == before);
}

TEST_CASE("a preview follows the selection", "[session][selection]") {
    Session s;
    s.execute(SelectSpec{"sphere:0,0,1,0.5"});
    const Operation op = parse_operation("smooth --iterations 5");
    s.execute(PreviewOperation{op});
    s.finish_jobs();
    REQUIRE(s.previews().shown(op));
    const std::vector<Point> first = s.shown().mesh->positions();
    s.execute(SelectSpec{"sphere:0,0,-1,0.5"});
    s.finish_jobs();
    REQUIRE(s.previews().shown(op));  // computed again, on the new selection
    const std::vector<Point> second = s.shown().mesh->positions();
    CHECK(first != second);
    const Selection w = weights_of(s);
    for (Vertex v : s.mesh().vertices())
        if (w[v.idx()] == 0.0f) CHECK(second[v.idx()] == s.mesh().position(v));
}

TEST_CASE("saving to PLY keeps the weights and loading reads them back", "[session][selection]") {
    Session s;
    s.execute(SelectSpec{"sphere:0,0,1,0.7,0.3"});
    const Selection w = weights_of(s);
    const std::string path =
        (std::filesystem::temp_directory_path() / "trilab_selection_session.ply").string();
    s.execute(SaveFile{path});
    s.finish_jobs();
    Session t;
    t.execute(LoadFile{path});
    t.finish_jobs();
    REQUIRE(t.document().path == path);
    CHECK(weights_of(t) == w);
    std::filesystem::remove(path);
}

TEST_CASE("the brush and the lasso select what the view shows", "[session][selection]") {
    const HalfedgeMesh sphere = make_icosphere(8);
    // Seen from +z: the brush at the centre takes the front cap only.
    const ProjectedVertices visible = project_front(sphere, false);
    Selection w(sphere.vertices_size(), 0.0f);
    const std::size_t painted =
        paint_brush(visible, Eigen::Vector2f(250, 250), Eigen::Vector2f(250, 250), 40, true, w);
    CHECK(painted == count_selected(w));
    REQUIRE(painted > 0);
    for (Vertex v : sphere.vertices()) {
        const Point& p = sphere.position(v);
        const double r = std::hypot(p.x(), p.y());  // pixels ≈ 200 r
        if (w[v.idx()] > 0) {
            CHECK(p.z() > 0);
            CHECK(r < 0.21);
        } else if (p.z() > 0.3) {
            CHECK(r > 0.19);
        }
    }
    // A drag covers the segment; removing takes it away again.
    Selection stroke(sphere.vertices_size(), 0.0f);
    paint_brush(visible, Eigen::Vector2f(150, 250), Eigen::Vector2f(350, 250), 20, true, stroke);
    CHECK(count_selected(stroke) > count_selected(w));
    paint_brush(visible, Eigen::Vector2f(150, 250), Eigen::Vector2f(350, 250), 20, false, stroke);
    CHECK(count_selected(stroke) == 0);

    // A lasso around the middle: the visible surface only, or through the model.
    const std::vector<Eigen::Vector2f> square{{200, 200}, {300, 200}, {300, 300}, {200, 300}};
    const Selection front = lasso_selection(visible, square);
    const Selection through = lasso_selection(project_front(sphere, true), square);
    std::size_t n_front = 0, n_back = 0;
    for (Vertex v : sphere.vertices()) {
        const Point& p = sphere.position(v);
        const bool inside = std::abs(p.x()) < 0.24 && std::abs(p.y()) < 0.24;
        if (front[v.idx()] > 0) {
            CHECK(p.z() > 0);
            ++n_front;
        }
        if (through[v.idx()] > 0) n_back += p.z() < 0;
        if (inside && p.z() > 0) CHECK(front[v.idx()] == 1.0f);
    }
    CHECK(n_front > 0);
    CHECK(n_back > 0);
    CHECK(count_selected(through) > count_selected(front));
}

TEST_CASE("a region's flip uses the state's components, kept with its topology",
          "[session][selection]") {
    // Two icospheres apart, one component each; the selection on the first.
    HalfedgeMesh two = make_icosphere(2);
    {
        PolygonSoup soup = to_soup(two), second = to_soup(two);
        const Index n = Index(soup.positions.size());
        for (const Point& p : second.positions) soup.positions.push_back(p + Point(3, 0, 0));
        for (std::size_t f = 0; f < second.n_faces(); ++f) {
            std::vector<Index> face;
            for (std::size_t c = second.face_offsets[f]; c < second.face_offsets[f + 1]; ++c)
                face.push_back(second.corners[c] + n);
            soup.add_face(face);
        }
        LoadReport report;
        two = build_mesh(soup, report);
    }
    const std::string path =
        (std::filesystem::temp_directory_path() / "trilab_two_spheres_session.ply").string();
    write_mesh(two, path);
    Session s;
    s.execute(LoadFile{path});
    s.finish_jobs();
    std::filesystem::remove(path);
    // The statistics' labels, for this topology.
    REQUIRE(s.document().components);
    CHECK(s.document().components->size() == s.mesh().vertices_size());
    CHECK(s.document().components_topology == s.mesh().topology_revision());
    std::vector<Index> labels;
    CHECK(label_components(s.mesh(), labels) == 2);
    CHECK(*s.document().components == labels);

    s.execute(SelectSpec{"sphere:0,0,1,0.5"});
    const HalfedgeMesh before = s.mesh();
    s.execute(RunOperation{parse_operation("flip")});
    s.finish_jobs();
    REQUIRE(s.history().info(s.history().current()).label == "Flip orientation");
    REQUIRE(validate(s.mesh()));
    // The first sphere turned, the second did not: what the core's flip does.
    HalfedgeMesh expected = before;
    FlipOptions options;
    const Selection w = weights_of(s);
    options.region = &w;
    flip_orientation(expected, options);
    CHECK(s.mesh().halfedge_next_array() == expected.halfedge_next_array());
    CHECK(s.mesh().halfedge_face_array() == expected.halfedge_face_array());
    CHECK(s.mesh().halfedge_next_array() != before.halfedge_next_array());
    // The new state has its own labels (the flip keeps the components, not the arrays).
    CHECK(s.document().components_topology == s.mesh().topology_revision());
}

TEST_CASE("a session's recipe replays its selections: the viewer's state bit for bit",
          "[session][selection][recipe]") {
    // Issue 38, item 1, as the viewer builds the session: noise on everything, a sphere
    // selected, implicit curvature flow on it, a brush stroke, grown, noise on that, and a
    // threshold of the colouring (weights only). The recipe replays every state.
    Session s;
    const HalfedgeMesh loaded = s.mesh();
    s.execute(RunOperation{parse_operation("noise --amount 20 --seed 3")});
    s.finish_jobs();
    s.execute(SelectSpec{"sphere:0,0,1,0.6"});
    s.execute(RunOperation{
        parse_operation("smooth --operator curvature-flow --integration implicit --step 3")});
    s.finish_jobs();
    Selection brush(s.mesh().vertices_size(), 0.0f);
    for (std::size_t i = 0; i < brush.size(); i += 5) brush[i] = i % 2 ? 1.0f : 0.5f;
    s.execute(SetSelection{brush, "Brush", "radius 12 px"});
    s.execute(EditSelection{EditSelection::Kind::Grow, 1, 0});
    s.execute(RunOperation{parse_operation("noise --amount 4 --seed 9")});
    s.finish_jobs();
    REQUIRE(s.history().size() == 7);
    const Recipe recipe = recipe_of(s.history());
    CHECK(recipe.operations() == 3);
    CHECK(recipe.selections() == 3);
    CHECK(recipe.steps[1].from == RecipeStep::From::Spec);
    const Recipe back = parse_recipe(recipe_json(recipe), "r.json");
    CHECK(first_difference(replay(back, loaded), s.mesh()) == "");
    // The smoothing moved the sphere's vertices only.
    const HalfedgeMesh before = s.history().mesh(2, 0), after = s.history().mesh(3, 0);
    const Selection sphere = *stored_selection(before);
    for (Vertex v : before.vertices())
        if (sphere[v.idx()] == 0.0f) REQUIRE(before.position(v) == after.position(v));
}

TEST_CASE("an empty selection is refused by every operation, adding no entry",
          "[session][selection]") {
    // Issue 38, item 10: a selection of 0 vertices; subdivision added a no-op entry, the
    // other operations ran and vanished.
    Session s;
    s.execute(SelectSpec{"sphere:100,100,100,0.1"});
    REQUIRE(s.selections().get());
    REQUIRE(s.selections().count() == 0);
    const std::size_t entries = s.history().size();
    for (const char* text : {"subdivide", "smooth --iterations 3", "noise", "decimate"}) {
        INFO(text);
        s.execute(RunOperation{parse_operation(text)});
        s.finish_jobs();
        CHECK(s.history().size() == entries);
        CHECK(s.notice().text.find("the region is empty (0 of") != std::string::npos);
    }
}
