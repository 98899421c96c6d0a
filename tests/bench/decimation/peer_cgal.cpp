// CGAL 5.5 peer of the decimation benchmark: Surface_mesh over Simple_cartesian<double>,
// Surface_mesh_simplification::edge_collapse with GarlandHeckbert_plane_policies (cost and
// placement) and a Count_stop_predicate (edges; 5.5 has no face-count predicate). Kept in its own
// file: CGAL compiles slowly.
#include <chrono>
#include <ctime>

#include "peers.h"

#ifdef TRILAB_HAS_CGAL
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Count_stop_predicate.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/GarlandHeckbert_plane_policies.h>
#include <CGAL/Surface_mesh_simplification/edge_collapse.h>
#endif

namespace trilab::bench {

#ifdef TRILAB_HAS_CGAL
namespace {
using Kernel = CGAL::Simple_cartesian<double>;
using SurfaceMesh = CGAL::Surface_mesh<Kernel::Point_3>;
namespace SMS = CGAL::Surface_mesh_simplification;
}  // namespace

bool have_cgal() {
    return true;
}

PeerRun cgal_decimate(const Soup& in, std::size_t target_edges) {
    SurfaceMesh mesh;
    std::vector<SurfaceMesh::Vertex_index> vh;
    vh.reserve(in.positions.size());
    for (const auto& p : in.positions)
        vh.push_back(mesh.add_vertex(Kernel::Point_3(p[0], p[1], p[2])));
    for (const auto& f : in.faces) mesh.add_face(vh[f[0]], vh[f[1]], vh[f[2]]);
    PeerRun run;
    const auto t0 = std::chrono::steady_clock::now();
    const std::clock_t c0 = std::clock();
    {
        SMS::GarlandHeckbert_plane_policies<SurfaceMesh, Kernel> policies(mesh);
        SMS::Count_stop_predicate<SurfaceMesh> stop(target_edges);
        SMS::edge_collapse(mesh, stop,
                           CGAL::parameters::get_cost(policies.get_cost())
                               .get_placement(policies.get_placement()));
        mesh.collect_garbage();
    }
    run.ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    run.cpu_ms = 1000.0 * double(std::clock() - c0) / CLOCKS_PER_SEC;
    for (auto v : mesh.vertices()) {
        const auto& p = mesh.point(v);
        run.soup.positions.push_back({p.x(), p.y(), p.z()});
    }
    for (auto f : mesh.faces()) {
        std::array<std::uint32_t, 3> c{};
        int i = 0;
        for (auto v : CGAL::vertices_around_face(mesh.halfedge(f), mesh)) c[i++] = std::uint32_t(v);
        run.soup.faces.push_back(c);
    }
    return run;
}
#else
bool have_cgal() {
    return false;
}
PeerRun cgal_decimate(const Soup&, std::size_t) {
    return {};
}
#endif

}  // namespace trilab::bench
