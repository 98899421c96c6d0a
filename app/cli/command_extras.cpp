// What single operation commands add to the shared shape of app/cli/operation_command.h:
// spectrum writes its eigenvalues (--eigenvalues FILE, and the JSON), subdivide its levels,
// features its histogram of dihedral angles.
#include "app/cli/operation_command.h"

#include <algorithm>
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

}  // namespace

CommandExtras command_extras(const std::string& name) {
    if (name == "spectrum")
        return CommandExtras{
            {"--eigenvalues"},
            std::string("  --eigenvalues FILE (write the K eigenvalues, one per line, ascending, "
                        "non-negative)\n") +
                kSpectrumFilterHelp,
            finish_spectrum};
    if (name == "subdivide") return CommandExtras{{}, "", finish_subdivide};
    if (name == "features") return CommandExtras{{}, "", finish_features};
    return {};
}

}  // namespace trilab::cli
