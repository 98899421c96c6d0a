#include "core/io/file_util.h"

#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <ostream>
#include <random>
#include <streambuf>
#include <thread>
#include <utility>
#include <vector>

#include "core/errors.h"
#include "core/prefault.h"
#include "core/system_memory.h"

namespace trilab {

namespace {

std::string errno_text(int err) {
    return std::strerror(err);
}

/// What a non-regular file is, for messages: "a directory", "a FIFO (named pipe)", ...
std::string file_type_name(mode_t mode) {
    if (S_ISDIR(mode)) return "a directory";
    if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
    if (S_ISCHR(mode)) return "a character device";
    if (S_ISBLK(mode)) return "a block device";
    if (S_ISSOCK(mode)) return "a socket";
    if (S_ISLNK(mode)) return "a symbolic link";
    return "not a regular file";
}

/// "338 MB" style size next to the exact byte count.
std::string size_text(std::uint64_t bytes) {
    const char* units[] = {"bytes", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
    double v = double(bytes);
    int u = 0;
    while (v >= 1024 && u < 6) {
        v /= 1024;
        ++u;
    }
    char buf[64];
    if (u == 0)
        std::snprintf(buf, sizeof(buf), "%llu bytes", static_cast<unsigned long long>(bytes));
    else
        std::snprintf(buf, sizeof(buf), "%llu bytes (%.1f %s)",
                      static_cast<unsigned long long>(bytes), v, units[u]);
    return buf;
}

[[noreturn]] void too_big(const std::string& path, std::uint64_t size, std::uint64_t limit,
                          bool at_least, const char* why) {
    throw IoError(path, 0,
                  std::string("the file is ") + (at_least ? "at least " : "") + size_text(size) +
                      ", more than the limit of " + size_text(limit) + why);
}

std::string read_bytes(const std::string& path, std::uint64_t max_bytes, const char* why);

void require_regular(const std::string& path, const struct stat& st) {
    if (!S_ISREG(st.st_mode))
        throw IoError(path, 0,
                      "not a regular file: it is " + file_type_name(st.st_mode) +
                          " (only regular files are read)");
}

/// stat (following links) and require_regular.
void stat_regular(const std::string& path, struct stat& st) {
    if (::stat(path.c_str(), &st) != 0) throw IoError(path, 0, "cannot open: " + errno_text(errno));
    require_regular(path, st);
}

class FileDescriptor {
public:
    explicit FileDescriptor(int fd = -1) : fd_(fd) {}
    ~FileDescriptor() { reset(); }
    FileDescriptor(const FileDescriptor&) = delete;
    FileDescriptor& operator=(const FileDescriptor&) = delete;
    int get() const { return fd_; }
    void reset(int fd = -1) {
        if (fd_ >= 0) ::close(fd_);
        fd_ = fd;
    }
    /// Closes and reports close()'s error (a delayed write error on some file systems).
    int close_checked() {
        const int r = ::close(fd_);
        fd_ = -1;
        return r;
    }

private:
    int fd_;
};

}  // namespace

std::uint64_t max_readable_file_bytes() {
    return available_memory_bytes() / 2;
}

std::string read_file_bytes(const std::string& path) {
    return read_bytes(
        path, max_readable_file_bytes(),
        " (half the memory this process may still allocate; the rest is needed for what is built "
        "from the file)");
}

void check_regular_file(const std::string& path) {
    struct stat st;
    stat_regular(path, st);
}

std::string read_file_bytes(const std::string& path, std::uint64_t max_bytes) {
    return read_bytes(path, max_bytes, "");
}

FileBytes read_large_file(const std::string& path) {
    constexpr std::uint64_t kLarge = std::uint64_t(64) << 20;
    const std::uint64_t max_bytes = max_readable_file_bytes();
    struct stat st;
    stat_regular(path, st);
    if (std::uint64_t(st.st_size) < kLarge || std::uint64_t(st.st_size) > max_bytes)
        return FileBytes(read_file_bytes(path));  // its checks and errors
    FileDescriptor fd(::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY));
    if (fd.get() < 0) throw IoError(path, 0, "cannot open: " + errno_text(errno));
    if (::fstat(fd.get(), &st) != 0) throw IoError(path, 0, "cannot stat: " + errno_text(errno));
    require_regular(path, st);
    const std::size_t size = std::size_t(st.st_size);
    if (std::uint64_t(size) < kLarge || std::uint64_t(size) > max_bytes)
        return FileBytes(read_file_bytes(path));
    std::unique_ptr<char[]> block(new char[size]);  // every byte is read into below
    // Each half by its own thread: the copies from the page cache, and the page faults
    // of the fresh block, run side by side. A short read or an error: errno, or -1 with 0.
    const std::size_t half = size / 2;
    auto read_part = [&](std::size_t from, std::size_t to) -> int {
        while (from < to) {
            const ssize_t n = ::pread(fd.get(), block.get() + from, to - from, off_t(from));
            if (n < 0 && errno == EINTR) continue;
            if (n < 0) return errno;
            if (n == 0) return -1;
            from += std::size_t(n);
        }
        return 0;
    };
    // Each thread maps its half's fresh pages first (prefault.h: one call, not a page fault
    // per page inside the copy).
    int first = 0;
    std::thread other([&] {
        populate_half(block.get(), size, 0);
        first = read_part(0, half);
    });
    populate_half(block.get(), size, 1);
    const int second = read_part(half, size);
    other.join();
    char extra = 0;
    ssize_t beyond = 0;
    if (first == 0 && second == 0) {
        while ((beyond = ::pread(fd.get(), &extra, 1, off_t(size))) < 0 && errno == EINTR) {
        }
    }
    // A read error, or a file that changed size since the stat: read_file_bytes decides
    // (its errors, its bytes).
    if (first != 0 || second != 0 || beyond != 0) return FileBytes(read_file_bytes(path));
    return FileBytes(std::move(block), size);
}

namespace {

std::string read_bytes(const std::string& path, std::uint64_t max_bytes, const char* why) {
    // The type first, by stat (which follows links): opening a FIFO would block until a
    // writer comes, and opening a device can have effects.
    struct stat st;
    stat_regular(path, st);
    if (std::uint64_t(st.st_size) > max_bytes)
        too_big(path, std::uint64_t(st.st_size), max_bytes, false, why);
    // O_NONBLOCK: should the path have been replaced by a FIFO since the stat, the open
    // still returns at once, and the fstat below refuses it.
    FileDescriptor fd(::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY));
    if (fd.get() < 0) throw IoError(path, 0, "cannot open: " + errno_text(errno));
    if (::fstat(fd.get(), &st) != 0) throw IoError(path, 0, "cannot stat: " + errno_text(errno));
    require_regular(path, st);
    const std::uint64_t size = std::uint64_t(st.st_size);
    if (size > max_bytes) too_big(path, size, max_bytes, false, why);

