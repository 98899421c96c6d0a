// `trilab-cli figures`: see figures_command.h.
#include "app/cli/figures_command.h"

#include <cstdio>
#include <string>
#include <vector>

#include "app/cli/arg_reader.h"
#include "app/cli/json_writer.h"
#include "app/session/reference_figures.h"
#include "core/errors.h"

namespace trilab::cli {
namespace {

constexpr const char* kFiguresUsage = R"(usage: trilab-cli figures [--json]

Lists the reference report's figures that the viewer loads (Help > Reference figures, or
`trilab --figure NAME`): each one's name, title, what the reference used, the built-in model
trilab starts from, the setup and the operation in trilab's syntax, and the step in the
reference's units and in trilab's scale-free ones with the translation.

options:
  --json   one JSON object: "figures", an array of objects with "name", "title", "reference",
           "model", "model_note", "setup", "operation", "reference_step", "step",
           "translation", "result" (smoothed, diverges, filtered, subdivided, decimated)
)";

const char* result_name(viewer::FigureResult r) {
    switch (r) {
        case viewer::FigureResult::Smoothed:
            return "smoothed";
        case viewer::FigureResult::Diverges:
            return "diverges";
        case viewer::FigureResult::Filtered:
            return "filtered";
        case viewer::FigureResult::Subdivided:
            return "subdivided";
        case viewer::FigureResult::Decimated:
            return "decimated";
    }
    return "";
}

}  // namespace

int run_figures_command(const std::vector<std::string>& args) {
    bool json = false, help = false;
    ArgReader reader(args, "figures");
    while (reader.next()) {
        if (reader.is_help())
            help = true;
        else if (reader.is("--json"))
            json = reader.flag();
        else if (reader.is_option())
            reader.refuse_unknown();
        else
            throw InvalidArgument("figures takes no file (got '" + reader.arg() + "')");
    }
    if (help) {
        std::fputs(kFiguresUsage, stdout);
        return 0;
    }
    const std::vector<viewer::ReferenceFigure>& figures = viewer::reference_figures();
    if (json) {
        std::string array = "[";
        for (std::size_t i = 0; i < figures.size(); ++i) {
            const viewer::ReferenceFigure& f = figures[i];
            JsonObject o;
            o.add("name", f.name)
                .add("title", f.title)
                .add("reference", f.reference)
                .add("model", f.model)
                .add("model_note", f.model_note)
                .add("setup", f.setup)
                .add("operation", f.operation)
                .add("reference_step", f.reference_step)
                .add("step", f.step)
                .add("translation", f.translation)
                .add("result", result_name(f.result));
            array += (i ? ", " : "") + o.str();
        }
        JsonObject out;
        out.raw("figures", array + "]");
        std::printf("%s\n", out.str().c_str());
        return 0;
    }
    for (const viewer::ReferenceFigure& f : figures) {
        std::printf("%s  %s\n", f.name.c_str(), f.title.c_str());
        std::printf("    reference: %s\n", f.reference.c_str());
        std::printf("    model:     %s (%s)\n", f.model.c_str(), f.model_note.c_str());
        for (const std::string& s : f.setup) std::printf("    setup:     %s\n", s.c_str());
        std::printf("    operation: %s  (%s)\n", f.operation.c_str(), result_name(f.result));
        if (f.step > 0)
            std::printf("    step:      %g in the reference = %g here: %s\n", f.reference_step,
                        f.step, f.translation.c_str());
    }
    return 0;
}

}  // namespace trilab::cli
