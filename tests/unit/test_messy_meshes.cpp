// Messy meshes (issue 17, item 8): coincident vertices (patch seams, the copies the loader
// makes of a non-manifold vertex) stay together through subdivision, fairing and decimation;
// welding joins them; pillows are left as they are while the rest is subdivided.
#include <algorithm>
#include <string>
#include <vector>

#include "app/ops/operation.h"
#include "core/algorithms/coincident.h"
#include "core/algorithms/decimation.h"
#include "core/algorithms/fairing.h"
#include "core/algorithms/generators.h"
#include "core/algorithms/mesh_stats.h"
#include "core/algorithms/noise.h"
#include "core/algorithms/pillows.h"
#include "core/algorithms/subdivision.h"
#include "core/algorithms/weld.h"
#include "core/errors.h"
#include "core/io/mesh_io.h"
#include "core/mesh_builder.h"
#include "test_helpers.h"

using namespace trilab;
using Scheme = SubdivisionScheme;

namespace {

const std::vector<Scheme> kAllSchemes = {Scheme::Loop, Scheme::Sqrt3, Scheme::Butterfly,
                                         Scheme::ModifiedButterfly};
const std::vector<Scheme> k1to4Schemes = {Scheme::Loop, Scheme::Butterfly,
                                          Scheme::ModifiedButterfly};

HalfedgeMesh build(const PolygonSoup& soup) {
    LoadReport report;
    return build_mesh(soup, report);
}

SubdivisionResult subdivide_n(const HalfedgeMesh& mesh, Scheme scheme, int iterations,
                              bool keep_levels = true) {
    NullProgress progress;
    SubdivisionOptions o;
    o.scheme = scheme;
    o.iterations = iterations;
    o.keep_levels = keep_levels;
    return subdivide(mesh, o, progress);
}

/// Two closed cones whose apexes are the same file vertex (0): the loader splits it in two.
HalfedgeMesh two_cones() {
    PolygonSoup s;
    s.positions.emplace_back(0, 0, 0);
    const unsigned n = 6;
    for (int side = 0; side < 2; ++side) {
        const double z = side == 0 ? 1.0 : -1.0;
        const Index ring = Index(s.positions.size());
        for (unsigned i = 0; i < n; ++i)
            s.positions.emplace_back(std::cos(2 * M_PI * i / n), std::sin(2 * M_PI * i / n), z);
        const Index centre = Index(s.positions.size());
        s.positions.emplace_back(0.1, 0, 1.2 * z);
        for (unsigned i = 0; i < n; ++i) {
            const Index a = ring + i, b = ring + (i + 1) % n;
            if (side == 0) {
                s.add_face({0, a, b});
                s.add_face({centre, b, a});
            } else {
                s.add_face({0, b, a});
                s.add_face({centre, a, b});
            }
        }
    }
    return build(s);
}

/// Two triangles touching at one vertex.
HalfedgeMesh bow_tie() {
    PolygonSoup s;
    s.positions = {{0, 0, 0}, {1, 0, 0.2}, {1, 1, 0}, {-1, 0, 0.3}, {-1, -1, 0}};
    s.add_face({0, 1, 2});
    s.add_face({0, 3, 4});
    return build(s);
}

/// An (n+1) x (n+1) bumpy grid cut along column `cut`: the cut's vertices are stored twice,
/// once for each half (a seam). `flip_right` reverses the right half's faces.
HalfedgeMesh seamed_grid(unsigned n, unsigned cut, bool flip_right = false, double gap = 0) {
    PolygonSoup s;
    auto id = [&](unsigned i, unsigned j, unsigned half) {
        // Left half: columns 0..cut; right half: columns cut..n.
        const unsigned left = (cut + 1) * (n + 1);
        return half == 0 ? Index(j * (cut + 1) + i) : Index(left + j * (n - cut + 1) + (i - cut));
    };
    for (unsigned half = 0; half < 2; ++half)
        for (unsigned j = 0; j <= n; ++j)
            for (unsigned i = half == 0 ? 0 : cut; i <= (half == 0 ? cut : n); ++i) {
                const double x = double(i) / n, y = double(j) / n;
                s.positions.emplace_back(
                    x + (half == 1 && i == cut ? gap : 0.0), y,
                    0.1 * std::sin(7 * x + 3 * y) + 0.05 * std::cos(11 * x * y));
            }
    for (unsigned half = 0; half < 2; ++half)
        for (unsigned j = 0; j < n; ++j)
            for (unsigned i = half == 0 ? 0 : cut; i < (half == 0 ? cut : n); ++i) {
                const Index a = id(i, j, half), b = id(i + 1, j, half), c = id(i + 1, j + 1, half),
                            d = id(i, j + 1, half);
                if (half == 1 && flip_right) {
                    s.add_face({a, c, b});
                    s.add_face({a, d, c});
                } else {
                    s.add_face({a, b, c});
                    s.add_face({a, c, d});
                }
            }
    return build(s);
}

/// Every group of `groups` (input vertex indices) has one position in `mesh` (the indices
/// are the same there: fairing, and subdivision's even vertices).
void require_together(const HalfedgeMesh& mesh, const CoincidentGroups& groups) {
    for (std::size_t g = 0; g < groups.size(); ++g)
        for (const Index* m = groups.begin(g) + 1; m != groups.end(g); ++m) {
            INFO("group " << g << ": vertex " << *m << " vs " << *groups.begin(g));
            REQUIRE(mesh.position(Vertex(*m)) == mesh.position(Vertex(*groups.begin(g))));
        }
}

/// Every live vertex of `a` lies within `d` of a vertex of `b` and the other way round.
bool same_points(const HalfedgeMesh& a, const HalfedgeMesh& b, double d) {
    std::vector<Point> p;
    std::vector<std::uint8_t> from_a;
    for (Vertex v : a.vertices()) {
        p.push_back(a.position(v));
        from_a.push_back(1);
    }
    for (Vertex v : b.vertices()) {
        p.push_back(b.position(v));
        from_a.push_back(0);
    }
    const CoincidentGroups g = find_coincident_points(p.data(), p.size(), nullptr, d);
    const std::vector<Index> group = g.group_of(p.size());
    std::vector<std::uint8_t> has_a(g.size(), 0), has_b(g.size(), 0);
    for (std::size_t i = 0; i < p.size(); ++i) {
        if (group[i] == kInvalidIndex) return false;  // nothing near it on the other side
        (from_a[i] ? has_a : has_b)[group[i]] = 1;
    }
    for (std::size_t k = 0; k < g.size(); ++k)
        if (!has_a[k] || !has_b[k]) return false;
    return true;
}

bool has_line(const std::vector<std::string>& lines, const std::string& text) {
    return std::any_of(lines.begin(), lines.end(),
                       [&](const std::string& l) { return l.find(text) != std::string::npos; });
}

}  // namespace

