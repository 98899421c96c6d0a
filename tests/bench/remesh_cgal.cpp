// The peer of tests/bench/remesh_bench.sh: CGAL's isotropic remeshing on one mesh, timed. Built
// and run by that script only (it installs libcgal-dev in its own set-up); never part of
// trilab's targets.
//   remesh_cgal IN.off OUT.off LENGTH ITERATIONS
// Prints one line: "ms <milliseconds of isotropic_remeshing alone> faces <output faces>".
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
namespace PMP = CGAL::Polygon_mesh_processing;

int main(int argc, char** argv) {
    if (argc != 5) {
        std::fprintf(stderr, "usage: remesh_cgal IN.off OUT.off LENGTH ITERATIONS\n");
        return 2;
    }
    Mesh mesh;
    if (!CGAL::IO::read_polygon_mesh(argv[1], mesh) || !CGAL::is_triangle_mesh(mesh)) {
        std::fprintf(stderr, "remesh_cgal: cannot read a triangle mesh from %s\n", argv[1]);
        return 1;
    }
    const double length = std::atof(argv[3]);
    const unsigned iterations = unsigned(std::atoi(argv[4]));
    const auto t0 = std::chrono::steady_clock::now();
    PMP::isotropic_remeshing(faces(mesh), length, mesh,
                             CGAL::parameters::number_of_iterations(iterations));
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    mesh.collect_garbage();
    if (!CGAL::IO::write_polygon_mesh(argv[2], mesh, CGAL::parameters::stream_precision(17))) {
        std::fprintf(stderr, "remesh_cgal: cannot write %s\n", argv[2]);
        return 1;
    }
    std::printf("ms %.1f faces %zu\n", ms, std::size_t(num_faces(mesh)));
    return 0;
}
