// Subdivision: exact element counts (the reference's 20-vertex model included), interpolation,
// linear precision, convergence towards the sphere, open meshes and boundary loops, the morph
// correspondence, per-vertex levels, texture coordinates, bad options and cancellation.
#include <algorithm>
#include <cmath>
#include <vector>

#include "core/algorithms/generators.h"
#include "core/algorithms/mesh_stats.h"
#include "core/algorithms/morph.h"
#include "core/algorithms/subdivision.h"
#include "core/errors.h"
#include "core/io/mesh_io.h"
#include "core/mesh_builder.h"
#include "test_helpers.h"

using namespace trilab;
using Scheme = SubdivisionScheme;

namespace {

const std::vector<Scheme> kAllSchemes = {Scheme::Loop, Scheme::Sqrt3, Scheme::Butterfly,
                                         Scheme::ModifiedButterfly};

SubdivisionResult run(const HalfedgeMesh& mesh, Scheme scheme, int iterations) {
    NullProgress progress;
    SubdivisionOptions options;
    options.scheme = scheme;
    options.iterations = iterations;
    return subdivide(mesh, options, progress);
}

bool all_finite(const HalfedgeMesh& mesh) {
    for (Vertex v : mesh.vertices())
        if (!mesh.position(v).allFinite()) return false;
    return true;
}

/// Every level is valid, finite and has a fitting FromEarlier correspondence.
void check_levels(const HalfedgeMesh& input, const SubdivisionResult& result) {
    const HalfedgeMesh* before = &input;
    for (const SubdivisionLevel& level : result.levels) {
        REQUIRE_VALID(level.mesh);
        REQUIRE(all_finite(level.mesh));
        REQUIRE(level.correspondence.kind == MorphCorrespondence::Kind::FromEarlier);
        REQUIRE_NOTHROW(check_correspondence(*before, level.mesh, level.correspondence));
        before = &level.mesh;
    }
}

/// A genus-0 closed model with 20 vertices and 36 faces: a bipyramid over an 18-gon.
HalfedgeMesh twenty_vertex_model() {
    PolygonSoup soup;
    const Index n = 18;
    for (Index i = 0; i < n; ++i) {
        const double a = 2 * 3.14159265358979323846 * i / n;
        soup.positions.emplace_back(std::cos(a), std::sin(a), 0.1 * std::sin(3 * a));
    }
    soup.positions.emplace_back(0, 0, 1);
    soup.positions.emplace_back(0, 0, -1);
    for (Index i = 0; i < n; ++i) {
        const Index j = (i + 1) % n;
        soup.add_face({i, j, n});
        soup.add_face({j, i, n + 1});
    }
    LoadReport report;
    return build_mesh(soup, report);
}

double radius_error(const Point& p) {
    return std::abs(p.norm() - 1.0);
}

}  // namespace

TEST_CASE("scheme names round-trip and bad options throw", "[subdivision]") {
    for (Scheme s : kAllSchemes) REQUIRE(parse_scheme(scheme_name(s)) == s);
    REQUIRE_THROWS_AS(parse_scheme("catmull-clark"), InvalidArgument);
    const HalfedgeMesh ico = make_icosahedron();
    NullProgress progress;
    for (int iterations : {0, -1, 11}) {
        SubdivisionOptions options;
        options.iterations = iterations;
        REQUIRE_THROWS_AS(subdivide(ico, options, progress), InvalidArgument);
        try {
            subdivide(ico, options, progress);
        } catch (const InvalidArgument& e) {
            REQUIRE(std::string(e.what()).find("iterations") != std::string::npos);
        }
    }
    // 1,280 faces * 4^10 is far beyond 50 million: refused before any work.
    SubdivisionOptions big;
    big.iterations = 10;
    REQUIRE_THROWS_AS(subdivide(make_icosphere(8), big, progress), InvalidArgument);
}

