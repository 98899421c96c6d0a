// Peers of the fairing benchmark, in their own file because CGAL's headers compile slowly.
//  - OpenMesh 9 JacobiLaplaceSmootherT, 10 iterations on the large mesh: "uniform" is
//    initialize(Tangential_and_Normal, C0) (uniform weights, damping 0.5 = trilab's explicit
//    umbrella with step 0.5); "cotangent" is initialize(Normal, C0) (cotangent weights, the
//    update projected on the normal; OpenMesh has no unprojected cotangent smoother) against
//    trilab's explicit curvature flow with step 0.5. Double-precision points like trilab's.
//  - CGAL 5.5 Polygon_mesh_processing::smooth_shape, one implicit mean-curvature-flow step
//    (time 1e-4 x the bounding-box diagonal squared is not needed: it takes a time and uses a
//    sparse Cholesky from Eigen) on the bunny, against trilab's implicit curvature flow.
// Building the peers' meshes and copying them before each run are not timed.
#include "fairing_bench_peers.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <vector>

#include "core/algorithms/fairing.h"

#ifdef TRILAB_HAS_OPENMESH
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include "openmesh_mesh.h"  // first: the tools need the mesh kernel

#include <OpenMesh/Tools/Smoother/JacobiLaplaceSmootherT.hh>
#endif

#ifdef TRILAB_HAS_CGAL
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/smooth_shape.h>
#include <CGAL/Surface_mesh.h>
#endif

using namespace trilab;

namespace {

using Clock = std::chrono::steady_clock;

/// Median of `runs` timings; `f` returns the milliseconds of its timed part.
double median_of(int runs, const std::function<double()>& f) {
    std::vector<double> t;
    f();  // warm-up
    for (int i = 0; i < runs; ++i) t.push_back(f());
    std::sort(t.begin(), t.end());
    return t[t.size() / 2];
}

double ms_since(Clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

[[maybe_unused]] double trilab_ms(const HalfedgeMesh& mesh, FairingOperator op,
                                  Integration integration, double step, int iterations, int runs) {
    FairingOptions o;
    o.op = op;
    o.integration = integration;
    o.step = step;
    o.iterations = iterations;
    o.keep_steps = false;
    o.estimate_max_stable_step = false;
    return median_of(runs, [&] {
        const auto t0 = Clock::now();
        smooth(mesh, o);
        return ms_since(t0);
    });
}

[[maybe_unused]] void print_ratio(const char* what, double peer_ms, double ours_ms, double aim) {
    std::printf("  %-46s peer %9.1f ms  trilab %8.1f ms  speed-up %5.2fx (aim %.0fx) %s\n", what,
                peer_ms, ours_ms, peer_ms / ours_ms, aim,
                peer_ms / ours_ms >= aim ? "met" : "below aim");
}

#ifdef TRILAB_HAS_OPENMESH
using OMMesh = bench::OpenMeshDouble;
using bench::to_openmesh;

double openmesh_ms(const OMMesh& source, bool cotangent, int runs) {
    using Smoother = OpenMesh::Smoother::JacobiLaplaceSmootherT<OMMesh>;
    return median_of(runs, [&] {
        OMMesh m = source;  // not timed
        m.request_vertex_normals();
        m.request_face_normals();
        m.update_normals();
        const auto t0 = Clock::now();
        Smoother smoother(m);
        smoother.initialize(cotangent ? Smoother::Normal : Smoother::Tangential_and_Normal,
                            Smoother::C0);
        smoother.smooth(10);
        return ms_since(t0);
    });
}
#endif

#ifdef TRILAB_HAS_CGAL
using CgalKernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using CgalMesh = CGAL::Surface_mesh<CgalKernel::Point_3>;

CgalMesh to_cgal(const HalfedgeMesh& m) {
    CgalMesh cm;
    std::vector<CgalMesh::Vertex_index> handles(m.vertices_size());
    for (Vertex v : m.vertices()) {
        const Point& p = m.position(v);
        handles[v.idx()] = cm.add_vertex(CgalKernel::Point_3(p.x(), p.y(), p.z()));
    }
    for (Face f : m.faces()) {
        const auto vs = m.face_vertices(f);
        cm.add_face(handles[vs[0].idx()], handles[vs[1].idx()], handles[vs[2].idx()]);
    }
    return cm;
}
#endif

}  // namespace

void run_peers([[maybe_unused]] const HalfedgeMesh* bunny,
               [[maybe_unused]] const HalfedgeMesh& large, [[maybe_unused]] int runs) {
    std::printf("\npeers (same run):\n");
#ifdef TRILAB_HAS_OPENMESH
    {
        const OMMesh om = to_openmesh(large);
        const int r = std::min(runs, 3);
        const double om_uniform = openmesh_ms(om, false, r);
        const double ours_uniform =
            trilab_ms(large, FairingOperator::Umbrella, Integration::Explicit, 0.5, 10, r);
        print_ratio("OpenMesh Jacobi uniform, 10 iterations", om_uniform, ours_uniform, 3);
        const double om_cot = openmesh_ms(om, true, r);
        const double ours_cot =
            trilab_ms(large, FairingOperator::CurvatureFlow, Integration::Explicit, 0.5, 10, r);
        print_ratio("OpenMesh Jacobi cotangent (normal), 10 iter.", om_cot, ours_cot, 3);
    }
#else
    std::printf("  OpenMesh not found at configure time (sudo apt-get install libopenmesh-dev)\n");
#endif
#ifdef TRILAB_HAS_CGAL
    if (bunny) {
        const CgalMesh source = to_cgal(*bunny);
        const double cgal = median_of(runs, [&] {
            CgalMesh m = source;  // not timed
            const auto t0 = Clock::now();
            CGAL::Polygon_mesh_processing::smooth_shape(m, 1e-4,
                                                        CGAL::parameters::number_of_iterations(1));
            return ms_since(t0);
        });
        const double ours =
            trilab_ms(*bunny, FairingOperator::CurvatureFlow, Integration::Implicit, 1.0, 1, runs);
        print_ratio("CGAL smooth_shape, 1 implicit step, bunny", cgal, ours, 2);
    }
#else
    (void)bunny;
    std::printf("  CGAL not found at configure time (sudo apt-get install libcgal-dev)\n");
#endif
}
