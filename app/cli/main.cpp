// trilab-cli: the viewer's operations, headless. Every command exits 0 on success and
// non-zero with one line on stderr otherwise; --json prints one JSON object on stdout that
// includes "ms", the time spent in the operation itself (file reading/writing excluded).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include "app/cli/compare_command.h"
#include "app/cli/json_writer.h"
#include "app/cli/operation_command.h"
#include "app/cli/record_command.h"
#include "app/cli/render_command.h"
#include "app/ops/operation.h"
#include "app/platform/heap_tuning.h"
#include "core/algorithms/coincident.h"
#include "core/algorithms/generators.h"
#include "core/algorithms/mesh_stats.h"
#include "core/errors.h"
#include "core/io/mesh_io.h"
#include "core/validate.h"

namespace trilab::cli {
namespace {

constexpr const char* kUsage = R"(usage: trilab-cli COMMAND [options]

commands:
  info MESH [--json]              counts, topology, seams, bounding box, area, volume, load report
  convert IN OUT [--ascii] [--big-endian] [--json]
                                  convert between .obj .off .ply .stl .om (by extension);
                                  .stl and .ply are written binary unless --ascii
  generate NAME OUT [--json]      write a built-in model (see `trilab-cli generate --list`)
  render MESH --out FILE.png [options]
                                  render offscreen to a PNG (`trilab-cli render --help`)
  record MESH --op "OP" --out DIR [options]
                                  render an operation's morph to PNG frames (`record --help`)
  compare A B [--samples N] [--json]
                                  sampled Hausdorff and RMS distance between two meshes
  help                            this text

operations (options: `trilab-cli NAME --help`):
)";

/// kUsage, then one line per registered operation, from its declaration.
std::string usage_text() {
    std::string s = kUsage;
    for (const trilab::OperationDef* def : trilab::operation_defs()) {
        std::string head = "  " + def->name + " [options] IN OUT [--json]";
        head.resize(std::max<std::size_t>(head.size() + 1, 34), ' ');
        s += head + def->label + "\n";
    }
    return s;
}

/// Command-line arguments split into positionals and --flags.
struct Args {
    std::vector<std::string> positional;
    std::map<std::string, std::string> flags;
    bool has(const std::string& f) const { return flags.count(f) > 0; }
};

Args parse(int argc, char** argv, int first, const std::vector<std::string>& known_flags) {
    Args a;
    for (int i = first; i < argc; ++i) {
        std::string s = argv[i];
        if (s.rfind("--", 0) == 0) {
            bool ok = false;
            for (const auto& k : known_flags) ok = ok || k == s;
            if (!ok) throw InvalidArgument("unknown option '" + s + "'");
            a.flags[s] = "1";
        } else {
            a.positional.push_back(s);
        }
    }
    return a;
}

double ms_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

JsonObject report_json(const LoadReport& r) {
    JsonObject j;
    j.add("format", r.format)
        .add("file_vertices", r.file_vertices)
        .add("file_faces", r.file_faces)
        .add("polygons_triangulated", r.polygons_triangulated)
        .add("triangles_from_polygons", r.triangles_from_polygons)
        .add("degenerate_faces_dropped", r.degenerate_faces_dropped)
        .add("detached_faces", r.detached_faces)
        .add("nonmanifold_vertices_split", r.nonmanifold_vertices_split)
        .add("vertex_copies_added", r.vertex_copies_added)
        .add("isolated_vertices", r.isolated_vertices)
        .add("merged_vertices", r.merged_vertices)
        .add("notes", r.notes);
    return j;
}

std::vector<double> vec(const Point& p) {
    return {p.x(), p.y(), p.z()};
}

int cmd_info(const Args& a) {
    if (a.positional.size() != 1) throw InvalidArgument("info: expected one MESH file");
    LoadedMesh loaded = read_mesh(a.positional[0]);
    const auto t0 = std::chrono::steady_clock::now();
    const MeshStats s = compute_stats(loaded.mesh);
    const ValidationResult valid = validate(loaded.mesh);
    const BoundaryPairing pairing = pair_boundary_edges(loaded.mesh);
    const double ms = ms_since(t0);
    const LoadReport& r = loaded.report;
    const bool manifold = r.detached_faces == 0 && r.nonmanifold_vertices_split == 0;
    if (a.has("--json")) {
        JsonObject j;
        j.add("file", a.positional[0])
            .add("vertices", s.vertices)
            .add("edges", s.edges)
            .add("faces", s.faces)
            .add("boundary_loops", s.boundary_loops)
            .add("boundary_edges", pairing.boundary_edges)
            .add("paired_boundary_edges", pairing.paired_edges)
            .add("unpaired_boundary_edges", pairing.unpaired_edges)
            .add("components", s.components)
            .add("isolated_vertices", s.isolated_vertices)
            .add("euler", s.euler)
            .add("genus", s.genus)
            .add("manifold", manifold)
            .add("bbox_min", vec(s.bbox.min))
            .add("bbox_max", vec(s.bbox.max))
            .add("area", s.area);
        if (s.volume)
            j.add("volume", *s.volume);
        else
            j.add_null("volume");
        j.add("valid", valid.ok).add("load_report", report_json(r)).add("ms", ms);
        std::cout << j.str() << "\n";
    } else {
        std::printf("file:            %s (%s)\n", a.positional[0].c_str(), r.format.c_str());
        std::printf("vertices:        %zu (%zu isolated)\n", s.vertices, s.isolated_vertices);
        std::printf("edges:           %zu\n", s.edges);
        std::printf("faces:           %zu\n", s.faces);
        std::printf("boundary loops:  %zu\n", s.boundary_loops);
        std::printf(
            "boundary edges:  %zu (%zu on seams: another boundary edge coincides; %zu "
            "unpaired)\n",
            pairing.boundary_edges, pairing.paired_edges, pairing.unpaired_edges);
        std::printf("components:      %zu\n", s.components);
        std::printf("euler:           %lld\n", s.euler);
        std::printf("genus:           %lld\n", s.genus);
        std::printf("manifold input:  %s\n", manifold ? "yes" : "no");
        std::printf("bbox:            [%g %g %g] - [%g %g %g]\n", s.bbox.min.x(), s.bbox.min.y(),
                    s.bbox.min.z(), s.bbox.max.x(), s.bbox.max.y(), s.bbox.max.z());
        std::printf("area:            %.9g\n", s.area);
        if (s.volume)
            std::printf("volume:          %.9g\n", *s.volume);
        else
            std::printf("volume:          (open mesh: not defined)\n");
        std::printf("valid:           %s\n", valid.ok ? "yes" : valid.message.c_str());
        std::printf("load report:\n");
        const auto lines = r.lines();
        if (lines.empty()) std::printf("  clean (nothing repaired)\n");
        for (const auto& l : lines) std::printf("  %s\n", l.c_str());
    }
    return 0;
}

WriteOptions write_options(const Args& a) {
    WriteOptions o;
    o.ascii = a.has("--ascii");
    o.big_endian = a.has("--big-endian");
    return o;
}

int cmd_convert(const Args& a) {
    if (a.positional.size() != 2) throw InvalidArgument("convert: expected IN and OUT files");
    LoadedMesh loaded = read_mesh(a.positional[0]);
    write_mesh(loaded.mesh, a.positional[1], write_options(a));
    if (a.has("--json")) {
        JsonObject j;
        j.add("input", a.positional[0])
            .add("output", a.positional[1])
            .add("vertices", loaded.mesh.n_vertices())
            .add("faces", loaded.mesh.n_faces())
            .add("ms", 0.0);
        std::cout << j.str() << "\n";
    }
    return 0;
}

int cmd_generate(const Args& a) {
    if (a.has("--list")) {
        for (const auto& n : generator_names()) std::cout << n << "\n";
        return 0;
    }
    if (a.positional.size() != 2) throw InvalidArgument("generate: expected NAME and OUT");
    const auto t0 = std::chrono::steady_clock::now();
    HalfedgeMesh mesh = generate(a.positional[0]);
    const double ms = ms_since(t0);
    write_mesh(mesh, a.positional[1], write_options(a));
    if (a.has("--json")) {
        JsonObject j;
        j.add("model", a.positional[0])
            .add("output", a.positional[1])
            .add("vertices", mesh.n_vertices())
            .add("faces", mesh.n_faces())
            .add("ms", ms);
        std::cout << j.str() << "\n";
    }
    return 0;
}

}  // namespace
}  // namespace trilab::cli

