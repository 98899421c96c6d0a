// What single operation commands add to the shared shape of app/cli/operation_command.h:
// spectrum writes its eigenvalues (--eigenvalues FILE, and the JSON), subdivide its levels,
// features its histogram of dihedral angles.
#include "app/cli/operation_command.h"

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <map>
#include <ostream>
#include <string>
#include <vector>

#include "app/cli/json_writer.h"
#include "app/cli/operation_command.h"
#include "app/cli/spectrum_filter_command.h"
#include "app/ops/operation.h"
#include "app/ops/spectrum_op.h"
#include "core/algorithms/hole_filling.h"
#include "core/algorithms/selection.h"
#include "core/errors.h"
#include "core/io/file_util.h"

namespace trilab::cli {
namespace {

/// Writes the eigenvalues (non-negative) to --eigenvalues FILE and adds them to the JSON.
void finish_spectrum(const OperationResult& result,
                     const std::map<std::string, std::string>& values, JsonObject* json) {
    std::vector<double> eigenvalues;
    for (const auto& [key, series] : result.series)
        if (key == "eigenvalues") eigenvalues = series;
    // The reference's sign convention made non-negative: lambda of K x = lambda S x (rounding
    // can leave -1e-16 on a zero eigenvalue).
    for (double& v : eigenvalues) v = std::max(v, 0.0);
    const auto file = values.find("--eigenvalues");
    if (file != values.end())
        write_file_atomically(file->second, [&](std::ostream& os) {
            std::string text;
            for (double v : eigenvalues) {
                append_number(text, v);
                text += '\n';
            }
            os << text;
        });
    if (json) {
        if (file != values.end()) json->add("eigenvalues_file", file->second);
        json->add("eigenvalues", eigenvalues);
        // A band edge inside a set of equal eigenvalues (band_warning holds the text).
        if (const SpectrumReport* r = report_of<SpectrumReport>(result)) {
            const MultipletSplit& split = r->band_split;
            json->add("band_splits_multiplet", split.splits);
            if (split.splits) {
                const auto band = [](const MultipletSplit::Band& b) {
                    return "[" + std::to_string(b.first) + ", " + std::to_string(b.second) + "]";
                };
                json->raw("suggested_bands",
                          "[" + (split.narrower ? band(*split.narrower) + ", " : std::string()) +
                              band(*split.wider) + "]");
            }
        }
    } else if (file != values.end()) {
        std::printf("wrote %s: %zu eigenvalues\n", file->second.c_str(), eigenvalues.size());
    }
}

/// Subdivide's JSON "levels": vertices and faces per level.
void finish_subdivide(const OperationResult& result, const std::map<std::string, std::string>&,
                      JsonObject* json) {
    if (!json) return;
    std::vector<double> vertices, faces;
    for (const auto& [key, series] : result.series) {
        if (key == "level_vertices") vertices = series;
        if (key == "level_faces") faces = series;
    }
    JsonObject levels;
    levels.add("vertices", vertices).add("faces", faces);
    json->add("levels", levels);
}

/// Features' histogram of dihedral angles: the JSON's "histogram" (one count per degree), or
/// the number of edges at or above every 10 degrees as text.
void finish_features(const OperationResult& result, const std::map<std::string, std::string>&,
                     JsonObject* json) {
    std::vector<double> counts;
    for (const auto& [key, series] : result.series)
        if (key == "histogram") counts = series;
    if (json) {
        json->add("histogram", counts);
        return;
    }
    std::string line = "  edges with an angle >= 10, 20, ..., 170 degrees:";
    for (std::size_t a = 10; a < counts.size(); a += 10) {
        double n = 0;
        for (std::size_t k = a; k < counts.size(); ++k) n += counts[k];
        line += " " + std::to_string(static_cast<long long>(n));
    }
    std::printf("%s\n", line.c_str());
}

/// fill-holes' --loops I,J: the indices, checked as text (before any file is read).
std::vector<long long> parse_loop_list(const std::string& text) {
    std::vector<long long> loops;
    std::size_t start = 0;
    while (start <= text.size()) {
        const std::size_t comma = std::min(text.find(',', start), text.size());
        const std::string item = text.substr(start, comma - start);
        long long value = -1;
        const auto [end, ec] = std::from_chars(item.data(), item.data() + item.size(), value);
        if (item.empty() || ec != std::errc() || end != item.data() + item.size() || value < 0)
            throw InvalidArgument(
                "--loops: expected loop indices I,J,... (whole numbers >= 0, "
                "as the --json report's \"holes\" numbers them), got '" +
                text + "'");
        loops.push_back(value);
        start = comma + 1;
    }
    return loops;
}

/// The rims of the --loops as a region (weight 1), checked against the mesh's loops.
bool fill_holes_region(const HalfedgeMesh* mesh, const std::map<std::string, std::string>& values,
                       Selection& region) {
    const auto given = values.find("--loops");
    if (given == values.end()) return false;
    const std::vector<long long> loops = parse_loop_list(given->second);
    if (!mesh) return true;
    const std::vector<BoundaryLoop> all = boundary_loops(*mesh);
    region = empty_selection(*mesh);
    for (long long i : loops) {
        if (std::size_t(i) >= all.size())
            throw InvalidArgument(
                "--loops: loop " + std::to_string(i) + " is past the end (the mesh has " +
                std::to_string(all.size()) + " boundary loop" + (all.size() == 1 ? "" : "s") +
                (all.empty() ? std::string() : ", 0 to " + std::to_string(all.size() - 1)) + ")");
        for (Vertex v : all[std::size_t(i)].vertices) region[v.idx()] = 1.0f;
    }
    return true;
}

/// fill-holes' JSON "holes": every loop with its size and what became of it.
void finish_fill_holes(const OperationResult& result, const std::map<std::string, std::string>&,
                       JsonObject* json) {
    const HoleFillingReport* r = report_of<HoleFillingReport>(result);
    if (!json || !r) return;
    std::string holes = "[";
    for (std::size_t i = 0; i < r->loop_edges.size(); ++i) {
        JsonObject hole;
        hole.add("loop", i).add("edges", r->loop_edges[i]);
        const bool filled = std::find(r->filled.begin(), r->filled.end(), i) != r->filled.end();
        std::string reason;
        for (const RefusedLoop& f : r->refused)
            if (f.loop == i) reason = f.reason;
        hole.add("status", filled ? "filled" : reason.empty() ? "not chosen" : "refused");
        if (!reason.empty()) hole.add("reason", reason);
        holes += (i ? ", " : "") + hole.str();
    }
    json->raw("holes", holes + "]");
}

}  // namespace

CommandExtras command_extras(const std::string& name) {
    if (name == "spectrum")
        return CommandExtras{
            {"--eigenvalues"},
            std::string("  --eigenvalues FILE (write the K eigenvalues, one per line, ascending, "
                        "non-negative)\n") +
                kSpectrumFilterHelp,
            finish_spectrum,
            {}};
    if (name == "subdivide") return CommandExtras{{}, "", finish_subdivide, {}};
    if (name == "fill-holes")
        return CommandExtras{{"--loops"},
                             "  --loops I,J,... (fill only these loops, numbered by their "
                             "smallest vertex index as the --json \"holes\" list them; "
                             "not with --region)\n",
                             finish_fill_holes,
                             fill_holes_region};
    if (name == "features") return CommandExtras{{}, "", finish_features, {}};
    return {};
}

}  // namespace trilab::cli
