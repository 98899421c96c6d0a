// Sliding features in fairing (issue 39, item 4; core/algorithms/feature_fairing.h): the crease
// vertices smooth along their feature curve with the curve's 1-D Laplacian, corners and curve
// ends stay bit for bit, for the operators and both integrations, through the operation too.
#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "app/ops/operation.h"
#include "core/algorithms/fairing.h"
#include "core/algorithms/feature_detection.h"
#include "core/algorithms/feature_fairing.h"
#include "core/algorithms/generators.h"
#include "core/errors.h"
#include "core/features.h"
#include "core/io/mesh_io.h"
#include "test_helpers.h"

using namespace trilab;

TEST_CASE("sliding features smooth a noisy crease towards the clean curve, corners stay",
          "[features][fairing]") {
    SKIP_IF_MISSING(test::shared_mesh("fandisk.obj"));
    HalfedgeMesh clean = read_mesh(test::shared_mesh("fandisk.obj")).mesh;
    FeatureDetectionOptions fo;
    fo.angle_deg = 60;
    detect_features(clean, fo);
    const VertexClassification cls = classify_vertices(clean, false);
    const std::vector<std::array<Point, 2>> curves = test::sharp_segments(clean);  // clean curves
    double mean_length = 0;
    for (const auto& c : curves) mean_length += (c[1] - c[0]).norm();
    REQUIRE(curves.size() > 600);
    mean_length /= double(curves.size());
    // Noise on the crease vertices only: a fifth of the curves' mean edge length, in a random
    // direction (seeded), so the features stay those of the clean part.
    HalfedgeMesh noisy = clean;
    std::mt19937 rng(39);
    std::normal_distribution<double> g(0.0, 1.0);
    std::vector<Vertex> creases, fixed_features;
    for (Vertex v : clean.vertices()) {
        if (cls.classes[v.idx()] == VertexClass::Crease) {
            const Vector3 d(g(rng), g(rng), g(rng));
            noisy.position(v) += 0.2 * mean_length * d.normalized();
            creases.push_back(v);
        } else if (cls.classes[v.idx()] != VertexClass::Smooth) {
            fixed_features.push_back(v);  // corners and darts' vertices
        }
    }
    REQUIRE(creases.size() > 600);
    REQUIRE(fixed_features.size() >= 22);
    const auto mean_to_curves = [&](const HalfedgeMesh& m) {
        double sum = 0;
        for (Vertex v : creases) sum += test::segments_distance(m.position(v), curves);
        return sum / double(creases.size());
    };
    const double before = mean_to_curves(noisy);
    struct Case {
        FairingOperator op;
        Integration integration;
        double step;
        int iterations;
    };
    for (const Case c : {Case{FairingOperator::Umbrella, Integration::Explicit, 0.5, 5},
                         Case{FairingOperator::Umbrella, Integration::Implicit, 2.0, 1},
                         Case{FairingOperator::CurvatureFlow, Integration::Explicit, 0.5, 3},
                         Case{FairingOperator::CurvatureFlow, Integration::Implicit, 2.0, 1},
                         Case{FairingOperator::Taubin, Integration::Explicit, 0.5, 5}}) {
        INFO(fairing_operator_name(c.op) << " " << integration_name(c.integration));
        FairingOptions o;
        o.op = c.op;
        o.integration = c.integration;
        o.step = c.step;
        o.iterations = c.iterations;
        o.keep_steps = false;
        o.estimate_max_stable_step = false;
        const FairingResult fixed = smooth(noisy, o);
        o.feature_mode = FeatureMode::Slide;
        const FairingResult slide = smooth(noisy, o);
        REQUIRE_FALSE(fixed.stopped_early);
        REQUIRE_FALSE(slide.stopped_early);
        REQUIRE_VALID(slide.mesh);
        // Fixed cannot move them; sliding brings them well towards the clean curve.
        CHECK(mean_to_curves(fixed.mesh) == before);
        const double after = mean_to_curves(slide.mesh);
        INFO("mean distance to the clean curves: " << before << " -> " << after);
        CHECK(after < 0.6 * before);
        // Corners and curve ends stay bit for bit; the crease vertices all moved.
        for (Vertex v : fixed_features) CHECK(slide.mesh.position(v) == noisy.position(v));
        std::size_t moved = 0;
        for (Vertex v : creases) moved += slide.mesh.position(v) != noisy.position(v);
        CHECK(moved == creases.size());
    }
    // Through the operation (the CLI and the viewer's panel): the same result.
    NullProgress progress;
    const OperationResult r = run_operation(
        parse_operation("smooth --iterations 5 --feature-mode slide"), noisy, progress);
    FairingOptions o;
    o.iterations = 5;
    o.feature_mode = FeatureMode::Slide;
    CHECK(r.steps.back().mesh.positions() == smooth(noisy, o).mesh.positions());
    CHECK(mean_to_curves(r.steps.back().mesh) < 0.6 * before);
}

TEST_CASE("sliding features: regions, closed curves, bad names", "[features][fairing]") {
    // A closed curve without corners: the outer equator of a torus, all its vertices crease
    // vertices; umbrella steps shrink it in its plane as the 1-D Laplacian does.
    HalfedgeMesh m = make_torus(16, 8, 2.0, 0.5);
    const auto outer = [&](Vertex v) {
        return m.position(v).z() == 0.0 && m.position(v).head<2>().norm() > 2.0;
    };
    for (Edge e : m.edges())
        if (outer(m.from_vertex(m.halfedge(e, 0))) && outer(m.to_vertex(m.halfedge(e, 0))))
            set_sharpness(m, e, 1.0f);
    std::vector<Vertex> ring;
    for (Vertex v : m.vertices())
        if (outer(v)) ring.push_back(v);
    REQUIRE(ring.size() == 16);
    FairingOptions o;
    o.feature_mode = FeatureMode::Slide;
    o.iterations = 3;
    for (Integration integration : {Integration::Explicit, Integration::Implicit}) {
        o.integration = integration;
        const FairingResult r = smooth(m, o);
        REQUIRE_VALID(r.mesh);
        for (Vertex v : ring) {
            const Point p = r.mesh.position(v);
            CHECK(p.z() == 0.0);  // the ring's own Laplacian keeps it in its plane
            CHECK(p.head<2>().norm() < m.position(v).head<2>().norm());
        }
    }
    // A region: only its crease vertices slide; the ring's others stay bit for bit.
    std::vector<float> region(m.vertices_size(), 1.0f);
    for (std::size_t k = 0; k < ring.size(); k += 2) region[ring[k].idx()] = 0.0f;
    o.region = &region;
    o.integration = Integration::Explicit;
    const FairingResult r = smooth(m, o);
    for (std::size_t k = 0; k < ring.size(); ++k)
        CHECK((r.mesh.position(ring[k]) == m.position(ring[k])) == (k % 2 == 0));
    CHECK(parse_feature_mode("slide") == FeatureMode::Slide);
    CHECK_THROWS_AS(parse_feature_mode("sliding"), InvalidArgument);
}
