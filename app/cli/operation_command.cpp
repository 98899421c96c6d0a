#include "app/cli/operation_command.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>

#include "core/errors.h"
#include "core/io/mesh_io.h"
#include "core/progress.h"

namespace trilab::cli {
namespace {

struct OperationArgs {
    std::string op_text;
    std::vector<std::string> files;
    std::map<std::string, std::string> own;  ///< the command's own value options
    bool json = false, help = false;
    WriteOptions write;
};

/// The command's own option `s` (with "=VALUE" or the next argument) when it is one of
/// `names`: stores its value in `own` and returns true.
bool take_own_option(const std::vector<std::string>& names, const std::vector<std::string>& args,
                     std::size_t& i, std::map<std::string, std::string>& own) {
    const std::string& s = args[i];
    for (const std::string& name : names) {
        std::string value;
        if (s == name) {
            if (i + 1 >= args.size()) throw InvalidArgument(name + ": missing FILE");
            value = args[++i];
        } else if (s.rfind(name + "=", 0) == 0) {
            value = s.substr(name.size() + 1);
        } else {
            continue;
        }
        if (value.empty()) throw InvalidArgument(name + ": missing FILE");
        own[name] = value;
        return true;
    }
    return false;
}

OperationArgs parse_args(const std::string& name, const std::vector<std::string>& args,
                         const std::vector<std::string>& flags,
                         const std::vector<std::string>& value_options) {
    OperationArgs a;
    a.op_text = name;
    for (std::size_t i = 0; i < args.size(); ++i) {
        const std::string& s = args[i];
        if (take_own_option(value_options, args, i, a.own)) continue;
        if (s == "--help" || s == "-h") {
            a.help = true;
        } else if (s == "--json") {
            a.json = true;
        } else if (s == "--ascii") {
            a.write.ascii = true;
        } else if (s == "--big-endian") {
            a.write.big_endian = true;
        } else if (s.rfind("--", 0) == 0) {
            // An operation option: it and its value go to the operation, which checks both.
            a.op_text += " " + s;
            const bool flag = std::find(flags.begin(), flags.end(), s) != flags.end();
            if (!flag && s.find('=') == std::string::npos && i + 1 < args.size())
                a.op_text += " " + args[++i];
        } else {
            a.files.push_back(s);
        }
    }
    return a;
}

}  // namespace

void add_operation_values(JsonObject& json, const OperationResult& result) {
    for (const auto& [key, value] : result.values) {
        if (key == "vertices" || key == "faces") continue;
        if (value == std::floor(value) && std::abs(value) < 9e15)
            json.add(key, static_cast<long long>(value));
        else
            json.add(key, value);
    }
}

int run_operation_command(const std::string& name, const char* usage,
                          const std::vector<std::string>& args, const AddJson& add_json,
                          const std::vector<std::string>& flags, const CommandExtras& extras) {
    const OperationArgs a = parse_args(name, args, flags, extras.value_options);
    if (a.help) {
        std::fputs(usage, stdout);
        return 0;
    }
    const Operation op = parse_operation(a.op_text);  // bad options fail before any file
    if (a.files.size() != 2)
        throw InvalidArgument("expected IN and OUT files (see `trilab-cli " + name + " --help`)");

    const LoadedMesh loaded = read_mesh(a.files[0]);  // not timed
    NullProgress progress;
    const OperationResult result = run_operation(op, loaded.mesh, progress);
    const HalfedgeMesh& out = result.steps.back().mesh;
    write_mesh(out, a.files[1], a.write);  // not timed

    if (a.json) {
        JsonObject j;
        j.add("input", a.files[0])
            .add("output", a.files[1])
            .add("operation", op.name)
            .add("parameters", result.parameters)
            .add("vertices", out.n_vertices())
            .add("faces", out.n_faces());
        add_json(j, result);
        for (const auto& [key, text] : result.texts) j.add(key, text);
        if (extras.finish) extras.finish(result, a.own, &j);
        j.add("report", result.report).add("ms", result.ms);
        std::cout << j.str() << "\n";
    } else {
        std::printf("wrote %s: %s %s (%.1f ms)\n", a.files[1].c_str(), result.label.c_str(),
                    result.parameters.c_str(), result.ms);
        for (const std::string& line : result.report) std::printf("  %s\n", line.c_str());
        if (extras.finish) extras.finish(result, a.own, nullptr);
    }
    return 0;
}

}  // namespace trilab::cli