TEST_CASE("subdivision gives exact element counts on closed meshes", "[subdivision]") {
    const std::vector<HalfedgeMesh> meshes = {make_tetrahedron(), make_icosahedron(), make_cube(),
                                              make_torus(8, 6, 1.0, 0.3)};
    for (const HalfedgeMesh& mesh : meshes) {
        for (Scheme s : kAllSchemes) {
            INFO(scheme_name(s));
            const auto result = run(mesh, s, 2);
            check_levels(mesh, result);
            const HalfedgeMesh* before = &mesh;
            for (const auto& level : result.levels) {
                const std::size_t v = before->n_vertices(), e = before->n_edges(),
                                  f = before->n_faces();
                if (s == Scheme::Sqrt3) {
                    REQUIRE(level.mesh.n_vertices() == v + f);
                    REQUIRE(level.mesh.n_faces() == 3 * f);
                    REQUIRE(level.mesh.n_edges() == e + 3 * f);
                } else {
                    REQUIRE(level.mesh.n_vertices() == v + e);
                    REQUIRE(level.mesh.n_faces() == 4 * f);
                    REQUIRE(level.mesh.n_edges() == 2 * e + 3 * f);
                }
                REQUIRE(compute_stats(level.mesh).euler == compute_stats(mesh).euler);
                before = &level.mesh;
            }
        }
    }
}

TEST_CASE("the reference's 20-vertex model gives the reference's vertex counts", "[subdivision]") {
    const HalfedgeMesh model = twenty_vertex_model();
    REQUIRE_VALID(model);
    REQUIRE(model.n_vertices() == 20);
    REQUIRE(model.n_faces() == 36);
    REQUIRE(model.n_edges() == 54);
    REQUIRE(long(model.n_vertices()) - long(model.n_edges()) + long(model.n_faces()) == 2);
    const std::vector<std::size_t> one_to_four = {74, 290, 1154, 4610, 18434};
    const std::vector<std::size_t> sqrt3 = {56, 164, 488, 1460, 4376};
    for (Scheme s : kAllSchemes) {
        INFO(scheme_name(s));
        const auto result = run(model, s, 5);
        REQUIRE(result.levels.size() == 5);
        check_levels(model, result);
        const auto& expected = s == Scheme::Sqrt3 ? sqrt3 : one_to_four;
        for (std::size_t i = 0; i < 5; ++i)
            REQUIRE(result.levels[i].mesh.n_vertices() == expected[i]);
    }
}

TEST_CASE("interpolating schemes keep even vertices exactly in place", "[subdivision]") {
    const std::vector<HalfedgeMesh> meshes = {make_noisy_sphere(3, 0.1, 7), make_grid(5),
                                              make_cylinder(12, 4), twenty_vertex_model()};
    for (const HalfedgeMesh& mesh : meshes) {
        for (Scheme s : {Scheme::Butterfly, Scheme::ModifiedButterfly}) {
            const auto result = run(mesh, s, 2);
            check_levels(mesh, result);
            const HalfedgeMesh* before = &mesh;
            for (const auto& level : result.levels) {
                for (Vertex v : before->vertices())
                    REQUIRE(level.mesh.position(v) == before->position(v));
                before = &level.mesh;
            }
        }
    }
}

TEST_CASE("loop subdivision has linear precision on a planar grid", "[subdivision]") {
    // Every Loop rule (interior and boundary) is an affine combination, so a grid whose heights
    // are z = a x + b y + c keeps every vertex (interior and boundary) on that plane.
    HalfedgeMesh grid = make_grid(8);
    const double a = 0.3, b = -0.7, c = 0.25;
    for (Vertex v : grid.vertices()) {
        Point& p = grid.position(v);
        p.z() = a * p.x() + b * p.y() + c;
    }
    for (Scheme s : {Scheme::Loop, Scheme::Sqrt3}) {
        INFO(scheme_name(s));
        const auto result = run(grid, s, 3);
        check_levels(grid, result);
        for (const auto& level : result.levels)
            for (Vertex v : level.mesh.vertices()) {
                const Point& p = level.mesh.position(v);
                REQUIRE(std::abs(p.z() - (a * p.x() + b * p.y() + c)) < 1e-12);
            }
    }
}

