#pragma once
// What every operation of the registry (app/ops/operation.h) is made of: the OptionReader that
// walks its "--option value" tokens, and the OperationEntry that pairs its parser with its
// runner. Each operation lives in its own file (app/ops/<name>_op.cpp) and exposes one
// function returning its entry, declared in app/ops/operation_entries.h.
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <functional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "app/ops/operation.h"
#include "core/errors.h"

namespace trilab {

/// Walks the "--option value" tokens of one operation. Usage, in a parser:
///   while (r.next()) { if (r.is("--amount")) o.amount = r.number(0, 100); else r.unknown(); }
class OptionReader {
public:
    OptionReader(std::string op, std::string usage, const std::vector<std::string>& args)
        : op_(std::move(op)), usage_(std::move(usage)), args_(args) {}

    /// Moves to the next option; false after the last. Throws for a token that is not an
    /// option, an option given twice, or an "--flag=value" whose value was not read.
    bool next() {
        if (has_inline_value_) throw bad_option("takes no value");
        if (i_ >= args_.size()) return false;
        const std::string& token = args_[i_++];
        if (token.rfind("--", 0) != 0 || token.size() == 2)
            throw InvalidArgument(op_ + ": unexpected argument '" + token +
                                  "' (options: " + usage_ + ")");
        const std::size_t eq = token.find('=');
        option_ = token.substr(0, eq);
        has_inline_value_ = eq != std::string::npos;
        inline_value_ = has_inline_value_ ? token.substr(eq + 1) : std::string();
        if (!seen_.insert(option_).second) throw bad_option("given more than once");
        return true;
    }
    bool is(const char* name) const { return option_ == name; }
    const std::string& option() const { return option_; }

    /// The current option's value text.
    const std::string& value() {
        if (has_inline_value_) {
            has_inline_value_ = false;
            return inline_value_;
        }
        if (i_ >= args_.size()) throw bad_option("missing value");
        return args_[i_++];
    }
    /// The value as a finite number in [min, max]; `unit` is appended to the range text.
    double number(double min, double max, const std::string& unit = "") {
        const std::string& text = value();
        double v = 0;
        const char* end = text.data() + text.size();
        const auto [ptr, ec] = std::from_chars(text.data(), end, v);
        if (text.empty() || ec != std::errc() || ptr != end || !std::isfinite(v) || v < min ||
            v > max)
            throw bad_value(
                "a number from " + format_number(min) + " to " + format_number(max) + unit, text);
        return v;
    }
    /// The value as a whole number in [min, max] (decimal digits only).
    std::uint64_t whole_number(std::uint64_t min, std::uint64_t max) {
        const std::string& text = value();
        std::uint64_t v = 0;
        const char* end = text.data() + text.size();
        const auto [ptr, ec] = std::from_chars(text.data(), end, v);
        if (text.empty() || ec != std::errc() || ptr != end || v < min || v > max)
            throw bad_value(
                "a whole number from " + std::to_string(min) + " to " + std::to_string(max), text);
        return v;
    }
    /// The value, which must be one of `choices`.
    std::string choice(const std::vector<std::string>& choices) {
        const std::string& text = value();
        std::string list;
        for (const std::string& c : choices) {
            if (c == text) return c;
            list += (list.empty() ? "" : ", ") + c;
        }
        throw bad_value("one of " + list, text);
    }
    /// Throws: the current option is not one of this operation's.
    [[noreturn]] void unknown() const {
        throw InvalidArgument("unknown option '" + option_ + "' for " + op_ +
                              " (options: " + usage_ + ")");
    }
    /// An error about the current option's value: "--amount: expected ..., got 'text'".
    InvalidArgument bad_value(const std::string& expected, const std::string& text) const {
        return InvalidArgument(option_ + ": expected " + expected + ", got '" + text + "'");
    }
    InvalidArgument bad_option(const std::string& reason) const {
        return InvalidArgument(option_ + ": " + reason);
    }
    /// Throws when tokens are left (a parser that stopped early).
    void finish() {
        if (next()) unknown();
    }

    /// Shortest text that reads back as exactly `v`.
    static std::string format_number(double v) {
        char buf[64];
        const auto [ptr, ec] = std::to_chars(buf, buf + sizeof(buf), v);
        return ec == std::errc() ? std::string(buf, ptr) : std::to_string(v);
    }

private:
    std::string op_, usage_;
    const std::vector<std::string>& args_;
    std::size_t i_ = 0;
    std::string option_, inline_value_;
    bool has_inline_value_ = false;
    std::set<std::string> seen_;
};

inline double ms_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

struct OperationEntry {
    const char* name;
    const char* usage;
    std::function<void(OptionReader&)> check;
    std::function<OperationResult(OptionReader&, const HalfedgeMesh&, Progress&)> run;
};

/// An entry from an operation's typed parser and runner.
template <class Options>
OperationEntry make_entry(const char* name, const char* usage, Options (*parse)(OptionReader&),
                          OperationResult (*run)(const Options&, const HalfedgeMesh&, Progress&)) {
    return OperationEntry{
        name, usage,
        [parse](OptionReader& r) {
            parse(r);
            r.finish();
        },
        [parse, run](OptionReader& r, const HalfedgeMesh& mesh, Progress& progress) {
            const Options options = parse(r);
            r.finish();
            return run(options, mesh, progress);
        }};
}

}  // namespace trilab