    std::string data(static_cast<std::size_t>(size), '\0');
    std::size_t have = 0;
    char more[1 << 16];
    for (;;) {
        if (have < data.size()) {
            const ssize_t n = ::read(fd.get(), &data[have], data.size() - have);
            if (n == 0) break;  // shorter than announced
            if (n < 0) {
                if (errno == EINTR) continue;
                throw IoError(path, 0, "read error: " + errno_text(errno));
            }
            have += std::size_t(n);
            continue;
        }
        // At the announced size (0 for files of /proc): anything more is appended, within
        // the limit.
        const ssize_t n = ::read(fd.get(), more, sizeof(more));
        if (n == 0) break;
        if (n < 0) {
            if (errno == EINTR) continue;
            throw IoError(path, 0, "read error: " + errno_text(errno));
        }
        if (std::uint64_t(have) + std::uint64_t(n) > max_bytes)
            too_big(path, std::uint64_t(have) + std::uint64_t(n), max_bytes, true, why);
        data.append(more, std::size_t(n));
        have += std::size_t(n);
    }
    data.resize(have);
    return data;
}

}  // namespace

// ---- saving -------------------------------------------------------------------------------

namespace {

std::atomic<bool> g_force_named{false};
std::atomic<bool> g_sync{true};
std::atomic<bool> g_no_link{false};

/// A stream buffer writing to a file descriptor in 64 KiB blocks; remembers the first error.
class FdOutBuf : public std::streambuf {
public:
    explicit FdOutBuf(int fd) : fd_(fd), buf_(1 << 16) { reset_put_area(); }
    int error() const { return error_; }

protected:
    int_type overflow(int_type ch) override {
        if (!flush_buffer()) return traits_type::eof();
        if (!traits_type::eq_int_type(ch, traits_type::eof())) {
            *pptr() = traits_type::to_char_type(ch);
            pbump(1);
        }
        return traits_type::not_eof(ch);
    }
    int sync() override { return flush_buffer() ? 0 : -1; }
    std::streamsize xsputn(const char* s, std::streamsize n) override {
        if (n < std::streamsize(buf_.size())) return std::streambuf::xsputn(s, n);
        if (!flush_buffer() || !write_all(s, std::size_t(n))) return 0;
        return n;
    }

private:
    void reset_put_area() { setp(buf_.data(), buf_.data() + buf_.size()); }
    bool flush_buffer() {
        const bool ok = write_all(pbase(), std::size_t(pptr() - pbase()));
        reset_put_area();
        return ok;
    }
    bool write_all(const char* p, std::size_t n) {
        if (error_) return false;
        while (n > 0) {
            const ssize_t w = ::write(fd_, p, n);
            if (w < 0) {
                if (errno == EINTR) continue;
                error_ = errno;
                return false;
            }
            p += w;
            n -= std::size_t(w);
        }
        return true;
    }
    int fd_;
    std::vector<char> buf_;
    int error_ = 0;
};

std::string folder_of(const std::string& path) {
    const std::size_t slash = path.find_last_of('/');
    if (slash == std::string::npos) return ".";
    if (slash == 0) return "/";
    return path.substr(0, slash);
}

std::string name_of(const std::string& path) {
    const std::size_t slash = path.find_last_of('/');
    return slash == std::string::npos ? path : path.substr(slash + 1);
}

/// The file a save of `path` replaces: symbolic links followed. `exists` tells whether it
/// exists; `st` is its lstat when it does.
std::string resolve_target(const std::string& path, struct stat& st, bool& exists) {
    std::string current = path;
    for (int hops = 0; hops <= 40; ++hops) {
        if (::lstat(current.c_str(), &st) != 0) {
            const int err = errno;
            // Missing (or under a component that is not a folder): a new file, whose
            // creation reports the problem.
            if (err == ENOENT || err == ENOTDIR) {
                exists = false;
                return current;
            }
            throw IoError(path, 0, "cannot inspect " + current + ": " + errno_text(err));
        }
        if (!S_ISLNK(st.st_mode)) {
            exists = true;
            return current;
        }
        std::vector<char> buf(std::size_t(st.st_size > 0 ? st.st_size : 255) + 2);
        const ssize_t n = ::readlink(current.c_str(), buf.data(), buf.size() - 1);
        if (n < 0)
            throw IoError(path, 0,
                          "cannot read the symbolic link " + current + ": " + errno_text(errno));
        const std::string target(buf.data(), std::size_t(n));
        current =
            (!target.empty() && target[0] == '/') ? target : folder_of(current) + "/" + target;
    }
    throw IoError(path, 0, "too many levels of symbolic links");
}

std::string octal_mode(mode_t mode) {
    char buf[16];
    std::snprintf(buf, sizeof(buf), "%04o", unsigned(mode & 07777));
    return buf;
}

std::string random_suffix() {
    static std::atomic<unsigned> counter{0};
    std::random_device rd;
    char buf[32];
    std::snprintf(buf, sizeof(buf), "%08x%04x", unsigned(rd()), counter++ & 0xffffu);
    return buf;
}

/// Removes named temporaries of `name` in `folder` whose process is gone.
void remove_stale_temporaries(const std::string& folder, const std::string& name) {
    const std::string prefix = detail::temporary_file_prefix(name);
    DIR* dir = ::opendir(folder.c_str());
    if (!dir) return;
    std::vector<std::string> stale;
    while (const dirent* e = ::readdir(dir)) {
        const std::string entry = e->d_name;
        if (entry.compare(0, prefix.size(), prefix) != 0) continue;
        const std::string rest = entry.substr(prefix.size());  // PID-RANDOM
        const std::size_t dash = rest.find('-');
        if (dash == std::string::npos || dash == 0) continue;
        long pid = 0;
        bool digits = dash <= 9;
        for (std::size_t i = 0; i < dash && digits; ++i) {
            digits = rest[i] >= '0' && rest[i] <= '9';
            pid = pid * 10 + (rest[i] - '0');
        }
        if (!digits || pid <= 0 || pid == long(::getpid())) continue;
        if (::kill(pid_t(pid), 0) != 0 && errno == ESRCH) stale.push_back(entry);
    }
    ::closedir(dir);
    for (const std::string& entry : stale) ::unlink((folder + "/" + entry).c_str());
}

/// Copies the first `size` bytes of `from` to the same offsets of `to`. Throws IoError
/// (`context` says where) on a read or write error.
void copy_all(int from, int to, off_t size, const std::string& path, const char* context) {
    std::vector<char> buf(1 << 20);
    for (off_t off = 0; off < size;) {
        const ssize_t n = ::pread(from, buf.data(), buf.size(), off);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0)
            throw IoError(path, 0, "cannot read the temporary file back: " + errno_text(errno));
        for (ssize_t done = 0; done < n;) {
            const ssize_t w = ::pwrite(to, buf.data() + done, std::size_t(n - done), off + done);
            if (w < 0 && errno == EINTR) continue;
            if (w < 0)
                throw IoError(path, 0,
                              std::string("write error") + context + ": " + errno_text(errno) +
                                  " (disk full?)");
            done += w;
        }
        off += n;
    }
}

