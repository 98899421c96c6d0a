#pragma once
// ArgReader: walks command-line arguments one option at a time; "--name=value" is the same
// as "--name value". Shared by the trilab-cli commands that parse their own options.
#include <string>
#include <vector>

#include "core/errors.h"

namespace trilab::cli {

class ArgReader {
public:
    explicit ArgReader(const std::vector<std::string>& args) : args_(args) {}
    /// Moves to the next argument; false at the end.
    bool next() {
        if (i_ >= args_.size()) return false;
        arg_ = args_[i_++];
        has_inline_ = false;
        const std::size_t eq = arg_.find('=');
        if (arg_.rfind("--", 0) == 0 && eq != std::string::npos) {
            inline_ = arg_.substr(eq + 1);
            arg_ = arg_.substr(0, eq);
            has_inline_ = true;
        }
        return true;
    }
    /// The current argument (without an inline "=value").
    const std::string& arg() const { return arg_; }
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

    /// Whether the current argument had an inline "=value" that value() has not taken (a
    /// flag given a value: callers refuse it).
    bool has_unused_value() const { return has_inline_; }

private:
    const std::vector<std::string>& args_;
    std::size_t i_ = 0;
    std::string arg_, inline_;
    bool has_inline_ = false;
};

}  // namespace trilab::cli
