// `trilab-cli inspect IN (--vertex N | --edge N | --face N | --point X,Y,Z) [--json]`: the
// inspector's fields (core/algorithms/inspect.h), the same lines the viewer's panel shows.
#include "app/cli/inspect_command.h"

#include <charconv>
#include <chrono>
#include <cstdio>
#include <iostream>

#include "app/cli/arg_reader.h"
#include "app/cli/json_writer.h"
#include "core/algorithms/inspect.h"
#include "core/errors.h"
#include "core/io/mesh_io.h"
#include "core/number_text.h"

namespace trilab::cli {
namespace {

constexpr const char* kInspectUsage =
    R"(usage: trilab-cli inspect IN (--vertex N | --edge N | --face N | --point X,Y,Z) [options] [--json]

Prints what the viewer's inspector shows for one element: for a vertex its position, normal,
valence, boundary and seam status, curvatures (k1, k2, mean, Gaussian, shape index), the length
of its Laplacian under each fairing operator and its subdivision or decimation provenance; for
an edge its length, dihedral angle, cotangent weight, its collapse cost under each decimation
cost and which of the decimator's constraints would refuse its collapse now, with the numbers
that decide it; for a face its area, angles, normal, aspect ratio and component.

options:
  --vertex N            inspect vertex N
  --edge N              inspect edge N
  --face N              inspect face N
  --point X,Y,Z         inspect the face nearest to the point (and name its nearest corner
                        and side)
  --cost quadric|roundness, --normal-flip X|off, --roundness X|off, --independent-set,
  --max-error X         the decimation options an edge is judged under (as `trilab-cli
                        decimate`; defaults: quadric, normal flip 90, roundness off, no limit)
  --json                one JSON object: "element", "index", "ms" and one key per field
                        (a number, an array of numbers, or the text where it has none)
)";

Index parse_index(const std::string& text, const char* option) {
    unsigned long long n = 0;
    const char* end = text.data() + text.size();
    const auto [ptr, ec] = std::from_chars(text.data(), end, n);
    if (text.empty() || ec != std::errc() || ptr != end || n >= kInvalidIndex)
        throw InvalidArgument(std::string(option) + ": expected an index, got '" + text + "'");
    return Index(n);
}

double parse_number(const std::string& text, const char* option) {
    double x = 0;
    const char* end = text.data() + text.size();
    const auto [ptr, ec] = std::from_chars(text.data(), end, x);
    if (text.empty() || ec != std::errc() || ptr != end || !std::isfinite(x))
        throw InvalidArgument(std::string(option) + ": expected a number, got '" + text + "'");
    return x;
}

Point parse_point(const std::string& text) {
    Point p;
    std::size_t start = 0;
    for (int k = 0; k < 3; ++k) {
        const std::size_t comma = text.find(',', start);
        if ((k < 2) != (comma != std::string::npos))
            throw InvalidArgument("--point: expected X,Y,Z (three numbers), got '" + text + "'");
        p[k] = parse_number(text.substr(start, comma - start), "--point");
        start = comma + 1;
    }
    return p;
}

/// Refuses an index that is not a live element, naming the option.
void check_index(Index i, std::size_t size, std::size_t live, bool deleted, const char* option,
                 const char* one, const char* many) {
    if (i >= size)
        throw InvalidArgument(std::string(option) + ": " + one + " " + std::to_string(i) +
                              " is out of range (the mesh has " + count_text(live, one, many) +
                              ")");
    if (deleted)
        throw InvalidArgument(std::string(option) + ": " + one + " " + std::to_string(i) +
                              " is deleted");
}

enum class Kind { None, Vertex, Edge, Face, Point };

/// Refuses an element that the mesh does not have, naming its option.
void check_request(const HalfedgeMesh& mesh, Kind kind, Index index) {
    switch (kind) {
        case Kind::Vertex:
            check_index(index, mesh.vertices_size(), mesh.n_vertices(),
                        index < mesh.vertices_size() && mesh.is_deleted(Vertex(index)), "--vertex",
                        "vertex", "vertices");
            break;
        case Kind::Edge:
            check_index(index, mesh.edges_size(), mesh.n_edges(),
                        index < mesh.edges_size() && mesh.is_deleted(Edge(index)), "--edge", "edge",
                        "edges");
            break;
        case Kind::Face:
            check_index(index, mesh.faces_size(), mesh.n_faces(),
                        index < mesh.faces_size() && mesh.is_deleted(Face(index)), "--face", "face",
                        "faces");
            break;
        case Kind::Point:
            if (mesh.n_faces() == 0) throw InvalidArgument("--point: the mesh has no faces");
            break;
        case Kind::None:
            break;
    }
}

void print_fields(const char* title, const std::vector<InspectionField>& fields) {
    std::printf("%s\n", title);
    std::size_t width = 0;
    for (const InspectionField& f : fields) width = std::max(width, f.label.size());
    for (const InspectionField& f : fields)
        std::printf("  %-*s  %s\n", int(width), f.label.c_str(), f.text.c_str());
}

void add_fields(JsonObject& j, const std::vector<InspectionField>& fields) {
    for (const InspectionField& f : fields) {
        if (f.numbers.empty())
            j.add(f.key, f.text);
        else if (f.numbers.size() == 1)
            j.add(f.key, f.numbers[0]);
        else
            j.add(f.key, f.numbers);
    }
}

}  // namespace