TEST_CASE("subdividing a sphere approximation moves it towards the sphere", "[subdivision]") {
    // What is checked: (1) on a noisy icosphere (frequency 4, radial noise +-10%), the mean
    // |r - 1| over the vertices drops after one step of every scheme (smoothing the noise
    // outweighs Loop's and Sqrt3's slight shrinking); (2) on the icosahedron (vertices on the
    // sphere, flat faces inside it) the roundness (max r - min r) / mean r over all vertices
    // and face centroids drops with each of three steps of every scheme (Loop and Sqrt3
    // shrink the shape, so the distance to the unit sphere itself is not the measure there);
    // (3) for the interpolating schemes, whose vertices stay on or near the sphere, the mean
    // |r - 1| over the face centroids drops with each step.
    const HalfedgeMesh noisy = make_noisy_sphere(4, 0.1, 11);
    double before = 0;
    for (Vertex v : noisy.vertices()) before += radius_error(noisy.position(v));
    before /= double(noisy.n_vertices());
    const HalfedgeMesh ico = make_icosahedron();
    auto centroid = [](const HalfedgeMesh& m, Face f) {
        const auto c = m.face_vertices(f);
        return Point((m.position(c[0]) + m.position(c[1]) + m.position(c[2])) / 3.0);
    };
    auto centroid_error = [&](const HalfedgeMesh& m) {
        double sum = 0;
        for (Face f : m.faces()) sum += radius_error(centroid(m, f));
        return sum / double(m.n_faces());
    };
    auto roundness = [&](const HalfedgeMesh& m) {
        std::vector<double> r;
        for (Vertex v : m.vertices()) r.push_back(m.position(v).norm());
        for (Face f : m.faces()) r.push_back(centroid(m, f).norm());
        double lo = r[0], hi = r[0], sum = 0;
        for (double x : r) {
            lo = std::min(lo, x);
            hi = std::max(hi, x);
            sum += x;
        }
        return (hi - lo) / (sum / double(r.size()));
    };
    for (Scheme s : kAllSchemes) {
        INFO(scheme_name(s));
        const auto result = run(noisy, s, 1);
        const HalfedgeMesh& fine = result.levels[0].mesh;
        double after = 0;
        for (Vertex v : fine.vertices()) after += radius_error(fine.position(v));
        after /= double(fine.n_vertices());
        INFO("mean |r - 1| " << before << " -> " << after);
        REQUIRE(after < before);

        const auto ico_result = run(ico, s, 3);
        double previous = roundness(ico), previous_error = centroid_error(ico);
        for (const auto& level : ico_result.levels) {
            const double e = roundness(level.mesh), ce = centroid_error(level.mesh);
            INFO("roundness " << previous << " -> " << e);
            INFO("centroid |r - 1| " << previous_error << " -> " << ce);
            REQUIRE(e < previous);
            if (s == Scheme::Butterfly || s == Scheme::ModifiedButterfly)
                REQUIRE(ce < previous_error);
            previous = e;
            previous_error = ce;
        }
    }
}

TEST_CASE("open meshes subdivide into valid meshes with the same boundary loops", "[subdivision]") {
    std::vector<HalfedgeMesh> meshes = {make_grid(4), make_cylinder(10, 3)};
    for (const char* name : {"teapot.obj", "suzanne.obj"}) {
        const std::string path = test::shared_mesh(name);
        if (!test::present_or_skip(path)) continue;
        HalfedgeMesh m = read_mesh(path).mesh;
        m.garbage_collection();
        meshes.push_back(std::move(m));
    }
    for (const HalfedgeMesh& mesh : meshes) {
        const std::size_t loops = count_boundary_loops(mesh);
        REQUIRE(loops > 0);
        std::size_t boundary = 0;
        for (Edge e : mesh.edges()) boundary += mesh.is_boundary(e) ? 1 : 0;
        for (Scheme s : kAllSchemes) {
            INFO(scheme_name(s) << " on a mesh with " << mesh.n_faces() << " faces");
            const int iterations = mesh.n_faces() > 5000 ? 2 : 3;
            const auto result = run(mesh, s, iterations);
            check_levels(mesh, result);
            std::size_t expected = boundary;
            for (int i = 0; i < iterations; ++i) {
                const HalfedgeMesh& m = result.levels[std::size_t(i)].mesh;
                REQUIRE(count_boundary_loops(m) == loops);
                // 1-to-4 splits every boundary edge; Sqrt3 splits them 1-to-3 every second step.
                if (s != Scheme::Sqrt3) expected *= 2;
                if (s == Scheme::Sqrt3 && i % 2 == 1) expected *= 3;
                std::size_t count = 0;
                for (Edge e : m.edges()) count += m.is_boundary(e) ? 1 : 0;
                REQUIRE(count == expected);
            }
        }
    }
}