/// Copies the whole temporary file `from` over `target` in place (hard-linked targets).
void copy_in_place(int from, const std::string& target, const struct stat& expected,
                   const std::string& path) {
    FileDescriptor out(::open(target.c_str(), O_WRONLY | O_CLOEXEC | O_NOFOLLOW | O_NONBLOCK));
    if (out.get() < 0) throw IoError(path, 0, "cannot open it for writing: " + errno_text(errno));
    struct stat now;
    if (::fstat(out.get(), &now) != 0 || now.st_dev != expected.st_dev ||
        now.st_ino != expected.st_ino)
        throw IoError(path, 0, "the file changed while it was being saved; not replaced");
    const off_t size = ::lseek(from, 0, SEEK_END);
    if (size < 0) throw IoError(path, 0, "cannot read the temporary file: " + errno_text(errno));
    // Reserve the space first: a full disk then fails here, before the content is touched.
    if (size > 0) {
        const int err = ::posix_fallocate(out.get(), 0, size);
        if (err == ENOSPC || err == EDQUOT || err == EFBIG)
            throw IoError(path, 0,
                          "not enough disk space to rewrite it in place: " + errno_text(err));
    }
    copy_all(from, out.get(), size, path, " while rewriting it in place");
    if (::ftruncate(out.get(), size) != 0 || (g_sync && ::fsync(out.get()) != 0) ||
        out.close_checked() != 0)
        throw IoError(path, 0,
                      "write error while rewriting it in place: " + errno_text(errno) +
                          " (the file may be incomplete)");
}

}  // namespace

