#include "test_helpers.h"

#include <atomic>
#include <random>

#include "core/algorithms/generators.h"
#include "core/errors.h"
#include "core/geometry.h"
#include "core/io/file_util.h"
#include "core/io/mesh_io.h"
#include "core/mesh_builder.h"

namespace trilab::test {

namespace {
// The tests save hundreds of small files: no fsync for each (about 7 ms on this disk).
// test_no_data_loss.cpp turns it on where the synced path itself is tested.
[[maybe_unused]] const bool kNoSyncedSaves = [] {
    set_sync_saves(false);
    return true;
}();
}  // namespace

std::vector<Point> cluster_means(const HalfedgeMesh& mesh, const std::vector<Point>& x,
                                 const std::vector<Index>& cluster_of, std::size_t clusters) {
    std::vector<Point> sum(clusters, Point::Zero());
    std::vector<int> count(clusters, 0);
    for (Vertex v : mesh.vertices()) {
        sum[cluster_of[v.idx()]] += x[v.idx()];
        ++count[cluster_of[v.idx()]];
    }
    for (std::size_t c = 0; c < clusters; ++c) {
        REQUIRE(count[c] > 0);
        sum[c] /= count[c];
    }
    return sum;
}

HalfedgeMesh two_spheres() {
    PolygonSoup soup = to_soup(make_icosphere(2));
    const std::size_t n = soup.positions.size(), c = soup.corners.size(), f = soup.n_faces();
    for (std::size_t i = 0; i < n; ++i)
        soup.positions.push_back(soup.positions[i] + Point(3, 0, 0));
    for (std::size_t i = 0; i < c; ++i) soup.corners.push_back(soup.corners[i] + Index(n));
    for (std::size_t i = 1; i <= f; ++i) soup.face_offsets.push_back(soup.face_offsets[i] + c);
    LoadReport report;
    return build_mesh(soup, report);
}

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