TEST_CASE("isolated vertices are kept, unmoved, at level 0", "[subdivision]") {
    HalfedgeMesh mesh = make_icosahedron();
    const Vertex lone = mesh.add_vertex(Point(3, 4, 5));
    for (Scheme s : kAllSchemes) {
        const auto result = run(mesh, s, 2);
        check_levels(mesh, result);
        const HalfedgeMesh& fine = result.levels.back().mesh;
        REQUIRE(fine.is_isolated(lone));
        REQUIRE(fine.position(lone) == Point(3, 4, 5));
        REQUIRE(fine.get_vertex_property<int>("v:subdivision_level")[lone] == 0);
    }
}

TEST_CASE("the subdivision morph starts on the coarse surface and ends on the fine one",
          "[subdivision]") {
    const std::vector<HalfedgeMesh> meshes = {make_noisy_sphere(2, 0.1, 3), make_grid(4)};
    for (const HalfedgeMesh& mesh : meshes) {
        for (Scheme s : kAllSchemes) {
            INFO(scheme_name(s));
            const auto result = run(mesh, s, 2);
            const HalfedgeMesh* before = &mesh;
            for (const auto& level : result.levels) {
                const MorphFrame start = morph_frame(*before, level.mesh, level.correspondence, 0);
                const MorphFrame end = morph_frame(*before, level.mesh, level.correspondence, 1);
                REQUIRE(start.topology == &level.mesh);
                REQUIRE(start.positions == level.correspondence.positions);
                REQUIRE(end.positions == level.mesh.positions());
                // Even vertices start exactly at their coarse positions.
                for (Vertex v : before->vertices())
                    REQUIRE(start.positions[v.idx()] == before->position(v));
                // Odd vertices start at an edge midpoint (1-to-4) or a face centroid (Sqrt3);
                // on the boundary in Sqrt3's even steps at the edge's third points.
                std::size_t odd = 0;
                if (s == Scheme::Sqrt3) {
                    for (Face f : before->faces()) {
                        const auto c = before->face_vertices(f);
                        const Point centroid = (before->position(c[0]) + before->position(c[1]) +
                                                before->position(c[2])) /
                                               3.0;
                        const Point& p = start.positions[before->vertices_size() + f.idx()];
                        REQUIRE((p - centroid).norm() < 1e-14);
                        ++odd;
                    }
                } else {
                    for (Edge e : before->edges()) {
                        const Point m = 0.5 * (before->position(before->vertex(e, 0)) +
                                               before->position(before->vertex(e, 1)));
                        REQUIRE(start.positions[before->vertices_size() + e.idx()] == m);
                        ++odd;
                    }
                }
                REQUIRE(odd > 0);
                before = &level.mesh;
            }
        }
    }
}

TEST_CASE("every vertex records the iteration that created it", "[subdivision]") {
    const HalfedgeMesh mesh = make_icosahedron();
    for (Scheme s : kAllSchemes) {
        INFO(scheme_name(s));
        const auto result = run(mesh, s, 3);
        for (std::size_t k = 0; k < result.levels.size(); ++k) {
            const HalfedgeMesh& m = result.levels[k].mesh;
            auto level = m.get_vertex_property<int>("v:subdivision_level");
            REQUIRE(level);
            std::vector<std::size_t> counts(k + 2, 0);
            for (Vertex v : m.vertices()) {
                REQUIRE(level[v] >= 0);
                REQUIRE(std::size_t(level[v]) <= k + 1);
                ++counts[std::size_t(level[v])];
            }
            // Level 0: the original vertices; level j: one per edge (1-to-4) or per face
            // (Sqrt3) of level j - 1.
            REQUIRE(counts[0] == mesh.n_vertices());
            for (std::size_t j = 1; j <= k + 1; ++j) {
                const HalfedgeMesh& parent = j == 1 ? mesh : result.levels[j - 2].mesh;
                REQUIRE(counts[j] == (s == Scheme::Sqrt3 ? parent.n_faces() : parent.n_edges()));
            }
        }
    }
}

