#include "app/cli/operation_command.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <optional>

#include "app/cli/arg_reader.h"
#include "app/cli/operation_report.h"
#include "app/cli/region_option.h"
#include "app/cli/write_options.h"
#include "core/errors.h"
#include "core/io/mesh_io.h"
#include "core/progress.h"

namespace trilab::cli {
namespace {

struct OperationArgs {
    std::vector<std::string> op_args;
    std::vector<std::string> files;
    std::map<std::string, std::string> own;  ///< the command's own value options
    bool json = false, help = false, keep_partial = false;
    std::optional<RegionSpec> region;
    WriteOptions write;
};

/// Whether "--name" is a flag of the operation (takes no value).
bool is_flag(const OperationDef& def, const std::string& option) {
    const std::string name = option.substr(2);
    for (const ParamSpec& p : def.params)
        if (p.name == name) return p.kind == ParamKind::Flag;
    return false;
}

/// Whether `option` is one of the command's own value options.
bool is_own_option(const CommandExtras& extras, const std::string& option) {
    for (const std::string& name : extras.value_options)
        if (option == name) return true;
    return false;
}

OperationArgs parse_args(const OperationDef& def, const std::vector<std::string>& args,
                         const CommandExtras& extras) {
    OperationArgs a;
    ArgReader reader(args, def.name);
    while (reader.next()) {
        const std::string& s = reader.arg();
        if (reader.is_help()) {
            a.help = true;
        } else if (reader.is("--json")) {
            a.json = reader.flag();
        } else if (take_write_option(reader, a.write)) {
            continue;
        } else if (reader.is("--region")) {
            a.region = parse_region_spec(reader.value());
        } else if (reader.is("--keep-partial")) {
            if (!def.may_stop_early)
                throw InvalidArgument("--keep-partial: does not apply to " + def.name +
                                      " (it never stops early)");
            a.keep_partial = reader.flag();
        } else if (is_own_option(extras, s)) {
            const std::string value = reader.value();
            if (value.empty()) throw InvalidArgument(s + ": missing value");
            a.own[s] = value;
        } else if (reader.is_option()) {
            // An operation option: it and its value go to the operation, which checks both.
            a.op_args.push_back(s);
            if (is_flag(def, s)) {
                reader.flag();
            } else if (reader.has_value()) {
                const std::string value = reader.value();
                // subdivide's --features auto:A is --features auto --feature-angle A.
                if (s == "--features" && value.rfind("auto:", 0) == 0) {
                    a.op_args.push_back("auto");
                    a.op_args.push_back("--feature-angle");
                    a.op_args.push_back(value.substr(5));
                } else {
                    a.op_args.push_back(value);
                }
            }
        } else {
            a.files.push_back(s);
        }
    }
    return a;
}

}  // namespace

std::string operation_command_help(const std::string& name) {
    const OperationDef& def = operation_def(name);
    const CommandExtras extras = command_extras(name);
    std::string s = "usage: trilab-cli " + name + " [options] IN OUT [--json] [--ascii] " +
                    "[--big-endian]" + (def.may_stop_early ? " [--keep-partial]" : "") + "\n\n";
    // The summary, wrapped at 95 columns.
    std::string line, word, text;
    for (char c : def.summary + " ") {
        if (c != ' ') {
            word += c;
            continue;
        }
        if (line.size() + word.size() + 1 > 95) {
            text += line + "\n";
            line.clear();
        }
        line += (line.empty() ? "" : " ") + word;
        word.clear();
    }
    text += line;
    s += text + "\n\noptions:\n" + def.help() + extras.help;
    if (def.takes_region)
        s += std::string(kRegionHelp) + "      on " + def.name + ": " + def.region_help + "\n";
    s += "  --ascii, --big-endian (how to write .ply and .stl, as for `trilab-cli convert`)\n";
    if (def.may_stop_early)
        s += "  --keep-partial (a run that stops early writes its last good state, still exit "
             "4)\n";
    s += "  --json (one JSON object: the parameters, the result's figures, \"ms\" the operation "
         "itself)\n";
    return s;
}

int run_operation_command(const std::string& name, const std::vector<std::string>& args) {
    const OperationDef& def = operation_def(name);
    const CommandExtras extras = command_extras(name);
    const OperationArgs a = parse_args(def, args, extras);
    if (a.help) {
        std::fputs(operation_command_help(name).c_str(), stdout);
        return 0;
    }
    const Operation op = parse_operation(name, a.op_args);  // bad options fail before any file
    if (a.region && !def.takes_region)
        throw InvalidArgument("--region: " + name +
                              " does not work on a region yet (it acts on the whole mesh)");
    if (a.files.size() != 2)
        throw InvalidArgument("expected IN and OUT files (see `trilab-cli " + name + " --help`)");
    Selection own_region;
    const bool has_own_region = extras.region && extras.region(nullptr, a.own, own_region);
    if (has_own_region && a.region)
        throw InvalidArgument(
            "--region: give either --region or the command's own choice of "
            "region (" +
            extras.value_options.front() + "), not both");

    LoadedMesh loaded = read_mesh(a.files[0]);  // not timed
    NullProgress progress;
    RunSettings settings;
    settings.keep_steps = false;  // only the last state is written
    settings.morph = false;
    settings.consumable = &loaded.mesh;  // the input is not needed after the run
    Selection region;                    // not timed, like the reading
    if (a.region) {
        region = make_region(loaded.mesh, *a.region);
        settings.region = &region;
    }
    if (has_own_region) {
        extras.region(&loaded.mesh, a.own, region);
        settings.region = &region;
    }
    const OperationResult result = run_operation(op, loaded.mesh, progress, settings);
    if (result.stopped_early && !a.keep_partial)
        throw RunStopped(result.stop_reason +
                         " (nothing written; --keep-partial writes the last "
                         "good state)");
    const HalfedgeMesh& out = result.steps.back().mesh;
    write_mesh(out, a.files[1], a.write);  // not timed
    const std::vector<std::string> save_notes = write_notes(out, a.files[1]);

    if (a.json) {
        JsonObject j;
        j.add("input", a.files[0]).add("output", a.files[1]);
        add_operation_report(j, op, result, extras, a.own, save_notes);
        j.add("ms", result.ms);
        std::cout << j.str() << "\n";
    } else {
        std::printf("wrote %s: %s%s%s (%.1f ms)\n", a.files[1].c_str(), result.label.c_str(),
                    result.parameters.empty() ? "" : " ", result.parameters.c_str(), result.ms);
        for (const std::string& line : result.report) std::printf("  %s\n", line.c_str());
        for (const std::string& line : save_notes) std::printf("  note: %s\n", line.c_str());
        if (extras.finish) extras.finish(result, a.own, nullptr);
    }
    if (result.stopped_early) {
        std::fflush(stdout);
        std::fprintf(stderr, "trilab-cli %s: %s (wrote the last good state: --keep-partial)\n",
                     name.c_str(), result.stop_reason.c_str());
        return 4;
    }
    return 0;
}

}  // namespace trilab::cli
