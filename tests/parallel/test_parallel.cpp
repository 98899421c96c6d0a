// core/parallel.h: the pool's loops over fixed blocks, and the passes that run on it, give the
// same bits for 1, 2 and 7 threads. Runs under ThreadSanitizer too (label `tsan`): the meshes
// are big enough (over kBlock elements) that every pass is split over several blocks.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>
#include <stdexcept>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

#include "core/algorithms/coincident.h"
#include "core/algorithms/coloring.h"
#include "core/algorithms/curvature.h"
#include "core/algorithms/denoise.h"
#include "core/algorithms/fairing.h"
#include "core/algorithms/generators.h"
#include "core/algorithms/mesh_stats.h"
#include "core/algorithms/spectral.h"
#include "core/algorithms/subdivision.h"
#include "core/errors.h"
#include "core/geometry.h"
#include "core/parallel.h"
#include "core/validate.h"

using namespace trilab;

namespace {

/// Runs `run` with 1, 2 and 7 threads (restoring the count at the end) and returns the three
/// results.
template <typename Run>
auto with_1_2_7_threads(const Run& run) {
    struct Restore {
        int n = thread_count();
        ~Restore() { set_thread_count(n); }
    } restore;
    std::vector<decltype(run())> results;
    for (int n : {1, 2, 7}) {
        set_thread_count(n);
        REQUIRE(thread_count() == n);
        results.push_back(run());
    }
    return results;
}

/// Pseudo-random doubles of widely different magnitudes (a sum's rounding depends on order).
std::vector<double> spread_values(std::size_t n) {
    std::vector<double> v(n);
    std::uint64_t s = 0x2545F4914F6CDD1Dull;
    for (double& x : v) {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        x = double(s % 1000003) * std::pow(10.0, double(int(s >> 60) - 8)) * ((s & 1) ? 1 : -1);
    }
    return v;
}

HalfedgeMesh sphere() {
    return make_icosphere(24);  // 5,762 vertices, 17,280 edges, 11,520 faces
}

}  // namespace

TEST_CASE("a sliced frequency decomposition gives the same bits on 1, 2 and 7 threads",
          "[parallel][spectral]") {
    // Two spectrum slices (their own two threads), then the final orthonormalization over two
    // fixed halves of the rows and the residuals over two halves of the columns, on two threads
    // or one as the pool allows: the bits must not depend on it.
    const HalfedgeMesh mesh = make_icosphere(8);
    SpectralOptions o;
    o.op = LaplacianOperator::CurvatureFlow;
    o.mass = MassMatrix::Voronoi;
    o.k = 60;
    o.band_size = 16;
    o.threads = 2;
    const auto results = with_1_2_7_threads([&] { return decompose(mesh, o); });
    REQUIRE(results[0].report.slices == 2);
    REQUIRE(results[0].size() == o.k);
    CHECK(results[0].report.max_residual < 1e-8);
    CHECK(s_orthonormality_error(results[0]) < 1e-8);
    for (std::size_t i = 1; i < results.size(); ++i) {
        CHECK(results[i].eigenvalues == results[0].eigenvalues);
        CHECK(results[i].eigenvectors == results[0].eigenvectors);
        CHECK(results[i].coefficients == results[0].coefficients);
        CHECK(results[i].report.max_residual == results[0].report.max_residual);
    }
}

TEST_CASE("parallel_for visits every index once, for any thread count", "[parallel]") {
    for (const std::size_t n :
         {std::size_t(0), std::size_t(1), kBlock - 1, kBlock + 1, std::size_t(10) * kBlock + 17}) {
        const auto counts = with_1_2_7_threads([&] {
            std::vector<std::atomic<int>> seen(n);
            parallel_for(0, n, [&](std::size_t i) { seen[i].fetch_add(1); });
            std::vector<int> out;
            for (auto& s : seen) out.push_back(s.load());
            return out;
        });
        for (const auto& c : counts) CHECK(c == std::vector<int>(n, 1));
    }
}

