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
        } else if (c_mode_ && c == '/' && pos_ + 1 < text_.size() &&
                   (text_[pos_ + 1] == '*' || text_[pos_ + 1] == '/')) {
            skip_c_comment();
        } else {
            break;
        }
    }
}

void TextScanner::skip_c_comment() {
    if (text_.compare(pos_, 2, "//") == 0) {
        while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
        return;
    }
    const std::size_t start_line = line_;
    pos_ += 2;
    for (;;) {
        if (pos_ >= text_.size()) fail_at(start_line, "unterminated comment");
        if (text_.compare(pos_, 2, "*/") == 0) {
            pos_ += 2;
            return;
        }
        if (text_[pos_] == '\n') ++line_;
        ++pos_;
    }
}

TextScanner TextScanner::c_source(std::string_view text, std::string file) {
    TextScanner scanner(text, std::move(file), '\0');
    scanner.c_mode_ = true;
    return scanner;
}

namespace {

bool is_c_digit(char c) {
    return c >= '0' && c <= '9';
}
bool is_c_ident_start(char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_';
}
int hex_value(char c) {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
}

}  // namespace

CToken TextScanner::next_c_token() {
    skip_space();
    token_line_ = line_;
    CToken t;
    t.line = line_;
    if (pos_ >= text_.size()) return t;
    const std::size_t begin = pos_;
    const char c = text_[pos_];
    if (is_c_ident_start(c) || is_c_digit(c)) {
        while (pos_ < text_.size() && (is_c_ident_start(text_[pos_]) || is_c_digit(text_[pos_])))
            ++pos_;
        t.kind = is_c_digit(c) ? CToken::Number : CToken::Identifier;
    } else if (c == '"') {
        t.kind = CToken::String;
        read_c_string(t.value);
    } else {
        t.kind = CToken::Punct;
        ++pos_;
    }
    t.text = text_.substr(begin, pos_ - begin);
    return t;
}

void TextScanner::read_c_string(std::string& out) {
    ++pos_;  // opening quote
    for (;;) {
        if (pos_ >= text_.size() || text_[pos_] == '\n')
            fail_at(line_, "unterminated string literal");
        const char c = text_[pos_++];
        if (c == '"') return;
        if (c != '\\') {
            out += c;
            continue;
        }
        if (pos_ >= text_.size()) fail_at(line_, "unterminated string literal");
        const char e = text_[pos_++];
        switch (e) {
            case 'n':
                out += '\n';
                break;
            case 't':
                out += '\t';
                break;
            case 'r':
                out += '\r';
                break;
            case '0':
            case '1':
            case '2':
            case '3':
            case '4':
            case '5':
            case '6':
            case '7': {
                int v = e - '0';
                for (int k = 0;
                     k < 2 && pos_ < text_.size() && text_[pos_] >= '0' && text_[pos_] <= '7'; ++k)
                    v = v * 8 + (text_[pos_++] - '0');
                out += char(v & 0xff);
                break;
            }
            case 'x': {
                int v = 0, digits = 0;
                while (pos_ < text_.size() && hex_value(text_[pos_]) >= 0 && digits < 2) {
                    v = v * 16 + hex_value(text_[pos_++]);
                    ++digits;
                }
                if (digits == 0) fail_at(line_, "invalid \\x escape in a string literal");
                out += char(v);
                break;
            }
            case '\n':  // line continuation
                ++line_;
                break;
            default:
                out += e;
                break;  // \" \\ \' \? and the rest stand for themselves
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
