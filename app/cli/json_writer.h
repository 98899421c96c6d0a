#pragma once
// A minimal streaming JSON object writer for the CLI's --json output.
#include <charconv>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

namespace trilab::cli {

class JsonObject {
public:
    JsonObject& add(const std::string& key, const std::string& value) {
        return raw(key, quote(value));
    }
    JsonObject& add(const std::string& key, const char* value) {
        return add(key, std::string(value));
    }
    JsonObject& add(const std::string& key, bool value) {
        return raw(key, value ? "true" : "false");
    }
    JsonObject& add(const std::string& key, double value) { return raw(key, number(value)); }
    JsonObject& add(const std::string& key, long long value) {
        return raw(key, std::to_string(value));
    }
    JsonObject& add(const std::string& key, std::size_t value) {
        return raw(key, std::to_string(value));
    }
    JsonObject& add(const std::string& key, int value) { return raw(key, std::to_string(value)); }
    JsonObject& add(const std::string& key, const std::vector<double>& values) {
        std::string s = "[";
        for (std::size_t i = 0; i < values.size(); ++i) s += (i ? ", " : "") + number(values[i]);
        return raw(key, s + "]");
    }
    JsonObject& add(const std::string& key, const std::vector<std::string>& values) {
        std::string s = "[";
        for (std::size_t i = 0; i < values.size(); ++i) s += (i ? ", " : "") + quote(values[i]);
        return raw(key, s + "]");
    }
    JsonObject& add(const std::string& key, const JsonObject& object) {
        return raw(key, object.str());
    }
    JsonObject& add_null(const std::string& key) { return raw(key, "null"); }
    JsonObject& raw(const std::string& key, const std::string& json) {
        body_ += (body_.empty() ? "" : ", ") + quote(key) + ": " + json;
        return *this;
    }
    std::string str() const { return "{" + body_ + "}"; }

    static std::string quote(const std::string& s) {
        std::string out = "\"";
        for (unsigned char c : s) {
            switch (c) {
                case '"':
                    out += "\\\"";
                    break;
                case '\\':
                    out += "\\\\";
                    break;
                case '\n':
                    out += "\\n";
                    break;
                case '\t':
                    out += "\\t";
                    break;
                case '\r':
                    out += "\\r";
                    break;
                default:
                    if (c < 0x20) {
                        char buf[8];
                        std::snprintf(buf, sizeof(buf), "\\u%04x", c);
                        out += buf;
                    } else {
                        out += char(c);
                    }
            }
        }
        return out + "\"";
    }
    /// Shortest text that reads back as exactly `v` (null for NaN and infinity).
    static std::string number(double v) {
        if (!std::isfinite(v)) return "null";
        char buf[64];
        const auto [end, ec] = std::to_chars(buf, buf + sizeof(buf), v);
        return ec == std::errc() ? std::string(buf, end) : "null";
    }

private:
    std::string body_;
};

}  // namespace trilab::cli