void set_sync_saves(bool on) {
    g_sync = on;
}

namespace detail {
void force_named_temporary_files(bool on) {
    g_force_named = on;
}
void force_unlinkable_temporary_files(bool on) {
    g_no_link = on;
}
std::string temporary_file_prefix(const std::string& file_name) {
    return "." + file_name + ".trilab-tmp-";
}
}  // namespace detail

namespace {

// write_file_atomically() in stages, each a function below: the target checked, a temporary
// file opened beside it, the content written (owner and mode kept), then either an in-place
// copy (hard links) or the temporary file named and renamed over the target.

/// Refuses a target that is not a regular file, is read-only or not writable by this user.
void check_replaceable(const std::string& path, const std::string& target, const struct stat& st) {
    const std::string shown =
        target == path ? std::string() : " (the link's target " + target + ")";
    if (!S_ISREG(st.st_mode))
        throw IoError(path, 0,
                      "cannot replace it" + shown + ": it is " + file_type_name(st.st_mode) +
                          ", not a regular file");
    if ((st.st_mode & 0222) == 0)
        throw IoError(path, 0,
                      "it is read-only" + shown + " (mode " + octal_mode(st.st_mode) +
                          "): not replaced; make it writable first");
    if (::access(target.c_str(), W_OK) != 0 && errno == EACCES)
        throw IoError(path, 0,
                      "it is not writable by this user" + shown + " (mode " +
                          octal_mode(st.st_mode) + "): not replaced");
}

/// Opens a new named temporary file `temp_name` + random suffix into `fd` (up to 8
/// attempts; `named` is its name, or what the last attempt tried when none opened).
void open_named_temporary(const std::string& temp_name, FileDescriptor& fd, std::string& named) {
    for (int attempt = 0; attempt < 8 && fd.get() < 0; ++attempt) {
        named = temp_name + random_suffix();
        fd.reset(::open(named.c_str(), O_RDWR | O_CREAT | O_EXCL | O_CLOEXEC, 0666));
        if (fd.get() < 0 && errno != EEXIST) break;
    }
}

/// The temporary file in `folder`: unnamed (O_TMPFILE) where possible (`named` stays
/// empty), else named.
void open_temporary(const std::string& folder, const std::string& temp_name,
                    const std::string& path, FileDescriptor& fd, std::string& named) {
#ifdef O_TMPFILE
    if (!g_force_named) fd.reset(::open(folder.c_str(), O_TMPFILE | O_RDWR | O_CLOEXEC, 0666));
#else
    (void)folder;
#endif
    if (fd.get() < 0) {
        open_named_temporary(temp_name, fd, named);
        if (fd.get() < 0)
            throw IoError(path, 0,
                          "cannot create a temporary file beside it: " + errno_text(errno));
    }
}

/// Runs `write` into the temporary file; keeps the owner, group and permissions of the file
/// replaced (when it exists); syncs when asked.
void write_temporary(int fd, const std::function<void(std::ostream&)>& write,
                     const std::string& path, bool exists, const struct stat& st) {
    FdOutBuf buf(fd);
    {
        std::ostream out(&buf);
        write(out);
        out.flush();
        if (out.fail() || buf.error())
            throw IoError(path, 0,
                          "write error" +
                              (buf.error() ? ": " + errno_text(buf.error()) : std::string()) +
                              " (disk full?)");
    }
    if (exists) {
        // Keep the owner, the group and the permissions of the file replaced (chown
        // first: it clears set-user-ID bits). Only root may give a file away: failures
        // of chown are ignored, the permissions are kept in any case.
        if (st.st_uid != ::geteuid() || st.st_gid != ::getegid())
            if (::fchown(fd, st.st_uid, st.st_gid) != 0) {
            }
        ::fchmod(fd, st.st_mode & 07777);
    }
    if (g_sync && ::fsync(fd) != 0)
        throw IoError(path, 0, "write error: " + errno_text(errno) + " (disk full?)");
}

/// No way to name the unnamed temporary file `fd` (no /proc, no privilege, link error `err`):
/// copies it into a named temporary file, which the next save removes should this one be
/// killed.
void copy_to_named_temporary(int fd, const std::string& temp_name, const std::string& path, int err,
                             std::string& named) {
    FileDescriptor copy;
    open_named_temporary(temp_name, copy, named);
    if (copy.get() < 0) {
        named.clear();
        throw IoError(path, 0, "cannot give the temporary file a name: " + errno_text(err));
    }
    const off_t size = ::lseek(fd, 0, SEEK_END);
    if (size < 0) throw IoError(path, 0, "cannot read the temporary file: " + errno_text(errno));
    copy_all(fd, copy.get(), size, path, "");
    struct stat mode;
    if (::fstat(fd, &mode) == 0) {
        if (::fchown(copy.get(), mode.st_uid, mode.st_gid) != 0) {
        }  // as above: only root may give a file away
        ::fchmod(copy.get(), mode.st_mode & 07777);
    }
    if ((g_sync && ::fsync(copy.get()) != 0) || copy.close_checked() != 0)
        throw IoError(path, 0, "write error: " + errno_text(errno) + " (disk full?)");
}

/// Gives the complete unnamed temporary file `fd` a name beside the target (in `named`).
void name_unnamed_temporary(int fd, const std::string& temp_name, const std::string& path,
                            std::string& named) {
    const std::string proc = "/proc/self/fd/" + std::to_string(fd);
    int err = EEXIST;
    for (int attempt = 0; attempt < 8 && err == EEXIST; ++attempt) {
        const std::string candidate = temp_name + random_suffix();
        int rc = g_no_link ? (errno = ENOENT, -1)
                           : ::linkat(AT_FDCWD, proc.c_str(), AT_FDCWD, candidate.c_str(),
                                      AT_SYMLINK_FOLLOW);
        if (rc != 0 && errno != EEXIST && !g_no_link)  // no /proc: privileged way
            rc = ::linkat(fd, "", AT_FDCWD, candidate.c_str(), AT_EMPTY_PATH);
        err = rc == 0 ? 0 : errno;
        if (rc == 0) named = candidate;
    }
    if (err != 0) copy_to_named_temporary(fd, temp_name, path, err, named);
}

}  // namespace

