#pragma once
// Session files (.trilab) and crash journals: a whole History on disk, every state restored
// bit for bit. The format is in docs/file-formats.md#session-files: a 16-byte header
// (magic, version) and CRC-32-checked chunks; each array's values are stored once however many
// states share them, so a geometry-only step costs its positions.
//
// A session file is read strictly: any damaged, truncated or inconsistent byte refuses the
// whole file (IoError naming the file, the chunk and the reason), nothing is half restored.
// A journal (app/history/journal.h) is read up to its last complete record: the longest valid
// prefix, with what was lost (entries recovered, bytes discarded).
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "app/history/history.h"

namespace trilab {

/// What the viewer stores beside the history; the history code never interprets it.
struct SessionExtras {
    /// key=value lines the viewer fills (camera, rendering and colouring settings with the
    /// legend range, panel parameters, ...). Empty: none.
    std::string viewer_settings;
    std::string texture_path;   ///< the texture's file, if any
    std::string texture_bytes;  ///< the texture file's bytes, if stored (may be empty)
};

/// One entry as `trilab-cli session info` lists it.
struct SessionEntrySummary {
    std::string label, parameters;
    Operation operation;  ///< empty `def` for loads and viewer-made states
    double ms = 0;
    std::vector<std::pair<std::size_t, std::size_t>> steps;  ///< vertices, faces per step
    /// Bytes of the file this entry added: the arrays and states first written for it and
    /// its own record.
    std::size_t bytes = 0;
};

/// A session or journal as read.
struct SessionContents {
    History history;  ///< every entry, the current one current
    SessionExtras extras;
    std::vector<SessionEntrySummary> entries;  ///< as in `history`, oldest first
    bool journal = false;
    /// Every byte was read (always for a session; a journal may end in an incomplete record).
    bool complete = true;
    std::size_t file_bytes = 0;
    std::size_t bytes_discarded = 0;    ///< a journal's bytes after its last complete record
    std::size_t records = 0;            ///< complete history records (a journal's changes)
    std::string stop_reason;            ///< why a journal's reading stopped early ("" if not)
    std::vector<std::string> messages;  ///< History's budget messages, skipped states
    /// A journal's writer: process id and program ("" for a session).
    std::uint32_t pid = 0;
    std::string program;
};

struct SessionWriteReport {
    std::size_t bytes = 0, arrays = 0, states = 0, entries = 0;
    /// Properties not stored (a type the format does not know), "v:name (...)".
    std::vector<std::string> skipped;
};

/// Writes `snapshot` (History::snapshot()) and `extras` to `path` through a temporary file and
/// a rename (core/io/file_util.h write_file_atomically): the old file stays until the new one
/// is complete. Throws IoError naming `path` (an unwritable folder, a full disk) and
/// InvalidArgument for an empty history or a state with deleted elements (garbage).
SessionWriteReport write_session(const std::string& path, const History::Snapshot& snapshot,
                                 const SessionExtras& extras = {});

/// Reads a session file. Throws IoError "PATH: chunk N (TYPE at byte B): REASON" (or the
/// header's reason) for anything not exactly as written: nothing is restored then. The
/// history's memory budget is `budget_bytes` (its default: History::default_budget()).
SessionContents read_session(const std::string& path,
                             std::size_t budget_bytes = History::default_budget());
/// The same from bytes; `name` stands for the file in messages (the fuzzer, tests).
SessionContents read_session_bytes(std::string_view bytes, const std::string& name,
                                   std::size_t budget_bytes = History::default_budget());

/// Reads a crash journal: every record up to the first incomplete or damaged one (the
/// longest valid prefix); `complete`, `records`, `bytes_discarded` and `stop_reason` say
/// what was lost. Throws IoError only when nothing can be restored (not a journal, no
/// complete entry).
SessionContents read_journal(const std::string& path,
                             std::size_t budget_bytes = History::default_budget());
SessionContents read_journal_bytes(std::string_view bytes, const std::string& name,
                                   std::size_t budget_bytes = History::default_budget());

/// A session or a journal, told apart by the header's magic.
SessionContents read_session_or_journal(const std::string& path,
                                        std::size_t budget_bytes = History::default_budget());

}  // namespace trilab