// ---- coincident vertices ----------------------------------------------------------------------

TEST_CASE("coincident points: exact groups treat -0 as +0, a tolerance links chains",
          "[coincident]") {
    const std::vector<Point> p = {{0, 0, 0},        {1, 2, 3}, {-0.0, 0, -0.0},
                                  {1, 2, 3.000001}, {1, 2, 3}, {5, 5, 5}};
    const CoincidentGroups exact = find_coincident_points(p.data(), p.size());
    REQUIRE(exact.size() == 2);
    REQUIRE(std::vector<Index>(exact.begin(0), exact.end(0)) == std::vector<Index>{0, 2});
    REQUIRE(std::vector<Index>(exact.begin(1), exact.end(1)) == std::vector<Index>{1, 4});
    const std::vector<std::uint8_t> skip = {0, 0, 1, 0, 0, 0};
    REQUIRE(find_coincident_points(p.data(), p.size(), skip.data()).size() == 1);
    const CoincidentGroups near = find_coincident_points(p.data(), p.size(), nullptr, 1e-5);
    REQUIRE(near.size() == 2);
    REQUIRE(std::vector<Index>(near.begin(1), near.end(1)) == std::vector<Index>{1, 3, 4});
    REQUIRE_THROWS_AS(find_coincident_points(p.data(), p.size(), nullptr, -1), InvalidArgument);
    REQUIRE_THROWS_AS(find_coincident_points(p.data(), p.size(), nullptr, 1e-300), InvalidArgument);
    // A tolerance that puts everything within reach of everything is refused, not quadratic.
    const HalfedgeMesh sphere = make_icosphere(80);  // 64,002 vertices
    REQUIRE_THROWS_WITH(find_coincident_vertices(sphere, 10.0),
                        Catch::Matchers::Contains("too large"));
    REQUIRE(find_coincident_vertices(sphere, 1e-9).empty());

    std::vector<Point> values = {{1, 0, 0}, {0, 0, 0}, {3, 0, 0}, {0, 0, 0}, {2, 0, 0}, {0, 0, 0}};
    REQUIRE(unify_groups(exact, values.data()) == 2);
    REQUIRE(values[0] == Point(2, 0, 0));
    REQUIRE(values[2] == Point(2, 0, 0));
    REQUIRE(values[1] == Point(1, 0, 0));
    REQUIRE(values[4] == Point(1, 0, 0));
    // Values that agree count once: the mean of the distinct values 0 and 6.
    const std::vector<Point> q = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
    const CoincidentGroups three = find_coincident_points(q.data(), q.size());
    std::vector<Point> agree = {{6, 0, 0}, {0, 0, 0}, {6, 0, 0}};
    unify_groups(three, agree.data());
    REQUIRE(agree == std::vector<Point>(3, Point(3, 0, 0)));
    REQUIRE(unify_groups(exact, values.data()) == 0);  // already equal: untouched
}

