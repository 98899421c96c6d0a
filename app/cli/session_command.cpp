// `trilab-cli session ...` and `trilab-cli replay` (app/cli/session_command.h).
#include "app/cli/session_command.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>
#include <ostream>
#include <utility>

#include "app/cli/arg_reader.h"
#include "app/cli/json_writer.h"
#include "app/cli/stopwatch.h"
#include "app/cli/write_options.h"
#include "app/history/recipe.h"
#include "app/history/session_file.h"
#include "app/ops/region_spec.h"
#include "core/errors.h"
#include "core/io/file_util.h"
#include "core/io/mesh_io.h"

namespace trilab::cli {
namespace {

constexpr const char* kSessionUsage = R"(usage: trilab-cli session SUBCOMMAND ...

  session info FILE [--json]
      the entries of a session (.trilab) or crash journal: label, typed parameters, vertex
      and face counts, bytes; for a journal whether it is complete, the entries recovered
      and the bytes discarded
  session export FILE --entry K [--step S] OUT [--ascii] [--big-endian]
      writes state K (its last step, or step S) as a mesh file
  session recipe SESSION OUT.json
      the typed operations and the selections from the loaded file to the current entry, as
      a recipe; a state the viewer made otherwise (texture coordinates) is refused by name
  session make IN OUT.trilab [--op "OPERATION --option value ..."]... [--select SPEC]...
               [--current K] [--viewer-settings FILE] [--json]
      loads IN and applies each --op and --select in order as the viewer does (one history
      entry each; an operation acts on the selection made before it), then writes the
      session; --current makes entry K current (an undo)
)";

constexpr const char* kReplayUsage =
    R"(usage: trilab-cli replay RECIPE.json IN OUT [--check SESSION] [--json]

Runs the recipe's operations and selections on IN in order, as the viewer runs them (each
operation on the selection at that point, or on its step's own "region"), and writes OUT. With
--check, compares the result with SESSION's current state (storage sizes, connectivity and
positions bit for bit) and exits 5 when they differ.
)";

/// One line per entry, as `session info` prints it.
std::string entry_line(std::size_t i, const SessionEntrySummary& e, bool current) {
    const auto& last = e.steps.back();
    std::string text = e.operation.def ? e.operation.text() : e.parameters;
    char buf[512];
    std::snprintf(buf, sizeof buf, "%c%3zu  %-24s %-40s %zu step%s  %zu v  %zu f  %zu bytes",
                  current ? '>' : ' ', i, e.label.c_str(), text.c_str(), e.steps.size(),
                  e.steps.size() == 1 ? "" : "s", last.first, last.second, e.bytes);
    return buf;
}

