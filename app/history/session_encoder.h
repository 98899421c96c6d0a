#pragma once
// SessionEncoder: writes history entries as chunks (docs/file-formats.md#session-files), each
// array's values once. Shared by the session writer (one pass over a snapshot) and the crash
// journal (one call per history change, over the life of the process).
//
// Arrays are told apart by the identity of their stored values (core/property.h: arrays that
// share values have the same values_id); an identity is only trusted while something holds
// the values, so a long-lived encoder (the journal) calls retain_only() with what it holds.
// States (a step's mesh) are told apart by the step's id.
#include <cstddef>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

#include "app/history/chunk_io.h"
#include "app/history/history.h"

namespace trilab {

namespace session_chunk {
inline constexpr std::uint32_t kArray = chunk_type("ARRY");
inline constexpr std::uint32_t kState = chunk_type("STAT");
inline constexpr std::uint32_t kEntry = chunk_type("ENTR");
inline constexpr std::uint32_t kCurrent = chunk_type("CURR");
inline constexpr std::uint32_t kDrop = chunk_type("DROP");
inline constexpr std::uint32_t kKeep = chunk_type("KEEP");
inline constexpr std::uint32_t kView = chunk_type("VIEW");
inline constexpr std::uint32_t kTexture = chunk_type("TXTR");
inline constexpr std::uint32_t kJournal = chunk_type("JRNL");
inline constexpr std::uint32_t kEnd = chunk_type("END ");
}  // namespace session_chunk

inline constexpr char kSessionMagic[9] = "TRILABSN";
inline constexpr char kJournalMagic[9] = "TRILABJN";
inline constexpr std::uint32_t kSessionFormatVersion = 1;
inline constexpr std::size_t kFileHeaderBytes = 16;
inline constexpr std::uint32_t kNoBlob = 0xFFFFFFFFu;

class SessionEncoder {
public:
    explicit SessionEncoder(ByteSink sink) : sink_(std::move(sink)) {}

    /// The 16-byte file header: magic (session or journal), version, zero.
    void file_header(bool journal);
    /// The chunks of entry `e` placed at `index` (the entries from `index` on are replaced):
    /// first the arrays and states not written yet, then the entry itself.
    void entry(std::uint32_t index, const History::EntryRecord& e);
    void current(std::uint32_t index);
    /// The journal's records of History's budget trims and dropped redo entries.
    void drop_front(std::uint32_t count);
    void keep(std::uint32_t count);
    void viewer_settings(const std::string& text);
    void texture(const std::string& path, const std::string& bytes);
    void journal_info(std::uint32_t pid, std::uint64_t start_ticks, const std::string& program);
    void end(std::uint32_t entries);
    /// Forgets every array and state identity `live` does not hold (the journal, before its
    /// previous snapshot is released).
    void retain_only(const History::Snapshot& live);

    std::size_t bytes() const { return bytes_; }
    std::size_t arrays() const { return next_blob_; }
    std::size_t states() const { return next_state_; }
    /// Properties of a type the format does not store ("v:name (type)"), once each.
    const std::vector<std::string>& skipped() const { return skipped_; }

private:
    std::uint32_t state(const History::StepRecord& step);
    template <class T>
    std::uint32_t array(const PropertyArray<T>& a, std::uint32_t code);
    std::uint32_t positions(const std::vector<Point>& p);
    void emit(std::uint32_t type, const std::string& head, const void* tail = nullptr,
              std::size_t tail_size = 0);

    ByteSink sink_;
    std::size_t bytes_ = 0;
    std::uint32_t next_blob_ = 0, next_state_ = 0;
    std::unordered_map<const void*, std::uint32_t> blobs_;     ///< values identity -> blob id
    std::unordered_map<std::uint64_t, std::uint32_t> states_;  ///< step id -> state id
    std::vector<std::string> skipped_;
};

}  // namespace trilab
