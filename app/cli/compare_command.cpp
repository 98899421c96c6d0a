// `trilab-cli compare A B`: the sampled two-sided Hausdorff and RMS distances between two
// meshes, absolute and relative to A's bounding-box diagonal; the mean and largest distance of
// B's vertices to A's surface; and, for two states of one mesh (the same connectivity), the
// face-normal deviation θ and the share of flipped faces. --region restricts the vertex and
// face figures to a region of A.
#include "app/cli/compare_command.h"

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <limits>
#include <optional>

#include "app/cli/arg_reader.h"
#include "app/cli/json_writer.h"
#include "app/cli/region_option.h"
#include "core/algorithms/mesh_distance.h"
#include "core/algorithms/region_subdivision.h"
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
  --region SPEC         measure the region's part only (SPEC as for --region of the
                        operations, made on A; B takes A's weights where it has A's vertex
                        count, the result of an operation on a region, else the SPEC on B):
                        the faces whose three vertices weigh > 0 are sampled, each sample
                        still against the other mesh's whole surface; the vertex distances
                        count B's vertices of weight > 0 and theta the faces whose three
                        corners have one. With the same vertex count it also reports the
                        displacements inside and outside the region: "moved_vertices",
                        "max_displacement_inside", "mean_displacement_moved" (over the moved
                        vertices), "max_displacement_outside", "outside_identical" (bit for bit)
  --json                one JSON object: "hausdorff", "rms", "a_to_b_max", "a_to_b_rms",
                        "b_to_a_max", "b_to_a_rms", "diagonal" (A's bounding box),
                        "hausdorff_relative", "rms_relative", "samples",
                        "vertex_distance_mean", "vertex_distance_max",
                        "vertex_distance_mean_relative" (over the diagonal),
                        "measured_vertices", "same_connectivity"; with the same
                        connectivity "theta_mean", "theta_max" (degrees), "compared_faces",
                        "flipped_faces", "flipped_share", "degenerate_faces"; with --region
                        "region", "region_vertices", "region_faces_a", "region_faces_b" and,
                        with the same connectivity, "region_faces" (the faces theta compares);
                        "ms"
)";

/// What --region adds: the region's sizes and, with A's vertex count, the displacements.
struct RegionComparison {
    Selection weights_a, weights_b;
    std::vector<std::uint8_t> faces_a, faces_b;
    std::size_t region_vertices = 0, faces_in_a = 0, faces_in_b = 0;
    bool same_vertices = false;
    std::size_t moved = 0;
    double max_inside = 0, mean_moved = 0, max_outside = 0;
    bool outside_identical = true;
};

std::size_t count_flags(const std::vector<std::uint8_t>& flags) {
    std::size_t n = 0;
    for (std::uint8_t f : flags) n += f ? 1 : 0;
    return n;
}

/// The region's faces on A and B and, where B has A's vertex count, the displacement of every
/// vertex inside and outside the region.
RegionComparison compare_region(const HalfedgeMesh& a, const HalfedgeMesh& b,
                                const RegionSpec& spec) {
    RegionComparison r;
    r.weights_a = make_region(a, spec);
    r.same_vertices = a.vertices_size() == b.vertices_size();
    r.weights_b = r.same_vertices ? r.weights_a : make_region(b, spec);
    r.region_vertices = count_selected(r.weights_a);
    r.faces_a = region_faces(a, r.weights_a);
    r.faces_b = region_faces(b, r.weights_b);
    r.faces_in_a = count_flags(r.faces_a);
    r.faces_in_b = count_flags(r.faces_b);
    if (r.faces_in_a == 0 || r.faces_in_b == 0)
        throw InvalidArgument("--region " + spec.text + ": the region holds no face of " +
                              (r.faces_in_a == 0 ? "A" : "B") + " (" +
                              std::to_string(r.region_vertices) +
                              " vertices of A selected; a face is in it when its three "
                              "vertices are)");
    if (!r.same_vertices) return r;
    double sum = 0;
    for (Vertex v : a.vertices()) {
        const Point& p = a.position(v);
        const Point& q = b.position(v);
        const double d = (p - q).norm();
        if (r.weights_a[v.idx()] > 0) {
            r.max_inside = std::max(r.max_inside, d);
            if (d > 0) ++r.moved, sum += d;
        } else {
            r.max_outside = std::max(r.max_outside, d);
            if (std::memcmp(p.data(), q.data(), sizeof(double) * 3) != 0)
                r.outside_identical = false;
        }
    }
    r.mean_moved = r.moved ? sum / double(r.moved) : 0;
    return r;
}

