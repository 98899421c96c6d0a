// The operation registry (app/ops/operation.h): one table entry per operation (each in its own
// file app/ops/<name>_op.cpp), a parser from "--option value" tokens to the operation's
// options struct and a runner that applies the core algorithm to a copy of the mesh. Method:
// the text is split on whitespace; the OptionReader of app/ops/operation_entry.h walks the tokens
// so every operation reports errors the same way, naming the option. Guarantees: parse_operation()
// runs nothing; run_operation() never modifies its input mesh, checks everything before working,
// and returns at least one step whose correspondence fits its predecessor; numbers print in
// shortest round-trip form, so the canonical parameters parse back to the same operation.
#include "app/ops/operation.h"

#include <cctype>
#include <string>
#include <vector>

#include "app/ops/operation_entries.h"
#include "core/errors.h"

namespace trilab {
namespace {

/// Every operation, in menu order (see app/ops/operation_entries.h).
const std::vector<OperationEntry>& registry() {
    static const std::vector<OperationEntry> entries = {
        noise_operation(),    subdivide_operation(), smooth_operation(),
        spectrum_operation(), decimate_operation(),
    };
    return entries;
}

std::string known_names() {
    std::string s;
    for (const OperationEntry& e : registry()) s += (s.empty() ? "" : ", ") + std::string(e.name);
    return s;
}

const OperationEntry& find_entry(const std::string& name) {
    for (const OperationEntry& e : registry())
        if (name == e.name) return e;
    if (name.empty()) throw InvalidArgument("empty operation (known: " + known_names() + ")");
    throw InvalidArgument("unknown operation '" + name + "' (known: " + known_names() + ")");
}

std::vector<std::string> tokenize(const std::string& text) {
    std::vector<std::string> tokens;
    std::size_t i = 0;
    const auto space = [&](std::size_t k) { return std::isspace((unsigned char)text[k]) != 0; };
    while (i < text.size()) {
        while (i < text.size() && space(i)) ++i;
        const std::size_t start = i;
        while (i < text.size() && !space(i)) ++i;
        if (i > start) tokens.push_back(text.substr(start, i - start));
    }
    return tokens;
}

}  // namespace

Operation parse_operation(const std::string& text) {
    std::vector<std::string> tokens = tokenize(text);
    Operation op;
    if (!tokens.empty()) op.name = tokens.front();
    const OperationEntry& entry = find_entry(op.name);
    op.args.assign(tokens.begin() + (tokens.empty() ? 0 : 1), tokens.end());
    OptionReader reader(entry.name, entry.usage, op.args);
    entry.check(reader);
    return op;
}

OperationResult run_operation(const Operation& op, const HalfedgeMesh& mesh, Progress& progress) {
    const OperationEntry& entry = find_entry(op.name);
    OptionReader reader(entry.name, entry.usage, op.args);
    return entry.run(reader, mesh, progress);
}

std::vector<std::string> operation_names() {
    std::vector<std::string> names;
    for (const OperationEntry& e : registry()) names.emplace_back(e.name);
    return names;
}

std::string operation_usage(const std::string& name) {
    return find_entry(name).usage;
}

}  // namespace trilab