TEST_CASE("parallel_reduce sums in block order: the same bits for 1, 2 and 7 threads",
          "[parallel]") {
    const std::vector<double> v = spread_values(20 * kBlock + 5);
    const auto sums = with_1_2_7_threads([&] {
        return parallel_reduce(
            0, v.size(), 0.0,
            [&](std::size_t b, std::size_t e) {
                double s = 0;
                for (std::size_t i = b; i < e; ++i) s += v[i];
                return s;
            },
            [](double a, double b) { return a + b; });
    });
    // The same sum computed here, block by block, in block order.
    double expected = 0;
    for (std::size_t b = 0; b < v.size(); b += kBlock) {
        double s = 0;
        for (std::size_t i = b; i < std::min(v.size(), b + kBlock); ++i) s += v[i];
        expected += s;
    }
    for (double s : sums) CHECK(s == expected);
    // The order matters on these values: a plain left-to-right sum differs (so the test can
    // fail when blocks are combined in another order).
    double plain = 0;
    for (double x : v) plain += x;
    CHECK(plain != expected);
}

TEST_CASE("parallel_reduce of bool: each block writes its own partial", "[parallel]") {
    // Block partials of type bool must not share a word (std::vector<bool>): the ThreadSanitizer
    // job runs this with 7 threads over 64 one-element blocks.
    std::vector<double> v(64, 1.0);
    v[41] = std::numeric_limits<double>::quiet_NaN();
    const auto all_finite = [&](std::size_t b, std::size_t e) {
        bool finite = true;
        for (std::size_t i = b; i < e; ++i) finite = finite && std::isfinite(v[i]);
        return finite;
    };
    const auto both = [](bool a, bool b) { return a && b; };
    const auto found = with_1_2_7_threads(
        [&] { return int(parallel_reduce(0, v.size(), true, all_finite, both, 1)); });
    for (int f : found) CHECK(f == 0);
    v[41] = 2.0;
    const auto none = with_1_2_7_threads(
        [&] { return int(parallel_reduce(0, v.size(), true, all_finite, both, 1)); });
    for (int f : none) CHECK(f == 1);
}

TEST_CASE("a block's exception reaches the caller, and nested loops run", "[parallel]") {
    const auto outcomes = with_1_2_7_threads([] {
        std::atomic<long> total{0};
        parallel_for(0, 8 * kBlock, [&](std::size_t i) {
            if (i % kBlock == 0)  // a loop inside a block runs in order on its thread
                parallel_for(0, 100, [&](std::size_t) { total.fetch_add(1); });
        });
        bool thrown = false;
        try {
            parallel_for(0, 8 * kBlock, [](std::size_t i) {
                if (i == 5 * kBlock + 3) throw InvalidArgument("block 5");
            });
        } catch (const InvalidArgument& e) {
            thrown = std::string(e.what()) == "block 5";
        }
        return std::make_pair(total.load(), thrown);
    });
    for (const auto& [total, thrown] : outcomes) {
        CHECK(total == 800);
        CHECK(thrown);
    }
}

TEST_CASE("thread counts are checked: --threads and TRILAB_THREADS values", "[parallel]") {
    CHECK(parse_thread_count("7", "--threads") == 7);
    CHECK(parse_thread_count("0", "--threads") == 0);
    CHECK_THROWS_WITH(parse_thread_count("-1", "--threads"),
                      Catch::Contains("--threads: expected a whole number"));
    CHECK_THROWS_WITH(parse_thread_count("two", "TRILAB_THREADS"),
                      Catch::Contains("TRILAB_THREADS") && Catch::Contains("'two'"));
    CHECK_THROWS_AS(parse_thread_count("5000", "--threads"), InvalidArgument);
    CHECK_THROWS_AS(set_thread_count(-3), InvalidArgument);
    CHECK(hardware_threads() >= 1);
}

