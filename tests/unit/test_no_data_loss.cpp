// No data loss on save: every writer goes through write_file_atomically (a temporary file
// in the target's folder, then a rename), so a save that fails for any reason leaves the old
// file byte for byte and no temporary file behind; a save never replaces what is not a
// regular file, writes through symbolic links, keeps permissions and hard links, refuses a
// read-only target, and a killed save leaves no temporary file (or the next save removes it).
#include <fcntl.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/algorithms/generators.h"
#include "core/errors.h"
#include "core/io/file_util.h"
#include "core/io/image_io.h"
#include "core/io/mesh_io.h"
#include "test_helpers.h"

using namespace trilab;
using namespace trilab::test;
namespace fs = std::filesystem;

namespace {

void write_text(const std::string& path, const std::string& text) {
    std::ofstream out(path, std::ios::binary);
    out << text;
}

/// The names of the entries in `dir`, sorted.
std::vector<std::string> entries(const fs::path& dir) {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename());
    std::sort(names.begin(), names.end());
    return names;
}

/// Makes `dir` read-only and says whether that stops this process from creating files in it
/// (it does not for root, which CI may be). The permissions are restored by the destructor.
class ReadOnlyFolder {
public:
    explicit ReadOnlyFolder(const fs::path& dir) : dir_(dir) {
        fs::permissions(dir_, fs::perms::owner_read | fs::perms::owner_exec);
        const fs::path probe = dir_ / "probe";
        std::ofstream out(probe);
        enforced_ = !out;
        out.close();
        if (!enforced_) fs::remove(probe);
    }
    ~ReadOnlyFolder() { fs::permissions(dir_, fs::perms::owner_all); }
    bool enforced() const { return enforced_; }

private:
    fs::path dir_;
    bool enforced_ = false;
};

const char* const kMeshFiles[] = {"m.obj", "m.off", "m.ply", "m.stl", "m.om"};

/// Forces named temporary files (instead of O_TMPFILE) while it lives.
class NamedTemporaries {
public:
    explicit NamedTemporaries(bool on) { detail::force_named_temporary_files(on); }
    ~NamedTemporaries() { detail::force_named_temporary_files(false); }
};

/// Whether this folder's file system gives unnamed temporary files (O_TMPFILE).
bool supports_unnamed_temporaries(const fs::path& dir) {
#ifdef O_TMPFILE
    const int fd = ::open(dir.c_str(), O_TMPFILE | O_RDWR, 0600);
    if (fd < 0) return false;
    ::close(fd);
    return true;
#else
    (void)dir;
    return false;
#endif
}

fs::perms mode_of(const std::string& path) {
    return fs::symlink_status(path).permissions() & fs::perms::mask;
}

/// The IoError's reason that `f` throws ("" when it throws none); checks it names `path`.
template <class F>
std::string save_error(const std::string& path, F&& f) {
    try {
        f();
    } catch (const IoError& e) {
        CHECK(e.file() == path);
        return e.reason();
    }
    return "";
}

}  // namespace

TEST_CASE("a save writes a temporary file in the target's folder, then renames it",
          "[io][no-data-loss]") {
    TempDir dir;
    const std::string path = dir.path("doc.txt");
    const std::string prefix = detail::temporary_file_prefix("doc.txt");
    CHECK(prefix == ".doc.txt.trilab-tmp-");
    for (const bool named : {false, true}) {
        INFO("named temporary file: " << named);
        write_text(path, "old");
        NamedTemporaries force(named);
        bool checked = false;
        write_file_atomically(path, [&](std::ostream& out) {
            out << "new";
            // While the new content is written, the target still holds the old one, and the
            // folder holds at most one more entry: the named temporary file (none with
            // O_TMPFILE, whose file has no name yet).
            CHECK(read_file_bytes(path) == "old");
            const std::vector<std::string> names = entries(dir.dir());
            if (named) {
                REQUIRE(names.size() == 2);
                CHECK(names[0].rfind(prefix + std::to_string(::getpid()) + "-", 0) == 0);
                CHECK(names[1] == "doc.txt");
            } else {
                REQUIRE(names.size() <= 2);
                CHECK(names.back() == "doc.txt");
                if (names.size() == 2) CHECK(names[0].rfind(prefix, 0) == 0);
            }
            checked = true;
        });
        REQUIRE(checked);
        CHECK(read_file_bytes(path) == "new");
        CHECK(entries(dir.dir()) == std::vector<std::string>{"doc.txt"});
    }
}

