// Morphing between two states: t = 0 is the earlier shape and t = 1 the later one for every
// correspondence kind, midpoints, clamping, size checks, easing curves and playback clocks.
#include <cmath>
#include <limits>

#include "core/algorithms/generators.h"
#include "core/algorithms/morph.h"
#include "core/errors.h"
#include "test_helpers.h"

using namespace trilab;
using Kind = MorphCorrespondence::Kind;

namespace {

/// Exact (bitwise for finite values) equality of two position arrays.
bool same_positions(const std::vector<Point>& a, const std::vector<Point>& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i)
        if (a[i] != b[i]) return false;
    return true;
}

/// An icosphere and the same mesh with every vertex moved outwards by 10%.
struct GeometryChange {
    HalfedgeMesh before = make_icosphere(2);
    HalfedgeMesh after = before;
    GeometryChange() {
        for (Vertex v : after.vertices()) after.position(v) *= 1.1;
    }
};

/// An icosphere with one edge split; the new vertex sits on the sphere and starts at the
/// edge's midpoint (a FromEarlier correspondence, as subdivision fills it in).
struct Refinement {
    HalfedgeMesh before = make_icosphere(2);
    HalfedgeMesh after = before;
    MorphCorrespondence corr{Kind::FromEarlier, {}};
    Vertex added;
    Point midpoint;
    Refinement() {
        const Edge e(0);
        midpoint =
            0.5 * (before.position(before.vertex(e, 0)) + before.position(before.vertex(e, 1)));
        added = after.split(e, midpoint.normalized());
        corr.positions = before.positions();
        corr.positions.resize(after.vertices_size());
        corr.positions[added.idx()] = midpoint;
    }
};

/// An icosphere with one edge collapsed; the removed vertex travels to the kept one (a
/// ToLater correspondence, as decimation fills it in).
struct Coarsening {
    HalfedgeMesh before = make_icosphere(2);
    HalfedgeMesh after = before;
    MorphCorrespondence corr{Kind::ToLater, {}};
    Vertex removed, kept;
    Coarsening() {
        const Halfedge h = HalfedgeMesh::halfedge(Edge(0), 0);
        removed = before.from_vertex(h);
        kept = before.to_vertex(h);
        REQUIRE(after.is_collapse_ok(h));
        after.collapse(h);
        corr.positions = before.positions();
        corr.positions[removed.idx()] = after.position(kept);
    }
};

}  // namespace

TEST_CASE("SameVertices: t = 0 is the earlier shape, t = 1 the later, 0.5 the midpoint",
          "[morph]") {
    GeometryChange g;
    const MorphCorrespondence corr{Kind::SameVertices, {}};
    const MorphFrame f0 = morph_frame(g.before, g.after, corr, 0.0);
    REQUIRE(f0.topology == &g.after);
    REQUIRE(same_positions(f0.positions, g.before.positions()));
    const MorphFrame f1 = morph_frame(g.before, g.after, corr, 1.0);
    REQUIRE(f1.topology == &g.after);
    REQUIRE(same_positions(f1.positions, g.after.positions()));
    const MorphFrame half = morph_frame(g.before, g.after, corr, 0.5);
    for (Vertex v : g.after.vertices()) {
        const Point mid = 0.5 * (g.before.position(v) + g.after.position(v));
        REQUIRE((half.positions[v.idx()] - mid).norm() < 1e-15);
    }
}

TEST_CASE("FromEarlier: a split vertex starts at its edge's midpoint", "[morph]") {
    Refinement r;
    REQUIRE_VALID(r.after);
    check_correspondence(r.before, r.after, r.corr);
    const MorphFrame f0 = morph_frame(r.before, r.after, r.corr, 0.0);
    REQUIRE(f0.topology == &r.after);
    REQUIRE(f0.positions.size() == r.after.vertices_size());
    // t = 0: the old vertices where they were, the new one on the old surface.
    for (Vertex v : r.before.vertices()) REQUIRE(f0.positions[v.idx()] == r.before.position(v));
    REQUIRE(f0.positions[r.added.idx()] == r.midpoint);
    const MorphFrame f1 = morph_frame(r.before, r.after, r.corr, 1.0);
    REQUIRE(f1.topology == &r.after);
    REQUIRE(same_positions(f1.positions, r.after.positions()));
    const MorphFrame half = morph_frame(r.before, r.after, r.corr, 0.5);
    const Point expected = 0.5 * (r.midpoint + r.after.position(r.added));
    REQUIRE((half.positions[r.added.idx()] - expected).norm() < 1e-15);
}

