#pragma once
// File helpers shared by every reader and writer: the one place where files are opened for
// reading (read_file_bytes) and replaced (write_file_atomically), so that the rules below
// hold for meshes, images, material libraries and text outputs alike.
#include <cstdint>
#include <functional>
#include <iosfwd>
#include <memory>
#include <string>
#include <string_view>
#include <utility>

#include "core/halfedge_mesh.h"
#include "core/mesh_builder.h"

namespace trilab {

/// The whole file as bytes. Only a regular file is read (symbolic links are followed): a
/// directory, a FIFO, a device or a socket is refused by its type before it is opened (and
/// the open itself never blocks), so `/dev/zero` or a named pipe cannot hang or exhaust the
/// process. A file larger than max_readable_file_bytes() is refused before reading, with
/// its size and the limit. Throws IoError naming `path` and the reason.
std::string read_file_bytes(const std::string& path);
/// A file's bytes as read_large_file gives them: a plain string, or for a large file an
/// uninitialized block filled by the read (no zero fill first).
class FileBytes {
public:
    FileBytes() = default;
    explicit FileBytes(std::string text) : text_(std::move(text)), size_(text_.size()) {}
    FileBytes(std::unique_ptr<char[]> block, std::size_t size)
        : block_(std::move(block)), size_(size) {}
    std::string_view view() const { return {block_ ? block_.get() : text_.data(), size_}; }

private:
    std::string text_;
    std::unique_ptr<char[]> block_;
    std::size_t size_ = 0;
};
/// read_file_bytes(path) for readers that parse a string_view: the same checks, errors and
/// bytes, but a file of 64 MiB or more is read by two threads, each reading half of it into
/// memory that is not zero-filled first (a 338 MB PLY reads in about half the time).
FileBytes read_large_file(const std::string& path);
/// Throws the IoError read_file_bytes(path) would throw for a missing file or one that is
/// not a regular file (readers check this before complaining about a file name).
void check_regular_file(const std::string& path);
/// The same with an explicit limit in bytes (material libraries use a small one; tests).
std::string read_file_bytes(const std::string& path, std::uint64_t max_bytes);
/// The size limit of read_file_bytes(path): half of available_memory_bytes() (core/platform.h),
/// the other half being left for what the readers build from the bytes.
std::uint64_t max_readable_file_bytes();

/// Replaces the file at `path` with what `write` puts on the stream, never leaving a half
/// written file or a stray temporary file, and never replacing what a user would not expect:
///  - The new content goes to a temporary file in the target's folder (Linux O_TMPFILE,
///    which has no name until it is complete, so a killed process leaves nothing behind;
///    where the file system lacks it, a named file ".NAME.trilab-tmp-PID-RANDOM", and the
///    next save of NAME removes those whose process is gone). If `write` throws or the
///    stream fails (disk full), the temporary file is removed, the target is untouched and
///    IoError is thrown.
///  - Only a regular file is replaced: a directory, FIFO, device or socket at the target is
///    refused (naming what it is) before anything is written.
///  - A symbolic link is followed (any number of levels): the file it points to is replaced,
///    atomically, in that file's folder, and the link stays a link.
///  - A read-only target (no write bit in its mode, checked explicitly so that root gets the
///    same answer, or not writable by this user) is refused.
///  - The replaced file keeps its permission bits (and its owner and group where this
///    process may set them).
///  - A target with several hard links keeps them: the complete new content is written to
///    the temporary file first, disk space for it is reserved in the target, then it is
///    copied over the target in place (so every link sees the new content). Only this case
///    is not atomic: a crash during that final copy can leave the target partly written.
/// The temporary file is synced (see set_sync_saves), linked into place and renamed over the
/// target.
void write_file_atomically(const std::string& path,
                           const std::function<void(std::ostream&)>& write);

/// Whether write_file_atomically flushes the new content to the disk (fsync) before it
/// replaces the target, so that a power loss just after a save leaves the old or the new
/// content, never an empty file, on every file system. On by default (it costs about 7 ms a
/// save on this machine's disk); the unit tests, which save hundreds of small files, turn
/// it off.
void set_sync_saves(bool on);

namespace detail {
/// Test hook: while set, write_file_atomically uses a named temporary file even where
/// O_TMPFILE works (to test the removal of stale ones).
void force_named_temporary_files(bool on);
/// Test hook: while set, an unnamed temporary file cannot be linked (as without /proc), so
/// write_file_atomically copies it into a named one.
void force_unlinkable_temporary_files(bool on);
/// The prefix of the named temporary files of `path`'s file name: ".NAME.trilab-tmp-".
std::string temporary_file_prefix(const std::string& file_name);
}  // namespace detail

/// Called with a file's soup once the whole file is read and the soup checked (every corner
/// index in range, every value finite: check_polygon_soup, check_finite_soup), before the
/// half-edge mesh is built from it; on the reading thread. What it throws ends the read.
using SoupObserver = std::function<void(const PolygonSoup&)>;

/// While alive, build_mesh_for_file on this thread calls `observer` (read_mesh's on_soup);
/// the observer set before is restored at the end of the scope.
class ScopedSoupObserver {
public:
    explicit ScopedSoupObserver(const SoupObserver* observer);
    ~ScopedSoupObserver();
    ScopedSoupObserver(const ScopedSoupObserver&) = delete;
    ScopedSoupObserver& operator=(const ScopedSoupObserver&) = delete;

private:
    const SoupObserver* before_;
};

/// Runs build_mesh and turns its InvalidArgument into an IoError naming `path`. A soup
/// without vertices is refused ("the file holds no vertices"), and so is a soup with a
/// non-finite value in any attribute (see check_finite_soup).
HalfedgeMesh build_mesh_for_file(const PolygonSoup& soup, LoadReport& report,
                                 const std::string& path);
/// The same, consuming the soup: its arrays are released (or moved into the mesh) as soon as
/// the build no longer needs them, which lowers the peak memory of a large load.
HalfedgeMesh build_mesh_for_file(PolygonSoup&& soup, LoadReport& report, const std::string& path);

/// Refuses NaN and infinity in every attribute of the soup (positions, normals, colours,
/// texture coordinates per vertex and per corner), naming `path`, the vertex (or corner)
/// index and the attribute: "vertex 12: non-finite normal (nan 0 1)". Binary readers
/// rely on it; text readers refuse such numbers earlier, naming the line.
void check_finite_soup(const PolygonSoup& soup, const std::string& path);

/// The same for a mesh a reader assembles without a soup (.om): positions and the
/// "v:normal", "v:color", "v:texcoord" and "h:texcoord" properties.
void check_finite_mesh(const HalfedgeMesh& mesh, const std::string& path);

/// What a writer calls before writing: refuses (IoError naming `path`, the vertex or corner
/// and the attribute) a non-finite value in the positions or in the attributes it writes
/// (`normals`, `colors`, `texcoords`: per vertex and per corner), since no reader accepts it.
void check_finite_for_writing(const PolygonSoup& soup, const std::string& path, bool normals,
                              bool colors, bool texcoords);
/// The same for a mesh's positions and its "v:normal", "v:color", "v:texcoord" and
/// "h:texcoord" properties (those present and selected).
void check_finite_for_writing(const HalfedgeMesh& mesh, const std::string& path, bool normals,
                              bool colors, bool texcoords);

/// The largest magnitude of any component of the values (0 for none).
double max_abs_component(const std::vector<Vector3>& values);
double max_abs_component(const std::vector<TexCoord>& values);

/// Refuses a declared element count that the file cannot possibly hold: `count` elements of
/// at least `min_bytes_each` bytes must fit in `available_bytes`. Prevents huge allocations
/// from a lying header. Throws IoError naming `what`.
void check_declared_count(std::size_t count, std::size_t min_bytes_each,
                          std::size_t available_bytes, const char* what, const std::string& path,
                          std::size_t line);

/// The text of a text-format file without a UTF-8 byte-order mark (EF BB BF), which editors
/// on Windows put at the start. A UTF-16 or UTF-32 byte-order mark is refused with an
/// IoError naming `path` ("the file is UTF-16 text ...; save it as UTF-8 or ASCII").
std::string_view strip_utf8_bom(std::string_view text, const std::string& path);

/// True when float32 holds values whose largest magnitude is `max_abs` with its full
/// relative precision (2^-24 of max_abs): max_abs <= FLT_MAX, and max_abs is 0 or at least
/// FLT_MIN * 2^24 (about 2e-31), so that nothing that matters at that scale underflows.
/// Writers of float formats use double where the format allows it, or refuse, otherwise.
bool float_range_suffices(double max_abs);

}  // namespace trilab

namespace trilab {
/// Appends the shortest decimal text that reads back as exactly `value`.
void append_number(std::string& out, double value);
/// Appends a float's shortest round-trip text.
void append_number(std::string& out, float value);
void append_number(std::string& out, std::size_t value);
}  // namespace trilab