TEST_CASE("boundary edges pair up across a seam", "[coincident]") {
    const HalfedgeMesh grid = seamed_grid(6, 3);
    const BoundaryPairing p = pair_boundary_edges(grid);
    REQUIRE(p.boundary_edges == 4 * 6 + 2 * 6);
    REQUIRE(p.paired_edges == 2 * 6);
    REQUIRE(p.unpaired_edges == 4 * 6);
    REQUIRE(pair_boundary_edges(make_grid(6)).paired_edges == 0);
}

// ---- welding ----------------------------------------------------------------------------------

TEST_CASE("weld glues a seam into one surface", "[weld]") {
    const HalfedgeMesh grid = seamed_grid(6, 3);
    const WeldResult w = weld_coincident_vertices(grid);
    REQUIRE_VALID(w.mesh);
    REQUIRE(w.report.groups == 7);
    REQUIRE(w.report.vertices_joined == 7);
    REQUIRE(w.report.edges_glued == 6);
    REQUIRE(w.report.vertices_left_apart == 0);
    REQUIRE(w.report.notes.empty());
    REQUIRE(w.mesh.n_faces() == grid.n_faces());
    REQUIRE(w.mesh.n_vertices() == 7 * 7);
    const BoundaryPairing after = pair_boundary_edges(w.mesh);
    REQUIRE(after.boundary_edges == 4 * 6);
    REQUIRE(after.paired_edges == 0);
    // The map sends every vertex to one at its position; welding again joins nothing.
    for (Vertex v : grid.vertices())
        REQUIRE(w.mesh.position(Vertex(w.vertex_map[v.idx()])) == grid.position(v));
    REQUIRE(weld_coincident_vertices(w.mesh).report.vertices_joined == 0);
}

TEST_CASE("weld with a tolerance joins a seam that is a little apart, at the mean", "[weld]") {
    const HalfedgeMesh grid = seamed_grid(4, 2, false, 1e-7);
    REQUIRE(weld_coincident_vertices(grid).report.vertices_joined == 0);
    WeldOptions o;
    o.tolerance = 1e-6;
    const WeldResult w = weld_coincident_vertices(grid, o);
    REQUIRE_VALID(w.mesh);
    REQUIRE(w.report.vertices_joined == 5);
    REQUIRE(w.report.edges_glued == 4);
    const Vertex joined(w.vertex_map[2]);  // (cut, 0) of the left half
    REQUIRE(w.mesh.position(joined).x() == Approx(0.5 + 0.5e-7).epsilon(1e-12));
    o.tolerance = -1;
    REQUIRE_THROWS_AS(weld_coincident_vertices(grid, o), InvalidArgument);
}