TEST_CASE("ToLater: a geomorph on the finer mesh, then the coarser mesh itself", "[morph]") {
    Coarsening c;
    REQUIRE_VALID(c.after);
    REQUIRE(c.after.is_deleted(c.removed));
    check_correspondence(c.before, c.after, c.corr);
    const MorphFrame f0 = morph_frame(c.before, c.after, c.corr, 0.0);
    REQUIRE(f0.topology == &c.before);
    REQUIRE(same_positions(f0.positions, c.before.positions()));
    const MorphFrame f1 = morph_frame(c.before, c.after, c.corr, 1.0);
    REQUIRE(f1.topology == &c.after);
    REQUIRE(same_positions(f1.positions, c.after.positions()));
    // Just before the end, the finer mesh with the removed vertex almost at its target.
    const MorphFrame late = morph_frame(c.before, c.after, c.corr, 0.999);
    REQUIRE(late.topology == &c.before);
    REQUIRE((late.positions[c.removed.idx()] - c.after.position(c.kept)).norm() < 1e-2);
    const MorphFrame half = morph_frame(c.before, c.after, c.corr, 0.5);
    const Point expected = 0.5 * (c.before.position(c.removed) + c.after.position(c.kept));
    REQUIRE((half.positions[c.removed.idx()] - expected).norm() < 1e-15);
    REQUIRE(half.positions[c.kept.idx()] == c.before.position(c.kept));
}

TEST_CASE("morph_frame clamps t to [0, 1]", "[morph]") {
    GeometryChange g;
    const MorphCorrespondence corr{Kind::SameVertices, {}};
    REQUIRE(
        same_positions(morph_frame(g.before, g.after, corr, -3).positions, g.before.positions()));
    REQUIRE(same_positions(morph_frame(g.before, g.after, corr, 7).positions, g.after.positions()));
    {
        const test::FpTrapsOff traps_off;  // NaN on purpose
        REQUIRE(same_positions(
            morph_frame(g.before, g.after, corr, std::numeric_limits<double>::quiet_NaN())
                .positions,
            g.before.positions()));
    }
    Coarsening c;
    REQUIRE(morph_frame(c.before, c.after, c.corr, 2).topology == &c.after);
    REQUIRE(morph_frame(c.before, c.after, c.corr, -2).topology == &c.before);
}

TEST_CASE("deleted vertices keep the drawn mesh's stored position", "[morph]") {
    // A geometry change after a collapse: the deleted vertex is not interpolated.
    Coarsening c;
    HalfedgeMesh moved = c.after;
    for (Vertex v : moved.vertices()) moved.position(v) *= 2.0;
    moved.positions()[c.removed.idx()] = Point(5, 5, 5);
    const MorphFrame f = morph_frame(c.after, moved, MorphCorrespondence{}, 0.5);
    REQUIRE(f.positions[c.removed.idx()] == Point(5, 5, 5));
    REQUIRE(f.positions[c.kept.idx()] == 1.5 * c.after.position(c.kept));
}

TEST_CASE("correspondences that do not fit the meshes are refused, naming the problem", "[morph]") {
    Refinement r;
    SECTION("SameVertices needs equal vertex storage") {
        const MorphCorrespondence corr{Kind::SameVertices, {}};
        REQUIRE_THROWS_AS(check_correspondence(r.before, r.after, corr), InvalidArgument);
        REQUIRE_THROWS_WITH(morph_frame(r.before, r.after, corr, 0.5),
                            Catch::Contains("SameVertices") && Catch::Contains("vertices"));
    }
    SECTION("FromEarlier needs one start per later vertex") {
        MorphCorrespondence corr = r.corr;
        corr.positions.pop_back();
        REQUIRE_THROWS_WITH(morph_frame(r.before, r.after, corr, 0.5),
                            Catch::Contains("FromEarlier") && Catch::Contains("start positions"));
    }
    SECTION("ToLater needs one end per earlier vertex") {
        MorphCorrespondence corr{Kind::ToLater, r.corr.positions};  // one too many
        REQUIRE_THROWS_WITH(check_correspondence(r.before, r.after, corr),
                            Catch::Contains("ToLater") && Catch::Contains("end positions"));
    }
    SECTION("positions must be finite") {
        MorphCorrespondence corr = r.corr;
        corr.positions[3].y() = std::numeric_limits<double>::infinity();
        REQUIRE_THROWS_WITH(check_correspondence(r.before, r.after, corr),
                            Catch::Contains("position 3") && Catch::Contains("not finite"));
    }
}