int session_info(const std::vector<std::string>& args) {
    std::string file;
    bool json = false;
    ArgReader reader(args, "session");
    while (reader.next()) {
        if (reader.is("--json"))
            json = reader.flag();
        else if (reader.is_option())
            reader.refuse_unknown();
        else if (file.empty())
            file = reader.arg();
        else
            throw InvalidArgument("session info: one FILE expected, got '" + reader.arg() +
                                  "' too");
    }
    if (file.empty()) throw InvalidArgument("session info: expected FILE");
    const SessionContents s = read_session_or_journal(file);
    const std::size_t current = s.history.current();
    if (json) {
        JsonObject j;
        j.add("file", file).add("kind", s.journal ? "journal" : "session");
        j.add("bytes", s.file_bytes).add("current", current);
        std::string list = "[";
        for (std::size_t i = 0; i < s.entries.size(); ++i) {
            const SessionEntrySummary& e = s.entries[i];
            JsonObject o;
            o.add("index", i).add("label", e.label).add("parameters", e.parameters);
            if (e.operation.def)
                o.add("operation", e.operation.name())
                    .raw("typed_parameters", typed_parameters_json(e.operation));
            else
                o.add_null("operation");
            o.add("ms", e.ms).add("steps", e.steps.size());
            o.add("vertices", e.steps.back().first).add("faces", e.steps.back().second);
            o.add("bytes", e.bytes);
            list += (i ? ", " : "") + o.str();
        }
        j.raw("entries", list + "]");
        j.add("complete", s.complete).add("entries_recovered", s.entries.size());
        j.add("records", s.records).add("bytes_discarded", s.bytes_discarded);
        if (!s.stop_reason.empty()) j.add("stop_reason", s.stop_reason);
        if (s.journal) j.add("pid", std::size_t(s.pid)).add("program", s.program);
        j.add("viewer_settings_bytes", s.extras.viewer_settings.size());
        if (!s.extras.texture_path.empty()) j.add("texture", s.extras.texture_path);
        j.add("messages", s.messages);
        std::cout << j.str() << "\n";
        return 0;
    }
    std::printf("%s: %s, %zu bytes, %zu entries, current %zu\n", file.c_str(),
                s.journal ? "crash journal" : "session", s.file_bytes, s.entries.size(), current);
    for (std::size_t i = 0; i < s.entries.size(); ++i)
        std::printf("%s\n", entry_line(i, s.entries[i], i == current).c_str());
    if (s.journal)
        std::printf("journal %s: %zu entries recovered from %zu records, %zu bytes discarded%s%s\n",
                    s.complete ? "complete" : "incomplete", s.entries.size(), s.records,
                    s.bytes_discarded, s.stop_reason.empty() ? "" : ": ", s.stop_reason.c_str());
    for (const std::string& m : s.messages) std::printf("  %s\n", m.c_str());
    return 0;
}

std::size_t parse_index(const std::string& option, const std::string& text) {
    if (text.empty() || text.size() > 9 ||
        text.find_first_not_of("0123456789") != std::string::npos)
        throw InvalidArgument(option + ": expected a whole number, got '" + text + "'");
    return std::size_t(std::stoul(text));
}

int session_export(const std::vector<std::string>& args) {
    std::vector<std::string> files;
    std::string entry, step;
    WriteOptions write;
    ArgReader reader(args, "session");
    while (reader.next()) {
        if (reader.is("--entry"))
            entry = reader.value();
        else if (reader.is("--step"))
            step = reader.value();
        else if (take_write_option(reader, write))
            continue;
        else if (reader.is_option())
            reader.refuse_unknown();
        else
            files.push_back(reader.arg());
    }
    if (files.size() != 2 || entry.empty())
        throw InvalidArgument("session export: expected FILE --entry K OUT");
    const std::size_t k = parse_index("--entry", entry);
    const SessionContents s = read_session_or_journal(files[0]);
    if (k >= s.history.size())
        throw InvalidArgument("--entry: " + files[0] + " has entries 0 to " +
                              std::to_string(s.history.size() - 1) + ", not " + entry);
    const std::size_t steps = s.history.info(k).steps.size();
    const std::size_t st = step.empty() ? steps - 1 : parse_index("--step", step);
    if (st >= steps)
        throw InvalidArgument("--step: entry " + entry + " has steps 0 to " +
                              std::to_string(steps - 1) + ", not " + step);
    const HalfedgeMesh mesh = s.history.mesh(k, st);
    write_mesh(mesh, files[1], write);
    std::printf("wrote %s: entry %zu \"%s\" step %zu (%zu vertices, %zu faces)\n", files[1].c_str(),
                k, s.history.info(k).label.c_str(), st, mesh.n_vertices(), mesh.n_faces());
    return 0;
}

int session_recipe(const std::vector<std::string>& args) {
    std::vector<std::string> files;
    ArgReader reader(args, "session");
    while (reader.next()) {
        if (reader.is_option())
            reader.refuse_unknown();
        else
            files.push_back(reader.arg());
    }
    if (files.size() != 2) throw InvalidArgument("session recipe: expected SESSION OUT.json");
    const SessionContents s = read_session_or_journal(files[0]);
    const Recipe recipe = recipe_of(s.history);
    const std::string json = recipe_json(recipe);
    write_file_atomically(files[1], [&](std::ostream& os) { os << json; });
    std::printf("wrote %s: %zu operations and %zu selections after \"%s\"\n", files[1].c_str(),
                recipe.operations(), recipe.selections(), recipe.source.c_str());
    return 0;
}

