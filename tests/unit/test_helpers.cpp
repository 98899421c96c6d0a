#include "test_helpers.h"

#include <atomic>
#include <random>

#include "core/errors.h"
#include "core/io/mesh_io.h"

namespace trilab::test {

std::string read_error(const std::string& path) {
    try {
        read_mesh(path);
    } catch (const IoError& e) {
        return e.what();
    }
    return "";
}

TempDir::TempDir() {
    static std::atomic<int> counter{0};
    std::random_device rd;
    dir_ = std::filesystem::temp_directory_path() /
           ("trilab_test_" + std::to_string(rd()) + "_" + std::to_string(counter++));
    std::filesystem::create_directories(dir_);
}

TempDir::~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(dir_, ec);
}

}  // namespace trilab::test