TEST_CASE("weld leaves apart what would not be manifold, and says why", "[weld]") {
    SECTION("faces running the same way along the seam") {
        const WeldResult w = weld_coincident_vertices(seamed_grid(4, 2, true));
        REQUIRE_VALID(w.mesh);
        REQUIRE(w.report.edges_glued == 0);
        REQUIRE(w.report.edges_left_open == 8);
        REQUIRE(has_line(w.report.notes, "run the same way"));
    }
    SECTION("two cones touching at their apex") {
        const HalfedgeMesh cones = two_cones();
        REQUIRE(cones.n_vertices() == 16);  // the apex split in two by the loader
        const WeldResult w = weld_coincident_vertices(cones);
        REQUIRE_VALID(w.mesh);
        REQUIRE(w.report.vertices_joined == 0);
        REQUIRE(w.report.vertices_left_apart == 1);
        REQUIRE(has_line(w.report.notes, "non-manifold vertex"));
    }
    SECTION("three sheets along one edge") {
        PolygonSoup s;
        s.positions = {{0, 0, 0},  {0, 1, 0}, {1, 0, 0}, {0, 0, 0}, {0, 1, 0},
                       {-1, 0, 0}, {0, 0, 0}, {0, 1, 0}, {0, 0, 1}};
        s.add_face({0, 2, 1});
        s.add_face({3, 4, 5});
        s.add_face({6, 8, 7});
        const WeldResult w = weld_coincident_vertices(build(s));
        REQUIRE_VALID(w.mesh);
        REQUIRE(w.report.edges_glued == 0);
        REQUIRE(w.report.edges_left_open == 3);
        REQUIRE(has_line(w.report.notes, "three or more faces"));
    }
    SECTION("glues that would double an edge are undone") {
        // A quad (x, y, p) + (y, x, q) and a triangle (x, p, y) lying on its first half the
        // other way round: its edges x-p and p-y pair with the quad's boundary, but gluing
        // them would give two edges x-y (the quad's diagonal and the triangle's side).
        PolygonSoup s;
        s.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, -1, 0},
                       {0, 0, 0}, {0, 1, 0}, {1, 0, 0}};
        s.add_face({0, 1, 2});
        s.add_face({1, 0, 3});
        s.add_face({4, 5, 6});
        const HalfedgeMesh m = build(s);
        const WeldResult w = weld_coincident_vertices(m);
        REQUIRE_VALID(w.mesh);
        REQUIRE(w.mesh.n_faces() == 3);
        REQUIRE(w.report.edges_glued == 0);
        REQUIRE(w.report.vertices_joined == 0);
        REQUIRE(has_line(w.report.notes, "two edges between the same vertices"));
    }
    SECTION("an isolated vertex on top of a used one disappears") {
        PolygonSoup s;
        s.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 0, 0}};
        s.add_face({0, 1, 2});
        const WeldResult w = weld_coincident_vertices(build(s));
        REQUIRE_VALID(w.mesh);
        REQUIRE(w.mesh.n_vertices() == 3);
        REQUIRE(w.vertex_map[3] == w.vertex_map[1]);
    }
}

TEST_CASE("weld keeps attributes and accepts a mesh with garbage", "[weld]") {
    HalfedgeMesh grid = seamed_grid(4, 2);
    auto uv = grid.vertex_property<TexCoord>("v:texcoord");
    for (Vertex v : grid.vertices()) uv[v] = TexCoord(grid.position(v).x(), 7);
    grid.collapse(grid.find_halfedge(Vertex(0), Vertex(1)));  // leaves garbage
    REQUIRE(grid.has_garbage());
    const WeldResult w = weld_coincident_vertices(grid);
    REQUIRE_VALID(w.mesh);
    REQUIRE(w.vertex_map[0] == kInvalidIndex);
    REQUIRE(w.report.edges_glued == 4);
    const auto wuv = w.mesh.get_vertex_property<TexCoord>("v:texcoord");
    REQUIRE(wuv);
    for (Vertex v : grid.vertices()) REQUIRE(wuv[Vertex(w.vertex_map[v.idx()])].y() == 7);
}

// ---- subdivision ------------------------------------------------------------------------------