void write_file_atomically(const std::string& path,
                           const std::function<void(std::ostream&)>& write) {
    if (path.empty()) throw IoError(path, 0, "empty file name");
    struct stat st;
    bool exists = false;
    const std::string target = resolve_target(path, st, exists);
    if (exists) check_replaceable(path, target, st);
    const std::string folder = folder_of(target);
    const std::string name = name_of(target);
    remove_stale_temporaries(folder, name);

    std::string named;  // the named temporary file, while it exists
    FileDescriptor fd;
    const std::string temp_name =
        folder + "/" + detail::temporary_file_prefix(name) + std::to_string(::getpid()) + "-";
    open_temporary(folder, temp_name, path, fd, named);
    const bool unnamed = named.empty();
    try {
        write_temporary(fd.get(), write, path, exists, st);
        if (exists && st.st_nlink > 1) {
            // Hard links: rewrite the target in place, from the complete temporary file.
            copy_in_place(fd.get(), target, st, path);
        } else {
            // Give the complete file a name, then rename it over the target.
            if (unnamed) name_unnamed_temporary(fd.get(), temp_name, path, named);
            if (fd.close_checked() != 0)
                throw IoError(path, 0, "write error: " + errno_text(errno) + " (disk full?)");
            if (::rename(named.c_str(), target.c_str()) != 0)
                throw IoError(path, 0, "cannot replace the file: " + errno_text(errno));
            named.clear();
        }
    } catch (...) {
        if (!named.empty()) ::unlink(named.c_str());
        throw;
    }
    if (!named.empty()) ::unlink(named.c_str());  // the named temporary of an in-place write
}

