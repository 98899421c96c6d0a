#include "core/io/text_scanner.h"

#include <charconv>
#include <cmath>
#include <cstdlib>

namespace trilab {

std::string printable(std::string_view text) {
    std::string out;
    for (char c : text.substr(0, 40)) out += (c >= 32 && c < 127) ? c : '?';
    if (text.size() > 40) out += "...";
    return out;
}

void TextScanner::skip_space() {
    while (pos_ < text_.size()) {
        const char c = text_[pos_];
        if (c == '\n') {
            ++line_;
            ++pos_;
        } else if (c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v') {
            ++pos_;
        } else if (comment_ != '\0' && c == comment_) {
            while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
        } else {
            break;
        }
    }
}

std::string_view TextScanner::next_token() {
    skip_space();
    token_line_ = line_;
    const std::size_t begin = pos_;
    while (pos_ < text_.size()) {
        const char c = text_[pos_];
        if (c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v') break;
        if (comment_ != '\0' && c == comment_) break;
        ++pos_;
    }
    return text_.substr(begin, pos_ - begin);
}

std::string_view TextScanner::expect_token(const char* what) {
    std::string_view t = next_token();
    if (t.empty()) {
        // Report the last line that has text, not the empty one after the final newline.
        if (!text_.empty() && text_.back() == '\n' && token_line_ > 1) --token_line_;
        fail(std::string("unexpected end of file, expected ") + what);
    }
    return t;
}

std::string_view TextScanner::rest_of_line() {
    const std::size_t begin = pos_;
    while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
    std::string_view rest = text_.substr(begin, pos_ - begin);
    if (pos_ < text_.size()) {
        ++pos_;
        ++line_;
    }
    return rest;
}

bool TextScanner::at_end() {
    skip_space();
    return pos_ >= text_.size();
}

double TextScanner::next_double(const char* what) {
    std::string_view t = expect_token(what);
    // std::from_chars for double is not in GCC 12's libstdc++ for all targets; strtod on a
    // bounded copy is portable and handles nan/inf spellings.
    char buf[64];
    if (t.size() >= sizeof(buf)) fail("'" + printable(t) + "' is not a number (" + what + ")");
    t.copy(buf, t.size());
    buf[t.size()] = '\0';
    char* end = nullptr;
    const double value = std::strtod(buf, &end);
    if (end != buf + t.size()) fail("'" + printable(t) + "' is not a number (" + what + ")");
    if (!std::isfinite(value)) fail("'" + printable(t) + "' is not a finite number (" + what + ")");
    return value;
}

long long TextScanner::next_integer(const char* what) {
    std::string_view t = expect_token(what);
    long long value = 0;
    const char* first = t.data();
    if (!t.empty() && t[0] == '+') ++first;
    auto [ptr, ec] = std::from_chars(first, t.data() + t.size(), value);
    if (ec != std::errc() || ptr != t.data() + t.size())
        fail("'" + printable(t) + "' is not an integer (" + what + ")");
    return value;
}

}  // namespace trilab
