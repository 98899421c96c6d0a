// The peer of `trilab-cli fill-holes` in tests/bench/hole_filling_bench.sh: CGAL's
// triangulate_refine_and_fair_hole (Liepa 2003 with Zou et al.'s Delaunay restriction) on every
// boundary loop of a mesh. Built by the benchmark's own set-up against libcgal-dev; never part
// of trilab's targets.
//   cgal_fill_holes IN [RUNS]
// prints one line of JSON: loops, filled, ms (the median over RUNS of the filling alone, the
// reading excluded), closed, faces_added, vertices_added, min_new_angle_deg, and the rim's
// smoothness: rim_bend_deg (the mean dihedral angle across the rim edges, between an old and a
// new face), near_bend_deg (the same over the old edges at rim vertices) and their difference
// rim_jump_deg (0: the fill bends across the rim as the surface does next to it).
//   cgal_fill_holes --rim ORIGINAL FILLED
// prints the rim figures of a fill made by another program (new faces: those of FILLED whose
// three corner positions are no face of ORIGINAL).
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iterator>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/IO/polygon_mesh_io.h>
#include <CGAL/Polygon_mesh_processing/compute_normal.h>
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

double dihedral_deg(const Mesh& m, Face a, Face b) {
    const auto na = PMP::compute_face_normal(a, m), nb = PMP::compute_face_normal(b, m);
    const double c = std::max(-1.0, std::min(1.0, CGAL::to_double(na * nb)));
    return std::acos(c) * 180 / M_PI;
}

struct RimFigures {
    double rim = 0, near = 0;
    std::size_t n_rim = 0, n_near = 0;
    std::array<double, 3> key{0, 0, 0};  ///< per hole: its lexicographically first rim point
};

/// The rim figures of a mesh whose new faces are marked: over every fill together (the
/// first), then per fill (a connected set of new faces), each keyed by its first rim point
/// (the input's position, the same in every program's output), sorted by key.
std::vector<RimFigures> rim_figures(const Mesh& m, const std::vector<char>& is_new) {
    // The fills: new faces joined across edges between two new faces (union-find).
    std::vector<std::size_t> parent(is_new.size());
    for (std::size_t i = 0; i < parent.size(); ++i) parent[i] = i;
    const auto find = [&](std::size_t x) {
        while (parent[x] != x) x = parent[x] = parent[parent[x]];
        return x;
    };
    for (auto e : m.edges()) {
        if (m.is_border(e)) continue;
        const Halfedge h = m.halfedge(e);
        const Face a = m.face(h), b = m.face(m.opposite(h));
        if (is_new[a] && is_new[b]) parent[find(std::size_t(a))] = find(std::size_t(b));
    }
    std::map<std::size_t, RimFigures> fills;
    const auto point = [&](Vertex v) {
        const auto& q = m.point(v);
        return std::array<double, 3>{CGAL::to_double(q.x()), CGAL::to_double(q.y()),
                                     CGAL::to_double(q.z())};
    };
    // Per rim vertex: the fill it borders.
    std::map<Vertex, std::size_t> rim_vertex;
    RimFigures all;
    for (auto e : m.edges()) {
        const Halfedge h = m.halfedge(e);
        if (m.is_border(e)) continue;
        const Face a = m.face(h), b = m.face(m.opposite(h));
        if (is_new[a] == is_new[b]) continue;
        const std::size_t fill = find(std::size_t(is_new[a] ? a : b));
        RimFigures& r = fills[fill];
        const double d = dihedral_deg(m, a, b);
        for (RimFigures* x : {&r, &all}) x->rim += d, ++x->n_rim;
        for (Vertex v : {m.source(h), m.target(h)}) {
            rim_vertex[v] = fill;
            const auto p = point(v);
            if (r.n_rim == 1 || p < r.key) r.key = p;
        }
    }
    for (auto e : m.edges()) {
        const Halfedge h = m.halfedge(e);
        if (m.is_border(e)) continue;
        const Face a = m.face(h), b = m.face(m.opposite(h));
        if (is_new[a] || is_new[b]) continue;
        for (Vertex v : {m.source(h), m.target(h)}) {
            const auto it = rim_vertex.find(v);
            if (it == rim_vertex.end()) continue;
            const double d = dihedral_deg(m, a, b);
            RimFigures& r = fills[it->second];
            for (RimFigures* x : {&r, &all}) x->near += d, ++x->n_near;
            break;  // an edge with both ends on the rim counts once
        }
    }
    std::vector<RimFigures> out{all};
    for (auto& [fill, r] : fills) out.push_back(r);
    std::sort(out.begin() + 1, out.end(),
              [](const RimFigures& x, const RimFigures& y) { return x.key < y.key; });
    for (RimFigures& r : out) {
        if (r.n_rim) r.rim /= double(r.n_rim);
        if (r.n_near) r.near /= double(r.n_near);
    }
    return out;
}