TEST_CASE("Loop subdivision: the same bits for 1, 2 and 7 threads", "[parallel]") {
    const HalfedgeMesh closed = sphere(), open = make_grid(80);  // boundary rules too
    for (const HalfedgeMesh* mesh : {&closed, &open}) {
        SubdivisionOptions o;
        o.keep_levels = false;
        o.morph = false;
        const auto levels = with_1_2_7_threads([&] {
            NullProgress progress;
            return subdivide(*mesh, o, progress).levels.back().mesh;
        });
        REQUIRE(validate(levels[0]).ok);
        for (const HalfedgeMesh& m : levels) {
            CHECK(m.positions() == levels[0].positions());
            CHECK(m.halfedge_to_array() == levels[0].halfedge_to_array());
            CHECK(m.halfedge_next_array() == levels[0].halfedge_next_array());
            CHECK(m.vertex_halfedge_array() == levels[0].vertex_halfedge_array());
        }
    }
}

TEST_CASE("explicit fairing, normals, statistics: the same bits for 1, 2 and 7 threads",
          "[parallel]") {
    const HalfedgeMesh mesh = make_noisy_sphere(24, 0.05, 7);
    FairingOptions o;
    o.iterations = 4;
    const auto faired = with_1_2_7_threads([&] { return smooth(mesh, o).mesh.positions(); });
    CHECK(faired[1] == faired[0]);
    CHECK(faired[2] == faired[0]);
    const auto normals = with_1_2_7_threads([&] {
        HalfedgeMesh m = mesh;
        compute_vertex_normals(m);
        return m.get_vertex_property<Vector3>("v:normal").vector();
    });
    CHECK(normals[1] == normals[0]);
    CHECK(normals[2] == normals[0]);
    const auto stats = with_1_2_7_threads([&] {
        const MeshStats s = compute_stats(mesh);
        return std::vector<double>{double(s.vertices), double(s.edges), double(s.faces),
                                   double(s.boundary_loops), double(s.components)};
    });
    CHECK(stats[1] == stats[0]);
    CHECK(stats[2] == stats[0]);
}

TEST_CASE("curvatures: the same bits for 1, 2 and 7 threads", "[parallel]") {
    const HalfedgeMesh mesh = make_noisy_sphere(24, 0.05, 3);  // two blocks of vertices
    const auto curvatures = with_1_2_7_threads([&] {
        const VertexCurvatures c = compute_curvatures(mesh);
        std::vector<double> all = c.mean;
        for (const auto* v : {&c.gaussian, &c.k1, &c.k2, &c.shape_index, &c.area})
            all.insert(all.end(), v->begin(), v->end());
        for (std::uint8_t valid : c.valid) all.push_back(valid);
        return all;
    });
    REQUIRE(curvatures[0].size() == 7 * mesh.vertices_size());
    CHECK(curvatures[1] == curvatures[0]);
    CHECK(curvatures[2] == curvatures[0]);
}

TEST_CASE("vertex colourings: the same colours and values for 1, 2 and 7 threads", "[parallel]") {
    const HalfedgeMesh mesh = make_noisy_sphere(24, 0.05, 5);
    for (VertexColoring coloring : {VertexColoring::Mean, VertexColoring::ShapeIndex,
                                    VertexColoring::MinAngle, VertexColoring::Normal}) {
        INFO(coloring_name(coloring));
        const auto colors = with_1_2_7_threads([&] {
            const VertexColors c = color_vertices(mesh, coloring, ColoringOptions{});
            std::vector<double> all(c.values.begin(), c.values.end());
            for (const Color& k : c.colors) all.insert(all.end(), {k.x(), k.y(), k.z()});
            return all;
        });
        REQUIRE(colors[0].size() >= 3 * mesh.vertices_size());
        // NaN != NaN: compare the bits.
        for (std::size_t t = 1; t < 3; ++t) {
            REQUIRE(colors[t].size() == colors[0].size());
            CHECK(std::memcmp(colors[t].data(), colors[0].data(),
                              colors[0].size() * sizeof(double)) == 0);
        }
    }
}

