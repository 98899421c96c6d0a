// The "flip" operation: reverses the orientation of every face (core/algorithms/orientation.h), for
// meshes whose faces point inwards (a closed mesh with a negative volume).
#include <chrono>
#include <cstdio>
#include <string>
#include <utility>

#include "app/ops/operation_decl.h"
#include "app/ops/operation_entries.h"
#include "core/algorithms/orientation.h"
#include "core/number_text.h"

namespace trilab {
namespace {

OperationResult run_flip(const FlipOptions&, const HalfedgeMesh& mesh, Progress& progress,
                         const RunSettings& settings) {
    progress.check_cancelled();
    progress.report(0, "flipping the orientation");
    OperationResult result;
    result.label = "Flip orientation";
    // The vertices do not move: the morph has nothing to show but is well defined.
    const bool consume = settings.consumable == &mesh;
    OperationStep step{consume ? std::move(*settings.consumable) : mesh,
                       MorphCorrespondence{MorphCorrespondence::Kind::SameVertices, {}}};
    const auto t0 = std::chrono::steady_clock::now();
    FlipOptions options;
    options.region = settings.region;
    options.components = settings.components;
    const FlipReport report = flip_orientation(step.mesh, options);
    result.ms = ms_since(t0);
    progress.report(1, "flipping the orientation");
    result.steps.push_back(std::move(step));
    result.report.push_back("reversed " + count_text(report.faces, "face", "faces"));
    if (settings.region)
        result.report.push_back("the region touches " +
                                count_text(report.components, "component", "components") +
                                ", flipped whole");
    char line[160];
    if (report.volume_before) {
        std::snprintf(line, sizeof(line), "volume %.6g -> %.6g", *report.volume_before,
                      *report.volume_after);
        result.report.emplace_back(line);
    } else {
        result.report.emplace_back("open mesh: no volume");
    }
    if (report.normals_negated) result.report.emplace_back("stored vertex normals negated");
    result.values = {{"faces", double(report.faces)}};
    if (report.volume_before)
        result.values.insert(result.values.end(), {{"volume_before", *report.volume_before},
                                                   {"volume_after", *report.volume_after}});
    result.typed_report = report;
    return result;
}

}  // namespace

std::unique_ptr<OperationDef> flip_operation() {
    OperationDecl<FlipOptions> d(
        "flip", "Flip orientation",
        "Reverses the orientation of every face, so a closed mesh whose faces point inwards "
        "(a negative volume; the viewer shows its back faces) faces outwards. Vertices, "
        "edges, faces and their attributes are kept; stored vertex normals are negated.");
    d.run(run_flip).acts_on_region(
        "every connected component with a vertex of positive weight is flipped whole");
    return d.build();
}

}  // namespace trilab