std::array<double, 9> corner_key(const Mesh& m, Face f) {
    std::vector<std::array<double, 3>> p;
    for (Vertex v : CGAL::vertices_around_face(m.halfedge(f), m)) {
        const auto& q = m.point(v);
        p.push_back({CGAL::to_double(q.x()), CGAL::to_double(q.y()), CGAL::to_double(q.z())});
    }
    std::sort(p.begin(), p.end());
    return {p[0][0], p[0][1], p[0][2], p[1][0], p[1][1], p[1][2], p[2][0], p[2][1], p[2][2]};
}

/// The figures over every fill, then "holes": one entry per fill, sorted by its key.
void print_rim(const std::vector<RimFigures>& all) {
    const auto one = [](const RimFigures& r) {
        std::printf("\"rim_bend_deg\": %.2f, \"near_bend_deg\": %.2f, \"rim_jump_deg\": %.2f",
                    r.rim, r.near, std::abs(r.rim - r.near));
    };
    one(all[0]);
    std::printf(", \"holes\": [");
    for (std::size_t i = 1; i < all.size(); ++i) {
        std::printf("%s{\"key\": [%.9g, %.9g, %.9g], ", i > 1 ? ", " : "", all[i].key[0],
                    all[i].key[1], all[i].key[2]);
        one(all[i]);
        std::printf("}");
    }
    std::printf("]");
}

int compare_rim(const char* original, const char* filled) {
    Mesh a, b;
    if (!PMP::IO::read_polygon_mesh(original, a) || !PMP::IO::read_polygon_mesh(filled, b)) {
        std::fprintf(stderr, "cgal_fill_holes: cannot read %s or %s\n", original, filled);
        return 1;
    }
    std::set<std::array<double, 9>> old;
    for (Face f : a.faces()) old.insert(corner_key(a, f));
    std::vector<char> is_new(b.number_of_faces() + b.number_of_removed_faces(), 0);
    std::size_t n_new = 0;
    for (Face f : b.faces()) n_new += (is_new[f] = !old.count(corner_key(b, f))) ? 1 : 0;
    std::printf("{\"new_faces\": %zu, ", n_new);
    print_rim(rim_figures(b, is_new));
    std::printf("}\n");
    return 0;
}

struct Run {
    double ms = 0, min_angle = 180;
    std::size_t loops = 0, filled = 0, faces = 0, vertices = 0;
    bool closed = false;
    std::vector<RimFigures> rim;
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
    std::vector<char> is_new(m.number_of_faces() + m.number_of_removed_faces(), 0);
    for (Face f : faces) is_new[f] = 1;
    r.rim = rim_figures(m, is_new);
    return r;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc == 4 && std::string(argv[1]) == "--rim") return compare_rim(argv[2], argv[3]);
    if (argc < 2) {
        std::fprintf(stderr, "usage: cgal_fill_holes IN [RUNS] | --rim ORIGINAL FILLED\n");
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
        "\"vertices_added\": %zu, \"min_new_angle_deg\": %.2f, ",
        last.loops, last.filled, ms[ms.size() / 2], last.closed ? "true" : "false", last.faces,
        last.vertices, last.min_angle);
    print_rim(last.rim);
    std::printf("}\n");
    return 0;
}
