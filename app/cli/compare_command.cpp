// `trilab-cli compare A B`: the sampled two-sided Hausdorff and RMS distances between two
// meshes, absolute and relative to A's bounding-box diagonal; the mean and largest distance of
// B's vertices to A's surface; and, for two states of one mesh (the same connectivity), the
// face-normal deviation θ and the share of flipped faces. --region restricts the vertex and
// face figures to a region of A.
#include "app/cli/compare_command.h"

#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>
#include <optional>

#include "app/cli/arg_reader.h"
#include "app/cli/json_writer.h"
#include "app/cli/region_option.h"
#include "core/algorithms/mesh_distance.h"
#include "core/errors.h"
#include "core/geometry.h"
#include "core/io/mesh_io.h"

namespace trilab::cli {
namespace {

constexpr const char* kCompareUsage =
    R"(usage: trilab-cli compare A B [--samples N] [--region SPEC] [--json]

Measures how far the surfaces of A and B are apart: every vertex plus N area-weighted
samples on each mesh (deterministic), each against the other mesh's closest point; and
every vertex of B against A's surface (A the reference, B the result: a denoised or
smoothed copy). When A and B have the same connectivity (two states of one mesh), also
the angle between the two normals of every face: theta, its mean and maximum, and the
faces flipped (more than 90 degrees apart).

options:
  --samples N           face samples per mesh, 1 to 100000000 (default 200000)
  --region SPEC         restrict the vertex distances to the vertices of weight > 0 and
                        theta to the faces whose three corners have weight > 0 (SPEC as for
                        the operations: sphere:X,Y,Z,R[,F], geodesic:V,R[,F], component:V,
                        file:PATH; made on A); A and B must have the same connectivity; the
                        Hausdorff and RMS figures stay the whole meshes'
  --json                one JSON object: "hausdorff", "rms", "a_to_b_max", "a_to_b_rms",
                        "b_to_a_max", "b_to_a_rms", "diagonal" (A's bounding box),
                        "hausdorff_relative", "rms_relative", "samples",
                        "vertex_distance_mean", "vertex_distance_max",
                        "vertex_distance_mean_relative" (over the diagonal),
                        "measured_vertices", "same_connectivity"; with the same
                        connectivity "theta_mean", "theta_max" (degrees), "compared_faces",
                        "flipped_faces", "flipped_share", "degenerate_faces"; with --region
                        "region_vertices", "region_faces"; "ms"
)";

struct CompareArgs {
    std::vector<std::string> files;
    bool json = false, help = false;
    MeshDistanceOptions options;
    std::optional<RegionSpec> region;
};

CompareArgs parse_compare_args(const std::vector<std::string>& args) {
    CompareArgs a;
    ArgReader reader(args, "compare");
    while (reader.next()) {
        if (reader.is_help()) {
            a.help = true;
        } else if (reader.is("--json")) {
            a.json = reader.flag();
        } else if (reader.is("--region")) {
            a.region = parse_region_spec(reader.value());
        } else if (reader.is("--samples")) {
            const std::string text = reader.has_value() ? reader.value() : std::string();
            unsigned long long n = 0;
            const char* end = text.data() + text.size();
            const auto [ptr, ec] = std::from_chars(text.data(), end, n);
            if (text.empty() || ec != std::errc() || ptr != end || n < 1 || n > 100000000ull)
                throw InvalidArgument(
                    "--samples: expected a whole number from 1 to 100000000, "
                    "got '" +
                    text + "'");
            a.options.samples = std::size_t(n);
        } else if (reader.is_option()) {
            reader.refuse_unknown();
        } else {
            a.files.push_back(reader.arg());
        }
    }
    return a;
}

/// The figures beyond the sampled distances.
struct VertexFigures {
    double mean = 0, max = 0;
    std::size_t measured = 0;
};

VertexFigures vertex_figures(const HalfedgeMesh& a, const HalfedgeMesh& b,
                             const Selection* region) {
    const std::vector<double> d = vertex_surface_distances(b, a);
    VertexFigures f;
    double sum = 0;
    for (std::size_t v = 0; v < d.size(); ++v) {
        if (std::isnan(d[v]) || (region && !((*region)[v] > 0.0f))) continue;
        sum += d[v];
        f.max = std::max(f.max, d[v]);
        ++f.measured;
    }
    f.mean = f.measured ? sum / double(f.measured) : 0.0;
    return f;
}

void print_json(const CompareArgs& args, const MeshDistance& d, const VertexFigures& vf,
                const std::optional<NormalDeviation>& nd, const Selection* region, double ms) {
    const double diag = d.diagonal > 0 ? d.diagonal : 1.0;
    JsonObject j;
    j.add("a", args.files[0])
        .add("b", args.files[1])
        .add("hausdorff", d.hausdorff)
        .add("rms", d.rms)
        .add("a_to_b_max", d.a_to_b_max)
        .add("a_to_b_rms", d.a_to_b_rms)
        .add("b_to_a_max", d.b_to_a_max)
        .add("b_to_a_rms", d.b_to_a_rms)
        .add("diagonal", d.diagonal)
        .add("hausdorff_relative", d.hausdorff / diag)
        .add("rms_relative", d.rms / diag)
        .add("samples", d.samples)
        .add("vertex_distance_mean", vf.mean)
        .add("vertex_distance_max", vf.max)
        .add("vertex_distance_mean_relative", vf.mean / diag)
        .add("measured_vertices", vf.measured)
        .add("same_connectivity", nd.has_value());
    if (nd)
        j.add("theta_mean", nd->mean_degrees)
            .add("theta_max", nd->max_degrees)
            .add("compared_faces", nd->faces)
            .add("flipped_faces", nd->flipped)
            .add("flipped_share", nd->flipped_share())
            .add("degenerate_faces", nd->degenerate);
    if (region && nd)
        j.add("region_vertices", count_selected(*region)).add("region_faces", nd->faces);
    j.add("ms", ms);
    std::cout << j.str() << "\n";
}

void print_text(const MeshDistance& d, const VertexFigures& vf,
                const std::optional<NormalDeviation>& nd, const Selection* region, double ms) {
    const double diag = d.diagonal > 0 ? d.diagonal : 1.0;
    std::printf("Hausdorff: %.6g (%.4f%% of the diagonal)\n", d.hausdorff,
                100 * d.hausdorff / diag);
    std::printf("RMS:       %.6g (%.4f%% of the diagonal)\n", d.rms, 100 * d.rms / diag);
    std::printf("A -> B:    max %.6g, RMS %.6g\n", d.a_to_b_max, d.a_to_b_rms);
    std::printf("B -> A:    max %.6g, RMS %.6g\n", d.b_to_a_max, d.b_to_a_rms);
    std::printf(
        "vertices of B to A's surface%s: mean %.6g (%.4f%% of the diagonal), max %.6g, "
        "%zu vertices\n",
        region ? " (region)" : "", vf.mean, 100 * vf.mean / diag, vf.max, vf.measured);
    if (nd) {
        std::printf(
            "face normals%s: theta mean %.4g deg, max %.4g deg over %zu faces; "
            "flipped (> 90 deg) %zu (%.3f%%)",
            region ? " (region)" : "", nd->mean_degrees, nd->max_degrees, nd->faces, nd->flipped,
            100 * nd->flipped_share());
        if (nd->degenerate) std::printf("; %zu degenerate faces left out", nd->degenerate);
        std::printf("\n");
    } else {
        std::printf("face normals: not compared (A and B differ in connectivity)\n");
    }
    std::printf("samples:   %zu, diagonal of A %.6g (%.1f ms)\n", d.samples, d.diagonal, ms);
}

}  // namespace