// ---- checks -------------------------------------------------------------------------------

namespace {

template <class V>
void check_finite_values(const std::vector<V>& values, const char* element, const char* what,
                         const std::string& path, const char* suffix = "") {
    for (std::size_t i = 0; i < values.size(); ++i) {
        if (values[i].allFinite()) continue;
        std::string text;
        for (Eigen::Index k = 0; k < values[i].size(); ++k) {
            if (k) text += ' ';
            char buf[32];
            std::snprintf(buf, sizeof(buf), "%g", double(values[i][k]));
            text += buf;
        }
        throw IoError(path, 0,
                      std::string(element) + " " + std::to_string(i) + ": non-finite " + what +
                          " (" + text + ")" + suffix);
    }
}

template <class V>
double max_abs_of(const std::vector<V>& values) {
    double m = 0;
    for (const V& v : values) m = std::max(m, double(v.cwiseAbs().maxCoeff()));
    return m;
}

constexpr const char* kNotWritten = "; not written: no reader accepts it";

}  // namespace

void check_finite_for_writing(const PolygonSoup& soup, const std::string& path, bool normals,
                              bool colors, bool texcoords) {
    check_finite_values(soup.positions, "vertex", "position", path, kNotWritten);
    if (normals) check_finite_values(soup.normals, "vertex", "normal", path, kNotWritten);
    if (colors) check_finite_values(soup.colors, "vertex", "colour", path, kNotWritten);
    if (texcoords) {
        check_finite_values(soup.texcoords, "vertex", "texture coordinate", path, kNotWritten);
        check_finite_values(soup.corner_texcoords, "face corner", "texture coordinate", path,
                            kNotWritten);
    }
}