TEST_CASE("a save that fails while writing keeps the old file and leaves no temporary file",
          "[io][no-data-loss]") {
    TempDir dir;
    const std::string path = dir.path("doc.txt");
    write_text(path, "old");
    SECTION("the writer throws") {
        CHECK_THROWS_AS(write_file_atomically(path,
                                              [](std::ostream& out) {
                                                  out << "half";
                                                  throw IoError("doc", 0, "failed midway");
                                              }),
                        IoError);
    }
    SECTION("the stream fails (as on a full disk)") {
        try {
            write_file_atomically(path, [](std::ostream& out) {
                out << "half";
                out.setstate(std::ios::badbit);
            });
            FAIL("no error");
        } catch (const IoError& e) {
            CHECK(e.file() == path);
            CHECK(e.reason().find("write error") != std::string::npos);
        }
    }
    CHECK(read_file_bytes(path) == "old");
    CHECK(entries(dir.dir()) == std::vector<std::string>{"doc.txt"});
}

TEST_CASE("saving into a read-only folder fails and keeps the old file", "[io][no-data-loss]") {
    TempDir dir;
    const HalfedgeMesh mesh = make_icosahedron();
    const HalfedgeMesh other = make_cube();
    std::vector<std::string> before;
    for (const char* name : kMeshFiles) {
        write_mesh(mesh, dir.path(name));
        before.push_back(read_file_bytes(dir.path(name)));
    }
    ReadOnlyFolder read_only(dir.dir());
    if (!read_only.enforced()) {
        SKIP_TEST(
            "this process can write into a read-only folder (running as root?); the "
            "other no-data-loss tests cover failed saves without permissions");
    }
    for (std::size_t i = 0; i < std::size(kMeshFiles); ++i) {
        const std::string path = dir.path(kMeshFiles[i]);
        INFO(path);
        try {
            write_mesh(other, path);
            FAIL("no error");
        } catch (const IoError& e) {
            CHECK(e.file() == path);
            CHECK_FALSE(e.reason().empty());
        }
        CHECK(read_file_bytes(path) == before[i]);
    }
    CHECK(entries(dir.dir()).size() == std::size(kMeshFiles));
}

TEST_CASE("saving where the folder is a regular file fails with a clear error",
          "[io][no-data-loss]") {
    // Works as root too: nobody can create a file inside a regular file.
    TempDir dir;
    const std::string not_a_folder = dir.path("plain");
    write_text(not_a_folder, "keep me");
    const HalfedgeMesh mesh = make_icosahedron();
    for (const char* name : kMeshFiles) {
        const std::string path = not_a_folder + "/" + name;
        INFO(path);
        try {
            write_mesh(mesh, path);
            FAIL("no error");
        } catch (const IoError& e) {
            CHECK(e.file() == path);
            CHECK(e.reason().find("temporary file") != std::string::npos);
        }
    }
    try {
        write_png(make_checkerboard(8, 2), not_a_folder + "/t.png");
        FAIL("no error");
    } catch (const IoError& e) {
        CHECK_FALSE(e.reason().empty());
    }
    CHECK(read_file_bytes(not_a_folder) == "keep me");
    CHECK(entries(dir.dir()) == std::vector<std::string>{"plain"});
}

