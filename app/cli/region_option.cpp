// `--region SPEC` and `trilab-cli select` (app/cli/region_option.h). Parsing is two-staged:
// the SPEC's syntax before any file is read (so a typo fails at once), the weights once the
// mesh is loaded.
#include "app/cli/region_option.h"

#include <cctype>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>

#include "app/cli/arg_reader.h"
#include "app/cli/json_writer.h"
#include "app/cli/write_options.h"
#include "core/errors.h"
#include "core/io/mesh_io.h"
#include "core/number_text.h"

namespace trilab::cli {

const char* const kRegionHelp =
    "  --region SPEC (act on a region only: sphere:X,Y,Z,R[,FEATHER], geodesic:V,R[,FEATHER], "
    "component:V, or file:PATH with one weight per vertex per line or a PLY/OM with a "
    "`selection` vertex property; weight-0 vertices stay as they are; --json adds "
    "\"region_vertices\")\n";

namespace {

constexpr const char* kSpecForms =
    "sphere:X,Y,Z,R[,FEATHER], geodesic:V,R[,FEATHER], component:V or file:PATH";

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

/// One weight per line of a text file.
Selection read_weights(const HalfedgeMesh& mesh, const RegionSpec& spec) {
    std::ifstream in(spec.path);
    const std::string head = "--region " + spec.text + ": ";
    if (!in) throw InvalidArgument(head + "cannot open '" + spec.path + "'");
    Selection weights;
    std::string line;
    std::size_t number = 0;
    while (std::getline(in, line)) {
        ++number;
        const std::size_t a = line.find_first_not_of(" \t\r");
        if (a == std::string::npos || line[a] == '#') continue;
        const std::size_t b = line.find_last_not_of(" \t\r");
        const std::string word = line.substr(a, b - a + 1);
        double w = 0;
        if (!parse_number(word, w) || w < 0 || w > 1)
            throw InvalidArgument(head + spec.path + ":" + std::to_string(number) +
                                  ": expected a weight from 0 to 1, got '" + word + "'");
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
        if (i == 0 && vertex_first && (x < 0 || x != std::floor(x)))
            throw InvalidArgument("--region " + text + ": V: expected a vertex index, got '" +
                                  parts[i] + "'");
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

int run_select_command(const std::vector<std::string>& args) {
    constexpr const char* kUsage =
        R"(usage: trilab-cli select IN OUT --region SPEC [--grow K] [--shrink K] [--invert] [--json]

Writes IN to OUT with a selection stored as the per-vertex weight `selection` (PLY property
`selection`, OM custom property `selection`; other formats drop it), for `--region file:OUT`
of any operation, or for the viewer.

options:
)";
    ArgReader reader(args, "select");
    std::vector<std::string> files;
    std::optional<RegionSpec> spec;
    int grow = 0, shrink = 0;
    bool invert = false, json = false;
    WriteOptions write;
    const auto rings = [&](const char* option) {
        const std::string text = reader.value();
        double x = 0;
        if (!parse_number(text, x) || x < 0 || x > 1000 || x != std::floor(x))
            throw InvalidArgument(std::string(option) +
                                  ": expected a whole number from 0 to 1000, got '" + text + "'");
        return int(x);
    };
    while (reader.next()) {
        if (reader.is_help()) {
            std::fputs(kUsage, stdout);
            std::fputs(kRegionHelp, stdout);
            std::fputs(
                "  --grow K, --shrink K (by K rings, in that order), --invert (1 - weight, "
                "last)\n  --json (one JSON object: \"vertices\", \"region_vertices\", "
                "\"ms\")\n",
                stdout);
            return 0;
        } else if (reader.is("--region")) {
            spec = parse_region_spec(reader.value());
        } else if (reader.is("--grow")) {
            grow = rings("--grow");
        } else if (reader.is("--shrink")) {
            shrink = rings("--shrink");
        } else if (reader.is("--invert")) {
            invert = reader.flag();
        } else if (reader.is("--json")) {
            json = reader.flag();
        } else if (take_write_option(reader, write)) {
            continue;
        } else if (reader.is_option()) {
            reader.refuse_unknown();
        } else {
            files.push_back(reader.arg());
        }
    }
    if (!spec) throw InvalidArgument("select: --region SPEC is required");
    if (files.size() != 2)
        throw InvalidArgument("expected IN and OUT files (see `trilab-cli select --help`)");
    LoadedMesh loaded = read_mesh(files[0]);
    const auto t0 = std::chrono::steady_clock::now();
    Selection s = make_region(loaded.mesh, *spec);
    if (grow > 0) grow_selection(loaded.mesh, s, grow);
    if (shrink > 0) shrink_selection(loaded.mesh, s, shrink);
    if (invert) invert_selection(loaded.mesh, s);
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    store_selection(loaded.mesh, s);
    write_mesh(loaded.mesh, files[1], write);
    const std::size_t n = count_selected(s);
    if (json) {
        JsonObject j;
        j.add("input", files[0])
            .add("output", files[1])
            .add("region", spec->text)
            .add("vertices", loaded.mesh.n_vertices())
            .add("region_vertices", n)
            .add("ms", ms);
        std::cout << j.str() << "\n";
    } else {
        std::printf("wrote %s: %zu of %zu vertices selected (%.1f ms)\n", files[1].c_str(), n,
                    loaded.mesh.n_vertices(), ms);
    }
    return 0;
}

}  // namespace trilab::cli
