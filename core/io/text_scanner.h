#pragma once
// TextScanner: a fast whitespace tokenizer over an in-memory text file that tracks line
// numbers, for the text formats (OFF, ASCII PLY, ASCII STL). Errors are IoErrors naming the
// file and the line of the offending token.
#include <cstddef>
#include <string>
#include <string_view>

#include "core/errors.h"

namespace trilab {

/// `text` made safe for an error message: at most 40 characters, non-printable bytes
/// replaced by '?'.
std::string printable(std::string_view text);

class TextScanner {
public:
    /// `comment` starts a comment that runs to the end of the line ('\0' for none).
    TextScanner(std::string_view text, std::string file, char comment = '#')
        : text_(text), file_(std::move(file)), comment_(comment) {}

    /// Next whitespace-separated token, or an empty view at the end of the text.
    std::string_view next_token();
    /// Like next_token(), but throws "unexpected end of file, expected <what>".
    std::string_view expect_token(const char* what);
    /// The rest of the current line (after the last token), without the newline; moves to
    /// the next line.
    std::string_view rest_of_line();
    double next_double(const char* what);
    long long next_integer(const char* what);
    bool at_end();
    /// Line of the last token returned (1-based).
    std::size_t line() const { return token_line_; }
    std::size_t offset() const { return pos_; }
    const std::string& file() const { return file_; }
    [[noreturn]] void fail(const std::string& reason) const {
        throw IoError(file_, token_line_, reason);
    }

private:
    void skip_space();
    std::string_view text_;
    std::string file_;
    char comment_;
    std::size_t pos_ = 0;
    std::size_t line_ = 1;
    std::size_t token_line_ = 1;
};

}  // namespace trilab