TEST_CASE("a save never replaces a folder, a FIFO or a socket, and says what is there",
          "[io][no-data-loss]") {
    TempDir dir;
    const std::string folder = dir.path("m.off");
    fs::create_directory(folder);
    write_text(folder + "/inside", "keep me");
    const std::string fifo = dir.path("fifo.obj");
    REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
    const std::string socket_path = dir.path("socket.ply");
    const int sock = ::socket(AF_UNIX, SOCK_STREAM, 0);
    REQUIRE(sock >= 0);
    sockaddr_un addr{};
    addr.sun_family = AF_UNIX;
    REQUIRE(socket_path.size() < sizeof(addr.sun_path));
    std::strcpy(addr.sun_path, socket_path.c_str());
    REQUIRE(::bind(sock, reinterpret_cast<sockaddr*>(&addr), sizeof(addr)) == 0);
    // A link to the FIFO: the link is followed, and the FIFO refused.
    const std::string link = dir.path("link.stl");
    fs::create_symlink("fifo.obj", link);

    struct Case {
        std::string path, what;
    };
    for (const Case& c : {Case{folder, "a directory"}, Case{fifo, "a FIFO"},
                          Case{socket_path, "a socket"}, Case{link, "a FIFO"}}) {
        INFO(c.path);
        const std::string reason =
            save_error(c.path, [&] { write_mesh(make_icosahedron(), c.path); });
        CHECK(reason.find("cannot replace it") != std::string::npos);
        CHECK(reason.find(c.what) != std::string::npos);
        CHECK(reason.find("not a regular file") != std::string::npos);
    }
    CHECK(save_error(link, [&] {
              write_mesh(make_icosahedron(), link);
          }).find("the link's target " + fifo) != std::string::npos);
    ::close(sock);
    CHECK(fs::is_directory(folder));
    CHECK(read_file_bytes(folder + "/inside") == "keep me");
    CHECK(fs::is_fifo(fifo));
    CHECK(fs::is_socket(socket_path));
    CHECK(fs::is_symlink(link));
    CHECK(entries(dir.dir()) ==
          std::vector<std::string>{"fifo.obj", "link.stl", "m.off", "socket.ply"});
}

TEST_CASE("a save that cannot replace the target keeps it and removes the temporary file",
          "[io][no-data-loss]") {
    // The target turns into a non-empty folder while the new content is written: the rename
    // fails, and the temporary file (named here, so that it is visible) is removed.
    TempDir dir;
    const std::string path = dir.path("doc.txt");
    for (const bool named : {false, true}) {
        INFO("named temporary file: " << named);
        fs::remove_all(path);
        write_text(path, "old");
        NamedTemporaries force(named);
        const std::string reason = save_error(path, [&] {
            write_file_atomically(path, [&](std::ostream& out) {
                out << "new";
                fs::remove(path);
                fs::create_directory(path);
                write_text(path + "/inside", "keep me");
            });
        });
        CHECK(reason.find("cannot replace the file") != std::string::npos);
        CHECK(read_file_bytes(path + "/inside") == "keep me");
        CHECK(entries(dir.dir()) == std::vector<std::string>{"doc.txt"});
    }
}

TEST_CASE("a save through a symbolic link replaces the file it points to, the link stays",
          "[io][no-data-loss]") {
    TempDir dir;
    fs::create_directory(dir.path("real"));
    const std::string real = dir.path("real/m.obj");
    write_mesh(make_icosahedron(), real);
    const fs::perms custom = fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read;
    fs::permissions(real, custom);
    // link.obj -> real/m.obj (relative), chain.obj -> link.obj (two levels).
    const std::string link = dir.path("link.obj"), chain = dir.path("chain.obj");
    fs::create_symlink("real/m.obj", link);
    fs::create_symlink(link, chain);

    write_mesh(make_cube(), link);
    CHECK(fs::is_symlink(link));
    CHECK(fs::read_symlink(link) == "real/m.obj");
    CHECK(read_mesh(real).mesh.n_vertices() == make_cube().n_vertices());
    CHECK(mode_of(real) == custom);

    write_mesh(make_tetrahedron(), chain);
    CHECK(fs::is_symlink(chain));
    CHECK(fs::is_symlink(link));
    CHECK(read_mesh(real).mesh.n_vertices() == 4);
    // The temporary file was made beside the real file and is gone; nothing else appeared.
    CHECK(entries(dir.dir()) == std::vector<std::string>{"chain.obj", "link.obj", "real"});
    CHECK(entries(dir.dir() / "real") == std::vector<std::string>{"m.obj"});

    // A dangling link: the file it names is created, the link stays.
    const std::string dangling = dir.path("dangling.off");
    fs::create_symlink("real/new.off", dangling);
    write_mesh(make_cube(), dangling);
    CHECK(fs::is_symlink(dangling));
    CHECK(fs::is_regular_file(dir.path("real/new.off")));

    // A loop of links is refused.
    fs::create_symlink("loop2.obj", dir.path("loop1.obj"));
    fs::create_symlink("loop1.obj", dir.path("loop2.obj"));
    CHECK(save_error(dir.path("loop1.obj"), [&] {
              write_mesh(make_cube(), dir.path("loop1.obj"));
          }).find("symbolic links") != std::string::npos);
}

