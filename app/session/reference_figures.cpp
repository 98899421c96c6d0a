// The reference's figures in trilab's terms (app/session/reference_figures.h).
//
// Translating the steps. The reference's umbrella (1.5), curvature flow (1.9) and second-order
// relaxation (1.12) divide by their own weights, as trilab's do: their steps mean the same
// here, and step 1 is step 1. Its improved umbrella (1.7), L = 2/E · Σ (x_j - x_i)/|e_ij|,
// does not: it scales like 1/length², so its step is in length² of that model's coordinates.
// trilab's improved umbrella is h² times it (h the mean edge length, core/algorithms/
// laplacian.h), so the reference's step s means s / h² here. The reference does not give its
// models' sizes: the sphere is taken as a unit sphere of about 1,000 vertices (h = 0.123, the
// default model's), the head as about one unit tall with its 17,358 vertices (h about 0.01).
#include "app/session/reference_figures.h"

#include <utility>

#include "app/ops/operation.h"
#include "core/algorithms/generators.h"

namespace trilab::viewer {
namespace {

/// The mean edge length assumed for the reference's head (see the file comment); its sphere's
/// is the default model's, 0.1226, so its step 1.0 is 1 / 0.1226² = 66.5 here.
constexpr double kHeadEdge = 0.01;

const char* const kSameUnits =
    "the reference's operator divides by its own weights, as trilab's does: its step means the "
    "same here";
const char* const kNoStep = "no step to translate";

const char* const kSphere = "default";
const char* const kSphereNote =
    "the default model: a noisy unit sphere of 1,002 vertices (the reference's has 1,026)";
const char* const kHead = "torus";
const char* const kHeadNote =
    "a noisy torus of 1,152 vertices stands in for the reference's noisy head (17,358 "
    "vertices), which trilab does not ship";
const char* const kHeadNoise = "noise --amount 30 --seed 1";
const char* const kBunnyNote =
    "the default model stands in for the reference's bunny (35,947 vertices): the steps are "
    "scale-free, and step 20 explodes any mesh";
const char* const kCube = "cube";
const char* const kCubeNote =
    "the cube (8 vertices) stands in for the reference's closed 20-vertex model";
const char* const kDecimationSetup = "subdivide --scheme loop --iterations 2";
const char* const kDecimationNote =
    "the torus refined by two Loop steps (18,432 vertices) stands in for the reference's "
    "28,264-vertex model";

ReferenceFigure fairing(std::string name, std::string title, std::string reference, bool head,
                        std::string operation, double reference_step, double step,
                        std::string translation, FigureResult result = FigureResult::Smoothed) {
    ReferenceFigure f;
    f.name = std::move(name);
    f.title = std::move(title);
    f.reference = std::move(reference);
    f.model = head ? kHead : kSphere;
    f.model_note = head ? kHeadNote : kSphereNote;
    if (head) f.setup = {kHeadNoise};
    f.operation = std::move(operation);
    f.reference_step = reference_step;
    f.step = step;
    f.translation = std::move(translation);
    f.result = result;
    return f;
}

ReferenceFigure other(std::string name, std::string title, std::string reference, std::string model,
                      std::string model_note, std::vector<std::string> setup, std::string operation,
                      FigureResult result) {
    ReferenceFigure f;
    f.name = std::move(name);
    f.title = std::move(title);
    f.reference = std::move(reference);
    f.model = std::move(model);
    f.model_note = std::move(model_note);
    f.setup = std::move(setup);
    f.operation = std::move(operation);
    f.translation = kNoStep;
    f.result = result;
    return f;
}

std::vector<ReferenceFigure> make_figures() {
    const double sphere_improved = 66.5;
    const double head_improved = 0.0002 / (kHeadEdge * kHeadEdge);  // 2
    const std::string sphere_improved_text =
        "the reference's improved umbrella is in 1/length² (1.7); trilab's is scale-free: step "
        "1.0 / h² with h = 0.123, the mean edge of a unit sphere of about 1,000 vertices = 66.5";
    return {
        fairing("1.2b", "Umbrella, 8 explicit steps of 1 on the noisy sphere",
                "noisy sphere (1,026 vertices); umbrella, step 1.0, 8 iterations", false,
                "smooth --operator umbrella --step 1 --iterations 8", 1, 1, kSameUnits),
        fairing("1.2d", "Umbrella, 2 explicit steps of 1 on the noisy head",
                "noisy head (17,358 vertices); umbrella, step 1.0, 2 iterations", true,
                "smooth --operator umbrella --step 1 --iterations 2", 1, 1, kSameUnits),
        fairing("1.4b", "Improved umbrella, one implicit step on the noisy sphere",
                "noisy sphere (1,026 vertices); improved umbrella, implicit, step 1.0, 1 "
                "iteration",
                false, "smooth --operator improved-umbrella --integration implicit --step 66.5",
                1.0, sphere_improved, sphere_improved_text),
        fairing("1.4d", "Improved umbrella, one implicit step on the noisy head",
                "noisy head (17,358 vertices); improved umbrella, implicit, step 0.0002, 1 "
                "iteration",
                true, "smooth --operator improved-umbrella --integration implicit --step 2", 0.0002,
                head_improved,
                "the reference's improved umbrella is in 1/length² (1.7); trilab's is "
                "scale-free: step 0.0002 / h² with h = 0.01, the mean edge of a head about one "
                "unit tall with 17,358 vertices = 2 (taken as it is, 0.0002 would barely move "
                "a vertex here)"),
        fairing("1.7b", "Curvature flow, 8 explicit steps of 1 on the noisy sphere",
                "noisy sphere (1,026 vertices); curvature flow, step 1.0, 8 iterations", false,
                "smooth --operator curvature-flow --step 1 --iterations 8", 1, 1, kSameUnits),
        fairing("1.7d", "Curvature flow, 2 explicit steps of 1 on the noisy head",
                "noisy head (17,358 vertices); curvature flow, step 1.0, 2 iterations", true,
                "smooth --operator curvature-flow --step 1 --iterations 2", 1, 1, kSameUnits),
        fairing("1.10b", "Second-order differences, 8 steps of 1 on the noisy sphere",
                "noisy sphere (1,026 vertices); second-order difference, step 1.0, 8 iterations",
                false, "smooth --operator second-order --step 1 --iterations 8", 1, 1, kSameUnits),
        fairing("1.10d", "Second-order differences, 2 steps of 1 on the noisy head",
                "noisy head (17,358 vertices); second-order difference, step 1.0, 2 iterations",
                true, "smooth --operator second-order --step 1 --iterations 2", 1, 1, kSameUnits),
        [&] {
            ReferenceFigure f =
                fairing("1.12b", "Explicit umbrella at step 20 explodes",
                        "bunny (35,947 vertices); umbrella, explicit, step 20.0, 1 iteration",
                        false, "smooth --operator umbrella --step 20", 20, 20,
                        std::string(kSameUnits) +
                            "; explicit steps are stable up to about 1.3, so trilab stops this run "
                            "and keeps nothing (Show the diverging run shows what it did)",
                        FigureResult::Diverges);
            f.model_note = kBunnyNote;
            return f;
        }(),
        [&] {
            ReferenceFigure f =
                fairing("1.12c", "Implicit umbrella at step 20 smooths",
                        "bunny (35,947 vertices); umbrella, implicit, step 20.0, 1 iteration",
                        false, "smooth --operator umbrella --integration implicit --step 20", 20,
                        20, std::string(kSameUnits) + "; implicit steps are stable at any size");
            f.model_note = kBunnyNote;
            return f;
        }(),
        [&] {
            ReferenceFigure f = fairing(
                "1.12d", "20 explicit umbrella steps of 1",
                "bunny (35,947 vertices); umbrella, explicit, step 1.0, 20 iterations", false,
                "smooth --operator umbrella --step 1 --iterations 20", 1, 1, kSameUnits);
            f.model_note = kBunnyNote;
            return f;
        }(),
        fairing("1.13b", "Improved umbrella, implicit step: the sphere shrinks",
                "noisy sphere (1,026 vertices); improved umbrella, implicit, step 1.0, no "
                "volume preservation",
                false, "smooth --operator improved-umbrella --integration implicit --step 66.5",
                1.0, sphere_improved, sphere_improved_text),
        fairing("1.13c", "The same with volume preservation (anti-shrinking)",
                "noisy sphere (1,026 vertices); improved umbrella, implicit, step 1.0, "
                "anti-shrinking on",
                false,
                "smooth --operator improved-umbrella --integration implicit --step 66.5 "
                "--preserve-volume",
                1.0, sphere_improved, sphere_improved_text),
        other("1.15b", "Low-pass: the 50 lowest frequencies of the noisy sphere",
              "noisy sphere (1,026 vertices/frequencies); the 50 lowest frequencies", kSphere,
              kSphereNote, {}, "spectrum --k 50 --band 0:49", FigureResult::Filtered),
        other("1.15c", "3 of the 50 frequencies (the band splits lambda_1's three)",
              "noisy sphere; 3 of the 50 computed frequencies", kSphere, kSphereNote, {},
              "spectrum --k 50 --band 0:2", FigureResult::Filtered),
        other("1.16", "Low-pass: the 150 lowest frequencies",
              "cow (11,610 vertices); the 150 lowest frequencies", kHead,
              "the torus (1,152 vertices) stands in for the reference's cow", {},
              "spectrum --k 150 --band 0:149", FigureResult::Filtered),
        other("1.20", "Loop subdivision, 5 iterations",
              "20 vertices to 74, 290, 1,154, 4,610, 18,434 (Loop)", kCube, kCubeNote, {},
              "subdivide --scheme loop --iterations 5", FigureResult::Subdivided),
        other("1.22", "Modified Butterfly subdivision, 5 iterations",
              "20 vertices to 74, 290, 1,154, 4,610, 18,434 (Modified Butterfly)", kCube, kCubeNote,
              {}, "subdivide --scheme modified-butterfly --iterations 5", FigureResult::Subdivided),
        other("1.26", "Sqrt3 subdivision, 5 iterations",
              "20 vertices to 56, 164, 488, 1,460, 4,376 (sqrt3)", kCube, kCubeNote, {},
              "subdivide --scheme sqrt3 --iterations 5", FigureResult::Subdivided),
        other("1.29", "Quadric decimation, 60 % per iteration, 5 iterations",
              "28,264 vertices to 11,306, 4,523, 1,810, 725, 291 (quadric error, 60 % of the "
              "edges collapsed per step)",
              kHead, kDecimationNote, {kDecimationSetup},
              "decimate --cost quadric --percent 60 --iterations 5", FigureResult::Decimated),
        other("1.31", "Roundness decimation, 30 % per iteration, 5 iterations",
              "28,264 vertices to 19,785, 13,850, 9,696, 6,788, 4,752 (normalized roundness, "
              "30 % per step)",
              kHead, kDecimationNote, {kDecimationSetup},
              "decimate --cost roundness --percent 30 --iterations 5", FigureResult::Decimated),
    };
}

}  // namespace

const std::vector<ReferenceFigure>& reference_figures() {
    static const std::vector<ReferenceFigure> figures = make_figures();
    return figures;
}

const ReferenceFigure* find_reference_figure(const std::string& name) {
    for (const ReferenceFigure& f : reference_figures())
        if (f.name == name) return &f;
    // "1.12": its first sub-figure ("1.12b"), never "1.120".
    for (const ReferenceFigure& f : reference_figures())
        if (f.name.size() == name.size() + 1 && f.name.compare(0, name.size(), name) == 0 &&
            f.name.back() >= 'a' && f.name.back() <= 'z')
            return &f;
    return nullptr;
}

std::string reference_figure_names() {
    std::string names;
    for (const ReferenceFigure& f : reference_figures())
        names += (names.empty() ? "" : ", ") + f.name;
    return names;
}

HalfedgeMesh reference_figure_input(const ReferenceFigure& figure, Progress& progress) {
    HalfedgeMesh mesh = generate(figure.model);
    RunSettings settings;
    settings.keep_steps = false;
    settings.morph = false;
    for (const std::string& text : figure.setup) {
        OperationResult result = run_operation(parse_operation(text), mesh, progress, settings);
        mesh = std::move(result.steps.back().mesh);
    }
    return mesh;
}

}  // namespace trilab::viewer
