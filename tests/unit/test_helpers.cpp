#include "test_helpers.h"

#include <atomic>
#include <random>

#include "core/algorithms/generators.h"
#include "core/errors.h"
#include "core/geometry.h"
#include "core/io/file_util.h"
#include "core/io/mesh_io.h"

namespace trilab::test {

namespace {
// The tests save hundreds of small files: no fsync for each (about 7 ms on this disk).
// test_no_data_loss.cpp turns it on where the synced path itself is tested.
[[maybe_unused]] const bool kNoSyncedSaves = [] {
    set_sync_saves(false);
    return true;
}();
}  // namespace

HalfedgeMesh attributed_sphere() {
    HalfedgeMesh m = make_icosphere(3);
    compute_vertex_normals(m);
    auto uv = m.vertex_property<TexCoord>("v:texcoord");
    auto color = m.vertex_property<Color>("v:color");
    for (Vertex v : m.vertices()) {
        const Point& p = m.position(v);
        uv[v] = TexCoord(0.5 + 0.5 * p.x(), 0.25 + 0.5 * p.y());
        color[v] = Color(float(v.idx() % 256) / 255.0f, 0.5f, float(p.z() * 0.5 + 0.5));
    }
    return m;
}

std::string read_error(const std::string& path) {
    return error_text<IoError>([&] { read_mesh(path); });
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