int session_make(const std::vector<std::string>& args) {
    std::vector<std::string> files;
    std::vector<std::pair<bool, std::string>> steps;  // (is a selection, its text), in order
    std::string settings_file, current;
    bool json = false;
    // --op repeats (applied in order), so no ArgReader here.
    for (std::size_t i = 0; i < args.size(); ++i) {
        const std::string& a = args[i];
        const auto value = [&]() -> std::string {
            if (i + 1 >= args.size()) throw InvalidArgument(a + ": missing value");
            return args[++i];
        };
        if (a == "--op")
            steps.emplace_back(false, value());
        else if (a == "--select")
            steps.emplace_back(true, value());
        else if (a == "--viewer-settings")
            settings_file = value();
        else if (a == "--current")
            current = value();
        else if (a == "--json")
            json = true;
        else if (a.rfind("--", 0) == 0)
            throw InvalidArgument("unknown option '" + a + "' (see `trilab-cli session --help`)");
        else
            files.push_back(a);
    }
    if (files.size() != 2) throw InvalidArgument("session make: expected IN OUT.trilab");
    Recipe parsed;  // checked before any file is read
    for (const auto& [select, text] : steps) {
        try {
            if (select) {
                parse_region_spec(text);
                RecipeStep step;
                step.kind = RecipeStep::Kind::SetSelection;
                step.region = text;
                step.text = "Select " + text;
                parsed.steps.push_back(std::move(step));
            } else {
                parsed.steps.emplace_back(parse_operation(text));
            }
        } catch (const InvalidArgument& e) {
            throw InvalidArgument((select ? "--select '" : "--op '") + text + "': " + e.what());
        }
    }
    SessionExtras extras;
    if (!settings_file.empty()) extras.viewer_settings = read_file_bytes(settings_file);

    LoadedMesh loaded = read_mesh(files[0]);
    const std::string name = std::filesystem::path(files[0]).filename().string();
    History history(std::size_t(-1));  // no budget: every entry is written
    history.reset(std::move(loaded.mesh), "Load " + name, files[0] == name ? "" : files[0]);
    extras.texture_path = loaded.texture_path;
    std::vector<std::string> notes;
    for (const RecipeStep& recipe_step : parsed.steps) {
        if (recipe_step.kind == RecipeStep::Kind::SetSelection) {
            // As the viewer's "Select SPEC": the current state with "v:selection" set.
            HalfedgeMesh mesh = history.current_mesh();
            apply_selection_step(recipe_step, mesh, "--select " + recipe_step.region);
            history.push("Select", recipe_step.region, 0.0, {std::move(mesh)},
                         {MorphCorrespondence{}});
            continue;
        }
        const Operation& op = recipe_step.operation;
        const std::optional<Selection> region = recipe_region(recipe_step, history.current_mesh());
        ReplayStep step = run_recipe_step(op, history.current_mesh(), region ? &*region : nullptr);
        if (!step.changed) {
            notes.push_back(op.text() + " changed nothing: no history entry");
            continue;
        }
        std::vector<HalfedgeMesh> meshes;
        std::vector<MorphCorrespondence> correspondences;
        for (OperationStep& s : step.result.steps) {
            meshes.push_back(std::move(s.mesh));
            correspondences.push_back(std::move(s.correspondence));
        }
        history.push(step.result.label, step.result.parameters, step.result.ms, std::move(meshes),
                     std::move(correspondences), op);
    }
    if (!current.empty()) history.jump(parse_index("--current", current));
    const SessionWriteReport r = write_session(files[1], history.snapshot(), extras);
    if (json) {
        JsonObject j;
        j.add("output", files[1]).add("entries", r.entries).add("states", r.states);
        j.add("arrays", r.arrays).add("bytes", r.bytes).add("current", history.current());
        j.add("skipped", r.skipped).add("notes", notes);
        std::cout << j.str() << "\n";
    } else {
        std::printf("wrote %s: %zu entries, %zu states, %zu arrays, %zu bytes\n", files[1].c_str(),
                    r.entries, r.states, r.arrays, r.bytes);
        for (const std::string& n : notes) std::printf("  %s\n", n.c_str());
        for (const std::string& n : r.skipped) std::printf("  not stored: %s\n", n.c_str());
    }
    return 0;
}

}  // namespace