TEST_CASE("easing curves run from 0 to 1, monotone, and clamp", "[morph]") {
    const Easing e = GENERATE(Easing::Linear, Easing::SmoothStep, Easing::EaseInOutCubic);
    INFO(easing_name(e));
    REQUIRE(ease(e, 0) == 0);
    REQUIRE(ease(e, 1) == 1);
    REQUIRE(ease(e, 0.5) == Approx(0.5));
    REQUIRE(ease(e, -1) == 0);
    REQUIRE(ease(e, 2) == 1);
    double previous = 0;
    for (int i = 1; i <= 1000; ++i) {
        const double value = ease(e, i / 1000.0);
        REQUIRE(value >= previous);
        previous = value;
    }
    REQUIRE(parse_easing(easing_name(e)) == e);
}

TEST_CASE("easing formulas", "[morph]") {
    REQUIRE(ease(Easing::SmoothStep, 0.25) == Approx(3 * 0.0625 - 2 * 0.015625));
    REQUIRE(ease(Easing::EaseInOutCubic, 0.25) == Approx(4 * 0.015625));
    REQUIRE(ease(Easing::EaseInOutCubic, 0.75) == Approx(1 - 4 * 0.015625));
    REQUIRE_THROWS_AS(parse_easing("bouncy"), InvalidArgument);
}

TEST_CASE("playback: once clamps, loop wraps, ping-pong goes there and back", "[morph]") {
    REQUIRE(playback_time(Playback::Once, -1, 2) == 0);
    REQUIRE(playback_time(Playback::Once, 1, 2) == 0.5);
    REQUIRE(playback_time(Playback::Once, 5, 2) == 1);

    REQUIRE(playback_time(Playback::Loop, 0, 2) == 0);
    REQUIRE(playback_time(Playback::Loop, 1, 2) == 0.5);
    REQUIRE(playback_time(Playback::Loop, 5, 2) == 0.5);
    REQUIRE(playback_time(Playback::Loop, 4, 2) == 0);
    REQUIRE(playback_time(Playback::Loop, -0.5, 2) == 0.75);

    REQUIRE(playback_time(Playback::PingPong, 0, 2) == 0);
    REQUIRE(playback_time(Playback::PingPong, 1, 2) == 0.5);
    REQUIRE(playback_time(Playback::PingPong, 2, 2) == 1);
    REQUIRE(playback_time(Playback::PingPong, 3, 2) == 0.5);
    REQUIRE(playback_time(Playback::PingPong, 4, 2) == 0);
    REQUIRE(playback_time(Playback::PingPong, 5, 2) == 0.5);
    // Continuous and within [0, 1] over several periods.
    const Playback p = GENERATE(Playback::Once, Playback::Loop, Playback::PingPong);
    for (int i = 0; i <= 1000; ++i) {
        const double t = playback_time(p, i * 0.0123, 1.7);
        REQUIRE(t >= 0);
        REQUIRE(t <= 1);
    }
    // A non-positive duration shows the end state.
    REQUIRE(playback_time(p, 0.3, 0) == 1);
    REQUIRE(playback_time(p, 0.3, -1) == 1);
    REQUIRE(playback_time(p, std::numeric_limits<double>::quiet_NaN(), 1) == 0);
    REQUIRE(parse_playback(playback_name(p)) == p);
    REQUIRE_THROWS_AS(parse_playback("sometimes"), InvalidArgument);
}