int main(int argc, char** argv) {
    using namespace trilab::cli;
    trilab::tune_heap_for_large_meshes();
    if (argc < 2) {
        std::fputs(usage_text().c_str(), stderr);
        return 2;
    }
    const std::string cmd = argv[1];
    try {
        if (cmd == "help" || cmd == "--help" || cmd == "-h") {
            std::fputs(usage_text().c_str(), stdout);
            return 0;
        }
        if (cmd == "info") return cmd_info(parse(argc, argv, 2, {"--json"}));
        if (cmd == "convert")
            return cmd_convert(parse(argc, argv, 2, {"--json", "--ascii", "--big-endian"}));
        if (cmd == "render")
            return run_render_command(std::vector<std::string>(argv + 2, argv + argc));
        for (const std::string& name : trilab::operation_names())
            if (cmd == name) return run_operation_command(name, {argv + 2, argv + argc});
        if (cmd == "compare") return run_compare_command({argv + 2, argv + argc});
        if (cmd == "record") return run_record_command({argv + 2, argv + argc});
        if (cmd == "generate")
            return cmd_generate(
                parse(argc, argv, 2, {"--json", "--ascii", "--big-endian", "--list"}));
        std::fprintf(stderr, "trilab-cli: unknown command '%s' (try `trilab-cli help`)\n",
                     cmd.c_str());
        return 2;
    } catch (const trilab::RunStopped& e) {
        std::fprintf(stderr, "trilab-cli %s: stopped early: %s\n", cmd.c_str(), e.what());
        return 4;
    } catch (const trilab::Error& e) {
        std::fprintf(stderr, "trilab-cli %s: %s\n", cmd.c_str(), e.what());
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "trilab-cli %s: internal error: %s\n", cmd.c_str(), e.what());
        return 3;
    }
}
