// read_large_file (core/io/file_util.h): the bytes and the errors of read_file_bytes, read by
// two threads into memory without a zero fill for files of 64 MiB or more.
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/errors.h"
#include "core/io/file_util.h"
#include "core/io/mesh_io.h"
#include "test_helpers.h"

using namespace trilab;
using namespace trilab::test;

namespace {

void write_file(const std::string& path, const std::string& bytes) {
    std::ofstream out(path, std::ios::binary);
    out.write(bytes.data(), std::streamsize(bytes.size()));
}

/// The IoError of `read` (which must throw one naming `path`).
template <class F>
IoError read_failure(const std::string& path, F&& read) {
    try {
        read();
    } catch (const IoError& e) {
        CHECK(e.file() == path);
        return e;
    }
    FAIL("no IoError for " << path);
    return IoError(path, 0, "");
}

/// `reason` with the memory limit's figures cut out: the limit is half the memory the process
/// may still allocate, which moves between two reads.
std::string without_limit_figures(const std::string& reason) {
    const std::string from = "more than the limit of ";
    const std::size_t begin = reason.find(from);
    const std::size_t end = reason.find(" (half the memory");
    if (begin == std::string::npos || end == std::string::npos || end < begin) return reason;
    return reason.substr(0, begin + from.size()) + reason.substr(end);
}

}  // namespace

TEST_CASE("read_large_file gives read_file_bytes's bytes, large and small", "[io][open]") {
    TempDir dir;
    // 64 MiB and an odd tail: two halves that do not split evenly, every byte distinct from
    // its neighbours so that a misplaced half shows.
    std::string large((std::size_t(64) << 20) + 13, '\0');
    for (std::size_t i = 0; i < large.size(); ++i) large[i] = char((i * 2654435761u) >> 13);
    const std::string large_path = dir.path("large.bin");
    write_file(large_path, large);
    CHECK(read_large_file(large_path).view() == large);

    const std::string small_path = dir.path("small.bin");
    write_file(small_path, "ply\n");
    CHECK(read_large_file(small_path).view() == "ply\n");
    std::filesystem::resize_file(small_path, 0);
    CHECK(read_large_file(small_path).view().empty());
}

TEST_CASE("read_large_file refuses what read_file_bytes refuses, with its message", "[io][open]") {
    TempDir dir;
    const std::string missing = dir.path("missing.ply");
    CHECK(read_failure(missing, [&] { read_large_file(missing); }).reason() ==
          read_failure(missing, [&] { read_file_bytes(missing); }).reason());
    CHECK(read_failure(dir.dir().string(), [&] { read_large_file(dir.dir().string()); }).reason() ==
          read_failure(dir.dir().string(), [&] { read_file_bytes(dir.dir().string()); }).reason());
    // Larger than the limit (a sparse file): refused before reading, as read_file_bytes does.
    const std::string huge = dir.path("huge.ply");
    write_file(huge, "ply\n");
    std::filesystem::resize_file(huge, std::uint64_t(1) << 40);
    // The limit itself moves with the memory that is free, so only its figures may differ.
    const std::string large_reason = read_failure(huge, [&] { read_large_file(huge); }).reason();
    const std::string bytes_reason = read_failure(huge, [&] { read_file_bytes(huge); }).reason();
    CHECK(large_reason.find("the file is 1099511627776 bytes (1.0 TiB), more than the limit of") ==
          0);
    CHECK(large_reason.find("half the memory this process may still allocate") !=
          std::string::npos);
    CHECK(without_limit_figures(large_reason) == without_limit_figures(bytes_reason));
}