TEST_CASE("subdividing a seamed mesh gives the welded surface's points, seams closed",
          "[subdivision][coincident]") {
    const HalfedgeMesh seamed = seamed_grid(6, 3);
    const HalfedgeMesh welded = weld_coincident_vertices(seamed).mesh;
    const CoincidentGroups copies = find_coincident_vertices(seamed);
    const std::size_t open = pair_boundary_edges(seamed).unpaired_edges;
    for (Scheme s : kAllSchemes) {
        INFO(scheme_name(s));
        const SubdivisionResult r = subdivide_n(seamed, s, 2);
        for (const SubdivisionLevel& level : r.levels) REQUIRE_VALID(level.mesh);
        const HalfedgeMesh& out = r.levels.back().mesh;
        require_together(out, copies);  // old vertices keep their indices
        const BoundaryPairing p = pair_boundary_edges(out);
        // Every seam edge stays paired; only the open boundary's pieces are unpaired.
        REQUIRE(p.unpaired_edges == (s == Scheme::Sqrt3 ? 3 : 4) * open);
        if (s != Scheme::Sqrt3)  // Sqrt3 keeps a seam as a boundary curve (its flips would
                                 // dissolve it)
            REQUIRE(same_points(out, subdivide_n(welded, s, 2).levels.back().mesh, 1e-12));
    }
}

TEST_CASE("the teapot's seams stay closed and its poles keep no hole when subdivided",
          "[subdivision][coincident][shared]") {
    const std::string path = test::shared_mesh("teapot.obj");
    SKIP_IF_MISSING(path);
    const HalfedgeMesh teapot = read_mesh(path).mesh;
    const BoundaryPairing before = pair_boundary_edges(teapot);
    const CoincidentGroups copies = find_coincident_vertices(teapot);
    // The lid knob's pole: one file vertex the loader split into one copy per patch fan.
    std::vector<Index> pole;
    for (Vertex v : teapot.vertices())
        if (teapot.position(v) == Point(0, 3.15, 0)) pole.push_back(v.idx());
    REQUIRE(pole.size() >= 2);
    const HalfedgeMesh welded = weld_coincident_vertices(teapot).mesh;
    for (Scheme s : kAllSchemes) {
        INFO(scheme_name(s));
        const SubdivisionResult r = subdivide_n(teapot, s, 2);
        const HalfedgeMesh& out = r.levels.back().mesh;
        REQUIRE_VALID(out);
        const BoundaryPairing after = pair_boundary_edges(out);
        const std::size_t factor = s == Scheme::Sqrt3 ? 3 : 4;
        WARN(scheme_name(s) << " x2: " << after.unpaired_edges << " unpaired boundary edges of "
                            << after.boundary_edges << " (input " << before.unpaired_edges << " of "
                            << before.boundary_edges << ")");
        REQUIRE(after.unpaired_edges == factor * before.unpaired_edges);
        require_together(out, copies);
        for (Index v : pole) REQUIRE(out.position(Vertex(v)) == out.position(Vertex(pole[0])));
        if (s != Scheme::Sqrt3)
            REQUIRE(same_points(out, subdivide_n(welded, s, 2).levels.back().mesh, 1e-9));
    }
}

TEST_CASE("an isolated vertex on a seam stays where it is", "[subdivision][fairing][coincident]") {
    PolygonSoup soup = to_soup(seamed_grid(4, 2));
    const Point on_seam = soup.positions[2];  // (cut, 0) of the left half
    soup.positions.push_back(on_seam);
    const HalfedgeMesh mesh = build(soup);
    const Vertex isolated(Index(soup.positions.size() - 1));
    REQUIRE(mesh.is_isolated(isolated));
    for (Scheme s : kAllSchemes) {
        const HalfedgeMesh out = subdivide_n(mesh, s, 2).levels.back().mesh;
        REQUIRE(out.position(isolated) == on_seam);
        if (s == Scheme::Loop) REQUIRE(out.position(Vertex(2)) != on_seam);  // approximating
    }
    const FairingResult r = smooth(mesh, FairingOptions{});
    REQUIRE(r.mesh.position(isolated) == on_seam);
}

TEST_CASE("non-manifold points stay together through subdivision", "[subdivision][coincident]") {
    for (const HalfedgeMesh& mesh : {two_cones(), bow_tie()}) {
        const CoincidentGroups copies = find_coincident_vertices(mesh);
        REQUIRE(copies.size() == 1);
        for (Scheme s : kAllSchemes) {
            INFO(scheme_name(s));
            const SubdivisionResult r = subdivide_n(mesh, s, 3, false);
            REQUIRE_VALID(r.levels.back().mesh);
            require_together(r.levels.back().mesh, copies);
            REQUIRE(find_coincident_vertices(r.levels.back().mesh).size() == 1);
        }
    }
}

