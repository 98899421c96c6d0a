// No data loss on save: every writer goes through write_file_atomically (a temporary file
// beside the target, then a rename), so a save that fails for any reason leaves the old file
// byte for byte and no temporary file behind.
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/errors.h"
#include "core/generators.h"
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

}  // namespace

TEST_CASE("a save writes a temporary file beside the target, then renames it",
          "[io][no-data-loss]") {
    TempDir dir;
    const std::string path = dir.path("doc.txt");
    write_text(path, "old");
    bool checked = false;
    write_file_atomically(path, [&](std::ostream& out) {
        out << "new";
        // While the new content is written, the target still holds the old one and the
        // new bytes go to a second file in the same folder.
        CHECK(read_file_bytes(path) == "old");
        const std::vector<std::string> names = entries(dir.dir());
        REQUIRE(names.size() == 2);
        CHECK(names[0] == "doc.txt");
        CHECK(names[1].rfind("doc.txt.tmp", 0) == 0);
        checked = true;
    });
    REQUIRE(checked);
    CHECK(read_file_bytes(path) == "new");
    CHECK(entries(dir.dir()) == std::vector<std::string>{"doc.txt"});
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
        WARN(
            "skipped: this process can write into a read-only folder (running as root?); the "
            "other no-data-loss tests cover failed saves without permissions");
        return;
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

TEST_CASE("a save that cannot replace the target keeps it and removes the temporary file",
          "[io][no-data-loss]") {
    // The target is a non-empty folder: the temporary file is written, the rename fails.
    TempDir dir;
    const std::string path = dir.path("m.off");
    fs::create_directory(path);
    write_text(path + "/inside", "keep me");
    try {
        write_mesh(make_icosahedron(), path);
        FAIL("no error");
    } catch (const IoError& e) {
        CHECK(e.file() == path);
        CHECK(e.reason().find("cannot replace") != std::string::npos);
    }
    CHECK(read_file_bytes(path + "/inside") == "keep me");
    CHECK(entries(dir.dir()) == std::vector<std::string>{"m.off"});
}

TEST_CASE("a save keeps the permissions of the file it replaces", "[io][no-data-loss]") {
    TempDir dir;
    const std::string path = dir.path("m.obj");
    write_mesh(make_icosahedron(), path);
    const fs::perms custom = fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read;
    fs::permissions(path, custom);
    write_mesh(make_cube(), path);
    CHECK((fs::status(path).permissions() & fs::perms::mask) == custom);
}
