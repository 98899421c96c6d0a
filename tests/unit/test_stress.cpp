// Randomized operation stress: long random sequences of every registered operation with
// random parameters, interleaved with undo, redo and jumps on the History, on the built-in
// models and the shared meshes. After every step: validate(), no NaN or infinite position,
// and the History's current state equal to the mesh the sequence expects.
//
// Reproducible: the seed and the length come from the environment,
//   TRILAB_STRESS_SEED=12345 TRILAB_STRESS_STEPS=400 ./build/tests/trilab_tests "[stress]"
// (defaults: seed 20261122, 60 steps per mesh; TRILAB_STRESS_VERBOSE=1 prints each operation
// and writes its input mesh to trilab-stress-input.om in the working directory); a failure prints
// the seed, the step and the operation text, which replays alone with `trilab-cli record --op
// "..."` or the viewer's --op. Every registered operation must have a parameter generator here: a
// new operation without one fails the test, so the stress test grows with the registry.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "app/history/history.h"
#include "app/ops/operation.h"
#include "core/algorithms/generators.h"
#include "core/algorithms/mesh_stats.h"
#include "core/errors.h"
#include "core/io/mesh_io.h"
#include "test_helpers.h"

using namespace trilab;

namespace {

using Rng = std::mt19937_64;

std::uint64_t env_number(const char* name, std::uint64_t fallback) {
    const char* text = std::getenv(name);
    if (!text || !*text) return fallback;
    char* end = nullptr;
    const unsigned long long v = std::strtoull(text, &end, 10);
    return end && *end == '\0' ? v : fallback;
}

int pick(Rng& rng, int lo, int hi) {
    return std::uniform_int_distribution<int>(lo, hi)(rng);
}

template <class T>
const T& pick_of(Rng& rng, const std::vector<T>& v) {
    return v[std::size_t(pick(rng, 0, int(v.size()) - 1))];
}

/// Random parameters for each registered operation; sizes kept so a sequence stays quick.
using Generator = std::function<std::string(Rng&, const HalfedgeMesh&)>;

const std::map<std::string, Generator>& generators() {
    static const std::map<std::string, Generator> g = {
        {"noise",
         [](Rng& rng, const HalfedgeMesh&) {
             return "noise --amount " + std::to_string(pick(rng, 0, 30)) + " --seed " +
                    std::to_string(pick(rng, 0, 1000));
         }},
        {"subdivide",
         [](Rng& rng, const HalfedgeMesh& m) {
             // Keep the meshes small: subdivide only below 20k faces, one iteration.
             const std::vector<std::string> schemes = {"loop", "sqrt3", "butterfly",
                                                       "modified-butterfly"};
             if (m.n_faces() > 20000) return std::string("noise --amount 1");
             return "subdivide --scheme " + pick_of(rng, schemes) + " --iterations 1";
         }},
        {"smooth",
         [](Rng& rng, const HalfedgeMesh&) {
             const std::vector<std::string> ops = {"umbrella", "improved-umbrella",
                                                   "curvature-flow", "second-order", "taubin"};
             const std::string op = pick_of(rng, ops);
             const bool implicit = op != "taubin" && pick(rng, 0, 1) == 1;
             const std::vector<std::string> steps = {"0.01", "0.1", "0.5", "1", "5", "20"};
             std::string text = "smooth --operator " + op + " --integration " +
                                (implicit ? "implicit" : "explicit") + " --step " +
                                pick_of(rng, steps) + " --iterations " +
                                std::to_string(pick(rng, 1, 4));
             if (pick(rng, 0, 3) == 0) text += " --boundary slide";
             return text;
         }},
        {"denoise",
         [](Rng& rng, const HalfedgeMesh&) {
             const std::vector<std::string> sigmas_s = {"0.1", "0.5", "1", "3", "100"};
             const std::vector<std::string> sigmas_r = {"0.05", "0.2", "0.35", "1", "100"};
             return std::string("denoise --method ") + (pick(rng, 0, 1) ? "bilateral" : "guided") +
                    " --normal-iterations " + std::to_string(pick(rng, 0, 30)) +
                    " --vertex-iterations " + std::to_string(pick(rng, 0, 20)) + " --sigma-s " +
                    pick_of(rng, sigmas_s) + " --sigma-r " + pick_of(rng, sigmas_r);
         }},
        {"decimate",
         [](Rng& rng, const HalfedgeMesh&) {
             std::string text =
                 std::string("decimate --cost ") + (pick(rng, 0, 1) ? "quadric" : "roundness");
             if (pick(rng, 0, 1))
                 text += " --percent " + std::to_string(pick(rng, 1, 90)) + " --iterations " +
                         std::to_string(pick(rng, 1, 3));
             else
                 text += " --target-vertices " + std::to_string(pick(rng, 3, 400));
             const int flip = pick(rng, 0, 3);  // default, an angle, or off
             if (flip == 1) text += " --normal-flip " + std::to_string(pick(rng, 5, 120));
             if (flip == 2) text += " --normal-flip off";
             if (pick(rng, 0, 3) == 0) text += " --roundness 0." + std::to_string(pick(rng, 1, 5));
             if (pick(rng, 0, 3) == 0) text += " --independent-set";
             return text;
         }},
        {"weld",
         [](Rng& rng, const HalfedgeMesh&) {
             const std::vector<std::string> tolerances = {"0", "1e-6", "0.01", "0.1"};
             return "weld --tolerance " + pick_of(rng, tolerances);
         }},
        {"spectrum",
         [](Rng& rng, const HalfedgeMesh& m) {
             const std::vector<std::string> ops = {"umbrella", "improved-umbrella",
                                                   "curvature-flow", "second-order"};
             const std::vector<std::string> masses = {"normalizer", "barycentric", "voronoi"};
             const int k = pick(rng, 1, 30);
             std::string text = "spectrum --operator " + pick_of(rng, ops) + " --k " +
                                std::to_string(k) + " --mass " + pick_of(rng, masses);
             if (pick(rng, 0, 4) == 0) text += " --which largest";
             if (pick(rng, 0, 2) == 0) {
                 const int lo = pick(rng, 0, k - 1);
                 text +=
                     " --band " + std::to_string(lo) + ":" + std::to_string(pick(rng, lo, k - 1));
             }
             // A dense solve is cubic: about a minute at 2,500 vertices on a loaded machine.
             if (m.n_vertices() <= 1200 && pick(rng, 0, 3) == 0) text += " --full";
             if (pick(rng, 0, 3) == 0) text += " --fix-boundary";
             return text;
         }},
        {"flip", [](Rng&, const HalfedgeMesh&) { return std::string("flip"); }},
        {"remove-components",
         [](Rng& rng, const HalfedgeMesh&) {
             const std::vector<std::string> fractions = {"0", "0.01", "0.3", "1"};
             const int rule = pick(rng, 0, 2);  // faces, size, or both
             std::string text = "remove-components";
             if (rule != 1) text += " --min-faces " + std::to_string(pick(rng, 0, 500));
             if (rule != 0) text += " --min-diameter " + pick_of(rng, fractions);
             return text;
         }},
        {"features",
         [](Rng& rng, const HalfedgeMesh&) {
             std::string text = "features --angle " + std::to_string(pick(rng, 1, 180));
             if (pick(rng, 0, 1)) text += " --min-chain " + std::to_string(pick(rng, 0, 10));
             if (pick(rng, 0, 1)) text += " --boundary";
             return text;
         }},
        {"sharpen",
         [](Rng& rng, const HalfedgeMesh& m) {
             // One edge of the mesh (the stress runs have no region): sharp, semi-sharp or
             // cleared.
             std::string text =
                 "sharpen --edge " + std::to_string(pick(rng, 0, int(m.edges_size()) - 1));
             const int kind = pick(rng, 0, 2);
             if (kind == 1) text += " --sharpness " + std::to_string(pick(rng, 0, 5));
             if (kind == 2) text += " --clear";
             return text;
         }},
        {"fill-holes",
         [](Rng& rng, const HalfedgeMesh&) {
             const std::vector<std::string> fairings = {"none", "c1", "c2"};
             const std::vector<std::string> fractions = {"0", "0.05", "0.5", "1"};
             std::string text = "fill-holes --fairing " + pick_of(rng, fairings);
             const int rule = pick(rng, 0, 3);  // any size, edges, size, or both
             if (rule & 1) text += " --max-edges " + std::to_string(pick(rng, 0, 60));
             if (rule & 2) text += " --max-diameter " + pick_of(rng, fractions);
             return text;
         }},
        {"remesh",
         [](Rng& rng, const HalfedgeMesh& m) {
             // Keep the meshes small: refine only below 5k faces, adaptively only there.
             const std::vector<std::string> small = {"0.5", "0.8", "1", "1.5", "3"};
             const std::vector<std::string> large = {"1", "1.5", "3"};
             const bool is_small = m.n_faces() < 5000;
             std::string text = "remesh --relative " + pick_of(rng, is_small ? small : large) +
                                " --iterations " + std::to_string(pick(rng, 1, 3));
             if (is_small && pick(rng, 0, 3) == 0) text += " --adaptive 0.05";
             return text;
         }},
    };
    return g;
}

void require_finite(const HalfedgeMesh& m) {
    for (Vertex v : m.vertices()) REQUIRE(m.position(v).allFinite());
}

/// Runs `steps` random actions on `start`; returns the number of operations that ran.
int stress(const HalfedgeMesh& start, const std::string& name, std::uint64_t seed, int steps) {
    Rng rng(seed);
    const bool verbose = env_number("TRILAB_STRESS_VERBOSE", 0) != 0;
    History history;
    history.reset(start, "load " + name);
    int ran = 0;
    const std::vector<std::string> names = operation_names();
    for (const std::string& op : names) {
        INFO("operation '" << op << "' has no generator in tests/unit/test_stress.cpp");
        REQUIRE(generators().count(op) == 1);
    }
    for (int step = 0; step < steps; ++step) {
        const int action = pick(rng, 0, 9);
        std::string what;
        if (action == 0) {
            what = "undo";
            history.undo();
        } else if (action == 1) {
            what = "redo";
            history.redo();
        } else if (action == 2 && history.size() > 0) {
            const auto index = std::size_t(pick(rng, 0, int(history.size()) - 1));
            what = "jump " + std::to_string(index);
            history.jump(index);
        } else {
            const HalfedgeMesh& mesh = history.current_mesh();
            what = generators().at(pick_of(rng, names))(rng, mesh);
            INFO(name << ": seed " << seed << ", step " << step << ": " << what);
            if (verbose) {  // the input of each operation, to replay one with trilab-cli
                std::fprintf(stderr, "%s: step %d: %s (%zu vertices)\n", name.c_str(), step,
                             what.c_str(), mesh.n_vertices());
                write_mesh(mesh, "trilab-stress-input.om");
            }
            try {
                NullProgress progress;
                OperationResult result = run_operation(parse_operation(what), mesh, progress);
                REQUIRE_FALSE(result.steps.empty());
                std::vector<HalfedgeMesh> meshes;
                std::vector<MorphCorrespondence> correspondences;
                for (OperationStep& s : result.steps) {
                    REQUIRE_VALID(s.mesh);
                    require_finite(s.mesh);
                    meshes.push_back(std::move(s.mesh));
                    correspondences.push_back(std::move(s.correspondence));
                }
                history.push(result.label, result.parameters, result.ms, std::move(meshes),
                             std::move(correspondences));
                ++ran;
            } catch (const Error& e) {
                // A refusal is fine when it says why (too small a mesh, a spectrum that does
                // not converge on a degenerate shape): trilab::Error with a message.
                INFO("refused: " << e.what());
                CHECK(std::string(e.what()).size() > 10);
            }
        }
        INFO(name << ": seed " << seed << ", step " << step << ": " << what);
        const HalfedgeMesh& now = history.current_mesh();
        REQUIRE_VALID(now);
        require_finite(now);
    }
    return ran;
}

}  // namespace

TEST_CASE("random operation sequences keep every mesh valid and finite", "[stress]") {
    const std::uint64_t seed = env_number("TRILAB_STRESS_SEED", 20261122);
    const int steps = int(env_number("TRILAB_STRESS_STEPS", 60));
    std::vector<std::pair<std::string, HalfedgeMesh>> meshes;
    meshes.emplace_back("default model", make_default_model());
    meshes.emplace_back("grid (open)", make_grid(6));
    meshes.emplace_back("cylinder (two boundary loops)", make_cylinder(12, 4));
    meshes.emplace_back("tetrahedron", make_tetrahedron());
    for (const char* file : {"spot.obj", "fandisk.obj"}) {
        const std::string path = test::shared_mesh(file);
        if (test::present_or_skip(path)) meshes.emplace_back(file, read_mesh(path).mesh);
    }
    std::uint64_t k = 0;
    for (const auto& [name, mesh] : meshes) {
        INFO("mesh " << name << ", TRILAB_STRESS_SEED=" << seed);
        REQUIRE_VALID(mesh);
        const int ran = stress(mesh, name, seed + 7919 * k++, steps);
        CHECK(ran > 0);
    }
}