TEST_CASE("exact coincident groups: the same groups for 1, 2 and 7 threads, as a map finds them",
          "[parallel]") {
    // 30,000 points on a lattice; every 5th repeats an earlier one (some as -0 for +0).
    std::vector<Point> p;
    std::uint64_t state = 1;
    for (int i = 0; i < 30000; ++i) {
        if (i % 5 == 4) {
            state = state * 6364136223846793005ull + 1442695040888963407ull;
            Point q = p[std::size_t((state >> 33) % std::uint64_t(i))];
            if (q.x() == 0) q.x() = -0.0;
            p.push_back(q);
        } else {
            p.emplace_back(double(i % 31), double(i / 31 % 37), double(i / (31 * 37)));
        }
    }
    const auto groups = with_1_2_7_threads([&] {
        const CoincidentGroups g = find_coincident_points(p.data(), p.size());
        return std::make_pair(g.members, g.offsets);
    });
    CHECK(groups[1] == groups[0]);
    CHECK(groups[2] == groups[0]);
    // Independently: each point's first equal point, groups of two or more ordered by it.
    std::map<std::array<double, 3>, std::vector<Index>> by_point;
    for (std::size_t i = 0; i < p.size(); ++i)
        by_point[{p[i].x() == 0 ? 0.0 : p[i].x(), p[i].y(), p[i].z()}].push_back(Index(i));
    std::vector<std::vector<Index>> expected;
    for (const auto& [point, members] : by_point)
        if (members.size() > 1) expected.push_back(members);
    std::sort(expected.begin(), expected.end());
    std::vector<std::vector<Index>> found;
    const auto& [members, offsets] = groups[0];
    for (std::size_t g = 0; g + 1 < offsets.size(); ++g)
        found.emplace_back(members.begin() + std::ptrdiff_t(offsets[g]),
                           members.begin() + std::ptrdiff_t(offsets[g + 1]));
    CHECK(found == expected);
    CHECK(found.size() > 1000);
}

TEST_CASE("components and validate(): the same for 1, 2 and 7 threads", "[parallel]") {
    const HalfedgeMesh mesh = make_torus(120, 60, 2.0, 0.5);
    const auto labels = with_1_2_7_threads([&] {
        std::vector<Index> component;
        const std::size_t n = label_components(mesh, component);
        return std::make_pair(n, component);
    });
    CHECK(labels[0].first == 1);
    CHECK(labels[1] == labels[0]);
    CHECK(labels[2] == labels[0]);
    const auto valid = with_1_2_7_threads([&] { return validate(mesh).ok; });
    CHECK(valid == std::vector<bool>{true, true, true});
}

TEST_CASE("explicit umbrella and Taubin in the Morton order: the bits of the storage order",
          "[parallel]") {
    // fairing_detail::set_locality_threshold(): 0 renumbers every run, the largest never does.
    struct Restore {
        std::size_t before = fairing_detail::set_locality_threshold(0);
        ~Restore() { fairing_detail::set_locality_threshold(before); }
    } restore;
    HalfedgeMesh open = make_grid(80);  // boundary vertices stay fixed
    std::uint64_t state = 0x9E3779B97F4A7C15ull;
    for (Point& p : open.positions()) {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        p.z() = double(state % 1000) * 1e-3;
    }
    const HalfedgeMesh closed = make_noisy_sphere(24, 0.05, 7);  // the volume check per step
    struct Case {
        FairingOperator op;
        double step;  // 1.5: the energy and area checks run too
    };
    for (const HalfedgeMesh* mesh : {static_cast<const HalfedgeMesh*>(&open), &closed})
        for (const Case c :
             {Case{FairingOperator::Umbrella, 0.5}, Case{FairingOperator::Umbrella, 1.5},
              Case{FairingOperator::Taubin, 0}}) {
            FairingOptions o;
            o.op = c.op;
            o.step = c.step;
            o.iterations = 3;
            fairing_detail::set_locality_threshold(std::size_t(-1));
            const FairingResult storage = smooth(*mesh, o);
            fairing_detail::set_locality_threshold(0);
            const auto local = with_1_2_7_threads([&] { return smooth(*mesh, o); });
            for (const FairingResult& r : local) {
                CHECK(r.iterations_done == storage.iterations_done);
                CHECK(r.stopped_early == storage.stopped_early);
                CHECK(r.mesh.positions() == storage.mesh.positions());
                CHECK(r.step_positions == storage.step_positions);
                CHECK(r.final_volume == storage.final_volume);
                // The estimate's sums run in the other order: equal up to rounding, and the
                // same bits for any thread count and as max_stable_explicit_step() gives.
                CHECK(r.max_stable_step == Approx(storage.max_stable_step).epsilon(1e-9));
                CHECK(r.max_stable_step == local[0].max_stable_step);
            }
            CHECK(local[0].max_stable_step == max_stable_explicit_step(*mesh, o.op));
        }
}

