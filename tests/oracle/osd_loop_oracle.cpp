// The oracle of trilab's crease-aware Loop subdivision (tests/unit/test_features.cpp): refines
// a triangle mesh uniformly with OpenSubdiv's Far::TopologyRefiner (Loop scheme, default
// Sdc::Options: boundary edges infinitely sharp, uniform creasing) and interpolates the
// positions in double precision with Far::PrimvarRefinerReal<double>. Built only where
// libosd-dev is installed (tests/CMakeLists.txt); never linked into trilab.
//
//   trilab_osd_loop_oracle LEVELS IN OUT [--ms]
//
// With --ms it prints "ms T" on stdout: the milliseconds of OpenSubdiv's own work (building the
// topology, refining it, interpolating every level's positions), what the features benchmark
// (tests/bench/features_cli.sh) sets against `trilab-cli subdivide --json`'s "ms".
// IN (text): "nv nf ncreases ncorners", nv lines "x y z", nf lines "a b c", ncreases lines
// "a b sharpness" (inf allowed: OpenSubdiv's infinite sharpness 10), ncorners lines "v".
// OUT (binary, little-endian host order): for each level 1..LEVELS: int32 n, then n pairs of
// int32 (a, b): the child vertex's parent in the level before, a vertex a (b = -1) or the edge
// a-b; then int32 n of the last level and n x 3 doubles, its positions.
#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/topologyDescriptor.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

namespace {

using namespace OpenSubdiv;

// NOLINTBEGIN(readability-identifier-naming): the names PrimvarRefiner calls
struct Vertex3 {
    double p[3];
    void Clear(void* = nullptr) { p[0] = p[1] = p[2] = 0; }
    void AddWithWeight(const Vertex3& s, double w) {
        for (int k = 0; k < 3; ++k) p[k] += w * s.p[k];
    }
};
// NOLINTEND(readability-identifier-naming)

int fail(const std::string& why) {
    std::fprintf(stderr, "trilab_osd_loop_oracle: %s\n", why.c_str());
    return 1;
}

void put(std::ofstream& out, std::int32_t v) {
    out.write(reinterpret_cast<const char*>(&v), sizeof v);
}

}  // namespace

int main(int argc, char** argv) {
    const bool timed = argc == 5 && std::string(argv[4]) == "--ms";
    if (argc != 4 && !timed) return fail("usage: trilab_osd_loop_oracle LEVELS IN OUT [--ms]");
    const int levels = std::atoi(argv[1]);
    if (levels < 1 || levels > 6) return fail("LEVELS must be 1 to 6");
    std::ifstream in(argv[2]);
    int nv = 0, nf = 0, nc = 0, nk = 0;
    if (!(in >> nv >> nf >> nc >> nk) || nv < 0 || nf < 0 || nc < 0 || nk < 0)
        return fail("bad header in " + std::string(argv[2]));
    std::vector<Vertex3> base(static_cast<std::size_t>(nv));
    for (Vertex3& v : base)
        if (!(in >> v.p[0] >> v.p[1] >> v.p[2])) return fail("bad vertex");
    std::vector<int> faces(3 * std::size_t(nf)), sizes(std::size_t(nf), 3);
    for (int& i : faces)
        if (!(in >> i)) return fail("bad face");
    std::vector<int> crease_pairs(2 * std::size_t(nc));
    std::vector<float> crease_weights(static_cast<std::size_t>(nc));
    for (int i = 0; i < nc; ++i) {
        std::string s;
        if (!(in >> crease_pairs[2 * i] >> crease_pairs[2 * i + 1] >> s)) return fail("bad crease");
        const double w = s == "inf" ? 10.0 : std::strtod(s.c_str(), nullptr);
        crease_weights[std::size_t(i)] = float(w >= 10.0 ? 10.0 : w);
    }
    std::vector<int> corners(static_cast<std::size_t>(nk));
    for (int& c : corners)
        if (!(in >> c)) return fail("bad corner");
    std::vector<float> corner_weights(std::size_t(nk), 10.0f);

    using Clock = std::chrono::steady_clock;
    Clock::duration work{};
    Clock::time_point t0 = Clock::now();
    Far::TopologyDescriptor desc;
    desc.numVertices = nv;
    desc.numFaces = nf;
    desc.numVertsPerFace = sizes.data();
    desc.vertIndicesPerFace = faces.data();
    desc.numCreases = nc;
    desc.creaseVertexIndexPairs = crease_pairs.data();
    desc.creaseWeights = crease_weights.data();
    desc.numCorners = nk;
    desc.cornerVertexIndices = corners.data();
    desc.cornerWeights = corner_weights.data();
    using Factory = Far::TopologyRefinerFactory<Far::TopologyDescriptor>;
    Sdc::Options sdc;  // the defaults: VTX_BOUNDARY_EDGE_ONLY, CREASE_UNIFORM
    Far::TopologyRefiner* refiner = Factory::Create(desc, Factory::Options(Sdc::SCHEME_LOOP, sdc));
    if (!refiner) return fail("OpenSubdiv refused the topology");
    refiner->RefineUniform(Far::TopologyRefiner::UniformOptions(levels));
    work += Clock::now() - t0;

    std::ofstream out(argv[3], std::ios::binary);
    std::vector<Vertex3> src = base, dst;
    Far::PrimvarRefinerReal<double> primvar(*refiner);
    for (int level = 1; level <= levels; ++level) {
        const Far::TopologyLevel& parent = refiner->GetLevel(level - 1);
        const int n = refiner->GetLevel(level).GetNumVertices();
        std::vector<std::int32_t> a(std::size_t(n), -2), b(std::size_t(n), -1);
        for (int v = 0; v < parent.GetNumVertices(); ++v) {
            const int c = parent.GetVertexChildVertex(v);
            if (c >= 0) a[std::size_t(c)] = v;
        }
        for (int e = 0; e < parent.GetNumEdges(); ++e) {
            const int c = parent.GetEdgeChildVertex(e);
            if (c < 0) continue;
            const auto ev = parent.GetEdgeVertices(e);
            a[std::size_t(c)] = ev[0];
            b[std::size_t(c)] = ev[1];
        }
        put(out, n);
        for (int i = 0; i < n; ++i) {
            put(out, a[std::size_t(i)]);
            put(out, b[std::size_t(i)]);
        }
        t0 = Clock::now();
        dst.assign(std::size_t(n), Vertex3{});
        const Vertex3* from = src.data();
        Vertex3* to = dst.data();
        primvar.Interpolate(level, from, to);
        src.swap(dst);
        work += Clock::now() - t0;
    }
    put(out, std::int32_t(src.size()));
    for (const Vertex3& v : src) out.write(reinterpret_cast<const char*>(v.p), sizeof v.p);
    delete refiner;
    if (timed) std::printf("ms %.3f\n", std::chrono::duration<double, std::milli>(work).count());
    return out ? 0 : fail("cannot write " + std::string(argv[3]));
}
