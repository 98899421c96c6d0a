#pragma once
// A small JSON reader for the files trilab writes itself (recipes): objects, arrays, strings
// (with \uXXXX escapes of the Basic Multilingual Plane), numbers, true, false, null. Numbers
// are read exactly (std::from_chars), so a number written in shortest round-trip form reads
// back as the same double. Errors throw InvalidArgument naming the file, the line and the
// reason; nesting deeper than 64 levels is refused.
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace trilab {

struct JsonValue {
    enum class Type { Null, Bool, Number, String, Array, Object };
    Type type = Type::Null;
    bool boolean = false;
    double number = 0;
    std::string text;
    std::vector<JsonValue> items;                            ///< Array
    std::vector<std::pair<std::string, JsonValue>> members;  ///< Object, in file order

    /// The member `key` of an object, or nullptr.
    const JsonValue* find(const std::string& key) const;
};

/// Parses `text` (the whole of it: one value, then only white space). `name` names the file.
JsonValue parse_json(const std::string& text, const std::string& name);

}  // namespace trilab
