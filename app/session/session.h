#pragma once
// Session: the document, its history, the job runner and the operations, with no window, no
// GL and no ImGui. A small facade over owners of one concern each (session_core.h holds what
// they share):
//   SessionDocument   the document and its history: loads, operations, undo and redo
//   SessionPreviews   the operation panels' live previews and spectral predictions
//   SessionLevels     Decimation's level-of-detail slider
//   SessionSelection  the document's selection
//   SessionPicking    picks, measurements and the Inspector
//   SessionFrequency  the frequency document: decomposition, live band, band entries
//   SessionFiles      files, session files and the crash journal
//   SessionFigures    the reference's figures and the diverging run
//   SessionColoring   the colouring job and the colouring's values
//   SessionMorph      the current entry's morph on the session's clock
//   SessionGuidance   Fairing's stable step and Decimation's collapsing edges, off the thread
// The window (and the headless tests) change it only through the typed commands the panels
// queue (commands.h), one executor for all of them, and read it through const views: shown()
// is what the view shows now (the document, a preview step, a morph frame, a level of detail
// or a frequency band).
//
// Threads: every method runs on the caller's (the render) thread. A job is handed what it
// reads (a copy-on-write snapshot of the mesh, taken here) and returns a finish function
// that poll() runs back on this thread; no job reaches into the session from its worker.
#include <cstddef>
#include <functional>
#include <memory>
#include <string>

#include "app/history/journal.h"
#include "app/history/session_file.h"
#include "app/session/commands.h"
#include "app/session/session_coloring.h"
#include "app/session/session_core.h"
#include "app/session/session_document.h"
#include "app/session/session_figures.h"
#include "app/session/session_files.h"
#include "app/session/session_frequency.h"
#include "app/session/session_guidance.h"
#include "app/session/session_levels.h"
#include "app/session/session_morph.h"
#include "app/session/session_picking.h"
#include "app/session/session_preview.h"
#include "app/session/session_selection.h"

namespace trilab::viewer {

class Session {
public:
    /// A session on the built-in default model.
    Session();
    ~Session();
    Session(const Session&) = delete;
    Session& operator=(const Session&) = delete;

    /// Carries out a document command (a load, an operation, a preview, undo...); commands that
    /// are the window's business (FitView, TakeScreenshot, Quit, ...) are ignored.
    void execute(const Command& command);
    /// Applies a finished job; returns true when one ended (the window redraws).
    bool poll();
    /// Runs jobs to their end (tests and scripted runs): poll() until no job runs.
    void finish_jobs();
    /// Waits up to `seconds` for a running preview, so that it shows in the coming frame.
    void wait_for_preview(double seconds);
    /// Advances the morph playback (time from now()) and updates shown().
    void update();
    SessionEvents take_events();

    // ---- what the window reads ---------------------------------------------------------------
    const Document& document() const { return core_.document; }
    const HalfedgeMesh& mesh() const { return core_.mesh(); }
    const History& history() const { return core_.document.history; }
    const Shown& shown() const { return core_.shown; }
    /// What the status bar shows (notify(), notify_error(); NoticeShown after the popup).
    const Notice& notice() const { return core_.notice; }
    const JobRunner& jobs() const { return core_.jobs; }
    bool busy() const { return core_.jobs.busy(); }
    /// The morph playback (changed by PlayMorph, ShowMorphAt and SetMorphAnimation).
    const MorphState& morph() const { return core_.morph; }
    /// Seconds on the session's clock (the morph's, and the panels' playback start).
    double now() const { return core_.now(); }
    const SessionDocument& editing() const { return document_; }
    const SessionPreviews& previews() const { return previews_; }
    const SessionLevels& levels() const { return levels_; }
    const SessionSelection& selections() const { return selection_; }
    const SessionPicking& picking() const { return picking_; }
    const SessionFiles& files() const { return files_; }
    const SessionFigures& figures() const { return figures_; }
    const SessionColoring& coloring() const { return coloring_; }
    const SessionGuidance& guidance() const { return guidance_; }

    // ---- messages: the log (thread-safe) and the status bar ----------------------------------
    Log& log() { return core_.log; }
    const Log& log() const { return core_.log; }
    /// An error in the status bar, the log and the popup.
    void notify_error(const std::string& text) { core_.notify_error(text); }
    /// Replaces the status bar's notice (Notice{}: none).
    void notify(Notice notice) { core_.notice = std::move(notice); }

    // ---- set-up by the window ----------------------------------------------------------------
    /// Loads make their picture with `maker` (none without one: the default).
    void set_loading_picture_maker(LoadingPictureMaker maker) {
        files_.set_loading_picture_maker(std::move(maker));
    }
    /// What SaveFile (of a .trilab) and SaveSession store beside the history.
    void set_extras_provider(std::function<SessionExtras()> provider) {
        files_.set_extras_provider(std::move(provider));
    }
    /// LoadFile and OpenSession of a document with unsaved changes wait for a confirmation.
    void set_ask_before_discarding(bool ask) { files_.set_ask_before_discarding(ask); }
    /// The history's memory budget in bytes (History::set_budget).
    void set_history_budget(std::size_t bytes) { core_.document.history.set_budget(bytes); }
    /// Journals every history change from now on (app/history/journal.h).
    void start_journal(JournalOptions options) { files_.start_journal(std::move(options)); }
    /// Writes what the journal has queued.
    void flush_journal() { files_.flush_journal(); }
    /// A clean end: writes what is queued and removes the journal's file.
    void close_journal() { files_.close_journal(); }
    /// An end without a chance to save (`how`: "SIGTERM"): the journal's file is kept for
    /// recovery, marked as unsaved work rather than a crash (Journal::end_unsaved).
    void end_journal_unsaved(const std::string& how) { files_.end_journal_unsaved(how); }

private:
    /// Every owner follows a new current state.
    void on_state_changed(bool fit);
    /// Carries out a command of the document, the previews or the levels of detail; false:
    /// not one.
    bool execute_document(const Command& command);
    /// Carries out a command of the other owners; false: not one.
    bool execute_other(const Command& command);

    SessionCore core_;
    SessionDocument document_{core_};
    SessionPreviews previews_{core_, document_};
    SessionLevels levels_{core_, document_};
    SessionPicking picking_{core_, document_};
    SessionColoring coloring_{core_};
    SessionSelection selection_{core_, previews_, picking_, coloring_};
    SessionMorph morph_{core_};
    SessionFrequency frequency_{core_, morph_};
    SessionFiles files_{core_, document_, previews_};
    SessionFigures figures_{core_, document_, previews_, levels_};
    SessionGuidance guidance_{core_};
};

}  // namespace trilab::viewer