TEST_CASE("texture coordinates are interpolated linearly", "[subdivision]") {
    // uv is an affine function of the position on the input, per vertex and per corner; the
    // corner uvs get a different offset on each side of a seam (x > 0 or not, by face). New
    // uvs must be the same affine function of each vertex's start position (where it sits on
    // the coarse surface), with the seam offset of the face it came from.
    auto chart = [](const Point& p) { return TexCoord(0.5 + 0.5 * p.x(), 0.25 + 0.5 * p.y()); };
    const TexCoord offset(10, 0);
    for (bool open : {false, true}) {
        HalfedgeMesh mesh = open ? make_cylinder(12, 4) : make_icosphere(2);
        auto vuv = mesh.vertex_property<TexCoord>("v:texcoord");
        for (Vertex v : mesh.vertices()) vuv[v] = chart(mesh.position(v));
        auto huv = mesh.halfedge_property<TexCoord>("h:texcoord");
        for (Face f : mesh.faces()) {
            const auto c = mesh.face_vertices(f);
            const bool side =
                (mesh.position(c[0]) + mesh.position(c[1]) + mesh.position(c[2])).x() > 0;
            for (Halfedge h : mesh.halfedges_of(f))
                huv[h] = chart(mesh.position(mesh.to_vertex(h))) + (side ? offset : TexCoord(0, 0));
        }
        for (Scheme s : kAllSchemes) {
            INFO(scheme_name(s) << (open ? " open" : " closed"));
            const auto result = run(mesh, s, 2);
            // Sqrt3's flips cut across old edges, so a seam cannot survive there: it is checked
            // on the vertex uvs and, per corner, up to the seam offset.
            const bool seams = s != Scheme::Sqrt3;
            const HalfedgeMesh* before = &mesh;
            for (const auto& level : result.levels) {
                const HalfedgeMesh& m = level.mesh;
                const auto& start = level.correspondence.positions;
                auto v2 = m.get_vertex_property<TexCoord>("v:texcoord");
                auto h2 = m.get_halfedge_property<TexCoord>("h:texcoord");
                REQUIRE(v2);
                REQUIRE(h2);
                REQUIRE_FALSE(m.has_vertex_property("v:normal"));
                for (Vertex v : m.vertices()) {
                    // Even vertices keep their uv exactly.
                    if (v.idx() < before->vertices_size())
                        REQUIRE(v2[v] == before->get_vertex_property<TexCoord>("v:texcoord")[v]);
                }
                // Level 1: the uvs are the affine chart of each vertex's start position (the
                // coarse input's surface). Later levels start on level 1's moved surface, where
                // the uvs are no longer the chart of the position.
                if (before != &mesh) break;
                for (Vertex v : m.vertices())
                    REQUIRE((v2[v] - chart(start[v.idx()])).norm() < 1e-12);
                for (Face f : m.faces()) {
                    std::vector<TexCoord> shift;
                    for (Halfedge h : m.halfedges_of(f)) {
                        const TexCoord d = h2[h] - chart(start[m.to_vertex(h).idx()]);
                        const bool zero = d.norm() < 1e-12, off = (d - offset).norm() < 1e-12;
                        REQUIRE((zero || off));
                        shift.push_back(d);
                    }
                    if (seams) {
                        REQUIRE((shift[0] - shift[1]).norm() < 1e-12);
                        REQUIRE((shift[0] - shift[2]).norm() < 1e-12);
                    }
                }
                before = &m;
            }
        }
    }
}

TEST_CASE("a cancelled subdivision throws and leaves the input untouched", "[subdivision]") {
    const HalfedgeMesh mesh = make_noisy_sphere(4, 0.05, 5);
    const HalfedgeMesh copy = mesh;
    for (Scheme s : kAllSchemes) {
        SubdivisionOptions options;
        options.scheme = s;
        options.iterations = 3;
        auto counter = test::CancellingProgress::after_checks(1 << 30);
        REQUIRE_NOTHROW(subdivide(mesh, options, counter));
        REQUIRE(counter.fractions_ok());  // never back, never past 1
        const int total = counter.checks();
        REQUIRE(total > 3);
        for (int allowed : {0, 1, total / 2, total - 1}) {
            auto cancel = test::CancellingProgress::after_checks(allowed);
            REQUIRE_THROWS_AS(subdivide(mesh, options, cancel), Cancelled);
            REQUIRE(cancel.fractions_ok());
        }
        REQUIRE(mesh.n_vertices() == copy.n_vertices());
        REQUIRE(mesh.positions() == copy.positions());
        REQUIRE(mesh.vertex_property_names() == copy.vertex_property_names());
    }
}

