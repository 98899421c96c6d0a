// meshoptimizer peer of the decimation benchmark: meshopt_simplify on float positions with no
// error limit (target_error 1, relative to the mesh extent), down to a face count.
#include <chrono>
#include <ctime>

#include "peers.h"

#ifdef TRILAB_HAS_MESHOPT
#include <meshoptimizer.h>
#endif

namespace trilab::bench {

Soup compact(const Soup& s) {
    Soup out;
    std::vector<std::uint32_t> index(s.positions.size(), UINT32_MAX);
    for (const auto& f : s.faces) {
        std::array<std::uint32_t, 3> c{};
        for (int i = 0; i < 3; ++i) {
            std::uint32_t& k = index[f[i]];
            if (k == UINT32_MAX) {
                k = std::uint32_t(out.positions.size());
                out.positions.push_back(s.positions[f[i]]);
            }
            c[i] = k;
        }
        out.faces.push_back(c);
    }
    return out;
}

#ifdef TRILAB_HAS_MESHOPT
bool have_meshopt() {
    return true;
}

PeerRun meshopt_decimate(const Soup& in, std::size_t target_faces) {
    std::vector<float> xyz;
    xyz.reserve(3 * in.positions.size());
    for (const auto& p : in.positions)
        for (double c : p) xyz.push_back(float(c));
    std::vector<unsigned int> indices;
    indices.reserve(3 * in.faces.size());
    for (const auto& f : in.faces) indices.insert(indices.end(), f.begin(), f.end());
    std::vector<unsigned int> out(indices.size());
    PeerRun run;
    const auto t0 = std::chrono::steady_clock::now();
    const std::clock_t c0 = std::clock();
    const std::size_t n =
        meshopt_simplify(out.data(), indices.data(), indices.size(), xyz.data(),
                         in.positions.size(), 3 * sizeof(float), 3 * target_faces, 1.0f);
    run.ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    run.cpu_ms = 1000.0 * double(std::clock() - c0) / CLOCKS_PER_SEC;
    Soup s;
    s.positions = in.positions;
    for (std::size_t i = 0; i + 2 < n; i += 3) s.faces.push_back({out[i], out[i + 1], out[i + 2]});
    run.soup = compact(s);
    return run;
}
#else
bool have_meshopt() {
    return false;
}
PeerRun meshopt_decimate(const Soup&, std::size_t) {
    return {};
}
#endif

}  // namespace trilab::bench
