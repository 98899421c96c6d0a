// The session's facade: it wires the owners, follows a new state in all of them and is the
// one executor of every command; see session.h.
#include "app/session/session.h"

#include <chrono>
#include <cstdio>
#include <thread>
#include <utility>

#include "app/ops/operation_entries.h"
#include "core/algorithms/generators.h"

namespace trilab::viewer {

Session::Session() {
    core_.state_changed = [this](bool fit) { on_state_changed(fit); };
    core_.document_shown = [this] { picking_.follow(); };
    document_.push_loaded(make_default_model(), "Default model", "default model", "", LoadReport{});
    core_.document.unsaved = false;
    core_.events = SessionEvents{};
    core_.events.state_changed = core_.events.fit = true;
}

Session::~Session() = default;

SessionEvents Session::take_events() {
    SessionEvents e = std::move(core_.events);
    core_.events = SessionEvents{};
    return e;
}

void Session::on_state_changed(bool fit) {
    levels_.clear(true);  // a level of detail belongs to the state it was built on
    document_.describe_state();
    morph_.reset(document_.entry_moves());
    // The status bar tells where the document is now (a load says more afterwards).
    const History& history = core_.document.history;
    const History::EntryInfo entry = history.info(history.current());
    core_.inform("state " + std::to_string(history.current()) + ": " + entry.label +
                 (entry.parameters.empty() ? "" : " " + entry.parameters));
    frequency_.follow_document();
    core_.show_document();
    files_.record();  // queues only
    core_.events.state_changed = true;
    core_.events.fit = core_.events.fit || fit;
}

void Session::execute(const Command& command) {
    if (selection_.execute(command) || morph_.execute(command) || files_.execute(command) ||
        execute_document(command))
        return;
    execute_other(command);
}

bool Session::execute_document(const Command& command) {
    if (std::holds_alternative<Undo>(command) || std::holds_alternative<Redo>(command) ||
        std::holds_alternative<JumpTo>(command)) {
        previews_.clear();  // a preview belongs to the state it was computed on
        levels_.clear(true);
        document_.step_history(command);
    } else if (auto* op = std::get_if<RunOperation>(&command)) {
        previews_.clear();
        document_.run(op->op);
    } else if (auto* preview = std::get_if<PreviewOperation>(&command)) {
        previews_.request(preview->op);
    } else if (auto* apply = std::get_if<ApplyOperation>(&command)) {
        previews_.apply(apply->op);
    } else if (std::holds_alternative<CancelPreview>(command)) {
        previews_.clear();
        levels_.clear(false);
    } else if (std::holds_alternative<PredictionDrawn>(command)) {
        previews_.prediction_drawn();
    } else if (auto* build = std::get_if<BuildLevelOfDetail>(&command)) {
        previews_.clear();
        levels_.build(build->op);
    } else if (auto* show = std::get_if<ShowLevelOfDetail>(&command)) {
        if (!levels_.ready()) return true;
        previews_.clear();
        levels_.show(show->percent);
    } else if (std::holds_alternative<ApplyLevelOfDetail>(command)) {
        levels_.apply();
    } else if (auto* t = std::get_if<ProjectTexCoords>(&command)) {
        document_.project_texcoords(t->projection, t->up);
    } else if (std::holds_alternative<CancelJob>(command)) {
        core_.jobs.cancel();
    } else {
        return false;
    }
    return true;
}

bool Session::execute_other(const Command& command) {
    if (auto* d = std::get_if<Decompose>(&command)) {
        frequency_.decompose(spectral_options(d->op));
    } else if (auto* band = std::get_if<PreviewBand>(&command)) {
        frequency_.preview_band(band->lo, band->hi);
    } else if (auto* commit = std::get_if<CommitBand>(&command)) {
        frequency_.push_band(commit->lo, commit->hi, false);
    } else if (std::holds_alternative<RestoreDecomposed>(command)) {
        frequency_.push_band(0, 0, true);
    } else if (auto* pick = std::get_if<PickAt>(&command)) {
        picking_.pick(pick->ray, pick->t_min, pick->second);
    } else if (std::holds_alternative<ClearPicks>(command)) {
        picking_.clear();
    } else if (auto* want = std::get_if<WantPickDistances>(&command)) {
        picking_.want_distances(want->want);
    } else if (auto* inspect = std::get_if<SetInspectionOptions>(&command)) {
        picking_.set_inspection_options(inspect->options);
    } else if (auto* figure = std::get_if<LoadFigure>(&command)) {
        figures_.load_figure(figure->name);
    } else if (auto* diverging = std::get_if<ShowDivergingRun>(&command)) {
        if (!busy()) figures_.show_diverging_run(diverging->op);
    } else if (auto* c = std::get_if<ComputeColoring>(&command)) {
        coloring_.compute(*c);
    } else if (auto* values = std::get_if<SetColoringValues>(&command)) {
        coloring_.set_values(values->values);
    } else if (auto* step = std::get_if<EstimateStableStep>(&command)) {
        guidance_.estimate_stable_step(step->op);
    } else if (auto* edges = std::get_if<FindCollapsingEdges>(&command)) {
        guidance_.find_collapsing_edges(edges->op);
    } else if (std::holds_alternative<NoticeShown>(command)) {
        core_.notice.popup_pending = false;
    } else {
        return false;
    }
    return true;
}

bool Session::poll() {
    picking_.update();
    guidance_.update();
    files_.check_journal();
    const JobRunner::Outcome outcome = core_.jobs.poll();
    using Kind = JobRunner::Outcome::Kind;
    if (outcome.kind == Kind::None) return false;
    files_.job_ended();  // the job ended (loaded, failed or cancelled): its loading picture goes
    if (outcome.job == JobKind::Preview) {
        previews_.job_ended(outcome);
        if (outcome.kind != Kind::Failed) return true;
    }
    if (outcome.kind == Kind::Failed) {
        core_.notify_error(outcome.message);
    } else if (outcome.kind == Kind::Cancelled) {
        core_.log.warning(outcome.name + ": cancelled, nothing changed");
        core_.inform(outcome.name + ": cancelled");
    } else {
        char buf[64];
        std::snprintf(buf, sizeof(buf), " (%.0f ms)", outcome.seconds * 1000.0);
        core_.log.info(outcome.name + " done" + buf);
    }
    return true;
}

void Session::finish_jobs() {
    while (core_.jobs.busy() || previews_.outstanding()) {
        previews_.advance();
        poll();
        if (core_.jobs.busy() || previews_.prediction_computing())
            std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    guidance_.finish();
    poll();
}

void Session::wait_for_preview(double seconds) {
    // A preview that is about to finish shows in this frame rather than the next: wait for it
    // a bounded time (a frame's hiccup, never a freeze). Not while the spectral prediction is
    // on the screen: it already shows the change, and the exact result replaces it when ready.
    previews_.advance();
    if (previews_.prediction_shown()) return;
    const double until = now() + seconds;
    while (core_.preview_job() && core_.jobs.elapsed_seconds() < seconds && now() < until) {
        poll();
        if (core_.preview_job()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
}

void Session::update() {
    if (!previews_.update()) morph_.update();
}

}  // namespace trilab::viewer
