#include "core/algorithms/generators.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "core/errors.h"
#include "core/mesh_builder.h"

namespace trilab {

namespace {
constexpr double kPi = 3.14159265358979323846;

HalfedgeMesh from_soup(const PolygonSoup& soup) {
    LoadReport report;
    return build_mesh(soup, report);
}

PolygonSoup soup_of(std::vector<Point> positions, const std::vector<std::vector<Index>>& faces) {
    PolygonSoup soup;
    soup.positions = std::move(positions);
    for (const auto& f : faces) soup.add_face(f);
    return soup;
}

const std::vector<Point>& icosahedron_points() {
    static const std::vector<Point> pts = [] {
        const double t = (1.0 + std::sqrt(5.0)) / 2.0;
        std::vector<Point> p = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
                                {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
                                {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
        for (Point& x : p) x.normalize();
        return p;
    }();
    return pts;
}
const std::vector<std::vector<Index>>& icosahedron_faces() {
    static const std::vector<std::vector<Index>> f = {
        {0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
        {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
        {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
    return f;
}
}  // namespace

HalfedgeMesh make_tetrahedron() {
    return from_soup(soup_of({{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}},
                             {{0, 1, 2}, {0, 2, 3}, {0, 3, 1}, {1, 3, 2}}));
}

HalfedgeMesh make_octahedron() {
    return from_soup(soup_of(
        {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}},
        {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}}));
}

HalfedgeMesh make_icosahedron() {
    return from_soup(soup_of(icosahedron_points(), icosahedron_faces()));
}

HalfedgeMesh make_cube() {
    return from_soup(soup_of(
        {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}},
        {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}}));
}

HalfedgeMesh make_icosphere(unsigned frequency) {
    if (frequency < 1) throw InvalidArgument("make_icosphere: frequency must be at least 1");
    const auto& ico = icosahedron_points();
    PolygonSoup soup;
    // A point is identified by its barycentric weights over the icosahedron's vertices, so
    // points on shared edges and corners are created once.
    std::map<std::array<Index, 6>, Index> ids;
    auto point = [&](const std::array<Index, 3>& v, Index a, Index b, Index c) {
        auto entry = [](Index vertex, Index weight) {
            return std::make_pair(weight ? vertex : kInvalidIndex, weight);
        };
        std::array<std::pair<Index, Index>, 3> w = {entry(v[0], a), entry(v[1], b), entry(v[2], c)};
        std::sort(w.begin(), w.end());
        std::array<Index, 6> key{};
        for (int k = 0; k < 3; ++k) {
            key[2 * k] = w[k].first;
            key[2 * k + 1] = w[k].second;
        }
        auto [it, inserted] = ids.emplace(key, Index(soup.positions.size()));
        if (inserted) {
            const Point p =
                (double(a) * ico[v[0]] + double(b) * ico[v[1]] + double(c) * ico[v[2]]) /
                double(frequency);
            soup.positions.push_back(p.normalized());
        }
        return it->second;
    };
    const Index n = frequency;
    for (const auto& f : icosahedron_faces()) {
        const std::array<Index, 3> v = {f[0], f[1], f[2]};
        // Row i, column j: weights (n - i - j, i, j) on (v0, v1, v2).
        for (Index i = 0; i < n; ++i) {
            for (Index j = 0; i + j < n; ++j) {
                const Index p0 = point(v, n - i - j, i, j);
                const Index p1 = point(v, n - i - j - 1, i + 1, j);
                const Index p2 = point(v, n - i - j - 1, i, j + 1);
                soup.add_face({p0, p1, p2});
                if (i + j + 2 <= n) {
                    const Index p3 = point(v, n - i - j - 2, i + 1, j + 1);
                    soup.add_face({p1, p3, p2});
                }
            }
        }
    }
    return from_soup(soup);
}

HalfedgeMesh make_noisy_sphere(unsigned frequency, double amplitude, std::uint32_t seed) {
    HalfedgeMesh mesh = make_icosphere(frequency);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> offset(-amplitude, amplitude);
    for (Vertex v : mesh.vertices()) mesh.position(v) *= 1.0 + offset(rng);
    return mesh;
}

HalfedgeMesh make_torus(unsigned nu, unsigned nv, double R, double r) {
    if (nu < 3 || nv < 3) throw InvalidArgument("make_torus: need at least 3 x 3 segments");
    PolygonSoup soup;
    soup.positions.reserve(std::size_t(nu) * nv);
    soup.corners.reserve(std::size_t(nu) * nv * 6);
    soup.face_offsets.reserve(std::size_t(nu) * nv * 2 + 1);
    for (unsigned i = 0; i < nu; ++i) {
        const double u = 2 * kPi * i / nu;
        for (unsigned j = 0; j < nv; ++j) {
            const double w = 2 * kPi * j / nv;
            soup.positions.emplace_back((R + r * std::cos(w)) * std::cos(u),
                                        (R + r * std::cos(w)) * std::sin(u), r * std::sin(w));
        }
    }
    auto id = [&](unsigned i, unsigned j) { return Index((i % nu) * nv + (j % nv)); };
    for (unsigned i = 0; i < nu; ++i) {
        for (unsigned j = 0; j < nv; ++j) {
            soup.add_face({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
            soup.add_face({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
        }
    }
    return from_soup(soup);
}

HalfedgeMesh make_grid(unsigned n) {
    if (n < 1) throw InvalidArgument("make_grid: n must be at least 1");
    PolygonSoup soup;
    for (unsigned j = 0; j <= n; ++j)
        for (unsigned i = 0; i <= n; ++i)
            soup.positions.emplace_back(double(i) / n, double(j) / n, 0);
    auto id = [&](unsigned i, unsigned j) { return Index(j * (n + 1) + i); };
    for (unsigned j = 0; j < n; ++j) {
        for (unsigned i = 0; i < n; ++i) {
            soup.add_face({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
            soup.add_face({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
        }
    }
    return from_soup(soup);
}

HalfedgeMesh make_block(unsigned nx, unsigned ny, unsigned nz) {
    const unsigned n[3] = {nx, ny, nz};
    for (unsigned c : n)
        if (c < 1 || c > 1000)
            throw InvalidArgument("make_block: the cell counts must be from 1 to 1000, got " +
                                  std::to_string(nx) + " x " + std::to_string(ny) + " x " +
                                  std::to_string(nz));
    const double h = 2.0 / double(std::max({nx, ny, nz}));
    // One vertex per lattice point on the surface, numbered through a full lattice table.
    std::vector<Index> id(std::size_t(nx + 1) * (ny + 1) * (nz + 1), kInvalidIndex);
    PolygonSoup soup;
    const auto vertex = [&](unsigned i, unsigned j, unsigned k) {
        Index& slot = id[(std::size_t(k) * (ny + 1) + j) * (nx + 1) + i];
        if (slot == kInvalidIndex) {
            slot = Index(soup.positions.size());
            soup.positions.emplace_back((double(i) - 0.5 * nx) * h, (double(j) - 0.5 * ny) * h,
                                        (double(k) - 0.5 * nz) * h);
        }
        return slot;
    };
    const auto at = [&](unsigned a, unsigned side, unsigned b, unsigned u, unsigned c, unsigned v) {
        unsigned p[3];
        p[a] = side;
        p[b] = u;
        p[c] = v;
        return vertex(p[0], p[1], p[2]);
    };
    for (unsigned a = 0; a < 3; ++a) {
        const unsigned b = (a + 1) % 3, c = (a + 2) % 3;  // e_b x e_c = e_a
        for (unsigned side : {0u, n[a]})
            for (unsigned u = 0; u < n[b]; ++u)
                for (unsigned v = 0; v < n[c]; ++v) {
                    Index q[4] = {at(a, side, b, u, c, v), at(a, side, b, u + 1, c, v),
                                  at(a, side, b, u + 1, c, v + 1), at(a, side, b, u, c, v + 1)};
                    if (side == 0) std::swap(q[1], q[3]);  // outward: -e_a
                    if ((u + v) % 2 == 0) {
                        soup.add_face({q[0], q[1], q[2]});
                        soup.add_face({q[0], q[2], q[3]});
                    } else {
                        soup.add_face({q[0], q[1], q[3]});
                        soup.add_face({q[1], q[2], q[3]});
                    }
                }
    }
    return from_soup(soup);
}

HalfedgeMesh make_cylinder(unsigned segments, unsigned rings) {
    if (segments < 3 || rings < 1)
        throw InvalidArgument("make_cylinder: need at least 3 segments and 1 ring");
    PolygonSoup soup;
    for (unsigned k = 0; k <= rings; ++k)
        for (unsigned i = 0; i < segments; ++i) {
            const double a = 2 * kPi * i / segments;
            soup.positions.emplace_back(std::cos(a), std::sin(a), double(k) / rings * 2.0 - 1.0);
        }
    auto id = [&](unsigned i, unsigned k) { return Index(k * segments + i % segments); };
    for (unsigned k = 0; k < rings; ++k)
        for (unsigned i = 0; i < segments; ++i) {
            soup.add_face({id(i, k), id(i + 1, k), id(i + 1, k + 1)});
            soup.add_face({id(i, k), id(i + 1, k + 1), id(i, k + 1)});
        }
    return from_soup(soup);
}

HalfedgeMesh make_default_model() {
    return make_noisy_sphere(10, 0.03, 1);
}

std::vector<std::string> generator_names() {
    return {"default", "sphere", "noisy-sphere", "tetrahedron", "octahedron", "icosahedron",
            "cube",    "torus",  "grid",         "cylinder",    "block"};
}

HalfedgeMesh generate(const std::string& name) {
    if (name == "default" || name == "noisy-sphere") return make_default_model();
    if (name == "sphere") return make_icosphere(10);
    if (name == "tetrahedron") return make_tetrahedron();
    if (name == "octahedron") return make_octahedron();
    if (name == "icosahedron") return make_icosahedron();
    if (name == "cube") return make_cube();
    if (name == "torus") return make_torus(48, 24, 1.0, 0.35);
    if (name == "grid") return make_grid(16);
    if (name == "cylinder") return make_cylinder(32, 8);
    if (name == "block") return make_block(24, 18, 12);
    std::string list;
    for (const auto& n : generator_names()) list += (list.empty() ? "" : ", ") + n;
    throw InvalidArgument("generate: unknown model '" + name + "' (known: " + list + ")");
}

}  // namespace trilab
