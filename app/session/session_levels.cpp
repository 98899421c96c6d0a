// Decimation's level-of-detail slider; see session_levels.h.
#include "app/session/session_levels.h"

#include <algorithm>
#include <cstdio>
#include <memory>
#include <utility>

#include "app/ops/decimate_op.h"
#include "app/ops/operation_entries.h"

namespace trilab::viewer {

bool SessionLevels::ready() const {
    return state_.lod && state_.base == core_.mesh().revision();
}

void SessionLevels::build(const Operation& op) {
    clear(true);
    DecimationOptions options;
    try {
        options = decimation_options(op);
    } catch (const std::exception& e) {
        core_.notify_error(e.what());
        return;
    }
    const HalfedgeMesh snapshot = core_.mesh();  // copy-on-write: the job's own
    const HalfedgeMesh::Revision base = snapshot.revision();
    state_.building = true;
    state_.op = op;
    const double t0 = core_.now();
    const bool started = core_.jobs.start(
        "Building levels of detail", [this, options, base, t0, snapshot](Progress& progress) {
            auto build = std::make_shared<ProgressiveBuild>(
                build_progressive_mesh(snapshot, options, 1.0, progress));
            auto lod = std::make_shared<LevelOfDetail>(build->progressive);
            return JobRunner::Finish([this, build, lod, base, t0] {
                state_.building = false;
                if (base != core_.mesh().revision()) return;
                state_.progressive =
                    std::shared_ptr<const ProgressiveMesh>(build, &build->progressive);
                state_.lod = lod;
                state_.base = base;
                char buf[200];
                std::snprintf(buf, sizeof buf,
                              "%zu levels, down to %.1f %% of the vertices (%.0f ms)",
                              lod->max_level(), lod->percent_at_level(lod->max_level()),
                              1000.0 * (core_.now() - t0));
                state_.note = buf;
                if (build->report.stop != DecimationStop::Done)
                    state_.note += ": " + build->report.stop_message;
            });
        });
    if (!started) {
        state_.building = false;
        core_.busy_error();
    }
}

void SessionLevels::show(double percent) {
    if (!ready()) return;
    LevelOfDetail& lod = *state_.lod;
    lod.set_level(lod.level_for_percent(std::clamp(percent, 0.0, 100.0)));
    core_.show(Shown::Kind::Level, &core_.mesh(), &lod);
}

void SessionLevels::clear(bool forget) {
    if (core_.shown.kind == Shown::Kind::Level) core_.show_document();
    if (forget) {
        const std::string note = state_.building ? state_.note : std::string();
        const bool building = state_.building;
        state_ = State{};
        state_.building = building;  // a build in flight finds the state moved on, and ends
        state_.note = note;
    }
}

void SessionLevels::apply() {
    if (!ready()) return;
    const LevelOfDetail& lod = *state_.lod;
    const ProgressiveMesh& pm = *state_.progressive;
    OperationResult result;
    result.label = "Decimate";
    HalfedgeMesh mesh = lod.mesh();
    // Each kept vertex starts where it was on the finer mesh (the level's vertices are the
    // live fine vertices, in the fine order).
    std::vector<Point> start;
    for (Index i = 0; i < Index(pm.positions.size()); ++i) {
        if (!pm.vertex_alive[i]) continue;
        const Index v = lod.vertex_of(i);
        if (v != kInvalidIndex && lod.vertex_alive()[v]) start.push_back(pm.positions[i]);
    }
    if (start.size() != mesh.vertices_size()) start = mesh.positions();  // no motion then
    char buf[160];
    std::snprintf(buf, sizeof buf, "level of detail: %zu of %zu vertices (%.1f %%)", lod.vertices(),
                  lod.fine_vertices(), lod.percent_at_level(lod.level()));
    result.report.push_back(buf);
    result.steps.push_back(OperationStep{
        std::move(mesh), MorphCorrespondence{MorphCorrespondence::Kind::FromEarlier, start}});
    Operation op = state_.op;
    DecimateOptions typed = options_of<DecimateOptions>(op);
    typed.target_vertices = lod.vertices();
    set_options(op, typed);
    result.parameters = op.parameters();
    clear(true);
    document_.commit(op, std::move(result));
}

}  // namespace trilab::viewer
