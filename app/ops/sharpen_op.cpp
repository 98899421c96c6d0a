// The "sharpen" operation: tags edges as features by hand (core/features.h, issue 39): one
// edge (--edge E, as the Inspector and `trilab-cli inspect` number them) or every edge whose
// two ends are in the region; infinitely sharp by default, semi-sharp with --sharpness S
// (Loop's rule for the first floor(S) levels, then blended), cleared with --clear. The
// Features tool's click on an edge and "Sharpen the selection's edges" run it, so each tag
// is one history entry, undone like any operation, and replayed by recipes.
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <utility>

#include "app/ops/operation_decl.h"
#include "app/ops/operation_entries.h"
#include "core/errors.h"
#include "core/features.h"
#include "core/number_text.h"

namespace trilab {
namespace {

struct SharpenOptions {
    bool semi = false;              ///< --sharpness S given (otherwise: infinitely sharp)
    double sharpness = 1.0;         ///< S, when semi
    std::optional<long long> edge;  ///< one edge (unset: the region's edges)
    bool clear = false;             ///< sharpness 0: smooth again
};

OperationResult run_sharpen(const SharpenOptions& o, const HalfedgeMesh& mesh, Progress& progress,
                            const RunSettings& settings) {
    progress.check_cancelled();
    const float value = o.clear ? 0.0f : o.semi ? float(o.sharpness) : kInfiniteSharpness;
    OperationStep step{mesh, MorphCorrespondence{MorphCorrespondence::Kind::SameVertices, {}}};
    HalfedgeMesh& m = step.mesh;
    std::size_t tagged = 0, changed = 0;
    const auto tag = [&](Edge e) {
        ++tagged;
        if (sharpness(m, e) != value) ++changed;
        set_sharpness(m, e, value);
    };
    if (o.edge) {
        const long long e = *o.edge;
        if (e < 0 || std::size_t(e) >= m.edges_size() || m.is_deleted(Edge(Index(e))))
            throw InvalidArgument("--edge: edge " + std::to_string(e) +
                                  " is not an edge of the mesh (it has " +
                                  std::to_string(m.edges_size()) + " edges)");
        tag(Edge(Index(e)));
    } else {
        if (!settings.region)
            throw InvalidArgument(
                "sharpen: give --edge E, or a region: its edges with both ends in it are tagged");
        const std::vector<float>& w = *settings.region;
        for (Edge e : m.edges()) {
            const Halfedge h = HalfedgeMesh::halfedge(e, 0);
            if (w[m.from_vertex(h).idx()] > 0.0f && w[m.to_vertex(h).idx()] > 0.0f) tag(e);
        }
        if (tagged == 0)
            throw InvalidArgument(
                "sharpen: the region holds no edge (an edge is tagged when both its ends are "
                "selected)");
    }
    OperationResult result;
    result.label = o.clear ? "Clear sharp edges" : "Sharpen edges";
    const std::string what = o.clear  ? "smooth (sharpness 0)"
                             : o.semi ? "semi-sharp (sharpness " + number_text(o.sharpness) + ")"
                                      : "infinitely sharp";
    result.report.push_back(count_text(tagged, "edge", "edges") + " made " + what + ", " +
                            std::to_string(changed) + " of them changed");
    result.values = {{"edges", double(tagged)}, {"changed", double(changed)}};
    result.steps.push_back(std::move(step));
    progress.report(1, "tagging edges");
    return result;
}

}  // namespace

std::unique_ptr<OperationDef> sharpen_operation() {
    OperationDecl<SharpenOptions> d(
        "sharpen", "Sharpen edges",
        "Tags edges by hand: one edge (--edge), or the edges with both ends in the region; "
        "infinitely sharp by default, semi-sharp with --sharpness (Loop's sharp rule for the "
        "first floor(S) levels, then blended), smooth again with --clear. Subdivision, "
        "decimation and fairing keep the tagged edges.");
    d.switchable(
         "sharpness", [](SharpenOptions & o) -> auto& { return o.semi; },
         [](SharpenOptions & o) -> auto& { return o.sharpness; }, 0, 1000, "infinite",
         "the edges' sharpness (infinite: a crease at every level)")
        .above_min()
        .label("sharpness");
    d.integer("edge", &SharpenOptions::edge, 0, 4e9, "one edge by its index")
        .default_note("the region's edges");
    d.flag("clear", &SharpenOptions::clear, "make the edges smooth again (sharpness 0)");
    d.run(run_sharpen)
        .acts_on_region("tags the edges with both ends in the region (without --edge)");
    return d.build();
}

}  // namespace trilab
