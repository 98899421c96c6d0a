// The JSON reader (app/history/json_reader.h): recursive descent over the text.
#include "app/history/json_reader.h"

#include <charconv>
#include <cmath>

#include "core/errors.h"

namespace trilab {

const JsonValue* JsonValue::find(const std::string& key) const {
    for (const auto& [k, v] : members)
        if (k == key) return &v;
    return nullptr;
}

namespace {

class Parser {
public:
    Parser(const std::string& text, const std::string& name) : s_(text), name_(name) {}

    JsonValue document() {
        JsonValue v = value(0);
        space();
        if (i_ != s_.size()) fail("unexpected text after the JSON value");
        return v;
    }

private:
    [[noreturn]] void fail(const std::string& why) const {
        std::size_t line = 1;
        for (std::size_t k = 0; k < i_ && k < s_.size(); ++k) line += s_[k] == '\n';
        throw InvalidArgument(name_ + ":" + std::to_string(line) + ": " + why);
    }
    void space() {
        while (i_ < s_.size() &&
               (s_[i_] == ' ' || s_[i_] == '\n' || s_[i_] == '\r' || s_[i_] == '\t'))
            ++i_;
    }
    bool take(char c) {
        space();
        if (i_ < s_.size() && s_[i_] == c) {
            ++i_;
            return true;
        }
        return false;
    }
    void expect(char c) {
        if (!take(c)) fail(std::string("expected '") + c + "'");
    }
    bool word(const char* w) {
        const std::string t(w);
        if (s_.compare(i_, t.size(), t) != 0) return false;
        i_ += t.size();
        return true;
    }

    JsonValue value(int depth) {
        if (depth > 64) fail("nested too deeply");
        space();
        if (i_ >= s_.size()) fail("unexpected end of the file");
        JsonValue v;
        const char c = s_[i_];
        if (c == '{') {
            ++i_;
            v.type = JsonValue::Type::Object;
            if (take('}')) return v;
            do {
                space();
                if (i_ >= s_.size() || s_[i_] != '"') fail("expected a member name");
                std::string key = string();
                expect(':');
                v.members.emplace_back(std::move(key), value(depth + 1));
            } while (take(','));
            expect('}');
        } else if (c == '[') {
            ++i_;
            v.type = JsonValue::Type::Array;
            if (take(']')) return v;
            do v.items.push_back(value(depth + 1));
            while (take(','));
            expect(']');
        } else if (c == '"') {
            v.type = JsonValue::Type::String;
            v.text = string();
        } else if (word("true")) {
            v.type = JsonValue::Type::Bool;
            v.boolean = true;
        } else if (word("false")) {
            v.type = JsonValue::Type::Bool;
        } else if (word("null")) {
            v.type = JsonValue::Type::Null;
        } else {
            v.type = JsonValue::Type::Number;
            v.number = number();
        }
        return v;
    }

    double number() {
        const std::size_t start = i_;
        while (i_ < s_.size() && std::string("+-0123456789.eE").find(s_[i_]) != std::string::npos)
            ++i_;
        double v = 0;
        const char* end = s_.data() + i_;
        const auto [ptr, ec] = std::from_chars(s_.data() + start, end, v);
        if (i_ == start || ec != std::errc() || ptr != end || !std::isfinite(v))
            fail("expected a value, got '" +
                 s_.substr(start, std::max<std::size_t>(i_ - start, 1)) + "'");
        return v;
    }

    std::string string() {
        ++i_;  // the opening quote
        std::string out;
        while (true) {
            if (i_ >= s_.size()) fail("unterminated string");
            const char c = s_[i_++];
            if (c == '"') return out;
            if (static_cast<unsigned char>(c) < 0x20) fail("a control character in a string");
            if (c != '\\') {
                out += c;
                continue;
            }
            if (i_ >= s_.size()) fail("unterminated string");
            const char e = s_[i_++];
            switch (e) {
                case '"':
                    out += '"';
                    break;
                case '\\':
                    out += '\\';
                    break;
                case '/':
                    out += '/';
                    break;
                case 'b':
                    out += '\b';
                    break;
                case 'f':
                    out += '\f';
                    break;
                case 'n':
                    out += '\n';
                    break;
                case 'r':
                    out += '\r';
                    break;
                case 't':
                    out += '\t';
                    break;
                case 'u': {
                    if (s_.size() - i_ < 4) fail("a short \\u escape");
                    unsigned code = 0;
                    const auto [ptr, ec] =
                        std::from_chars(s_.data() + i_, s_.data() + i_ + 4, code, 16);
                    if (ec != std::errc() || ptr != s_.data() + i_ + 4) fail("a bad \\u escape");
                    i_ += 4;
                    if (code < 0x80) {
                        out += char(code);
                    } else if (code < 0x800) {
                        out += char(0xC0 | (code >> 6));
                        out += char(0x80 | (code & 0x3F));
                    } else {
                        out += char(0xE0 | (code >> 12));
                        out += char(0x80 | ((code >> 6) & 0x3F));
                        out += char(0x80 | (code & 0x3F));
                    }
                    break;
                }
                default:
                    fail(std::string("a bad escape \\") + e);
            }
        }
    }

    const std::string& s_;
    const std::string& name_;
    std::size_t i_ = 0;
};

}  // namespace

JsonValue parse_json(const std::string& text, const std::string& name) {
    return Parser(text, name).document();
}

}  // namespace trilab
