#pragma once
// The crash journal: while a session runs, every completed history change is appended to
// $XDG_STATE_HOME/trilab/recovery/trilab-PID.journal (default ~/.local/state/trilab/recovery/)
// in the session-file format (docs/file-formats.md#crash-journals), and flushed to the disk
// (fdatasync) when the change is complete; a clean close removes the file. After a crash,
// read_journal() (app/history/session_file.h) restores the longest valid prefix: exactly the
// changes that were complete.
//
// Threads: record() only hands an immutable snapshot (History::snapshot(), a pointer per
// entry) to a writer thread and returns; the writer compares it with the last snapshot it
// wrote and appends what changed: new entries (their arrays that no written state holds, so
// a geometry-only step costs its positions), entries dropped at the front (the memory
// budget) or at the back, and the current entry (undo, redo, jump). Snapshots that queue up
// while the writer is busy are coalesced into the newest. Errors (an unwritable folder, a
// full disk) never reach the caller: the journal stops, and take_warning() returns one
// message, once.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "app/history/history.h"

namespace trilab {

/// $XDG_STATE_HOME/trilab/recovery, or ~/.local/state/trilab/recovery ("" when neither
/// XDG_STATE_HOME nor HOME is set).
std::string default_recovery_directory();

struct JournalOptions {
    std::string directory;  ///< "": default_recovery_directory()
    std::string program = "trilab";
    /// fdatasync after each record (the guarantee after a power loss); tests may turn it off.
    bool sync = true;
};

class Journal {
public:
    /// Starts the writer thread; the file is created (with its folder) by the first record.
    /// Never throws for file errors (see take_warning()).
    explicit Journal(JournalOptions options = {});
    /// Writes what is queued and stops; the file stays (only close() removes it).
    ~Journal();
    Journal(const Journal&) = delete;
    Journal& operator=(const Journal&) = delete;

    /// Records the history as it is after a change. Cheap: no copy of any array.
    void record(History::Snapshot snapshot) noexcept;
    /// Records the viewer's settings (key=value text, as in a session file).
    void record_viewer_settings(std::string text) noexcept;
    /// Waits until everything recorded so far is written and synced.
    void flush();
    /// A clean end: writes what is queued, stops the thread and removes the file.
    void close();
    /// An end without a chance to save (SIGTERM at a logout, `systemctl stop`): writes what is
    /// queued, stops the thread and keeps the file for recovery, with a note beside it
    /// (PATH.ended, holding `how`) that the next start reads: not a crash, unsaved work.
    void end_unsaved(const std::string& how);

    /// The journal's path ("" until the writer has created it, or when it could not).
    std::string path() const;
    /// The warning of a failure, once (then ""); thread-safe.
    std::string take_warning();
    bool failed() const;

    struct Stats {
        std::size_t records = 0;                          ///< snapshots written (after coalescing)
        std::size_t bytes = 0;                            ///< file size
        double encode_ms = 0, write_ms = 0, sync_ms = 0;  ///< the writer thread's time
    };
    Stats stats() const;

private:
    /// Writes what is queued and stops the writer thread (the file stays).
    void stop();
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

/// A journal whose process no longer runs (a crash).
struct OrphanJournal {
    std::string path;
    std::uint32_t pid = 0;
    std::uint64_t bytes = 0;
    std::int64_t modified = 0;  ///< seconds since the epoch
    /// How its viewer ended without saving ("SIGTERM": Journal::end_unsaved()); "" for a crash.
    std::string ended;
};
/// The journals in `directory` ("": the default) whose process is gone (or is another
/// process with the same id, told apart by its start time), newest first. Never throws.
std::vector<OrphanJournal> find_orphan_journals(const std::string& directory = "");
/// Removes the journal at `path` and its note (PATH.ended), restored or discarded. Never
/// throws.
void remove_journal(const std::string& path);

}  // namespace trilab
