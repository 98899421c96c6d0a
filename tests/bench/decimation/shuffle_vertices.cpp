// trilab_shuffle_vertices IN OUT [SEED]: writes IN's mesh to OUT with its vertices in a random
// order (a Fisher-Yates shuffle from SEED, default 1; the faces keep their order and corners),
// as another tool may write the same mesh. A benchmark helper, not a user option: the
// decimation benchmark in docs/benchmarks.md times the same mesh in both orders.
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "core/io/mesh_io.h"
#include "core/mesh_builder.h"

namespace {

// Reorders one per-vertex attribute (empty: nothing to do): new slot i holds old slot order[i].
template <class T>
void permute(std::vector<T>& values, const std::vector<trilab::Index>& order) {
    if (values.empty()) return;
    std::vector<T> out(values.size());
    for (std::size_t i = 0; i < order.size(); ++i) out[i] = values[order[i]];
    values = std::move(out);
}

}  // namespace

int main(int argc, char** argv) {
    using namespace trilab;
    if (argc < 3 || argc > 4) {
        std::fprintf(stderr, "usage: %s IN OUT [SEED]\n", argv[0]);
        return 2;
    }
    try {
        const unsigned long seed = argc == 4 ? std::strtoul(argv[3], nullptr, 10) : 1;
        PolygonSoup soup = to_soup(read_mesh(argv[1]).mesh);
        const std::size_t n = soup.positions.size();
        std::vector<Index> order(n);  // new index -> old index
        for (std::size_t i = 0; i < n; ++i) order[i] = Index(i);
        std::mt19937_64 rng(seed);
        for (std::size_t i = n; i > 1; --i) {
            const std::size_t j = std::size_t(rng() % i);
            std::swap(order[i - 1], order[j]);
        }
        std::vector<Index> new_index(n);
        for (std::size_t i = 0; i < n; ++i) new_index[order[i]] = Index(i);
        permute(soup.positions, order);
        permute(soup.normals, order);
        permute(soup.colors, order);
        permute(soup.texcoords, order);
        permute(soup.distances, order);
        permute(soup.selections, order);
        for (Index& c : soup.corners) c = new_index[c];
        LoadReport report;
        write_mesh(build_mesh(soup, report), argv[2]);
        std::printf("%s: %zu vertices shuffled (seed %lu), %zu faces\n", argv[2], n, seed,
                    soup.n_faces());
    } catch (const std::exception& e) {
        std::fprintf(stderr, "trilab_shuffle_vertices: %s\n", e.what());
        return 1;
    }
    return 0;
}
