// `trilab-cli spectrum`: reads a mesh, runs the "spectrum" operation of the registry, writes
// the reconstruction from the band and, with --eigenvalues, one eigenvalue per line. The
// conventions are those of app/cli/operation_command.h (options checked before any file is
// read, atomic writes, "ms" the operation alone).
#include "app/cli/spectrum_command.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>

#include "app/cli/json_writer.h"
#include "app/cli/operation_command.h"
#include "app/ops/operation.h"
#include "core/errors.h"
#include "core/io/file_util.h"
#include "core/io/mesh_io.h"
#include "core/progress.h"

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

struct SpectrumArgs {
    std::string op_text = "spectrum";
    std::vector<std::string> files;
    std::string eigenvalues_file;
    bool json = false, help = false;
    WriteOptions write;
};

SpectrumArgs parse_args(const std::vector<std::string>& args) {
    SpectrumArgs a;
    for (std::size_t i = 0; i < args.size(); ++i) {
        const std::string& s = args[i];
        if (s == "--help" || s == "-h") {
            a.help = true;
        } else if (s == "--json") {
            a.json = true;
        } else if (s == "--ascii") {
            a.write.ascii = true;
        } else if (s == "--big-endian") {
            a.write.big_endian = true;
        } else if (s == "--eigenvalues" || s.rfind("--eigenvalues=", 0) == 0) {
            if (s == "--eigenvalues") {
                if (i + 1 >= args.size()) throw InvalidArgument("--eigenvalues: missing FILE");
                a.eigenvalues_file = args[++i];
            } else {
                a.eigenvalues_file = s.substr(14);
            }
            if (a.eigenvalues_file.empty()) throw InvalidArgument("--eigenvalues: missing FILE");
        } else if (s.rfind("--", 0) == 0) {
            a.op_text += " " + s;
            const bool flag = s == "--full" || s == "--fix-boundary";
            if (!flag && s.find('=') == std::string::npos && i + 1 < args.size())
                a.op_text += " " + args[++i];
        } else {
            a.files.push_back(s);
        }
    }
    return a;
}

}  // namespace

int run_spectrum_command(const std::vector<std::string>& args) {
    const SpectrumArgs a = parse_args(args);
    if (a.help) {
        std::fputs(kSpectrumUsage, stdout);
        return 0;
    }
    const Operation op = parse_operation(a.op_text);  // bad options fail before any file
    if (a.files.size() != 2)
        throw InvalidArgument("expected IN and OUT files (see `trilab-cli spectrum --help`)");

    const LoadedMesh loaded = read_mesh(a.files[0]);  // not timed
    NullProgress progress;
    const OperationResult result = run_operation(op, loaded.mesh, progress);
    const HalfedgeMesh& out = result.steps.back().mesh;
    std::vector<double> eigenvalues;
    for (const auto& [key, values] : result.series)
        if (key == "eigenvalues") eigenvalues = values;
    // The reference's sign convention made non-negative: lambda of K x = lambda S x (rounding
    // can leave -1e-16 on a zero eigenvalue).
    for (double& v : eigenvalues) v = std::max(v, 0.0);
    write_mesh(out, a.files[1], a.write);  // not timed
    if (!a.eigenvalues_file.empty())
        write_file_atomically(a.eigenvalues_file, [&](std::ostream& os) {
            std::string text;
            for (double v : eigenvalues) {
                append_number(text, v);
                text += '\n';
            }
            os << text;
        });

    if (a.json) {
        JsonObject j;
        j.add("input", a.files[0])
            .add("output", a.files[1])
            .add("operation", op.name)
            .add("parameters", result.parameters)
            .add("vertices", out.n_vertices())
            .add("faces", out.n_faces());
        add_operation_values(j, result);
        for (const auto& [key, text] : result.texts) j.add(key, text);
        if (!a.eigenvalues_file.empty()) j.add("eigenvalues_file", a.eigenvalues_file);
        j.add("eigenvalues", eigenvalues);
        j.add("report", result.report).add("ms", result.ms);
        std::cout << j.str() << "\n";
    } else {
        std::printf("wrote %s: %s %s (%.1f ms)\n", a.files[1].c_str(), result.label.c_str(),
                    result.parameters.c_str(), result.ms);
        for (const std::string& line : result.report) std::printf("  %s\n", line.c_str());
        if (!a.eigenvalues_file.empty())
            std::printf("wrote %s: %zu eigenvalues\n", a.eigenvalues_file.c_str(),
                        eigenvalues.size());
    }
    return 0;
}

}  // namespace trilab::cli
