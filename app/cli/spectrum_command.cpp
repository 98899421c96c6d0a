// `trilab-cli spectrum`: reads a mesh, runs the "spectrum" operation of the registry, writes
// the reconstruction from the band and, with --eigenvalues, one eigenvalue per line. The
// conventions are those of app/cli/operation_command.h (options checked before any file is
// read, atomic writes, "ms" the operation alone).
#include "app/cli/spectrum_command.h"

#include <algorithm>
#include <cstdio>
#include <map>
#include <ostream>
#include <string>
#include <vector>

#include "app/cli/json_writer.h"
#include "app/cli/operation_command.h"
#include "app/ops/operation.h"
#include "core/io/file_util.h"

namespace trilab::cli {
namespace {

constexpr const char* kSpectrumUsage =
    R"(usage: trilab-cli spectrum --operator OP --k K [--which smallest|largest] [--band LO:HI]
                             [--full] [--mass M] [--fix-boundary] [--max-full N] [--threads T]
                             IN OUT [--eigenvalues FILE] [--json] [--ascii] [--big-endian]

Decomposes the geometry of IN into the eigenvectors of a fairing Laplacian (K x = lambda S x,
sections 1.2.2, 1.2.11, 1.2.12 of the reference) and writes to OUT the mesh reconstructed from
the band LO..HI of the computed frequencies (0-based, ascending). Isolated vertices keep their
positions.

options:
  --operator OP       umbrella (default), improved-umbrella, curvature-flow, second-order
  --k K               frequencies to compute: 1 to vertices - 1 (default 50); with --full
                      the default is all of them
  --which W           smallest (default: shift-invert Lanczos, band by band above 150) or
                      largest (Lanczos on the operator)
  --band LO:HI        the frequencies used for the reconstruction, 0 <= LO <= HI < K
                      (default all K)
  --full              dense decomposition of every frequency (up to --max-full vertices)
  --max-full N        the size limit of --full (default 5000)
  --mass M            normalizer (default: the operator's row normalizer), barycentric or
                      voronoi (lumped area mass matrices; with curvature-flow the eigenvalues
                      approximate the Laplace-Beltrami spectrum)
  --fix-boundary      boundary vertices fixed (Dirichlet); default free (Neumann)
  --threads T         1 or 2: smallest end, two spectrum slices at once (default 2 when the
                      machine has two cores; the results agree to the solver's tolerance)
  --eigenvalues FILE  write the K eigenvalues, one per line, ascending, non-negative
  --json              one JSON object: "ms", "k", "lo", "hi", "rows", "bands", "solver",
                      "max_residual", "eigenvalues", ...
)";

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
    } else if (file != values.end()) {
        std::printf("wrote %s: %zu eigenvalues\n", file->second.c_str(), eigenvalues.size());
    }
}

}  // namespace

int run_spectrum_command(const std::vector<std::string>& args) {
    return run_operation_command("spectrum", kSpectrumUsage, args, add_operation_values,
                                 {"--full", "--fix-boundary"},
                                 CommandExtras{{"--eigenvalues"}, finish_spectrum});
}

}  // namespace trilab::cli