TEST_CASE("a pillow is left as it is while the rest is subdivided, with a note",
          "[subdivision][coincident]") {
    PolygonSoup soup = to_soup(make_icosahedron());
    const Index first = Index(soup.positions.size());
    soup.positions.emplace_back(3, 0, 0);
    soup.positions.emplace_back(4, 0, 0);
    soup.positions.emplace_back(3, 1, 0);
    soup.add_face({first, first + 1, first + 2});
    soup.add_face({first, first + 2, first + 1});
    const HalfedgeMesh mesh = build(soup);
    REQUIRE_VALID(mesh);
    REQUIRE(pillow_faces(mesh).size() == 2);
    for (Scheme s : kAllSchemes) {
        for (bool keep : {true, false}) {
            INFO(scheme_name(s) << (keep ? " all levels" : " last level"));
            const SubdivisionResult r = subdivide_n(mesh, s, 2, keep);
            REQUIRE(r.notes == std::vector<std::string>{
                                   "1 component left as it is: two triangles on the same three "
                                   "vertices"});
            const std::size_t factor = s == Scheme::Sqrt3 ? 3 : 4;
            REQUIRE(r.level_counts.back()[1] == 20 * factor * factor + 2);
            for (const SubdivisionLevel& level : r.levels) {
                REQUIRE_VALID(level.mesh);
                REQUIRE(level.correspondence.positions.size() == level.mesh.vertices_size());
                REQUIRE(pillow_faces(level.mesh).size() == 2);
                std::size_t found = 0;
                for (Vertex v : level.mesh.vertices())
                    for (Index k = 0; k < 3; ++k)
                        if (level.mesh.position(v) == soup.positions[first + k]) ++found;
                REQUIRE(found == 3);
            }
            REQUIRE(r.levels.back().mesh.n_faces() == r.level_counts.back()[1]);
        }
    }
    // Nothing set aside, no note, on a mesh without pillows.
    REQUIRE(subdivide_n(make_icosahedron(), Scheme::Loop, 1).notes.empty());
}

// ---- fairing ----------------------------------------------------------------------------------

TEST_CASE("fairing smooths a seam as one surface and keeps copies together",
          "[fairing][coincident]") {
    HalfedgeMesh seamed = seamed_grid(8, 4);
    const WeldResult weld = weld_coincident_vertices(seamed);
    const CoincidentGroups copies = find_coincident_vertices(seamed);
    std::vector<FairingOptions> runs(5);
    runs[1].op = FairingOperator::CurvatureFlow;
    runs[1].integration = Integration::Implicit;
    runs[1].step = 2;
    runs[2].op = FairingOperator::Taubin;
    runs[3].op = FairingOperator::SecondOrder;
    runs[4].boundary = BoundaryMode::Slide;
    for (FairingOptions o : runs) {
        o.iterations = 5;
        INFO(fairing_operator_name(o.op) << " " << integration_name(o.integration));
        const FairingResult a = smooth(seamed, o);
        const FairingResult b = smooth(weld.mesh, o);
        REQUIRE(!a.stopped_early);
        REQUIRE_VALID(a.mesh);
        require_together(a.mesh, copies);
        REQUIRE(a.step_positions.size() == 5);
        REQUIRE(a.step_positions.back() == a.mesh.positions());
        bool seam_moved = false;
        for (Vertex v : seamed.vertices()) {
            const Point& p = a.mesh.position(v);
            REQUIRE((p - b.mesh.position(Vertex(weld.vertex_map[v.idx()]))).norm() < 1e-12);
            if (copies.group_of(seamed.vertices_size())[v.idx()] != kInvalidIndex &&
                !weld.mesh.is_boundary(Vertex(weld.vertex_map[v.idx()])) && p != seamed.position(v))
                seam_moved = true;
        }
        REQUIRE(seam_moved);  // a seam is not a fixed boundary
        REQUIRE(has_line(a.report, "coincident vertices"));
    }
}

