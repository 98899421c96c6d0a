// libFuzzer target: the polygon-soup builder (the repairs every reader relies on) and the
// subdivision schemes on whatever it builds. The bytes encode a soup: byte 0 gives the vertex
// count (1 to 32), then three bytes per vertex give small integer coordinates (-2 to 2, so
// coincident and collinear points are common), then each face is a corner count (0 to 5)
// followed by that many vertex indices. The built mesh and every subdivision level must pass
// validate() and have finite positions; a trilab::Error with a message is a clean refusal.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "core/algorithms/subdivision.h"
#include "core/errors.h"
#include "core/mesh_builder.h"
#include "core/progress.h"
#include "core/validate.h"

namespace {

void require_valid(const trilab::HalfedgeMesh& mesh, const char* what) {
    const trilab::ValidationResult r = trilab::validate(mesh);
    if (!r.ok) {
        std::fprintf(stderr, "%s: invalid mesh: %s\n", what, r.message.c_str());
        std::abort();
    }
    for (trilab::Vertex v : mesh.vertices()) {
        const trilab::Point& p = mesh.position(v);
        if (!std::isfinite(p.x()) || !std::isfinite(p.y()) || !std::isfinite(p.z())) {
            std::fprintf(stderr, "%s: non-finite position\n", what);
            std::abort();
        }
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size == 0) return 0;
    std::size_t at = 0;
    auto next = [&]() -> unsigned { return at < size ? data[at++] : 0u; };
    trilab::PolygonSoup soup;
    const unsigned nv = 1 + next() % 32;
    for (unsigned i = 0; i < nv; ++i) {
        const double x = double(int(next() % 5) - 2), y = double(int(next() % 5) - 2),
                     z = double(int(next() % 5) - 2);
        soup.positions.emplace_back(x, y, z);
    }
    while (at < size && soup.n_faces() < 64) {
        const unsigned corners = next() % 6;
        std::vector<trilab::Index> face;
        for (unsigned k = 0; k < corners; ++k) face.push_back(trilab::Index(next() % nv));
        soup.add_face(face);
    }
    trilab::LoadReport report;
    trilab::HalfedgeMesh mesh;
    try {
        mesh = trilab::build_mesh(soup, report);
    } catch (const trilab::Error& e) {
        std::fprintf(stderr, "the builder refused a soup of valid indices: %s\n", e.what());
        std::abort();
    }
    require_valid(mesh, "build_mesh");
    trilab::NullProgress progress;
    for (trilab::SubdivisionScheme scheme :
         {trilab::SubdivisionScheme::Loop, trilab::SubdivisionScheme::Sqrt3,
          trilab::SubdivisionScheme::Butterfly, trilab::SubdivisionScheme::ModifiedButterfly}) {
        trilab::SubdivisionOptions options;
        options.scheme = scheme;
        options.iterations = 2;
        try {
            const trilab::SubdivisionResult result = trilab::subdivide(mesh, options, progress);
            for (const trilab::SubdivisionLevel& level : result.levels)
                require_valid(level.mesh, trilab::scheme_name(scheme));
        } catch (const trilab::Error& e) {
            if (std::string(e.what()).empty()) std::abort();
        }
    }
    return 0;
}
