// `SPEC` of a region (core/algorithms/selection.h), as trilab-cli's `--region SPEC` and the
// viewer's `--select SPEC` take it (app/ops/region_spec.h).
#include "app/ops/region_spec.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>

#include "core/algorithms/coloring.h"
#include "core/algorithms/feature_detection.h"
#include "core/errors.h"
#include "core/io/file_util.h"
#include "core/io/mesh_io.h"
#include "core/number_text.h"

namespace trilab {

namespace {

constexpr const char* kSpecForms =
    "sphere:X,Y,Z,R[,FEATHER], geodesic:V,R[,FEATHER], component:V, threshold:QUANTITY,LO,HI, "
    "feature:K[,FEATHER] or file:PATH";

bool parse_number(const std::string& text, double& out) {
    const char* end = text.data() + text.size();
    const auto [ptr, ec] = std::from_chars(text.data(), end, out);
    return !text.empty() && ec == std::errc() && ptr == end && std::isfinite(out);
}

std::vector<std::string> split_commas(const std::string& text) {
    std::vector<std::string> parts;
    std::size_t start = 0;
    for (;;) {
        const std::size_t comma = text.find(',', start);
        parts.push_back(text.substr(start, comma - start));
        if (comma == std::string::npos) return parts;
        start = comma + 1;
    }
}

/// A vertex index of `spec` at `value`, checked against the mesh.
Vertex spec_vertex(const HalfedgeMesh& mesh, const RegionSpec& spec, double value) {
    const std::string head = "--region " + spec.text + ": ";
    if (value >= double(mesh.vertices_size()))
        throw InvalidArgument(head + "vertex " + number_text(value) +
                              " is out of range (the mesh has " +
                              std::to_string(mesh.vertices_size()) + " vertices)");
    const Vertex v{Index(value)};
    if (mesh.is_deleted(v))
        throw InvalidArgument(head + "vertex " + std::to_string(v.idx()) + " is deleted");
    return v;
}

}  // namespace

std::uint64_t weight_file_budget(std::size_t vertices) {
    // A weight per line: "0.123456789\n" is 12 bytes; comments and blank lines are allowed,
    // so 64 bytes a vertex and 1 MiB of slack, never more than a file read may take at all.
    const std::uint64_t budget = (std::uint64_t(1) << 20) + 64 * std::uint64_t(vertices);
    return std::min(budget, max_readable_file_bytes());
}

namespace {

/// One weight per line of a text file, read from a regular file only and within
/// weight_file_budget() (issue 38, item 15: /dev/zero or a FIFO is refused at once).
Selection read_weights(const HalfedgeMesh& mesh, const RegionSpec& spec) {
    const std::string head = "--region " + spec.text + ": ";
    std::string text;
    try {
        text = read_file_bytes(spec.path, weight_file_budget(mesh.vertices_size()));
    } catch (const IoError& e) {
        throw IoError(e.file(), e.line(),
                      e.reason() + " (" + head + "a weight file is a regular file of at most " +
                          std::to_string(weight_file_budget(mesh.vertices_size())) +
                          " bytes for this mesh)");
    }
    Selection weights;
    std::size_t number = 0, start = 0;
    while (start < text.size()) {
        std::size_t end = text.find('\n', start);
        if (end == std::string::npos) end = text.size();
        const std::string line = text.substr(start, end - start);
        start = end + 1;
        ++number;
        const std::size_t a = line.find_first_not_of(" \t\r");
        if (a == std::string::npos || line[a] == '#') continue;
        const std::size_t b = line.find_last_not_of(" \t\r");
        const std::string word = line.substr(a, b - a + 1);
        double w = 0;
        if (!parse_number(word, w) || w < 0 || w > 1)
            throw InvalidArgument(head + spec.path + ":" + std::to_string(number) +
                                  ": expected a weight from 0 to 1, got '" + word + "'");
        if (weights.size() == mesh.vertices_size())
            throw InvalidArgument(head + spec.path + ":" + std::to_string(number) +
                                  ": more weights than the mesh's " +
                                  std::to_string(mesh.vertices_size()) + " vertices");
        weights.push_back(float(w));
    }
    if (weights.size() != mesh.vertices_size())
        throw InvalidArgument(head + "expected one weight per vertex (" +
                              std::to_string(mesh.vertices_size()) + "), the file has " +
                              std::to_string(weights.size()));
    return weights;
}

/// Whether `path` names a mesh file (by its extension) rather than a list of weights.
bool is_mesh_file(const std::string& path) {
    const std::size_t dot = path.rfind('.');
    if (dot == std::string::npos) return false;
    std::string ext = path.substr(dot + 1);
    for (char& c : ext) c = char(std::tolower((unsigned char)c));
    return ext == "ply" || ext == "om" || ext == "obj" || ext == "off" || ext == "stl";
}

}  // namespace

namespace {

/// threshold:QUANTITY,LO,HI after the colon.
RegionSpec parse_threshold_spec(RegionSpec spec, const std::string& rest) {
    const std::string head = "--region " + spec.text + ": ";
    const std::vector<std::string> parts = split_commas(rest);
    if (parts.size() != 3)
        throw InvalidArgument(head + "expected threshold:QUANTITY,LO,HI (" +
                              std::to_string(parts.size()) + " parts given)");
    spec.kind = RegionSpec::Kind::Threshold;
    try {
        parse_coloring(parts[0]);
    } catch (const InvalidArgument& e) {
        const std::string what = e.what();
        throw InvalidArgument(head + "QUANTITY: " + what.substr(what.find(':') + 2));
    }
    spec.quantity = parts[0];
    for (std::size_t i = 1; i < 3; ++i) {
        double x = 0;
        if (!parse_number(parts[i], x))
            throw InvalidArgument(head + (i == 1 ? "LO" : "HI") + ": expected a number, got '" +
                                  parts[i] + "'");
        spec.numbers.push_back(x);
    }
    if (spec.numbers[0] > spec.numbers[1])
        throw InvalidArgument(head + "LO " + parts[1] + " is above HI " + parts[2]);
    return spec;
}

/// The vertices whose value of the spec's colouring lies in [LO, HI].
Selection threshold_region(const HalfedgeMesh& mesh, const RegionSpec& spec) {
    const std::string head = "--region " + spec.text + ": ";
    const VertexColoring coloring = parse_coloring(spec.quantity);
    if (coloring == VertexColoring::None || coloring == VertexColoring::Normal)
        throw InvalidArgument(head + "the colouring '" + spec.quantity +
                              "' has no value per vertex (use k1, k2, mean, gaussian, "
                              "shape-index, subdivision or geodesic-distance)");
    if (coloring == VertexColoring::SmoothingDistance)
        throw InvalidArgument(head +
                              "smoothing-distance needs the state before an operation, "
                              "which a region SPEC does not have");
    const bool has_distance = mesh.has_vertex_property("v:distance");
    if (coloring_needs_field(coloring) &&
        !(coloring == VertexColoring::GeodesicDistance && has_distance))
        throw InvalidArgument(
            head + "the colouring '" + spec.quantity + "' needs " +
            (coloring == VertexColoring::GeodesicDistance
                 ? std::string("a \"v:distance\" vertex property (trilab-cli geodesic writes it)")
                 : std::string("a spectral decomposition, which a region SPEC does not compute")));
    const VertexColors colors = color_vertices(mesh, coloring);
    const double lo = spec.numbers[0], hi = spec.numbers[1];
    Selection s(mesh.vertices_size(), 0.0f);
    for (Vertex v : mesh.vertices()) {
        const double x = colors.values[v.idx()];
        if (std::isfinite(x) && x >= lo && x <= hi) s[v.idx()] = 1.0f;
    }
    return s;
}

}  // namespace

RegionSpec parse_region_spec(const std::string& text) {
    RegionSpec spec;
    spec.text = text;
    const std::size_t colon = text.find(':');
    if (colon == std::string::npos)
        throw InvalidArgument("--region: expected " + std::string(kSpecForms) + ", got '" + text +
                              "'");
    const std::string kind = text.substr(0, colon), rest = text.substr(colon + 1);
    if (kind == "file") {
        if (rest.empty()) throw InvalidArgument("--region file: missing PATH");
        spec.kind = RegionSpec::Kind::File;
        spec.path = rest;
        return spec;
    }
    if (kind == "threshold") return parse_threshold_spec(spec, rest);
    std::size_t min_parts = 0, max_parts = 0;
    const char* form = "";
    if (kind == "sphere") {
        spec.kind = RegionSpec::Kind::Sphere;
        min_parts = 4, max_parts = 5, form = "sphere:X,Y,Z,R[,FEATHER]";
    } else if (kind == "geodesic") {
        spec.kind = RegionSpec::Kind::Geodesic;
        min_parts = 2, max_parts = 3, form = "geodesic:V,R[,FEATHER]";
    } else if (kind == "component") {
        spec.kind = RegionSpec::Kind::Component;
        min_parts = max_parts = 1, form = "component:V";
    } else if (kind == "feature") {
        spec.kind = RegionSpec::Kind::Feature;
        min_parts = 1, max_parts = 2, form = "feature:K[,FEATHER]";
    } else {
        throw InvalidArgument("--region: unknown kind '" + kind + "' (expected " + kSpecForms +
                              ")");
    }
    const std::vector<std::string> parts = split_commas(rest);
    if (parts.size() < min_parts || parts.size() > max_parts)
        throw InvalidArgument("--region " + text + ": expected " + form + " (" +
                              std::to_string(parts.size()) + " numbers given)");
    const bool vertex_first = spec.kind != RegionSpec::Kind::Sphere;
    for (std::size_t i = 0; i < parts.size(); ++i) {
        double x = 0;
        if (!parse_number(parts[i], x))
            throw InvalidArgument("--region " + text + ": expected a number, got '" + parts[i] +
                                  "' (in " + form + ")");
        const bool rings = spec.kind == RegionSpec::Kind::Feature;
        if (i == 0 && vertex_first && (x < 0 || x != std::floor(x) || (rings && x > 1e6)))
            throw InvalidArgument("--region " + text + ": " + (rings ? "K" : "V") + ": expected " +
                                  (rings ? "a number of rings (0 to 1000000)" : "a vertex index") +
                                  ", got '" + parts[i] + "'");
        const bool radius_or_feather = vertex_first ? i >= 1 : i >= 3;
        if (radius_or_feather && x < 0)
            throw InvalidArgument("--region " + text + ": " +
                                  (i + 1 == max_parts ? "FEATHER" : "R") +
                                  ": expected a number >= 0, got '" + parts[i] + "'");
        spec.numbers.push_back(x);
    }
    return spec;
}

Selection make_region(const HalfedgeMesh& mesh, const RegionSpec& spec) {
    const std::vector<double>& n = spec.numbers;
    Selection s;
    double feather = 0;
    switch (spec.kind) {
        case RegionSpec::Kind::Sphere:
            s = sphere_selection(mesh, Point(n[0], n[1], n[2]), n[3]);
            if (n.size() > 4) feather = n[4];
            break;
        case RegionSpec::Kind::Geodesic:
            s = geodesic_selection(mesh, spec_vertex(mesh, spec, n[0]), n[1]);
            if (n.size() > 2) feather = n[2];
            break;
        case RegionSpec::Kind::Component:
            s = component_selection(mesh, spec_vertex(mesh, spec, n[0]));
            break;
        case RegionSpec::Kind::Threshold:
            s = threshold_region(mesh, spec);
            break;
        case RegionSpec::Kind::Feature:
            if (!has_features(mesh))
                throw InvalidArgument("--region " + spec.text +
                                      ": the mesh has no features (no sharp edge, no corner "
                                      "tag): run `trilab-cli features` first");
            s = feature_neighbourhood(mesh, unsigned(n[0]));
            if (n.size() > 1) feather = n[1];
            break;
        case RegionSpec::Kind::File:
            if (is_mesh_file(spec.path)) {
                const LoadedMesh loaded = read_mesh(spec.path);
                std::optional<Selection> stored = stored_selection(loaded.mesh);
                if (!stored)
                    throw InvalidArgument("--region " + spec.text + ": '" + spec.path +
                                          "' has no `selection` vertex property");
                if (stored->size() != mesh.vertices_size())
                    throw InvalidArgument("--region " + spec.text + ": '" + spec.path + "' has " +
                                          std::to_string(stored->size()) + " vertices, the mesh " +
                                          std::to_string(mesh.vertices_size()));
                s = std::move(*stored);
            } else {
                s = read_weights(mesh, spec);
            }
            break;
    }
    if (feather > 0) feather_selection(mesh, s, feather);
    return s;
}

}  // namespace trilab