TEST_CASE("a save refuses a read-only target, even as root", "[io][no-data-loss]") {
    TempDir dir;
    const std::string path = dir.path("m.ply");
    write_mesh(make_icosahedron(), path);
    const std::string before = read_file_bytes(path);
    const fs::perms read_only =
        fs::perms::owner_read | fs::perms::group_read | fs::perms::others_read;  // 0444
    fs::permissions(path, read_only);
    const std::string reason = save_error(path, [&] { write_mesh(make_cube(), path); });
    CHECK(reason.find("read-only") != std::string::npos);
    CHECK(reason.find("0444") != std::string::npos);
    CHECK(read_file_bytes(path) == before);
    CHECK(mode_of(path) == read_only);
    // Through a link too.
    fs::create_symlink("m.ply", dir.path("link.ply"));
    CHECK(save_error(dir.path("link.ply"), [&] {
              write_mesh(make_cube(), dir.path("link.ply"));
          }).find("read-only") != std::string::npos);
    CHECK(read_file_bytes(path) == before);
    CHECK(entries(dir.dir()) == std::vector<std::string>{"link.ply", "m.ply"});
}

TEST_CASE("a save whose unnamed temporary file cannot be linked copies it into a named one",
          "[io][no-data-loss]") {
    TempDir dir;
    if (!supports_unnamed_temporaries(dir.dir())) {
        SKIP_TEST(dir.dir() << " has no O_TMPFILE");
    }
    const std::string path = dir.path("m.ply");
    write_mesh(make_icosahedron(), path);
    fs::permissions(path, fs::perms::owner_read | fs::perms::owner_write);
    detail::force_unlinkable_temporary_files(true);
    write_mesh(make_cube(), path);
    detail::force_unlinkable_temporary_files(false);
    CHECK(read_mesh(path).mesh.n_vertices() == make_cube().n_vertices());
    CHECK(mode_of(path) == (fs::perms::owner_read | fs::perms::owner_write));
    CHECK(entries(dir.dir()) == std::vector<std::string>{"m.ply"});
}

TEST_CASE("a save keeps the permissions of the file it replaces", "[io][no-data-loss]") {
    TempDir dir;
    const std::string path = dir.path("m.obj");
    write_mesh(make_icosahedron(), path);
    for (const fs::perms custom :
         {fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read,
          fs::perms::owner_write | fs::perms::owner_read,
          fs::perms::owner_all | fs::perms::group_all | fs::perms::others_read}) {
        fs::permissions(path, custom);
        write_mesh(make_cube(), path);
        CHECK(mode_of(path) == custom);
    }
    for (const bool sync : {true, false}) {  // the synced path (the default) as well
        set_sync_saves(sync);
        fs::permissions(path, fs::perms::owner_read | fs::perms::owner_write);
        write_mesh(make_tetrahedron(), path);
        CHECK(mode_of(path) == (fs::perms::owner_read | fs::perms::owner_write));
    }
    set_sync_saves(false);
}