void add_region_json(JsonObject& j, const RegionSpec& spec, const RegionComparison& r) {
    j.add("region", spec.text).add("region_vertices", r.region_vertices);
    j.add("region_faces_a", r.faces_in_a).add("region_faces_b", r.faces_in_b);
    if (!r.same_vertices) return;
    j.add("moved_vertices", r.moved).add("max_displacement_inside", r.max_inside);
    j.add("mean_displacement_moved", r.mean_moved);
    j.add("max_displacement_outside", r.max_outside).add("outside_identical", r.outside_identical);
}

void print_region(const RegionSpec& spec, const RegionComparison& r) {
    std::printf("region:    %s: %zu vertices of A, %zu faces of A, %zu of B sampled\n",
                spec.text.c_str(), r.region_vertices, r.faces_in_a, r.faces_in_b);
    if (!r.same_vertices) return;
    std::printf(
        "moved:     %zu vertices inside, largest %.6g, mean %.6g over them; outside largest "
        "%.6g (%s)\n",
        r.moved, r.max_inside, r.mean_moved, r.max_outside,
        r.outside_identical ? "bit for bit the same" : "the outside moved");
}

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
                const std::optional<NormalDeviation>& nd, const RegionComparison& rc, double ms) {
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
    if (args.region) add_region_json(j, *args.region, rc);
    if (args.region && nd) j.add("region_faces", nd->faces);
    j.add("ms", ms);
    std::cout << j.str() << "\n";
}

void print_text(const CompareArgs& args, const MeshDistance& d, const VertexFigures& vf,
                const std::optional<NormalDeviation>& nd, const RegionComparison& rc, double ms) {
    const bool region = args.region.has_value();
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
    if (region) print_region(*args.region, rc);
}

}  // namespace

int run_compare_command(const std::vector<std::string>& args) {
    CompareArgs a = parse_compare_args(args);
    if (a.help) {
        std::fputs(kCompareUsage, stdout);
        return 0;
    }
    if (a.files.size() != 2)
        throw InvalidArgument("expected two mesh files A and B (see `trilab-cli compare --help`)");
    const LoadedMesh ma = read_mesh(a.files[0]);
    const LoadedMesh mb = read_mesh(a.files[1]);
    const bool same = same_connectivity(ma.mesh, mb.mesh);
    RegionComparison rc;
    if (a.region) {
        rc = compare_region(ma.mesh, mb.mesh, *a.region);
        a.options.a_faces = &rc.faces_a;
        a.options.b_faces = &rc.faces_b;
    }
    const auto t0 = std::chrono::steady_clock::now();
    const MeshDistance d = mesh_distance(ma.mesh, mb.mesh, a.options);
    const VertexFigures vf = vertex_figures(ma.mesh, mb.mesh, a.region ? &rc.weights_b : nullptr);
    std::optional<NormalDeviation> nd;
    if (same) nd = normal_deviation(ma.mesh, mb.mesh, a.region ? &rc.weights_a : nullptr);
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    if (a.json)
        print_json(a, d, vf, nd, rc, ms);
    else
        print_text(a, d, vf, nd, rc, ms);
    return 0;
}

}  // namespace trilab::cli