TEST_CASE("fairing keeps non-manifold copies where they are, and the teapot closed",
          "[fairing][coincident]") {
    for (const HalfedgeMesh& mesh : {two_cones(), bow_tie()}) {
        const CoincidentGroups copies = find_coincident_vertices(mesh);
        for (Integration in : {Integration::Explicit, Integration::Implicit}) {
            FairingOptions o;
            o.integration = in;
            o.iterations = 3;
            o.boundary = BoundaryMode::Slide;
            const FairingResult r = smooth(mesh, o);
            REQUIRE_VALID(r.mesh);
            require_together(r.mesh, copies);
            REQUIRE(r.mesh.position(Vertex(copies.members[0])) ==
                    mesh.position(Vertex(copies.members[0])));
        }
    }
    const std::string path = test::shared_mesh("teapot.obj");
    SKIP_IF_MISSING(path);
    const HalfedgeMesh teapot = read_mesh(path).mesh;
    const CoincidentGroups copies = find_coincident_vertices(teapot);
    FairingOptions o;
    o.op = FairingOperator::CurvatureFlow;
    o.iterations = 3;
    const FairingResult r = smooth(teapot, o);
    REQUIRE(!r.stopped_early);
    require_together(r.mesh, copies);
    REQUIRE(pair_boundary_edges(r.mesh).paired_edges == pair_boundary_edges(teapot).paired_edges);
}

// ---- decimation -------------------------------------------------------------------------------

TEST_CASE("decimation never moves one copy of a coincident vertex alone",
          "[decimation][coincident]") {
    std::vector<std::pair<std::string, HalfedgeMesh>> meshes = {{"seamed grid", seamed_grid(10, 5)},
                                                                {"two cones", two_cones()}};
    const std::string path = test::shared_mesh("teapot.obj");
    if (test::present_or_skip(path)) meshes.emplace_back("teapot", read_mesh(path).mesh);
    for (const auto& [name, mesh] : meshes) {
        for (DecimationCost cost : {DecimationCost::Quadric, DecimationCost::Roundness}) {
            INFO(name << ", " << decimation_cost_name(cost));
            const CoincidentGroups copies = find_coincident_vertices(mesh);
            DecimationOptions o;
            o.cost = cost;
            o.percent = 60;
            const DecimationResult r = decimate(mesh, o);
            REQUIRE(r.report.collapses > 0);
            REQUIRE(r.report.coincident_vertices == copies.members.size());
            const HalfedgeMesh& out = r.levels.back().mesh;
            REQUIRE_VALID(out);
            // The copies of a vertex end at one place (the geomorph's end positions) ...
            const auto& end = r.levels.back().correspondence.positions;
            for (std::size_t g = 0; g < copies.size(); ++g)
                for (const Index* m = copies.begin(g); m != copies.end(g); ++m)
                    REQUIRE(end[*m] == end[*copies.begin(g)]);
            // ... so welding opens no crack: the welded result has the input's boundary loops.
            REQUIRE(count_boundary_loops(weld_coincident_vertices(out).mesh) ==
                    count_boundary_loops(weld_coincident_vertices(mesh).mesh));
            const std::size_t left = find_coincident_vertices(out).members.size();
            if (name == "two cones")
                REQUIRE(left == copies.members.size());  // a non-manifold point stays
            else
                REQUIRE(left < copies.members.size());  // seams are decimated, both sides
        }
    }
}

// ---- the operation ----------------------------------------------------------------------------

TEST_CASE("the weld operation parses, runs and reports", "[operation][weld]") {
    const Operation op = parse_operation("weld --tolerance 0.001");
    REQUIRE(op.text() == "weld --tolerance 0.001");
    REQUIRE_THROWS_WITH(parse_operation("weld --tolerance -1"),
                        Catch::Matchers::Contains("--tolerance"));
    NullProgress progress;
    const HalfedgeMesh grid = seamed_grid(4, 2);
    const OperationResult r = run_operation(parse_operation("weld"), grid, progress);
    REQUIRE(r.steps.size() == 1);
    REQUIRE_VALID(r.steps[0].mesh);
    REQUIRE(r.steps[0].mesh.n_vertices() == grid.n_vertices() - 5);
    REQUIRE(r.steps[0].correspondence.positions.size() == r.steps[0].mesh.vertices_size());
    REQUIRE(has_line(r.report, "4 boundary edge pairs glued"));
    // Subdividing a pillow notes it in the report.
    const HalfedgeMesh pillow =
        read_mesh(test::data_file("good/pillow_beside_tetrahedron.off")).mesh;
    const OperationResult s = run_operation(parse_operation("subdivide"), pillow, progress);
    REQUIRE(has_line(s.report, "note: 1 component left as it is"));
}