int run_inspect_command(const std::vector<std::string>& args) {
    std::vector<std::string> files;
    Kind kind = Kind::None;
    const char* kind_option = "";
    Index index = 0;
    Point point = Point::Zero();
    bool json = false, help = false;
    DecimationOptions options;
    ArgReader reader(args, "inspect");
    const auto choose = [&](Kind k, const char* option) {
        if (kind != Kind::None)
            throw InvalidArgument(std::string(option) + ": give only one of --vertex, --edge, " +
                                  "--face and --point (" + kind_option + " was given too)");
        kind = k;
        kind_option = option;
    };
    while (reader.next()) {
        if (reader.is_help()) {
            help = true;
        } else if (reader.is("--json")) {
            json = reader.flag();
        } else if (reader.is("--vertex") || reader.is("--edge") || reader.is("--face")) {
            const char* option = reader.is("--vertex") ? "--vertex"
                                 : reader.is("--edge") ? "--edge"
                                                       : "--face";
            choose(reader.is("--vertex") ? Kind::Vertex
                   : reader.is("--edge") ? Kind::Edge
                                         : Kind::Face,
                   option);
            index = parse_index(reader.value(), option);
        } else if (reader.is("--point")) {
            choose(Kind::Point, "--point");
            point = parse_point(reader.value());
        } else if (reader.is("--cost")) {
            options.cost = parse_decimation_cost(reader.value());
        } else if (reader.is("--normal-flip")) {
            const std::string v = reader.value();
            options.normal_flip = v != "off";
            if (options.normal_flip) options.max_normal_angle = parse_number(v, "--normal-flip");
        } else if (reader.is("--roundness")) {
            const std::string v = reader.value();
            options.roundness = v != "off";
            if (options.roundness) options.min_roundness = parse_number(v, "--roundness");
        } else if (reader.is("--independent-set")) {
            options.independent_set = reader.flag();
        } else if (reader.is("--max-error")) {
            options.max_error = parse_number(reader.value(), "--max-error");
        } else if (reader.is_option()) {
            reader.refuse_unknown();
        } else {
            files.push_back(reader.arg());
        }
    }
    if (help) {
        std::fputs(kInspectUsage, stdout);
        return 0;
    }
    if (files.size() != 1)
        throw InvalidArgument("expected one mesh file IN (see `trilab-cli inspect --help`)");
    if (kind == Kind::None)
        throw InvalidArgument(
            "give the element: --vertex N, --edge N, --face N or --point X,Y,Z (see `trilab-cli "
            "inspect --help`)");
    LoadedMesh in = read_mesh(files[0]);
    const HalfedgeMesh& mesh = in.mesh;
    check_request(mesh, kind, index);

    const auto t0 = std::chrono::steady_clock::now();
    std::vector<InspectionField> fields;
    const char* element = "vertex";
    Face picked;
    Vertex corner;
    Edge side;
    switch (kind) {
        case Kind::Vertex:
            fields = inspection_fields(inspect_vertex(mesh, Vertex(index)));
            break;
        case Kind::Edge:
            element = "edge";
            fields = inspection_fields(inspect_edge(mesh, Edge(index), options));
            break;
        case Kind::Face:
        case Kind::Point:
            element = "face";
            picked = kind == Kind::Face ? Face(index) : nearest_face(mesh, point);
            fields = inspection_fields(inspect_face(mesh, picked));
            if (kind == Kind::Point) {
                corner = nearest_corner(mesh, picked, point);
                side = nearest_side(mesh, picked, point);
                fields.push_back({"nearest_vertex",
                                  "Nearest corner to the point",
                                  std::to_string(corner.idx()),
                                  {double(corner.idx())}});
                fields.push_back({"nearest_edge",
                                  "Nearest side to the point",
                                  std::to_string(side.idx()),
                                  {double(side.idx())}});
            }
            break;
        case Kind::None:
            break;
    }
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    if (json) {
        JsonObject j;
        j.add("in", files[0]).add("element", element);
        j.add("index", std::size_t(kind == Kind::Point ? picked.idx() : index));
        j.add("ms", ms);
        add_fields(j, fields);
        std::cout << j.str() << "\n";
    } else {
        const std::string title = std::string(element) + " " +
                                  std::to_string(kind == Kind::Point ? picked.idx() : index) +
                                  (kind == Kind::Point ? " (nearest to the point)" : "");
        print_fields(title.c_str(), fields);
    }
    return 0;
}

}  // namespace trilab::cli
