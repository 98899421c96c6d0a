#pragma once
// ArgReader: the one argument reader of every trilab-cli command. It walks the arguments one
// at a time; "--name=value" is the same as "--name value". Every option may be given once: a
// second "--name" is refused naming it ("--op: given more than once"), never silently
// overwriting the first (no command has an option that makes sense twice).
//
//   ArgReader reader(args, "render");
//   while (reader.next()) {
//       if (reader.is("--out")) out = reader.value();
//       else if (reader.is("--json")) json = reader.flag();
//       else if (reader.is_option()) reader.refuse_unknown();
//       else files.push_back(reader.arg());
//   }
#include <set>
#include <string>
#include <vector>

#include "core/errors.h"

namespace trilab::cli {

class ArgReader {
public:
    /// `command`: the trilab-cli command, for the hint in refusals ("see `trilab-cli render
    /// --help`").
    ArgReader(const std::vector<std::string>& args, std::string command)
        : args_(args), command_(std::move(command)) {}

    /// Moves to the next argument; false at the end. Refuses the previous option when it was
    /// a flag given "=value" (value() was not asked for), and an option given a second time.
    bool next() {
        check_no_unused_value();
        if (i_ >= args_.size()) return false;
        arg_ = args_[i_++];
        has_inline_ = false;
        const std::size_t eq = arg_.find('=');
        if (is_option() && eq != std::string::npos) {
            inline_ = arg_.substr(eq + 1);
            arg_ = arg_.substr(0, eq);
            has_inline_ = true;
        }
        if (is_option() && !seen_.insert(arg_).second)
            throw InvalidArgument(arg_ + ": given more than once");
        return true;
    }
    /// The current argument (without an inline "=value").
    const std::string& arg() const { return arg_; }
    /// Whether the current argument is `name`.
    bool is(const char* name) const { return arg_ == name; }
    /// Whether the current argument is --help or -h.
    bool is_help() const { return arg_ == "--help" || arg_ == "-h"; }
    /// Whether the current argument is an option ("--name"), not a file or a value.
    bool is_option() const { return arg_.rfind("--", 0) == 0; }
    /// The current option's value: its inline "=value" or the next argument. Throws
    /// InvalidArgument naming the option when there is none.
    std::string value() {
        if (has_inline_) {
            has_inline_ = false;
            return inline_;
        }
        if (i_ >= args_.size()) throw InvalidArgument(arg_ + ": missing value");
        return args_[i_++];
    }
    /// The current option as a flag (it takes no value): returns true.
    bool flag() {
        check_no_unused_value();
        return true;
    }
    /// Whether the current option has a value: an inline "=value" or a next argument.
    bool has_value() const { return has_inline_ || i_ < args_.size(); }
    /// Refuses the current option as unknown to this command.
    [[noreturn]] void refuse_unknown() const {
        throw InvalidArgument("unknown option '" + arg_ + "' (see `trilab-cli " + command_ +
                              " --help`)");
    }

private:
    void check_no_unused_value() {
        if (has_inline_) {
            has_inline_ = false;
            throw InvalidArgument(arg_ + ": takes no value");
        }
    }

    const std::vector<std::string>& args_;
    std::string command_;
    std::size_t i_ = 0;
    std::string arg_, inline_;
    bool has_inline_ = false;
    std::set<std::string> seen_;
};

}  // namespace trilab::cli
