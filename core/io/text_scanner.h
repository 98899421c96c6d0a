#pragma once
// TextScanner: a fast whitespace tokenizer over an in-memory text file that tracks line
// numbers, for the text formats (OFF, ASCII PLY, ASCII STL), and in C mode a tiny C tokenizer
// (comments, identifiers, numbers, string literals, punctuation) for XBM and XPM images.
// Errors are IoErrors naming the file and the line of the offending token.
#include <cstddef>
#include <string>
#include <string_view>

#include "core/errors.h"

namespace trilab {

/// `text` made safe for an error message: at most 40 characters, non-printable bytes
/// replaced by '?'.
std::string printable(std::string_view text);

/// A token of C source, from TextScanner::next_c_token().
struct CToken {
    enum Kind { End, Identifier, Number, String, Punct } kind = End;
    std::string_view text;  ///< source text (for strings: with the quotes)
    std::string value;      ///< the unescaped contents of a string literal
    std::size_t line = 0;
};

class TextScanner {
public:
    /// `comment` starts a comment that runs to the end of the line ('\0' for none).
    TextScanner(std::string_view text, std::string file, char comment = '#')
        : text_(text), file_(std::move(file)), comment_(comment) {}
    /// A scanner in C mode: C comments (/* */ and //) are skipped as space; read it with
    /// next_c_token(). Throws "unterminated comment" (at the comment's line).
    static TextScanner c_source(std::string_view text, std::string file);

    /// Next C token: an identifier or number (letters, digits and '_'; a number starts with
    /// a digit), a string literal (C escapes; throws "unterminated string literal" at a
    /// newline or the end), or one punctuation character; End at the end of the text.
    CToken next_c_token();

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
    /// Like fail(), at `line`.
    [[noreturn]] void fail_at(std::size_t line, const std::string& reason) const {
        throw IoError(file_, line, reason);
    }

private:
    void skip_space();
    void skip_c_comment();
    void read_c_string(std::string& out);
    std::string_view text_;
    std::string file_;
    char comment_;
    bool c_mode_ = false;
    std::size_t pos_ = 0;
    std::size_t line_ = 1;
    std::size_t token_line_ = 1;
};

}  // namespace trilab