TEST_CASE("a mesh with garbage or earlier levels subdivides from level 0", "[subdivision]") {
    HalfedgeMesh mesh = make_icosphere(2);
    for (Halfedge h : mesh.halfedges())
        if (mesh.is_collapse_ok(h)) {
            mesh.collapse(h);
            break;
        }
    REQUIRE(mesh.has_garbage());
    const HalfedgeMesh copy = mesh;
    for (Scheme s : kAllSchemes) {
        const auto first = run(mesh, s, 1);
        REQUIRE(mesh.has_garbage());  // the input is not collected in place
        REQUIRE(mesh.positions() == copy.positions());
        const HalfedgeMesh& once = first.levels[0].mesh;
        REQUIRE_VALID(once);
        // Subdividing the result again starts a new count: its vertices are all level 0.
        const auto second = run(once, s, 1);
        auto level = second.levels[0].mesh.get_vertex_property<int>("v:subdivision_level");
        std::size_t zero = 0;
        for (Vertex v : second.levels[0].mesh.vertices()) zero += level[v] == 0 ? 1 : 0;
        REQUIRE(zero == once.n_vertices());
    }
}

TEST_CASE("without levels and morph only the finest level comes back, the same mesh",
          "[subdivision]") {
    // The CLI's call (keep_levels and morph off) must give exactly the mesh of the viewer's
    // call (every level, with the morph): same connectivity, positions, levels and uvs.
    HalfedgeMesh open = make_cylinder(9, 3);
    auto vuv = open.vertex_property<TexCoord>("v:texcoord");
    auto huv = open.halfedge_property<TexCoord>("h:texcoord");
    for (Vertex v : open.vertices()) vuv[v] = TexCoord(open.position(v).x(), open.position(v).z());
    for (Halfedge h : open.halfedges())
        if (!open.is_boundary(h)) huv[h] = vuv[open.to_vertex(h)] + TexCoord(0.5, 0);
    const std::vector<HalfedgeMesh> meshes = {make_noisy_sphere(2, 0.1, 5), open};
    NullProgress progress;
    for (const HalfedgeMesh& mesh : meshes) {
        for (Scheme s : kAllSchemes) {
            INFO(scheme_name(s));
            SubdivisionOptions all;
            all.scheme = s;
            all.iterations = 3;
            const SubdivisionResult full = subdivide(mesh, all, progress);
            for (bool morph : {false, true}) {
                SubdivisionOptions lean = all;
                lean.keep_levels = false;
                lean.morph = morph;
                const SubdivisionResult r = subdivide(mesh, lean, progress);
                REQUIRE(r.levels.size() == 1);
                const HalfedgeMesh& a = r.levels[0].mesh;
                const HalfedgeMesh& b = full.levels.back().mesh;
                REQUIRE_VALID(a);
                REQUIRE(a.vertices_size() == b.vertices_size());
                REQUIRE(a.halfedges_size() == b.halfedges_size());
                REQUIRE(a.faces_size() == b.faces_size());
                REQUIRE(a.positions() == b.positions());
                for (Halfedge h : b.halfedges()) {
                    REQUIRE(a.to_vertex(h) == b.to_vertex(h));
                    REQUIRE(a.next(h) == b.next(h));
                    REQUIRE(a.face(h) == b.face(h));
                }
                for (Vertex v : b.vertices()) REQUIRE(a.halfedge(v) == b.halfedge(v));
                REQUIRE(a.vertex_property_names() == b.vertex_property_names());
                REQUIRE(a.halfedge_property_names() == b.halfedge_property_names());
                REQUIRE(a.get_vertex_property<int>("v:subdivision_level").vector() ==
                        b.get_vertex_property<int>("v:subdivision_level").vector());
                if (auto uv = b.get_halfedge_property<TexCoord>("h:texcoord"))
                    REQUIRE(a.get_halfedge_property<TexCoord>("h:texcoord").vector() ==
                            uv.vector());
                const MorphCorrespondence& c = r.levels[0].correspondence;
                REQUIRE(c.kind == MorphCorrespondence::Kind::FromEarlier);
                if (morph) {
                    REQUIRE(c.positions == full.levels.back().correspondence.positions);
                    REQUIRE_NOTHROW(check_correspondence(full.levels[1].mesh, a, c));
                } else {
                    REQUIRE(c.positions.empty());
                    REQUIRE_THROWS_AS(check_correspondence(full.levels[1].mesh, a, c),
                                      InvalidArgument);
                }
            }
        }
    }
}
