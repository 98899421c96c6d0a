// Every input that ever made a fuzzer (tests/fuzz) fail is kept in
// tests/data/fuzz-regressions/<reader>/ with the reader's extension; each must now load as a
// valid mesh with finite positions (or a consistent image), or be refused with an IoError
// that names the file and gives a reason.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "core/errors.h"
#include "core/io/image_io.h"
#include "core/io/mesh_io.h"
#include "test_helpers.h"

using namespace trilab;
using namespace trilab::test;
namespace fs = std::filesystem;

namespace {

std::vector<std::string> regression_files() {
    std::vector<std::string> files;
    const fs::path root = data_file("fuzz-regressions");
    if (!fs::exists(root)) return files;
    const std::vector<std::string> meshes = supported_mesh_extensions();
    const std::vector<std::string> images = supported_image_extensions();
    for (const auto& entry : fs::recursive_directory_iterator(root)) {
        const std::string ext = file_extension(entry.path().string());
        const bool known = std::find(meshes.begin(), meshes.end(), ext) != meshes.end() ||
                           std::find(images.begin(), images.end(), ext) != images.end();
        if (entry.is_regular_file() && known) files.push_back(entry.path().string());
    }
    std::sort(files.begin(), files.end());
    return files;
}

bool is_image(const std::string& path) {
    const std::vector<std::string> exts = supported_image_extensions();
    return std::find(exts.begin(), exts.end(), file_extension(path)) != exts.end();
}

void check_refusal(const IoError& e, const std::string& path) {
    INFO(e.what());
    REQUIRE(e.file() == path);
    REQUIRE_FALSE(e.reason().empty());
}

}  // namespace

TEST_CASE("every input a fuzzer ever failed on now loads or is refused cleanly",
          "[io][fuzz-regressions]") {
    const std::vector<std::string> files = regression_files();
    if (files.empty()) WARN("no fuzz regression inputs yet (tests/data/fuzz-regressions/)");
    for (const std::string& path : files) {
        INFO("input: " << path);
        if (is_image(path)) {
            try {
                const Image image = read_image(path);
                REQUIRE(image.rgba.size() ==
                        std::size_t(image.width) * std::size_t(image.height) * 4);
            } catch (const IoError& e) {
                check_refusal(e, path);
            }
            continue;
        }
        try {
            const LoadedMesh loaded = read_mesh(path);
            REQUIRE_VALID(loaded.mesh);
            for (Vertex v : loaded.mesh.vertices()) {
                const Point& p = loaded.mesh.position(v);
                REQUIRE((std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z())));
            }
        } catch (const IoError& e) {
            check_refusal(e, path);
        }
    }
}
