// The peer of `trilab-cli fill-holes` in tests/bench/hole_filling_bench.sh: CGAL's
// triangulate_refine_and_fair_hole (Liepa 2003 with Zou et al.'s Delaunay restriction) on every
// boundary loop of a mesh. Built by the benchmark's own set-up against libcgal-dev; never part
// of trilab's targets.
//   cgal_fill_holes IN [RUNS]
// prints one line of JSON: loops, filled, ms (the median over RUNS of the filling alone, the
// reading excluded), closed, faces_added, vertices_added, min_new_angle_deg.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iterator>
#include <set>
#include <vector>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/IO/polygon_mesh_io.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/helpers.h>

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
using Face = Mesh::Face_index;
using Vertex = Mesh::Vertex_index;
using Halfedge = Mesh::Halfedge_index;
namespace PMP = CGAL::Polygon_mesh_processing;

namespace {

double min_angle_deg(const Mesh& m, Face f) {
    std::vector<Kernel::Point_3> p;
    for (Vertex v : CGAL::vertices_around_face(m.halfedge(f), m)) p.push_back(m.point(v));
    double best = 180;
    for (int i = 0; i < 3; ++i) {
        const Kernel::Vector_3 a = p[(i + 1) % 3] - p[i], b = p[(i + 2) % 3] - p[i];
        const double c = std::sqrt(CGAL::to_double(CGAL::cross_product(a, b).squared_length()));
        best = std::min(best, std::atan2(c, CGAL::to_double(a * b)) * 180 / M_PI);
    }
    return best;
}

struct Run {
    double ms = 0, min_angle = 180;
    std::size_t loops = 0, filled = 0, faces = 0, vertices = 0;
    bool closed = false;
};

Run fill(Mesh m) {
    Run r;
    std::vector<Halfedge> starts;
    std::set<Halfedge> seen;
    for (Halfedge h : m.halfedges()) {
        if (!m.is_border(h) || seen.count(h)) continue;
        starts.push_back(h);
        for (Halfedge g : CGAL::halfedges_around_face(h, m)) seen.insert(g);
    }
    r.loops = starts.size();
    std::vector<Face> faces;
    std::vector<Vertex> vertices;
    const auto t0 = std::chrono::steady_clock::now();
    for (Halfedge h : starts) {
        const auto result = PMP::triangulate_refine_and_fair_hole(m, h, std::back_inserter(faces),
                                                                  std::back_inserter(vertices));
        if (std::get<0>(result)) ++r.filled;
    }
    r.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    r.faces = faces.size();
    r.vertices = vertices.size();
    for (Face f : faces) r.min_angle = std::min(r.min_angle, min_angle_deg(m, f));
    r.closed = CGAL::is_closed(m);
    return r;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: cgal_fill_holes IN [RUNS]\n");
        return 2;
    }
    Mesh mesh;
    if (!PMP::IO::read_polygon_mesh(argv[1], mesh)) {
        std::fprintf(stderr, "cgal_fill_holes: cannot read %s\n", argv[1]);
        return 1;
    }
    const int runs = argc > 2 ? std::max(1, std::atoi(argv[2])) : 5;
    std::vector<double> ms;
    Run last;
    for (int i = 0; i < runs; ++i) {
        last = fill(mesh);
        ms.push_back(last.ms);
    }
    std::sort(ms.begin(), ms.end());
    std::printf(
        "{\"loops\": %zu, \"filled\": %zu, \"ms\": %.2f, \"closed\": %s, \"faces_added\": %zu, "
        "\"vertices_added\": %zu, \"min_new_angle_deg\": %.2f}\n",
        last.loops, last.filled, ms[ms.size() / 2], last.closed ? "true" : "false", last.faces,
        last.vertices, last.min_angle);
    return 0;
}