TEST_CASE("a save keeps hard links: every name sees the new content", "[io][no-data-loss]") {
    TempDir dir;
    const std::string a = dir.path("a.off"), b = dir.path("b.off");
    write_mesh(make_icosahedron(), a);
    fs::create_hard_link(a, b);
    fs::permissions(a, fs::perms::owner_read | fs::perms::owner_write | fs::perms::others_read);
    for (const bool named : {false, true}) {
        INFO("named temporary file: " << named);
        NamedTemporaries force(named);
        write_mesh(named ? make_cube() : make_tetrahedron(), a);
        CHECK(fs::hard_link_count(a) == 2);
        CHECK(fs::equivalent(a, b));
        CHECK(read_file_bytes(b) == read_file_bytes(a));
        CHECK(read_mesh(b).mesh.n_vertices() ==
              (named ? make_cube() : make_tetrahedron()).n_vertices());
        CHECK(mode_of(b) ==
              (fs::perms::owner_read | fs::perms::owner_write | fs::perms::others_read));
        CHECK(entries(dir.dir()) == std::vector<std::string>{"a.off", "b.off"});
    }
    // A failed save leaves both names untouched.
    const std::string before = read_file_bytes(a);
    CHECK_THROWS_AS(write_file_atomically(a,
                                          [](std::ostream& out) {
                                              out << "half";
                                              throw IoError("a.off", 0, "failed midway");
                                          }),
                    IoError);
    CHECK(read_file_bytes(b) == before);
    CHECK(entries(dir.dir()) == std::vector<std::string>{"a.off", "b.off"});
}

namespace {

/// Forks a child that saves `path` with a writer that writes `bytes` bytes and then waits
/// forever; kills it with SIGKILL once the bytes are written. Returns the child's pid.
pid_t kill_a_save(const std::string& path, std::size_t bytes) {
    int ready[2];
    REQUIRE(::pipe(ready) == 0);
    const pid_t pid = ::fork();
    REQUIRE(pid >= 0);
    if (pid == 0) {
        ::close(ready[0]);
        try {
            write_file_atomically(path, [&](std::ostream& out) {
                const std::string block(1 << 16, 'x');
                for (std::size_t n = 0; n < bytes; n += block.size()) out << block;
                out.flush();
                const char c = 1;
                if (::write(ready[1], &c, 1) != 1) ::_exit(2);
                for (;;) ::pause();
            });
        } catch (...) {
        }
        ::_exit(3);  // not reached: the parent kills this process while it waits
    }
    ::close(ready[1]);
    char c = 0;
    const bool signalled = ::read(ready[0], &c, 1) == 1;
    ::close(ready[0]);
    ::kill(pid, SIGKILL);
    int status = 0;
    ::waitpid(pid, &status, 0);
    REQUIRE(signalled);
    REQUIRE(WIFSIGNALED(status));
    REQUIRE(WTERMSIG(status) == SIGKILL);
    return pid;
}

}  // namespace

TEST_CASE("a save killed with SIGKILL keeps the old file and leaves no temporary file",
          "[io][no-data-loss]") {
    TempDir dir;
    const std::string path = dir.path("big.stl");
    write_text(path, "old content");
    const std::string prefix = detail::temporary_file_prefix("big.stl");

    SECTION("unnamed temporary file (O_TMPFILE): nothing is left at all") {
        if (!supports_unnamed_temporaries(dir.dir())) {
            SKIP_TEST(dir.dir() << " has no O_TMPFILE; the named case covers it");
        }
        for (int kill = 0; kill < 3; ++kill) kill_a_save(path, 8 << 20);
        CHECK(read_file_bytes(path) == "old content");
        CHECK(entries(dir.dir()) == std::vector<std::string>{"big.stl"});
    }
    SECTION("named temporary file: the next save removes what the killed ones left") {
        NamedTemporaries force(true);
        // Each killed save leaves its temporary file; the next save (here the next killed
        // one) removes it: one is left, the last one's.
        for (int kill = 0; kill < 3; ++kill) {
            const pid_t pid = kill_a_save(path, 8 << 20);
            const std::vector<std::string> names = entries(dir.dir());
            REQUIRE(names.size() == 2);
            CHECK(names[0].rfind(prefix + std::to_string(pid) + "-", 0) == 0);
            CHECK(fs::file_size(dir.dir() / names[0]) >= (8u << 20));
            CHECK(names[1] == "big.stl");
        }
        CHECK(read_file_bytes(path) == "old content");
        // A temporary file of a process that is alive (pid 1) is not touched.
        const std::string alive = dir.path(prefix + "1-0123456789ab");
        write_text(alive, "someone else's save");
        write_mesh(make_cube(), path);
        CHECK(read_mesh(path).mesh.n_faces() == make_cube().n_faces());
        CHECK(entries(dir.dir()) == std::vector<std::string>{prefix + "1-0123456789ab", "big.stl"});
    }
}