int run_session_command(const std::vector<std::string>& args) {
    if (args.empty() || args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
        std::fputs(kSessionUsage, args.empty() ? stderr : stdout);
        return args.empty() ? 2 : 0;
    }
    const std::vector<std::string> rest(args.begin() + 1, args.end());
    for (const std::string& a : rest)
        if (a == "--help" || a == "-h") {
            std::fputs(kSessionUsage, stdout);
            return 0;
        }
    if (args[0] == "info") return session_info(rest);
    if (args[0] == "export") return session_export(rest);
    if (args[0] == "recipe") return session_recipe(rest);
    if (args[0] == "make") return session_make(rest);
    throw InvalidArgument("unknown subcommand '" + args[0] +
                          "' (info, export, recipe, make; see `trilab-cli session --help`)");
}

int run_replay_command(const std::vector<std::string>& args) {
    std::vector<std::string> files;
    std::string check;
    bool json = false;
    WriteOptions write;
    ArgReader reader(args, "replay");
    while (reader.next()) {
        if (reader.is_help()) {
            std::fputs(kReplayUsage, stdout);
            return 0;
        }
        if (reader.is("--check"))
            check = reader.value();
        else if (reader.is("--json"))
            json = reader.flag();
        else if (take_write_option(reader, write))
            continue;
        else if (reader.is_option())
            reader.refuse_unknown();
        else
            files.push_back(reader.arg());
    }
    if (files.size() != 3)
        throw InvalidArgument("expected RECIPE.json IN OUT (see `trilab-cli replay --help`)");
    const Recipe recipe = parse_recipe(read_file_bytes(files[0]), files[0]);
    LoadedMesh loaded = read_mesh(files[1]);
    const auto t0 = std::chrono::steady_clock::now();
    const HalfedgeMesh result = replay(recipe, std::move(loaded.mesh));
    const double ms = ms_since(t0);
    write_mesh(result, files[2], write);
    std::string difference;
    if (!check.empty()) {
        const SessionContents s = read_session_or_journal(check);
        difference = first_difference(result, s.history.current_mesh());
    }
    if (json) {
        JsonObject j;
        j.add("recipe", files[0]).add("input", files[1]).add("output", files[2]);
        j.add("operations", recipe.operations()).add("selections", recipe.selections());
        j.add("vertices", result.n_vertices()).add("faces", result.n_faces());
        if (!check.empty()) {
            j.add("check", check).add("identical", difference.empty());
            if (!difference.empty()) j.add("difference", difference);
        }
        j.add("ms", ms);
        std::cout << j.str() << "\n";
    } else {
        std::printf(
            "wrote %s: %zu operations and %zu selections replayed (%zu vertices, %zu faces, "
            "%.1f ms)\n",
            files[2].c_str(), recipe.operations(), recipe.selections(), result.n_vertices(),
            result.n_faces(), ms);
        if (!check.empty() && difference.empty())
            std::printf(
                "identical to the current state of %s (connectivity and positions bit "
                "for bit)\n",
                check.c_str());
    }
    if (!difference.empty()) {
        std::fflush(stdout);
        std::fprintf(stderr, "trilab-cli replay: the result differs from %s's current state: %s\n",
                     check.c_str(), difference.c_str());
        return 5;
    }
    return 0;
}

}  // namespace trilab::cli