namespace {
void check_mesh(const HalfedgeMesh& mesh, const std::string& path, bool normals, bool colors,
                bool texcoords, const char* suffix) {
    check_finite_values(mesh.positions(), "vertex", "position", path, suffix);
    if (normals)
        if (const auto p = mesh.get_vertex_property<Vector3>("v:normal"))
            check_finite_values(p.vector(), "vertex", "normal", path, suffix);
    if (colors)
        if (const auto p = mesh.get_vertex_property<Color>("v:color"))
            check_finite_values(p.vector(), "vertex", "colour", path, suffix);
    if (texcoords) {
        if (const auto p = mesh.get_vertex_property<TexCoord>("v:texcoord"))
            check_finite_values(p.vector(), "vertex", "texture coordinate", path, suffix);
        if (const auto p = mesh.get_halfedge_property<TexCoord>("h:texcoord"))
            check_finite_values(p.vector(), "halfedge", "texture coordinate", path, suffix);
    }
}
}  // namespace

void check_finite_for_writing(const HalfedgeMesh& mesh, const std::string& path, bool normals,
                              bool colors, bool texcoords) {
    // Deleted elements are not written; a mesh with garbage is compacted by the caller.
    check_mesh(mesh, path, normals, colors, texcoords, kNotWritten);
}

void check_finite_mesh(const HalfedgeMesh& mesh, const std::string& path) {
    check_mesh(mesh, path, true, true, true, "");
}

double max_abs_component(const std::vector<Vector3>& values) {
    return max_abs_of(values);
}
double max_abs_component(const std::vector<TexCoord>& values) {
    return max_abs_of(values);
}

void check_finite_soup(const PolygonSoup& soup, const std::string& path) {
    check_finite_values(soup.positions, "vertex", "position", path);
    check_finite_values(soup.normals, "vertex", "normal", path);
    check_finite_values(soup.colors, "vertex", "colour", path);
    check_finite_values(soup.texcoords, "vertex", "texture coordinate", path);
    check_finite_values(soup.corner_texcoords, "face corner", "texture coordinate", path);
    for (std::size_t i = 0; i < soup.distances.size(); ++i)
        if (!std::isfinite(soup.distances[i]))
            throw IoError(path, 0, "vertex " + std::to_string(i) + ": non-finite distance");
    for (std::size_t i = 0; i < soup.selections.size(); ++i)
        if (!(soup.selections[i] >= 0.0f && soup.selections[i] <= 1.0f))
            throw IoError(path, 0,
                          "vertex " + std::to_string(i) + ": selection weight " +
                              std::to_string(soup.selections[i]) + " is not in [0, 1]");
}