TEST_CASE("denoise: the same bits for 1, 2 and 7 threads", "[parallel]") {
    // 32,000 faces: 8 blocks of every per-face pass; few iterations keep it fast.
    const HalfedgeMesh mesh = make_noisy_sphere(40, 0.05, 3);
    REQUIRE(mesh.n_faces() > 4 * kBlock);
    std::vector<float> half(mesh.vertices_size());
    for (Vertex v : mesh.vertices()) half[v.idx()] = mesh.position(v).z() > 0 ? 1.0f : 0.25f;
    for (int variant = 0; variant < 3; ++variant) {
        DenoiseOptions o;
        o.normal_iterations = 4;
        o.vertex_iterations = 3;
        if (variant == 1) {  // the sectors' path: guidance from every patch of N(i)
            o.features = FeatureSource::Auto;
            o.feature_angle = 12;
        }
        if (variant == 2) {
            o.method = DenoiseMethod::Bilateral;
            o.region = &half;
        }
        INFO("variant " << variant);
        const auto runs = with_1_2_7_threads([&] {
            HalfedgeMesh m = mesh;
            const DenoiseReport r = denoise(m, o);
            CHECK(validate(m).ok);
            return std::make_pair(
                m.positions(),
                std::vector<double>{r.noise_level, r.sigma_r, double(r.inverted_faces),
                                    double(r.feature_edges), double(r.vertex_iterations_done),
                                    r.mean_normal_change_degrees, r.max_displacement,
                                    double(r.moved_vertices), double(r.folded_faces)});
        });
        CHECK(runs[0].second[7] > 0.5 * double(mesh.n_vertices()));  // it did move the mesh
        if (variant == 1) CHECK(runs[0].second[3] > 0);              // and found features
        CHECK(runs[1] == runs[0]);
        CHECK(runs[2] == runs[0]);
    }
}

#if !defined(__SANITIZE_THREAD__)  // ThreadSanitizer does not support a multi-threaded fork
TEST_CASE("a forked child runs its loops on its own thread (the pool's workers stay behind)",
          "[parallel]") {
    set_thread_count(2);
    parallel_for(0, 4 * kBlock, [](std::size_t) {});  // the pool has its worker now
    const pid_t child = fork();
    REQUIRE(child >= 0);
    if (child == 0) {
        alarm(20);  // a loop waiting for the parent's workers would hang: SIGALRM ends it
        std::vector<double> v = spread_values(8 * kBlock);
        const double s = parallel_reduce(
            0, v.size(), 0.0,
            [&](std::size_t b, std::size_t e) {
                double part = 0;
                for (std::size_t i = b; i < e; ++i) part += v[i];
                return part;
            },
            [](double a, double b) { return a + b; });
        _exit(std::isfinite(s) ? 0 : 1);
    }
    int status = 0;
    REQUIRE(waitpid(child, &status, 0) == child);
    CHECK(WIFEXITED(status));
    CHECK(WEXITSTATUS(status) == 0);
    set_thread_count(0);
}
#endif
