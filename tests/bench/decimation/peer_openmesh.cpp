// OpenMesh 9 peer of the decimation benchmark: DecimaterT + ModQuadricT (no error limit),
// double-precision points, decimate_to(target vertices), then garbage collection.
#include <chrono>
#include <ctime>

#include "peers.h"

#ifdef TRILAB_HAS_OPENMESH
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Decimater/DecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModQuadricT.hh>
#endif

namespace trilab::bench {

#ifdef TRILAB_HAS_OPENMESH
namespace {
struct DoubleTraits : OpenMesh::DefaultTraits {
    typedef OpenMesh::Vec3d Point;
    typedef OpenMesh::Vec3d Normal;
};
using OmMesh = OpenMesh::TriMesh_ArrayKernelT<DoubleTraits>;
}  // namespace

bool have_openmesh() {
    return true;
}

PeerRun openmesh_decimate(const Soup& in, std::size_t target_vertices) {
    OmMesh mesh;
    std::vector<OmMesh::VertexHandle> vh;
    vh.reserve(in.positions.size());
    for (const auto& p : in.positions)
        vh.push_back(mesh.add_vertex(OmMesh::Point(p[0], p[1], p[2])));
    for (const auto& f : in.faces) mesh.add_face(vh[f[0]], vh[f[1]], vh[f[2]]);
    PeerRun run;
    const auto t0 = std::chrono::steady_clock::now();
    const std::clock_t c0 = std::clock();
    {
        OpenMesh::Decimater::DecimaterT<OmMesh> decimater(mesh);
        OpenMesh::Decimater::ModQuadricT<OmMesh>::Handle quadric;
        decimater.add(quadric);
        decimater.module(quadric).unset_max_err();
        decimater.initialize();
        decimater.decimate_to(target_vertices);
        mesh.garbage_collection();
    }
    run.ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    run.cpu_ms = 1000.0 * double(std::clock() - c0) / CLOCKS_PER_SEC;
    for (auto v : mesh.vertices()) {
        const auto& p = mesh.point(v);
        run.soup.positions.push_back({p[0], p[1], p[2]});
    }
    for (auto f : mesh.faces()) {
        std::array<std::uint32_t, 3> c{};
        int i = 0;
        for (auto v : mesh.fv_range(f)) c[i++] = std::uint32_t(v.idx());
        run.soup.faces.push_back(c);
    }
    return run;
}
#else
bool have_openmesh() {
    return false;
}
PeerRun openmesh_decimate(const Soup&, std::size_t) {
    return {};
}
#endif

}  // namespace trilab::bench