namespace {

/// This thread's soup observer (ScopedSoupObserver), or null.
thread_local const SoupObserver* t_soup_observer = nullptr;

template <typename Soup>
HalfedgeMesh build_checked(Soup&& soup, LoadReport& report, const std::string& path) {
    if (soup.positions.empty()) throw IoError(path, 0, "the file holds no vertices");
    check_finite_soup(soup, path);
    if (t_soup_observer && *t_soup_observer) {
        try {
            check_polygon_soup(soup);  // indices in range before anyone sees the soup
        } catch (const Error& e) {
            throw IoError(path, 0, e.what());
        }
        (*t_soup_observer)(soup);  // what it throws (a cancellation) passes unchanged
    }
    try {
        return build_mesh(std::forward<Soup>(soup), report);
    } catch (const IoError&) {
        throw;
    } catch (const Error& e) {
        throw IoError(path, 0, e.what());
    }
}

}  // namespace

ScopedSoupObserver::ScopedSoupObserver(const SoupObserver* observer) : before_(t_soup_observer) {
    t_soup_observer = observer;
}

ScopedSoupObserver::~ScopedSoupObserver() {
    t_soup_observer = before_;
}

HalfedgeMesh build_mesh_for_file(const PolygonSoup& soup, LoadReport& report,
                                 const std::string& path) {
    return build_checked(soup, report, path);
}

HalfedgeMesh build_mesh_for_file(PolygonSoup&& soup, LoadReport& report, const std::string& path) {
    return build_checked(std::move(soup), report, path);
}

void check_declared_count(std::size_t count, std::size_t min_bytes_each,
                          std::size_t available_bytes, const char* what, const std::string& path,
                          std::size_t line) {
    if (min_bytes_each == 0) min_bytes_each = 1;
    if (count > available_bytes / min_bytes_each)
        throw IoError(path, line,
                      "the header declares " + std::to_string(count) + " " + what +
                          ", more than the file's " + std::to_string(available_bytes) +
                          " bytes can hold");
}

std::string_view strip_utf8_bom(std::string_view text, const std::string& path) {
    auto starts = [&](std::initializer_list<unsigned char> bytes) {
        if (text.size() < bytes.size()) return false;
        std::size_t i = 0;
        for (unsigned char b : bytes)
            if (static_cast<unsigned char>(text[i++]) != b) return false;
        return true;
    };
    if (starts({0xEF, 0xBB, 0xBF})) return text.substr(3);
    const char* encoding = nullptr;
    if (starts({0xFF, 0xFE, 0x00, 0x00}))
        encoding = "UTF-32 little-endian (byte-order mark FF FE 00 00)";
    else if (starts({0x00, 0x00, 0xFE, 0xFF}))
        encoding = "UTF-32 big-endian (byte-order mark 00 00 FE FF)";
    else if (starts({0xFF, 0xFE}))
        encoding = "UTF-16 little-endian (byte-order mark FF FE)";
    else if (starts({0xFE, 0xFF}))
        encoding = "UTF-16 big-endian (byte-order mark FE FF)";
    if (encoding)
        throw IoError(path, 1,
                      std::string("the file is ") + encoding +
                          " text, which is not supported; save it as UTF-8 or ASCII");
    return text;
}

bool float_range_suffices(double max_abs) {
    constexpr double kSmallest = double(FLT_MIN) * 16777216.0;  // FLT_MIN * 2^24
    return max_abs <= double(FLT_MAX) && (max_abs == 0 || max_abs >= kSmallest);
}

}  // namespace trilab

#include <charconv>

namespace trilab {

void append_number(std::string& out, double value) {
    char buf[32];
    auto res = std::to_chars(buf, buf + sizeof(buf), value);
    out.append(buf, res.ptr);
}

void append_number(std::string& out, float value) {
    char buf[32];
    auto res = std::to_chars(buf, buf + sizeof(buf), value);
    out.append(buf, res.ptr);
}

void append_number(std::string& out, std::size_t value) {
    char buf[24];
    auto res = std::to_chars(buf, buf + sizeof(buf), value);
    out.append(buf, res.ptr);
}

}  // namespace trilab
