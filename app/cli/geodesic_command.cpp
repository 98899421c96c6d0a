// `trilab-cli geodesic IN OUT --from N[,N...] [--to M]`: the geodesic distance of every vertex
// from the nearest source (heat method), stored as the "v:distance" scalar (PLY property
// `distance`), and with --to the distance to M and the traced path's points.
#include "app/cli/geodesic_command.h"

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>

#include "app/cli/arg_reader.h"
#include "app/cli/json_writer.h"
#include "app/cli/write_options.h"
#include "core/algorithms/geodesic.h"
#include "core/errors.h"
#include "core/io/mesh_io.h"

namespace trilab::cli {
namespace {

constexpr const char* kGeodesicUsage =
    R"(usage: trilab-cli geodesic IN OUT --from N[,N...] [--to M] [--json]

Geodesic distances on the surface by the heat method (Crane, Weischedel, Wardetzky 2013) from
the nearest of the source vertices N, written to OUT as the per-vertex property `distance`
(PLY; other formats drop it). Vertices no source reaches (another connected component, an
isolated vertex) are written with distance -1.

options:
  --from N[,N...]       source vertex indices (required)
  --to M                also trace the geodesic path from vertex M down to a source
  --json                one JSON object: "vertices", "sources", "ms" (the solve),
                        "max_distance", "unreached"; with --to "distance_to",
                        "path_points", "path_vertices" (the points on vertices; the
                        others cross edges), "path_length"
)";

/// A vertex index of option `option` ("--from", "--to").
Index parse_index(const std::string& text, const char* option) {
    unsigned long long n = 0;
    const char* end = text.data() + text.size();
    const auto [ptr, ec] = std::from_chars(text.data(), end, n);
    if (text.empty() || ec != std::errc() || ptr != end || n >= kInvalidIndex)
        throw InvalidArgument(std::string(option) + ": expected a vertex index, got '" + text +
                              "'");
    return Index(n);
}

void check_vertex(const HalfedgeMesh& mesh, Index i, const char* option) {
    if (i >= mesh.vertices_size())
        throw InvalidArgument(std::string(option) + ": vertex " + std::to_string(i) +
                              " is out of range (the mesh has " +
                              std::to_string(mesh.vertices_size()) + " vertices)");
    if (mesh.is_deleted(Vertex(i)))
        throw InvalidArgument(std::string(option) + ": vertex " + std::to_string(i) +
                              " is deleted");
}

}  // namespace

int run_geodesic_command(const std::vector<std::string>& args) {
    std::vector<std::string> files;
    std::vector<Index> from;
    Index to = kInvalidIndex;
    bool json = false, help = false, has_from = false;
    WriteOptions write;
    ArgReader reader(args, "geodesic");
    while (reader.next()) {
        if (reader.is_help()) {
            help = true;
        } else if (reader.is("--json")) {
            json = reader.flag();
        } else if (reader.is("--from")) {
            const std::string text = reader.has_value() ? reader.value() : std::string();
            has_from = true;
            std::size_t start = 0;
            while (true) {
                const std::size_t comma = text.find(',', start);
                from.push_back(parse_index(text.substr(start, comma - start), "--from"));
                if (comma == std::string::npos) break;
                start = comma + 1;
            }
        } else if (reader.is("--to")) {
            to = parse_index(reader.has_value() ? reader.value() : std::string(), "--to");
        } else if (take_write_option(reader, write)) {
        } else if (reader.is_option()) {
            reader.refuse_unknown();
        } else {
            files.push_back(reader.arg());
        }
    }
    if (help) {
        std::fputs(kGeodesicUsage, stdout);
        return 0;
    }
    if (files.size() != 2)
        throw InvalidArgument("expected IN and OUT (see `trilab-cli geodesic --help`)");
    if (!has_from) throw InvalidArgument("--from: required (the source vertex indices)");
    LoadedMesh in = read_mesh(files[0]);
    HalfedgeMesh& mesh = in.mesh;
    std::vector<Vertex> sources;
    for (Index i : from) {
        check_vertex(mesh, i, "--from");
        sources.push_back(Vertex(i));
    }
    if (to != kInvalidIndex) check_vertex(mesh, to, "--to");

    const auto t0 = std::chrono::steady_clock::now();
    const std::vector<double> d = geodesic_distances(mesh, sources);
    std::vector<SurfacePoint> path;
    if (to != kInvalidIndex && std::isfinite(d[to])) path = geodesic_path(mesh, d, Vertex(to));
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();

    double max_distance = 0;
    std::size_t unreached = 0;
    auto out = mesh.vertex_property<double>("v:distance");
    for (Vertex v : mesh.vertices()) {
        const double x = d[v.idx()];
        if (std::isfinite(x)) {
            max_distance = std::max(max_distance, x);
            out[v] = x;
        } else {
            ++unreached;
            out[v] = -1.0;
        }
    }
    write_mesh(mesh, files[1], write);  // not timed

    if (json) {
        JsonObject j;
        j.add("in", files[0])
            .add("out", files[1])
            .add("vertices", mesh.n_vertices())
            .add("sources", sources.size())
            .add("ms", ms)
            .add("max_distance", max_distance)
            .add("unreached", unreached);
        if (to != kInvalidIndex) {
            if (std::isfinite(d[to]))
                j.add("distance_to", d[to]);
            else
                j.add("distance_to", -1.0);
            // The path's points: on vertices (path_vertices) or crossing edges.
            const std::size_t on_vertices = std::size_t(std::count_if(
                path.begin(), path.end(), [](const SurfacePoint& p) { return p.on_vertex(); }));
            j.add("path_points", path.size())
                .add("path_vertices", on_vertices)
                .add("path_length", path_length(path));
        }
        std::cout << j.str() << "\n";
    } else {
        std::printf("geodesic: %zu sources, max distance %.6g, %zu unreached (%.1f ms)\n",
                    sources.size(), max_distance, unreached, ms);
        if (to != kInvalidIndex) {
            if (std::isfinite(d[to]))
                std::printf("to %u: distance %.6g, path of %zu points, length %.6g\n", unsigned(to),
                            d[to], path.size(), path_length(path));
            else
                std::printf("to %u: not reached from the sources\n", unsigned(to));
        }
    }
    return 0;
}

}  // namespace trilab::cli