int run_compare_command(const std::vector<std::string>& args) {
    const CompareArgs a = parse_compare_args(args);
    if (a.help) {
        std::fputs(kCompareUsage, stdout);
        return 0;
    }
    if (a.files.size() != 2)
        throw InvalidArgument("expected two mesh files A and B (see `trilab-cli compare --help`)");
    const LoadedMesh ma = read_mesh(a.files[0]);
    const LoadedMesh mb = read_mesh(a.files[1]);
    const bool same = same_connectivity(ma.mesh, mb.mesh);
    Selection region;
    if (a.region) {
        if (!same)
            throw InvalidArgument("--region: A and B must have the same connectivity (" +
                                  std::to_string(ma.mesh.n_faces()) + " and " +
                                  std::to_string(mb.mesh.n_faces()) + " faces)");
        region = make_region(ma.mesh, *a.region);
    }
    const Selection* r = a.region ? &region : nullptr;
    const auto t0 = std::chrono::steady_clock::now();
    const MeshDistance d = mesh_distance(ma.mesh, mb.mesh, a.options);
    const VertexFigures vf = vertex_figures(ma.mesh, mb.mesh, r);
    std::optional<NormalDeviation> nd;
    if (same) nd = normal_deviation(ma.mesh, mb.mesh, r);
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    if (a.json)
        print_json(a, d, vf, nd, r, ms);
    else
        print_text(d, vf, nd, r, ms);
    return 0;
}

}  // namespace trilab::cli
