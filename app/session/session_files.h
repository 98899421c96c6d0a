#pragma once
// SessionFiles: files, session files and the crash journal. Loads a mesh (with a simplified
// picture of a large file while it is built) or a texture, saves the mesh or the whole
// session, opens a session file or journal, and journals every history change; each as a job
// on the one runner. LoadFile and OpenSession of a document with unsaved changes can wait for
// the window's confirmation.
#include <functional>
#include <memory>
#include <mutex>
#include <string>

#include "app/history/journal.h"
#include "app/history/session_file.h"
#include "app/session/commands.h"
#include "app/session/session_core.h"
#include "app/session/session_document.h"
#include "app/session/session_preview.h"

namespace trilab::viewer {

class SessionFiles {
public:
    SessionFiles(SessionCore& core, SessionDocument& document, SessionPreviews& previews)
        : core_(core), document_(document), previews_(previews) {}

    /// The picture of the file being loaded, once its arrays are read (null otherwise; cleared
    /// when the load job ends). Safe to call while the job runs.
    std::shared_ptr<const LoadingPicture> loading_picture() const;
    /// The journal, or nullptr when none runs (--no-recovery).
    const Journal* journal() const { return journal_.get(); }

    /// Carries out a file command (LoadFile, SaveFile, SaveSession, OpenSession,
    /// RecoverJournal, RevertFile, LoadTexture, JournalSettings); false: not one.
    bool execute(const Command& command);
    /// A job ended (whatever its outcome): its loading picture goes.
    void job_ended();
    /// After every history change: the journal queues it.
    void record();
    /// Each frame: a journal that stopped (a full disk) says so once, in the log and the
    /// status bar; the viewer goes on without it.
    void check_journal();

    // ---- set-up by the window ----------------------------------------------------------------
    /// Loads make their picture with `maker` (none without one: the default).
    void set_loading_picture_maker(LoadingPictureMaker maker) { picture_maker_ = std::move(maker); }
    /// What SaveFile (of a .trilab) and SaveSession store beside the history: the window's
    /// view, panels and texture (none without a provider: a headless session).
    void set_extras_provider(std::function<SessionExtras()> provider) {
        extras_provider_ = std::move(provider);
    }
    /// LoadFile and OpenSession of a document with unsaved changes wait for a confirmation
    /// (SessionEvents::confirm_discard) instead of replacing it; off by default (headless).
    void set_ask_before_discarding(bool ask) { ask_before_discarding_ = ask; }
    /// Journals every history change from now on, starting with the history as it is.
    void start_journal(JournalOptions options);
    /// Writes what the journal has queued (tests).
    void flush_journal();
    /// A clean end: writes what is queued and removes the journal's file.
    void close_journal();
    /// An end without saving: the journal's file stays, marked (Journal::end_unsaved).
    void end_journal_unsaved(const std::string& how);

private:
    void load(const std::string& path);
    void save(const std::string& path);
    void load_texture(const std::string& path);
    void save_session(const std::string& path);
    void open_session(const std::string& path, bool remove_after = false);
    void restore_session(SessionContents contents, const std::string& path);
    /// The document has unsaved changes and the window asks before replacing it: the command
    /// for `path` waits (SessionEvents::confirm_discard); returns true then.
    bool asks_before_discarding(bool discard_changes, const std::string& path);
    /// A save ended: the events and the document say so.
    void saved(const std::string& path);

    SessionCore& core_;
    SessionDocument& document_;
    SessionPreviews& previews_;
    /// The load job's picture, handed from the job's thread to the window's.
    struct PictureSlot {
        mutable std::mutex mutex;
        std::shared_ptr<const LoadingPicture> picture;
    };
    std::shared_ptr<PictureSlot> picture_slot_ = std::make_shared<PictureSlot>();
    LoadingPictureMaker picture_maker_;
    std::function<SessionExtras()> extras_provider_;
    bool ask_before_discarding_ = false;
    bool continue_after_save_ = false;  ///< the running save was asked for with then_continue
    std::unique_ptr<Journal> journal_;  ///< records every history change (crash recovery)
};

}  // namespace trilab::viewer
